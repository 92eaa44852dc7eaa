//! Projection of a point onto a triangle (sphere–PFacet contacts) and the barycentric weights
//! of a PFacet (paper eq 15).

use crate::{project_point_segment, Real, SegmentLocation, TriangleLocation, Vec3};

/// A triangle is degenerate when its height is below this fraction of its longest edge:
/// `|ab × ac| <= ε |l_max|²`. At `ε = 1e-8 ≈ sqrt(f64::EPSILON)` the plane's normal is known to
/// about `f64::EPSILON / ε = 1e-8` (the round-off of the inputs over the height), and treating the
/// triangle as its three edges moves the closest point by at most its height, `ε l_max`: both
/// errors are `1e-8 l_max` there, and each is smaller on its own side of the threshold.
pub(crate) const TRIANGLE_DEGENERACY_TOLERANCE: Real = 1e-8;

/// The point of a triangle `(a, b, c)` closest to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PointTriangleProjection {
    /// The closest point of the triangle, `wa a + wb b + wc c`.
    pub point: Vec3,
    /// Barycentric weights `[wa, wb, wc]` of `point`: all `>= 0`, sum 1.
    pub weights: [Real; 3],
    /// The feature `point` lies on: `OnFace` only when all weights are `> 0`; on an edge the
    /// weight of the opposite vertex is exactly 0; on a vertex the weights are exactly one-hot.
    pub location: TriangleLocation,
}

/// The plane of a non-degenerate triangle, set up to evaluate the barycentric weights of the
/// projection of many points (paper eq 15) with two dot products each.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriangleFrame {
    /// Vertex `a`, origin of the frame.
    pub(crate) a: Vec3,
    /// `b - a`.
    pub(crate) ab: Vec3,
    /// `c - a`.
    pub(crate) ac: Vec3,
    /// Unit normal `ab × ac / |ab × ac|`.
    pub(crate) normal: Vec3,
    /// `(ac × n) / |n|²`: `wb = (p - a) · grad_b`.
    grad_b: Vec3,
    /// `(n × ab) / |n|²`: `wc = (p - a) · grad_c`.
    grad_c: Vec3,
}

impl TriangleFrame {
    /// The frame of `(a, b, c)`, `None` when the triangle is degenerate (collinear or coincident
    /// vertices, or a height below [`TRIANGLE_DEGENERACY_TOLERANCE`] times the longest edge).
    pub(crate) fn new(a: &Vec3, b: &Vec3, c: &Vec3) -> Option<Self> {
        let (ab, ac) = (b - a, c - a);
        let n = ab.cross(&ac);
        let n2 = n.norm_squared();
        let l2 = ab.norm_squared().max(ac.norm_squared()).max((c - b).norm_squared());
        let tol = TRIANGLE_DEGENERACY_TOLERANCE * l2;
        // NaN inputs are rejected too.
        if n2.is_nan() || n2 <= tol * tol {
            return None;
        }
        let inv = 1.0 / n2;
        Some(Self {
            a: *a,
            ab,
            ac,
            normal: n / n2.sqrt(),
            grad_b: ac.cross(&n) * inv,
            grad_c: n.cross(&ab) * inv,
        })
    }

    /// Unclamped barycentric weights `[wa, wb, wc]` of the orthogonal projection of `p` onto
    /// the plane (eq 15).
    #[inline]
    pub(crate) fn weights(&self, p: &Vec3) -> [Real; 3] {
        let ap = p - self.a;
        let wb = ap.dot(&self.grad_b);
        let wc = ap.dot(&self.grad_c);
        [1.0 - wb - wc, wb, wc]
    }

    /// Signed distance of `p` to the plane, positive on the side of the normal.
    #[inline]
    pub(crate) fn signed_distance(&self, p: &Vec3) -> Real {
        (p - self.a).dot(&self.normal)
    }

    /// The point of the plane with weights `w`: `a + wb (b - a) + wc (c - a)`.
    #[inline]
    pub(crate) fn point(&self, w: &[Real; 3]) -> Vec3 {
        self.a + self.ab * w[1] + self.ac * w[2]
    }
}

