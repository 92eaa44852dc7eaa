//! Per-stage wall-clock timers (collision, contacts, links, loads, integration, bookkeeping),
//! as rapier's counters: a run reports where its time goes.

use std::time::{Duration, Instant};

/// A stage of a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Broad phase (candidate pairs), when the Verlet distance is used up.
    Collision,
    /// Exact contact geometry, ownership, contact law and force distribution.
    Contacts,
    /// Beam links.
    Links,
    /// Imposed loads and the user's force hook.
    Loads,
    /// Leapfrog integration.
    Integration,
    /// Checks (NaN, a particle jumping), energy terms and watch, time step.
    Bookkeeping,
}

/// Accumulated time per stage.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timers {
    /// Broad phase.
    pub collision: Duration,
    /// Contacts.
    pub contacts: Duration,
    /// Links.
    pub links: Duration,
    /// Imposed loads and the force hook.
    pub loads: Duration,
    /// Integration.
    pub integration: Duration,
    /// Checks, energy, time step.
    pub bookkeeping: Duration,
}

impl Timers {
    /// Starts timing a stage.
    pub fn start(&self) -> Instant {
        Instant::now()
    }

    /// Adds the time since `start` to `stage`.
    pub fn stop(&mut self, stage: Stage, start: Instant) {
        let d = start.elapsed();
        match stage {
            Stage::Collision => self.collision += d,
            Stage::Contacts => self.contacts += d,
            Stage::Links => self.links += d,
            Stage::Loads => self.loads += d,
            Stage::Integration => self.integration += d,
            Stage::Bookkeeping => self.bookkeeping += d,
        }
    }

    /// Sum over the stages.
    pub fn total(&self) -> Duration {
        self.collision
            + self.contacts
            + self.links
            + self.loads
            + self.integration
            + self.bookkeeping
    }
}
