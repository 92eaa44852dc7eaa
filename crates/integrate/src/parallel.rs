//! How finely the engine's parallel loops are split.

/// Fewest items a parallel task is given in a loop of cheap items (tens of nanoseconds each:
/// a hull, a prefilter test, a particle check): below it rayon does not split, since sending
/// work to another thread costs microseconds. Results do not depend on it (indexed maps and
/// collects keep their order).
pub(crate) const MIN_PARALLEL_CHEAP: usize = 1024;

/// Fewest items a parallel task is given in a loop of costly items (a contact's kernel or
/// law, up to a microsecond each).
pub(crate) const MIN_PARALLEL_COSTLY: usize = 64;

/// Below this many items [`any_index`] scans on this thread: a small scene's check costs
/// less than sending it to rayon (the bridge, the shared stop flag read per item).
const SEQUENTIAL_SCAN: usize = 4 * MIN_PARALLEL_CHEAP;

/// Whether `f(i)` holds for some i in `0..n`: a scan of every item without early exit (no
/// branch per item, so the compiler may vectorize it) below [`SEQUENTIAL_SCAN`] items, rayon's
/// `any` in chunks of [`MIN_PARALLEL_CHEAP`] above. For the per-step checks of every particle,
/// where the answer is almost always no.
pub(crate) fn any_index(n: usize, f: impl Fn(usize) -> bool + Sync + Send) -> bool {
    use rayon::prelude::*;
    if n < SEQUENTIAL_SCAN {
        (0..n).fold(false, |found, i| found | f(i))
    } else {
        (0..n).into_par_iter().with_min_len(MIN_PARALLEL_CHEAP).any(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn any_index_finds_one_item_on_both_sides_of_the_switch() {
        for n in [0, 1, 7, SEQUENTIAL_SCAN - 1, SEQUENTIAL_SCAN, 3 * SEQUENTIAL_SCAN + 5] {
            assert!(!any_index(n, |_| false), "{n}");
            for hit in [0, n / 2, n.saturating_sub(1)].into_iter().filter(|&h| h < n) {
                assert!(any_index(n, |i| i == hit), "{n}: {hit}");
            }
        }
    }
}
