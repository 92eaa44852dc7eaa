use super::*;
use crate::builders::test_support::{assert_rel, model_with_material};
use crate::builders::{chain, net, straight_line, StructureOptions};
use crate::{Dofs, MassLumping};
use flexdem_geom::Aabb;

/// A model with one material, a free sphere (particle 0) and a 3-segment chain along x
/// (nodes 1..5, connections 0..3).
fn small_model() -> (Model, StructureId) {
    let (mut model, mat) = model_with_material(1000.0);
    model.add_sphere(Vec3::new(0.0, 0.0, 1.0), 0.1, mat).unwrap();
    let pts = straight_line(Vec3::zeros(), Vec3::new(3.0, 0.0, 0.0), 3).unwrap();
    let s = chain(&mut model, &pts, &StructureOptions::new("chain", 0.05, mat)).unwrap();
    (model, s)
}

#[track_caller]
fn assert_invalid(model: &Model, needle: &str) {
    let msg = model.validate().unwrap_err().to_string();
    assert!(msg.contains(needle), "expected {needle:?} in: {msg}");
}

#[test]
fn sphere_mass_and_inertia() {
    let (mut model, mat) = model_with_material(2500.0);
    let id = model.add_sphere(Vec3::new(1.0, 2.0, 3.0), 0.2, mat).unwrap();
    let m = 4.0 / 3.0 * PI * 0.008 * 2500.0;
    assert_rel(model.particles.mass[id as usize], m, 1e-14);
    assert_rel(model.particles.inertia[id as usize], 0.4 * m * 0.04, 1e-14);
    assert_eq!(model.particles.structure[0], crate::NO_STRUCTURE);
    assert_eq!(model.particles.kind[0], ParticleKind::Sphere);
    model.validate().unwrap();
    let err = model.add_sphere(Vec3::zeros(), 0.0, mat).unwrap_err();
    assert_eq!(err.to_string(), "particle 1 has radius 0: expected a finite value > 0");
    let err = model.add_sphere(Vec3::new(f64::NAN, 0.0, 0.0), 1.0, mat).unwrap_err();
    assert!(err.to_string().contains("non-finite position"), "{err}");
    let err = model.add_sphere(Vec3::zeros(), 1.0, 3).unwrap_err();
    assert!(err.to_string().contains("uses material 3, but the model has 1 materials"), "{err}");
    assert_eq!(model.particles.len(), 1);
}

#[test]
fn materials_are_validated() {
    let (mut model, _) = model_with_material(1000.0);
    let mut bad = model.materials[0];
    bad.density = -1.0;
    let err = model.add_material(bad).unwrap_err();
    assert!(err.to_string().starts_with("material 1: "), "{err}");
    assert_eq!(model.materials.len(), 1);
    model.materials[0].young = f64::NAN;
    assert_invalid(&model, "material 0");
}

#[test]
fn walls_are_normalized_and_checked() {
    let (mut model, mat) = model_with_material(1000.0);
    let w = model.add_wall(Vec3::zeros(), Vec3::new(0.0, 0.0, 2.0), mat).unwrap();
    assert_eq!(model.walls[w as usize].normal, Vec3::z());
    assert!(model.add_wall(Vec3::zeros(), Vec3::zeros(), mat).is_err());
    model.validate().unwrap();
    model.walls[0].normal = Vec3::new(0.0, 0.0, 2.0);
    assert_invalid(&model, "wall 0 has normal (0, 0, 2)");
    model.walls[0].normal = Vec3::z();
    model.walls[0].velocity.x = f64::INFINITY;
    assert_invalid(&model, "wall 0 has a non-finite velocity");
}

