//! Exact rotations used by the shear update (eq 2) and the link moments (eq 5, 6).
//!
//! YADE rotates the stored shear force with the small-angle form F ← F − F×(n_old×n_new), then
//! F ← F − F×twist (reference §4.2), which changes |F| and is not objective. Here the rotation
//! is exact (Rodrigues) and preserves the magnitude.

use flexdem_geom::{Real, Vec3};
use nalgebra::UnitQuaternion;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
use std::ops::{Add, Div, Mul, Sub};

/// Rotates `v` by `angle` about the unit `axis` (Rodrigues):
/// v' = v cosψ + (a×v) sinψ + a(a·v)(1 − cosψ).
#[inline]
pub fn rotate_about_axis(v: Vec3, axis: Vec3, angle: Real) -> Vec3 {
    let (s, one_minus_c) = sin_one_minus_cos(angle);
    v * (1.0 - one_minus_c) + axis.cross(&v) * s + axis * (axis.dot(&v) * one_minus_c)
}

/// Below this angle `sin_one_minus_cos` uses its series: the first omitted terms, ψ⁷/7! and
/// ψ⁸/8!, are below 1e-18 relative there.
pub(crate) const SMALL_ANGLE: Real = 5e-3;

/// (sin ψ, 1 − cos ψ), by Taylor series for |ψ| < 5e-3 (a twist of spin·dt is almost always
/// that small; the series is exact to round-off there and four times cheaper than libm's
/// `sin_cos`), else by `sin_cos`. 1 − cos ψ keeps its relative precision for tiny ψ.
#[inline]
pub fn sin_one_minus_cos(angle: Real) -> (Real, Real) {
    if angle.abs() < SMALL_ANGLE {
        sin_one_minus_cos_series(angle, |x| x)
    } else {
        let (s, c) = angle.sin_cos();
        (s, 1.0 - c)
    }
}

/// The series of [`sin_one_minus_cos`] for any number type with +, − and ×, `c` making its
/// constants: the four links' lanes (`link_lanes.rs`, on `f64x4`) take the same operations
/// in the same order, so the same bits per lane.
#[inline(always)]
pub(crate) fn sin_one_minus_cos_series<T>(angle: T, c: impl Fn(Real) -> T) -> (T, T)
where
    T: Copy + Add<Output = T> + Sub<Output = T> + Mul<Output = T>,
{
    let a2 = angle * angle;
    let s = angle * (c(1.0) - a2 * c(1.0 / 6.0) * (c(1.0) - a2 * c(1.0 / 20.0)));
    let omc = c(0.5) * a2 * (c(1.0) - a2 * c(1.0 / 12.0) * (c(1.0) - a2 * c(1.0 / 30.0)));
    (s, omc)
}

/// Below this x, atan(x)/x is summed as a series: the first omitted term, x¹⁰/11, is below
/// 6e-17 relative there.
pub(crate) const ATAN_SERIES_BELOW: Real = 0.03;

/// atan(x)/x from y = x² for x < [`ATAN_SERIES_BELOW`]: 1 − y/3 + y²/5 − y³/7 + y⁴/9.
#[inline(always)]
pub(crate) fn atan_over_x_series<T>(y: T, c: impl Fn(Real) -> T) -> T
where
    T: Copy + Add<Output = T> + Mul<Output = T>,
{
    c(1.0) + y * (c(-1.0 / 3.0) + y * (c(1.0 / 5.0) + y * (c(-1.0 / 7.0) + y * c(1.0 / 9.0))))
}

/// atan(x) for x ≥ 0: x·[`atan_over_x_series`] below 0.03, else [`atan_of_ratio`].
#[cfg(test)]
fn atan_non_negative(x: Real) -> Real {
    if x < ATAN_SERIES_BELOW {
        x * atan_over_x_series(x * x, |x| x)
    } else {
        atan_of_ratio(x, 1.0)
    }
}

