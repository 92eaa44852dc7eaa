//! Which thread steps which particles, the same in every parallel loop of a step (but the
//! leapfrog's after a step of the pairs in parts, which follows the parts:
//! [`Homes::set_by_parts`]).
//!
//! A line of memory that one core writes and another reads costs a round trip between the
//! two; on a host that puts the two cores on two AMD core complexes, through the I/O die
//! (330–380 ns against 51–67 with a shared L3, `bench/pingpong.c`). Each loop of a step, left
//! to rayon, halves its own items: the leapfrog its particles, the links their links, the
//! hulls their elements (spheres first, then PFacets), so that on the membrane of 10⁵
//! PFacets about 6 700 nodes were stepped by one thread and linked by the other, and every
//! sphere was stepped by the second thread and had its hull written by the first
//! (bench/README, twenty-third session).
//!
//! [`Homes`] cuts the particles into runs, each at a home; the loops share their items by the
//! home of a particle each item reads ([`Homes::home_of`]), and [`in_homes`] hands every home's
//! pieces to one task, the homes halved recursively (`rayon::join`: the first half on the
//! calling thread, the second stolen by another), as every loop of the step halves them. The
//! particles are cut by kind ([`particle_blocks`]: the structures' nodes, the free spheres),
//! each run of one kind into as many runs of about equal length as there are threads: the
//! grids and the spheres the engine's builders make are in the order of their places, so
//! that the first half of a membrane's nodes lies under the first half of its spheres.
//! What each item computes, and the order in which anything is summed, do not depend on the
//! homes: only which thread does it.

use flexdem_elements::{ParticleKind, Particles};
use flexdem_geom::Vec3;
use smallvec::SmallVec;
use std::ops::Range;

/// Runs or pieces a loop keeps on the stack: the pairs' parts of 4 threads
/// (`pair_parts::PARTS_PER_THREAD` each), or two kinds of particles on 8 threads. Beyond, a
/// step allocates their lists.
const ON_STACK: usize = 16;

/// Runs of items: each one's first item and home, in item order.
pub(crate) type Runs = SmallVec<[(usize, usize); ON_STACK]>;

/// A home's pieces of a loop's items, each with its first item, in item order.
pub(crate) type Pieces<P> = SmallVec<[(usize, P); ON_STACK]>;

/// The pieces of a loop's items with their first items and homes.
type HomePieces<P> = SmallVec<[(usize, usize, P); ON_STACK]>;

/// Per-particle force and torque sums, cut by home.
pub(crate) type Sums<'a> = (&'a mut [Vec3], &'a mut [Vec3]);

/// The particles cut into runs, each at one of `count` homes.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Homes {
    /// Per run, its first particle; then the particle count.
    starts: Vec<usize>,
    /// Per run, its home.
    home: Vec<usize>,
    /// The number of homes.
    count: usize,
}

/// The most runs of particles of one kind [`particle_blocks`] keeps apart.
const MAX_BLOCKS: usize = 4;

/// The first particle of each run of particles of one kind (a structure's node, a free
/// sphere), then the particle count; all the particles in one run when they make more than
/// [`MAX_BLOCKS`] (structures and spheres interleaved, bags among grains: each loop would
/// then go through a piece per run and thread, however small).
pub(crate) fn particle_blocks(p: &Particles) -> Vec<usize> {
    if p.is_empty() {
        return vec![0];
    }
    let node = |i: usize| p.kind[i] != ParticleKind::Sphere;
    let mut blocks = vec![0];
    blocks.extend((1..p.len()).filter(|&i| node(i) != node(i - 1)));
    if blocks.len() > MAX_BLOCKS {
        blocks.truncate(1);
    }
    blocks.push(p.len());
    blocks
}

/// Position `x` moved to the nearest multiple of `grain`, at most `end`.
fn nearest_multiple(x: usize, grain: usize, end: usize) -> usize {
    ((x + grain / 2) / grain * grain).min(end)
}

