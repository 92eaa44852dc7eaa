//! Results do not depend on the number of threads when a particle's loads come from both
//! contact lists: spheres resting on a PFacet membrane (general contacts) and on each other
//! (the free spheres' neighbour list). With more than one thread, each particle's loads are
//! summed in parallel, merged from the two lists by key (`gather.rs`); with one, in a single
//! pass in key order. The two must add the same loads in the same order.

use flexdem_bench::scenes::{membrane, MEMBRANE_CELL};
use flexdem_elements::virtual_sphere::Feature;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::Simulation;

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
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
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
