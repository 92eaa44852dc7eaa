//! The beam links of the model: one per connection, made when the scene is built
//! (model.md §3), updated in parallel each step, their node loads summed per node in a fixed
//! order so that the result does not depend on the number of threads.

use crate::home_loops::{by_runs, chunk_home_runs};
use crate::homes::{in_homes, Homes, Piece, Pieces, Runs, Sums};
use crate::integrator::CHUNK as STEP_CHUNK;
use crate::parallel::MAX_CHUNKS_PER_TASK;
use flexdem_contact::link_lanes::{update_link_lanes, LaneNodes, LANES};
use flexdem_contact::{
    link_elastic_energy, update_link_parts, FailureMode, LinkClass, LinkEvent, LinkKinematics,
    LinkKinematicsMode, LinkPlastic, LinkSpring, LinkState, LinkStatus,
};
use flexdem_elements::{Model, Particles};
use flexdem_geom::{Real, Vec3};
use rayon::iter::Either;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// What one update of every link returns.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkUpdate {
    /// Breakage events.
    pub events: LinkEvents,
    /// Elastic energy stored in the links after the update (J).
    pub elastic_energy: Real,
    /// Energy the links dissipated in this update (J): plastic caps, slip after decohesion,
    /// breakage.
    pub dissipated: Real,
}

/// Links per parallel chunk.
const CHUNK: usize = 512;

/// What the force assembly reads of a link's last update (72 bytes; the full `LinkForces` of
/// `update_link` is 216). The loads on the nodes are F₁ = −F₂, τ₁ = τ_lever − M,
/// τ₂ = τ_lever + M; the shear force is the state's (`LinkState::shear_force`), the twisting
/// moment (M·n)n and the bending moment the rest (n the state's normal). What only the output
/// and the messages read is made from these when asked: the normal force
/// ([`Links::normal_force`]) and the elastic energy ([`Links::elastic_energy`]); the links'
/// total energy is summed by the update itself.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkLoad {
    /// Force on node 2, Fn·n + Fs (N).
    pub force_on_2: Vec3,
    /// The shear force's torque about each node, −(L/2) n × Fs (N·m; the same on both).
    pub lever_torque: Vec3,
    /// Moment on node 2, Mt + Mb (N·m).
    pub moment_on_2: Vec3,
}

/// Every beam link: constants, state, and the forces of the last step. Per link, 176 bytes:
/// nodes 8, class 4, spring 4, state 88, loads 72 (and 16 of the node → loads index), and 32
/// of plastic state when some material is plastic; the constants links share (limits, radius,
/// failure mode) are kept once per class, their stiffnesses and rest length once per distinct
/// spring (a regular mesh has a few: 2 in the benchmark's membrane; an irregular one pays 40
/// bytes per link in the table).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Links {
    /// The two nodes of link `i` (those of connection `i`).
    pub nodes: Vec<[u32; 2]>,
    /// The constants shared by the links of one material and radius (limits, failure mode,
    /// kinematics), once each.
    pub classes: Vec<LinkClass>,
    /// The class of link `i` (an index into `classes`).
    pub class: Vec<u32>,
    /// The distinct stiffnesses and rest lengths (to the bit), once each.
    pub springs: Vec<LinkSpring>,
    /// The spring of link `i` (an index into `springs`).
    pub spring: Vec<u32>,
    /// State carried from step to step (shear force, reference rotation, status).
    pub state: Vec<LinkState>,
    /// The plastic part of link `i`'s state (plastic elongation and rotation), when some class
    /// is plastic; empty otherwise (a fragile link's is always zero).
    pub plastic: Vec<LinkPlastic>,
    /// Loads of the last update.
    #[serde(skip)]
    pub loads: Vec<LinkLoad>,
    /// For each node, the offsets into `node_loads` (CSR).
    node_offsets: Vec<u32>,
    /// For each node, the loads it receives: `2·link + side`.
    node_loads: Vec<u32>,
    /// Per-chunk sums of the last update (a buffer kept between steps).
    #[serde(skip)]
    chunk_sums: Vec<LinkUpdate>,
}

/// Events of one links update.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LinkEvents {
    /// Links broken for good in this step.
    pub broken: u32,
    /// Links that lost their cohesion in this step.
    pub decohered: u32,
}

