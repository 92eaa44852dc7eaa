//! Cheap tests that prove two candidate elements do not touch, run before the exact
//! closest-point kernels (which cost up to a microsecond for triangle–triangle). Most pairs of
//! a Verlet list are near misses: neighbours of neighbours on a mesh, spheres a little apart.
//!
//! Every element is a convex hull of one to three points (sphere centre, connection ends,
//! PFacet corners) grown by a radius. Two such bodies are apart when, along some unit axis n,
//!
//! min_j (b_j · n) − max_i (a_i · n) > r_a + r_b,
//!
//! (a separating slab wider than the two radii). The tests below are conservative: they only
//! ever answer "apart" when the exact distance exceeds r_a + r_b.

use flexdem_elements::touching::Element;
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};

/// An element in its current configuration: its skeleton points and radius.
#[derive(Clone, Copy, Debug)]
pub struct Hull {
    /// Skeleton points; only the first `count` are used.
    pub points: [Vec3; 3],
    /// 1 (sphere), 2 (connection) or 3 (PFacet).
    pub count: usize,
    /// Radius the skeleton is grown by.
    pub radius: Real,
    /// Mean of the skeleton points.
    pub centroid: Vec3,
    /// Unit normal of a PFacet's plane (zero for the other elements or a degenerate one).
    pub normal: Vec3,
}

impl Hull {
    /// The skeleton points in use.
    pub fn skeleton(&self) -> &[Vec3] {
        &self.points[..self.count]
    }

    /// The hull of the first `count` (1 to 3) of `points` grown by `radius`.
    #[inline]
    pub fn new(points: [Vec3; 3], count: usize, radius: Real) -> Hull {
        let z = Vec3::zeros();
        let mut h = Hull { points, count, radius, centroid: z, normal: z };
        match count {
            1 => fill::<1>(&mut h, points, radius),
            2 => fill::<2>(&mut h, points, radius),
            _ => fill::<3>(&mut h, points, radius),
        }
        h
    }
}

/// Writes the hull of element `e` of `model` into `h`, field by field (assigning a whole
/// hull went through `memcpy`, 9 % of a 2-thread membrane step).
#[inline]
pub fn write_hull(model: &Model, e: Element, h: &mut Hull) {
    let p = &model.particles.pos;
    match e {
        Element::Particle(i) => {
            fill::<1>(h, [p[i as usize]; 3], model.particles.radius[i as usize]);
        }
        Element::Connection(k) => {
            let c = &model.connections[k as usize];
            let (a, b) = (p[c.nodes[0] as usize], p[c.nodes[1] as usize]);
            fill::<2>(h, [a, b, b], c.radius);
        }
        Element::PFacet(k) => {
            let f = &model.pfacets[k as usize];
            fill::<3>(h, f.nodes.map(|n| p[n as usize]), f.radius);
        }
    }
}

/// [`Hull::new`] written into `h`, with the count known when compiled (the centroid's sum
/// unrolled, the normal only for a PFacet).
#[inline(always)]
fn fill<const COUNT: usize>(h: &mut Hull, points: [Vec3; 3], radius: Real) {
    h.centroid = points[..COUNT].iter().sum::<Vec3>() / COUNT as Real;
    h.normal = if COUNT == 3 {
        let [p, q, r] = points;
        (q - p).cross(&(r - p)).try_normalize(0.0).unwrap_or_else(Vec3::zeros)
    } else {
        Vec3::zeros()
    };
    h.points = points;
    h.count = COUNT;
    h.radius = radius;
}

/// The hull of element `e` of `model` ([`write_hull`] into a new one).
#[inline]
pub fn hull(model: &Model, e: Element) -> Hull {
    let z = Vec3::zeros();
    let mut h = Hull { points: [z; 3], count: 1, radius: 0.0, centroid: z, normal: z };
    write_hull(model, e, &mut h);
    h
}

/// Whether `a` and `b` are proven apart by a slab normal to `axis` (any non-zero vector):
/// min over b of x·n − max over a of x·n > r_a + r_b, n = axis/|axis|.
pub fn separated_along(a: &Hull, b: &Hull, axis: &Vec3) -> bool {
    let len2 = axis.norm_squared();
    if !(len2 > 0.0) {
        return false;
    }
    let max_a = a.skeleton().iter().map(|x| x.dot(axis)).fold(Real::NEG_INFINITY, Real::max);
    let min_b = b.skeleton().iter().map(|x| x.dot(axis)).fold(Real::INFINITY, Real::min);
    let gap = min_b - max_a;
    let reach = a.radius + b.radius;
    gap > 0.0 && gap * gap > reach * reach * len2
}

/// Whether `a` and `b` are proven apart, by the axis joining their centroids, then (for
/// PFacets) by their face normals, on either side: with n the unit normal of a PFacet h and o
/// the other body, apart when min_o(x·n) − h₀·n > r_a + r_b or h₀·n − max_o(x·n) > r_a + r_b;
/// then, for two PFacets, by their in-plane edge normals u (pointing out of the PFacet):
/// min_o(x·u) − max_h(x·u) > (r_a + r_b)·|u|. The last separates the near misses of a flat
/// mesh whose nodes are thick next to its cells (triangles two cells apart, side by side in
/// one plane), which neither the centroid axis nor the face normals can.
pub fn proven_apart(a: &Hull, b: &Hull) -> bool {
    let axis = b.centroid - a.centroid;
    if separated_along(a, b, &axis) {
        return true;
    }
    let reach = a.radius + b.radius;
    for (h, other) in [(a, b), (b, a)] {
        if h.count == 3 && h.normal != Vec3::zeros() {
            let n = &h.normal;
            let plane = h.points[0].dot(n);
            let (lo, hi) = other
                .skeleton()
                .iter()
                .map(|x| x.dot(n))
                .fold((Real::INFINITY, Real::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)));
            if lo - plane > reach || plane - hi > reach {
                return true;
            }
        }
    }
    // two PFacets only: a sphere or a connection beside a PFacet is separated by the centroid
    // axis already, and the test would be paid by every sphere resting on a membrane
    a.count == 3 && b.count == 3 && (apart_beyond_an_edge(a, b) || apart_beyond_an_edge(b, a))
}

