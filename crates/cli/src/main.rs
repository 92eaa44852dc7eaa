//! The `flexdem` command: run a scene file, check it, describe it, resume a run from a
//! checkpoint.
//!
//! Exit codes: 0 success, 1 the run failed (an unstable run, an output file that cannot be
//! written), 2 bad input (scene file, checkpoint, command-line arguments), 130 interrupted by
//! Ctrl-C (a checkpoint was written), 3 this machine lacks instructions the binary was compiled
//! for (a binary built on another machine, `flexdem_run::cpu`).

mod cli;
mod commands;
mod error;
mod progress;
mod report;

use clap::Parser;
use cli::{Cli, Command};
use error::Outcome;

/// The system allocator, with a count of the bytes allocated: `flexdem bench` reports the
/// heap a scene holds per element from it (`flexdem_bench::heap`). One atomic addition per
/// allocation, and a step allocates nothing once warm.
#[global_allocator]
static ALLOCATOR: cap::Cap<std::alloc::System> = cap::Cap::new(std::alloc::System, usize::MAX);

fn main() {
    // before any code compiled for this CPU's extensions runs (see `flexdem_run::cpu`)
    if let Some(message) =
        flexdem_run::cpu::unsupported_message(&flexdem_run::cpu::unsupported_features())
    {
        eprintln!("error: {message}");
        std::process::exit(3);
    }
    run_command()
}

/// The command line's work, once the CPU is known to run it.
#[inline(never)]
fn run_command() {
    flexdem_bench::set_heap_probe(|| ALLOCATOR.allocated());
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(args) => commands::run::run(&args),
        Command::Check(args) => commands::check::check(&args),
        Command::Info(args) => commands::info::info(&args),
        Command::Resume(args) => commands::resume::resume(&args),
        Command::Validate(args) => commands::validate::validate(&args),
        Command::Bench(args) => commands::bench::bench(&args),
        Command::Spheres(args) => commands::spheres::spheres(&args),
    };
    let code = match result {
        Ok(Outcome::Done) => 0,
        Ok(Outcome::Interrupted) => 130,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    };
    std::process::exit(code);
}
