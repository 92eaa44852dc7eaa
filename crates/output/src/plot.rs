//! `series.png`: the CSV series as a [`Figure`] of one chart per series, time on the x axis,
//! one line per column with a legend.

use crate::chart::{Curve, CurveStyle, Figure, LineChart};
use crate::error::OutputError;
use crate::series::{series_columns, Quantity, SeriesSpec};
use flexdem_geom::Real;
use std::path::Path;

/// Width of the image (pixels).
const WIDTH: u32 = 1100;
/// Height of one series' chart (pixels).
const CHART_HEIGHT: u32 = 320;

/// The y-axis description of a series: what its quantity is, and its unit.
fn quantity_label(quantity: &Quantity) -> &'static str {
    match quantity {
        Quantity::Position(_) => "position (m)",
        Quantity::Velocity(_) => "velocity (m/s)",
        Quantity::AngularVelocity(_) => "angular velocity (rad/s)",
        Quantity::Energy => "energy (J)",
        Quantity::ForceOnParticles(_) => "force (N)",
        Quantity::ContactCount => "contacts",
        Quantity::BrokenLinks => "broken links",
        Quantity::WallForce(_) => "force (N)",
        Quantity::WallStress { .. } | Quantity::Stress { .. } => "stress (Pa)",
        Quantity::SolidFraction(_) => "solid fraction",
        Quantity::EnclosedVolume { .. } => "volume (m³)",
    }
}

/// The chart of `spec`, whose columns are `first..` in `rows`.
fn series_chart(spec: &SeriesSpec, first: usize, rows: &[Vec<Real>]) -> LineChart {
    let value = |row: &Vec<Real>, k: usize| row.get(k).copied().unwrap_or(Real::NAN);
    let mut chart = LineChart::new(&spec.name, "time (s)", quantity_label(&spec.quantity));
    for (c, column) in series_columns(spec).iter().enumerate() {
        let points = rows.iter().map(|row| (value(row, 0), value(row, first + c))).collect();
        let label = column.get(spec.name.len() + 1..).unwrap_or(column);
        chart.curves.push(Curve::new(label, points, CurveStyle::Line));
    }
    chart
}

/// Draws the series `rows` (time, step, then the columns of `series` in order, as recorded by
/// [`crate::Output`]) to the PNG `path`, one chart per series. Written to a temporary file
/// first and renamed, like every output file.
pub fn plot_series(
    path: &Path,
    series: &[SeriesSpec],
    rows: &[Vec<Real>],
) -> Result<(), OutputError> {
    if series.is_empty() {
        return Err(OutputError::Plot {
            path: path.to_path_buf(),
            message: "no series to plot".into(),
        });
    }
    let mut figure = Figure::new(WIDTH, CHART_HEIGHT);
    let mut first = 2;
    for spec in series {
        figure.charts.push(series_chart(spec, first, rows));
        first += series_columns(spec).len();
    }
    figure
        .save_png(path)
        .map_err(|e| OutputError::Plot { path: path.to_path_buf(), message: e.message })
}
