//! Every example scene parses, builds a valid `Simulation`, and holds what its comments say.

use flexdem_elements::{Dofs, ParticleKind};
use flexdem_integrate::{Simulation, TimeStep};
use flexdem_output::Quantity;
use flexdem_scene::{load_scene, RunLength, Scene};
use std::path::PathBuf;

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)
}

/// Loads an example and builds a simulation with its loads.
fn load_and_simulate(name: &str) -> Scene {
    let scene = load_scene(&example(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut sim = Simulation::new(scene.model.clone(), scene.settings.clone())
        .unwrap_or_else(|e| panic!("{name}: Simulation::new: {e}"));
    for load in &scene.loads {
        sim.add_load(load.clone()).unwrap_or_else(|e| panic!("{name}: add_load: {e}"));
    }
    for pressure in &scene.pressures {
        sim.add_pressure(pressure.clone()).unwrap_or_else(|e| panic!("{name}: add_pressure: {e}"));
    }
    assert!(sim.dt() > 0.0, "{name}: dt = {}", sim.dt());
    scene
}

#[test]
fn every_example_builds_a_simulation() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    for required in [
        "cantilever.toml",
        "membrane_spheres.toml",
        "net_drop.toml",
        "tube_impact_hollow.toml",
        "tube_impact_solid.toml",
    ] {
        assert!(names.iter().any(|n| n == required), "missing example {required}");
    }
    for name in &names {
        let scene = load_and_simulate(name);
        assert!(scene
            .output
            .directory
            .ends_with(format!("output/{}", name.trim_end_matches(".toml"))));
    }
}

#[test]
fn tube_impact_solid_matches_the_paper() {
    let s = load_and_simulate("tube_impact_solid.toml");
    let m = &s.model;
    assert_eq!(m.structures.len(), 1);
    assert_eq!(m.pfacets.len(), 640);
    assert_eq!(m.structures[0].nodes.len(), 336);
    assert!(m.particles.radius[..336].iter().all(|&r| r == 0.002));
    assert_eq!(m.materials.iter().map(|x| x.young).collect::<Vec<_>>(), vec![100e6, 1e6]);
    let sphere = 336;
    assert_eq!(m.particles.kind[sphere], ParticleKind::Sphere);
    assert_eq!(m.particles.radius[sphere], 0.1);
    assert_eq!(m.particles.vel[sphere].z, -2.0);
    assert_eq!(s.settings.gravity.norm(), 0.0);
    assert!(matches!(s.settings.time_step, TimeStep::Auto { safety } if safety == 0.3));
    assert_eq!(s.run, RunLength::Duration(1.0));
    // both end rings (2 × 16 nodes) clamped, nothing else
    let clamped = m.particles.blocked.iter().filter(|&&b| b == Dofs::ALL).count();
    assert_eq!(clamped, 32);
    // the sphere does not touch the tube at the start
    let top = (0..336).map(|i| m.particles.pos[i].z).fold(f64::MIN, f64::max);
    assert!(m.particles.pos[sphere].z - 0.1 > top + 0.002);
    assert!(s.output.series.iter().any(|x| x.quantity == Quantity::Position(sphere as u32)));
}

#[test]
fn tube_impact_hollow_has_a_128_pfacet_shell() {
    let s = load_and_simulate("tube_impact_hollow.toml");
    let m = &s.model;
    assert_eq!(m.structures.len(), 2);
    let shell = &m.structures[1];
    assert_eq!(shell.pfacets.len(), 128);
    assert_eq!(shell.nodes.len(), 66);
    for n in shell.nodes.clone() {
        assert_eq!(m.particles.vel[n as usize].z, -2.0);
    }
    let lowest = shell
        .nodes
        .clone()
        .min_by(|&a, &b| m.particles.pos[a as usize].z.total_cmp(&m.particles.pos[b as usize].z))
        .unwrap();
    assert!(s.output.series.iter().any(|x| x.quantity == Quantity::Position(lowest)));
}

#[test]
fn cantilever_is_validation_case_2() {
    let s = load_and_simulate("cantilever.toml");
    let m = &s.model;
    assert_eq!(m.particles.len(), 11);
    assert_eq!(m.connections.len(), 10);
    assert_eq!(m.particles.blocked[0], Dofs::ALL);
    assert!(m.particles.blocked[1..].iter().all(|b| b.is_empty()));
    assert_eq!(s.loads.len(), 1);
    assert_eq!(s.loads[0].particles, vec![10]);
    assert_eq!(s.loads[0].force.z, -0.01);
    assert_eq!(s.settings.damping, 0.3);
    assert!((m.particles.pos[10].x - 1.0).abs() < 1e-15);
}

#[test]
fn net_drop_and_membrane_spheres() {
    let s = load_and_simulate("net_drop.toml");
    assert_eq!(s.model.structures[0].nodes.len(), 21 * 21);
    let pinned = s.model.particles.blocked.iter().filter(|&&b| b == Dofs::TRANSLATION).count();
    assert_eq!(pinned, 4);
    assert_eq!(s.model.walls.len(), 1);
    assert_eq!(s.settings.gravity.z, -9.81);

    let s = load_and_simulate("membrane_spheres.toml");
    assert_eq!(s.model.pfacets.len(), 2 * 16 * 16);
    let spheres = s.model.particles.kind.iter().filter(|&&k| k == ParticleKind::Sphere).count();
    assert_eq!(spheres, 300);
    let pinned = s.model.particles.blocked.iter().filter(|&&b| b == Dofs::TRANSLATION).count();
    assert_eq!(pinned, 4 * 16);
}