/// Barycentric coordinates `[wa, wb, wc]` of the orthogonal projection `P'` of `p` onto the plane
/// of the triangle `(a, b, c)`, unclamped (negative outside the triangle), or `None` when the
/// triangle is degenerate (height below `1e-8` times its longest edge).
///
/// Paper eq 15 with `N1 = a`, `N2 = b`, `N3 = c`: `P' - a = p1 (b - a) + p2 (c - a)`, and
/// ```text
/// p1 = (|ac|² (ab·ap) - (ab·ac)(ac·ap)) / (|ab|² |ac|² - (ab·ac)²)
/// p2 = (|ab|² (ac·ap) - (ab·ac)(ab·ap)) / (|ab|² |ac|² - (ab·ac)²)
/// ```
/// (the paper prints `‖·‖` for the squared norms). So `P' = p3 a + p1 b + p2 c` with
/// `p3 = 1 - p1 - p2`, and the weights returned are `[wa, wb, wc] = [p3, p1, p2]`: they sum to 1
/// and reproduce `P' = wa a + wb b + wc c` (YADE's `node1 <- p1` mapping is the bug of
/// yade-grid-pfacet.md §6.3). By Lagrange's identity the same ratios are evaluated as
/// `p1 = n · (ap × ac) / |n|²`, `p2 = n · (ab × ap) / |n|²` with `n = ab × ac`, which keeps its
/// accuracy for thin triangles (the Gram determinant above cancels catastrophically).
pub fn barycentric_coordinates(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> Option<[Real; 3]> {
    TriangleFrame::new(a, b, c).map(|f| f.weights(p))
}

/// Location and weights on the triangle of a point on edge `edge` (0 = ab, 1 = bc, 2 = ca) given
/// by its location on that edge as a segment from its first vertex to its second.
pub(crate) fn triangle_location_on_edge(
    edge: usize,
    on_edge: SegmentLocation,
) -> (TriangleLocation, [Real; 3]) {
    let (first, second) = TriangleLocation::edge_vertices(edge);
    let mut weights = [0.0; 3];
    match on_edge {
        SegmentLocation::OnVertex(end) => {
            let vertex = if end == 0 { first } else { second };
            weights[vertex] = 1.0;
            (TriangleLocation::OnVertex(vertex), weights)
        }
        SegmentLocation::OnEdge { t } => {
            weights[first] = 1.0 - t;
            weights[second] = t;
            (TriangleLocation::OnEdge { edge, t }, weights)
        }
    }
}

/// The triangle's vertices as an array indexed by vertex number.
#[inline]
pub(crate) fn vertices<'a>(a: &'a Vec3, b: &'a Vec3, c: &'a Vec3) -> [&'a Vec3; 3] {
    [a, b, c]
}

