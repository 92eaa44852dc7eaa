//! The candidate pairs split into parts for the parallel update (issue 14): each part a run
//! of whole chunks of pairs, stepped on one thread in key order, and owning the particles
//! from the first sphere of its first pair to the first of the next part's. A particle whose
//! loads all come from pairs of two spheres of its owner's part has them summed there as
//! they come, as the one-thread pass sums them: from zero, in key order. The parts keep the
//! loads on the other particles, in pair order, in lists by the particle's owner
//! (`part_step.rs`); once all are done, each owner's lists are added in part order, which is
//! key order: after the part's sum for a particle whose only other loads are walls' (whose
//! pairs come last in key order, after every pair of two spheres), onto zero for one loaded
//! from several parts. A particle that a general contact loads is summed from zero over all
//! its entries from the index (`gather.rs`). Every particle's sum is the same additions in the
//! same order whatever the split, so the split may follow the thread count.
//!
//! With two parts of a packing of 10⁵ spheres in Morton order, 1 % of the spheres get loads
//! from both parts and 14 % touch a wall: the gather of every particle's loads, which the
//! one-thread pass does not need, took 14 % of a two-thread step. With 8 parts, 7 % get
//! loads from several parts; gathered from the index (three scattered reads per load), they
//! and the walls' loads took 8 % of the step.

use crate::neighbours::NeighbourList;
use crate::pair_chunk::PAIR_CHUNK;
use flexdem_elements::virtual_sphere::Feature;

/// How a particle's loads are summed when the pairs are stepped in parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SumBy {
    /// Every load comes from pairs of two spheres of the part that owns it: summed there.
    Part,
    /// As [`SumBy::Part`], then its walls' loads, kept by their parts, added.
    PartThenWalls,
    /// Loads from more than one part: each part keeps its loads on it, added in part order
    /// onto zero.
    Deferred,
    /// Loaded by a general contact: summed by the gather from the index.
    Gather,
}

/// Parts per thread: more parts share the work better between threads when one is slowed
/// (see `parallel::MAX_CHUNKS_PER_TASK`), and put more particles on the parts' borders
/// (packing of 10⁵ spheres with 8 parts: 7 % of the spheres loaded from several). With 2 per
/// thread, 2 threads: the same fastest step as with 4 (4.800 against 4.783 ms), but a median
/// of 6.737 against 5.526 ms over 12 runs on a shared host (`bench/alternate.sh`).
pub(crate) const PARTS_PER_THREAD: usize = 4;

/// The cost of a wall's pair in the parallel update, in pairs of two spheres (10⁵-sphere
/// packing in a box, 2 threads: 42 ns against 17.5 ns; the walls' pairs are last, and with
/// parts of equal numbers of pairs the last took 1.6 times as long as the others).
const WALL_PAIR_COST: f64 = 2.4;

/// Splits `len` pairs, whose walls' pairs start at `first_wall`, into `parts` runs of whole
/// chunks of about the same cost ([`WALL_PAIR_COST`]): `first_chunk` gets each run's first
/// chunk, then the number of chunks.
fn split_by_cost(len: usize, first_wall: usize, parts: usize, first_chunk: &mut Vec<usize>) {
    let chunks = len.div_ceil(PAIR_CHUNK);
    // the cost of the pairs before pair n
    let cost_before = |n: usize| {
        let walls = n.saturating_sub(first_wall);
        (n - walls) as f64 + WALL_PAIR_COST * walls as f64
    };
    let total = cost_before(len);
    first_chunk.clear();
    first_chunk.push(0);
    let mut c = 0;
    for p in 1..parts {
        let target = total * p as f64 / parts as f64;
        while c < chunks && cost_before((c * PAIR_CHUNK).min(len)) < target {
            c += 1;
        }
        first_chunk.push(c);
    }
    first_chunk.push(chunks);
}

