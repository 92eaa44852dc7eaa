//! Energy terms of one contact or link (model.md §3, §7): elastic energy stored in the springs
//! of eq 1, 2, 5, 6 and the energy dissipated by slip, plastic caps (eq 7), breakage and the
//! contact dashpots.

use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};
use std::ops::AddAssign;

/// Energy dissipated (J), either in one update (an increment) or accumulated over a contact's
/// life (the `dissipated` field of a state).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Dissipation {
    /// Coulomb slip of a non-cohesive contact (or of a link that lost its cohesion).
    pub friction: Real,
    /// Plastic caps of a cohesive link (eq 7): tension, cohesive shear, twist, bending.
    pub plastic: Real,
    /// Elastic energy released when a fragile link breaks or loses cohesion.
    pub breakage: Real,
    /// The dashpots of a damped contact (model.md §7): `−F_d·v_rel·dt` per update, `F_d` the
    /// dashpots' force as applied and `v_rel` the relative velocity the update was given.
    pub viscous: Real,
}

impl Dissipation {
    /// Sum of the four terms.
    pub fn total(&self) -> Real {
        self.friction + self.plastic + self.breakage + self.viscous
    }
}

impl AddAssign for Dissipation {
    fn add_assign(&mut self, o: Self) {
        self.friction += o.friction;
        self.plastic += o.plastic;
        self.breakage += o.breakage;
        self.viscous += o.viscous;
    }
}

/// Energy F²/(2k) of a linear spring of stiffness k carrying a force (or moment) of magnitude
/// `f`; 0 when k ≤ 0.
#[inline]
pub fn spring_energy(f: Real, k: Real) -> Real {
    if k > 0.0 {
        0.5 * f * f / k
    } else {
        0.0
    }
}

/// Energy F²/(2k) of a linear spring from the squared magnitude F² of its force (or moment),
/// without the square root; 0 when k ≤ 0.
#[inline]
pub fn spring_energy_squared(f2: Real, k: Real) -> Real {
    if k > 0.0 {
        0.5 * f2 / k
    } else {
        0.0
    }
}

/// Energy dissipated when a trial force of magnitude `trial` is capped to `capped` on a spring
/// of stiffness k: the work of the capped force over the slip (|F_trial| − |F_capped|)/k, i.e.
/// (|F_trial| − |F_capped|)·|F_capped|/k (YADE's form). 0 when k ≤ 0 or nothing was capped.
///
/// Exact for slip at a constant cap; when the cap itself shrinks during a step (a cohesive shear
/// limit lowered by growing tension) it under-reports by (|F_trial| − |F_capped|)²/(2k), an
/// O(step²) error per step that vanishes with small steps.
#[inline]
pub fn cap_dissipation(trial: Real, capped: Real, k: Real) -> Real {
    if k > 0.0 && trial > capped {
        (trial - capped) * capped / k
    } else {
        0.0
    }
}

/// Energy dissipated in one step by a slip from the trial force `trial` back to the capped
/// force `capped`, on a spring of stiffness k whose force was `old` at the previous step:
/// `½·(F_old + F_capped)·(F_trial − F_capped)/k` — the slip `(F_trial − F_capped)/k` times the
/// mean force over the step. This is the energy the leapfrog loses with the slip: for a
/// spring with a moving plastic offset, the leapfrog's modified energy
/// `½m·v(t−dt/2)·v(t+dt/2) + F²/(2k)` changes by exactly this amount, so the balance closes.
/// YADE's `(|F_trial| − |F_capped|)·|F_capped|/k` ([`cap_dissipation`]) misses
/// `(|F_old| − |F_capped|)` times half the slip, which adds up when contacts open and close.
/// The result is never negative: a step whose increment reverses the force past the opposite
/// limit (`F_old` and `F_trial` opposed) would give a negative value, an artefact of a step
/// too coarse to follow the reversal, and counts as no dissipation.
#[inline]
pub fn slip_dissipation(old: &Vec3, trial: &Vec3, capped: &Vec3, k: Real) -> Real {
    slip_energy(old, trial, capped, k).max(0.0)
}

/// [`slip_dissipation`] without its floor at 0: `½·(F_old + F_capped)·(F_trial − F_capped)/k`,
/// the energy the spring loses in the slip, exactly (0 when k ≤ 0). A damped contact uses it
/// (model.md §7): when its tangential dashpot alone exceeds the Coulomb limit, the spring is
/// set against the slip (LAMMPS's rescaling) and takes energy, which this counts as a negative
/// friction dissipation so that the balance closes.
#[inline]
pub fn slip_energy(old: &Vec3, trial: &Vec3, capped: &Vec3, k: Real) -> Real {
    if k > 0.0 {
        0.5 * (old + capped).dot(&(trial - capped)) / k
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slip_dissipation_is_mean_force_times_slip() {
        let k = 10.0;
        // steady sliding: old = capped = 2, trial = 3: slip 0.1, mean force 2
        let d = slip_dissipation(
            &Vec3::new(2.0, 0.0, 0.0),
            &Vec3::new(3.0, 0.0, 0.0),
            &Vec3::new(2.0, 0.0, 0.0),
            k,
        );
        assert!((d - 0.2).abs() < 1e-15);
        // unloading cap: old 4, capped 2, trial 3: slip 0.1, mean force 3
        let d = slip_dissipation(
            &Vec3::new(4.0, 0.0, 0.0),
            &Vec3::new(3.0, 0.0, 0.0),
            &Vec3::new(2.0, 0.0, 0.0),
            k,
        );
        assert!((d - 0.3).abs() < 1e-15);
        // reversal past the opposite limit: clamped to 0
        let d = slip_dissipation(
            &Vec3::new(5.0, 0.0, 0.0),
            &Vec3::new(-15.0, 0.0, 0.0),
            &Vec3::new(-3.0, 0.0, 0.0),
            k,
        );
        assert_eq!(d, 0.0);
        assert_eq!(slip_dissipation(&Vec3::x(), &Vec3::x(), &Vec3::x(), 0.0), 0.0);
        // ... which slip_energy keeps: ½·(5 − 3)·(−15 + 3)/10
        let e = slip_energy(
            &Vec3::new(5.0, 0.0, 0.0),
            &Vec3::new(-15.0, 0.0, 0.0),
            &Vec3::new(-3.0, 0.0, 0.0),
            k,
        );
        assert!((e + 1.2).abs() < 1e-15, "{e}");
    }

    #[test]
    fn spring_and_cap_energies() {
        assert_eq!(spring_energy(2.0, 4.0), 0.5);
        assert_eq!(spring_energy(2.0, 0.0), 0.0);
        // Slip of (5 − 3)/2 = 1 under a force of 3: 3 J.
        assert_eq!(cap_dissipation(5.0, 3.0, 2.0), 3.0);
        assert_eq!(cap_dissipation(3.0, 3.0, 2.0), 0.0);
        let mut d = Dissipation { friction: 1.0, ..Default::default() };
        d += Dissipation { friction: 1.0, plastic: 2.0, breakage: 3.0, viscous: 4.0 };
        assert_eq!(d.total(), 11.0);
    }
}
