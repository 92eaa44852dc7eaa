//! `yade_sphere_on_net`: a sphere dropped on a net pinned at its corners, against YADE
//! 2023.02a (`validation/yade/sphere_on_net/`): the rest state of the reference run, and the
//! contact forces over an ensemble of starts.
//!
//! How a contact's force splits into normal and shear parts at rest is not set by the statics:
//! friction locks shear in during the bouncing transient, and which shear is chaotic in both
//! codes (a start 1e-10 m higher changes it). One run is one sample of it, so the forces are
//! compared as means over the same 16 starts in both codes (YADE's
//! `sphere_on_net_ensemble.py`).

use super::yade_side_by_side::{json_number, read_csv_columns, read_json, yade_data_dir};
use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Check, Context, Figure};
use crate::rest::max_speed;
use crate::ValidationError;
use flexdem_contact::{LinkKinematicsMode, Material};
use flexdem_elements::builders::{net, GridLayout, StructureOptions};
use flexdem_elements::{Dofs, Model};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation, TimeStep};
use rayon::prelude::*;
use serde_json::Value;
use std::f64::consts::PI;

/// Net of the YADE scene: cells, spacing (m), link radius (m).
const NET_CELLS: usize = 6;
const NET_SPACING: Real = 0.1;
const NET_RADIUS: Real = 0.005;
/// Sphere radius (m) and mass (kg).
const SPHERE_RADIUS: Real = 0.1;
const SPHERE_MASS: Real = 1.0;
/// The ensemble's starts: the sphere `k·ENSEMBLE_SHIFT` higher for `k` in `ENSEMBLE_KS`, as
/// in `sphere_on_net_ensemble.py` (`k = 0` is the reference run).
const ENSEMBLE_SHIFT: Real = 1e-10;
const ENSEMBLE_KS: std::ops::RangeInclusive<i32> = -7..=8;

/// One run of the scene until at rest, with its heights every 1000 steps.
struct NetRun {
    sim: Simulation,
    sphere: usize,
    centre: usize,
    grid: GridLayout,
    /// The sphere's starting height (m).
    z0: Real,
    steps: u64,
    /// (time, sphere height), (time, contacts), (time, centre node height), every 1000 steps.
    history: Vec<(Real, Real)>,
    contact_history: Vec<(Real, Real)>,
    centre_history: Vec<(Real, Real)>,
}

/// The scene of `sphere_on_net.py` with the sphere `shift` higher, run with step `dt` until
/// every speed stays below 1e-9 m/s at 10 outputs 1000 steps apart, or `max_steps`.
fn run_net(dt: Real, max_steps: u64, shift: Real) -> Result<NetRun, ValidationError> {
    let phi = 30f64.to_radians();
    let mut model = Model::new();
    let net_mat = model.add_material(Material::new(1e8, 0.3, 1000.0, phi)?)?;
    let size = NET_SPACING * NET_CELLS as Real;
    let opts = StructureOptions::new("net", NET_RADIUS, net_mat);
    let s = net(
        &mut model,
        Vec3::zeros(),
        Vec3::x(),
        Vec3::y(),
        size,
        size,
        NET_CELLS,
        NET_CELLS,
        false,
        &opts,
    )?;
    let grid = GridLayout::of(&model, s, NET_CELLS, NET_CELLS)?;
    model.block(grid.corners(), Dofs::TRANSLATION)?;
    let sphere_density = SPHERE_MASS / (4.0 / 3.0 * PI * SPHERE_RADIUS.powi(3));
    let sphere_mat = model.add_material(Material::new(1e8, 0.3, sphere_density, phi)?)?;
    let half = NET_CELLS / 2;
    let centre_xy = NET_SPACING * half as Real;
    let z0 = SPHERE_RADIUS + NET_RADIUS + shift;
    let sphere =
        model.add_sphere(Vec3::new(centre_xy, centre_xy, z0), SPHERE_RADIUS, sphere_mat)? as usize;
    let centre = grid.node(half, half) as usize;
    let settings = Settings {
        time_step: TimeStep::Fixed(dt),
        gravity: Vec3::new(0.0, 0.0, -10.0),
        damping: 0.3,
        link_mode: LinkKinematicsMode::Yade,
        ..Settings::default()
    };
    let mut sim = Simulation::new(model, settings)?;
    let at = |sim: &Simulation, i: usize| sim.model().particles.pos[i].z;
    let mut history = vec![(0.0, at(&sim, sphere))];
    let mut contact_history = vec![(0.0, sim.contacts().len() as Real)];
    let mut centre_history = vec![(0.0, at(&sim, centre))];
    let (mut steps, mut quiet_chunks) = (0, 0);
    while steps < max_steps && quiet_chunks < 10 {
        sim.run(1000)?;
        steps += 1000;
        history.push((sim.time(), at(&sim, sphere)));
        contact_history.push((sim.time(), sim.contacts().len() as Real));
        centre_history.push((sim.time(), at(&sim, centre)));
        quiet_chunks = if max_speed(&sim) <= 1e-9 { quiet_chunks + 1 } else { 0 };
    }
    Ok(NetRun { sim, sphere, centre, grid, z0, steps, history, contact_history, centre_history })
}

