//! The subcommands; what they share is in `common`.

pub mod bench;
pub mod check;
mod common;
pub mod execute;
pub mod info;
pub mod resume;
pub mod run;
pub mod spheres;
pub mod validate;
