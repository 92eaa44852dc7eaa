//! Tests of `links.rs`.

use super::*;
use crate::homes::Homes;
use flexdem_contact::Material;
use flexdem_elements::builders::{chain, straight_line};
use flexdem_elements::StructureOptions;

fn chain_model() -> Model {
    let mut model = Model::new();
    let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let points = straight_line(Vec3::zeros(), Vec3::x(), 4).unwrap();
    chain(&mut model, &points, &StructureOptions::new("c", 0.01, mat)).unwrap();
    model
}

/// The sizes the layout's documentation states (a field added to the hot path shows here).
#[test]
fn a_link_holds_the_bytes_documented() {
    use std::mem::size_of;
    // nodes, class, spring, state, loads
    let per_link = size_of::<[u32; 2]>()
        + 2 * size_of::<u32>()
        + size_of::<LinkState>()
        + size_of::<LinkLoad>();
    assert_eq!(
        (size_of::<LinkSpring>(), size_of::<LinkState>(), size_of::<LinkLoad>(), per_link),
        (40, 88, 72, 176)
    );
}

/// The normal force and the elastic energy made from a link's load and state are the
/// update's: a chain with its last node pulled, bent and turned, in both kinematics.
#[test]
fn normal_force_and_energy_are_made_from_the_load() {
    for mode in [LinkKinematicsMode::Beam, LinkKinematicsMode::Yade] {
        let mut model = chain_model();
        let mut links = Links::from_model(&model, mode);
        assert_eq!((links.normal_force(0), links.elastic_energy(0, &model.particles)), (0.0, 0.0));
        let p = &mut model.particles;
        let last = p.len() - 1;
        p.pos[last] += Vec3::new(1e-3, 2e-3, -1e-3);
        p.ori[last] = nalgebra::UnitQuaternion::from_scaled_axis(Vec3::new(0.01, 0.02, 0.03));
        p.vel[last] = Vec3::new(0.1, 0.0, 0.0);
        let update = links.update(p, 1e-5);
        let k = links.len() - 1;
        // the last link alone is strained: its force from the update's own terms
        let l = (p.pos[last] - p.pos[last - 1]).norm();
        let spring = *links.spring_of(k);
        let expected = spring.stiffness.kn * (spring.rest_length - l);
        let fn_ = links.normal_force(k);
        assert!((fn_ - expected).abs() <= 1e-12 * expected.abs(), "{fn_} vs {expected}");
        assert!(fn_ < 0.0, "pulled: tension");
        let total: Real = (0..links.len()).map(|k| links.elastic_energy(k, p)).sum();
        assert!(update.elastic_energy > 0.0);
        assert!(
            (total - update.elastic_energy).abs() <= 1e-12 * update.elastic_energy,
            "{mode:?}: {total} vs the update's {}",
            update.elastic_energy
        );
    }
}

/// Links with the same stiffnesses and rest length share one spring: a chain of equal
/// segments has one, and each link still reads its own constants.
#[test]
fn equal_links_share_a_spring() {
    let model = chain_model();
    let links = Links::from_model(&model, LinkKinematicsMode::Beam);
    let material = &model.materials[0];
    for (k, c) in model.connections.iter().enumerate() {
        let own = LinkSpring::from_material(material, c.radius, c.rest_length);
        assert_eq!(*links.spring_of(k), own);
    }
    let distinct: std::collections::HashSet<u64> =
        model.connections.iter().map(|c| c.rest_length.to_bits()).collect();
    assert_eq!(links.springs.len(), distinct.len());
    assert!(links.springs.len() < links.len());
}