/// What the contacts carrying load hold at rest, and the run's lowest sphere height.
#[derive(Clone, Copy, Debug)]
struct RestForces {
    /// Mean normal force (N).
    normal: Real,
    /// Mean shear force (N).
    shear: Real,
    /// Contacts carrying load.
    count: usize,
    /// The sphere's lowest height at the outputs every 1000 steps (m).
    lowest: Real,
}

fn rest_forces(run: &NetRun) -> RestForces {
    let touching: Vec<_> =
        run.sim.contacts().into_iter().filter(|c| c.forces.normal_force > 0.0).collect();
    let n = touching.len().max(1) as Real;
    RestForces {
        normal: touching.iter().map(|c| c.forces.normal_force).sum::<Real>() / n,
        shear: touching.iter().map(|c| c.forces.shear_force.norm()).sum::<Real>() / n,
        count: touching.len(),
        lowest: run.history.iter().map(|h| h.1).fold(Real::INFINITY, Real::min),
    }
}

/// Mean, smallest and largest of `x`.
fn spread(x: &[Real]) -> (Real, Real, Real) {
    let mean = x.iter().sum::<Real>() / x.len().max(1) as Real;
    (
        mean,
        x.iter().copied().fold(Real::INFINITY, Real::min),
        x.iter().copied().fold(Real::NEG_INFINITY, Real::max),
    )
}

