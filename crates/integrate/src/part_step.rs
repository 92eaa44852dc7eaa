//! The step of the candidate pairs in parts (`pair_parts.rs`,
//! `NeighbourList::update_in_parts`): the parts' runs in parallel, each part's chunks in order on
//! one thread, which sums as they come the loads on the particles it owns and sums
//! ([`SumBy::Part`], and [`SumBy::PartThenWalls`] but for its walls) and keeps the others'
//! loads, in pair order, in one list per owner part ([`DeferredLoad`]); then, in parallel
//! over the owners, each owner's lists added to its particles in part order
//! ([`add_deferred`]). Per particle that is every load in key order: the part's sum first
//! for one that sums in its part (its other loads are walls', whose pairs come last), from
//! zero for the others.

use crate::contact::BirthReport;
use crate::neighbours::{NeighbourList, PairContact};
use crate::pair_chunk::{EmitLoads, PAIR_CHUNK};
use crate::pair_keys::ContactKey;
use crate::pair_parts::{PairParts, SumBy};
use crate::pair_passes::{
    chunks_for, trim, ChunkOut, DeferredLoad, PairScratch, PassInputs, ToOutcomes,
};
use crate::pair_store::{BlockContacts, BLOCK};
use flexdem_elements::virtual_sphere::{Feature, Kinematics, NodeLoad};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};

/// The parts' [`EmitLoads`]: the loads of a pair on a particle its part sums added to it as
/// they come, on one summed after the parts
/// ([`SumBy::PartThenWalls`]'s walls' loads, [`SumBy::Deferred`]'s) kept in the list of the
/// particle's owner, and the whole pair's outcome kept when the gather sums one of its
/// particles ([`SumBy::Gather`]).
struct ToParts<'a> {
    /// The part's particles, from `first_particle`.
    force: &'a mut [Vec3],
    torque: &'a mut [Vec3],
    first_particle: usize,
    parts: &'a PairParts,
    /// The part's lists, one per owner part.
    deferred: &'a mut [Vec<DeferredLoad>],
    kept: ToOutcomes<'a>,
}

impl ToParts<'_> {
    /// Load `l` of particle `node`, summed as `by` says (the gather's: nothing here).
    #[inline(always)]
    fn take(&mut self, node: u32, by: SumBy, l: &NodeLoad) {
        match by {
            SumBy::Part => add_load(self.force, self.torque, self.first_particle, l),
            SumBy::PartThenWalls | SumBy::Deferred => {
                let owner = self.parts.owner(node as usize);
                let load = DeferredLoad { particle: node, force: l.force, torque: l.torque };
                self.deferred[owner].push(load);
            }
            SumBy::Gather => {}
        }
    }
}

/// Load `l` added to its particle's sums, those of the particles from `first_particle`.
#[inline(always)]
fn add_load(force: &mut [Vec3], torque: &mut [Vec3], first_particle: usize, l: &NodeLoad) {
    let k = l.node as usize - first_particle;
    force[k] += l.force;
    torque[k] += l.torque;
}

/// [`ToParts`] for a chunk whose pairs are all of two spheres its part sums
/// (`PairParts::summed_in_part`): each load added to its particle as it comes, body 1's then
/// body 2's (what [`ToParts`] does with them).
struct ToPart<'a> {
    force: &'a mut [Vec3],
    torque: &'a mut [Vec3],
    first_particle: usize,
}

impl EmitLoads for ToPart<'_> {
    #[inline(always)]
    fn emit(&mut self, _: usize, key: &ContactKey, loads: &[NodeLoad; 2]) {
        debug_assert!(matches!(key, (Feature::Particle(_), Feature::Particle(_))), "{key:?}");
        for l in loads {
            add_load(self.force, self.torque, self.first_particle, l);
        }
    }
}

