//! How long a run lasts, and the largest run accepted.

use flexdem_geom::Real;

/// Largest number of steps a run may last (`steps`, or `duration` over the time step): 10¹²
/// steps take weeks even at a million steps per second, so more is a typo (`dt = 1e-300`).
pub const MAX_STEPS: u64 = 1_000_000_000_000;

/// `Err(message)` when `run` at time step `dt` lasts more than [`MAX_STEPS`] steps.
pub fn check_step_count(run: RunLength, dt: Real) -> Result<(), String> {
    let steps = match run {
        RunLength::Steps(n) => n as Real,
        RunLength::Duration(d) => d / dt,
    };
    if steps <= MAX_STEPS as Real {
        return Ok(());
    }
    Err(match run {
        RunLength::Steps(n) => format!("is {n} steps: expected at most {MAX_STEPS}"),
        RunLength::Duration(d) => format!(
            "{d} s at dt = {dt:e} s is {steps:.3e} steps: expected at most {:e} \
             (a shorter duration or a larger time step)",
            MAX_STEPS as Real
        ),
    })
}

/// How long a run lasts.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum RunLength {
    /// A number of steps.
    Steps(u64),
    /// A simulated time (s).
    Duration(Real),
}
