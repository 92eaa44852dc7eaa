//! [`Run`]: a simulation stepped to its run length with its output, periodic checkpoints, an
//! interrupt flag and callbacks, ending in a [`Summary`].

use crate::build::build_simulation;
use crate::error::RunError;
use crate::observer::RunObserver;
use crate::options::RunOptions;
use crate::summary::{
    tracked_values, ColliderSummary, Counts, EnergySummary, OutputSummary, Stages, Status, Summary,
};
use flexdem_integrate::Simulation;
use flexdem_io::checkpoint::{read_checkpoint, write_checkpoint, Checkpoint};
use flexdem_output::{Output, OutputProgress, OutputSettings};
use flexdem_scene::{load_scene, RunLength, Scene};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// Name of the checkpoint file in the output folder.
pub const CHECKPOINT_FILE: &str = "checkpoint.flexdem";

/// Why [`Run::advance`] returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The run length is reached.
    Reached,
    /// The number of steps asked of this call is done.
    StepLimit,
    /// The interrupt flag is set; [`Run::finish`] writes a checkpoint.
    Interrupted,
}

/// A run: the simulation, its output, where it ends and where its checkpoints go.
///
/// ```no_run
/// use flexdem_run::{NoObserver, Run, RunOptions};
///
/// let mut run = Run::from_scene("scene.toml".as_ref(), RunOptions::default())?;
/// run.advance(Some(1000), &mut NoObserver)?; // 1000 steps, with output
/// println!("t = {} s", run.sim().time());
/// run.advance(None, &mut NoObserver)?; // to the run length
/// let summary = run.finish(&mut NoObserver)?;
/// println!("energy balance error {:.2e}", summary.energy.relative_balance_error);
/// # Ok::<(), flexdem_run::RunError>(())
/// ```
pub struct Run {
    sim: Simulation,
    /// The output being written (None: nothing is written).
    output: Option<Output>,
    /// A resumed run's output not opened yet: the checkpoint's run length was reached, so the
    /// output was left as that run wrote it. It opens when the run steps on
    /// ([`Run::open_resumed_output`]) and its progress is what checkpoints store until then.
    resumed_output: Option<ResumedOutput>,
    /// The output settings (the series give the tracked quantities even without output).
    output_settings: OutputSettings,
    /// Where the run ends, since the start of the simulation. Stored in checkpoints.
    target: RunLength,
    /// Worker threads asked for (stored in checkpoints).
    threads: Option<usize>,
    /// The scene file.
    scene: PathBuf,
    checkpoint_path: PathBuf,
    checkpoint_every: Option<u64>,
    interrupt: Option<Arc<AtomicBool>>,
    /// When the first [`Run::advance`] started, and the step count then.
    started: Option<(Instant, u64)>,
    /// Warnings of the engine already reported.
    warned: usize,
    interrupted: bool,
    /// The first error of the run, as reported in the summary.
    failure: Option<String>,
    checkpoint_written: Option<PathBuf>,
}

/// A checkpoint's output, to continue once the resumed run steps on.
struct ResumedOutput {
    /// What the checkpointed run had written.
    progress: OutputProgress,
    /// The checkpoint file (named in errors).
    checkpoint: PathBuf,
}

/// `path` made absolute against the current folder (so that a checkpoint can be resumed
/// from anywhere); unchanged if that fails.
fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}

/// Whether `settings` writes anything at all.
fn writes_something(settings: &OutputSettings) -> bool {
    settings.vtk_every.is_some() || settings.series_every.is_some()
}

/// `settings` writing nothing.
fn without_files(settings: &mut OutputSettings) {
    settings.vtk_every = None;
    settings.series_every = None;
    settings.plot = false;
}

/// Whether `sim` has reached `target`.
fn reached(sim: &Simulation, target: RunLength) -> bool {
    match target {
        RunLength::Steps(n) => sim.steps() >= n,
        RunLength::Duration(d) => sim.time() >= d,
    }
}

impl Run {
    /// Reads the scene file at `path` and sets up its run ([`Run::new`]).
    pub fn from_scene(path: &Path, options: RunOptions) -> Result<Run, RunError> {
        Run::new(load_scene(path)?, options)
    }

