//! The step of every candidate pair of the neighbour list (`neighbours.rs`): in parallel
//! (`update`, its outcomes kept per chunk for the loads' sum, `gather.rs`), in parts
//! (`part_step.rs`, with this file's chunk step and buffers) or in one pass on this thread
//! (`update_in_order`, the loads handed on as they come). All sum the step's energy terms
//! per chunk of [`PAIR_CHUNK`] candidates, in pair order, then over the chunks in order: the
//! same additions whichever pass ran, so the same bits whatever the number of threads.

use crate::contact::BirthReport;
use crate::dashpots::pair_dashpot_power;
use crate::fresh_shares::PairShares;
use crate::neighbours::{AppliedForce, NeighbourList, PairContact, Sink};
use crate::pair_book::{ChunkBook, ChunkSums};
use crate::pair_chunk::{ChunkPass, EmitLoads, PAIR_CHUNK};
use crate::pair_keys::ContactKey;
use crate::pair_store::{BlockContacts, BLOCK, NO_CONTACT};
use crate::parallel::MAX_CHUNKS_PER_TASK;
use flexdem_elements::virtual_sphere::{Feature, Kinematics, NodeLoad};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use rayon::prelude::*;

/// The loads of a touching pair at the parallel update, kept for their sum (`gather.rs`):
/// the force on body 2 (body 1's is its opposite) and the torques on the two bodies; 72
/// bytes where its two [`NodeLoad`]s are 112 (the nodes are the key's).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairLoads {
    force_on_2: Vec3,
    torques: [Vec3; 2],
}

impl PairLoads {
    /// The loads of a pair's two node loads (body 1's force is −body 2's, exactly).
    #[inline]
    pub(crate) fn of_loads(loads: &[NodeLoad; 2]) -> Self {
        debug_assert_eq!(loads[0].force, -loads[1].force);
        PairLoads { force_on_2: loads[1].force, torques: [loads[0].torque, loads[1].torque] }
    }

    /// Body `side`'s load (0: body 1, 1: body 2) on node `node`.
    #[inline]
    fn load(&self, side: usize, node: u32) -> NodeLoad {
        let force = if side == 0 { -self.force_on_2 } else { self.force_on_2 };
        NodeLoad { node, force, torque: self.torques[side] }
    }
}

/// A load that a part of the update in parts keeps for a particle it does not sum
/// (`part_step.rs`; 56 bytes).
#[derive(Clone, Copy, Debug)]
pub(crate) struct DeferredLoad {
    pub(crate) particle: u32,
    pub(crate) force: Vec3,
    pub(crate) torque: Vec3,
}

/// The parallel update's [`EmitLoads`]: each touching pair's loads kept in its chunk's
/// outcomes, and where, for their sum per particle (`gather.rs`).
pub(crate) struct ToOutcomes<'a> {
    pub(crate) positions: &'a mut [u32],
    pub(crate) outcomes: &'a mut Vec<(u32, PairLoads)>,
    pub(crate) base: usize,
}

impl EmitLoads for ToOutcomes<'_> {
    #[inline(always)]
    fn emit(&mut self, i: usize, _: &ContactKey, loads: &[NodeLoad; 2]) {
        self.positions[i] = self.outcomes.len() as u32;
        self.outcomes.push(((self.base + i) as u32, PairLoads::of_loads(loads)));
    }
}

/// The one-pass update's [`EmitLoads`]: each touching pair's key, then its particles'
/// loads, to the sink.
struct ToSink<'a, F>(&'a mut F);

impl<F: FnMut(Sink<'_>)> EmitLoads for ToSink<'_, F> {
    #[inline(always)]
    fn emit(&mut self, _: usize, key: &ContactKey, loads: &[NodeLoad; 2]) {
        (self.0)(Sink::Before(key));
        if !matches!(key.0, Feature::Wall(_)) {
            (self.0)(Sink::Load(&loads[0]));
        }
        (self.0)(Sink::Load(&loads[1]));
    }
}

/// What [`NeighbourList::load_view`] reads: the slices taken once, where a call per load
/// through the list and its scratch reloaded their pointers each time.
pub(crate) struct PairLoadView<'a> {
    slots: &'a [u32],
    position: &'a [u32],
    chunks: &'a [ChunkOut],
}

