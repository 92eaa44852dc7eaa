//! Energy terms of a simulation, the works of a step not yet added to them, and the energy
//! watch (model.md §3, §4, §7).

use flexdem_elements::Dofs;
use flexdem_geom::{Real, Vec3};

/// Energy terms of a simulation (model.md §6). Works and dissipations are cumulative since the
/// start; kinetic and elastic terms are the current values.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Energy {
    /// Translational kinetic energy (J).
    pub kinetic_translation: Real,
    /// Rotational kinetic energy (J).
    pub kinetic_rotation: Real,
    /// Elastic energy stored in links (J).
    pub elastic_links: Real,
    /// Elastic energy stored in contacts (J).
    pub elastic_contacts: Real,
    /// Work done by gravity (J).
    pub gravity_work: Real,
    /// Work done by imposed loads and the user's force hook: forces and torques on the free
    /// DOFs, `Σ (F·v + τ·ω)·dt`; and by the user's kicks, velocities and spins set by hand on
    /// free DOFs after the first step, `Σ ½m·(v² − v₀²)` (and `½I·(ω² − ω₀²)`); and the
    /// normal spring energy `½·kn·(L0 − L)²` of links a model edit made at rest (J).
    pub load_work: Real,
    /// Work done by the boundaries: moving walls (`Σ F_wall→body·v_wall·dt` over wall
    /// contacts) and imposed velocities and spins (the support's reaction, `−Σ (F·v + τ·ω)·dt`
    /// over blocked DOFs, `F` and `τ` from links and contacts) (J).
    pub boundary_work: Real,
    /// Energy put in by contacts that started or ended between two steps (J): `½·kn·δ·δ₋`
    /// per first touch (`δ₋` the overlap one step before: negative for a contact found on
    /// time, positive for one found late, with an overlap one step of approach does not
    /// explain) and `−½·F·δ_now` per contact ended by separating (see
    /// `ContactPipeline::settle_births`). Collisions found on time add as much as they take.
    /// Also the energy put into (or taken from) contact springs as their overlap offsets are
    /// given back (`offsets.rs`, docs/model.md §2).
    pub contact_births: Real,
    /// Elastic energy given up by contacts that ended or were handed over while holding it
    /// (J).
    pub contact_releases: Real,
    /// Energy removed by damping (J).
    pub damping: Real,
    /// Energy dissipated by links (plastic caps, slip after decohesion, breakage) (J).
    pub links_dissipated: Real,
    /// Energy dissipated by contact friction (J).
    pub friction: Real,
    /// Energy dissipated by the contacts' viscous dashpots (model.md §7), contacts that ended
    /// included: the work of each dashpot force over the half kick before it and the half
    /// kick after, as the leapfrog's kinetic energy sees it (J).
    pub contact_damping: Real,
}

impl Energy {
    /// Energy stored in the system: kinetic plus elastic.
    pub fn stored(&self) -> Real {
        self.kinetic_translation
            + self.kinetic_rotation
            + self.elastic_links
            + self.elastic_contacts
    }

    /// Energy put in: the works of gravity, loads and boundaries and the late contact births.
    pub fn put_in(&self) -> Real {
        self.gravity_work + self.load_work + self.boundary_work + self.contact_births
    }

    /// Energy taken out: damping, link and contact dissipation (friction and dashpots),
    /// contact releases.
    pub fn taken_out(&self) -> Real {
        self.damping
            + self.links_dissipated
            + self.friction
            + self.contact_damping
            + self.contact_releases
    }

