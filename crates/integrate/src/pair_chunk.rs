//! The step of one chunk of candidate pairs of the neighbour list, in key order, for both
//! passes (`pair_passes.rs`): the runs of spheres apart without a contact skipped in a loop
//! of their own (`first_not_apart`), the contacts of two free spheres that go on updated four
//! at once (`update_sphere_pair_lanes`, the scalar path's bits lane by lane), everything
//! else (births, ends, walls, the lanes the four-lane path leaves) by the general step
//! (`step_pair`). The wall's pairs (after the spheres') likewise: the contacts that go on four
//! at once (`update_wall_sphere_lanes`), the pairs without a contact that do not touch
//! skipped (`wall_apart`: their general step does nothing). Each touching pair's loads go to
//! the pass's `emit` in key order, and its energy, dashpots' record and (a wall's) applied
//! force to the chunk's book, as the scalar path gives them.
//!
//! The pairs waiting for their four-lane update are updated before any general step and
//! before pairs of the other kind wait (the loads, sums and records stay in key order); a
//! wait of one pair takes the scalar path.

use crate::fresh_shares::PairShares;
use crate::neighbours::{AppliedForce, LawOut, PairContact, PairOutcome, Pushed};
use crate::pair_book::ChunkBook;
use crate::pair_keys::{key_at, ContactKey};
use crate::pair_step::{continuing_pair, first_not_apart, step_pair, wall_apart};
use crate::pair_store::{BlockContacts, BLOCK, NO_CONTACT};
use flexdem_contact::frictional_lanes::{
    update_sphere_pair_lanes, update_wall_sphere_lanes, ContactLanesOut, SpherePairLanes,
    WallSphereLanes, LANES,
};
use flexdem_elements::virtual_sphere::{Feature, Kinematics, NodeLoad};
use flexdem_elements::{Model, Particles};
use flexdem_geom::Real;

/// Candidate pairs per chunk (fixed: the work is split the same way whatever the number of
/// threads, and the sums are taken per chunk, then over the chunks in order). 2048 rather
/// than the 4096 it was: the walls' pairs go to the threads by chunk (`pair_parts.rs`), and a
/// chunk of the packing's floor then spans a fifth of the spheres instead of two fifths;
/// 1024 and 512 cost more per chunk than they saved (packing of 10⁵ spheres at 2 threads,
/// contacts stage 3.45 and 3.65 ms against 3.3; twenty-third session).
pub(crate) const PAIR_CHUNK: usize = 2048;

/// A chunk holds whole blocks of the contacts' store.
const _: () = assert!(PAIR_CHUNK % BLOCK == 0);

/// One chunk of candidates and what its step reads: the keys' ids, the slots of their
/// contacts and the blocks that hold them (the chunk's), the index of its first candidate
/// in the list (`base`) and of the list's first wall pair.
pub(crate) struct ChunkPass<'a> {
    pub(crate) model: &'a Model,
    pub(crate) kinematics: &'a Kinematics<'a>,
    pub(crate) ids: &'a [(u32, u32)],
    pub(crate) slots: &'a mut [u32],
    pub(crate) blocks: &'a mut [BlockContacts<PairContact>],
    pub(crate) base: usize,
    pub(crate) first_wall: usize,
    pub(crate) dt: Real,
}

/// Where a chunk pass gives each touching pair's loads, in key order (the passes'
/// implementations inline their `emit` into the four-lane path: as a closure it was a call,
/// whose loads went through the stack in stores narrower than its loads, which store
/// forwarding cannot serve).
pub(crate) trait EmitLoads {
    /// Pair `i` (its index in the chunk, its `key`) touches after its step, with these two
    /// node loads (a wall's pair: body 1's is the wall's, not a particle's).
    fn emit(&mut self, i: usize, key: &ContactKey, loads: &[NodeLoad; 2]);
}

/// Pairs in contact (their indices in the chunk) waiting for their update together: two
/// free spheres each, or (`walls`) a wall and a sphere each.
#[derive(Default)]
struct Waiting {
    at: [usize; LANES],
    len: usize,
    walls: bool,
}

