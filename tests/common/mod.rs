//! Helpers shared by the workspace validation tests.
#![allow(dead_code)]

use flexdem::contact::{LinkKinematicsMode, Material};
use flexdem::elements::builders::{chain, straight_line, StructureOptions};
use flexdem::elements::{Dofs, Model};
use flexdem::geom::{Real, Vec3};
use flexdem::integrate::{Load, Ramp, Settings, Simulation, TimeStep};

/// A straight cantilever along x: `n` connections over length `l`, radius `r`, material
/// (E, ν, ρ); node 0 clamped in all 6 DOF. Returns the simulation and the tip node.
pub fn cantilever(
    n: usize,
    l: Real,
    r: Real,
    young: Real,
    poisson: Real,
    density: Real,
    mode: LinkKinematicsMode,
    damping: Real,
) -> (Simulation, u32) {
    let mut model = Model::new();
    let m = model.add_material(Material::new(young, poisson, density, 0.5).unwrap()).unwrap();
    let points = straight_line(Vec3::zeros(), Vec3::new(l, 0.0, 0.0), n).unwrap();
    let s = chain(&mut model, &points, &StructureOptions::new("beam", r, m)).unwrap();
    let nodes = model.structures[s as usize].nodes.clone();
    model.block([nodes.start], Dofs::ALL).unwrap();
    let settings = Settings {
        time_step: TimeStep::Auto { safety: 0.5 },
        damping,
        link_mode: mode,
        ..Settings::default()
    };
    let sim = Simulation::new(model, settings).unwrap();
    (sim, nodes.end - 1)
}

/// Constant load on one particle.
pub fn tip_load(particle: u32, force: Vec3, torque: Vec3) -> Load {
    Load { particles: vec![particle], force, torque, ramp: Ramp::Constant }
}

/// Largest particle speed.
pub fn max_speed(sim: &Simulation) -> Real {
    sim.model().particles.vel.iter().map(|v| v.norm()).fold(0.0, Real::max)
}

/// Runs until the largest speed (and angular speed times `r`) stays below `tol` for a whole
/// chunk of steps, or `max_steps` is reached; returns the steps run.
pub fn run_to_rest(sim: &mut Simulation, tol: Real, chunk: u64, max_steps: u64) -> u64 {
    let mut done = 0;
    while done < max_steps {
        let mut quiet = true;
        for _ in 0..chunk {
            sim.step().unwrap();
            if max_speed(sim) > tol {
                quiet = false;
            }
        }
        done += chunk;
        if quiet {
            break;
        }
    }
    done
}
