//! validation.md case 6: a chain pinned at both ends sagging under gravity approaches the
//! catenary of the same length.
//!
//! Continuous catenary of length S between supports a span D apart at the same height:
//! S = 2a·sinh(D/(2a)) fixes the parameter a = H/w (H the horizontal tension, w the weight
//! per length), the shape is z(x) = a·(cosh(x/a) − cosh(D/(2a))) and the mid-span sag is
//! f = a·(cosh(D/(2a)) − 1).
//!
//! flexdem's chain is N straight links of length ℓ = S/N with the weight lumped on the nodes
//! (wℓ on each inner node). The exact equilibrium of that discrete chain (inextensible,
//! without bending stiffness) is known in closed form up to one scalar equation: link k
//! carries the horizontal tension H and the vertical one V_k = (N/2 − 1/2 − k)·wℓ, so its
//! direction is (H, −V_k)/√(H² + V_k²), and H is the root of Σ ℓ·H/√(H² + V_k²) = D. Its sag
//! differs from the continuous one by the discretisation error, O(1/N²); that difference,
//! computed before the run, sets the tolerance against the catenary.

use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Check, Context, Figure};
use crate::rest::run_to_rest;
use crate::ValidationError;
use flexdem_contact::Material;
use flexdem_elements::builders::{chain, StructureOptions};
use flexdem_elements::{Dofs, Model};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation, TimeStep};
use std::f64::consts::PI;

/// Span D between the supports (m).
const SPAN: Real = 1.0;
/// Length S of the chain (m).
const LENGTH: Real = 1.2;
/// Radius of the chain (m): thin, so that the bending stiffness is negligible (see the notes).
const RADIUS: Real = 1e-5;
/// Density (kg/m³) and gravity (m/s²).
const DENSITY: Real = 7850.0;
const GRAVITY: Real = 9.81;
/// Largest axial strain aimed at: E = w·(a + f)/(A·ε) makes the most stretched link (at the
/// supports, tension w·(a + f)) stretch by this much.
const STRAIN: Real = 1e-5;
/// Cundall damping (the answer is static).
const DAMPING: Real = 0.7;

