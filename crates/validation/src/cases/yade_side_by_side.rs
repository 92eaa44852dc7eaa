//! flexdem with the `yade` link kinematics against YADE 2023.02a on the same scenes, from the
//! YADE outputs committed under `validation/yade/` (read here, so the report reruns without
//! YADE installed):
//!
//! - `yade_cantilever`: the 10-link cantilever under a tip load (validation.md case 2), node by
//!   node (`validation/yade/cantilever/`, our script `cantilever.py`);
//! - `yade_sphere_on_net`: a sphere dropped on a net pinned at its corners, the rest state
//!   (`validation/yade/sphere_on_net/`).

use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Check, Context, Figure};
use crate::rest::{max_speed, run_to_rest};
use crate::ValidationError;
use flexdem_contact::{LinkKinematicsMode, Material};
use flexdem_elements::builders::{chain, net, straight_line, GridLayout, StructureOptions};
use flexdem_elements::{Dofs, Model};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Load, Ramp, Settings, Simulation, TimeStep};
use serde_json::Value;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// The folder of the committed YADE scripts and data.
pub fn yade_data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../validation/yade")
}

/// Reads `path` as text.
fn read_text(path: &Path) -> Result<String, ValidationError> {
    std::fs::read_to_string(path)
        .map_err(|source| ValidationError::Io { path: path.to_path_buf(), source })
}

/// A CSV file with a header row: the columns named in `columns`, one row per line.
pub fn read_csv_columns(path: &Path, columns: &[&str]) -> Result<Vec<Vec<Real>>, ValidationError> {
    let text = read_text(path)?;
    let bad = |message: String| ValidationError::Data { path: path.to_path_buf(), message };
    let mut lines = text.lines();
    let header: Vec<&str> =
        lines.next().ok_or_else(|| bad("empty file".into()))?.split(',').collect();
    let index: Vec<usize> = columns
        .iter()
        .map(|c| {
            header
                .iter()
                .position(|h| h.trim() == *c)
                .ok_or_else(|| bad(format!("no column '{c}'")))
        })
        .collect::<Result<_, _>>()?;
    let mut rows = Vec::new();
    for (n, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let fields: Vec<&str> = line.split(',').collect();
        let row = index
            .iter()
            .map(|&k| {
                fields.get(k).and_then(|f| f.trim().parse::<Real>().ok()).ok_or_else(|| {
                    bad(format!("line {}: column {} is not a number", n + 2, header[k]))
                })
            })
            .collect::<Result<Vec<Real>, _>>()?;
        rows.push(row);
    }
    Ok(rows)
}

/// A JSON file.
pub fn read_json(path: &Path) -> Result<Value, ValidationError> {
    serde_json::from_str(&read_text(path)?)
        .map_err(|e| ValidationError::Data { path: path.to_path_buf(), message: e.to_string() })
}

/// The number at the JSON pointer `pointer` (e.g. `/final/sphere_pos_final/2`) of `value`.
pub fn json_number(value: &Value, pointer: &str, path: &Path) -> Result<Real, ValidationError> {
    value.pointer(pointer).and_then(Value::as_f64).ok_or_else(|| ValidationError::Data {
        path: path.to_path_buf(),
        message: format!("no number at {pointer}"),
    })
}