/// Where [`atan_of_ratio`] changes its reduction: s/a at most 0.66 is taken as it is, at
/// most 1 + √2 = tan(3π/8) as (s − a)/(s + a) (atan = π/4 + atan of it), beyond as −a/s
/// (atan = π/2 + atan of it), so that the rational function's argument stays within ±0.66.
pub(crate) const ATAN_DIRECT_UP_TO: Real = 0.66;
pub(crate) const ATAN_OFFSET_UP_TO: Real = std::f64::consts::SQRT_2 + 1.0;
/// π/2 less its double (Cephes' `MOREBITS`): added with the offsets π/4 (half of it) and π/2.
/// (Cephes' published digits, kept as printed.)
#[allow(clippy::excessive_precision)]
pub(crate) const ATAN_MORE_BITS: Real = 6.123233995736765886130e-17;

/// atan(z) + `base` + `more` for |z| ≤ 0.66: z + z·z²·P(z²)/Q(z²) with Cephes' degree 4/5
/// rational function (Moshier's `atan.c`, relative error 1.8e-16 over ±0.66), for any number
/// type with +, −, ×, ÷ (`c` makes its constants): [`atan_of_ratio`] and the four links'
/// lanes (`link_lanes.rs`, on `f64x4`) take the same operations in the same order, so the
/// same bits per lane. Plain products and sums, no fused multiply–add: the same bits on
/// every x86-64 machine, where libm's `atan2` picks an FMA variant by processor.
#[inline(always)]
#[allow(clippy::excessive_precision)] // Cephes' published digits, kept as printed
pub(crate) fn atan_rational<T>(z: T, base: T, more: T, c: impl Fn(Real) -> T) -> T
where
    T: Copy + Add<Output = T> + Mul<Output = T> + Div<Output = T>,
{
    let z2 = z * z;
    let p = (((c(-8.750608600031904122785e-1) * z2 + c(-1.615753718733365076637e1)) * z2
        + c(-7.500855792314704667340e1))
        * z2
        + c(-1.228866684490136173410e2))
        * z2
        + c(-6.485021904942025371773e1);
    let q = ((((z2 + c(2.485846490142306297962e1)) * z2 + c(1.650270098316988542046e2)) * z2
        + c(4.328810604912902668951e2))
        * z2
        + c(4.853903996359136964868e2))
        * z2
        + c(1.945506571482613964425e2);
    base + ((z * (z2 * p / q) + z) + more)
}

/// atan(s/a) for s > 0 and a ≥ 0, in [0, π/2]: half the angle of a rotation whose
/// quaternion has |v| = s and |w| = a ([`rotation_vector`] beyond its series). The quotient
/// is reduced to |z| ≤ 0.66 with one division (`ATAN_DIRECT_UP_TO`), then
/// [`atan_rational`]. Within 2.2e-16 of libm's `atan2(s, a)` relative
/// (`atan_of_ratio_is_libms_to_an_ulp`). The four links' lanes compute four at once with one
/// division: the links stage of the tube twin against YADE took 11 % less time than with
/// libm's `atan2` lane by lane (bench/README.md, "eleventh session").
#[inline]
pub fn atan_of_ratio(s: Real, a: Real) -> Real {
    let (z, base, more) = if s <= ATAN_DIRECT_UP_TO * a {
        (s / a, 0.0, 0.0)
    } else if s <= ATAN_OFFSET_UP_TO * a {
        ((s - a) / (s + a), FRAC_PI_4, 0.5 * ATAN_MORE_BITS)
    } else {
        (-a / s, FRAC_PI_2, ATAN_MORE_BITS)
    };
    atan_rational(z, base, more, |x| x)
}

/// Rotates `v` by the minimal rotation taking the unit vector `a` onto the unit vector `b`:
/// with s = a + b, v' = v − s(s·v)/(1 + a·b) + 2b(a·v), the same rotation as
/// v cosθ + c×v + c(c·v)/(1 + cosθ) (c = a×b, cosθ = a·b) with dot products only (two
/// reflections: R = I − s sᵀ/(1 + a·b) + 2 b aᵀ). Exact for any angle below π; `None` when
/// `a` and `b` are (nearly) opposite (1 + a·b < 1e-12), where the minimal rotation is not
/// defined.
#[inline]
pub fn rotate_between(v: Vec3, a: Vec3, b: Vec3) -> Option<Vec3> {
    let one_plus = 1.0 + a.dot(&b);
    if one_plus < 1e-12 {
        return None;
    }
    let s = a + b;
    Some(v - s * (s.dot(&v) / one_plus) + b * (2.0 * a.dot(&v)))
}

