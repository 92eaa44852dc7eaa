//! Rectangular nets (YADE's `Simple_Grid_Falling.py` and the grids of the PFacet examples):
//! nodes on a grid, connections along the grid lines, optionally one diagonal per cell; and
//! the node layout shared with the PFacet rectangle, to pin edges and corners.

use super::skeleton::{add_skeleton, Skeleton, StructureOptions};
use crate::error::{count, direction, finite_point, positive, BuildError, ModelError};
use crate::{Model, NodeId, StructureId};
use flexdem_geom::{Real, Vec3};

/// The parallelogram grid of nodes shared by [`net`] and
/// [`membrane_rectangle`](super::membrane_rectangle): node (i, j) at
/// `origin + i·(size_u/n_u)·û + j·(size_v/n_v)·v̂`, i in 0..=n_u, j in 0..=n_v.
pub(crate) fn grid_points(
    origin: Vec3,
    u_dir: Vec3,
    v_dir: Vec3,
    size_u: Real,
    size_v: Real,
    n_u: usize,
    n_v: usize,
) -> Result<(Vec<Vec3>, GridShape), BuildError> {
    finite_point("origin", origin)?;
    let u = direction("u_dir", u_dir)?;
    let v = direction("v_dir", v_dir)?;
    if u.cross(&v).norm() <= 1e-6 {
        return Err(BuildError::InvalidParameter {
            name: "v_dir",
            value: format!("{v_dir:?} (parallel to u_dir {u_dir:?})"),
            expected: "a direction not parallel to u_dir",
        });
    }
    let du = u * positive("size_u", size_u)? / count("n_u", n_u, 1)? as Real;
    let dv = v * positive("size_v", size_v)? / count("n_v", n_v, 1)? as Real;
    count("(n_u + 1)·(n_v + 1)", (n_u + 1) * (n_v + 1), 1)?;
    let shape = GridShape { n_u, n_v };
    let points = (0..=n_v)
        .flat_map(|j| (0..=n_u).map(move |i| origin + du * i as Real + dv * j as Real))
        .collect();
    Ok((points, shape))
}

/// Number of cells of a node grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct GridShape {
    pub n_u: usize,
    pub n_v: usize,
}

impl GridShape {
    /// Local index of node (i, j): i + j·(n_u + 1).
    pub fn index(&self, i: usize, j: usize) -> u32 {
        (i + j * (self.n_u + 1)) as u32
    }
}

/// Adds a rectangular net: `(n_u + 1)·(n_v + 1)` nodes on the grid spanned from `origin` by
/// `size_u` along `u_dir` and `size_v` along `v_dir` (directions normalized here; they need
/// not be orthogonal, which gives a parallelogram net, but must not be parallel), with
/// `n_u`, `n_v` ≥ 1 cells. Connections follow the grid lines (`n_u·(n_v + 1) + n_v·(n_u + 1)`
/// of them); with `diagonals`, each cell also gets the diagonal from node (i, j) to
/// (i + 1, j + 1) (one per cell: two crossing diagonals would touch at rest). Node (i, j) is
/// the structure's `nodes.start + i + j·(n_u + 1)`: see [`GridLayout`] to pin sides and
/// corners.
pub fn net(
    model: &mut Model,
    origin: Vec3,
    u_dir: Vec3,
    v_dir: Vec3,
    size_u: Real,
    size_v: Real,
    n_u: usize,
    n_v: usize,
    diagonals: bool,
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    let (points, g) = grid_points(origin, u_dir, v_dir, size_u, size_v, n_u, n_v)?;
    let mut edges = Vec::new();
    for j in 0..=n_v {
        for i in 0..=n_u {
            if i < n_u {
                edges.push([g.index(i, j), g.index(i + 1, j)]);
            }
            if j < n_v {
                edges.push([g.index(i, j), g.index(i, j + 1)]);
            }
            if diagonals && i < n_u && j < n_v {
                edges.push([g.index(i, j), g.index(i + 1, j + 1)]);
            }
        }
    }
    add_skeleton(model, &Skeleton { points, edges, faces: vec![] }, opts)
}

