//! Results do not depend on the number of threads when a particle's loads come from both
//! contact lists: spheres resting on a PFacet membrane (general contacts) and on each other
//! (the free spheres' neighbour list). With more than one thread, each particle's loads are
//! summed in parallel, merged from the two lists by key (`gather.rs`), or, where the pairs
//! are many, in the parts the pairs are stepped in and from the lists of loads the parts
//! keep (`pair_parts.rs`, `part_step.rs`); with one, in a single pass in key order. They
//! must add the same loads in the same order.

use flexdem_bench::scenes::{
    membrane, packing, packing_columns, MEMBRANE_CELL, PACKING_LAYERS, PACKING_RADIUS,
};
use flexdem_contact::Material;
use flexdem_elements::builders::{net, GridLayout};
use flexdem_elements::virtual_sphere::Feature;
use flexdem_elements::{Dofs, ParticleKind, StructureOptions};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::Simulation;

/// `f`'s result in a pool of `threads` threads.
fn with_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(f)
}

/// The bench's membrane (about 2000 PFacets, one layer of spheres of one cell's diameter, 2
/// cells apart) with two more spheres beside each, 0.99 of a cell from it along x and y: each
/// pair overlaps, and all rest on the membrane, so that a sphere gets three or more loads
/// from the two lists (with two, any order gives the same sum).
fn scene() -> Simulation {
    let (mut model, settings) = membrane(2000).unwrap();
    let spheres: Vec<(Vec3, Real, u32)> = (0..model.particles.len())
        .filter(|&i| model.particles.radius[i] > 0.25 * MEMBRANE_CELL)
        .map(|i| (model.particles.pos[i], model.particles.radius[i], model.particles.material[i]))
        .collect();
    for (c, r, m) in spheres {
        for side in [Vec3::x(), Vec3::y()] {
            model.add_sphere(c + side * (0.99 * MEMBRANE_CELL), r, m).unwrap();
        }
    }
    Simulation::new(model, settings).unwrap()
}

/// Whether a sphere has contacts with two other spheres and one with the membrane: the case
/// the test is about.
fn has_a_sphere_in_both_lists(sim: &Simulation) -> bool {
    let contacts = sim.contacts();
    // (a membrane node is a particle too: the spheres are the large ones)
    let radius = &sim.model().particles.radius;
    let sphere = |i: u32| radius[i as usize] > 0.25 * MEMBRANE_CELL;
    let with_membrane = |i: u32| {
        contacts.iter().any(|c| match c.key() {
            (Feature::Particle(a), b) => a == i && !matches!(b, Feature::Particle(_)),
            (a, Feature::Particle(b)) => b == i && !matches!(a, Feature::Particle(_)),
            _ => false,
        })
    };
    let sphere_contacts = |i: u32| {
        contacts
            .iter()
            .filter(|c| match c.key() {
                (Feature::Particle(a), Feature::Particle(b)) => {
                    sphere(a) && sphere(b) && (a == i || b == i)
                }
                _ => false,
            })
            .count()
    };
    (0..radius.len() as u32).any(|i| sphere(i) && with_membrane(i) && sphere_contacts(i) >= 2)
}

#[test]
fn mixed_contact_lists_give_the_same_results_with_one_and_two_threads() {
    let run = |threads: usize| {
        with_threads(threads, || {
            let mut sim = scene();
            let mut mixed_steps = 0;
            for _ in 0..30 {
                sim.run(10).unwrap();
                mixed_steps += usize::from(has_a_sphere_in_both_lists(&sim));
            }
            let p = &sim.model().particles;
            (mixed_steps, p.pos.clone(), p.vel.clone(), p.ang_vel.clone())
        })
    };
    let one = run(1);
    let two = run(2);
    assert!(one.0 > 0, "no sphere touched both another sphere and the membrane");
    assert!(one.1 == two.1, "positions differ between 1 and 2 threads");
    assert!(one.2 == two.2, "velocities differ between 1 and 2 threads");
    assert!(one.3 == two.3, "angular velocities differ between 1 and 2 threads");
}

