//! Projection of a point onto a segment (sphere–connection contacts).

use crate::{Real, SegmentLocation, Vec3};

/// The point of a segment `[a, b]` closest to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PointSegmentProjection {
    /// Parameter of the closest point, clamped to `[0, 1]`: `point = a + t (b - a)`.
    pub t: Real,
    /// The closest point of the segment.
    pub point: Vec3,
    /// `OnVertex(0)` when `t == 0` after clamping, `OnVertex(1)` when `t == 1`, else
    /// `OnEdge { t }`.
    pub location: SegmentLocation,
}

impl PointSegmentProjection {
    /// Whether the closest point is an end of the segment (the query point is in an end cap's
    /// region, or the segment has zero length).
    pub fn is_at_end(&self) -> bool {
        matches!(self.location, SegmentLocation::OnVertex(_))
    }
}

/// `clamp(num / den, 0, 1)` decided by regions, never dividing when the answer is an end:
/// `0` when `num <= 0`, `1` when `num >= den`, else `num / den`. With `den >= 0` this never
/// produces NaN, also for `den == 0` (then `num` is `0` for a zero-length segment and the answer
/// is `0`).
pub(crate) fn clamped_ratio(num: Real, den: Real) -> Real {
    if num <= 0.0 {
        0.0
    } else if num >= den {
        1.0
    } else {
        num / den
    }
}

/// The location on a segment of a parameter already clamped to `[0, 1]`: the ends are the
/// clamped values `0` and `1` exactly (region classification, not a tolerance).
pub(crate) fn segment_location(t: Real) -> SegmentLocation {
    if t <= 0.0 {
        SegmentLocation::OnVertex(0)
    } else if t >= 1.0 {
        SegmentLocation::OnVertex(1)
    } else {
        SegmentLocation::OnEdge { t }
    }
}

