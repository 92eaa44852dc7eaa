//! Stiffnesses: contacts (eq 3, 4) and beam links (eq 8).

use crate::material::Material;
use flexdem_geom::Real;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Normal and shear stiffness of a contact (N/m).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactStiffness {
    /// Normal stiffness kn (eq 3).
    pub kn: Real,
    /// Shear stiffness ks (eq 4).
    pub ks: Real,
}

/// Stiffnesses of a beam link (eq 8).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LinkStiffness {
    /// Axial kn = E·A/L0 (N/m).
    pub kn: Real,
    /// Shear ks = 12·E·I/L0³ (N/m).
    pub ks: Real,
    /// Bending kb = E·I/L0 (N·m/rad).
    pub kb: Real,
    /// Twist kt = G·J/L0 (N·m/rad).
    pub kt: Real,
}

/// Harmonic-type mean 2ab/(a+b) of eq 3–4, 0 when either is 0 (no 0/0).
fn series(a: Real, b: Real) -> Real {
    if a <= 0.0 || b <= 0.0 {
        0.0
    } else {
        2.0 * a * b / (a + b)
    }
}

/// Contact stiffness between spheres (E1, R1, ν1) and (E2, R2, ν2), eq 3 and 4:
///
/// kn = 2·E1R1·E2R2 / (E1R1 + E2R2) (eq 3),
/// ks = 2·E1R1ν1·E2R2ν2 / (E1R1ν1 + E2R2ν2) (eq 4),
///
/// where ν is the material's `shear_ratio` (ks/kn, YADE's "poisson"), not the Poisson ratio.
/// A non-positive radius (a wall) is replaced by the other one, as YADE does; ks = 0 when a
/// shear ratio is 0.
pub fn contact_stiffness(m1: &Material, r1: Real, m2: &Material, r2: Real) -> ContactStiffness {
    let (r1, r2) = match (r1 > 0.0, r2 > 0.0) {
        (true, false) => (r1, r1),
        (false, true) => (r2, r2),
        _ => (r1, r2),
    };
    let (a, b) = (m1.young * r1, m2.young * r2);
    ContactStiffness { kn: series(a, b), ks: series(a * m1.shear_ratio, b * m2.shear_ratio) }
}

/// Beam-link stiffnesses of a connection of radius r and rest length L0 (eq 8), with
/// A = πr², I = πr⁴/4, J = 2I and G = E/(2(1+ν)) (ν the true Poisson ratio):
///
/// kn = E·A/L0, ks = 12·E·I/L0³, kb = E·I/L0, kt = G·J/L0.
pub fn beam_link_stiffness(m: &Material, r: Real, l0: Real) -> LinkStiffness {
    let a = PI * r * r;
    let i = PI * r.powi(4) / 4.0;
    let j = 2.0 * i;
    let (e, g) = (m.young, m.shear_modulus());
    LinkStiffness {
        kn: e * a / l0,
        ks: 12.0 * e * i / (l0 * l0 * l0),
        kb: e * i / l0,
        kt: g * j / l0,
    }
}

/// Friction coefficient tanφ with φ = min(φ1, φ2) (eq 7).
pub fn friction_coefficient(m1: &Material, m2: &Material) -> Real {
    m1.friction_angle.min(m2.friction_angle).tan()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: Real, b: Real) -> Real {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn yade_cantilever_link_stiffness() {
        // L = 0.1, r = 0.01, E = 1e8, ν = 0.3 (reference values from the brief).
        let m = Material::new(1e8, 0.3, 1000.0, 0.5).unwrap();
        let k = beam_link_stiffness(&m, 0.01, 0.1);
        assert!(rel(k.kn, 3.14159e5) < 1e-5, "{}", k.kn);
        assert!(rel(k.ks, 9.42478e3) < 1e-5, "{}", k.ks);
        assert!(rel(k.kb, 7.85398) < 1e-5, "{}", k.kb);
        assert!(rel(k.kt, 6.04152) < 1e-5, "{}", k.kt);
    }

    #[test]
    fn contact_stiffness_equal_spheres() {
        // Equal E R: kn = E R, ks = ν E R.
        let m = Material::new(1e7, 0.3, 1000.0, 0.5).unwrap().with_shear_ratio(0.25);
        let k = contact_stiffness(&m, 0.02, &m, 0.02);
        assert!(rel(k.kn, 1e7 * 0.02) < 1e-14);
        assert!(rel(k.ks, 0.25 * 1e7 * 0.02) < 1e-14);
    }

    #[test]
    fn contact_stiffness_hand_values() {
        // E1R1 = 1e9·0.01 = 1e7, E2R2 = 1e8·0.05 = 5e6: kn = 2·5e13/1.5e7 = 6.6667e6.
        let m1 = Material::new(1e9, 0.3, 1000.0, 0.5).unwrap().with_shear_ratio(0.5);
        let m2 = Material::new(1e8, 0.3, 1000.0, 0.5).unwrap().with_shear_ratio(0.2);
        let k = contact_stiffness(&m1, 0.01, &m2, 0.05);
        assert!(rel(k.kn, 2.0 * 1e7 * 5e6 / 1.5e7) < 1e-14);
        // ks = 2·5e6·1e6/(5e6+1e6) = 1.6667e6.
        assert!(rel(k.ks, 2.0 * 5e6 * 1e6 / 6e6) < 1e-14);
        // Symmetric in the two bodies.
        assert_eq!(k, contact_stiffness(&m2, 0.05, &m1, 0.01));
        // A wall (radius 0) takes the sphere's radius.
        let w = contact_stiffness(&m1, 0.01, &m1, 0.0);
        assert!(rel(w.kn, 1e7) < 1e-14);
        // A zero shear ratio gives ks = 0, not NaN.
        let z = contact_stiffness(&m1.with_shear_ratio(0.0), 0.01, &m2, 0.05);
        assert_eq!(z.ks, 0.0);
    }

    #[test]
    fn friction_takes_the_smaller_angle() {
        let a = Material::new(1e7, 0.3, 1000.0, 0.2).unwrap();
        let b = Material::new(1e7, 0.3, 1000.0, 0.6).unwrap();
        assert_eq!(friction_coefficient(&a, &b), 0.2_f64.tan());
        assert_eq!(friction_coefficient(&b, &a), 0.2_f64.tan());
    }
}