/// A plastic material's links keep a plastic state, and a link pulled past its tensile
/// limit keeps its plastic elongation there; a fragile material's links keep none.
#[test]
fn plastic_links_keep_their_plastic_state() {
    assert!(Links::from_model(&chain_model(), LinkKinematicsMode::Beam).plastic.is_empty());
    let mut model = Model::new();
    let plastic = Material::new(1e7, 0.3, 1000.0, 0.5)
        .unwrap()
        .with_tensile_strength(Some(1e3))
        .with_failure(FailureMode::Plastic);
    let mat = model.add_material(plastic).unwrap();
    let points = straight_line(Vec3::zeros(), Vec3::x(), 4).unwrap();
    chain(&mut model, &points, &StructureOptions::new("c", 0.01, mat)).unwrap();
    let mut links = Links::from_model(&model, LinkKinematicsMode::Beam);
    assert_eq!(links.plastic.len(), links.len());
    assert!(links.check_against(&model));
    let last = model.particles.len() - 1;
    model.particles.pos[last].x += 0.01;
    links.update(&model.particles, 1e-5);
    let elongation = links.plastic[links.len() - 1].elongation;
    assert!(elongation > 0.0 && links.plastic[0].elongation == 0.0, "{elongation}");
    let mut lost = links.clone();
    lost.plastic.clear();
    assert!(!lost.check_against(&model));
}

#[test]
fn links_of_the_model_fit_it() {
    let model = chain_model();
    let links = Links::from_model(&model, LinkKinematicsMode::Beam);
    assert!(links.check_against(&model));
}

/// A checkpoint whose links were altered (with a recomputed checksum) used to panic with
/// an index out of bounds in `add_loads`: each alteration is caught.
#[test]
fn altered_links_do_not_fit() {
    let model = chain_model();
    let good = Links::from_model(&model, LinkKinematicsMode::Beam);
    let alterations: [fn(&mut Links); 11] = [
        |l| l.node_loads[3] = 1000,
        |l| l.node_loads.swap(0, 1),
        |l| l.node_offsets[2] = 99,
        |l| l.node_offsets.truncate(3),
        |l| l.nodes[1] = [0, 4],
        |l| l.nodes[0] = [0, 77],
        |l| l.state.truncate(2),
        |l| l.class[2] = 1,
        |l| l.spring.truncate(1),
        |l| l.spring[0] = 7,
        |l| l.plastic.push(LinkPlastic::default()),
    ];
    for (k, alter) in alterations.iter().enumerate() {
        let mut links = good.clone();
        alter(&mut links);
        assert!(!links.check_against(&model), "alteration {k} not caught");
    }
    let mut other = chain_model();
    other.connections.pop();
    assert!(!good.check_against(&other));
}

/// The node index stops at the last node: free spheres after it take no room, and a
/// checkpoint's index with a row for every particle (as written before) still fits.
#[test]
fn the_node_index_stops_at_the_last_node() {
    let mut model = chain_model();
    let nodes = model.particles.len();
    let mat = model.particles.material[0];
    for k in 0..3 {
        model.add_sphere(Vec3::new(5.0, k as Real, 0.0), 0.1, mat).unwrap();
    }
    let links = Links::from_model(&model, LinkKinematicsMode::Beam);
    assert_eq!(links.node_offsets.len(), nodes + 1);
    let mut force = vec![Vec3::zeros(); model.particles.len()];
    let mut torque = force.clone();
    // (forces longer than the index: the free spheres get nothing, and no panic)
    links.add_loads(&mut force, &mut torque);
    let total = *links.node_offsets.last().unwrap();
    let mut old = links.clone();
    old.node_offsets.resize(model.particles.len() + 1, total);
    assert!(links.check_against(&model) && old.check_against(&model));
    let mut too_long = old.clone();
    too_long.node_offsets.push(total);
    let mut not_empty = old.clone();
    *not_empty.node_offsets.last_mut().unwrap() = total + 1;
    assert!(!too_long.check_against(&model) && !not_empty.check_against(&model));
    let mut free = Model::new();
    let mat = free.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    free.add_sphere(Vec3::zeros(), 0.1, mat).unwrap();
    let none = Links::from_model(&free, LinkKinematicsMode::Beam);
    assert!(none.node_offsets.is_empty() && none.check_against(&free));
    let mut old_none = none.clone();
    old_none.node_offsets = vec![0, 0];
    assert!(old_none.check_against(&free));
}