/// The sphere on a net against YADE.
pub fn run_sphere_on_net(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let dir = yade_data_dir().join("sphere_on_net");
    let summary_path = dir.join("sphere_on_net_summary.json");
    let summary = read_json(&summary_path)?;
    let number = |pointer: &str| json_number(&summary, pointer, &summary_path);
    let yade_sphere_z = number("/final/sphere_pos_final/2")?;
    let yade_centre_z = number("/final/centre_node_pos_final/2")?;
    let contacts = summary.pointer("/final/active_contacts_final").and_then(Value::as_array);
    let yade_fn: Vec<Real> = contacts
        .map(|list| list.iter().filter_map(|c| c.get("fn").and_then(Value::as_f64)).collect())
        .unwrap_or_default();
    if yade_fn.is_empty() {
        return Err(ValidationError::Data {
            path: summary_path,
            message: "no contact normal forces at /final/active_contacts_final".into(),
        });
    }
    let yade_nodes =
        read_csv_columns(&dir.join("sphere_on_net_final_nodes.csv"), &["i", "j", "x", "y", "z"])?;
    let ensemble_path = dir.join("sphere_on_net_ensemble.csv");
    let yade_ensemble = read_csv_columns(
        &ensemble_path,
        &["k", "fn_mean", "fs_mean", "min_sphere_z_history", "n_active"],
    )?;
    let yade_ks: Vec<i32> = yade_ensemble.iter().map(|r| r[0] as i32).collect();
    if yade_ks != ENSEMBLE_KS.collect::<Vec<_>>() {
        return Err(ValidationError::Data {
            path: ensemble_path,
            message: format!("starts k = {yade_ks:?}, expected {ENSEMBLE_KS:?}"),
        });
    }
    let dt = number("/dt")?;
    let max_steps = number("/final/steps")? as u64;

    // every start, in the order of k (the reference start, k = 0, among them)
    let runs: Vec<Result<NetRun, ValidationError>> = ENSEMBLE_KS
        .collect::<Vec<_>>()
        .into_par_iter()
        .map(|k| run_net(dt, max_steps, k as Real * ENSEMBLE_SHIFT))
        .collect();
    let runs = runs.into_iter().collect::<Result<Vec<_>, _>>()?;
    let forces: Vec<RestForces> = runs.iter().map(rest_forces).collect();
    let reference = (0 - ENSEMBLE_KS.start()) as usize;
    let run = &runs[reference];
    let rest = forces[reference];
    let (sim, sphere, centre, grid) = (&run.sim, run.sphere, run.centre, &run.grid);
    let p = &sim.model().particles;
    let sphere_z = p.pos[sphere].z;
    let centre_z = p.pos[centre].z;
    let node_difference = yade_nodes
        .iter()
        .map(|row| {
            let q = p.pos[grid.node(row[0] as usize, row[1] as usize) as usize];
            (q - Vec3::new(row[2], row[3], row[4])).norm()
        })
        .fold(0.0, Real::max);
    let column = |rows: &[Vec<Real>], i: usize| rows.iter().map(|r| r[i]).collect::<Vec<_>>();
    let (yade_fn_ens, yade_fs_ens, yade_low_ens) =
        (column(&yade_ensemble, 1), column(&yade_ensemble, 2), column(&yade_ensemble, 3));
    let ours = |f: fn(&RestForces) -> Real| forces.iter().map(f).collect::<Vec<_>>();
    let (fn_ens, fs_ens, low_ens) = (ours(|f| f.normal), ours(|f| f.shear), ours(|f| f.lowest));

    let mut report = CaseReport::new("yade_sphere_on_net", "Sphere on a net against YADE 2023.02a");
    report.setup = format!(
        "The scene of `validation/yade/sphere_on_net/sphere_on_net.py` rebuilt in flexdem: a net of \
         {NET_CELLS} × {NET_CELLS} cells of {NET_SPACING} m (49 nodes, 84 links, r = {NET_RADIUS} m, \
         E = 1e8 Pa, ν = 0.3, ρ = 1000 kg/m³, friction 30°), flat at z = 0, the 4 corners pinned \
         (translations blocked, rotations free); a sphere r = {SPHERE_RADIUS} m of mass {SPHERE_MASS} \
         kg (E = 1e8 Pa, friction 30°) starting at rest touching the centre node from above; \
         g = 10 m/s², Cundall damping 0.3, dt = {dt:e} s as in YADE, `yade` link kinematics (YADE's \
         links, and for a contact on a link YADE's spin of the virtual sphere, moment shared \
         as node torques and non-ratcheting relative velocity), contact \
         kn = 2·E·r_s·E·r_c/(E·r_s + E·r_c), ks = 0.3·kn (eq 3–4, as YADE's FrictPhys). Run until \
         every speed stays below 1e-9 m/s at 10 successive outputs 1000 steps apart ({} steps; \
         YADE ran {max_steps}). The ensemble: the same run from {} starts k·{ENSEMBLE_SHIFT:e} m \
         higher, k = {}..{} (YADE: `sphere_on_net_ensemble.py`, the same starts).",
        run.steps,
        forces.len(),
        ENSEMBLE_KS.start(),
        ENSEMBLE_KS.end(),
    );
    report.checks.push(Check::relative(
        "sphere drop z0 − z",
        "m",
        run.z0 - yade_sphere_z,
        run.z0 - sphere_z,
        0.01,
        "YADE 2023.02a",
    ));
    report.checks.push(Check::relative(
        "centre node height",
        "m",
        yade_centre_z,
        centre_z,
        0.01,
        "YADE 2023.02a",
    ));
    report.checks.push(Check::relative(
        "mean contact normal force, mean over the starts",
        "N",
        spread(&yade_fn_ens).0,
        spread(&fn_ens).0,
        0.02,
        "YADE 2023.02a, the same starts",
    ));
    report.checks.push(Check::relative(
        "lowest sphere height at the outputs, mean over the starts",
        "m",
        spread(&yade_low_ens).0,
        spread(&low_ens).0,
        0.05,
        "YADE 2023.02a, the same starts",
    ));
    report.checks.push(Check::absolute(
        "number of contacts carrying load",
        "",
        yade_fn.len() as Real,
        rest.count as Real,
        0.0,
        "YADE 2023.02a",
    ));
    let range = |x: &[Real], digits: usize| {
        let (mean, lo, hi) = spread(x);
        format!("mean {mean:.digits$}, {lo:.digits$} to {hi:.digits$}")
    };
    report.inform(
        "mean contact normal force over the starts (N)",
        format!("flexdem {}; YADE {}", range(&fn_ens, 4), range(&yade_fn_ens, 4)),
    );
    report.inform(
        "mean contact shear force over the starts (N)",
        format!("flexdem {}; YADE {}", range(&fs_ens, 4), range(&yade_fs_ens, 4)),
    );
    report.inform(
        "lowest sphere height at the outputs over the starts (m)",
        format!("flexdem {}; YADE {}", range(&low_ens, 5), range(&yade_low_ens, 5)),
    );
    report.inform(
        "reference start: mean contact normal force",
        format!("flexdem {:.5} N, YADE {:.5} N", rest.normal, spread(&yade_fn).0),
    );
    report.inform(
        "reference start: energy balance error at rest, (B(t) − B(0)) / scale (YADE's pair does \
         not conserve energy; the beam pair's is tested in tests/energy.rs)",
        format!("{:.3e}", sim.energy_watch().relative_error(sim.energy())),
    );
    let support: Real = sim.contacts().iter().map(|c| c.forces.force_on_2.z.abs()).sum();
    report.inform("vertical contact force on the sphere (weight 10 N)", format!("{support:.6} N"));
    let centre_pos = p.pos[centre];
    for c in sim.contacts().iter().filter(|c| c.forces.normal_force > 0.0) {
        let f = c.forces.force_on_2;
        let normal_dir = (f - c.forces.shear_force).normalize();
        report.inform(
            "flexdem contact: distance from centre node, normal tilt, |Fs|, Fs_z",
            format!(
                "{:.5} m, {:.2}°, {:.4} N, {:.4} N",
                (c.point - centre_pos).norm(),
                normal_dir.z.abs().acos().to_degrees(),
                c.forces.shear_force.norm(),
                c.forces.shear_force.z
            ),
        );
    }
    report.inform("largest node position difference from YADE", format!("{node_difference:.3e} m"));
    plot_rest_shape(ctx, &mut report, run, &yade_nodes)?;
    plot_history(ctx, &mut report, run, &dir)?;
    plot_mean_history(ctx, &mut report, &runs, dt, &dir)?;
    let first_contact = |h: &[(Real, Real)]| {
        h.iter().find(|c| c.1 > 0.0).map_or("never".to_string(), |c| format!("{:.2} s", c.0))
    };
    let yade_history = read_csv_columns(
        &dir.join("sphere_on_net_history.csv"),
        &["time", "sphere_z", "n_contacts", "centre_node_z"],
    )?;
    let yade_contacts: Vec<(Real, Real)> = yade_history.iter().map(|r| (r[0], r[2])).collect();
    report.inform(
        "reference start: first output with a contact (every 1000 steps)",
        format!(
            "flexdem {}, YADE {}",
            first_contact(&run.contact_history),
            first_contact(&yade_contacts)
        ),
    );
    report.inform(
        "reference start: lowest sphere height at the outputs",
        format!(
            "flexdem {:.5} m, YADE {:.5} m",
            rest.lowest,
            number("/final/min_sphere_z_history")?
        ),
    );
    report.notes =
        "Tolerances: the rest state is set by the links' stiffness under the same total \
        load (weight of sphere and net), identical in both codes with the yade kinematics, and by \
        how each contact's force splits into normal and shear parts. The heights are checked to \
        1%. The split is not set by the statics: friction locks shear in while the sphere bounces \
        on the net, and which shear is chaotic in both codes: over 16 starts 1e-10 m apart YADE's \
        mean normal force per contact ranges as shown above (its reference run is one of them). \
        So the normal force is checked as the mean over the same 16 starts in both codes, to 2% \
        (YADE's ensemble has a spread of about 2% about its mean), and the first dip as the mean \
        of the lowest heights at the outputs, to 5% (outputs every 1000 steps sample a bounce of \
        some 2000 steps). **The `yade` link kinematics are YADE's pair for a contact on a \
        link:** the virtual sphere spins with the axis at YADE's s × (v₂ − v₁) (the rigid rate \
        is s × (v₂ − v₁)/L², docs/model.md) and the contact's moment goes to the nodes as node \
        torques w·τ, as YADE's Law2_ScGridCoGeom_FrictPhys_CundallStrack does, and the \
        shear increment takes YADE's non-ratcheting relative velocity α(v₂ − v₁) − r₂ω₂×n − \
        r₁ω₁×n (the `beam` kinematics keep the exact spin, the contact point's velocity and \
        share the moment's perpendicular part as a force couple, which conserves energy; \
        YADE's pair does not). A single impact of a sliding sphere on a free three-node chain \
        then follows YADE to 1e-8 of the forces (the contact point's velocity: 3e-4 at the \
        second step of contact, 5 % of a node's lateral velocity after it). Measured step by step against \
        YADE's history written every step (2026-12-04): the first contact's shear force 0.6714 \
        N against YADE's 0.6716 (exact spin: 0.7734), the second bounce's forces within 0.3%, \
        the third's within 10% (the chatter that follows is sensitive to the nets' 1e-8 m \
        round-off difference before the first contact). Over the 16 starts (means): exact spin \
        and force couple 2.747 N normal, 0.737 N shear, first dip -0.0212 m; YADE's spin with \
        the force couple 2.707 N, 0.564 N, -0.0102 m, but the sphere at rest on four sliding \
        contacts rocked at a growing amplitude (spin 1e-11 to 8e-4 rad/s from step 7 700; \
        YADE's stays at 1e-10); YADE's pair 2.611 N, 0.212 N, -0.0107 m; YADE 2.630 N, 0.250 \
        N, -0.0101 m; with the non-ratcheting velocity too 2.627 N, 0.292 N, -0.0107 m. \
        **Why the first-dip check fails:** with YADE's pair the sphere dips \
        6% deeper than YADE's on average; the difference builds up during the chatter of steps \
        3 900-4 500 (the sphere 1.3e-4 m lower at 4 500 in the reference start), while the \
        nodes' motion after the first bounce matches YADE's to 1e-4 (node (2,3)'s spin 5.3271 \
        against 5.3274 rad/s at step 3 401). The ensembles' mean heights (figure) agree before \
        the first impact and part in it: flexdem's sphere goes some 6% deeper and rebounds some \
        30% higher (the values above), so its sphere-net oscillation loses less in the \
        impact's chatter; the separation is 2-3 standard errors of independent samples at each \
        output (neighbouring starts are correlated, so weaker evidence than it looks). Not \
        identified yet."
            .into();
    Ok(report)
}

