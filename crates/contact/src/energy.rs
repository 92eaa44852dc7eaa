//! Energy terms of one contact or link (model.md §6): elastic energy stored in the springs of
//! eq 1, 2, 5, 6 and the energy dissipated by slip, plastic caps (eq 7) and breakage.

use flexdem_geom::Real;
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
}

impl Dissipation {
    /// Sum of the three terms.
    pub fn total(&self) -> Real {
        self.friction + self.plastic + self.breakage
    }
}

impl AddAssign for Dissipation {
    fn add_assign(&mut self, o: Self) {
        self.friction += o.friction;
        self.plastic += o.plastic;
        self.breakage += o.breakage;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spring_and_cap_energies() {
        assert_eq!(spring_energy(2.0, 4.0), 0.5);
        assert_eq!(spring_energy(2.0, 0.0), 0.0);
        // Slip of (5 − 3)/2 = 1 under a force of 3: 3 J.
        assert_eq!(cap_dissipation(5.0, 3.0, 2.0), 3.0);
        assert_eq!(cap_dissipation(3.0, 3.0, 2.0), 0.0);
        let mut d = Dissipation { friction: 1.0, ..Default::default() };
        d += Dissipation { friction: 1.0, plastic: 2.0, breakage: 3.0 };
        assert_eq!(d.total(), 7.0);
    }
}
