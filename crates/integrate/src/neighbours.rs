//! Contacts of free spheres with free spheres and with walls, kept in a neighbour list with
//! history (as LAMMPS and LIGGGHTS keep granular contacts, issue 14): between two builds of
//! the collider the candidate pairs do not change, so each carries its contact state in place
//! instead of being found, ordered and matched again every step.
//!
//! These contacts are the same as those of the general pipeline (`contacts.rs`), bit for bit:
//! the same closest points (`pairs::sphere_sphere`, the wall's plane), the same new-contact
//! rule, the same law and the same force distribution. What a free sphere cannot have is
//! skipped: the one-contact-per-touching rule (a sphere is one element) and hand-overs and
//! splits (a contact can only be taken over by a contact of the same two bodies, and two
//! free spheres, or a sphere and a wall, touch once). The births and ends enter the energy
//! balance as in [`crate::contacts`]. The forces are summed into the particles in the order
//! of the contacts' keys, merged with the general contacts' ([`merged`]): the results do not
//! depend on which pipeline a contact went through, nor on the thread count.

use crate::contact::{geometry_of, Contact, SPHERE_OWNER, WALL_OWNER};
pub use crate::pair_keys::ContactKey;
use crate::pair_keys::PairKeys;
use crate::pair_store::{blocks_for, BlockContacts, BLOCK, NO_CONTACT};
use flexdem_contact::{
    spring_energy, spring_energy_squared, ContactForces, FrictionalContact, FrictionalParams,
};
use flexdem_elements::virtual_sphere::{Feature, Kinematics, NodeLoad, Site};
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};

/// The state of a touching pair: what a [`Contact`] holds less what the key says (the sites
/// and the owners) and less what the last update gave, which is made when asked (its
/// forces, [`PairContact::applied`] and [`PairContact::forces`]; its point,
/// `NeighbourList::contact`): 112 bytes where a [`Contact`] is 320. The pairs' step reads
/// and writes all of it and nothing else (it was 176 bytes with the force applied and the
/// point written at every update for output alone: 57 % more memory to stream through per
/// step; the LAMMPS twin's step took 3–10 % longer with it, bench/README's eighth session).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairContact {
    /// Stiffnesses, friction and dashpots.
    pub params: FrictionalParams,
    /// Shear force, last normal, dissipation.
    pub state: FrictionalContact,
}

/// The force a pair contact's last update applied, as the law gave it
/// ([`update_frictional_contact`]'s `normal_force`, `shear_force` and `sliding`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AppliedForce {
    /// Normal force Fn, the normal dashpot's included; compression positive.
    pub normal_force: Real,
    /// Tangential force on body 2 (spring and dashpot, capped by Coulomb).
    pub shear_force: Vec3,
    /// The tangential force was capped by Coulomb.
    pub sliding: bool,
}

impl PairContact {
    /// Elastic energy of the springs after the last update, `(kn·δ)²/(2kn) + |Fs|²/(2ks)`
    /// from the state: the law's `elastic_energy`, by the same operations (the same bits).
    #[inline]
    pub fn elastic_energy(&self) -> Real {
        spring_energy(self.state.normal_force, self.params.kn)
            + spring_energy_squared(self.state.shear_force.norm_squared(), self.params.ks)
    }

