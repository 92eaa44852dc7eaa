//! Materials (paper §2): elastic constants, density, friction and the strengths of eq 7, with
//! validation that names the bad field, its value and what is expected.

use flexdem_geom::Real;
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_2;

/// What a cohesive link does when it reaches a limit of eq 7.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum FailureMode {
    /// Tensile limit exceeded: the link breaks for good. Shear (or moment) limit exceeded: the
    /// link loses its cohesion and becomes a frictional, compression-only contact.
    #[default]
    Fragile,
    /// The force or moment is capped at the limit; the excess becomes a plastic offset, so
    /// unloading is elastic.
    Plastic,
}

/// Viscous contact damping of a material (model.md §7): how the dashpots of its contacts are
/// set. `None` (the default) is the purely elastic–frictional contact of the paper.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, Default)]
pub enum ContactDamping {
    /// No dashpot.
    #[default]
    None,
    /// A coefficient of restitution e, 0 < e ≤ 1: the normal damping ratio
    /// ζ = −ln e/√(π² + ln² e) of a linear spring–dashpot, cn = 2ζ·√(m_eff·kn) and
    /// ct = 2ζ·√(m_eff·ks) (the same ratio, as LIGGGHTS does).
    Restitution(Real),
    /// Damping rates per unit mass (1/s), LAMMPS `gran/hooke` style: cn = m_eff·γn,
    /// ct = m_eff·γt.
    Viscous {
        /// γn (1/s), finite and ≥ 0.
        gamma_n: Real,
        /// γt (1/s), finite and ≥ 0.
        gamma_t: Real,
    },
}

/// A material (paper §2–3).
///
/// - `young` E (Pa) and `poisson` ν, a **true** Poisson ratio: it gives G = E/(2(1+ν)) for the
///   torsion stiffness of beam links (eq 8).
/// - `shear_ratio`: the ratio ks/kn used as "ν" in eq 4 for contacts (YADE's `poisson`).
/// - `density` ρ (kg/m³), `friction_angle` φ (radians).
/// - `tensile_strength` σn and `shear_strength` σs (Pa) of eq 7. `None` or a negative value means
///   unbreakable (YADE's negative defaults break every link at step 1; flexdem reads them as
///   infinite, which is what YADE's documentation promises).
/// - `failure`: fragile or plastic behaviour at the limits.
/// - `moments`: whether cohesive links carry twisting and bending moments (eq 5, 6).
/// - `damping`: the viscous damping of its contacts ([`ContactDamping`], model.md §7).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Young's modulus E (Pa), finite and > 0.
    pub young: Real,
    /// True Poisson ratio ν, −1 < ν ≤ 0.5 (torsion of links: G = E/(2(1+ν))).
    pub poisson: Real,
    /// Ratio ks/kn used in eq 4 for contacts, ≥ 0 (YADE's "poisson").
    pub shear_ratio: Real,
    /// Density ρ (kg/m³), finite and > 0.
    pub density: Real,
    /// Friction angle φ (radians), 0 ≤ φ < π/2.
    pub friction_angle: Real,
    /// Tensile strength σn (Pa); `None` or negative = unbreakable in tension.
    pub tensile_strength: Option<Real>,
    /// Shear strength σs (Pa); `None` or negative = unbreakable in shear.
    pub shear_strength: Option<Real>,
    /// Fragile or plastic behaviour at the limits of eq 7.
    pub failure: FailureMode,
    /// Cohesive links carry twisting and bending moments (eq 5, 6).
    pub moments: bool,
    /// Viscous damping of its contacts (model.md §7); [`ContactDamping::None`] by default.
    pub damping: ContactDamping,
}

/// A material value that does not make sense. Each message names the field, the value given
/// and what is expected.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum MaterialError {
    /// Young's modulus not finite or not positive.
    #[error("material field `young` (Young's modulus) is {0}: expected a finite value > 0 (Pa)")]
    Young(Real),
    /// Poisson ratio outside (−1, 0.5].
    #[error("material field `poisson` (Poisson ratio) is {0}: expected -1 < poisson <= 0.5")]
    Poisson(Real),
    /// Negative or non-finite ks/kn ratio.
    #[error("material field `shear_ratio` (ks/kn of eq 4) is {0}: expected a finite value >= 0")]
    ShearRatio(Real),
    /// Density not finite or not positive.
    #[error("material field `density` is {0}: expected a finite value > 0 (kg/m^3)")]
    Density(Real),
    /// Friction angle outside [0, π/2).
    #[error(
        "material field `friction_angle` is {0}: expected radians with 0 <= friction_angle < pi/2 \
         (did you pass degrees?)"
    )]
    FrictionAngle(Real),
    /// NaN tensile strength.
    #[error(
        "material field `tensile_strength` is {0}: expected a number (None or negative = unbreakable)"
    )]
    TensileStrength(Real),
    /// NaN shear strength.
    #[error(
        "material field `shear_strength` is {0}: expected a number (None or negative = unbreakable)"
    )]
    ShearStrength(Real),
    /// Coefficient of restitution outside (0, 1] (or NaN).
    #[error(
        "material field `restitution` (coefficient of restitution) is {0}: expected 0 < restitution <= 1"
    )]
    Restitution(Real),
    /// Negative or non-finite normal damping rate.
    #[error("material field `gamma_n` (normal damping per unit mass) is {0}: expected a finite value >= 0 (1/s)")]
    GammaN(Real),
    /// Negative or non-finite tangential damping rate.
    #[error("material field `gamma_t` (tangential damping per unit mass) is {0}: expected a finite value >= 0 (1/s)")]
    GammaT(Real),
}

