//! Axis-aligned bounding boxes: the broad-phase boxes of spheres, connections and PFacets.

use crate::{Real, Vec3};

/// A closed axis-aligned box `[mins, maxs]`.
///
/// A box with some `mins[i] > maxs[i]` is empty; [`Aabb::empty`] is the neutral element of
/// [`Aabb::merged`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Aabb {
    /// Lower corner.
    pub mins: Vec3,
    /// Upper corner.
    pub maxs: Vec3,
}

impl Aabb {
    /// The box with corners `mins` and `maxs` (not reordered: `mins > maxs` gives an empty box).
    pub const fn new(mins: Vec3, maxs: Vec3) -> Self {
        Self { mins, maxs }
    }

    /// The empty box, `mins = +∞`, `maxs = -∞`: it intersects and contains nothing, and
    /// `Aabb::empty().merged(&b) == b`.
    pub fn empty() -> Self {
        Self::new(Vec3::repeat(Real::INFINITY), Vec3::repeat(Real::NEG_INFINITY))
    }

    /// The smallest box containing all `points` (empty for no points).
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a Vec3>) -> Self {
        points.into_iter().fold(Self::empty(), |b, p| Self::new(b.mins.inf(p), b.maxs.sup(p)))
    }

    /// Whether the box contains no point (`mins[i] > maxs[i]` on some axis).
    pub fn is_empty(&self) -> bool {
        (0..3).any(|i| self.mins[i] > self.maxs[i])
    }

    /// The box grown by `margin` on every side: `[mins - margin, maxs + margin]` (the Verlet
    /// margin of the broad phase; a negative margin shrinks it).
    pub fn loosened(&self, margin: Real) -> Self {
        let m = Vec3::repeat(margin);
        Self::new(self.mins - m, self.maxs + m)
    }

    /// Whether the two closed boxes share a point (boxes that touch on a face intersect).
    pub fn intersects(&self, other: &Self) -> bool {
        (0..3).all(|i| self.mins[i] <= other.maxs[i] && other.mins[i] <= self.maxs[i])
    }

    /// The smallest box containing both boxes.
    pub fn merged(&self, other: &Self) -> Self {
        Self::new(self.mins.inf(&other.mins), self.maxs.sup(&other.maxs))
    }

    /// Whether `p` lies in the closed box.
    pub fn contains_point(&self, p: &Vec3) -> bool {
        (0..3).all(|i| self.mins[i] <= p[i] && p[i] <= self.maxs[i])
    }

    /// The centre `(mins + maxs) / 2` (NaN for [`Aabb::empty`]).
    pub fn center(&self) -> Vec3 {
        (self.mins + self.maxs) * 0.5
    }

    /// The half extents `(maxs - mins) / 2` (negative for an empty box).
    pub fn half_extents(&self) -> Vec3 {
        (self.maxs - self.mins) * 0.5
    }
}

/// The box of the ball of centre `c` and radius `r`: `[c - r, c + r]` on each axis.
pub fn aabb_sphere(c: &Vec3, r: Real) -> Aabb {
    aabb_sphere_swept_points(&[*c], r)
}

/// The box of the segment `[a, b]` swept by a ball of radius `r` (a cylinder with spherical
/// caps, a connection): `[min(a, b) - r, max(a, b) + r]` per axis. Exact, since the support
/// function of a Minkowski sum is the sum of the support functions: the box touches the shape on
/// each face, at the cap of the end that is extreme along that axis.
pub fn aabb_swept_segment(a: &Vec3, b: &Vec3, r: Real) -> Aabb {
    aabb_sphere_swept_points(&[*a, *b], r)
}

/// The box of the triangle `(a, b, c)` swept by a ball of radius `r` (a PFacet with its
/// connections and nodes): `[min(a, b, c) - r, max(a, b, c) + r]` per axis, exact for the same
/// reason as [`aabb_swept_segment`].
pub fn aabb_swept_triangle(a: &Vec3, b: &Vec3, c: &Vec3, r: Real) -> Aabb {
    aabb_sphere_swept_points(&[*a, *b, *c], r)
}