impl Homes {
    /// Each of `blocks` (first particles, then the count: [`particle_blocks`]) cut into
    /// `threads` runs of about equal length, run `k` of each block at home `k` (runs left
    /// empty dropped).
    pub(crate) fn set_by_blocks(&mut self, blocks: &[usize], threads: usize) {
        let threads = threads.max(1);
        let n = blocks.last().copied().unwrap_or(0);
        self.clear(threads);
        for b in blocks.windows(2) {
            let (first, len) = (b[0], b[1] - b[0]);
            for k in 0..threads {
                self.push(first + len * k / threads, k);
            }
        }
        self.finish(n);
    }

    /// One run per part, part `k` from `firsts[k]` (the first particles of the parts the
    /// pairs were stepped in, then the particle count: `PairParts::homes`) at home `k`: the
    /// particles are shared among the threads as the parts were (`part_step::step_runs`
    /// halves them as [`in_homes`] does).
    pub(crate) fn set_by_parts(&mut self, firsts: &[usize]) {
        debug_assert!(firsts.first() == Some(&0) && firsts.windows(2).all(|w| w[0] <= w[1]));
        let n = firsts.last().copied().unwrap_or(0);
        self.clear(firsts.len().saturating_sub(1).max(1));
        for (k, &first) in firsts[..firsts.len().saturating_sub(1)].iter().enumerate() {
            self.push(first.min(n), k);
        }
        self.finish(n);
    }

    fn clear(&mut self, count: usize) {
        self.starts.clear();
        self.home.clear();
        self.count = count;
    }

    /// Adds a run from `start` at `home`, the last one ending there (an empty one replaced).
    fn push(&mut self, start: usize, home: usize) {
        if self.starts.last() == Some(&start) {
            self.starts.pop();
            self.home.pop();
        }
        self.starts.push(start);
        self.home.push(home);
    }

    fn finish(&mut self, n: usize) {
        // (runs left empty at the end: none)
        while self.starts.len() > 1 && self.starts.last() == Some(&n) {
            self.starts.pop();
            self.home.pop();
        }
        if self.starts.first() != Some(&0) {
            // (no particle: one empty run)
            self.clear(self.count);
            self.starts.push(0);
            self.home.push(0);
        }
        self.starts.push(n);
    }

    /// Whether these homes share the first `n` particles among more than one home (they
    /// cover at least `n`: those of this step, or the nodes before free spheres).
    pub(crate) fn shares(&self, n: usize) -> bool {
        self.count > 1 && n > 0 && self.len() >= n
    }

    /// The number of homes.
    pub(crate) fn count(&self) -> usize {
        self.count
    }

    /// The particle count the runs cover.
    pub(crate) fn len(&self) -> usize {
        self.starts.last().copied().unwrap_or(0)
    }

    /// The home of particle `i` (the last run's past the end).
    #[inline]
    pub(crate) fn home_of(&self, i: usize) -> usize {
        let run = self.starts[..self.home.len()].partition_point(|&s| s <= i).max(1) - 1;
        self.home.get(run).copied().unwrap_or(0)
    }

    /// The runs: each one's particles and home, in particle order.
    pub(crate) fn runs(&self) -> impl Iterator<Item = (Range<usize>, usize)> + '_ {
        self.starts.windows(2).zip(&self.home).map(|(s, &h)| (s[0]..s[1], h))
    }

    /// The runs within particles `0..len` (`len` at most [`Homes::len`]) as the starts of
    /// runs of items ([`in_homes`]), each moved to the multiple of `grain` nearest it (the
    /// leapfrog's chunks; a run left empty dropped): the runs of the loops over the
    /// particles' arrays (the leapfrog, the sums of the loads it reads).
    pub(crate) fn item_runs(&self, len: usize, grain: usize, runs: &mut Runs) {
        runs.clear();
        for (r, h) in self.runs().filter(|(r, _)| r.start < len) {
            let start = nearest_multiple(r.start, grain, len);
            if runs.last().is_some_and(|&(s, _)| s == start) {
                runs.pop();
            }
            if start < len {
                runs.push((start, h));
            }
        }
    }
}