    /// The terms by name, in the order of the energy output's columns.
    pub fn named_terms(&self) -> [(&'static str, Real); 13] {
        [
            ("kinetic_translation", self.kinetic_translation),
            ("kinetic_rotation", self.kinetic_rotation),
            ("elastic_links", self.elastic_links),
            ("elastic_contacts", self.elastic_contacts),
            ("gravity_work", self.gravity_work),
            ("load_work", self.load_work),
            ("boundary_work", self.boundary_work),
            ("contact_births", self.contact_births),
            ("damping", self.damping),
            ("links_dissipated", self.links_dissipated),
            ("friction", self.friction),
            ("contact_damping", self.contact_damping),
            ("contact_releases", self.contact_releases),
        ]
    }

    /// The first term that is NaN or infinite, if any.
    pub fn first_non_finite(&self) -> Option<(&'static str, Real)> {
        self.named_terms().into_iter().find(|(_, v)| !v.is_finite())
    }

    /// Stored energy minus the energy put in plus the energy taken out: constant in time when
    /// the balance closes.
    pub fn balance(&self) -> Real {
        self.stored() - self.put_in() + self.taken_out()
    }

    /// The energy scale a balance error is measured against: the largest of the stored
    /// energy, each work, the births and what was taken out.
    pub fn scale(&self) -> Real {
        [
            self.stored().abs(),
            self.gravity_work.abs(),
            self.load_work.abs(),
            self.boundary_work.abs(),
            self.contact_births.abs(),
            self.taken_out().abs(),
        ]
        .into_iter()
        .fold(0.0, Real::max)
    }
}

/// Works of one step (from x(t) to x(t + dt)), added to [`Energy`] at the next step so that
/// every term refers to the same instant.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PendingWork {
    /// Gravity (J).
    pub gravity: Real,
    /// Imposed loads, the force hook and kicks by hand (J).
    pub load: Real,
    /// Moving walls and imposed velocities (J).
    pub boundary: Real,
    /// The second half of the last kick's damping (J, see `StepWork::damping_next`).
    pub damping: Real,
    /// The second half of the contact dashpots' dissipation at the last step (J, see
    /// `StepWork::contact_damping_next`).
    pub contact_damping: Real,
}

/// The energy watch (model: "a run watches its energy"): the balance at the start (after the
/// first step), its lowest value since, the largest energy scale seen, against which the
/// balance error is measured each step, and the energy put in by contacts found late, which
/// the balance counts (in `contact_births`) and the watch limits on its own.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EnergyWatch {
    /// The balance at the start of the simulation (J).
    pub initial_balance: Real,
    /// The lowest balance since the start (J): once it is below the start by more than the
    /// tolerance, energy created is measured from it ([`EnergyWatch::reference`]), so that
    /// energy lost first (which the watch only warns of) does not hide energy created later.
    pub lowest_balance: Real,
    /// The largest of |initial balance| and [`Energy::scale`] over the run so far (J).
    pub scale: Real,
    /// Energy put in since the start (after the first step, whose overlaps are the start
    /// state) by first touches found with more overlap than one step of approach explains:
    /// `Σ ½·kn·δ·δ₋` (J, δ₋ = δ − u·dt₀ > 0 the overlap one step before). The balance counts
    /// it as put in, so the balance error cannot show it: it is energy the run made (bodies
    /// that passed a step overlapping unseen, or were made or moved into each other), limited
    /// by the same tolerance ([`EnergyWatch::relative_late_births`]).
    pub late_births: Real,
    /// The energy of the normal springs of the contacts a model edit ended
    /// (`Simulation::edit_model`): found again at the next step, late, they bring it back
    /// (reborn with no shear), and it is taken off that step's late births (J; 0 once that
    /// step is done).
    pub late_credit: Real,
}

impl EnergyWatch {
    /// The watch of a run whose balance starts at `balance`, on the energy scale `scale`.
    pub fn starting_at(balance: Real, scale: Real) -> EnergyWatch {
        let (late_births, late_credit) = (0.0, 0.0);
        EnergyWatch {
            initial_balance: balance,
            lowest_balance: balance,
            scale,
            late_births,
            late_credit,
        }
    }

    /// The watch turned on again at a balance `balance`: it watches from there (its start
    /// and lowest balance that one, no contact found late yet), keeping the largest scale
    /// seen. What the run made while the watch was off was let through by whoever switched
    /// it off; the balance itself still shows it.
    pub(crate) fn restart_at(&mut self, balance: Real) {
        self.initial_balance = balance;
        self.lowest_balance = balance;
        self.late_births = 0.0;
    }

