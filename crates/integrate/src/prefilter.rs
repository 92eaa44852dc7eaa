//! Cheap tests that prove two candidate elements do not touch, run before the exact
//! closest-point kernels (which cost up to a microsecond for triangle–triangle). Most pairs of
//! a Verlet list are near misses: neighbours of neighbours on a mesh, spheres a little apart.
//!
//! Every element is a convex hull of one to three points (sphere centre, connection ends,
//! PFacet corners) grown by a radius. Two such bodies are apart when, along some axis u ≠ 0,
//!
//! min_j (b_j · u) − max_i (a_i · u) > (r_a + r_b)·|u|,
//!
//! (a separating slab wider than the two radii). A sphere beside a PFacet, at contact height
//! over its plane (resting on a membrane next to the cells it touches), has no such slab; its
//! centre's distance to the triangle, beyond r_a + r_b by a slack far above the round-off,
//! separates them. The tests are conservative: they only ever answer "apart" when the exact
//! distance exceeds r_a + r_b.
//!
//! A hull is written for every collidable element at every step, so it holds only its
//! points, centroid, radius and count (112 bytes; 136 with the unit normal): a PFacet's face
//! normal (x₁ − x₀) × (x₂ − x₀), not normalised, is computed where a test needs it (any
//! non-zero axis is valid: each test scales the radii by its axis's length).

use flexdem_elements::touching::Element;
use flexdem_elements::Model;
use flexdem_geom::{closest_point_triangle, Real, Vec3};

/// An element in its current configuration (112 bytes): its skeleton points and radius.
#[derive(Clone, Copy, Debug)]
pub struct Hull {
    /// Skeleton points: the first `count` are the element's, the others repeat the last of
    /// them (so that a test may take all three, with no loop of unknown length).
    pub points: [Vec3; 3],
    /// Mean of the skeleton points.
    pub centroid: Vec3,
    /// Radius the skeleton is grown by.
    pub radius: Real,
    /// 1 (sphere), 2 (connection) or 3 (PFacet).
    pub count: u32,
}

