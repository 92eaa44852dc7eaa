//! Contact bookkeeping and forces: each step, the exact closest features of every candidate
//! pair, the one-contact-per-touching rule (`flexdem_elements::touching`), persistent contacts
//! keyed by their two features with their shear history, handed over to the neighbouring
//! feature when a touching slides across elements, the contact law in parallel, and the
//! node loads summed in contact order (independent of the thread count).

use crate::collider::{Collider, NONE};
pub(crate) use crate::contact::BirthReport;
use crate::contact::{
    birth_jump, extent, geometry, material, mirrored, new_contact, owner, wall_touching, Contact,
    Touching,
};
use crate::contact_list::Contacts;
use crate::dashpots::account_ended_springs;
use crate::gather::LoadIndex;
use crate::home_loops::{by_runs, chunk_home_runs, element_particle, shared, write_hulls};
use crate::homes::{Homes, PerChunk};
use crate::offsets::continued_overlap;
use crate::pair_parts::PairParts;
use crate::pair_passes::PairScratch;
use crate::parallel::MAX_CHUNKS_PER_TASK;
use crate::parallel::MIN_PARALLEL_COSTLY;
use crate::part_step::PartsRoom;
use crate::prefilter::{proven_apart, Hull};
use crate::touchings::{match_sorted, Touchings};
use flexdem_contact::{ContactDamping, LinkKinematicsMode};
use flexdem_elements::pairs::{self, Candidate, ConnectionRef, PFacetRef, SphereRef};
use flexdem_elements::touching::{dominates, Element, ElementCandidate, Topology};
use flexdem_elements::virtual_sphere::{Feature, Kinematics, NodeLoad};
use flexdem_elements::{Adjacency, Model};
use flexdem_geom::{Real, Vec3};
use rayon::prelude::*;

/// The buffers and caches that find and update the contacts, rebuilt from the model: nothing
/// here is saved.
#[derive(Clone, Debug, Default)]
pub(crate) struct ContactPipeline {
    /// Indices in `list` of the contacts made at the last detection (new keys).
    pub(crate) fresh: Vec<usize>,
    /// Buffers of the neighbour list's update (its fresh pairs among them).
    pub(crate) pairs: PairScratch,
    pub(crate) loads: Vec<[NodeLoad; 6]>,
    /// Whether a contact may have a dashpot (a material has damping, or a contact kept from
    /// before has a dashpot): then `dashpot_loads` (and the neighbour list's) are kept.
    pub(crate) damped: bool,
    /// Per contact, the node loads of its dashpots' force alone, for their power over the
    /// step after the kick (`dashpots.rs`); empty when `damped` is false.
    pub(crate) dashpot_loads: Vec<[NodeLoad; 6]>,
    /// Buffers reused from step to step, so that detection does not allocate once warm.
    scratch: Scratch,
    /// Per contact, the particles its loads go to, slot by slot (`NO_NODE` for a slot not
    /// used): what the index of `gather.rs` reads, written where the loads are made.
    pub(crate) load_nodes: Vec<[u32; 6]>,
    /// Per general contact, its elastic energy and the friction it dissipated, after the
    /// last update, in list order (written where the law runs, for the energy balance:
    /// [`Contacts::energy_sums_from`]).
    pub(crate) energies: Vec<(Real, Real)>,
    /// Where each particle's loads are, for their parallel sum (`gather.rs`).
    pub(crate) load_index: LoadIndex,
    /// The free spheres' pairs split into parts for their parallel update (`pair_parts.rs`).
    pub(crate) pair_parts: PairParts,
    /// The memory of the list of the parts' inputs at that update (`part_step.rs`).
    pub(crate) part_inputs: PartsRoom,
    /// The links' kinematics, which say how a virtual sphere on a connection turns
    /// (`Kinematics::link_mode`).
    pub(crate) link_mode: LinkKinematicsMode,
}

/// Candidate pairs per parallel task of the detection (fixed, the order of the touchings does
/// not depend on it: each chunk keeps its own in pair order, read back in chunk order).
const DETECT_CHUNK: usize = 1024;