impl Material {
    /// A checked material with `shear_ratio = poisson`, no strengths (unbreakable), fragile,
    /// moments on. Use the `with_*` methods and [`Material::validate`] (or
    /// [`Material::checked`]) for the other fields.
    pub fn new(
        young: Real,
        poisson: Real,
        density: Real,
        friction_angle: Real,
    ) -> Result<Self, MaterialError> {
        Material {
            young,
            poisson,
            shear_ratio: poisson,
            density,
            friction_angle,
            tensile_strength: None,
            shear_strength: None,
            failure: FailureMode::Fragile,
            moments: true,
            damping: ContactDamping::None,
        }
        .checked()
    }

    /// Sets the ks/kn ratio of eq 4 (unchecked until [`Material::checked`]).
    pub fn with_shear_ratio(mut self, shear_ratio: Real) -> Self {
        self.shear_ratio = shear_ratio;
        self
    }

    /// Sets the tensile strength σn of eq 7 (`None` or negative = unbreakable).
    pub fn with_tensile_strength(mut self, sigma_n: Option<Real>) -> Self {
        self.tensile_strength = sigma_n;
        self
    }

    /// Sets the shear strength σs of eq 7 (`None` or negative = unbreakable).
    pub fn with_shear_strength(mut self, sigma_s: Option<Real>) -> Self {
        self.shear_strength = sigma_s;
        self
    }

    /// Sets the failure mode.
    pub fn with_failure(mut self, failure: FailureMode) -> Self {
        self.failure = failure;
        self
    }

    /// Switches link moments (eq 5, 6) on or off.
    pub fn with_moments(mut self, moments: bool) -> Self {
        self.moments = moments;
        self
    }

    /// Sets the viscous damping of its contacts (unchecked until [`Material::checked`]).
    pub fn with_damping(mut self, damping: ContactDamping) -> Self {
        self.damping = damping;
        self
    }

    /// `self` if [`Material::validate`] passes.
    pub fn checked(self) -> Result<Self, MaterialError> {
        self.validate().map(|()| self)
    }

    /// Checks every field: E > 0 finite, −1 < ν ≤ 0.5, shear_ratio ≥ 0 finite, ρ > 0 finite,
    /// 0 ≤ φ < π/2, strengths not NaN, a restitution in (0, 1], damping rates finite and
    /// ≥ 0. Reports the first bad field in declaration order.
    pub fn validate(&self) -> Result<(), MaterialError> {
        let ok = |c: bool, e: MaterialError| if c { Ok(()) } else { Err(e) };
        ok(self.young.is_finite() && self.young > 0.0, MaterialError::Young(self.young))?;
        ok(self.poisson > -1.0 && self.poisson <= 0.5, MaterialError::Poisson(self.poisson))?;
        ok(
            self.shear_ratio.is_finite() && self.shear_ratio >= 0.0,
            MaterialError::ShearRatio(self.shear_ratio),
        )?;
        ok(self.density.is_finite() && self.density > 0.0, MaterialError::Density(self.density))?;
        ok(
            self.friction_angle >= 0.0 && self.friction_angle < FRAC_PI_2,
            MaterialError::FrictionAngle(self.friction_angle),
        )?;
        if let Some(s) = self.tensile_strength {
            ok(!s.is_nan(), MaterialError::TensileStrength(s))?;
        }
        if let Some(s) = self.shear_strength {
            ok(!s.is_nan(), MaterialError::ShearStrength(s))?;
        }
        let rate = |g: Real| g.is_finite() && g >= 0.0;
        match self.damping {
            ContactDamping::None => {}
            ContactDamping::Restitution(e) => {
                ok(e > 0.0 && e <= 1.0, MaterialError::Restitution(e))?;
            }
            ContactDamping::Viscous { gamma_n, gamma_t } => {
                ok(rate(gamma_n), MaterialError::GammaN(gamma_n))?;
                ok(rate(gamma_t), MaterialError::GammaT(gamma_t))?;
            }
        }
        Ok(())
    }

