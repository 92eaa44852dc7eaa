//! The point of a triangle closest to a query point, by Ericson's region tests (Real-Time
//! Collision Detection §5.1.5): the vertex, edge or face region of the point from six dot
//! products, no square root and no frame. It gives the point alone, for a distance bound
//! (the contact prefilter's sphere beside a PFacet); [`project_point_triangle`] gives the
//! kernel's projection with its weights and feature, robust on thin triangles, and costs
//! more than twice as much (a frame with a square root, then up to three edge projections:
//! 44 ns a call against 19 for the prefilter's whole test, by perf on the membrane of 10⁵
//! PFacets).
//!
//! [`project_point_triangle`]: crate::project_point_triangle

use crate::Vec3;

/// The point of the triangle `(a, b, c)` closest to `p` (Ericson §5.1.5, his order of the
/// regions: a, b, edge ab, c, edge ac, edge bc, face). The face region's weights come from
/// Gram determinants, which lose accuracy on thin triangles: a caller that needs the distance
/// to within round-off should keep to triangles of some height (the prefilter asks 10⁻⁴ of the
/// longest edge) or use [`crate::project_point_triangle`]. NaN in, NaN out; a degenerate
/// triangle in the face region gives NaN or ±∞.
#[inline]
pub fn closest_point_triangle(p: &Vec3, a: &Vec3, b: &Vec3, c: &Vec3) -> Vec3 {
    let (ab, ac, bc) = (b - a, c - a, c - b);
    let ap = p - a;
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    let (vc, vb, va) = (d1 * d4 - d3 * d2, d5 * d2 - d1 * d6, d3 * d6 - d5 * d4);
    if d1 <= 0.0 && d2 <= 0.0 {
        *a
    } else if d3 >= 0.0 && d4 <= d3 {
        *b
    } else if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        a + ab * (d1 / (d1 - d3))
    } else if d6 >= 0.0 && d5 <= d6 {
        *c
    } else if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        a + ac * (d2 / (d2 - d6))
    } else if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        b + bc * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))
    } else {
        let denom = 1.0 / (va + vb + vc);
        a + ab * (vb * denom) + ac * (vc * denom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::proptest_support::{triangle, vec3};
    use crate::{project_point_triangle, Real};
    use proptest::prelude::*;

    proptest! {
        /// On triangles at least 10⁻² high over their longest edge, the distance to the
        /// closest point is the kernel's projection's to round-off, from any point.
        #[test]
        fn the_distance_is_the_projections((a, b, c) in triangle(1.0), p in vec3(3.0)) {
            let l2 = [b - a, c - a, c - b].iter().map(|e| e.norm_squared()).fold(0.0, Real::max);
            prop_assume!((b - a).cross(&(c - a)).norm_squared() > 1e-4 * l2 * l2);
            let exact = (project_point_triangle(&p, &a, &b, &c).point - p).norm();
            let here = (closest_point_triangle(&p, &a, &b, &c) - p).norm();
            prop_assert!((here - exact).abs() <= 1e-12 * (1.0 + p.norm()), "{here} {exact}");
        }
    }

    /// The seven regions of the unit right triangle.
    #[test]
    fn each_region_gives_its_feature() {
        let (a, b, c) = (Vec3::zeros(), Vec3::x(), Vec3::y());
        let at =
            |x: Real, y: Real, z: Real| closest_point_triangle(&Vec3::new(x, y, z), &a, &b, &c);
        assert_eq!(at(-1.0, -1.0, 0.3), a);
        assert_eq!(at(2.0, -0.5, 0.0), b);
        assert_eq!(at(-0.5, 2.0, 0.0), c);
        assert_eq!(at(0.25, -1.0, 0.0), Vec3::new(0.25, 0.0, 0.0));
        assert_eq!(at(-1.0, 0.25, 0.0), Vec3::new(0.0, 0.25, 0.0));
        assert_eq!(at(1.0, 1.0, 0.0), Vec3::new(0.5, 0.5, 0.0));
        assert_eq!(at(0.25, 0.25, 2.0), Vec3::new(0.25, 0.25, 0.0));
    }
}
