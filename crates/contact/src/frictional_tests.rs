use super::*;
use crate::test_support::{
    any_perpendicular, close, log_uniform, unit_quaternion, unit_vec3, vec3,
};
use nalgebra::UnitQuaternion;
use proptest::prelude::*;

fn params(kn: Real, shear_ratio: Real, tan_phi: Real) -> FrictionalParams {
    FrictionalParams { kn, ks: kn * shear_ratio, tan_phi, cn: 0.0, ct: 0.0 }
}

/// Two spheres, body 1 fixed at the origin, body 2 centred at `x2`, radii summing to `s`,
/// no rotation: the contact point's relative velocity is v2.
fn two_sphere_kin(x2: Vec3, v2: Vec3, s: Real) -> ContactKinematics {
    let d = x2.norm();
    ContactKinematics {
        normal: x2 / d,
        overlap: s - d,
        relative_velocity: v2,
        spin_about_normal: 0.0,
    }
}

/// Drives body 2 through the velocities `vs` (one per step) from `x0`; returns the work done on
/// the contact (trapezoid), the final elastic energy, and the dissipation.
fn drive(
    p: &FrictionalParams,
    x0: Vec3,
    s: Real,
    vs: &[Vec3],
    dt: Real,
) -> (Real, Real, Real, Vec<Real>) {
    let mut x = x0;
    let k0 = two_sphere_kin(x, Vec3::zeros(), s);
    let mut st = FrictionalContact::new(k0.normal);
    let mut f_old = update_frictional_contact(p, &mut st, &k0, dt);
    let mut work = 0.0;
    let mut incs = Vec::new();
    let e0 = f_old.elastic_energy;
    for &v in vs {
        x += v * dt;
        let f = update_frictional_contact(p, &mut st, &two_sphere_kin(x, v, s), dt);
        work -= 0.5 * (f_old.force_on_2 + f.force_on_2).dot(&(v * dt));
        incs.push(f.dissipated.friction);
        f_old = f;
    }
    (work, f_old.elastic_energy - e0, st.dissipated_friction, incs)
}

#[test]
fn separation_gives_no_force_and_resets_history() {
    let p = params(1e6, 0.5, 0.5);
    let n = Vec3::z();
    let mut st = FrictionalContact::new(n);
    let kin = ContactKinematics {
        normal: n,
        overlap: 1e-4,
        relative_velocity: Vec3::x(),
        spin_about_normal: 0.0,
    };
    let f = update_frictional_contact(&p, &mut st, &kin, 1e-5);
    assert!((f.normal_force - 100.0).abs() < 1e-9);
    assert!(st.shear_force.norm() > 0.0);
    let f =
        update_frictional_contact(&p, &mut st, &ContactKinematics { overlap: 0.0, ..kin }, 1e-5);
    assert_eq!(f, ContactForces::default());
    assert_eq!(st.shear_force, Vec3::zeros());
}

#[test]
fn shear_opposes_relative_sliding_of_body_2() {
    // Body 2 moves +x relative to body 1: the shear force on body 2 points −x (eq 2).
    let p = params(1e6, 0.5, 10.0);
    let mut st = FrictionalContact::new(Vec3::z());
    let kin = ContactKinematics {
        normal: Vec3::z(),
        overlap: 1e-3,
        relative_velocity: Vec3::new(2.0, 0.0, 5.0),
        spin_about_normal: 0.0,
    };
    let f = update_frictional_contact(&p, &mut st, &kin, 1e-4);
    // ks·u̇s·dt = 5e5·2·1e-4 = 100; the normal part of the velocity is ignored.
    assert!((f.shear_force - Vec3::new(-100.0, 0.0, 0.0)).norm() < 1e-9);
    assert!((f.force_on_2 - Vec3::new(-100.0, 0.0, 1000.0)).norm() < 1e-9);
    assert!(!f.sliding);
    let e = 1000.0_f64.powi(2) / 2e6 + 100.0_f64.powi(2) / 1e6;
    assert!((f.elastic_energy - e).abs() < 1e-9);
}

