//! A particle's turn over a step as a unit quaternion, and the renormalization of the turned
//! orientation (`integrator.rs`, and its four-particle lanes, `integrator_lanes.rs`).

use flexdem_geom::{Real, Vec3};
use nalgebra::{Quaternion, UnitQuaternion};
use std::ops::{Add, Mul};

/// Below this angle [`turn_quaternion`] sums series: a step's turn almost always is smaller
/// (nodes of an impacted tube turn by up to about 1e-2 per step), and the branch is then
/// never mispredicted.
pub(crate) const SERIES_TURN: Real = 0.2;

/// The unit quaternion of the rotation vector `turn` (angle θ = |turn| about turn/θ):
/// (cos(θ/2), sin(θ/2)·turn/θ). Below θ = 0.2 by the series of cos x and sin x/x in
/// y = x² = θ²/4 through y⁶ (the first terms left out, y⁷/14! and y⁷/15!, are below 2e-25
/// there), with no square root and no `sin_cos`; above, nalgebra's `from_scaled_axis`. Equal
/// to it to round-off at every angle, except that a turn below 1e-140 rad is none.
#[inline]
pub(crate) fn turn_quaternion(turn: Vec3) -> UnitQuaternion<Real> {
    let t2 = turn.norm_squared();
    if t2 >= SERIES_TURN * SERIES_TURN {
        return UnitQuaternion::from_scaled_axis(turn);
    }
    if t2 < 1e-280 {
        // a turn below 1e-140 rad is none: it would only seed the orientation with numbers
        // whose products are subnormal, slow to compute with (in the links' quaternion
        // products too: the tube impact's integration took 0.0135 ms/step with them, 0.0078
        // without, where a wave ahead of its front leaves such turns)
        return UnitQuaternion::identity();
    }
    let (cos, sin_over_x) = half_turn_series(0.25 * t2, |x| x);
    // sin x · axis = (sin x / x)·x·turn/θ = (sin x / x)·turn/2
    let v = turn * (0.5 * sin_over_x);
    UnitQuaternion::new_unchecked(Quaternion::new(cos, v.x, v.y, v.z))
}

/// cos x and sin x / x from y = x², by their series through y⁶ ([`turn_quaternion`]'s), for
/// any number type with + and ×, `c` making its constants: the four particles' lanes
/// (`integrator_lanes.rs`, on `f64x4`) take the same operations in the same order, so the
/// same bits per lane.
#[inline(always)]
pub(crate) fn half_turn_series<T>(y: T, c: impl Fn(Real) -> T) -> (T, T)
where
    T: Copy + Add<Output = T> + Mul<Output = T>,
{
    let cos = c(1.0)
        + y * (c(-1.0 / 2.0)
            + y * (c(1.0 / 24.0)
                + y * (c(-1.0 / 720.0)
                    + y * (c(1.0 / 40_320.0)
                        + y * (c(-1.0 / 3_628_800.0) + y * c(1.0 / 479_001_600.0))))));
    let sin_over_x = c(1.0)
        + y * (c(-1.0 / 6.0)
            + y * (c(1.0 / 120.0)
                + y * (c(-1.0 / 5_040.0)
                    + y * (c(1.0 / 362_880.0)
                        + y * (c(-1.0 / 39_916_800.0) + y * c(1.0 / 6_227_020_800.0))))));
    (cos, sin_over_x)
}

/// `q` scaled to unit norm. A product of unit quaternions is off by round-off only: where
/// |q|² = 1 + ε with |ε| < 1e-8, by 1 − ε/2 = 1.5 − |q|²/2 (Newton's step for 1/√(1 + ε),
/// whose error 3ε²/8 is below round-off), with no square root and no division; else exactly.
#[inline]
pub(crate) fn renormalized(q: Quaternion<Real>) -> UnitQuaternion<Real> {
    let n2 = q.norm_squared();
    if (n2 - 1.0).abs() < 1e-8 {
        UnitQuaternion::new_unchecked(q * (1.5 - 0.5 * n2))
    } else {
        UnitQuaternion::new_normalize(q)
    }
}