/// A side of a grid structure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GridSide {
    /// The nodes with i = 0 (the side through `origin` along `v_dir`).
    UMin,
    /// The nodes with i = n_u.
    UMax,
    /// The nodes with j = 0 (the side through `origin` along `u_dir`).
    VMin,
    /// The nodes with j = n_v.
    VMax,
}

/// The node layout of a structure built by [`net`] or
/// [`membrane_rectangle`](super::membrane_rectangle), to select its sides and corners for
/// pinning (with [`Model::block`]) or loading.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GridLayout {
    /// Id of node (0, 0).
    pub first_node: NodeId,
    /// Cells along u.
    pub n_u: usize,
    /// Cells along v.
    pub n_v: usize,
}

impl GridLayout {
    /// The layout of `structure`, built with `n_u × n_v` cells; checks the node count.
    pub fn of(
        model: &Model,
        structure: StructureId,
        n_u: usize,
        n_v: usize,
    ) -> Result<GridLayout, ModelError> {
        let nodes = &model.structure(structure)?.nodes;
        let expected = (n_u + 1).checked_mul(n_v + 1);
        if n_u == 0 || n_v == 0 || expected != Some(nodes.len()) {
            return Err(ModelError::StructureMismatch {
                item: crate::error::Item::Structure(structure),
                structure: crate::error::Item::Structure(structure),
                reason: format!(
                    "it has {} nodes, not the (n_u + 1)·(n_v + 1) of a {n_u} × {n_v} grid",
                    nodes.len()
                ),
            });
        }
        Ok(GridLayout { first_node: nodes.start, n_u, n_v })
    }

    /// Node (i, j) (i ≤ n_u, j ≤ n_v; larger values are clamped).
    pub fn node(&self, i: usize, j: usize) -> NodeId {
        let (i, j) = (i.min(self.n_u), j.min(self.n_v));
        self.first_node + (i + j * (self.n_u + 1)) as NodeId
    }

    /// The nodes of one side, in order of increasing i or j (corners included).
    pub fn side(&self, side: GridSide) -> Vec<NodeId> {
        match side {
            GridSide::UMin => (0..=self.n_v).map(|j| self.node(0, j)).collect(),
            GridSide::UMax => (0..=self.n_v).map(|j| self.node(self.n_u, j)).collect(),
            GridSide::VMin => (0..=self.n_u).map(|i| self.node(i, 0)).collect(),
            GridSide::VMax => (0..=self.n_u).map(|i| self.node(i, self.n_v)).collect(),
        }
    }

    /// The four corners: (0, 0), (n_u, 0), (n_u, n_v), (0, n_v).
    pub fn corners(&self) -> [NodeId; 4] {
        [
            self.node(0, 0),
            self.node(self.n_u, 0),
            self.node(self.n_u, self.n_v),
            self.node(0, self.n_v),
        ]
    }

