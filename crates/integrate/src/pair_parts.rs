//! The candidate pairs split into parts for the parallel update (issue 14): each part a run
//! of whole chunks of pairs, stepped on one thread in key order; a spheres' part owns the
//! particles from the first sphere of its first pair to the first of the next one's (a
//! walls' part, below, owns none). A particle whose loads all come from pairs of two spheres of
//! its owner's part has them summed there as they come, as the one-thread pass sums them: from
//! zero, in key order. The parts keep the loads on the other particles, in pair order, in lists
//! by the particle's owner (`part_step.rs`); once all are done, each owner's lists are added in
//! part order, which is key order: after the part's sum for a particle whose only other loads
//! are walls' (whose pairs come last in key order, after every pair of two spheres), onto zero
//! for one loaded from several parts. A particle that a general contact loads is summed from
//! zero over all its entries from the index (`gather.rs`). Every particle's sum is the same
//! additions in the same order whatever the split, so the split may follow the thread count.
//!
//! When the spheres' pairs fill at least a chunk per part asked for, the walls' pairs
//! (after the spheres' in key order) are split into parts of their own, each a run of
//! chunks whose spheres one spheres' part owns, and stepped with that part, on its thread
//! ([`PairParts::runs`]): a sphere's wall is then met by the thread that steps the sphere's
//! other pairs and its leapfrog. (In one part, the packing's floor, which every tenth
//! sphere of 10⁵ touches, had one thread read and load half of the spheres of the other at
//! every step: on a host that put the two cores on two AMD core complexes, where a line one
//! core reads and the other writes goes through the I/O die, the leapfrog stage took 1.35
//! times as long as with a shared L3, 1.518 against 1.125 ms; `bench/README.md`,
//! twenty-third session.)
//!
//! With two parts of a packing of 10⁵ spheres in Morton order, 1 % of the spheres get loads
//! from both parts and 14 % touch a wall: the gather of every particle's loads, which the
//! one-thread pass does not need, took 14 % of a two-thread step. With 8 parts, 7 % get
//! loads from several parts; gathered from the index (three scattered reads per load), they
//! and the walls' loads took 8 % of the step.

use crate::neighbours::NeighbourList;
use crate::pair_chunk::PAIR_CHUNK;
use crate::pair_keys::PairKeys;
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

/// Spheres' parts per thread: more parts share the work better between threads when one is slowed
/// (see `parallel::MAX_CHUNKS_PER_TASK`), and put more particles on the parts' borders
/// (packing of 10⁵ spheres with 8 parts: 7 % of the spheres loaded from several). With 2 per
/// thread, 2 threads: the same fastest step as with 4 (4.800 against 4.783 ms), but a median
/// of 6.737 against 5.526 ms over 12 runs on a shared host (`bench/alternate.sh`).
pub(crate) const PARTS_PER_THREAD: usize = 4;

/// The cost of a wall's pair in the parallel update, in pairs of two spheres (10⁵-sphere
/// packing in a box, 2 threads: 42 ns against 17.5 ns; the walls' pairs are last, and with
/// parts of equal numbers of pairs the last took 1.6 times as long as the others).
const WALL_PAIR_COST: f64 = 2.4;

/// The cost of chunk `c` of `len` pairs whose walls' pairs start at `first_wall`, in pairs
/// of two spheres ([`WALL_PAIR_COST`] a wall's pair).
fn chunk_cost(c: usize, len: usize, first_wall: usize) -> f64 {
    let (start, end) = (c * PAIR_CHUNK, ((c + 1) * PAIR_CHUNK).min(len));
    let walls = end.saturating_sub(first_wall.max(start));
    (end - start - walls) as f64 + walls as f64 * WALL_PAIR_COST
}

