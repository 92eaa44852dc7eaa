//! Closest points of two triangles (PFacet–PFacet contacts).

use crate::point_triangle::{triangle_location_on_edge, TriangleFrame};
use crate::{
    closest_points_segment_triangle, project_point_triangle, Real, TriangleLocation, Vec3,
    PARALLEL_EPSILON,
};

/// The closest points of two triangles `(a0, b0, c0)` and `(a1, b1, c1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TriangleTriangleClosestPoints {
    /// The closest point of the first triangle, `Σ weights_0[i] v_i`.
    pub point_0: Vec3,
    /// Barycentric weights of `point_0` on the first triangle: all `>= 0`, sum 1.
    pub weights_0: [Real; 3],
    /// The feature of the first triangle `point_0` lies on.
    pub location_0: TriangleLocation,
    /// The closest point of the second triangle.
    pub point_1: Vec3,
    /// Barycentric weights of `point_1` on the second triangle.
    pub weights_1: [Real; 3],
    /// The feature of the second triangle `point_1` lies on.
    pub location_1: TriangleLocation,
    /// `|point_0 - point_1|²`.
    pub distance_squared: Real,
}

impl TriangleTriangleClosestPoints {
    /// `|point_0 - point_1|`.
    pub fn distance(&self) -> Real {
        self.distance_squared.sqrt()
    }

    /// The same answer with the two triangles' roles exchanged.
    fn swapped(self) -> Self {
        Self {
            point_0: self.point_1,
            weights_0: self.weights_1,
            location_0: self.location_1,
            point_1: self.point_0,
            weights_1: self.weights_0,
            location_1: self.location_0,
            distance_squared: self.distance_squared,
        }
    }

    /// The answer made of the closest points of each triangle to the point `x`.
    fn projections_of(x: &Vec3, t0: &[Vec3; 3], t1: &[Vec3; 3]) -> Self {
        let p0 = project_point_triangle(x, &t0[0], &t0[1], &t0[2]);
        let p1 = project_point_triangle(x, &t1[0], &t1[1], &t1[2]);
        Self {
            point_0: p0.point,
            weights_0: p0.weights,
            location_0: p0.location,
            point_1: p1.point,
            weights_1: p1.weights,
            location_1: p1.location,
            distance_squared: (p0.point - p1.point).norm_squared(),
        }
    }
}

type Point2 = [Real; 2];

/// `(q - p) × (x - p)` in 2-D: positive when `x` is left of the line `p → q`.
fn cross2(p: &Point2, q: &Point2, x: &Point2) -> Real {
    (q[0] - p[0]) * (x[1] - p[1]) - (q[1] - p[1]) * (x[0] - p[0])
}

/// Sutherland–Hodgman: clips the convex polygon `poly[..n]` by the half-plane left of `p → q`.
/// A triangle clipped by a triangle has at most 6 vertices; the buffer holds 9.
fn clip_by_half_plane(
    poly: &[Point2; 9],
    n: usize,
    p: &Point2,
    q: &Point2,
) -> ([Point2; 9], usize) {
    let mut out = [[0.0; 2]; 9];
    let mut m = 0;
    for i in 0..n {
        let (x, y) = (&poly[i], &poly[(i + 1) % n]);
        let (dx, dy) = (cross2(p, q, x), cross2(p, q, y));
        if dx >= 0.0 && m < 9 {
            out[m] = *x;
            m += 1;
        }
        if ((dx >= 0.0) != (dy >= 0.0)) && m < 9 {
            let t = dx / (dx - dy);
            out[m] = [x[0] + t * (y[0] - x[0]), x[1] + t * (y[1] - x[1])];
            m += 1;
        }
    }
    (out, m)
}