    /// The force the last update applied, made from the state and `dashpot`, the force its
    /// dashpots pushed body 2 with (None when they did not push). The law leaves its springs
    /// in the state: without a dashpot's push the force is theirs, the law's exactly
    /// (`Fn = kn·δ`, and the shear spring, which the law sets to the capped force when it
    /// slides); with one, `Fn = kn·δ + fd·n` and `Fs = Fs,spring + fd − (fd·n)·n` (the law's
    /// to round-off; an `Fn` within the round-off of that sum of zero is the law's clamp of
    /// Fn at zero, and is zero). Sliding: `|Fs|` at the Coulomb limit `tanφ·Fn`, to
    /// round-off (a limit of zero counts as sliding).
    pub fn applied(&self, dashpot: Option<&Vec3>) -> AppliedForce {
        let s = &self.state;
        let (normal_force, shear_force) = match dashpot {
            Some(fd) => {
                let along = fd.dot(&s.normal);
                // the law clamps Fn at zero (the dashpot never pulls): a force within the
                // round-off of this sum of zero is that clamp
                let fn_ = s.normal_force + along;
                let round_off = 1e-12 * (s.normal_force.abs() + fd.norm());
                let fn_ = if fn_ <= round_off { 0.0 } else { fn_ };
                (fn_, s.shear_force + (fd - s.normal * along))
            }
            None => (s.normal_force, s.shear_force),
        };
        let limit = (normal_force * self.params.tan_phi).max(0.0);
        let sliding = shear_force.norm_squared() >= limit * limit * (1.0 - 1e-9);
        AppliedForce { normal_force, shear_force, sliding }
    }

    /// The forces of the last update as the law returned them, made from the force it
    /// applied (`a`: [`PairContact::applied`], or a wall pair's as its update kept it) and the
    /// state: the forces (`force_on_2 = Fn·n + Fs`, with the normal the update stored) and
    /// the elastic energy as `a` and the state have them; the dashpots' part as
    /// `(Fn − kn·δ)·n + (Fs − Fs,spring)` (the law's to round-off; zero without dashpots);
    /// the update's own dissipation is not kept (zero here: the contact's lifetime friction
    /// is `state.dissipated_friction`).
    pub fn forces(&self, a: &AppliedForce) -> ContactForces {
        let s = &self.state;
        let dashpot_force = if self.params.is_damped() {
            s.normal * (a.normal_force - s.normal_force) + (a.shear_force - s.shear_force)
        } else {
            Vec3::zeros()
        };
        ContactForces {
            normal_force: a.normal_force,
            shear_force: a.shear_force,
            force_on_2: s.normal * a.normal_force + a.shear_force,
            dashpot_force,
            elastic_energy: self.elastic_energy(),
            dissipated: Default::default(),
            sliding: a.sliding,
        }
    }
}

/// The candidate pairs of free spheres (with free spheres, then with walls), sorted by key,
/// each with its contact while it touches. Saved (and compared) as its touching pairs only:
/// the candidates are rebuilt with the collider.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(from = "Vec<(ContactKey, PairContact)>", into = "Vec<(ContactKey, PairContact)>")]
pub struct NeighbourList {
    pub(crate) keys: PairKeys,
    /// One per key: the index of its contact in its block's array while it touches, else
    /// [`NO_CONTACT`] (most candidates do not touch: 4 bytes each, see `pair_store.rs`).
    pub(crate) slots: Vec<u32>,
    /// Per block of [`BLOCK`] keys, the contacts of its touching pairs.
    pub(crate) blocks: Vec<BlockContacts<PairContact>>,
    /// `energy_sums` as the last update in one pass found them (its pass visits every
    /// contact anyway); `None` when not known (after a parallel update, a clear, a load).
    pub(crate) sums: Option<(Real, Real)>,
    /// Which set of candidates this is: a number no other set of this process had, changed
    /// when the candidates change (a rebuild, a clear, a load), for the indexes built on them
    /// (`gather::LoadIndex`).
    generation: u64,
}

/// The source of [`NeighbourList`] generations.
static GENERATIONS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