/// The cantilever against YADE (validation.md case 2, yade kinematics).
pub fn run_cantilever(ctx: &Context) -> Result<CaseReport, ValidationError> {
    let dir = yade_data_dir().join("cantilever");
    let summary_path = dir.join("cantilever_summary.json");
    let summary = read_json(&summary_path)?;
    let number = |pointer: &str| json_number(&summary, pointer, &summary_path);
    let (n, l, r) = (number("/segments")? as usize, number("/length")?, number("/radius")?);
    let (young, poisson, density) = (number("/young")?, number("/poisson")?, number("/density")?);
    let (damping, load) = (number("/damping")?, number("/tip_load")?);
    let yade_nodes =
        read_csv_columns(&dir.join("cantilever_nodes.csv"), &["x0", "deflection", "rot_y"])?;
    if yade_nodes.len() != n + 1 {
        return Err(ValidationError::Data {
            path: dir.join("cantilever_nodes.csv"),
            message: format!("{} nodes, expected {}", yade_nodes.len(), n + 1),
        });
    }
    let mut model = Model::new();
    let mat = model.add_material(Material::new(young, poisson, density, 30f64.to_radians())?)?;
    let points = straight_line(Vec3::zeros(), Vec3::new(l, 0.0, 0.0), n)?;
    let s = chain(&mut model, &points, &StructureOptions::new("cantilever", r, mat))?;
    let nodes = model.structures[s as usize].nodes.clone();
    model.block([nodes.start], Dofs::ALL)?;
    let tip = nodes.end - 1;
    let settings = Settings {
        time_step: TimeStep::Auto { safety: 0.5 },
        damping,
        link_mode: LinkKinematicsMode::Yade,
        ..Settings::default()
    };
    let mut sim = Simulation::new(model, settings)?;
    sim.add_load(Load {
        particles: vec![tip],
        force: Vec3::new(0.0, 0.0, -load),
        torque: Vec3::zeros(),
        ramp: Ramp::Constant,
    })?;
    let max_steps = 3_000_000;
    let steps = run_to_rest(&mut sim, 1e-10, 20_000, max_steps)?;
    let p = &sim.model().particles;
    let deflection: Vec<Real> = nodes.clone().map(|i| -p.pos[i as usize].z).collect();
    let yade_tip = yade_nodes[n][1];
    let node_difference =
        deflection.iter().zip(&yade_nodes).map(|(d, y)| (d - y[1]).abs()).fold(0.0, Real::max)
            / yade_tip;
    // rotation about y of the tip node (small: the rotation vector's y component)
    let tip_rotation = p.ori[tip as usize].scaled_axis().y;
    let inertia = PI * r.powi(4) / 4.0;
    let euler_bernoulli = load * l.powi(3) / (3.0 * young * inertia);
    let mut report = CaseReport::new("yade_cantilever", "Cantilever against YADE 2023.02a");
    report.setup = format!(
        "validation.md case 2 in both codes: {n} links along x, L = {l} m, r = {r} m, E = {young:e} Pa, \
         ν = {poisson}, ρ = {density} kg/m³, node 0 clamped, tip force {load} N along −z, no \
         gravity, Cundall damping {damping}. flexdem: `yade` link kinematics (shear increment \
         scaled by 2r/ℓ as YADE's GridNodeGeom6D), dt = 0.5 × critical ({:.3e} s), run until every \
         speed stays below 1e-10 m/s for 20000 steps ({steps} steps). YADE: our script \
         `validation/yade/cantilever/cantilever.py` (GridNodes, GridConnections, CohFrictMat, \
         dt = 0.5·PWaveTimeStep = {:.3e} s, {} steps, run until the tip deflection changes by \
         < 1e-9 over 20000 steps), data in `cantilever_nodes.csv` and `cantilever_summary.json`.",
        sim.dt(),
        number("/dt")?,
        number("/steps")?,
    );
    report.checks.push(Check::absolute(
        "max over nodes |δ_flexdem − δ_YADE| / δ_tip,YADE",
        "",
        0.0,
        node_difference,
        1e-3,
        "YADE 2023.02a, node by node",
    ));
    report.checks.push(Check::relative(
        "tip deflection",
        "m",
        yade_tip,
        deflection[n],
        1e-3,
        "YADE 2023.02a",
    ));
    report.checks.push(Check::relative(
        "tip rotation about y",
        "rad",
        number("/tip_rotation_y")?,
        tip_rotation,
        1e-3,
        "YADE 2023.02a",
    ));
    report.inform("Euler–Bernoulli P·L³/(3EI)", format!("{euler_bernoulli:.6e} m"));
    report.inform(
        "flexdem tip deflection / P·L³/(3EI)",
        format!("{:.5}", deflection[n] / euler_bernoulli),
    );
    report.inform("YADE tip deflection / P·L³/(3EI)", format!("{:.5}", yade_tip / euler_bernoulli));
    if steps >= max_steps {
        report.inform("warning", format!("not at rest after {steps} steps"));
    }
    let x: Vec<Real> = yade_nodes.iter().map(|row| row[0]).collect();
    let fine: Vec<(Real, Real)> = (0..=100)
        .map(|k| {
            let xi = l * k as Real / 100.0;
            (xi, 1e3 * load * xi * xi * (3.0 * l - xi) / (6.0 * young * inertia))
        })
        .collect();
    let file = "yade_cantilever_deflection.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Cantilever, tip load: deflection along the beam",
            x_label: "x (m)",
            y_label: "deflection (mm)",
            curves: &[
                Curve::new("Euler-Bernoulli", fine, CurveStyle::Dashed),
                Curve::new(
                    "YADE 2023.02a",
                    x.iter().zip(&yade_nodes).map(|(&x, y)| (x, 1e3 * y[1])).collect(),
                    CurveStyle::Line,
                ),
                Curve::new(
                    "flexdem (yade kinematics)",
                    x.iter().zip(&deflection).map(|(&x, d)| (x, 1e3 * d)).collect(),
                    CurveStyle::Points,
                ),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "Static deflection of the nodes: flexdem with the yade kinematics (points), YADE \
                  (line), Euler–Bernoulli P·x²(3L − x)/(6EI) (dashed)."
            .into(),
    });
    report.notes = "Both codes are about 1% softer than Euler–Bernoulli with these kinematics: \
        YADE's shear increment uses a branch of length r instead of ℓ/2, which adds \
        N·P·ℓ³/(12EI)·(ℓ/(2r) − 1) to the tip deflection (ratio 1.010 here). The comparison \
        is of the two static states, so the time steps and transients need not match."
        .into();
    Ok(report)
}