    /// Sets up the run of `scene`: builds the simulation with its loads, opens the output
    /// (creating its folder, made absolute, and the CSV header). The worker threads must be
    /// set up before ([`crate::configure_threads`]).
    pub fn new(scene: Scene, options: RunOptions) -> Result<Run, RunError> {
        let threads = options.threads.or(scene.threads);
        let (sim, mut rest) = build_simulation(scene)?;
        if let Some(dir) = &options.output_directory {
            rest.output.directory = dir.clone();
        }
        rest.output.directory = absolute(&rest.output.directory);
        if options.no_output {
            without_files(&mut rest.output);
        }
        let target = options.steps.map_or(rest.run, RunLength::Steps);
        let output = if writes_something(&rest.output) {
            Some(Output::new(&rest.output, &sim).map_err(RunError::OutputSetup)?)
        } else {
            None
        };
        let checkpoint_path = match &options.checkpoint_path {
            Some(path) => absolute(path),
            None => rest.output.directory.join(CHECKPOINT_FILE),
        };
        Ok(Run::assemble(
            sim,
            output,
            rest.output,
            target,
            threads,
            absolute(&rest.source),
            checkpoint_path,
            options,
        ))
    }

    /// Reads the checkpoint at `path` and sets up the run that continues it
    /// ([`Run::from_checkpoint`]).
    pub fn resume(path: &Path, options: RunOptions) -> Result<Run, RunError> {
        let checkpoint =
            read_checkpoint(path).map_err(|e| RunError::ReadCheckpoint(Box::new(e)))?;
        Run::from_checkpoint(checkpoint, path, options)
    }

    /// Sets up the run that continues `checkpoint` (read from `path`) to its run length (or
    /// `options.steps` more), appending to its output. When the run length is already
    /// reached ([`Run::is_done`]) the output is opened only once the run steps on (a later
    /// [`Run::set_target`], then [`Run::advance`]): until then it is left as the run wrote it. The
    /// worker threads must be set up before ([`crate::configure_threads`]; the checkpoint's
    /// `threads` are the ones the run had).
    pub fn from_checkpoint(
        checkpoint: Checkpoint,
        path: &Path,
        options: RunOptions,
    ) -> Result<Run, RunError> {
        let threads = options.threads.or(checkpoint.threads);
        let (sim, info) = checkpoint.into_simulation().map_err(|source| RunError::Resume {
            path: path.to_owned(),
            source: Box::new(source),
        })?;
        let target = match options.steps {
            Some(n) => RunLength::Steps(sim.steps().saturating_add(n)),
            None => info.run,
        };
        let mut settings = info.output;
        if options.no_output {
            without_files(&mut settings);
        }
        let mut output = None;
        let mut resumed_output = None;
        if writes_something(&settings) {
            if reached(&sim, target) {
                let checkpoint = path.to_owned();
                resumed_output = Some(ResumedOutput { progress: info.output_progress, checkpoint });
            } else {
                let resumed = Output::resume(&settings, &sim, &info.output_progress)
                    .map_err(|source| RunError::OutputResume { path: path.to_owned(), source })?;
                output = Some(resumed);
            }
        }
        let checkpoint_path = absolute(options.checkpoint_path.as_deref().unwrap_or(path));
        let mut run = Run::assemble(
            sim,
            output,
            settings,
            target,
            threads,
            info.scene,
            checkpoint_path,
            options,
        );
        run.resumed_output = resumed_output;
        Ok(run)
    }

    /// Opens the output of a run resumed at its run length once it steps on: the files are
    /// cut back to the checkpoint's progress, as for any resumed run (the row its end added is
    /// dropped, and its frame leaves the `.pvd`), and the current state is recorded if due.
    fn open_resumed_output(&mut self) -> Result<(), RunError> {
        let Some(resumed) = self.resumed_output.as_ref().filter(|_| !self.is_done()) else {
            return Ok(());
        };
        let mut output =
            Output::resume(&self.output_settings, &self.sim, &resumed.progress).map_err(
                |source| RunError::OutputResume { path: resumed.checkpoint.clone(), source },
            )?;
        output.record(&self.sim).map_err(RunError::Output)?;
        self.output = Some(output);
        self.resumed_output = None;
        Ok(())
    }

    /// The output's progress for a checkpoint: what is written, or what the checkpoint this
    /// run resumed had written while its output is not open yet.
    fn output_progress(&self) -> OutputProgress {
        match (&self.output, &self.resumed_output) {
            (Some(output), _) => output.progress(),
            (None, Some(resumed)) => resumed.progress.clone(),
            (None, None) => OutputProgress { vtk_frames: Vec::new(), series_rows: 0 },
        }
    }

