//! Paper §7 (validation.md case 16): a solid sphere, then a hollow PFacet sphere, hits a
//! PFacet tube at 2 m/s. The paper reports that the solid sphere "is stopped with the creation
//! of a crater" whose depth "almost corresponds to [the tube's] radius", and that the hollow
//! sphere deforms itself and the tube less.
//!
//! Both cases run the example scenes `examples/tube_impact_solid.toml` and
//! `examples/tube_impact_hollow.toml` (so `flexdem run` shows the same scene), record the
//! impactor's centre of mass and velocity, the total contact force on it, the crater depth
//! (largest displacement of a tube node), the impactor's own deformation and the energy
//! terms, and stop once the impactor has stopped (its mean vertical velocity is no longer
//! downwards) or at the scene's duration.

use crate::cases::brazier::min_self_distance;
use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Check, Context, Figure};
use crate::ValidationError;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Energy, Simulation};
use flexdem_scene::{load_scene, RunLength};
use std::path::{Path, PathBuf};

/// Tube radius (paper §7), m.
const TUBE_RADIUS: Real = 0.1;
/// Impact speed (paper §7), m/s.
const IMPACT_SPEED: Real = 2.0;
/// Crater depth of the solid sphere: the paper's "almost corresponds to its radius", read as
/// "of the order of R": within [R/2, 2R] (the paper gives no number, only figure 5, and no
/// densities; the crater measured here includes the sag of the clamped middle section).
const CRATER_BAND: (Real, Real) = (0.5, 2.0);
/// The largest displacement of a tube node in YADE 2023.02a's run of the same scene (the
/// light sphere: shared/reference/yade/tube_impact, mode `solid`), m; and the tolerance of the
/// comparison (the meshes differ: YADE's has no node at the top of the tube).
const YADE_CRATER: Real = 0.143;
const YADE_CRATER_TOL: Real = 0.2;
/// "Stopped": the residual approach speed is below 5 % of the impact speed.
const STOP_TOL: Real = 0.05 * IMPACT_SPEED;
/// Energy balance error, relative to the initial kinetic energy.
const ENERGY_TOL: Real = 5e-3;
/// Self-penetration not carried by a contact, as a fraction of 2r (the long runs).
const UNEXPLAINED_PENETRATION: Real = 1e-2;
/// The long runs look at the node–PFacet distances every this many steps.
const PENETRATION_EVERY: u64 = 10;
/// Steps of the quick runs: a few hundred steps into the contact.
const QUICK_STEPS_SOLID: u64 = 300;
const QUICK_STEPS_HOLLOW: u64 = 400;
/// A sample of the time series every this many steps.
const SAMPLE_EVERY: u64 = 5;
/// Impactor densities (kg/m³) of the informative sweep of the solid case.
const SWEEP_DENSITIES: [Real; 4] = [10.0, 30.0, 100.0, 300.0];
/// The heavy sphere's scene: density 1000 kg/m³ (4.19 kg).
const HEAVY: &str = "tube_impact_heavy.toml";
/// Name of the tube structure in both scenes.
const TUBE: &str = "tube";

/// One sample of an impact run.
#[derive(Clone, Copy, Debug)]
struct Sample {
    time: Real,
    /// Impactor centre of mass (m) and mean velocity (m/s).
    centre: Vec3,
    velocity: Vec3,
    /// Total force on the impactor's particles (N): the contact force (no gravity, no load;
    /// the links of a shell cancel in the sum).
    force: Vec3,
    /// Largest displacement of a tube node since the start (m).
    crater: Real,
    /// Largest change of a shell node's distance to the shell's centre of mass, over its
    /// initial mean radius (0 for a solid sphere).
    shell_strain: Real,
    energy: Energy,
}

/// What an impact run gave.
struct ImpactRun {
    samples: Vec<Sample>,
    impactor_mass: Real,
    tube_mass: Real,
    kinetic0: Real,
    /// Largest |B(t) − B(0)| over every step, B the energy balance, over `kinetic0`.
    balance_error: Real,
    /// Time and crater depth when the impactor stopped (mean v_z ≥ 0 after the impact).
    stopped: Option<(Real, Real)>,
    /// The engine's error that ended the run early, if any.
    engine_error: Option<String>,
    steps: u64,
    dt_range: (Real, Real),
}

