//! The touchings a detection found, read where the parallel search left them: one list per
//! chunk of candidate pairs (`contacts.rs`), indexed as one list in pair order.

use flexdem_elements::touching::ElementCandidate;
use rayon::prelude::*;

/// Entries of the new list per parallel task of [`match_sorted`] (one task below it).
const MATCH_CHUNK: usize = if cfg!(test) { 16 } else { 1024 };

/// For each entry of `new` (sorted by `new_key`), the index in `old` (sorted by `old_key`)
/// of the first entry with its key, if any: `matched[n]`, what merging the two lists in one
/// pass gives. In parallel per chunk of [`MATCH_CHUNK`] new entries, each chunk's merge
/// starting where a bisection of `old` puts its first key. (The one-pass merge of a
/// detection's touchings with the last step's contacts, reading each old contact's key, 320
/// bytes apart, took 200 µs a step of the membrane of 10⁵ PFacets.)
pub(crate) fn match_sorted<N: Sync, T: Sync, K: Ord>(
    new: &[N],
    old: &[T],
    new_key: impl Fn(&N) -> K + Sync,
    old_key: impl Fn(&T) -> K + Sync,
    matched: &mut Vec<Option<u32>>,
) {
    matched.clear();
    matched.resize(new.len(), None);
    let merge = |new: &[N], matched: &mut [Option<u32>]| {
        let Some(first) = new.first() else { return };
        let first = new_key(first);
        let mut k = old.partition_point(|t| old_key(t) < first);
        for (n, m) in new.iter().zip(matched) {
            let key = new_key(n);
            while k < old.len() && old_key(&old[k]) < key {
                k += 1;
            }
            *m = (k < old.len() && old_key(&old[k]) == key).then_some(k as u32);
        }
    };
    if new.len() <= MATCH_CHUNK {
        merge(new, matched);
        return;
    }
    new.par_chunks(MATCH_CHUNK)
        .zip(matched.par_chunks_mut(MATCH_CHUNK))
        .for_each(|(new, matched)| merge(new, matched));
}

/// The touchings of a detection in pair order, as the per-chunk lists of the parallel search
/// hold them: touching `n` is in the chunk `c` with `starts[c] ≤ n < starts[c + 1]` (found by
/// bisection over the chunks). No concatenated copy: 184 bytes per touching.
#[derive(Clone, Copy)]
pub(crate) struct Touchings<'a> {
    pub(crate) chunks: &'a [Vec<ElementCandidate>],
    pub(crate) starts: &'a [u32],
}

impl<'a> Touchings<'a> {
    /// Number of touchings.
    pub(crate) fn len(&self) -> usize {
        self.starts.last().map_or(0, |&end| end as usize)
    }

    /// Touching `n`, if there is one.
    pub(crate) fn get(&self, n: usize) -> Option<&'a ElementCandidate> {
        if n >= self.len() {
            return None;
        }
        // the last chunk starting at or before n (empty chunks share their start with the
        // next one, so it holds n)
        let c = self.starts.partition_point(|&s| s as usize <= n) - 1;
        self.chunks[c].get(n - self.starts[c] as usize)
    }

    /// The touchings in pair order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &'a ElementCandidate> + 'a {
        self.chunks.iter().flatten()
    }
}

impl std::ops::Index<usize> for Touchings<'_> {
    type Output = ElementCandidate;

    fn index(&self, n: usize) -> &ElementCandidate {
        self.get(n).expect("a touching in range")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexdem_elements::pairs::Candidate;
    use flexdem_elements::touching::Element;
    use flexdem_elements::virtual_sphere::Site;
    use flexdem_geom::Vec3;

    fn touching(id: u32) -> ElementCandidate {
        let site = Site::particle(id, 1.0);
        ElementCandidate {
            element1: Element::Particle(id),
            element2: Element::Particle(id + 1),
            candidate: Candidate {
                site1: site,
                site2: site,
                center1: Vec3::zeros(),
                center2: Vec3::x(),
                distance: 1.0,
            },
        }
    }

    /// Matched per chunk, each new key finds the first old entry of its key, as one merge
    /// finds it: keys repeated in both lists, missing from either, chunks starting on a
    /// repeated key.
    #[test]
    fn the_matches_per_chunk_are_those_of_one_merge() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = |m: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % m
        };
        for (n_new, n_old) in [(0, 5), (5, 0), (7, 9), (100, 60), (333, 500)] {
            let mut new: Vec<(u64, u32)> = (0..n_new).map(|i| (next(200), i as u32)).collect();
            let mut old: Vec<u64> = (0..n_old).map(|_| next(200)).collect();
            new.sort_unstable();
            old.sort_unstable();
            let mut matched = vec![Some(7); 3];
            match_sorted(&new, &old, |n| n.0, |&o| o, &mut matched);
            let mut one_pass = Vec::new();
            let mut k = 0;
            for &(key, _) in &new {
                while k < old.len() && old[k] < key {
                    k += 1;
                }
                one_pass.push((k < old.len() && old[k] == key).then_some(k as u32));
            }
            assert_eq!(matched, one_pass, "{n_new} new, {n_old} old");
            if n_new > 2 * MATCH_CHUNK && n_old > 0 {
                assert!(matched.iter().any(Option::is_some) && matched.iter().any(Option::is_none));
            }
        }
    }

    #[test]
    fn touching_n_is_the_nth_of_the_chunks_in_order() {
        // empty chunks first, between and last
        let sizes = [0, 3, 0, 0, 1, 2, 0];
        let mut next = 0;
        let chunks: Vec<Vec<ElementCandidate>> = sizes
            .iter()
            .map(|&n| {
                (0..n)
                    .map(|_| {
                        next += 1;
                        touching(next - 1)
                    })
                    .collect()
            })
            .collect();
        let mut starts = vec![0u32];
        for c in &chunks {
            starts.push(starts[starts.len() - 1] + c.len() as u32);
        }
        let t = Touchings { chunks: &chunks, starts: &starts };
        assert_eq!(t.len(), 6);
        let flat: Vec<u32> = t.iter().map(|c| c.candidate.site1.nodes[0]).collect();
        assert_eq!(flat, [0, 1, 2, 3, 4, 5]);
        for n in 0..6 {
            assert_eq!(t[n].candidate.site1.nodes[0], n as u32, "touching {n}");
        }
        assert!(t.get(6).is_none());
        let none = Touchings { chunks: &[], starts: &[0] };
        assert_eq!((none.len(), none.get(0).is_none()), (0, true));
    }
}
