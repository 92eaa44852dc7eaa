//! Broad phase: the pairs of overlapping axis-aligned boxes, by a cell list.
//!
//! Each box is entered in the cells of a uniform grid it covers; boxes sharing a cell are
//! tested, and a pair is reported only by the cell that holds the minimum corner of the two
//! boxes' intersection, so it is reported once without a hash set. Cells are found by sorting
//! (cell key, box) entries, so nothing is hashed and the output is deterministic. Boxes much
//! larger than a cell (a big sphere among small elements) go to a short list tested against
//! every box. The cost is O(N log N) for the sort plus O(N) for the tests at bounded density;
//! the engine calls it only when its Verlet distance is used up, not every step.

use flexdem_geom::{Aabb, Real, Vec3};
use rayon::prelude::*;

/// A box may cover at most this many cells per axis before it is treated as large.
const MAX_CELLS_PER_AXIS: i64 = 4;

/// Cell entries kept from build to build (128 KiB: a net or a cantilever of a few thousand
/// elements); more are given back after the build.
const KEPT_ENTRIES: usize = 1 << 14;

/// Reusable buffers for [`BroadPhase::overlapping_pairs`].
#[derive(Clone, Debug, Default)]
pub struct BroadPhase {
    /// (cell, box) entries, packed ([`Packing`]).
    entries: Vec<u64>,
    large: Vec<u32>,
    /// Where each cell's entries start, then their end.
    starts: Vec<usize>,
    /// Fewer bits for the entries than 64 (tests of cells that share a key).
    #[cfg(test)]
    entry_bits: Option<u32>,
}

/// Cell coordinates of a point for cells of size `h` anchored at `origin`.
fn cell_of(p: &Vec3, origin: &Vec3, inv_h: Real) -> [i64; 3] {
    std::array::from_fn(|k| floor_to_int((p[k] - origin[k]) * inv_h))
}

/// ⌊x⌋ as an integer, without libm's `floor` (not an instruction on baseline x86-64): the
/// truncation, one less when it rounded up. Saturates like `as` for huge values.
fn floor_to_int(x: Real) -> i64 {
    let t = x as i64;
    if (t as Real) > x {
        t - 1
    } else {
        t
    }
}

/// How an entry packs a cell and a box into one `u64` (8 bytes, where a `(u64, u32)` pair
/// takes 16, and sorted as one integer): the box's index in the low `index_bits`, the cell's
/// key above it, `bits[k]` bits of its coordinate on axis k. Each axis has the bits its
/// number of cells needs, so that no two cells share a key; a grid too large for the 64
/// bits (more than 2²¹ cells on an axis, or more cells and boxes than 2⁶⁴) takes bits from
/// its longest axes, and cells a multiple of 2^bits[k] apart then share a key: that only
/// adds tests of boxes that cannot intersect, never a missed or a doubled pair (an axis
/// keeps 10 bits at least, and a box covers at most [`MAX_CELLS_PER_AXIS`] cells per axis,
/// so it is never twice under one key).
#[derive(Clone, Copy, Debug)]
struct Packing {
    bits: [u32; 3],
    index_bits: u32,
}

/// Bits that hold the numbers 0 to n − 1.
fn bits_for(n: u64) -> u32 {
    u64::BITS - n.saturating_sub(1).leading_zeros()
}

impl Packing {
    /// The packing of `boxes` boxes in a grid of `cells` cells per axis into `total` bits
    /// (64; fewer in tests, to make cells share keys).
    fn new(cells: [i64; 3], boxes: usize, total: u32) -> Self {
        let index_bits = bits_for(boxes as u64).max(1);
        let mut bits = cells.map(|c| bits_for(c.clamp(1, 1 << 21) as u64));
        while index_bits + bits.iter().sum::<u32>() > total {
            let longest = (0..3).max_by_key(|&k| (bits[k], k)).expect("three axes");
            bits[longest] -= 1;
        }
        Packing { bits, index_bits }
    }

    /// The key of the cell at integer coordinates `c`.
    fn key(&self, c: [i64; 3]) -> u64 {
        let [bx, by, bz] = self.bits;
        let low = |x: i64, b: u32| x as u64 & ((1u64 << b) - 1);
        (low(c[0], bx) << (by + bz)) | (low(c[1], by) << bz) | low(c[2], bz)
    }

