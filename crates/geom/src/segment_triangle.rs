//! Closest points of a segment and a triangle (connection–PFacet contacts).

use crate::point_segment::segment_location;
use crate::point_triangle::{triangle_location_on_edge, vertices, TriangleFrame};
use crate::{
    closest_points_segment_segment, project_point_triangle, Real, SegmentLocation,
    TriangleLocation, Vec3, PARALLEL_EPSILON,
};

/// The closest points of a segment `[p0, p1]` and a triangle `(a, b, c)`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SegmentTriangleClosestPoints {
    /// Parameter on the segment in `[0, 1]`: `point_segment = p0 + s (p1 - p0)`.
    pub s: Real,
    /// The closest point of the segment.
    pub point_segment: Vec3,
    /// Where `point_segment` lies on the segment (an end exactly when `s` is 0 or 1).
    pub location_segment: SegmentLocation,
    /// The closest point of the triangle, `wa a + wb b + wc c`.
    pub point_triangle: Vec3,
    /// Barycentric weights `[wa, wb, wc]` of `point_triangle`: all `>= 0`, sum 1.
    pub weights: [Real; 3],
    /// The feature `point_triangle` lies on (`OnFace` only when all weights are `> 0`).
    pub location_triangle: TriangleLocation,
    /// `|point_segment - point_triangle|²`.
    pub distance_squared: Real,
}

impl SegmentTriangleClosestPoints {
    /// `|point_segment - point_triangle|`.
    pub fn distance(&self) -> Real {
        self.distance_squared.sqrt()
    }
}

