//! The per-particle stiffness sums of the time-step estimate (`time_step.rs`, model.md §4):
//! every intact link on its two nodes, in link order, then every contact on the nodes of its
//! two sites, in the contacts' key order. Summed in one pass over the links and the
//! contacts (`add_in_order`, one thread), or in parallel per range of particles
//! (`add_in_ranges`: each task the same pass, adding to its own particles only), with the
//! same additions in the same order: the same bits either way. The estimate runs every 10
//! steps while contacts appear; on one thread it was a twentieth of the two-thread step of
//! the 10⁵-sphere packing (issue 14).

use crate::contact_list::Contacts;
use crate::dashpots::FactorMemo;
use crate::fresh_shares::{contact_increments, site_shares, NodeShare, PairShares, SumsRange};
use crate::links::Links;
use crate::neighbours::{merged_fresh, ContactKey, Pick};
use crate::time_step::{spring_increments, StiffnessSums};
use flexdem_contact::{FrictionalParams, LinkSpring, LinkStatus};
use flexdem_elements::virtual_sphere::{Feature, Site};
use flexdem_elements::{Model, Particles};
use flexdem_geom::{Real, Vec3};
use rayon::prelude::*;

/// Below this many particles the sums are taken on one thread (a small scene's estimate
/// costs less than the tasks; fewer in the tests, whose scenes are small).
pub(crate) const MIN_PARALLEL_SUMS: usize = if cfg!(test) { 64 } else { 4096 };

/// Link `l`'s springs as the estimate counts them, unless it is broken: its unit axis
/// (x for coincident nodes), half its length (the shear's lever arm) and its spring.
#[inline]
fn link_spring<'a>(
    links: &'a Links,
    p: &Particles,
    l: usize,
) -> Option<(Vec3, Real, &'a LinkSpring)> {
    if links.state[l].status == LinkStatus::Broken {
        return None;
    }
    let [a, b] = links.nodes[l].map(|n| n as usize);
    let d = p.pos[b] - p.pos[a];
    let len = d.norm();
    let n = if len > 0.0 { d / len } else { Vec3::x() };
    Some((n, 0.5 * len, links.spring_of(l)))
}

/// Adds a contact's stiffness to every node of its two sites that `k` holds
/// ([`contact_increments`]; the others are passed over).
fn add_contact_stiffness(
    k: &mut SumsRange<'_>,
    sites: [&Site; 2],
    params: &FrictionalParams,
    n: &Vec3,
    p: &Particles,
    memo: &mut [FactorMemo; 2],
) {
    for site in sites {
        for &node in &site.nodes[..site.node_count()] {
            let node = node as usize;
            if k.holds(node) {
                k.add(node, contact_increments(p.mass[node], params, n, site.radius, memo));
            }
        }
    }
}

/// Adds the links' and the contacts' stiffness to `k` (zeroed, one entry per particle) in one
/// pass over the links, then over the contacts in key order.
pub(crate) fn add_in_order(
    k: &mut StiffnessSums,
    links: &Links,
    contacts: &Contacts,
    model: &Model,
) {
    add_in_order_to(&mut SumsRange::whole(k), links, contacts, model);
}

/// [`add_in_order`]'s sums, one task per thread over its own range of particles, into `k`
/// (sized here to the particles; what it held before does not count, each task zeroes its
/// range). Each task passes over every link and every contact in [`add_in_order`]'s order
/// and adds those of its nodes: each node gets the same additions in the same order, the
/// same bits as one pass. What a task reads of a link or a contact whose nodes are all
/// another's is its nodes (a free sphere's pair: its key), and it works out only its own
/// nodes' springs. (Summed per particle from an index of its links and contacts, each
/// link's spring was worked out twice, the contacts were read in the order of the
/// particles, and the general contacts' index was built on one thread: on the membrane of
/// 10⁵ PFacets the estimate took 5.4 ms at 2 threads, against 4.0 in one pass.)
pub(crate) fn add_in_ranges(
    k: &mut StiffnessSums,
    links: &Links,
    contacts: &Contacts,
    model: &Model,
) {
    let particles = model.particles.len();
    k.translational.resize(particles, Vec3::zeros());
    k.rotational.resize(particles, Vec3::zeros());
    let per = particles.div_ceil(rayon::current_num_threads()).max(1);
    let (translational, rotational) = (&mut k.translational, &mut k.rotational);
    let ranges = translational.par_chunks_mut(per).zip(rotational.par_chunks_mut(per));
    ranges.enumerate().for_each(|(r, (translational, rotational))| {
        translational.fill(Vec3::zeros());
        rotational.fill(Vec3::zeros());
        let mut range = SumsRange { first: r * per, translational, rotational };
        add_in_order_to(&mut range, links, contacts, model);
    });
}