impl Links {
    /// One link per connection of `model`, at rest in the current configuration, with the
    /// material of the connection and the given shear kinematics. Links of the same material
    /// and radius (to the bit) share one class.
    pub fn from_model(model: &Model, mode: LinkKinematicsMode) -> Self {
        let p = &model.particles;
        let n = model.connections.len();
        let mut links = Links {
            nodes: Vec::with_capacity(n),
            classes: Vec::new(),
            class: Vec::with_capacity(n),
            springs: Vec::new(),
            spring: Vec::with_capacity(n),
            state: Vec::with_capacity(n),
            plastic: Vec::new(),
            loads: Vec::new(),
            node_offsets: Vec::new(),
            node_loads: Vec::new(),
            chunk_sums: Vec::new(),
        };
        let mut class_of: HashMap<(u32, u64), u32> = HashMap::new();
        let mut spring_of: HashMap<[u64; 5], u32> = HashMap::new();
        for c in &model.connections {
            let [a, b] = c.nodes.map(|n| n as usize);
            let material = &model.materials[c.material as usize];
            let class = *class_of.entry((c.material, c.radius.to_bits())).or_insert_with(|| {
                links.classes.push(LinkClass::from_material(material, c.radius, mode));
                (links.classes.len() - 1) as u32
            });
            links.nodes.push(c.nodes);
            links.class.push(class);
            let spring = LinkSpring::from_material(material, c.radius, c.rest_length);
            let k = &spring.stiffness;
            let bits = [k.kn, k.ks, k.kb, k.kt, spring.rest_length].map(Real::to_bits);
            let index = *spring_of.entry(bits).or_insert_with(|| {
                links.springs.push(spring);
                (links.springs.len() - 1) as u32
            });
            links.spring.push(index);
            links.state.push(LinkState::new(p.pos[a], p.pos[b], p.ori[a], p.ori[b]));
        }
        if links.some_plastic() {
            links.plastic = vec![LinkPlastic::default(); n];
        }
        links.loads = vec![LinkLoad::default(); links.nodes.len()];
        links.index_nodes();
        links
    }

    /// Whether some class is plastic (then every link keeps a plastic state).
    fn some_plastic(&self) -> bool {
        self.classes.iter().any(|c| c.failure == FailureMode::Plastic)
    }

    /// Builds the node → loads index (counting sort, loads of a node in link order), up to
    /// the last node a link holds: the particles after it (a packing's free spheres, all of
    /// them without structures) take no offsets (4 bytes per sphere before).
    fn index_nodes(&mut self) {
        let rows = self.nodes.iter().flatten().max().map_or(0, |&last| last as usize + 1);
        if rows == 0 {
            self.node_offsets = Vec::new();
            self.node_loads = Vec::new();
            return;
        }
        let mut count = vec![0u32; rows + 1];
        for l in &self.nodes {
            count[l[0] as usize + 1] += 1;
            count[l[1] as usize + 1] += 1;
        }
        for i in 0..rows {
            count[i + 1] += count[i];
        }
        let mut next = count.clone();
        self.node_loads = vec![0; 2 * self.nodes.len()];
        for (k, l) in self.nodes.iter().enumerate() {
            for side in 0..2 {
                let n = l[side] as usize;
                self.node_loads[next[n] as usize] = (2 * k + side) as u32;
                next[n] += 1;
            }
        }
        self.node_offsets = count;
    }