    /// A run not started yet.
    fn assemble(
        sim: Simulation,
        output: Option<Output>,
        output_settings: OutputSettings,
        target: RunLength,
        threads: Option<usize>,
        scene: PathBuf,
        checkpoint_path: PathBuf,
        options: RunOptions,
    ) -> Run {
        Run {
            sim,
            output,
            resumed_output: None,
            output_settings,
            target,
            threads,
            scene,
            checkpoint_path,
            checkpoint_every: options.checkpoint_every,
            interrupt: options.interrupt,
            started: None,
            warned: 0,
            interrupted: false,
            failure: None,
            checkpoint_written: None,
        }
    }

    /// The simulation.
    pub fn sim(&self) -> &Simulation {
        &self.sim
    }

    /// The simulation, to change between stages of a run (a script's new loads, damping,
    /// wall or imposed velocities): through `Simulation`'s setters and `edit_model`, which
    /// keep its caches right.
    pub fn sim_mut(&mut self) -> &mut Simulation {
        &mut self.sim
    }

    /// The simulation, given back when the run is over.
    pub fn into_simulation(self) -> Simulation {
        self.sim
    }

    /// Where the run ends (step count or simulated time since the start of the simulation).
    pub fn target(&self) -> RunLength {
        self.target
    }

    /// Moves where the run ends (a script running in stages); later checkpoints store the
    /// new run length.
    pub fn set_target(&mut self, target: RunLength) {
        self.target = target;
    }

    /// Whether the run length is reached.
    pub fn is_done(&self) -> bool {
        reached(&self.sim, self.target)
    }

    /// The scene file the run came from.
    pub fn scene_file(&self) -> &Path {
        &self.scene
    }

    /// The output settings (with the caller's changes).
    pub fn output_settings(&self) -> &OutputSettings {
        &self.output_settings
    }

    /// Where checkpoints go.
    pub fn checkpoint_path(&self) -> &Path {
        &self.checkpoint_path
    }

    /// Sends later checkpoints to `path` (made absolute against the current folder).
    pub fn set_checkpoint_path(&mut self, path: &Path) {
        self.checkpoint_path = absolute(path);
    }

    /// Worker threads asked for (None: the machine's default), as stored in checkpoints.
    pub fn threads(&self) -> Option<usize> {
        self.threads
    }

    /// Steps on until the run length, `max_steps` more steps (None: no limit), the interrupt
    /// flag or an error, writing the output (the state before the first step on the first
    /// call) and the periodic checkpoints. An error ends the run: it is reported again by
    /// [`Run::finish`], which still finishes the output.
    pub fn advance(
        &mut self,
        max_steps: Option<u64>,
        observer: &mut dyn RunObserver,
    ) -> Result<Stop, RunError> {
        if let Some(message) = &self.failure {
            return Err(RunError::Summary(format!("the run has failed: {message}")));
        }
        if self.started.is_none() {
            for warning in self.sim.warnings() {
                observer.warning(warning);
            }
            self.warned = self.sim.warnings().len();
            self.started = Some((Instant::now(), self.sim.steps()));
            observer.started(&self.sim, self.target);
            let recorded = match self.output.as_mut() {
                Some(out) => out.record(&self.sim),
                None => Ok(()),
            };
            recorded.map_err(|e| self.fail(RunError::Output(e)))?;
        }
        self.open_resumed_output().map_err(|e| self.fail(e))?;
        let mut done = 0;
        loop {
            if self.is_done() {
                return Ok(Stop::Reached);
            }
            if max_steps.is_some_and(|n| done >= n) {
                return Ok(Stop::StepLimit);
            }
            if self.interrupt.as_ref().is_some_and(|flag| flag.load(Ordering::SeqCst)) {
                self.interrupted = true;
                return Ok(Stop::Interrupted);
            }
            self.step(observer).map_err(|e| self.fail(e))?;
            done += 1;
        }
    }

    /// One step with its output, periodic checkpoint and callbacks.
    fn step(&mut self, observer: &mut dyn RunObserver) -> Result<(), RunError> {
        self.sim.step().map_err(|e| RunError::Step(Box::new(e)))?;
        if let Some(out) = self.output.as_mut() {
            out.record(&self.sim).map_err(RunError::Output)?;
        }
        if self.checkpoint_every.is_some_and(|n| self.sim.steps() % n == 0) {
            self.save_checkpoint()?;
            observer.checkpoint_written(&self.checkpoint_path);
        }
        // warnings raised during the run (a fixed dt that became too large)
        for warning in &self.sim.warnings()[self.warned..] {
            observer.warning(warning);
        }
        self.warned = self.sim.warnings().len();
        observer.stepped(&self.sim);
        Ok(())
    }

