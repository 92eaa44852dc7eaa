//! Beam-link kinematics: the frame-element stiffness matrix, yade mode, objectivity and energy.

use super::*;
use crate::test_support::{close, unit_quaternion, unit_vec3, vec3};
use nalgebra::DMatrix;
use proptest::prelude::*;

pub(crate) const L: Real = 0.1;
pub(crate) const R: Real = 0.01;

pub(crate) fn mat() -> Material {
    Material::new(1e8, 0.3, 1000.0, 0.5).unwrap()
}

/// The kinematics of two nodes at `x`, turned to `q`, moving at `v` and spinning at `w`.
pub(crate) fn kinematics(
    x: [Vec3; 2],
    q: [UnitQuaternion<Real>; 2],
    v: [Vec3; 2],
    w: [Vec3; 2],
) -> LinkKinematics {
    LinkKinematics {
        x1: x[0],
        x2: x[1],
        v1: v[0],
        v2: v[1],
        w1: w[0],
        w2: w[1],
        q1: q[0],
        q2: q[1],
    }
}

/// Two nodes joined by one link, advanced by prescribed velocities with q ← exp(ω·dt)·q.
pub(crate) struct Sim {
    pub p: LinkParams,
    pub s: LinkState,
    pub plastic: LinkPlastic,
    pub x: [Vec3; 2],
    pub q: [UnitQuaternion<Real>; 2],
    pub last: LinkForces,
    /// Energy the link has dissipated (the updates' sum).
    pub dissipated: Dissipation,
    /// Work done on the link by the nodes (trapezoid in time).
    pub work: Real,
}

impl Sim {
    pub fn new(p: LinkParams, x: [Vec3; 2], q: [UnitQuaternion<Real>; 2]) -> Self {
        let s = LinkState::new(x[0], x[1], q[0], q[1]);
        Sim {
            p,
            s,
            plastic: LinkPlastic::default(),
            x,
            q,
            last: LinkForces::default(),
            dissipated: Dissipation::default(),
            work: 0.0,
        }
    }

    /// Link of length L along `dir` from the origin, made of `m`, in `mode`.
    pub fn along(dir: Vec3, m: &Material, mode: LinkKinematicsMode) -> Self {
        let x2 = dir * L;
        // The rest length as a builder would measure it (|dir·L| may differ from L by round-off).
        let p = LinkParams::from_material(m, R, x2.norm(), mode);
        Sim::new(p, [Vec3::zeros(), x2], [UnitQuaternion::identity(); 2])
    }

    /// Advances the nodes with q ← exp(ω·dt)·q, x ← x + v·dt, then updates the link.
    pub fn step(&mut self, v: [Vec3; 2], w: [Vec3; 2], dt: Real) -> LinkForces {
        let x = std::array::from_fn(|i| self.x[i] + v[i] * dt);
        let q = std::array::from_fn(|i| UnitQuaternion::from_scaled_axis(w[i] * dt) * self.q[i]);
        self.apply(x, q, v, w, dt)
    }

    /// Sets the end-of-step poses and velocities, updates the link and accumulates the work.
    pub fn apply(
        &mut self,
        x: [Vec3; 2],
        q: [UnitQuaternion<Real>; 2],
        v: [Vec3; 2],
        w: [Vec3; 2],
        dt: Real,
    ) -> LinkForces {
        self.x = x;
        self.q = q;
        let kin = kinematics(x, q, v, w);
        let f = update_link(&self.p, &mut self.s, &mut self.plastic, &kin, dt);
        self.dissipated += f.dissipated;
        let o = &self.last;
        self.work -= 0.5
            * ((o.force_on_1 + f.force_on_1).dot(&v[0])
                + (o.force_on_2 + f.force_on_2).dot(&v[1])
                + (o.torque_on_1 + f.torque_on_1).dot(&w[0])
                + (o.torque_on_2 + f.torque_on_2).dot(&w[1]))
            * dt;
        self.last = f;
        f
    }

