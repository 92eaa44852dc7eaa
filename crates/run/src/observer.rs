//! [`RunObserver`]: what a caller hears of a run as it goes (a progress bar, a log, a plot
//! updated live); every method has an empty default.

use flexdem_integrate::Simulation;
use flexdem_scene::RunLength;
use std::path::Path;

/// Callbacks of a run, called on the thread that runs it ([`crate::Run::execute`] runs on a
/// rayon worker, hence `Send` there).
pub trait RunObserver {
    /// The run starts (first call of [`crate::Run::advance`]): its state and where it ends.
    fn started(&mut self, _sim: &Simulation, _target: RunLength) {}

    /// A step is done and its output and checkpoint written.
    fn stepped(&mut self, _sim: &Simulation) {}

    /// The engine raised a warning (at the start: the ones raised while building).
    fn warning(&mut self, _message: &str) {}

    /// A checkpoint was written to `path`.
    fn checkpoint_written(&mut self, _path: &Path) {}

    /// The stepping is over ([`crate::Run::finish`] starts): the last output follows.
    fn finished(&mut self, _sim: &Simulation) {}
}

/// An observer that ignores everything.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoObserver;

impl RunObserver for NoObserver {}
