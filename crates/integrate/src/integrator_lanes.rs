//! Four particles advanced at once (`flexdem_geom::lanes`: SIMD with nalgebra's formulas
//! term for term), the leapfrog of `integrator.rs` with the same bits for every state: each
//! lane's velocity, position and orientation are computed by the same operations in the same
//! order. A blocked DOF's lane computes the free kick too and keeps its velocity by a select.
//! A turn beyond the series of `turn_quaternion` and a product off unit norm by more than the
//! Newton step's range are made for that lane by the scalar functions.
//!
//! The energy terms are summed lane by lane ([`LaneSums`], one vector add per term and
//! component), and the four lanes into the chunk's sums at its end: the order of the
//! additions is not the scalar loop's, so the energy terms differ from a one-by-one sum by
//! round-off (the same whatever the number of threads: the chunks are fixed). A term the
//! scalar loop does not add (a blocked component's kick, a free component's support work,
//! the rotation of a particle whose rotations are all blocked and at rest, a lane past the
//! batch) is made +0 by a select, which leaves a sum as it is.

use crate::homes::Piece;
use crate::step_work::StepWork;
use crate::turn::{half_turn_series, turn_quaternion, SERIES_TURN};
use flexdem_elements::Dofs;
use flexdem_geom::lanes::{f64x4, Q4, V3};
use flexdem_geom::{Real, Vec3};
use nalgebra::{Quaternion, UnitQuaternion};

/// What [`leapfrog_four`] is given besides the particles.
#[derive(Clone, Copy)]
pub(crate) struct Kick {
    pub(crate) gravity: Vec3,
    pub(crate) lambda: Real,
    pub(crate) undamped: bool,
    /// `(dt₀ + dt)/2`.
    pub(crate) kick: Real,
    /// The step before, dt₀ (for the supports' work).
    pub(crate) previous: Real,
    pub(crate) dt: Real,
}

/// `damped` of `integrator.rs` lane by lane: `a·(1 − λ·sign(a·(v + a·dt/2)))`.
#[inline(always)]
fn damped(a: f64x4, v: f64x4, lambda: f64x4, dt: f64x4) -> f64x4 {
    let (zero, one) = (f64x4::splat(0.0), f64x4::splat(1.0));
    let s = a * (v + f64x4::splat(0.5) * a * dt);
    let sign = s.simd_gt(zero).select(one, zero) - s.simd_lt(zero).select(one, zero);
    a * (one - lambda * sign)
}

/// One component of the kick of four lanes: the new velocity, the acceleration and the free
/// one (for the damping's terms).
#[inline(always)]
fn kick_component(v0: f64x4, a_free: f64x4, k: &Kick) -> (f64x4, f64x4) {
    let a = if k.undamped {
        a_free
    } else {
        damped(a_free, v0, f64x4::splat(k.lambda), f64x4::splat(k.kick))
    };
    (v0 + a * f64x4::splat(k.kick), a)
}

/// `[f(0), f(1), f(2)]`: the three components' terms kept in vectors, each lane read where
/// it is added (an array of arrays made by `std::array::from_fn` was written by 32-byte
/// stores and copied by 64-byte loads, which wait for them: a failed store forwarding that
/// took a fifth of this function's time on the net twin).
#[inline(always)]
fn three(f: impl Fn(usize) -> f64x4) -> [f64x4; 3] {
    [f(0), f(1), f(2)]
}

/// The particles of one parallel chunk of the leapfrog, and their loads.
pub(crate) struct Chunk<'a> {
    pub(crate) pos: &'a mut [Vec3],
    pub(crate) vel: &'a mut [Vec3],
    pub(crate) ori: &'a mut [UnitQuaternion<Real>],
    pub(crate) ang: &'a mut [Vec3],
    pub(crate) mass: &'a [Real],
    pub(crate) inertia: &'a [Real],
    pub(crate) f: &'a [Vec3],
    pub(crate) t: &'a [Vec3],
    /// Each particle's blocked DOFs.
    pub(crate) blocked: &'a [Dofs],
}

impl Piece for Chunk<'_> {
    fn split_at(self, at: usize) -> (Self, Self) {
        Chunk::split_at(self, at)
    }
}

