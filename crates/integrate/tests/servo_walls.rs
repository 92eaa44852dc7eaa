//! Walls that hold a stress, against known answers: the force on a wall is the weight it
//! carries, a servo wall holds its target stress at rest with the energy balance closed, the
//! Love–Weber stress of the sample it presses is the wall's stress, and the controls are
//! refused or kept as the API says.

use flexdem_contact::Material;
use flexdem_elements::Model;
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{
    deviator_stress, love_weber_stress, mean_stress, normal_force, wall_normal_stress, Region,
    Settings, Simulation, StressControl, TimeStep, WallControl,
};

const G: Real = 9.81;

/// The gap between neighbouring spheres of [`lattice_under_a_platen`] (m).
const SLACK: Real = 1e-6;

/// Two spheres stacked on a floor (wall 0) under gravity, a side wall (wall 1) out of reach:
/// once at rest, the floor carries their weight and the side wall nothing.
#[test]
fn the_force_on_a_wall_is_the_weight_it_carries() {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e7, 0.3, 2000.0, 0.5).unwrap()).unwrap();
    let r = 0.01;
    model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    model.add_wall(Vec3::new(-1.0, 0.0, 0.0), Vec3::x(), m).unwrap();
    model.add_sphere(Vec3::new(0.0, 0.0, r), r, m).unwrap();
    model.add_sphere(Vec3::new(0.0, 0.0, 3.0 * r), r, m).unwrap();
    let weight: Real = model.particles.mass.iter().sum::<Real>() * G;
    let settings =
        Settings { gravity: Vec3::new(0.0, 0.0, -G), damping: 0.5, ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    assert_eq!(sim.wall_forces(), &[Vec3::zeros(), Vec3::zeros()]);
    sim.run(20_000).unwrap();
    let [floor, side] = [sim.wall_forces()[0], sim.wall_forces()[1]];
    // the bodies push the floor down: F = (0, 0, −m·g), normal force m·g
    let error = (floor - Vec3::new(0.0, 0.0, -weight)).norm() / weight;
    eprintln!("floor force {floor:?}, weight {weight:.6e} N, relative error {error:.2e}");
    assert!(error < 1e-6, "{floor:?} vs {weight}");
    assert!((normal_force(&sim.model().walls[0], &floor) / weight - 1.0).abs() < 1e-6);
    assert_eq!(side, Vec3::zeros());
}

/// A simple cubic lattice of `n × n × layers` spheres of radius `r`, `SLACK` apart from each
/// other and from a floor at z = 0 (wall 0), and a top wall (wall 1, normal −z) `gap` above
/// the top layer. (Spheres that touch exactly make contacts of round-off forces, whose
/// energy, some 1e-28 J, is then the whole energy scale of the watch: the round-off of the
/// first steps passes its tolerance.)
fn lattice_under_a_platen(n: usize, layers: usize, r: Real, gap: Real) -> Model {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e8, 0.3, 2600.0, 0.5).unwrap()).unwrap();
    model.add_wall(Vec3::zeros(), Vec3::z(), m).unwrap();
    let pitch = 2.0 * r + SLACK;
    let top = pitch * layers as Real + gap;
    model.add_wall(Vec3::new(0.0, 0.0, top), -Vec3::z(), m).unwrap();
    for i in 0..n {
        for j in 0..n {
            for k in 0..layers {
                let c =
                    Vec3::new(i as Real, j as Real, k as Real) * pitch + Vec3::repeat(r + SLACK);
                model.add_sphere(c, r, m).unwrap();
            }
        }
    }
    model
}

/// Runs `sim` until the top wall's normal stress has stayed within `1e-4` of `target` for
/// 2000 steps (at most `limit` steps); returns the steps run.
fn settle(sim: &mut Simulation, target: Real, area: Real, limit: u64) -> u64 {
    let mut steady = 0;
    for step in 1..=limit {
        sim.step().unwrap();
        let wall = &sim.model().walls[1];
        let stress = wall_normal_stress(wall, &sim.wall_forces()[1], area);
        steady = if (stress / target - 1.0).abs() < 1e-4 { steady + 1 } else { 0 };
        if steady == 2000 {
            return step;
        }
    }
    limit
}