impl PairLoadView<'_> {
    /// Body `side`'s node load of candidate pair `n`, if the pair touches (its node is not
    /// filled in: the caller sums into the particle it asked for).
    #[inline]
    pub(crate) fn load(&self, n: usize, side: usize) -> Option<NodeLoad> {
        if self.slots[n] == NO_CONTACT {
            return None;
        }
        let position = self.position[n] as usize;
        Some(self.chunks[n / PAIR_CHUNK].outcomes[position].1.load(side, u32::MAX))
    }
}

/// One chunk's part of the last update.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChunkOut {
    /// The loads of its pairs that touch after the update, with their index, in order (the
    /// parallel update only).
    pub(crate) outcomes: Vec<(u32, PairLoads)>,
    /// What its pairs added to the step's records.
    pub(crate) book: ChunkBook,
}

/// Buffers of [`NeighbourList::update`] (nothing here is saved).
#[derive(Clone, Debug, Default)]
pub(crate) struct PairScratch {
    /// Per chunk of [`PAIR_CHUNK`] candidates, its part of the last update.
    pub(crate) chunks: Vec<ChunkOut>,
    /// Indices of the pairs that started touching at the last update.
    pub(crate) fresh: Vec<usize>,
    /// The chunks of the last update (the first ones of `chunks`; those past them hold
    /// records of an update of more candidates).
    used: usize,
    /// Per candidate pair, where its outcome is in its chunk's list at the last parallel
    /// update (written for the pairs it stepped only).
    pub(crate) position: Vec<u32>,
    /// The generation of the candidates of the last update (`NeighbourList::generation`;
    /// 0 before any): its records are theirs.
    generation: u64,
    /// The loads the parts kept for the particles they do not sum at the last update in
    /// parts (`part_step.rs`): part `q`'s for the particles of part `o` at `q·owners + o`.
    pub(crate) deferred: Vec<Vec<DeferredLoad>>,
}

/// What the last update of a neighbour list gave besides its contacts' states, for the
/// forces of its touching pairs: the dashpots' force of each pair they pushed, and the
/// force applied on each pair of a wall. Empty when the scratch's last update was of other
/// candidates than the list's (a rebuild, a clear or a load since; none in a step, which
/// updates the pairs after its rebuild): then each pair's force is its springs'.
pub(crate) struct LastUpdate<'a> {
    chunks: &'a [ChunkOut],
}

impl LastUpdate<'_> {
    /// The force the last update applied to touching pair `n` (`c`, its contact): a wall
    /// pair's as its law gave it, else [`PairContact::applied`] with the dashpots' record.
    pub(crate) fn applied(&self, c: &PairContact, n: usize) -> AppliedForce {
        let Some(book) = self.chunks.get(n / PAIR_CHUNK).map(|c| &c.book) else {
            return c.applied(None);
        };
        if let Ok(w) = book.walls.binary_search_by_key(&(n as u32), |w| w.0) {
            return book.walls[w].1;
        }
        let record = book.pushed.binary_search_by_key(&(n as u32), |r| r.index).ok();
        c.applied(record.map(|r| &book.pushed[r].force))
    }

    /// The touching pairs of a wall at the last update, in key order: each one's index and
    /// the force its law applied.
    pub(crate) fn walls(&self) -> impl Iterator<Item = &(u32, AppliedForce)> + '_ {
        self.chunks.iter().flat_map(|c| &c.book.walls)
    }
}

/// Gives back a buffer's room when it is more than four times its contents (and more than
/// 4 KiB), down to twice (at least 2 KiB's worth of places: 512 of `u32`): buffers kept
/// from step to step (no allocation in a steady run) also keep the room of a step unlike
/// the others. The first step of a packing makes all its contacts at once, and the lists of
/// fresh pairs held 26 bytes per sphere for the rest of the run (with a floor of 1024 places
/// whatever their size, the new pairs' stiffness shares, 152 bytes each, kept 220 bytes per
/// sphere of the packing of 10⁵ spheres in its 75 chunks of 4096 pairs).
pub(crate) fn trim<T>(buffer: &mut Vec<T>) {
    let floor = (2048 / std::mem::size_of::<T>().max(1)).max(1);
    let room = 2 * buffer.len().max(floor);
    if buffer.capacity() > 2 * room {
        buffer.shrink_to(room);
    }
}