    /// The entry of box `i` in the cell of key `key`.
    fn entry(&self, key: u64, i: u32) -> u64 {
        (key << self.index_bits) | u64::from(i)
    }

    /// The cell key of an entry.
    fn key_of(&self, entry: u64) -> u64 {
        entry >> self.index_bits
    }

    /// The box of an entry.
    fn index_of(&self, entry: u64) -> u32 {
        (entry & ((1u64 << self.index_bits) - 1)) as u32
    }
}

/// Cell size: twice the median of the boxes' largest extents, so that a typical box covers
/// one or two cells per axis. Zero for no boxes. The extents are sorted in `scratch` (the
/// entries' buffer, a `u64` per box: no buffer of their own) as [`total_order_bits`].
fn choose_cell_size(boxes: impl Iterator<Item = Aabb>, scratch: &mut Vec<u64>) -> Real {
    scratch.clear();
    scratch.extend(
        boxes.map(|b| (b.maxs - b.mins).max()).filter(|e| e.is_finite()).map(total_order_bits),
    );
    if scratch.is_empty() {
        return 0.0;
    }
    let mid = scratch.len() / 2;
    let (_, median, _) = scratch.select_nth_unstable(mid);
    let median = from_total_order_bits(*median);
    scratch.clear();
    2.0 * median.max(Real::MIN_POSITIVE)
}

/// The bits of `x` as an integer whose order is `Real::total_cmp`'s: a negative number's bits
/// flipped, a positive one's sign bit set.
fn total_order_bits(x: Real) -> u64 {
    let b = x.to_bits();
    if b >> 63 == 1 {
        !b
    } else {
        b | 1 << 63
    }
}

/// The number of [`total_order_bits`].
fn from_total_order_bits(b: u64) -> Real {
    Real::from_bits(if b >> 63 == 1 { b & !(1 << 63) } else { !b })
}

/// The sorted cell entries of a build and where each cell's run of them starts.
struct Cells<'a> {
    entries: &'a [u64],
    /// Where each cell's entries start, then their end.
    starts: &'a [usize],
    packing: Packing,
    origin: Vec3,
    inv_h: Real,
}

impl Cells<'_> {
    /// Calls `found(i, j)`, `i < j`, for each pair of boxes that share one of the cells
    /// `cells` (indices into `starts`), intersect and that `accept` accepts, reported only by
    /// the cell that holds the minimum corner of their intersection (so once). Each cell's
    /// boxes are asked for once (`box_of` may make them from the elements' nodes) and kept
    /// while its pairs are tested.
    fn pairs<B, F>(
        &self,
        cells: std::ops::Range<usize>,
        box_of: &B,
        accept: &F,
        mut found: impl FnMut(u32, u32),
    ) where
        B: Fn(u32) -> Aabb,
        F: Fn(u32, u32) -> bool,
    {
        let Cells { entries, starts, packing, origin, inv_h } = self;
        let mut cell: Vec<(u32, Aabb)> = Vec::new();
        for b in cells {
            let (s, e) = (starts[b], starts[b + 1]);
            let key = packing.key_of(entries[s]);
            cell.clear();
            cell.extend(entries[s..e].iter().map(|&entry| {
                let i = packing.index_of(entry);
                (i, box_of(i))
            }));
            for (a, &(i, bi)) in cell.iter().enumerate() {
                for &(j, bj) in &cell[a + 1..] {
                    if !bi.intersects(&bj) {
                        continue;
                    }
                    let corner = bi.mins.sup(&bj.mins);
                    if packing.key(cell_of(&corner, origin, *inv_h)) != key {
                        continue;
                    }
                    let (p, q) = if i < j { (i, j) } else { (j, i) };
                    if accept(p, q) {
                        found(p, q);
                    }
                }
            }
        }
    }
}