impl ChunkPass<'_> {
    /// Steps the chunk's candidates in key order (module documentation), giving `emit` the
    /// loads of each pair that touches after its step.
    pub(crate) fn step(&mut self, book: &mut ChunkBook, emit: &mut impl EmitLoads) {
        let p = &self.model.particles;
        let spheres = self.first_wall.saturating_sub(self.base).min(self.ids.len());
        let mut waiting = Waiting::default();
        let mut i = 0;
        while i < self.ids.len() {
            // the spheres apart without a contact, in a loop of their own
            i = first_not_apart(p, &self.ids[..spheres], &self.slots[..spheres], i);
            if i == self.ids.len() {
                break;
            }
            let (ids, held) = (self.ids[i], self.slots[i] != NO_CONTACT);
            let walls = i >= spheres;
            if held {
                if waiting.len > 0 && waiting.walls != walls {
                    self.update_waiting(&mut waiting, book, emit);
                }
                (waiting.at[waiting.len], waiting.walls) = (i, walls);
                waiting.len += 1;
                if waiting.len == LANES {
                    self.update_waiting(&mut waiting, book, emit);
                }
            } else if !(walls && wall_apart(self.model, ids.0, ids.1)) {
                self.update_waiting(&mut waiting, book, emit);
                self.step_one(i, book, emit);
            }
            i += 1;
        }
        self.update_waiting(&mut waiting, book, emit);
    }

    /// The waiting pairs' step, in order: four (or two, three, padded with the first) at
    /// once, the lanes the path leaves and a single pair by [`Self::step_one`].
    fn update_waiting(
        &mut self,
        waiting: &mut Waiting,
        book: &mut ChunkBook,
        emit: &mut impl EmitLoads,
    ) {
        let len = std::mem::take(&mut waiting.len);
        if len < 2 {
            waiting.at[..len].iter().for_each(|&i| self.step_one(i, book, emit));
            return;
        }
        let at: [usize; LANES] = std::array::from_fn(|j| waiting.at[if j < len { j } else { 0 }]);
        let p: &Particles = &self.model.particles;
        let (blocks, slots, ids) = (&*self.blocks, &*self.slots, self.ids);
        let held: [&PairContact; LANES] = std::array::from_fn(|j| {
            let i = at[j];
            blocks[i / BLOCK].get(slots[i]).expect("a waiting pair has a contact")
        });
        let params = held.map(|c| &c.params);
        let states = held.map(|c| &c.state);
        let out = if waiting.walls {
            let walls = &self.model.walls;
            let lanes = WallSphereLanes {
                pos: &p.pos,
                vel: &p.vel,
                ang_vel: &p.ang_vel,
                radius: &p.radius,
                walls: at.map(|i| {
                    let w = &walls[ids[i].0 as usize];
                    [w.point, w.normal, w.velocity]
                }),
                spheres: at.map(|i| ids[i].1 as usize),
            };
            update_wall_sphere_lanes(params, states, &lanes, self.dt)
        } else {
            let lanes = SpherePairLanes {
                pos: &p.pos,
                vel: &p.vel,
                ang_vel: &p.ang_vel,
                radius: &p.radius,
                pairs: at.map(|i| [ids[i].0 as usize, ids[i].1 as usize]),
            };
            update_sphere_pair_lanes(params, states, &lanes, self.dt)
        };
        // (lane by lane with a constant index: with a variable one, the lanes' values were
        // read by AVX-512 gathers, microcoded, a twentieth of the LAMMPS twin's step)
        let walls = waiting.walls;
        self.lane_step::<0>(&out, &at, len, walls, book, emit);
        self.lane_step::<1>(&out, &at, len, walls, book, emit);
        self.lane_step::<2>(&out, &at, len, walls, book, emit);
        self.lane_step::<3>(&out, &at, len, walls, book, emit);
    }

    /// Lane `J` of the waiting pairs `at` (if it holds one of the `len`): booked as the
    /// four-lane path gave it ([`Self::book_lane`]), or stepped alone when the path left it.
    #[inline(always)]
    #[allow(clippy::too_many_arguments, reason = "the lanes' update and where it goes")]
    fn lane_step<const J: usize>(
        &mut self,
        out: &ContactLanesOut,
        at: &[usize; LANES],
        len: usize,
        walls: bool,
        book: &mut ChunkBook,
        emit: &mut impl EmitLoads,
    ) {
        if J >= len {
            return;
        }
        if out.taken & (1 << J) == 0 {
            self.step_one(at[J], book, emit);
        } else {
            self.book_lane(out, J, at[J], walls, book, emit);
        }
    }

    /// Books lane `j` of `out`, pair `i` (a wall's when `wall`), which took the four-lane
    /// path: its state written, its energy, dashpots' record and (a wall's) applied force to
    /// `book`, its loads to `emit`, as its general step would (a contact that goes on adds
    /// nothing to the births' and ends' sums).
    #[inline(always)]
    fn book_lane(
        &mut self,
        out: &ContactLanesOut,
        j: usize,
        i: usize,
        wall: bool,
        book: &mut ChunkBook,
        emit: &mut impl EmitLoads,
    ) {
        let (ids, n) = (self.ids[i], self.base + i);
        let c = self.blocks[i / BLOCK].get_mut(self.slots[i]).expect("a waiting pair");
        out.write_state(j, &mut c.state);
        book.record_continuing(c, out.elastic_energy(j));
        if out.pushed & (1 << j) != 0 {
            let (force, moments, viscous) = out.dashpot(j);
            book.pushed.push(Pushed { index: n as u32, force, moments, viscous });
        }
        let (f2, torques) = (out.force_on_2(j), out.torques(j));
        let key = if wall {
            let (normal_force, shear_force) = out.applied(j);
            let sliding = out.sliding & (1 << j) != 0;
            book.walls.push((n as u32, AppliedForce { normal_force, shear_force, sliding }));
            (Feature::Wall(ids.0), Feature::Particle(ids.1))
        } else {
            (Feature::Particle(ids.0), Feature::Particle(ids.1))
        };
        // (a wall's site has node 0, `Site::wall`)
        let node_1 = if wall { 0 } else { ids.0 };
        let loads = [
            NodeLoad { node: node_1, force: -f2, torque: torques[0] },
            NodeLoad { node: ids.1, force: f2, torque: torques[1] },
        ];
        emit.emit(i, &key, &loads);
    }

    /// The step of candidate `i` alone: a contact of two free spheres that goes on by
    /// [`went_on`], else the general step ([`general_step`]).
    fn step_one(&mut self, i: usize, book: &mut ChunkBook, emit: &mut impl EmitLoads) {
        let (n, ids) = (self.base + i, self.ids[i]);
        let p = &self.model.particles;
        let (block, slot) = (&mut self.blocks[i / BLOCK], &mut self.slots[i]);
        if n < self.first_wall && *slot != NO_CONTACT {
            // two free spheres (the ids are theirs, `pair_keys::key_at`) in contact
            if let Some(loads) = went_on(p, ids, *slot, block, book, n, self.dt) {
                emit.emit(i, &(Feature::Particle(ids.0), Feature::Particle(ids.1)), &loads);
                return;
            }
        }
        let key = &key_at(self.first_wall, n, ids);
        let k = self.kinematics;
        if let Some(o) = general_step(self.model, k, key, slot, block, book, n, self.dt) {
            emit.emit(i, key, &o.loads);
        }
    }
}

