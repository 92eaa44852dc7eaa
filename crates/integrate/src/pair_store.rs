//! Where the neighbour list keeps the contacts of its touching pairs: per block of
//! [`BLOCK`] candidate pairs, one dense array of contacts (an arena), and per candidate the
//! index of its contact in its block's array, or [`NO_CONTACT`].
//!
//! The pairs are stepped in key order, block after block: a block's contacts are one array
//! of about 60 kB, in key order after each rebuild of the candidates (the rebuild lays them
//! out anew), and a contact born between rebuilds takes the place an ended contact of its
//! block left, or goes at the end of the block's array. Boxed one by one (one heap
//! allocation per contact, handed from ended contacts to new ones), the contacts of a
//! packing scattered over the heap within a few hundred steps, and reading each one's last
//! normal was a cache miss: the step of the LAMMPS twin's 16 000 spheres spent 54 % of the
//! pair step's time on that one load, and its contact stage took 7.4–9.3 ms per step where
//! contacts laid out in key order took 5.3–5.7.

/// Candidate pairs per block (the parallel chunk of `pair_chunk::PAIR_CHUNK` candidates
/// holds a whole number of blocks).
pub(crate) const BLOCK: usize = 512;

/// A candidate pair that does not touch.
pub(crate) const NO_CONTACT: u32 = u32::MAX;

/// The contacts `C` of one block of candidate pairs (the neighbour list's `PairContact`),
/// with the places ended contacts left.
#[derive(Clone, Debug)]
pub(crate) struct BlockContacts<C> {
    contacts: Vec<C>,
    holes: Vec<u32>,
    /// Contacts born since the block was last laid out in key order.
    births: u32,
}

impl<C> Default for BlockContacts<C> {
    fn default() -> Self {
        BlockContacts { contacts: Vec::new(), holes: Vec::new(), births: 0 }
    }
}

impl<C> BlockContacts<C> {
    /// An empty block with room for `n` contacts and a few births ([`room_for_births`]).
    pub(crate) fn with_room(n: usize) -> Self {
        BlockContacts {
            contacts: Vec::with_capacity(n + room_for_births(n)),
            holes: Vec::new(),
            births: 0,
        }
    }

    /// The contact at `slot` (a candidate's index into this block), if it has one.
    #[inline(always)]
    pub(crate) fn get(&self, slot: u32) -> Option<&C> {
        if slot == NO_CONTACT {
            None
        } else {
            Some(&self.contacts[slot as usize])
        }
    }

    /// The contact at `slot`, mutable, if it has one.
    #[inline(always)]
    pub(crate) fn get_mut(&mut self, slot: u32) -> Option<&mut C> {
        if slot == NO_CONTACT {
            None
        } else {
            Some(&mut self.contacts[slot as usize])
        }
    }

    /// The number of contacts held (those of the block's touching candidates).
    #[inline]
    pub(crate) fn live(&self) -> usize {
        self.contacts.len() - self.holes.len()
    }

    /// Stores a new contact and returns its slot: the place an ended contact left, else the
    /// end of the array (grown by an eighth at a time, not doubled: a block gains few
    /// contacts between rebuilds).
    pub(crate) fn insert(&mut self, contact: C) -> u32 {
        self.births += 1;
        if let Some(hole) = self.holes.pop() {
            self.contacts[hole as usize] = contact;
            return hole;
        }
        if self.contacts.len() == self.contacts.capacity() {
            self.contacts.reserve_exact(headroom(self.contacts.len()));
        }
        self.contacts.push(contact);
        (self.contacts.len() - 1) as u32
    }

    /// Ends the contact at `slot` (its place serves the next birth in this block).
    pub(crate) fn remove(&mut self, slot: u32) {
        debug_assert!((slot as usize) < self.contacts.len() && !self.holes.contains(&slot));
        self.holes.push(slot);
    }

    /// Pushes a contact carried by a rebuild (in key order, into a block made
    /// [`BlockContacts::with_room`] for them) and returns its slot.
    pub(crate) fn push_carried(&mut self, contact: C) -> u32 {
        self.contacts.push(contact);
        (self.contacts.len() - 1) as u32
    }