    /// Shear modulus G = E/(2(1+ν)) (eq 8, links).
    pub fn shear_modulus(&self) -> Real {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    /// Tensile strength σn, `None` when unbreakable (absent or negative).
    pub fn effective_tensile_strength(&self) -> Option<Real> {
        effective_strength(self.tensile_strength)
    }

    /// Shear strength σs, `None` when unbreakable (absent or negative).
    pub fn effective_shear_strength(&self) -> Option<Real> {
        effective_strength(self.shear_strength)
    }
}

/// A strength as used by eq 7: absent or negative = unbreakable (`None`).
pub fn effective_strength(s: Option<Real>) -> Option<Real> {
    s.filter(|&v| v >= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Material {
        Material::new(210e9, 0.3, 7850.0, 0.5).unwrap()
    }

    #[test]
    fn new_defaults() {
        let m = steel();
        assert_eq!(m.shear_ratio, 0.3);
        assert_eq!(m.tensile_strength, None);
        assert_eq!(m.failure, FailureMode::Fragile);
        assert!(m.moments);
        assert_eq!(m.damping, ContactDamping::None);
        let e1 = m.with_damping(ContactDamping::Restitution(1.0));
        assert!(e1.validate().is_ok(), "e = 1 is an elastic dashpot-free contact");
        assert!((m.shear_modulus() - 210e9 / 2.6).abs() < 1.0);
    }

    #[test]
    fn negative_strength_is_unbreakable() {
        let m = steel().with_tensile_strength(Some(-1.0)).with_shear_strength(Some(2e6));
        assert!(m.validate().is_ok());
        assert_eq!(m.effective_tensile_strength(), None);
        assert_eq!(m.effective_shear_strength(), Some(2e6));
    }

    fn err_msg(m: Material) -> String {
        m.validate().unwrap_err().to_string()
    }

    #[test]
    fn each_bad_field_gives_its_message() {
        let m = steel();
        let cases: Vec<(Material, MaterialError, &str)> = vec![
            (Material { young: -1.0, ..m }, MaterialError::Young(-1.0), "`young`"),
            (Material { young: 0.0, ..m }, MaterialError::Young(0.0), "> 0"),
            (
                Material { young: Real::INFINITY, ..m },
                MaterialError::Young(Real::INFINITY),
                "finite",
            ),
            (Material { poisson: 0.6, ..m }, MaterialError::Poisson(0.6), "`poisson`"),
            (Material { poisson: -1.0, ..m }, MaterialError::Poisson(-1.0), "-1 < poisson"),
            (Material { shear_ratio: -0.1, ..m }, MaterialError::ShearRatio(-0.1), "`shear_ratio`"),
            (Material { density: 0.0, ..m }, MaterialError::Density(0.0), "`density`"),
            (Material { friction_angle: 30.0, ..m }, MaterialError::FrictionAngle(30.0), "degrees"),
            (
                Material { friction_angle: -0.1, ..m },
                MaterialError::FrictionAngle(-0.1),
                "`friction_angle`",
            ),
            (
                m.with_damping(ContactDamping::Restitution(0.0)),
                MaterialError::Restitution(0.0),
                "`restitution`",
            ),
            (
                m.with_damping(ContactDamping::Restitution(1.5)),
                MaterialError::Restitution(1.5),
                "0 < restitution <= 1",
            ),
            (
                m.with_damping(ContactDamping::Viscous { gamma_n: -1.0, gamma_t: 0.0 }),
                MaterialError::GammaN(-1.0),
                "`gamma_n`",
            ),
            (
                m.with_damping(ContactDamping::Viscous { gamma_n: 1.0, gamma_t: Real::INFINITY }),
                MaterialError::GammaT(Real::INFINITY),
                "`gamma_t`",
            ),
        ];
        for (bad, err, needle) in cases {
            assert_eq!(bad.validate(), Err(err));
            let msg = err_msg(bad);
            assert!(msg.contains(needle), "{msg} lacks {needle}");
        }
    }

    #[test]
    fn nan_rejected_everywhere() {
        let m = steel();
        let nan = Real::NAN;
        let bads = [
            Material { young: nan, ..m },
            Material { poisson: nan, ..m },
            Material { shear_ratio: nan, ..m },
            Material { density: nan, ..m },
            Material { friction_angle: nan, ..m },
            m.with_tensile_strength(Some(nan)),
            m.with_shear_strength(Some(nan)),
            m.with_damping(ContactDamping::Restitution(nan)),
            m.with_damping(ContactDamping::Viscous { gamma_n: nan, gamma_t: 0.0 }),
            m.with_damping(ContactDamping::Viscous { gamma_n: 0.0, gamma_t: nan }),
        ];
        let fields = [
            "`young`",
            "`poisson`",
            "`shear_ratio`",
            "`density`",
            "`friction_angle`",
            "`tensile_strength`",
            "`shear_strength`",
            "`restitution`",
            "`gamma_n`",
            "`gamma_t`",
        ];
        for (bad, field) in bads.into_iter().zip(fields) {
            let msg = err_msg(bad);
            assert!(msg.contains(field) && msg.contains("NaN"), "{msg}");
        }
        assert!(Material::new(nan, 0.3, 1000.0, 0.5).is_err());
    }
}