impl ImpactRun {
    fn last(&self) -> &Sample {
        &self.samples[self.samples.len() - 1]
    }
    /// Crater depth at the stop, else at the end (m).
    fn crater(&self) -> Real {
        self.stopped.map_or(self.last().crater, |(_, c)| c)
    }
    /// max(0, smallest approach speed −v_z over the run): 0 once the impactor stopped or
    /// rebounds, else how fast it still moves into the tube (m/s).
    fn residual_speed(&self) -> Real {
        self.samples.iter().map(|s| -s.velocity.z).fold(Real::INFINITY, Real::min).max(0.0)
    }
    fn max_force(&self) -> Real {
        self.samples.iter().map(|s| s.force.norm()).fold(0.0, Real::max)
    }
    fn max_shell_strain(&self) -> Real {
        self.samples.iter().map(|s| s.shell_strain).fold(0.0, Real::max)
    }
}

/// `examples/<file>` of the workspace.
fn scene_path(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(file)
}

/// Runs the scene `file` for at most `max_steps` steps (else its duration), with the
/// impactor's density replaced by `density` (kg/m³) when given (mass and inertia scaled).
fn run_impact(
    case: &str,
    file: &str,
    max_steps: Option<u64>,
    density: Option<Real>,
) -> Result<ImpactRun, ValidationError> {
    let fail = |message: String| ValidationError::Case { case: case.into(), message };
    let scene = load_scene(&scene_path(file))?;
    let mut model = scene.model;
    let tube_id = model
        .structure_by_name(TUBE)
        .ok_or_else(|| fail(format!("{file}: no structure named `{TUBE}`")))?;
    let tube = model.structure(tube_id)?.nodes.clone();
    let tube: Vec<usize> = tube.map(|i| i as usize).collect();
    let impactor: Vec<usize> =
        (0..model.particles.len()).filter(|i| tube.binary_search(i).is_err()).collect();
    if impactor.is_empty() {
        return Err(fail(format!("{file}: no impactor besides the tube")));
    }
    if let Some(rho) = density {
        for &i in &impactor {
            let scale = rho / model.materials[model.particles.material[i] as usize].density;
            model.particles.mass[i] *= scale;
            model.particles.inertia[i] *= scale;
        }
    }
    let p = &model.particles;
    let impactor_mass: Real = impactor.iter().map(|&i| p.mass[i]).sum();
    let tube_mass: Real = tube.iter().map(|&i| p.mass[i]).sum();
    let centre_of =
        |pos: &[Vec3]| impactor.iter().map(|&i| pos[i] * p.mass[i]).sum::<Vec3>() / impactor_mass;
    let (pos0, c0) = (p.pos.clone(), centre_of(&p.pos));
    let radius0 =
        impactor.iter().map(|&i| (pos0[i] - c0).norm()).sum::<Real>() / impactor.len() as Real;
    let end = match scene.run {
        RunLength::Duration(d) => (Real::INFINITY, d),
        RunLength::Steps(n) => (n as Real, Real::INFINITY),
    };
    let max_steps = max_steps.map_or(end.0, |n| (n as Real).min(end.0));

    let mut sim = Simulation::new(model, scene.settings)?;
    let kinetic0 = sim.energy().kinetic_translation + sim.energy().kinetic_rotation;
    let balance0 = sim.energy().balance();
    let sample = |sim: &Simulation| {
        let p = &sim.model().particles;
        let m = |i: usize| p.mass[i];
        let centre = impactor.iter().map(|&i| p.pos[i] * m(i)).sum::<Vec3>() / impactor_mass;
        let velocity = impactor.iter().map(|&i| p.vel[i] * m(i)).sum::<Vec3>() / impactor_mass;
        let force = impactor.iter().map(|&i| sim.forces()[i]).sum::<Vec3>();
        let crater = tube.iter().map(|&i| (p.pos[i] - pos0[i]).norm()).fold(0.0, Real::max);
        let shell_strain = if impactor.len() > 1 {
            let change = |i: usize| ((p.pos[i] - centre).norm() - (pos0[i] - c0).norm()).abs();
            impactor.iter().map(|&i| change(i)).fold(0.0, Real::max) / radius0
        } else {
            0.0
        };
        Sample {
            time: sim.time(),
            centre,
            velocity,
            force,
            crater,
            shell_strain,
            energy: *sim.energy(),
        }
    };
    let mut run = ImpactRun {
        samples: vec![sample(&sim)],
        impactor_mass,
        tube_mass,
        kinetic0,
        balance_error: 0.0,
        stopped: None,
        engine_error: None,
        steps: 0,
        dt_range: (sim.dt(), sim.dt()),
    };
    while (sim.steps() as Real) < max_steps && sim.time() < end.1 {
        if let Err(e) = sim.step() {
            run.engine_error = Some(e.to_string());
            break;
        }
        run.dt_range = (run.dt_range.0.min(sim.dt()), run.dt_range.1.max(sim.dt()));
        run.balance_error =
            run.balance_error.max((sim.energy().balance() - balance0).abs() / kinetic0);
        let s = sample(&sim);
        if s.velocity.z >= 0.0 {
            run.stopped = Some((s.time, s.crater));
            run.samples.push(s);
            break;
        }
        if sim.steps() % SAMPLE_EVERY == 0 {
            run.samples.push(s);
        }
    }
    run.steps = sim.steps();
    if run.samples.last().map(|s| s.time) != Some(sim.time()) {
        run.samples.push(sample(&sim));
    }
    Ok(run)
}

