//! What a run reports at the end, as plain data ([`Summary`]): what the command line prints
//! as text and writes as JSON (`--summary`), what a library user reads.

use crate::error::RunError;
use flexdem_elements::ParticleKind;
use flexdem_integrate::{Energy, Simulation};
use flexdem_output::{
    header_columns, row_values, series_columns, OutputReport, OutputSettings, CSV_FILE, PLOT_FILE,
    PVD_FILE,
};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// It reached its run length.
    Completed,
    /// Ctrl-C stopped it; a checkpoint was written.
    Interrupted,
    /// It stopped on an error (an unstable run, an output that cannot be written).
    Failed,
}

/// The JSON summary of a run (`--summary FILE.json`); every time in seconds, every energy
/// in joules.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// Version of flexdem that ran it.
    pub flexdem_version: String,
    /// The scene file.
    pub scene: PathBuf,
    /// How the run ended.
    pub status: Status,
    /// The error that stopped a failed run.
    pub error: Option<String>,
    /// The engine's warnings over the simulation, earlier runs of a resumed one included
    /// (energy lost that the balance does not count, a fixed dt above the critical step, ...):
    /// a run with warnings still completes, and its summary says why to look closer.
    pub warnings: Vec<String>,
    /// Steps done since the start of the simulation (a resumed run counts the earlier ones).
    pub steps: u64,
    /// Steps done by this command.
    pub steps_this_run: u64,
    /// Simulated time (s).
    pub time: f64,
    /// Time step at the end (s).
    pub dt: f64,
    /// Critical time step at the last estimate (s).
    pub critical_dt: f64,
    /// Wall-clock time of this command's steps and output (s).
    pub wall_time: f64,
    /// Steps per wall-clock second.
    pub steps_per_second: f64,
    /// Number of worker threads.
    pub threads: usize,
    /// Wall-clock time per stage of the step (s).
    pub stages: Stages,
    /// Bodies and contacts at the end.
    pub counts: Counts,
    /// The broad phase's work.
    pub collider: ColliderSummary,
    /// Energy terms at the end and the balance.
    pub energy: EnergySummary,
    /// Final value of each tracked series quantity: series name → CSV column → value.
    pub tracked: BTreeMap<String, BTreeMap<String, f64>>,
    /// The output written (None with `--no-output` or when the scene asks for none).
    pub output: Option<OutputSummary>,
    /// The last checkpoint written by this run.
    pub checkpoint: Option<PathBuf>,
}

/// Wall-clock time per stage (s); `other` is output, checkpoints and progress.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Stages {
    /// Broad phase.
    pub collision: f64,
    /// Contact detection, law and force distribution.
    pub contacts: f64,
    /// Beam links.
    pub links: f64,
    /// Imposed loads and the force hook.
    pub loads: f64,
    /// Leapfrog integration.
    pub integration: f64,
    /// Checks, energy terms and watch, time step.
    pub bookkeeping: f64,
    /// Everything else: output, checkpoints, progress.
    pub other: f64,
}

/// Counts of bodies and contacts.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Counts {
    /// Every particle (spheres and nodes).
    pub particles: usize,
    /// Free spheres.
    pub spheres: usize,
    /// Structure nodes.
    pub nodes: usize,
    /// Connections (one beam link each).
    pub connections: usize,
    /// Links still intact.
    pub intact_links: usize,
    /// Links broken.
    pub broken_links: usize,
    /// PFacets.
    pub pfacets: usize,
    /// Walls.
    pub walls: usize,
    /// Structures.
    pub structures: usize,
    /// Contacts at the end.
    pub contacts: usize,
}

/// The broad phase's work (not part of the state: a resumed run rebuilds its candidate pairs
/// at the resume, so these differ from an uninterrupted run's).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ColliderSummary {
    /// Candidate pairs of the last build.
    pub candidate_pairs: usize,
    /// Builds (broad phase runs) since the simulation started or was resumed.
    pub builds: u64,
}

/// The energy terms (J) and the balance.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct EnergySummary {
    /// Every term, as the engine reports it.
    #[serde(flatten)]
    pub terms: Energy,
    /// Kinetic plus elastic energy.
    pub stored: f64,
    /// Stored energy minus work in plus dissipated (constant when the balance closes).
    pub balance: f64,
    /// The balance at the start of the simulation (kept in checkpoints).
    pub initial_balance: f64,
    /// The energy scale the error is measured against: the largest of the initial balance,
    /// the stored energy, the works and the energy taken out, over the whole run.
    pub scale: f64,
    /// The lowest balance since the start: once it is below the start by more than the
    /// tolerance, the watch measures energy created from it (plus the tolerance).
    pub lowest_balance: f64,
    /// (balance − initial balance) / scale: the drift since the start (the energy watch
    /// stops a run when it passes the tolerance, or when the balance rises by more than twice
    /// the tolerance above its lowest after a loss: docs/model.md §4).
    pub relative_balance_error: f64,
    /// First touches found with more overlap than one step of approach explains (their
    /// energy is `contact_births`).
    pub contacts_born_deep: u64,
    /// The energy those found after the first step put in (J, part of `contact_births`):
    /// the energy watch stops a run when it passes the tolerance times the scale.
    pub late_contacts_energy: f64,
}