/// Candidate pairs and their chunks' touching candidates and pairs, cut by home.
type DetectPiece<'a> =
    (&'a [(u32, u32)], (PerChunk<'a, Vec<ElementCandidate>>, PerChunk<'a, Vec<(u32, u32)>>));

/// Buffers of [`ContactPipeline::detect`].
#[derive(Clone, Debug, Default)]
struct Scratch {
    order: Vec<(Feature, Feature, u32)>,
    hulls: Vec<Hull>,
    /// Per chunk of [`DETECT_CHUNK`] candidate pairs, its touching ones at the last detection
    /// (read through [`Touchings`], not copied into one list).
    found: Vec<Vec<ElementCandidate>>,
    /// Where each chunk's touchings start in pair order, then their end ([`Touchings`]).
    starts: Vec<u32>,
    /// Per chunk, its touchings' candidate pairs (collidable indices), in pair order.
    found_pairs: Vec<Vec<(u32, u32)>>,
    /// Every touching's candidate pair, in pair order (sorted: the one-contact rule's
    /// lookups).
    keys: Vec<(u32, u32)>,
    /// Per chunk, per touching, whether it survived the one-contact rule (its oriented
    /// `Touching` is made from the touching where it is read: 1 byte here instead of a copy).
    survived: Vec<Vec<bool>>,
    /// Per chunk, the sort keys of its touchings that survived (see `order`).
    chunk_order: Vec<Vec<(Feature, Feature, u32)>>,
    /// The walls' touchings (they come after the touchings in the key order's indices).
    walls: Vec<Touching>,
    previous: Vec<Contact>,
    /// Per touching (in key order), the index of the last step's contact of its key.
    matched: Vec<Option<u32>>,
    taken: Vec<bool>,
    ended: Vec<usize>,
    by_owners: Vec<usize>,
}

/// Makes `per_chunk` hold at least `chunks` lists (the new ones empty; those past `chunks`
/// are kept for their memory).
fn at_least<T>(per_chunk: &mut Vec<Vec<T>>, chunks: usize) {
    if per_chunk.len() < chunks {
        per_chunk.resize_with(chunks, Vec::new);
    }
}

/// A touching turned so that body 1 is the one with the smaller (owner, feature): the
/// contact of a touching then has the same key and the same body 1 whichever pair of
/// elements reported it (a structure touching itself is seen from both sides).
fn oriented(t: Touching) -> Touching {
    let c = &t.candidate;
    if (t.owners.1, c.site2.feature) >= (t.owners.0, c.site1.feature) {
        return t;
    }
    Touching {
        candidate: Candidate {
            site1: c.site2,
            site2: c.site1,
            center1: c.center2,
            center2: c.center1,
            distance: c.distance,
        },
        materials: (t.materials.1, t.materials.0),
        owners: (t.owners.1, t.owners.0),
    }
}

/// The contact-to-be of a touching that survived the one-contact rule: its materials and
/// owners, turned by [`oriented`].
#[inline]
fn surviving(model: &Model, ci: &ElementCandidate) -> Touching {
    oriented(Touching {
        candidate: ci.candidate,
        materials: (material(model, ci.element1), material(model, ci.element2)),
        owners: (owner(model, ci.element1), owner(model, ci.element2)),
    })
}

/// The closest features of two collidable elements (`a` before `b` in collidable order:
/// spheres, then connections, then PFacets).
pub(crate) fn candidate(model: &Model, a: Element, b: Element) -> Candidate {
    let p = &model.particles;
    let sphere =
        |i: u32| SphereRef { id: i, center: p.pos[i as usize], radius: p.radius[i as usize] };
    let conn = |k: u32| {
        let c = &model.connections[k as usize];
        ConnectionRef {
            id: k,
            nodes: c.nodes,
            ends: c.nodes.map(|n| p.pos[n as usize]),
            radius: c.radius,
        }
    };
    let pf = |k: u32| {
        let f = &model.pfacets[k as usize];
        PFacetRef {
            id: k,
            nodes: f.nodes,
            connections: f.connections,
            corners: f.nodes.map(|n| p.pos[n as usize]),
            radius: f.radius,
        }
    };
    match (a, b) {
        (Element::Particle(i), Element::Particle(j)) => {
            pairs::sphere_sphere(&sphere(i), &sphere(j))
        }
        (Element::Particle(i), Element::Connection(k)) => {
            pairs::sphere_connection(&sphere(i), &conn(k))
        }
        (Element::Particle(i), Element::PFacet(k)) => pairs::sphere_pfacet(&sphere(i), &pf(k)),
        (Element::Connection(i), Element::Connection(k)) => {
            pairs::connection_connection(&conn(i), &conn(k))
        }
        (Element::Connection(i), Element::PFacet(k)) => pairs::connection_pfacet(&conn(i), &pf(k)),
        (Element::PFacet(i), Element::PFacet(k)) => pairs::pfacet_pfacet(&pf(i), &pf(k)),
        // collidable order puts spheres before connections before PFacets
        (x, y) => {
            let c = candidate(model, y, x);
            Candidate {
                site1: c.site2,
                site2: c.site1,
                center1: c.center2,
                center2: c.center1,
                distance: c.distance,
            }
        }
    }
}

/// Collidable indices of the elements that contain `feature` (no buffer): a free sphere's
/// own element, or a node's connections then PFacets; an edge's connection then its PFacets;
/// a face's PFacet; nothing for a wall.
fn containing<'a>(
    collider: &'a Collider,
    adj: &'a Adjacency,
    feature: Feature,
) -> impl Iterator<Item = u32> + Clone + 'a {
    let none: &[u32] = &[];
    let (own, connections, pfacets) = match feature {
        Feature::Particle(i) => {
            let s = collider.sphere_element[i as usize];
            if s != NONE {
                (Some(s), none, none)
            } else {
                (None, adj.node_connections.get(i as usize), adj.node_pfacets.get(i as usize))
            }
        }
        Feature::Edge(c) => {
            let e = collider.connection_element(c);
            ((e != NONE).then_some(e), none, adj.connection_pfacets.get(c as usize))
        }
        Feature::Face(f) => (Some(collider.pfacet_element[f as usize]), none, none),
        Feature::Wall(_) => (None, none, none),
    };
    own.into_iter()
        .chain(connections.iter().map(|&c| collider.connection_element(c)).filter(|&e| e != NONE))
        .chain(pfacets.iter().map(|&f| collider.pfacet_element[f as usize]))
}

