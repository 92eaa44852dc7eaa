//! The contacts' node loads summed per particle, in parallel over the particles, each
//! particle's loads in the contacts' key order: the same additions, in the same order, as the
//! one-thread pass that adds every contact's loads as it goes (`ContactPipeline::apply`), so
//! that the results do not depend on the number of threads. It replaces a pass over every
//! contact on one thread after the parallel update, which capped the speed-up of two threads
//! (issue 14).
//!
//! A particle's loads come from two lists, both sorted by key: the general contacts (rebuilt
//! each step, indexed here each step) and the free spheres' candidate pairs (indexed once per
//! set of candidates, `NeighbourList::generation`). The two never share a key; each
//! particle's entries of the two are merged by key.

use crate::contact::Contact;
use crate::homes::{in_homes, Homes, Pieces, Runs, Sums};
use crate::integrator::CHUNK as STEP_CHUNK;
use crate::neighbours::NeighbourList;
use crate::pair_parts::SumBy;
use crate::pair_passes::PairScratch;
use crate::parallel::MAX_CHUNKS_PER_TASK;
use flexdem_elements::virtual_sphere::{Feature, NodeLoad};
use flexdem_geom::Vec3;
use rayon::prelude::*;

/// Particles per parallel task.
const CHUNK: usize = 1024;

/// Per particle, where its loads are: the candidate pairs it is in and the general contacts'
/// loads on it, each in key order (two CSR tables). Nothing here is saved.
#[derive(Clone, Debug, Default)]
pub(crate) struct LoadIndex {
    /// The neighbour list generation and particle count the pair table was built for.
    pairs_built_for: Option<(u64, usize)>,
    /// Per particle, its range in `pair_entries` (`pair_offsets[i]..pair_offsets[i + 1]`).
    pair_offsets: Vec<u32>,
    /// `2·n + side`: candidate pair `n`, the particle being its body 1 (side 0) or body 2.
    pair_entries: Vec<u32>,
    /// Per particle, its range in `general_entries`; empty when there is no general contact.
    general_offsets: Vec<u32>,
    /// `8·n + slot`: the load `slot` (0–5) of general contact `n`.
    general_entries: Vec<u32>,
    /// The counts of the counting sorts (a buffer).
    count: Vec<u32>,
}

/// A slot of a contact's six node loads that no particle receives (`load_nodes`).
pub(crate) const NO_NODE: u32 = u32::MAX;

/// The particles a contact's six node loads go to: the first `n1` slots (site 1's nodes) and
/// slots 3 to 3 + `n2` (site 2's), [`NO_NODE`] for the others.
#[inline]
pub(crate) fn load_nodes(n1: usize, n2: usize, loads: &[NodeLoad; 6]) -> [u32; 6] {
    std::array::from_fn(|slot| {
        let used = if slot < 3 { slot < n1 } else { slot - 3 < n2 };
        if used {
            loads[slot].node
        } else {
            NO_NODE
        }
    })
}

/// Whether `len` entries fit the `u32` codes of the index (`8·n + slot`, `2·n + side`).
pub(crate) fn fits_codes(general: usize, pairs: usize) -> bool {
    general < (u32::MAX / 8) as usize && pairs < (u32::MAX / 2) as usize
}

impl LoadIndex {
    /// Indexes the candidate pairs of `pairs` for `particles` particles, unless done already.
    pub(crate) fn index_pairs(&mut self, pairs: &NeighbourList, particles: usize) {
        let built_for = Some((pairs.generation(), particles));
        if self.pairs_built_for == built_for {
            return;
        }
        let keys = pairs.keys();
        let entries = keys.iter().enumerate().flat_map(|(n, key)| {
            let side = |f: Feature, s: u32| match f {
                Feature::Particle(i) => Some((i, 2 * n as u32 + s)),
                _ => None,
            };
            side(key.0, 0).into_iter().chain(side(key.1, 1))
        });
        counting_sort(
            entries,
            particles,
            &mut self.count,
            &mut self.pair_offsets,
            &mut self.pair_entries,
        );
        self.pairs_built_for = built_for;
    }

    /// Frees the pair table and the sorts' counts (the next [`LoadIndex::index_pairs`]
    /// builds them anew): for the update in parts with no general contact, whose split reads
    /// the pairs' table only when it is made (once per neighbour list). On the packing of 10⁵
    /// spheres at 2 threads they were 62 of its 503 bytes per sphere.
    pub(crate) fn release_pairs(&mut self) {
        self.pairs_built_for = None;
        self.pair_offsets = Vec::new();
        self.pair_entries = Vec::new();
        self.count = Vec::new();
    }

