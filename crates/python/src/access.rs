//! Every read of the engine's state that the module makes, in one place: the only code that
//! knows the fields of [`Simulation`] (`model`, `contacts`, `links`). Issue 13 moves them
//! behind methods (`sim.model()`, `sim.contacts()`, ...); only this file changes then.
//!
//! Each function copies what it reads into flat vectors (x, y, z of each row in turn) in
//! one pass, ready to become numpy arrays.

use flexdem_contact::LinkStatus;
use flexdem_elements::virtual_sphere::{Feature, Site};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::Simulation;

/// `vectors` as x, y, z of each in turn.
pub(crate) fn flat(vectors: &[Vec3]) -> Vec<Real> {
    vectors.iter().flat_map(|v| [v.x, v.y, v.z]).collect()
}

/// The particles' columns a script reads.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ParticleColumn {
    /// Positions of the centres (m).
    Positions,
    /// Velocities (m/s).
    Velocities,
    /// Angular velocities (rad/s).
    AngularVelocities,
    /// Total force of the last step (N): links, contacts, loads, gravity.
    Forces,
}

/// Number of particles (free spheres and structure nodes).
pub(crate) fn particle_count(sim: &Simulation) -> usize {
    sim.model().particles.len()
}

/// One vector per particle, flat (see [`flat`]).
pub(crate) fn particle_vectors(sim: &Simulation, column: ParticleColumn) -> Vec<Real> {
    let p = &sim.model().particles;
    match column {
        ParticleColumn::Positions => flat(&p.pos),
        ParticleColumn::Velocities => flat(&p.vel),
        ParticleColumn::AngularVelocities => flat(&p.ang_vel),
        ParticleColumn::Forces => {
            let forces = sim.forces();
            if forces.len() == p.len() {
                flat(forces)
            } else {
                // no step yet (a fresh or resumed simulation): no force computed
                vec![0.0; 3 * p.len()]
            }
        }
    }
}

/// Radii of the particles (m).
pub(crate) fn radii(sim: &Simulation) -> Vec<Real> {
    sim.model().particles.radius.clone()
}

/// Masses of the particles (kg).
pub(crate) fn masses(sim: &Simulation) -> Vec<Real> {
    sim.model().particles.mass.clone()
}

/// Structure of each particle, −1 for a free sphere (as in the VTK output).
pub(crate) fn structures(sim: &Simulation) -> Vec<i64> {
    let none = flexdem_elements::NO_STRUCTURE;
    sim.model().particles.structure.iter().map(|&s| if s == none { -1 } else { s as i64 }).collect()
}

/// The contacts of the last step, one row each.
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactTable {
    /// Feature ids of the two sites (particle, edge = connection, face = PFacet, or wall
    /// index), 2 per contact.
    pub features: Vec<i64>,
    /// Kinds of the two sites, 2 per contact: 0 particle, 1 edge, 2 face, 3 wall (the VTK
    /// output's `kind1`, `kind2`).
    pub kinds: Vec<i8>,
    /// Contact points, 3 per contact.
    pub points: Vec<Real>,
    /// Unit normals from body 1 to body 2, 3 per contact.
    pub normals: Vec<Real>,
    /// Normal force, compression positive.
    pub normal_force: Vec<Real>,
    /// Shear force on body 2, 3 per contact.
    pub shear_force: Vec<Real>,
    /// Total force on body 2, 3 per contact.
    pub force: Vec<Real>,
}

/// The id and kind of a site's feature (kinds as in the VTK output).
fn feature(site: &Site) -> (i64, i8) {
    match site.feature {
        Feature::Particle(i) => (i as i64, 0),
        Feature::Edge(i) => (i as i64, 1),
        Feature::Face(i) => (i as i64, 2),
        Feature::Wall(i) => (i as i64, 3),
    }
}

/// The contacts of the last step.
pub(crate) fn contacts(sim: &Simulation) -> ContactTable {
    let list = sim.contacts();
    let mut t = ContactTable::default();
    for c in list {
        let (f1, k1) = feature(&c.site1);
        let (f2, k2) = feature(&c.site2);
        t.features.extend([f1, f2]);
        t.kinds.extend([k1, k2]);
        t.points.extend([c.point.x, c.point.y, c.point.z]);
        let n = c.state.normal;
        t.normals.extend([n.x, n.y, n.z]);
        t.normal_force.push(c.forces.normal_force);
        let s = c.forces.shear_force;
        t.shear_force.extend([s.x, s.y, s.z]);
        let f = c.forces.force_on_2;
        t.force.extend([f.x, f.y, f.z]);
    }
    t
}

