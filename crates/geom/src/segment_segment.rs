//! Closest points between two segments (connection–connection contacts, paper eq 9–14).

use crate::point_segment::{clamped_ratio, segment_location};
use crate::{Real, SegmentLocation, Vec3};

/// Relative tolerance on the angle between two segments below which they are treated as
/// parallel: `|d_a × d_b|² <= ε² |d_a|² |d_b|²`, i.e. `sin θ <= ε`.
///
/// Above it the exact answer is used; it is ill-conditioned along the lines (the distance is
/// flat there) but the distance it returns stays within round-off of the true one because the
/// second parameter is always recomputed by projection (see
/// [`closest_points_segment_segment`]). Below it the segments are parallel to the last few ulps
/// and the middle of the overlap is returned, whose distance exceeds the true minimum by at most
/// `ε` times the segment length.
pub const PARALLEL_EPSILON: Real = 1e-12;

/// The closest points of two segments `a = [a0, a1]` and `b = [b0, b1]`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SegmentSegmentClosestPoints {
    /// Parameter on `a` in `[0, 1]`: `point_a = a0 + s (a1 - a0)`.
    pub s: Real,
    /// Parameter on `b` in `[0, 1]`: `point_b = b0 + t (b1 - b0)`.
    pub t: Real,
    /// The closest point of `a`.
    pub point_a: Vec3,
    /// The closest point of `b`.
    pub point_b: Vec3,
    /// Where `point_a` lies on `a` (from `s`: an end exactly when `s` was clamped to 0 or 1).
    pub location_a: SegmentLocation,
    /// Where `point_b` lies on `b` (from `t`).
    pub location_b: SegmentLocation,
    /// Whether the segments were treated as parallel ([`PARALLEL_EPSILON`]), which includes
    /// one or both of them having zero length. The closest set is then not unique in general
    /// and its middle was returned.
    pub parallel: bool,
    /// `|point_a - point_b|²`.
    pub distance_squared: Real,
}

impl SegmentSegmentClosestPoints {
    /// `|point_a - point_b|`.
    pub fn distance(&self) -> Real {
        self.distance_squared.sqrt()
    }
}

/// Closest points of the segments `a = [a0, a1]` and `b = [b0, b1]`:
/// `min over (s, t) in [0, 1]² of |A(s) - B(t)|²` with `A(s) = a0 + s d_a`, `B(t) = b0 + t d_b`
/// (paper eq 9–12, `d_a = a1 - a0`, `d_b = b1 - b0`).
///
/// **General case** (`|d_a × d_b|² > ε² |d_a|² |d_b|²`, [`PARALLEL_EPSILON`]). The unclamped
/// minimiser over the two lines is the paper's eq 14. With `w0 = a0 - b0` and `n = d_a × d_b`,
/// eq 14 reads `s_C = ((d_a·d_b)(d_b·w0) - |d_b|²(d_a·w0)) / (|d_a|²|d_b|² - (d_a·d_b)²)` (the
/// paper writes `‖a‖` for `a·a`); by the identities of Lagrange and Binet–Cauchy this is
/// `s_C = ((b0 - a0) × d_b) · n / |n|²`, the form computed here because it does not subtract
/// nearly equal products when the segments are nearly parallel. Then (Ericson, *Real-Time
/// Collision Detection* §5.1.9; correct because the squared distance is convex):
/// `s = clamp(s_C)`, `t = clamp-free projection of A(s) on line b`; if that `t` leaves
/// `[0, 1]` it is clamped and `s` becomes the clamped projection of `B(t)` on `a`. Recomputing
/// one parameter from the other keeps the pair on the valley of the squared distance, so an
/// error of `s_C` (large for nearly parallel segments) moves the points along the segments
/// without adding more than round-off to the distance. No tolerance is involved.
///
/// **Parallel case** (including zero-length segments). Both segments are projected on the
/// line of the longer one. When the projections overlap (touching counts), the middle of the
/// overlap is taken on each segment (YADE's choice, continuous as the segments slide): `s` is the
/// middle of the part of `a` whose projection lies within `b`, `t` likewise. Otherwise the
/// closest pair of ends is returned. A zero-length segment gets parameter 0. Two zero-length
/// segments give `s = t = 0`.
///
/// Clamped parameters are exactly 0 or 1, which is what `location_a`/`location_b` report as
/// `OnVertex`. Never produces NaN for finite inputs.
pub fn closest_points_segment_segment(
    a0: &Vec3,
    a1: &Vec3,
    b0: &Vec3,
    b1: &Vec3,
) -> SegmentSegmentClosestPoints {
    let da = a1 - a0;
    let db = b1 - b0;
    let aa = da.norm_squared();
    let bb = db.norm_squared();
    let n = da.cross(&db);
    let nn = n.norm_squared();
    let parallel = nn <= PARALLEL_EPSILON * PARALLEL_EPSILON * (aa * bb);

    let (s, t) = if parallel {
        if aa >= bb {
            middle_of_parallel_overlap(a0, &da, aa, b0, b1)
        } else {
            let (t, s) = middle_of_parallel_overlap(b0, &db, bb, a0, a1);
            (s, t)
        }
    } else {
        // Here `nn > 0`, so `aa > 0` and `bb > 0`.
        let s = clamped_ratio((b0 - a0).cross(&db).dot(&n), nn);
        let t = (a0 + da * s - b0).dot(&db) / bb;
        if t < 0.0 {
            (clamped_ratio((b0 - a0).dot(&da), aa), 0.0)
        } else if t > 1.0 {
            (clamped_ratio((b1 - a0).dot(&da), aa), 1.0)
        } else {
            (s, t)
        }
    };

    let point_a = point_on_segment(a0, a1, &da, s);
    let point_b = point_on_segment(b0, b1, &db, t);
    SegmentSegmentClosestPoints {
        s,
        t,
        point_a,
        point_b,
        location_a: segment_location(s),
        location_b: segment_location(t),
        parallel,
        distance_squared: (point_a - point_b).norm_squared(),
    }
}

