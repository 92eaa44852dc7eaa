//! [`Output`]: writes the frames, the series and the plot of a run as it goes, and continues
//! them after a checkpoint.

use crate::error::OutputError;
use crate::files;
use crate::frames::{
    connections_polydata, contacts_polydata, particles_polydata, pfacets_polydata,
};
use crate::pvd::{pvd_xml, PvdEntry};
use crate::series::{header_columns, row_values, validate_series, OutputSettings, SeriesSpec};
use crate::table::CsvSeries;
use flexdem_geom::Real;
use flexdem_integrate::Simulation;
use serde::{Deserialize, Serialize};
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// Name of the `.pvd` time series in the output folder.
pub const PVD_FILE: &str = "flexdem.pvd";
/// Name of the CSV series in the output folder.
pub const CSV_FILE: &str = "series.csv";
/// Name of the PNG plot in the output folder.
pub const PLOT_FILE: &str = "series.png";

/// The `.pvd` is rewritten after each of the first this many frames, then after every this
/// many (so a long run does not rewrite a growing file each frame), and at the end.
pub const PVD_REWRITE_PERIOD: usize = 64;

/// What the output of a run has written so far, so that a resumed run continues the same
/// VTK series and CSV file (stored in checkpoints; see [`Output::progress`] and
/// [`Output::resume`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct OutputProgress {
    /// The VTK frames written: (step, simulated time in s) of each, in order.
    pub vtk_frames: Vec<(u64, f64)>,
    /// Number of data rows written to the CSV series (header not counted).
    pub series_rows: u64,
}

/// What a run wrote.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OutputReport {
    /// Every file written, each once, in the order first written.
    pub files: Vec<PathBuf>,
    /// Number of VTK frames.
    pub vtk_frames: usize,
    /// Number of CSV rows (header excluded).
    pub series_rows: usize,
}

/// Writes the output of a run as it goes: call [`Output::record`] after each step (and once
/// before the first) and [`Output::finish`] at the end.
#[derive(Debug)]
pub struct Output {
    settings: OutputSettings,
    pvd_entries: Vec<PvdEntry>,
    /// Step and time of each frame in `pvd_entries`.
    frames: Vec<(u64, Real)>,
    last_frame_step: Option<u64>,
    last_row_step: Option<u64>,
    csv: Option<CsvSeries>,
    rows: Vec<Vec<Real>>,
    files: Vec<PathBuf>,
    noted: HashSet<PathBuf>,
}

impl Output {
    /// An output with nothing written yet.
    fn empty(settings: &OutputSettings) -> Output {
        Output {
            settings: settings.clone(),
            pvd_entries: Vec::new(),
            frames: Vec::new(),
            last_frame_step: None,
            last_row_step: None,
            csv: None,
            rows: Vec::new(),
            files: Vec::new(),
            noted: HashSet::new(),
        }
    }

    /// Checks the settings against `sim`, creates the output folder and, when series are
    /// recorded, writes the CSV header.
    pub fn new(settings: &OutputSettings, sim: &Simulation) -> Result<Output, OutputError> {
        check_output_settings(settings, sim)?;
        files::create_directory(&settings.directory)?;
        let mut output = Output::empty(settings);
        if settings.series_every.is_some() {
            let path = settings.directory.join(CSV_FILE);
            let csv = CsvSeries::create(&path, &header_columns(&settings.series))?;
            output.note_file(path);
            output.csv = Some(csv);
        }
        Ok(output)
    }

