//! The touchings a detection found, read where the parallel search left them: one list per
//! chunk of candidate pairs (`contacts.rs`), indexed as one list in pair order.

use flexdem_elements::touching::ElementCandidate;

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
