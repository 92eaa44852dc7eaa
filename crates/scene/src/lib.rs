//! Scene files: a TOML description of a simulation (settings, materials, structures from the
//! builders or from mesh files, free spheres, walls, boundary conditions, loads, pressures
//! and outputs), read into a [`Scene`] ready for [`flexdem_integrate::Simulation::new`]. The
//! keys, their units and defaults are in `docs/scene-reference.md`.
//!
//! Every error names the file, the line and column, the key and what is expected; unknown
//! keys are errors, with the nearest known key suggested. Relative paths (meshes, the output
//! folder) are relative to the folder of the scene file.
//!
//! The scene keeps its structure and sphere group names ([`SceneNames`]), so that loads
//! given after the build (a script's, between the stages of a run) select as the file's do:
//! [`parse_loads`].

mod build;
mod builder;
mod built;
mod check;
pub mod dense;
mod dense_spheres;
mod error;
mod loads;
pub mod memory;
mod output;
mod output_measures;
mod output_triaxial;
pub mod packing;
pub mod placement;
mod pressure;
mod read;
pub mod region;
mod run_length;
mod scene;
mod schema;
mod selection;
pub mod sphere_file;
mod spheres;
mod structures;
mod walls;

pub use built::SceneNames;
pub use error::SceneError;
pub use loads::parse_loads;
pub use read::{load_scene, parse_scene};
pub use run_length::{check_step_count, RunLength, MAX_STEPS};
pub use scene::{Scene, MAX_THREADS};
