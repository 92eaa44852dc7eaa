//! The engine's Rust API: free fall, time-step warnings, unstable runs stopped with an error
//! that names the body, callbacks, moving walls and bad settings.

mod common;

use flexdem::contact::{LinkKinematicsMode, Material};
use flexdem::elements::Model;
use flexdem::geom::{Real, Vec3};
use flexdem::integrate::{Control, Settings, Simulation, SimulationError, TimeStep};

fn one_sphere(settings: Settings) -> Simulation {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 2000.0, 0.5).unwrap()).unwrap();
    let s = model.add_sphere(Vec3::new(0.0, 0.0, 1.0), 0.05, m).unwrap();
    model.particles.vel[s as usize] = Vec3::new(0.5, 0.0, 2.0);
    Simulation::new(model, settings).unwrap()
}

/// Free fall: x = x0 + v0·t + g·t²/2 (the leapfrog's half-step start adds g·dt·t/2).
#[test]
fn free_fall_follows_the_parabola() {
    let g = Vec3::new(0.0, 0.0, -9.81);
    let mut sim = one_sphere(Settings {
        gravity: g,
        time_step: TimeStep::Fixed(1e-4),
        ..Settings::default()
    });
    sim.step().unwrap();
    let b0 = sim.energy().balance();
    sim.run(4999).unwrap();
    let t = sim.time();
    let exact = Vec3::new(0.0, 0.0, 1.0) + Vec3::new(0.5, 0.0, 2.0) * t + g * (0.5 * t * t);
    let x = sim.model().particles.pos[0];
    assert!((x - exact).norm() < 0.5 * 9.81 * 1e-4 * t + 1e-9, "{x} vs {exact}");
    // energy: kinetic gained = work of gravity, to round-off
    let e = sim.energy();
    assert!((e.balance() - b0).abs() < 1e-9 * e.gravity_work.abs(), "{e:?}, initially {b0}");
}

#[test]
fn a_fixed_step_above_the_critical_one_warns() {
    let (sim, _) =
        common::cantilever(10, 1.0, 0.01, 1e8, 0.3, 1000.0, LinkKinematicsMode::Beam, 0.0);
    let crit = sim.critical_dt();
    let settings = Settings { time_step: TimeStep::Fixed(3.0 * crit), ..sim.settings().clone() };
    let sim = Simulation::new(sim.model().clone(), settings).unwrap();
    assert!(
        sim.warnings().iter().any(|w| w.contains("above the critical step")),
        "{:?}",
        sim.warnings()
    );
}

/// A fixed dt below the critical step at the start, above it once the sphere has hit the tube
/// (the contacts stiffen the nodes): the critical step is re-estimated during the run and one
/// warning is raised, before the run becomes unstable.
#[test]
fn a_fixed_step_overtaken_by_contacts_warns_during_the_run() {
    let scene = root_path("examples/tube_impact_heavy.toml");
    let scene = flexdem::io::scene::load_scene(&scene).unwrap();
    let probe = Simulation::new(scene.model.clone(), scene.settings.clone()).unwrap();
    let dt = 0.8 * probe.critical_dt();
    let settings = Settings { time_step: TimeStep::Fixed(dt), ..scene.settings.clone() };
    let mut sim = Simulation::new(scene.model, settings).unwrap();
    assert!(sim.warnings().is_empty(), "{:?}", sim.warnings());
    let (mut warned_at, mut below_at) = (None, None);
    for _ in 0..2000 {
        if sim.step().is_err() {
            break;
        }
        if warned_at.is_none() && !sim.warnings().is_empty() {
            warned_at = Some(sim.steps());
        }
        if below_at.is_none() {
            // a full estimate now, on a copy: the step from which the warning is due
            let mut copy = Simulation::from_state(sim.state().clone()).unwrap();
            copy.update_time_step().unwrap();
            if copy.critical_dt() < dt {
                below_at = Some(sim.steps());
            }
        }
    }
    let said: Vec<_> =
        sim.warnings().iter().filter(|w| w.contains("above the critical step")).collect();
    assert_eq!(said.len(), 1, "{:?}", sim.warnings());
    assert!(warned_at.is_some_and(|s| s > 1) && sim.critical_dt() < dt);
    // not more than 10 steps late (the new contacts' stiffness is added as they come, and the
    // full estimate redone at most every 10 steps)
    let (warned, below) = (warned_at.unwrap(), below_at.unwrap());
    assert!(below <= warned && warned <= below + 10, "due at step {below}, said at {warned}");
}

