//! The tracked series of a run (the scene's `[[output.series]]`, what the command line
//! writes to `series.csv`), recorded in memory whether or not the output is written, at the
//! same steps as the CSV rows: at the start, every `series_every` steps, and at the end
//! ([`SeriesRecorder::finish`]).

use crate::arrays::column;
use flexdem_geom::Real;
use flexdem_integrate::Simulation;
use flexdem_output::{header_columns, row_values, CsvSeries, OutputError, SeriesSpec, CSV_FILE};
use flexdem_run::{RunLength, RunObserver};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::Path;

/// Records the rows of the series as a run steps (a [`RunObserver`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct SeriesRecorder {
    /// The series, in the CSV's order.
    specs: Vec<SeriesSpec>,
    /// Steps between rows (None: nothing is recorded, as the CSV has no rows then).
    every: Option<u64>,
    /// The rows so far: time, step, then the series' columns.
    rows: Vec<Vec<Real>>,
}

impl SeriesRecorder {
    /// A recorder of `specs` every `every` steps.
    pub(crate) fn new(specs: Vec<SeriesSpec>, every: Option<u64>) -> SeriesRecorder {
        SeriesRecorder { specs, every, rows: Vec::new() }
    }

    /// Starts with the first `rows` rows of `folder/series.csv` (the checkpoint's: the ones a
    /// resumed output keeps), when that file has this recorder's header; otherwise with none.
    pub(crate) fn continue_csv(&mut self, folder: &Path, rows: u64) {
        let columns = header_columns(&self.specs);
        let Ok(text) = std::fs::read_to_string(folder.join(CSV_FILE)) else { return };
        let mut lines = text.lines();
        if lines.next() != Some(columns.join(",").as_str()) {
            return;
        }
        self.rows = lines
            .map_while(|line| {
                line.split(',').map(|v| v.parse::<Real>().ok()).collect::<Option<Vec<_>>>()
            })
            .take_while(|row| row.len() == columns.len())
            .take(usize::try_from(rows).unwrap_or(usize::MAX))
            .collect();
    }

    /// The column names: `time_s`, `step`, then those of each series (as in the CSV).
    pub(crate) fn columns(&self) -> Vec<String> {
        header_columns(&self.specs)
    }

    /// Records the current state if a row is due at this step and not recorded yet.
    fn record_if_due(&mut self, sim: &Simulation) {
        let step = sim.steps();
        if self.every.is_some_and(|n| step % n == 0) {
            self.record(sim);
        }
    }

    /// Records the current state unless this step has its row already.
    fn record(&mut self, sim: &Simulation) {
        let step = sim.steps() as Real;
        if self.rows.last().is_none_or(|row| row[1] != step) {
            self.rows.push(row_values(&self.specs, sim));
        }
    }

    /// The end of a run: the last row if it is not recorded yet (as the CSV's).
    pub(crate) fn finish(&mut self, sim: &Simulation) {
        if self.every.is_some() {
            self.record(sim);
        }
    }

    /// The rows as a dict of numpy arrays, one per column: `time_s` (s), `step` (integers),
    /// then the series' columns (float64).
    pub(crate) fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (i, name) in self.columns().iter().enumerate() {
            if i == 1 {
                let steps: Vec<i64> = self.rows.iter().map(|r| r[1] as i64).collect();
                d.set_item(name, column(py, steps))?;
            } else {
                d.set_item(name, column(py, self.rows.iter().map(|r| r[i]).collect::<Vec<_>>()))?;
            }
        }
        Ok(d)
    }

    /// Writes the rows as the command line's `series.csv` to `path`.
    pub(crate) fn write_csv(&self, path: &Path) -> Result<(), OutputError> {
        let mut csv = CsvSeries::create(path, &self.columns())?;
        for row in &self.rows {
            csv.append(row)?;
        }
        csv.flush()
    }
}

impl RunObserver for SeriesRecorder {
    fn started(&mut self, sim: &Simulation, _target: RunLength) {
        self.record_if_due(sim);
    }

    fn stepped(&mut self, sim: &Simulation) {
        self.record_if_due(sim);
    }
}