/// Splits chunks whose costs are `cost` into `parts` runs of whole chunks of about the same
/// cost (each run ends at the first chunk boundary where the cost before reaches its share):
/// `first_chunk` gets each run's first chunk, then the number of chunks.
fn split_costs(cost: &[f64], parts: usize, first_chunk: &mut Vec<usize>) {
    let total: f64 = cost.iter().sum();
    first_chunk.clear();
    first_chunk.push(0);
    let (mut c, mut before) = (0, 0.0);
    for p in 1..parts {
        let target = total * p as f64 / parts as f64;
        while c < cost.len() && before < target {
            before += cost[c];
            c += 1;
        }
        first_chunk.push(c);
    }
    first_chunk.push(cost.len());
}

/// The sphere of pair `n` of `keys` (below `particles`): the first of two spheres, a wall's
/// sphere; `particles` past the end.
fn pair_sphere(keys: &PairKeys, n: usize, particles: usize) -> usize {
    match keys.try_get(n) {
        Some((Feature::Particle(i), _)) | Some((Feature::Wall(_), Feature::Particle(i))) => {
            (i as usize).min(particles)
        }
        _ => particles,
    }
}

/// The sphere of the middle pair of chunk `c` of `keys` ([`pair_sphere`]): where a walls'
/// chunk's spheres are (a wall's pairs are in the order of their spheres).
fn middle_sphere(keys: &PairKeys, c: usize, particles: usize) -> usize {
    let end = ((c + 1) * PAIR_CHUNK).min(keys.len());
    pair_sphere(keys, (c * PAIR_CHUNK + end) / 2, particles)
}

/// Splits `len` pairs, whose walls' pairs start at `first_wall`, into `parts` runs of whole
/// chunks of about the same cost ([`WALL_PAIR_COST`]): `first_chunk` gets each run's first
/// chunk, then the number of chunks.
#[cfg(test)]
fn split_by_cost(len: usize, first_wall: usize, parts: usize, first_chunk: &mut Vec<usize>) {
    let cost: Vec<f64> =
        (0..len.div_ceil(PAIR_CHUNK)).map(|c| chunk_cost(c, len, first_wall)).collect();
    split_costs(&cost, parts, first_chunk);
}

/// The split of a neighbour list's pairs into parts and how each particle's loads are
/// summed (nothing here is saved).
#[derive(Clone, Debug, Default)]
pub(crate) struct PairParts {
    /// The neighbour list generation, particle count and count of parts asked for, of the
    /// split.
    built_for: Option<(u64, usize, usize)>,
    /// Per part, its first chunk of [`PAIR_CHUNK`] pairs; then the number of chunks. The
    /// spheres' parts come first, then the walls' parts.
    first_chunk: Vec<usize>,
    /// Per part, the first particle it owns (a walls' part owns none: the particle count);
    /// then the number of particles.
    first_particle: Vec<usize>,
    /// The number of spheres' parts: the parts that own particles.
    spheres: usize,
    /// Per part, the spheres' part it is stepped with: its own for a spheres' part, for a
    /// walls' part the owner of its chunks' middle spheres.
    home: Vec<usize>,
    /// Per spheres' part, where its run (itself, then the walls' parts stepped with it)
    /// starts in the order the parts are stepped (by `home`, then in part order); then the
    /// number of parts.
    run_start: Vec<usize>,
    /// Per chunk of spheres' pairs, its cost with that of the walls' chunks its spheres go
    /// with (the split's buffer).
    chunk_cost: Vec<f64>,
    /// Per chunk of spheres' pairs, the sphere of its first pair (the split's buffer).
    chunk_sphere: Vec<usize>,
    /// Per particle, from the pairs alone.
    by_pairs: Vec<SumBy>,
    /// Whether the last update of the pairs was in these parts.
    in_use: bool,
    /// Per particle at this step: `by_pairs`, with the general contacts' particles
    /// [`SumBy::Gather`] (when there are general contacts).
    this_step: Vec<SumBy>,
    /// Whether `this_step` holds this step's (else `by_pairs` does).
    general: bool,
    /// Per chunk of pairs, whether each of its pairs is of two spheres its part sums
    /// ([`SumBy::Part`] or [`SumBy::PartThenWalls`], from the pairs alone).
    summed_in_part: Vec<bool>,
}

