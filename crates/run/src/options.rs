//! [`RunOptions`]: what a caller changes in a scene's or checkpoint's plan.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// Changes to the run a scene or checkpoint describes; the default changes nothing.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Run this many steps: from a scene, in all (instead of its `steps` or `duration`); from
    /// a checkpoint, this many more (instead of going on to the original run length).
    pub steps: Option<u64>,
    /// Worker threads to record in checkpoints instead of the scene's or checkpoint's. The
    /// thread pool itself is the caller's ([`crate::configure_threads`]), set up before the
    /// simulation is built.
    pub threads: Option<usize>,
    /// Write the output into this folder instead of the scene's (ignored when resuming: the
    /// output continues where it was).
    pub output_directory: Option<PathBuf>,
    /// Write no output files (the series are still evaluated for the summary).
    pub no_output: bool,
    /// Where checkpoints go (default: `checkpoint.flexdem` in the output folder for a scene,
    /// the checkpoint itself when resuming).
    pub checkpoint_path: Option<PathBuf>,
    /// Steps between periodic checkpoints (None: only when interrupted).
    pub checkpoint_every: Option<u64>,
    /// A flag that stops the run cleanly before its next step when set (by a Ctrl-C handler,
    /// another thread, a GUI); the run then writes a checkpoint.
    pub interrupt: Option<Arc<AtomicBool>>,
}
