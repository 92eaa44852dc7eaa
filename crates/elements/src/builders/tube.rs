//! Tubes (open cylinders) of PFacets (paper §6–7).

use super::skeleton::{add_skeleton, orthonormal_basis, Skeleton, StructureOptions};
use crate::error::{count, direction, finite_point, positive, BuildError};
use crate::{Model, StructureId};
use flexdem_geom::{Real, Vec3};
use std::f64::consts::TAU;

/// Adds an open tube of PFacets: `n_along + 1` rings of `n_around` nodes, ring j at
/// `center_start + j·(length/n_along)·â` (â = `axis` normalized), node i of a ring at angle
/// 2πi/n_around counterclockwise about â. Each quad between rings is split along its
/// diagonal from (i, j) to (i + 1, j + 1) into two PFacets whose normals point outward.
/// Counts: `n_around·(n_along + 1)` nodes, `n_around·(3·n_along + 1)` connections,
/// `2·n_around·n_along` PFacets (V − E + F = 0). Needs `n_around` ≥ 3, `n_along` ≥ 1.
pub fn tube(
    model: &mut Model,
    center_start: Vec3,
    axis: Vec3,
    radius: Real,
    length: Real,
    n_around: usize,
    n_along: usize,
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    finite_point("center_start", center_start)?;
    let a = direction("axis", axis)?;
    positive("radius", radius)?;
    positive("length", length)?;
    let m = count("n_around", n_around, 3)?;
    let k = count("n_along", n_along, 1)?;
    count("n_around·(n_along + 1)", m * (k + 1), 1)?;
    let (e1, e2) = orthonormal_basis(a);
    let points = (0..=k)
        .flat_map(|j| {
            (0..m).map(move |i| {
                let theta = TAU * i as Real / m as Real;
                center_start
                    + a * (length * j as Real / k as Real)
                    + radius * (theta.cos() * e1 + theta.sin() * e2)
            })
        })
        .collect();
    let node = |i: usize, j: usize| ((i % m) + j * m) as u32;
    let mut faces = Vec::with_capacity(2 * m * k);
    for j in 0..k {
        for i in 0..m {
            // (tangent × axis) is the outward radial direction.
            faces.push([node(i, j), node(i + 1, j), node(i, j + 1)]);
            faces.push([node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)]);
        }
    }
    add_skeleton(model, &Skeleton { points, edges: vec![], faces }, opts)
}

/// A tube's geometry, for presets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TubeSpec {
    /// Centre of the first ring.
    pub center_start: Vec3,
    /// Axis direction.
    pub axis: Vec3,
    /// Tube radius.
    pub radius: Real,
    /// Tube length.
    pub length: Real,
    /// Nodes around a ring.
    pub n_around: usize,
    /// Segments along the axis.
    pub n_along: usize,
}

impl TubeSpec {
    /// Adds this tube to `model` (see [`tube`]).
    pub fn build(
        &self,
        model: &mut Model,
        opts: &StructureOptions,
    ) -> Result<StructureId, BuildError> {
        tube(
            model,
            self.center_start,
            self.axis,
            self.radius,
            self.length,
            self.n_around,
            self.n_along,
            opts,
        )
    }
}

/// Node (and PFacet) radius of the paper's tube and hollow sphere (§7): 2 mm.
pub const PAPER_NODE_RADIUS: Real = 0.002;

/// The paper's tube (§7): 640 PFacets, radius 0.1 m, length 0.8 m, along x from the origin.
/// The paper does not give its mesh; this preset uses 16 nodes around and 20 segments along
/// (2·16·20 = 640 PFacets, 336 nodes, 976 connections), the split of 640 whose cells are
/// closest to square: 2π·0.1/16 = 39.3 mm around by 0.8/20 = 40 mm along. Use it with
/// [`PAPER_NODE_RADIUS`].
pub fn paper_tube() -> TubeSpec {
    TubeSpec {
        center_start: Vec3::zeros(),
        axis: Vec3::x(),
        radius: 0.1,
        length: 0.8,
        n_around: 16,
        n_along: 20,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builders::test_support::*;
    use std::f64::consts::PI;

    #[test]
    fn paper_tube_has_640_pfacets() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("tube", PAPER_NODE_RADIUS, mat);
        let s = paper_tube().build(&mut model, &opts).unwrap();
        let st = model.structure(s).unwrap().clone();
        assert_eq!(st.pfacets.len(), 640);
        assert_eq!(st.nodes.len(), 336);
        assert_eq!(st.connections.len(), 976);
        // Open tube (an annulus): V − E + F = 0, the two end rings have one PFacet per edge.
        assert_eq!(euler_characteristic(&model, s), 0);
        let per_edge = faces_per_connection(&model, s);
        assert!(per_edge.iter().all(|&k| k == 1 || k == 2));
        assert_eq!(per_edge.iter().filter(|&&k| k == 1).count(), 2 * 16);
        // Mass: Σ πr²Lρ over the connections.
        let lengths: Real = model.connections.iter().map(|c| c.rest_length).sum();
        assert_rel(model.total_mass(), PI * 4e-6 * lengths * 1000.0, 1e-12);
        check_adjacency(&model);
    }

    #[test]
    fn tube_normals_point_outward_and_nodes_lie_on_the_cylinder() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("tube", 0.01, mat);
        let c0 = Vec3::new(1.0, -1.0, 0.5);
        let axis = Vec3::new(0.0, 1.0, 1.0);
        let s = tube(&mut model, c0, axis, 0.3, 2.0, 7, 5, &opts).unwrap();
        let st = model.structure(s).unwrap().clone();
        assert_eq!(st.pfacets.len(), 70);
        assert_eq!(st.connections.len(), 7 * 16);
        let a = axis.normalize();
        for n in st.nodes.clone() {
            let d = model.particles.pos[n as usize] - c0;
            let along = d.dot(&a);
            assert!((-1e-12..=2.0 + 1e-12).contains(&along));
            assert_rel((d - along * a).norm(), 0.3, 1e-12);
        }
        for f in st.pfacets.clone() {
            let (normal, centroid) = pfacet_normal_centroid(&model, f as usize);
            let d = centroid - c0;
            let radial = d - d.dot(&a) * a;
            assert!(normal.dot(&radial) > 0.0, "PFacet {f} points inward");
            assert!(normal.dot(&a).abs() < 1e-12 * normal.norm() + 1e-12);
        }
        assert!(tube(&mut model, c0, axis, 0.3, 2.0, 2, 5, &opts).is_err());
        assert!(tube(&mut model, c0, Vec3::zeros(), 0.3, 2.0, 8, 5, &opts).is_err());
        assert!(tube(&mut model, c0, axis, 0.3, -2.0, 8, 5, &opts).is_err());
        assert_eq!(model.structures.len(), 1);
    }
}