    /// Continues the output of an earlier run from a checkpoint, for `sim` restored from it:
    /// the `.pvd` keeps the checkpoint's frames (whose `.vtp` files must still be there) and
    /// `series.csv` keeps its header and its first `progress.series_rows` rows (rows written
    /// after the checkpoint are dropped, as are frames), then both go on as with
    /// [`Output::new`]. The plot at the end covers the whole series.
    pub fn resume(
        settings: &OutputSettings,
        sim: &Simulation,
        progress: &OutputProgress,
    ) -> Result<Output, OutputError> {
        check_output_settings(settings, sim)?;
        files::create_directory(&settings.directory)?;
        let mut output = Output::empty(settings);
        for &(step, time) in &progress.vtk_frames {
            for (part, name) in PARTS.iter().enumerate() {
                let file = frame_file_name(name, step);
                let path = settings.directory.join(&file);
                if !path.is_file() {
                    return Err(OutputError::Resume {
                        path,
                        problem: format!("the frame of step {step} is missing"),
                    });
                }
                output.pvd_entries.push(PvdEntry {
                    time,
                    part: part as u32,
                    name: name.to_string(),
                    file,
                });
            }
            output.frames.push((step, time));
            output.last_frame_step = Some(step);
        }
        if settings.series_every.is_some() {
            let path = settings.directory.join(CSV_FILE);
            let columns = header_columns(&settings.series);
            let rows = usize::try_from(progress.series_rows).unwrap_or(usize::MAX);
            let (csv, kept) = if rows == 0 {
                (CsvSeries::create(&path, &columns)?, Vec::new())
            } else {
                CsvSeries::resume(&path, &columns, rows)?
            };
            output.last_row_step = kept.last().and_then(|row| row.get(1)).map(|&s| s as u64);
            output.rows = kept;
            output.note_file(path);
            output.csv = Some(csv);
        }
        Ok(output)
    }

    /// What has been written so far, for a checkpoint: the step and time of each VTK frame
    /// and the number of CSV rows ([`Output::resume`] continues from it).
    pub fn progress(&self) -> OutputProgress {
        OutputProgress { vtk_frames: self.frames.clone(), series_rows: self.rows.len() as u64 }
    }

    /// The settings this output was made with.
    pub fn settings(&self) -> &OutputSettings {
        &self.settings
    }

    /// The CSV rows recorded so far (time, step, then the series' columns).
    pub fn rows(&self) -> &[Vec<Real>] {
        &self.rows
    }

    /// Writes what is due at step `sim.steps()`: a VTK frame every `vtk_every` steps and a CSV
    /// row every `series_every` steps (so both at step 0); nothing twice for the same step.
    pub fn record(&mut self, sim: &Simulation) -> Result<(), OutputError> {
        let step = sim.steps();
        let due = |every: Option<u64>| every.is_some_and(|n| step % n == 0);
        if due(self.settings.vtk_every) && self.last_frame_step != Some(step) {
            self.write_frame(sim)?;
        }
        if due(self.settings.series_every) && self.last_row_step != Some(step) {
            self.write_row(sim)?;
        }
        Ok(())
    }

    /// Writes the last frame and row (if not written at this step yet), the `.pvd`, flushes
    /// the CSV and draws the plot; returns the files written.
    pub fn finish(&mut self, sim: &Simulation) -> Result<OutputReport, OutputError> {
        let step = sim.steps();
        if self.settings.vtk_every.is_some() && self.last_frame_step != Some(step) {
            self.write_frame(sim)?;
        }
        if self.settings.series_every.is_some() && self.last_row_step != Some(step) {
            self.write_row(sim)?;
        }
        if self.settings.vtk_every.is_some() {
            self.write_pvd()?;
        }
        if let Some(csv) = self.csv.as_mut() {
            csv.flush()?;
        }
        if self.settings.plot {
            let path = self.settings.directory.join(PLOT_FILE);
            draw_plot(&path, &self.settings.series, &self.rows)?;
            self.note_file(path);
        }
        Ok(OutputReport {
            files: self.files.clone(),
            vtk_frames: self.pvd_entries.len() / 4,
            series_rows: self.rows.len(),
        })
    }

    /// Writes the four `.vtp` files of the current state and rewrites the `.pvd`.
    fn write_frame(&mut self, sim: &Simulation) -> Result<(), OutputError> {
        let step = sim.steps();
        let written = write_parts(&self.settings.directory, sim)?;
        let mut entries = Vec::with_capacity(written.len());
        for (part, (file, path)) in written.into_iter().enumerate() {
            self.note_file(path);
            entries.push(PvdEntry {
                time: sim.time(),
                part: part as u32,
                name: PARTS[part].to_string(),
                file,
            });
        }
        // the frame enters the series only once all its parts are written
        self.pvd_entries.extend(entries);
        self.frames.push((step, sim.time()));
        self.last_frame_step = Some(step);
        let frames = self.pvd_entries.len() / 4;
        if frames < PVD_REWRITE_PERIOD || frames % PVD_REWRITE_PERIOD == 0 {
            self.write_pvd()?;
        }
        Ok(())
    }