/// Rotates `t`, tangent to the unit `axis`, by `angle` about it: t cosψ + (a×t) sinψ, the
/// Rodrigues rotation ([`rotate_about_axis`]) without its a(a·t)(1 − cosψ) term, which is
/// round-off for a tangent vector (the caller projects onto the tangent plane after).
#[inline]
fn twist_tangent(t: Vec3, axis: Vec3, angle: Real) -> Vec3 {
    let (s, one_minus_c) = sin_one_minus_cos(angle);
    t * (1.0 - one_minus_c) + axis.cross(&t) * s
}

/// Below this |δ| the magnitude of a carried tangent vector is restored by 1 − δ/2
/// ([`transport_tangent`]): the first omitted term, 3δ²/8, is below 4e-19 relative there.
pub(crate) const FIRST_ORDER_RESTORE_BELOW: Real = 1e-9;

/// Carries a tangential vector (the shear force) from the tangent plane of the previous normal
/// `n_old` onto that of `n_new` (eq 2, "rotate onto the new tangent plane"): the minimal rotation
/// taking `n_old` to `n_new`, then a twist of `twist_angle` (= spin·dt) about `n_new`; the
/// round-off normal component is then removed and the magnitude restored, so that |v| does not
/// drift over millions of steps. The rotations keep |v| but for round-off, `|t|² = |v|²(1 + δ)`
/// with δ of the order of 1e-16, and the factor √(|v|²/|t|²) = (1 + δ)^(−1/2) is then
/// `1 − δ/2` ([`FIRST_ORDER_RESTORE_BELOW`]; `1/|v|²` is taken at the start, off the path of
/// the rest: a square root and a division at its end were 5 % of the LAMMPS twin's step),
/// else the root itself. When the normal flipped (opposite normals) the history has no
/// meaning and zero is returned.
#[inline(always)]
pub fn transport_tangent(v: Vec3, n_old: Vec3, n_new: Vec3, twist_angle: Real) -> Vec3 {
    let mag2 = v.norm_squared();
    if mag2 == 0.0 {
        return v;
    }
    let inv_mag2 = 1.0 / mag2;
    let Some(swung) = rotate_between(v, n_old, n_new) else {
        return Vec3::zeros();
    };
    let t = if twist_angle == 0.0 { swung } else { twist_tangent(swung, n_new, twist_angle) };
    restore_magnitude(t - n_new * n_new.dot(&t), mag2, inv_mag2)
}

/// `t` scaled to the squared magnitude `mag2` (`inv_mag2` its inverse) when it has one: by
/// `1 − δ/2` where `|t|² = mag2·(1 + δ)` with |δ| below [`FIRST_ORDER_RESTORE_BELOW`], else
/// by √(mag2/|t|²).
#[inline(always)]
fn restore_magnitude(t: Vec3, mag2: Real, inv_mag2: Real) -> Vec3 {
    let t2 = t.norm_squared();
    let delta = (t2 - mag2) * inv_mag2;
    if delta.abs() < FIRST_ORDER_RESTORE_BELOW {
        t * (1.0 - 0.5 * delta)
    } else if t2 > 0.0 {
        t * (mag2 / t2).sqrt()
    } else {
        t
    }
}