    /// Indexes the loads of the general contacts from the particles each contact's six slots
    /// go to (`load_nodes`, as `apply` wrote them: body 1's first `n1`, body 2's from slot 3,
    /// [`NO_NODE`] for the others) for `particles` particles.
    pub(crate) fn index_general(&mut self, load_nodes: &[[u32; 6]], particles: usize) {
        // (24 bytes per contact read, where the contacts and their loads are 680)
        let entries = load_nodes.iter().enumerate().flat_map(|(n, nodes)| {
            let code = 8 * n as u32;
            (0..6u32).filter_map(move |slot| {
                let node = nodes[slot as usize];
                (node != NO_NODE).then_some((node, code + slot))
            })
        });
        self.index_general_entries(entries, particles);
    }

    /// The general contacts' table from its `(particle, code)` items, in contact order;
    /// empty (no entry for any particle, nothing counted) when there is none.
    fn index_general_entries(
        &mut self,
        entries: impl Iterator<Item = (u32, u32)> + Clone,
        particles: usize,
    ) {
        let (offsets, table) = (&mut self.general_offsets, &mut self.general_entries);
        if entries.clone().next().is_none() {
            offsets.clear();
            table.clear();
            return;
        }
        counting_sort(entries, particles, &mut self.count, offsets, table);
    }

    /// Writes in `force` and `torque` (one entry per particle) the sums of the loads of the
    /// general contacts (`list`, `loads`) and of the touching candidate pairs of `pairs` at
    /// its last parallel update (`scratch`), each particle's in key order from +0, in
    /// parallel over the particles: what adding them to zeroed arrays gave, bit for bit. With
    /// `sum_by` (the update was in parts, `pair_parts.rs`), only the particles the parts did
    /// not sum ([`SumBy::Gather`]); without, every particle's (no pass to zero them first).
    /// The index must be up to date ([`LoadIndex::index_pairs`],
    /// [`LoadIndex::index_general`]).
    #[allow(clippy::too_many_arguments, reason = "the sums, the two lists and the split")]
    pub(crate) fn write_loads(
        &self,
        force: &mut [Vec3],
        torque: &mut [Vec3],
        list: &[Contact],
        loads: &[[NodeLoad; 6]],
        pairs: &NeighbourList,
        scratch: &PairScratch,
        sum_by: Option<&[SumBy]>,
    ) {
        let general_load = |code: u32| &loads[(code / 8) as usize][(code % 8) as usize];
        let view = pairs.load_view(scratch);
        let pair_load = |code: u32| view.load((code / 2) as usize, (code % 2) as usize);
        let chunks = force.par_chunks_mut(CHUNK).zip(torque.par_chunks_mut(CHUNK)).enumerate();
        chunks.with_max_len(MAX_CHUNKS_PER_TASK).for_each(|(c, (f, t))| {
            for (k, (f, t)) in f.iter_mut().zip(t).enumerate() {
                let i = c * CHUNK + k;
                if sum_by.is_some_and(|s| s[i] != SumBy::Gather) {
                    // summed by the parts (`part_step.rs`)
                    continue;
                }
                if self.general_entries(i).is_empty() {
                    // no general contact on it (every particle of a granular scene): the
                    // pairs' entries alone, in their order, without the merge by key (two
                    // thirds of the gather's instructions in a packing), summed in
                    // registers and stored once
                    let (mut fi, mut ti) = (Vec3::zeros(), Vec3::zeros());
                    for &code in self.pair_entries(i) {
                        if let Some(l) = pair_load(code) {
                            fi += l.force;
                            ti += l.torque;
                        }
                    }
                    (*f, *t) = (fi, ti);
                    continue;
                }
                (*f, *t) = (Vec3::zeros(), Vec3::zeros());
                let mut add = |l: &NodeLoad| {
                    *f += l.force;
                    *t += l.torque;
                };
                // (a pair that does not touch adds nothing)
                self.in_key_order(i, list, pairs, |entry| match entry {
                    Entry::General(code) => add(general_load(code)),
                    Entry::Pair(code) => {
                        if let Some(l) = pair_load(code) {
                            add(&l);
                        }
                    }
                });
            }
        });
    }

    /// Particle `i`'s entries among the candidate pairs (`2·n + side`), in pair order. The
    /// pairs' index must be up to date ([`LoadIndex::index_pairs`]).
    #[inline]
    pub(crate) fn pair_entries(&self, i: usize) -> &[u32] {
        range(&self.pair_offsets, &self.pair_entries, i)
    }

