//! Running a case's simulation until it comes to rest, shared by the cases.

use crate::ValidationError;
use flexdem_geom::Real;
use flexdem_integrate::Simulation;

/// Largest speed of any particle (m/s).
pub fn max_speed(sim: &Simulation) -> Real {
    sim.model().particles.vel.iter().map(|v| v.norm()).fold(0.0, Real::max)
}

/// Runs `sim` in chunks of `chunk` steps until the largest speed stays below `tol` for a
/// whole chunk or `max_steps` are done; returns the steps run.
pub fn run_to_rest(
    sim: &mut Simulation,
    tol: Real,
    chunk: u64,
    max_steps: u64,
) -> Result<u64, ValidationError> {
    let mut done = 0;
    while done < max_steps {
        let mut quiet = true;
        for _ in 0..chunk {
            sim.step()?;
            quiet &= max_speed(sim) <= tol;
        }
        done += chunk;
        if quiet {
            break;
        }
    }
    Ok(done)
}