    /// Records `error` as the run's failure and gives it back.
    fn fail(&mut self, error: RunError) -> RunError {
        self.failure = Some(error.to_string());
        error
    }

    /// Writes the checkpoint of the current state to [`Run::checkpoint_path`], with the
    /// output's progress: resuming from it continues bit-identically.
    pub fn save_checkpoint(&mut self) -> Result<(), RunError> {
        let output_progress = self.output_progress();
        let checkpoint = Checkpoint {
            state: self.sim.state().clone(),
            run: self.target,
            threads: self.threads,
            output: self.output_settings.clone(),
            scene: self.scene.clone(),
            output_progress,
        };
        if let Some(dir) = self.checkpoint_path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .map_err(|source| RunError::CheckpointFolder { path: dir.to_owned(), source })?;
        }
        write_checkpoint(&self.checkpoint_path, &checkpoint)
            .map_err(|e| RunError::WriteCheckpoint(Box::new(e)))?;
        self.checkpoint_written = Some(self.checkpoint_path.clone());
        Ok(())
    }

    /// Ends the run: a checkpoint if it was interrupted, the last frame and row, the `.pvd`
    /// and the plot; returns the summary (its `status` and `error` say how the run ended). An
    /// error is returned only when the interrupted run's checkpoint cannot be written.
    pub fn finish(&mut self, observer: &mut dyn RunObserver) -> Result<Summary, RunError> {
        let (start, start_steps) = *self.started.get_or_insert((Instant::now(), self.sim.steps()));
        observer.finished(&self.sim);
        let mut status = match (&self.failure, self.interrupted) {
            (Some(_), _) => Status::Failed,
            (None, true) => Status::Interrupted,
            (None, false) => Status::Completed,
        };
        if status == Status::Interrupted {
            // the progress before `finish`, which adds a frame and a row off the schedule: a
            // resumed run then writes the same series as an uninterrupted one
            self.save_checkpoint()?;
        }
        let output_summary = match self.output.as_mut() {
            Some(out) => match out.finish(&self.sim) {
                Ok(report) => Some(OutputSummary::of(&self.output_settings, &report)),
                Err(e) => {
                    let message = match self.failure.take() {
                        Some(first) => format!("{first}; then finishing the output failed: {e}"),
                        None => e.to_string(),
                    };
                    self.failure = Some(message);
                    status = Status::Failed;
                    None
                }
            },
            None => None,
        };
        let wall = start.elapsed();
        let sim = &self.sim;
        let steps_this_run = sim.steps() - start_steps;
        Ok(Summary {
            flexdem_version: env!("CARGO_PKG_VERSION").to_string(),
            scene: self.scene.clone(),
            status,
            error: self.failure.clone(),
            warnings: self.sim.warnings().to_vec(),
            steps: sim.steps(),
            steps_this_run,
            time: sim.time(),
            dt: sim.dt(),
            critical_dt: sim.critical_dt(),
            wall_time: wall.as_secs_f64(),
            steps_per_second: steps_this_run as f64 / wall.as_secs_f64().max(1e-9),
            threads: rayon::current_num_threads(),
            stages: Stages::of(sim, wall),
            counts: Counts::of(sim),
            collider: ColliderSummary {
                candidate_pairs: sim.collider().pairs.len(),
                builds: sim.collider().builds,
            },
            energy: EnergySummary::of(sim),
            tracked: tracked_values(&self.output_settings, sim),
            output: output_summary,
            checkpoint: self.checkpoint_written.clone(),
        })
    }

    /// The whole run: [`Run::advance`] to the end, then [`Run::finish`].
    ///
    /// It runs on one of rayon's worker threads: the engine's parallel loops then start on
    /// that worker instead of being handed over from the calling thread, which would wake a
    /// worker and wait for it some ten times per step (tens of microseconds per step, as much
    /// as the step itself on a small scene).
    pub fn execute(
        &mut self,
        observer: &mut (dyn RunObserver + Send),
    ) -> Result<Summary, RunError> {
        rayon::join(
            || {
                // an error is recorded by the run and reported in the summary
                let _ = self.advance(None, observer);
                self.finish(observer)
            },
            || (),
        )
        .0
    }
}
