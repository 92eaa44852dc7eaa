//! Drained triaxial tests of a granular sample: in a PFacet membrane
//! (`examples/triaxial_membrane.toml`) and between six rigid walls
//! (`examples/triaxial_rigid.toml`), the same kind of packing (5 000 spheres, solid fraction
//! 0.60, the same radii), consolidated to 100 kPa then compressed to 15 % axial strain.
//!
//! Checks: the isotropic state after consolidation (platen stress and the grains'
//! Love–Weber mean stress against the confining pressure, 3 %); the peak friction angles of
//! the two tests within 3° of each other and in the range published for frictional spheres;
//! the energy balance of each whole test (pressure and wall work counted).

use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Check, Context, Figure};
use crate::ValidationError;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{love_weber_stress, mean_stress, Region};
use flexdem_output::triaxial::{triaxial_state, TriaxialSpec};
use flexdem_output::Quantity;
use flexdem_run::{NoObserver, Run, RunOptions, Stop};
use flexdem_scene::load_scene;
use std::path::Path;

/// The confining pressure of both tests (Pa).
const CONFINING: Real = 1e5;
/// The end of consolidation in both scenes (s).
const CONSOLIDATED_AT: Real = 0.03;
/// Steps between samples.
const SAMPLE_EVERY: u64 = 100;

/// One sample of a test.
#[derive(Clone, Copy, Debug)]
struct Sample {
    time: Real,
    axial_strain: Real,
    volumetric_strain: Real,
    mean: Real,
    deviator: Real,
}

/// What a test gives.
struct TestRun {
    samples: Vec<Sample>,
    /// Platen stress and the grains' Love–Weber mean stress at the end of consolidation (Pa).
    consolidated: (Real, Real),
    balance_error: Real,
    steps: u64,
    wall_time: Real,
}

impl TestRun {
    /// The largest friction angle `asin(3M/(6 + M))`, `M = q/p`, during compression, and the
    /// axial strain where it is reached (degrees).
    fn peak_friction_angle(&self) -> (Real, Real) {
        self.samples
            .iter()
            .filter(|s| s.time > CONSOLIDATED_AT && s.mean > 0.0)
            .map(|s| (friction_angle(s.deviator / s.mean), s.axial_strain))
            .fold((Real::NEG_INFINITY, 0.0), |a, b| if b.0 > a.0 { b } else { a })
    }

    /// The friction angle at the end (degrees).
    fn final_friction_angle(&self) -> Real {
        self.samples.last().map_or(Real::NAN, |s| friction_angle(s.deviator / s.mean))
    }
}

/// `φ = asin(3M/(6 + M))` in degrees: the friction angle of a triaxial compression whose
/// stress ratio is `M = q/p`.
fn friction_angle(m: Real) -> Real {
    (3.0 * m / (6.0 + m)).clamp(-1.0, 1.0).asin().to_degrees()
}

/// `examples/<file>` of the workspace.
fn scene_path(file: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(file)
}

/// Runs the example `file`, sampling its triaxial measures every [`SAMPLE_EVERY`] steps.
fn run_test(case: &str, file: &str) -> Result<TestRun, ValidationError> {
    let fail = |message: String| ValidationError::Case { case: case.into(), message };
    let scene = load_scene(&scene_path(file))?;
    let options = RunOptions { no_output: true, ..RunOptions::default() };
    let mut run = Run::new(scene, options).map_err(|e| fail(e.to_string()))?;
    let spec: TriaxialSpec = run
        .output_settings()
        .series
        .iter()
        .find_map(|s| match &s.quantity {
            Quantity::Triaxial(spec) => Some(spec.clone()),
            _ => None,
        })
        .ok_or_else(|| fail(format!("{file}: no triaxial series")))?;
    let started = std::time::Instant::now();
    let mut samples = Vec::new();
    let mut consolidated = None;
    loop {
        let stop =
            run.advance(Some(SAMPLE_EVERY), &mut NoObserver).map_err(|e| fail(e.to_string()))?;
        let sim = run.sim();
        let state = triaxial_state(sim, &spec).map_err(fail)?;
        let [axial_strain, volumetric_strain, ..] = state.values(&spec);
        samples.push(Sample {
            time: sim.time(),
            axial_strain,
            volumetric_strain,
            mean: state.mean_stress(),
            deviator: state.deviator_stress(),
        });
        if consolidated.is_none() && sim.time() + SAMPLE_EVERY as Real * sim.dt() > CONSOLIDATED_AT
        {
            // the grains' stress over the sample's volume, from every sphere
            let everywhere = Region::Box { min: Vec3::repeat(-1e3), max: Vec3::repeat(1e3) };
            let sigma =
                love_weber_stress(sim.model(), &sim.contacts(), &everywhere, Some(state.volume));
            consolidated = Some((state.axial_stress, mean_stress(&sigma)));
        }
        if stop == Stop::Reached {
            break;
        }
    }
    let sim = run.sim();
    Ok(TestRun {
        samples,
        consolidated: consolidated.unwrap_or((Real::NAN, Real::NAN)),
        balance_error: sim.energy_watch().relative_error(sim.energy()),
        steps: sim.steps(),
        wall_time: started.elapsed().as_secs_f64(),
    })
}