/// A check that `measured` lies in [lo, hi]: the middle as expected value, half the width as
/// absolute tolerance.
fn in_range(
    quantity: &str,
    unit: &str,
    (lo, hi): (Real, Real),
    measured: Real,
    source: &str,
) -> Check {
    Check::absolute(quantity, unit, 0.5 * (lo + hi), measured, 0.5 * (hi - lo), source)
}

/// The checks every run makes: energy balance and no engine error.
fn common_checks(report: &mut CaseReport, run: &ImpactRun) {
    report.checks.push(Check::absolute(
        "energy balance error max |B(t) − B(0)| / Ek(0)",
        "",
        0.0,
        run.balance_error,
        ENERGY_TOL,
        "energy conservation (model.md §6): B = kinetic + elastic − works + dissipated",
    ));
    report.checks.push(Check::absolute(
        "engine errors during the run",
        "",
        0.0,
        if run.engine_error.is_some() { 1.0 } else { 0.0 },
        0.0,
        "a stable run",
    ));
}

/// The quick check that the impactor slows down in the first steps of the contact.
fn slowing_check(run: &ImpactRun) -> Check {
    in_range(
        "speed lost by the impactor at the end of the quick run, in [1 mm/s, 2 m/s]",
        "m/s",
        (1e-3, IMPACT_SPEED),
        IMPACT_SPEED - run.last().velocity.norm(),
        "the tube resists the impact",
    )
}

/// The informative values of a run.
fn inform_run(report: &mut CaseReport, run: &ImpactRun) {
    let last = run.last();
    report.inform(
        "impactor mass",
        format!("{:.4} kg (tube {:.4} kg)", run.impactor_mass, run.tube_mass),
    );
    report.inform("initial kinetic energy", format!("{:.4} J", run.kinetic0));
    report.inform(
        "steps, time, dt",
        format!(
            "{} steps to t = {:.4} s, dt from {:.2e} to {:.2e} s",
            run.steps, last.time, run.dt_range.0, run.dt_range.1
        ),
    );
    match run.stopped {
        Some((t, c)) => report.inform(
            "impactor stopped",
            format!("at t = {t:.4} s, crater {c:.4} m = {:.2} tube radii", c / TUBE_RADIUS),
        ),
        None => report
            .inform("impactor stopped", format!("no: v_z = {:.3} m/s at the end", last.velocity.z)),
    }
    report.inform(
        "impactor centre travel",
        format!("{:.4} m", run.samples[0].centre.z - last.centre.z),
    );
    report.inform("largest contact force on the impactor", format!("{:.2} N", run.max_force()));
    let e = &last.energy;
    report.inform(
        "energy at the end (J)",
        format!(
            "kinetic {:.4}, elastic links {:.4}, elastic contacts {:.4}, friction {:.4}",
            e.kinetic_translation + e.kinetic_rotation,
            e.elastic_links,
            e.elastic_contacts,
            e.friction
        ),
    );
    if let Some(error) = &run.engine_error {
        report.inform("engine error", error.clone());
    }
}

