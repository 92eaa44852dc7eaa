//! Chung & Ooi (2011) DEM benchmark, tests 1, 2 and 4, with flexdem's linear contact law
//! (kn = 2·E1R1·E2R2/(E1R1 + E2R2), eq 3; ks = ν·kn, eq 4; Coulomb friction, eq 7). The
//! paper's analytic answers are for Hertz–Mindlin contacts, which flexdem does not have: we
//! compare with the analytic answers for a linear spring instead.
//!
//! - Test 1, a sphere on a rigid wall: contact duration tc = π·√(m/kn), rebound speed equal to
//!   the impact speed (no damping, restitution 1).
//! - Test 2, two identical spheres head on: tc = π·√(m*/kn) with m* = m/2, restitution 1.
//! - Test 4, oblique impact on a wall at angle θ from the normal: in gross sliding
//!   (tanθ ≥ (7/2)·μ·(1+e) for a solid sphere), the tangential velocity ratio is
//!   1 − μ(1+e)/tanθ and the spin after impact 5μ(1+e)·vn/(2R) (rigid-body impulse theory).

use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Check, Context, Figure};
use crate::ValidationError;
use flexdem_contact::Material;
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation, TimeStep};
use std::f64::consts::PI;

/// Steps per contact duration.
const STEPS_PER_CONTACT: Real = 1000.0;
/// Tolerance of contact durations and restitutions (validation.md case 11).
const NORMAL_TOL: Real = 1e-3;
/// Tolerance of the gross-sliding answers of test 4 (validation.md case 12).
const OBLIQUE_TOL: Real = 0.02;