    /// Whether these links (read from a checkpoint, say) fit `model`: one link per
    /// connection, on the connection's nodes, with as many classes (each in range), springs
    /// and states (and plastic states when a class is plastic, none otherwise), and the
    /// node → loads index that [`Links::from_model`] builds for them (every offset and load
    /// code in range). [`Links::update`] and [`Links::add_loads`] index the particles and the
    /// forces with these numbers without further checks. `model` must have been validated
    /// (`Model::validate`: connection node ids in range).
    pub fn check_against(&self, model: &Model) -> bool {
        let n_links = model.connections.len();
        let n_particles = model.particles.len();
        let same_nodes = self.nodes.len() == n_links
            && self.nodes.iter().zip(&model.connections).all(|(l, c)| *l == c.nodes)
            && self.nodes.iter().flatten().all(|&n| (n as usize) < n_particles);
        let classes_in_range = self.class.len() == n_links
            && self.class.iter().all(|&c| (c as usize) < self.classes.len());
        let plastic_states = if self.some_plastic() { n_links } else { 0 };
        let springs_in_range = self.spring.len() == n_links
            && self.spring.iter().all(|&s| (s as usize) < self.springs.len());
        if !(same_nodes
            && classes_in_range
            && springs_in_range
            && self.state.len() == n_links
            && self.plastic.len() == plastic_states)
        {
            return false;
        }
        let mut fresh = Links {
            nodes: self.nodes.clone(),
            classes: Vec::new(),
            class: Vec::new(),
            springs: Vec::new(),
            spring: Vec::new(),
            state: Vec::new(),
            plastic: Vec::new(),
            loads: Vec::new(),
            node_offsets: Vec::new(),
            node_loads: Vec::new(),
            chunk_sums: Vec::new(),
        };
        fresh.index_nodes();
        // a checkpoint written before the index stopped at the last node held a row per
        // particle: the same index with the empty rows after the last node
        let total = fresh.node_loads.len() as u32;
        let (kept, after) =
            self.node_offsets.split_at(fresh.node_offsets.len().min(self.node_offsets.len()));
        // (no links: `total` is 0 and every saved offset must be 0)
        let empty_after =
            self.node_offsets.len() <= n_particles + 1 && after.iter().all(|&o| o == total);
        kept == fresh.node_offsets && empty_after && fresh.node_loads == self.node_loads
    }

    /// The stiffnesses and rest length of link `k`.
    pub fn spring_of(&self, k: usize) -> &LinkSpring {
        &self.springs[self.spring[k] as usize]
    }

    /// Normal force Fn of link `k` at its last update (N, compression positive): the force
    /// on node 2 along the link's normal, F₂·n (F₂ = Fn·n + Fs, Fs ⟂ n: the update's Fn to
    /// rounding). Zero before the first update and for a broken link.
    pub fn normal_force(&self, k: usize) -> Real {
        self.loads.get(k).map_or(0.0, |l| l.force_on_2.dot(&self.state[k].normal))
    }

    /// Elastic energy held by link `k` after its last update (J):
    /// `Fn²/2kn + |Fs|²/2ks + |Mt|²/2kt + |Mb|²/2kb` from its load and state
    /// ([`link_elastic_energy`]), with the nodes' positions `p` for the length (YADE's
    /// kinematics soften the shear by 2r/L: the length now, not at the update, which moves
    /// that term by O(v·dt/L)). Zero before the first update and for a broken link.
    pub fn elastic_energy(&self, k: usize, p: &Particles) -> Real {
        let Some(load) = self.loads.get(k) else { return 0.0 };
        let [a, b] = self.nodes[k].map(|n| n as usize);
        let length = (p.pos[b] - p.pos[a]).norm();
        let class = &self.classes[self.class[k] as usize];
        let m = &load.moment_on_2;
        link_elastic_energy(
            class,
            self.spring_of(k),
            &self.state[k],
            self.normal_force(k),
            m,
            length,
        )
    }

    /// Number of links.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether there is no link.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Number of links still holding (not broken).
    pub fn intact(&self) -> usize {
        self.state.iter().filter(|s| s.status != LinkStatus::Broken).count()
    }

    /// Updates every link from the particles' state (in parallel) and returns the step's
    /// breakage events and energy sums (summed per chunk of links, then over the chunks in
    /// order: independent of the thread count).
    pub fn update(&mut self, p: &Particles, dt: Real) -> LinkUpdate {
        self.update_in_homes(p, dt, &Homes::default())
    }