/// The step of candidate `n`, two free spheres `ids` whose contact (at `slot` of `block`)
/// goes on: its law and loads (`continuing_pair`), its energy booked in `book`; None where
/// the general step has to decide (apart now, centres crossed).
#[inline(always)]
fn went_on(
    p: &Particles,
    ids: (u32, u32),
    slot: u32,
    block: &mut BlockContacts<PairContact>,
    book: &mut ChunkBook,
    n: usize,
    dt: Real,
) -> Option<[NodeLoad; 2]> {
    let mut law = LawOut::new(&mut book.pushed, n);
    let loads = continuing_pair(p, ids.0, ids.1, slot, block, dt, &mut law)?;
    let elastic = law.elastic;
    let c = block.get(slot).expect("a contact that goes on");
    book.record_continuing(c, elastic);
    Some(loads)
}

/// The general step of candidate `n` (`key`, its contact at `slot` of `block`): its
/// births, ends and law (`step_pair`), booked in `book`; its outcome when the pair touches
/// after it.
#[allow(clippy::too_many_arguments, reason = "one pair's inputs and its book")]
#[inline(always)]
fn general_step(
    model: &Model,
    k: &Kinematics<'_>,
    key: &ContactKey,
    slot: &mut u32,
    block: &mut BlockContacts<PairContact>,
    book: &mut ChunkBook,
    n: usize,
    dt: Real,
) -> Option<PairOutcome> {
    let mut law = LawOut::new(&mut book.pushed, n);
    let mut o = PairOutcome::default();
    step_pair(model, k, key, slot, block, dt, &mut o, &mut law);
    let elastic = law.elastic;
    book.record(n, &o, block.get(*slot), elastic);
    if o.fresh {
        // its stiffness for the time step, while its contact and particles are at hand
        let c = block.get(*slot).expect("a new pair's contact");
        let shares = PairShares::of(model, key, &c.params, &c.state.normal, &mut book.memo);
        book.fresh_shares.push(shares);
    }
    let touches = *slot != NO_CONTACT;
    if touches && matches!(key.0, Feature::Wall(_)) {
        book.walls.push((n as u32, o.applied));
    }
    touches.then_some(o)
}

#[cfg(test)]
#[path = "pair_chunk_tests.rs"]
mod tests;
