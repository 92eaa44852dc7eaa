//! The report's figures: one [`LineChart`] per PNG, drawn by `flexdem-output`'s chart layer
//! (plotters, with the embedded DejaVu Sans font), as the series plots of a run are.

use crate::error::ValidationError;
pub use flexdem_output::chart::{Curve, CurveStyle};
use flexdem_output::chart::{Figure, LineChart};
use std::path::Path;

/// Width of every plot (pixels).
pub const PLOT_WIDTH: u32 = 900;
/// Height of every plot (pixels).
pub const PLOT_HEIGHT: u32 = 500;

/// What a plot shows.
#[derive(Clone, Copy, Debug)]
pub struct PlotSpec<'a> {
    /// Title, drawn above the plot.
    pub title: &'a str,
    /// Label of the x axis, drawn below it.
    pub x_label: &'a str,
    /// Label of the y axis, drawn along it.
    pub y_label: &'a str,
    /// The data, drawn in order (later curves on top).
    pub curves: &'a [Curve],
}

/// Draws the curves of `spec` into the PNG `path` ([`PLOT_WIDTH`] × [`PLOT_HEIGHT`] pixels):
/// axes fitted to the finite data, round ticks, a legend in the emptiest corner. Written to
/// a temporary file `.NAME.tmp.png` next to `path` first and renamed over it.
pub fn plot_xy(path: &Path, spec: &PlotSpec<'_>) -> Result<(), ValidationError> {
    let chart = LineChart {
        title: spec.title.into(),
        x_label: spec.x_label.into(),
        y_label: spec.y_label.into(),
        curves: spec.curves.to_vec(),
    };
    Figure::new(PLOT_WIDTH, PLOT_HEIGHT)
        .with_chart(chart)
        .save_png(path)
        .map_err(|e| ValidationError::Plot { path: e.path, message: e.message })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Width and height from a PNG's IHDR chunk, after checking the signature.
    fn png_size(bytes: &[u8]) -> (u32, u32) {
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
        assert_eq!(&bytes[12..16], b"IHDR");
        let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
        (be(&bytes[16..20]), be(&bytes[20..24]))
    }

    #[test]
    fn plot_xy_writes_a_png_of_the_requested_size() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sine.png");
        let line: Vec<_> = (0..100).map(|k| (k as f64 * 0.1, (k as f64 * 0.1).sin())).collect();
        let points: Vec<_> = line.iter().step_by(10).map(|&(x, y)| (x, 0.9 * y)).collect();
        let curves = [
            Curve::new("sin x", line.clone(), CurveStyle::Line),
            Curve::new("0.9 sin x", points, CurveStyle::Points),
            Curve::new(
                "shifted",
                line.iter().map(|&(x, y)| (x, y + 0.2)).collect(),
                CurveStyle::Dashed,
            ),
        ];
        let spec =
            PlotSpec { title: "a test", x_label: "x (m)", y_label: "y (N)", curves: &curves };
        plot_xy(&path, &spec).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(png_size(&bytes), (PLOT_WIDTH, PLOT_HEIGHT));
        assert!(!dir.path().join(".sine.tmp.png").exists(), "the temporary file is left");
    }

    #[test]
    fn empty_and_degenerate_data_still_plot() {
        let dir = tempfile::tempdir().unwrap();
        let curves = [Curve::new("one", vec![(1.0, 2.0), (f64::NAN, 3.0)], CurveStyle::Line)];
        let spec = PlotSpec { title: "", x_label: "", y_label: "", curves: &curves };
        plot_xy(&dir.path().join("one.png"), &spec).unwrap();
        let spec = PlotSpec { title: "none", x_label: "", y_label: "", curves: &[] };
        plot_xy(&dir.path().join("none.png"), &spec).unwrap();
    }

    #[test]
    fn a_bad_file_name_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let spec = PlotSpec { title: "", x_label: "", y_label: "", curves: &[] };
        let err = plot_xy(&dir.path().join("plot.txt"), &spec).unwrap_err();
        assert!(err.to_string().contains("plot.txt"), "{err}");
        let err = plot_xy(&dir.path().join("missing/plot.png"), &spec).unwrap_err();
        assert!(err.to_string().contains("missing"), "{err}");
    }
}
