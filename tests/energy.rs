//! validation.md case 14: a net dropped on a sphere. Without damping or friction the total
//! energy drifts by less than 1e-4 (relative) over 1e5 steps; with damping and friction the
//! energy balance closes within 1e-3.

use flexdem::contact::Material;
use flexdem::elements::builders::{net, StructureOptions};
use flexdem::elements::{Dofs, Model};
use flexdem::geom::{Real, Vec3};
use flexdem::integrate::{Settings, Simulation, TimeStep};

fn net_on_sphere(friction_deg: Real, damping: Real) -> Simulation {
    let mut model = Model::new();
    let wire = Material::new(2e9, 0.3, 7850.0, friction_deg.to_radians()).unwrap();
    let wire = model.add_material(wire).unwrap();
    let opts = StructureOptions::new("net", 0.004, wire);
    net(&mut model, Vec3::new(-0.4, -0.4, 0.0), Vec3::x(), Vec3::y(), 0.8, 0.8, 8, 8, false, &opts)
        .unwrap();
    let rock = Material::new(1e8, 0.3, 2600.0, friction_deg.to_radians()).unwrap();
    let rock = model.add_material(rock).unwrap();
    let s = model.add_sphere(Vec3::new(0.02, 0.01, -0.2), 0.15, rock).unwrap();
    model.block([s], Dofs::ALL).unwrap();
    let settings = Settings {
        gravity: Vec3::new(0.0, 0.0, -9.81),
        damping,
        time_step: TimeStep::Auto { safety: 0.3 },
        ..Settings::default()
    };
    Simulation::new(model, settings).unwrap()
}

/// Runs `steps` steps and returns (largest |balance − initial balance|, energy scale).
fn drift(sim: &mut Simulation, steps: u64) -> (Real, Real) {
    sim.step().unwrap();
    let b0 = sim.energy().balance();
    let (mut worst, mut scale): (Real, Real) = (0.0, 0.0);
    let mut touched = false;
    for _ in 0..steps {
        sim.step().unwrap();
        let e = sim.energy();
        worst = worst.max((e.balance() - b0).abs());
        scale = scale.max(e.gravity_work.abs()).max(e.stored());
        touched |= !sim.contacts().is_empty();
    }
    assert!(touched, "the net never reached the sphere");
    (worst, scale)
}

#[test]
fn energy_is_conserved_without_damping_or_friction() {
    let mut sim = net_on_sphere(0.0, 0.0);
    let (worst, scale) = drift(&mut sim, 100_000);
    assert!(sim.energy().elastic_contacts >= 0.0);
    assert!(worst < 1e-4 * scale, "drift {worst:.3e} J of {scale:.3e} J ({:.2e})", worst / scale);
}

#[test]
fn energy_balance_closes_with_damping_and_friction() {
    let mut sim = net_on_sphere(30.0, 0.1);
    let (worst, scale) = drift(&mut sim, 50_000);
    let e = sim.energy();
    assert!(e.damping > 0.0 && e.friction > 0.0, "{e:?}");
    assert!(
        worst < 1e-3 * scale,
        "balance off by {worst:.3e} J of {scale:.3e} J ({:.2e})",
        worst / scale
    );
}