    /// Moves by small increments (u1, θ1, u2, θ2) in one step.
    pub fn nudge(&mut self, d: &[Vec3; 4], dt: Real) -> LinkForces {
        self.step([d[0] / dt, d[2] / dt], [d[1] / dt, d[3] / dt], dt)
    }
}

/// The 12×12 Euler–Bernoulli frame-element stiffness matrix in local axes (x along the beam),
/// DOF order (u1, θ1, u2, θ2), each a 3-vector.
fn local_frame_matrix(ea: Real, ei: Real, gj: Real, l: Real) -> DMatrix<Real> {
    let mut k = DMatrix::zeros(12, 12);
    let mut set = |i: usize, j: usize, v: Real| {
        k[(i, j)] = v;
        k[(j, i)] = v;
    };
    let (a, t) = (ea / l, gj / l);
    let (b12, b6, b4, b2) =
        (12.0 * ei / l.powi(3), 6.0 * ei / l.powi(2), 4.0 * ei / l, 2.0 * ei / l);
    // Axial u_x: 0, 6. Torsion θ_x: 3, 9.
    set(0, 0, a);
    set(6, 6, a);
    set(0, 6, -a);
    set(3, 3, t);
    set(9, 9, t);
    set(3, 9, -t);
    // Bending in the xy plane: v = 1, 7; θz = 5, 11.
    set(1, 1, b12);
    set(7, 7, b12);
    set(1, 7, -b12);
    set(1, 5, b6);
    set(1, 11, b6);
    set(5, 7, -b6);
    set(7, 11, -b6);
    set(5, 5, b4);
    set(11, 11, b4);
    set(5, 11, b2);
    // Bending in the xz plane: w = 2, 8; θy = 4, 10 (coupling signs flip).
    set(2, 2, b12);
    set(8, 8, b12);
    set(2, 8, -b12);
    set(2, 4, -b6);
    set(2, 10, -b6);
    set(4, 8, b6);
    set(8, 10, b6);
    set(4, 4, b4);
    set(10, 10, b4);
    set(4, 10, b2);
    k
}

/// The frame matrix for a beam along the unit `dir` (K_global = B·K_local·Bᵀ, B = diag(Q,Q,Q,Q)
/// with Q = [e1 e2 e3], e1 = dir).
fn global_frame_matrix(dir: Vec3, ea: Real, ei: Real, gj: Real, l: Real) -> DMatrix<Real> {
    let e2 = crate::test_support::any_perpendicular(dir);
    let e3 = dir.cross(&e2);
    let mut b = DMatrix::zeros(12, 12);
    for blk in 0..4 {
        for (c, e) in [dir, e2, e3].iter().enumerate() {
            for r in 0..3 {
                b[(3 * blk + r, 3 * blk + c)] = e[r];
            }
        }
    }
    &b * local_frame_matrix(ea, ei, gj, l) * b.transpose()
}

/// The 12×12 matrix measured from the link by central differences: column j =
/// −[(F1, T1, F2, T2)(+ε e_j) − (…)(−ε e_j)]/(2ε) for one-step increments ±ε along DOF j
/// (translations scaled by L), from a fresh link with node orientations `q`.
fn measured_matrix(
    dir: Vec3,
    q: [UnitQuaternion<Real>; 2],
    mode: LinkKinematicsMode,
    eps: Real,
) -> DMatrix<Real> {
    let mut k = DMatrix::zeros(12, 12);
    for j in 0..12 {
        let scale = if (j / 3) % 2 == 0 { L } else { 1.0 };
        let mut cols = [[Vec3::zeros(); 4]; 2];
        for (c, sign) in [1.0, -1.0].into_iter().enumerate() {
            let mut sim = Sim::along(dir, &mat(), mode);
            sim.q = q;
            sim.s = LinkState::new(sim.x[0], sim.x[1], q[0], q[1]);
            let mut d = [Vec3::zeros(); 4];
            d[j / 3][j % 3] = sign * eps * scale;
            let f = sim.nudge(&d, 1e-3);
            cols[c] = [f.force_on_1, f.torque_on_1, f.force_on_2, f.torque_on_2];
        }
        for i in 0..12 {
            k[(i, j)] = -(cols[0][i / 3][i % 3] - cols[1][i / 3][i % 3]) / (2.0 * eps * scale);
        }
    }
    k
}