/// A generation no set of candidates had before.
fn new_generation() -> u64 {
    GENERATIONS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

impl From<Vec<(ContactKey, PairContact)>> for NeighbourList {
    fn from(touching: Vec<(ContactKey, PairContact)>) -> Self {
        let count = touching.len();
        let mut list = NeighbourList {
            keys: PairKeys::with_capacity(count),
            slots: Vec::with_capacity(count),
            blocks: Vec::with_capacity(blocks_for(count)),
            sums: None,
            generation: new_generation(),
        };
        for (n, (key, contact)) in touching.into_iter().enumerate() {
            if n % BLOCK == 0 {
                list.blocks.push(BlockContacts::with_room(BLOCK.min(count - n)));
            }
            list.keys.push(key);
            list.slots.push(list.blocks[n / BLOCK].push_carried(contact));
        }
        list
    }
}

impl From<NeighbourList> for Vec<(ContactKey, PairContact)> {
    fn from(list: NeighbourList) -> Self {
        list.touching().map(|(k, c)| (k, *c)).collect()
    }
}

impl PartialEq for NeighbourList {
    fn eq(&self, other: &Self) -> bool {
        self.touching().eq(other.touching())
    }
}

/// What one pair did at a step: its node loads (body 1's unused for a wall) and the force
/// its law applied when it touches after the step, and what its birth or end moved the
/// energy balance by.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairOutcome {
    pub(crate) loads: [NodeLoad; 2],
    pub(crate) applied: AppliedForce,
    pub(crate) born_energy: Real,
    pub(crate) released: Real,
    pub(crate) ended_dissipation: Real,
    pub(crate) born_deep: bool,
    pub(crate) fresh: bool,
}

impl Default for PairOutcome {
    fn default() -> Self {
        let none = NodeLoad { node: 0, force: Vec3::zeros(), torque: Vec3::zeros() };
        PairOutcome {
            loads: [none; 2],
            applied: AppliedForce::default(),
            born_energy: 0.0,
            released: 0.0,
            ended_dissipation: 0.0,
            born_deep: false,
            fresh: false,
        }
    }
}

/// Where the law of a pair that touches after its step puts what it gave besides its loads:
/// its elastic energy, and, when its dashpots pushed, their record, appended to `pushed`
/// (the pair's chunk's list) under the pair's `index`, field by field in its place (a record
/// made whole on the stack by small stores and copied into the list by wide loads waited on
/// a failed store forwarding: the costliest instruction of the LAMMPS twin's contacts).
#[derive(Debug)]
pub(crate) struct LawOut<'a> {
    pub(crate) elastic: Real,
    pub(crate) pushed: &'a mut Vec<Pushed>,
    pub(crate) index: u32,
}

impl<'a> LawOut<'a> {
    /// For pair `index`, its records going to `pushed`.
    pub(crate) fn new(pushed: &'a mut Vec<Pushed>, index: usize) -> Self {
        LawOut { elastic: 0.0, pushed, index: index as u32 }
    }
}

/// A pair whose dashpots pushed at an update: its index, the dashpots' force alone on body 2
/// (body 1 has the opposite), its moments about the two bodies' centres, and the law's count
/// of its dissipation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Pushed {
    pub(crate) index: u32,
    pub(crate) force: Vec3,
    pub(crate) moments: [Vec3; 2],
    pub(crate) viscous: Real,
}

/// The sites of the contact of `key` (a free sphere's radius from the model).
pub(crate) fn sites(model: &Model, key: &ContactKey) -> (Site, Site) {
    let r = &model.particles.radius;
    let particle = |f: Feature| match f {
        Feature::Particle(i) => Site::particle(i, r[i as usize]),
        Feature::Wall(w) => Site::wall(w),
        // the list holds only particles and walls
        Feature::Edge(_) | Feature::Face(_) => Site::wall(u32::MAX),
    };
    (particle(key.0), particle(key.1))
}

/// Owner code of a key's body (as `contacts::owner`): a free sphere or a wall.
fn owners(key: &ContactKey) -> (u64, u64) {
    let code = |f: Feature| match f {
        Feature::Wall(w) => WALL_OWNER | u64::from(w),
        Feature::Particle(i) => SPHERE_OWNER | u64::from(i),
        Feature::Edge(_) | Feature::Face(_) => u64::MAX,
    };
    (code(key.0), code(key.1))
}

