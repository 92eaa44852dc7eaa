//! The command line: subcommands and their options (clap derive).

use clap::{Args, Parser, Subcommand};
use flexdem_io::scene::MAX_THREADS;
use std::path::PathBuf;

/// flexdem: discrete element simulations of deformable structures (nets, cables, membranes,
/// shells) described by TOML scene files.
#[derive(Debug, Parser)]
#[command(name = "flexdem", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a scene file and write its output (VTK for ParaView, CSV series, PNG plot).
    Run(RunArgs),
    /// Check a scene file: read it and build the simulation without running it.
    Check(SceneArgs),
    /// Describe a scene: counts, masses, materials, time step and run length.
    Info(SceneArgs),
    /// Continue a run from a checkpoint (written by Ctrl-C or --checkpoint-every).
    Resume(ResumeArgs),
    /// Run the validation cases and write their report (Markdown and PNG plots).
    Validate(crate::commands::validate::ValidateArgs),
    /// Time the benchmark scenes (tube impact, PFacet membrane, sphere packing) with 1 and 2
    /// threads: a table of ms/step, ns per element-step, stage split, memory; CSV to
    /// target/flexdem/bench/latest.csv by default (--update-committed: bench/results/).
    Bench(crate::commands::bench::BenchArgs),
    /// Write the free spheres of a scene (e.g. a dense packing) or of a checkpoint (a sample
    /// settled by a run) to a CSV file that `[[spheres]] kind = "file"` reads back.
    Spheres(SpheresArgs),
}

/// A scene file, for `check` and `info`.
#[derive(Debug, Args)]
pub struct SceneArgs {
    /// The scene file (TOML; see docs/scene-reference.md).
    pub scene: PathBuf,
}

/// `flexdem spheres`.
#[derive(Debug, Args)]
pub struct SpheresArgs {
    /// A scene file (.toml) or a checkpoint (written by --checkpoint-every or Ctrl-C).
    pub input: PathBuf,
    /// The CSV file to write (columns x, y, z, radius).
    #[arg(long, short, value_name = "FILE.csv")]
    pub output: PathBuf,
}

/// Options shared by `run` and `resume`.
#[derive(Debug, Args)]
pub struct ExecOptions {
    /// Number of worker threads (default: the scene's `threads`, else one per core).
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u64).range(1..=MAX_THREADS as u64))]
    pub threads: Option<u64>,
    /// Write no output files (VTK, CSV, PNG); checkpoints are still written when asked for.
    #[arg(long)]
    pub no_output: bool,
    /// Write a JSON summary of the run to this file (steps, times, counts, energy, final
    /// values of the tracked series).
    #[arg(long, value_name = "FILE.json")]
    pub summary: Option<PathBuf>,
    /// Write a checkpoint (`checkpoint.flexdem` in the output folder) every N steps.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub checkpoint_every: Option<u64>,
    /// Where checkpoints go (default: `checkpoint.flexdem` in the output folder).
    #[arg(long, value_name = "FILE")]
    pub checkpoint: Option<PathBuf>,
    /// No progress bar and no report at the end (errors and warnings are still printed).
    #[arg(long, short)]
    pub quiet: bool,
}

/// `flexdem run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scene file (TOML; see docs/scene-reference.md).
    pub scene: PathBuf,
    /// Run this many steps instead of the scene's `steps` or `duration`.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub steps: Option<u64>,
    /// Write the output into this folder instead of the scene's `[output] directory`.
    #[arg(long, value_name = "DIR", conflicts_with = "no_output")]
    pub output: Option<PathBuf>,
    /// Options shared with `resume`.
    #[command(flatten)]
    pub exec: ExecOptions,
}

/// `flexdem resume`.
#[derive(Debug, Args)]
pub struct ResumeArgs {
    /// The checkpoint file (`checkpoint.flexdem` in the output folder of the run).
    pub checkpoint_file: PathBuf,
    /// Run this many more steps instead of going on to the original run length.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub steps: Option<u64>,
    /// Options shared with `run`.
    #[command(flatten)]
    pub exec: ExecOptions,
}
