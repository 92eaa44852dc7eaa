//! Adjacency of a model in compressed sparse row form: node → connections, node → PFacets,
//! connection → PFacets. The engine uses it for "elements sharing a node never pair" and for
//! the one-contact-per-touching rule.

use crate::Model;
use serde::{Deserialize, Serialize};

/// Rows of sorted `u32` lists in compressed sparse row form: row `i` is
/// `items[offsets[i]..offsets[i + 1]]`. Rows past the last non-empty one are not stored
/// (they read empty): a packing's free spheres cost no offsets (the two node rows took 8
/// bytes per sphere of a packing with no structure).
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Csr {
    /// Row starts into `items`; `offsets.len()` is the number of rows + 1.
    pub offsets: Vec<u32>,
    /// The items of all rows, each row sorted ascending.
    pub items: Vec<u32>,
}

impl Csr {
    /// Builds `rows` rows from `(row, item)` pairs (counting sort, O(rows + pairs)), up to
    /// the last non-empty one. Pairs whose row is out of range are skipped. Each row is
    /// sorted; a pair given twice appears twice.
    pub fn from_pairs(rows: usize, pairs: impl Iterator<Item = (u32, u32)> + Clone) -> Csr {
        let rows = pairs
            .clone()
            .map(|(row, _)| row as usize)
            .filter(|&row| row < rows)
            .max()
            .map_or(0, |last| last + 1);
        if rows == 0 {
            return Csr::default();
        }
        let mut offsets = vec![0u32; rows + 1];
        for (row, _) in pairs.clone() {
            if (row as usize) < rows {
                offsets[row as usize + 1] += 1;
            }
        }
        for i in 0..rows {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut items = vec![0u32; offsets[rows] as usize];
        for (row, item) in pairs {
            if (row as usize) < rows {
                let slot = &mut fill[row as usize];
                items[*slot as usize] = item;
                *slot += 1;
            }
        }
        for i in 0..rows {
            items[offsets[i] as usize..offsets[i + 1] as usize].sort_unstable();
        }
        Csr { offsets, items }
    }

    /// Number of rows stored: one past the last non-empty row.
    pub fn rows(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Row `i` (sorted); empty when `i` is out of range.
    pub fn get(&self, i: usize) -> &[u32] {
        if i + 1 < self.offsets.len() {
            &self.items[self.offsets[i] as usize..self.offsets[i + 1] as usize]
        } else {
            &[]
        }
    }
}

/// Which elements touch which: node → connections, node → PFacets, connection → PFacets.
/// Rows are indexed by particle id (free spheres have empty rows) and connection id.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Adjacency {
    /// The connections attached to each particle.
    pub node_connections: Csr,
    /// The PFacets having each particle as a node.
    pub node_pfacets: Csr,
    /// The PFacets having each connection as an edge.
    pub connection_pfacets: Csr,
}

impl Model {
    /// The model's adjacency (built in O(particles + connections + PFacets)). Meant for a
    /// validated model: references out of range are skipped.
    pub fn adjacency(&self) -> Adjacency {
        self.adjacency_where(|_| true)
    }

    /// The adjacency that contact detection reads: [`Model::adjacency`] with only the
    /// connections that are edges of no PFacet in the node → connections rows (a PFacet's
    /// edges are touched through the PFacet, never as elements of their own), so that a
    /// membrane's nodes have none (4 bytes per connection end less).
    pub fn contact_adjacency(&self) -> Adjacency {
        let mut in_pfacet = vec![false; self.connections.len()];
        for c in self.pfacets.iter().flat_map(|f| f.connections) {
            if let Some(flag) = in_pfacet.get_mut(c as usize) {
                *flag = true;
            }
        }
        self.adjacency_where(|c| !in_pfacet[c])
    }

