//! The Love–Weber stress and the solid fraction against hand-made lattices whose contact
//! forces are known: every contact with the same overlap δ carries F = kn·δ, and every
//! sphere is in equilibrium from the first step.

use flexdem_contact::Material;
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{
    deviator_stress, love_weber_stress, mean_stress, solid_fraction, wall_normal_stress, Region,
    Settings, Simulation,
};
use nalgebra::Matrix3;
use std::f64::consts::PI;

const R: Real = 0.01;
const DELTA: Real = 1e-5;

/// A lattice of `n³` spheres of radius `R`, `spacing[k]` apart along axis `k`, lowest centre
/// at the origin, with a pair of walls on each axis in `walled` placed at overlap `DELTA`
/// with the outer spheres (walls 2k and 2k + 1 for the k-th walled axis: the low side, then
/// the high side). Returns the simulation after one step (the forces of the initial
/// configuration) and the material's contact stiffness.
fn lattice(n: usize, spacing: Vec3, walled: &[usize]) -> (Simulation, Real) {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e8, 0.3, 2600.0, 0.5).unwrap()).unwrap();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let c = Vec3::new(i as Real, j as Real, k as Real).component_mul(&spacing);
                model.add_sphere(c, R, m).unwrap();
            }
        }
    }
    for &k in walled {
        let axis = Vec3::ith(k, 1.0);
        let far = spacing[k] * (n - 1) as Real;
        model.add_wall(-axis * (R - DELTA), axis, m).unwrap();
        model.add_wall(axis * (far + R - DELTA), -axis, m).unwrap();
    }
    let mut sim = Simulation::new(model, Settings::default()).unwrap();
    sim.step().unwrap();
    (sim, 1e8 * R)
}

/// The relative difference of two tensors, in the largest norm of the expected one.
fn relative(a: &Matrix3<Real>, expected: &Matrix3<Real>) -> Real {
    (a - expected).abs().max() / expected.abs().max()
}

/// A simple cubic lattice squeezed equally by six walls: each sphere carries F = kn·δ on
/// each face, σ = F/s²·I exactly over the lattice's Voronoi box (side n·s), equal to the
/// stress each wall receives over its face of the box.
#[test]
fn a_lattice_squeezed_by_six_walls_is_hydrostatic() {
    let (n, s) = (3, 2.0 * R - DELTA);
    let (sim, kn) = lattice(n, Vec3::repeat(s), &[0, 1, 2]);
    let f = kn * DELTA;
    let expected = f / (s * s);
    let lo = Vec3::repeat(-s / 2.0);
    let region = Region::Box { min: lo, max: lo + Vec3::repeat(n as Real * s) };
    let sigma = love_weber_stress(sim.model(), &sim.contacts(), &region, None);
    let error = relative(&sigma, &(Matrix3::identity() * expected));
    eprintln!("hydrostatic: σ = {:?}, expected {expected:.9e} Pa, error {error:.1e}", sigma);
    assert!(error < 1e-12, "{sigma:?} vs {expected}");
    assert!((mean_stress(&sigma) / expected - 1.0).abs() < 1e-12);
    assert!(deviator_stress(&sigma) < 1e-12 * expected);
    let face = (n as Real * s).powi(2);
    for (w, wall) in sim.model().walls.iter().enumerate() {
        let stress = wall_normal_stress(wall, &sim.wall_forces()[w], face);
        assert!((stress / expected - 1.0).abs() < 1e-12, "wall {w}: {stress} vs {expected}");
    }
    // the spheres were in equilibrium: nothing moved
    assert!(sim.model().particles.vel.iter().all(|v| v.norm() < 1e-12));
}

/// Columns of spheres `L > 2R` apart pressed between two walls along z: uniaxial stress
/// σzz = F/L² = the walls' stress, the other components zero, p = σzz/3, q = σzz. The
/// volume given instead of the region's scales σ as it should.
#[test]
fn columns_pressed_between_two_walls_carry_a_uniaxial_stress() {
    let (n, s, l) = (3, 2.0 * R - DELTA, 2.5 * R);
    let (sim, kn) = lattice(n, Vec3::new(l, l, s), &[2]);
    let expected = kn * DELTA / (l * l);
    let lo = Vec3::new(-l / 2.0, -l / 2.0, -s / 2.0);
    let size = Vec3::new(n as Real * l, n as Real * l, n as Real * s);
    let region = Region::Box { min: lo, max: lo + size };
    let sigma = love_weber_stress(sim.model(), &sim.contacts(), &region, None);
    let uniaxial = Matrix3::from_diagonal(&Vec3::new(0.0, 0.0, expected));
    let error = relative(&sigma, &uniaxial);
    eprintln!(
        "uniaxial: σzz = {:.9e} Pa, expected {expected:.9e} Pa, error {error:.1e}",
        sigma[(2, 2)]
    );
    assert!(error < 1e-12, "{sigma:?} vs {expected}");
    assert!((mean_stress(&sigma) * 3.0 / expected - 1.0).abs() < 1e-12);
    assert!((deviator_stress(&sigma) / expected - 1.0).abs() < 1e-12);
    let face = size.x * size.y;
    for (w, wall) in sim.model().walls.iter().enumerate() {
        let stress = wall_normal_stress(wall, &sim.wall_forces()[w], face);
        assert!((stress / expected - 1.0).abs() < 1e-12, "wall {w}: {stress} vs {expected}");
    }
    let doubled =
        love_weber_stress(sim.model(), &sim.contacts(), &region, Some(2.0 * region.volume()));
    assert!(relative(&(doubled * 2.0), &sigma) < 1e-15);
    // a region holding only the middle layer: one sphere per column, each with its two
    // contacts, over a third of the volume: the same stress
    let middle = Region::Box {
        min: lo + Vec3::new(0.0, 0.0, s),
        max: lo + Vec3::new(size.x, size.y, 2.0 * s),
    };
    let sigma = love_weber_stress(sim.model(), &sim.contacts(), &middle, None);
    assert!(relative(&sigma, &uniaxial) < 1e-12, "{sigma:?}");
}

/// Solid fraction by centre counting: a simple cubic lattice of touching spheres fills
/// π/6 of its Voronoi box, exactly; a cylinder around one column holds its spheres.
#[test]
fn the_solid_fraction_of_a_simple_cubic_lattice_is_pi_over_six() {
    let (sim, _) = lattice(4, Vec3::repeat(2.0 * R), &[]);
    let lo = Vec3::repeat(-R);
    let region = Region::Box { min: lo, max: lo + Vec3::repeat(8.0 * R) };
    let phi = solid_fraction(&sim.model().particles, &region);
    assert!((phi / (PI / 6.0) - 1.0).abs() < 1e-12, "{phi}");
    // a cylinder of radius R about the column at x = y = 0, from z = −R over 4 spheres: 4
    // spheres of volume 4/3·πR³ in π·R²·8R
    let column = Region::Cylinder {
        start: Vec3::new(0.0, 0.0, -R),
        axis: Vec3::z(),
        radius: R,
        length: 8.0 * R,
    };
    let phi = solid_fraction(&sim.model().particles, &column);
    assert!((phi - 2.0 / 3.0).abs() < 1e-12, "{phi}");
}