impl<'a> Chunk<'a> {
    /// The first `n` particles and the others.
    pub(crate) fn split_at(self, n: usize) -> (Chunk<'a>, Chunk<'a>) {
        let Chunk { pos, vel, ori, ang, mass, inertia, f, t, blocked } = self;
        let (pos, pos_b) = pos.split_at_mut(n);
        let (vel, vel_b) = vel.split_at_mut(n);
        let (ori, ori_b) = ori.split_at_mut(n);
        let (ang, ang_b) = ang.split_at_mut(n);
        let (mass, mass_b) = mass.split_at(n);
        let (inertia, inertia_b) = inertia.split_at(n);
        let (f, f_b) = f.split_at(n);
        let (t, t_b) = t.split_at(n);
        let (blocked, blocked_b) = blocked.split_at(n);
        let a = Chunk { pos, vel, ori, ang, mass, inertia, f, t, blocked };
        let b = Chunk {
            pos: pos_b,
            vel: vel_b,
            ori: ori_b,
            ang: ang_b,
            mass: mass_b,
            inertia: inertia_b,
            f: f_b,
            t: t_b,
            blocked: blocked_b,
        };
        (a, b)
    }
}

/// Advances the particles `idx[..count]` of chunk `p` (`count` from 1 to 4, any blocked
/// DOFs; the lanes past `count` repeat a particle and are dropped) by one leapfrog step, as
/// `leapfrog_step` advances each, adding their energy terms to `sums` lane by lane. `HELD`
/// false is for four particles with no blocked DOF (the caller checks): their code is then
/// the one without selects and their terms.
pub(crate) fn leapfrog_four<const HELD: bool>(
    p: &mut Chunk<'_>,
    idx: [usize; 4],
    count: usize,
    k: &Kick,
    sums: &mut LaneSums,
) {
    let Chunk { pos, vel, ori, ang, mass, inertia, f, t, blocked } = p;
    let held = if HELD { idx.map(|i| blocked[i]) } else { [Dofs::NONE; 4] };
    let any_held = HELD && held.iter().any(|b| !b.is_empty());
    let lanes = |x: &[Real]| f64x4::new(idx.map(|i| x[i]));
    let (m, j) = (lanes(mass), lanes(inertia));
    let half = f64x4::splat(0.5);
    let (kick, dt) = (f64x4::splat(k.kick), f64x4::splat(k.dt));
    // lane by lane, whether a DOF is blocked (all set) or free (all clear)
    let zero = f64x4::splat(0.0);
    let mask =
        |d: Dofs| f64x4::new(held.map(|b| Real::from(u8::from(b.contains(d))))).simd_gt(zero);

    // translation
    let inv_mass = f64x4::splat(1.0) / m;
    let v0 = V3::gather(|l| vel[idx[l]]);
    let force = V3::gather(|l| f[idx[l]]);
    let g = k.gravity;
    let (vx, ax_free) = (v0.x, force.x * inv_mass + f64x4::splat(g.x));
    let (vy, ay_free) = (v0.y, force.y * inv_mass + f64x4::splat(g.y));
    let (vz, az_free) = (v0.z, force.z * inv_mass + f64x4::splat(g.z));
    let (v1x, ax) = kick_component(vx, ax_free, k);
    let (v1y, ay) = kick_component(vy, ay_free, k);
    let (v1z, az) = kick_component(vz, az_free, k);
    let mut v1 = V3 { x: v1x, y: v1y, z: v1z };
    if any_held {
        // a blocked component keeps its velocity
        v1 = V3 {
            x: mask(Dofs::X).select(vx, v1x),
            y: mask(Dofs::Y).select(vy, v1y),
            z: mask(Dofs::Z).select(vz, v1z),
        };
    }
    let v0s = [vx, vy, vz];
    let v1s = [v1x, v1y, v1z];
    let losses = [ax_free - ax, ay_free - ay, az_free - az];
    let gs = [g.x, g.y, g.z];
    // the terms: ½m·v0·v1, m·g·v1·dt, m·(a_free − a)·½·v0·kick and ·v1·kick
    let kinetic: [f64x4; 3] = three(|c| half * m * v0s[c] * v1s[c]);
    let gravity: [f64x4; 3] = three(|c| m * f64x4::splat(gs[c]) * v1s[c] * dt);
    let damping: [f64x4; 3] = three(|c| m * losses[c] * half * v0s[c] * kick);
    let damping_next: [f64x4; 3] = three(|c| m * losses[c] * half * v1s[c] * kick);
    // a blocked component's: ½m·v·v, and the support's ½f·v·dt₀ and ½f·v·dt
    let fs = [force.x, force.y, force.z];
    let supports = |p: &[f64x4; 3], f: &[f64x4; 3], v: &[f64x4; 3]| -> Supports {
        let (prev, dt) = (f64x4::splat(k.previous), dt);
        Supports {
            kinetic: three(|c| half * p[c] * v[c] * v[c]),
            before: three(|c| half * f[c] * v[c] * prev),
            after: three(|c| half * f[c] * v[c] * dt),
        }
    };
    let held_translation = any_held.then(|| supports(&[m; 3], &fs, &v0s));
    let x = V3::gather(|l| pos[idx[l]]);
    let x1 = x.plus(v1.scale(dt));

    // rotation
    let inv_inertia = f64x4::splat(1.0) / j;
    let w0 = V3::gather(|l| ang[idx[l]]);
    let torque = V3::gather(|l| t[idx[l]]);
    let (w1x, bx) = kick_component(w0.x, torque.x * inv_inertia, k);
    let (w1y, by) = kick_component(w0.y, torque.y * inv_inertia, k);
    let (w1z, bz) = kick_component(w0.z, torque.z * inv_inertia, k);
    let w0s = [w0.x, w0.y, w0.z];
    let w1s = [w1x, w1y, w1z];
    let rot_losses =
        [torque.x * inv_inertia - bx, torque.y * inv_inertia - by, torque.z * inv_inertia - bz];
    let kinetic_rot: [f64x4; 3] = three(|c| half * j * w0s[c] * w1s[c]);
    let rot_damping: [f64x4; 3] = three(|c| j * rot_losses[c] * half * w0s[c] * kick);
    let rot_damping_next: [f64x4; 3] = three(|c| j * rot_losses[c] * half * w1s[c] * kick);
    let mut w1 = V3 { x: w1x, y: w1y, z: w1z };
    if any_held {
        w1 = V3 {
            x: mask(Dofs::RX).select(w0.x, w1x),
            y: mask(Dofs::RY).select(w0.y, w1y),
            z: mask(Dofs::RZ).select(w0.z, w1z),
        };
    }
    let ts = [torque.x, torque.y, torque.z];
    let held_rotation = any_held.then(|| supports(&[j; 3], &ts, &w0s));

    // the orientation turned by rot(ω·dt) (`turn_quaternion`, its series), renormalized
    let turn = w1.scale(dt);
    let t2 = turn.norm_squared();
    let c = |x: Real| f64x4::splat(x);
    let (cos, sin_over_x) = half_turn_series(c(0.25) * t2, c);
    let v = turn.scale(c(0.5) * sin_over_x);
    let mut tq = Q4 { w: cos, i: v.x, j: v.y, k: v.z };
    let t2s = t2.to_array();
    if !t2.simd_lt(c(SERIES_TURN * SERIES_TURN)).all() || !t2.simd_ge(c(1e-280)).all() {
        // (beyond the series or below 1e-140 rad: `turn_quaternion` itself for those lanes)
        let (mut w, mut i, mut jj, mut kk) =
            (tq.w.to_array(), tq.i.to_array(), tq.j.to_array(), tq.k.to_array());
        for l in 0..4 {
            if !(t2s[l] < SERIES_TURN * SERIES_TURN && t2s[l] >= 1e-280) {
                let q = turn_quaternion(turn.lane(l));
                (w[l], i[l], jj[l], kk[l]) = (q.w, q.i, q.j, q.k);
            }
        }
        tq = Q4 { w: f64x4::new(w), i: f64x4::new(i), j: f64x4::new(jj), k: f64x4::new(kk) };
    }
    let q = tq.times(Q4 {
        w: f64x4::new(idx.map(|i| ori[i].w)),
        i: f64x4::new(idx.map(|i| ori[i].i)),
        j: f64x4::new(idx.map(|i| ori[i].j)),
        k: f64x4::new(idx.map(|i| ori[i].k)),
    });
    let n2 = q.norm_squared();
    let q = q.scale(c(1.5) - c(0.5) * n2);
    let (n2, w, qi, jj, kk) =
        (n2.to_array(), q.w.to_array(), q.i.to_array(), q.j.to_array(), q.k.to_array());

    // the energy terms, lane by lane: kept where the scalar loop adds them, +0 elsewhere
    let live = if count == 4 {
        None
    } else {
        Some(f64x4::new(std::array::from_fn(|l| Real::from(u8::from(l < count)))).simd_gt(zero))
    };
    let keep = |m: Option<f64x4>, x: f64x4| m.map_or(x, |m| m.select(x, zero));
    let both = |a: Option<f64x4>, b: f64x4| Some(a.map_or(b, |a| a & b));
    // (rotations all blocked and at rest: the scalar loop leaves them alone)
    let turning = if any_held {
        let rest =
            (mask(Dofs::ROTATION) & w0.x.simd_eq(zero) & w0.y.simd_eq(zero)) & w0.z.simd_eq(zero);
        both(live, !rest)
    } else {
        live
    };
    let axes = [(Dofs::X, Dofs::RX), (Dofs::Y, Dofs::RY), (Dofs::Z, Dofs::RZ)];
    for (c, (dt_c, dr_c)) in axes.into_iter().enumerate() {
        let (free_t, free_r) = if any_held {
            (both(live, !mask(dt_c)), both(turning, !mask(dr_c)))
        } else {
            (live, turning)
        };
        sums.kinetic_translation += keep(free_t, kinetic[c]);
        if gs[c] != 0.0 {
            sums.gravity += keep(free_t, gravity[c]);
        }
        sums.kinetic_rotation += keep(free_r, kinetic_rot[c]);
        if !k.undamped {
            sums.damping += keep(free_t, damping[c]) + keep(free_r, rot_damping[c]);
            sums.damping_next += keep(free_t, damping_next[c]) + keep(free_r, rot_damping_next[c]);
        }
        if let (Some(ht), Some(hr)) = (&held_translation, &held_rotation) {
            let (held_t, held_r) = (both(live, mask(dt_c)), both(turning, mask(dr_c)));
            sums.kinetic_translation += keep(held_t, ht.kinetic[c]);
            sums.kinetic_rotation += keep(held_r, hr.kinetic[c]);
            sums.boundary -= keep(held_t, ht.before[c]) + keep(held_r, hr.before[c]);
            sums.boundary_next -= keep(held_t, ht.after[c]) + keep(held_r, hr.after[c]);
        }
    }

    // written back
    for l in 0..count {
        let i = idx[l];
        vel[i] = v1.lane(l);
        pos[i] = x1.lane(l);
        // (a lane whose rotations are all blocked keeps its angular velocity: the same bits)
        ang[i] = w1.lane(l);
        if turn.lane(l) != Vec3::zeros() {
            ori[i] = if (n2[l] - 1.0).abs() < 1e-8 {
                UnitQuaternion::new_unchecked(Quaternion::new(w[l], qi[l], jj[l], kk[l]))
            } else {
                // (off unit norm beyond the Newton step: `renormalized`'s exact scaling)
                let q = turn_quaternion(turn.lane(l)) * ori[i];
                UnitQuaternion::new_normalize(q.into_inner())
            };
        }
    }
}

