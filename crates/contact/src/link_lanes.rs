//! Four beam links updated at once (SIMD, `wide::f64x4`) on their common path: a cohesive
//! link of a fragile material with moments, stretched, sheared, bent and twisted below its
//! limits. Every operation is the one [`update_link_parts`](crate::update_link_parts) does, in
//! the same order, lane by lane (IEEE additions, products, divisions and square roots give
//! the same bits in a vector as alone; no fused multiply–add), so a lane's state and loads
//! are the scalar update's to the bit. Where the scalar law calls libm (a twist of 5e-3 rad
//! or more in the step) that lane's coefficient is computed alone by the same call; a
//! relative rotation beyond the series of `rotation_vector` takes the four lanes' atan
//! together ([`atan_of_ratio_lanes`], the scalar `atan_of_ratio`'s operations). A lane off
//! the path (broken or frictional, plastic, a limit reached, coincident nodes, a flipped
//! normal, a NaN) is left untouched and reported, for the caller to update with the scalar
//! law.
//!
//! The branches of the scalar law that the path keeps (zero shear force, no twist, a zero
//! relative rotation, YADE's shear factor) are taken lane by lane with selects that give the
//! branch's own value. On this machine (SSE2, two lanes per instruction) it takes a fifth
//! off the links stage (bench/README.md, "2026-12-04, second session").

use crate::link::{LinkClass, LinkSpring, LinkState, LinkStatus};
use crate::material::FailureMode;
use crate::rotation::{
    atan_over_x_series, atan_rational, ATAN_DIRECT_UP_TO, ATAN_MORE_BITS, ATAN_OFFSET_UP_TO,
    ATAN_SERIES_BELOW,
};
use crate::transport_lanes::{flipped, transport_tangent_lanes};
use crate::LinkKinematicsMode;
use flexdem_geom::lanes::{f64x4, Q4, V3};
use flexdem_geom::{Real, Vec3};
use nalgebra::UnitQuaternion;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// Links per call.
pub const LANES: usize = 4;

/// What the engine keeps of a link's update on the common path: the load on node 2 and the
/// elastic energy (no event, nothing dissipated).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneLoad {
    /// Force on node 2, Fn·n + Fs (N).
    pub force_on_2: Vec3,
    /// The shear force's torque about each node, −(L/2) n × Fs (N·m).
    pub lever_torque: Vec3,
    /// Moment on node 2, Mt + Mb (N·m).
    pub moment_on_2: Vec3,
    /// Elastic energy stored after the update (J).
    pub elastic_energy: Real,
}

/// Whether a link may take the common path before anything is computed: cohesive, of a
/// fragile material (its plastic part is zero), with moments.
fn eligible(class: &LinkClass, state: &LinkState) -> bool {
    state.status == LinkStatus::Cohesive && class.failure == FailureMode::Fragile && class.moments
}

/// The nodes' state the four links read: the particles' arrays (as the engine keeps them)
/// and each link's two nodes, [`LinkKinematics`] lane by lane without the copies.
#[derive(Clone, Copy)]
pub struct LaneNodes<'a> {
    /// Positions.
    pub pos: &'a [Vec3],
    /// Velocities.
    pub vel: &'a [Vec3],
    /// Angular velocities.
    pub ang_vel: &'a [Vec3],
    /// Orientations.
    pub ori: &'a [UnitQuaternion<Real>],
    /// Node 1 and node 2 of each link.
    pub nodes: [[usize; 2]; LANES],
}