/// The split of a neighbour list's pairs into parts and how each particle's loads are
/// summed (nothing here is saved).
#[derive(Clone, Debug, Default)]
pub(crate) struct PairParts {
    /// The neighbour list generation, particle count and part count of the split.
    built_for: Option<(u64, usize, usize)>,
    /// Per part, its first chunk of [`PAIR_CHUNK`] pairs; then the number of chunks.
    first_chunk: Vec<usize>,
    /// Per part, the first particle it owns; then the number of particles.
    first_particle: Vec<usize>,
    /// Per particle, from the pairs alone.
    by_pairs: Vec<SumBy>,
    /// Per particle at this step: `by_pairs`, with the general contacts' particles
    /// [`SumBy::Gather`] (when there are general contacts).
    this_step: Vec<SumBy>,
    /// Whether `this_step` holds this step's (else `by_pairs` does).
    general: bool,
}

impl PairParts {
    /// Splits the candidate pairs of `pairs` into `parts` parts (at most one per chunk) for
    /// `particles` particles, unless done already; `entries(i)` are particle `i`'s entries
    /// among the pairs in pair order (`2·n + side`, `gather::LoadIndex`).
    pub(crate) fn split<'a>(
        &mut self,
        pairs: &NeighbourList,
        particles: usize,
        parts: usize,
        entries: impl Fn(usize) -> &'a [u32],
    ) {
        if self.is_split_for(pairs, particles, parts) {
            return;
        }
        let built_for = Some((pairs.generation(), particles, parts));
        let keys = pairs.keys();
        let chunks = keys.len().div_ceil(PAIR_CHUNK);
        let parts = parts.clamp(1, chunks.max(1));
        split_by_cost(keys.len(), keys.first_wall(), parts, &mut self.first_chunk);
        // a part owns from the sphere of its first pair (none: from the end, a part of walls'
        // pairs); the pairs are in key order, so these do not decrease
        let first_sphere = |chunk: usize| match keys.try_get(chunk * PAIR_CHUNK) {
            Some((Feature::Particle(i), _)) => (i as usize).min(particles),
            _ => particles,
        };
        self.first_particle.clear();
        self.first_particle.push(0);
        self.first_particle.extend(self.first_chunk[1..parts].iter().map(|&c| first_sphere(c)));
        self.first_particle.push(particles);
        let first_wall = keys.first_wall();
        let part_of_pair =
            |n: usize| self.first_chunk.partition_point(|&c| c <= n / PAIR_CHUNK) - 1;
        let mut owner = 0;
        self.by_pairs.clear();
        self.by_pairs.extend((0..particles).map(|i| {
            while self.first_particle[owner + 1] <= i {
                owner += 1;
            }
            let mut walls = false;
            for &code in entries(i) {
                let n = (code / 2) as usize;
                if n >= first_wall {
                    walls = true;
                } else if part_of_pair(n) != owner {
                    return SumBy::Deferred;
                }
            }
            if walls {
                SumBy::PartThenWalls
            } else {
                SumBy::Part
            }
        }));
        self.built_for = built_for;
    }

    /// Whether the split is that of `pairs` into `parts` parts for `particles` particles
    /// ([`PairParts::split`] would keep it).
    pub(crate) fn is_split_for(
        &self,
        pairs: &NeighbourList,
        particles: usize,
        parts: usize,
    ) -> bool {
        self.built_for == Some((pairs.generation(), particles, parts))
    }

    /// Marks for this step the particles that general contacts load (`loaded(i)`) as
    /// [`SumBy::Gather`]; none when `any` is false.
    pub(crate) fn with_general(&mut self, any: bool, loaded: impl Fn(usize) -> bool) {
        self.general = any;
        if !any {
            return;
        }
        self.this_step.clear();
        self.this_step.extend(self.by_pairs.iter().enumerate().map(|(i, &by)| {
            if loaded(i) {
                SumBy::Gather
            } else {
                by
            }
        }));
    }

    /// How each particle's loads are summed at this step.
    pub(crate) fn sum_by(&self) -> &[SumBy] {
        if self.general {
            &self.this_step
        } else {
            &self.by_pairs
        }
    }

    /// The number of parts.
    pub(crate) fn len(&self) -> usize {
        self.first_chunk.len().saturating_sub(1)
    }

    /// Part `p`'s chunks of pairs.
    pub(crate) fn chunks(&self, p: usize) -> std::ops::Range<usize> {
        self.first_chunk[p]..self.first_chunk[p + 1]
    }

    /// The particles part `p` owns.
    pub(crate) fn particles(&self, p: usize) -> std::ops::Range<usize> {
        self.first_particle[p]..self.first_particle[p + 1]
    }

    /// The part that owns particle `i` (below the particle count): the last whose first
    /// particle is at most `i` (a part that owns none starts where the next does).
    #[inline]
    pub(crate) fn owner(&self, i: usize) -> usize {
        self.first_particle.partition_point(|&first| first <= i) - 1
    }
}