/// The bench's packing of about 12 000 spheres (35 × 35 columns of 10 in a box of five
/// walls: about 37 000 candidate pairs, 19 chunks) with a steel net pinned at its corners
/// lying on the top layer: sphere pairs, walls' pairs and the net's general contacts with
/// the top spheres, so that with more than one thread the pairs are stepped in parts and
/// some spheres' loads are summed in their part, some after it from the parts' lists (walls'
/// loads, spheres on the parts' borders) and some by the gather (the net's). The net's wires
/// are `clearance` above the top spheres (negative: into them).
fn packing_under_a_net(clearance: Real) -> Simulation {
    let (mut model, settings) = packing(12_000).unwrap();
    let side = packing_columns(12_000) as Real * 2.1 * PACKING_RADIUS;
    let steel = model.add_material(Material::new(2e9, 0.3, 7850.0, 0.5).unwrap()).unwrap();
    let opts = StructureOptions::new("net", 0.002, steel);
    let top = 2.0 * PACKING_RADIUS * PACKING_LAYERS as Real + 0.002 + clearance;
    let corner = Vec3::new(0.1 * side, 0.1 * side, top);
    let (x, y, size) = (Vec3::x(), Vec3::y(), 0.8 * side);
    let s = net(&mut model, corner, x, y, size, size, 8, 8, false, &opts).unwrap();
    let grid = GridLayout::of(&model, s, 8, 8).unwrap();
    model.block(grid.corners(), Dofs::ALL).unwrap();
    Simulation::new(model, settings).unwrap()
}

/// Spheres in a box under a net: positions, velocities and contact forces bit-identical with
/// 1, 2 and 3 threads (the pairs stepped in one pass, and in 8 and 12 spheres' parts with
/// the walls' parts stepped with them).
#[test]
fn a_packing_under_a_net_does_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        with_threads(threads, || {
            // the net's wires 0.1 mm into the top spheres
            let mut sim = packing_under_a_net(-1e-4);
            sim.run(300).unwrap();
            let p = &sim.model().particles;
            let forces: Vec<Vec3> = sim.contacts().iter().map(|c| c.forces.force_on_2).collect();
            assert!(!forces.is_empty(), "the net touches the spheres");
            (p.pos.clone(), p.vel.clone(), p.ang_vel.clone(), forces)
        })
    };
    let one = run(1);
    for threads in [2, 3] {
        assert!(run(threads) == one, "{threads} threads give other results than one");
    }
}

/// The net's contacts: with one of its wires or nodes (the particles after the spheres,
/// which are the bench's packing of 12 000).
fn net_contacts(sim: &Simulation) -> usize {
    let kind = &sim.model().particles.kind;
    let first_node = kind.iter().position(|k| *k != ParticleKind::Sphere).unwrap_or(kind.len());
    let first_node = first_node as u32;
    let net = |f: Feature| match f {
        Feature::Edge(_) | Feature::Face(_) => true,
        Feature::Particle(i) => i >= first_node,
        Feature::Wall(_) => false,
    };
    sim.contacts().iter().filter(|c| net(c.key().0) || net(c.key().1)).count()
}

/// The net 20 µm above the packing, falling onto it: the first steps have no general
/// contact (with more than one thread the parts' split frees the index of the pairs), the
/// later ones have (the index is made again for the gather). Bit-identical with 1, 2 and 3
/// threads.
#[test]
fn a_net_falling_onto_a_packing_does_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        with_threads(threads, || {
            let mut sim = packing_under_a_net(2e-5);
            sim.run(1).unwrap();
            let before = net_contacts(&sim);
            sim.run(299).unwrap();
            let p = &sim.model().particles;
            let forces: Vec<Vec3> = sim.contacts().iter().map(|c| c.forces.force_on_2).collect();
            (before, net_contacts(&sim), p.pos.clone(), p.vel.clone(), p.ang_vel.clone(), forces)
        })
    };
    let one = run(1);
    assert_eq!(one.0, 0, "the net touches the spheres from the start");
    assert!(one.1 > 0, "the net has not reached the spheres");
    for threads in [2, 3] {
        assert!(run(threads) == one, "{threads} threads give other results than one");
    }
}
