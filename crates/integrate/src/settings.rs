//! Simulation settings and imposed loads.

use crate::SimulationError;
use flexdem_contact::LinkKinematicsMode;
use flexdem_geom::{Real, Vec3};
use serde::{Deserialize, Serialize};

/// How the time step is chosen (model.md §4).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum TimeStep {
    /// `safety × critical step`, recomputed as links and contacts change.
    Auto {
        /// Safety factor in (0, 1].
        safety: Real,
    },
    /// A fixed step (s); a warning is raised when it exceeds the critical step.
    Fixed(Real),
}

impl Default for TimeStep {
    fn default() -> Self {
        TimeStep::Auto { safety: 0.5 }
    }
}

/// Settings of a simulation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Settings {
    /// Time step choice.
    pub time_step: TimeStep,
    /// Gravity (m/s²).
    pub gravity: Vec3,
    /// Cundall damping λ in [0, 1).
    pub damping: Real,
    /// Shear kinematics of beam links.
    pub link_mode: LinkKinematicsMode,
    /// Verlet distance of the broad phase, as a fraction of each element's size (see
    /// [`crate::Collider`]).
    pub verlet_factor: Real,
    /// Recompute the automatic time step every this many steps (and when contacts appear).
    pub time_step_interval: u64,
    /// The run stops when the energy balance error, relative to the energy scale, passes this
    /// on the side of energy created (energy lost beyond it raises a warning; see
    /// `EnergyWatch`); `None` switches the watch off. Switched on again in a run
    /// (`Simulation::set_settings`), it watches from then on: the balance of that moment is
    /// its start, and contacts found late while it was off do not count.
    pub energy_tolerance: Option<Real>,
}

/// The default of [`Settings::energy_tolerance`]: 5 % of the energy scale. Far above what a
/// sound run reaches (1e-3 and below in the validation cases) and far below a blow-up.
pub const DEFAULT_ENERGY_TOLERANCE: Real = 0.05;

impl Default for Settings {
    fn default() -> Self {
        Settings {
            time_step: TimeStep::default(),
            gravity: Vec3::zeros(),
            damping: 0.0,
            link_mode: LinkKinematicsMode::Beam,
            verlet_factor: 0.5,
            time_step_interval: 100,
            energy_tolerance: Some(DEFAULT_ENERGY_TOLERANCE),
        }
    }
}

impl Settings {
    /// Checks every value, naming the bad one.
    pub fn validate(&self) -> Result<(), SimulationError> {
        let bad = |what: &str, value: String, expected: &str| {
            Err(SimulationError::Setting { what: what.into(), value, expected: expected.into() })
        };
        match self.time_step {
            TimeStep::Auto { safety } if !(safety > 0.0 && safety <= 1.0) => {
                return bad("time step safety factor", safety.to_string(), "a number in (0, 1]");
            }
            TimeStep::Fixed(dt) if !(dt > 0.0 && dt.is_finite()) => {
                return bad("time step", dt.to_string(), "a positive finite number of seconds");
            }
            _ => {}
        }
        if !self.gravity.iter().all(|g| g.is_finite()) {
            return bad("gravity", format!("{:?}", self.gravity), "three finite numbers (m/s²)");
        }
        if !(0.0..1.0).contains(&self.damping) {
            return bad("damping", self.damping.to_string(), "a number in [0, 1)");
        }
        if !(self.verlet_factor > 0.0 && self.verlet_factor.is_finite()) {
            return bad("verlet factor", self.verlet_factor.to_string(), "a positive number");
        }
        if let Some(tol) = self.energy_tolerance {
            if !(tol > 0.0 && tol.is_finite()) {
                return bad(
                    "energy tolerance",
                    tol.to_string(),
                    "a positive fraction of the energy scale (or off)",
                );
            }
        }
        if self.time_step_interval == 0 {
            return bad("time step interval", "0".into(), "at least 1 step");
        }
        Ok(())
    }
}

/// How an imposed load grows in time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Ramp {
    /// Full value from the start.
    Constant,
    /// From 0 at `start` to the full value at `start + duration`, then constant.
    Linear {
        /// Time the ramp starts (s).
        start: Real,
        /// Duration of the ramp (s).
        duration: Real,
    },
}

impl Ramp {
    /// The fraction of the load applied at time `t`.
    pub fn factor(&self, t: Real) -> Real {
        match *self {
            Ramp::Constant => 1.0,
            Ramp::Linear { start, duration } => {
                if t <= start {
                    0.0
                } else if duration <= 0.0 || t >= start + duration {
                    1.0
                } else {
                    (t - start) / duration
                }
            }
        }
    }
}

/// A force and a torque imposed on each of a set of particles.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Load {
    /// The particles loaded.
    pub particles: Vec<u32>,
    /// Force on each (N).
    pub force: Vec3,
    /// Torque on each (N·m).
    pub torque: Vec3,
    /// Growth in time.
    pub ramp: Ramp,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramps_grow_linearly_then_hold() {
        let r = Ramp::Linear { start: 1.0, duration: 2.0 };
        assert_eq!(r.factor(0.5), 0.0);
        assert_eq!(r.factor(1.0), 0.0);
        assert!((r.factor(2.0) - 0.5).abs() < 1e-15);
        assert_eq!(r.factor(3.0), 1.0);
        assert_eq!(r.factor(10.0), 1.0);
        assert_eq!(Ramp::Linear { start: 0.0, duration: 0.0 }.factor(1e-9), 1.0);
        assert_eq!(Ramp::Constant.factor(0.0), 1.0);
    }
}
