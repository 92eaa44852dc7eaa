//! What the step of a chunk of candidate pairs adds to the step's records (`ChunkBook`)
//! and sums (`ChunkSums`), in pair order: written by the chunk's pass (`pair_chunk.rs`),
//! read by both passes over the chunks (`pair_passes.rs`).

use crate::dashpots::FactorMemo;
use crate::fresh_shares::PairShares;
use crate::neighbours::{AppliedForce, PairContact, PairOutcome, Pushed};
use flexdem_geom::Real;

/// What the pairs of one chunk added to the step's sums, each in pair order (from +0 for the
/// births and ends, from −0 for the touching pairs' energy, as `Iterator::sum`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ChunkSums {
    pub(crate) born_energy: Real,
    pub(crate) released: Real,
    pub(crate) born_deep: u64,
    /// The part of `born_energy` of the pairs found late (`born_deep`).
    pub(crate) late_energy: Real,
    pub(crate) ended_dissipation: Real,
    /// Elastic energy of the touching pairs after their update.
    pub(crate) elastic: Real,
    /// Friction dissipated by the touching pairs over their lives.
    pub(crate) friction: Real,
}

impl Default for ChunkSums {
    fn default() -> Self {
        ChunkSums {
            born_energy: 0.0,
            released: 0.0,
            born_deep: 0,
            late_energy: 0.0,
            ended_dissipation: 0.0,
            elastic: -0.0,
            friction: -0.0,
        }
    }
}

impl ChunkSums {
    fn add_outcome(&mut self, o: &PairOutcome) {
        self.born_energy += o.born_energy;
        self.released += o.released;
        self.born_deep += u64::from(o.born_deep);
        if o.born_deep {
            self.late_energy += o.born_energy;
        }
        self.ended_dissipation += o.ended_dissipation;
    }

    /// Adds a touching pair's energy: its elastic energy `elastic` (its law's, or
    /// [`PairContact::elastic_energy`], the same bits) and its friction over its life.
    pub(crate) fn add_touching(&mut self, c: &PairContact, elastic: Real) {
        self.elastic += elastic;
        self.friction += c.state.dissipated_friction;
    }

    /// Adds this chunk's sums to the step's: `total`, the report and the ended pairs'
    /// friction.
    pub(crate) fn add_to(&self, total: &mut ChunkSums) {
        total.born_energy += self.born_energy;
        total.released += self.released;
        total.born_deep += self.born_deep;
        total.late_energy += self.late_energy;
        total.ended_dissipation += self.ended_dissipation;
        total.elastic += self.elastic;
        total.friction += self.friction;
    }
}

/// What the pairs of one chunk added to the step's records, in pair order (both passes).
#[derive(Clone, Debug, Default)]
pub(crate) struct ChunkBook {
    /// The pairs that started touching.
    pub(crate) fresh: Vec<usize>,
    /// Their nodes' shares of their stiffness, for the time step (`stiffness_sums::add_fresh`).
    pub(crate) fresh_shares: Vec<PairShares>,
    /// The last damping factors the shares asked for (nothing saved).
    pub(crate) memo: [FactorMemo; 2],
    /// The touching pairs whose dashpots pushed, in key order: what `dashpot_dissipation`
    /// needs, gathered while each contact was at hand.
    pub(crate) pushed: Vec<Pushed>,
    /// The touching pairs of a wall and a sphere, in key order: each one's index and the
    /// force its law applied, as it gave it (the walls' loads, `Contacts::for_each_on_wall`,
    /// steer servos and make the walls' power: the law's bits, where a sphere pair's force
    /// is made from its state when asked, [`PairContact::applied`]).
    pub(crate) walls: Vec<(u32, AppliedForce)>,
    pub(crate) sums: ChunkSums,
}

impl ChunkBook {
    /// Books the step of pair `n`: its outcome `o`, and when it touches after the step
    /// (`contact`), its energy (`elastic`, what its law gave; the law has appended the
    /// record of its dashpots).
    pub(crate) fn record(
        &mut self,
        n: usize,
        o: &PairOutcome,
        contact: Option<&PairContact>,
        elastic: Real,
    ) {
        self.sums.add_outcome(o);
        if o.fresh {
            self.fresh.push(n);
        }
        if let Some(c) = contact {
            self.record_continuing(c, elastic);
        }
    }

    /// Books the step of a contact `c` that went on (its outcome adds +0 to the births' and
    /// ends' sums, which start at +0 and never reach −0: nothing to add).
    #[inline]
    pub(crate) fn record_continuing(&mut self, c: &PairContact, elastic: Real) {
        self.sums.add_touching(c, elastic);
    }
}
