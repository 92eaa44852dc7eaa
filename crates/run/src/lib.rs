//! The run driver of flexdem: what `flexdem run` and `flexdem resume` do, as a library that a
//! Rust program (or a Python module) calls instead of copying the loop.
//!
//! A [`Run`] is set up from a scene file ([`Run::from_scene`], or [`Run::new`] from a
//! [`flexdem_scene::Scene`] already read) or from a checkpoint ([`Run::resume`],
//! [`Run::from_checkpoint`]), with [`RunOptions`] (run length, output folder, checkpoints, an
//! interrupt flag). [`Run::advance`] steps it, writing the output ([`flexdem_output`]) and
//! periodic checkpoints ([`flexdem_io::checkpoint`]) as it goes, and tells a [`RunObserver`]
//! about each step and warning; [`Run::finish`] writes the last output (and a checkpoint when
//! interrupted) and returns a [`Summary`], plain data that [`write_json`] writes as JSON.
//! Printing (a progress bar, the report) is the caller's: the command line does it in an
//! observer.
//!
//! A run resumed from a checkpoint ends bit-identically to one that was never stopped: the
//! checkpoint holds the whole simulation state (the energy watch's initial balance included,
//! so the scene file is not read again), the run length and how far the output got.

mod build;
pub mod cpu;
mod driver;
mod error;
mod observer;
mod options;
mod summary;

/// How long a run lasts (from `flexdem-scene`): the type of [`Run::target`].
pub use flexdem_scene::RunLength;

pub use build::{build_simulation, configure_threads, SceneRest};
pub use driver::{Run, Stop, CHECKPOINT_FILE};
pub use error::RunError;
pub use observer::{NoObserver, RunObserver};
pub use options::RunOptions;
pub use summary::{
    tracked_values, write_json, ColliderSummary, Counts, EnergySummary, OutputSummary, Stages,
    Status, Summary,
};
