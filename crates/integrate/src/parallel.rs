//! How finely the engine's parallel loops are split.

/// Fewest items a parallel task is given in a loop of cheap items (tens of nanoseconds each:
/// a hull, a prefilter test, a particle check): below it rayon does not split, since sending
/// work to another thread costs microseconds. Results do not depend on it (indexed maps and
/// collects keep their order).
pub(crate) const MIN_PARALLEL_CHEAP: usize = 1024;

/// At most this many chunks per rayon task in the loops over fixed chunks (the pairs'
/// update, the leapfrog, the loads' gather). Left to itself, rayon splits such a loop into
/// four tasks with two threads and splits further only what another thread steals: the
/// last task of the slower thread (a quarter of the work when the host took that thread's
/// core for a while) was done alone while the other thread waited. Tasks of a few chunks
/// let the threads share the end of the loop; the chunks, and so the results, are the same.
pub(crate) const MAX_CHUNKS_PER_TASK: usize = 4;

/// Fewest items a parallel task is given in a loop of costly items (a contact's kernel or
/// law, up to a microsecond each).
pub(crate) const MIN_PARALLEL_COSTLY: usize = 64;

/// Below this many items [`any_zipped`] scans on this thread: a small scene's check costs
/// less than sending it to rayon (the bridge, the shared stop flag read per item).
const SEQUENTIAL_SCAN: usize = 4 * MIN_PARALLEL_CHEAP;

/// Whether `bad` holds for some item of `seq`, the same items as `par` (slices zipped, one
/// iterator of each kind): a scan of every item without early exit and without indices (no
/// branch and no bounds check per item: the compiler may vectorize it) below
/// [`SEQUENTIAL_SCAN`] items, rayon's `any` on `par` in chunks of [`MIN_PARALLEL_CHEAP`] above.
/// For the per-step checks of every particle, where the answer is almost always no.
pub(crate) fn any_zipped<S, P>(seq: S, par: P, bad: impl Fn(S::Item) -> bool + Sync + Send) -> bool
where
    S: ExactSizeIterator,
    P: rayon::iter::IndexedParallelIterator<Item = S::Item>,
{
    use rayon::prelude::*;
    if seq.len() < SEQUENTIAL_SCAN {
        seq.fold(false, |found, item| found | bad(item))
    } else {
        par.with_min_len(MIN_PARALLEL_CHEAP).any(bad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;

    #[test]
    fn any_zipped_finds_one_item_on_both_sides_of_the_switch() {
        for n in [0, 1, 7, SEQUENTIAL_SCAN - 1, SEQUENTIAL_SCAN, 3 * SEQUENTIAL_SCAN + 5] {
            let (a, b): (Vec<usize>, Vec<usize>) =
                ((0..n).collect(), (0..n).map(|i| 2 * i).collect());
            let any = |hit: Option<usize>| {
                let bad = |(x, y): (&usize, &usize)| Some(*x) == hit && *y == 2 * *x;
                any_zipped(a.iter().zip(&b), a.par_iter().zip(&b), bad)
            };
            assert!(!any(None), "{n}");
            for hit in [0, n / 2, n.saturating_sub(1)].into_iter().filter(|&h| h < n) {
                assert!(any(Some(hit)), "{n}: {hit}");
            }
        }
    }
}