fn section() -> (Real, Real, Real) {
    let m = mat();
    let a = std::f64::consts::PI * R * R;
    let i = std::f64::consts::PI * R.powi(4) / 4.0;
    (m.young * a, m.young * i, m.shear_modulus() * 2.0 * i)
}

/// Compares entry by entry: relative 1e-6 on non-zero entries, and zero entries below 1e-6 of
/// the smallest non-zero entry of the same kind (force/displacement, force/rotation, ...).
fn assert_matrix_close(got: &DMatrix<Real>, want: &DMatrix<Real>, tol: Real) {
    let (ea, ei, gj) = section();
    let kind_floor = |i: usize, j: usize| match ((i / 3) % 2, (j / 3) % 2) {
        (0, 0) => (12.0 * ei / L.powi(3)).min(ea / L),
        (1, 1) => (ei / L).min(gj / L),
        _ => 6.0 * ei / L.powi(2),
    };
    for i in 0..12 {
        for j in 0..12 {
            let (g, w) = (got[(i, j)], want[(i, j)]);
            let err = (g - w).abs();
            assert!(err <= tol * w.abs().max(kind_floor(i, j)), "K[{i},{j}]: got {g}, want {w}");
        }
    }
}

#[test]
fn beam_mode_is_the_euler_bernoulli_frame_element_along_x() {
    let (ea, ei, gj) = section();
    let want = global_frame_matrix(Vec3::x(), ea, ei, gj, L);
    let got =
        measured_matrix(Vec3::x(), [UnitQuaternion::identity(); 2], LinkKinematicsMode::Beam, 1e-6);
    assert_matrix_close(&got, &want, 1e-6);
    // Spot checks of the classical entries (node 2 rows).
    assert!((got[(6, 6)] - ea / L).abs() < 1e-6 * ea / L);
    assert!((got[(7, 7)] - 12.0 * ei / L.powi(3)).abs() < 1e-6 * 12.0 * ei / L.powi(3));
    assert!((got[(11, 11)] - 4.0 * ei / L).abs() < 1e-6 * ei / L);
    assert!((got[(11, 5)] - 2.0 * ei / L).abs() < 1e-6 * ei / L);
    assert!((got[(9, 9)] - gj / L).abs() < 1e-6 * gj / L);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn beam_mode_is_the_frame_element_in_any_direction_and_node_orientation(
        dir in unit_vec3(), q1 in unit_quaternion(), q2 in unit_quaternion(),
    ) {
        let (ea, ei, gj) = section();
        let want = global_frame_matrix(dir, ea, ei, gj, L);
        let got = measured_matrix(dir, [q1, q2], LinkKinematicsMode::Beam, 1e-6);
        assert_matrix_close(&got, &want, 1e-6);
    }
}

/// Tip deflection of a one-element cantilever (node 1 clamped, tip load P across the axis,
/// no tip moment) from the measured (v2, θz2) stiffness block.
fn cantilever_tip(mode: LinkKinematicsMode, p_load: Real) -> Real {
    let k = measured_matrix(Vec3::x(), [UnitQuaternion::identity(); 2], mode, 1e-6);
    let k22 = nalgebra::Matrix2::new(k[(7, 7)], k[(7, 11)], k[(11, 7)], k[(11, 11)]);
    let sol = k22.lu().solve(&nalgebra::Vector2::new(p_load, 0.0)).unwrap();
    sol[0]
}

