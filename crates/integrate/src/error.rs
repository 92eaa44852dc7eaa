//! Errors of the engine: bad settings, bad models, and runs that go wrong.

use flexdem_elements::ModelError;
use flexdem_geom::Real;
use thiserror::Error;

/// What can stop a simulation from starting or going on.
#[derive(Debug, Error)]
pub enum SimulationError {
    /// A setting has a value outside its range.
    #[error("setting `{what}` is {value}: expected {expected}")]
    Setting {
        /// The setting.
        what: String,
        /// Its value.
        value: String,
        /// What it should be.
        expected: String,
    },
    /// The model is inconsistent (an id out of range, NaN, a zero-length connection, ...).
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A particle that can move has no mass or no inertia.
    #[error(
        "particle {particle} is free to move but has mass {mass} and inertia {inertia}: \
         give it connections (a node), a density (a sphere), or block its DOFs"
    )]
    NoMass {
        /// The particle.
        particle: u32,
        /// Its mass.
        mass: Real,
        /// Its inertia.
        inertia: Real,
    },
    /// Nothing gives a time step: no stiffness and no massive particle.
    #[error("no time step can be estimated (no links, contacts or massive particles): set dt")]
    NoTimeStep,
    /// A particle moved by more than its reach in one step (its radius, or for a node the size
    /// of the smallest element holding it, if larger): the run is unstable.
    #[error(
        "particle {particle} moved by {displacement:.3e} m in one step at step {step} \
         (t = {time:.6e} s), more than its reach {reach:.3e} m (its radius, or the size of its \
         smallest element): the run is unstable (dt = {dt:.3e} s, critical step \
         {critical_dt:.3e} s); use a smaller dt or dt = auto with a smaller safety factor"
    )]
    Exploding {
        /// The fastest such particle.
        particle: u32,
        /// Its displacement in the step.
        displacement: Real,
        /// The most it may move in one step.
        reach: Real,
        /// The step.
        step: u64,
        /// The time.
        time: Real,
        /// The time step in use.
        dt: Real,
        /// The last critical step estimate.
        critical_dt: Real,
    },
    /// A position or velocity became NaN or infinite.
    #[error(
        "particle {particle} has a non-finite position or velocity at step {step} \
         (t = {time:.6e} s) with dt = {dt:.3e} s (critical step {critical_dt:.3e} s): \
         the run is unstable; use a smaller dt or dt = auto with a smaller safety factor"
    )]
    NonFinite {
        /// The first such particle.
        particle: u32,
        /// The step.
        step: u64,
        /// The time.
        time: Real,
        /// The time step in use.
        dt: Real,
        /// The last critical step estimate.
        critical_dt: Real,
    },
    /// An energy term became NaN or infinite while the positions and velocities are finite: a
    /// force or a dissipation is garbage, and the balance can no longer watch the run.
    #[error(
        "the energy term `{term}` is {value} at step {step} (t = {time:.6e} s): a contact or \
         link force, a load or a dissipation is not finite, and the energy balance can no \
         longer be checked; the run is stopped. {culprit}"
    )]
    NonFiniteEnergy {
        /// The first non-finite term (named as in the energy output).
        term: &'static str,
        /// Its value.
        value: Real,
        /// The step.
        step: u64,
        /// The time.
        time: Real,
        /// Where the energy is (see `EnergyBalance::culprit`).
        culprit: String,
    },
    /// The energy balance error passed the limit on the side of energy created: the run made
    /// energy it cannot account for.
    #[error(
        "the energy balance is off by {error:+.3e} of the energy scale {scale:.4e} J \
         ({change:+.4e} J) {} at step {step} (t = {time:.6e} s), beyond the limit \
         {limit:.1e}: \
         the run created energy it cannot account for. {culprit}. Use a smaller time step \
         (dt = auto with a smaller safety factor), or widen the check with \
         `energy_tolerance` in [simulation] (\"off\" switches it off)",
        reference_text(.after_loss)
    )]
    EnergyBalance {
        /// The step.
        step: u64,
        /// The time.
        time: Real,
        /// (B(t) − B_ref) / scale: the rise of the balance above its reference, B(0) or,
        /// once energy was lost beyond the limit, the lowest balance plus limit·scale
        /// (`EnergyWatch::reference`).
        error: Real,
        /// Whether the reference is the lowest balance plus the limit (energy was lost beyond
        /// the limit before) rather than B(0).
        after_loss: bool,
        /// The limit it passed.
        limit: Real,
        /// B(t) − B_ref (J).
        change: Real,
        /// The energy scale (J).
        scale: Real,
        /// Where the energy is: the contact and the link holding the most elastic energy,
        /// the fastest particle.
        culprit: String,
    },
    /// Contacts found late (first touches with more overlap than one step of approach
    /// explains) put in more energy than the limit allows: the balance counts it
    /// (`contact_births`), but it is energy the run made, not energy a load or a support
    /// gave (`EnergyWatch::late_births`).
    #[error(
        "contacts found late have put {energy:.4e} J into the run since the start, \
         {:.3e} of the energy scale {scale:.4e} J, beyond the limit {limit:.1e}, by step \
         {step} (t = {time:.6e} s; {contacts} first touches found late since the simulation \
         began, the first step's overlaps included): bodies passed a \
         step overlapping unseen, or were made or moved into each other, and their springs \
         started with energy no work gave. {culprit}. Use a smaller time step (dt = auto with \
         a smaller safety factor) or start the bodies apart, or widen the check with \
         `energy_tolerance` in [simulation] (\"off\" switches it off)",
        .energy / .scale
    )]
    LateContacts {
        /// The step.
        step: u64,
        /// The time.
        time: Real,
        /// The energy they put in since the start (J): `energy / scale` passed `limit`.
        energy: Real,
        /// The limit it passed.
        limit: Real,
        /// The energy scale (J).
        scale: Real,
        /// The first touches found late since the simulation began (the first step's
        /// overlaps included, whose energy is not counted).
        contacts: u64,
        /// Where the energy is (see `EnergyBalance::culprit`).
        culprit: String,
    },
}

/// How the energy balance error names its reference (`EnergyBalance::after_loss`).
fn reference_text(after_loss: &bool) -> &'static str {
    if *after_loss {
        "above its lowest value plus the limit (after a loss)"
    } else {
        "since the start"
    }
}