/// The rest shape of the middle row of nodes in both codes.
fn plot_rest_shape(
    ctx: &Context,
    report: &mut CaseReport,
    run: &NetRun,
    yade_nodes: &[Vec<Real>],
) -> Result<(), ValidationError> {
    let half = NET_CELLS / 2;
    let p = &run.sim.model().particles;
    let yade_row: Vec<(Real, Real)> = yade_nodes
        .iter()
        .filter(|row| row[1] as usize == half)
        .map(|row| (row[2], row[4]))
        .collect();
    let ours: Vec<(Real, Real)> = (0..=NET_CELLS)
        .map(|i| {
            let q = p.pos[run.grid.node(i, half) as usize];
            (q.x, q.z)
        })
        .collect();
    let file = "yade_sphere_on_net_profile.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Sphere on a net: nodes of the middle row (y = 0.3) at rest",
            x_label: "x (m)",
            y_label: "z (m)",
            curves: &[
                Curve::new("YADE 2023.02a", yade_row, CurveStyle::Line),
                Curve::new("flexdem (yade kinematics)", ours, CurveStyle::Points),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "Rest shape of the middle row of nodes: YADE (line) and flexdem (points).".into(),
    });
    Ok(())
}

/// The heights of the sphere and the centre node during the drop in both codes.
fn plot_history(
    ctx: &Context,
    report: &mut CaseReport,
    run: &NetRun,
    dir: &std::path::Path,
) -> Result<(), ValidationError> {
    let yade_history = read_csv_columns(
        &dir.join("sphere_on_net_history.csv"),
        &["time", "sphere_z", "n_contacts", "centre_node_z"],
    )?;
    let t_end = run.history.last().map_or(0.0, |h| h.0).max(1.0);
    let yade = |column: usize| -> Vec<(Real, Real)> {
        yade_history.iter().map(|r| (r[0], r[column])).filter(|r| r.0 <= t_end).collect()
    };
    let file = "yade_sphere_on_net_history.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Sphere on a net: heights of the sphere's centre and the centre node",
            x_label: "time (s)",
            y_label: "z (m)",
            curves: &[
                Curve::new("YADE 2023.02a", yade(1), CurveStyle::Line),
                Curve::new("flexdem (yade kinematics)", run.history.clone(), CurveStyle::Dashed),
                Curve::new("YADE: centre node", yade(3), CurveStyle::Line),
                Curve::new("flexdem: centre node", run.centre_history.clone(), CurveStyle::Dashed),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "Heights of the sphere's centre and of the net's centre node during the drop \
                  (reference start): YADE (lines) and flexdem (dashed), every 1000 steps."
            .into(),
    });
    Ok(())
}

