//! Proptest strategies for geometric inputs, shared with the other crates' property tests
//! (feature `proptest-support`; always on in this crate's own tests).
//!
//! Sizes are given by a `range`: coordinates lie in `[-range, range]`. Combine with [`scale`]
//! (log-uniform over `1e-3 ..= 1e3`) and [`rotation`] to check that a result does not depend on
//! units or orientation.

use crate::{Real, Vec3};
use nalgebra::{Quaternion, Rotation3, UnitQuaternion};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// A vector with each component uniform in `[-range, range]`.
pub fn vec3(range: Real) -> impl Strategy<Value = Vec3> + Clone {
    let c = -range..=range;
    (c.clone(), c.clone(), c).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A unit vector, uniform on the sphere (Archimedes: `z` uniform in `[-1, 1]`, azimuth uniform).
pub fn unit_vec3() -> impl Strategy<Value = Vec3> + Clone {
    (-1.0..=1.0_f64, 0.0..TAU).prop_map(|(z, phi): (Real, Real)| {
        let rho = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(rho * phi.cos(), rho * phi.sin(), z)
    })
}

/// A segment `(a, b)` with both ends from [`vec3`]`(range)`.
pub fn segment(range: Real) -> impl Strategy<Value = (Vec3, Vec3)> + Clone {
    (vec3(range), vec3(range))
}

/// A triangle `(a, b, c)` with its vertices from [`vec3`]`(range)`.
pub fn triangle(range: Real) -> impl Strategy<Value = (Vec3, Vec3, Vec3)> + Clone {
    (vec3(range), vec3(range), vec3(range))
}

/// A rotation uniform over SO(3) (Shoemake's unit quaternion from three uniforms).
pub fn unit_quaternion() -> impl Strategy<Value = UnitQuaternion<Real>> + Clone {
    (0.0..=1.0_f64, 0.0..=1.0_f64, 0.0..=1.0_f64).prop_map(|(u1, u2, u3): (Real, Real, Real)| {
        let (r1, r2) = ((1.0 - u1).sqrt(), u1.sqrt());
        let (a, b) = (TAU * u2, TAU * u3);
        UnitQuaternion::new_normalize(Quaternion::new(
            r2 * b.cos(),
            r1 * a.sin(),
            r1 * a.cos(),
            r2 * b.sin(),
        ))
    })
}

/// A rotation matrix uniform over SO(3) (see [`unit_quaternion`]).
pub fn rotation() -> impl Strategy<Value = Rotation3<Real>> + Clone {
    unit_quaternion().prop_map(|q| q.to_rotation_matrix())
}

/// A length scale, log-uniform over `1e-3 ..= 1e3` (millimetres to kilometres in SI units).
pub fn scale() -> impl Strategy<Value = Real> + Clone {
    (-3.0..=3.0_f64).prop_map(|e: Real| 10.0_f64.powf(e))
}

/// Two segments `(a0, a1, b0, b1)` drawn from a mix of configurations where closest-point
/// algorithms go wrong: general position, exactly parallel, collinear, nearly parallel
/// (angles down to 3e-13 rad, on both sides of the parallel threshold), one or both of zero
/// length, and segments that intersect.
pub fn segment_pair(range: Real) -> impl Strategy<Value = (Vec3, Vec3, Vec3, Vec3)> + Clone {
    let general =
        (segment(range), segment(range)).prop_map(|((a0, a1), (b0, b1))| (a0, a1, b0, b1));
    let parallel = (segment(range), vec3(range), -1.0..=1.0_f64)
        .prop_map(|((a0, a1), b0, k): (_, _, Real)| (a0, a1, b0, b0 + (a1 - a0) * k));
    let collinear = (segment(range), -2.0..=2.0_f64, -2.0..=2.0_f64).prop_map(
        |((a0, a1), u, v): (_, Real, Real)| (a0, a1, a0 + (a1 - a0) * u, a0 + (a1 - a0) * v),
    );
    let nearly_parallel =
        (segment(range), vec3(range), unit_vec3(), -12.5..=-2.0_f64, -1.0..=1.0_f64).prop_map(
            |((a0, a1), b0, dir, e, k): (_, _, _, Real, Real)| {
                let d = a1 - a0;
                let tilt = dir.cross(&d) * 10.0_f64.powf(e);
                (a0, a1, b0, b0 + (d + tilt) * k)
            },
        );
    let one_point = (segment(range), vec3(range)).prop_map(|((a0, a1), p)| (a0, a1, p, p));
    let two_points = (vec3(range), vec3(range)).prop_map(|(p, q)| (p, p, q, q));
    let crossing = (segment(range), vec3(range), 0.0..=1.0_f64, 0.0..=1.0_f64).prop_map(
        |((a0, a1), dir, s, k): (_, _, Real, Real)| {
            let x = a0 + (a1 - a0) * s;
            (a0, a1, x - dir * k, x + dir * (1.0 - k))
        },
    );
    prop_oneof![
        3 => general,
        2 => parallel,
        1 => collinear,
        2 => nearly_parallel,
        1 => one_point.clone(),
        1 => one_point.prop_map(|(a0, a1, b0, b1)| (b0, b1, a0, a1)),
        1 => two_points,
        1 => crossing,
    ]
}