/// Plots `curves` into `<id>_<name>.png` and adds it to the report's figures.
fn figure(
    ctx: &Context,
    report: &mut CaseReport,
    name: &str,
    (title, x_label, y_label): (&str, &str, &str),
    curves: &[Curve],
    caption: &str,
) -> Result<(), ValidationError> {
    let file = format!("{}_{name}.png", report.id);
    plot_xy(&ctx.out_dir.join(&file), &PlotSpec { title, x_label, y_label, curves })?;
    report.figures.push(Figure { file, caption: caption.into() });
    Ok(())
}

/// The four time plots of a run: trajectory and velocity, contact force, crater depth,
/// energy terms.
fn plot_run(
    ctx: &Context,
    report: &mut CaseReport,
    run: &ImpactRun,
) -> Result<(), ValidationError> {
    let series = |f: &dyn Fn(&Sample) -> Real| {
        run.samples.iter().map(|s| (s.time, f(s))).collect::<Vec<_>>()
    };
    let line =
        |label: &str, f: &dyn Fn(&Sample) -> Real| Curve::new(label, series(f), CurveStyle::Line);
    let z0 = run.samples[0].centre.z;
    figure(
        ctx,
        report,
        "trajectory",
        ("Impactor: centre height drop and vertical velocity", "time (s)", "m, m/s"),
        &[
            line("centre drop z0 - z (m)", &|s| z0 - s.centre.z),
            line("velocity v_z (m/s)", &|s| s.velocity.z),
        ],
        "Impactor centre of mass: how far it has moved down, and its vertical velocity.",
    )?;
    figure(
        ctx,
        report,
        "contact_force",
        ("Total contact force on the impactor", "time (s)", "force (N)"),
        &[line("F_z (up)", &|s| s.force.z), line("|F|", &|s| s.force.norm())],
        "Sum of the contact forces on the impactor's particles.",
    )?;
    let crater = [
        line("crater depth (max tube node displacement)", &|s| s.crater),
        Curve::new("tube radius R", series(&|_| TUBE_RADIUS), CurveStyle::Dashed),
    ];
    figure(
        ctx,
        report,
        "crater",
        ("Crater depth", "time (s)", "m"),
        &crater,
        "Largest displacement of a tube node, against the tube radius (paper: crater about R).",
    )?;
    if run.max_shell_strain() > 0.0 {
        figure(
            ctx,
            report,
            "deformation",
            ("Deformation of the hollow impactor", "time (s)", "max |dr| / R0 (%)"),
            &[line("largest change of a node's distance to the centre", &|s| {
                100.0 * s.shell_strain
            })],
            "Largest change of a shell node's distance to the shell's centre of mass, over its \
             initial mean radius R0.",
        )?;
    }
    let b0 = run.samples[0].energy.balance();
    figure(
        ctx,
        report,
        "energy",
        ("Energy terms", "time (s)", "energy (J)"),
        &[
            line("kinetic", &|s| s.energy.kinetic_translation + s.energy.kinetic_rotation),
            line("elastic, links", &|s| s.energy.elastic_links),
            line("elastic, contacts", &|s| s.energy.elastic_contacts),
            line("friction", &|s| s.energy.friction),
            line("balance B(t) - B(0)", &|s| s.energy.balance() - b0),
        ],
        "Energy terms; the balance stays at 0 when energy is conserved.",
    )
}

