//! Proptest strategies and helpers shared by this crate's tests.

use flexdem_geom::{Real, Vec3};
use proptest::prelude::*;

// Points, directions and rotations: geom's exported strategies.
pub use flexdem_geom::proptest_support::{unit_quaternion, unit_vec3, vec3};

/// Log-uniform positive number in `[lo, hi]`.
pub fn log_uniform(lo: Real, hi: Real) -> impl Strategy<Value = Real> + Clone {
    (lo.ln()..=hi.ln()).prop_map(Real::exp)
}

/// A unit vector orthogonal to the unit `n`.
pub fn any_perpendicular(n: Vec3) -> Vec3 {
    let a = if n.x.abs() < 0.9 { Vec3::x() } else { Vec3::y() };
    n.cross(&a).normalize()
}

/// `|a − b| ≤ tol·max(|b|, floor)`.
pub fn close(a: Vec3, b: Vec3, tol: Real, floor: Real) -> bool {
    (a - b).norm() <= tol * b.norm().max(floor)
}