impl PairParts {
    /// Splits the candidate pairs of `pairs` into `parts` spheres' parts (at most one per
    /// chunk) and the walls' parts ([`PairParts::split_chunks`]) for `particles` particles,
    /// unless done already; `entries(i)` are particle `i`'s entries
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
        self.split_chunks(pairs, particles, parts);
        let first_wall = pairs.keys().first_wall();
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
        let in_part = |i: u32| self.by_pairs[i as usize] != SumBy::Deferred;
        let chunk_in_part = |c: usize| {
            let end = ((c + 1) * PAIR_CHUNK).min(keys.len());
            (c * PAIR_CHUNK..end).all(|n| match keys.get(n) {
                (Feature::Particle(a), Feature::Particle(b)) => in_part(a) && in_part(b),
                _ => false,
            })
        };
        // (its memory kept from split to split)
        let mut summed = std::mem::take(&mut self.summed_in_part);
        summed.clear();
        summed.extend((0..keys.len().div_ceil(PAIR_CHUNK)).map(chunk_in_part));
        self.summed_in_part = summed;
        self.built_for = built_for;
    }

    /// Splits the pairs of `pairs` (for `particles` particles) into about `parts` spheres'
    /// parts, then walls' parts ([`PairParts::split_spheres`], [`PairParts::split_walls`]).
    fn split_chunks(&mut self, pairs: &NeighbourList, particles: usize, parts: usize) {
        let keys = pairs.keys();
        let (len, first_wall) = (keys.len(), keys.first_wall());
        // the chunks that hold a pair of two spheres (the last may hold walls' pairs too)
        let chunks = len.div_ceil(PAIR_CHUNK);
        let sphere_chunks = first_wall.div_ceil(PAIR_CHUNK).min(chunks);
        // too few spheres' chunks for the parts asked (spheres sparse between walls): every
        // chunk is split by cost, as the spheres' are, and no walls' part is made
        let split = if sphere_chunks >= parts { sphere_chunks } else { chunks };
        self.split_spheres(keys, particles, parts, split);
        self.split_walls(keys, particles, split);
    }

    /// The first `costed` chunks (those of spheres' pairs, or all) in `parts` runs of
    /// about the same cost (at most one per chunk), each chunk's with that of the walls'
    /// chunks after them whose middle sphere is among its own ([`middle_sphere`]); each owns
    /// the particles from the sphere of its first pair, none from a walls' pair (the pairs
    /// are in key order: these do not decrease). `first_chunk` and `first_particle` get the
    /// runs' starts, not yet the ends.
    fn split_spheres(&mut self, keys: &PairKeys, particles: usize, parts: usize, costed: usize) {
        let (len, first_wall) = (keys.len(), keys.first_wall());
        // (a chunk that starts with a walls' pair, when all are split so: from the end)
        let first_sphere = |c: usize| {
            let n = c * PAIR_CHUNK;
            if n < first_wall {
                pair_sphere(keys, n, particles)
            } else {
                particles
            }
        };
        self.chunk_sphere.clear();
        self.chunk_sphere.extend((0..costed).map(first_sphere));
        self.chunk_cost.clear();
        self.chunk_cost.extend((0..costed).map(|c| chunk_cost(c, len, first_wall)));
        if costed > 0 {
            for c in costed..len.div_ceil(PAIR_CHUNK) {
                let i = middle_sphere(keys, c, particles);
                let home = self.chunk_sphere.partition_point(|&first| first <= i).max(1) - 1;
                self.chunk_cost[home] += chunk_cost(c, len, first_wall);
            }
        }
        self.spheres = parts.clamp(1, costed.max(1));
        split_costs(&self.chunk_cost, self.spheres, &mut self.first_chunk);
        self.first_chunk.pop();
        self.first_particle.clear();
        self.first_particle.push(0);
        let first = |c: usize| self.chunk_sphere.get(c).copied().unwrap_or(particles);
        let firsts = self.first_chunk[1..].iter().map(|&c| first(c));
        self.first_particle.extend(firsts);
    }

    /// The walls' chunks (from chunk `sphere_chunks` on) in walls' parts: runs of chunks
    /// whose middle spheres ([`middle_sphere`]) one spheres' part owns, each stepped with
    /// that part (`home`, `run_start`) and owning no particle; then the
    /// ends of `first_chunk` and `first_particle`.
    fn split_walls(&mut self, keys: &PairKeys, particles: usize, sphere_chunks: usize) {
        let chunks = keys.len().div_ceil(PAIR_CHUNK);
        self.home.clear();
        self.home.extend(0..self.spheres);
        let owners = &self.first_particle[..self.spheres];
        for c in sphere_chunks..chunks {
            let i = middle_sphere(keys, c, particles);
            let home = owners.partition_point(|&first| first <= i) - 1;
            if self.home.len() == self.spheres || self.home.last() != Some(&home) {
                self.home.push(home);
                self.first_chunk.push(c);
            }
        }
        self.first_chunk.push(chunks);
        let parts = self.home.len();
        self.first_particle.resize(parts + 1, particles);
        // the runs: the parts by home, then in part order
        let home = &self.home;
        self.run_start.clear();
        self.run_start
            .extend((0..self.spheres).map(|g| (0..parts).filter(|&p| home[p] < g).count()));
        self.run_start.push(parts);
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

    /// Whether chunk `c`'s pairs are all of two spheres whose loads its part sums at this
    /// step (no general contact loads them): its loads can be added as they come, with no
    /// particle's [`SumBy`] looked at.
    #[inline]
    pub(crate) fn summed_in_part(&self, c: usize) -> bool {
        !self.general && self.summed_in_part.get(c) == Some(&true)
    }

    /// How each particle's loads are summed at this step.
    pub(crate) fn sum_by(&self) -> &[SumBy] {
        if self.general {
            &self.this_step
        } else {
            &self.by_pairs
        }
    }

    /// The number of spheres' parts: the parts that own particles, the first ones.
    pub(crate) fn owners(&self) -> usize {
        self.spheres
    }

    /// Per part, the spheres' part it is stepped with (its run); and per run where it starts
    /// in the order the parts are stepped (by run, then in part order), then the number of
    /// parts.
    pub(crate) fn runs(&self) -> (&[usize], &[usize]) {
        (&self.home, &self.run_start)
    }

    /// The number of parts, the walls' included.
    pub(crate) fn len(&self) -> usize {
        self.first_chunk.len().saturating_sub(1)
    }

    /// Part `p`'s chunks of pairs.
    pub(crate) fn chunks(&self, p: usize) -> std::ops::Range<usize> {
        self.first_chunk[p]..self.first_chunk[p + 1]
    }

    /// Per spheres' part, the first particle it owns, then the particle count, when the pairs
    /// were stepped in these parts at the last update ([`PairParts::set_in_use`]); empty if
    /// not. The threads step the particles as they stepped these parts.
    pub(crate) fn homes(&self) -> &[usize] {
        if self.in_use {
            &self.first_particle[..=self.spheres]
        } else {
            &[]
        }
    }

    /// Says whether the last update of the pairs was in these parts.
    pub(crate) fn set_in_use(&mut self, in_use: bool) {
        self.in_use = in_use;
    }

    /// The particles part `p` owns.
    pub(crate) fn particles(&self, p: usize) -> std::ops::Range<usize> {
        self.first_particle[p]..self.first_particle[p + 1]
    }

    /// The part that owns particle `i` (below the particle count): the last whose first
    /// particle is at most `i` (a part that owns none starts where the next does).
    #[inline]
    pub(crate) fn owner(&self, i: usize) -> usize {
        self.first_particle[..=self.spheres].partition_point(|&first| first <= i) - 1
    }
}

