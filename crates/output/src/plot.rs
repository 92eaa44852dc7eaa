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
        Quantity::Triaxial(_) => "",
    }
}

/// The two charts of a triaxial series whose columns are `first..` in `rows` (in the order of
/// [`crate::triaxial::TRIAXIAL_COLUMNS`]): the stress ratio q/p and the volumetric strain,
/// both against the axial strain (the curves of a drained triaxial test).
fn triaxial_charts(name: &str, first: usize, rows: &[Vec<Real>]) -> [LineChart; 2] {
    let value = |row: &Vec<Real>, k: usize| row.get(first + k).copied().unwrap_or(Real::NAN);
    // columns: 0 axial strain, 1 volumetric strain, 4 mean stress, 5 deviator stress
    let ratio = rows
        .iter()
        .map(|r| (value(r, 0), if value(r, 4) != 0.0 { value(r, 5) / value(r, 4) } else { 0.0 }))
        .collect();
    let volumetric = rows.iter().map(|r| (value(r, 0), value(r, 1))).collect();
    [
        LineChart::new(&format!("{name}: stress ratio"), "axial strain", "q/p")
            .with_curve(Curve::new("q/p", ratio, CurveStyle::Line)),
        LineChart::new(&format!("{name}: volumetric strain"), "axial strain", "volumetric strain")
            .with_curve(Curve::new(
                "volumetric strain (contraction > 0)",
                volumetric,
                CurveStyle::Line,
            )),
    ]
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
        if matches!(spec.quantity, Quantity::Triaxial(_)) {
            figure.charts.extend(triaxial_charts(&spec.name, first, rows));
        } else {
            figure.charts.push(series_chart(spec, first, rows));
        }
        first += series_columns(spec).len();
    }
    figure
        .save_png(path)
        .map_err(|e| OutputError::Plot { path: path.to_path_buf(), message: e.message })
}