/// The chunks of `candidates` pairs, cleared (their buffers kept).
pub(crate) fn chunks_for(chunks: &mut Vec<ChunkOut>, candidates: usize) -> &mut [ChunkOut] {
    let used = candidates.div_ceil(PAIR_CHUNK);
    if chunks.len() < used {
        chunks.resize_with(used, ChunkOut::default);
    }
    for c in &mut chunks[..used] {
        c.outcomes.clear();
        c.book.fresh.clear();
        c.book.fresh_shares.clear();
        c.book.pushed.clear();
        c.book.walls.clear();
        c.book.sums = ChunkSums::default();
    }
    &mut chunks[..used]
}

impl PairScratch {
    /// The node shares of the pairs that started touching at the last update, in the order
    /// of `fresh`: read from the chunks' records where their steps wrote them (gathered into
    /// one array, they were 137 kB to copy at a step of the packing of 10⁵ spheres settling).
    pub(crate) fn fresh_shares(
        &self,
    ) -> impl Iterator<Item = &PairShares> + Clone + Send + Sync + '_ {
        self.chunks[..self.used.min(self.chunks.len())].iter().flat_map(|c| &c.book.fresh_shares)
    }

    /// The step's sums from the chunks', in chunk order: the report, the ended pairs'
    /// friction added to `ended_dissipation`, and the fresh pairs gathered in order (their
    /// shares stay in the chunks: [`PairScratch::fresh_shares`]).
    fn totals(&mut self, used: usize, ended_dissipation: &mut Real) -> (BirthReport, ChunkSums) {
        let mut total = ChunkSums::default();
        self.fresh.clear();
        self.used = used;
        for c in &mut self.chunks[..used] {
            c.book.sums.add_to(&mut total);
            self.fresh.extend_from_slice(&c.book.fresh);
            trim(&mut c.book.fresh);
            trim(&mut c.book.fresh_shares);
            trim(&mut c.book.pushed);
            trim(&mut c.book.walls);
            trim(&mut c.outcomes);
        }
        trim(&mut self.fresh);
        *ended_dissipation += total.ended_dissipation;
        let report = BirthReport {
            born_deep: total.born_deep,
            born_energy: total.born_energy,
            late_energy: total.late_energy,
            released: total.released,
        };
        (report, total)
    }
}

impl NeighbourList {
    /// One step of every pair (in parallel): whether it touches; a new contact made as the
    /// general pipeline makes it (`contacts::new_contact`) with its birth accounted for; an
    /// ended one's friction, elastic and shear energy accounted for; then the contact law
    /// and the node loads of every touching pair, into the scratch's chunks (the outcomes of
    /// the pairs that are not far apart, in order, per chunk), with the records of the pairs
    /// whose dashpots pushed. `dt` is the step just done (the contact law's and the births'
    /// step). Returns what the births and ends moved the energy balance by, and adds the
    /// ended pairs' friction to `ended_dissipation`.
    pub(crate) fn update(
        &mut self,
        model: &Model,
        dt: Real,
        scratch: &mut PairScratch,
        ended_dissipation: &mut Real,
    ) -> BirthReport {
        let k = Kinematics::of(&model.particles);
        let pass = PassInputs::new(model, &k, self.keys.first_wall(), dt);
        scratch.position.resize(self.keys.len(), 0);
        let chunks = chunks_for(&mut scratch.chunks, self.keys.len());
        self.keys
            .ids()
            .par_chunks(PAIR_CHUNK)
            .zip(self.slots.par_chunks_mut(PAIR_CHUNK))
            .zip(self.blocks.par_chunks_mut(PAIR_CHUNK / BLOCK))
            .zip(scratch.position.par_chunks_mut(PAIR_CHUNK))
            .zip(chunks.par_iter_mut())
            .enumerate()
            .with_max_len(MAX_CHUNKS_PER_TASK)
            .for_each(|(c, ((((ids, slots), blocks), positions), out))| {
                let base = c * PAIR_CHUNK;
                let mut to = ToOutcomes { positions, outcomes: &mut out.outcomes, base };
                pass.step_chunk(c, ids, slots, blocks, &mut out.book, &mut to);
            });
        self.finish_update(scratch, ended_dissipation)
    }