/// Centroid of the overlap of triangle `t0` (with frame `f0`) and the orthogonal projection of
/// `t1` onto its plane, as a point of that plane, or `None` when the overlap's area is below
/// `1e-12` times the squared longest edge `l2`.
///
/// The projection of `t1` is clipped by the three edges of `t0` (Sutherland–Hodgman) in the
/// plane frame `e1 = ab / |ab|`, `e2 = n × e1`, where `t0` is counter-clockwise; the centroid is
/// the area-weighted mean of the fan triangles' centroids.
fn overlap_centroid(f0: &TriangleFrame, t1: &[Vec3; 3], l2: Real) -> Option<Vec3> {
    let e1 = f0.ab.normalize();
    let e2 = f0.normal.cross(&e1);
    let to2 = |v: &Vec3| -> Point2 {
        let r = v - f0.a;
        [r.dot(&e1), r.dot(&e2)]
    };
    let t0 = [[0.0, 0.0], to2(&(f0.a + f0.ab)), to2(&(f0.a + f0.ac))];
    let mut poly = [[0.0; 2]; 9];
    for (k, v) in t1.iter().enumerate() {
        poly[k] = to2(v);
    }
    // Make the clipped polygon counter-clockwise too (its orientation does not matter for
    // clipping, but the signed area below assumes it).
    if cross2(&poly[0], &poly[1], &poly[2]) < 0.0 {
        poly.swap(1, 2);
    }
    let mut n = 3;
    for e in 0..3 {
        (poly, n) = clip_by_half_plane(&poly, n, &t0[e], &t0[(e + 1) % 3]);
        if n < 3 {
            return None;
        }
    }
    let (mut area2, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for i in 1..n - 1 {
        let a = cross2(&poly[0], &poly[i], &poly[i + 1]);
        area2 += a;
        cx += a * (poly[0][0] + poly[i][0] + poly[i + 1][0]);
        cy += a * (poly[0][1] + poly[i][1] + poly[i + 1][1]);
    }
    if area2.is_nan() || 0.5 * area2 <= 1e-12 * l2 {
        return None;
    }
    let (cx, cy) = (cx / (3.0 * area2), cy / (3.0 * area2));
    Some(f0.a + e1 * cx + e2 * cy)
}

/// Closest points of the triangles `T0 = (a0, b0, c0)` and `T1 = (a1, b1, c1)`:
/// `min |Σ w0_i T0_i - Σ w1_i T1_i|²` over weights `>= 0` summing to 1.
///
/// The PFacet–PFacet pair. Computed in coordinates relative to `a0` (translation invariance):
/// - **coplanar-parallel, overlapping**: when the normals are parallel
///   (`|n̂0 × n̂1| <= ε`, ε = [`PARALLEL_EPSILON`]) and the projection of `T1` onto the plane of
///   `T0` overlaps `T0` with positive area, every point of the overlap is closest (at the
///   planes' distance); the centroid of the overlap polygon (Sutherland–Hodgman clipping) is
///   projected onto each triangle, so a membrane resting on another gets a stable, centred
///   contact;
/// - **otherwise** the minimum has a point on an edge of one triangle (two face-interior points
///   are closest only for parallel planes or at an intersection, which an edge reaches too):
///   each of the six edges against the other triangle ([`closest_points_segment_triangle`]:
///   vertex–face, edge–edge, an edge piercing the face, and an edge parallel over the face with
///   the middle of its stretch). The smallest wins;
/// - **intersecting** (distance below `1e-12` times the longest edge, planes not parallel):
///   the zero-distance candidates are the ends of the intersection segment (where edges pierce
///   the other triangle); the middle of the extreme ones along `n0 × n1` is returned, projected
///   onto each triangle.
///
/// Degenerate triangles need no special case: their edges are segments, and
/// [`closest_points_segment_triangle`] handles a degenerate triangle by its edges. Never NaN for
/// finite inputs.
pub fn closest_points_triangle_triangle(
    a0: &Vec3,
    b0: &Vec3,
    c0: &Vec3,
    a1: &Vec3,
    b1: &Vec3,
    c1: &Vec3,
) -> TriangleTriangleClosestPoints {
    let origin = *a0;
    let t0 = [Vec3::zeros(), b0 - origin, c0 - origin];
    let t1 = [a1 - origin, b1 - origin, c1 - origin];
    let mut result = closest_points_local(&t0, &t1);
    result.point_0 += origin;
    result.point_1 += origin;
    result
}

/// [`closest_points_triangle_triangle`] in coordinates where the inputs are small.
fn closest_points_local(t0: &[Vec3; 3], t1: &[Vec3; 3]) -> TriangleTriangleClosestPoints {
    let longest =
        |t: &[Vec3; 3]| (0..3).map(|e| (t[(e + 1) % 3] - t[e]).norm_squared()).fold(0.0, Real::max);
    let l2 = longest(t0).max(longest(t1));
    let frames =
        (TriangleFrame::new(&t0[0], &t0[1], &t0[2]), TriangleFrame::new(&t1[0], &t1[1], &t1[2]));
    let mut line_direction = None;
    if let (Some(f0), Some(f1)) = frames {
        let cross = f0.normal.cross(&f1.normal);
        if cross.norm_squared() <= PARALLEL_EPSILON * PARALLEL_EPSILON {
            if let Some(centroid) = overlap_centroid(&f0, t1, l2) {
                return TriangleTriangleClosestPoints::projections_of(&centroid, t0, t1);
            }
        } else {
            line_direction = Some(cross);
        }
    }

    let mut candidates = [None; 6];
    for edge in 0..3 {
        let (i, j) = TriangleLocation::edge_vertices(edge);
        for (k, (from, to)) in [(t0, t1), (t1, t0)].into_iter().enumerate() {
            let r = closest_points_segment_triangle(&from[i], &from[j], &to[0], &to[1], &to[2]);
            let (location, weights) = triangle_location_on_edge(edge, r.location_segment);
            let c = TriangleTriangleClosestPoints {
                point_0: r.point_segment,
                weights_0: weights,
                location_0: location,
                point_1: r.point_triangle,
                weights_1: r.weights,
                location_1: r.location_triangle,
                distance_squared: r.distance_squared,
            };
            candidates[2 * edge + k] = Some(if k == 0 { c } else { c.swapped() });
        }
    }
    let mut best = candidates[0]
        .unwrap_or_else(|| TriangleTriangleClosestPoints::projections_of(&t0[0], t0, t1));
    for c in candidates.iter().flatten() {
        if c.distance_squared < best.distance_squared {
            best = *c;
        }
    }

    let zero = 1e-24 * l2;
    if let (Some(u), true) = (line_direction, best.distance_squared <= zero) {
        // Ends of the intersection segment along the intersection line `u`.
        let mut ends: Option<(Real, Vec3, Real, Vec3)> = None;
        for c in candidates.iter().flatten().filter(|c| c.distance_squared <= zero) {
            let x = (c.point_0 + c.point_1) * 0.5;
            let s = x.dot(&u);
            ends = Some(match ends {
                None => (s, x, s, x),
                Some((lo, xl, hi, xh)) => {
                    let (lo, xl) = if s < lo { (s, x) } else { (lo, xl) };
                    let (hi, xh) = if s > hi { (s, x) } else { (hi, xh) };
                    (lo, xl, hi, xh)
                }
            });
        }
        if let Some((_, xl, _, xh)) = ends {
            if (xh - xl).norm_squared() > zero {
                return TriangleTriangleClosestPoints::projections_of(&((xl + xh) * 0.5), t0, t1);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::point_triangle::test_support::*;
    use crate::proptest_support::{rotation, scale, triangle, unit_vec3, vec3};
    use proptest::prelude::*;

    type Pair = ([Vec3; 3], [Vec3; 3]);

    fn run(t0: &[Vec3; 3], t1: &[Vec3; 3]) -> TriangleTriangleClosestPoints {
        closest_points_triangle_triangle(&t0[0], &t0[1], &t0[2], &t1[0], &t1[1], &t1[2])
    }

    fn oracle_distance(t0: &[Vec3; 3], t1: &[Vec3; 3]) -> Real {
        let f = |z: &[Real; 4]| {
            (triangle_point(t0, z[0], z[1]) - triangle_point(t1, z[2], z[3])).norm_squared()
        };
        oracle_min::<4>(6, f).sqrt().min(oracle_feature_pairs(t0, t1))
    }

    fn check(
        t0: &[Vec3; 3],
        t1: &[Vec3; 3],
    ) -> Result<TriangleTriangleClosestPoints, TestCaseError> {
        let r = run(t0, t1);
        check_on_triangle(t0, &r.point_0, &r.weights_0, r.location_0, 1e-12)
            .map_err(TestCaseError::fail)?;
        check_on_triangle(t1, &r.point_1, &r.weights_1, r.location_1, 1e-12)
            .map_err(TestCaseError::fail)?;
        let size = (0..3).map(|i| (t0[i] - t0[0]).norm() + (t1[i] - t0[0]).norm()).sum::<Real>();
        prop_assert!(
            ((r.point_0 - r.point_1).norm_squared() - r.distance_squared).abs()
                <= 1e-14 * size * size
        );
        let (d, oracle) = (r.distance(), oracle_distance(t0, t1));
        prop_assert!(d <= oracle + 1e-12 * size, "d {} > oracle {}", d, oracle);
        prop_assert!(d >= oracle - 1e-9 * size, "d {} < oracle {}", d, oracle);
        Ok(r)
    }

    fn right_triangle(k: Real) -> [Vec3; 3] {
        [Vec3::zeros(), Vec3::x() * k, Vec3::y() * k]
    }

    fn shifted(t: &[Vec3; 3], v: Vec3) -> [Vec3; 3] {
        [t[0] + v, t[1] + v, t[2] + v]
    }

    #[test]
    fn coplanar_overlapping_triangles_give_overlap_centroid() {
        // Overlap of x, y >= 0.5, x + y <= 2: the triangle (0.5, 0.5), (1.5, 0.5), (0.5, 1.5).
        let t0 = right_triangle(2.0);
        for h in [0.0, 0.3] {
            let t1 = shifted(&t0, Vec3::new(0.5, 0.5, h));
            let r = run(&t0, &t1);
            let c = Vec3::new(5.0 / 6.0, 5.0 / 6.0, 0.0);
            assert!((r.point_0 - c).norm() < 1e-14, "{:?}", r.point_0);
            assert!((r.point_1 - c - Vec3::z() * h).norm() < 1e-14, "{:?}", r.point_1);
            assert!((r.distance() - h).abs() < 1e-15);
            assert_eq!(
                (r.location_0, r.location_1),
                (TriangleLocation::OnFace, TriangleLocation::OnFace)
            );
        }
    }

    #[test]
    fn stacked_parallel_triangles_are_centred() {
        let t0 = [Vec3::new(0.1, 0.2, 0.3), Vec3::new(1.3, 0.1, 0.5), Vec3::new(0.4, 1.1, -0.2)];
        let n = (t0[1] - t0[0]).cross(&(t0[2] - t0[0])).normalize();
        let h = 0.01;
        let t1 = shifted(&t0, n * h);
        let r = run(&t0, &t1);
        let centroid = (t0[0] + t0[1] + t0[2]) / 3.0;
        assert!((r.distance() - h).abs() < 1e-15);
        assert!(
            (r.point_0 - centroid).norm() < 1e-14 && (r.point_1 - centroid - n * h).norm() < 1e-14
        );
        for w in r.weights_0.iter().chain(&r.weights_1) {
            assert!((w - 1.0 / 3.0).abs() < 1e-14);
        }
    }

    #[test]
    fn intersecting_triangles_give_middle_of_intersection() {
        // T1 lies in x = 0.5 and cuts z = 0 along y in [-1, 1]; T0 holds y in [0, 1.5] there.
        let t0 = right_triangle(2.0);
        let t1 = [Vec3::new(0.5, -1.0, -1.0), Vec3::new(0.5, -1.0, 1.0), Vec3::new(0.5, 3.0, -1.0)];
        let r = run(&t0, &t1);
        assert!(r.distance_squared < 1e-30);
        assert!((r.point_0 - Vec3::new(0.5, 0.5, 0.0)).norm() < 1e-14, "{:?}", r.point_0);
        let rs = run(&t1, &t0);
        assert!((rs.point_1 - r.point_0).norm() < 1e-14);
    }

    #[test]
    fn edge_resting_on_face_gets_middle_of_stretch() {
        // A tilted triangle whose edge y = 0.5 lies 0.1 above the face, over x in [0.2, 0.8].
        let t0 = right_triangle(2.0);
        let t1 = [Vec3::new(0.2, 0.5, 0.1), Vec3::new(0.8, 0.5, 0.1), Vec3::new(0.5, 0.9, 1.0)];
        let r = run(&t0, &t1);
        assert!((r.distance() - 0.1).abs() < 1e-15);
        assert!((r.point_0 - Vec3::new(0.5, 0.5, 0.0)).norm() < 1e-14);
        assert_eq!(r.location_1, TriangleLocation::OnEdge { edge: 0, t: 0.5 });
    }

    /// Pairs of triangles: general, parallel (stacked or coplanar, rotated in the plane),
    /// intersecting (the second rotated about a point of the first).
    fn pair() -> impl Strategy<Value = Pair> {
        let arr = |(a, b, c): (Vec3, Vec3, Vec3)| [a, b, c];
        let general = (triangle(1.0), triangle(1.0)).prop_map(move |(x, y)| (arr(x), arr(y)));
        let parallel = (triangle(1.0), 0.0..6.3_f64, vec3(0.5), -0.5..0.5_f64, 0.3..1.5_f64)
            .prop_map(move |(x, angle, shift, h, k)| {
                let t0 = arr(x);
                let n = (t0[1] - t0[0]).cross(&(t0[2] - t0[0])).normalize();
                let rot = nalgebra::Rotation3::new(n * angle);
                let shift = shift - n * n.dot(&shift) + n * h;
                let t1 =
                    [rot * t0[0] * k + shift, rot * t0[1] * k + shift, rot * t0[2] * k + shift];
                (t0, t1)
            });
        let crossing = (triangle(1.0), triangle(1.0), 0.0..1.0_f64, 0.0..1.0_f64).prop_map(
            move |(x, y, u, v)| {
                let (t0, t1) = (arr(x), arr(y));
                let q = triangle_point(&t0, u, v) - (t1[0] + t1[1] + t1[2]) / 3.0;
                (t0, shifted(&t1, q))
            },
        );
        prop_oneof![2 => general, 2 => parallel, 2 => crossing]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn matches_oracle_and_is_consistent((t0, t1) in pair()) {
            check(&t0, &t1)?;
        }

        #[test]
        fn degenerate_triangles_match_oracle((t0, _) in pair(), a in vec3(1.0), b in vec3(1.0),
                                             u in -1.0..2.0_f64, kind in 0..4usize, swap in any::<bool>()) {
            let t = match kind {
                0 => [a, b, a + (b - a) * u],
                1 => [a, a, b],
                2 => [a, a, a],
                _ => [a, b, a + (b - a) * u + (b - a).cross(&Vec3::z()) * 1e-9],
            };
            if swap { check(&t, &t0)?; } else { check(&t0, &t)?; }
        }

        #[test]
        fn swapping_the_triangles_swaps_the_answer((t0, t1) in pair()) {
            let (r, q) = (run(&t0, &t1), run(&t1, &t0));
            prop_assert!((r.distance() - q.distance()).abs() <= 1e-12);
            check_on_triangle(&t0, &q.point_1, &q.weights_1, q.location_1, 1e-12).map_err(TestCaseError::fail)?;
            check_on_triangle(&t1, &q.point_0, &q.weights_0, q.location_0, 1e-12).map_err(TestCaseError::fail)?;
        }

        /// In general position the closest pair is unique: swapping gives the same points.
        #[test]
        fn swapping_general_triangles_gives_the_same_points(x in triangle(1.0), y in triangle(1.0)) {
            let (t0, t1) = ([x.0, x.1, x.2], [y.0, y.1, y.2]);
            let (r, q) = (run(&t0, &t1), run(&t1, &t0));
            prop_assume!(r.distance() > 1e-6);
            prop_assert!((r.point_0 - q.point_1).norm() <= 1e-9 && (r.point_1 - q.point_0).norm() <= 1e-9, "{:?} vs {:?}", r, q);
            prop_assert!(same_location(r.location_0, q.location_1, 1e-9) && same_location(r.location_1, q.location_0, 1e-9));
        }

        #[test]
        fn rigid_motion_and_scale_invariance((t0, t1) in pair(), shift in vec3(1e3), rot in rotation(), k in scale()) {
            let m = |t: &[Vec3; 3]| [(rot * t[0] + shift) * k, (rot * t[1] + shift) * k, (rot * t[2] + shift) * k];
            let (r, q) = (run(&t0, &t1), run(&m(&t0), &m(&t1)));
            prop_assert!((q.distance() - r.distance() * k).abs() <= 1e-9 * k, "{} {}", q.distance(), r.distance() * k);
        }

        #[test]
        fn distance_is_lipschitz((t0, t1) in pair(), dir in unit_vec3(), which in 0..6usize) {
            let eps = 1e-3;
            let (mut s0, mut s1) = (t0, t1);
            if which < 3 { s0[which] += dir * eps } else { s1[which - 3] += dir * eps }
            prop_assert!((run(&s0, &s1).distance() - run(&t0, &t1).distance()).abs() <= eps * (1.0 + 1e-9));
        }
    }
}
