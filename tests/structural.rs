//! validation.md cases 1–4: axial bar, cantilever (beam and yade kinematics), torsion and
//! the first bending frequency, with links only.

mod common;

use common::*;
use flexdem::contact::LinkKinematicsMode;
use flexdem::geom::{Real, Vec3};
use nalgebra::UnitQuaternion;
use std::f64::consts::PI;

const L: Real = 1.0;
const R: Real = 0.01;
const E: Real = 1e8;
const NU: Real = 0.3;
const RHO: Real = 1000.0;

fn area() -> Real {
    PI * R * R
}
fn inertia() -> Real {
    PI * R.powi(4) / 4.0
}

/// Case 1: elongation P·L/(E·πr²) to 1e-6 (YADE: ratio 1.0000000).
#[test]
fn axial_bar_elongation() {
    let (mut sim, tip) = cantilever(10, L, R, E, NU, RHO, LinkKinematicsMode::Beam, 0.3);
    let p = 10.0;
    sim.add_load(tip_load(tip, Vec3::new(p, 0.0, 0.0), Vec3::zeros())).unwrap();
    run_to_rest(&mut sim, 1e-9, 2000, 200_000);
    let elongation = sim.model().particles.pos[tip as usize].x - L;
    let expected = p * L / (E * area());
    assert!((elongation / expected - 1.0).abs() < 1e-6, "{elongation} vs {expected}");
}

/// Case 2, beam option: tip deflection P·L³/(3EI) and rotation P·L²/(2EI) to 1e-4, for any
/// number of segments.
#[test]
fn cantilever_beam_mode_matches_euler_bernoulli() {
    for n in [1, 4, 10] {
        let (mut sim, tip) = cantilever(n, L, R, E, NU, RHO, LinkKinematicsMode::Beam, 0.5);
        let p = 0.01;
        sim.add_load(tip_load(tip, Vec3::new(0.0, 0.0, -p), Vec3::zeros())).unwrap();
        run_to_rest(&mut sim, 1e-10, 5000, 2_000_000);
        let w = -sim.model().particles.pos[tip as usize].z;
        let expected = p * L.powi(3) / (3.0 * E * inertia());
        assert!((w / expected - 1.0).abs() < 1e-4, "n = {n}: {w} vs {expected}");
        let rot = sim.model().particles.ori[tip as usize].scaled_axis();
        let expected_rot = p * L * L / (2.0 * E * inertia());
        assert!(
            (rot.y / expected_rot - 1.0).abs() < 1e-4,
            "n = {n}: rotation {} vs {expected_rot}",
            rot.y
        );
    }
}

/// Case 2, yade option with 10 segments: ratio 1.0100 to P·L³/(3EI); YADE 2023.02a measured
/// 1.00998 and a tip rotation of 6.3661e-3 (../shared/reference/yade/cantilever).
#[test]
fn cantilever_yade_mode_matches_yade() {
    let (mut sim, tip) = cantilever(10, L, R, E, NU, RHO, LinkKinematicsMode::Yade, 0.5);
    let p = 0.01;
    sim.add_load(tip_load(tip, Vec3::new(0.0, 0.0, -p), Vec3::zeros())).unwrap();
    run_to_rest(&mut sim, 1e-10, 5000, 2_000_000);
    let w = -sim.model().particles.pos[tip as usize].z;
    let eb = p * L.powi(3) / (3.0 * E * inertia());
    // the discrete prediction: P L^3/(3EI) + N P Ls^3/(12 E I) (Ls/(2r) - 1)
    let ls = L / 10.0;
    let predicted = eb + 10.0 * p * ls.powi(3) / (12.0 * E * inertia()) * (ls / (2.0 * R) - 1.0);
    assert!((w / predicted - 1.0).abs() < 1e-4, "{w} vs {predicted}");
    let yade_tip = 0.004286493337240651;
    assert!((w / yade_tip - 1.0).abs() < 1e-4, "ratio to YADE {}", w / yade_tip);
    let rot = sim.model().particles.ori[tip as usize].scaled_axis().y;
    assert!((rot / 0.006366102581528891 - 1.0).abs() < 1e-4, "rotation {rot}");
}