    /// The balance energy created is measured from, on the energy scale `scale` with the
    /// tolerance `limit`: `min(B(0), min B + limit·scale)`. The balance may swing by the
    /// tolerance on either side of its start (the lagged kinetic energy of violent first
    /// steps does); once it has fallen further (energy lost, which the watch warns of), the
    /// reference follows it down, so that a loss cannot hide energy created later: a rise of
    /// more than twice the tolerance above the lowest balance is then energy created, even
    /// one that only brings the balance back to its start.
    pub fn reference(&self, limit: Real, scale: Real) -> Real {
        self.initial_balance.min(self.lowest_balance + limit * scale)
    }

    /// `(B(t) − reference) / scale` ([`EnergyWatch::reference`]): energy created when above
    /// `limit`; 0 while the scale is 0. (The watch measures a tiny scale against the
    /// round-off of the motions instead, `round_off_energy`: this does not.)
    pub fn relative_created(&self, e: &Energy, limit: Real) -> Real {
        if self.scale > 0.0 {
            (e.balance() - self.reference(limit, self.scale)) / self.scale
        } else {
            0.0
        }
    }

    /// `late_births / scale`, compared with the tolerance; 0 while the scale is 0.
    pub fn relative_late_births(&self) -> Real {
        if self.scale > 0.0 {
            self.late_births / self.scale
        } else {
            0.0
        }
    }

    /// Whether the watch holds usable numbers (a state read from a file may be damaged):
    /// finite, a scale, late births and a credit ≥ 0 and the lowest balance not above the
    /// start's.
    pub(crate) fn is_consistent(&self) -> bool {
        let (b0, lowest, credit) = (self.initial_balance, self.lowest_balance, self.late_credit);
        [b0, lowest, self.scale, self.late_births, credit].iter().all(|x| x.is_finite())
            && self.scale >= 0.0
            && self.late_births >= 0.0
            && credit >= 0.0
            && self.lowest_balance <= self.initial_balance
    }

    /// Takes in the energy `late` that contacts found late put in at a step, less what a
    /// model edit before it released ([`EnergyWatch::late_credit`], then spent).
    pub(crate) fn note_late_births(&mut self, late: Real) {
        self.late_births += (late - self.late_credit).max(0.0);
        self.late_credit = 0.0;
    }

    /// Takes in the balance and the energy scale of a step.
    pub fn note(&mut self, e: &Energy) {
        self.lowest_balance = self.lowest_balance.min(e.balance());
        self.scale = self.scale.max(e.scale());
    }

    /// `(B(t) − B(0)) / scale`: positive when energy appeared from nowhere, negative when it
    /// went unaccounted; 0 while the scale is 0.
    pub fn relative_error(&self, e: &Energy) -> Real {
        if self.scale > 0.0 {
            (e.balance() - self.initial_balance) / self.scale
        } else {
            0.0
        }
    }
}

/// The energy bookkeeping of a simulation: the terms, the works of the last step not yet in
/// them, and the watch.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EnergyAccount {
    /// Energy terms at the last step.
    pub terms: Energy,
    /// Works of the last step (from x(t) to x(t + dt)), added at the next step so that every
    /// energy term refers to the same instant.
    pub pending: PendingWork,
    /// The balance at the start and the energy scale so far.
    pub watch: EnergyWatch,
}

/// The translational DOFs, in the order of a vector's components.
pub(crate) const TRANSLATIONS: [Dofs; 3] = [Dofs::X, Dofs::Y, Dofs::Z];

/// The rotational DOFs, in the order of a vector's components.
pub(crate) const ROTATIONS: [Dofs; 3] = [Dofs::RX, Dofs::RY, Dofs::RZ];

/// The work a support does when the velocity of its blocked components is changed between
/// steps (an imposed velocity set or changed): `Σ ½p·(v_c² − v₀_c²)` over the components of
/// `axes` that `blocked` holds, `p` the mass or the moment of inertia. The leapfrog counts a
/// blocked component's kinetic energy as `½p·v_c²` (`add_support_terms`), so this closes the
/// balance at the next step, where it is added to the boundary work (`PendingWork::boundary`).
/// A component that was free counted `½p·v₀(t − dt/2)·v₀(t + dt/2)`: the change leaves an
/// error of the order of `F·v·dt`, once.
pub(crate) fn support_jump(
    p: Real,
    old: &Vec3,
    new: &Vec3,
    blocked: Dofs,
    axes: [Dofs; 3],
) -> Real {
    jump_where(p, old, new, |c| blocked.contains(axes[c]))
}