/// One step of the four links `states` (their classes, springs and nodes lane by lane), on
/// the common path (module documentation). Where a lane takes it, its state is written as
/// [`update_link_parts`](crate::update_link_parts) writes it (with a zero plastic part) and
/// `store(j, load)` is called, in lane order; the returned bits say which lanes took it (bit
/// j for lane j). A lane that did not is untouched: the caller updates it with the scalar law.
pub fn update_link_lanes(
    classes: [&LinkClass; LANES],
    springs: [&LinkSpring; LANES],
    states: &mut [LinkState; LANES],
    at: &LaneNodes<'_>,
    dt: Real,
    mut store: impl FnMut(usize, &LaneLoad),
) -> u8 {
    let ok: [bool; LANES] = std::array::from_fn(|j| eligible(classes[j], &states[j]));
    if !ok.iter().any(|&o| o) {
        return 0;
    }
    let [n1, n2] = [0, 1].map(|side| at.nodes.map(|n| n[side]));
    fn lanes(f: impl Fn(usize) -> Real) -> f64x4 {
        f64x4::new(std::array::from_fn(f))
    }
    let zero = f64x4::splat(0.0);
    let one = f64x4::splat(1.0);
    let half = f64x4::splat(0.5);
    let dt4 = f64x4::splat(dt);

    // length and normal
    let x1 = V3::gather(|j| at.pos[n1[j]]);
    let x2 = V3::gather(|j| at.pos[n2[j]]);
    let d = x2.minus(x1);
    let l = d.norm_squared().sqrt();
    let inv_l = one / l;
    let n = d.scale(inv_l);
    let w1 = V3::gather(|j| at.ang_vel[n1[j]]);
    let w2 = V3::gather(|j| at.ang_vel[n2[j]]);
    let w12 = w1.plus(w2);
    let spin = half * n.dot(w12);

    // the stored shear force carried onto the new tangent plane (`transport_tangent`)
    let v = V3::gather(|j| states[j].shear_force);
    let a = V3::gather(|j| states[j].normal);
    let angle = spin * dt4;
    let rotated = transport_tangent_lanes(v, a, n, angle);

    // relative tangential velocity of the midpoint
    let v1 = V3::gather(|j| at.vel[n1[j]]);
    let v2 = V3::gather(|j| at.vel[n2[j]]);
    let us = v2.minus(v1).minus(w12.cross(n).scale(half * l));
    let us = us.minus(n.scale(n.dot(us)));
    // YADE's shear factor 2R/L where L > 0, else 1
    let yade = lanes(|j| Real::from(u8::from(classes[j].mode == LinkKinematicsMode::Yade)));
    let radius = lanes(|j| classes[j].radius);
    let alpha =
        (yade.simd_gt(zero) & l.simd_gt(zero)).select(f64x4::splat(2.0) * radius * inv_l, one);
    let kn = lanes(|j| springs[j].stiffness.kn);
    let ks = lanes(|j| springs[j].stiffness.ks) * alpha;
    let kt = lanes(|j| springs[j].stiffness.kt);
    let kb = lanes(|j| springs[j].stiffness.kb);
    let rest = lanes(|j| springs[j].rest_length);
    // (the plastic elongation of a fragile link is zero)
    let fn_ = kn * ((rest + zero) - l);
    let fs = rotated.minus(us.scale(ks * dt4));

    // moments from the relative rotation q2·q2⁰⁻¹·q1⁰·q1⁻¹ (`rotation_vector`, its series)
    fn quat(f: impl Fn(usize) -> UnitQuaternion<Real>) -> Q4 {
        let q: [UnitQuaternion<Real>; LANES] = std::array::from_fn(f);
        Q4 {
            w: f64x4::new(q.map(|q| q.w)),
            i: f64x4::new(q.map(|q| q.i)),
            j: f64x4::new(q.map(|q| q.j)),
            k: f64x4::new(q.map(|q| q.k)),
        }
    }
    let q2 = quat(|j| at.ori[n2[j]]);
    let r = quat(|j| states[j].rest_rotation);
    // (a unit quaternion's inverse is its conjugate: the same negations as nalgebra's)
    let q1 = quat(|j| at.ori[n1[j]]);
    let q1_inv = Q4 { w: q1.w, i: -q1.i, j: -q1.j, k: -q1.k };
    let q = q2.times(r).times(q1_inv);
    let qv = V3 { x: q.i, y: q.j, z: q.k };
    let s2 = qv.norm_squared();
    let aw = q.w.abs();
    let limit = f64x4::splat(ATAN_SERIES_BELOW) * aw;
    let inv_w = one / aw;
    let y = s2 * inv_w * inv_w;
    let series = atan_over_x_series(y, f64x4::splat);
    let factor = f64x4::splat(2.0) * inv_w * series;
    let sign = q.w & f64x4::splat(-0.0);
    let factor = factor.abs() | sign;
    // (a relative rotation beyond the series: 2·atan(|v|/|w|)·sign(w)/|v|, the four lanes'
    // atan together as the scalar law's `atan_of_ratio` computes each)
    let in_series = s2.simd_lt(limit * limit);
    let factor = if in_series.all() {
        factor
    } else {
        let s = s2.sqrt();
        let beyond = (f64x4::splat(2.0) * atan_of_ratio_lanes(s, aw)).abs() | sign;
        in_series.select(factor, beyond / s)
    };
    let theta = V3::select(s2.simd_eq(zero), V3::gather(|_| Vec3::zeros()), qv.scale(factor));
    let tw = n.scale(n.dot(theta));
    let mt = tw.scale(-kt);
    let mb = theta.minus(tw).scale(-kb);

    // energy (`spring_energy`, `spring_energy_squared`: zero for a stiffness ≤ 0)
    let fs2 = fs.norm_squared();
    let (mt2, mb2) = (mt.norm_squared(), mb.norm_squared());
    let energy = |num: f64x4, k: f64x4| k.simd_gt(zero).select(num / k, zero);
    let e = energy(half * fn_ * fn_, kn)
        + energy(half * fs2, ks)
        + energy(half * mt2, kt)
        + energy(half * mb2, kb);

    // loads (`assemble`)
    let f2 = n.scale(fn_).plus(fs);
    let lever = n.cross(fs).scale(f64x4::splat(-0.5) * l);
    let m = mt.plus(mb);

    // lanes that stay on the path: checked as the scalar law branches
    // the scalar law's own checks, in the lanes: a positive length, a normal not flipped
    // where there is a shear force, and (a NaN goes the scalar way, whose checks name it) a
    // finite turn and relative rotation (|x| < ∞ is false for a NaN)
    let infinite = f64x4::splat(Real::INFINITY);
    let sane = (l.simd_gt(zero)
        & !flipped(v, a, n)
        & angle.abs().simd_lt(infinite)
        & s2.abs().simd_lt(infinite))
    .to_bitmask();
    let fn_ = fn_.to_array();
    let (fs2, mt2, mb2, e) = (fs2.to_array(), mt2.to_array(), mb2.to_array(), e.to_array());
    let mut taken = 0;
    for j in 0..LANES {
        let lim = &classes[j].strength;
        let exceeds = |mag2: Real, cap: Real| cap < 0.0 || mag2 > cap * cap;
        let stays = ok[j]
            && sane & (1 << j) != 0
            && !lim.tensile_force.is_some_and(|tmax| -fn_[j] > tmax)
            && !lim.shear_limit(fn_[j]).is_some_and(|c| exceeds(fs2[j], c))
            && !lim.twist_moment.is_some_and(|c| exceeds(mt2[j], c))
            && !lim.bending_moment.is_some_and(|c| exceeds(mb2[j], c));
        if !stays {
            continue;
        }
        let state = &mut states[j];
        // (each lane read from the vectors where it is: `V3::lane`)
        state.normal = n.lane(j);
        state.shear_force = fs.lane(j);
        let load = LaneLoad {
            force_on_2: f2.lane(j),
            lever_torque: lever.lane(j),
            moment_on_2: m.lane(j),
            elastic_energy: e[j],
        };
        store(j, &load);
        taken |= 1 << j;
    }
    taken
}