/// A net's loads summed link after link (the path of a structure of one chunk) have the
/// bits of the per-node sum, onto forces and torques already holding other loads.
#[test]
fn loads_summed_link_after_link_are_the_per_node_sums() {
    use flexdem_elements::builders::net;
    let mut model = Model::new();
    let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let opts = StructureOptions::new("net", 0.01, mat);
    let (x, y) = (Vec3::x(), Vec3::y());
    net(&mut model, Vec3::zeros(), x, y, 1.0, 1.0, 6, 5, true, &opts).unwrap();
    model.add_sphere(Vec3::new(0.5, 0.5, 1.0), 0.1, mat).unwrap();
    let mut links = Links::from_model(&model, LinkKinematicsMode::Beam);
    let mut state = 0x9e3779b97f4a7c15u64;
    let mut r = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as Real / (1u64 << 53) as Real - 0.5
    };
    let mut v = || Vec3::new(r(), r(), r());
    for l in &mut links.loads {
        *l = LinkLoad { force_on_2: v() * 1e3, lever_torque: v(), moment_on_2: v() * 0.1 };
    }
    let n = model.particles.len();
    let force: Vec<Vec3> = (0..n).map(|_| v() * 10.0).collect();
    let torque: Vec<Vec3> = (0..n).map(|_| v()).collect();
    let (mut f1, mut t1, mut f2, mut t2) = (force.clone(), torque.clone(), force, torque);
    assert!(links.len() <= CHUNK);
    let (mut f3, mut t3) = (f2.clone(), t2.clone());
    links.add_loads(&mut f1, &mut t1);
    links.add_loads_per_node(&mut f2, &mut t2, &Homes::default());
    // by the step's homes, the structure's nodes and the free sphere in blocks cut by thread
    let mut homes = Homes::default();
    homes.set_by_blocks(&crate::homes::particle_blocks(&model.particles), 3);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
    pool.install(|| links.add_loads_per_node(&mut f3, &mut t3, &homes));
    let bits =
        |x: &[Vec3]| x.iter().flat_map(|v| v.iter().map(|c| c.to_bits())).collect::<Vec<_>>();
    assert_eq!(bits(&f1), bits(&f2));
    assert_eq!(bits(&t1), bits(&t2));
    assert_eq!((bits(&f1), bits(&t1)), (bits(&f3), bits(&t3)));
    // (the free sphere after the nodes took nothing)
    assert!(f1[n - 1] == f2[n - 1]);
}

/// Updated by the homes of their chunks' first nodes (a chain of many chunks of links, free
/// spheres after it, blocks cut by 2 or 3 threads), the links get the bits, the loads and
/// the sums of one update on one thread.
#[test]
fn links_updated_by_homes_get_the_same_bits() {
    let mut model = Model::new();
    let mat = model.add_material(Material::new(1e7, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let points = straight_line(Vec3::zeros(), Vec3::x() * 40.0, 4 * CHUNK + 77).unwrap();
    chain(&mut model, &points, &StructureOptions::new("c", 0.004, mat)).unwrap();
    for k in 0..2000 {
        model.add_sphere(Vec3::new(k as Real, 5.0, 0.0), 0.1, mat).unwrap();
    }
    let n = model.particles.len();
    let p = &mut model.particles;
    for i in 0..n {
        let s = (i as Real * 0.618).fract();
        p.pos[i] += Vec3::new(0.0, 1e-4 * s, -2e-4 * s * s);
        p.vel[i] = Vec3::new(0.01 * s, -0.02, 0.03 * (1.0 - s));
        p.ang_vel[i] = Vec3::new(s, 0.2, -s);
    }
    let fresh = Links::from_model(&model, LinkKinematicsMode::Beam);
    let run = |threads: usize, homes: &Homes| {
        let mut links = fresh.clone();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let sums = pool.install(|| {
            (0..3).map(|_| links.update_in_homes(&model.particles, 1e-5, homes)).last()
        });
        let loads: Vec<u64> = links
            .loads
            .iter()
            .flat_map(|l| l.force_on_2.iter().chain(&l.lever_torque).chain(&l.moment_on_2))
            .map(|c| c.to_bits())
            .collect();
        (format!("{sums:?} {:?}", links.state), loads)
    };
    let one = run(1, &Homes::default());
    let blocks = crate::homes::particle_blocks(&model.particles);
    assert_eq!(blocks, [0, 4 * CHUNK + 78, n]);
    for threads in [2, 3] {
        let mut homes = Homes::default();
        homes.set_by_blocks(&blocks, threads);
        assert!(one == run(threads, &homes), "{threads} threads");
    }
}
