//! The energy watch and round-off: spheres that touch exactly (a lattice at spacing 2r, as a
//! scene's `lattice` builds it, no gravity) hold contacts whose forces and energies are
//! round-off. The watch must not stop such a run (its energy scale is itself round-off), and
//! must still stop a run that creates energy.

use flexdem_contact::Material;
use flexdem_elements::{Dofs, Model};
use flexdem_geom::{Real, Vec3};
use flexdem_integrate::{Settings, Simulation, SimulationError};

const R: Real = 0.01;

/// A 3 × 3 × 3 lattice of spheres of radius `R` spaced 2R, from the corner `R` (positions
/// that are not exact in binary: the neighbours overlap or gap by round-off).
fn touching_lattice() -> Model {
    let mut model = Model::new();
    let m = model.add_material(Material::new(1e8, 0.3, 2600.0, 0.5).unwrap()).unwrap();
    for i in 0..3 {
        for j in 0..3 {
            for k in 0..3 {
                let c = Vec3::repeat(R) + Vec3::new(i as Real, j as Real, k as Real) * (2.0 * R);
                model.add_sphere(c, R, m).unwrap();
            }
        }
    }
    model
}

#[test]
fn spheres_touching_exactly_run_on() {
    let mut sim = Simulation::new(touching_lattice(), Settings::default()).unwrap();
    for _ in 0..500 {
        sim.step().unwrap_or_else(|e| panic!("step {}: {e}", sim.steps()));
    }
    assert!(sim.energy().stored() < 1e-20, "{:?}", sim.energy());
}

#[test]
fn energy_created_is_still_caught_above_the_round_off() {
    // the same lattice squeezed: one sphere pushed into its neighbour by a kick the balance
    // does not see (a velocity changed in a model edit: `set_velocity` would book it as the
    // user's work, an edit does not)
    let mut sim = Simulation::new(touching_lattice(), Settings::default()).unwrap();
    sim.step().unwrap();
    sim.edit_model(|m| m.particles.vel[0] = Vec3::new(1.0, 0.0, 0.0)).unwrap();
    let mut caught = None;
    for _ in 0..100 {
        if let Err(e) = sim.step() {
            caught = Some(e);
            break;
        }
    }
    assert!(matches!(caught, Some(SimulationError::EnergyBalance { .. })), "{caught:?}");
}

#[test]
fn a_non_finite_energy_term_stops_the_run_even_with_the_watch_off() {
    // a force hook that computes 0/0 on a support: the blocked sphere does not move, so
    // every position and velocity stays finite, but the load's work `F·v·dt` is NaN. A NaN
    // balance error compares false with any limit; it must stop the run, not pass for a
    // closed balance
    for tolerance in [Some(0.05), None] {
        let mut model = touching_lattice();
        model.block([13], Dofs::ALL).unwrap();
        let settings = Settings { energy_tolerance: tolerance, ..Settings::default() };
        let mut sim = Simulation::new(model, settings).unwrap();
        sim.step().unwrap();
        let zero = sim.energy().stored() * 0.0;
        sim.set_force_hook(Box::new(move |_, _, forces, _| forces[13].x += zero / zero));
        let caught = sim.step().unwrap_err();
        match &caught {
            SimulationError::NonFiniteEnergy { term, step, .. } => {
                assert_eq!((*term, *step), ("load_work", 2), "{caught}");
            }
            other => panic!("{other:?}"),
        }
        let message = caught.to_string();
        assert!(message.contains("`load_work` is NaN at step 2"), "{message}");
        for i in 0..sim.model().particles.len() {
            assert!(sim.model().particles.pos[i].iter().all(|x| x.is_finite()));
        }
    }
}
