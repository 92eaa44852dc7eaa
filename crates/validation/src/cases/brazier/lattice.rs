//! Analytic stiffness of the tube's wall: the PFacet lattice as a pin-jointed truss in its
//! plane, its ring-bending stiffness, and Brazier's limit moment (eq 18).

use super::TubeCase;
use flexdem_geom::Real;
use std::f64::consts::PI;

/// In-plane and ring-bending stiffness of the tube's lattice of beam links.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatticeStiffness {
    /// Axial membrane stiffness C (N/m): axial force per unit circumference per unit axial
    /// strain, under uniaxial axial stress (ring and shear stresses zero).
    pub axial: Real,
    /// Poisson ratio of the membrane under that stress: −ε_θ/ε_x.
    pub poisson: Real,
    /// Ring-bending stiffness D (N·m): bending moment per unit length of tube per unit
    /// curvature of the ring.
    pub ring_bending: Real,
}

impl LatticeStiffness {
    /// The lattice of `tube`: cells a (chord, around) × b (along) with bars along the axis
    /// (length b), around (a) and one diagonal (c = √(a² + b²)), each of axial stiffness
    /// EA/length (A = πr², beam link kn of eq 8). Membrane stiffness of the truss:
    /// Q = (EA/(ab))·Σ_bars ℓ·v·vᵀ with v = (cos²θ, sin²θ, sinθcosθ), θ the bar's angle to
    /// the axis; C = 1/S₁₁, ν = −S₂₁/S₁₁ with S = Q⁻¹ (shear free). Ring bending: each bar
    /// bent along its length by κ·sin²θ and twisted by κ·sinθcosθ stores
    /// ½ℓ(EI·sin⁴θ + GJ·sin²θcos²θ)κ², so D = Σ_bars ℓ(EI·sin⁴θ + GJ·sin²θcos²θ)/(ab),
    /// I = πr⁴/4, J = 2I, G = E/(2(1 + ν)).
    pub fn of(tube: &TubeCase) -> LatticeStiffness {
        let a = tube.chord();
        let b = tube.length / tube.n_along as Real;
        let c = a.hypot(b);
        let e = tube.young;
        let r = tube.node_radius;
        let ea = e * PI * r * r;
        let ei = e * PI * r.powi(4) / 4.0;
        let gj = e / (2.0 * (1.0 + tube.poisson)) * 2.0 * PI * r.powi(4) / 4.0;
        // (length, cos θ, sin θ) of the three bars of a cell
        let bars = [(b, 1.0, 0.0), (a, 0.0, 1.0), (c, b / c, a / c)];
        let mut q = [[0.0; 3]; 3];
        let mut d = 0.0;
        for (l, cs, sn) in bars {
            let v = [cs * cs, sn * sn, sn * cs];
            for (i, row) in q.iter_mut().enumerate() {
                for (j, qij) in row.iter_mut().enumerate() {
                    *qij += ea * l * v[i] * v[j] / (a * b);
                }
            }
            d += l * (ei * sn.powi(4) + gj * sn * sn * cs * cs) / (a * b);
        }
        let s = inverse_3x3(&q);
        LatticeStiffness { axial: 1.0 / s[0][0], poisson: -s[1][0] / s[0][0], ring_bending: d }
    }
}

/// Inverse of a 3×3 matrix by cofactors (the membrane matrix is symmetric positive definite).
fn inverse_3x3(m: &[[Real; 3]; 3]) -> [[Real; 3]; 3] {
    let cof = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
    };
    let det = (0..3).map(|j| m[0][j] * cof(0, j)).sum::<Real>();
    let mut inv = [[0.0; 3]; 3];
    for (i, row) in inv.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = cof(j, i) / det;
        }
    }
    inv
}

/// Eq 18: M_max = 2√2·K_n·d / (9(1 − ν²)), K_n the tension stiffness (N per unit strain), ν
/// the wall's Poisson ratio, d the wall thickness.
pub fn eq18_moment(k_n: Real, poisson: Real, d: Real) -> Real {
    2.0 * 2.0_f64.sqrt() * k_n * d / (9.0 * (1.0 - poisson * poisson))
}

/// Brazier's limit moment of a thin tube of radius R whose wall has axial membrane stiffness
/// C and ring-bending stiffness D: M = (2√2π/9)·R·√(12·C·D) (for a continuous wall of
/// thickness t, C = Et and D = Et³/(12(1 − ν²)) give (2√2/9)·π·E·R·t²/√(1 − ν²)).
pub fn brazier_moment(radius: Real, axial: Real, ring_bending: Real) -> Real {
    2.0 * 2.0_f64.sqrt() * PI / 9.0 * radius * (12.0 * axial * ring_bending).sqrt()
}