impl NeighbourList {
    /// Candidate pairs (touching or not).
    pub fn candidates(&self) -> usize {
        self.keys.len()
    }

    /// Touching pairs.
    pub fn len(&self) -> usize {
        // per block, its contacts less the places ends left (a look at ~150 blocks where a
        // count of the slots read all the candidates' 4 bytes, twice a step)
        let count = self.blocks.iter().map(BlockContacts::live).sum();
        debug_assert_eq!(count, self.slots.iter().filter(|&&s| s != NO_CONTACT).count());
        count
    }

    /// Whether no pair touches.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The contact of candidate `index`, if it touches.
    #[inline]
    pub(crate) fn contact_at(&self, index: usize) -> Option<&PairContact> {
        self.blocks[index / BLOCK].get(self.slots[index])
    }

    /// Whether candidate `index` touches.
    #[inline]
    pub(crate) fn touches(&self, index: usize) -> bool {
        self.slots[index] != NO_CONTACT
    }

    /// The touching pairs, in key order.
    pub fn touching(&self) -> impl Iterator<Item = (ContactKey, &PairContact)> + '_ {
        self.keys.iter().enumerate().filter_map(|(n, k)| Some((k, self.contact_at(n)?)))
    }

    /// The pair at `index` (of the candidates) as a [`Contact`], if it touches: its forces
    /// made from `applied`, the force its last update applied (see
    /// `pair_passes::LastUpdate`), its point the contact point of the bodies where they are
    /// now (`contact::geometry_of` with the normal of the last update: the point is not kept
    /// from step to step, see [`PairContact`]).
    pub(crate) fn contact(
        &self,
        model: &Model,
        index: usize,
        applied: &AppliedForce,
    ) -> Option<Contact> {
        let c = self.contact_at(index)?;
        let key = &self.keys.get(index);
        let (site1, site2) = sites(model, key);
        let p = &model.particles;
        let k = Kinematics::of(p);
        let (_, _, g) = geometry_of(model, &k, &site1, &site2, &c.state.normal);
        Some(Contact {
            site1,
            site2,
            owners: owners(key),
            params: c.params,
            state: c.state,
            forces: c.forces(applied),
            point: g.point,
        })
    }

    /// The key and contact of the touching pair at candidate index `index`.
    pub(crate) fn get(&self, index: usize) -> (ContactKey, &PairContact) {
        (self.keys.get(index), self.contact_at(index).expect("a touching pair"))
    }

    /// Ends every contact (the model changed): their friction and elastic energy are the
    /// caller's to account for.
    pub(crate) fn clear(&mut self) {
        self.keys.clear();
        self.slots.clear();
        self.blocks.clear();
        self.sums = None;
        self.generation = new_generation();
    }

    /// The keys of the candidate pairs, sorted.
    pub(crate) fn keys(&self) -> &PairKeys {
        &self.keys
    }

    /// This set of candidates' generation (see the field).
    pub(crate) fn generation(&self) -> u64 {
        self.generation
    }

    /// Whether every pair refers to particles and walls of a model of `particles` particles
    /// and `walls` walls, free spheres against free spheres or walls.
    pub(crate) fn fits(&self, particles: usize, walls: usize) -> bool {
        self.keys.fits(particles, walls)
    }

    /// The candidates of a new build of the collider: `spheres` (particle pairs, sorted; its
    /// array becomes the keys') and `walls` ((wall, particle) pairs, sorted), with the
    /// contacts of the touching pairs carried over by key. A touching pair missing from the
    /// new candidates (which the collider's margins exclude) is kept, so that its end is
    /// accounted for.
    pub(crate) fn rebuild(&mut self, spheres: Vec<(u32, u32)>, walls: &[(u32, u32)]) {
        self.generation = new_generation();
        let old_keys = std::mem::take(&mut self.keys);
        let old_slots = std::mem::take(&mut self.slots);
        let old_blocks = std::mem::take(&mut self.blocks);
        // the old touching pairs in key order: (key, old block, slot in it)
        let old = old_keys
            .iter()
            .zip(old_slots.iter().copied())
            .enumerate()
            .filter(|(_, (_, s))| *s != NO_CONTACT)
            .map(|(n, (k, s))| (k, n / BLOCK, s));
        // first the keys: the candidates, and the touching pairs they lack in their places
        let new = spheres
            .iter()
            .map(|&(i, j)| (Feature::Particle(i), Feature::Particle(j)))
            .chain(walls.iter().map(|&(w, i)| (Feature::Wall(w), Feature::Particle(i))));
        let lacking = keys_lacking(new, old.clone().map(|(k, _, _)| k));
        self.keys = PairKeys::from_candidates(spheres, walls, &lacking);
        // then where each carried contact goes and comes from: (new index, old block, slot)
        let mut keys = self.keys.iter().enumerate();
        let carried: Vec<(usize, usize, u32)> = old
            .map(|(k, b, s)| {
                let (n, _) =
                    keys.find(|&(_, key)| key == k).expect("every old touching pair is a key");
                (n, b, s)
            })
            .collect();
        drop((old_keys, old_slots));
        // then the contacts, laid out anew in key order, each block made with its count and
        // room for births when its first contact comes, each old block dropped once passed
        // (both in key order: the old and the new contacts are never all held at once)
        let blocks = blocks_for(self.keys.len());
        let mut count = vec![0usize; blocks];
        carried.iter().for_each(|&(n, _, _)| count[n / BLOCK] += 1);
        self.blocks.reserve_exact(blocks);
        self.slots = vec![NO_CONTACT; self.keys.len()];
        let mut old_blocks = old_blocks.into_iter().enumerate();
        let mut current = old_blocks.next();
        for (n, b, s) in carried {
            while current.as_ref().is_some_and(|(index, _)| *index < b) {
                current = old_blocks.next();
            }
            let from = current.as_ref().and_then(|(_, block)| block.get(s));
            let contact = from.cloned().expect("a carried pair touches");
            while self.blocks.len() <= n / BLOCK {
                self.blocks.push(BlockContacts::with_room(count[self.blocks.len()]));
            }
            self.slots[n] = self.blocks[n / BLOCK].push_carried(contact);
        }
        while self.blocks.len() < blocks {
            self.blocks.push(BlockContacts::with_room(count[self.blocks.len()]));
        }
    }
}