/// Outputs (every 1000 steps) over which the ensembles' mean heights are compared, as far as
/// `sphere_on_net_ensemble.py` writes them (100 000 steps).
const MEAN_HISTORY_OUTPUTS: usize = 100;

/// Mean and standard error over the starts of the sphere's height at each output:
/// `histories[start][output]`, as long as every start has it.
fn mean_history(histories: &[Vec<Real>]) -> Vec<(Real, Real)> {
    let outputs = histories.iter().map(Vec::len).min().unwrap_or(0);
    let n = histories.len() as Real;
    (0..outputs)
        .map(|i| {
            let mean = histories.iter().map(|h| h[i]).sum::<Real>() / n;
            let var = histories.iter().map(|h| (h[i] - mean).powi(2)).sum::<Real>() / (n - 1.0);
            (mean, (var / n).sqrt())
        })
        .collect()
}

/// The two ensembles' mean heights of the sphere during the drop, and how far apart they are
/// at the first dip and the rebound, in standard errors.
fn plot_mean_history(
    ctx: &Context,
    report: &mut CaseReport,
    runs: &[NetRun],
    dt: Real,
    dir: &std::path::Path,
) -> Result<(), ValidationError> {
    let rows = read_csv_columns(
        &dir.join("sphere_on_net_ensemble_history.csv"),
        &["k", "step", "sphere_z"],
    )?;
    let mut yade: Vec<Vec<Real>> = Vec::new();
    for k in ENSEMBLE_KS {
        let mut h: Vec<(Real, Real)> =
            rows.iter().filter(|r| r[0] as i32 == k).map(|r| (r[1], r[2])).collect();
        h.sort_by(|a, b| a.0.total_cmp(&b.0));
        yade.push(h.into_iter().map(|(_, z)| z).collect());
    }
    // flexdem's histories start at step 0; YADE's at step 1000
    let ours: Vec<Vec<Real>> = runs
        .iter()
        .map(|r| r.history.iter().skip(1).take(MEAN_HISTORY_OUTPUTS).map(|h| h.1).collect())
        .collect();
    let (yade, ours) = (mean_history(&yade), mean_history(&ours));
    let at = |i: usize| (i + 1) as Real * 1000.0 * dt;
    let curve = |m: &[(Real, Real)]| m.iter().enumerate().map(|(i, v)| (at(i), v.0)).collect();
    let file = "yade_sphere_on_net_mean_history.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Sphere on a net: the sphere's height, mean over the 16 starts",
            x_label: "time (s)",
            y_label: "z (m)",
            curves: &[
                Curve::new("YADE 2023.02a", curve(&yade), CurveStyle::Line),
                Curve::new("flexdem (yade kinematics)", curve(&ours), CurveStyle::Dashed),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "The sphere's height every 1000 steps, mean over the same 16 starts in both \
                  codes: YADE (line) and flexdem (dashed)."
            .into(),
    });
    let apart = |step: usize| {
        let i = step / 1000 - 1;
        match (yade.get(i), ours.get(i)) {
            (Some(y), Some(f)) => format!(
                "step {step}: flexdem {:.5}, YADE {:.5} ({:+.1} standard errors)",
                f.0,
                y.0,
                (f.0 - y.0) / (f.1 * f.1 + y.1 * y.1).sqrt().max(Real::MIN_POSITIVE)
            ),
            _ => format!("step {step}: no data"),
        }
    };
    report.inform(
        "mean sphere height over the starts (m)",
        [5000, 6000, 11_000, 15_000].map(apart).join("; "),
    );
    Ok(())
}