/// The setup text shared by both cases.
const SETUP_COMMON: &str = "Tube (paper §7): 640 PFacets (16 nodes around × 20 segments \
    along, flexdem's `paper_tube`), radius R = 0.1 m, length 0.8 m, node radius 2 mm, E = 1 MPa, \
    ν = 0.3, along x; the impactor (radius 0.1 m, E = 100 MPa, ν = 0.3) starts 5 mm above the \
    middle of the tube at 2 m/s downwards; no gravity, no damping, beam link kinematics, dt = auto \
    with safety 0.3. **Not in the paper, our choices:** the tube's density 1000 kg/m³ (YADE's \
    default); the solid sphere's 26.77 kg/m³, the mass of the hollow impactor (0.112 kg) as in the \
    YADE reference runs (`tube_impact_heavy.toml`: 1000 kg/m³, 4.19 kg, safety 0.1); friction \
    angle 30°, both end rings of the tube clamped (all DOFs). Measured every step: \
    impactor centre of mass and mean velocity, total contact force on it, crater depth = largest \
    displacement of a tube node (with clamped ends it includes the sag of the whole middle \
    section), energy terms (`Simulation::energy`), balance error = max |B(t) − B(0)| / Ek(0). \
    The run stops when the impactor has stopped (mean v_z ≥ 0) or at the scene's duration.";

/// Paper §7, first impact: the solid sphere.
pub fn impact_solid(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let id = "impact_solid";
    let mut report = CaseReport::new(id, "Paper §7: a solid sphere hits a PFacet tube");
    let quick_steps = ctx.quick.then_some(QUICK_STEPS_SOLID);
    let run = run_impact(id, "tube_impact_solid.toml", quick_steps, None)?;
    report.setup = format!(
        "Scene `examples/tube_impact_solid.toml`. {SETUP_COMMON} Impactor: one solid sphere \
         ({:.3} kg). {}",
        run.impactor_mass,
        if ctx.quick {
            format!(
                "Quick run: the first {QUICK_STEPS_SOLID} steps; checks the energy balance and \
                 that the sphere slows down."
            )
        } else {
            "Full run; plus an informative sweep of the impactor density (10–300 kg/m³), same \
             scene."
                .into()
        }
    );
    common_checks(&mut report, &run);
    if ctx.quick {
        report.checks.push(slowing_check(&run));
    } else {
        report.checks.push(in_range(
            "crater depth / tube radius when the sphere stops, in [0.5, 2]",
            "",
            CRATER_BAND,
            run.crater() / TUBE_RADIUS,
            "paper §7: the deformation 'almost corresponds to its radius' (figure 5)",
        ));
        report.checks.push(Check::relative(
            "crater depth when the sphere stops",
            "m",
            YADE_CRATER,
            run.crater(),
            YADE_CRATER_TOL,
            "YADE 2023.02a, same scene: largest tube node displacement 0.143 m",
        ));
        report.checks.push(Check::absolute(
            "residual approach speed max(0, min −v_z)",
            "m/s",
            0.0,
            run.residual_speed(),
            STOP_TOL,
            "paper §7: 'the sphere is stopped' (5 % of 2 m/s)",
        ));
    }
    inform_run(&mut report, &run);
    plot_run(ctx, &mut report, &run)?;
    if !ctx.quick {
        density_sweep(ctx, &mut report, &run)?;
    }
    report.notes = "The sphere has the mass of the paper's hollow impactor (0.112 kg, density \
        26.77 kg/m³), as in the YADE reference runs: the paper gives no densities, and its tube \
        (2 mm links of E = 1 MPa: kn = E·A/L ≈ 314 N/m per link, bending EI/L ≈ 3e-7 N·m per \
        40 mm link: a membrane with almost no ring stiffness) cannot stop a sphere of YADE's \
        default density 1000 kg/m³ (4.19 kg, 8.38 J) in a crater of about R: that one drags \
        the clamped tube down like a sling by about four radii (examples/tube_impact_heavy.toml, \
        and the long runs below). The light sphere stops in a crater of about 1.5 R, as YADE's \
        run of the same scene (0.143 m), and rebounds at about 1.35 m/s. The paper's 'almost \
        corresponds to its radius' comes with figure 5 only, so the check reads it as 'of the \
        order of R', [R/2, 2R]; the crater measured here (the largest displacement of a tube \
        node) includes the sag of the whole clamped middle section."
        .into();
    Ok(report)
}

