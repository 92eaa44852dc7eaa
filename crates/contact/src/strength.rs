//! Elastic limits of eq 7.

use crate::material::Material;
use flexdem_geom::Real;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The limits of eq 7 for a cohesive contact or link, as forces and moments. `None` = no limit
/// (unbreakable). With R = min(R1, R2), A = πR², It = πR⁴/4, Ib = πR⁴/8:
///
/// - |Fn| ≤ σn·A in tension,
/// - |Fs| ≤ Fn·tanφ + σs·A,
/// - Mt ≤ σn·Ib/R,
/// - Mb ≤ σs·It/R.
///
/// (The pairing of It and Ib with Mt and Mb is the paper's, kept as written.)
/// A non-cohesive contact is [`ContactStrength::frictional`]: σn = σs = 0 (pure Coulomb, no
/// tension).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactStrength {
    /// Tensile force limit σn·A (N).
    pub tensile_force: Option<Real>,
    /// Cohesive part of the shear limit σs·A (N).
    pub shear_force: Option<Real>,
    /// Twisting moment limit σn·Ib/R (N·m).
    pub twist_moment: Option<Real>,
    /// Bending moment limit σs·It/R (N·m).
    pub bending_moment: Option<Real>,
    /// tanφ, φ = min(φ1, φ2).
    pub tan_phi: Real,
}

/// The smaller of two optional strengths (`None` = infinite).
fn min_strength(a: Option<Real>, b: Option<Real>) -> Option<Real> {
    match (a, b) {
        (Some(x), Some(y)) => Some(x.min(y)),
        (x, None) => x,
        (None, y) => y,
    }
}

impl ContactStrength {
    /// The limits of a non-cohesive contact: σn = σs = 0, so no tension and |Fs| ≤ Fn·tanφ.
    pub fn frictional(tan_phi: Real) -> Self {
        ContactStrength {
            tensile_force: Some(0.0),
            shear_force: Some(0.0),
            twist_moment: Some(0.0),
            bending_moment: Some(0.0),
            tan_phi,
        }
    }

    /// Shear limit Fn·tanφ + σs·A (eq 7), clamped at ≥ 0; `None` when σs is unbreakable.
    pub fn shear_limit(&self, normal_force: Real) -> Option<Real> {
        self.shear_force.map(|c| (normal_force * self.tan_phi + c).max(0.0))
    }
}

/// Limits of eq 7 between two bodies of materials m1, m2 and radii r1, r2: σ = the smaller of
/// the two materials' strengths (a negative or absent one counts as infinite), R = min(R1, R2)
/// (a non-positive radius is ignored), φ = min(φ1, φ2).
pub fn contact_strength(m1: &Material, r1: Real, m2: &Material, r2: Real) -> ContactStrength {
    let r = match (r1 > 0.0, r2 > 0.0) {
        (true, true) => r1.min(r2),
        (true, false) => r1,
        _ => r2,
    };
    let sn = min_strength(m1.effective_tensile_strength(), m2.effective_tensile_strength());
    let ss = min_strength(m1.effective_shear_strength(), m2.effective_shear_strength());
    let a = PI * r * r;
    let it = PI * r.powi(4) / 4.0;
    let ib = PI * r.powi(4) / 8.0;
    ContactStrength {
        tensile_force: sn.map(|s| s * a),
        shear_force: ss.map(|s| s * a),
        twist_moment: sn.map(|s| s * ib / r),
        bending_moment: ss.map(|s| s * it / r),
        tan_phi: crate::stiffness::friction_coefficient(m1, m2),
    }
}

/// Limits of eq 7 for a beam link of radius r made of material m (both nodes alike).
pub fn link_strength(m: &Material, r: Real) -> ContactStrength {
    contact_strength(m, r, m, r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eq7_hand_values() {
        let m = Material::new(1e8, 0.3, 1000.0, 0.4)
            .unwrap()
            .with_tensile_strength(Some(1e6))
            .with_shear_strength(Some(2e6));
        let s = link_strength(&m, 0.01);
        let a = PI * 1e-4;
        assert!((s.tensile_force.unwrap() - 1e6 * a).abs() < 1e-9);
        assert!((s.shear_force.unwrap() - 2e6 * a).abs() < 1e-9);
        // Mt ≤ σn·(πR⁴/8)/R, Mb ≤ σs·(πR⁴/4)/R.
        assert!((s.twist_moment.unwrap() - 1e6 * PI * 1e-6 / 8.0).abs() < 1e-12);
        assert!((s.bending_moment.unwrap() - 2e6 * PI * 1e-6 / 4.0).abs() < 1e-12);
        // Shear limit Fn·tanφ + σs·A, clamped at 0 in strong tension.
        let fs = s.shear_limit(10.0).unwrap();
        assert!((fs - (10.0 * 0.4_f64.tan() + 2e6 * a)).abs() < 1e-9);
        assert_eq!(s.shear_limit(-1e9), Some(0.0));
    }

    #[test]
    fn smaller_radius_and_strength_win_and_negative_is_infinite() {
        let weak = Material::new(1e8, 0.3, 1000.0, 0.4)
            .unwrap()
            .with_tensile_strength(Some(1e5))
            .with_shear_strength(Some(-1.0));
        let strong = weak.with_tensile_strength(Some(1e7)).with_shear_strength(None);
        let s = contact_strength(&strong, 0.05, &weak, 0.01);
        assert!((s.tensile_force.unwrap() - 1e5 * PI * 1e-4).abs() < 1e-9);
        assert_eq!(s.shear_force, None);
        assert_eq!(s.bending_moment, None);
        assert_eq!(s.shear_limit(1.0), None);
        let free = strong.with_tensile_strength(None);
        let none = contact_strength(&free, 0.1, &free, 0.1);
        assert_eq!(none.tensile_force, None);
        assert_eq!(none.twist_moment, None);
    }

    #[test]
    fn frictional_is_pure_coulomb() {
        let s = ContactStrength::frictional(0.5);
        assert_eq!(s.shear_limit(2.0), Some(1.0));
        assert_eq!(s.shear_limit(-2.0), Some(0.0));
        assert_eq!(s.tensile_force, Some(0.0));
    }
}