/// The catenary parameter a of a chain of length `s` over the span `d`: the root of
/// 2a·sinh(d/(2a)) = s (bisection; s > d).
pub fn catenary_parameter(d: Real, s: Real) -> Real {
    let excess = |a: Real| 2.0 * a * (d / (2.0 * a)).sinh() - s;
    // excess decreases with a: large for small a, → d − s < 0 as a → ∞
    let (mut lo, mut hi) = (d / 200.0, d);
    while excess(hi) > 0.0 {
        hi *= 2.0;
    }
    while excess(lo) < 0.0 {
        lo /= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if excess(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Equilibrium of `n` inextensible links of length `s/n` with weight `w·s/n` lumped on each
/// inner node, pinned at (−d/2, 0) and (d/2, 0): the horizontal tension H (in units of w, i.e.
/// H/w in m) and the node positions (x, z). `n` must be even for a node at mid-span.
pub fn discrete_chain(d: Real, s: Real, n: usize) -> (Real, Vec<(Real, Real)>) {
    let l = s / n as Real;
    // vertical tension (per w) of link k: (n/2 − 1/2 − k)·ℓ
    let v = |k: usize| (0.5 * n as Real - 0.5 - k as Real) * l;
    let span = |h: Real| (0..n).map(|k| l * h / (h * h + v(k) * v(k)).sqrt()).sum::<Real>();
    let (mut lo, mut hi) = (0.0, s);
    while span(hi) < d {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if span(mid) < d {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let h = 0.5 * (lo + hi);
    let mut points = vec![(-0.5 * d, 0.0)];
    for k in 0..n {
        let norm = (h * h + v(k) * v(k)).sqrt();
        let (x, z) = points[k];
        points.push((x + l * h / norm, z - l * v(k) / norm));
    }
    (h, points)
}

/// The nodes of `n` equal chords of total length `s` on a circular arc hanging between
/// (−d/2, 0, 0) and (d/2, 0, 0) in the x–z plane: the arc of half-angle θ and radius R with
/// 2R·sinθ = d and n·2R·sin(θ/n) = s (θ by bisection; s > d).
pub fn circular_arc_chain(d: Real, s: Real, n: usize) -> Vec<Vec3> {
    let n_real = n as Real;
    // chord-length ratio d/s = sinθ / (n·sin(θ/n)), decreasing in θ on (0, π)
    let ratio = |theta: Real| theta.sin() / (n_real * (theta / n_real).sin());
    let (mut lo, mut hi) = (1e-9, PI - 1e-9);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if ratio(mid) > d / s {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let theta = 0.5 * (lo + hi);
    let radius = d / (2.0 * theta.sin());
    let centre_z = radius * theta.cos();
    (0..=n)
        .map(|k| {
            let phi = -theta + 2.0 * theta * k as Real / n_real;
            Vec3::new(radius * phi.sin(), 0.0, centre_z - radius * phi.cos())
        })
        .collect()
}

/// validation.md case 6: catenary.
pub fn run_catenary(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let n: usize = 20;
    let a = catenary_parameter(SPAN, LENGTH);
    let sag = a * ((SPAN / (2.0 * a)).cosh() - 1.0);
    let (h_discrete, discrete) = discrete_chain(SPAN, LENGTH, n);
    let sag_discrete = -discrete[n / 2].1;
    let discretisation = (sag_discrete - sag).abs() / sag;
    // tolerance: twice the discretisation error, rounded up to one significant digit
    let tol_catenary = {
        let t = 2.0 * discretisation;
        let scale = 10f64.powf(t.log10().floor());
        (t / scale).ceil() * scale
    };
    let area = PI * RADIUS * RADIUS;
    let w = DENSITY * GRAVITY * area;
    let young = w * (a + sag) / (area * STRAIN);
    let mut model = Model::new();
    let mat = model.add_material(Material::new(young, 0.3, DENSITY, 0.5)?)?;
    let half = n / 2;
    let points = circular_arc_chain(SPAN, LENGTH, n);
    let s = chain(&mut model, &points, &StructureOptions::new("catenary", RADIUS, mat))?;
    let nodes = model.structures[s as usize].nodes.clone();
    let (first, last) = (nodes.start, nodes.end - 1);
    model.block([first, last], Dofs::TRANSLATION)?;
    let settings = Settings {
        time_step: TimeStep::Auto { safety: 0.5 },
        gravity: Vec3::new(0.0, 0.0, -GRAVITY),
        damping: DAMPING,
        ..Settings::default()
    };
    let mut sim = Simulation::new(model, settings)?;
    let max_steps = 3_000_000;
    let steps = run_to_rest(&mut sim, 1e-8, 10_000, max_steps)?;
    let pos = &sim.model().particles.pos;
    let shape: Vec<(Real, Real)> =
        (first..=last).map(|i| (pos[i as usize].x, pos[i as usize].z)).collect();
    let sag_measured = -shape[half].1;
    let deviation = shape
        .iter()
        .zip(&discrete)
        .map(|(p, q)| ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt())
        .fold(0.0, Real::max);
    let h_measured = sim.forces()[first as usize].x.abs();
    let mut report = CaseReport::new("catenary", "Catenary (validation.md case 6)");
    report.setup = format!(
        "A chain of N = {n} links (radius {RADIUS} m, ρ = {DENSITY} kg/m³, Poisson 0.3, E = {:.4e} \
         Pa so that the largest axial strain w(a+f)/(EA) is {STRAIN:e}), length S = {LENGTH} m, \
         pinned (translations blocked, rotations free) at two supports D = {SPAN} m apart at the \
         same height, gravity {GRAVITY} m/s², Cundall damping {DAMPING}, beam link kinematics, \
         automatic dt = {:.3e} s. It starts as a circular arc (N equal chords of total length S) \
         and is run until every speed stays below 1e-8 m/s for 10000 \
         steps ({steps} steps, {:.1} s simulated). Measured: the sag of the mid-span node, the \
         largest distance of a node from the exact equilibrium of the discrete chain, and the \
         horizontal reaction at a support.",
        young,
        sim.dt(),
        sim.time()
    );
    report.checks.push(Check::relative(
        "mid-span sag vs the continuous catenary",
        "m",
        sag,
        sag_measured,
        tol_catenary,
        "a(cosh(D/2a) − 1), 2a·sinh(D/2a) = S",
    ));
    report.checks.push(Check::absolute(
        "largest node distance from the discrete chain's equilibrium / sag",
        "",
        0.0,
        deviation / sag,
        1e-3,
        "exact equilibrium of N inextensible links, weight lumped on the nodes",
    ));
    report.checks.push(Check::relative(
        "horizontal support reaction",
        "N",
        h_discrete * w,
        h_measured,
        1e-3,
        "H of the discrete chain",
    ));
    report.inform("catenary parameter a = H/w", format!("{a:.6} m"));
    report.inform("continuous horizontal tension w·a", format!("{:.6e} N", w * a));
    report.inform("sag of the exact discrete chain", format!("{sag_discrete:.6} m"));
    report.inform(
        "discretisation error of the sag |f_N − f|/f",
        format!("{discretisation:.3e} (tolerance set to {tol_catenary:e})"),
    );
    if steps >= max_steps {
        report.inform("warning", format!("not at rest after {steps} steps"));
    }
    let fine: Vec<(Real, Real)> = (0..=200)
        .map(|k| {
            let x = -0.5 * SPAN + SPAN * k as Real / 200.0;
            (x, a * ((x / a).cosh() - (SPAN / (2.0 * a)).cosh()))
        })
        .collect();
    let file = "catenary_shape.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Catenary: chain of 20 links at rest",
            x_label: "x (m)",
            y_label: "z (m)",
            curves: &[
                Curve::new("catenary of the same length", fine, CurveStyle::Line),
                Curve::new(
                    "initial arc",
                    points.iter().map(|p| (p.x, p.z)).collect(),
                    CurveStyle::Dashed,
                ),
                Curve::new("flexdem nodes", shape, CurveStyle::Points),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "Shape at rest: flexdem's nodes (points), the continuous catenary of the same \
                  length (line) and the initial circular arc (dashed)."
            .into(),
    });
    report.notes = format!(
        "Tolerance against the catenary: a chain of N straight links with its weight lumped on \
         the nodes is not a continuous catenary; its exact equilibrium (computed before the run, \
         see the module doc) has a mid-span sag {discretisation:.2e} away from the catenary's \
         (an O(1/N²) error), so the check allows twice that, {tol_catenary:e}. The engine itself \
         is checked against that discrete equilibrium to 1e-3 of the sag. The two other effects \
         are kept below 1e-4: axial stretch (strain ≤ {STRAIN:e}) and bending stiffness (the \
         links' rest shape is the initial arc, so bending moments kb·Δθ, kb = EI/ℓ, remain at \
         rest where the catenary turns by Δθ more or less than the arc at a node; relative to \
         the moment H·f they are of order E·r²/(4ℓ·ρ·g·a·f) per radian, {:.1e} here, with Δθ of \
         a few hundredths of a radian: hence the thin radius).",
        young * RADIUS * RADIUS / (4.0 * (LENGTH / n as Real) * DENSITY * GRAVITY * a * sag)
    );
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circular_arc_chain_has_the_length_and_span() {
        let p = circular_arc_chain(1.0, 1.2, 20);
        let total: Real = p.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        assert!((total - 1.2).abs() < 1e-9, "{total}");
        assert!((p[0] - Vec3::new(-0.5, 0.0, 0.0)).norm() < 1e-9, "{}", p[0]);
        assert!((p[20] - Vec3::new(0.5, 0.0, 0.0)).norm() < 1e-9, "{}", p[20]);
        assert!(p[10].z < -0.2);
    }

    #[test]
    fn catenary_parameter_gives_the_length() {
        let a = catenary_parameter(1.0, 1.2);
        assert!((2.0 * a * (0.5 / a).sinh() - 1.2).abs() < 1e-12);
    }

    #[test]
    fn discrete_chain_spans_the_supports_and_converges() {
        let a = catenary_parameter(1.0, 1.2);
        let sag = a * ((0.5 / a).cosh() - 1.0);
        let error = |n: usize| {
            let (_, p) = discrete_chain(1.0, 1.2, n);
            assert!((p[n].0 - 0.5).abs() < 1e-9 && p[n].1.abs() < 1e-9, "{:?}", p[n]);
            (-p[n / 2].1 - sag).abs()
        };
        // second order: halving the links divides the error by about 4
        let (e10, e20) = (error(10), error(20));
        assert!(e10 / e20 > 3.5 && e10 / e20 < 4.5, "{e10} {e20}");
    }
}