impl EmitLoads for ToParts<'_> {
    #[inline(always)]
    fn emit(&mut self, i: usize, key: &ContactKey, loads: &[NodeLoad; 2]) {
        let sum_by = self.parts.sum_by();
        match *key {
            (Feature::Particle(a), Feature::Particle(b)) => {
                debug_assert_eq!((loads[0].node, loads[1].node), (a, b));
                let by = [sum_by[a as usize], sum_by[b as usize]];
                // (a PartThenWalls particle's loads from pairs of two spheres are its
                // part's: only its walls' are kept)
                let by = by.map(|s| if s == SumBy::PartThenWalls { SumBy::Part } else { s });
                // body 1's, then body 2's, as the one-thread pass adds them
                self.take(a, by[0], &loads[0]);
                self.take(b, by[1], &loads[1]);
                if by.contains(&SumBy::Gather) {
                    self.kept.emit(i, key, loads);
                }
            }
            (Feature::Wall(_), Feature::Particle(b)) => {
                debug_assert_eq!(loads[1].node, b);
                let by = sum_by[b as usize];
                debug_assert!(by != SumBy::Part, "a particle that touches a wall");
                self.take(b, by, &loads[1]);
                if by == SumBy::Gather {
                    self.kept.emit(i, key, loads);
                }
            }
            _ => self.kept.emit(i, key, loads),
        }
    }
}

impl NeighbourList {
    /// [`NeighbourList::update`] in the parts of `parts` (`pair_parts.rs`, `part_step.rs`;
    /// `room` the memory of the list of their inputs):
    /// the parts' runs in parallel, each part's chunks in order on one thread, then the loads
    /// they kept added. Writes in `force` and `torque` (one entry per particle) the sum of every
    /// particle's pair loads in key order, except those the gather sums (`gather.rs`,
    /// [`SumBy::Gather`](crate::pair_parts::SumBy), zero here), whose pairs' outcomes it
    /// keeps. The same contacts, records and sums as `update`.
    #[allow(clippy::too_many_arguments, reason = "update's inputs, the parts and the sums")]
    pub(crate) fn update_in_parts(
        &mut self,
        model: &Model,
        dt: Real,
        scratch: &mut PairScratch,
        ended_dissipation: &mut Real,
        (parts, room): (&PairParts, &mut PartsRoom),
        force: &mut [Vec3],
        torque: &mut [Vec3],
    ) -> BirthReport {
        let k = Kinematics::of(&model.particles);
        let pass = PassInputs::new(model, &k, self.keys.first_wall(), dt);
        scratch.position.resize(self.keys.len(), 0);
        let chunks = chunks_for(&mut scratch.chunks, self.keys.len());
        let lists = parts.len() * parts.owners();
        if scratch.deferred.len() != lists {
            scratch.deferred.resize_with(lists, Vec::new);
        }
        let shared = PartShared { pass, parts };
        let inputs = PartInputs {
            ids: self.keys.ids(),
            slots: &mut self.slots,
            blocks: &mut self.blocks,
            positions: &mut scratch.position,
            chunks,
            force: &mut *force,
            torque: &mut *torque,
            deferred: &mut scratch.deferred,
        };
        step_in_runs(&shared, parts, inputs, room);
        add_deferred(parts, force, torque, &scratch.deferred);
        scratch.deferred.iter_mut().for_each(trim);
        self.finish_update(scratch, ended_dissipation)
    }
}

/// The memory of the list of the parts' inputs, kept from step to step (in the contact
/// pipeline): an empty list, so that a step allocates none.
#[derive(Default)]
pub(crate) struct PartsRoom(Vec<(usize, PartInputs<'static>)>);

impl Clone for PartsRoom {
    /// Empty: a copy's first step makes its own.
    fn clone(&self) -> Self {
        PartsRoom::default()
    }
}

impl std::fmt::Debug for PartsRoom {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "PartsRoom(room for {})", self.0.capacity())
    }
}

/// What every part reads.
struct PartShared<'a> {
    pass: PassInputs<'a>,
    parts: &'a PairParts,
}