/// One point of Brazier's pre-buckling path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BrazierPoint {
    /// Curvature κ (1/m).
    pub curvature: Real,
    /// Moment M (N·m).
    pub moment: Real,
    /// Ovalisation ζ (diameters 2R(1 ± ζ)).
    pub ovalisation: Real,
}

/// Brazier's path from κ = 0 to the limit κ* = √(8D/(3CR⁴)) in `n` ≥ 2 points:
/// ζ = C·R⁴·κ²/(12·D) and M = EI·κ·(1 − (κ/κ*)²/3), with EI the section's bending stiffness
/// (πR³C for a continuous wall); M is largest at κ*, where ζ = 2/9.
pub fn brazier_path(
    radius: Real,
    axial: Real,
    ring_bending: Real,
    bending_stiffness: Real,
    n: usize,
) -> Vec<BrazierPoint> {
    let r4 = radius.powi(4);
    let limit = (8.0 * ring_bending / (3.0 * axial * r4)).sqrt();
    let n = n.max(2);
    (0..n)
        .map(|i| {
            let kappa = limit * i as Real / (n - 1) as Real;
            BrazierPoint {
                curvature: kappa,
                moment: bending_stiffness * kappa * (1.0 - (kappa / limit).powi(2) / 3.0),
                ovalisation: axial * r4 * kappa * kappa / (12.0 * ring_bending),
            }
        })
        .collect()
}

impl TubeCase {
    /// Period of the slowest of the two modes that govern the quasi-static bending: the first
    /// bending mode of the tube as a cantilever, ω = 1.875²·√(EI/(μL⁴)) with EI = πR³·C and
    /// μ = 2πR·ρ_s, and the ovalisation (n = 2) mode of a ring,
    /// ω² = (36/5)·D/(ρ_s·R⁴) (ring of bending stiffness D per unit length).
    pub fn slowest_period(&self) -> Real {
        let lattice = LatticeStiffness::of(self);
        let rho_s = self.areal_mass();
        let ei = PI * self.radius.powi(3) * lattice.axial;
        let mu = 2.0 * PI * self.radius * rho_s;
        let w_bend = 1.875_f64.powi(2) * (ei / (mu * self.length.powi(4))).sqrt();
        let w_oval = (7.2 * lattice.ring_bending / (rho_s * self.radius.powi(4))).sqrt();
        2.0 * PI / w_bend.min(w_oval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brazier_moment_of_a_continuous_shell_is_the_classical_one() {
        let (e, nu, r, t): (Real, Real, Real, Real) = (2.0e11, 0.3, 0.5, 0.01);
        let d = e * t.powi(3) / (12.0 * (1.0 - nu * nu));
        let classical = 2.0 * 2.0_f64.sqrt() / 9.0 * PI * e * r * t * t / (1.0 - nu * nu).sqrt();
        let m = brazier_moment(r, e * t, d);
        assert!((m / classical - 1.0).abs() < 1e-12, "{m} {classical}");
        // eq 18 with K_n = πR·Et is the same up to √(1 − ν²)
        let m18 = eq18_moment(PI * r * e * t, nu, t);
        assert!((m18 * (1.0 - nu * nu).sqrt() / classical - 1.0).abs() < 1e-12);
    }

    #[test]
    fn brazier_path_peaks_at_the_limit_moment_with_ovalisation_two_ninths() {
        let (r, c, d) = (0.1, 3000.0, 0.005);
        let path = brazier_path(r, c, d, PI * r.powi(3) * c, 101);
        let last = path.last().unwrap();
        assert!((last.moment / brazier_moment(r, c, d) - 1.0).abs() < 1e-12);
        assert!((last.ovalisation - 2.0 / 9.0).abs() < 1e-12);
        assert!(path.windows(2).all(|w| w[1].moment > w[0].moment));
    }

    #[test]
    fn lattice_with_one_diagonal_carries_axial_tension_in_its_axial_bars_only() {
        let tube = TubeCase::default();
        let l = LatticeStiffness::of(&tube);
        let ea = tube.young * PI * tube.node_radius.powi(2);
        assert!((l.axial / (ea / tube.chord()) - 1.0).abs() < 1e-9, "{l:?}");
        assert!(l.poisson.abs() < 1e-9, "{l:?}");
        assert!(l.ring_bending > 0.0);
    }
}
