//! Flat PFacet membranes: a rectangle (two PFacets per grid cell) and a disc (rings of
//! PFacets). All PFacets of a membrane have the same orientation: their normal
//! (b − a) × (c − a) is the membrane's normal.

use super::net::grid_points;
use super::skeleton::{add_skeleton, orthonormal_basis, Skeleton, StructureOptions};
use crate::error::{count, direction, finite_point, positive, BuildError};
use crate::{Model, StructureId};
use flexdem_geom::{Real, Vec3};
use std::f64::consts::TAU;

/// Adds a rectangular PFacet membrane on the node grid of [`net`](super::net) (same
/// parameters, same node numbering: see [`GridLayout`](super::GridLayout)). Each cell
/// (i, j) is split along its diagonal from node (i, j) to (i + 1, j + 1) into the PFacets
/// ((i, j), (i + 1, j), (i + 1, j + 1)) and ((i, j), (i + 1, j + 1), (i, j + 1)), both with
/// normal along û × v̂. Counts: `(n_u + 1)(n_v + 1)` nodes,
/// `n_u(n_v + 1) + n_v(n_u + 1) + n_u·n_v` connections, `2·n_u·n_v` PFacets.
pub fn membrane_rectangle(
    model: &mut Model,
    origin: Vec3,
    u_dir: Vec3,
    v_dir: Vec3,
    size_u: Real,
    size_v: Real,
    n_u: usize,
    n_v: usize,
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    let (points, g) = grid_points(origin, u_dir, v_dir, size_u, size_v, n_u, n_v)?;
    let mut faces = Vec::with_capacity(2 * n_u * n_v);
    for j in 0..n_v {
        for i in 0..n_u {
            let (p00, p10) = (g.index(i, j), g.index(i + 1, j));
            let (p01, p11) = (g.index(i, j + 1), g.index(i + 1, j + 1));
            faces.push([p00, p10, p11]);
            faces.push([p00, p11, p01]);
        }
    }
    add_skeleton(model, &Skeleton { points, edges: vec![], faces }, opts)
}

/// Adds a PFacet disc of radius `radius` centred on `center`, in the plane normal to
/// `normal` (the PFacets' normal). Node 0 is the centre; ring k = 1..=n_rings, at radius
/// k·radius/n_rings, has 6k equally spaced nodes (the first on a direction perpendicular to
/// `normal`), so the triangles stay of similar size and shape. Consecutive rings are
/// stitched by walking both around in angle. Counts: `1 + 3·n_rings(n_rings + 1)` nodes,
/// `6·n_rings²` PFacets, `9·n_rings² + 3·n_rings` connections.
pub fn membrane_disc(
    model: &mut Model,
    center: Vec3,
    normal: Vec3,
    radius: Real,
    n_rings: usize,
    opts: &StructureOptions,
) -> Result<StructureId, BuildError> {
    finite_point("center", center)?;
    let n = direction("normal", normal)?;
    positive("radius", radius)?;
    let rings = count("n_rings", n_rings, 1)?;
    count("1 + 3·n_rings·(n_rings + 1)", 1 + 3 * rings * (rings + 1), 1)?;
    let (e1, e2) = orthonormal_basis(n);
    let mut points = vec![center];
    let mut faces = Vec::with_capacity(6 * rings * rings);
    let mut inner: Vec<u32> = vec![0];
    for k in 1..=rings {
        let m = 6 * k;
        let rho = radius * k as Real / rings as Real;
        let start = points.len() as u32;
        points.extend((0..m).map(|i| {
            let theta = TAU * i as Real / m as Real;
            center + rho * (theta.cos() * e1 + theta.sin() * e2)
        }));
        let outer: Vec<u32> = (start..start + m as u32).collect();
        stitch_rings(&inner, &outer, &mut faces);
        inner = outer;
    }
    add_skeleton(model, &Skeleton { points, edges: vec![], faces }, opts)
}