#[cfg(test)]
mod tests {
    use super::{middle_sphere, split_by_cost, PairParts, PAIR_CHUNK, WALL_PAIR_COST};
    use crate::neighbours::NeighbourList;
    use flexdem_elements::virtual_sphere::Feature;
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
        let parts =
            PairParts { first_particle: vec![0, 3, 3, 7, 10], spheres: 4, ..Default::default() };
        let owners: Vec<usize> = (0..10).map(|i| parts.owner(i)).collect();
        assert_eq!(owners, [0, 0, 0, 2, 2, 2, 2, 3, 3, 3]);
        assert!((0..10).all(|i| parts.particles(parts.owner(i)).contains(&i)));
    }

    /// A packing's list: columns of ten spheres (each on the one below), a floor under every
    /// tenth sphere, a side wall along the first 3 000 and another at every hundredth. The
    /// walls' parts are runs of walls' chunks whose middle spheres one spheres' part owns,
    /// stepped in that part's run; every part is stepped once; the spheres' parts own the
    /// particles in order, the walls' parts none.
    #[test]
    fn walls_pairs_go_with_the_part_that_owns_their_spheres() {
        let n = 20_000u32;
        let spheres: Vec<(u32, u32)> =
            (0..n - 1).filter(|i| i % 10 != 9).map(|i| (i, i + 1)).collect();
        let mut walls: Vec<(u32, u32)> = (0..n).filter(|i| i % 10 == 0).map(|i| (0, i)).collect();
        walls.extend((0..3000).map(|i| (1, i)));
        walls.extend((0..n).filter(|i| i % 100 == 0).map(|i| (2, i)));
        let mut list = NeighbourList::default();
        list.rebuild(spheres, &walls);
        let (keys, particles) = (list.keys(), n as usize);
        let chunks = keys.len().div_ceil(PAIR_CHUNK);
        let sphere_chunks = keys.first_wall().div_ceil(PAIR_CHUNK);
        let mut parts = PairParts::default();
        parts.split(&list, particles, 4, |_| &[]);
        let owners = parts.owners();
        assert_eq!(owners, 4);
        assert!(parts.len() > owners + 1, "the walls' chunks in several parts: {}", parts.len());
        // the parts cover the chunks in order: the spheres' first, then the walls'
        assert_eq!(parts.chunks(0).start, 0);
        assert_eq!(parts.chunks(parts.len() - 1).end, chunks);
        assert!((1..parts.len()).all(|p| parts.chunks(p).start == parts.chunks(p - 1).end));
        assert_eq!(parts.chunks(owners).start, sphere_chunks);
        // the spheres' parts own the particles in order, the walls' parts none
        assert_eq!(parts.particles(0).start, 0);
        assert_eq!(parts.particles(owners - 1).end, particles);
        assert!((owners..parts.len()).all(|p| parts.particles(p).is_empty()));
        // each run: its spheres' part, then walls' parts whose chunks' spheres it owns
        let (home, runs) = parts.runs();
        assert_eq!((home.len(), runs.len()), (parts.len(), owners + 1));
        assert_eq!((runs[0], runs[owners]), (0, parts.len()));
        for g in 0..owners {
            assert_eq!(home[g], g);
            let size = (0..parts.len()).filter(|&p| home[p] == g).count();
            assert_eq!(runs[g + 1] - runs[g], size, "run {g}");
        }
        for q in owners..parts.len() {
            for c in parts.chunks(q) {
                assert_eq!(parts.owner(middle_sphere(keys, c, particles)), home[q], "chunk {c}");
            }
            // a walls' part is a run of chunks of one home: the next has another
            assert!(q + 1 == parts.len() || home[q + 1] != home[q], "part {q}");
        }
        assert!(
            (owners..parts.len()).any(|q| home[q] != owners - 1),
            "walls' parts on several homes"
        );
        // the leapfrog's homes: the spheres' parts' first particles, once the parts were used
        assert!(parts.homes().is_empty());
        parts.set_in_use(true);
        let homes: Vec<usize> =
            (0..owners).map(|p| parts.particles(p).start).chain([particles]).collect();
        assert_eq!(parts.homes(), homes);
    }

    /// Spheres sparse between walls (fewer spheres' chunks than parts asked for): every
    /// chunk is split by cost as the spheres' are, and no walls' part is made, so that the
    /// walls' pairs still spread over the threads.
    #[test]
    fn sparse_spheres_split_the_walls_pairs_with_theirs() {
        let n = 20_000u32;
        let spheres: Vec<(u32, u32)> =
            (0..n - 1).filter(|i| i % 20 == 0).map(|i| (i, i + 1)).collect();
        let walls: Vec<(u32, u32)> = (0..2).flat_map(|w| (0..n).map(move |i| (w, i))).collect();
        let mut list = NeighbourList::default();
        list.rebuild(spheres, &walls);
        let mut parts = PairParts::default();
        parts.split(&list, n as usize, 8, |_| &[]);
        assert_eq!(parts.owners(), 8);
        assert_eq!(parts.len(), 8, "no walls' part");
        assert_eq!(parts.chunks(7).end, list.keys().len().div_ceil(PAIR_CHUNK));
        // the parts after the spheres' pairs own no particle; the owners cover them all
        assert_eq!(parts.particles(0).start, 0);
        assert!((0..n as usize).all(|i| parts.particles(parts.owner(i)).contains(&i)));
        assert!(parts.particles(7).is_empty());
    }

    /// A chunk is summed in its part when every pair of it is of two spheres that only pairs
    /// of that part load: a chain's chunks but those holding a pair across two parts, and no
    /// walls' chunk; none at a step with general contacts.
    #[test]
    fn chunks_summed_in_their_part_hold_no_pair_across_parts() {
        let n = 40 * PAIR_CHUNK as u32;
        let spheres: Vec<(u32, u32)> = (0..n - 1).map(|i| (i, i + 1)).collect();
        let walls: Vec<(u32, u32)> = (0..n).step_by(7).map(|i| (0, i)).collect();
        let mut list = NeighbourList::default();
        list.rebuild(spheres, &walls);
        let keys = list.keys();
        let mut entries = vec![Vec::new(); n as usize];
        for (k, &(a, b)) in keys.ids().iter().enumerate() {
            match keys.get(k) {
                (Feature::Particle(_), Feature::Particle(_)) => {
                    entries[a as usize].push(2 * k as u32);
                    entries[b as usize].push(2 * k as u32 + 1);
                }
                _ => entries[b as usize].push(2 * k as u32 + 1),
            }
        }
        entries.iter_mut().for_each(|e| e.sort_unstable());
        let mut parts = PairParts::default();
        parts.split(&list, n as usize, 4, |i| &entries[i]);
        let chunks = keys.len().div_ceil(PAIR_CHUNK);
        let first_wall_chunk = keys.first_wall() / PAIR_CHUNK;
        // (the chunks on either side of a part's start: the pair across holds one sphere of
        // each part, the next pair the later one's first sphere, loaded from both)
        let starts: Vec<usize> = (1..parts.owners()).map(|p| parts.chunks(p).start).collect();
        let across = |c: usize| starts.iter().any(|&s| c + 1 == s || c == s);
        for c in 0..chunks {
            let expected = c < first_wall_chunk && !across(c);
            assert_eq!(parts.summed_in_part(c), expected, "chunk {c}");
        }
        let summed = (0..chunks).filter(|&c| parts.summed_in_part(c)).count();
        assert_eq!(summed, first_wall_chunk - 2 * starts.len());
        parts.with_general(true, |i| i == 5);
        assert!((0..chunks).all(|c| !parts.summed_in_part(c)));
        parts.with_general(false, |_| false);
        assert!(parts.summed_in_part(1));
    }
}
