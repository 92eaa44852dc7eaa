//! Per-stage wall-clock timers (collision, contacts, links, loads, integration, bookkeeping),
//! as rapier's counters: a run reports where its time goes.
//!
//! The clock is read once at the start of a step and once at the end of each stage, whose
//! time is the lap since the read before: a read costs about 25 ns here (47 % of the perf
//! samples of a one-sphere scene when every stage read it twice, 27 % since).

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
    /// The last read of the clock in this step (none between steps).
    mark: Option<Instant>,
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
    /// Starts the laps of a step.
    pub(crate) fn begin(&mut self) {
        self.mark = Some(Instant::now());
    }

    /// Adds the time since the last read of this step to `stage` (the time from the start of
    /// the step, or from the end of the stage before: a stage that did not run gives its
    /// check's nanoseconds to the next).
    pub(crate) fn lap(&mut self, stage: Stage) {
        let now = Instant::now();
        let d = self.mark.map_or(Duration::ZERO, |m| now.duration_since(m));
        self.mark = Some(now);
        match stage {
            Stage::Collision => self.collision += d,
            Stage::Contacts => self.contacts += d,
            Stage::Links => self.links += d,
            Stage::Loads => self.loads += d,
            Stage::Integration => self.integration += d,
            Stage::Bookkeeping => self.bookkeeping += d,
        }
    }

    /// Ends the laps of a step: the time until the next step is no stage's.
    pub(crate) fn end(&mut self) {
        self.mark = None;
    }

    /// The time each stage took since `before` (an earlier copy of these timers).
    pub fn since(&self, before: &Timers) -> Timers {
        Timers {
            mark: None,
            collision: self.collision.saturating_sub(before.collision),
            contacts: self.contacts.saturating_sub(before.contacts),
            links: self.links.saturating_sub(before.links),
            loads: self.loads.saturating_sub(before.loads),
            integration: self.integration.saturating_sub(before.integration),
            bookkeeping: self.bookkeeping.saturating_sub(before.bookkeeping),
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