/// Net of the YADE scene: cells, spacing (m), link radius (m).
const NET_CELLS: usize = 6;
const NET_SPACING: Real = 0.1;
const NET_RADIUS: Real = 0.005;
/// Sphere radius (m) and mass (kg).
const SPHERE_RADIUS: Real = 0.1;
const SPHERE_MASS: Real = 1.0;

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
    let yade_fn_mean = yade_fn.iter().sum::<Real>() / yade_fn.len() as Real;
    let yade_nodes =
        read_csv_columns(&dir.join("sphere_on_net_final_nodes.csv"), &["i", "j", "x", "y", "z"])?;

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
    let z0 = SPHERE_RADIUS + NET_RADIUS;
    let sphere =
        model.add_sphere(Vec3::new(centre_xy, centre_xy, z0), SPHERE_RADIUS, sphere_mat)? as usize;
    let centre = grid.node(half, half) as usize;
    let settings = Settings {
        time_step: TimeStep::Fixed(number("/dt")?),
        gravity: Vec3::new(0.0, 0.0, -10.0),
        damping: 0.3,
        link_mode: LinkKinematicsMode::Yade,
        ..Settings::default()
    };
    let mut sim = Simulation::new(model, settings)?;
    let max_steps = number("/final/steps")? as u64;
    // the sphere's height every 1000 steps (as YADE's history) until at rest
    let mut history = vec![(0.0, sim.model().particles.pos[sphere].z)];
    let mut contact_history = vec![(0.0, sim.contacts().len() as Real)];
    let mut centre_history = vec![(0.0, sim.model().particles.pos[centre].z)];
    let (mut steps, mut quiet_chunks) = (0, 0);
    while steps < max_steps && quiet_chunks < 10 {
        sim.run(1000)?;
        steps += 1000;
        history.push((sim.time(), sim.model().particles.pos[sphere].z));
        contact_history.push((sim.time(), sim.contacts().len() as Real));
        centre_history.push((sim.time(), sim.model().particles.pos[centre].z));
        quiet_chunks = if max_speed(&sim) <= 1e-9 { quiet_chunks + 1 } else { 0 };
    }
    let yade_history = read_csv_columns(
        &dir.join("sphere_on_net_history.csv"),
        &["time", "sphere_z", "n_contacts", "centre_node_z"],
    )?;
    let p = &sim.model().particles;
    let sphere_z = p.pos[sphere].z;
    let centre_z = p.pos[centre].z;
    let touching: Vec<Real> = sim
        .contacts()
        .iter()
        .filter(|c| c.forces.normal_force > 0.0)
        .map(|c| c.forces.normal_force)
        .collect();
    let fn_mean = touching.iter().sum::<Real>() / touching.len().max(1) as Real;
    let support: Real = sim.contacts().iter().map(|c| c.forces.force_on_2.z.abs()).sum();
    let node_difference = yade_nodes
        .iter()
        .map(|row| {
            let q = p.pos[grid.node(row[0] as usize, row[1] as usize) as usize];
            (q - Vec3::new(row[2], row[3], row[4])).norm()
        })
        .fold(0.0, Real::max);
    let mut report = CaseReport::new("yade_sphere_on_net", "Sphere on a net against YADE 2023.02a");
    report.setup = format!(
        "The scene of `validation/yade/sphere_on_net/sphere_on_net.py` rebuilt in flexdem: a net of \
         {NET_CELLS} × {NET_CELLS} cells of {NET_SPACING} m (49 nodes, 84 links, r = {NET_RADIUS} m, \
         E = 1e8 Pa, ν = 0.3, ρ = 1000 kg/m³, friction 30°), flat at z = 0, the 4 corners pinned \
         (translations blocked, rotations free); a sphere r = {SPHERE_RADIUS} m of mass {SPHERE_MASS} \
         kg (E = 1e8 Pa, friction 30°) starting at rest touching the centre node from above; \
         g = 10 m/s², Cundall damping 0.3, dt = {:e} s as in YADE, `yade` link kinematics, contact \
         kn = 2·E·r_s·E·r_c/(E·r_s + E·r_c), ks = 0.3·kn (eq 3–4, as YADE's FrictPhys). Run until \
         every speed stays below 1e-9 m/s at 10 successive outputs 1000 steps apart ({steps} steps; \
         YADE ran {max_steps}).",
        sim.dt()
    );
    report.checks.push(Check::relative(
        "sphere drop z0 − z",
        "m",
        z0 - yade_sphere_z,
        z0 - sphere_z,
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
        "mean contact normal force",
        "N",
        yade_fn_mean,
        fn_mean,
        0.02,
        "YADE 2023.02a",
    ));
    report.checks.push(Check::absolute(
        "number of contacts carrying load",
        "",
        yade_fn.len() as Real,
        touching.len() as Real,
        0.0,
        "YADE 2023.02a",
    ));
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
    report.inform(
        "contact normal forces (flexdem)",
        touching.iter().map(|f| format!("{f:.5}")).collect::<Vec<_>>().join(", "),
    );
    report.inform(
        "contact normal forces (YADE)",
        yade_fn.iter().map(|f| format!("{f:.5}")).collect::<Vec<_>>().join(", "),
    );
    let profile = |z: &dyn Fn(usize) -> Real| -> Vec<(Real, Real)> {
        (0..=NET_CELLS).map(|i| (NET_SPACING * i as Real, z(i))).collect()
    };
    let yade_row: Vec<(Real, Real)> = yade_nodes
        .iter()
        .filter(|row| row[1] as usize == half)
        .map(|row| (row[2], row[4]))
        .collect();
    let ours = profile(&|i| p.pos[grid.node(i, half) as usize].z);
    let ours_x: Vec<(Real, Real)> = ours
        .iter()
        .enumerate()
        .map(|(i, &(_, z))| (p.pos[grid.node(i, half) as usize].x, z))
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
                Curve::new("flexdem (yade kinematics)", ours_x, CurveStyle::Points),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "Rest shape of the middle row of nodes: YADE (line) and flexdem (points).".into(),
    });
    let t_end = history.last().map_or(0.0, |h| h.0).max(1.0);
    let file = "yade_sphere_on_net_history.png";
    plot_xy(
        &ctx.out_dir.join(file),
        &PlotSpec {
            title: "Sphere on a net: heights of the sphere's centre and the centre node",
            x_label: "time (s)",
            y_label: "z (m)",
            curves: &[
                Curve::new(
                    "YADE 2023.02a",
                    yade_history.iter().map(|r| (r[0], r[1])).filter(|r| r.0 <= t_end).collect(),
                    CurveStyle::Line,
                ),
                Curve::new("flexdem (yade kinematics)", history.clone(), CurveStyle::Dashed),
                Curve::new(
                    "YADE: centre node",
                    yade_history.iter().map(|r| (r[0], r[3])).filter(|r| r.0 <= t_end).collect(),
                    CurveStyle::Line,
                ),
                Curve::new("flexdem: centre node", centre_history, CurveStyle::Dashed),
            ],
        },
    )?;
    report.figures.push(Figure {
        file: file.into(),
        caption: "Heights of the sphere's centre and of the net's centre node during the drop: \
                  YADE (lines) and flexdem (dashed), every 1000 steps."
            .into(),
    });
    let first_contact = |h: &[(Real, Real)]| {
        h.iter().find(|c| c.1 > 0.0).map_or("never".to_string(), |c| format!("{:.2} s", c.0))
    };
    let most = |h: &[(Real, Real)]| h.iter().map(|c| c.1).fold(0.0, Real::max);
    let yade_contacts: Vec<(Real, Real)> = yade_history.iter().map(|r| (r[0], r[2])).collect();
    report.inform(
        "first output with a contact (every 1000 steps)",
        format!(
            "flexdem {}, YADE {}",
            first_contact(&contact_history),
            first_contact(&yade_contacts)
        ),
    );
    report.inform(
        "most contacts at an output",
        format!("flexdem {}, YADE {}", most(&contact_history), most(&yade_contacts)),
    );
    let lowest = history.iter().map(|h| h.1).fold(Real::INFINITY, Real::min);
    let yade_lowest = number("/final/min_sphere_z_history")?;
    report.inform(
        "lowest sphere height during the drop (outputs every 1000 steps)",
        format!("flexdem {lowest:.5} m, YADE {yade_lowest:.5} m"),
    );
    report.notes = format!(
        "Tolerances: the rest state is set by the links' stiffness under the same total load \
         (weight of sphere and net), identical in both codes with the yade kinematics, and by how \
         each contact's force splits into normal and shear parts. The heights are checked to 1%. \
         The normal force is checked to 2%: YADE's shear forces at rest (0.19 N per contact, 7% of \
         the normal force) are locked in by friction during the transient and their vertical \
         share is about 2% of the support. **Why the normal force check fails:** flexdem's \
         transient is not YADE's (figure: the sphere's first dip goes to {lowest:.4} m against \
         {yade_lowest:.4} m in YADE), so the friction locks in about three times YADE's shear \
         force (see the informative values), and with the same contact geometry (same contact \
         positions and normal tilt to 0.2°) the normal force must then be larger to carry the \
         same weight. The difference lies in the transient, not in the static law: with the \
         shear force taken into account both codes are in equilibrium with the same 10 N \
         support. The sphere's settling on fixed connections and PFacets follows YADE's to 1e-12 m \
         ([`yade_force_splits`](#yade_force_splits)), so the contact law, the damping and the \
         integration agree step for step; the difference lies where the net moves (the links' \
         dynamics, node rotational inertia and damping, or the contact's shear kinematics on \
         moving connections) and is not identified yet. **This check's pass is not robust:** \
         the shear locked in during the transient is chaotic. Starts of the sphere 1e-12 m \
         higher or lower give a mean normal force of 2.679 or 2.758 N (fails), 1e-10 and 1e-9 m \
         higher 2.721 and 2.597 N: over these five starts 2.597–2.758 N, median 2.679 N, 2.2 % \
         above YADE's one run. Round-off moves it alike: builds whose shear transport rounds \
         its magnitude restore otherwise (issue 14) gave 2.646 N (shear 0.28–0.32 N per \
         contact) and 2.690 N (shear 0.49 N). YADE's own run is one sample of such a spread."
    );
    Ok(report)
}