#[cfg(test)]
mod tests {
    use super::{split_by_cost, PairParts, PAIR_CHUNK, WALL_PAIR_COST};
    use proptest::prelude::*;

    /// The cost of chunks `a..b` of `len` pairs whose walls' start at `first_wall`.
    fn cost(a: usize, b: usize, len: usize, first_wall: usize) -> f64 {
        (a * PAIR_CHUNK..(b * PAIR_CHUNK).min(len))
            .map(|n| if n >= first_wall { WALL_PAIR_COST } else { 1.0 })
            .sum()
    }

    proptest! {
        /// The parts are runs of whole chunks covering all of them in order, each costing
        /// at most its share plus one chunk's worth of walls' pairs.
        #[test]
        fn parts_cover_the_chunks_in_shares_of_the_cost(
            len in 1usize..40 * PAIR_CHUNK,
            walls in 0.0f64..1.0,
            parts in 1usize..13,
        ) {
            let first_wall = ((1.0 - walls) * len as f64) as usize;
            let mut first_chunk = Vec::new();
            split_by_cost(len, first_wall, parts, &mut first_chunk);
            let chunks = len.div_ceil(PAIR_CHUNK);
            prop_assert_eq!(first_chunk.len(), parts + 1);
            prop_assert_eq!((first_chunk[0], first_chunk[parts]), (0, chunks));
            prop_assert!(first_chunk.windows(2).all(|w| w[0] <= w[1]));
            let share = cost(0, chunks, len, first_wall) / parts as f64;
            let most = share + WALL_PAIR_COST * PAIR_CHUNK as f64;
            for w in first_chunk.windows(2) {
                prop_assert!(cost(w[0], w[1], len, first_wall) <= most);
            }
        }
    }

    /// Equal pairs split into equal parts; walls' pairs, dearer, into fewer chunks per part.
    #[test]
    fn walls_pairs_count_for_more() {
        let mut first_chunk = Vec::new();
        split_by_cost(8 * PAIR_CHUNK, 8 * PAIR_CHUNK, 2, &mut first_chunk);
        assert_eq!(first_chunk, [0, 4, 8]);
        split_by_cost(8 * PAIR_CHUNK, 4 * PAIR_CHUNK, 2, &mut first_chunk);
        assert_eq!(first_chunk, [0, 6, 8]);
    }

    /// A particle's owner is the part whose particles hold it, past parts that own none.
    #[test]
    fn a_particle_is_owned_by_the_part_whose_range_holds_it() {
        let parts = PairParts { first_particle: vec![0, 3, 3, 7, 10], ..Default::default() };
        let owners: Vec<usize> = (0..10).map(|i| parts.owner(i)).collect();
        assert_eq!(owners, [0, 0, 0, 2, 2, 2, 2, 3, 3, 3]);
        assert!((0..10).all(|i| parts.particles(parts.owner(i)).contains(&i)));
    }
}
