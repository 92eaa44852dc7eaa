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

    /// The hull of the first `count` of `points` grown by `radius`.
    pub fn new(points: [Vec3; 3], count: usize, radius: Real) -> Hull {
        let centroid = points[..count].iter().sum::<Vec3>() / count as Real;
        let normal = if count == 3 {
            let [p, q, r] = points;
            (q - p).cross(&(r - p)).try_normalize(0.0).unwrap_or_else(Vec3::zeros)
        } else {
            Vec3::zeros()
        };
        Hull { points, count, radius, centroid, normal }
    }
}

/// The hull of element `e` of `model`.
pub fn hull(model: &Model, e: Element) -> Hull {
    let p = &model.particles.pos;
    match e {
        Element::Particle(i) => {
            Hull::new([p[i as usize]; 3], 1, model.particles.radius[i as usize])
        }
        Element::Connection(k) => {
            let c = &model.connections[k as usize];
            let (a, b) = (p[c.nodes[0] as usize], p[c.nodes[1] as usize]);
            Hull::new([a, b, b], 2, c.radius)
        }
        Element::PFacet(k) => {
            let f = &model.pfacets[k as usize];
            Hull::new(f.nodes.map(|n| p[n as usize]), 3, f.radius)
        }
    }
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
/// the other body, apart when min_o(x·n) − h₀·n > r_a + r_b or h₀·n − max_o(x·n) > r_a + r_b.
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
    false
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