    /// [`NeighbourList::update`] in one pass on this thread, giving `sink` each touching
    /// pair's key (`Sink::Before`), then its node loads (`Sink::Load`), in key order: the
    /// loads are summed as they come (no buffer), with the same results (and the records of
    /// the pairs whose dashpots pushed, as `update` keeps them).
    pub(crate) fn update_in_order(
        &mut self,
        model: &Model,
        dt: Real,
        scratch: &mut PairScratch,
        ended_dissipation: &mut Real,
        mut sink: impl FnMut(Sink<'_>),
    ) -> BirthReport {
        let k = Kinematics::of(&model.particles);
        let pass = PassInputs::new(model, &k, self.keys.first_wall(), dt);
        let chunks = chunks_for(&mut scratch.chunks, self.keys.len());
        let each = self.keys.ids().chunks(PAIR_CHUNK).zip(self.slots.chunks_mut(PAIR_CHUNK));
        let each = each.zip(self.blocks.chunks_mut(PAIR_CHUNK / BLOCK)).zip(chunks.iter_mut());
        for (c, (((ids, slots), blocks), out)) in each.enumerate() {
            pass.step_chunk(c, ids, slots, blocks, &mut out.book, &mut ToSink(&mut sink));
        }
        self.finish_update(scratch, ended_dissipation)
    }

    /// What every update ends with: the step's report and sums from the chunks' (in chunk
    /// order, [`PairScratch::totals`]), the ended pairs' friction added to
    /// `ended_dissipation`, and the scratch marked as this list's.
    pub(crate) fn finish_update(
        &mut self,
        scratch: &mut PairScratch,
        ended_dissipation: &mut Real,
    ) -> BirthReport {
        let used = self.keys.len().div_ceil(PAIR_CHUNK);
        let (report, total) = scratch.totals(used, ended_dissipation);
        scratch.generation = self.generation();
        self.sums = Some((total.elastic, total.friction));
        report
    }

    /// The dashpots of the touching pairs at the last update (`update` with `damped`):
    /// `(Σ dissipated.viscous, Σ power)`, the law's own count and the power of their forces
    /// with the particles' and walls' current velocities (`dashpots::dashpot_power`; called
    /// after the kick).
    pub(crate) fn dashpot_dissipation(&self, scratch: &PairScratch, model: &Model) -> (Real, Real) {
        let (mut law, mut power) = (0.0, 0.0);
        let used = self.keys.len().div_ceil(PAIR_CHUNK).min(scratch.chunks.len());
        for d in scratch.chunks[..used].iter().flat_map(|c| &c.book.pushed) {
            law += d.viscous;
            power +=
                pair_dashpot_power(&self.keys.get(d.index as usize), &d.force, &d.moments, model);
        }
        (law, power)
    }

    /// The touching pairs after the last (parallel) update, in order: each one's index and
    /// node loads (body 1's, none for a wall, and body 2's), as `merged` picks them.
    pub(crate) fn touching_loads<'a>(
        &'a self,
        scratch: &'a PairScratch,
    ) -> impl Iterator<Item = (usize, impl Iterator<Item = NodeLoad>)> + 'a {
        let used = self.keys.len().div_ceil(PAIR_CHUNK);
        scratch.chunks[..used.min(scratch.chunks.len())].iter().flat_map(|c| &c.outcomes).map(
            move |&(n, loads)| {
                let (body_1, body_2) = self.keys.get(n as usize);
                let node = |f: Feature| match f {
                    Feature::Particle(i) => Some(i),
                    _ => None,
                };
                let sides = [node(body_1), node(body_2)];
                let each = (0..2).filter_map(move |side| Some(loads.load(side, sides[side]?)));
                (n as usize, each)
            },
        )
    }

    /// What the last update in `scratch` gave besides the contacts' states, if it was of
    /// these candidates ([`LastUpdate`]).
    pub(crate) fn last_update<'a>(&self, scratch: &'a PairScratch) -> LastUpdate<'a> {
        let used = self.keys.len().div_ceil(PAIR_CHUNK).min(scratch.chunks.len());
        let current = scratch.generation == self.generation();
        LastUpdate { chunks: if current { &scratch.chunks[..used] } else { &[] } }
    }

    /// The touching pairs' loads at the last parallel update ([`NeighbourList::update`]),
    /// for their gather per particle (`gather.rs`).
    pub(crate) fn load_view<'a>(&'a self, scratch: &'a PairScratch) -> PairLoadView<'a> {
        PairLoadView { slots: &self.slots, position: &scratch.position, chunks: &scratch.chunks }
    }

    /// Elastic energy stored at the last update.
    pub fn elastic_energy(&self) -> Real {
        self.energy_sums().0
    }

    /// Friction dissipated by the touching pairs over their lives.
    pub fn dissipated(&self) -> Real {
        self.energy_sums().1
    }

    /// `(elastic_energy(), dissipated())` in one pass over the contacts: as the last update
    /// summed them (per chunk of candidates, then over the chunks), or summed so.
    pub(crate) fn energy_sums(&self) -> (Real, Real) {
        self.sums.unwrap_or_else(|| self.chunked_energy_sums())
    }

    /// `(elastic energy, friction)` of the touching pairs, summed per chunk of
    /// [`PAIR_CHUNK`] candidates and then over the chunks, as the updates sum them.
    pub(crate) fn chunked_energy_sums(&self) -> (Real, Real) {
        let mut total = ChunkSums::default();
        for (c, chunk) in self.slots.chunks(PAIR_CHUNK).enumerate() {
            let mut sums = ChunkSums::default();
            let base = c * PAIR_CHUNK;
            let touching = (0..chunk.len()).filter_map(|i| self.contact_at(base + i));
            touching.for_each(|c| sums.add_touching(c, c.elastic_energy()));
            total.elastic += sums.elastic;
            total.friction += sums.friction;
        }
        (total.elastic, total.friction)
    }
}