/// A servo platen pressing a 3 × 3 × 3 lattice (no gravity) to 100 kPa, then to 200 kPa: at
/// rest its stress is the target within 1 %, the energy balance (the platen's work counted)
/// closes within 1e-3, and the Love–Weber stress of the lattice is the platen's.
#[test]
fn a_servo_wall_holds_its_target_stress_at_rest() {
    let (n, r) = (3, 0.01);
    let side = (2.0 * r + SLACK) * n as Real;
    let area = side * side;
    let model = lattice_under_a_platen(n, 3, r, 0.1 * r);
    let settings = Settings { damping: 0.3, ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    let servo = StressControl { target: 1e5, area, gain: None, max_speed: 0.05, section: None };
    sim.set_wall_control(1, WallControl::Stress(servo)).unwrap();
    let mut energy_error: Real = 0.0;
    for target in [1e5, 2e5] {
        sim.set_wall_control(1, WallControl::Stress(StressControl { target, ..servo })).unwrap();
        let steps = settle(&mut sim, target, area, 100_000);
        sim.run(2000).unwrap();
        let wall = sim.model().walls[1];
        let force = sim.wall_forces()[1];
        let stress = wall_normal_stress(&wall, &force, area);
        let error = (stress / target - 1.0).abs();
        energy_error = energy_error.max(sim.relative_balance_error().abs());
        eprintln!(
            "target {target:.0} Pa: settled in {steps} steps, stress {stress:.6e} Pa \
             (error {error:.2e}), wall speed {:.2e} m/s, energy error {:.2e}",
            wall.velocity.norm(),
            sim.relative_balance_error()
        );
        assert!(steps < 100_000, "the platen never settled at {target} Pa");
        assert!(error <= 1e-2, "{stress} vs {target}");
        // the lattice between the walls: the Love–Weber σzz over the box between the wall
        // planes is the wall's stress times (H + δ)/H, the columns reaching δ/2 beyond each
        // plane (δ the sphere–wall overlap)
        let height = wall.point.z;
        let region = Region::Box { min: Vec3::zeros(), max: Vec3::new(side, side, height) };
        let sigma = love_weber_stress(sim.model(), &sim.contacts(), &region, None);
        let kn = sim.contacts()[0].params.kn;
        let delta = force.norm() / (n * n) as Real / kn;
        let expected = stress * (height + delta) / height;
        let lw_error = (sigma[(2, 2)] / expected - 1.0).abs();
        eprintln!(
            "Love–Weber σzz {:.6e} Pa, expected {expected:.6e} Pa (error {lw_error:.2e}), \
             p {:.6e}, q {:.6e}",
            sigma[(2, 2)],
            mean_stress(&sigma),
            deviator_stress(&sigma)
        );
        assert!(lw_error < 1e-9, "{sigma:?} vs {expected}");
        assert!(sigma[(0, 0)].abs() < 1e-9 * expected && sigma[(1, 1)].abs() < 1e-9 * expected);
        assert!((mean_stress(&sigma) * 3.0 / sigma[(2, 2)] - 1.0).abs() < 1e-9);
        assert!((deviator_stress(&sigma) / sigma[(2, 2)] - 1.0).abs() < 1e-9);
    }
    eprintln!("largest energy balance error {energy_error:.2e}");
    assert!(energy_error <= 1e-3, "energy balance error {energy_error}");
}

/// One sphere between a floor and a servo platen with a fixed gain, no damping, a fixed step:
/// the platen's velocity changes at every step, and its work, trapezoidal with the velocity
/// it moved with over each step, closes the energy balance of these linear springs to
/// round-off. (With dt = "auto" each change of the step leaves an error of its own in the
/// balance, whatever the walls do: a fixed step keeps the test to the servo's accounting.)
#[test]
fn the_work_of_a_servo_wall_closes_the_energy_balance() {
    let r = 0.01;
    // the platen starts 1 µm into the sphere
    let model = lattice_under_a_platen(1, 1, r, -1e-6);
    let settings = Settings { time_step: TimeStep::Fixed(4e-5), ..Settings::default() };
    let mut sim = Simulation::new(model, settings).unwrap();
    let servo = StressControl {
        target: 1e5,
        area: 4.0 * r * r,
        gain: Some(2e-3),
        max_speed: 1.0,
        section: None,
    };
    sim.set_wall_control(1, WallControl::Stress(servo)).unwrap();
    let mut speeds = Vec::new();
    let mut worst: Real = 0.0;
    for _ in 0..20_000 {
        sim.step().unwrap();
        speeds.push(sim.model().walls[1].velocity.z);
        worst = worst.max(sim.relative_balance_error().abs());
    }
    let changes = speeds.windows(2).filter(|w| w[0] != w[1]).count();
    let e = sim.energy();
    let stress = wall_normal_stress(&sim.model().walls[1], &sim.wall_forces()[1], servo.area);
    eprintln!(
        "velocity changed at {changes} of {} steps, boundary work {:.4e} J, stored {:.4e} J, \
         stress {stress:.6e} Pa, worst balance error {worst:.2e}",
        speeds.len(),
        e.boundary_work,
        e.stored()
    );
    assert!(changes > 10_000, "the servo did not steer: {changes}");
    assert!((stress / servo.target - 1.0).abs() < 1e-6, "{stress}");
    assert!(e.boundary_work > 0.0, "{e:?}");
    assert!(worst < 1e-9, "energy balance error {worst}");
}

/// A fixed gain moves the wall at `G·(F_target − F_n)` and never faster than its largest
/// speed: before it touches anything the platen comes down at exactly `max_speed`.
#[test]
fn a_servo_wall_approaches_at_its_largest_speed() {
    let r = 0.01;
    let model = lattice_under_a_platen(1, 1, r, r);
    let mut sim = Simulation::new(model, Settings::default()).unwrap();
    let servo = StressControl {
        target: 1e4,
        area: 4.0 * r * r,
        gain: Some(1.0),
        max_speed: 0.2,
        section: None,
    };
    sim.set_wall_control(1, WallControl::Stress(servo)).unwrap();
    let z0 = sim.model().walls[1].point.z;
    sim.step().unwrap();
    let dt = sim.dt();
    assert_eq!(sim.model().walls[1].velocity, Vec3::new(0.0, 0.0, -0.2));
    assert!((sim.model().walls[1].point.z - (z0 - 0.2 * dt)).abs() < 1e-15);
}

#[test]
fn bad_wall_controls_are_refused_and_change_nothing() {
    let r = 0.01;
    let mut sim = Simulation::new(lattice_under_a_platen(1, 1, r, r), Settings::default()).unwrap();
    let ok = StressControl { target: 1e4, area: 1e-3, gain: None, max_speed: 0.1, section: None };
    assert_eq!(sim.wall_controls(), &[WallControl::Velocity, WallControl::Velocity]);
    let e = sim.set_wall_control(2, WallControl::Stress(ok)).unwrap_err().to_string();
    assert!(e.contains("wall id below 2"), "{e}");
    for bad in [
        StressControl { target: -1.0, ..ok },
        StressControl { area: Real::NAN, ..ok },
        StressControl { gain: Some(-1.0), ..ok },
        StressControl { max_speed: Real::INFINITY, ..ok },
    ] {
        assert!(sim.set_wall_control(1, WallControl::Stress(bad)).is_err());
        assert_eq!(sim.wall_controls()[1], WallControl::Velocity);
    }
    sim.set_wall_control(1, WallControl::Stress(ok)).unwrap();
    assert_eq!(sim.wall_controls()[1], WallControl::Stress(ok));
    // an imposed velocity is strain control
    sim.set_wall_velocity(1, Vec3::new(0.0, 0.0, -0.01)).unwrap();
    assert_eq!(sim.wall_controls()[1], WallControl::Velocity);
    // a state whose controls do not fit its walls is refused
    sim.set_wall_control(1, WallControl::Stress(ok)).unwrap();
    let mut state = sim.state().clone();
    state.wall_controls.pop();
    assert!(Simulation::from_state(state).is_err());
    let mut state = sim.state().clone();
    state.wall_controls[1] = WallControl::Stress(StressControl { area: 0.0, ..ok });
    assert!(Simulation::from_state(state).is_err());
    // walls added by an edit are strain-controlled; the others keep their control
    let mat = sim.model().walls[0].material;
    sim.edit_model(|m| m.add_wall(Vec3::new(0.0, 0.0, -1.0), Vec3::z(), mat)).unwrap().unwrap();
    assert_eq!(
        sim.wall_controls(),
        &[WallControl::Velocity, WallControl::Stress(ok), WallControl::Velocity]
    );
    sim.run(10).unwrap();
    assert_eq!(sim.wall_forces().len(), 3);
}