impl ContactPipeline {
    /// Empty buffers for the contacts of `model` (`contacts` the ones it starts with), whose
    /// links have the kinematics `link_mode`.
    pub(crate) fn new(model: &Model, contacts: &Contacts, link_mode: LinkKinematicsMode) -> Self {
        ContactPipeline {
            link_mode,
            damped: model.materials.iter().any(|m| m.damping != ContactDamping::None)
                || contacts.list.iter().any(|c| c.params.is_damped())
                || contacts.pairs.touching().any(|(_, c)| c.params.is_damped()),
            ..Default::default()
        }
    }

    /// The buffer of the elements' hulls, which [`ContactPipeline::detect`] writes anew at
    /// each step, lent to the collider's build between the steps.
    pub(crate) fn hull_buffer(&mut self) -> &mut Vec<Hull> {
        &mut self.scratch.hulls
    }

    /// Finds this step's touchings among the collider's candidate pairs, applies the
    /// one-contact-per-touching rule, and matches them with the last step's contacts (keeping
    /// their state, or handing it over to the feature a touching moved to, see
    /// [`ContactPipeline::settle_births`]). `dt` is the step about to be taken (to tell a contact
    /// found late from one found on time).
    pub(crate) fn detect(
        &mut self,
        contacts: &mut Contacts,
        model: &Model,
        adj: &Adjacency,
        collider: &Collider,
        dt: Real,
        homes: &Homes,
    ) -> BirthReport {
        // 1. exact closest features of every candidate pair; keep the touching ones. The
        // exact kernels cost up to a microsecond (triangle–triangle) and most candidate pairs
        // of the Verlet list do not touch: a separating slab between the elements' hulls
        // (taken once per element) says so first, and only the remaining pairs go on.
        let elements = &collider.elements;
        // (only for the elements in a pair: free spheres among themselves are not here)
        let unused = Hull::new([Vec3::zeros(); 3], 1, 0.0);
        let paired = |i: usize| collider.paired.get(i).copied().unwrap_or(true);
        if collider.pairs.is_empty() {
            // (free spheres and walls only: no hull is looked at)
            self.scratch.hulls.clear();
        } else {
            // written in place: a collect copies each hull through `memcpy`
            self.scratch.hulls.resize(elements.len(), unused);
            write_hulls(&mut self.scratch.hulls, elements, model, &paired, homes);
        }
        // per fixed chunk of candidate pairs, in parallel: the slab test, then the exact
        // kernel of the survivors, the touching ones kept in pair order (one pass, no
        // serial filtering of every pair's flag in between)
        let chunks = collider.pairs.len().div_ceil(DETECT_CHUNK);
        let scratch = &mut self.scratch;
        let hulls = &scratch.hulls;
        at_least(&mut scratch.found, chunks);
        at_least(&mut scratch.found_pairs, chunks);
        at_least(&mut scratch.chunk_order, chunks);
        let detect_chunks = |_: usize, (pairs, (found, found_pairs)): DetectPiece<'_>| {
            pairs
                .par_chunks(DETECT_CHUNK)
                .zip(found.outputs.par_iter_mut())
                .zip(found_pairs.outputs.par_iter_mut())
                .with_max_len(MAX_CHUNKS_PER_TASK)
                .for_each(|((pairs, found), found_pairs)| {
                    found.clear();
                    found_pairs.clear();
                    for &(i, j) in pairs {
                        if proven_apart(&hulls[i as usize], &hulls[j as usize]) {
                            continue;
                        }
                        let (a, b) = (elements[i as usize], elements[j as usize]);
                        let c = candidate(model, a, b);
                        if c.overlap() > 0.0 {
                            found.push(ElementCandidate { element1: a, element2: b, candidate: c });
                            found_pairs.push((i, j));
                        }
                    }
                });
        };
        // by the home of each chunk's first pair's first element (`home_loops.rs`)
        let pairs = &collider.pairs[..];
        let found = PerChunk { outputs: &mut scratch.found[..chunks], chunk: DETECT_CHUNK };
        let found_pairs =
            PerChunk { outputs: &mut scratch.found_pairs[..chunks], chunk: DETECT_CHUNK };
        let homes = shared(homes, model).then_some(homes);
        let home = |c: usize| {
            let e = elements[pairs[c * DETECT_CHUNK].0 as usize];
            homes.map_or(0, |h| h.home_of(element_particle(model, e)))
        };
        let runs = chunk_home_runs(pairs.len(), DETECT_CHUNK, homes, home);
        by_runs((pairs, (found, found_pairs)), pairs.len(), runs, &detect_chunks);
        let scratch = &mut self.scratch;
        scratch.starts.clear();
        scratch.starts.push(0);
        let mut end = 0;
        for found in &scratch.found[..chunks] {
            end += found.len() as u32;
            scratch.starts.push(end);
        }
        let touching = Touchings { chunks: &scratch.found[..chunks], starts: &scratch.starts };

