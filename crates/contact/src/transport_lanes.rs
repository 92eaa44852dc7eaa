//! [`transport_tangent`](crate::transport_tangent) for four tangent vectors at once (SIMD,
//! `wide::f64x4`), the operations of the scalar function in its order, lane by lane (IEEE
//! additions, products, divisions and square roots give the same bits in a vector as
//! alone; no fused multiply–add), for the four-lane laws ([`crate::link_lanes`],
//! [`crate::frictional_lanes`]).

use crate::rotation::{sin_one_minus_cos_series, FIRST_ORDER_RESTORE_BELOW, SMALL_ANGLE};
use flexdem_geom::lanes::{f64x4, V3};

/// The stored tangent vectors `v` (tangent to the unit `a`) carried onto the tangent planes
/// of the unit `n` and twisted by `angle` about it, lane by lane as
/// [`transport_tangent`](crate::transport_tangent) carries one: the minimal rotation taking
/// `a` to `n` (`rotate_between`), the twist (`twist_tangent`; a turn beyond the series,
/// |ψ| ≥ 5e-3, takes libm's `sin_cos` for that lane as the scalar function does), the normal
/// part removed and the magnitude restored (`restore_magnitude`); a zero `v` kept.
///
/// A lane whose normal flipped (`1 + a·n < 1e-12` with a non-zero `v`, where the scalar
/// function returns zero) gets no meaningful value: [`flipped`] tells the caller which.
#[inline(always)]
pub(crate) fn transport_tangent_lanes(v: V3, a: V3, n: V3, angle: f64x4) -> V3 {
    let zero = f64x4::splat(0.0);
    let one = f64x4::splat(1.0);
    let half = f64x4::splat(0.5);
    let mag2 = v.norm_squared();
    let one_plus = one + a.dot(n);
    let s = a.plus(n);
    let swung = v.minus(s.scale(s.dot(v) / one_plus)).plus(n.scale(f64x4::splat(2.0) * a.dot(v)));
    let (sin, omc) = sin_one_minus_cos_series(angle, f64x4::splat);
    let (sin, omc) = if angle.abs().simd_lt(f64x4::splat(SMALL_ANGLE)).all() {
        (sin, omc)
    } else {
        let (angles, mut sin, mut omc) = (angle.to_array(), sin.to_array(), omc.to_array());
        for j in 0..4 {
            if !(angles[j].abs() < SMALL_ANGLE) {
                let (s, c) = angles[j].sin_cos();
                (sin[j], omc[j]) = (s, 1.0 - c);
            }
        }
        (f64x4::new(sin), f64x4::new(omc))
    };
    let twisted = swung.scale(one - omc).plus(n.cross(swung).scale(sin));
    let t = V3::select(angle.simd_eq(zero), swung, twisted);
    let t = t.minus(n.scale(n.dot(t)));
    let t2 = t.norm_squared();
    let delta = (t2 - mag2) * (one / mag2);
    let first_order = delta.abs().simd_lt(f64x4::splat(FIRST_ORDER_RESTORE_BELOW));
    let near = t.scale(one - half * delta);
    // (a lane without a vector keeps it, below: it does not hold the others back)
    let restored = if (first_order | mag2.simd_eq(zero)).all() {
        near
    } else {
        let far = V3::select(t2.simd_gt(zero), t.scale((mag2 / t2).sqrt()), t);
        V3::select(first_order, near, far)
    };
    V3::select(mag2.simd_eq(zero), v, restored)
}

/// The lanes whose normal flipped under a non-zero `v` (`1 + a·n < 1e-12`, a NaN
/// included), where [`transport_tangent_lanes`] has no meaning: all bits set there.
#[inline(always)]
pub(crate) fn flipped(v: V3, a: V3, n: V3) -> f64x4 {
    let one_plus = f64x4::splat(1.0) + a.dot(n);
    let zero = f64x4::splat(0.0);
    !(v.norm_squared().simd_eq(zero) | one_plus.simd_ge(f64x4::splat(1e-12)))
}