/// Projects `p` onto the segment `[a, b]`.
///
/// `t = clamp(((p - a) · (b - a)) / |b - a|², 0, 1)`, `point = a + t (b - a)`. The clamp is a
/// region test (Ericson): `t = 0` when `(p - a) · (b - a) <= 0` (the end cap of `a`), `t = 1` when
/// it reaches `|b - a|²` (the end cap of `b`); the division happens only strictly inside, so a
/// zero-length segment gives `t = 0`, `OnVertex(0)` and no NaN. This is the sphere–connection
/// pair of the paper: the end caps of the cylinder come from the clamping.
pub fn project_point_segment(p: &Vec3, a: &Vec3, b: &Vec3) -> PointSegmentProjection {
    let ab = b - a;
    let t = clamped_ratio((p - a).dot(&ab), ab.norm_squared());
    let point = if t >= 1.0 { *b } else { a + ab * t };
    PointSegmentProjection { t, point, location: segment_location(t) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::proptest_support::{rotation, scale, segment, vec3};
    use proptest::prelude::*;

    /// Brute-force distance from `p` to `[a, b]`: dense sampling of `t` then golden-section
    /// refinement around the best sample (the squared distance is convex in `t`).
    fn oracle_distance(p: &Vec3, a: &Vec3, b: &Vec3) -> Real {
        let f = |t: Real| (a + (b - a) * t - p).norm();
        let n = 64;
        let best =
            (0..=n).map(|i| i as Real / n as Real).min_by(|x, y| f(*x).total_cmp(&f(*y))).unwrap();
        let (mut lo, mut hi) =
            ((best - 1.0 / n as Real).max(0.0), (best + 1.0 / n as Real).min(1.0));
        let g = 0.5 * (5.0_f64.sqrt() - 1.0);
        for _ in 0..100 {
            let x1 = hi - g * (hi - lo);
            let x2 = lo + g * (hi - lo);
            if f(x1) <= f(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        f(0.5 * (lo + hi)).min(f(best))
    }

    #[test]
    fn point_segment_interior() {
        let r = project_point_segment(&Vec3::new(0.3, 1.0, 0.0), &Vec3::zeros(), &Vec3::x());
        assert!((r.t - 0.3).abs() < 1e-15);
        assert_eq!(r.location, SegmentLocation::OnEdge { t: r.t });
        assert!(!r.is_at_end());
        assert!((r.point - Vec3::new(0.3, 0.0, 0.0)).norm() < 1e-15);
    }

    #[test]
    fn point_segment_end_caps() {
        let (a, b) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(2.0, 2.0, 3.0));
        let before = project_point_segment(&Vec3::new(0.0, 5.0, 3.0), &a, &b);
        assert_eq!(
            (before.t, before.location, before.point),
            (0.0, SegmentLocation::OnVertex(0), a)
        );
        assert!(before.is_at_end());
        let after = project_point_segment(&Vec3::new(7.0, -1.0, 3.0), &a, &b);
        assert_eq!((after.t, after.location, after.point), (1.0, SegmentLocation::OnVertex(1), b));
        assert!(after.is_at_end());
    }

    #[test]
    fn point_segment_zero_length() {
        let a = Vec3::new(1.0, -2.0, 0.5);
        let r = project_point_segment(&Vec3::new(3.0, 1.0, 0.0), &a, &a);
        assert_eq!((r.t, r.location, r.point), (0.0, SegmentLocation::OnVertex(0), a));
        let on = project_point_segment(&a, &a, &a);
        assert_eq!((on.t, on.location, on.point), (0.0, SegmentLocation::OnVertex(0), a));
    }

    #[test]
    fn point_segment_tiny_segment_far_point() {
        // A segment 1e-200 long: the division happens only inside, no overflow or NaN.
        // Its squared length underflows to 0 while the dot product does not.
        let a = Vec3::zeros();
        let b = Vec3::new(1e-200, 0.0, 0.0);
        let r = project_point_segment(&Vec3::new(2.0, 1.0, 0.0), &a, &b);
        assert_eq!(r.location, SegmentLocation::OnVertex(1));
        assert!(r.t.is_finite() && r.point.iter().all(|x| x.is_finite()));
    }

    #[test]
    fn point_segment_point_on_segment() {
        let (a, b) = (Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0));
        let r = project_point_segment(&Vec3::new(0.5, 0.5, 0.5), &a, &b);
        assert!((r.t - 0.75).abs() < 1e-15);
        assert!((r.point - Vec3::new(0.5, 0.5, 0.5)).norm() < 1e-15);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn point_segment_matches_oracle(p in vec3(1.0), (a, b) in segment(1.0), k in scale()) {
            let (p, a, b) = (p * k, a * k, b * k);
            let r = project_point_segment(&p, &a, &b);
            let d = (r.point - p).norm();
            let oracle = oracle_distance(&p, &a, &b);
            let size = k * (1.0 + (b - a).norm());
            prop_assert!(d <= oracle + 1e-14 * size, "d {d} oracle {oracle}");
            prop_assert!(oracle >= d - 1e-12 * size, "d {d} oracle {oracle}");
        }

        #[test]
        fn point_segment_result_is_consistent(p in vec3(1.0), (a, b) in segment(1.0)) {
            let r = project_point_segment(&p, &a, &b);
            prop_assert!((0.0..=1.0).contains(&r.t));
            let tol = 1e-15 * (1.0 + a.norm() + b.norm());
            prop_assert!((r.point - (a + (b - a) * r.t)).norm() <= tol);
            match r.location {
                SegmentLocation::OnVertex(0) => prop_assert_eq!(r.t, 0.0),
                SegmentLocation::OnVertex(1) => prop_assert_eq!(r.t, 1.0),
                SegmentLocation::OnVertex(i) => prop_assert!(false, "bad vertex {}", i),
                SegmentLocation::OnEdge { t } => {
                    prop_assert_eq!(t, r.t);
                    prop_assert!(t > 0.0 && t < 1.0);
                    // Inside, the offset is perpendicular to the segment.
                    let ab = b - a;
                    let perp = (p - r.point).dot(&ab).abs();
                    prop_assert!(perp <= 1e-12 * ab.norm() * (1.0 + (p - a).norm()));
                }
            }
        }

        #[test]
        fn point_segment_reversal_symmetry(p in vec3(1.0), (a, b) in segment(1.0)) {
            let r = project_point_segment(&p, &a, &b);
            let q = project_point_segment(&p, &b, &a);
            let size = 1.0 + (b - a).norm();
            prop_assert!((r.point - q.point).norm() <= 1e-13 * size);
            prop_assert!((r.t - (1.0 - q.t)).abs() <= 1e-12 * size / (b - a).norm().max(1e-300));
        }

        #[test]
        fn point_segment_rigid_motion_and_scale_invariance(
            p in vec3(1.0),
            (a, b) in segment(1.0),
            shift in vec3(10.0),
            rot in rotation(),
            k in scale(),
        ) {
            let r = project_point_segment(&p, &a, &b);
            let m = |x: &Vec3| rot * x * k + shift * k;
            let q = project_point_segment(&m(&p), &m(&a), &m(&b));
            let d = (r.point - p).norm() * k;
            let e = (q.point - m(&p)).norm();
            prop_assert!((d - e).abs() <= 1e-12 * k * (12.0 + 20.0), "d {d} e {e}");
            prop_assert!((m(&r.point) - q.point).norm() <= 1e-9 * k * 30.0);
        }

        #[test]
        fn point_segment_distance_is_lipschitz(
            p in vec3(1.0),
            (a, b) in segment(1.0),
            dir in crate::proptest_support::unit_vec3(),
            which in 0..3usize,
        ) {
            let eps = 1e-3;
            let d0 = (project_point_segment(&p, &a, &b).point - p).norm();
            let (mut p1, mut a1, mut b1) = (p, a, b);
            [&mut p1, &mut a1, &mut b1][which].axpy(eps, &dir, 1.0);
            let d1 = (project_point_segment(&p1, &a1, &b1).point - p1).norm();
            prop_assert!((d1 - d0).abs() <= eps * (1.0 + 1e-9) + 1e-14, "d0 {d0} d1 {d1}");
        }
    }
}