/// Informative sweep of the solid sphere's density: crater depth when it stops.
fn density_sweep(
    ctx: &Context,
    report: &mut CaseReport,
    main: &ImpactRun,
) -> Result<(), ValidationError> {
    let mut points = Vec::new();
    let mut text = Vec::new();
    for rho in SWEEP_DENSITIES {
        let run = run_impact(&report.id, "tube_impact_solid.toml", None, Some(rho))?;
        let outcome = match (run.stopped, &run.engine_error) {
            (Some((t, c)), _) => {
                points.push((run.impactor_mass, c / TUBE_RADIUS));
                format!("stops at t = {t:.3} s, crater {:.2} R", c / TUBE_RADIUS)
            }
            (None, Some(_)) => "engine error before the stop".to_string(),
            (None, None) => {
                format!("not stopped, crater {:.2} R at the end", run.last().crater / TUBE_RADIUS)
            }
        };
        text.push(format!("{rho} kg/m³ ({:.3} kg): {outcome}", run.impactor_mass));
    }
    if let Some((_, c)) = main.stopped {
        points.push((main.impactor_mass, c / TUBE_RADIUS));
    }
    report.inform("density sweep (crater when stopped)", text.join("; "));
    let band =
        |v: Real| Curve::new("", vec![(0.0, v), (main.impactor_mass, v)], CurveStyle::Dashed);
    figure(
        ctx,
        report,
        "density_sweep",
        ("Crater depth at the stop vs impactor mass", "impactor mass (kg)", "crater / R"),
        &[
            Curve::new("flexdem, density 10, 26.8, 30, 100, 300 kg/m3", points, CurveStyle::Points),
            band(CRATER_BAND.0),
            band(CRATER_BAND.1),
        ],
        "Crater depth when the sphere stops, over the tube radius, for several sphere densities; \
         dashed: the band [R/2, 2R] read from the paper's 'about R'.",
    )
}

/// Paper §7, second impact: the hollow deformable sphere (128 PFacets).
pub fn impact_hollow(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let id = "impact_hollow";
    let mut report = CaseReport::new(id, "Paper §7: a hollow PFacet sphere hits a PFacet tube");
    let quick_steps = ctx.quick.then_some(QUICK_STEPS_HOLLOW);
    let run = run_impact(id, "tube_impact_hollow.toml", quick_steps, None)?;
    report.setup = format!(
        "Scene `examples/tube_impact_hollow.toml`. {SETUP_COMMON} Impactor: a hollow sphere of \
         128 PFacets (octahedron subdivided twice, 66 nodes, node radius 2 mm, flexdem's \
         `paper_hollow_sphere`), mass lumped from its connections ({:.4} kg). Its deformation is \
         the largest change of a node's distance to the shell's centre of mass over the initial \
         mean radius. {}",
        run.impactor_mass,
        if ctx.quick {
            format!(
                "Quick run: the first {QUICK_STEPS_HOLLOW} steps; checks the energy balance and \
                 that the shell slows down."
            )
        } else {
            "Full run; the heavy solid sphere's scene (examples/tube_impact_heavy.toml, 4.19 kg) \
             is run too for the comparison of craters."
                .into()
        }
    );
    common_checks(&mut report, &run);
    if ctx.quick {
        report.checks.push(slowing_check(&run));
    } else {
        let solid = run_impact(id, HEAVY, None, None)?;
        report.checks.push(in_range(
            "crater depth hollow / heavy solid, in (0, 1)",
            "",
            (0.0, 1.0),
            run.crater() / solid.crater(),
            "paper §7: 'the tube is not as deformed as in the previous case'",
        ));
        report.checks.push(Check::absolute(
            "residual approach speed max(0, min −v_z)",
            "m/s",
            0.0,
            run.residual_speed(),
            STOP_TOL,
            "the shell is stopped (5 % of 2 m/s)",
        ));
        report.checks.push(in_range(
            "shell deformation max |Δr| / R0, in [1 %, 100 %]",
            "",
            (0.01, 1.0),
            run.max_shell_strain(),
            "paper §7: 'the impacting sphere deforms itself'",
        ));
        report.inform(
            "craters (at the stop)",
            format!("hollow {:.4} m, heavy solid {:.4} m", run.crater(), solid.crater()),
        );
    }
    inform_run(&mut report, &run);
    report.inform("largest shell deformation", format!("{:.2} %", 100.0 * run.max_shell_strain()));
    plot_run(ctx, &mut report, &run)?;
    report.notes = "The shell's mass is lumped from its connections (YADE's rule), 0.112 kg \
        against 4.19 kg for a solid sphere of the same density (the heavy example): it carries \
        0.22 J instead of 8.38 J, so the tube deforms much less, as in the paper, and the shell \
        stops in a crater of about 1.5 tube radii. The shell itself deforms little \
        (E = 100 MPa): peaks of ~1.4 % of its radius at contact events, 0.3–0.7 % otherwise as \
        it rings; the 1 % threshold of the check is ours."
        .into();
    Ok(report)
}