    /// Lays the block's contacts out anew in key order (`slots`, the block's candidates'
    /// slots, are renumbered) once an eighth of them (and at least 8) were born, or ended,
    /// since the last layout: births go where ends left a place or at the end, out of key
    /// order, and a packing whose candidates are not rebuilt for thousands of steps (a
    /// settled one, or one whose contacts all came after the first build) would keep them
    /// so. Stepped in key order, contacts in key order are read in the order of memory, which
    /// the processor fetches ahead. The places ends left are given back: a packing that
    /// loosens (the benchmark's, 70 000 contacts on 100 000 spheres at its 20th step, 54 000
    /// five steps on) kept 30 % of its contacts' memory as holes until the next rebuild. The
    /// array itself shrinks when more than an eighth of it is spare
    /// ([`BlockContacts::shrink_spare`]).
    ///
    /// In place: `source[k]`, where the contact that goes to place k is now (the live ones
    /// in key order, then the places ends left, dropped after), is a permutation, applied
    /// by swaps along its cycles. It is built in the holes' array (no allocation once that
    /// has held a block's count; no copy of the contacts).
    pub(crate) fn tidy(&mut self, slots: &mut [u32]) {
        let n = self.contacts.len();
        let ended = self.holes.len();
        let live = n - ended;
        if (self.births as usize) < headroom(live) && ended < headroom(live) {
            return;
        }
        let mut source = std::mem::take(&mut self.holes);
        for slot in slots.iter_mut().filter(|s| **s != NO_CONTACT) {
            source.push(*slot);
            *slot = (source.len() - ended - 1) as u32;
        }
        source.rotate_left(ended);
        debug_assert_eq!(source.len(), n);
        for start in 0..n {
            // along the cycle through `start`: place j takes the contact at source[j] (a
            // swap carries the one displaced on, until the cycle closes); a place done
            // points at itself
            let mut j = start;
            while source[j] as usize != start {
                let from = source[j] as usize;
                if from == j {
                    break;
                }
                self.contacts.swap(j, from);
                source[j] = j as u32;
                j = from;
            }
            source[j] = j as u32;
        }
        self.contacts.truncate(live);
        source.clear();
        self.holes = source;
        self.births = 0;
        self.shrink_spare();
    }

    /// Gives back the array's spare room when it is more than a [`headroom`] and a
    /// [`room_for_births`] over the live contacts (an eighth and a thirty-second), down to
    /// the room a rebuild makes; one reallocation, at a layout, which moves them all anyway.
    /// Not at one headroom: a block made with room for births that then grew by a headroom
    /// (births outran ends by a thirty-second) sits just over it, and was shrunk and grown
    /// again at every layout (0.145 allocations per step in a settling packing of 1000,
    /// `crates/bench/tests/allocations.rs`). Not at two: a packing that loosens held 16 bytes
    /// per sphere more. (The holes' array, 4 bytes a contact, keeps its room: the next layout
    /// builds its permutation there.)
    fn shrink_spare(&mut self) {
        let live = self.contacts.len();
        if self.contacts.capacity() > live + headroom(live) + room_for_births(live) {
            self.contacts.shrink_to(live + room_for_births(live));
        }
    }
}

/// Room for births a block is made with: a thirty-second more, at least 4 (births mostly
/// take the places of ends; an eighth more, as the array grows, held 44 bytes per sphere of
/// a packing idle).
fn room_for_births(n: usize) -> usize {
    (n / 32).max(4)
}

/// An eighth of a block of `n` contacts, at least 8: what a full block grows by, and the
/// births that call for a new layout.
fn headroom(n: usize) -> usize {
    (n / 8).max(8)
}

