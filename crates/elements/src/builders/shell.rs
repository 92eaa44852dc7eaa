//! Closed sphere shells of PFacets: a regular polyhedron with its triangles subdivided and the
//! new vertices pushed onto the sphere (paper §7's hollow sphere).

use super::skeleton::{add_skeleton, Skeleton, StructureOptions};
use crate::error::{finite_point, positive, BuildError};
use crate::{Model, StructureId};
use flexdem_geom::{Real, Vec3};
use std::collections::HashMap;

/// The polyhedron a sphere shell is subdivided from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShellBase {
    /// 20 faces, 12 vertices: the most uniform triangles ("icosphere").
    Icosahedron,
    /// 8 faces, 6 vertices (on the axes).
    Octahedron,
}

impl ShellBase {
    fn faces(self) -> usize {
        match self {
            ShellBase::Icosahedron => 20,
            ShellBase::Octahedron => 8,
        }
    }
}

/// Largest subdivision level accepted (8·4⁹ ≈ 2.1 million PFacets on an octahedron).
pub const MAX_SHELL_SUBDIVISIONS: u32 = 9;

/// Adds a closed sphere shell of radius `radius` centred on `center`: the base polyhedron's
/// triangles each split `subdivisions` times into 4 (edge midpoints pushed onto the sphere).
/// Counts: F = F₀·4^subdivisions PFacets (F₀ = 20 or 8), E = 3F/2 connections,
/// V = F/2 + 2 nodes (V − E + F = 2); every connection is shared by exactly 2 PFacets, and
/// every PFacet's normal (b − a) × (c − a) points outward.
pub fn sphere_shell(
    model: &mut Model,
    center: Vec3,
    radius: Real,
    base: ShellBase,
    subdivisions: u32,
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    finite_point("center", center)?;
    positive("radius", radius)?;
    if subdivisions > MAX_SHELL_SUBDIVISIONS {
        return Err(BuildError::InvalidParameter {
            name: "subdivisions",
            value: subdivisions.to_string(),
            expected: "at most MAX_SHELL_SUBDIVISIONS = 9",
        });
    }
    let (mut points, mut faces) = base_polyhedron(base);
    debug_assert_eq!(faces.len(), base.faces());
    for _ in 0..subdivisions {
        faces = subdivide(&mut points, &faces);
    }
    let points = points.iter().map(|p| center + radius * p).collect();
    add_skeleton(model, &Skeleton { points, edges: vec![], faces }, opts)
}

/// Unit-sphere vertices and outward-oriented faces of the base polyhedron.
fn base_polyhedron(base: ShellBase) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let (points, faces): (Vec<Vec3>, Vec<[u32; 3]>) = match base {
        ShellBase::Octahedron => (
            vec![Vec3::x(), -Vec3::x(), Vec3::y(), -Vec3::y(), Vec3::z(), -Vec3::z()],
            vec![
                [0, 2, 4],
                [2, 1, 4],
                [1, 3, 4],
                [3, 0, 4],
                [2, 0, 5],
                [1, 2, 5],
                [3, 1, 5],
                [0, 3, 5],
            ],
        ),
        ShellBase::Icosahedron => {
            let phi = (1.0 + 5.0_f64.sqrt()) / 2.0;
            let raw = [
                (-1.0, phi, 0.0),
                (1.0, phi, 0.0),
                (-1.0, -phi, 0.0),
                (1.0, -phi, 0.0),
                (0.0, -1.0, phi),
                (0.0, 1.0, phi),
                (0.0, -1.0, -phi),
                (0.0, 1.0, -phi),
                (phi, 0.0, -1.0),
                (phi, 0.0, 1.0),
                (-phi, 0.0, -1.0),
                (-phi, 0.0, 1.0),
            ];
            (
                raw.iter().map(|&(x, y, z)| Vec3::new(x, y, z).normalize()).collect(),
                vec![
                    [0, 11, 5],
                    [0, 5, 1],
                    [0, 1, 7],
                    [0, 7, 10],
                    [0, 10, 11],
                    [1, 5, 9],
                    [5, 11, 4],
                    [11, 10, 2],
                    [10, 7, 6],
                    [7, 1, 8],
                    [3, 9, 4],
                    [3, 4, 2],
                    [3, 2, 6],
                    [3, 6, 8],
                    [3, 8, 9],
                    [4, 9, 5],
                    [2, 4, 11],
                    [6, 2, 10],
                    [8, 6, 7],
                    [9, 8, 1],
                ],
            )
        }
    };
    (points, faces)
}