/// What some consecutive parts write: their pairs' ids, slots, blocks, outcomes' positions
/// and chunks, their particles' sums and their lists of kept loads (one per owner part for
/// each of these parts).
#[derive(Default)]
struct PartInputs<'a> {
    ids: &'a [(u32, u32)],
    slots: &'a mut [u32],
    blocks: &'a mut [BlockContacts<PairContact>],
    positions: &'a mut [u32],
    chunks: &'a mut [ChunkOut],
    force: &'a mut [Vec3],
    torque: &'a mut [Vec3],
    deferred: &'a mut [Vec<DeferredLoad>],
}

impl PartInputs<'_> {
    /// These parts' inputs split before their `chunk`-th chunk, `particle`-th particle and
    /// `part`-th part (`owners` lists of kept loads each).
    fn split(self, chunk: usize, particle: usize, part: usize, owners: usize) -> (Self, Self) {
        let pairs = (chunk * PAIR_CHUNK).min(self.ids.len());
        let blocks = (chunk * (PAIR_CHUNK / BLOCK)).min(self.blocks.len());
        let (ids, ids_b) = self.ids.split_at(pairs);
        let (slots, slots_b) = self.slots.split_at_mut(pairs);
        let (positions, positions_b) = self.positions.split_at_mut(pairs);
        let (blocks, blocks_b) = self.blocks.split_at_mut(blocks);
        let (chunks, chunks_b) = self.chunks.split_at_mut(chunk);
        let (force, force_b) = self.force.split_at_mut(particle);
        let (torque, torque_b) = self.torque.split_at_mut(particle);
        let (deferred, deferred_b) = self.deferred.split_at_mut(part * owners);
        let a = PartInputs { ids, slots, blocks, positions, chunks, force, torque, deferred };
        let b = PartInputs {
            ids: ids_b,
            slots: slots_b,
            blocks: blocks_b,
            positions: positions_b,
            chunks: chunks_b,
            force: force_b,
            torque: torque_b,
            deferred: deferred_b,
        };
        (a, b)
    }
}

/// Steps the parts of `parts` (whose inputs are `inputs`, in part order) by their runs
/// ([`PairParts::runs`], [`step_runs`]). `room` is the list of the parts' inputs kept from
/// step to step, empty: its memory serves again (the inputs borrow this step's buffers).
fn step_in_runs(
    s: &PartShared<'_>,
    parts: &PairParts,
    inputs: PartInputs<'_>,
    room: &mut PartsRoom,
) {
    let (home, runs) = parts.runs();
    let mut each: Vec<(usize, PartInputs<'_>)> = reuse(std::mem::take(&mut room.0));
    let mut rest = inputs;
    for p in 0..parts.len() {
        let (chunks, particles) = (parts.chunks(p).len(), parts.particles(p).len());
        let (a, b) = rest.split(chunks, particles, 1, parts.owners());
        each.push((p, a));
        rest = b;
    }
    // by run, then in part order (no allocation: the keys are distinct)
    each.sort_unstable_by_key(|&(p, _)| (home[p], p));
    step_runs(s, runs, &mut each);
    each.clear();
    room.0 = reuse(each);
}

/// An empty `Vec` of another lifetime with the memory of `v` (emptied): the same layout, so
/// the standard library collects in place and allocates nothing (its in-place collect is not
/// a documented guarantee; without it this allocates, nothing worse: the allocation test at
/// 2 threads counted 0.095 allocations per step of the packing of 1000 spheres, as at one
/// thread).
fn reuse<'b>(mut v: Vec<(usize, PartInputs<'_>)>) -> Vec<(usize, PartInputs<'b>)> {
    v.clear();
    v.into_iter().map(|_| unreachable!("emptied")).collect()
}

