//! What a leapfrog step (`integrator.rs`, and its four-particle lanes, `integrator_lanes.rs`)
//! gives besides the motion: its energy terms, and its check of the particles it moved.

use flexdem_geom::{Real, Vec3};

/// Energy terms of one integration step from `x(t)` to `x(t + dt)`.
///
/// The kinetic energy at time t is taken as `½·m·v(t − dt/2)·v(t + dt/2)` (and likewise for
/// rotation): with it, `kinetic + potential` is exactly conserved by the leapfrog for linear
/// springs, and to O(dt²) without drift otherwise, whereas `½·m·v(t + dt/2)²` oscillates by
/// O(ω·dt).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepWork {
    /// Translational kinetic energy at time t (J).
    pub kinetic_translation: Real,
    /// Rotational kinetic energy at time t (J).
    pub kinetic_rotation: Real,
    /// Work done by gravity from t to t + dt: `m·g·v(t + dt/2)·dt` over free DOFs (J).
    pub gravity: Real,
    /// Energy removed by Cundall damping in the kick at t, the part that the kinetic energy at
    /// t already shows: `Σ m·(a_free − a)·v(t − dt/2)·h/2` (J). The other half of the kick's
    /// damping, with v(t + dt/2), shows in the kinetic energy at t + dt: `damping_next`. (With
    /// the kinetic energy `½m·v(t − dt/2)·v(t + dt/2)`, this split closes the balance at every
    /// step, where the mean velocity booked at once leaves an offset of half a kick.)
    pub damping: Real,
    /// The second half of the kick's damping, `Σ m·(a_free − a)·v(t + dt/2)·h/2` (J).
    pub damping_next: Real,
    /// Work of the supports that impose the velocity of blocked DOFs, whose reaction is minus
    /// the node's force: the half of `−Σ (F·v + τ·ω)` at t over the step before,
    /// `·dt₀/2` (J; 0 for DOFs held at rest). The force at t works half over the step before
    /// and half over the step after (the trapezoidal rule, which the kinetic energy
    /// `½m·v(t − dt/2)·v(t + dt/2)` matches).
    pub boundary: Real,
    /// The other half: `−Σ (F·v + τ·ω)·dt/2`, over the step after (J).
    pub boundary_next: Real,
    /// Energy dissipated by the contact dashpots' forces at t in the kick at t, the part the
    /// kinetic energy at t shows: `−Σ F_d·v_rel(t − dt₀/2)·h/2` (J), `h` the kick, as for
    /// Cundall damping. Not the leapfrog's: the integration stage sets it (model.md §7).
    pub contact_damping: Real,
    /// The other half, with the velocities of the kick: `−Σ F_d·v_rel(t + dt/2)·h/2` (J).
    pub contact_damping_next: Real,
}

impl std::ops::AddAssign for StepWork {
    fn add_assign(&mut self, o: Self) {
        self.kinetic_translation += o.kinetic_translation;
        self.kinetic_rotation += o.kinetic_rotation;
        self.gravity += o.gravity;
        self.damping += o.damping;
        self.damping_next += o.damping_next;
        self.boundary += o.boundary;
        self.boundary_next += o.boundary_next;
        self.contact_damping += o.contact_damping;
        self.contact_damping_next += o.contact_damping_next;
    }
}

/// What the leapfrog checks after moving a chunk: the particles' reaches (none: no check)
/// and their smallest per chunk, the collider's watch of their moves since its last build
/// (none: no check) and the chunks' answers (a buffer kept by the caller).
pub(crate) struct Checks<'a> {
    pub(crate) reach: Option<&'a [Real]>,
    /// The smallest reach of each chunk (empty: every particle is checked against its own).
    pub(crate) chunk_reach: &'a [Real],
    pub(crate) verlet: Option<VerletWatch<'a>>,
    pub(crate) flags: &'a mut Vec<ChunkCheck>,
}

/// Where each particle was at the collider's last build and how far it may move from there
/// before the next (`Collider::verlet_watch`), one entry per particle; and per chunk of the
/// leapfrog, the smallest limit and a bound on how far its particles have moved since
/// (`drift`: while it is below the limit, no particle of the chunk can be beyond its own,
/// and the chunk's references and limits are not read).
#[derive(Clone, Copy)]
pub(crate) struct VerletWatch<'a> {
    pub(crate) reference: &'a [Vec3],
    pub(crate) limits: &'a [Real],
    pub(crate) chunk_limits: &'a [Real],
    pub(crate) drift: &'a [Real],
}

/// The smallest of `v` in each chunk of `chunk` entries (the leapfrog's, `integrator::CHUNK`):
/// the per-chunk reaches and limits of [`Checks`] and [`VerletWatch`].
pub(crate) fn chunk_minima(v: &[Real], chunk: usize) -> Vec<Real> {
    let chunks = v.chunks(chunk);
    chunks.map(|c| c.iter().copied().fold(Real::INFINITY, Real::min)).collect()
}

/// The part of a chunk's limit its drift may reach before its particles are checked one by
/// one: the drift is an upper bound (the round-off of `x + v·dt` included), and the margin
/// left absorbs the round-off of its own sums and of [`beyond_limit`], so the answers are
/// those of checking every particle (speeds below 1e-154 m/s, whose squares underflow,
/// aside: they would matter only for limits below some 1e-140 m).
pub(crate) const DRIFT_CHECKED_BEYOND: Real = 0.75;

impl VerletWatch<'_> {
    /// Whether one of the particles from `first` on, at `pos`, is farther than its limit
    /// from its reference ([`beyond_limit`], the collider's own test).
    #[inline]
    pub(crate) fn any_beyond(&self, first: usize, pos: &[Vec3]) -> bool {
        let at = first..first + pos.len();
        let (reference, limits) = (&self.reference[at.clone()], &self.limits[at]);
        let moved = pos.iter().zip(reference).zip(limits);
        moved.fold(false, |any, ((x, x0), &limit)| any | beyond_limit(x, x0, limit))
    }
}

/// Whether a particle at `x` is farther than `limit` from where it was at the collider's last
/// build, `x0`: `|x − x₀|² > limit²` (a NaN position is not: `flags_step` catches it).
#[inline]
pub(crate) fn beyond_limit(x: &Vec3, x0: &Vec3, limit: Real) -> bool {
    (x - x0).norm_squared() > limit * limit
}

/// A chunk's answers to the leapfrog's checks.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ChunkCheck {
    /// A particle may have gone wrong ([`flags_step`]).
    pub(crate) flagged: bool,
    /// A particle moved beyond its limit since the collider's last build.
    pub(crate) beyond: bool,
    /// The chunk's drift after the step (see [`VerletWatch`]; 0 without a watch).
    pub(crate) drift: Real,
}

/// Whether a particle may have gone wrong in the step (`x`, `v`, `w` its new position,
/// velocity and spin): a value not finite, or a move `|v|·dt` beyond its `reach`. One cheap
/// test, no root or division; the caller seeks the culprit when it says yes.
#[inline]
pub(crate) fn flags_step(x: &Vec3, v: &Vec3, w: &Vec3, reach: Real, dt2: Real) -> bool {
    let sum = x.sum() + v.sum() + w.sum();
    !(sum.is_finite() && v.norm_squared() * dt2 <= reach * reach)
}