/// [`atan_of_ratio`](crate::rotation::atan_of_ratio) of four lanes: each lane's reduction
/// chosen by selects (the quotient's numerator and denominator, the offset and its extra
/// bits), one division for the four, then the same rational function: the scalar function's
/// bits lane by lane.
#[inline(always)]
fn atan_of_ratio_lanes(s: f64x4, a: f64x4) -> f64x4 {
    let direct = s.simd_le(f64x4::splat(ATAN_DIRECT_UP_TO) * a);
    let offset = s.simd_le(f64x4::splat(ATAN_OFFSET_UP_TO) * a);
    let pick = |d: f64x4, o: f64x4, far: f64x4| direct.select(d, offset.select(o, far));
    let splat = f64x4::splat;
    let num = pick(s, s - a, -a);
    let den = pick(a, s + a, s);
    let base = pick(splat(0.0), splat(FRAC_PI_4), splat(FRAC_PI_2));
    let more = pick(splat(0.0), splat(0.5 * ATAN_MORE_BITS), splat(ATAN_MORE_BITS));
    atan_rational(num / den, base, more, splat)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::tests::{kinematics, mat, Sim};
    use crate::link::{update_link_parts, LinkKinematics, LinkPlastic};
    use crate::test_support::{unit_quaternion, unit_vec3, vec3};
    use nalgebra::UnitQuaternion;
    use proptest::prelude::*;

    fn bits(v: Vec3) -> [u64; 3] {
        v.map(Real::to_bits).into()
    }

    /// A link along `dir` loaded by `pre` (random increments through the scalar law), then the
    /// kinematics of one more step with velocities `v` and spins `w`.
    fn loaded(
        dir: Vec3,
        mode: LinkKinematicsMode,
        strong: bool,
        pre: &[Vec3],
        v: [Vec3; 2],
        w: [Vec3; 2],
        dt: Real,
    ) -> (Sim, LinkKinematics) {
        let m = if strong {
            mat()
        } else {
            mat().with_tensile_strength(Some(1e5)).with_shear_strength(Some(1e4))
        };
        let mut sim = Sim::along(dir, &m, mode);
        for step in pre.chunks(4) {
            sim.nudge(&[step[0], step[1], step[2], step[3]], 1e-4);
        }
        let x = std::array::from_fn::<Vec3, 2, _>(|i| sim.x[i] + v[i] * dt);
        let q = std::array::from_fn::<UnitQuaternion<Real>, 2, _>(|i| {
            UnitQuaternion::from_scaled_axis(w[i] * dt) * sim.q[i]
        });
        (sim, kinematics(x, q, v, w))
    }

    /// Runs four lanes and the scalar law on copies: a lane that took the path has the scalar
    /// update's state and loads to the bit, one that did not is untouched. Returns how many
    /// took it.
    fn compare(sims: &[Sim; LANES], kin: &[LinkKinematics; LANES], dt: Real) -> usize {
        let classes = std::array::from_fn(|j| &sims[j].p.class);
        let springs = std::array::from_fn(|j| &sims[j].p.spring);
        let mut states: [LinkState; LANES] = std::array::from_fn(|j| sims[j].s.clone());
        // each link's two nodes as particles 2j and 2j + 1
        let node = |f: &dyn Fn(&LinkKinematics) -> [Vec3; 2]| -> Vec<Vec3> {
            kin.iter().flat_map(f).collect()
        };
        let (pos, vel) = (node(&|k| [k.x1, k.x2]), node(&|k| [k.v1, k.v2]));
        let ang_vel = node(&|k| [k.w1, k.w2]);
        let ori: Vec<UnitQuaternion<Real>> = kin.iter().flat_map(|k| [k.q1, k.q2]).collect();
        let nodes = std::array::from_fn(|j| [2 * j, 2 * j + 1]);
        let at = LaneNodes { pos: &pos, vel: &vel, ang_vel: &ang_vel, ori: &ori, nodes };
        let mut loads = [None; LANES];
        let taken =
            update_link_lanes(classes, springs, &mut states, &at, dt, |j, l| loads[j] = Some(*l));
        let mut fast = 0;
        for j in 0..LANES {
            let (p, before) = (&sims[j].p, &sims[j].s);
            assert_eq!(taken & (1 << j) != 0, loads[j].is_some(), "lane {j}: the bits say");
            let Some(load) = loads[j] else {
                assert_eq!(&states[j], before, "lane {j} left the path: untouched");
                continue;
            };
            fast += 1;
            let mut scalar = before.clone();
            let mut plastic = LinkPlastic::default();
            let f = update_link_parts(&p.class, &p.spring, &mut scalar, &mut plastic, &kin[j], dt);
            assert_eq!(plastic, LinkPlastic::default());
            assert_eq!(f.event, crate::LinkEvent::None, "lane {j}");
            assert_eq!(f.dissipated.total(), 0.0, "lane {j}");
            assert_eq!(bits(states[j].normal), bits(scalar.normal), "lane {j} normal");
            assert_eq!(bits(states[j].shear_force), bits(scalar.shear_force), "lane {j} shear");
            assert_eq!(states[j].status, scalar.status);
            assert_eq!(states[j].rest_rotation, scalar.rest_rotation);
            assert_eq!(bits(load.force_on_2), bits(f.force_on_2), "lane {j} force");
            assert_eq!(bits(load.lever_torque), bits(f.lever_torque), "lane {j} lever");
            let m = f.twist_moment + f.bending_moment;
            assert_eq!(bits(load.moment_on_2), bits(m), "lane {j} moment");
            assert_eq!(
                load.elastic_energy.to_bits(),
                f.elastic_energy.to_bits(),
                "lane {j} energy {} vs {}",
                load.elastic_energy,
                f.elastic_energy
            );
        }
        fast
    }

    /// Four links bent, stretched and twisted a little, in both kinematics: all four take the
    /// path, with the scalar law's bits.
    #[test]
    fn small_motions_take_the_path_with_the_scalar_bits() {
        let dt = 1e-5;
        for mode in [LinkKinematicsMode::Beam, LinkKinematicsMode::Yade] {
            let dirs = [Vec3::x(), Vec3::y(), Vec3::new(1.0, 1.0, 0.3).normalize(), -Vec3::z()];
            let pairs: [(Sim, LinkKinematics); LANES] = std::array::from_fn(|j| {
                let s = 1e-4 * (j as Real + 1.0);
                let pre =
                    [Vec3::new(s, 0.0, 0.0), Vec3::new(0.0, s, 0.0), Vec3::y() * s, Vec3::z() * s];
                let v = [Vec3::new(0.01, -0.02, 0.005), Vec3::new(-0.01, 0.03, 0.0)];
                let w = [Vec3::new(0.1, 0.2, -0.1), Vec3::new(-0.3, 0.1, 0.2)];
                loaded(dirs[j], mode, true, &pre, v, w, dt)
            });
            let [a, b, c, d] = pairs;
            let mut kin = [a.1, b.1, c.1, d.1];
            // one node 2 turned as −q: the same rotation, the relative one's w negative
            kin[3].q2 = UnitQuaternion::new_unchecked(-kin[3].q2.into_inner());
            assert_eq!(compare(&[a.0, b.0, c.0, d.0], &kin, dt), LANES, "{mode:?}");
        }
    }

    /// Lanes off the path by the scalar law's own checks (a NaN spin, coincident nodes, a
    /// shear force whose normal flipped) are left to it, untouched; the fourth takes the path.
    #[test]
    fn nan_coincident_and_flipped_lanes_are_left_to_the_scalar_law() {
        let dt = 1e-5;
        let pre = [Vec3::new(1e-4, 0.0, 0.0), Vec3::y() * 1e-4, Vec3::y() * 1e-4, Vec3::z() * 1e-4];
        let v = [Vec3::new(0.01, -0.02, 0.005), Vec3::new(-0.01, 0.03, 0.0)];
        let w = [Vec3::new(0.1, 0.2, -0.1), Vec3::new(-0.3, 0.1, 0.2)];
        let mode = LinkKinematicsMode::Yade;
        let [a, b, mut c, d] =
            std::array::from_fn(|_| loaded(Vec3::x(), mode, true, &pre, v, w, dt));
        let mut kin = [a.1, b.1, c.1, d.1];
        kin[0].w2 = Vec3::new(Real::NAN, 0.0, 0.0);
        kin[1].x2 = kin[1].x1;
        assert_ne!(c.0.s.shear_force, Vec3::zeros());
        c.0.s.normal = -(kin[2].x2 - kin[2].x1).normalize();
        assert_eq!(compare(&[a.0, b.0, c.0, d.0], &kin, dt), 1);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// Random links (both kinematics, with and without limits, loaded by random
        /// increments, some of them past their limits), then a random step: every lane that
        /// takes the path matches the scalar law to the bit; the others are untouched.
        #[test]
        fn lanes_are_the_scalar_law_to_the_bit(
            dirs in prop::collection::vec(unit_vec3(), LANES),
            pre in prop::collection::vec(vec3(1.0), 4 * 2 * LANES),
            vel in prop::collection::vec(vec3(1.0), 4 * LANES),
            turn in prop::collection::vec(unit_quaternion(), LANES),
            yade in prop::collection::vec(any::<bool>(), LANES),
            strong in prop::collection::vec(any::<bool>(), LANES),
            scale in prop::collection::vec(0..4i32, LANES),
            flip in prop::collection::vec(any::<bool>(), LANES),
            big in prop::collection::vec(0..3u8, LANES),
        ) {
            let dt = 1e-5;
            let pairs: Vec<(Sim, LinkKinematics)> = (0..LANES)
                .map(|j| {
                    let mode =
                        if yade[j] { LinkKinematicsMode::Yade } else { LinkKinematicsMode::Beam };
                    // increments from 1e-7 to 1e-4 m (and rad): some links pass their limits
                    let size = 10f64.powi(-7 + scale[j]);
                    let pre: Vec<Vec3> = pre[8 * j..8 * j + 8].iter().map(|x| x * size).collect();
                    let v = [vel[4 * j] * 0.05, vel[4 * j + 2] * 0.05];
                    // big = 1: spins of up to 1000 rad/s, turns of 1e-2 in the step
                    // (beyond the twist's series); big = 2: a large relative rotation
                    // (beyond the rotation vector's series)
                    let spin = if big[j] == 1 { 1000.0 } else { 2.0 };
                    let w = [vel[4 * j + 1] * spin, turn[j] * vel[4 * j + 3] * spin];
                    let (mut sim, kin) = loaded(dirs[j], mode, strong[j], &pre, v, w, dt);
                    if big[j] == 2 {
                        sim.s.rest_rotation = turn[j] * sim.s.rest_rotation;
                    }
                    (sim, kin)
                })
                .collect();
            // node 2's orientation as −q (the same rotation: the relative rotation's w < 0)
            let kin: [LinkKinematics; LANES] = std::array::from_fn(|j| {
                let mut k = pairs[j].1;
                if flip[j] {
                    k.q2 = UnitQuaternion::new_unchecked(-k.q2.into_inner());
                }
                k
            });
            let sims: Vec<Sim> = pairs.into_iter().map(|p| p.0).collect();
            let sims: [Sim; LANES] = sims.try_into().ok().expect("four links");
            compare(&sims, &kin, dt);
        }
    }
}