/// A thin cable (radius 2 µm, links of 0.1 m) swinging under gravity moves by far more than its
/// radius per step: that is no instability, and the run goes on (the guard uses the size of
/// the smallest element holding a node).
#[test]
fn a_thin_cable_moving_more_than_its_radius_per_step_is_not_unstable() {
    let (sim, tip) =
        common::cantilever(10, 1.0, 2e-6, 1e8, 0.3, 1000.0, LinkKinematicsMode::Beam, 0.0);
    let settings = Settings { gravity: Vec3::new(0.0, 0.0, -9.81), ..sim.settings().clone() };
    let mut sim = Simulation::new(sim.model().clone(), settings).unwrap();
    sim.run(3000).unwrap();
    let p = &sim.model().particles;
    let step_motion = p.vel[tip as usize].norm() * sim.dt();
    assert!(step_motion > 10.0 * p.radius[tip as usize], "the tip moved {step_motion} m per step");
    assert!(p.pos[tip as usize].z < -0.1, "the cable swung down: {:?}", p.pos[tip as usize]);
}

/// A step ten times the critical one blows up; the run stops with an error naming the
/// particle and suggesting a smaller dt, before any NaN is written.
#[test]
fn an_unstable_run_stops_with_an_error_naming_the_body() {
    let (mut sim, tip) =
        common::cantilever(10, 1.0, 0.01, 1e8, 0.3, 1000.0, LinkKinematicsMode::Beam, 0.0);
    let settings =
        Settings { time_step: TimeStep::Fixed(10.0 * sim.critical_dt()), ..sim.settings().clone() };
    sim = Simulation::new(sim.model().clone(), settings).unwrap();
    sim.add_load(common::tip_load(tip, Vec3::new(0.0, 0.0, -1.0), Vec3::zeros())).unwrap();
    let err = sim.run(100_000).unwrap_err();
    let msg = err.to_string();
    assert!(
        matches!(err, SimulationError::Exploding { .. } | SimulationError::NonFinite { .. }),
        "{msg}"
    );
    assert!(msg.contains("particle") && msg.contains("smaller dt"), "{msg}");
    assert!(
        sim.model().particles.pos.iter().all(|p| p.iter().all(|x| x.is_finite()))
            || msg.contains("non-finite")
    );
}

#[test]
fn callbacks_see_every_chunk_and_can_stop_the_run() {
    let mut sim = one_sphere(Settings { time_step: TimeStep::Fixed(1e-3), ..Settings::default() });
    let mut seen = Vec::new();
    let done = sim
        .run_with(1000, 100, |s| {
            seen.push(s.steps());
            if s.steps() >= 300 {
                Control::Stop
            } else {
                Control::Continue
            }
        })
        .unwrap();
    assert_eq!(done, 300);
    assert_eq!(seen, vec![100, 200, 300]);
}

/// A wall moving up at 1 m/s lifts a sphere resting on it under gravity.
#[test]
fn a_moving_wall_pushes_a_sphere() {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 2000.0, 0.5).unwrap()).unwrap();
    let w = model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    model.walls[w as usize].velocity = Vec3::new(0.0, 0.0, 1.0);
    model.add_sphere(Vec3::new(0.0, 0.0, 0.05), 0.05, m).unwrap();
    let settings =
        Settings { gravity: Vec3::new(0.0, 0.0, -9.81), damping: 0.3, ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    let mut lowest = Real::INFINITY;
    while sim.time() < 0.5 {
        sim.step().unwrap();
        lowest = lowest.min(sim.model().particles.pos[0].z - sim.model().walls[0].point.z);
    }
    let wall = sim.model().walls[0].point.z;
    assert!((wall - sim.time()).abs() < 1e-9);
    // never pushed through the wall (overlap well under the radius), and lifted with it
    assert!(lowest > 0.045, "closest approach {lowest}");
    assert!(sim.model().particles.pos[0].z > wall + 0.045);
}

#[test]
fn bad_settings_and_massless_bodies_are_refused() {
    let model = || {
        let mut m = Model::new();
        let mat = m.add_material(Material::new(1e7, 0.3, 2000.0, 0.5).unwrap()).unwrap();
        m.add_sphere(Vec3::zeros(), 0.05, mat).unwrap();
        m
    };
    for (settings, text) in [
        (Settings { damping: 1.0, ..Settings::default() }, "damping"),
        (Settings { time_step: TimeStep::Fixed(-1.0), ..Settings::default() }, "time step"),
        (Settings { time_step: TimeStep::Auto { safety: 0.0 }, ..Settings::default() }, "safety"),
        (Settings { gravity: Vec3::new(0.0, Real::NAN, 0.0), ..Settings::default() }, "gravity"),
    ] {
        let err = Simulation::new(model(), settings).err().expect("refused").to_string();
        assert!(err.contains(text), "{err}");
    }
    let mut sim = Simulation::new(model(), Settings::default()).unwrap();
    let ramp = flexdem::integrate::Ramp::Linear { start: 0.0, duration: Real::NAN };
    let load = flexdem::integrate::Load {
        particles: vec![0],
        force: Vec3::x(),
        torque: Vec3::zeros(),
        ramp,
    };
    let err = sim.add_load(load).unwrap_err().to_string();
    assert!(err.contains("load ramp"), "{err}");
    let mut m = model();
    m.particles.mass[0] = 0.0;
    let err = Simulation::new(m, Settings::default()).err().expect("refused").to_string();
    assert!(err.contains("particle 0"), "{err}");
}