#[test]
fn yade_mode_is_softer_in_shear_as_documented() {
    let (ea, ei, gj) = section();
    let p = 0.01;
    let beam = cantilever_tip(LinkKinematicsMode::Beam, p);
    assert!((beam / (p * L.powi(3) / (3.0 * ei)) - 1.0).abs() < 1e-6, "{beam}");
    // Reference §5.4: PL³/(4EI) + PL³/(12βEI), β = 2r/L.
    let beta = 2.0 * R / L;
    let want = p * L.powi(3) / (4.0 * ei) + p * L.powi(3) / (12.0 * beta * ei);
    let yade = cantilever_tip(LinkKinematicsMode::Yade, p);
    assert!((yade / want - 1.0).abs() < 1e-6, "{yade} vs {want}");
    // Axial, torsion and pure bending terms are those of beam mode.
    let k =
        measured_matrix(Vec3::x(), [UnitQuaternion::identity(); 2], LinkKinematicsMode::Yade, 1e-6);
    assert!((k[(6, 6)] - ea / L).abs() < 1e-6 * ea / L);
    assert!((k[(9, 9)] - gj / L).abs() < 1e-6 * gj / L);
    // θ2 column, moment rows: 3EI/L·β + EI/L on the diagonal, 3EI/L·β − EI/L across.
    assert!((k[(11, 11)] - (3.0 * beta + 1.0) * ei / L).abs() < 1e-6 * ei / L);
    assert!((k[(5, 11)] - (3.0 * beta - 1.0) * ei / L).abs() < 1e-6 * ei / L);
}