/// What every chunk's step reads besides its own pairs: the model, its kinematics, the list's
/// first wall pair and the step.
#[derive(Clone, Copy)]
pub(crate) struct PassInputs<'a> {
    model: &'a Model,
    kinematics: &'a Kinematics<'a>,
    first_wall: usize,
    dt: Real,
}

impl<'a> PassInputs<'a> {
    /// The inputs of a pass over the pairs of a list whose first wall pair is `first_wall`.
    pub(crate) fn new(
        model: &'a Model,
        kinematics: &'a Kinematics<'a>,
        first_wall: usize,
        dt: Real,
    ) -> Self {
        PassInputs { model, kinematics, first_wall, dt }
    }

    /// Steps chunk `c` (its pairs' `ids`, `slots` and `blocks`), its records in `book`, its
    /// touching pairs' loads given to `emit`: the chunk's blocks tidied, then
    /// [`ChunkPass::step`].
    #[inline]
    pub(crate) fn step_chunk(
        &self,
        c: usize,
        ids: &[(u32, u32)],
        slots: &mut [u32],
        blocks: &mut [BlockContacts<PairContact>],
        book: &mut ChunkBook,
        emit: &mut impl EmitLoads,
    ) {
        blocks.iter_mut().zip(slots.chunks_mut(BLOCK)).for_each(|(b, s)| b.tidy(s));
        let Self { model, kinematics, first_wall, dt } = *self;
        let base = c * PAIR_CHUNK;
        let mut pass = ChunkPass { model, kinematics, ids, slots, blocks, base, first_wall, dt };
        pass.step(book, emit);
    }
}

#[cfg(test)]
mod tests {
    use super::trim;

    #[test]
    fn trim_gives_back_room_only_past_four_times_the_contents() {
        let mut big: Vec<u32> = Vec::with_capacity(10_000);
        big.extend(0..600);
        trim(&mut big);
        assert_eq!((big.len(), big.capacity()), (600, 1200));
        assert!(big.iter().copied().eq(0..600));
        // at most four times: kept
        let mut kept: Vec<u32> = Vec::with_capacity(4000);
        kept.extend(0..1000);
        trim(&mut kept);
        assert_eq!(kept.capacity(), 4000);
        // small buffers keep 2048 places (of u32) whatever they hold
        let mut small: Vec<u32> = Vec::with_capacity(2048);
        trim(&mut small);
        assert_eq!(small.capacity(), 2048);
        // the floor is in bytes: places of 152 bytes keep 2·13 when empty
        let mut wide: Vec<[u64; 19]> = Vec::with_capacity(1000);
        trim(&mut wide);
        assert!(wide.capacity() >= 26 && wide.capacity() < 64, "{}", wide.capacity());
    }
}
