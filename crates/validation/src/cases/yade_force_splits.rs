//! How a sphere at rest on fixed elements shares its weight among their nodes, flexdem with
//! the `yade` link kinematics against the YADE 2023.02a runs committed in
//! `validation/yade/sphere_on_cylinder/` and `validation/yade/sphere_on_pfacet/`
//! (validation.md cases 7, 8 and 9): a sphere on a connection at t = 0.25 (node forces
//! (1 − t)·W and t·W), above the node shared by two connections (one contact, W on that node),
//! and above the barycentric points (0.1, 0.1) and (0.2, 0.1) of a PFacet (node forces
//! (1 − x − y, x, y)·W).

use super::yade_side_by_side::{json_number, read_csv_columns, read_json, yade_data_dir};
use crate::report::{CaseReport, Check, Context};
use crate::ValidationError;
use flexdem_contact::{LinkKinematicsMode, Material};
use flexdem_elements::builders::{chain, pfacets_from_mesh, StructureOptions};
use flexdem_elements::{Dofs, Model};
use flexdem_geom::{Real, TriMesh, Vec3};
use flexdem_integrate::{Settings, Simulation, TimeStep};
use std::f64::consts::PI;
use std::ops::Range;

/// Element radius, sphere radius (m), sphere mass (kg) and gravity (m/s²) of the YADE scenes.
const ELEMENT_RADIUS: Real = 0.01;
const SPHERE_RADIUS: Real = 0.05;
const SPHERE_MASS: Real = 1.0;
const GRAVITY: Real = 10.0;
/// Relative tolerance of the node forces and the contact force: both codes are at rest to
/// round-off after the same 4000 steps, so the shares agree to round-off; 1e-6 leaves room
/// for the residual motion.
const TOL: Real = 1e-6;

/// What a sphere at rest on fixed elements gave: the z force on each node (N), the number of
/// contacts and the sphere's height (m).
struct Rest {
    node_fz: Vec<Real>,
    contacts: usize,
    sphere_z: Real,
    /// (time, sphere height) every 20 steps, as YADE's histories.
    history: Vec<(Real, Real)>,
}

/// Adds the sphere above (x, y) touching elements in the plane z = 0, runs the YADE scene's
/// 4000 steps of 1e-4 s (g = 10, Cundall damping 0.3) and reads the rest state; `nodes` are
/// the fixed nodes.
fn settle(mut model: Model, nodes: Range<u32>, x: Real, y: Real) -> Result<Rest, ValidationError> {
    model.block(nodes.clone(), Dofs::ALL)?;
    let density = SPHERE_MASS / (4.0 / 3.0 * PI * SPHERE_RADIUS.powi(3));
    let mat = model.add_material(Material::new(1e8, 0.3, density, 30f64.to_radians())?)?;
    let z0 = SPHERE_RADIUS + ELEMENT_RADIUS;
    let sphere = model.add_sphere(Vec3::new(x, y, z0), SPHERE_RADIUS, mat)? as usize;
    let settings = Settings {
        time_step: TimeStep::Fixed(1e-4),
        gravity: Vec3::new(0.0, 0.0, -GRAVITY),
        damping: 0.3,
        link_mode: LinkKinematicsMode::Yade,
        ..Settings::default()
    };
    let mut sim = Simulation::new(model, settings)?;
    let mut history = vec![(0.0, sim.model().particles.pos[sphere].z)];
    for _ in 0..200 {
        sim.run(20)?;
        history.push((sim.time(), sim.model().particles.pos[sphere].z));
    }
    Ok(Rest {
        history,
        node_fz: nodes.map(|n| sim.forces()[n as usize].z).collect(),
        contacts: sim.contacts().iter().filter(|c| c.forces.normal_force > 0.0).count(),
        sphere_z: sim.model().particles.pos[sphere].z,
    })
}

/// A model with a chain through `points` (radius 0.01 m, E = 1e8 Pa, ν = 0.3, ρ = 1000,
/// friction 30°) and its nodes.
fn chain_model(points: &[Vec3]) -> Result<(Model, Range<u32>), ValidationError> {
    let mut model = Model::new();
    let mat = model.add_material(Material::new(1e8, 0.3, 1000.0, 30f64.to_radians())?)?;
    let s = chain(&mut model, points, &StructureOptions::new("cylinder", ELEMENT_RADIUS, mat))?;
    let nodes = model.structures[s as usize].nodes.clone();
    Ok((model, nodes))
}

/// A model with the PFacet (0,0,0), (1,0,0), (0,1,0) and its nodes.
fn pfacet_model() -> Result<(Model, Range<u32>), ValidationError> {
    let mut model = Model::new();
    let mat = model.add_material(Material::new(1e8, 0.3, 1000.0, 30f64.to_radians())?)?;
    let mesh =
        TriMesh { vertices: vec![Vec3::zeros(), Vec3::x(), Vec3::y()], triangles: vec![[0, 1, 2]] };
    let s = pfacets_from_mesh(
        &mut model,
        &mesh,
        0.0,
        &StructureOptions::new("pfacet", ELEMENT_RADIUS, mat),
    )?;
    let nodes = model.structures[s as usize].nodes.clone();
    Ok((model, nodes))
}