        // 2. one contact per touching: drop the dominated candidates (indexed lookups)
        let topology = Topology::of(model);
        let index_of = |e: Element| -> u32 {
            match e {
                Element::Particle(i) => collider.sphere_element[i as usize],
                Element::Connection(k) => collider.connection_element(k),
                Element::PFacet(k) => collider.pfacet_element[k as usize],
            }
        };
        // each touching's key is its candidate pair (its elements' collidable indices), kept
        // by the search: looked up from the elements, one touching after another, the keys
        // took 150 µs a step of the membrane of 10⁵ PFacets on one thread
        let keys = &mut scratch.keys;
        keys.clear();
        scratch.found_pairs[..chunks].iter().for_each(|p| keys.extend_from_slice(p));
        debug_assert!(touching
            .iter()
            .zip(keys.iter())
            .all(|(c, &key)| (index_of(c.element1), index_of(c.element2)) == key));
        let keys = &*keys;
        let survives = |i: usize, ci: &ElementCandidate| {
            let side2 = containing(collider, adj, ci.candidate.site2.feature);
            for e1 in containing(collider, adj, ci.candidate.site1.feature) {
                for e2 in side2.clone() {
                    let key = (e1.min(e2), e1.max(e2));
                    if let Ok(j) = keys.binary_search(&key) {
                        if dominates(&touching[j], j, ci, i, &topology) {
                            return false;
                        }
                    }
                }
            }
            true
        };
        at_least(&mut scratch.survived, chunks);
        // sorted by key through a small (key, code) list: the touchings themselves are large
        // and moving them in the sort cost more than the sort's comparisons. Code
        // c·DETECT_CHUNK + l is touching l of chunk c (if it survived; increasing in pair
        // order), W + m wall touching m, W = chunks·DETECT_CHUNK: as if both were in one list
        // (the dominated ones left out and no copy)
        let key = |t: &Touching, n: u32| (t.candidate.site1.feature, t.candidate.site2.feature, n);
        // per chunk, in parallel (each touching's index from its chunk's start): whether each
        // touching survives, and the sort keys of those that do (made one chunk after
        // another, they took 290 µs a step of the membrane of 10⁵ PFacets)
        touching
            .chunks
            .par_iter()
            .zip(touching.starts.par_iter())
            .zip(scratch.survived[..chunks].par_iter_mut())
            .zip(scratch.chunk_order[..chunks].par_iter_mut())
            .enumerate()
            .with_max_len(MAX_CHUNKS_PER_TASK)
            .for_each(|(c, (((found, &start), survived), order))| {
                survived.clear();
                survived.extend(
                    found.iter().enumerate().map(|(l, ci)| survives(start as usize + l, ci)),
                );
                order.clear();
                let code = |l: usize| (c * DETECT_CHUNK + l) as u32;
                let kept = found.iter().zip(survived.iter()).enumerate().filter(|(_, (_, &s))| s);
                order.extend(kept.map(|(l, (t, _))| key(&surviving(model, t), code(l))));
            });