/// Projects `p` onto the triangle `(a, b, c)`.
///
/// Region classification equivalent to Ericson's (Real-Time Collision Detection §5.1.5), done in
/// two steps: the unclamped weights `w` of the plane projection `P'` (eq 15,
/// [`barycentric_coordinates`]) decide the face region, `w_i > 0` for all `i` (then
/// `point = P'`, `OnFace`). Otherwise `P'` is outside (or on the boundary) and the closest point
/// of the triangle is the closest point of its boundary; it lies on an edge whose supporting
/// line separates `P'` from the triangle, i.e. an edge whose opposite weight is `<= 0`, so only
/// those edges are projected ([`project_point_segment`]), which covers the three edge regions
/// and the three vertex regions (a clamped edge parameter is a vertex, with one-hot weights).
/// A degenerate triangle (collinear or coincident vertices, height `<= 1e-8` times its longest
/// edge) is its three edges: the same boundary search over all of them, never NaN.
pub fn project_point_triangle(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> PointTriangleProjection {
    let mut candidate_edges = [true; 3];
    if let Some(frame) = TriangleFrame::new(a, b, c) {
        let w = frame.weights(p);
        if w.iter().all(|&x| x > 0.0) {
            return PointTriangleProjection {
                point: frame.point(&w),
                weights: w,
                location: TriangleLocation::OnFace,
            };
        }
        for (edge, candidate) in candidate_edges.iter_mut().enumerate() {
            // The vertex opposite edge `e` is `(e + 2) % 3`.
            *candidate = w[(edge + 2) % 3] <= 0.0;
        }
    }
    let v = vertices(a, b, c);
    let mut best: Option<(Real, PointTriangleProjection)> = None;
    for edge in (0..3).filter(|&e| candidate_edges[e]) {
        let (i, j) = TriangleLocation::edge_vertices(edge);
        let proj = project_point_segment(p, v[i], v[j]);
        let d2 = (proj.point - p).norm_squared();
        if best.is_none_or(|(best_d2, _)| d2 < best_d2) {
            let (location, weights) = triangle_location_on_edge(edge, proj.location);
            best = Some((d2, PointTriangleProjection { point: proj.point, weights, location }));
        }
    }
    // At least one edge is a candidate: the weights sum to 1, so they are not all positive here.
    best.map(|(_, proj)| proj).unwrap_or(PointTriangleProjection {
        point: *a,
        weights: [1.0, 0.0, 0.0],
        location: TriangleLocation::OnVertex(0),
    })
}

/// Helpers shared by the tests of the triangle modules: a brute-force minimiser and checks of
/// a (point, weights, location) answer.
#[cfg(test)]
pub(crate) mod test_support {
    use super::*;

    /// The point of the triangle at square parameters `(u, v) ∈ [0, 1]²`, folded onto the
    /// triangle by reflecting across `u + v = 1` (a continuous map with no spurious minima).
    pub(crate) fn triangle_point(t: &[Vec3; 3], u: Real, v: Real) -> Vec3 {
        let (u, v) = if u + v > 1.0 { (1.0 - v, 1.0 - u) } else { (u, v) };
        t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v
    }

    /// Brute-force minimum of `f` over `[0, 1]^N`: a grid of `grid + 1` values per axis, then
    /// local refinement by pattern search over the `3^N` neighbours at halving steps. `f` is a
    /// squared distance between points depending affinely (piecewise) on the parameters.
    pub(crate) fn oracle_min<const N: usize>(grid: usize, f: impl Fn(&[Real; N]) -> Real) -> Real {
        let (mut best, mut best_f) = ([0.0; N], Real::INFINITY);
        let total = (grid + 1).pow(N as u32);
        for idx in 0..total {
            let mut z = [0.0; N];
            let mut k = idx;
            for zi in z.iter_mut() {
                *zi = (k % (grid + 1)) as Real / grid as Real;
                k /= grid + 1;
            }
            let fz = f(&z);
            if fz < best_f {
                (best, best_f) = (z, fz);
            }
        }
        let mut step = 1.0 / grid as Real;
        while step > 1e-14 {
            for _ in 0..64 {
                let mut improved = false;
                for idx in 0..3usize.pow(N as u32) {
                    let mut z = best;
                    let mut k = idx;
                    for zi in z.iter_mut() {
                        *zi = (*zi + step * ((k % 3) as Real - 1.0)).clamp(0.0, 1.0);
                        k /= 3;
                    }
                    let fz = f(&z);
                    if fz < best_f {
                        (best, best_f, improved) = (z, fz, true);
                    }
                }
                if !improved {
                    break;
                }
            }
            step *= 0.5;
        }
        best_f
    }

    /// Exact brute-force distance between the convex hulls of `x` and `y` (1 to 3 points each):
    /// for every pair of features (non-empty vertex subsets), the least-squares closest points of
    /// their affine hulls (SVD pseudo-inverse, so rank-deficient features are fine), with the
    /// parameters clamped back onto the features. Every candidate is a pair of actual points,
    /// and the true minimum is the unconstrained minimum of some feature pair, so the smallest
    /// candidate distance is the distance up to round-off.
    pub(crate) fn oracle_feature_pairs(x: &[Vec3], y: &[Vec3]) -> Real {
        use nalgebra::{DMatrix, DVector};
        let subsets = |n: usize| -> Vec<Vec<usize>> {
            (1..(1usize << n)).map(|m| (0..n).filter(|&i| m & (1 << i) != 0).collect()).collect()
        };
        // The point of feature `f` of `v` at affine parameters `alpha` (clamped onto the feature).
        let point = |v: &[Vec3], f: &[usize], alpha: &[Real]| {
            let mut a: Vec<Real> = alpha.iter().map(|&t| t.max(0.0)).collect();
            let sum: Real = a.iter().sum();
            if sum > 1.0 {
                a.iter_mut().for_each(|t| *t /= sum);
            }
            f[1..].iter().zip(&a).fold(v[f[0]], |acc, (&i, &t)| acc + (v[i] - v[f[0]]) * t)
        };
        let mut best = Real::INFINITY;
        for f in subsets(x.len()) {
            for g in subsets(y.len()) {
                let cols: Vec<DVector<Real>> = f[1..]
                    .iter()
                    .map(|&i| x[i] - x[f[0]])
                    .chain(g[1..].iter().map(|&j| y[g[0]] - y[j]))
                    .map(|c| DVector::from_column_slice(c.as_slice()))
                    .collect();
                let params = if cols.is_empty() {
                    Vec::new()
                } else {
                    let j = DMatrix::from_columns(&cols);
                    let rhs = DVector::from_column_slice((y[g[0]] - x[f[0]]).as_slice());
                    let svd = j.svd(true, true);
                    let tol = 1e-13 * svd.singular_values.max();
                    match svd.solve(&rhs, tol) {
                        Ok(sol) => sol.iter().copied().collect(),
                        Err(_) => continue,
                    }
                };
                let (pa, pb) = params.split_at(f.len() - 1);
                let d = (point(x, &f, pa) - point(y, &g, pb)).norm();
                best = best.min(d);
            }
        }
        best
    }

    /// Checks a (point, weights, location) answer on the triangle `t`: weights `>= 0`, sum 1,
    /// reproduce the point, and agree with the location.
    pub(crate) fn check_on_triangle(
        t: &[Vec3; 3],
        point: &Vec3,
        w: &[Real; 3],
        location: TriangleLocation,
        tol: Real,
    ) -> Result<(), String> {
        let sum = w[0] + w[1] + w[2];
        let rebuilt = t[0] * w[0] + t[1] * w[1] + t[2] * w[2];
        let size = (t[1] - t[0]).norm() + (t[2] - t[0]).norm() + t[0].norm();
        let ok = w.iter().all(|&x| x >= 0.0)
            && (sum - 1.0).abs() <= 1e-12
            && (rebuilt - point).norm() <= tol * size.max(Real::MIN_POSITIVE);
        if !ok {
            return Err(format!("weights {w:?} point {point:?} rebuilt {rebuilt:?}"));
        }
        let consistent = match location {
            TriangleLocation::OnFace => w.iter().all(|&x| x > 0.0),
            TriangleLocation::OnVertex(i) => (0..3).all(|j| w[j] == if i == j { 1.0 } else { 0.0 }),
            TriangleLocation::OnEdge { edge, t } => {
                let (i, j) = TriangleLocation::edge_vertices(edge);
                w[(edge + 2) % 3] == 0.0 && w[i] == 1.0 - t && w[j] == t && t > 0.0 && t < 1.0
            }
        };
        if consistent {
            Ok(())
        } else {
            Err(format!("location {location:?} inconsistent with weights {w:?}"))
        }
    }

    /// The location on the triangle permuted by `perm` (new vertex `k` is old vertex
    /// `perm[k]`), expressed with the old numbering.
    pub(crate) fn unpermute_location(
        location: TriangleLocation,
        perm: [usize; 3],
    ) -> TriangleLocation {
        match location {
            TriangleLocation::OnFace => TriangleLocation::OnFace,
            TriangleLocation::OnVertex(k) => TriangleLocation::OnVertex(perm[k]),
            TriangleLocation::OnEdge { edge, t } => {
                let (i, j) = TriangleLocation::edge_vertices(edge);
                let (oi, oj) = (perm[i], perm[j]);
                let old_edge = (0..3).find(|&e| {
                    let (a, b) = TriangleLocation::edge_vertices(e);
                    (a, b) == (oi, oj) || (a, b) == (oj, oi)
                });
                let old_edge = old_edge.unwrap_or(0);
                let forward = TriangleLocation::edge_vertices(old_edge).0 == oi;
                TriangleLocation::OnEdge { edge: old_edge, t: if forward { t } else { 1.0 - t } }
            }
        }
    }

    /// The six permutations of three vertices.
    pub(crate) const PERMUTATIONS: [[usize; 3]; 6] =
        [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]];

    /// The location at weights `w` snapped to exact zeros and ones, for comparing locations that
    /// carry an edge parameter up to round-off.
    pub(crate) fn same_location(x: TriangleLocation, y: TriangleLocation, tol: Real) -> bool {
        match (x, y) {
            (
                TriangleLocation::OnEdge { edge: e, t },
                TriangleLocation::OnEdge { edge: f, t: s },
            ) => e == f && (t - s).abs() <= tol,
            _ => x == y,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::test_support::*;
    use super::*;
    use crate::proptest_support::{rotation, scale, triangle, unit_vec3, vec3};
    use proptest::prelude::*;

    fn oracle_distance(p: &Vec3, t: &[Vec3; 3]) -> Real {
        let sampled =
            oracle_min::<2>(40, |z| (triangle_point(t, z[0], z[1]) - p).norm_squared()).sqrt();
        sampled.min(oracle_feature_pairs(&[*p], t))
    }

    fn check(p: &Vec3, t: &[Vec3; 3], tol: Real) -> Result<PointTriangleProjection, TestCaseError> {
        let r = project_point_triangle(p, &t[0], &t[1], &t[2]);
        check_on_triangle(t, &r.point, &r.weights, r.location, tol).map_err(TestCaseError::fail)?;
        let (d, oracle) = ((r.point - p).norm(), oracle_distance(p, t));
        let size = (t[1] - t[0]).norm().max((t[2] - t[0]).norm()) + (p - t[0]).norm();
        prop_assert!(d <= oracle + 1e-12 * size, "d {} > oracle {}", d, oracle);
        prop_assert!(d >= oracle - 1e-9 * size, "d {} < oracle {}", d, oracle);
        Ok(r)
    }

    fn unit_right_triangle() -> [Vec3; 3] {
        [Vec3::zeros(), Vec3::x(), Vec3::y()]
    }

    #[test]
    fn yade_weights_case() {
        // YADE maps p1 to node1; the weights of (0.1, 0.1) are 0.8 on a, not on c.
        let t = unit_right_triangle();
        let p = Vec3::new(0.1, 0.1, 0.7);
        let w = barycentric_coordinates(&p, &t[0], &t[1], &t[2]).unwrap();
        assert!(
            (w[0] - 0.8).abs() < 1e-15 && (w[1] - 0.1).abs() < 1e-15 && (w[2] - 0.1).abs() < 1e-15
        );
        let r = project_point_triangle(&p, &t[0], &t[1], &t[2]);
        assert_eq!(r.location, TriangleLocation::OnFace);
        assert_eq!(r.weights, w);
        let rebuilt = t[0] * w[0] + t[1] * w[1] + t[2] * w[2];
        assert!((rebuilt - Vec3::new(0.1, 0.1, 0.0)).norm() < 1e-15);
        assert!((r.point - Vec3::new(0.1, 0.1, 0.0)).norm() < 1e-15);
    }

    #[test]
    fn barycentric_coordinates_are_unclamped_and_none_when_degenerate() {
        let t = unit_right_triangle();
        let w = barycentric_coordinates(&Vec3::new(2.0, -1.0, 5.0), &t[0], &t[1], &t[2]).unwrap();
        assert!(
            (w[0] - 0.0).abs() < 1e-15 && (w[1] - 2.0).abs() < 1e-15 && (w[2] + 1.0).abs() < 1e-15
        );
        let (a, b) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(2.0, 0.0, 1.0));
        assert_eq!(barycentric_coordinates(&Vec3::zeros(), &a, &b, &(a + (b - a) * 3.0)), None);
        assert_eq!(barycentric_coordinates(&Vec3::zeros(), &a, &a, &b), None);
        assert_eq!(barycentric_coordinates(&Vec3::zeros(), &a, &a, &a), None);
        // Relative, not absolute: a 1 µm triangle is fine.
        let k = 1e-6;
        assert!(barycentric_coordinates(&Vec3::zeros(), &(t[0] * k), &(t[1] * k), &(t[2] * k))
            .is_some());
    }

    /// In-plane outward normal of edge `e` (away from the opposite vertex), unit length.
    fn outward(t: &[Vec3; 3], e: usize) -> Vec3 {
        let (i, j) = TriangleLocation::edge_vertices(e);
        let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
        (t[j] - t[i]).cross(&n).normalize()
    }

    /// A well-shaped triangle: edges at least `range / 4`, angles at least ~15°.
    fn fat_triangle(range: Real) -> impl Strategy<Value = [Vec3; 3]> {
        triangle(range).prop_map(|(a, b, c)| [a, b, c]).prop_filter("well shaped", |t| {
            let n = (t[1] - t[0]).cross(&(t[2] - t[0])).norm();
            let l2 = (0..3).map(|e| (t[(e + 1) % 3] - t[e]).norm_squared()).fold(0.0, Real::max);
            n > 0.25 * l2 && l2.sqrt() > 0.25
        })
    }

    fn check_constructed(
        p: &Vec3,
        t: &[Vec3; 3],
        expected: &Vec3,
        location: TriangleLocation,
    ) -> Result<(), TestCaseError> {
        let r = check(p, t, 1e-12)?;
        prop_assert!(
            (r.point - expected).norm() <= 1e-12 * (1.0 + p.norm()),
            "{:?} vs {:?}",
            r.point,
            expected
        );
        prop_assert!(
            same_location(r.location, location, 1e-12),
            "{:?} vs {:?}",
            r.location,
            location
        );
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// The seven regions, each built from a feature point plus an offset in its normal cone.
        #[test]
        fn constructed_regions(t in fat_triangle(1.0), w in (0.05..1.0_f64, 0.05..1.0_f64, 0.05..1.0_f64),
                               h in -1.0..1.0_f64, out in (0.01..1.0_f64, 0.01..1.0_f64), s in 0.05..0.95_f64) {
            let n = (t[1] - t[0]).cross(&(t[2] - t[0])).normalize();
            // Face.
            let sum = w.0 + w.1 + w.2;
            let q = (t[0] * w.0 + t[1] * w.1 + t[2] * w.2) / sum;
            check_constructed(&(q + n * h), &t, &q, TriangleLocation::OnFace)?;
            for e in 0..3 {
                // Edge e at parameter s, pushed out along its outward normal.
                let (i, j) = TriangleLocation::edge_vertices(e);
                let q = t[i] + (t[j] - t[i]) * s;
                check_constructed(&(q + outward(&t, e) * out.0 + n * h), &t, &q, TriangleLocation::OnEdge { edge: e, t: s })?;
                // Vertex j: the cone spanned by the outward normals of its two edges.
                let next = (e + 1) % 3;
                let p = t[j] + outward(&t, e) * out.0 + outward(&t, next) * out.1 + n * h;
                check_constructed(&p, &t, &t[j], TriangleLocation::OnVertex(j))?;
            }
        }

        #[test]
        fn matches_oracle_and_is_consistent(p in vec3(1.5), (a, b, c) in triangle(1.0)) {
            check(&p, &[a, b, c], 1e-12)?;
        }

        #[test]
        fn vertex_permutation_permutes_weights(p in vec3(1.5), (a, b, c) in triangle(1.0), k in 0..6usize) {
            let t = [a, b, c];
            let perm = PERMUTATIONS[k];
            let r = project_point_triangle(&p, &t[0], &t[1], &t[2]);
            let q = project_point_triangle(&p, &t[perm[0]], &t[perm[1]], &t[perm[2]]);
            prop_assert!((r.point - q.point).norm() <= 1e-12);
            for i in 0..3 {
                prop_assert!((q.weights[i] - r.weights[perm[i]]).abs() <= 1e-10);
            }
            prop_assert!(same_location(unpermute_location(q.location, perm), r.location, 1e-10),
                "{:?} {:?}", q.location, r.location);
        }

        #[test]
        fn rigid_motion_and_scale_invariance(p in vec3(1.5), (a, b, c) in triangle(1.0),
                                             shift in vec3(1e3), rot in rotation(), k in scale()) {
            let m = |x: &Vec3| (rot * x + shift) * k;
            let r = project_point_triangle(&p, &a, &b, &c);
            let q = project_point_triangle(&m(&p), &m(&a), &m(&b), &m(&c));
            let d = (r.point - p).norm() * k;
            prop_assert!(((q.point - m(&p)).norm() - d).abs() <= 1e-9 * k);
            prop_assert!((m(&r.point) - q.point).norm() <= 1e-8 * k);
            for i in 0..3 {
                prop_assert!((q.weights[i] - r.weights[i]).abs() <= 1e-6);
            }
        }

        #[test]
        fn distance_is_lipschitz(p in vec3(1.5), (a, b, c) in triangle(1.0), dir in unit_vec3(), which in 0..4usize) {
            let eps = 1e-3;
            let dist = |x: &[Vec3; 4]| (project_point_triangle(&x[0], &x[1], &x[2], &x[3]).point - x[0]).norm();
            let x = [p, a, b, c];
            let mut y = x;
            y[which] += dir * eps;
            prop_assert!((dist(&y) - dist(&x)).abs() <= eps * (1.0 + 1e-9));
        }

        #[test]
        fn degenerate_triangles_fall_back_to_edges(p in vec3(1.5), a in vec3(1.0), b in vec3(1.0),
                                                  u in -1.0..2.0_f64, kind in 0..4usize, k in scale()) {
            let t = match kind {
                0 => [a, b, a + (b - a) * u],                        // collinear
                1 => [a, a, b],                                      // two coincident
                2 => [a, a, a],                                      // all three coincident
                _ => [a, b, a + (b - a) * u + (b - a).cross(&Vec3::z()) * 1e-9], // aspect 1e-9
            };
            let (p, t) = (p * k, [t[0] * k, t[1] * k, t[2] * k]);
            let r = check(&p, &t, 1e-12)?;
            prop_assert!(r.location != TriangleLocation::OnFace || kind == 3);
        }
    }

    #[test]
    fn millimetre_and_kilometre_scales() {
        for k in [1e-3, 1e3] {
            let t = [
                Vec3::new(0.0, 0.0, 0.0) * k,
                Vec3::new(1.0, 0.0, 0.0) * k,
                Vec3::new(0.0, 1.0, 0.0) * k,
            ];
            let r = project_point_triangle(&(Vec3::new(0.2, 0.3, 0.5) * k), &t[0], &t[1], &t[2]);
            assert_eq!(r.location, TriangleLocation::OnFace);
            assert!((r.point - Vec3::new(0.2, 0.3, 0.0) * k).norm() < 1e-15 * k);
            let r = project_point_triangle(&(Vec3::new(0.75, 0.75, 0.5) * k), &t[0], &t[1], &t[2]);
            assert_eq!(r.location, TriangleLocation::OnEdge { edge: 1, t: 0.5 });
            let r = project_point_triangle(&(Vec3::new(-1.0, -1.0, 0.0) * k), &t[0], &t[1], &t[2]);
            assert_eq!(
                (r.location, r.weights, r.point),
                (TriangleLocation::OnVertex(0), [1.0, 0.0, 0.0], t[0])
            );
        }
    }

    #[test]
    fn very_thin_triangle_is_exact_along_its_length() {
        let t = [Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.5, 1e-9, 0.0)];
        let r = project_point_triangle(&Vec3::new(0.3, 0.5, 0.2), &t[0], &t[1], &t[2]);
        assert!((r.point - Vec3::new(0.3, 1e-9 * 0.6, 0.0)).norm() < 1e-8);
        let r = project_point_triangle(&Vec3::new(0.3, -0.5, 0.2), &t[0], &t[1], &t[2]);
        assert_eq!(r.location, TriangleLocation::OnEdge { edge: 0, t: 0.3 });
    }
}