/// Splits each triangle (a, b, c) into (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca),
/// with each edge midpoint created once and pushed onto the unit sphere. Orientation is kept.
fn subdivide(points: &mut Vec<Vec3>, faces: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let mut midpoints: HashMap<(u32, u32), u32> = HashMap::with_capacity(faces.len() * 3 / 2);
    let mut midpoint = |a: u32, b: u32, points: &mut Vec<Vec3>| -> u32 {
        *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
            points.push((points[a as usize] + points[b as usize]).normalize());
            (points.len() - 1) as u32
        })
    };
    let mut out = Vec::with_capacity(faces.len() * 4);
    for &[a, b, c] in faces {
        let ab = midpoint(a, b, points);
        let bc = midpoint(b, c, points);
        let ca = midpoint(c, a, points);
        out.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    out
}

/// A sphere shell's geometry, for presets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellSpec {
    /// Centre.
    pub center: Vec3,
    /// Radius.
    pub radius: Real,
    /// Base polyhedron.
    pub base: ShellBase,
    /// Subdivision level.
    pub subdivisions: u32,
}

impl ShellSpec {
    /// Adds this shell to `model` (see [`sphere_shell`]).
    pub fn build(
        &self,
        model: &mut Model,
        opts: &StructureOptions,
    ) -> Result<StructureId, BuildError> {
        sphere_shell(model, self.center, self.radius, self.base, self.subdivisions, opts)
    }
}

/// The paper's hollow sphere (§7): 128 PFacets, radius 0.1 m, at the origin. The paper does
/// not give its mesh; YADE's `sphere.mesh` example has 128 triangles, and an octahedron
/// subdivided twice gives exactly 8·4² = 128 PFacets, 66 nodes and 192 connections. Use it
/// with [`PAPER_NODE_RADIUS`](super::PAPER_NODE_RADIUS).
pub fn paper_hollow_sphere() -> ShellSpec {
    ShellSpec { center: Vec3::zeros(), radius: 0.1, base: ShellBase::Octahedron, subdivisions: 2 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builders::test_support::*;
    use crate::builders::PAPER_NODE_RADIUS;

    fn check_closed_outward_shell(model: &Model, s: StructureId, center: Vec3, radius: Real) {
        assert_eq!(euler_characteristic(model, s), 2);
        assert!(faces_per_connection(model, s).iter().all(|&k| k == 2));
        let st = model.structure(s).unwrap();
        for n in st.nodes.clone() {
            assert_rel((model.particles.pos[n as usize] - center).norm(), radius, 1e-12);
        }
        for f in st.pfacets.clone() {
            let (normal, centroid) = pfacet_normal_centroid(model, f as usize);
            assert!(normal.dot(&(centroid - center)) > 0.0, "PFacet {f} points inward");
        }
        // Consistent orientation: each shared edge is traversed in opposite directions by its
        // two PFacets.
        let mut directed = std::collections::HashSet::new();
        for f in st.pfacets.clone() {
            for e in 0..3 {
                assert!(
                    directed.insert(model.pfacets[f as usize].edge_nodes(e)),
                    "edge used twice in one direction"
                );
            }
        }
        check_adjacency(model);
    }

    #[test]
    fn paper_hollow_sphere_has_128_pfacets_and_66_nodes() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("hollow sphere", PAPER_NODE_RADIUS, mat);
        let s = paper_hollow_sphere().build(&mut model, &opts).unwrap();
        let st = model.structure(s).unwrap().clone();
        assert_eq!(st.pfacets.len(), 128);
        assert_eq!(st.nodes.len(), 66);
        assert_eq!(st.connections.len(), 192);
        check_closed_outward_shell(&model, s, Vec3::zeros(), 0.1);
    }

    #[test]
    fn icospheres_and_octaspheres_have_the_expected_counts() {
        for (base, f0) in [(ShellBase::Icosahedron, 20usize), (ShellBase::Octahedron, 8)] {
            for k in 0..=3u32 {
                let (mut model, mat) = model_with_material(1000.0);
                let c = Vec3::new(0.5, -2.0, 1.0);
                let opts = StructureOptions::new("shell", 0.01, mat);
                let s = sphere_shell(&mut model, c, 0.7, base, k, &opts).unwrap();
                let st = model.structure(s).unwrap().clone();
                let f = f0 * 4usize.pow(k);
                assert_eq!(st.pfacets.len(), f, "{base:?} k = {k}");
                assert_eq!(st.connections.len(), 3 * f / 2);
                assert_eq!(st.nodes.len(), f / 2 + 2);
                check_closed_outward_shell(&model, s, c, 0.7);
            }
        }
    }

    #[test]
    fn shell_rejects_bad_parameters() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("shell", 0.01, mat);
        let b = ShellBase::Icosahedron;
        assert!(sphere_shell(&mut model, Vec3::zeros(), -1.0, b, 1, &opts).is_err());
        let err = sphere_shell(&mut model, Vec3::zeros(), 1.0, b, 12, &opts).unwrap_err();
        assert!(err.to_string().contains("subdivisions = 12"), "{err}");
        assert!(sphere_shell(&mut model, Vec3::repeat(f64::NAN), 1.0, b, 1, &opts).is_err());
        assert!(model.structures.is_empty());
    }
}