/// Case 3: twist T·L/(G·J), J = πr⁴/2, to 1e-6.
#[test]
fn torsion_twist_angle() {
    let (mut sim, tip) = cantilever(10, L, R, E, NU, RHO, LinkKinematicsMode::Beam, 0.3);
    let t = 1e-3;
    sim.add_load(tip_load(tip, Vec3::zeros(), Vec3::new(t, 0.0, 0.0))).unwrap();
    run_to_rest(&mut sim, 1e-10, 2000, 1_000_000);
    let twist = sim.model().particles.ori[tip as usize].scaled_axis().x;
    let g = E / (2.0 * (1.0 + NU));
    let expected = t * L / (g * PI * R.powi(4) / 2.0);
    assert!((twist / expected - 1.0).abs() < 1e-6, "{twist} vs {expected}");
}

/// Case 4: first bending frequency (1.8751²/2π)·√(EI/(ρAL⁴)) within 2% with 20 segments
/// (steel, r = 10 mm, L = 1 m: 14.47 Hz). Released from the static shape of a tip load,
/// without damping.
#[test]
fn cantilever_first_frequency() {
    let (e, rho, r) = (210e9, 7850.0, 0.01);
    let n = 20;
    let (mut sim, tip) = cantilever(n, L, r, e, 0.3, rho, LinkKinematicsMode::Beam, 0.0);
    let i = PI * r.powi(4) / 4.0;
    let p = 10.0;
    // static deflected shape under a tip load P (w and slope), set as the initial state
    for k in 0..=n {
        let x = L * k as Real / n as Real;
        let w = p * x * x * (3.0 * L - x) / (6.0 * e * i);
        let slope = p * x * (2.0 * L - x) / (2.0 * e * i);
        let mut pos = sim.model().particles.pos[k];
        pos.z = -w;
        sim.set_position(k as u32, pos).unwrap();
        let ori = UnitQuaternion::from_scaled_axis(Vec3::new(0.0, slope, 0.0));
        sim.set_orientation(k as u32, ori).unwrap();
    }
    let expected =
        1.8751_f64.powi(2) / (2.0 * PI) * (e * i / (rho * PI * r * r * L.powi(4))).sqrt();
    assert!((expected - 14.47).abs() < 0.01);
    // upward zero crossings of the tip's z, interpolated
    let mut crossings = Vec::new();
    let mut prev = sim.model().particles.pos[tip as usize].z;
    while crossings.len() < 6 && sim.time() < 1.0 {
        sim.step().unwrap();
        let z = sim.model().particles.pos[tip as usize].z;
        if prev < 0.0 && z >= 0.0 {
            let f = prev / (prev - z);
            crossings.push(sim.time() - sim.dt() * (1.0 - f));
        }
        prev = z;
    }
    assert!(crossings.len() >= 6, "only {} crossings", crossings.len());
    let period = (crossings[5] - crossings[0]) / 5.0;
    let f = 1.0 / period;
    assert!((f / expected - 1.0).abs() < 0.02, "f = {f} Hz vs {expected} Hz");
}

/// The P-wave step r/√(E/ρ_eff) of the YADE cantilever (ρ_eff from the lumped node mass):
/// YADE 2023.02a's PWaveTimeStep gives 6.123724356957945e-5 s (set by the end nodes, which
/// hold half an inner node's mass).
#[test]
fn p_wave_step_matches_yade() {
    let (sim, _) = cantilever(10, L, R, E, NU, RHO, LinkKinematicsMode::Yade, 0.3);
    let dt = flexdem::integrate::p_wave_time_step(sim.model()).unwrap();
    assert!((dt / 6.123724356957945e-5 - 1.0).abs() < 1e-12, "{dt}");
}