/// Steps the runs of parts `runs` (where each starts in `parts`, then the end; a run is a
/// spheres' part and the walls' parts that go with it): halved, the halves in parallel, each
/// run's parts in order on one thread.
fn step_runs(s: &PartShared<'_>, runs: &[usize], parts: &mut [(usize, PartInputs<'_>)]) {
    let count = runs.len() - 1;
    if count <= 1 {
        for (p, inputs) in parts.iter_mut() {
            step_part(s, *p, std::mem::take(inputs));
        }
        return;
    }
    let mid = count / 2;
    let (a, b) = parts.split_at_mut(runs[mid] - runs[0]);
    rayon::join(|| step_runs(s, &runs[..=mid], a), || step_runs(s, &runs[mid..], b));
}

/// Steps part `p` (its inputs: `inputs`) on this thread: its particles' sums zeroed and its
/// lists emptied, then its chunks in order, each as `update` steps it, with the loads given
/// to [`ToParts`].
fn step_part(s: &PartShared<'_>, p: usize, inputs: PartInputs<'_>) {
    let PartInputs { ids, slots, blocks, positions, chunks, force, torque, deferred } = inputs;
    force.fill(Vec3::zeros());
    torque.fill(Vec3::zeros());
    deferred.iter_mut().for_each(Vec::clear);
    let (first_chunk, first_particle) = (s.parts.chunks(p).start, s.parts.particles(p).start);
    let each = ids.chunks(PAIR_CHUNK).zip(slots.chunks_mut(PAIR_CHUNK));
    let each =
        each.zip(blocks.chunks_mut(PAIR_CHUNK / BLOCK)).zip(positions.chunks_mut(PAIR_CHUNK));
    for (c, ((((ids, slots), blocks), positions), out)) in each.zip(chunks).enumerate() {
        let c = first_chunk + c;
        if s.parts.summed_in_part(c) {
            // (no particle's way of summing to look at, and no outcome to keep)
            let mut to = ToPart { force: &mut *force, torque: &mut *torque, first_particle };
            s.pass.step_chunk(c, ids, slots, blocks, &mut out.book, &mut to);
            continue;
        }
        let kept = ToOutcomes { positions, outcomes: &mut out.outcomes, base: c * PAIR_CHUNK };
        let (force, torque, deferred) = (&mut *force, &mut *torque, &mut *deferred);
        let parts = s.parts;
        let mut to = ToParts { force, torque, first_particle, parts, deferred, kept };
        s.pass.step_chunk(c, ids, slots, blocks, &mut out.book, &mut to);
    }
}

/// Adds to `force` and `torque` (one entry per particle) the loads the parts kept
/// (`deferred`: part `q`'s list for owner `o` at `q·owners + o`), in parallel over the owner
/// parts, each owner's lists in part order, each list in its order: the loads in key order.
fn add_deferred(
    parts: &PairParts,
    force: &mut [Vec3],
    torque: &mut [Vec3],
    deferred: &[Vec<DeferredLoad>],
) {
    add_owners(parts, 0..parts.owners(), force, torque, deferred);
}

/// [`add_deferred`] for owners `owners` (consecutive), whose particles' sums are `force` and
/// `torque`: halved, the halves in parallel.
fn add_owners(
    parts: &PairParts,
    owners: std::ops::Range<usize>,
    force: &mut [Vec3],
    torque: &mut [Vec3],
    deferred: &[Vec<DeferredLoad>],
) {
    if owners.len() > 1 {
        let (first, mid) = (owners.start, owners.start + owners.len() / 2);
        let at = parts.particles(mid).start - parts.particles(first).start;
        let (force, force_b) = force.split_at_mut(at);
        let (torque, torque_b) = torque.split_at_mut(at);
        rayon::join(
            || add_owners(parts, first..mid, force, torque, deferred),
            || add_owners(parts, mid..owners.end, force_b, torque_b, deferred),
        );
        return;
    }
    let Some(o) = owners.clone().next() else { return };
    let first_particle = parts.particles(o).start;
    for q in 0..parts.len() {
        for l in &deferred[q * parts.owners() + o] {
            let k = l.particle as usize - first_particle;
            force[k] += l.force;
            torque[k] += l.torque;
        }
    }
}
