//! The elements built on nodes (connections, PFacets), walls and structures: plain data
//! referring to particles by id.

use crate::{ConnectionId, MaterialId, NodeId, PFacetId, StructureId};
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};
use std::ops::Range;

/// A connection ("GridConnection"): the cylinder joining two nodes, the Minkowski sum of the
/// segment [node 0, node 1] and a sphere of radius `radius`. It owns one cohesive beam link
/// between its nodes (eq 8); the link's mutable state lives in the engine.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Connection {
    /// The two nodes (particle ids).
    pub nodes: [NodeId; 2],
    /// Cylinder radius (the nodes' radius).
    pub radius: Real,
    /// Material of the cylinder (its link and its external contacts).
    pub material: MaterialId,
    /// Collision group bits.
    pub mask: u32,
    /// The structure it belongs to.
    pub structure: StructureId,
    /// Rest length L0 of the link: the node distance when it was built.
    pub rest_length: Real,
}

/// A PFacet: the Minkowski sum of the triangle (node 0, node 1, node 2) and a sphere of radius
/// `radius`. Edge numbering of `docs/architecture.md`: `connections[0]` joins nodes 0–1,
/// `[1]` joins 1–2, `[2]` joins 2–0. Its normal (1 − 0) × (2 − 0) points to the side the
/// builders call "outside".
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PFacet {
    /// The three nodes (particle ids).
    pub nodes: [NodeId; 3],
    /// The three edge connections, numbered as above.
    pub connections: [ConnectionId; 3],
    /// Radius (the nodes' radius; half the membrane thickness).
    pub radius: Real,
    /// Material of the face's external contacts.
    pub material: MaterialId,
    /// Collision group bits.
    pub mask: u32,
    /// The structure it belongs to.
    pub structure: StructureId,
}

impl PFacet {
    /// The two nodes joined by edge `edge` (0 = nodes 0–1, 1 = 1–2, 2 = 2–0).
    pub fn edge_nodes(&self, edge: usize) -> [NodeId; 2] {
        [self.nodes[edge % 3], self.nodes[(edge + 1) % 3]]
    }
}

/// An infinite plane wall, kinematic only: `point` on the plane moves at `velocity`; bodies
/// live on the side `normal` points to.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Wall {
    /// A point of the plane.
    pub point: Vec3,
    /// Unit outward normal: the side where bodies live.
    pub normal: Vec3,
    /// Imposed velocity of the plane.
    pub velocity: Vec3,
    /// Material.
    pub material: MaterialId,
    /// Collision group bits.
    pub mask: u32,
}

/// A named group of nodes, connections and PFacets built together, each a contiguous range
/// of ids.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Structure {
    /// Name given by the user (not necessarily unique).
    pub name: String,
    /// Its nodes (particle ids).
    pub nodes: Range<NodeId>,
    /// Its connections.
    pub connections: Range<ConnectionId>,
    /// Its PFacets.
    pub pfacets: Range<PFacetId>,
    /// Whether its elements touch one another (self-contact; elements sharing a node never
    /// do). `false` skips those pairs in the collider, as YADE's `avoidSelfInteractionMask`.
    pub self_contact: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pfacet_edge_numbering_follows_the_architecture() {
        let f = PFacet {
            nodes: [7, 8, 9],
            connections: [0, 1, 2],
            radius: 0.1,
            material: 0,
            mask: 1,
            structure: 0,
        };
        assert_eq!(f.edge_nodes(0), [7, 8]);
        assert_eq!(f.edge_nodes(1), [8, 9]);
        assert_eq!(f.edge_nodes(2), [9, 7]);
    }
}