/// A simulation rebuilt from its state continues bit-identically (contacts with their shear
/// history, links, time-step bookkeeping and energy terms included).
#[test]
fn a_saved_state_continues_bit_identically() {
    use flexdem::elements::builders::{net, GridLayout, StructureOptions};
    use flexdem::elements::Dofs;
    let mut model = Model::new();
    let wire = model.add_material(Material::new(2e9, 0.3, 7850.0, 0.5).unwrap()).unwrap();
    let opts = StructureOptions::new("net", 0.004, wire);
    let s = net(
        &mut model,
        Vec3::new(-0.3, -0.3, 0.0),
        Vec3::x(),
        Vec3::y(),
        0.6,
        0.6,
        6,
        6,
        false,
        &opts,
    )
    .unwrap();
    let grid = GridLayout::of(&model, s, 6, 6).unwrap();
    model.block(grid.corners(), Dofs::ALL).unwrap();
    let rock = model.add_material(Material::new(1e8, 0.3, 2600.0, 0.5).unwrap()).unwrap();
    model.add_sphere(Vec3::new(0.01, 0.02, 0.09), 0.08, rock).unwrap();
    let settings =
        Settings { gravity: Vec3::new(0.0, 0.0, -9.81), damping: 0.05, ..Settings::default() };
    let mut a = Simulation::new(model, settings).unwrap();
    while a.contacts().is_empty() {
        a.step().unwrap();
    }
    a.run(500).unwrap();
    let saved = a.state().clone();
    a.run(1500).unwrap();
    let mut b = Simulation::from_state(saved).unwrap();
    b.run(1500).unwrap();
    assert_eq!(a.steps(), b.steps());
    assert_eq!(a.time().to_bits(), b.time().to_bits());
    assert!(a.model().particles.pos == b.model().particles.pos, "positions differ");
    assert!(a.model().particles.vel == b.model().particles.vel, "velocities differ");
    assert_eq!(a.energy(), b.energy());
    assert_eq!(a.contacts().len(), b.contacts().len());
}

/// A path relative to the workspace root.
fn root_path(relative: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(relative)
}

/// An automatic step falls at once when a contact stiffens a body, and grows back by at most
/// 10 % per estimate of the critical step once the contact has ended (model.md §3: a step
/// raised much at once puts a spike into the energy balance).
#[test]
fn an_automatic_step_falls_at_once_and_grows_back_gradually() {
    use flexdem::elements::builders::{chain, straight_line, StructureOptions};
    // a soft chain (its links set dt) hit end-on by a stiff sphere: the contact, far stiffer
    // than the links, lowers dt while it lasts
    let mut model = Model::new();
    let soft = model.add_material(Material::new(1e6, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let stiff = model.add_material(Material::new(1e9, 0.3, 1000.0, 0.5).unwrap()).unwrap();
    let points = straight_line(Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0), 4).unwrap();
    chain(&mut model, &points, &StructureOptions::new("chain", 0.01, soft)).unwrap();
    let sphere = model.add_sphere(Vec3::new(-0.0605, 0.0, 0.0), 0.05, stiff).unwrap();
    model.particles.vel[sphere as usize] = Vec3::new(0.1, 0.0, 0.0);
    let settings = Settings { time_step: TimeStep::Auto { safety: 0.3 }, ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    let free = sim.dt();
    let mut dts = vec![free];
    while sim.steps() < 5000 {
        sim.step().unwrap();
        dts.push(sim.dt());
    }
    let lowest = dts.iter().copied().fold(Real::INFINITY, Real::min);
    assert!(lowest < 0.5 * free, "the contact did not lower dt: {lowest} vs {free}");
    assert!(sim.contacts().is_empty(), "the spheres did not separate");
    for (k, w) in dts.windows(2).enumerate() {
        assert!(w[1] <= 1.1 * w[0] * (1.0 + 1e-12), "step {k}: dt {} -> {}", w[0], w[1]);
    }
    // back to the chain's own step (within its links' stretch)
    assert!((sim.dt() / free - 1.0).abs() < 0.01, "dt {} did not grow back to {free}", sim.dt());
}