/// Rotation vector θ = angle·axis of a unit quaternion, with the angle in [0, π] (the
/// representative of (−π, π] with a non-negative angle), computed as
/// 2·atan(|v|/|w|)·sign(w)·v/|v| so that small angles keep full relative precision
/// (nalgebra's `scaled_axis` goes through `acos` and loses it). A link's relative rotation is
/// usually small (|v| < 0.03|w|): there the factor is 2·sign(w)/|w|·atan(x)/x with x = |v|/|w|,
/// by its series in x², with one division and no square root; beyond, atan by
/// [`atan_of_ratio`] (a rational function the four links' lanes compute together).
#[inline]
pub fn rotation_vector(q: &UnitQuaternion<Real>) -> Vec3 {
    let w = q.w;
    let v = q.imag();
    let s2 = v.norm_squared();
    if s2 == 0.0 {
        return Vec3::zeros();
    }
    let aw = w.abs();
    let limit = ATAN_SERIES_BELOW * aw;
    if s2 < limit * limit {
        let inv_w = 1.0 / aw;
        let y = s2 * inv_w * inv_w;
        return v * (2.0 * inv_w * atan_over_x_series(y, |x| x)).copysign(w);
    }
    let s = s2.sqrt();
    v * ((2.0 * atan_of_ratio(s, aw)).copysign(w) / s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn series_match_libm_to_round_off() {
        let mut worst: (Real, Real) = (0.0, 0.0);
        for k in -2000i32..=2000 {
            let x = k as Real * 4e-6; // up to ±8e-3, across the switch at 5e-3
            let (s, omc) = sin_one_minus_cos(x);
            let (sl, cl) = x.sin_cos();
            if x != 0.0 && x.abs() < SMALL_ANGLE {
                // beyond the switch, 1 − cos comes from libm's cos and keeps only ~1e-11
                worst.0 = worst.0.max(((s - sl) / sl).abs());
                // 1 − cos from libm loses digits for tiny x: compare with 2 sin²(x/2)
                let reference = 2.0 * (0.5 * x).sin().powi(2);
                worst.1 = worst.1.max(((omc - reference) / reference).abs());
            }
            let _ = cl;
            let y = (k.abs() as Real) * 2e-5; // up to 0.04, across the switch at 0.03
            if y > 0.0 {
                let rel = ((atan_non_negative(y) - y.atan()) / y.atan()).abs();
                worst.0 = worst.0.max(rel);
            }
        }
        assert!(worst.0 < 4e-16 && worst.1 < 4e-16, "worst relative errors {worst:?}");
    }

    #[test]
    fn rotate_between_maps_a_to_b_and_keeps_norm() {
        let a = Vec3::new(1.0, 0.2, -0.3).normalize();
        let b = Vec3::new(-0.4, 0.9, 0.1).normalize();
        assert!((rotate_between(a, a, b).unwrap() - b).norm() < 1e-15);
        let v = Vec3::new(0.3, -2.0, 1.0);
        let w = rotate_between(v, a, b).unwrap();
        assert!((w.norm() - v.norm()).abs() < 1e-14);
        // Equals the quaternion rotation between a and b.
        let q = UnitQuaternion::rotation_between(&a, &b).unwrap();
        assert!((q * v - w).norm() < 1e-14);
        assert!(rotate_between(v, a, -a).is_none());
    }

    #[test]
    fn transport_keeps_tangency_and_magnitude() {
        let n0 = Vec3::new(0.0, 0.0, 1.0);
        let n1 = Vec3::new(0.1, 0.3, 1.0).normalize();
        let f = Vec3::new(2.0, -1.0, 0.0);
        let g = transport_tangent(f, n0, n1, 0.7);
        assert!(g.dot(&n1).abs() < 1e-14);
        assert!((g.norm() - f.norm()).abs() < 1e-14);
        // Pure twist about a fixed normal.
        let h = transport_tangent(Vec3::x(), n0, n0, PI / 2.0);
        assert!((h - Vec3::y()).norm() < 1e-15);
        assert_eq!(transport_tangent(f, n0, -n0, 0.0), Vec3::zeros());
    }

    /// A million small transports (the normal and the twist turning each step, as a shear
    /// force's do) keep the magnitude: round-off drifts it by 5.9e-11 relative.
    #[test]
    fn transport_does_not_drift_over_a_million_steps() {
        let f0 = Vec3::new(0.0, 3.0, -4.0);
        let (mut f, mut n) = (f0, Vec3::x());
        for k in 0..1_000_000 {
            let phase = k as Real * 1e-4;
            let next = Vec3::new(1.0, 1e-2 * phase.sin(), 1e-2 * phase.cos()).normalize();
            f = transport_tangent(f, n, next, 1e-4 * (1.0 + phase.cos()));
            n = next;
        }
        assert!((f.norm() - 5.0).abs() <= 1e-9, "|F| − 5 = {:e}", f.norm() - 5.0);
        assert!(f.dot(&n).abs() <= 1e-13);
        // a vector not tangent to n_old: its normal part goes, its magnitude is restored
        let g = transport_tangent(Vec3::new(1.0, 1.0, 0.0), Vec3::z(), Vec3::z(), 0.0);
        assert!((g.norm() - 2.0_f64.sqrt()).abs() < 1e-15 && g.z == 0.0);
    }

    /// The first-order restore is the root's to round-off where it is taken, and the root
    /// is taken beyond it.
    #[test]
    fn the_first_order_restore_is_the_roots() {
        let v = Vec3::new(0.0, 3.0, -4.0);
        for delta in [1e-16, -3e-16, 1e-13, -1e-11, 9e-10, -9e-10, 2e-9, 1e-3, -0.5_f64] {
            let t = v * (1.0 + delta).sqrt(); // |t|² = 25·(1 + δ)
            let got = restore_magnitude(t, 25.0, 1.0 / 25.0);
            let root = t * (25.0 / t.norm_squared()).sqrt();
            assert!((got - root).norm() <= 5.0 * 4e-16, "{delta}: {got:?} {root:?}");
            assert!((got.norm() - 5.0).abs() <= 5.0 * 4e-16, "{delta}: {}", got.norm());
        }
        assert_eq!(restore_magnitude(Vec3::zeros(), 25.0, 1.0 / 25.0), Vec3::zeros());
    }

    /// `atan_of_ratio` against libm's `atan2` over quotients from 1e-8 to 1e8 (log-uniform,
    /// and dense about the switches at 0.66 and 1 + √2) and at the ends (a = 0: π/2).
    #[test]
    fn atan_of_ratio_is_libms_to_an_ulp() {
        let mut worst: Real = 0.0;
        let mut check = |s: Real, a: Real| {
            let (ours, libm) = (atan_of_ratio(s, a), s.atan2(a));
            worst = worst.max(((ours - libm) / libm).abs());
        };
        for k in 0..=200_000 {
            let t = 10f64.powf(-8.0 + 16.0 * k as Real / 200_000.0);
            check(t, 1.0);
            check(1.0, 1.0 / t);
            check(0.37 * t, 0.37);
        }
        for &edge in &[ATAN_DIRECT_UP_TO, ATAN_OFFSET_UP_TO, 1.0] {
            for k in -2000..=2000 {
                check(edge * (1.0 + k as Real * 1e-6), 1.0);
            }
        }
        check(1.0, 0.0);
        assert_eq!(atan_of_ratio(1.0, 0.0), FRAC_PI_2);
        assert_eq!(atan_of_ratio(1.0, 1.0), FRAC_PI_4);
        assert!(worst <= 2.3e-16, "worst relative difference {worst:e}");
    }

    #[test]
    fn rotation_vector_small_and_large_angles() {
        let axis = Vec3::new(0.3, -0.5, 0.8).normalize();
        for &ang in &[1e-12, 1e-7, 1e-3, 0.0599, 0.06, 0.0601, 1.0, 3.0, PI - 1e-9] {
            let q = UnitQuaternion::from_scaled_axis(axis * ang);
            let th = rotation_vector(&q);
            assert!((th - axis * ang).norm() <= 1e-15 * ang.max(1.0) + 1e-12 * ang, "{ang}");
            // Negated quaternion (same rotation) gives the same vector.
            let qn = UnitQuaternion::new_unchecked(-q.into_inner());
            assert!((rotation_vector(&qn) - axis * ang).norm() <= 1e-12 * ang.max(1e-3));
        }
        // An angle slightly above π comes back as the opposite rotation below π.
        let q = UnitQuaternion::from_scaled_axis(axis * (PI + 0.1));
        assert!((rotation_vector(&q) + axis * (PI - 0.1)).norm() < 1e-12);
        assert_eq!(rotation_vector(&UnitQuaternion::identity()), Vec3::zeros());
    }
}
