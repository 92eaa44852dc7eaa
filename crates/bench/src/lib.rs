//! Scene benchmarks for flexdem (`flexdem bench`): named scenes at several sizes, run for a
//! fixed number of steps in a rayon pool of 1, 2, … threads, reporting the time per step,
//! per element and step, the split over the engine's stages (collision, contacts, links,
//! integration), the memory per element and whether the final state is the same for every
//! thread count.
//!
//! Scenes ([`SceneKind`]): the paper's tube impact (§7, the heavy sphere) with a fixed time
//! step; a PFacet membrane of about 10³–10⁶
//! PFacets, edges pinned, under a layer of spheres; spheres falling in a box of walls; and
//! any scene file ([`Case::File`]: the twins of other codes' inputs under `bench/`).
//!
//! Definitions:
//! - elements = the bodies the engine handles: particles (structure nodes and free
//!   spheres) + connections + PFacets (walls are not counted);
//! - memory = `VmRSS` of `/proc/self/status` after building the simulation and running its
//!   warm-up, minus `VmRSS` before building it (the previous run's simulation is dropped
//!   by then), divided by the elements;
//! - CPU time = user + system time of the process's threads during the timed steps
//!   (`/proc/self/stat`, 10 ms resolution): on a shared machine, CPU time / wall time below
//!   the thread count says that the run did not get its cores;
//! - checksum = FNV-1a of the bits of every particle's position, velocity, orientation and
//!   angular velocity after the timed steps, and of the contact count.

mod case;
mod error;
pub mod heap;
pub mod procfs;
pub mod report;
pub mod runner;
pub mod scenes;

pub use case::{Case, FILE_WARMUP_STEPS};
pub use error::BenchError;
pub use heap::{heap_bytes, set_heap_probe};
pub use runner::{run_case, run_plan, state_checksum, BenchResult, Plan, PlanRow, StepChoice};
pub use scenes::SceneKind;

#[cfg(test)]
mod tests;