impl BroadPhase {
    /// Writes into `pairs` every pair `(i, j)`, `i < j`, of boxes that intersect (closed
    /// boxes) and that `accept(i, j)` accepts, sorted and each once. `accept` carries the
    /// collision masks and the rule that adjacent elements never pair.
    ///
    /// Boxes with a NaN coordinate intersect nothing (the engine rejects NaN before).
    pub fn overlapping_pairs<F>(&mut self, boxes: &[Aabb], accept: F, pairs: &mut Vec<(u32, u32)>)
    where
        F: Fn(u32, u32) -> bool + Sync,
    {
        let box_of = |i: u32| boxes[i as usize];
        let no = |_, _| false;
        self.overlapping_pairs_split(boxes.len(), box_of, accept, no, &mut Vec::new(), pairs);
    }

    /// [`BroadPhase::overlapping_pairs`] of the `count` boxes `box_of(0..count)` (the caller
    /// may store them or make them on demand: a free sphere's box is its centre ± its radius
    /// and margin), each pair written into `firsts` where
    /// `is_first(i, j)`, else into `rest` (both sorted). Each list is as long as its pairs,
    /// its room kept from build to build and grown to the count exactly: the collider's
    /// pairs of free spheres go straight to their own list (written to one list and moved
    /// to the other, a packing of 10⁵ spheres held both lists' room, 84 bytes per sphere).
    /// Each chunk of cells writes its pairs to a buffer of its own, dropped once the pairs
    /// are in the lists: kept for the next build, those buffers (grown by doubling) held 37
    /// bytes per sphere of a packing between builds. (Counting the pairs first and writing
    /// them in place, which never holds them twice, doubled the pair tests: the tube
    /// impact's builds took 60 % longer, 7 % of its step.)
    pub fn overlapping_pairs_split<B, F, G>(
        &mut self,
        count: usize,
        box_of: B,
        accept: F,
        is_first: G,
        firsts: &mut Vec<(u32, u32)>,
        rest: &mut Vec<(u32, u32)>,
    ) where
        F: Fn(u32, u32) -> bool + Sync,
        G: Fn(u32, u32) -> bool,
        B: Fn(u32) -> Aabb + Sync,
    {
        let boxes = || (0..count as u32).map(&box_of);
        firsts.clear();
        rest.clear();
        self.entries.clear();
        self.large.clear();
        let h = choose_cell_size(boxes(), &mut self.entries);
        if h == 0.0 {
            return;
        }
        let inv_h = 1.0 / h;
        let origin = boxes().fold(Vec3::repeat(Real::INFINITY), |m, b| m.inf(&b.mins));
        let finite = |b: &Aabb| b.mins.iter().chain(b.maxs.iter()).all(|x| x.is_finite());
        let top = boxes().filter(finite).fold(origin, |m, b| m.sup(&b.maxs));
        let last = cell_of(&top, &origin, inv_h);
        let total = u64::BITS;
        #[cfg(test)]
        let total = self.entry_bits.unwrap_or(total);
        let packing = Packing::new(last.map(|c| c.saturating_add(1)), count, total);
        // the cells each box covers, or None for a box with a NaN coordinate or a large one
        let span = |b: &Aabb| {
            if !(b.mins.iter().chain(b.maxs.iter()).all(|x| x.is_finite())) {
                return None;
            }
            let lo = cell_of(&b.mins, &origin, inv_h);
            let hi = cell_of(&b.maxs, &origin, inv_h);
            Some((lo, hi)).filter(|_| (0..3).all(|k| hi[k] - lo[k] < MAX_CELLS_PER_AXIS))
        };
        // the entries counted first: their room grown to the count, not doubled past it
        let entry_count: usize = boxes()
            .filter_map(|b| span(&b))
            .map(|(lo, hi)| (0..3).map(|k| (hi[k] - lo[k] + 1) as usize).product::<usize>())
            .sum();
        self.entries.reserve_exact(entry_count);
        for (i, b) in boxes().enumerate() {
            let Some((lo, hi)) = span(&b) else {
                if b.mins.iter().chain(b.maxs.iter()).all(|x| x.is_finite()) {
                    self.large.push(i as u32);
                }
                continue;
            };
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        self.entries.push(packing.entry(packing.key([x, y, z]), i as u32));
                    }
                }
            }
        }
        self.entries.par_sort_unstable();

        // bucket boundaries (the buffers keep their memory from build to build)
        let entries = &self.entries;
        let starts = &mut self.starts;
        starts.clear();
        starts.extend(
            (0..entries.len())
                .filter(|&k| k == 0 || packing.key_of(entries[k]) != packing.key_of(entries[k - 1]))
                .chain(std::iter::once(entries.len())),
        );
        let cells = Cells { entries, starts: &self.starts, packing, origin, inv_h };
        // large boxes against every box (each large-large pair once)
        let mut large_pairs = Vec::new();
        for (n, &i) in self.large.iter().enumerate() {
            let bi = box_of(i);
            for (j, bj) in boxes().enumerate() {
                let j = j as u32;
                if j == i || (self.large[..n].contains(&j)) || !bi.intersects(&bj) {
                    continue;
                }
                let (p, q) = if i < j { (i, j) } else { (j, i) };
                if accept(p, q) {
                    large_pairs.push((p, q));
                }
            }
        }
        // chunk c holds buckets c·chunk to (c + 1)·chunk; each chunk's pairs go to a buffer
        // of the build's (none kept between builds), then to the two lists
        let buckets = cells.starts.len() - 1;
        let chunk = (buckets / (4 * rayon::current_num_threads()).max(1)).max(64);
        let found: Vec<Vec<(u32, u32)>> = (0..buckets.div_ceil(chunk))
            .into_par_iter()
            .map(|c| {
                let mut out = Vec::new();
                let cells_of_chunk = c * chunk..((c + 1) * chunk).min(buckets);
                cells.pairs(cells_of_chunk, &box_of, &accept, |p, q| out.push((p, q)));
                out
            })
            .collect();
        let all = || found.iter().flatten().chain(&large_pairs);
        let firsts_count = all().filter(|&&(i, j)| is_first(i, j)).count();
        firsts.reserve_exact(firsts_count);
        rest.reserve_exact(all().count() - firsts_count);
        for &(i, j) in all() {
            if is_first(i, j) {
                firsts.push((i, j));
            } else {
                rest.push((i, j));
            }
        }
        drop(found);
        firsts.par_sort_unstable();
        rest.par_sort_unstable();
        // the entries of a large scene are given back until the next build (27 bytes per
        // sphere of a packing); a small one's, which may build every few steps, are kept
        if self.entries.capacity() > KEPT_ENTRIES {
            self.entries = Vec::new();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn total_order_bits_sort_as_total_cmp_and_come_back() {
        let mut xs = [3.5, -0.0, 0.0, -2.0, 1e-310, -1e-310, Real::INFINITY, -Real::INFINITY, 7.0];
        let mut bits = xs.map(total_order_bits);
        xs.sort_by(Real::total_cmp);
        bits.sort_unstable();
        let back = bits.map(from_total_order_bits);
        assert_eq!(back.map(Real::to_bits), xs.map(Real::to_bits));
    }

    #[test]
    fn floor_to_int_matches_floor() {
        for x in [-2.5, -2.0, -1e-300, -0.0, 0.0, 0.3, 1.0, 1.999_999, 7e15, -7e15] {
            assert_eq!(floor_to_int(x), x.floor() as i64, "x = {x}");
        }
    }

    fn brute_force(boxes: &[Aabb], accept: impl Fn(u32, u32) -> bool) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if boxes[i].intersects(&boxes[j]) && accept(i as u32, j as u32) {
                    out.push((i as u32, j as u32));
                }
            }
        }
        out
    }

    fn boxes_strategy() -> impl Strategy<Value = Vec<Aabb>> {
        prop::collection::vec(
            (prop::array::uniform3(-5.0..5.0f64), prop::array::uniform3(0.0..1.0f64), 0u8..10),
            0..120,
        )
        .prop_map(|v| {
            v.into_iter()
                .map(|(c, e, kind)| {
                    // one box in ten is large (up to 8 units), a few are flat (zero extent)
                    let s = if kind == 0 { 8.0 } else { 1.0 };
                    let c = Vec3::from(c);
                    let e = Vec3::from(e) * s * if kind == 1 { 0.0 } else { 1.0 };
                    Aabb::new(c - e * 0.5, c + e * 0.5)
                })
                .collect()
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn cell_list_matches_brute_force(boxes in boxes_strategy()) {
            let accept = |i: u32, j: u32| (i + j) % 7 != 3;
            let mut bp = BroadPhase::default();
            let mut pairs = Vec::new();
            bp.overlapping_pairs(&boxes, accept, &mut pairs);
            prop_assert_eq!(pairs, brute_force(&boxes, accept));
        }

        #[test]
        fn split_pairs_are_the_pairs_divided_by_the_rule(boxes in boxes_strategy()) {
            // large boxes among them: their pairs go to both lists too
            let accept = |i: u32, j: u32| (i + j) % 7 != 3;
            let is_first = |i: u32, j: u32| (i * j) % 3 == 1;
            let (mut firsts, mut rest) = (vec![(9, 9)], vec![(8, 8)]);
            let box_of = |i: u32| boxes[i as usize];
            BroadPhase::default().overlapping_pairs_split(
                boxes.len(), box_of, accept, is_first, &mut firsts, &mut rest,
            );
            let all = brute_force(&boxes, accept);
            let (want_firsts, want_rest): (Vec<_>, Vec<_>) =
                all.into_iter().partition(|&(i, j)| is_first(i, j));
            prop_assert_eq!(firsts, want_firsts);
            prop_assert_eq!(rest, want_rest);
        }

        #[test]
        fn cells_that_share_a_key_give_the_same_pairs(boxes in boxes_strategy()) {
            // 2 bits per axis besides the boxes' index: cells 4 apart share a key
            let accept = |i: u32, j: u32| (i + j) % 7 != 3;
            let index_bits = bits_for(boxes.len() as u64).max(1);
            let mut bp = BroadPhase { entry_bits: Some(index_bits + 6), ..Default::default() };
            let mut pairs = Vec::new();
            bp.overlapping_pairs(&boxes, accept, &mut pairs);
            prop_assert_eq!(pairs, brute_force(&boxes, accept));
        }
    }

    #[test]
    fn a_packing_gives_back_its_cell_and_box_and_shares_keys_only_when_short_of_bits() {
        let p = Packing::new([3000, 5, 1], 10_000, u64::BITS);
        assert_eq!((p.bits, p.index_bits), ([12, 3, 0], 14));
        let e = p.entry(p.key([2999, 4, 0]), 9_999);
        assert_eq!((p.key_of(e), p.index_of(e)), (p.key([2999, 4, 0]), 9_999));
        // the largest grid and the most boxes: 32 bits of index, 11 + 11 + 10 of cells
        let p = Packing::new([1 << 21; 3], u32::MAX as usize, u64::BITS);
        assert_eq!((p.bits, p.index_bits), ([11, 11, 10], 32));
        assert_eq!(p.key([0, 0, 0]), p.key([0, 0, 1 << 10]));
        assert_ne!(p.key([0, 0, 0]), p.key([0, 0, 1 << 9]));
        let e = p.entry(p.key([7, 2047, 1023]), u32::MAX - 1);
        assert_eq!((p.key_of(e), p.index_of(e)), (p.key([7, 2047, 1023]), u32::MAX - 1));
    }

    #[test]
    fn touching_boxes_pair_and_separated_ones_do_not() {
        let boxes = [
            Aabb::new(Vec3::zeros(), Vec3::repeat(1.0)),
            Aabb::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 1.0)), // shares a face
            Aabb::new(Vec3::new(2.5, 0.0, 0.0), Vec3::new(3.0, 1.0, 1.0)),
        ];
        let mut pairs = Vec::new();
        BroadPhase::default().overlapping_pairs(&boxes, |_, _| true, &mut pairs);
        assert_eq!(pairs, vec![(0, 1)]);
    }

    #[test]
    fn no_boxes_and_nan_boxes_give_no_pairs() {
        let mut pairs = vec![(9, 9)];
        let mut bp = BroadPhase::default();
        bp.overlapping_pairs(&[], |_, _| true, &mut pairs);
        assert!(pairs.is_empty());
        let nan = Aabb::new(Vec3::repeat(f64::NAN), Vec3::repeat(1.0));
        let ok = Aabb::new(Vec3::zeros(), Vec3::repeat(1.0));
        bp.overlapping_pairs(&[nan, ok, ok], |_, _| true, &mut pairs);
        assert_eq!(pairs, vec![(1, 2)]);
    }
}