/// What [`NeighbourList::update_in_order`] hands on: the key of the next touching pair (the
/// contacts of smaller keys come first), then its node loads.
pub(crate) enum Sink<'a> {
    /// The next touching pair's key.
    Before(&'a ContactKey),
    /// One of its node loads.
    Load(&'a NodeLoad),
}

/// Which list the next contact in key order comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Pick {
    /// The general contacts' list, at this index.
    General(usize),
    /// The neighbour list, at this candidate index (a touching pair).
    Pair(usize),
}

/// The contacts of both lists in key order: the general contacts (sorted by key) and the
/// touching pairs of the neighbour list (sorted by key). The two never share a key.
pub(crate) fn merged<'a>(
    general: &'a [Contact],
    pairs: &'a NeighbourList,
) -> impl Iterator<Item = Pick> + 'a {
    let (mut g, mut n) = (0, 0);
    std::iter::from_fn(move || {
        while n < pairs.keys.len() && !pairs.touches(n) {
            n += 1;
        }
        match (general.get(g), pairs.keys.try_get(n)) {
            (Some(c), Some(key)) if c.key() < key => {
                g += 1;
                Some(Pick::General(g - 1))
            }
            (Some(_), None) => {
                g += 1;
                Some(Pick::General(g - 1))
            }
            (_, Some(_)) => {
                n += 1;
                Some(Pick::Pair(n - 1))
            }
            (None, None) => None,
        }
    })
}