/// The number of blocks of `candidates` candidate pairs.
pub(crate) fn blocks_for(candidates: usize) -> usize {
    candidates.div_ceil(BLOCK)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stand-in for a contact: its "point".
    #[derive(Clone, Debug, PartialEq)]
    struct Contact {
        point: [f64; 1],
    }

    impl Contact {
        fn x(&self) -> f64 {
            self.point[0]
        }
    }

    fn contact(x: f64) -> Contact {
        Contact { point: [x] }
    }

    #[test]
    fn a_birth_takes_the_place_an_end_left_before_the_end_of_the_array() {
        let mut block = BlockContacts::with_room(2);
        let (a, b) = (block.push_carried(contact(1.0)), block.push_carried(contact(2.0)));
        assert_eq!((a, b), (0, 1));
        block.remove(a);
        assert_eq!(block.insert(contact(3.0)), 0);
        assert_eq!(block.insert(contact(4.0)), 2);
        let points: Vec<f64> = (0..3).map(|s| block.get(s).unwrap().x()).collect();
        assert_eq!(points, [3.0, 2.0, 4.0]);
        assert!(block.get(NO_CONTACT).is_none() && block.get_mut(NO_CONTACT).is_none());
    }

    #[test]
    fn a_block_is_laid_out_in_key_order_again_after_enough_births() {
        let mut block = BlockContacts::with_room(0);
        // 12 candidates; births in the order 11, 10, ..., 0 (8 is the least that triggers)
        let mut slots = vec![NO_CONTACT; 12];
        for n in (0..12).rev() {
            slots[n] = block.insert(contact(n as f64));
        }
        block.remove(slots[5]);
        slots[5] = NO_CONTACT;
        block.tidy(&mut slots);
        let live: Vec<u32> = slots.iter().copied().filter(|&s| s != NO_CONTACT).collect();
        assert_eq!(live, (0..11).collect::<Vec<u32>>());
        let points: Vec<f64> = slots.iter().filter_map(|&s| Some(block.get(s)?.x())).collect();
        assert_eq!(points, [0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0]);
        assert!(block.holes.is_empty() && block.births == 0);
        // scrambled births and ends over many layouts: each layout leaves the live
        // contacts in key order, every one the candidate's own
        let mut block = BlockContacts::with_room(0);
        let mut slots = vec![NO_CONTACT; 200];
        let mut x: u64 = 7;
        for round in 0..300 {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let n = (x >> 33) as usize % 200;
            if slots[n] == NO_CONTACT {
                slots[n] = block.insert(contact(n as f64));
            } else {
                block.remove(slots[n]);
                slots[n] = NO_CONTACT;
            }
            if round % 7 == 0 {
                block.tidy(&mut slots);
                if block.births == 0 {
                    let live: Vec<u32> =
                        slots.iter().copied().filter(|&s| s != NO_CONTACT).collect();
                    assert_eq!(live, (0..live.len() as u32).collect::<Vec<_>>(), "round {round}");
                    assert_eq!(block.contacts.len(), live.len());
                }
            }
            for (k, &s) in slots.iter().enumerate() {
                assert!(s == NO_CONTACT || block.get(s).unwrap().x() == k as f64, "round {round}");
            }
        }
        // fewer births than an eighth: left as it is
        let (before, births) = (slots.clone(), block.births);
        assert!(births + 1 < headroom(block.contacts.len() - block.holes.len()) as u32);
        block.remove(slots[0]);
        slots[0] = block.insert(contact(0.5));
        block.tidy(&mut slots);
        assert_eq!((slots, block.births), (before, births + 1));
    }

    #[test]
    fn ends_alone_lay_a_block_out_and_give_back_its_spare_room() {
        let mut block = BlockContacts::with_room(400);
        let mut slots: Vec<u32> = (0..400).map(|k| block.push_carried(contact(k as f64))).collect();
        // 134 ends (a third): laid out, and the array (412) shrinks to 266 live and room
        for k in (0..400).step_by(3) {
            block.remove(slots[k]);
            slots[k] = NO_CONTACT;
        }
        block.tidy(&mut slots);
        assert!(block.holes.is_empty());
        assert_eq!(block.contacts.len(), 266);
        assert_eq!(block.contacts.capacity(), 266 + room_for_births(266));
        for (k, &s) in slots.iter().enumerate() {
            assert_eq!(k % 3 == 0, s == NO_CONTACT);
            assert!(s == NO_CONTACT || block.get(s).unwrap().x() == k as f64);
        }
        // fewer ends than an eighth: left as it is
        block.remove(slots[1]);
        slots[1] = NO_CONTACT;
        block.tidy(&mut slots);
        assert_eq!((block.holes.len(), block.contacts.len()), (1, 266));
        // 34 ends of 266 (an eighth of the 232 left): laid out, and the array (274) is more
        // than an eighth over them, so it shrinks
        for k in (2..400).filter(|k| k % 3 != 0).take(33) {
            block.remove(slots[k]);
            slots[k] = NO_CONTACT;
        }
        block.tidy(&mut slots);
        assert_eq!((block.holes.len(), block.contacts.len()), (0, 232));
        assert_eq!(block.contacts.capacity(), 232 + room_for_births(232));
    }

    #[test]
    fn a_block_grows_by_an_eighth_not_twofold() {
        let mut block = BlockContacts::with_room(400);
        assert_eq!(block.contacts.capacity(), 412);
        for k in 0..413 {
            block.insert(contact(k as f64));
        }
        assert_eq!(block.contacts.capacity(), 412 + 51);
    }
}