#[test]
fn validate_names_the_bad_element() {
    let (model, _) = small_model();
    model.validate().unwrap();

    let mut m = model.clone();
    m.connections[1].nodes[1] = 99;
    assert_invalid(&m, "connection 1 refers to particle 99, but the model has 5 particles");
    let mut m = model.clone();
    m.connections[2].nodes[0] = 0;
    assert_invalid(&m, "connection 2 refers to particle 0, which is a free sphere");
    let mut m = model.clone();
    m.connections[0].nodes = [1, 1];
    assert_invalid(&m, "connection 0 joins nodes 1 and 1");
    let mut m = model.clone();
    m.particles.pos[2] = m.particles.pos[1];
    assert_invalid(&m, "connection 0 joins nodes 1 and 2 at distance 0");
    let mut m = model.clone();
    m.connections[0].radius = -0.1;
    assert_invalid(&m, "connection 0 has radius -0.1");
    let mut m = model.clone();
    m.connections[0].rest_length = f64::NAN;
    assert_invalid(&m, "connection 0 has rest length NaN");
    let mut m = model.clone();
    m.connections[0].material = 4;
    assert_invalid(&m, "connection 0 uses material 4");
    let mut m = model.clone();
    m.particles.vel[3].y = f64::NAN;
    assert_invalid(&m, "particle 3 has a non-finite velocity");
    let mut m = model.clone();
    m.particles.radius[2] = f64::INFINITY;
    assert_invalid(&m, "particle 2 has radius inf");
    let mut m = model.clone();
    m.particles.mass[4] = 0.0;
    assert_invalid(&m, "particle 4 has mass 0 but its DOFs xyz are free");
    m.particles.blocked[4] = Dofs::TRANSLATION;
    m.validate().unwrap();
    let mut m = model.clone();
    m.particles.inertia[4] = -1.0;
    assert_invalid(&m, "particle 4 has inertia -1");
    let mut m = model.clone();
    m.particles.structure[0] = 0;
    assert_invalid(&m, "particle 0 is inconsistent with structure 0");
    let mut m = model.clone();
    m.structures[0].connections = 0..7;
    assert_invalid(&m, "connections range 0..7 is not within 0..3");
    let mut m = model.clone();
    m.structures[0].connections = 0..2;
    assert_invalid(
        &m,
        "connection 2 is inconsistent with structure 0: it names the structure but lies outside",
    );
    let mut m = model.clone();
    m.connections[1].structure = 5;
    assert_invalid(&m, "connection 1 is inconsistent with structure 0");
    let mut m = model.clone();
    m.particles.mask.pop();
    assert_invalid(&m, "different lengths");
}

#[test]
fn validate_checks_pfacet_connections() {
    let (mut model, mat) = model_with_material(1000.0);
    let s = model.add_structure("hand-made").unwrap();
    let n: Vec<u32> = [Vec3::zeros(), Vec3::x(), Vec3::y()]
        .iter()
        .map(|&p| model.add_node(s, p, 0.01, mat, 1).unwrap())
        .collect();
    let c01 = model.add_connection(s, [n[0], n[1]], 0.01, mat, 1).unwrap();
    let c12 = model.add_connection(s, [n[2], n[1]], 0.01, mat, 1).unwrap();
    let c20 = model.add_connection(s, [n[2], n[0]], 0.01, mat, 1).unwrap();
    let err = model.add_pfacet(s, [n[0], n[1], n[2]], [c12, c01, c20], 0.01, mat, 1).unwrap_err();
    assert_eq!(
        err.to_string(),
        "PFacet 0: edge 0 joins nodes [0, 1] but its connection 1 joins nodes [2, 1] \
         (connections[0] must join nodes 0-1, [1] 1-2, [2] 2-0)"
    );
    let err = model.add_pfacet(s, [n[0], n[1], n[1]], [c01, c12, c20], 0.01, mat, 1).unwrap_err();
    assert!(err.to_string().contains("expected three distinct nodes"), "{err}");
    let f = model.add_pfacet(s, [n[0], n[1], n[2]], [c01, c12, c20], 0.01, mat, 1).unwrap();
    // Masses are lumped only when asked.
    assert_invalid(&model, "has mass 0");
    model.lump_structure_mass(s, MassLumping::Plate).unwrap();
    model.validate().unwrap();
    let lengths = 2.0 + 2.0_f64.sqrt();
    let expected = PI * 1e-4 * lengths * 1000.0 + 0.5 * 0.02 * 1000.0;
    assert_rel(model.total_mass(), expected, 1e-13);
    model.pfacets[f as usize].connections[2] = 9;
    assert_invalid(&model, "PFacet 0 refers to connection 9, but the model has 3 connections");
}