/// Whether `other` lies beyond one of PFacet `h`'s edges by more than the two radii, along
/// that edge's in-plane normal u = (x_{k+1} − x_k) × n (pointing out of the triangle, with
/// |u| = |x_{k+1} − x_k| since n is a unit normal to the edge): min_other(x·u) − x_k·u >
/// (r_h + r_other)·|u|, the edge's corners being h's farthest points along u. Computed only
/// for the pairs that reach it, and compared squared (no square root).
#[inline]
fn apart_beyond_an_edge(h: &Hull, other: &Hull) -> bool {
    if h.normal == Vec3::zeros() {
        return false;
    }
    let reach = h.radius + other.radius;
    (0..3).any(|k| {
        let edge = h.points[(k + 1) % 3] - h.points[k];
        let u = edge.cross(&h.normal);
        let from = h.points[k].dot(&u);
        let gap = other.skeleton().iter().map(|x| x.dot(&u)).fold(Real::INFINITY, Real::min) - from;
        gap > 0.0 && gap * gap > reach * reach * edge.norm_squared()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexdem_geom::closest_points_triangle_triangle;
    use proptest::prelude::*;

    fn tri(points: [Vec3; 3], radius: Real) -> Hull {
        Hull::new(points, 3, radius)
    }

    #[test]
    fn coplanar_neighbours_of_neighbours_are_apart() {
        let a = tri(
            [Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.04, 0.0, 0.0), Vec3::new(0.0, 0.04, 0.0)],
            0.002,
        );
        let b = tri(
            [Vec3::new(0.08, 0.0, 0.0), Vec3::new(0.12, 0.0, 0.0), Vec3::new(0.08, 0.04, 0.0)],
            0.002,
        );
        assert!(proven_apart(&a, &b));
        let touching = tri(
            [Vec3::new(0.043, 0.0, 0.0), Vec3::new(0.08, 0.0, 0.0), Vec3::new(0.043, 0.04, 0.0)],
            0.002,
        );
        assert!(!proven_apart(&a, &touching));
    }

    #[test]
    fn stacked_triangles_are_apart_along_the_normal() {
        let base = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
        let a = tri(base, 0.01);
        let b = tri(base.map(|p| p + Vec3::new(0.0, 0.0, 0.03)), 0.01);
        assert!(proven_apart(&a, &b));
        let c = tri(base.map(|p| p + Vec3::new(0.0, 0.0, 0.019)), 0.01);
        assert!(!proven_apart(&a, &c));
    }

    /// Two triangles of a flat mesh that share no node, side by side 9 mm apart with nodes of
    /// 3 mm: the centroid axis and the face normals cannot separate them, an edge normal does.
    #[test]
    fn side_by_side_triangles_are_apart_along_an_edge_normal() {
        let h = 0.0127;
        // YADE's membrane scaling mesh (N = 80): cells split along (i, j)–(i+1, j+1)
        let a =
            tri([Vec3::new(0.0, 0.0, 0.0), Vec3::new(h, 0.0, 0.0), Vec3::new(h, h, 0.0)], 0.003);
        let b = tri(
            [Vec3::new(0.0, h, 0.0), Vec3::new(h, 2.0 * h, 0.0), Vec3::new(0.0, 2.0 * h, 0.0)],
            0.003,
        );
        let cp = closest_points_triangle_triangle(
            &a.points[0],
            &a.points[1],
            &a.points[2],
            &b.points[0],
            &b.points[1],
            &b.points[2],
        );
        let distance = (cp.point_1 - cp.point_0).norm();
        assert!(distance > 0.006, "{distance}");
        let axis = b.centroid - a.centroid;
        assert!(!separated_along(&a, &b, &axis), "the centroid axis already separates them");
        assert!(proven_apart(&a, &b));
    }

    fn vec3() -> impl Strategy<Value = Vec3> {
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        /// Never "apart" when the exact distance is within the two radii.
        #[test]
        fn never_rejects_a_touching_pair(
            a in [vec3(), vec3(), vec3()],
            b in [vec3(), vec3(), vec3()],
            ra in 0.0..0.5f64,
            rb in 0.0..0.5f64,
        ) {
            let cp = closest_points_triangle_triangle(&a[0], &a[1], &a[2], &b[0], &b[1], &b[2]);
            let distance = (cp.point_1 - cp.point_0).norm();
            if distance <= ra + rb {
                prop_assert!(!proven_apart(&tri(a, ra), &tri(b, rb)));
            }
        }

        /// Segments and points against triangles, by their degenerate hulls.
        #[test]
        fn never_rejects_a_touching_segment(
            a in [vec3(), vec3()],
            b in [vec3(), vec3(), vec3()],
            ra in 0.0..0.5f64,
            rb in 0.0..0.5f64,
        ) {
            let s = Hull::new([a[0], a[1], a[1]], 2, ra);
            let cp = flexdem_geom::closest_points_segment_triangle(&a[0], &a[1], &b[0], &b[1], &b[2]);
            let distance = (cp.point_triangle - cp.point_segment).norm();
            if distance <= ra + rb {
                prop_assert!(!proven_apart(&s, &tri(b, rb)));
            }
        }
    }
}