    /// Rewrites the `.pvd` with every frame so far.
    fn write_pvd(&mut self) -> Result<(), OutputError> {
        let path = self.settings.directory.join(PVD_FILE);
        files::write_atomically(&path, pvd_xml(&self.pvd_entries).as_bytes())?;
        self.note_file(path);
        Ok(())
    }

    /// Appends one CSV row of the current state.
    fn write_row(&mut self, sim: &Simulation) -> Result<(), OutputError> {
        let row = row_values(&self.settings.series, sim);
        if let Some(csv) = self.csv.as_mut() {
            csv.append(&row)?;
        }
        self.rows.push(row);
        self.last_row_step = Some(sim.steps());
        Ok(())
    }

    /// Adds `path` to the list of files written, once.
    fn note_file(&mut self, path: PathBuf) {
        if self.noted.insert(path.clone()) {
            self.files.push(path);
        }
    }
}

/// The parts of a frame, in the order of their part numbers in the `.pvd`.
const PARTS: [&str; 4] = ["particles", "connections", "pfacets", "contacts"];

/// Writes the four `.vtp` files of `sim`'s current state into `directory`, in the order of
/// [`PARTS`]; returns the file name and path of each.
fn write_parts(directory: &Path, sim: &Simulation) -> Result<Vec<(String, PathBuf)>, OutputError> {
    let step = sim.steps();
    let parts = [
        particles_polydata(sim),
        connections_polydata(sim),
        pfacets_polydata(sim),
        contacts_polydata(sim),
    ];
    let mut written = Vec::with_capacity(parts.len());
    for (name, data) in PARTS.iter().zip(parts) {
        let file = frame_file_name(name, step);
        let path = directory.join(&file);
        files::write_atomically(&path, data.to_xml().as_bytes())?;
        written.push((file, path));
    }
    Ok(written)
}

/// Writes the frame of `sim`'s current state into `directory` (created if missing): the
/// four `.vtp` files an [`Output`] writes at this step (`particles_N.vtp`,
/// `connections_N.vtp`, `pfacets_N.vtp`, `contacts_N.vtp`), without a `.pvd`. Returns their
/// paths, in that order. For a frame off an output's schedule (a script's).
pub fn write_frame(directory: &Path, sim: &Simulation) -> Result<Vec<PathBuf>, OutputError> {
    files::create_directory(directory)?;
    Ok(write_parts(directory, sim)?.into_iter().map(|(_, path)| path).collect())
}

/// Checks `settings` against `sim`: output periods of at least one step, series to plot when
/// a plot is asked for, valid series. [`Output`] checks this when it opens; a checkpoint's
/// settings are checked with it on resume, output or not (`flexdem-io`).
pub fn check_output_settings(
    settings: &OutputSettings,
    sim: &Simulation,
) -> Result<(), OutputError> {
    for (what, every) in
        [("vtk_every", settings.vtk_every), ("series_every", settings.series_every)]
    {
        if every == Some(0) {
            return Err(OutputError::Setting {
                what: what.into(),
                value: "0".into(),
                expected: "a number of steps of at least 1 (or none)".into(),
            });
        }
    }
    if settings.plot && (settings.series_every.is_none() || settings.series.is_empty()) {
        return Err(OutputError::Setting {
            what: "plot".into(),
            value: "true".into(),
            expected: "series to plot: set series_every and at least one series".into(),
        });
    }
    validate_series(&settings.series, sim)?;
    Ok(())
}

/// Draws `series.png` ([`crate::plot_series`]).
#[cfg(feature = "plot")]
fn draw_plot(path: &Path, series: &[SeriesSpec], rows: &[Vec<Real>]) -> Result<(), OutputError> {
    crate::plot::plot_series(path, series, rows)
}

/// Without the `plot` feature a plot cannot be drawn: an error saying so.
#[cfg(not(feature = "plot"))]
fn draw_plot(path: &Path, _: &[SeriesSpec], _: &[Vec<Real>]) -> Result<(), OutputError> {
    Err(OutputError::Plot {
        path: path.to_path_buf(),
        message: "this build of flexdem-output has no `plot` feature (plotters)".into(),
    })
}

/// The path of the `.pvd` file for `settings`.
pub fn pvd_path(settings: &OutputSettings) -> PathBuf {
    settings.directory.join(PVD_FILE)
}

/// The file name of a frame's part (`particles`, `connections`, `pfacets`, `contacts`).
pub fn frame_file_name(part: &str, step: u64) -> String {
    format!("{part}_{step:06}.vtp")
}
