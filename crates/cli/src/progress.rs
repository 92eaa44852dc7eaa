//! The progress bar of a run: fraction of the run length, simulated time, steps/s, ETA.
//! Drawn on stderr only when it is a terminal (and not with `--quiet`).

use flexdem_integrate::Simulation;
use flexdem_io::scene::RunLength;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::time::{Duration, Instant};

/// Resolution of the bar: its length in ticks.
const TICKS: u64 = 10_000;
/// Minimum wall-clock time between two updates of the bar.
const REDRAW: Duration = Duration::from_millis(100);

/// A progress bar that follows a simulation towards its run length.
pub struct Progress {
    bar: ProgressBar,
    target: RunLength,
    start: Instant,
    start_steps: u64,
    start_time: f64,
    last: Instant,
}

impl Progress {
    /// A bar for a run from the state of `sim` to `target`; hidden when `hidden` or when
    /// stderr is not a terminal.
    pub fn new(sim: &Simulation, target: RunLength, hidden: bool) -> Progress {
        let bar = if hidden || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::with_draw_target(Some(TICKS), ProgressDrawTarget::stderr());
            let style =
                ProgressStyle::with_template("{bar:30.cyan/blue} {percent:>3}% {msg} ETA {eta} ")
                    .unwrap_or_else(|_| ProgressStyle::default_bar())
                    .progress_chars("=> ");
            bar.set_style(style);
            bar
        };
        let now = Instant::now();
        let p = Progress {
            bar,
            target,
            start: now,
            start_steps: sim.steps(),
            start_time: sim.time(),
            last: now,
        };
        p.draw(sim);
        p
    }

    /// Fraction of the run done, in [0, 1].
    fn fraction(&self, sim: &Simulation) -> f64 {
        let f = match self.target {
            RunLength::Steps(n) => {
                let todo = n.saturating_sub(self.start_steps);
                if todo == 0 {
                    1.0
                } else {
                    sim.steps().saturating_sub(self.start_steps) as f64 / todo as f64
                }
            }
            RunLength::Duration(d) => {
                let todo = d - self.start_time;
                if todo <= 0.0 {
                    1.0
                } else {
                    (sim.time() - self.start_time) / todo
                }
            }
        };
        f.clamp(0.0, 1.0)
    }

    /// Runs `f` (which prints to the terminal) with the bar cleared, then redraws it.
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    /// Updates the bar (at most every 100 ms).
    pub fn tick(&mut self, sim: &Simulation) {
        if self.bar.is_hidden() {
            return;
        }
        let now = Instant::now();
        if now.duration_since(self.last) >= REDRAW {
            self.last = now;
            self.draw(sim);
        }
    }

    /// Draws the current state.
    fn draw(&self, sim: &Simulation) {
        if self.bar.is_hidden() {
            return;
        }
        let elapsed = self.start.elapsed().as_secs_f64();
        let steps = sim.steps().saturating_sub(self.start_steps) as f64;
        let rate = if elapsed > 0.0 { steps / elapsed } else { 0.0 };
        self.bar.set_position((self.fraction(sim) * TICKS as f64) as u64);
        self.bar.set_message(format!(
            "step {} t = {:.4e} s, {rate:.0} steps/s,",
            sim.steps(),
            sim.time()
        ));
    }

    /// Removes the bar from the terminal.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