#[test]
fn rigid_motion_of_a_loaded_link_changes_no_force() {
    // Load the link (stretch, shear, bend, twist), then move both nodes as one rigid body:
    // spin about an oblique axis while translating. Magnitudes stay; vectors turn with R(t).
    for mode in [LinkKinematicsMode::Beam, LinkKinematicsMode::Yade] {
        let mut sim = Sim::along(Vec3::new(1.0, 0.5, -0.2).normalize(), &mat(), mode);
        let load = [
            Vec3::zeros(),
            Vec3::new(0.0, 0.0, 1e-3),
            Vec3::new(1e-5, -2e-4, 3e-4),
            Vec3::new(2e-3, -1e-3, 4e-3),
        ];
        let f0 = sim.nudge(&load, 1e-3);
        assert!(f0.shear_force.norm() > 0.0 && f0.bending_moment.norm() > 0.0);
        assert!(f0.twist_moment.norm() > 0.0 && f0.normal_force != 0.0);
        let (omega, vel, dt) = (Vec3::new(0.4, -1.2, 0.9), Vec3::new(0.3, 0.1, -0.2), 1e-4);
        let (x0, q0) = (sim.x, sim.q);
        let c0 = (x0[0] + x0[1]) * 0.5;
        for k in 1..=4000 {
            let t = k as Real * dt;
            let rot = UnitQuaternion::from_scaled_axis(omega * t);
            let c = c0 + vel * t;
            // Exact rigid motion at the end of the step, with its instantaneous velocities.
            let x: [Vec3; 2] = std::array::from_fn(|i| c + rot * (x0[i] - c0));
            let q = q0.map(|q| rot * q);
            let v = x.map(|xi| vel + omega.cross(&(xi - c)));
            let f = sim.apply(x, q, v, [omega; 2], dt);
            let tol = 1e-9;
            assert!(
                (f.normal_force - f0.normal_force).abs() <= tol * f0.normal_force.abs(),
                "{mode:?} {k}"
            );
            assert!(
                (f.shear_force.norm() - f0.shear_force.norm()).abs() <= tol * f0.shear_force.norm()
            );
            assert!(
                (f.twist_moment.norm() - f0.twist_moment.norm()).abs()
                    <= tol * f0.twist_moment.norm()
            );
            assert!(
                (f.bending_moment.norm() - f0.bending_moment.norm()).abs()
                    <= tol * f0.bending_moment.norm()
            );
            if k % 1000 == 0 {
                assert!(close(f.shear_force, rot * f0.shear_force, 1e-5, 0.0), "{mode:?} {k}");
                assert!(close(f.bending_moment, rot * f0.bending_moment, 1e-9, 0.0));
                assert!(close(f.force_on_1, rot * f0.force_on_1, 1e-6, 0.0));
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The energy made from the kept parts of an update (normal force, summed moment, the
    /// state's shear force and normal, the length) is the update's, through random motions
    /// of elastic, plastic and fragile links in both kinematics, to breakage.
    #[test]
    fn elastic_energy_from_the_kept_parts_is_the_updates(
        dir in unit_vec3(),
        moves in prop::collection::vec(vec3(1.0), 4 * 6),
        yade in any::<bool>(), failure in 0..3u8,
    ) {
        let mode = if yade { LinkKinematicsMode::Yade } else { LinkKinematicsMode::Beam };
        let m = match failure {
            0 => mat(),
            1 => mat().with_failure(FailureMode::Plastic)
                .with_tensile_strength(Some(1e5)).with_shear_strength(Some(1e4)),
            _ => mat().with_tensile_strength(Some(1e5)).with_shear_strength(Some(1e4)),
        };
        let mut sim = Sim::along(dir, &m, mode);
        for step in moves.chunks(4) {
            let f = sim.nudge(&[step[0] * 2e-3, step[1] * 0.05, step[2] * 2e-3, step[3] * 0.05], 1e-4);
            let l = (sim.x[1] - sim.x[0]).norm();
            let m_on_2 = f.twist_moment + f.bending_moment;
            let e = link_elastic_energy(&sim.p.class, &sim.p.spring, &sim.s, f.normal_force, &m_on_2, l);
            prop_assert!(
                (e - f.elastic_energy).abs() <= 1e-9 * f.elastic_energy.max(1e-300),
                "{} vs the update's {} ({:?})", e, f.elastic_energy, sim.s.status
            );
        }
    }

    #[test]
    fn objectivity_rotating_and_translating_everything(
        dir in unit_vec3(),
        q1 in unit_quaternion(), q2 in unit_quaternion(),
        pre in prop::collection::vec(vec3(1e-3), 4),
        vel in prop::collection::vec(vec3(1.0), 4),
        rot in unit_quaternion(), shift in vec3(10.0),
        yade in any::<bool>(), plastic in any::<bool>(),
    ) {
        // A link loaded by one random increment, then one more random update: the same update
        // with everything rotated by `rot` and shifted by `shift` (state included) gives the
        // rotated forces.
        let mode = if yade { LinkKinematicsMode::Yade } else { LinkKinematicsMode::Beam };
        let m = if plastic {
            mat().with_failure(FailureMode::Plastic)
                .with_tensile_strength(Some(1e5)).with_shear_strength(Some(1e4))
        } else { mat() };
        let p = LinkParams::from_material(&m, R, L, mode);
        let mut a = Sim::new(p, [Vec3::zeros(), dir * L], [q1, q2]);
        a.nudge(&[pre[0] * L, pre[1], pre[2] * L, pre[3]], 1e-3);
        let mut b = Sim::new(p, [shift, shift + rot * (dir * L)], [rot * q1, rot * q2]);
        // (the rest rotation q2⁰⁻¹·q1⁰ and the plastic rotation, in node 1's body frame, do
        // not turn with the world)
        b.s = LinkState {
            normal: rot * a.s.normal,
            shear_force: rot * a.s.shear_force,
            ..a.s.clone()
        };
        b.plastic = a.plastic;
        b.x = [rot * a.x[0] + shift, rot * a.x[1] + shift];
        b.q = [rot * a.q[0], rot * a.q[1]];
        let dt = 1e-4;
        let v = [vel[0], vel[2]].map(|x| x * 1e-2);
        let w = [vel[1], vel[3]];
        let fa = a.step(v, w, dt);
        let fb = b.step(v.map(|x| rot * x), w.map(|x| rot * x), dt);
        prop_assert_eq!(fa.event, fb.event);
        let fs = fa.force_on_2.norm().max(1e-12);
        let ts = fa.torque_on_2.norm().max(fa.torque_on_1.norm()).max(1e-12);
        prop_assert!((fa.normal_force - fb.normal_force).abs() <= 1e-8 * fs);
        prop_assert!((rot * fa.force_on_2 - fb.force_on_2).norm() <= 1e-8 * fs);
        prop_assert!((rot * fa.torque_on_1 - fb.torque_on_1).norm() <= 1e-8 * ts);
        prop_assert!((rot * fa.torque_on_2 - fb.torque_on_2).norm() <= 1e-8 * ts);
        prop_assert!((fa.elastic_energy - fb.elastic_energy).abs() <= 1e-8 * fa.elastic_energy.max(1e-12));
    }

    #[test]
    fn closed_elastic_paths_return_zero_net_work(
        dir in unit_vec3(),
        legs in prop::collection::vec(prop::collection::vec(vec3(1.0), 4), 2..5),
        yade in any::<bool>(),
        same_path_back in any::<bool>(),
    ) {
        // Out along random legs, then back: the same legs reversed (same path) or the negated
        // legs in the same order (a different path closing the loop). Amplitudes 1e-4·L and
        // 1e-4 rad keep the link in the small-rotation, elastic range.
        let mode = if yade { LinkKinematicsMode::Yade } else { LinkKinematicsMode::Beam };
        let mut sim = Sim::along(dir, &mat(), mode);
        let (dt, steps) = (1e-3, 50);
        let amp = 1e-4 / (steps as Real * dt);
        let mut seq: Vec<[Vec3; 4]> = legs
            .iter()
            .map(|l| [l[0] * amp * L, l[1] * amp, l[2] * amp * L, l[3] * amp])
            .collect();
        let back: Vec<[Vec3; 4]> = if same_path_back {
            seq.iter().rev().map(|l| l.map(|x| -x)).collect()
        } else {
            seq.iter().map(|l| l.map(|x| -x)).collect()
        };
        seq.extend(back);
        let mut e_max: Real = 0.0;
        for l in &seq {
            for _ in 0..steps {
                let f = sim.step([l[0], l[2]], [l[1], l[3]], dt);
                e_max = e_max.max(f.elastic_energy);
            }
        }
        prop_assert!(e_max > 0.0);
        prop_assert!(sim.work.abs() <= 1e-3 * e_max, "net work {} vs E_max {}", sim.work, e_max);
        prop_assert!(sim.last.elastic_energy <= 1e-3 * e_max);
        prop_assert_eq!(sim.dissipated.total(), 0.0);
    }
}

#[test]
fn work_done_equals_stored_energy_on_an_elastic_path() {
    // Random-looking but fixed smooth path: the trapezoidal work equals the change of the
    // reported elastic energy (to O(dt²) and O(θ²)), in both modes.
    for mode in [LinkKinematicsMode::Beam, LinkKinematicsMode::Yade] {
        let mut sim = Sim::along(Vec3::new(0.3, -0.8, 0.5).normalize(), &mat(), mode);
        let dt = 1e-3;
        let mut last = 0.0;
        for k in 0..400 {
            let t = k as Real * dt;
            let s = (7.0 * t).sin();
            let c = (3.0 * t).cos();
            let v = [Vec3::new(1e-6 * c, 0.0, -2e-6 * s), Vec3::new(2e-6 * s, 3e-6 * c, 1e-6)];
            let w = [Vec3::new(1e-4 * s, -2e-4, 1e-4 * c), Vec3::new(3e-4 * c, 1e-4 * s, -1e-4)];
            last = sim.step(v, w, dt).elastic_energy;
        }
        assert!(last > 0.0);
        assert!((sim.work - last).abs() <= 1e-3 * last, "{mode:?}: work {} vs E {last}", sim.work);
    }
}

#[test]
fn moments_off_gives_no_moment() {
    let mut sim = Sim::along(Vec3::x(), &mat().with_moments(false), LinkKinematicsMode::Beam);
    let f =
        sim.nudge(&[Vec3::zeros(), Vec3::zeros(), Vec3::zeros(), Vec3::new(1e-3, 2e-3, 0.0)], 1e-3);
    assert_eq!(f.twist_moment, Vec3::zeros());
    assert_eq!(f.bending_moment, Vec3::zeros());
    // Rotating node 2 still shears the link through the (L/2)·ω × n term.
    assert!(f.shear_force.norm() > 0.0);
}