/// [`add_in_order`] onto the particles of `k`'s range.
fn add_in_order_to(k: &mut SumsRange<'_>, links: &Links, contacts: &Contacts, model: &Model) {
    let p = &model.particles;
    for l in 0..links.nodes.len() {
        let [a, b] = links.nodes[l].map(|n| n as usize);
        if !k.holds(a) && !k.holds(b) {
            continue;
        }
        let Some((n, lever, s)) = link_spring(links, p, l) else { continue };
        let s = &s.stiffness;
        let increments = spring_increments(&n, s.kn, s.ks, lever, s.kt, s.kb);
        for i in [a, b] {
            if k.holds(i) {
                k.add(i, increments);
            }
        }
    }
    let mut memo = Default::default();
    let (first, end) = (k.first, k.first + k.translational.len());
    let holds = |i: u32| (first..end).contains(&(i as usize));
    let wanted = |key: &ContactKey| match *key {
        (Feature::Particle(a), Feature::Particle(b)) => holds(a) || holds(b),
        (_, Feature::Particle(b)) => holds(b),
        _ => true,
    };
    contacts.for_each_law(model, wanted, |site1, site2, params, normal| {
        add_contact_stiffness(k, [site1, site2], params, normal, p, &mut memo)
    });
}

/// Below this many new contacts in a step, [`add_fresh`] adds their stiffness on one thread.
const MIN_PARALLEL_FRESH: usize = if cfg!(test) { 8 } else { 256 };

/// Adds the stiffness of the contacts made at this step (`fresh`, indices into the general
/// list, and `fresh_pairs`, into the neighbour list, whose node shares their step found:
/// `pair_shares`, in the same order, cloned for each task) to `k`, in key order, and returns the lowest critical
/// step `√(2·min(m/K_trans, J/K_rot))` of the nodes they touch that are free in a DOF, with
/// each node's sums as they are after each of its additions (infinite for none).
///
/// With more than one thread and [`MIN_PARALLEL_FRESH`] new contacts, one task per thread,
/// each over its own range of particles: every task reads every new contact's shares
/// (152 bytes a pair, from the cache) and adds those of its nodes, in key order, so that
/// each node gets the same additions in the same order as in one pass; the lowest step is
/// the least of the tasks' (a minimum, whatever the order). The additions wait on memory
/// (two sums at a node of 10⁵): the 900 new pairs of a step of the settling packing of 10⁵
/// spheres took 113–135 µs in one pass, 1.5–2.5 % of the step at 2 threads.
pub(crate) fn add_fresh<'a>(
    k: &mut StiffnessSums,
    contacts: &Contacts,
    fresh: &[usize],
    fresh_pairs: &[usize],
    pair_shares: impl Iterator<Item = &'a PairShares> + Clone + Send + Sync,
    model: &Model,
) -> Real {
    debug_assert_eq!(fresh_pairs.len(), pair_shares.clone().count());
    let tasks = rayon::current_num_threads();
    let particles = k.translational.len();
    let add = |range| add_fresh_in(range, contacts, fresh, fresh_pairs, pair_shares.clone(), model);
    if tasks == 1 || fresh.len() + fresh_pairs.len() < MIN_PARALLEL_FRESH || particles < tasks {
        return add(SumsRange::whole(k));
    }
    let per = particles.div_ceil(tasks);
    let (translational, rotational) = (&mut k.translational, &mut k.rotational);
    let ranges = translational.par_chunks_mut(per).zip(rotational.par_chunks_mut(per));
    ranges
        .enumerate()
        .map(|(r, (translational, rotational))| {
            add(SumsRange { first: r * per, translational, rotational })
        })
        .reduce(|| Real::INFINITY, Real::min)
}