/// `p0 + t d` with the ends returned exactly at `t = 0` and `t = 1`.
fn point_on_segment(p0: &Vec3, p1: &Vec3, d: &Vec3, t: Real) -> Vec3 {
    if t >= 1.0 {
        *p1
    } else {
        p0 + d * t
    }
}

/// Parameters `(s_p, s_q)` on a segment `p = [p0, p0 + dp]` (`pp = |dp|²`, the longer of the
/// two) and a segment `q = [q0, q1]` parallel to it.
///
/// With `σ(x) = (x - p0) · dp`, `p` covers `[0, pp]` and `q` covers `[σ(q0), σ(q1)]` (in
/// either order). If the two intervals overlap in `[lo, hi]`, both parameters are those of its
/// middle `m = (lo + hi) / 2`: `s_p = m / pp`, `s_q = (m - σ(q0)) / (σ(q1) - σ(q0))`. Otherwise
/// the nearest ends. Every division goes through [`clamped_ratio`], so zero lengths give 0.
fn middle_of_parallel_overlap(
    p0: &Vec3,
    dp: &Vec3,
    pp: Real,
    q0: &Vec3,
    q1: &Vec3,
) -> (Real, Real) {
    let u0 = (q0 - p0).dot(dp);
    let u1 = (q1 - p0).dot(dp);
    let (q_min, q_max) = (u0.min(u1), u0.max(u1));
    let lo = q_min.max(0.0);
    let hi = q_max.min(pp);
    if lo <= hi {
        let m = 0.5 * (lo + hi);
        let s_q =
            if u1 >= u0 { clamped_ratio(m - u0, u1 - u0) } else { clamped_ratio(u0 - m, u0 - u1) };
        (clamped_ratio(m, pp), s_q)
    } else if q_max < 0.0 {
        // q lies before p0: p's first end against q's end of largest σ.
        (0.0, if u1 > u0 { 1.0 } else { 0.0 })
    } else {
        // q lies beyond p's second end: p's second end against q's end of smallest σ.
        (1.0, if u1 < u0 { 1.0 } else { 0.0 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::proptest_support::{rotation, scale, segment, segment_pair, unit_vec3, vec3};
    use nalgebra::{Rotation3, Vector3};
    use proptest::prelude::*;

    type Case = (Vec3, Vec3, Vec3, Vec3);

    fn v(x: Real, y: Real, z: Real) -> Vec3 {
        Vec3::new(x, y, z)
    }

    fn closest(c: &Case) -> SegmentSegmentClosestPoints {
        closest_points_segment_segment(&c.0, &c.1, &c.2, &c.3)
    }

    /// Size of a case: the largest coordinate or length involved (tolerances are relative to it).
    fn size(c: &Case) -> Real {
        [c.0, c.1, c.2, c.3]
            .iter()
            .map(|p| p.amax())
            .fold((c.1 - c.0).norm() + (c.3 - c.2).norm(), Real::max)
    }

    /// `(|d_a|² + |d_b|²)² / |d_a × d_b|²`: the condition number of the closest points (∞ when
    /// parallel); points are compared between equivalent cases only when it is moderate.
    fn condition(c: &Case) -> Real {
        let (da, db) = (c.1 - c.0, c.3 - c.2);
        (da.norm_squared() + db.norm_squared()).powi(2) / da.cross(&db).norm_squared()
    }

    /// Minimum of a function convex on `[0, 1]`: sampling then golden-section search.
    fn golden_min(f: impl Fn(Real) -> Real) -> Real {
        let n = 16;
        let best = (0..=n).map(|i| f(i as Real / n as Real)).fold(Real::INFINITY, Real::min);
        let g = 0.5 * (5.0_f64.sqrt() - 1.0);
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..90 {
            let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if f(x1) <= f(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        best.min(f(0.5 * (lo + hi)))
    }

    /// Brute-force distance: a dense grid of `(s, t)`, then nested golden sections (the
    /// distance is convex over the square, and so is its minimum over `t` as a function of `s`).
    fn oracle_distance(c: &Case) -> Real {
        let f = |s: Real, t: Real| (c.0 + (c.1 - c.0) * s - c.2 - (c.3 - c.2) * t).norm();
        let n = 32;
        let grid = (0..=n * n + 2 * n)
            .map(|k| f((k / (n + 1)) as Real / n as Real, (k % (n + 1)) as Real / n as Real))
            .fold(Real::INFINITY, Real::min);
        grid.min(golden_min(|s| golden_min(|t| f(s, t))))
    }

    /// Checks the returned points, parameters, locations and distance against each other.
    fn check_consistency(c: &Case, r: &SegmentSegmentClosestPoints) -> Result<(), TestCaseError> {
        let tol = 4.0 * Real::EPSILON * size(c);
        for (p0, p1, u, point, loc) in
            [(c.0, c.1, r.s, r.point_a, r.location_a), (c.2, c.3, r.t, r.point_b, r.location_b)]
        {
            prop_assert!((0.0..=1.0).contains(&u));
            prop_assert!((point - (p0 + (p1 - p0) * u)).norm() <= tol);
            match loc {
                SegmentLocation::OnVertex(0) => prop_assert!(u == 0.0 && point == p0),
                SegmentLocation::OnVertex(1) => prop_assert!(u == 1.0 && point == p1),
                SegmentLocation::OnVertex(i) => prop_assert!(false, "bad vertex {}", i),
                SegmentLocation::OnEdge { t } => prop_assert!(t == u && t > 0.0 && t < 1.0),
            }
        }
        prop_assert_eq!(r.distance_squared, (r.point_a - r.point_b).norm_squared());
        Ok(())
    }

    fn assert_close(x: Real, y: Real, tol: Real) {
        assert!((x - y).abs() <= tol, "{x} vs {y} (tol {tol})");
    }

    #[test]
    fn segment_segment_parallel_disjoint() {
        let r = closest_points_segment_segment(
            &v(0., 0., 0.),
            &v(1., 0., 0.),
            &v(2., 1., 0.),
            &v(3., 1., 0.),
        );
        assert!(r.parallel);
        assert_eq!((r.s, r.t, r.distance_squared), (1.0, 0.0, 2.0));
        assert_eq!(
            (r.location_a, r.location_b),
            (SegmentLocation::OnVertex(1), SegmentLocation::OnVertex(0))
        );
        // b before a and reversed.
        let r = closest_points_segment_segment(
            &v(0., 0., 0.),
            &v(1., 0., 0.),
            &v(-1., 0., 2.),
            &v(-3., 0., 2.),
        );
        assert!(r.parallel);
        assert_eq!((r.s, r.t, r.distance_squared), (0.0, 0.0, 5.0));
    }

    #[test]
    fn segment_segment_parallel_overlapping() {
        // Overlap of the projections: x in [1, 2], middle 1.5.
        let r = closest_points_segment_segment(
            &v(0., 0., 0.),
            &v(2., 0., 0.),
            &v(1., 1., 0.),
            &v(3., 1., 0.),
        );
        assert!(r.parallel);
        assert_eq!((r.s, r.t, r.distance_squared), (0.75, 0.25, 1.0));
        assert_eq!(
            (r.location_a, r.location_b),
            (SegmentLocation::OnEdge { t: 0.75 }, SegmentLocation::OnEdge { t: 0.25 })
        );
        // Opposite directions.
        let r = closest_points_segment_segment(
            &v(0., 0., 0.),
            &v(2., 0., 0.),
            &v(3., 1., 0.),
            &v(1., 1., 0.),
        );
        assert_eq!((r.s, r.t), (0.75, 0.75));
        // b contained in a's projection: middle of b.
        let r = closest_points_segment_segment(
            &v(0., 0., 0.),
            &v(4., 0., 0.),
            &v(1., 0., 3.),
            &v(2., 0., 3.),
        );
        assert_eq!((r.s, r.t, r.distance_squared), (0.375, 0.5, 9.0));
        // Same, b longer than a (the axis is b's line).
        let r = closest_points_segment_segment(
            &v(1., 0., 3.),
            &v(2., 0., 3.),
            &v(0., 0., 0.),
            &v(4., 0., 0.),
        );
        assert_eq!((r.s, r.t, r.distance_squared), (0.5, 0.375, 9.0));
    }

    #[test]
    fn segment_segment_collinear_overlapping() {
        let r = closest_points_segment_segment(
            &v(0., 0., 0.),
            &v(2., 0., 0.),
            &v(1., 0., 0.),
            &v(3., 0., 0.),
        );
        assert!(r.parallel);
        assert_eq!((r.s, r.t, r.distance_squared), (0.75, 0.25, 0.0));
        assert_eq!(r.point_a, v(1.5, 0., 0.));
    }

    #[test]
    fn segment_segment_collinear_disjoint_and_touching() {
        let r = closest_points_segment_segment(
            &v(0., 0., 0.),
            &v(1., 0., 0.),
            &v(2., 0., 0.),
            &v(3., 0., 0.),
        );
        assert!(r.parallel);
        assert_eq!((r.s, r.t, r.distance_squared), (1.0, 0.0, 1.0));
        let r = closest_points_segment_segment(
            &v(0., 0., 0.),
            &v(1., 0., 0.),
            &v(2., 0., 0.),
            &v(1., 0., 0.),
        );
        assert_eq!((r.s, r.t, r.distance_squared), (1.0, 1.0, 0.0));
        assert_eq!(
            (r.location_a, r.location_b),
            (SegmentLocation::OnVertex(1), SegmentLocation::OnVertex(1))
        );
    }

    #[test]
    fn segment_segment_one_zero_length() {
        let (a0, a1, p) = (v(0., 0., 0.), v(2., 0., 0.), v(0.5, 1., 0.));
        let r = closest_points_segment_segment(&a0, &a1, &p, &p);
        assert!(r.parallel);
        assert_eq!((r.s, r.t, r.distance_squared), (0.25, 0.0, 1.0));
        assert_eq!(r.location_b, SegmentLocation::OnVertex(0));
        let r = closest_points_segment_segment(&p, &p, &a0, &a1);
        assert_eq!((r.s, r.t, r.distance_squared), (0.0, 0.25, 1.0));
        let beyond = v(5., 0., 4.);
        let r = closest_points_segment_segment(&a0, &a1, &beyond, &beyond);
        assert_eq!((r.s, r.t, r.distance_squared), (1.0, 0.0, 25.0));
    }

    #[test]
    fn segment_segment_both_zero_length() {
        let (p, q) = (v(1., 2., 3.), v(1., 2., 5.));
        let r = closest_points_segment_segment(&p, &p, &q, &q);
        assert!(r.parallel);
        assert_eq!((r.s, r.t, r.point_a, r.point_b, r.distance_squared), (0.0, 0.0, p, q, 4.0));
        let r = closest_points_segment_segment(&p, &p, &p, &p);
        assert_eq!((r.s, r.t, r.distance_squared), (0.0, 0.0, 0.0));
    }

    #[test]
    fn segment_segment_intersecting() {
        let r = closest_points_segment_segment(
            &v(-1., 0., 0.),
            &v(1., 0., 0.),
            &v(0., -1., 0.),
            &v(0., 1., 0.),
        );
        assert!(!r.parallel);
        assert_eq!((r.s, r.t, r.distance_squared), (0.5, 0.5, 0.0));
        // Oblique crossing at s = 0.3, t = 0.8.
        let x = v(0.3, 0.3, 0.3);
        let (u, w) = (v(1., -2., 0.5), v(0.2, 1., -1.));
        let r = closest_points_segment_segment(
            &(x - u * 0.3),
            &(x + u * 0.7),
            &(x - w * 0.8),
            &(x + w * 0.2),
        );
        assert_close(r.s, 0.3, 1e-14);
        assert_close(r.t, 0.8, 1e-14);
        assert!(r.distance_squared < 1e-30);
    }

    #[test]
    fn segment_segment_t_configuration() {
        // b starts on a's interior.
        let r = closest_points_segment_segment(
            &v(-1., 0., 0.),
            &v(1., 0., 0.),
            &v(0.2, 0., 0.),
            &v(0.2, 1., 0.),
        );
        assert_close(r.s, 0.6, 1e-15);
        assert_eq!((r.t, r.location_b), (0.0, SegmentLocation::OnVertex(0)));
        assert!(r.distance_squared < 1e-30);
        // Same with a gap of 0.5, and with b's end on the other side.
        let r = closest_points_segment_segment(
            &v(-1., 0., 0.),
            &v(1., 0., 0.),
            &v(0.2, 2., 0.),
            &v(0.2, 0.5, 0.),
        );
        assert_close(r.s, 0.6, 1e-15);
        assert_eq!((r.t, r.location_b), (1.0, SegmentLocation::OnVertex(1)));
        assert_close(r.distance_squared, 0.25, 1e-15);
    }

    #[test]
    fn segment_segment_skew_clamped_to_corner() {
        // The lines' closest points are outside both segments: the answer is an end pair.
        let r = closest_points_segment_segment(
            &v(1., 0., 0.),
            &v(2., 0., 0.),
            &v(0., 1., 1.),
            &v(0., 2., 1.),
        );
        assert_eq!((r.s, r.t), (0.0, 0.0));
        assert_eq!(r.distance_squared, 3.0);
    }

    /// Two segments of length `len` crossing at their middles at 0.5 degrees, `len / 10` apart.
    fn nearly_parallel_at(len: Real) {
        let a0 = v(0., 0., 0.);
        let a1 = v(len, 0., 0.);
        let mid = v(0.5 * len, 0., 0.);
        let rot = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.5_f64.to_radians());
        let lift = v(0., 0., 0.1 * len);
        let (b0, b1) = (mid + rot * (a0 - mid) + lift, mid + rot * (a1 - mid) + lift);
        let r = closest_points_segment_segment(&a0, &a1, &b0, &b1);
        assert!(!r.parallel);
        assert_close(r.s, 0.5, 1e-12);
        assert_close(r.t, 0.5, 1e-12);
        assert_close(r.distance(), 0.1 * len, 1e-13 * len);
        assert!((r.point_a - mid).norm() < 1e-12 * len);
    }

    #[test]
    fn segment_segment_nearly_parallel_mm_scale() {
        nearly_parallel_at(1e-3);
    }

    #[test]
    fn segment_segment_nearly_parallel_km_scale() {
        nearly_parallel_at(1e3);
    }

    #[test]
    fn segment_segment_crossing_at_tiny_angle_has_zero_distance() {
        // 1e-10 rad, in the same plane: the distance is ill-conditioned along the segments but
        // must stay 0 to round-off.
        let a0 = v(-1., 0., 0.);
        let a1 = v(1., 0., 0.);
        let r = closest_points_segment_segment(&a0, &a1, &v(-1., -1e-10, 0.), &v(1., 1e-10, 0.));
        assert!(!r.parallel);
        assert!(r.distance() < 1e-15, "{}", r.distance());
        // Below the parallel threshold: the middle of the overlap.
        let r = closest_points_segment_segment(&a0, &a1, &v(-1., -1e-13, 0.), &v(1., 1e-13, 0.));
        assert!(r.parallel);
        assert_eq!((r.s, r.t), (0.5, 0.5));
    }

    #[test]
    fn segment_segment_constructed_answer() {
        // Common perpendicular z of length 0.7 between s* = 0.3 on a and t* = 0.6 on b.
        let p = v(0.2, -0.4, 1.0);
        let (u, w) = (v(1., 1., 0.).normalize(), v(1., -0.5, 0.).normalize());
        let q = p + v(0., 0., 0.7);
        let (a0, a1) = (p - u * 0.3 * 2.0, p + u * 0.7 * 2.0);
        let (b0, b1) = (q - w * 0.6 * 0.5, q + w * 0.4 * 0.5);
        let r = closest_points_segment_segment(&a0, &a1, &b0, &b1);
        assert_close(r.s, 0.3, 1e-14);
        assert_close(r.t, 0.6, 1e-14);
        assert_close(r.distance(), 0.7, 1e-14);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1024))]

        #[test]
        fn segment_segment_matches_oracle(c in segment_pair(1.0), k in scale()) {
            let c = (c.0 * k, c.1 * k, c.2 * k, c.3 * k);
            let r = closest(&c);
            check_consistency(&c, &r)?;
            let (d, oracle) = (r.distance(), oracle_distance(&c));
            // Round-off; for parallel results, the documented `ε L` of the overlap's middle
            // (the lines may still diverge by `sin θ <= ε` along it).
            let excess = if r.parallel { 1e-13 + PARALLEL_EPSILON } else { 1e-13 };
            prop_assert!(d <= oracle + excess * size(&c), "d {d} oracle {oracle}");
            prop_assert!(d >= oracle - 1e-9 * size(&c), "d {d} oracle {oracle}");
        }

        #[test]
        fn segment_segment_first_order_optimality((a, b) in (segment(1.0), segment(1.0))) {
            // KKT conditions, when the answer is well conditioned: along each segment the
            // distance cannot decrease by moving into it.
            let c = (a.0, a.1, b.0, b.1);
            prop_assume!(condition(&c) < 1e6);
            let r = closest(&c);
            let w = r.point_a - r.point_b;
            let tol = 1e-9 * size(&c).powi(2);
            let (ga, gb) = (w.dot(&(c.1 - c.0)), -w.dot(&(c.3 - c.2)));
            let gradients = [(ga, r.location_a), (gb, r.location_b)];
            for (g, loc) in gradients {
                match loc {
                    SegmentLocation::OnEdge { .. } => prop_assert!(g.abs() <= tol, "gradient {g}"),
                    SegmentLocation::OnVertex(0) => prop_assert!(g >= -tol, "gradient {g}"),
                    SegmentLocation::OnVertex(_) => prop_assert!(g <= tol, "gradient {g}"),
                }
            }
        }

        #[test]
        fn segment_segment_swap_and_reversal_symmetry(c in segment_pair(1.0)) {
            let r = closest(&c);
            let tol = 1e-12 * size(&c);
            let well_posed = r.parallel || condition(&c) < 1e6;
            let variants = [
                ((c.2, c.3, c.0, c.1), true, false, false),
                ((c.1, c.0, c.2, c.3), false, true, false),
                ((c.0, c.1, c.3, c.2), false, false, true),
            ];
            for (cv, swapped, rev_a, rev_b) in variants {
                let q = closest(&cv);
                prop_assert_eq!(q.parallel, r.parallel);
                let (dq, dr) = (q.distance(), r.distance());
                prop_assert!((dq - dr).abs() <= tol, "{} vs {}", dq, dr);
                let (qa, qb) =
                    if swapped { (q.point_b, q.point_a) } else { (q.point_a, q.point_b) };
                if well_posed {
                    let (ea, eb) = ((qa - r.point_a).norm(), (qb - r.point_b).norm());
                    prop_assert!(ea <= 1e3 * tol && eb <= 1e3 * tol,
                        "{:?} vs {:?}", q, r);
                }
                if r.parallel && (c.1 - c.0).norm() > 1e-3 && (c.3 - c.2).norm() > 1e-3 {
                    // The middle of the overlap maps to s ↔ 1 - s under reversal.
                    let (qs, qt) = if swapped { (q.t, q.s) } else { (q.s, q.t) };
                    let qs = if rev_a { 1.0 - qs } else { qs };
                    let qt = if rev_b { 1.0 - qt } else { qt };
                    let (es, et) = ((qs - r.s).abs(), (qt - r.t).abs());
                    prop_assert!(es <= 1e-9 && et <= 1e-9, "{:?} vs {:?}", q, r);
                }
            }
        }

        #[test]
        fn segment_segment_rigid_motion_and_scale_invariance(
            c in segment_pair(1.0), rot in rotation(), shift in vec3(10.0), k in scale(),
        ) {
            let m = |p: &Vec3| (rot * p + shift) * k;
            let cm = (m(&c.0), m(&c.1), m(&c.2), m(&c.3));
            let (r, q) = (closest(&c), closest(&cm));
            let tol = 1e-12 * k * (size(&c) + 20.0);
            let (dq, dr) = (q.distance(), r.distance() * k);
            prop_assert!((dq - dr).abs() <= tol, "{} vs {}", dq, dr);
            if q.parallel == r.parallel && (r.parallel || condition(&c) < 1e6) {
                prop_assert!((q.point_a - m(&r.point_a)).norm() <= 1e3 * tol);
                prop_assert!((q.point_b - m(&r.point_b)).norm() <= 1e3 * tol);
            }
        }

        #[test]
        fn segment_segment_distance_is_lipschitz(
            c in segment_pair(1.0),
            dir in unit_vec3(),
            which in 0..4usize,
        ) {
            let eps = 1e-3;
            let mut moved = [c.0, c.1, c.2, c.3];
            moved[which] += dir * eps;
            let d0 = closest(&c).distance();
            let d1 = closest(&(moved[0], moved[1], moved[2], moved[3])).distance();
            let bound = eps * (1.0 + 1e-9) + 1e-13 * size(&c);
            prop_assert!((d1 - d0).abs() <= bound, "d0 {d0} d1 {d1}");
        }

        #[test]
        fn segment_segment_finds_constructed_answer(
            p in vec3(1.0),
            u in unit_vec3(),
            w in unit_vec3(),
            s in 0.05..0.95_f64,
            t in 0.05..0.95_f64,
            h in 0.0..1.0_f64,
            la in 0.1..2.0_f64,
            lb in 0.1..2.0_f64,
            k in scale(),
        ) {
            let n = u.cross(&w);
            prop_assume!(n.norm() > 0.05);
            let q = p + n.normalize() * h;
            let (a0, a1) = (p - u * s * la, p + u * (1.0 - s) * la);
            let (b0, b1) = (q - w * t * lb, q + w * (1.0 - t) * lb);
            let c = (a0 * k, a1 * k, b0 * k, b1 * k);
            let r = closest(&c);
            prop_assert!(!r.parallel);
            let (es, et) = ((r.s - s).abs(), (r.t - t).abs());
            prop_assert!(es <= 1e-10 && et <= 1e-10, "{:?} vs s {s} t {t}", r);
            let inside = |l: SegmentLocation| matches!(l, SegmentLocation::OnEdge { .. });
            prop_assert!(inside(r.location_a) && inside(r.location_b));
            prop_assert!((r.distance() - h * k).abs() <= 1e-13 * size(&c));
        }
    }
}