/// What a long run of an example scene measured.
struct LongRun {
    end_time: Real,
    steps: u64,
    /// max |B(t) − B(0)| / Ek(0) over every step.
    balance_error: Real,
    /// Largest (2r − node–PFacet distance) − largest F_n/k_n of the contacts, over the samples.
    unexplained_penetration: Real,
    /// The same without the overlap offsets: beyond the largest F_n/k_n alone (m).
    beyond_force: Real,
    /// Smallest node–PFacet distance between non-neighbours over the samples (m).
    min_distance: Real,
    contacts_born_deep: u64,
    engine_error: Option<String>,
    energy: Energy,
    node_radius: Real,
}

/// Runs the scene `file` to its duration, watching the energy balance every step and the
/// node–PFacet distances of the tube every [`PENETRATION_EVERY`] steps.
fn long_run(file: &str) -> Result<LongRun, ValidationError> {
    let scene = load_scene(&scene_path(file))?;
    let end = match scene.run {
        RunLength::Duration(d) => d,
        RunLength::Steps(_) => Real::INFINITY,
    };
    let node_radius = scene.model.particles.radius[0];
    let mut sim = Simulation::new(scene.model, scene.settings)?;
    let kinetic0 = sim.energy().kinetic_translation + sim.energy().kinetic_rotation;
    let balance0 = sim.energy().balance();
    let mut run = LongRun {
        end_time: 0.0,
        steps: 0,
        balance_error: 0.0,
        unexplained_penetration: 0.0,
        beyond_force: 0.0,
        min_distance: Real::INFINITY,
        contacts_born_deep: 0,
        engine_error: None,
        energy: *sim.energy(),
        node_radius,
    };
    while sim.time() < end {
        // a step's contact forces come from the positions it starts from: the penetration
        // they are compared with is measured there too (one step of motion, v·dt, is of the
        // order of the tolerance)
        let look = (sim.steps() + 1) % PENETRATION_EVERY == 0;
        let distance = if look { min_self_distance(sim.model()) } else { Real::INFINITY };
        if let Err(e) = sim.step() {
            run.engine_error = Some(e.to_string());
            break;
        }
        run.balance_error =
            run.balance_error.max((sim.energy().balance() - balance0).abs() / kinetic0);
        if look {
            // the overlap the contact law holds for its force: F_n/k_n plus the contact's
            // overlap offset (a contact handed over or split keeps its force continuous
            // through the offset, eq 1 with δ − δ₀)
            let carried = sim
                .contacts()
                .iter()
                .map(|c| c.forces.normal_force / c.params.kn + c.state.overlap_offset)
                .fold(0.0, Real::max);
            let by_force = sim
                .contacts()
                .iter()
                .map(|c| c.forces.normal_force / c.params.kn)
                .fold(0.0, Real::max);
            let penetration = 2.0 * node_radius - distance;
            run.unexplained_penetration = run.unexplained_penetration.max(penetration - carried);
            run.beyond_force = run.beyond_force.max(penetration - by_force);
            run.min_distance = run.min_distance.min(distance);
        }
    }
    run.end_time = sim.time();
    run.steps = sim.steps();
    run.contacts_born_deep = sim.contacts_born_deep();
    run.energy = *sim.energy();
    Ok(run)
}