    /// Every boundary node once, ascending.
    pub fn boundary(&self) -> Vec<NodeId> {
        let mut nodes: Vec<NodeId> =
            [GridSide::UMin, GridSide::UMax, GridSide::VMin, GridSide::VMax]
                .iter()
                .flat_map(|&s| self.side(s))
                .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builders::test_support::*;
    use crate::{Dofs, ParticleKind};
    use std::f64::consts::PI;

    #[test]
    fn net_counts_and_mass() {
        // YADE's Simple_Grid_Falling.py: 10 × 5 nodes, spacing 0.01: 85 connections.
        let (mut model, mat) = model_with_material(10.0);
        let opts = StructureOptions::new("net", 0.001, mat);
        let s =
            net(&mut model, Vec3::zeros(), Vec3::x(), Vec3::y(), 0.09, 0.04, 9, 4, false, &opts)
                .unwrap();
        let st = model.structure(s).unwrap().clone();
        assert_eq!(st.nodes.len(), 50);
        assert_eq!(st.connections.len(), 85);
        assert_eq!(st.pfacets.len(), 0);
        let expected = 85.0 * PI * 1e-6 * 0.01 * 10.0;
        assert_rel(model.total_mass(), expected, 1e-12);
        // Corner nodes have 2 connections, side nodes 3, inner nodes 4.
        let adj = model.adjacency();
        let layout = GridLayout::of(&model, s, 9, 4).unwrap();
        for c in layout.corners() {
            assert_eq!(adj.node_connections.get(c as usize).len(), 2);
        }
        assert_eq!(adj.node_connections.get(layout.node(4, 2) as usize).len(), 4);
        assert_eq!(adj.node_connections.get(layout.node(0, 2) as usize).len(), 3);
        check_adjacency(&model);
        assert!(model.structure_ends(s).unwrap().is_empty());

        let d = net(&mut model, Vec3::zeros(), Vec3::x(), Vec3::z(), 1.0, 1.0, 3, 2, true, &opts)
            .unwrap();
        let st = model.structure(d).unwrap();
        assert_eq!(st.nodes.len(), 12);
        assert_eq!(st.connections.len(), 3 * 3 + 2 * 4 + 6);
        check_adjacency(&model);
    }

    #[test]
    fn grid_layout_sides_and_pinning() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("net", 0.01, mat);
        model.add_sphere(Vec3::new(0.0, 0.0, 5.0), 0.1, mat).unwrap();
        let s = net(&mut model, Vec3::zeros(), Vec3::x(), Vec3::y(), 2.0, 1.0, 4, 2, false, &opts)
            .unwrap();
        let g = GridLayout::of(&model, s, 4, 2).unwrap();
        assert_eq!(g.first_node, 1);
        let pos = |n: NodeId| model.particles.pos[n as usize];
        for n in g.side(GridSide::UMin) {
            assert!(pos(n).x.abs() < 1e-12);
        }
        for n in g.side(GridSide::UMax) {
            assert!((pos(n).x - 2.0).abs() < 1e-12);
        }
        for n in g.side(GridSide::VMax) {
            assert!((pos(n).y - 1.0).abs() < 1e-12);
        }
        assert_eq!(g.side(GridSide::VMin).len(), 5);
        assert_eq!(g.boundary().len(), 2 * 5 + 2 * 3 - 4);
        assert_eq!(pos(g.corners()[2]), Vec3::new(2.0, 1.0, 0.0));
        // Same selection by plane.
        let mut by_plane = model.nodes_on_plane(Vec3::zeros(), Vec3::x(), 1e-9).unwrap();
        by_plane.sort_unstable();
        assert_eq!(by_plane, g.side(GridSide::UMin));
        model.block(g.boundary(), Dofs::ALL).unwrap();
        for n in g.boundary() {
            assert_eq!(model.particles.blocked[n as usize], Dofs::ALL);
        }
        assert_eq!(model.particles.blocked[g.node(2, 1) as usize], Dofs::NONE);
        assert_eq!(model.particles.kind[0], ParticleKind::Sphere);
        assert!(GridLayout::of(&model, s, 3, 2).is_err());
    }

    #[test]
    fn net_rejects_bad_parameters() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("net", 0.01, mat);
        let z = Vec3::zeros();
        let (x, y) = (Vec3::x(), Vec3::y());
        let err = net(&mut model, z, x, x * 2.0, 1.0, 1.0, 2, 2, false, &opts).unwrap_err();
        assert!(err.to_string().contains("parallel"), "{err}");
        let err = net(&mut model, z, z, y, 1.0, 1.0, 2, 2, false, &opts).unwrap_err();
        assert!(err.to_string().contains("u_dir"), "{err}");
        let err = net(&mut model, z, x, y, 1.0, 1.0, 0, 2, false, &opts).unwrap_err();
        assert!(err.to_string().contains("n_u = 0"), "{err}");
        let err = net(&mut model, z, x, y, 1.0, f64::NAN, 2, 2, false, &opts).unwrap_err();
        assert!(err.to_string().contains("size_v = NaN"), "{err}");
        assert_eq!(model.particles.len(), 0);
    }
}