    /// [`Links::update`], the chunks of links shared among the threads by the home of each
    /// chunk's first node when `homes` cut the particles at more than one (`homes.rs`): the
    /// thread that steps a node links it. The same bits.
    pub(crate) fn update_in_homes(&mut self, p: &Particles, dt: Real, homes: &Homes) -> LinkUpdate {
        if self.loads.len() != self.nodes.len() {
            self.loads = vec![LinkLoad::default(); self.nodes.len()];
        }
        let (classes, springs) = (&self.classes, &self.springs);
        // each chunk's plastic states, or none (no plastic class: see `zero` below); a
        // plastic vector of another length is refused by `check_against` when links are
        // read, and would be cut short by the chunks' split
        assert!(self.plastic.is_empty() || self.plastic.len() == self.nodes.len());
        // one chunk's links (`plastic`: their plastic states, or none when no class is
        // plastic), its sums
        let step_chunk = |nodes: &[[u32; 2]],
                          class: &[u32],
                          spring: &[u32],
                          state: &mut [LinkState],
                          loads: &mut [LinkLoad],
                          mut plastic: Option<&mut [LinkPlastic]>| {
            let mut sums = LinkUpdate::default();
            // one zero plastic state for the chunk's links when no class is plastic: a
            // fragile link never writes it (`a_fragile_link_never_yields`)
            let mut zero = LinkPlastic::default();
            let kin_of = |k: usize| {
                let [a, b] = nodes[k].map(|n| n as usize);
                LinkKinematics {
                    x1: p.pos[a],
                    x2: p.pos[b],
                    v1: p.vel[a],
                    v2: p.vel[b],
                    w1: p.ang_vel[a],
                    w2: p.ang_vel[b],
                    q1: p.ori[a],
                    q2: p.ori[b],
                }
            };
            // four links at once on their common path (`update_link_lanes`: the scalar
            // law's bits), the scalar law for those off it and for the last few; the
            // sums added in link order either way
            let n = nodes.len();
            let mut k = 0;
            while k < n {
                // the lanes' energies, added below in link order with the others'
                let mut energy = [0.0; LANES];
                let (count, taken) = if k + LANES <= n {
                    let cls = std::array::from_fn(|j| &classes[class[k + j] as usize]);
                    let sps = std::array::from_fn(|j| &springs[spring[k + j] as usize]);
                    let four: &mut [LinkState; LANES] =
                        (&mut state[k..k + LANES]).try_into().expect("four links");
                    let at = LaneNodes {
                        pos: &p.pos,
                        vel: &p.vel,
                        ang_vel: &p.ang_vel,
                        ori: &p.ori,
                        nodes: std::array::from_fn(|j| nodes[k + j].map(|n| n as usize)),
                    };
                    let out = &mut loads[k..k + LANES];
                    let taken = update_link_lanes(cls, sps, four, &at, dt, |j, l| {
                        energy[j] = l.elastic_energy;
                        // field by field: a `LinkLoad` built whole was assembled on the
                        // stack by small stores and copied by one 64-byte load, which
                        // waits for them all (a failed store forwarding: a fifth of the
                        // links stage of the net twin)
                        let out = &mut out[j];
                        out.force_on_2 = l.force_on_2;
                        out.lever_torque = l.lever_torque;
                        out.moment_on_2 = l.moment_on_2;
                    });
                    (LANES, taken)
                } else {
                    (1, 0)
                };
                for j in 0..count {
                    if taken & (1 << j) != 0 {
                        // (no event, nothing dissipated: the sum would gain +0, which
                        // changes no bit of a sum started at +0, never −0)
                        sums.elastic_energy += energy[j];
                        continue;
                    }
                    let i = k + j;
                    let kin = kin_of(i);
                    let cl = &classes[class[i] as usize];
                    let pl = match plastic.as_deref_mut() {
                        Some(pl) => &mut pl[i],
                        None => &mut zero,
                    };
                    let sp = &springs[spring[i] as usize];
                    let f = update_link_parts(cl, sp, &mut state[i], pl, &kin, dt);
                    match f.event {
                        LinkEvent::BrokeInTension | LinkEvent::Separated => sums.events.broken += 1,
                        LinkEvent::LostCohesion => sums.events.decohered += 1,
                        LinkEvent::None => {}
                    }
                    sums.elastic_energy += f.elastic_energy;
                    sums.dissipated += f.dissipated.total();
                    loads[i] = LinkLoad {
                        force_on_2: f.force_on_2,
                        lever_torque: f.lever_torque,
                        moment_on_2: f.twist_moment + f.bending_moment,
                    };
                }
                k += count;
            }
            sums
        };
        if self.nodes.len() <= CHUNK {
            // one chunk (a small structure): on this thread, without a parallel dispatch
            let plastic = (!self.plastic.is_empty()).then_some(&mut self.plastic[..]);
            let (state, loads) = (&mut self.state[..], &mut self.loads[..]);
            let sums = step_chunk(&self.nodes, &self.class, &self.spring, state, loads, plastic);
            self.chunk_sums.clear();
            self.chunk_sums.push(sums);
        } else {
            let chunks = self.nodes.len().div_ceil(CHUNK);
            self.chunk_sums.clear();
            self.chunk_sums.resize(chunks, LinkUpdate::default());
            let plastic = (!self.plastic.is_empty()).then_some(&mut self.plastic[..]);
            let all = LinkChunks {
                nodes: &self.nodes,
                class: &self.class,
                spring: &self.spring,
                state: &mut self.state,
                loads: &mut self.loads,
                plastic,
                sums: &mut self.chunk_sums,
            };
            let in_chunks = |l: LinkChunks<'_>| {
                let chunks = l.sums.len();
                let plastic = match l.plastic {
                    None => Either::Left((0..chunks).into_par_iter().map(|_| None)),
                    Some(p) => Either::Right(p.par_chunks_mut(CHUNK).map(Some)),
                };
                (
                    l.nodes.par_chunks(CHUNK),
                    l.class.par_chunks(CHUNK),
                    l.spring.par_chunks(CHUNK),
                    l.state.par_chunks_mut(CHUNK),
                    l.loads.par_chunks_mut(CHUNK),
                    l.sums.par_iter_mut(),
                )
                    .into_par_iter()
                    .zip(plastic)
                    .with_max_len(MAX_CHUNKS_PER_TASK)
                    .for_each(
                        |((nodes, class, spring, state, loads, sums), plastic)| {
                            *sums = step_chunk(nodes, class, spring, state, loads, plastic);
                        },
                    );
            };
            let n = self.nodes.len();
            // by the home of each chunk's first node
            let shared = (homes.shares(p.len()) && homes.len() == p.len()).then_some(homes);
            let home = |c: usize| homes.home_of(self.nodes[c * CHUNK][0] as usize);
            let runs = chunk_home_runs(n, CHUNK, shared, home);
            by_runs(all, n, runs, &|_, l| in_chunks(l));
        }
        self.chunk_sums.iter().fold(LinkUpdate::default(), |a, c| LinkUpdate {
            events: LinkEvents {
                broken: a.events.broken + c.events.broken,
                decohered: a.events.decohered + c.events.decohered,
            },
            elastic_energy: a.elastic_energy + c.elastic_energy,
            dissipated: a.dissipated + c.dissipated,
        })
    }

    /// Adds the last update's loads to the per-particle `force` and `torque` sums, each
    /// node's in link order: for a structure of one chunk (a net, a cantilever) link after
    /// link on this thread ([`Links::add_loads_in_link_order`]), where the per-node sum's
    /// index and dispatch cost a small scene more than its additions; else node by node in
    /// parallel ([`Links::add_loads_per_node`]). The same bits either way, whatever the
    /// number of threads.
    pub fn add_loads(&self, force: &mut [Vec3], torque: &mut [Vec3]) {
        self.add_loads_in_homes(force, torque, &Homes::default());
    }

    /// [`Links::add_loads`], the nodes shared among the threads by the step's `homes` when
    /// they cut the particles at more than one (`homes.rs`).
    pub(crate) fn add_loads_in_homes(
        &self,
        force: &mut [Vec3],
        torque: &mut [Vec3],
        homes: &Homes,
    ) {
        let rows = self.node_offsets.len().saturating_sub(1);
        if self.loads.len() <= CHUNK && rows <= force.len() && rows <= torque.len() {
            self.add_loads_in_link_order(force, torque);
        } else {
            self.add_loads_per_node(force, torque, homes);
        }
    }

    /// [`Links::add_loads`] link after link: each node's loads come in link order, as the
    /// per-node sum adds them (node 1 takes F·(−1) = −F and L + M·(−1) = L − M, node 2
    /// F·1 and L + M·1: that sum's operations). Every node of a link must have its place in
    /// `force` and `torque`.
    fn add_loads_in_link_order(&self, force: &mut [Vec3], torque: &mut [Vec3]) {
        for (l, &[a, b]) in self.loads.iter().zip(&self.nodes) {
            let (a, b) = (a as usize, b as usize);
            force[a] += l.force_on_2 * -1.0;
            torque[a] += l.lever_torque + l.moment_on_2 * -1.0;
            force[b] += l.force_on_2 * 1.0;
            torque[b] += l.lever_torque + l.moment_on_2 * 1.0;
        }
    }

    /// [`Links::add_loads`] node by node in link order (CSR), in parallel over the nodes: per
    /// home of `homes`, when they cut these particles, else over all.
    fn add_loads_per_node(&self, force: &mut [Vec3], torque: &mut [Vec3], homes: &Homes) {
        let n = self.node_offsets.len().saturating_sub(1).min(force.len()).min(torque.len());
        let nodes = |first: usize, f: &mut [Vec3], t: &mut [Vec3]| {
            (f, t)
                .into_par_iter()
                .enumerate()
                .with_min_len(CHUNK)
                .with_max_len(MAX_CHUNKS_PER_TASK * CHUNK)
                .for_each(|(k, (f, t))| {
                    let i = first + k;
                    let (s, e) = (self.node_offsets[i] as usize, self.node_offsets[i + 1] as usize);
                    // summed in registers, stored once (the same additions in the same order)
                    let (mut fi, mut ti) = (*f, *t);
                    for &code in &self.node_loads[s..e] {
                        let l = &self.loads[(code / 2) as usize];
                        // node 1 (even code) takes −F and L − M, node 2 F and L + M: as a sign
                        // s = ∓1 and no branch (which node a link's load goes to is as good as
                        // random from one to the next); F·(−1) = −F exactly, and x + (−y) is
                        // x − y, so the sums have the bits of the two-way form
                        let s = Real::from(code % 2) * 2.0 - 1.0;
                        fi += l.force_on_2 * s;
                        ti += l.lever_torque + l.moment_on_2 * s;
                    }
                    (*f, *t) = (fi, ti);
                });
        };
        let (force, torque) = (&mut force[..n], &mut torque[..n]);
        if homes.shares(n) {
            let mut runs = Runs::new();
            homes.item_runs(n, STEP_CHUNK, &mut runs);
            in_homes((force, torque), &runs, n, homes.count(), &|pieces: Pieces<Sums<'_>>| {
                for (first, (f, t)) in pieces {
                    nodes(first, f, t);
                }
            });
        } else {
            nodes(0, force, torque);
        }
    }
}

