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

/// Candidate pairs per block (the parallel chunk of `pair_passes::PAIR_CHUNK` candidates
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

impl<C: Clone> BlockContacts<C> {
    /// An empty block with room for `n` contacts and a few births.
    pub(crate) fn with_room(n: usize) -> Self {
        BlockContacts {
            contacts: Vec::with_capacity(n + headroom(n)),
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
}

impl<C: Clone> BlockContacts<C> {
    /// Lays the block's contacts out anew in key order (`slots`, the block's candidates'
    /// slots, are renumbered) once an eighth of them (and at least 8) were born since the
    /// last layout: births go where ends left a place or at the end, out of key order, and
    /// a packing whose candidates are not rebuilt for thousands of steps (a settled one, or
    /// one whose contacts all came after the first build) would keep them so. Stepped in
    /// key order, contacts in key order are read in the order of memory, which the
    /// processor fetches ahead. `laid` is a buffer the caller keeps (no allocation once it
    /// has held a block), the block keeps its array.
    pub(crate) fn tidy(&mut self, slots: &mut [u32], laid: &mut Vec<C>) {
        let live = self.contacts.len() - self.holes.len();
        if (self.births as usize) < headroom(live) {
            return;
        }
        laid.clear();
        for slot in slots.iter_mut().filter(|s| **s != NO_CONTACT) {
            laid.push(self.contacts[*slot as usize].clone());
            *slot = (laid.len() - 1) as u32;
        }
        self.contacts.clear();
        self.contacts.extend_from_slice(laid);
        self.holes.clear();
        self.births = 0;
    }
}

/// Room for births in a block of `n` contacts: an eighth more, at least 8.
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
        block.tidy(&mut slots, &mut Vec::new());
        let live: Vec<u32> = slots.iter().copied().filter(|&s| s != NO_CONTACT).collect();
        assert_eq!(live, (0..11).collect::<Vec<u32>>());
        let points: Vec<f64> = slots.iter().filter_map(|&s| Some(block.get(s)?.x())).collect();
        assert_eq!(points, [0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0]);
        assert!(block.holes.is_empty() && block.births == 0);
        // fewer births than an eighth: left as it is
        let before = slots.clone();
        block.remove(slots[0]);
        slots[0] = block.insert(contact(0.5));
        block.tidy(&mut slots, &mut Vec::new());
        assert_eq!((slots, block.births), (before, 1));
    }

    #[test]
    fn a_block_grows_by_an_eighth_not_twofold() {
        let mut block = BlockContacts::with_room(400);
        assert_eq!(block.contacts.capacity(), 450);
        for k in 0..451 {
            block.insert(contact(k as f64));
        }
        assert_eq!(block.contacts.capacity(), 450 + 56);
    }
}