/// Plots curves of both tests against the axial strain.
fn figure(
    ctx: &Context,
    report: &mut CaseReport,
    name: &str,
    y_label: &str,
    curves: &[Curve],
    caption: &str,
) -> Result<(), ValidationError> {
    let file = format!("{}_{name}.png", report.id);
    let spec = PlotSpec { title: caption, x_label: "axial strain", y_label, curves };
    plot_xy(&ctx.out_dir.join(&file), &spec)?;
    report.figures.push(Figure { file, caption: caption.into() });
    Ok(())
}

/// The case.
pub fn run(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let mut report =
        CaseReport::new("triaxial", "Drained triaxial tests: membrane and rigid walls");
    report.setup = "Scenes `examples/triaxial_membrane.toml` and `examples/triaxial_rigid.toml`: \
        5 000 polydisperse spheres (radius ratio 2, E = 100 MPa, ν = 0.3, friction angle 30°, \
        density 10 × quartz, no gravity) packed at a solid fraction of 0.60 by the dense \
        packing (same seed, same radii), in a cylinder of radius 5 cm and height 20 cm inside a \
        PFacet membrane (48 × 30 cells, E = 10 MPa, node radius 1 mm) under a 100 kPa pressure, \
        or in a square prism of the same volume and height between six smooth servo walls. \
        Consolidation to 100 kPa until 0.03 s (the platen's servo follows the sample's \
        cross-section), then the top platen down at 0.2 m/s (1 /s) to 15 % axial strain. \
        Damping 0.2."
        .into();
    let membrane = run_test("triaxial", "triaxial_membrane.toml")?;
    let rigid = run_test("triaxial", "triaxial_rigid.toml")?;
    for (name, t) in [("membrane", &membrane), ("rigid walls", &rigid)] {
        report.checks.push(Check::relative(
            &format!("{name}: platen stress after consolidation"),
            "Pa",
            CONFINING,
            t.consolidated.0,
            0.03,
            "the confining pressure",
        ));
        report.checks.push(Check::relative(
            &format!("{name}: Love–Weber mean stress after consolidation"),
            "Pa",
            CONFINING,
            t.consolidated.1,
            0.03,
            "the confining pressure",
        ));
        report.checks.push(Check::absolute(
            &format!("{name}: energy balance error"),
            "",
            0.0,
            t.balance_error,
            1e-2,
            "balance closes (pressure and wall work counted)",
        ));
        let (peak, at) = t.peak_friction_angle();
        report.checks.push(Check::absolute(
            &format!("{name}: peak friction angle"),
            "°",
            29.0,
            peak,
            5.0,
            "24–34°: frictional spheres at medium density (Thornton 2000; Huang et al. 2014)",
        ));
        report.inform(&format!("{name}: peak at axial strain"), format!("{at:.4}"));
        report.inform(
            &format!("{name}: friction angle at 15 %"),
            format!("{:.1}°", t.final_friction_angle()),
        );
        report.inform(
            &format!("{name}: run"),
            format!("{} steps, {:.0} s of wall time", t.steps, t.wall_time),
        );
    }
    let difference = membrane.peak_friction_angle().0 - rigid.peak_friction_angle().0;
    report.checks.push(Check::absolute(
        "peak friction angle, membrane − rigid walls",
        "°",
        0.0,
        difference,
        3.0,
        "the same kind of sample",
    ));
    report.notes = "The friction angle is asin(3M/(6 + M)) with M = q/p, p = (σa + 2σr)/3 and q = σa − σr from \
        the platens' stress on the sample's cross-section and the applied confining stress (the \
        membrane's pressure; the lateral walls' stress). Published DEM tests of frictional \
        spheres find a critical-state friction angle that saturates near 23–24° for \
        interparticle friction ≥ 0.5 (Huang, Hanley, O'Sullivan and Kwok, IJNAMG 38, 2014) and \
        peaks a few degrees to ten degrees above it depending on density (Thornton, \
        Géotechnique 50, 2000). Why the tests differ: the rigid walls force a uniform \
        deformation and hold the sample's corners, so it reaches its peak early and softens \
        toward the critical state; the membrane lets the sample barrel, its hoop tension adds \
        a few kPa of confinement that the confining stress (the applied pressure) does not \
        count, and its grains indent it (membrane penetration: the larger volumetric strain of \
        its consolidation), so its stress ratio rises to a plateau instead of a peak."
        .into();
    let curve = |t: &TestRun, label: &str, y: fn(&Sample) -> Real| {
        let points =
            t.samples.iter().filter(|s| s.mean > 0.0).map(|s| (s.axial_strain, y(s))).collect();
        Curve::new(label, points, CurveStyle::Line)
    };
    let ratio = |s: &Sample| s.deviator / s.mean;
    let volumetric = |s: &Sample| s.volumetric_strain;
    figure(
        ctx,
        &mut report,
        "stress_ratio",
        "q/p",
        &[curve(&membrane, "membrane", ratio), curve(&rigid, "rigid walls", ratio)],
        "Stress ratio q/p against axial strain",
    )?;
    figure(
        ctx,
        &mut report,
        "volumetric",
        "volumetric strain (contraction > 0)",
        &[curve(&membrane, "membrane", volumetric), curve(&rigid, "rigid walls", volumetric)],
        "Volumetric strain against axial strain",
    )?;
    Ok(report)
}