/// The part `[s_lo, s_hi]` of `[0, 1]` where the affine weights `w0 + s (w1 - w0)` are all
/// `>= 0`, or `None` when it is empty.
fn stretch_inside(w0: &[Real; 3], w1: &[Real; 3]) -> Option<(Real, Real)> {
    let (mut lo, mut hi): (Real, Real) = (0.0, 1.0);
    for (&g0, &g1) in w0.iter().zip(w1) {
        if g0 < 0.0 && g1 < 0.0 {
            return None;
        } else if g0 < 0.0 {
            lo = lo.max(g0 / (g0 - g1));
        } else if g1 < 0.0 {
            hi = hi.min(g0 / (g0 - g1));
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// `w0 + s (w1 - w0)`, with the sum kept at 1.
fn lerp_weights(w0: &[Real; 3], w1: &[Real; 3], s: Real) -> [Real; 3] {
    let wb = w0[1] + s * (w1[1] - w0[1]);
    let wc = w0[2] + s * (w1[2] - w0[2]);
    [1.0 - wb - wc, wb, wc]
}

/// The answer at segment parameter `s` and a point strictly inside the face with weights `w`.
fn on_face(
    p0: &Vec3,
    p1: &Vec3,
    frame: &TriangleFrame,
    s: Real,
    w: [Real; 3],
) -> SegmentTriangleClosestPoints {
    let point_segment = point_on_segment(p0, p1, s);
    let point_triangle = frame.point(&w);
    SegmentTriangleClosestPoints {
        s,
        point_segment,
        location_segment: segment_location(s),
        point_triangle,
        weights: w,
        location_triangle: TriangleLocation::OnFace,
        distance_squared: (point_segment - point_triangle).norm_squared(),
    }
}

/// `p0 + s (p1 - p0)`, exactly `p0` and `p1` at the ends.
fn point_on_segment(p0: &Vec3, p1: &Vec3, s: Real) -> Vec3 {
    if s <= 0.0 {
        *p0
    } else if s >= 1.0 {
        *p1
    } else {
        p0 + (p1 - p0) * s
    }
}

/// Closest points of the segment `[p0, p1]` and the triangle `(a, b, c)`:
/// `min over s in [0, 1] and (wa, wb, wc) >= 0, sum 1, of |p0 + s (p1 - p0) - (wa a + wb b + wc c)|²`.
///
/// The connection–PFacet pair. Unlike YADE (which splits it into node–face and edge–edge
/// contacts and misses a cylinder crossing the face's interior with both ends outside), the
/// whole segment is tested against the face. With `h(s)` the signed distance of the segment
/// point to the plane (affine in `s`) and `w(s)` the barycentric weights of its projection
/// (eq 15, affine in `s`):
/// - **parallel** to the plane (`|n̂ · d|² <= ε² |d|²`, `d = p1 - p0`, ε = [`PARALLEL_EPSILON`]):
///   the closest set is the stretch `{s : w(s) >= 0}` of the segment above the face, at
///   constant height; its middle is returned (continuous as the segment slides). Within ε the
///   distance exceeds the true minimum by at most `ε |d|`;
/// - otherwise, **piercing**: `h` changes sign at `s* = h(0) / (h(0) - h(1))`; if `w(s*) > 0` the
///   segment pierces the face there and the distance is 0;
/// - otherwise the minimum is on the boundary of one of the two sets (the distance to the
///   plane is monotone in `s` over the face): each end projected on the face when it lands
///   strictly inside, and the segment against each edge ([`closest_points_segment_segment`]).
///   The smallest wins, the face candidates first on a tie.
///
/// Degenerate inputs: a segment shorter than ε times the longest triangle edge is its end `p0`
/// ([`project_point_triangle`], `s = 0`); a degenerate triangle (height below `1e-8` of its
/// longest edge) is its three edges. Never NaN for finite inputs.
pub fn closest_points_segment_triangle(
    p0: &Vec3,
    p1: &Vec3,
    a: &Vec3,
    b: &Vec3,
    c: &Vec3,
) -> SegmentTriangleClosestPoints {
    let d = p1 - p0;
    let d2 = d.norm_squared();
    let v = vertices(a, b, c);
    let l2 = (b - a).norm_squared().max((c - b).norm_squared()).max((a - c).norm_squared());
    if d2 <= PARALLEL_EPSILON * PARALLEL_EPSILON * l2 {
        let proj = project_point_triangle(p0, a, b, c);
        return SegmentTriangleClosestPoints {
            s: 0.0,
            point_segment: *p0,
            location_segment: SegmentLocation::OnVertex(0),
            point_triangle: proj.point,
            weights: proj.weights,
            location_triangle: proj.location,
            distance_squared: (p0 - proj.point).norm_squared(),
        };
    }

    let mut best: Option<SegmentTriangleClosestPoints> = None;
    let mut consider = |candidate: SegmentTriangleClosestPoints| {
        if best.is_none_or(|b| candidate.distance_squared < b.distance_squared) {
            best = Some(candidate);
        }
    };
    if let Some(frame) = TriangleFrame::new(a, b, c) {
        let (w0, w1) = (frame.weights(p0), frame.weights(p1));
        let (h0, h1) = (frame.signed_distance(p0), frame.signed_distance(p1));
        let dh = h0 - h1;
        let inside = |w: &[Real; 3]| w.iter().all(|&x| x > 0.0);
        if dh * dh <= PARALLEL_EPSILON * PARALLEL_EPSILON * d2 {
            if let Some((lo, hi)) = stretch_inside(&w0, &w1) {
                let s = 0.5 * (lo + hi);
                let w = lerp_weights(&w0, &w1, s);
                if inside(&w) {
                    return on_face(p0, p1, &frame, s, w);
                }
            }
        } else if h0 * h1 <= 0.0 {
            let s = (h0 / dh).clamp(0.0, 1.0);
            let w = lerp_weights(&w0, &w1, s);
            if inside(&w) {
                return on_face(p0, p1, &frame, s, w);
            }
        }
        if inside(&w0) {
            consider(on_face(p0, p1, &frame, 0.0, w0));
        }
        if inside(&w1) {
            consider(on_face(p0, p1, &frame, 1.0, w1));
        }
    }
    for edge in 0..3 {
        let (i, j) = TriangleLocation::edge_vertices(edge);
        let r = closest_points_segment_segment(p0, p1, v[i], v[j]);
        let (location_triangle, weights) = triangle_location_on_edge(edge, r.location_b);
        consider(SegmentTriangleClosestPoints {
            s: r.s,
            point_segment: r.point_a,
            location_segment: r.location_a,
            point_triangle: r.point_b,
            weights,
            location_triangle,
            distance_squared: r.distance_squared,
        });
    }
    // Three edge candidates were considered, so `best` is set.
    best.unwrap_or_else(|| unreachable_fallback(p0, a))
}

/// Never reached (the edge loop always proposes a candidate); a valid answer rather than a
/// panic.
fn unreachable_fallback(p0: &Vec3, a: &Vec3) -> SegmentTriangleClosestPoints {
    SegmentTriangleClosestPoints {
        s: 0.0,
        point_segment: *p0,
        location_segment: SegmentLocation::OnVertex(0),
        point_triangle: *a,
        weights: [1.0, 0.0, 0.0],
        location_triangle: TriangleLocation::OnVertex(0),
        distance_squared: (p0 - a).norm_squared(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::point_triangle::test_support::*;
    use crate::proptest_support::{rotation, scale, segment, triangle, unit_vec3, vec3};
    use proptest::prelude::*;

    fn oracle_distance(p0: &Vec3, p1: &Vec3, t: &[Vec3; 3]) -> Real {
        let f =
            |z: &[Real; 3]| (p0 + (p1 - p0) * z[0] - triangle_point(t, z[1], z[2])).norm_squared();
        oracle_min::<3>(16, f).sqrt().min(oracle_feature_pairs(&[*p0, *p1], t))
    }

    fn run(p0: &Vec3, p1: &Vec3, t: &[Vec3; 3]) -> SegmentTriangleClosestPoints {
        closest_points_segment_triangle(p0, p1, &t[0], &t[1], &t[2])
    }

    /// Consistency of an answer and agreement with the brute-force oracle.
    fn check(
        p0: &Vec3,
        p1: &Vec3,
        t: &[Vec3; 3],
    ) -> Result<SegmentTriangleClosestPoints, TestCaseError> {
        let r = run(p0, p1, t);
        check_on_triangle(t, &r.point_triangle, &r.weights, r.location_triangle, 1e-12)
            .map_err(TestCaseError::fail)?;
        let size =
            (p1 - p0).norm() + (t[1] - t[0]).norm() + (t[2] - t[0]).norm() + (p0 - t[0]).norm();
        prop_assert!((0.0..=1.0).contains(&r.s));
        prop_assert!((r.point_segment - (p0 + (p1 - p0) * r.s)).norm() <= 1e-14 * size);
        match r.location_segment {
            SegmentLocation::OnVertex(i) => prop_assert_eq!(r.s, i as Real),
            SegmentLocation::OnEdge { t } => prop_assert!(t == r.s && t > 0.0 && t < 1.0),
        }
        prop_assert!(
            ((r.point_segment - r.point_triangle).norm_squared() - r.distance_squared).abs()
                <= 1e-14 * size * size
        );
        let (d, oracle) = (r.distance(), oracle_distance(p0, p1, t));
        prop_assert!(d <= oracle + 1e-12 * size, "d {} > oracle {}", d, oracle);
        prop_assert!(d >= oracle - 1e-9 * size, "d {} < oracle {}", d, oracle);
        Ok(r)
    }

    fn unit_right_triangle() -> [Vec3; 3] {
        [Vec3::zeros(), Vec3::x(), Vec3::y()]
    }

    #[test]
    fn segment_crossing_face_interior_is_found() {
        // Parallel to the face at height 0.3, both ends outside the triangle: the contact is over
        // the face, in the middle of the stretch x in [0, 0.75] (YADE only sees the edges).
        let t = unit_right_triangle();
        let (p0, p1) = (Vec3::new(-1.0, 0.25, 0.3), Vec3::new(2.0, 0.25, 0.3));
        let r = run(&p0, &p1, &t);
        assert_eq!(r.location_triangle, TriangleLocation::OnFace);
        assert!((r.distance() - 0.3).abs() < 1e-15);
        assert!((r.point_triangle - Vec3::new(0.375, 0.25, 0.0)).norm() < 1e-15);
        assert!((r.s - 1.375 / 3.0).abs() < 1e-15);
        assert_eq!(r.location_segment, SegmentLocation::OnEdge { t: r.s });
    }

    #[test]
    fn piercing_segment_with_ends_outside_has_distance_zero() {
        let t = unit_right_triangle();
        let (p0, p1) = (Vec3::new(-1.0, 0.25, -0.5), Vec3::new(2.0, 0.25, 0.4));
        let r = run(&p0, &p1, &t);
        assert_eq!(r.location_triangle, TriangleLocation::OnFace);
        assert!(r.distance_squared < 1e-30);
        assert!((r.point_triangle - Vec3::new(2.0 / 3.0, 0.25, 0.0)).norm() < 1e-15);
        assert!((r.s - 5.0 / 9.0).abs() < 1e-15);
    }

    #[test]
    fn parallel_segment_over_face_gives_middle_of_stretch() {
        let t = unit_right_triangle();
        // Wholly over the face: the middle of the segment.
        let r = run(&Vec3::new(0.1, 0.1, -0.5), &Vec3::new(0.3, 0.2, -0.5), &t);
        assert_eq!((r.s, r.location_triangle), (0.5, TriangleLocation::OnFace));
        assert!((r.point_triangle - Vec3::new(0.2, 0.15, 0.0)).norm() < 1e-15);
        // One end outside: the middle of the part over the face, x in [0.1, 0.6].
        let r = run(&Vec3::new(0.1, 0.4, 0.2), &Vec3::new(1.1, 0.4, 0.2), &t);
        assert!((r.point_segment - Vec3::new(0.35, 0.4, 0.2)).norm() < 1e-15);
        // In the plane, crossing the triangle: distance 0 at the middle of the chord.
        let r = run(&Vec3::new(-1.0, 0.5, 0.0), &Vec3::new(1.0, 0.5, 0.0), &t);
        assert!(
            r.distance_squared < 1e-30
                && (r.point_triangle - Vec3::new(0.25, 0.5, 0.0)).norm() < 1e-15
        );
    }

    #[test]
    fn millimetre_segment_slightly_tilted_gets_the_exact_answer() {
        // 1 mm triangle, segment tilted by 1e-6 rad (far above ε): its lower end is closest.
        let k = 1e-3;
        let t = [Vec3::zeros(), Vec3::x() * k, Vec3::y() * k];
        let (p0, p1) = (Vec3::new(0.1, 0.1, 0.2) * k, Vec3::new(0.3, 0.1, 0.2 + 2e-7) * k);
        let r = run(&p0, &p1, &t);
        assert_eq!((r.s, r.location_triangle), (0.0, TriangleLocation::OnFace));
        assert!((r.distance() - 0.2 * k).abs() < 1e-18);
    }

    #[test]
    fn degenerate_segment_and_triangle() {
        let t = unit_right_triangle();
        let p = Vec3::new(0.2, 0.2, 1.0);
        let r = run(&p, &p, &t);
        assert_eq!(
            (r.s, r.location_segment, r.location_triangle),
            (0.0, SegmentLocation::OnVertex(0), TriangleLocation::OnFace)
        );
        assert!((r.distance() - 1.0).abs() < 1e-15);
        // All three vertices equal: the segment against a point.
        let a = Vec3::new(0.5, 0.0, 0.0);
        let r = run(&Vec3::new(0.0, -1.0, 1.0), &Vec3::new(0.0, 1.0, 1.0), &[a, a, a]);
        assert!((r.distance_squared - 1.25).abs() < 1e-15 && (r.s - 0.5).abs() < 1e-15);
        assert!(matches!(r.location_triangle, TriangleLocation::OnVertex(_)));
        // Collinear triangle crossed by the segment.
        let r = run(
            &Vec3::new(0.5, -1.0, 0.0),
            &Vec3::new(0.5, 1.0, 0.0),
            &[Vec3::zeros(), Vec3::x() * 2.0, Vec3::x()],
        );
        assert!(
            r.distance_squared < 1e-30
                && (r.point_triangle - Vec3::new(0.5, 0.0, 0.0)).norm() < 1e-15
        );
    }

    /// A segment from a mix of configurations: general, parallel to the triangle's plane (over
    /// the face or not), piercing, nearly parallel, zero length.
    fn segment_near(t: [Vec3; 3]) -> impl Strategy<Value = (Vec3, Vec3)> {
        let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
        let n = if n.norm() > 0.0 { n.normalize() } else { Vec3::z() };
        let general = segment(1.5);
        let parallel = (vec3(1.5), vec3(1.5), -9.0..=-2.0_f64, any::<bool>()).prop_map(
            move |(p, q, e, tilt)| {
                let d = q - n * n.dot(&q);
                (p, p + d + if tilt { n * 10.0_f64.powf(e) } else { Vec3::zeros() })
            },
        );
        let piercing = (0.0..1.0_f64, 0.0..1.0_f64, unit_vec3(), 0.0..1.5_f64, 0.0..1.5_f64)
            .prop_map(move |(u, v, dir, l0, l1)| {
                let q = triangle_point(&t, u, v);
                (q - dir * l0, q + dir * l1)
            });
        let point = vec3(1.5).prop_map(|p| (p, p));
        prop_oneof![3 => general, 3 => parallel, 2 => piercing, 1 => point]
    }

    fn triangle_and_segment() -> impl Strategy<Value = ([Vec3; 3], (Vec3, Vec3))> {
        triangle(1.0).prop_flat_map(|(a, b, c)| (Just([a, b, c]), segment_near([a, b, c])))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn matches_oracle_and_is_consistent((t, (p0, p1)) in triangle_and_segment()) {
            check(&p0, &p1, &t)?;
        }

        #[test]
        fn degenerate_triangles_match_oracle((p0, p1) in segment(1.5), a in vec3(1.0), b in vec3(1.0),
                                             u in -1.0..2.0_f64, kind in 0..4usize, k in scale()) {
            let t = match kind {
                0 => [a, b, a + (b - a) * u],
                1 => [a, a, b],
                2 => [a, a, a],
                _ => [a, b, a + (b - a) * u + (b - a).cross(&Vec3::z()) * 1e-9],
            };
            check(&(p0 * k), &(p1 * k), &[t[0] * k, t[1] * k, t[2] * k])?;
        }

        /// Parallel over the face: the middle of the stretch, found by construction.
        #[test]
        fn parallel_over_face_is_middle_of_stretch(t in triangle(1.0), u in 0.0..1.0_f64, v in 0.0..1.0_f64,
                                                   dir in unit_vec3(), l in 0.1..2.0_f64, h in -1.0..1.0_f64) {
            let t = [t.0, t.1, t.2];
            let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
            prop_assume!(n.norm() > 1e-3);
            let n = n.normalize();
            let d = dir - n * n.dot(&dir);
            prop_assume!(d.norm() > 1e-3);
            let q = triangle_point(&t, u, v) + n * h;
            let r = check(&(q - d * l), &(q + d * l), &t)?;
            prop_assert!((r.distance() - h.abs()).abs() <= 1e-12);
            // Middle of the stretch: bisect its two ends from the returned parameter.
            prop_assert_eq!(r.location_triangle, TriangleLocation::OnFace);
            let inside = |s: Real| {
                let p = q + d * (l * (2.0 * s - 1.0));
                project_point_triangle(&p, &t[0], &t[1], &t[2]).location == TriangleLocation::OnFace
            };
            let bisect = |mut out: Real, mut inn: Real| {
                if inside(out) {
                    return out;
                }
                for _ in 0..60 {
                    let m = 0.5 * (out + inn);
                    if inside(m) { inn = m } else { out = m }
                }
                inn
            };
            let (lo, hi) = (bisect(0.0, r.s), bisect(1.0, r.s));
            prop_assert!((r.s - 0.5 * (lo + hi)).abs() <= 1e-9, "s {} stretch {} {}", r.s, lo, hi);
        }

        #[test]
        fn piercing_gives_distance_zero(t in triangle(1.0), w in (0.01..1.0_f64, 0.01..1.0_f64, 0.01..1.0_f64),
                                        dir in unit_vec3(), l0 in 0.01..1.0_f64, l1 in 0.01..1.0_f64) {
            let t = [t.0, t.1, t.2];
            let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
            prop_assume!(n.norm() > 1e-2 && n.normalize().dot(&dir).abs() > 1e-2);
            let q = (t[0] * w.0 + t[1] * w.1 + t[2] * w.2) / (w.0 + w.1 + w.2);
            let r = check(&(q - dir * l0), &(q + dir * l1), &t)?;
            prop_assert!(r.distance() <= 1e-12);
            prop_assert!((r.point_triangle - q).norm() <= 1e-9);
            prop_assert_eq!(r.location_triangle, TriangleLocation::OnFace);
        }

        #[test]
        fn reversal_maps_s_to_one_minus_s((t, (p0, p1)) in triangle_and_segment()) {
            let r = run(&p0, &p1, &t);
            let q = run(&p1, &p0, &t);
            prop_assert!((r.distance() - q.distance()).abs() <= 1e-12);
            // The closest pair is unique unless parallel; compare parameters when it is.
            let unique = (r.point_segment - q.point_segment).norm() <= 1e-9;
            if unique && (p1 - p0).norm() > 1e-6 {
                prop_assert!((r.s - (1.0 - q.s)).abs() <= 1e-9 / (p1 - p0).norm());
            }
        }

        #[test]
        fn rigid_motion_and_scale_invariance((t, (p0, p1)) in triangle_and_segment(), shift in vec3(1e3),
                                             rot in rotation(), k in scale()) {
            let m = |x: &Vec3| (rot * x + shift) * k;
            let r = run(&p0, &p1, &t);
            let q = closest_points_segment_triangle(&m(&p0), &m(&p1), &m(&t[0]), &m(&t[1]), &m(&t[2]));
            prop_assert!((q.distance() - r.distance() * k).abs() <= 1e-9 * k, "{} {}", q.distance(), r.distance() * k);
        }

        #[test]
        fn distance_is_lipschitz((t, (p0, p1)) in triangle_and_segment(), dir in unit_vec3(), which in 0..5usize) {
            let eps = 1e-3;
            let x = [p0, p1, t[0], t[1], t[2]];
            let dist = |x: &[Vec3; 5]| closest_points_segment_triangle(&x[0], &x[1], &x[2], &x[3], &x[4]).distance();
            let mut y = x;
            y[which] += dir * eps;
            prop_assert!((dist(&y) - dist(&x)).abs() <= eps * (1.0 + 1e-9));
        }
    }
}