impl Hull {
    /// The hull of the first `count` (1 to 3) of `points` grown by `radius`.
    #[inline]
    pub fn new(points: [Vec3; 3], count: usize, radius: Real) -> Hull {
        let mut h = Hull { points, centroid: points[0], radius, count: 1 };
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
/// unrolled). The points past `COUNT` are set to the last one: the extents along an axis can
/// then be taken over all three points, without a loop of unknown length, and are the same
/// (a copy's `x·u` is its original's).
#[inline(always)]
fn fill<const COUNT: usize>(h: &mut Hull, points: [Vec3; 3], radius: Real) {
    h.centroid = points[..COUNT].iter().sum::<Vec3>() / COUNT as Real;
    h.points = std::array::from_fn(|k| points[k.min(COUNT - 1)]);
    h.count = COUNT as u32;
    h.radius = radius;
}

/// The hull of element `e` of `model` ([`write_hull`] into a new one).
#[inline]
pub fn hull(model: &Model, e: Element) -> Hull {
    let z = Vec3::zeros();
    let mut h = Hull { points: [z; 3], centroid: z, radius: 0.0, count: 1 };
    write_hull(model, e, &mut h);
    h
}

/// (min, max) of x·axis over a hull's `points` (all three: those past its count repeat its
/// last, `fill`, and change neither).
#[inline]
fn extent(points: &[Vec3; 3], axis: &Vec3) -> (Real, Real) {
    points
        .iter()
        .map(|x| x.dot(axis))
        .fold((Real::INFINITY, Real::NEG_INFINITY), |(lo, hi), d| (lo.min(d), hi.max(d)))
}

/// Whether a gap along an axis of squared length `len2` exceeds `reach` times its length:
/// gap > 0 and gap² > reach²·len2 (no square root).
#[inline]
fn wider(gap: Real, reach: Real, len2: Real) -> bool {
    gap > 0.0 && gap * gap > reach * reach * len2
}

/// Whether `a` and `b` are proven apart by a slab normal to `axis` (any non-zero vector), `b`
/// on its positive side: min over b of x·u − max over a of x·u > (r_a + r_b)·|u|.
#[cfg(test)]
pub fn separated_along(a: &Hull, b: &Hull, axis: &Vec3) -> bool {
    separated_points(&a.points, &b.points, a.radius + b.radius, axis)
}

/// [`separated_along`] for two hulls' points `pa`, `pb` (all three of each, see [`extent`])
/// and the sum of the radii `reach`.
#[inline(always)]
fn separated_points(pa: &[Vec3; 3], pb: &[Vec3; 3], reach: Real, axis: &Vec3) -> bool {
    let len2 = axis.norm_squared();
    if !(len2 > 0.0) {
        return false;
    }
    let max_a = pa.iter().map(|x| x.dot(axis)).fold(Real::NEG_INFINITY, Real::max);
    let min_b = pb.iter().map(|x| x.dot(axis)).fold(Real::INFINITY, Real::min);
    wider(min_b - max_a, reach, len2)
}

/// Whether `a` and `b` are proven apart, by the axis joining their centroids, then (for
/// PFacets) by their face normals n, on either side: apart when one body's extent along n
/// ends more than (r_a + r_b)·|n| before the other's begins; then, for two PFacets, by their
/// in-plane edge normals u (pointing out of the PFacet): min_o(x·u) − max_h(x·u) >
/// (r_a + r_b)·|u|. The last separates the near misses of a flat mesh whose nodes are thick
/// next to its cells (triangles two cells apart, side by side in one plane), which neither
/// the centroid axis nor the face normals can.
pub fn proven_apart(a: &Hull, b: &Hull) -> bool {
    let (pa, pb) = (&a.points, &b.points);
    let reach = a.radius + b.radius;
    let axis = b.centroid - a.centroid;
    if separated_points(pa, pb, reach, &axis) {
        return true;
    }
    // a PFacet's normal (x₁ − x₀) × (x₂ − x₀) (zero for the other elements and a degenerate PFacet)
    let normal = |h: &Hull| {
        if h.count == 3 {
            let [p, q, r] = &h.points;
            (q - p).cross(&(r - p))
        } else {
            Vec3::zeros()
        }
    };
    let (na, nb) = (normal(a), normal(b));
    for (h, ph, n, po) in [(a, pa, &na, pb), (b, pb, &nb, pa)] {
        if h.count == 3 {
            // (the PFacet's own extent along its normal is its plane x₀·n)
            let plane = ph[0].dot(n);
            let (lo, hi) = extent(po, n);
            let len2 = n.norm_squared();
            if wider(lo - plane, reach, len2) || wider(plane - hi, reach, len2) {
                return true;
            }
        }
    }
    match (a.count, b.count) {
        (3, 3) => {
            apart_beyond_an_edge(pa, &na, pb, reach) || apart_beyond_an_edge(pb, &nb, pa, reach)
        }
        // a sphere resting on a membrane is at contact distance from the plane of each
        // PFacet around those it touches, and no slab of the tests above separates it from
        // them (18 400 such pairs a step of the membrane of 10⁵ PFacets reached the exact
        // kernel and did not touch): its centre's distance to the triangle does
        (1, 3) => point_beyond_triangle(&pa[0], pb, reach),
        (3, 1) => point_beyond_triangle(&pb[0], pa, reach),
        // a connection beside a PFacet is separated by the centroid axis already
        _ => false,
    }
}

/// The least height of a triangle, over its longest edge, for [`point_beyond_triangle`] to
/// answer (below it the closest point's weights lose their accuracy: the exact kernel
/// decides).
const WELL_SHAPED: Real = 1e-4;

/// The slack [`point_beyond_triangle`] asks beyond `reach`, relative to the sizes at play (the
/// reach, the longest edge, the coordinates): far above the round-off of the distance here and
/// in the exact kernel (`flexdem_geom::project_point_triangle`), about 10⁻⁸ of the edge on a
/// triangle of [`WELL_SHAPED`] height, so that it never calls apart a pair the kernel finds
/// touching; far below the gaps of near misses (the sphere beside a PFacet it does not touch:
/// millimetres).
const POINT_SLACK: Real = 1e-6;

/// Whether the point `p` is farther than `reach` from the triangle `t`: the distance to its
/// closest point (`flexdem_geom::closest_point_triangle`, Ericson's six dot products, less
/// than half the kernel's projection's cost), above `reach + s` with the slack
/// s = 10⁻⁶ (reach + l_max) + 10⁻¹² |x|_∞ ([`POINT_SLACK`]). No answer (false) for a triangle
/// whose height is below 10⁻⁴ of its longest edge ([`WELL_SHAPED`]), or for a NaN.
#[inline]
fn point_beyond_triangle(p: &Vec3, t: &[Vec3; 3], reach: Real) -> bool {
    let [a, b, c] = t;
    let (ab, ac, bc) = (b - a, c - a, c - b);
    let l2 = ab.norm_squared().max(ac.norm_squared()).max(bc.norm_squared());
    let n2 = ab.cross(&ac).norm_squared();
    // (n² > (ε·l²)² says height / l_max > ε, up to a factor 2; false for a NaN)
    if !(n2 > (WELL_SHAPED * l2) * (WELL_SHAPED * l2)) {
        return false;
    }
    let closest = closest_point_triangle(p, a, b, c);
    let far = p.amax().max(a.amax()).max(b.amax()).max(c.amax());
    let beyond = reach + POINT_SLACK * (reach + l2.sqrt()) + 1e-12 * far;
    (p - closest).norm_squared() > beyond * beyond
}

/// Whether PFacet `other` lies beyond one of PFacet `h`'s edges (`h` its corners, `n` its
/// normal) by more than `reach`, along that edge's in-plane normal u = (x_{k+1} − x_k) × n
/// (pointing out of the triangle): min_other(x·u) − max_h(x·u) > reach·|u|. Computed only
/// for the pairs that reach it, and compared squared (no square root).
#[inline]
fn apart_beyond_an_edge(h: &[Vec3; 3], n: &Vec3, other: &[Vec3; 3], reach: Real) -> bool {
    if *n == Vec3::zeros() {
        return false;
    }
    (0..3).any(|k| {
        let u = (h[(k + 1) % 3] - h[k]).cross(n);
        // the edge's corners are h's farthest points along u
        let from = h[k].dot(&u);
        let (to, _) = extent(other, &u);
        wider(to - from, reach, u.norm_squared())
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

    /// A point's or a segment's hull repeats its last point, whatever it was given: the
    /// extents over all three points are those over its own.
    #[test]
    fn points_past_the_count_repeat_the_last() {
        let (p, q, far) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(-1.0, 0.5, 2.0), Vec3::repeat(9.0));
        let segment = Hull::new([p, q, far], 2, 0.1);
        assert_eq!(segment.points, [p, q, q]);
        assert_eq!(Hull::new([p, far, far], 1, 0.1).points, [p, p, p]);
        let axis = Vec3::new(0.3, -0.2, 0.9);
        let (d0, d1) = (p.dot(&axis), q.dot(&axis));
        assert_eq!(extent(&segment.points, &axis), (d0.min(d1), d0.max(d1)));
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
        let [p, q] = [a, b].map(|h| h.points);
        let cp = closest_points_triangle_triangle(&p[0], &p[1], &p[2], &q[0], &q[1], &q[2]);
        let distance = (cp.point_1 - cp.point_0).norm();
        assert!(distance > 0.006, "{distance}");
        let axis = b.centroid - a.centroid;
        assert!(!separated_along(&a, &b, &axis), "the centroid axis already separates them");
        assert!(proven_apart(&a, &b));
    }

    /// A sphere beside a PFacet it does not touch, at contact height over the PFacet's plane
    /// (a sphere resting on a flat membrane, 5 mm beyond the cell under it): no slab of the
    /// centroid axis or the face normal separates them, the centre's distance to the triangle
    /// (0.4 mm beyond the reach) does. A sphere over the cell, touching it, is not apart.
    #[test]
    fn a_sphere_resting_beside_a_pfacet_is_apart() {
        let (h, r_node, r_sphere) = (0.0125, 0.002, 0.03);
        let cell =
            tri([Vec3::new(0.0, 0.0, 0.0), Vec3::new(h, 0.0, 0.0), Vec3::new(h, h, 0.0)], r_node);
        let beside = Hull::new([Vec3::new(h + 0.005, 0.5 * h, r_node + r_sphere); 3], 1, r_sphere);
        let axis = cell.centroid - beside.centroid;
        assert!(!separated_along(&beside, &cell, &axis), "the centroid axis separates them");
        assert!(!separated_along(&cell, &beside, &Vec3::z()), "the face normal separates them");
        assert!(proven_apart(&beside, &cell) && proven_apart(&cell, &beside));
        // (1 µm into it: at exactly the reach, the slabs' round-off decides)
        let into = r_node + r_sphere - 1e-6;
        let over = Hull::new([Vec3::new(0.7 * h, 0.3 * h, into); 3], 1, r_sphere);
        assert!(!proven_apart(&over, &cell) && !proven_apart(&cell, &over));
    }

    /// A point's distance to a triangle of any shape, with `reach` from 0.99 to 1.01 of it
    /// (the kernel's `project_point_triangle`): never apart within the reach; apart beyond it
    /// by more than the slack when the triangle is well shaped.
    fn check_point_triangle(p: Vec3, t: [Vec3; 3], scale: Real) -> Result<(), TestCaseError> {
        let exact = flexdem_geom::project_point_triangle(&p, &t[0], &t[1], &t[2]);
        let distance = (exact.point - p).norm();
        for f in [0.99, 0.999_999, 1.0, 1.000_001, 1.01] {
            let reach = distance * f;
            let apart = point_beyond_triangle(&p, &t, reach);
            prop_assert!(!(apart && distance <= reach), "{p:?} {t:?} {reach}");
        }
        // effective: well shaped, 1 % beyond the reach (10⁴ times the slack), apart
        let (ab, ac) = (t[1] - t[0], t[2] - t[0]);
        let l2 = ab.norm_squared().max(ac.norm_squared()).max((t[2] - t[1]).norm_squared());
        let shaped = ab.cross(&ac).norm_squared() > 1e-4 * l2 * l2;
        if shaped && distance > 1e-3 * scale {
            prop_assert!(point_beyond_triangle(&p, &t, distance / 1.01));
        }
        Ok(())
    }

    fn vec3() -> impl Strategy<Value = Vec3> {
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    /// The layout's size (what the contact stage writes per element and step), and a hull
    /// with a coordinate that is not a number is never apart.
    #[test]
    fn a_hull_is_112_bytes_and_nan_is_never_apart() {
        assert_eq!(std::mem::size_of::<Hull>(), 112);
        let origin = Hull::new([Vec3::zeros(); 3], 1, 0.1);
        let base = [Vec3::new(5.0, 0.0, 0.0), Vec3::new(6.0, 0.0, 0.0), Vec3::new(5.0, 1.0, 0.0)];
        assert!(proven_apart(&origin, &tri(base, 0.1)));
        for k in 0..3 {
            let mut p = base;
            p[k].y = Real::NAN;
            assert!(!proven_apart(&origin, &tri(p, 0.1)) && !proven_apart(&tri(p, 0.1), &origin));
        }
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

        /// The point–triangle test never calls apart a point within its reach of the
        /// triangle (the kernel's distance), for triangles of any shape, thin ones too, at
        /// any scale and far from the origin, and the point in any of the seven regions.
        #[test]
        fn a_point_within_its_reach_of_a_triangle_is_never_apart(
            t in [vec3(), vec3(), vec3()],
            thin in 0usize..3,
            p in vec3(),
            k in -12i32..6,
            offset in vec3(),
        ) {
            let scale = (10.0 as Real).powi(k);
            // thin: the third corner pulled towards the first edge's line
            let mut t = t;
            if thin > 0 {
                let squash = (10.0 as Real).powi(-4 * thin as i32);
                t[2] = t[0] + (t[1] - t[0]) * 0.3 + (t[2] - t[0]) * squash;
            }
            let offset = offset * 1e3 * scale;
            let t = t.map(|x| x * scale + offset);
            check_point_triangle(p * scale + offset, t, scale)?;
            // the point over the triangle's face and over its first edge, near the plane
            let (face, edge) = (t[0] * 0.2 + t[1] * 0.3 + t[2] * 0.5, (t[0] + t[1]) * 0.5);
            let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
            let up = if n.norm() > 0.0 { n / n.norm() } else { Vec3::z() };
            for (base, h) in [(face, 1e-3), (edge, 1e-3), (face, 0.0), (t[2], 0.5)] {
                check_point_triangle(base + up * (h * scale), t, scale)?;
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
