//! A new contact's stiffness as the time step's sums take it (`stiffness_sums.rs`,
//! model.md §4): what it adds to each node of its sites ([`contact_increments`]), and a new
//! pair's node shares, found by the pair's step (`pair_chunk.rs`) and added in key order by
//! `stiffness_sums::add_fresh`.

use crate::dashpots::FactorMemo;
use crate::neighbours::sites;
use crate::pair_keys::ContactKey;
use crate::time_step::{spring_increments, StiffnessSums};
use flexdem_contact::FrictionalParams;
use flexdem_elements::virtual_sphere::Site;
use flexdem_elements::{Dofs, Model, Particles};
use flexdem_geom::{Real, Vec3};

/// What a contact's stiffness adds to the sums of one node of mass `mass` carrying one of its
/// sites, of radius `radius` (the lever arm of the shear): the full contact stiffness
/// (conservative). A contact with dashpots counts for the stiffer spring whose stability
/// limit it has (`damped_stiffness_factor`, model.md §7; `memo` keeps its last answers, one
/// for the normal spring and one for the shear spring).
#[inline]
pub(crate) fn contact_increments(
    mass: Real,
    params: &FrictionalParams,
    n: &Vec3,
    radius: Real,
    memo: &mut [FactorMemo; 2],
) -> (Vec3, Vec3) {
    let c = params;
    let (kn, ks) = (c.kn, c.ks);
    if c.is_damped() {
        let kn = kn * memo[0].factor(kn, c.cn, mass);
        let ks = ks * memo[1].factor(ks, c.ct, mass);
        spring_increments(n, kn, ks, radius, 0.0, 0.0)
    } else {
        spring_increments(n, kn, ks, radius, 0.0, 0.0)
    }
}

/// One node's share of a new contact's stiffness (`stiffness_sums::add_fresh`): the node,
/// what the contact adds to its translational and rotational sums, and what the node's
/// critical step reads of it: its mass, its inertia and whether it is free in a DOF (a
/// held node's step is not counted). 72 bytes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NodeShare {
    node: u32,
    free: bool,
    increments: (Vec3, Vec3),
    mass: Real,
    inertia: Real,
}

impl NodeShare {
    /// No share (a place to fill).
    fn none() -> Self {
        let zero = (Vec3::zeros(), Vec3::zeros());
        NodeShare { node: 0, free: false, increments: zero, mass: 0.0, inertia: 0.0 }
    }

    /// Node `node`'s share of a contact of constants `params` and normal `n` on a site of
    /// radius `radius` ([`contact_increments`]).
    #[inline]
    fn of(
        p: &Particles,
        node: u32,
        params: &FrictionalParams,
        n: &Vec3,
        radius: Real,
        memo: &mut [FactorMemo; 2],
    ) -> Self {
        let i = node as usize;
        let (mass, inertia) = (p.mass[i], p.inertia[i]);
        let increments = contact_increments(mass, params, n, radius, memo);
        NodeShare { node, free: p.blocked[i] != Dofs::ALL, increments, mass, inertia }
    }

    /// Adds the share to its node's sums if `k` holds them; returns the node's critical step
    /// after it, `√(2·min(m/K_trans, J/K_rot))` with the largest components of its sums
    /// (infinite for no stiffness, or for a held node, whose step is not counted), or None
    /// for a node out of `k`'s range.
    #[inline]
    pub(crate) fn add_to(&self, k: &mut SumsRange<'_>) -> Option<Real> {
        let node = self.node as usize;
        if !k.holds(node) {
            return None;
        }
        k.add(node, self.increments);
        if !self.free {
            return Some(Real::INFINITY);
        }
        let n = node - k.first;
        let (kt, kr) = (k.translational[n].max(), k.rotational[n].max());
        let mut ratio = Real::INFINITY;
        if kt > 0.0 {
            ratio = ratio.min(self.mass / kt);
        }
        if kr > 0.0 {
            ratio = ratio.min(self.inertia / kr);
        }
        Some((2.0 * ratio).sqrt())
    }
}

/// The stiffness sums of the particles from `first` on, as many as the slices hold: the part
/// of [`StiffnessSums`] one task of `stiffness_sums::add_fresh` or `add_in_ranges` adds to.
pub(crate) struct SumsRange<'a> {
    /// The first particle's index.
    pub(crate) first: usize,
    /// Their translational sums.
    pub(crate) translational: &'a mut [Vec3],
    /// Their rotational sums (as many).
    pub(crate) rotational: &'a mut [Vec3],
}

impl<'a> SumsRange<'a> {
    /// Every particle's sums.
    pub(crate) fn whole(k: &'a mut StiffnessSums) -> Self {
        debug_assert_eq!(k.translational.len(), k.rotational.len());
        SumsRange { first: 0, translational: &mut k.translational, rotational: &mut k.rotational }
    }

    /// Whether particle `i`'s sums are in the range.
    #[inline]
    pub(crate) fn holds(&self, i: usize) -> bool {
        i.wrapping_sub(self.first) < self.translational.len()
    }

    /// Adds increments `(t, r)` to particle `i`'s sums (in the range).
    #[inline]
    pub(crate) fn add(&mut self, i: usize, (t, r): (Vec3, Vec3)) {
        let k = i - self.first;
        self.translational[k] += t;
        self.rotational[k] += r;
    }
}

/// The shares of the nodes of a new contact's `sites` (body 1's first; at most `N` in all),
/// for its constants `params` and normal `n`, and how many there are.
pub(crate) fn site_shares<const N: usize>(
    p: &Particles,
    sites: [&Site; 2],
    params: &FrictionalParams,
    n: &Vec3,
    memo: &mut [FactorMemo; 2],
) -> ([NodeShare; N], usize) {
    let mut shares = [NodeShare::none(); N];
    let mut len = 0;
    for site in sites {
        for &node in &site.nodes[..site.node_count()] {
            shares[len] = NodeShare::of(p, node, params, n, site.radius, memo);
            len += 1;
        }
    }
    (shares, len)
}

/// The node shares of a new pair of the neighbour list, body 1's first: two for two
/// spheres, one for a wall and a sphere (a wall has no node). Found by the pair's step,
/// where its contact and particles are at hand (`pair_chunk.rs`), for
/// `stiffness_sums::add_fresh`: found there from the contacts, they were 4 % of a step of
/// the packing of 10⁵ spheres settling (900 new pairs a step, 440 ns each, most of it
/// waiting on memory).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairShares {
    shares: [NodeShare; 2],
    len: u8,
}

impl PairShares {
    /// The shares of pair `key`'s nodes, for its contact's constants `params` and normal
    /// `n` (after its law).
    #[inline]
    pub(crate) fn of(
        model: &Model,
        key: &ContactKey,
        params: &FrictionalParams,
        n: &Vec3,
        memo: &mut [FactorMemo; 2],
    ) -> Self {
        let (site1, site2) = sites(model, key);
        let (shares, len) = site_shares(&model.particles, [&site1, &site2], params, n, memo);
        PairShares { shares, len: len as u8 }
    }

    /// The shares, body 1's first.
    pub(crate) fn shares(&self) -> &[NodeShare] {
        &self.shares[..self.len as usize]
    }
}