/// A material of the benchmark: name, E (Pa), ν, ρ (kg/m³).
type NamedMaterial = (&'static str, Real, Real, Real);

/// The two materials of test 1 (sphere radius 0.01 m, impact speed 10 m/s).
const TEST_1_MATERIALS: [NamedMaterial; 2] =
    [("glass", 4.8e10, 0.20, 2800.0), ("limestone", 2.0e10, 0.25, 2500.0)];
/// The two materials of test 2 (sphere radius 0.1 m, each sphere at 10 m/s).
const TEST_2_MATERIALS: [NamedMaterial; 2] =
    [("aluminium alloy", 7.0e10, 0.33, 2699.0), ("nylon", 2.5e9, 0.40, 1000.0)];

/// Mass of a solid sphere of radius `r` and density `rho`: 4/3·π·r³·ρ.
fn sphere_mass(r: Real, rho: Real) -> Real {
    4.0 / 3.0 * PI * r.powi(3) * rho
}

/// What a normal impact gave: contact duration (s) and the ratio of the separation speed after
/// to the approach speed before.
struct NormalImpact {
    duration: Real,
    restitution: Real,
}

/// Steps `sim` until `gap` becomes positive again after having been ≤ 0 (the contact ended),
/// for at most `t_max`; returns the start and end of the contact, each linearly interpolated
/// between the two steps around the sign change of the gap.
fn contact_interval(
    sim: &mut Simulation,
    gap: impl Fn(&Simulation) -> Real,
    t_max: Real,
) -> Result<Option<(Real, Real)>, ValidationError> {
    let mut start = None;
    let mut prev = gap(sim);
    while sim.time() < t_max {
        sim.step()?;
        let g = gap(sim);
        let t_cross = sim.time() - sim.dt() * g / (g - prev);
        if prev > 0.0 && g <= 0.0 {
            start = Some(t_cross);
        } else if prev <= 0.0 && g > 0.0 {
            if let Some(s) = start {
                return Ok(Some((s, t_cross)));
            }
        }
        prev = g;
    }
    Ok(None)
}

/// Test 1: a sphere of radius `r` falls at `v` (no gravity) on a wall at z = 0.
fn sphere_on_wall(
    material: NamedMaterial,
    r: Real,
    v: Real,
) -> Result<NormalImpact, ValidationError> {
    let (_, e, nu, rho) = material;
    let mut model = Model::new();
    let mat = model.add_material(Material::new(e, nu, rho, 0.5)?)?;
    model.add_wall(Vec3::zeros(), Vec3::z(), mat)?;
    let s = model.add_sphere(Vec3::new(0.0, 0.0, r * 1.001), r, mat)? as usize;
    model.particles.vel[s] = Vec3::new(0.0, 0.0, -v);
    let tc = PI * (sphere_mass(r, rho) / (e * r)).sqrt();
    let settings =
        Settings { time_step: TimeStep::Fixed(tc / STEPS_PER_CONTACT), ..Settings::default() };
    let mut sim = Simulation::new(model, settings)?;
    let t_max = 1e-3 * r / v + 5.0 * tc;
    let interval = contact_interval(&mut sim, |sim| sim.model().particles.pos[s].z - r, t_max)?;
    let Some((start, end)) = interval else {
        return Err(ValidationError::Case {
            case: "chung_ooi_1".into(),
            message: "no rebound".into(),
        });
    };
    Ok(NormalImpact { duration: end - start, restitution: sim.model().particles.vel[s].z / v })
}

/// Test 2: two spheres of radius `r` approach each other along x, each at `v`.
fn two_spheres(material: NamedMaterial, r: Real, v: Real) -> Result<NormalImpact, ValidationError> {
    let (_, e, nu, rho) = material;
    let mut model = Model::new();
    let mat = model.add_material(Material::new(e, nu, rho, 0.5)?)?;
    let a = model.add_sphere(Vec3::new(-r * 1.001, 0.0, 0.0), r, mat)? as usize;
    let b = model.add_sphere(Vec3::new(r * 1.001, 0.0, 0.0), r, mat)? as usize;
    model.particles.vel[a] = Vec3::new(v, 0.0, 0.0);
    model.particles.vel[b] = Vec3::new(-v, 0.0, 0.0);
    let tc = PI * (0.5 * sphere_mass(r, rho) / (e * r)).sqrt();
    let settings =
        Settings { time_step: TimeStep::Fixed(tc / STEPS_PER_CONTACT), ..Settings::default() };
    let mut sim = Simulation::new(model, settings)?;
    let gap = |sim: &Simulation| {
        let p = &sim.model().particles.pos;
        (p[b] - p[a]).norm() - 2.0 * r
    };
    let t_max = 1e-3 * r / v + 5.0 * tc;
    let Some((start, end)) = contact_interval(&mut sim, gap, t_max)? else {
        return Err(ValidationError::Case {
            case: "chung_ooi_2".into(),
            message: "no rebound".into(),
        });
    };
    let vel = &sim.model().particles.vel;
    Ok(NormalImpact { duration: end - start, restitution: (vel[b].x - vel[a].x) / (2.0 * v) })
}

/// The checks of a normal impact with expected duration `tc`.
fn normal_checks(
    report: &mut CaseReport,
    name: &str,
    impact: &NormalImpact,
    tc: Real,
    formula: &str,
) {
    report.checks.push(Check::relative(
        &format!("{name}: contact duration"),
        "s",
        tc,
        impact.duration,
        NORMAL_TOL,
        formula,
    ));
    report.checks.push(Check::relative(
        &format!("{name}: restitution"),
        "",
        1.0,
        impact.restitution,
        NORMAL_TOL,
        "linear spring, no damping: e = 1",
    ));
}

/// Chung & Ooi test 1: elastic normal impact of a sphere on a rigid wall.
pub fn run_test_1(_ctx: &Context) -> Result<CaseReport, ValidationError> {
    let (r, v) = (0.01, 10.0);
    let mut report = CaseReport::new(
        "chung_ooi_1",
        "Chung & Ooi test 1: normal impact of a sphere on a rigid wall",
    );
    report.setup = format!(
        "A sphere of radius {r} m moving at {v} m/s along −z hits a fixed wall (z = 0), no gravity, \
         no damping. Materials of the benchmark: glass (E = 48 GPa, ν = 0.2, ρ = 2800 kg/m³) and \
         limestone (E = 20 GPa, ν = 0.25, ρ = 2500 kg/m³); sphere and wall share the material. \
         Linear law: kn = E·R for a sphere on a wall (eq 3 with the wall taking the sphere's radius). \
         dt = tc/{STEPS_PER_CONTACT}; the contact starts and ends where the gap z − R changes sign \
         (interpolated linearly between steps)."
    );
    for material in TEST_1_MATERIALS {
        let (name, e, _, rho) = material;
        let impact = sphere_on_wall(material, r, v)?;
        let tc = PI * (sphere_mass(r, rho) / (e * r)).sqrt();
        normal_checks(&mut report, name, &impact, tc, "π·√(m/kn), linear spring");
    }
    report.notes = "Chung & Ooi give Hertzian answers (duration depending on the impact speed); \
        flexdem's contact law is linear, so the analytic reference is the half period of the \
        linear spring–mass system, independent of the speed. The materials are those we take for \
        the benchmark's test; the checked ratios do not depend on their values."
        .into();
    Ok(report)
}

/// Chung & Ooi test 2: elastic normal impact of two identical spheres.
pub fn run_test_2(_ctx: &Context) -> Result<CaseReport, ValidationError> {
    let (r, v) = (0.1, 10.0);
    let mut report = CaseReport::new(
        "chung_ooi_2",
        "Chung & Ooi test 2: normal impact of two identical spheres",
    );
    report.setup = format!(
        "Two identical spheres of radius {r} m approach head on, each at {v} m/s, no gravity, no \
         damping. Materials of the benchmark: aluminium alloy (E = 70 GPa, ν = 0.33, ρ = 2699 kg/m³) \
         and nylon (E = 2.5 GPa, ν = 0.4, ρ = 1000 kg/m³). Linear law: kn = E·R (eq 3, equal \
         spheres), reduced mass m* = m/2. dt = tc/{STEPS_PER_CONTACT}; contact start and end \
         interpolated where the gap |x2 − x1| − 2R changes sign. Restitution = relative speed after \
         / relative speed before."
    );
    for material in TEST_2_MATERIALS {
        let (name, e, _, rho) = material;
        let impact = two_spheres(material, r, v)?;
        let tc = PI * (0.5 * sphere_mass(r, rho) / (e * r)).sqrt();
        normal_checks(&mut report, name, &impact, tc, "π·√(m*/kn), m* = m/2");
    }
    report.notes =
        "As for test 1, the reference is the linear-spring answer, not Hertz's, and the checked \
        ratios do not depend on the material values."
            .into();
    Ok(report)
}

/// What an oblique impact gave: tangential velocity ratio vt'/vt, spin after (rad/s, about
/// the axis that rolling forward would give) and normal restitution vn'/vn.
struct ObliqueImpact {
    ratio: Real,
    spin: Real,
    restitution: Real,
}

/// Test 4 parameters: R (m), E (Pa), ν, ρ (kg/m³), μ, impact speed (m/s).
const TEST_4: (Real, Real, Real, Real, Real, Real) = (2.5e-3, 380e9, 0.23, 4000.0, 0.092, 3.9);

/// Test 4: the sphere hits the wall z = 0 at `theta` (radians) from the normal, moving along
/// +x tangentially; the state is read 3 contact durations after the start.
fn oblique_impact(theta: Real) -> Result<ObliqueImpact, ValidationError> {
    let (r, e, nu, rho, mu, speed) = TEST_4;
    let mut model = Model::new();
    let mat = model.add_material(Material::new(e, nu, rho, mu.atan())?)?;
    model.add_wall(Vec3::zeros(), Vec3::z(), mat)?;
    let s = model.add_sphere(Vec3::new(0.0, 0.0, r + 1e-6), r, mat)? as usize;
    let (vt, vn) = (speed * theta.sin(), speed * theta.cos());
    model.particles.vel[s] = Vec3::new(vt, 0.0, -vn);
    let tc = PI * (sphere_mass(r, rho) / (e * r)).sqrt();
    let settings =
        Settings { time_step: TimeStep::Fixed(tc / STEPS_PER_CONTACT), ..Settings::default() };
    let mut sim = Simulation::new(model, settings)?;
    // 1 µm of free flight, the contact, and a margin
    let t_end = 1e-6 / vn + 2.0 * tc;
    while sim.time() < t_end {
        sim.step()?;
    }
    let (v, w) = (sim.model().particles.vel[s], sim.model().particles.ang_vel[s]);
    Ok(ObliqueImpact { ratio: v.x / vt, spin: w.y, restitution: v.z / vn })
}

/// Rigid-body answers of an oblique impact in gross sliding at `theta` with restitution `e`:
/// (vt'/vt = 1 − μ(1+e)/tanθ, ω' = 5μ(1+e)·vn/(2R)).
fn gross_sliding_answer(theta: Real, e: Real) -> (Real, Real) {
    let (r, _, _, _, mu, speed) = TEST_4;
    let vn = speed * theta.cos();
    (1.0 - mu * (1.0 + e) / theta.tan(), 5.0 * mu * (1.0 + e) * vn / (2.0 * r))
}

/// Chung & Ooi test 4: oblique impact of a sphere on a rigid wall over a sweep of angles.
pub fn run_test_4(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let (r, e, nu, rho, mu, speed) = TEST_4;
    let restitution = 1.0;
    let threshold = (3.5 * mu * (1.0 + restitution)).atan();
    let angles: Vec<Real> = if ctx.quick {
        vec![10.0, 45.0, 60.0, 80.0]
    } else {
        (1..=17).map(|k| 5.0 * k as Real).collect()
    };
    let mut report =
        CaseReport::new("chung_ooi_4", "Chung & Ooi test 4: oblique impact on a rigid wall");
    report.setup = format!(
        "A sphere (R = {} mm, E = {} GPa, ν = {nu}, ρ = {rho} kg/m³, μ = {mu}) hits a fixed wall of \
         the same material at {speed} m/s, at angle θ from the wall normal (θ = {}°), no gravity, no \
         damping (restitution e = 1), no initial spin. Linear law: kn = E·R, ks = ν·kn (eq 3–4), \
         Coulomb friction μ = tanφ (eq 7). dt = tc/{STEPS_PER_CONTACT}, velocities read 2 contact \
         durations after the start. Gross sliding throughout the contact for tanθ ≥ (7/2)·μ·(1+e), \
         i.e. θ ≥ {:.1}°: there the tangential velocity ratio vt'/vt = 1 − μ(1+e)/tanθ and the spin \
         ω' = 5μ(1+e)·vn/(2R) are checked to {}%.",
        r * 1e3,
        e * 1e-9,
        angles.iter().map(|a| format!("{a}")).collect::<Vec<_>>().join(", "),
        threshold.to_degrees(),
        OBLIQUE_TOL * 100.0,
    );
    let (mut ratio_sim, mut spin_sim, mut restitutions) = (Vec::new(), Vec::new(), Vec::new());
    for &deg in &angles {
        let theta = deg.to_radians();
        let impact = oblique_impact(theta)?;
        ratio_sim.push((deg, impact.ratio));
        spin_sim.push((deg, impact.spin));
        let (ratio, spin) = gross_sliding_answer(theta, restitution);
        if theta >= threshold {
            let source = "1 − μ(1+e)/tanθ (gross sliding)";
            report.checks.push(Check::relative(
                &format!("θ = {deg}°: vt'/vt"),
                "",
                ratio,
                impact.ratio,
                OBLIQUE_TOL,
                source,
            ));
            let source = "5μ(1+e)·vn/(2R) (gross sliding)";
            report.checks.push(Check::relative(
                &format!("θ = {deg}°: spin ω'"),
                "rad/s",
                spin,
                impact.spin,
                OBLIQUE_TOL,
                source,
            ));
        } else {
            report.inform(
                &format!("θ = {deg}° (sticking regime)"),
                format!(
                    "vt'/vt = {:.4} (rigid rolling 5/7 = {:.4}), ω' = {:.1} rad/s (rolling 5·vt/(7R) = {:.1})",
                    impact.ratio,
                    5.0 / 7.0,
                    impact.spin,
                    5.0 * speed * theta.sin() / (7.0 * r)
                ),
            );
        }
        restitutions.push(impact.restitution);
    }
    let (lo, hi) = restitutions
        .iter()
        .fold((Real::INFINITY, Real::NEG_INFINITY), |(lo, hi), &e| (lo.min(e), hi.max(e)));
    report.inform("normal restitution vn'/vn over all angles", format!("{lo:.6} to {hi:.6}"));
    let fine: Vec<Real> = (0..=170).map(|k| 0.5 * k as Real).collect();
    let analytic = |pick: fn((Real, Real)) -> Real| -> Vec<(Real, Real)> {
        fine.iter()
            .filter(|&&deg| deg.to_radians() >= threshold)
            .map(|&deg| (deg, pick(gross_sliding_answer(deg.to_radians(), restitution))))
            .collect()
    };
    let rolling_ratio: Vec<(Real, Real)> = fine
        .iter()
        .filter(|&&d| d > 0.0 && d.to_radians() <= threshold)
        .map(|&d| (d, 5.0 / 7.0))
        .collect();
    let rolling_spin: Vec<(Real, Real)> = fine
        .iter()
        .filter(|&&d| d.to_radians() <= threshold)
        .map(|&d| (d, 5.0 * speed * d.to_radians().sin() / (7.0 * r)))
        .collect();
    let ratio_file = "chung_ooi_4_velocity_ratio.png";
    plot_xy(
        &ctx.out_dir.join(ratio_file),
        &PlotSpec {
            title: "Chung & Ooi test 4: tangential velocity ratio",
            x_label: "impact angle from the normal (deg)",
            y_label: "vt'/vt",
            curves: &[
                Curve::new(
                    "gross sliding 1-mu(1+e)/tan(theta)",
                    analytic(|a| a.0),
                    CurveStyle::Line,
                ),
                Curve::new("rolling without slip 5/7", rolling_ratio, CurveStyle::Dashed),
                Curve::new("flexdem", ratio_sim, CurveStyle::Points),
            ],
        },
    )?;
    let spin_file = "chung_ooi_4_spin.png";
    plot_xy(
        &ctx.out_dir.join(spin_file),
        &PlotSpec {
            title: "Chung & Ooi test 4: spin after impact",
            x_label: "impact angle from the normal (deg)",
            y_label: "spin (rad/s)",
            curves: &[
                Curve::new("gross sliding 5mu(1+e)vn/(2R)", analytic(|a| a.1), CurveStyle::Line),
                Curve::new("rolling without slip 5vt/(7R)", rolling_spin, CurveStyle::Dashed),
                Curve::new("flexdem", spin_sim, CurveStyle::Points),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: ratio_file.into(),
        caption:
            "Tangential velocity ratio vt'/vt against the impact angle: flexdem (points), the \
                  gross-sliding answer (line) and rolling without slip (dashed)."
                .into(),
    });
    report.figures.push(Figure {
        file: spin_file.into(),
        caption: "Spin after impact against the impact angle: flexdem (points), the gross-sliding \
                  answer (line) and rolling without slip (dashed)."
            .into(),
    });
    report.notes = format!(
        "Below θ = {:.1}° the contact sticks for part of the impact. The rigid-body theory then \
         predicts rolling without slip at separation (vt'/vt = 5/7), but with a tangential spring \
         (ks = ν·kn) the contact point stores elastic energy that is given back at the end of the \
         contact, so the sphere may leave with a reversed tangential velocity at the contact point \
         (as Maw, Barber & Fawcett's compliant theory and Chung & Ooi's Hertz–Mindlin results show). \
         Its answer depends on ks/kn and the loading history, not on a closed formula for a linear \
         spring, so these angles are shown in the plots and listed as informative values, not \
         checked. The normal restitution is 1 for every angle (no damping).",
        threshold.to_degrees()
    );
    Ok(report)
}
