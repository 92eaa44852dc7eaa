//! The run loop shared by `run` and `resume`: steps to the run length with the output, the
//! progress bar, periodic checkpoints and Ctrl-C, then the report and the JSON summary.

use crate::error::{CliError, Outcome};
use crate::progress::Progress;
use crate::report;
use crate::summary::{
    tracked_values, write_json, ColliderSummary, Counts, EnergySummary, OutputSummary, Stages,
    Status, Summary,
};
use flexdem_integrate::Simulation;
use flexdem_io::checkpoint::{write_checkpoint, Checkpoint, OutputProgress};
use flexdem_io::output::{Output, OutputSettings};
use flexdem_io::scene::RunLength;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::Instant;

/// Name of the checkpoint file in the output folder.
pub const CHECKPOINT_FILE: &str = "checkpoint.flexdem";

/// A run to do: the simulation and everything about how to run it.
pub struct Job {
    /// The simulation, at its first step for `run`, at the checkpoint's for `resume`.
    pub sim: Simulation,
    /// The output being written (None: nothing is written).
    pub output: Option<Output>,
    /// The output settings (the series give the tracked quantities even without output;
    /// with `--no-output` they write nothing). Stored in checkpoints.
    pub output_settings: OutputSettings,
    /// Where the run ends: a step count or a simulated time since the start of the
    /// simulation. Stored in checkpoints.
    pub target: RunLength,
    /// Worker threads asked for (stored in checkpoints) and in use.
    pub threads: (Option<usize>, usize),
    /// The scene file.
    pub scene: PathBuf,
    /// Where checkpoints go.
    pub checkpoint_path: PathBuf,
    /// Steps between periodic checkpoints.
    pub checkpoint_every: Option<u64>,
    /// Where the JSON summary goes.
    pub summary: Option<PathBuf>,
    /// No progress bar and no report.
    pub quiet: bool,
}

/// The flag set by Ctrl-C, with the handler installed on first use. A second Ctrl-C while
/// the first is being handled ends the process at once (exit code 130).
fn interrupt_flag() -> Result<Arc<AtomicBool>, CliError> {
    static FLAG: OnceLock<Result<Arc<AtomicBool>, String>> = OnceLock::new();
    FLAG.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let handler_flag = Arc::clone(&flag);
        ctrlc::set_handler(move || {
            if handler_flag.swap(true, Ordering::SeqCst) {
                eprintln!("\nsecond Ctrl-C: stopping now, without a checkpoint");
                std::process::exit(130);
            }
        })
        .map_err(|e| format!("cannot install the Ctrl-C handler: {e}"))?;
        Ok(flag)
    })
    .clone()
    .map_err(CliError::Run)
}

/// Whether `sim` has reached `target`.
pub fn reached(sim: &Simulation, target: RunLength) -> bool {
    match target {
        RunLength::Steps(n) => sim.steps() >= n,
        RunLength::Duration(d) => sim.time() >= d,
    }
}

/// Writes the checkpoint of the current state to `job.checkpoint_path`.
fn save_checkpoint(job: &Job, progress: OutputProgress) -> Result<(), CliError> {
    let checkpoint = Checkpoint {
        snapshot: job.sim.snapshot(),
        run: job.target,
        threads: job.threads.0,
        output: job.output_settings.clone(),
        scene: job.scene.clone(),
        output_progress: progress,
    };
    if let Some(dir) = job.checkpoint_path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| {
            CliError::Run(format!("cannot create the checkpoint folder {}: {e}", dir.display()))
        })?;
    }
    write_checkpoint(&job.checkpoint_path, &checkpoint).map_err(|e| CliError::Run(e.to_string()))
}

/// The output progress to store in a checkpoint now.
fn output_progress(output: Option<&Output>) -> OutputProgress {
    output
        .map(Output::progress)
        .unwrap_or(OutputProgress { vtk_frames: Vec::new(), series_rows: 0 })
}

/// Runs `job` to its end, Ctrl-C or an error; writes the checkpoints, the output, the report
/// and the summary.
///
/// The whole run goes to one of rayon's worker threads: the engine's parallel loops then start
/// on that worker instead of being handed over from the main thread, which would wake a
/// worker and wait for it some ten times per step (tens of microseconds per step, as much as
/// the step itself on a small scene).
pub fn execute(job: Job) -> Result<Outcome, CliError> {
    rayon::join(move || execute_on_worker(job), || ()).0
}

