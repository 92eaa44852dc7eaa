//! Proptest strategies and helpers shared by this crate's tests.

use flexdem_geom::{Real, Vec3};
use nalgebra::{Quaternion, UnitQuaternion};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// A vector with components uniform in `[-range, range]`.
pub fn vec3(range: Real) -> impl Strategy<Value = Vec3> + Clone {
    let c = -range..=range;
    (c.clone(), c.clone(), c).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A unit vector uniform on the sphere.
pub fn unit_vec3() -> impl Strategy<Value = Vec3> + Clone {
    (-1.0..=1.0_f64, 0.0..TAU).prop_map(|(z, phi): (Real, Real)| {
        let rho = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(rho * phi.cos(), rho * phi.sin(), z)
    })
}

/// A rotation uniform over SO(3) (Shoemake).
pub fn unit_quaternion() -> impl Strategy<Value = UnitQuaternion<Real>> + Clone {
    (0.0..=1.0_f64, 0.0..TAU, 0.0..TAU).prop_map(|(u1, a, b): (Real, Real, Real)| {
        let (r1, r2) = ((1.0 - u1).sqrt(), u1.sqrt());
        UnitQuaternion::from_quaternion(Quaternion::new(
            r2 * b.cos(),
            r1 * a.sin(),
            r1 * a.cos(),
            r2 * b.sin(),
        ))
    })
}

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