    /// Particle `i`'s entries among the general contacts' loads (`8·n + slot`), in contact
    /// order (none when the general index is empty).
    #[inline]
    pub(crate) fn general_entries(&self, i: usize) -> &[u32] {
        range(&self.general_offsets, &self.general_entries, i)
    }

    /// Whether the general contacts' index has an entry.
    pub(crate) fn has_general(&self) -> bool {
        !self.general_entries.is_empty()
    }

    /// Gives `f` particle `i`'s entries in the contacts' key order: those of the general
    /// contacts `list` and of the candidate pairs of `pairs` (touching or not), the two
    /// lists merged by key. The index must be up to date.
    #[inline]
    pub(crate) fn in_key_order(
        &self,
        i: usize,
        list: &[Contact],
        pairs: &NeighbourList,
        mut f: impl FnMut(Entry),
    ) {
        let keys = pairs.keys();
        let general = range(&self.general_offsets, &self.general_entries, i);
        let paired = range(&self.pair_offsets, &self.pair_entries, i);
        let general_key = |code: u32| list[(code / 8) as usize].key();
        let pair_key = |code: u32| keys.get((code / 2) as usize);
        let (mut a, mut b) = (0, 0);
        while a < general.len() || b < paired.len() {
            let take_general = match (general.get(a), paired.get(b)) {
                (Some(&g), Some(&p)) => general_key(g) < pair_key(p),
                (Some(_), None) => true,
                _ => false,
            };
            if take_general {
                f(Entry::General(general[a]));
                a += 1;
            } else {
                f(Entry::Pair(paired[b]));
                b += 1;
            }
        }
    }
}

/// Writes in `force` and `torque` (one entry per particle) the sums of the general
/// contacts' node loads (`loads`, with the particles they go to, `load_nodes`, [`NO_NODE`]
/// for none), each particle's in contact order and slot order from +0: what adding them to
/// zeroed arrays in one pass gives, bit for bit, when no candidate pair touches (with
/// pairs touching, their loads come among these in key order: `LoadIndex`). In parallel
/// over the homes' ranges of particles (`homes.rs`: those the leapfrog steps on the same
/// thread; without homes as many equal ranges as there are threads), each home's ranges
/// zeroed, then given the loads on their particles by a scan of every contact's nodes (24
/// bytes a contact; a load is read only by its home). Without an index: for the PFacet
/// membrane of 10⁵ elements under spheres (9 300 contacts, no pair), the index of the general loads (a counting sort on one
/// thread) and the gather per particle took 195 and 274 µs of a 2-thread step.
pub(crate) fn write_general_loads(
    force: &mut [Vec3],
    torque: &mut [Vec3],
    loads: &[[NodeLoad; 6]],
    load_nodes: &[[u32; 6]],
    homes: &Homes,
) {
    let n = force.len().min(torque.len());
    let mut runs = Runs::new();
    let count = if homes.shares(n) && homes.len() == n {
        // the ranges of the step's homes: the threads write the sums the leapfrog reads
        homes.item_runs(n, STEP_CHUNK, &mut runs);
        homes.count()
    } else {
        let ranges = rayon::current_num_threads().max(1);
        let per = n.div_ceil(ranges).max(1);
        runs.extend((0..ranges).map(|r| (r * per, r)).filter(|&(s, _)| s < n));
        ranges
    };
    if runs.is_empty() {
        return;
    }
    let all = (&mut force[..n], &mut torque[..n]);
    in_homes(all, &runs, n, count, &|mut pieces: Pieces<Sums<'_>>| {
        for (_, (f, t)) in pieces.iter_mut() {
            f.fill(Vec3::zeros());
            t.fill(Vec3::zeros());
        }
        for (nodes, loads) in load_nodes.iter().zip(loads) {
            for (&node, l) in nodes.iter().zip(loads) {
                let node = node as usize;
                for (first, (f, t)) in pieces.iter_mut() {
                    if let Some(k) = node.checked_sub(*first).filter(|&k| k < f.len()) {
                        f[k] += l.force;
                        t[k] += l.torque;
                        break;
                    }
                }
            }
        }
    });
}

/// A particle's entry in the index: a general contact's `8·n + slot`, or a candidate pair's
/// `2·n + side`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Entry {
    /// Slot `code % 8` of general contact `code / 8`.
    General(u32),
    /// Side `code % 2` (0: body 1) of candidate pair `code / 2`.
    Pair(u32),
}

/// Entries of particle `i` in a CSR table (none beyond the table).
#[inline]
fn range<'a>(offsets: &[u32], entries: &'a [u32], i: usize) -> &'a [u32] {
    match (offsets.get(i), offsets.get(i + 1)) {
        (Some(&s), Some(&e)) => &entries[s as usize..e as usize],
        _ => &[],
    }
}