/// Links in whole chunks of [`CHUNK`]: their tables, their plastic states (none when no
/// class is plastic) and their chunks' sums.
struct LinkChunks<'a> {
    nodes: &'a [[u32; 2]],
    class: &'a [u32],
    spring: &'a [u32],
    state: &'a mut [LinkState],
    loads: &'a mut [LinkLoad],
    plastic: Option<&'a mut [LinkPlastic]>,
    sums: &'a mut [LinkUpdate],
}

impl Piece for LinkChunks<'_> {
    /// The first `at` links (a multiple of [`CHUNK`], or all) and the others.
    fn split_at(self, at: usize) -> (Self, Self) {
        let (nodes, nodes_b) = self.nodes.split_at(at);
        let (class, class_b) = self.class.split_at(at);
        let (spring, spring_b) = self.spring.split_at(at);
        let (state, state_b) = self.state.split_at_mut(at);
        let (loads, loads_b) = self.loads.split_at_mut(at);
        let (plastic, plastic_b) = match self.plastic {
            Some(p) => {
                let (a, b) = p.split_at_mut(at);
                (Some(a), Some(b))
            }
            None => (None, None),
        };
        let (sums, sums_b) = self.sums.split_at_mut(at.div_ceil(CHUNK));
        let a = LinkChunks { nodes, class, spring, state, loads, plastic, sums };
        let b = LinkChunks {
            nodes: nodes_b,
            class: class_b,
            spring: spring_b,
            state: state_b,
            loads: loads_b,
            plastic: plastic_b,
            sums: sums_b,
        };
        (a, b)
    }
}

#[cfg(test)]
#[path = "links_tests.rs"]
mod tests;