        // walls touch every particle on their side (one contact per wall and particle)
        let walls = &mut scratch.walls;
        walls.clear();
        walls.extend(collider.wall_pairs.iter().filter_map(|&(w, i)| wall_touching(model, w, i)));
        let first_wall = (chunks * DETECT_CHUNK) as u32;
        let order = &mut scratch.order;
        order.clear();
        scratch.chunk_order[..chunks].iter().for_each(|o| order.extend_from_slice(o));
        order.extend(walls.iter().enumerate().map(|(m, t)| key(t, first_wall + m as u32)));
        order.par_sort_unstable();

        // 3. match with the last step's contacts (both sorted by key): each touching's old
        // contact (the first of its key) found by merging the two lists, the new list made
        // in parallel (the copies of the old contacts are most of the work), then the old
        // ones taken and the fresh ones noted in order
        std::mem::swap(&mut contacts.list, &mut scratch.previous);
        let old = &scratch.previous;
        let new_key = |&(f1, f2, _): &(Feature, Feature, u32)| (f1, f2);
        match_sorted(order, old, new_key, Contact::key, &mut scratch.matched);
        let walls = &scratch.walls;
        let touching_at = |n: u32| match n.checked_sub(first_wall) {
            Some(m) => walls[m as usize],
            None => {
                let (c, l) = (n as usize / DETECT_CHUNK, n as usize % DETECT_CHUNK);
                surviving(model, &touching.chunks[c][l])
            }
        };
        order
            .par_iter()
            .zip(scratch.matched.par_iter())
            .with_min_len(MIN_PARALLEL_COSTLY)
            .map(|(&(_, _, index), &k)| {
                let t = touching_at(index);
                match k {
                    Some(k) => {
                        let mut c = old[k as usize].clone();
                        c.site1 = t.candidate.site1;
                        c.site2 = t.candidate.site2;
                        c
                    }
                    None => new_contact(model, &t),
                }
            })
            .collect_into_vec(&mut contacts.list);
        let taken = &mut scratch.taken;
        taken.clear();
        taken.resize(old.len(), false);
        let mut fresh = std::mem::take(&mut self.fresh);
        fresh.clear();
        for (n, &k) in scratch.matched.iter().enumerate() {
            match k {
                Some(k) => taken[k as usize] = true,
                None => fresh.push(n),
            }
        }
        self.fresh = fresh;
        self.settle_births(contacts, model, dt)
    }

    /// What the contacts made at this detection inherit, so that no energy comes from a
    /// contact's birth or hand-over (model: "contacts born deep"), and what the contacts that
    /// started or ended between the last step and this one move the energy balance by. With
    /// `old` the last step's contacts, each new contact (a new pair of features) is one of:
    ///
    /// - **a hand-over**: an ended contact of the same owners (a free sphere, a structure or a
    ///   wall on each side) whose point is the nearest within the elements' extent: the
    ///   touching moved to other features (face to edge to face, edge to faces at a fold, or
    ///   across an element between nearly parallel elements). The new contact takes its shear
    ///   force, normal (when within the contact's size: the same touching) and dissipation,
    ///   and an overlap offset `δ₀ = δ_new − δ_old·kn_old/kn_new`, `δ_old` the ended
    ///   contact's overlap (less its offset) continued to now (`continued_overlap`): the
    ///   normal force does not jump across the switch, and so neither does the elastic
    ///   energy; the offset is given back over the next steps (`offsets.rs`);
    /// - **a split**: no ended contact to take over, but a contact of the same owners within
    ///   the elements' extent existed at the last step, and the new one is found deeper than
    ///   the approach of one step explains (`δ > u·dt`, `u` the approach speed): the touching
    ///   spread onto more features (a surface turning from convex to concave under a
    ///   sphere). It is made with no force, `δ₀ = δ`;
    /// - **a first touch**: full force; found late (`δ > u·dt`: it passed a step with overlap
    ///   unseen) it is counted as born deep.
    ///
    /// The leapfrog's works (trapezoidal, with the kinetic energy `½m·v(t−dt/2)·v(t+dt/2)`)
    /// close the balance exactly for linear springs that exist at both ends of a step. A
    /// spring that enters at this step with overlap `δ` (one step before: `δ₋ = δ − u·dt`)
    /// moves the balance by `½·kn·δ·δ₋`, one that leaves it (force `F` at the last step,
    /// overlap `δ_now` continued to now) by `−½·F·δ_now`: small and of opposite signs for a
    /// collision found on time, which then leaves no trace; positive for a contact found late
    /// (energy put in: `born_energy`). A contact that ended while compressed (dropped by
    /// the one-contact rule with no successor) gives up `½·F·δ_now`, and every ended contact
    /// its shear spring's `½|Fs|²/ks` (`released`). A hand-over counts the ended contact's
    /// exit and the new one's entry, which cancel to first order.
    fn settle_births(&mut self, contacts: &mut Contacts, model: &Model, dt: Real) -> BirthReport {
        let p = &model.particles;
        let k = Kinematics::of(p).with_link_mode(self.link_mode);
        let scratch = &mut self.scratch;
        let old = &scratch.previous;
        let taken = &mut scratch.taken;
        let mut report = BirthReport::default();
        // the ended ones, sorted by owners, so that each new contact looks only at its own
        let ended = &mut scratch.ended;
        ended.clear();
        ended.extend((0..old.len()).filter(|&o| !taken[o]));
        ended.sort_unstable_by_key(|&o| (old[o].owners, o));
        // every old contact by owners, for splits: sorted when the first one is looked for
        let by_owners = &mut scratch.by_owners;
        by_owners.clear();
        for &n in &self.fresh {
            let c = &contacts.list[n];
            // the closest features of two elements may jump across an element in one step
            // (nearly parallel edges or faces): a touching is looked for within the elements'
            // extent
            let reach = c.site1.radius
                + c.site2.radius
                + extent(&c.site1, &p.pos)
                + extent(&c.site2, &p.pos);
            // both are contact points: the old one at its last update, the new one estimated
            // by new_contact
            let point = c.point;
            let owners = c.owners;
            let near = |list: &[usize], taken: Option<&[bool]>| {
                let start = list.partition_point(|&o| old[o].owners < owners);
                list[start..]
                    .iter()
                    .take_while(|&&o| old[o].owners == owners)
                    .filter(|&&o| taken.is_none_or(|t| !t[o]))
                    .map(|&o| (o, (old[o].point - point).norm()))
                    .filter(|&(_, d)| d <= reach)
                    .min_by(|a, b| a.1.total_cmp(&b.1))
            };
            if let Some((o, distance)) = near(ended, Some(taken)) {
                taken[o] = true;
                let before = &old[o];
                let (_, _, g_old) = geometry(model, &k, before);
                let carried = continued_overlap(before, &g_old, dt);
                // the ended contact's spring leaves the balance as if it had ended ...
                report.born_energy -= 0.5 * before.state.normal_force * carried;
                let force = before.params.kn * carried.max(0.0);
                let c = &mut contacts.list[n];
                let normal = c.state.normal;
                c.state = before.state;
                c.state.overlap_offset = 0.0;
                if distance <= c.site1.radius + c.site2.radius {
                    // the same touching on other features: it keeps the side it was made on
                    if mirrored(c, before, &p.pos) {
                        c.state.normal = -c.state.normal;
                        c.state.shear_force = -c.state.shear_force;
                    }
                } else {
                    // the closest features jumped across an element: the new ones' normal,
                    // the shear force turned onto its plane by the law
                    c.state.normal = normal;
                    if mirrored(c, before, &p.pos) {
                        c.state.shear_force = -c.state.shear_force;
                    }
                }
                let (_, _, g) = geometry(model, &k, c);
                let offset = g.overlap - force / c.params.kn;
                // the ended contact is continued on its last closest points, which lag the
                // motion by a second-order amount (a sphere sliding by dx over a face at
                // height h: dx²/2h): a touching that moved on continuously keeps its offset
                let continuous = (offset - before.state.overlap_offset).abs()
                    <= 1e-6 * (c.site1.radius + c.site2.radius)
                    && before.params.kn == c.params.kn;
                // (negative when the new features are nearer than the force asks: given
                // back over the next steps, `offsets.rs`)
                c.state.overlap_offset =
                    if continuous { before.state.overlap_offset } else { offset };
                // ... and the new one enters it as if it were born: the two nearly cancel
                report.born_energy += birth_jump(&c.params, &c.state, &g, dt);
                continue;
            }
            let (_, _, g) = geometry(model, &k, c);
            let approach = -g.relative_velocity.dot(&g.normal);
            // the overlap one step before, from the approach over the step
            if !(g.overlap - approach * dt > 1e-12 * reach) {
                report.born_energy += birth_jump(&c.params, &c.state, &g, dt); // found on time
                continue;
            }
            if by_owners.is_empty() {
                by_owners.extend(0..old.len());
                by_owners.sort_unstable_by_key(|&o| (old[o].owners, o));
            }
            if near(by_owners, None).is_some() {
                // a split: made with no force, on its own normal
                contacts.list[n].state.overlap_offset = g.overlap.max(0.0);
                continue;
            }
            // found late: the energy it puts in is also watched on its own (model.md §4)
            let jump = birth_jump(&c.params, &c.state, &g, dt);
            report.born_energy += jump;
            report.late_energy += jump;
            report.born_deep += 1;
        }
        for &o in ended.iter() {
            if taken[o] {
                continue;
            }
            let c = &old[o];
            contacts.ended_dissipation += c.state.dissipated_friction;
            let (_, _, g) = geometry(model, &k, c);
            let now = continued_overlap(c, &g, dt);
            // the springs leave the balance (see above): ended by separating (δ_now ≤ 0) the
            // normal spring's −½·F·δ_now is put in, ended while compressed it is released
            let (params, state, v) = (&c.params, &c.state, &g.relative_velocity);
            let (put_in, released) = (&mut report.born_energy, &mut report.released);
            account_ended_springs(params, state, now, v, dt, put_in, released);
        }
        report
    }
}