/// The indices of `fresh_general` (into the general list) and `fresh_pairs` (into the
/// neighbour list), both sorted by key, merged in key order (no buffer).
pub(crate) fn merged_fresh<'a>(
    general: &'a [Contact],
    fresh_general: &'a [usize],
    pairs: &'a NeighbourList,
    fresh_pairs: &'a [usize],
) -> impl Iterator<Item = Pick> + 'a {
    let (mut a, mut b) = (0, 0);
    std::iter::from_fn(move || {
        let take_general = match (fresh_general.get(a), fresh_pairs.get(b)) {
            (Some(&g), Some(&n)) => general[g].key() < pairs.keys.get(n),
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (None, None) => return None,
        };
        if take_general {
            a += 1;
            Some(Pick::General(fresh_general[a - 1]))
        } else {
            b += 1;
            Some(Pick::Pair(fresh_pairs[b - 1]))
        }
    })
}

/// The keys of `old` (sorted) that `new` (sorted) lacks, in order.
fn keys_lacking(
    new: impl Iterator<Item = ContactKey>,
    old: impl Iterator<Item = ContactKey>,
) -> Vec<ContactKey> {
    let mut new = new.peekable();
    old.filter(|k| {
        while new.next_if(|key| key < k).is_some() {}
        new.peek() != Some(k)
    })
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_candidate_costs_its_key_and_a_slot_and_a_touching_pair_its_contact() {
        use std::mem::size_of;
        // the 3 to 5 candidates per sphere of a packing: 12 bytes each (two ids and a
        // slot, `pair_keys.rs`); the 1.5 to 2 touching ones: a contact each besides (its
        // size known: a change shows here)
        assert_eq!(size_of::<(u32, u32)>() + size_of::<u32>(), 12);
        assert_eq!(size_of::<PairContact>(), 112);
    }

    impl NeighbourList {
        /// Makes candidate `index` touch with `contact`.
        fn set(&mut self, index: usize, contact: PairContact) {
            self.slots[index] = self.blocks[index / BLOCK].insert(contact);
        }
    }

    /// A contact told apart by its normal force.
    fn contact(normal_force: Real) -> PairContact {
        let mut state = FrictionalContact::new(Vec3::z());
        state.normal_force = normal_force;
        PairContact {
            params: FrictionalParams { kn: 1.0, ks: 0.5, tan_phi: 0.3, cn: 0.0, ct: 0.0 },
            state,
        }
    }

    #[test]
    fn a_rebuild_carries_the_touching_pairs_by_key_and_keeps_those_it_lost() {
        let mut list = NeighbourList::default();
        list.rebuild(vec![(0, 1), (0, 2), (1, 2)], &[(0, 1)]);
        assert_eq!(list.candidates(), 4);
        list.set(1, contact(2.0)); // (0, 2)
        list.set(3, contact(3.0)); // wall 0, particle 1
        list.rebuild(vec![(0, 2), (2, 3)], &[]);
        let touching: Vec<_> = list.touching().map(|(k, c)| (k, c.state.normal_force)).collect();
        assert_eq!(
            touching,
            vec![
                ((Feature::Particle(0), Feature::Particle(2)), 2.0),
                ((Feature::Wall(0), Feature::Particle(1)), 3.0)
            ]
        );
        assert_eq!(list.candidates(), 3);
        assert!(list.fits(4, 1) && !list.fits(3, 1) && !list.fits(4, 0));
    }

    #[test]
    fn saved_and_compared_as_its_touching_pairs() {
        let mut a = NeighbourList::default();
        a.rebuild(vec![(0, 1), (1, 2)], &[]);
        a.set(1, contact(1.0));
        let mut b = NeighbourList::default();
        b.rebuild(vec![(1, 2)], &[(0, 0)]);
        b.set(0, contact(1.0));
        assert_eq!(a, b);
        let saved: Vec<(ContactKey, PairContact)> = a.clone().into();
        assert_eq!(saved.len(), 1);
        assert_eq!(NeighbourList::from(saved), b);
    }
}