/// The box of the convex hull of `points` swept by a ball of radius `r`.
fn aabb_sphere_swept_points(points: &[Vec3], r: Real) -> Aabb {
    Aabb::from_points(points).loosened(r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::proptest_support::{triangle, unit_vec3, vec3};
    use proptest::prelude::*;

    /// A point of the ball of radius `r`: `r u^(1/3)` times a unit vector, with `u` in [0, 1].
    fn in_ball(dir: Vec3, u: Real, r: Real) -> Vec3 {
        dir * (r * u.cbrt())
    }

    /// Checks that the box's faces are the support function of the swept hull of `points`,
    /// computed independently as `max over vertices of ±p[i]` plus `r`, and that the point of the
    /// shape realising it lies in the box (the box touches the shape on each face).
    fn check_tight(bx: &Aabb, points: &[Vec3], r: Real) -> Result<(), TestCaseError> {
        for i in 0..3 {
            for sign in [-1.0, 1.0] {
                let v =
                    points.iter().max_by(|p, q| (sign * p[i]).total_cmp(&(sign * q[i]))).unwrap();
                let mut touch = *v;
                touch[i] += sign * r;
                let face = if sign > 0.0 { bx.maxs[i] } else { bx.mins[i] };
                let tol = 4.0 * Real::EPSILON * (touch[i].abs() + r);
                prop_assert!((touch[i] - face).abs() <= tol, "axis {i} face {face} touch {touch}");
                prop_assert!(bx.loosened(tol).contains_point(&touch));
            }
        }
        Ok(())
    }

    #[test]
    fn aabb_empty_is_neutral_and_disjoint() {
        let e = Aabb::empty();
        let b = Aabb::new(Vec3::new(-1., 0., 2.), Vec3::new(1., 3., 2.5));
        assert!(e.is_empty() && !b.is_empty());
        assert_eq!(e.merged(&b), b);
        assert_eq!(b.merged(&e), b);
        assert!(!e.intersects(&b) && !b.intersects(&e) && !e.intersects(&e));
        assert!(!e.contains_point(&Vec3::zeros()));
        assert_eq!(Aabb::from_points(&[]), e);
    }

    #[test]
    fn aabb_touching_boxes_intersect() {
        let a = Aabb::new(Vec3::zeros(), Vec3::repeat(1.0));
        let b = Aabb::new(Vec3::new(1.0, 0.5, -3.0), Vec3::new(2.0, 0.7, 0.0));
        assert!(a.intersects(&b) && b.intersects(&a));
        let c = Aabb::new(Vec3::new(1.0 + 1e-12, 0.5, -3.0), Vec3::new(2.0, 0.7, 0.0));
        assert!(!a.intersects(&c) && !c.intersects(&a));
        assert!(a.loosened(1e-12).intersects(&c));
        // Overlapping on two axes only.
        let d = Aabb::new(Vec3::new(0.5, 0.5, 1.5), Vec3::new(0.7, 0.7, 2.0));
        assert!(!a.intersects(&d));
    }

    #[test]
    fn aabb_center_half_extents_and_contains() {
        let b = Aabb::new(Vec3::new(-1., 2., 0.), Vec3::new(3., 4., 1.));
        assert_eq!(b.center(), Vec3::new(1., 3., 0.5));
        assert_eq!(b.half_extents(), Vec3::new(2., 1., 0.5));
        assert!(b.contains_point(&Vec3::new(3., 2., 0.5)));
        assert!(!b.contains_point(&Vec3::new(3.000001, 2., 0.5)));
        assert_eq!(
            b.loosened(0.5),
            Aabb::new(Vec3::new(-1.5, 1.5, -0.5), Vec3::new(3.5, 4.5, 1.5))
        );
    }

    #[test]
    fn aabb_sphere_segment_triangle_known() {
        let s = aabb_sphere(&Vec3::new(1., 2., 3.), 0.5);
        assert_eq!(s, Aabb::new(Vec3::new(0.5, 1.5, 2.5), Vec3::new(1.5, 2.5, 3.5)));
        let g = aabb_swept_segment(&Vec3::new(1., 0., 0.), &Vec3::new(-1., 2., 0.), 0.25);
        assert_eq!(g, Aabb::new(Vec3::new(-1.25, -0.25, -0.25), Vec3::new(1.25, 2.25, 0.25)));
        let t = aabb_swept_triangle(&Vec3::zeros(), &Vec3::x(), &Vec3::y(), 1.0);
        assert_eq!(t, Aabb::new(Vec3::repeat(-1.0), Vec3::new(2., 2., 1.)));
        // Zero radius: the box of the vertices.
        let p = aabb_swept_segment(&Vec3::x(), &Vec3::x(), 0.0);
        assert_eq!(p, Aabb::new(Vec3::x(), Vec3::x()));
        assert!(!p.is_empty());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn aabb_sphere_contains_and_is_tight(
            c in vec3(10.0), r in 0.0..3.0_f64, dir in unit_vec3(), u in 0.0..=1.0_f64,
        ) {
            let bx = aabb_sphere(&c, r);
            prop_assert!(bx.contains_point(&(c + in_ball(dir, u, r))));
            check_tight(&bx, &[c], r)?;
        }

        #[test]
        fn aabb_swept_segment_contains_and_is_tight(
            a in vec3(10.0), b in vec3(10.0), r in 0.0..3.0_f64,
            samples in prop::collection::vec((0.0..=1.0_f64, unit_vec3(), 0.0..=1.0_f64), 16),
        ) {
            let bx = aabb_swept_segment(&a, &b, r);
            for (t, dir, u) in samples {
                let p = a + (b - a) * t + in_ball(dir, u, r);
                prop_assert!(bx.loosened(1e-14 * 20.0).contains_point(&p), "{p} not in {bx:?}");
            }
            check_tight(&bx, &[a, b], r)?;
        }

        #[test]
        fn aabb_swept_triangle_contains_and_is_tight(
            (a, b, c) in triangle(10.0), r in 0.0..3.0_f64,
            samples in prop::collection::vec(
                (0.0..=1.0_f64, 0.0..=1.0_f64, unit_vec3(), 0.0..=1.0_f64),
                16,
            ),
        ) {
            let bx = aabb_swept_triangle(&a, &b, &c, r);
            for (x, y, dir, u) in samples {
                let (x, y) = if x + y > 1.0 { (1.0 - x, 1.0 - y) } else { (x, y) };
                let p = a + (b - a) * x + (c - a) * y + in_ball(dir, u, r);
                prop_assert!(bx.loosened(1e-14 * 40.0).contains_point(&p), "{p} not in {bx:?}");
            }
            check_tight(&bx, &[a, b, c], r)?;
        }

        #[test]
        fn aabb_merge_and_intersection_agree_with_points(
            (a0, a1) in (vec3(5.0), vec3(5.0)), (b0, b1) in (vec3(5.0), vec3(5.0)), p in vec3(6.0),
        ) {
            let (a, b) = (Aabb::from_points(&[a0, a1]), Aabb::from_points(&[b0, b1]));
            let m = a.merged(&b);
            for i in 0..3 {
                prop_assert_eq!(m.mins[i], a0[i].min(a1[i]).min(b0[i]).min(b1[i]));
                prop_assert_eq!(m.maxs[i], a0[i].max(a1[i]).max(b0[i]).max(b1[i]));
            }
            // Closed boxes intersect iff they share a point: the centre of their overlap.
            let overlap = Aabb::new(a.mins.sup(&b.mins), a.maxs.inf(&b.maxs));
            prop_assert_eq!(a.intersects(&b), b.intersects(&a));
            prop_assert_eq!(a.intersects(&b), !overlap.is_empty());
            if a.intersects(&b) {
                let x = overlap.center();
                prop_assert!(a.contains_point(&x) && b.contains_point(&x));
            }
            if a.contains_point(&p) && b.contains_point(&p) {
                prop_assert!(a.intersects(&b));
            }
        }
    }
}