/// The beam links (one per connection), one row each.
#[derive(Clone, Debug, Default)]
pub(crate) struct LinkTable {
    /// The two nodes (particle ids), 2 per link.
    pub nodes: Vec<i64>,
    /// 0 cohesive, 1 frictional (lost its cohesion), 2 broken.
    pub status: Vec<i8>,
    /// Normal force of the last step, compression positive (N).
    pub normal_force: Vec<Real>,
    /// Shear force on node 2, 3 per link (N).
    pub shear_force: Vec<Real>,
    /// Total force on node 2, 3 per link (N).
    pub force: Vec<Real>,
}

/// The links and their forces of the last step (zero before the first step).
pub(crate) fn links(sim: &Simulation) -> LinkTable {
    let links = sim.links();
    let count = links.nodes.len();
    let mut t = LinkTable {
        nodes: links.nodes.iter().flat_map(|n| n.map(i64::from)).collect(),
        status: links
            .state
            .iter()
            .map(|s| match s.status {
                LinkStatus::Cohesive => 0,
                LinkStatus::Frictional => 1,
                LinkStatus::Broken => 2,
            })
            .collect(),
        ..LinkTable::default()
    };
    if links.loads.len() == count {
        for (k, (f, s)) in links.loads.iter().zip(&links.state).enumerate() {
            t.normal_force.push(links.normal_force(k));
            t.shear_force.extend([s.shear_force.x, s.shear_force.y, s.shear_force.z]);
            t.force.extend([f.force_on_2.x, f.force_on_2.y, f.force_on_2.z]);
        }
    } else {
        // no step yet (the forces are not saved in checkpoints)
        t.normal_force = vec![0.0; count];
        t.shear_force = vec![0.0; 3 * count];
        t.force = vec![0.0; 3 * count];
    }
    t
}

/// Every energy term by name (the fields of `flexdem_integrate::Energy`, as in the summary),
/// then `stored`, `put_in`, `taken_out`, `balance`, `initial_balance`, `lowest_balance` (energy
/// created is measured from it), `scale`, `relative_balance_error` and `late_births` (the
/// energy contacts found late put in, part of `contact_births`, which the watch limits).
pub(crate) fn energy(sim: &Simulation) -> Vec<(String, Real)> {
    let e = sim.energy();
    let mut terms: Vec<(String, Real)> = match serde_json::to_value(e) {
        Ok(serde_json::Value::Object(map)) => {
            map.into_iter().filter_map(|(k, v)| v.as_f64().map(|x| (k, x))).collect()
        }
        _ => Vec::new(),
    };
    let watch = sim.energy_watch();
    terms.extend([
        ("stored".to_string(), e.stored()),
        ("put_in".to_string(), e.put_in()),
        ("taken_out".to_string(), e.taken_out()),
        ("balance".to_string(), e.balance()),
        ("initial_balance".to_string(), watch.initial_balance),
        ("lowest_balance".to_string(), watch.lowest_balance),
        ("scale".to_string(), watch.scale),
        ("relative_balance_error".to_string(), sim.relative_balance_error()),
        ("late_births".to_string(), watch.late_births),
    ]);
    terms
}

/// A change a script makes between stages of a run, through the engine's setters (which
/// check the values and keep the simulation's caches right).
pub(crate) enum Change {
    /// Cundall damping coefficient.
    Damping(Real),
    /// Gravity vector (m/s²).
    Gravity(Vec3),
    /// Velocity of a wall (m/s).
    WallVelocity(u32, Vec3),
    /// Imposed velocity of particles (m/s): their translations are blocked and driven.
    ImposedVelocity(Vec<u32>, Vec3),
    /// Velocity set by hand on particles (m/s): a kick on their free DOFs (load work).
    Velocity(Vec<u32>, Vec3),
    /// Angular velocity set by hand on particles (rad/s).
    AngularVelocity(Vec<u32>, Vec3),
    /// A wall's control (a servo, or back to its velocity).
    WallControl(u32, flexdem_integrate::WallControl),
    /// A pressure on the PFacets of a structure, by name.
    AddPressure {
        /// The structure's name.
        structure: String,
        /// The pressure load (its PFacets filled from the structure).
        pressure: flexdem_integrate::Pressure,
    },
    /// No pressure any more.
    ClearPressures,
}