/// Both solid-sphere examples (light and heavy) run to their 1 s: through the impact, the
/// rebound and the tube ringing after it (the heavy sphere winds the flattened tube around
/// itself), the energy balance holds and nothing passes through.
pub fn impact_long(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let id = "impact_long";
    let mut report = CaseReport::new(
        id,
        "Paper §7 impacts run to 1 s: energy and self-contact through the rebound",
    );
    report.setup = format!(
        "Scenes `examples/tube_impact_solid.toml` (0.112 kg sphere, safety 0.3) and \
         `examples/{HEAVY}` (4.19 kg, safety 0.1), each run to its duration of 1 s with the \
         engine's energy watch on. Every step: the energy balance error |B(t) − B(0)| / Ek(0). \
         Every {PENETRATION_EVERY} steps: the smallest distance between a tube node and a \
         PFacet it is not part of (nor a neighbour's), and the penetration 2r − distance \
         beyond what the contacts carry (the largest F_n/k_n + δ₀, eq 1 with the overlap \
         offset δ₀ of contacts handed over or split): a penetration beyond it would be a \
         self-contact the detection missed or elements passing through."
    );
    if ctx.quick {
        report.setup.push_str(" (Not in the quick subset.)");
    }
    for (label, file) in [("light sphere", "tube_impact_solid.toml"), ("heavy sphere", HEAVY)] {
        let run = long_run(file)?;
        let d = 2.0 * run.node_radius;
        report.checks.push(Check::absolute(
            &format!("{label}: energy balance error max |B(t) − B(0)| / Ek(0) to 1 s"),
            "",
            0.0,
            run.balance_error,
            ENERGY_TOL,
            "energy conservation (model.md §6), issue: ≤ 5e-3",
        ));
        report.checks.push(Check::absolute(
            &format!("{label}: engine errors (instability, energy watch)"),
            "",
            0.0,
            if run.engine_error.is_some() { 1.0 } else { 0.0 },
            0.0,
            "a stable run to 1 s",
        ));
        report.checks.push(Check::absolute(
            &format!("{label}: self-penetration not carried by a contact, max over the run"),
            "m",
            0.0,
            run.unexplained_penetration.max(0.0),
            UNEXPLAINED_PENETRATION * d,
            "contact law eq 1 (δ = F_n/k_n + δ₀): nothing passes through",
        ));
        report.inform(
            &format!("{label}: run"),
            format!(
                "{} steps to t = {:.4} s; smallest node–PFacet distance {:.3}·2r; penetration \
                 beyond the largest F_n/k_n alone (offsets not counted) {:.3e} m; {} contacts \
                 found late{}",
                run.steps,
                run.end_time,
                run.min_distance / d,
                run.beyond_force.max(0.0),
                run.contacts_born_deep,
                run.engine_error.as_ref().map_or(String::new(), |e| format!("; error: {e}"))
            ),
        );
        let e = &run.energy;
        report.inform(
            &format!("{label}: energy at the end (J)"),
            format!(
                "kinetic {:.4}, elastic links {:.4}, friction {:.4}, contact births and ends \
                 {:.2e}, released {:.2e}",
                e.kinetic_translation + e.kinetic_rotation,
                e.elastic_links,
                e.friction,
                e.contact_births,
                e.contact_releases
            ),
        );
    }
    report.notes = "Before the large-deformation work (contacts handed over with their force, \
        the side a contact was made on kept when skeletons cross, contacts that start or end \
        between steps counted, a variable step integrated consistently) the heavy sphere's \
        run went from 8.38 J to 546 J by 0.36 s and ended as 'completed'; the scenes then \
        stopped at 0.28 s. The heavy run needs safety 0.1: the beam links' energy error grows \
        as dt² with the large rotations of the crumpled, ringing tube (3e-2 at 1 s with safety \
        0.3, 6e-3 with 0.15)."
        .into();
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn in_range_accepts_the_interval_only() {
        let check = |m| in_range("q", "", (0.0, 1.0), m, "s").passed();
        assert!(check(0.0) && check(0.5) && check(1.0));
        assert!(!check(-1e-9) && !check(1.0 + 1e-9) && !check(Real::NAN));
    }
}