fn execute_on_worker(mut job: Job) -> Result<Outcome, CliError> {
    let interrupted = interrupt_flag()?;
    for warning in job.sim.warnings() {
        eprintln!("warning: {warning}");
    }
    let wall = Instant::now();
    let start_steps = job.sim.steps();
    let mut failure: Option<String> = None;
    let mut checkpoint_written: Option<PathBuf> = None;
    if let Some(out) = job.output.as_mut() {
        if let Err(e) = out.record(&job.sim) {
            failure = Some(e.to_string());
        }
    }
    let mut progress = Progress::new(&job.sim, job.target, job.quiet);
    let mut status = Status::Completed;
    let mut warned = job.sim.warnings().len();
    while failure.is_none() && !reached(&job.sim, job.target) {
        if interrupted.load(Ordering::SeqCst) {
            status = Status::Interrupted;
            break;
        }
        if let Err(e) = job.sim.step() {
            failure = Some(e.to_string());
            break;
        }
        if let Some(out) = job.output.as_mut() {
            if let Err(e) = out.record(&job.sim) {
                failure = Some(e.to_string());
                break;
            }
        }
        if job.checkpoint_every.is_some_and(|n| job.sim.steps() % n == 0) {
            match save_checkpoint(&job, output_progress(job.output.as_ref())) {
                Ok(()) => checkpoint_written = Some(job.checkpoint_path.clone()),
                Err(e) => {
                    failure = Some(e.to_string());
                    break;
                }
            }
        }
        // warnings raised during the run (a fixed dt that became too large)
        for warning in &job.sim.warnings()[warned..] {
            progress.suspend(|| eprintln!("warning: {warning}"));
        }
        warned = job.sim.warnings().len();
        progress.tick(&job.sim);
    }
    progress.finish();
    if failure.is_some() {
        status = Status::Failed;
    }
    if status == Status::Interrupted {
        // the progress before `finish`, which adds a frame and a row off the schedule: a
        // resumed run then writes the same series as an uninterrupted one
        save_checkpoint(&job, output_progress(job.output.as_ref()))?;
        checkpoint_written = Some(job.checkpoint_path.clone());
    }
    let output_summary = match job.output.as_mut() {
        Some(out) => match out.finish(&job.sim) {
            Ok(report) => Some(OutputSummary::of(&job.output_settings, &report)),
            Err(e) => {
                let message = match failure.take() {
                    Some(first) => format!("{first}; then finishing the output failed: {e}"),
                    None => e.to_string(),
                };
                failure = Some(message);
                status = Status::Failed;
                None
            }
        },
        None => None,
    };
    let wall = wall.elapsed();
    let steps_this_run = job.sim.steps() - start_steps;
    let summary = Summary {
        flexdem_version: env!("CARGO_PKG_VERSION").to_string(),
        scene: job.scene.clone(),
        status,
        error: failure.clone(),
        steps: job.sim.steps(),
        steps_this_run,
        time: job.sim.time(),
        dt: job.sim.dt(),
        critical_dt: job.sim.critical_dt(),
        wall_time: wall.as_secs_f64(),
        steps_per_second: steps_this_run as f64 / wall.as_secs_f64().max(1e-9),
        threads: job.threads.1,
        stages: Stages::of(&job.sim, wall),
        counts: Counts::of(&job.sim),
        collider: ColliderSummary {
            candidate_pairs: job.sim.collider.pairs.len(),
            builds: job.sim.collider.builds,
        },
        energy: EnergySummary::of(&job.sim),
        tracked: tracked_values(&job.output_settings, &job.sim),
        output: output_summary,
        checkpoint: checkpoint_written,
    };
    if !job.quiet {
        print!("{}", report::text(&summary));
    }
    if let Some(path) = &job.summary {
        write_json(&summary, path).map_err(CliError::Run)?;
    }
    match (status, failure) {
        (_, Some(message)) => Err(CliError::Run(match &summary.output {
            Some(o) => {
                format!("{message}\n(the output written so far is in {})", o.directory.display())
            }
            None => message,
        })),
        (Status::Interrupted, None) => {
            eprintln!(
                "interrupted at step {}: checkpoint written to {}; continue with `flexdem resume {}`",
                job.sim.steps(),
                job.checkpoint_path.display(),
                job.checkpoint_path.display()
            );
            Ok(Outcome::Interrupted)
        }
        _ => Ok(Outcome::Done),
    }
}

/// The default checkpoint path: `checkpoint.flexdem` in `directory`.
pub fn default_checkpoint_path(directory: &Path) -> PathBuf {
    directory.join(CHECKPOINT_FILE)
}

/// Whether `settings` writes anything at all.
pub fn writes_something(settings: &OutputSettings) -> bool {
    settings.vtk_every.is_some() || settings.series_every.is_some()
}