/// The work of a kick by hand on the free components (those of `axes` that `blocked` does
/// not hold) of a velocity or spin set between steps: `Σ ½p·(v_c² − v₀_c²)`, the user's, added
/// to the load work at the next step (`PendingWork::load`). The leapfrog counts a free
/// component's kinetic energy as `½p·v(t − dt₀/2)·v(t + dt/2)`; with `v(t − dt₀/2)` replaced
/// by the kick, the next step's kinetic energy differs from `½p·v_c²` by `½p·a·h·v_c` (`h` the
/// kick's span, `a` the next acceleration): the balance is left `½F·h·(v_c − v₀_c)` off, once
/// (`F` from gravity, links and contacts: the works of loads and damping use the kick)
/// (for a 100 kg rock kicked to 10 m/s under gravity with dt = 10⁻⁵ s, 0.05 J of 5 kJ).
pub(crate) fn kick_jump(p: Real, old: &Vec3, new: &Vec3, blocked: Dofs, axes: [Dofs; 3]) -> Real {
    jump_where(p, old, new, |c| !blocked.contains(axes[c]))
}

/// `Σ ½p·(new_c² − old_c²)` over the components `c` that `counted` takes.
fn jump_where(p: Real, old: &Vec3, new: &Vec3, counted: impl Fn(usize) -> bool) -> Real {
    (0..3).filter(|&c| counted(c)).map(|c| 0.5 * p * (new[c] * new[c] - old[c] * old[c])).sum()
}

/// [`support_jump`] summed over the particles `ids` (each once) when all of `axes` get the
/// imposed `new` value: `p` their masses or moments of inertia, `old` their velocities or
/// spins. An id past the arrays adds nothing (the model refuses it).
pub(crate) fn imposed_jump(
    ids: &[u32],
    p: &[Real],
    old: &[Vec3],
    new: &Vec3,
    axes: [Dofs; 3],
) -> Real {
    let all = axes.into_iter().fold(Dofs::NONE, |d, a| d | a);
    ids.iter()
        .filter_map(|&i| Some((*p.get(i as usize)?, old.get(i as usize)?)))
        .map(|(p, old)| support_jump(p, old, new, all, axes))
        .sum()
}

/// The particles of `particles` in increasing order, each once (a particle named twice has
/// its velocity changed once).
pub(crate) fn distinct(particles: impl IntoIterator<Item = u32>) -> Vec<u32> {
    let mut ids: Vec<u32> = particles.into_iter().collect();
    ids.sort_unstable();
    ids.dedup();
    ids
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_support_gives_the_kinetic_energy_of_its_blocked_components_only() {
        let (old, new) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(-1.0, 0.0, 5.0));
        let all = support_jump(2.0, &old, &new, Dofs::TRANSLATION, TRANSLATIONS);
        assert_eq!(all, new.norm_squared() - old.norm_squared());
        assert_eq!(support_jump(2.0, &old, &new, Dofs::Y, TRANSLATIONS), -4.0);
        assert_eq!(support_jump(2.0, &old, &new, Dofs::ROTATION, TRANSLATIONS), 0.0);
        assert_eq!(support_jump(2.0, &old, &new, Dofs::RZ, ROTATIONS), 16.0);
        // a kick by hand counts the other components: the two make the whole change
        assert_eq!(kick_jump(2.0, &old, &new, Dofs::Y, TRANSLATIONS), all + 4.0);
        assert_eq!(kick_jump(2.0, &old, &new, Dofs::ROTATION, TRANSLATIONS), all);
        assert_eq!(kick_jump(2.0, &old, &new, Dofs::TRANSLATION, TRANSLATIONS), 0.0);
        assert_eq!(distinct([3, 1, 3, 0]), vec![0, 1, 3]);
        // every component imposed, summed over the particles; an id past the arrays adds 0
        let (p, v) = ([2.0, 4.0], [old, Vec3::zeros()]);
        let jump = imposed_jump(&[0, 1, 7], &p, &v, &new, TRANSLATIONS);
        assert_eq!(jump, all + 2.0 * new.norm_squared());
    }
}