#[test]
fn steady_sliding_dissipates_force_times_distance() {
    let p = params(1e6, 0.5, 0.3);
    let (dt, v, overlap) = (1e-4, 0.5, 1e-3);
    let mut st = FrictionalContact::new(Vec3::z());
    let kin = ContactKinematics {
        normal: Vec3::z(),
        overlap,
        relative_velocity: Vec3::x() * v,
        spin_about_normal: 0.0,
    };
    let mut last = ContactForces::default();
    for _ in 0..200 {
        last = update_frictional_contact(&p, &mut st, &kin, dt);
    }
    let cap = 1000.0 * 0.3;
    assert!(last.sliding);
    assert!((last.shear_force - Vec3::x() * -cap).norm() < 1e-9);
    // In steady sliding each step dissipates cap·v·dt exactly.
    assert!((last.dissipated.friction - cap * v * dt).abs() < 1e-12);
}

#[test]
fn twist_rotates_the_stored_shear_force() {
    let p = params(1e6, 0.5, 10.0);
    let mut st = FrictionalContact::new(Vec3::z());
    st.shear_force = Vec3::x() * 3.0;
    let kin = ContactKinematics {
        normal: Vec3::z(),
        overlap: 1e-3,
        relative_velocity: Vec3::zeros(),
        spin_about_normal: std::f64::consts::FRAC_PI_2,
    };
    let f = update_frictional_contact(&p, &mut st, &kin, 1.0);
    assert!((f.shear_force - Vec3::y() * 3.0).norm() < 1e-14);
}

#[test]
fn rigid_rotation_of_both_bodies_changes_no_force() {
    // A loaded contact whose two bodies turn together about an oblique axis: the normal and the
    // stored shear force turn with them; the magnitudes stay, and the shear force follows R(t).
    let p = params(1e6, 0.5, 0.8);
    let omega = Vec3::new(0.3, -1.1, 0.7);
    let n0 = Vec3::new(0.2, 0.1, 1.0).normalize();
    let mut st = FrictionalContact::new(n0);
    st.shear_force = any_perpendicular(n0) * 150.0;
    let dt = 1e-4;
    let overlap = 1e-3;
    for k in 1..=5000 {
        let r = UnitQuaternion::from_scaled_axis(omega * (k as Real * dt));
        let n = r * n0;
        let kin = ContactKinematics {
            normal: n,
            overlap,
            relative_velocity: Vec3::zeros(),
            spin_about_normal: n.dot(&omega),
        };
        let f = update_frictional_contact(&p, &mut st, &kin, dt);
        assert!((f.shear_force.norm() - 150.0).abs() < 1e-10, "{k} {}", f.shear_force.norm());
        assert!((f.normal_force - 1000.0).abs() < 1e-9);
        if k % 1000 == 0 {
            let expected = r * (any_perpendicular(n0) * 150.0);
            assert!(close(f.shear_force, expected, 1e-6, 1.0), "{k}");
        }
    }
}

#[test]
fn closed_elastic_path_returns_zero_work() {
    // Body 2 goes around a small closed loop (a square in the tangent plane, with a normal
    // indentation leg) well below the Coulomb limit.
    let p = params(1e6, 0.4, 100.0);
    let s = 0.02;
    let x0 = Vec3::new(0.0, 0.0, s - 1e-3);
    let (dt, v, n) = (1e-4, 1e-3, 400);
    let legs = [Vec3::x(), Vec3::y(), -Vec3::z(), -Vec3::x(), -Vec3::y(), Vec3::z()];
    let vs: Vec<Vec3> = legs.iter().flat_map(|d| std::iter::repeat_n(d * v, n)).collect();
    let (work, de, diss, _) = drive(&p, x0, s, &vs, dt);
    assert_eq!(diss, 0.0);
    let e_scale = 1e6 * 1e-3 * 1e-3; // kn·δ²
    assert!(work.abs() < 1e-6 * e_scale, "net work {work}");
    assert!(de.abs() < 1e-6 * e_scale, "energy change {de}");
}