/// The runs of `chunks` chunks of items by the home of each chunk (`home(c)`): each run's
/// first item (chunks of `chunk` items) and home, a run for each change of home.
pub(crate) fn chunk_runs(
    chunks: usize,
    chunk: usize,
    home: impl Fn(usize) -> usize,
    runs: &mut Runs,
) {
    runs.clear();
    for c in 0..chunks {
        let h = home(c);
        if runs.last().is_none_or(|&(_, last)| last != h) {
            runs.push((c * chunk, h));
        }
    }
}

/// Items that can be cut in two: the first `at` and the others.
pub(crate) trait Piece: Sized + Send {
    fn split_at(self, at: usize) -> (Self, Self);
}

impl<T: Send> Piece for &mut [T] {
    fn split_at(self, at: usize) -> (Self, Self) {
        self.split_at_mut(at)
    }
}

impl<T: Sync> Piece for &[T] {
    fn split_at(self, at: usize) -> (Self, Self) {
        <[T]>::split_at(self, at)
    }
}

impl<A: Piece, B: Piece> Piece for (A, B) {
    fn split_at(self, at: usize) -> (Self, Self) {
        let ((a, a2), (b, b2)) = (self.0.split_at(at), self.1.split_at(at));
        ((a, b), (a2, b2))
    }
}

/// Per-chunk outputs of items in chunks of `chunk`, cut where the items are cut (at a
/// multiple of `chunk`, or at their end).
pub(crate) struct PerChunk<'a, T> {
    pub(crate) outputs: &'a mut [T],
    pub(crate) chunk: usize,
}

impl<T: Send> Piece for PerChunk<'_, T> {
    fn split_at(self, at: usize) -> (Self, Self) {
        let (a, b) = self.outputs.split_at_mut(at.div_ceil(self.chunk));
        (PerChunk { outputs: a, chunk: self.chunk }, PerChunk { outputs: b, chunk: self.chunk })
    }
}

/// Runs `task` once per home of `homes` homes, with that home's pieces of `all` (items
/// `runs[0].0..end`; `runs` the first item and home of each run, in item order), each with
/// its first item: the homes halved recursively by `rayon::join`, the first half on this
/// thread. The pieces of a home come in item order.
pub(crate) fn in_homes<P, F>(all: P, runs: &[(usize, usize)], end: usize, homes: usize, task: &F)
where
    P: Piece,
    F: Fn(Pieces<P>) + Sync,
{
    let mut pieces = HomePieces::new();
    let mut rest = Some(all);
    for (k, &(start, home)) in runs.iter().enumerate() {
        let (start, next) = (start.min(end), runs.get(k + 1).map_or(end, |r| r.0.min(end)));
        let (piece, after) = rest.take().expect("a piece left").split_at(next - start);
        if next > start {
            pieces.push((start, home, piece));
        }
        rest = Some(after);
    }
    split_homes(pieces, 0..homes.max(1), task);
}