/// Applies `change` to `sim`; the engine's message when it refuses it.
pub(crate) fn apply(sim: &mut Simulation, change: Change) -> Result<(), String> {
    match change {
        Change::Damping(d) => sim.set_damping(d),
        Change::Gravity(g) => sim.set_gravity(g),
        Change::WallVelocity(w, v) => sim.set_wall_velocity(w, v),
        Change::ImposedVelocity(particles, v) => sim.impose_velocity(particles, v),
        Change::Velocity(particles, v) => sim.set_velocities(particles, v),
        Change::AngularVelocity(particles, w) => sim.set_angular_velocities(particles, w),
        Change::WallControl(w, control) => sim.set_wall_control(w, control),
        Change::AddPressure { structure, mut pressure } => {
            let model = sim.model();
            let Some(id) = model.structure_by_name(&structure) else {
                let known: Vec<&str> = model.structures.iter().map(|s| s.name.as_str()).collect();
                return Err(format!(
                    "unknown structure `{structure}`; the structures are: {}",
                    known.join(", ")
                ));
            };
            pressure.pfacets = model.structures[id as usize].pfacets.clone().collect();
            if pressure.pfacets.is_empty() {
                return Err(format!("structure `{structure}` has no PFacets to press on"));
            }
            sim.add_pressure(pressure)
        }
        Change::ClearPressures => sim.set_pressures(Vec::new()),
    }
    .map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexdem_scene::parse_scene;

    /// A chain of 4 links clamped at its start, pulled at its end.
    fn chain() -> Simulation {
        let text = r#"
            [simulation]
            steps = 10
            [materials.m]
            young = 1e8
            poisson = 0.3
            density = 1000
            friction_angle_deg = 30
            [[structures]]
            name = "c"
            kind = "chain"
            material = "m"
            node_radius = 0.01
            start = [0, 0, 0]
            end = [1, 0, 0]
            segments = 4
            [[spheres]]
            name = "s"
            kind = "single"
            material = "m"
            center = [0.5, 0, 0.5]
            radius = 0.05
            [[boundary]]
            select = { structure = "c", side = "start" }
            block = "xyzXYZ"
            [[loads]]
            select = { structure = "c", side = "end" }
            force = [1, 0, 0]
        "#;
        let scene = parse_scene(text, "chain.toml".as_ref()).expect("scene");
        flexdem_run::build_simulation(scene).expect("simulation").0
    }

    #[test]
    fn particle_columns_are_flat_rows_of_three() {
        let mut sim = chain();
        assert_eq!(particle_count(&sim), 6);
        let pos = particle_vectors(&sim, ParticleColumn::Positions);
        assert_eq!(pos.len(), 18);
        assert_eq!(&pos[15..], &[0.5, 0.0, 0.5]);
        assert_eq!(structures(&sim), vec![0, 0, 0, 0, 0, -1]);
        assert_eq!(radii(&sim)[5], 0.05);
        // no force before the first step, the load after it
        assert!(particle_vectors(&sim, ParticleColumn::Forces).iter().all(|&f| f == 0.0));
        sim.step().expect("step");
        let forces = particle_vectors(&sim, ParticleColumn::Forces);
        assert!(forces[12] > 0.0, "the pulled end: {forces:?}");
    }

    #[test]
    fn links_and_energy() {
        let mut sim = chain();
        let t = links(&sim);
        assert_eq!(t.nodes, vec![0, 1, 1, 2, 2, 3, 3, 4]);
        assert_eq!(t.status, vec![0; 4]);
        assert_eq!(t.force, vec![0.0; 12]);
        sim.run(10).expect("run");
        let t = links(&sim);
        assert_eq!(t.normal_force.len(), 4);
        assert!(t.normal_force[3] < 0.0, "the last link in tension: {:?}", t.normal_force);
        assert!(contacts(&sim).normal_force.is_empty());
        let e = energy(&sim);
        let names: Vec<&str> = e.iter().map(|(k, _)| k.as_str()).collect();
        assert!(names.contains(&"elastic_links") && names.contains(&"balance"));
        assert_eq!(names.len(), 13 + 9);
    }
}