/// A CSR table of `(particle, code)` items: `offsets` (particles + 1) and `entries`, each
/// particle's codes in the order the items came (a stable counting sort).
fn counting_sort(
    items: impl Iterator<Item = (u32, u32)> + Clone,
    particles: usize,
    count: &mut Vec<u32>,
    offsets: &mut Vec<u32>,
    entries: &mut Vec<u32>,
) {
    count.clear();
    count.resize(particles + 1, 0);
    for (i, _) in items.clone() {
        count[i as usize + 1] += 1;
    }
    // (a running sum: count[0] is 0)
    let mut sum = 0;
    for c in count.iter_mut() {
        sum += *c;
        *c = sum;
    }
    offsets.clear();
    offsets.extend_from_slice(count);
    entries.clear();
    entries.resize(count[particles] as usize, 0);
    for (i, code) in items {
        let slot = &mut count[i as usize];
        entries[*slot as usize] = code;
        *slot += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The general loads summed per range of particles, with 1 to 4 threads, are the sums
    /// of one pass in contact and slot order onto zeros, to the bit: 500 contacts loading 3
    /// to 6 of 40 particles (about 60 loads each, of magnitudes from 10⁻³ to 10³, whose
    /// sums in another order differ).
    #[test]
    fn the_general_loads_per_range_are_the_one_pass_sums() {
        let particles = 40;
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut loads, mut nodes) = (Vec::new(), Vec::new());
        for _ in 0..500 {
            let mut l = [NodeLoad { node: 0, force: Vec3::zeros(), torque: Vec3::zeros() }; 6];
            let mut n = [NO_NODE; 6];
            let used = 3 + (next() * 4.0) as usize;
            for slot in 0..6 {
                let scale = 10f64.powf(6.0 * next() - 3.0);
                let mut v = || Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * scale;
                l[slot].force = v();
                l[slot].torque = v();
                if slot < used {
                    n[slot] = (next() * particles as f64) as u32;
                }
            }
            loads.push(l);
            nodes.push(n);
        }
        let mut one_pass = (vec![Vec3::zeros(); particles], vec![Vec3::zeros(); particles]);
        for (n, l) in nodes.iter().zip(&loads) {
            for slot in (0..6).filter(|&s| n[s] != NO_NODE) {
                one_pass.0[n[slot] as usize] += l[slot].force;
                one_pass.1[n[slot] as usize] += l[slot].torque;
            }
        }
        let bits = |v: &[Vec3]| -> Vec<[u64; 3]> {
            v.iter().map(|x| [x.x, x.y, x.z].map(f64::to_bits)).collect()
        };
        for threads in 1..=4 {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let (mut f, mut t) =
                (vec![Vec3::repeat(7.0); particles], vec![Vec3::repeat(7.0); particles]);
            let mut homes = Homes::default();
            pool.install(|| write_general_loads(&mut f, &mut t, &loads, &nodes, &homes));
            assert_eq!(bits(&f), bits(&one_pass.0), "{threads} threads");
            assert_eq!(bits(&t), bits(&one_pass.1), "{threads} threads");
            // the step's homes: blocks of particles cut by thread
            homes.set_by_blocks(&[0, particles / 3, particles / 2, particles], threads);
            f.fill(Vec3::repeat(7.0));
            t.fill(Vec3::repeat(7.0));
            pool.install(|| write_general_loads(&mut f, &mut t, &loads, &nodes, &homes));
            assert_eq!(bits(&f), bits(&one_pass.0), "{threads} threads, {homes:?}");
            assert_eq!(bits(&t), bits(&one_pass.1), "{threads} threads, {homes:?}");
        }
    }

    #[test]
    fn counting_sort_keeps_each_particles_order() {
        let items = [(2u32, 10u32), (0, 11), (2, 12), (1, 13), (0, 14)];
        let (mut count, mut offsets, mut entries) = (Vec::new(), Vec::new(), Vec::new());
        counting_sort(items.iter().copied(), 4, &mut count, &mut offsets, &mut entries);
        assert_eq!(offsets, vec![0, 2, 3, 5, 5]);
        assert_eq!(entries, vec![11, 14, 13, 10, 12]);
        assert_eq!(range(&offsets, &entries, 2), &[10, 12]);
        assert_eq!(range(&offsets, &entries, 3), &[] as &[u32]);
        assert_eq!(range(&offsets, &entries, 9), &[] as &[u32]);
    }
}