fn split_homes<P, F>(pieces: HomePieces<P>, homes: Range<usize>, task: &F)
where
    P: Piece,
    F: Fn(Pieces<P>) + Sync,
{
    if pieces.is_empty() {
        return;
    }
    if homes.len() <= 1 || pieces.iter().all(|p| p.1 == pieces[0].1) {
        task(pieces.into_iter().map(|(start, _, p)| (start, p)).collect());
        return;
    }
    let mid = homes.start + homes.len() / 2;
    let (a, b): (HomePieces<P>, HomePieces<P>) = pieces.into_iter().partition(|p| p.1 < mid);
    rayon::join(|| split_homes(a, homes.start..mid, task), || split_homes(b, mid..homes.end, task));
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn blocks_are_cut_in_runs_of_about_equal_length() {
        let mut h = Homes::default();
        h.set_by_blocks(&[0, 5000, 6000], 2);
        let runs: Vec<_> = h.runs().collect();
        assert_eq!(runs, [(0..2500, 0), (2500..5000, 1), (5000..5500, 0), (5500..6000, 1)]);
        h.set_by_blocks(&[0, 50_625, 63_169], 2);
        let runs: Vec<_> = h.runs().collect();
        let cuts = [(0..25_312, 0), (25_312..50_625, 1), (50_625..56_897, 0), (56_897..63_169, 1)];
        assert_eq!(runs, cuts);
        assert_eq!((h.home_of(0), h.home_of(25_311), h.home_of(25_312)), (0, 0, 1));
        assert_eq!((h.home_of(50_625), h.home_of(63_168), h.home_of(70_000)), (0, 1, 1));
        assert_eq!(h.count(), 2);
        // at the leapfrog's chunks
        let mut runs = Runs::new();
        h.item_runs(63_169, 1024, &mut runs);
        assert_eq!(runs[..], [(0, 0), (25_600, 1), (50_176, 0), (57_344, 1)]);
        h.item_runs(50_625, 1024, &mut runs);
        assert_eq!(runs[..], [(0, 0), (25_600, 1)]);
        h.set_by_blocks(&[0], 2);
        assert_eq!(h.runs().collect::<Vec<_>>(), [(0..0, 0)]);
    }

    #[test]
    fn parts_keep_their_order_and_their_empty_runs_go() {
        let mut h = Homes::default();
        h.set_by_parts(&[0, 1000, 1100, 4000, 4000, 5000]);
        let runs: Vec<_> = h.runs().collect();
        assert_eq!(runs, [(0..1000, 0), (1000..1100, 1), (1100..4000, 2), (4000..5000, 4)]);
        assert_eq!(h.count(), 5);
        let mut runs = Runs::new();
        h.item_runs(5000, 1024, &mut runs);
        assert_eq!(runs[..], [(0, 0), (1024, 2), (4096, 4)]);
    }

    #[test]
    fn chunks_of_one_home_make_one_run() {
        let mut runs = Runs::new();
        chunk_runs(6, 10, |c| [0, 0, 1, 0, 0, 1][c], &mut runs);
        assert_eq!(runs[..], [(0, 0), (20, 1), (30, 0), (50, 1)]);
    }

    /// Every item is given once, to the task of its home, the pieces in item order.
    #[test]
    fn every_item_goes_once_to_its_home() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
        let mut items: Vec<usize> = (0..100).collect();
        let runs = [(0, 2), (10, 0), (10, 1), (40, 2), (55, 0), (90, 1)];
        let seen = Mutex::new(Vec::new());
        pool.install(|| {
            in_homes(&mut items[..], &runs, 100, 3, &|pieces: Pieces<&mut [usize]>| {
                let mut got = Vec::new();
                for (start, p) in pieces {
                    assert_eq!(p[0], start);
                    got.extend(p.iter().copied());
                    p.iter_mut().for_each(|x| *x += 1000);
                }
                seen.lock().unwrap().push(got);
            });
        });
        let mut seen = seen.into_inner().unwrap();
        seen.sort();
        // home 0: 10..10 (empty) and 55..90; home 1: 10..40 and 90..100; home 2: 0..10, 40..55
        let mut by_home: Vec<Vec<usize>> = vec![
            (55..90).collect(),
            (10..40).chain(90..100).collect(),
            (0..10).chain(40..55).collect(),
        ];
        by_home.sort();
        assert_eq!(seen, by_home);
        assert!(items.iter().enumerate().all(|(i, &x)| x == i + 1000));
    }

    /// Runs of one kind: a membrane's nodes, then spheres; interleaved structures and
    /// spheres beyond [`MAX_BLOCKS`] runs in one.
    #[test]
    fn particles_are_in_blocks_of_one_kind_unless_too_many() {
        use flexdem_elements::Particle;
        let of = |kinds: &[ParticleKind]| {
            let mut p = Particles::default();
            for &k in kinds {
                p.push(Particle::at_rest(k, Vec3::zeros(), 0.01, 0));
            }
            particle_blocks(&p)
        };
        let (node, sphere) = (ParticleKind::Node, ParticleKind::Sphere);
        assert_eq!(of(&[]), [0]);
        assert_eq!(of(&[node, node, sphere, sphere, sphere]), [0, 2, 5]);
        assert_eq!(of(&[sphere, node, node, sphere]), [0, 1, 3, 4]);
        assert_eq!(of(&[node, sphere, node, sphere, node]), [0, 5]);
    }
}
