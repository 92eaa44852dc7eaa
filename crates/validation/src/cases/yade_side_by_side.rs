//! flexdem with the `yade` link kinematics against YADE 2023.02a on the same scenes, from the
//! YADE outputs committed under `validation/yade/` (read here, so the report reruns without
//! YADE installed):
//!
//! - `yade_cantilever`: the 10-link cantilever under a tip load (validation.md case 2), node by
//!   node (`validation/yade/cantilever/`, our script `cantilever.py`);
//! - `yade_sphere_on_net` (its own module): a sphere dropped on a net pinned at its corners.

use crate::plot::{plot_xy, Curve, CurveStyle, PlotSpec};
use crate::report::{CaseReport, Check, Context, Figure};
use crate::rest::run_to_rest;
use crate::ValidationError;
use flexdem_contact::{LinkKinematicsMode, Material};
use flexdem_elements::builders::{chain, straight_line, StructureOptions};
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