/// Where the output went.
#[derive(Clone, Debug, Serialize)]
pub struct OutputSummary {
    /// The output folder.
    pub directory: PathBuf,
    /// The ParaView time series, if VTK frames were written.
    pub pvd: Option<PathBuf>,
    /// The CSV series, if written.
    pub csv: Option<PathBuf>,
    /// The PNG plot, if drawn.
    pub plot: Option<PathBuf>,
    /// VTK frames in the time series.
    pub vtk_frames: usize,
    /// CSV rows in the series.
    pub series_rows: usize,
    /// Number of files written by this run.
    pub files_written: usize,
}

impl Counts {
    /// The counts of `sim` now.
    pub fn of(sim: &Simulation) -> Counts {
        let m = &sim.model();
        let spheres = m.particles.kind.iter().filter(|k| **k == ParticleKind::Sphere).count();
        Counts {
            particles: m.particles.len(),
            spheres,
            nodes: m.particles.len() - spheres,
            connections: m.connections.len(),
            intact_links: sim.links().intact(),
            broken_links: sim.links().len() - sim.links().intact(),
            pfacets: m.pfacets.len(),
            walls: m.walls.len(),
            structures: m.structures.len(),
            contacts: sim.contacts().len(),
        }
    }
}

impl EnergySummary {
    /// The energy of `sim` and its balance, as the engine's energy watch measures it.
    pub fn of(sim: &Simulation) -> EnergySummary {
        let e = *sim.energy();
        let watch = sim.energy_watch();
        EnergySummary {
            terms: e,
            stored: e.stored(),
            balance: e.balance(),
            initial_balance: watch.initial_balance,
            lowest_balance: watch.lowest_balance,
            scale: watch.scale,
            relative_balance_error: sim.relative_balance_error(),
            contacts_born_deep: sim.contacts_born_deep(),
            late_contacts_energy: watch.late_births,
        }
    }
}

impl Stages {
    /// The engine's stage timers; `wall` is the whole run, the rest of it goes to `other`.
    pub fn of(sim: &Simulation, wall: Duration) -> Stages {
        let t = sim.timers();
        Stages {
            collision: t.collision.as_secs_f64(),
            contacts: t.contacts.as_secs_f64(),
            links: t.links.as_secs_f64(),
            loads: t.loads.as_secs_f64(),
            integration: t.integration.as_secs_f64(),
            bookkeeping: t.bookkeeping.as_secs_f64(),
            other: wall.saturating_sub(t.total()).as_secs_f64(),
        }
    }
}

/// The current value of every column of every series in `settings`, grouped by series.
pub fn tracked_values(
    settings: &OutputSettings,
    sim: &Simulation,
) -> BTreeMap<String, BTreeMap<String, f64>> {
    let columns = header_columns(&settings.series);
    let values = row_values(&settings.series, sim);
    let mut tracked = BTreeMap::new();
    let mut column = 2; // after time_s and step
    for spec in &settings.series {
        let n = series_columns(spec).len();
        let entry: BTreeMap<String, f64> = (column..column + n)
            .filter_map(|i| Some((columns.get(i)?.clone(), *values.get(i)?)))
            .collect();
        tracked.insert(spec.name.clone(), entry);
        column += n;
    }
    tracked
}

impl OutputSummary {
    /// What `report` says was written into the folder of `settings`.
    pub fn of(settings: &OutputSettings, report: &OutputReport) -> OutputSummary {
        let written = |name: &str| {
            let path = settings.directory.join(name);
            report.files.contains(&path).then_some(path)
        };
        OutputSummary {
            directory: settings.directory.clone(),
            pvd: written(PVD_FILE),
            csv: written(CSV_FILE),
            plot: written(PLOT_FILE),
            vtk_frames: report.vtk_frames,
            series_rows: report.series_rows,
            files_written: report.files.len(),
        }
    }
}

/// Writes `summary` as pretty JSON to `path` (creating its folder).
pub fn write_json(summary: &Summary, path: &Path) -> Result<(), RunError> {
    write_json_text(summary, path).map_err(RunError::Summary)
}

/// [`write_json`] with the error as a message.
fn write_json_text(summary: &Summary, path: &Path) -> Result<(), String> {
    let text = serde_json::to_string_pretty(summary)
        .map_err(|e| format!("cannot encode the summary as JSON: {e}"))?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create the folder {}: {e}", dir.display()))?;
    }
    std::fs::write(path, text + "\n")
        .map_err(|e| format!("cannot write the summary {}: {e}", path.display()))
}