/// A run of 1 to 19 updates of a contact: the direction the normal tilts towards, the tilt,
/// the overlap, the relative velocity, the spin about the normal and the step.
fn law_steps() -> impl Strategy<Value = Vec<(Vec3, Real, Real, Vec3, Real, Real)>> {
    prop::collection::vec(
        (
            unit_vec3(),
            0.0..0.3_f64,
            -1e-3..1e-2_f64,
            vec3(10.0),
            -50.0..50.0_f64,
            log_uniform(1e-7, 1e-2),
        ),
        1..20,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn coulomb_holds_after_every_update(
        kn in log_uniform(1e2, 1e9),
        ratio in 0.0..1.0_f64,
        tan_phi in 0.0..2.0_f64,
        n0 in unit_vec3(),
        steps in law_steps(),
    ) {
        let p = params(kn, ratio, tan_phi);
        let mut st = FrictionalContact::new(n0);
        let mut n = n0;
        for (dir, tilt, overlap, v, spin, dt) in steps {
            n = (n + dir * tilt).normalize();
            let kin = ContactKinematics {
                normal: n, overlap, relative_velocity: v, spin_about_normal: spin,
            };
            let f = update_frictional_contact(&p, &mut st, &kin, dt);
            let limit = (kn * overlap).max(0.0) * tan_phi;
            prop_assert!(f.shear_force.norm() <= limit * (1.0 + 1e-12) + 1e-300);
            prop_assert!(f.shear_force.dot(&n).abs() <= 1e-12 * f.shear_force.norm() + 1e-300);
            prop_assert!(f.dissipated.friction >= 0.0);
            prop_assert!(f.normal_force >= 0.0);
            prop_assert_eq!(st.shear_force, f.shear_force);
        }
    }

    #[test]
    fn objectivity_rotating_everything_rotates_the_result(
        kn in log_uniform(1e2, 1e9),
        tan_phi in 0.0..2.0_f64,
        n_old in unit_vec3(),
        fs_dir in unit_vec3(),
        fs_mag in 0.0..1.0_f64,
        tilt in vec3(0.5),
        overlap in 1e-6..1e-2_f64,
        v in vec3(5.0),
        spin in -20.0..20.0_f64,
        dt in log_uniform(1e-6, 1e-2),
        rot in unit_quaternion(),
    ) {
        let p = params(kn, 0.7, tan_phi);
        let t = fs_dir - n_old * n_old.dot(&fs_dir);
        let fs = t * (fs_mag * kn * overlap * tan_phi / t.norm().max(1e-300));
        let n_new = (n_old + tilt).normalize();
        let mut a = FrictionalContact { shear_force: fs, ..FrictionalContact::new(n_old) };
        let mut b = FrictionalContact { shear_force: rot * fs, ..FrictionalContact::new(rot * n_old) };
        let ka = ContactKinematics {
            normal: n_new, overlap, relative_velocity: v, spin_about_normal: spin,
        };
        let kb = ContactKinematics {
            normal: rot * n_new, relative_velocity: rot * v, ..ka
        };
        let fa = update_frictional_contact(&p, &mut a, &ka, dt);
        let fb = update_frictional_contact(&p, &mut b, &kb, dt);
        let scale = fa.force_on_2.norm().max(1e-300);
        prop_assert!((fa.normal_force - fb.normal_force).abs() <= 1e-12 * scale);
        prop_assert!((fa.shear_force.norm() - fb.shear_force.norm()).abs() <= 1e-12 * scale);
        prop_assert!((rot * fa.force_on_2 - fb.force_on_2).norm() <= 1e-12 * scale);
        prop_assert!((rot * fa.shear_force - fb.shear_force).norm() <= 1e-12 * scale);
        prop_assert!((fa.elastic_energy - fb.elastic_energy).abs() <= 1e-10 * fa.elastic_energy.max(1e-300));
    }

    #[test]
    fn a_contact_never_creates_energy(
        tan_phi in 0.05..1.0_f64,
        ratio in 0.1..1.0_f64,
        legs in prop::collection::vec((unit_vec3(), 0.2..3.0_f64, 5..60usize), 1..8),
    ) {
        // Random piecewise-constant velocity paths of body 2 with slip; the contact stays
        // closed (overlap kept positive by a normal pull-in). Work in ≥ stored energy change,
        // and work in ≤ change + dissipation (the slip work is at most what the cap reports).
        let p = params(1e6, ratio, tan_phi);
        let s = 0.02;
        let x0 = Vec3::new(0.0, 0.0, s - 1e-3);
        let dt = 1e-5;
        let mut vs = Vec::new();
        for (dir, speed, n) in legs {
            let mut d = dir * speed * 1e-3;
            d.z = d.z.min(0.0) * 0.1; // never pull apart
            vs.extend(std::iter::repeat_n(d, n * 10));
        }
        let (work, de, diss, incs) = drive(&p, x0, s, &vs, dt);
        prop_assert!(incs.iter().all(|&d| d >= 0.0));
        let e_scale = 1e6 * 1e-6;
        prop_assert!(work >= de - 1e-6 * e_scale, "work {work} < dE {de}");
        prop_assert!(work <= de + diss + 1e-6 * e_scale, "work {work} > dE {de} + D {diss}");
    }
}

/// The law as it was before the dashpots (copied verbatim): with cn = ct = 0 the law must give
/// exactly this, bit for bit.
fn undamped_reference(
    params: &FrictionalParams,
    state: &mut FrictionalContact,
    kin: &ContactKinematics,
    dt: Real,
) -> ContactForces {
    use crate::energy::{slip_dissipation, spring_energy, spring_energy_squared, Dissipation};
    use crate::rotation::transport_tangent;
    let n = kin.normal;
    let overlap = kin.overlap - state.overlap_offset;
    if overlap.is_nan() || overlap <= 0.0 {
        state.shear_force = Vec3::zeros();
        state.normal = n;
        state.normal_force = 0.0;
        return ContactForces::default();
    }
    let rotated = transport_tangent(state.shear_force, state.normal, n, kin.spin_about_normal * dt);
    let v = kin.relative_velocity;
    let us_dot = v - n * n.dot(&v);
    let trial = rotated - us_dot * (params.ks * dt);
    let fn_ = params.kn * overlap;
    let limit = (fn_ * params.tan_phi).max(0.0);
    let trial2 = trial.norm_squared();
    let (fs, sliding, friction) = if trial2 > limit * limit {
        let trial_mag = trial2.sqrt();
        let fs = if trial_mag > 0.0 { trial * (limit / trial_mag) } else { Vec3::zeros() };
        (fs, true, slip_dissipation(&rotated, &trial, &fs, params.ks))
    } else {
        (trial, false, 0.0)
    };
    state.shear_force = fs;
    state.normal = n;
    state.normal_force = fn_;
    let dissipated = Dissipation { friction, ..Default::default() };
    state.dissipated_friction += friction;
    ContactForces {
        normal_force: fn_,
        shear_force: fs,
        force_on_2: n * fn_ + fs,
        dashpot_force: Vec3::zeros(),
        elastic_energy: spring_energy(fn_, params.kn)
            + spring_energy_squared(fs.norm_squared(), params.ks),
        dissipated,
        sliding,
    }
}

fn damped(kn: Real, shear_ratio: Real, tan_phi: Real, cn: Real, ct: Real) -> FrictionalParams {
    FrictionalParams { cn, ct, ..params(kn, shear_ratio, tan_phi) }
}

#[test]
fn the_normal_dashpot_pushes_on_approach_and_never_pulls() {
    let (kn, cn, overlap, dt) = (1e6, 50.0, 1e-4, 1e-5);
    let p = damped(kn, 0.5, 0.5, cn, 0.0);
    let kin = |vn: Real| ContactKinematics {
        normal: Vec3::z(),
        overlap,
        relative_velocity: Vec3::z() * vn,
        spin_about_normal: 0.0,
    };
    // approaching at 1 m/s: kn·δ + cn·1 = 100 + 50
    let mut st = FrictionalContact::new(Vec3::z());
    let f = update_frictional_contact(&p, &mut st, &kin(-1.0), dt);
    assert!((f.normal_force - 150.0).abs() < 1e-9, "{f:?}");
    assert!((f.dashpot_force - Vec3::z() * 50.0).norm() < 1e-9);
    assert!((f.dissipated.viscous - 50.0 * dt).abs() < 1e-15);
    assert_eq!(st.normal_force, kn * overlap, "the state keeps the spring's force");
    // separating at 1 m/s: 100 − 50
    let f = update_frictional_contact(&p, &mut st, &kin(1.0), dt);
    assert!((f.normal_force - 50.0).abs() < 1e-9);
    // separating at 4 m/s: 100 − 200 < 0 is clamped; the dashpot applies −kn·δ only
    let f = update_frictional_contact(&p, &mut st, &kin(4.0), dt);
    assert_eq!(f.normal_force, 0.0);
    assert_eq!(f.force_on_2, Vec3::zeros());
    assert!((f.dashpot_force + Vec3::z() * 100.0).norm() < 1e-9);
    assert!((f.dissipated.viscous - 100.0 * 4.0 * dt).abs() < 1e-15);
    // the spring still holds its energy (the dashpot takes it as the overlap closes)
    assert!((f.elastic_energy - 0.5 * kn * overlap * overlap).abs() < 1e-15);
}

#[test]
fn sliding_with_a_dashpot_caps_spring_plus_dashpot() {
    // Steady sliding at v: the tangential force is the Coulomb limit, the spring holds
    // limit − ct·v against it, and friction plus dashpot dissipate limit·v·dt per step (the
    // friction term negative when the dashpot alone is above the limit).
    let (kn, overlap, tan_phi, dt, v) = (1e6, 1e-3, 0.3, 1e-5, 0.5);
    let limit = kn * overlap * tan_phi; // 300 N
    for ct in [200.0, 900.0] {
        let p = damped(kn, 0.5, tan_phi, 0.0, ct);
        let mut st = FrictionalContact::new(Vec3::z());
        let kin = ContactKinematics {
            normal: Vec3::z(),
            overlap,
            relative_velocity: Vec3::x() * v,
            spin_about_normal: 0.0,
        };
        let mut f = ContactForces::default();
        for _ in 0..100 {
            f = update_frictional_contact(&p, &mut st, &kin, dt);
        }
        assert!(f.sliding);
        assert!((f.shear_force + Vec3::x() * limit).norm() < 1e-9, "{ct}: {f:?}");
        assert!((st.shear_force - Vec3::x() * (ct * v - limit)).norm() < 1e-9, "{ct}");
        assert!((f.dashpot_force + Vec3::x() * ct * v).norm() < 1e-9);
        let d = f.dissipated;
        assert!((d.viscous - ct * v * v * dt).abs() < 1e-12, "{ct}: {d:?}");
        assert!((d.friction - (limit - ct * v) * v * dt).abs() < 1e-12, "{ct}: {d:?}");
        assert!((d.friction + d.viscous - limit * v * dt).abs() < 1e-12);
        let spring = (ct * v - limit).abs();
        let e = 0.5 * (kn * overlap).powi(2) / kn + 0.5 * spring * spring / (0.5 * kn);
        assert!((f.elastic_energy - e).abs() < 1e-9 * e);
    }
}

#[test]
fn sticking_with_a_dashpot_adds_it_to_the_spring() {
    let p = damped(1e6, 0.5, 10.0, 0.0, 20.0);
    let mut st = FrictionalContact::new(Vec3::z());
    let kin = ContactKinematics {
        normal: Vec3::z(),
        overlap: 1e-3,
        relative_velocity: Vec3::new(2.0, 0.0, 0.0),
        spin_about_normal: 0.0,
    };
    let f = update_frictional_contact(&p, &mut st, &kin, 1e-4);
    // spring −ks·u̇s·dt = −100, dashpot −ct·u̇s = −40
    assert!(!f.sliding);
    assert!((st.shear_force + Vec3::x() * 100.0).norm() < 1e-9);
    assert!((f.shear_force + Vec3::x() * 140.0).norm() < 1e-9);
    assert_eq!(f.dissipated.friction, 0.0);
    assert!((f.dissipated.viscous - 40.0 * 2.0 * 1e-4).abs() < 1e-15);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn without_dashpots_the_law_is_bit_identical_to_the_undamped_one(
        kn in log_uniform(1e2, 1e9),
        ratio in 0.0..1.0_f64,
        tan_phi in 0.0..2.0_f64,
        n0 in unit_vec3(),
        steps in law_steps(),
    ) {
        let p = params(kn, ratio, tan_phi);
        prop_assert!(!p.is_damped());
        let (mut a, mut b) = (FrictionalContact::new(n0), FrictionalContact::new(n0));
        let mut n = n0;
        for (dir, tilt, overlap, v, spin, dt) in steps {
            n = (n + dir * tilt).normalize();
            let kin = ContactKinematics {
                normal: n, overlap, relative_velocity: v, spin_about_normal: spin,
            };
            let fa = update_frictional_contact(&p, &mut a, &kin, dt);
            let fb = undamped_reference(&p, &mut b, &kin, dt);
            // Debug prints every float exactly (and −0 as −0): equal strings are equal bits
            prop_assert_eq!(format!("{fa:?}"), format!("{fb:?}"));
            prop_assert_eq!(format!("{a:?}"), format!("{b:?}"));
        }
    }

    #[test]
    fn damped_contacts_keep_coulomb_and_the_dashpots_dissipate(
        kn in log_uniform(1e2, 1e9),
        ratio in 0.0..1.0_f64,
        tan_phi in 0.0..2.0_f64,
        zeta in (0.0..1.5_f64, 0.0..1.5_f64),
        n0 in unit_vec3(),
        steps in law_steps(),
    ) {
        // dashpots of damping ratio up to 1.5 on a 1 kg pair
        let p = damped(kn, ratio, tan_phi, 2.0 * zeta.0 * kn.sqrt(), 2.0 * zeta.1 * (kn * ratio).sqrt());
        let mut st = FrictionalContact::new(n0);
        let mut n = n0;
        for (dir, tilt, overlap, v, spin, dt) in steps {
            n = (n + dir * tilt).normalize();
            let kin = ContactKinematics {
                normal: n, overlap, relative_velocity: v, spin_about_normal: spin,
            };
            let f = update_frictional_contact(&p, &mut st, &kin, dt);
            let scale = f.force_on_2.norm() + f.dashpot_force.norm() + kn * overlap.abs() + 1e-300;
            prop_assert!(f.normal_force >= 0.0);
            prop_assert!(f.shear_force.norm() <= f.normal_force * tan_phi * (1.0 + 1e-12) + 1e-300);
            prop_assert!(f.dissipated.viscous >= -1e-12 * scale * v.norm() * dt);
            // the force is the springs' plus the dashpots'
            let springs = n * st.normal_force + st.shear_force;
            prop_assert!((springs + f.dashpot_force - f.force_on_2).norm() <= 1e-12 * scale);
            let e = spring_energy(st.normal_force, kn) + spring_energy(st.shear_force.norm(), p.ks);
            prop_assert!((f.elastic_energy - e).abs() <= 1e-12 * e.max(1e-300));
        }
    }
}