#[test]
fn structures_grow_only_at_the_end() {
    let (mut model, mat) = model_with_material(1000.0);
    let s = model.add_structure("a").unwrap();
    let a = model.add_node(s, Vec3::zeros(), 0.1, mat, 1).unwrap();
    model.add_sphere(Vec3::new(5.0, 0.0, 0.0), 0.1, mat).unwrap();
    let err = model.add_node(s, Vec3::x(), 0.1, mat, 1).unwrap_err();
    assert!(err.to_string().contains("a particle was added after it"), "{err}");
    let t = model.add_structure("b").unwrap();
    let b = model.add_node(t, Vec3::x(), 0.1, mat, 1).unwrap();
    let err = model.add_connection(s, [a, b], 0.1, mat, 1).unwrap_err();
    assert!(err.to_string().contains("a later structure exists"), "{err}");
    // A connection may join nodes of different structures.
    model.add_connection(t, [a, b], 0.1, mat, 1).unwrap();
    let err = model.add_connection(t, [a, 1], 0.1, mat, 1).unwrap_err();
    assert!(err.to_string().contains("free sphere"), "{err}");
    assert_eq!(model.structure_by_name("b"), Some(t));
    assert_eq!(model.structure_by_name("c"), None);
    assert!(model.structure(7).unwrap_err().to_string().contains("structure 7 does not exist"));
}

#[test]
fn selections() {
    let (mut model, mat) = model_with_material(1000.0);
    model.add_sphere(Vec3::new(0.5, 0.5, 0.0), 0.1, mat).unwrap();
    let opts = StructureOptions::new("net", 0.01, mat);
    let s =
        net(&mut model, Vec3::zeros(), Vec3::x(), Vec3::y(), 1.0, 1.0, 2, 2, false, &opts).unwrap();
    assert_eq!(model.structure_nodes(s).unwrap(), (1..10).collect::<Vec<_>>());
    // The box holds the sphere's centre too: only nodes are selected.
    let b = Aabb { mins: Vec3::new(0.4, -0.1, -0.1), maxs: Vec3::new(1.1, 0.6, 0.1) };
    assert_eq!(model.nodes_in_box(&b), vec![2, 3, 5, 6]);
    let on_plane = model.nodes_on_plane(Vec3::new(0.0, 1.0, 0.0), -Vec3::y() * 3.0, 1e-9).unwrap();
    assert_eq!(on_plane, vec![7, 8, 9]);
    assert!(model.nodes_on_plane(Vec3::zeros(), Vec3::zeros(), 1e-9).is_err());
    assert!(model.nodes_on_plane(Vec3::zeros(), Vec3::x(), -1.0).is_err());

    let pts = straight_line(Vec3::new(0.0, 0.0, 2.0), Vec3::new(1.0, 0.0, 2.0), 4).unwrap();
    let c = chain(&mut model, &pts, &StructureOptions::new("c", 0.01, mat)).unwrap();
    let ends = model.structure_ends(c).unwrap();
    assert_eq!(ends, vec![10, 14]);

    model.block([ends[0]], "xyzXYZ".parse().unwrap()).unwrap();
    model.block([ends[1]], Dofs::Z).unwrap();
    model.block([ends[1]], Dofs::RX).unwrap();
    assert_eq!(model.particles.blocked[14], Dofs::Z | Dofs::RX);
    model.unblock([14], Dofs::Z).unwrap();
    assert_eq!(model.particles.blocked[14], Dofs::RX);
    let v = Vec3::new(0.0, 0.0, 0.1);
    model.impose_velocity(ends.iter().copied(), v).unwrap();
    for &e in &ends {
        assert_eq!(model.particles.vel[e as usize], v);
        assert!(model.particles.blocked[e as usize].contains(Dofs::TRANSLATION));
    }
    model.impose_angular_velocity([11], Vec3::x()).unwrap();
    assert_eq!(model.particles.blocked[11], Dofs::ROTATION);
    // All or nothing: an unknown id changes nothing.
    let err = model.block([12, 99], Dofs::ALL).unwrap_err();
    assert_eq!(
        err.to_string(),
        "particle 99 does not exist: the model has 15 particles (ids 0..15)"
    );
    assert_eq!(model.particles.blocked[12], Dofs::NONE);
    assert!(model.impose_velocity([12], Vec3::repeat(f64::NAN)).is_err());
    assert_eq!(model.particles.vel[12], Vec3::zeros());
    model.validate().unwrap();
}