/// The force splits against YADE.
pub fn run_force_splits(_ctx: &Context) -> Result<CaseReport, ValidationError> {
    let mut report =
        CaseReport::new("yade_force_splits", "Force splits among nodes against YADE 2023.02a");
    report.setup = format!(
        "The scenes of `validation/yade/sphere_on_cylinder/` and `validation/yade/sphere_on_pfacet/` \
         rebuilt in flexdem: fixed nodes (all 6 DOF blocked) of radius {ELEMENT_RADIUS} m joined by \
         connections or a PFacet (E = 1e8 Pa, ν = 0.3, ρ = 1000 kg/m³, friction 30°) in the plane \
         z = 0; a sphere of radius {SPHERE_RADIUS} m and mass {SPHERE_MASS} kg (W = 10 N, E = 1e8 Pa) \
         starting at rest touching them from above; g = {GRAVITY} m/s², Cundall damping 0.3, \
         dt = 1e-4 s, 4000 steps as in YADE, `yade` link kinematics. Scenes: `t025`, one \
         connection (0,0,0)–(1,0,0), sphere above x = 0.25; `node`, connections \
         (0,0,0)–(0.5,0,0)–(1,0,0), sphere above the shared node; `p0101` and `p0201`, the PFacet \
         (0,0,0), (1,0,0), (0,1,0), sphere above (0.1, 0.1) and (0.2, 0.1). Measured: the z force \
         of the contact on each node, the number of contacts, the sphere's rest height and its \
         height every 20 steps while it settles (against YADE's histories)."
    );
    let cylinder_path = yade_data_dir().join("sphere_on_cylinder/sphere_on_cylinder_summary.json");
    let pfacet_path = yade_data_dir().join("sphere_on_pfacet/sphere_on_pfacet_summary.json");
    let cylinder = read_json(&cylinder_path)?;
    let pfacet = read_json(&pfacet_path)?;
    let two_links = [Vec3::zeros(), Vec3::new(0.5, 0.0, 0.0), Vec3::x()];
    // (scene, model, sphere x, sphere y, YADE summary, its path)
    let scenes = [
        ("t025", chain_model(&[Vec3::zeros(), Vec3::x()])?, 0.25, 0.0, &cylinder, &cylinder_path),
        ("node", chain_model(&two_links)?, 0.5, 0.0, &cylinder, &cylinder_path),
        ("p0101", pfacet_model()?, 0.1, 0.1, &pfacet, &pfacet_path),
        ("p0201", pfacet_model()?, 0.2, 0.1, &pfacet, &pfacet_path),
    ];
    for (name, (model, nodes), x, y, data, path) in scenes {
        let count = nodes.len();
        let rest = settle(model, nodes, x, y)?;
        for k in 0..count {
            let expected =
                json_number(data, &format!("/cases/{name}/node_force_final/{k}/2"), path)?;
            let quantity = format!("{name}: node {k} force z");
            let check = if expected == 0.0 {
                Check::absolute(
                    &quantity,
                    "N",
                    0.0,
                    rest.node_fz[k],
                    TOL * SPHERE_MASS * GRAVITY,
                    "YADE 2023.02a",
                )
            } else {
                Check::relative(&quantity, "N", expected, rest.node_fz[k], TOL, "YADE 2023.02a")
            };
            report.checks.push(check);
        }
        let yade_contacts = json_number(data, &format!("/cases/{name}/n_contacts_final"), path)?;
        report.checks.push(Check::absolute(
            &format!("{name}: contacts"),
            "",
            yade_contacts,
            rest.contacts as Real,
            0.0,
            "YADE 2023.02a",
        ));
        let history_path = path.with_file_name(format!(
            "{}_{name}_history.csv",
            if name.starts_with('p') { "sphere_on_pfacet" } else { "sphere_on_cylinder" }
        ));
        if history_path.is_file() {
            let yade_history = read_csv_columns(&history_path, &["time", "sphere_z"])?;
            let difference = rest
                .history
                .iter()
                .zip(&yade_history)
                .map(|(ours, theirs)| (ours.1 - theirs[1]).abs())
                .fold(0.0, Real::max);
            report.checks.push(Check::absolute(
                &format!("{name}: largest |z_flexdem − z_YADE| of the sphere while settling"),
                "m",
                0.0,
                difference,
                1e-12,
                "YADE 2023.02a history, every 20 steps",
            ));
        }
        let yade_z = json_number(data, &format!("/cases/{name}/sphere_pos_final/2"), path)?;
        report.checks.push(Check::absolute(
            &format!("{name}: sphere height"),
            "m",
            yade_z,
            rest.sphere_z,
            1e-9,
            "YADE 2023.02a (r_s + r − W/kn)",
        ));
    }
    report.notes = "The node forces are the contact's force shared by the weights of the contact \
        point: (1 − t, t) on a connection, barycentric on a PFacet. YADE 2023.02a has the correct \
        PFacet weights (the pre-MR-628 permutation would put 80% on node 2 for p0101). The \
        sphere height is r_s + r − W/kn with kn = 2·E·r_s·E·r/(E·r_s + E·r) in both codes, to \
        1e-9 m (the overlap is 6e-6 m). The sphere's whole settling (a damped bounce of 4000 \
        steps) follows YADE's to 1e-12 m: the contact law, Cundall damping and the leapfrog \
        integration are the same step for step."
        .into();
    Ok(report)
}