    /// The adjacency with the connections `c` where `listed(c)` in the node → connections
    /// rows.
    fn adjacency_where(&self, listed: impl Fn(usize) -> bool) -> Adjacency {
        let n = self.particles.len();
        let conns = &self.connections;
        let facets = &self.pfacets;
        let node_connections = Csr::from_pairs(
            n,
            conns
                .iter()
                .enumerate()
                .filter(|&(c, _)| listed(c))
                .flat_map(|(c, k)| k.nodes.map(|node| (node, c as u32))),
        );
        let node_pfacets = Csr::from_pairs(
            n,
            facets.iter().enumerate().flat_map(|(f, p)| p.nodes.map(|node| (node, f as u32))),
        );
        let connection_pfacets = Csr::from_pairs(
            conns.len(),
            facets.iter().enumerate().flat_map(|(f, p)| p.connections.map(|c| (c, f as u32))),
        );
        Adjacency { node_connections, node_pfacets, connection_pfacets }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builders::test_support;
    use proptest::prelude::*;

    /// A membrane and a cable: the contact adjacency lists the cable's connections at its
    /// nodes and none of the membrane's (all of them PFacet edges); the rest is the full
    /// adjacency.
    #[test]
    fn contact_adjacency_lists_only_connections_outside_pfacets() {
        use crate::builders::{chain, membrane_rectangle, straight_line};
        use crate::StructureOptions;
        use flexdem_geom::Vec3;
        let (mut model, mat) = test_support::model_with_material(900.0);
        let opts = StructureOptions::new("m", 0.01, mat);
        let (x, z) = (Vec3::x(), Vec3::z());
        membrane_rectangle(&mut model, Vec3::zeros(), x, z, 1.0, 1.0, 3, 2, &opts).unwrap();
        let line = straight_line(Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 1.0, 0.0), 4).unwrap();
        chain(&mut model, &line, &StructureOptions::new("cable", 0.01, mat)).unwrap();
        let (full, contact) = (model.adjacency(), model.contact_adjacency());
        assert_eq!(full.node_pfacets, contact.node_pfacets);
        assert_eq!(full.connection_pfacets, contact.connection_pfacets);
        let edges = |c: u32| full.connection_pfacets.get(c as usize).len();
        let mut cable_ends = 0;
        for n in 0..model.particles.len() {
            let outside: Vec<u32> =
                full.node_connections.get(n).iter().copied().filter(|&c| edges(c) == 0).collect();
            assert_eq!(contact.node_connections.get(n), outside.as_slice(), "node {n}");
            cable_ends += outside.len();
        }
        assert_eq!(cable_ends, 2 * 4, "each of the cable's 4 connections at both its nodes");
    }

    #[test]
    fn csr_rows_are_sorted_and_complete() {
        let pairs = [(2u32, 5u32), (0, 3), (2, 1), (0, 0), (9, 9)];
        let csr = Csr::from_pairs(4, pairs.iter().copied());
        assert_eq!(csr.rows(), 3, "row 3 is empty, past the last non-empty row");
        assert_eq!(csr.get(0), &[0, 3]);
        assert_eq!(csr.get(1), &[] as &[u32]);
        assert_eq!(csr.get(2), &[1, 5]);
        assert_eq!(csr.get(3), &[] as &[u32]);
        assert_eq!(csr.get(4), &[] as &[u32], "out of range row is empty");
        assert_eq!(Csr::default().get(0), &[] as &[u32]);
        let none = Csr::from_pairs(1000, [(1000u32, 1u32)].into_iter());
        assert_eq!((none.rows(), none.offsets.len(), none.items.len()), (0, 0, 0));
    }

    proptest! {
        /// Row i of the CSR is exactly the sorted multiset of items paired with i.
        #[test]
        fn csr_matches_naive_lists(
            rows in 0usize..12,
            pairs in proptest::collection::vec((0u32..14, 0u32..50), 0..60),
        ) {
            let csr = Csr::from_pairs(rows, pairs.iter().copied());
            let last = pairs.iter().map(|p| p.0 as usize).filter(|&r| r < rows).max();
            prop_assert_eq!(csr.rows(), last.map_or(0, |r| r + 1));
            for r in 0..rows + 2 {
                let mut expected: Vec<u32> =
                    pairs.iter().filter(|p| p.0 as usize == r && r < rows).map(|p| p.1).collect();
                expected.sort_unstable();
                prop_assert_eq!(csr.get(r), expected.as_slice());
            }
        }
    }
}
