//! Viscous contact damping (model.md §7): the normal and tangential dashpots `cn`, `ct`
//! (N·s/m) of a contact, from the [`ContactDamping`] of its two materials and the pair's
//! effective mass.

use crate::material::{ContactDamping, Material};
use flexdem_geom::Real;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The dashpots of a contact (N·s/m); 0 is no dashpot.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Dashpots {
    /// Normal dashpot cn.
    pub cn: Real,
    /// Tangential dashpot ct.
    pub ct: Real,
}

/// The damping ratio of a linear spring–dashpot whose coefficient of restitution is `e`
/// (0 < e ≤ 1): `ζ = −ln e / √(π² + ln² e)`, the inverse of `e = exp(−πζ/√(1 − ζ²))`
/// ([`restitution_of_ratio`]). 0 for e = 1; it tends to 1 as e tends to 0.
pub fn damping_ratio(e: Real) -> Real {
    let l = e.ln();
    -l / (PI * PI + l * l).sqrt()
}

/// The coefficient of restitution of a linear spring–dashpot of damping ratio ζ whose force
/// may pull (no clamp at Fn ≥ 0): `e = exp(−πζ/√(1 − ζ²))` for ζ < 1, 0 when overdamped.
pub fn restitution_of_ratio(zeta: Real) -> Real {
    if zeta >= 1.0 {
        0.0
    } else {
        (-PI * zeta / (1.0 - zeta * zeta).sqrt()).exp()
    }
}

/// The effective mass `m1·m2/(m1 + m2)` of two bodies (kg); an infinitely massive body (a
/// wall, a site whose nodes are held) gives the other's mass, two give infinity.
pub fn effective_mass(m1: Real, m2: Real) -> Real {
    match (m1.is_finite(), m2.is_finite()) {
        (true, true) => m1 * m2 / (m1 + m2),
        (false, true) => m2,
        (true, false) => m1,
        (false, false) => Real::INFINITY,
    }
}

/// The dashpots one material asks for on a contact of effective mass `m_eff` and stiffnesses
/// `kn`, `ks`: with a restitution e, `cn = 2ζ·√(m_eff·kn)`, `ct = 2ζ·√(m_eff·ks)`,
/// ζ = [`damping_ratio`]`(e)`; with rates per unit mass, `cn = m_eff·γn`, `ct = m_eff·γt`
/// (LAMMPS `gran/hooke`).
pub fn material_dashpots(m: &Material, m_eff: Real, kn: Real, ks: Real) -> Dashpots {
    match m.damping {
        ContactDamping::None => Dashpots::default(),
        ContactDamping::Restitution(e) => {
            let zeta = damping_ratio(e);
            Dashpots {
                cn: 2.0 * zeta * (m_eff * kn.max(0.0)).sqrt(),
                ct: 2.0 * zeta * (m_eff * ks.max(0.0)).sqrt(),
            }
        }
        ContactDamping::Viscous { gamma_n, gamma_t } => {
            Dashpots { cn: m_eff * gamma_n, ct: m_eff * gamma_t }
        }
    }
}

/// The dashpots of a contact between materials `m1` and `m2` (model.md §7): each material's
/// [`material_dashpots`] with the pair's `m_eff`, `kn`, `ks`, and for each coefficient the
/// larger of the two (the more dissipative material sets it; a material without damping
/// against a damped one gives the damped one's). No dashpot when `m_eff` is not finite or not
/// > 0 (two bodies neither of which can move).
pub fn contact_dashpots(m1: &Material, m2: &Material, m_eff: Real, kn: Real, ks: Real) -> Dashpots {
    if !(m_eff.is_finite() && m_eff > 0.0) {
        return Dashpots::default();
    }
    let (a, b) = (material_dashpots(m1, m_eff, kn, ks), material_dashpots(m2, m_eff, kn, ks));
    Dashpots { cn: a.cn.max(b.cn), ct: a.ct.max(b.ct) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mat(damping: ContactDamping) -> Material {
        Material::new(1e8, 0.3, 2650.0, 0.5).unwrap().with_damping(damping)
    }

    #[test]
    fn the_ratio_inverts_the_restitution() {
        assert_eq!(damping_ratio(1.0), 0.0);
        for e in [0.9, 0.5, 0.1, 1e-3] {
            let z = damping_ratio(e);
            assert!(z > 0.0 && z < 1.0);
            assert!((restitution_of_ratio(z) / e - 1.0).abs() < 1e-13, "{e}: {z}");
        }
        assert_eq!(restitution_of_ratio(1.0), 0.0);
    }

    #[test]
    fn walls_and_held_sites_are_infinitely_massive() {
        assert_eq!(effective_mass(2.0, 2.0), 1.0);
        assert_eq!(effective_mass(Real::INFINITY, 3.0), 3.0);
        assert_eq!(effective_mass(3.0, Real::INFINITY), 3.0);
        assert_eq!(effective_mass(Real::INFINITY, Real::INFINITY), Real::INFINITY);
        let d = mat(ContactDamping::Restitution(0.5));
        assert_eq!(contact_dashpots(&d, &d, Real::INFINITY, 1e6, 1e5), Dashpots::default());
    }

    #[test]
    fn the_more_dissipative_material_sets_each_dashpot() {
        let (m_eff, kn, ks): (Real, Real, Real) = (0.5, 1e6, 3e5);
        let none = mat(ContactDamping::None);
        let e = mat(ContactDamping::Restitution(0.5));
        let g = mat(ContactDamping::Viscous { gamma_n: 100.0, gamma_t: 2000.0 });
        let z = damping_ratio(0.5);
        let de = Dashpots { cn: 2.0 * z * (m_eff * kn).sqrt(), ct: 2.0 * z * (m_eff * ks).sqrt() };
        assert_eq!(contact_dashpots(&none, &none, m_eff, kn, ks), Dashpots::default());
        assert_eq!(contact_dashpots(&none, &e, m_eff, kn, ks), de);
        assert_eq!(contact_dashpots(&e, &none, m_eff, kn, ks), de);
        // a mix: cn from the restitution (about 305 N·s/m > 50), ct from γt (1000 > 167)
        let mixed = contact_dashpots(&e, &g, m_eff, kn, ks);
        assert_eq!(mixed, Dashpots { cn: de.cn, ct: 1000.0 });
        assert_eq!(contact_dashpots(&g, &e, m_eff, kn, ks), mixed);
    }
}