/// The energy terms of the blocked components of four lanes (translation or rotation), per
/// component and lane: the kinetic ½p·v·v (p the mass or the moment of inertia) and the
/// support's work −½f·v·dt₀ and −½f·v·dt (f the force or torque the support cancels).
struct Supports {
    kinetic: [f64x4; 3],
    before: [f64x4; 3],
    after: [f64x4; 3],
}

/// The energy terms of a chunk's four-particle batches, summed lane by lane (the fields of
/// [`StepWork`] that the leapfrog fills).
#[derive(Clone, Copy, Debug)]
pub(crate) struct LaneSums {
    kinetic_translation: f64x4,
    kinetic_rotation: f64x4,
    gravity: f64x4,
    damping: f64x4,
    damping_next: f64x4,
    boundary: f64x4,
    boundary_next: f64x4,
}

impl Default for LaneSums {
    fn default() -> Self {
        let zero = f64x4::splat(0.0);
        LaneSums {
            kinetic_translation: zero,
            kinetic_rotation: zero,
            gravity: zero,
            damping: zero,
            damping_next: zero,
            boundary: zero,
            boundary_next: zero,
        }
    }
}

impl LaneSums {
    /// Adds the four lanes of each sum to `work`, lane 0 first.
    pub(crate) fn add_to(&self, work: &mut StepWork) {
        let total = |x: f64x4| x.to_array().iter().fold(0.0, |a, &b| a + b);
        work.kinetic_translation += total(self.kinetic_translation);
        work.kinetic_rotation += total(self.kinetic_rotation);
        work.gravity += total(self.gravity);
        work.damping += total(self.damping);
        work.damping_next += total(self.damping_next);
        work.boundary += total(self.boundary);
        work.boundary_next += total(self.boundary_next);
    }
}
