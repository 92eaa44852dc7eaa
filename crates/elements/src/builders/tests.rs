//! Tests across builders: several structures in one model, and properties of random ones.

use super::test_support::*;
use super::*;
use crate::{MassLumping, Model};
use flexdem_geom::{Real, Vec3};
use proptest::prelude::*;
use std::f64::consts::PI;

/// Σ πr²Lρ over the connections of the model.
fn connection_mass(model: &Model) -> Real {
    model
        .connections
        .iter()
        .map(|c| {
            PI * c.radius * c.radius * c.rest_length * model.materials[c.material as usize].density
        })
        .sum()
}

#[test]
fn structures_compose_in_one_model() {
    let (mut model, steel) = model_with_material(7850.0);
    let rubber = model
        .add_material(flexdem_contact::Material::new(1e6, 0.45, 1100.0, 0.6).unwrap())
        .unwrap();
    model.add_sphere(Vec3::new(0.0, 0.0, 2.0), 0.1, steel).unwrap();
    let opts = StructureOptions::new("cable", 0.005, steel).with_mask(2);
    let pts = helix(Vec3::zeros(), 0.2, 0.05, 3.0, 16).unwrap();
    let c = chain(&mut model, &pts, &opts).unwrap();
    let t = paper_tube()
        .build(&mut model, &StructureOptions::new("tube", PAPER_NODE_RADIUS, rubber))
        .unwrap();
    let h = paper_hollow_sphere()
        .build(&mut model, &StructureOptions::new("ball", PAPER_NODE_RADIUS, rubber))
        .unwrap();
    model.add_sphere(Vec3::new(0.0, 0.0, 3.0), 0.1, steel).unwrap();
    assert_eq!((c, t, h), (0, 1, 2));
    assert_eq!(model.structures[1].name, "tube");
    assert_eq!(model.structures[1].nodes.start, model.structures[0].nodes.end);
    for n in model.structures[0].nodes.clone() {
        assert_eq!(model.particles.mask[n as usize], 2);
        assert_eq!(model.particles.structure[n as usize], 0);
    }
    let ball = &model.structures[2].connections;
    assert!(model.connections[ball.start as usize..ball.end as usize]
        .iter()
        .all(|k| k.material == rubber && k.mask == 1 && k.structure == 2));
    assert_rel(model.total_mass() - 2.0 * model.particles.mass[0], connection_mass(&model), 1e-12);
    check_adjacency(&model);
}

fn options(mass: MassLumping) -> impl Strategy<Value = (Real, MassLumping)> {
    (0.001..0.05, Just(mass))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Any net: valid, counts as documented, mass Σ πr²Lρ, adjacency matches a naive count.
    #[test]
    fn random_nets_are_valid(
        n_u in 1usize..6, n_v in 1usize..6, diagonals: bool,
        size_u in 0.1..3.0, size_v in 0.1..3.0,
        (r, mass) in options(MassLumping::Connections),
        angle in 0.3..2.8f64,
    ) {
        let (mut model, mat) = model_with_material(1234.0);
        let opts = StructureOptions::new("n", r, mat).with_mass(mass);
        let v_dir = Vec3::new(angle.cos(), angle.sin(), 0.0);
        let s = net(&mut model, Vec3::new(1.0, 2.0, 3.0), Vec3::x(), v_dir, size_u, size_v,
            n_u, n_v, diagonals, &opts).unwrap();
        let st = model.structure(s).unwrap();
        prop_assert_eq!(st.nodes.len(), (n_u + 1) * (n_v + 1));
        let diag = if diagonals { n_u * n_v } else { 0 };
        prop_assert_eq!(st.connections.len(), n_u * (n_v + 1) + n_v * (n_u + 1) + diag);
        assert_rel(model.total_mass(), connection_mass(&model), 1e-12);
        check_adjacency(&model);
    }

    /// Any membrane rectangle or disc, with either lumping: valid, one open surface
    /// (V − E + F = 1), boundary edges in one PFacet and the others in two, and the mass of
    /// the connections plus, with `Plate`, the plate (area · 2r · ρ).
    #[test]
    fn random_membranes_are_valid(
        n_u in 1usize..6, n_v in 1usize..6, rings in 1usize..5, plate: bool,
        r in 0.001..0.05f64,
    ) {
        let mass = if plate { MassLumping::Plate } else { MassLumping::Connections };
        let (mut model, mat) = model_with_material(900.0);
        let opts = StructureOptions::new("m", r, mat).with_mass(mass);
        let a = membrane_rectangle(&mut model, Vec3::zeros(), Vec3::x(), Vec3::z(), 2.0, 1.0,
            n_u, n_v, &opts).unwrap();
        let b = membrane_disc(&mut model, Vec3::x(), Vec3::y(), 0.7, rings, &opts).unwrap();
        let mut area = 0.0;
        for s in [a, b] {
            prop_assert_eq!(euler_characteristic(&model, s), 1);
            prop_assert!(faces_per_connection(&model, s).iter().all(|&k| k == 1 || k == 2));
            for f in model.structure(s).unwrap().pfacets.clone() {
                area += 0.5 * pfacet_normal_centroid(&model, f as usize).0.norm();
            }
        }
        let plate_mass = if plate { area * 2.0 * r * 900.0 } else { 0.0 };
        assert_rel(model.total_mass(), connection_mass(&model) + plate_mass, 1e-12);
        check_adjacency(&model);
    }

    /// Any tube: open (V − E + F = 0), every connection in 1 or 2 PFacets.
    #[test]
    fn random_tubes_are_valid(n_around in 3usize..12, n_along in 1usize..8) {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("t", 0.01, mat);
        let s = tube(&mut model, Vec3::zeros(), Vec3::new(1.0, 2.0, 3.0), 0.5, 2.0, n_around,
            n_along, &opts).unwrap();
        prop_assert_eq!(model.structure(s).unwrap().pfacets.len(), 2 * n_around * n_along);
        prop_assert_eq!(euler_characteristic(&model, s), 0);
        prop_assert!(faces_per_connection(&model, s).iter().all(|&k| k == 1 || k == 2));
        check_adjacency(&model);
    }
}
