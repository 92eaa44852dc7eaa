//! The general contacts' loops shared among the threads by the step's homes (`homes.rs`):
//! the elements' hulls by the home of each chunk's first element, the detection by that of
//! each chunk's first candidate pair, the contact law by that of each chunk's first contact.
//! An element's or a pair's home is that of its first particle: a free sphere, or a
//! structure's first node ([`element_particle`]); a contact's, that of the first node of its
//! first site (a free sphere before a structure); the thread that steps a particle writes the
//! hulls that read it, and meets the contacts of the spheres it steps. The items,
//! what each computes and where it is written do not depend on the homes.

use crate::homes::{chunk_runs, in_homes, Homes, Piece, Pieces, Runs};
use crate::parallel::MIN_PARALLEL_CHEAP;
use crate::prefilter::{write_hull, Hull};
use flexdem_elements::touching::Element;
use flexdem_elements::Model;

/// Elements per chunk when their loops are shared by home (the runs change home between
/// chunks).
const ELEMENT_CHUNK: usize = 1024;

/// The first particle element `e` reads: a free sphere, or a connection's or a PFacet's
/// first node.
pub(crate) fn element_particle(model: &Model, e: Element) -> usize {
    match e {
        Element::Particle(i) => i as usize,
        Element::Connection(k) => model.connections[k as usize].nodes[0] as usize,
        Element::PFacet(k) => model.pfacets[k as usize].nodes[0] as usize,
    }
}

/// Whether `homes` share the particles of `model` among more than one home.
pub(crate) fn shared(homes: &Homes, model: &Model) -> bool {
    homes.shares(model.particles.len()) && homes.len() == model.particles.len()
}

/// The runs of `len` items in chunks of `chunk` by the home of each chunk (`home(c)`), with
/// the number of homes; none when `homes` share nothing or the items fit in one chunk.
pub(crate) fn chunk_home_runs(
    len: usize,
    chunk: usize,
    homes: Option<&Homes>,
    home: impl Fn(usize) -> usize,
) -> Option<(Runs, usize)> {
    let homes = homes.filter(|h| h.count() > 1 && len > chunk)?;
    let mut runs = Runs::new();
    chunk_runs(len.div_ceil(chunk), chunk, home, &mut runs);
    Some((runs, homes.count()))
}

/// Runs `task(first, piece)` on the pieces of `all` (`len` items) cut at `runs`
/// ([`chunk_home_runs`]), each piece with its first item, every home's pieces on one task
/// (`homes::in_homes`); all on this task without runs.
pub(crate) fn by_runs<P, F>(all: P, len: usize, runs: Option<(Runs, usize)>, task: &F)
where
    P: Piece,
    F: Fn(usize, P) + Sync,
{
    let Some((runs, count)) = runs else {
        task(0, all);
        return;
    };
    in_homes(all, &runs, len, count, &|pieces: Pieces<P>| {
        pieces.into_iter().for_each(|(first, p)| task(first, p));
    });
}

/// Writes the hull of every element `paired` marks (others keep theirs: none reads them),
/// in parallel, by the homes of the elements' particles when `homes` share them.
pub(crate) fn write_hulls(
    hulls: &mut [Hull],
    elements: &[Element],
    model: &Model,
    paired: &(impl Fn(usize) -> bool + Sync),
    homes: &Homes,
) {
    use rayon::prelude::*;
    let write = |first: usize, (hulls, elements): (&mut [Hull], &[Element])| {
        let each = hulls.par_iter_mut().zip(elements.par_iter()).enumerate();
        each.with_min_len(MIN_PARALLEL_CHEAP).for_each(|(k, (h, &e))| {
            if paired(first + k) {
                write_hull(model, e, h);
            }
        });
    };
    let homes = shared(homes, model).then_some(homes);
    let home = |c: usize| {
        homes.map_or(0, |h| h.home_of(element_particle(model, elements[c * ELEMENT_CHUNK])))
    };
    let runs = chunk_home_runs(elements.len(), ELEMENT_CHUNK, homes, home);
    by_runs((hulls, elements), elements.len(), runs, &write);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::homes::PerChunk;

    /// Cut by the homes of their chunks, every chunk's output is written once, by the task
    /// given that chunk's items, as on one thread.
    #[test]
    fn per_chunk_outputs_follow_their_items() {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
        let items: Vec<u64> = (0..1000).map(|i| i * i % 97).collect();
        let chunk = 64;
        let expected: Vec<u64> = items.chunks(chunk).map(|c| c.iter().sum()).collect();
        let mut homes = Homes::default();
        homes.set_by_blocks(&[0, 300, 1000], 3);
        for shared in [None, Some(&homes)] {
            let mut sums = vec![u64::MAX; expected.len()];
            let home = |c: usize| homes.home_of(c * chunk);
            let runs = chunk_home_runs(items.len(), chunk, shared, home);
            if shared.is_some() {
                assert_eq!(runs.as_ref().map(|r| r.0.len()), Some(6));
            }
            let all = (&items[..], PerChunk { outputs: &mut sums[..], chunk });
            pool.install(|| {
                by_runs(
                    all,
                    items.len(),
                    runs,
                    &|first: usize, (items, sums): (&[u64], PerChunk<'_, u64>)| {
                        assert_eq!(first % chunk, 0);
                        for (c, s) in items.chunks(chunk).zip(sums.outputs.iter_mut()) {
                            *s = c.iter().sum();
                        }
                    },
                );
            });
            assert_eq!(sums, expected, "{shared:?}");
        }
    }
}