/// Triangulates the band between two closed rings of nodes, both equally spaced in angle
/// from angle 0 and running counterclockwise about the normal, `inner` inside `outer`.
/// Walks both rings, always advancing the one whose next node comes first in angle, giving
/// `inner.len() + outer.len()` triangles (`outer.len()` for a one-node inner ring, a fan),
/// each with normal along the rings' normal.
fn stitch_rings(inner: &[u32], outer: &[u32], faces: &mut Vec<[u32; 3]>) {
    let (m, n) = (inner.len(), outer.len());
    if m == 1 {
        faces.extend((0..n).map(|o| [inner[0], outer[o], outer[(o + 1) % n]]));
        return;
    }
    let (mut i, mut o) = (0usize, 0usize);
    while i < m || o < n {
        // Compare the angles of the next nodes, (i + 1)/m and (o + 1)/n of a turn.
        let advance_outer = i == m || (o < n && (o + 1) * m <= (i + 1) * n);
        if advance_outer {
            faces.push([inner[i % m], outer[o % n], outer[(o + 1) % n]]);
            o += 1;
        } else {
            faces.push([inner[i % m], outer[o % n], inner[(i + 1) % m]]);
            i += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builders::test_support::*;
    use crate::MassLumping;
    use std::f64::consts::PI;

    #[test]
    fn rectangle_counts_orientation_and_topology() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("membrane", 0.005, mat);
        let (u, v) = (Vec3::new(1.0, 1.0, 0.0), Vec3::new(-1.0, 1.0, 0.0));
        let s = membrane_rectangle(&mut model, Vec3::zeros(), u, v, 1.0, 0.5, 5, 3, &opts).unwrap();
        let st = model.structure(s).unwrap().clone();
        assert_eq!(st.nodes.len(), 24);
        assert_eq!(st.connections.len(), 5 * 4 + 3 * 6 + 15);
        assert_eq!(st.pfacets.len(), 30);
        // A disc-like open surface: V − E + F = 1.
        assert_eq!(euler_characteristic(&model, s), 1);
        let per_edge = faces_per_connection(&model, s);
        assert!(per_edge.iter().all(|&k| k == 1 || k == 2));
        assert_eq!(per_edge.iter().filter(|&&k| k == 1).count(), 2 * (5 + 3));
        let expected_n = u.cross(&v).normalize();
        for f in st.pfacets.clone() {
            let (normal, _) = pfacet_normal_centroid(&model, f as usize);
            assert_rel(normal.normalize().dot(&expected_n), 1.0, 1e-12);
        }
        check_adjacency(&model);
    }

    #[test]
    fn plate_mass_adds_the_plate() {
        let (mut model, mat) = model_with_material(1000.0);
        let r = 0.005;
        let opts = StructureOptions::new("m", r, mat).with_mass(MassLumping::Plate);
        membrane_rectangle(&mut model, Vec3::zeros(), Vec3::x(), Vec3::y(), 1.0, 0.5, 4, 2, &opts)
            .unwrap();
        let lengths: Real = model.connections.iter().map(|c| c.rest_length).sum();
        let cylinders = PI * r * r * lengths * 1000.0;
        let plate = 1.0 * 0.5 * 2.0 * r * 1000.0;
        assert_rel(model.total_mass(), cylinders + plate, 1e-12);
    }

    #[test]
    fn disc_counts_orientation_and_radius() {
        for rings in 1..=4 {
            let (mut model, mat) = model_with_material(1000.0);
            let opts = StructureOptions::new("disc", 0.002, mat);
            let normal = Vec3::new(0.3, -0.2, 1.0);
            let c = Vec3::new(1.0, 2.0, 3.0);
            let s = membrane_disc(&mut model, c, normal, 0.5, rings, &opts).unwrap();
            let st = model.structure(s).unwrap().clone();
            assert_eq!(st.nodes.len(), 1 + 3 * rings * (rings + 1));
            assert_eq!(st.pfacets.len(), 6 * rings * rings);
            assert_eq!(st.connections.len(), 9 * rings * rings + 3 * rings);
            assert_eq!(euler_characteristic(&model, s), 1);
            let per_edge = faces_per_connection(&model, s);
            assert!(per_edge.iter().all(|&k| k == 1 || k == 2));
            assert_eq!(per_edge.iter().filter(|&&k| k == 1).count(), 6 * rings);
            let n = normal.normalize();
            let mut area = 0.0;
            for f in st.pfacets.clone() {
                let (fnormal, _) = pfacet_normal_centroid(&model, f as usize);
                assert!(fnormal.normalize().dot(&n) > 1.0 - 1e-12);
                area += 0.5 * fnormal.norm();
            }
            // Area of the inscribed polygon of 6·rings sides.
            let m = 6.0 * rings as Real;
            assert_rel(area, 0.5 * m * 0.25 * (TAU / m).sin(), 1e-12);
            for p in st.nodes.clone() {
                let d = model.particles.pos[p as usize] - c;
                assert!(d.dot(&n).abs() < 1e-12 && d.norm() <= 0.5 + 1e-12);
            }
            check_adjacency(&model);
        }
    }

    #[test]
    fn disc_rejects_bad_parameters() {
        let (mut model, mat) = model_with_material(1000.0);
        let opts = StructureOptions::new("disc", 0.002, mat);
        assert!(membrane_disc(&mut model, Vec3::zeros(), Vec3::zeros(), 1.0, 2, &opts).is_err());
        assert!(membrane_disc(&mut model, Vec3::zeros(), Vec3::z(), 0.0, 2, &opts).is_err());
        let err = membrane_disc(&mut model, Vec3::zeros(), Vec3::z(), 1.0, 0, &opts).unwrap_err();
        assert!(err.to_string().contains("n_rings = 0"), "{err}");
        assert!(model.structures.is_empty());
    }
}