/// [`add_fresh`]'s additions onto the nodes of `k`'s range (the others' shares are passed
/// over), and the lowest step of those nodes.
fn add_fresh_in<'a>(
    mut k: SumsRange<'_>,
    contacts: &Contacts,
    fresh: &[usize],
    fresh_pairs: &[usize],
    mut pairs: impl Iterator<Item = &'a PairShares>,
    model: &Model,
) -> Real {
    let p = &model.particles;
    let mut memo = Default::default();
    let mut lowest = Real::INFINITY;
    let mut add = |share: &NodeShare| {
        if let Some(step) = share.add_to(&mut k) {
            lowest = lowest.min(step);
        }
    };
    for pick in merged_fresh(&contacts.list, fresh, &contacts.pairs, fresh_pairs) {
        match pick {
            Pick::General(i) => {
                let c = &contacts.list[i];
                let (params, normal) = (&c.params, &c.state.normal);
                let sites = [&c.site1, &c.site2];
                let (shares, len) = site_shares::<6>(p, sites, params, normal, &mut memo);
                shares[..len].iter().for_each(&mut add);
            }
            Pick::Pair(_) => {
                let shares = pairs.next().expect("a new pair's shares");
                shares.shares().iter().for_each(&mut add);
            }
        }
    }
    lowest
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::neighbours::sites;
    use crate::{Settings, Simulation};
    use flexdem_contact::{ContactDamping, Material};
    use flexdem_elements::builders::{membrane_rectangle, StructureOptions};
    use flexdem_elements::Dofs;

    /// A damped PFacet membrane (links, nodes) under a heap of overlapping spheres that touch
    /// it (general contacts), each other and a wall (the neighbour list's pairs), its
    /// corners pinned.
    fn heap_on_membrane() -> flexdem_elements::Model {
        let mut model = flexdem_elements::Model::new();
        let material = Material::new(1e7, 0.3, 1000.0, 0.5)
            .unwrap()
            .with_damping(ContactDamping::Restitution(0.5));
        let id = model.add_material(material).unwrap();
        let opts = StructureOptions::new("membrane", 0.002, id);
        let (o, u, v) = (Vec3::new(-0.1, -0.1, 0.0), Vec3::x(), Vec3::y());
        let s = membrane_rectangle(&mut model, o, u, v, 0.2, 0.2, 6, 6, &opts).unwrap();
        let nodes = model.structures[s as usize].nodes.clone();
        let corners = [0, 6, 42, 48].map(|k| nodes.start + k);
        model.block(corners, Dofs::TRANSLATION).unwrap();
        // two layers of spheres of radius 0.011 at a spacing of 0.02 (each overlaps its
        // neighbours), the lower one on the membrane, and a column down to a wall beside it
        let r = 0.011;
        for (i, j, layer) in (0..5).flat_map(|i| (0..5).flat_map(move |j| [(i, j, 0), (i, j, 1)])) {
            let c = Vec3::new(-0.04 + 0.02 * i as Real, -0.04 + 0.02 * j as Real, 0.0125);
            model.add_sphere(c + Vec3::z() * (0.02 * layer as Real), r, id).unwrap();
        }
        for k in 0..4 {
            model.add_sphere(Vec3::new(0.2, 0.0, -0.0495 + 0.02 * k as Real), r, id).unwrap();
        }
        model.add_wall(Vec3::new(0.0, 0.0, -0.06), Vec3::z(), id).unwrap();
        model
    }

    /// After a few steps of [`heap_on_membrane`], the sums per range of particles, with 2 to
    /// 5 threads, are the one-pass sums to the bit, links and contacts whose nodes are in two
    /// ranges included.
    #[test]
    fn the_sums_per_range_are_the_one_pass_sums() {
        let model = heap_on_membrane();
        let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
        let mut sim = Simulation::new(model, settings).unwrap();
        sim.run(5).unwrap();
        let state = &sim.state;
        let (links, contacts, model) = (&state.links, &state.contacts, &state.model);
        let walls = contacts.pairs.touching().filter(|(key, _)| matches!(key.0, Feature::Wall(_)));
        let counts = (links.intact(), contacts.list.len(), contacts.pairs.len(), walls.count());
        assert!(counts.0 > 0 && counts.1 > 0 && counts.2 > counts.3 && counts.3 > 0, "{counts:?}");
        assert!(contacts.list.iter().all(|c| c.params.is_damped()));
        let n = model.particles.len();
        assert!(n >= MIN_PARALLEL_SUMS, "{n} particles");
        let mut one_pass = StiffnessSums::new(n);
        add_in_order(&mut one_pass, links, contacts, model);
        assert!(one_pass.translational.iter().all(|t| t.max() > 0.0), "every particle counted");
        let bits = |k: &StiffnessSums| -> Vec<[u64; 6]> {
            let both = k.translational.iter().zip(&k.rotational);
            both.map(|(t, r)| [t.x, t.y, t.z, r.x, r.y, r.z].map(Real::to_bits)).collect()
        };
        let (mut split_links, mut split_contacts) = (0, 0);
        for threads in 2..=5 {
            let per = n.div_ceil(threads);
            let range = |i: u32| i as usize / per;
            split_links += links.nodes.iter().filter(|[a, b]| range(*a) != range(*b)).count();
            let sites = contacts.list.iter().map(|c| [&c.site1, &c.site2]);
            let ranges = sites.map(|s| s.map(|s| range(s.nodes[0])));
            split_contacts += ranges.filter(|[a, b]| a != b).count();
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            // the sums overwrite what they held, and are sized to the particles
            let old = vec![Vec3::repeat(7.0); n - 1];
            let mut per_range = StiffnessSums { translational: old.clone(), rotational: old };
            pool.install(|| add_in_ranges(&mut per_range, links, contacts, model));
            assert_eq!(bits(&one_pass), bits(&per_range), "{threads} threads");
        }
        assert!(split_links > 0 && split_contacts > 0, "{split_links} {split_contacts}");
    }

    /// A contact's two sites, law constants and normal, from the contacts.
    fn law_of(
        pick: Pick,
        contacts: &Contacts,
        model: &Model,
    ) -> ((Site, Site), FrictionalParams, Vec3) {
        match pick {
            Pick::General(i) => {
                let c = &contacts.list[i];
                ((c.site1, c.site2), c.params, c.state.normal)
            }
            Pick::Pair(i) => {
                let (key, c) = contacts.pairs.get(i);
                (sites(model, &key), c.params, c.state.normal)
            }
        }
    }

    /// The new contacts of [`heap_on_membrane`]'s first step (general and pairs, damped, with
    /// a light sphere held among them): [`add_fresh`], with the pairs' shares their step
    /// found (two threads), gives the sums and the lowest step of one pass in key order from
    /// the contacts, contact by contact, each node's step after each of its additions, the
    /// held one's left out, to the bit.
    #[test]
    fn the_fresh_contacts_add_as_one_pass_does() {
        let mut model = heap_on_membrane();
        // a light sphere among eight of the heap, held: its step, the lowest, is not counted
        let centre = Vec3::new(-0.03, -0.03, 0.0225);
        let held = model.add_sphere(centre, 0.0075, model.particles.material[0]).unwrap();
        model.block([held], Dofs::ALL).unwrap();
        let held = held as usize;
        let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..Settings::default() };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        pool.install(|| {
            let mut sim = Simulation::new(model, settings).unwrap();
            sim.step().unwrap();
            let fresh = &sim.pipeline.contacts;
            let (general, pairs) = (&fresh.fresh, &fresh.pairs.fresh);
            // (pairs of two spheres and of a wall and a sphere)
            assert!(!general.is_empty() && pairs.len() > 40, "{} {}", general.len(), pairs.len());
            let on_wall = |&&n: &&usize| {
                let key = sim.state.contacts.pairs.get(n).0;
                matches!(key.0, flexdem_elements::virtual_sphere::Feature::Wall(_))
            };
            assert!(pairs.iter().filter(on_wall).count() > 0);
            let (contacts, model) = (&sim.state.contacts, &sim.state.model);
            let p = &model.particles;
            let mut one_pass = sim.state.clock.stiffness.clone();
            let (mut lowest, mut lowest_held) = (Real::INFINITY, Real::INFINITY);
            let mut memo = Default::default();
            for pick in merged_fresh(&contacts.list, general, &contacts.pairs, pairs) {
                let ((site1, site2), params, normal) = law_of(pick, contacts, model);
                let k = &mut one_pass;
                let whole = &mut SumsRange::whole(k);
                add_contact_stiffness(whole, [&site1, &site2], &params, &normal, p, &mut memo);
                for site in [&site1, &site2] {
                    for &n in &site.nodes[..site.node_count()] {
                        let n = n as usize;
                        let (kt, kr) = (k.translational[n].max(), k.rotational[n].max());
                        let mut ratio = Real::INFINITY;
                        if kt > 0.0 {
                            ratio = ratio.min(p.mass[n] / kt);
                        }
                        if kr > 0.0 {
                            ratio = ratio.min(p.inertia[n] / kr);
                        }
                        let step = (2.0 * ratio).sqrt();
                        if p.blocked[n] == Dofs::ALL {
                            lowest_held = lowest_held.min(step);
                            continue;
                        }
                        lowest = lowest.min(step);
                    }
                }
            }
            let mut k = sim.state.clock.stiffness.clone();
            let shares = fresh.pairs.fresh_shares();
            let found = add_fresh(&mut k, contacts, general, pairs, shares, model);
            assert!(lowest.is_finite() && lowest_held < lowest, "{lowest} {lowest_held}");
            assert_eq!(found.to_bits(), lowest.to_bits());
            assert_eq!(k, one_pass);
            // (the held sphere's sums grow as the others')
            assert!(
                k.translational[held].max() > sim.state.clock.stiffness.translational[held].max()
            );
        });
    }
}
