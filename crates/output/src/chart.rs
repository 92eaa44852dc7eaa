//! PNG line charts drawn with plotters' chart layer (`ChartBuilder`, its mesh, `LineSeries`,
//! `DashedLineSeries`, series labels), the text set in DejaVu Sans embedded in this crate and
//! rendered by plotters' `ab_glyph` backend: no system font library, and any character of the
//! font prints (`−`, `³`, `×`, `μ`, `θ`, ...).
//!
//! The charts of this crate (`series.png`, see [`crate::plot_series`]) and the validation
//! report's figures both use it:
//!
//! ```no_run
//! use flexdem_output::chart::{Curve, CurveStyle, Figure, LineChart};
//!
//! let sine: Vec<(f64, f64)> = (0..100).map(|k| (k as f64 * 0.1, (k as f64 * 0.1).sin())).collect();
//! let chart = LineChart::new("sin x", "x (rad)", "y (m³)")
//!     .with_curve(Curve::new("sin x", sine.clone(), CurveStyle::Line))
//!     .with_curve(Curve::new("reference", sine, CurveStyle::Dashed));
//! Figure::new(900, 500).with_chart(chart).save_png("sine.png".as_ref())?;
//! # Ok::<(), flexdem_output::chart::ChartError>(())
//! ```

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// DejaVu Sans (Bitstream Vera license, `fonts/LICENSE`), the font of every chart.
static FONT_BYTES: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");

/// The family name the font is registered under in plotters: its default family, so that any
/// text plotters draws with its defaults uses it too.
const FONT_FAMILY: &str = "sans-serif";

/// Text sizes (pixels): chart titles, axis descriptions, tick labels and legends.
const TITLE_SIZE: u32 = 22;
const LABEL_SIZE: u32 = 17;
const TICK_SIZE: u32 = 15;

/// Fraction of the data range added on each side of both axes.
const PADDING: f64 = 0.04;
/// Dash and gap lengths of [`CurveStyle::Dashed`] (pixels).
const DASH: u32 = 9;
const GAP: u32 = 6;
/// Tick labels aimed at on each axis.
const X_LABELS: usize = 8;
const Y_LABELS: usize = 7;

/// Curve colours, one per curve of a chart (cycled).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Why a chart could not be drawn or written.
#[derive(Debug, thiserror::Error)]
#[error("cannot draw the chart {}: {message}", path.display())]
pub struct ChartError {
    /// The PNG file.
    pub path: PathBuf,
    /// What went wrong.
    pub message: String,
}

/// How a curve is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveStyle {
    /// A solid line through the points in order.
    Line,
    /// A dashed line through the points in order (reference curves).
    Dashed,
    /// A marker at each point, no line.
    Points,
}

/// One data set of a chart.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Its legend text (empty: not in the legend).
    pub label: String,
    /// Its (x, y) points; non-finite points are skipped and break a line.
    pub points: Vec<(f64, f64)>,
    /// How it is drawn.
    pub style: CurveStyle,
}

impl Curve {
    /// A curve `label` of `points` drawn in `style`.
    pub fn new(label: &str, points: Vec<(f64, f64)>, style: CurveStyle) -> Curve {
        Curve { label: label.into(), points, style }
    }
}

/// One chart: a title, two linear axes fitted to the finite data, and curves with a legend
/// in the corner that covers the fewest points.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LineChart {
    /// Title, above the chart.
    pub title: String,
    /// Description of the x axis (quantity and unit), below it.
    pub x_label: String,
    /// Description of the y axis (quantity and unit), along it.
    pub y_label: String,
    /// The data, drawn in order (later curves on top).
    pub curves: Vec<Curve>,
}

impl LineChart {
    /// An empty chart with its title and axis descriptions.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> LineChart {
        LineChart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            curves: Vec::new(),
        }
    }

    /// The chart with `curve` added on top of the others.
    pub fn with_curve(mut self, curve: Curve) -> LineChart {
        self.curves.push(curve);
        self
    }
}

/// A PNG image of charts stacked vertically, each `width × chart_height` pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// Width of the image (pixels).
    pub width: u32,
    /// Height of each chart (pixels); the image is as high as all of them.
    pub chart_height: u32,
    /// The charts, top to bottom.
    pub charts: Vec<LineChart>,
}

impl Figure {
    /// An empty figure whose charts are `width × chart_height` pixels each.
    pub fn new(width: u32, chart_height: u32) -> Figure {
        Figure { width, chart_height, charts: Vec::new() }
    }

    /// The figure with `chart` added below the others.
    pub fn with_chart(mut self, chart: LineChart) -> Figure {
        self.charts.push(chart);
        self
    }

    /// Height of the whole image (pixels).
    pub fn height(&self) -> u32 {
        self.chart_height.saturating_mul(self.charts.len().max(1) as u32)
    }

    /// Draws the figure into the PNG file `path` (whose name must end in `.png`). It is
    /// written to a temporary file `.NAME.tmp.png` next to `path` first and renamed over it,
    /// so a failure leaves any earlier file intact.
    pub fn save_png(&self, path: &Path) -> Result<(), ChartError> {
        let fail = |message: String| ChartError { path: path.to_path_buf(), message };
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if !name.ends_with(".png") {
            return Err(fail("the file name must end in .png".into()));
        }
        if self.width == 0 || self.chart_height == 0 {
            return Err(fail(format!("an image of {} × {} pixels", self.width, self.height())));
        }
        register_font().map_err(fail)?;
        let temp = crate::files::temporary_path(path);
        let drawn = (|| -> Result<(), String> {
            let root = BitMapBackend::new(&temp, (self.width, self.height())).into_drawing_area();
            root.fill(&WHITE).map_err(|e| e.to_string())?;
            let areas = root.split_evenly((self.charts.len().max(1), 1));
            for (area, chart) in areas.iter().zip(&self.charts) {
                draw_chart(area, chart)?;
            }
            root.present().map_err(|e| e.to_string())
        })();
        if let Err(message) = drawn {
            let _ = std::fs::remove_file(&temp);
            return Err(fail(message));
        }
        std::fs::rename(&temp, path).map_err(|e| {
            let _ = std::fs::remove_file(&temp);
            fail(e.to_string())
        })
    }
}

/// Registers the embedded font with plotters, once per process.
fn register_font() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, FONT_BYTES)
                .map_err(|_| "the embedded font DejaVuSans.ttf cannot be read".to_string())
        })
        .clone()
}

/// The finite range of `values` widened by [`PADDING`] on each side, and given a length when
/// empty or a single value.
fn padded_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return (-1.0, 1.0);
    }
    let width = hi - lo;
    if !(width > 1e-12 * lo.abs().max(hi.abs())) || !width.is_finite() {
        let pad = if lo.abs() > 0.0 { 0.1 * lo.abs() } else { 1.0 };
        return (lo - pad, hi + pad);
    }
    (lo - PADDING * width, hi + PADDING * width)
}

/// Superscript digits and minus sign, for the powers of ten of tick labels.
fn superscript(exponent: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits = exponent.unsigned_abs().to_string();
    let mut s = String::new();
    if exponent < 0 {
        s.push('⁻');
    }
    s.extend(digits.bytes().map(|b| DIGITS[(b - b'0') as usize]));
    s
}

/// The text of a tick at `v` on an axis spanning `span` with about `labels` ticks: as few
/// digits as tell the ticks apart, a true minus sign, and `m×10ⁿ` for very large or small
/// magnitudes.
fn tick_text(v: f64, span: f64, labels: usize) -> String {
    let finest = (span / labels as f64).abs();
    let v = if v.abs() < 1e-9 * span.abs() { 0.0 } else { v };
    let step_exp =
        if finest > 0.0 && finest.is_finite() { finest.log10().floor() as i32 } else { 0 };
    let trim = |s: String| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    let big = v.abs().max(finest);
    let text = if (1e-3..1e5).contains(&big) {
        trim(format!("{:.*}", (-step_exp).max(0) as usize, v))
    } else if v == 0.0 {
        "0".to_string()
    } else {
        let exp = v.abs().log10().floor() as i32;
        let mantissa = v / 10f64.powi(exp);
        let mantissa = trim(format!("{:.*}", (exp - step_exp).max(0) as usize, mantissa));
        format!("{mantissa}×10{}", superscript(exp))
    };
    text.replace('-', "−")
}

/// The legend position: the corner of the chart whose quarter (a box over 40 % of the
/// width and height) holds the fewest of `chart`'s points.
fn legend_position(chart: &LineChart, x: (f64, f64), y: (f64, f64)) -> SeriesLabelPosition {
    let corners = [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
        (SeriesLabelPosition::LowerLeft, false, false),
    ];
    let covered = |&(_, right, upper): &(SeriesLabelPosition, bool, bool)| {
        chart
            .curves
            .iter()
            .flat_map(|c| c.points.iter())
            .filter(|&&(px, py)| {
                let u = (px - x.0) / (x.1 - x.0);
                let v = (py - y.0) / (y.1 - y.0);
                let in_x = if right { u >= 0.6 } else { u <= 0.4 };
                let in_y = if upper { v >= 0.6 } else { v <= 0.4 };
                in_x && in_y
            })
            .count()
    };
    corners.into_iter().min_by_key(covered).map_or(SeriesLabelPosition::UpperRight, |c| c.0)
}

/// The finite stretches of `points` (a non-finite point ends one).
fn finite_runs(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for &(x, y) in points {
        if x.is_finite() && y.is_finite() {
            if let Some(run) = runs.last_mut() {
                run.push((x, y));
            }
        } else if runs.last().is_some_and(|run| !run.is_empty()) {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// Draws `chart` into `area` with plotters' chart layer.
fn draw_chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &LineChart,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let points = || chart.curves.iter().flat_map(|c| c.points.iter());
    let x = padded_range(points().map(|p| p.0));
    let y = padded_range(points().map(|p| p.1));
    let mut builder = ChartBuilder::on(area);
    builder.margin(12).margin_right(24).x_label_area_size(52).y_label_area_size(96);
    if !chart.title.is_empty() {
        builder.caption(&chart.title, (FONT_FAMILY, TITLE_SIZE));
    }
    let mut cc = builder.build_cartesian_2d(x.0..x.1, y.0..y.1).map_err(err)?;
    let (x_span, y_span) = (x.1 - x.0, y.1 - y.0);
    let x_text = |v: &f64| tick_text(*v, x_span, X_LABELS);
    let y_text = |v: &f64| tick_text(*v, y_span, Y_LABELS);
    cc.configure_mesh()
        .x_labels(X_LABELS)
        .y_labels(Y_LABELS)
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .x_label_formatter(&x_text)
        .y_label_formatter(&y_text)
        .label_style((FONT_FAMILY, TICK_SIZE))
        .axis_desc_style((FONT_FAMILY, LABEL_SIZE))
        .light_line_style(RGBColor(240, 240, 240))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(err)?;
    let mut labelled = false;
    for (k, curve) in chart.curves.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let style = ShapeStyle::from(color).stroke_width(2);
        for (r, run) in finite_runs(&curve.points).into_iter().enumerate() {
            let drawn = match curve.style {
                CurveStyle::Line => cc.draw_series(LineSeries::new(run, style)),
                CurveStyle::Dashed => cc.draw_series(DashedLineSeries::new(run, DASH, GAP, style)),
                CurveStyle::Points => {
                    cc.draw_series(run.into_iter().map(|p| Circle::new(p, 4, color.filled())))
                }
            }
            .map_err(err)?;
            if r == 0 && !curve.label.is_empty() {
                labelled = true;
                let anno = drawn.label(curve.label.as_str());
                match curve.style {
                    CurveStyle::Line => {
                        anno.legend(move |(lx, ly)| {
                            PathElement::new(vec![(lx, ly), (lx + 20, ly)], style)
                        });
                    }
                    CurveStyle::Dashed => {
                        anno.legend(move |(lx, ly)| {
                            DashedPathElement::new(vec![(lx, ly), (lx + 22, ly)], 6, 4, style)
                        });
                    }
                    CurveStyle::Points => {
                        anno.legend(move |(lx, ly)| Circle::new((lx + 10, ly), 4, color.filled()));
                    }
                }
            }
        }
    }
    if labelled {
        cc.configure_series_labels()
            .position(legend_position(chart, x, y))
            .label_font((FONT_FAMILY, TICK_SIZE))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(200, 200, 200))
            .draw()
            .map_err(err)?;
    }
    Ok(())
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
    fn a_figure_is_a_png_of_the_requested_size() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sine.png");
        let line: Vec<_> = (0..100).map(|k| (k as f64 * 0.1, (k as f64 * 0.1).sin())).collect();
        let points: Vec<_> = line.iter().step_by(10).map(|&(x, y)| (x, 0.9 * y)).collect();
        let chart = LineChart::new("μ × θ³ − 1", "x (m)", "y (kg/m³)")
            .with_curve(Curve::new("sin x", line.clone(), CurveStyle::Line))
            .with_curve(Curve::new("0.9 sin x", points, CurveStyle::Points))
            .with_curve(Curve::new(
                "shifted",
                line.iter().map(|&(x, y)| (x, y + 0.2)).collect(),
                CurveStyle::Dashed,
            ));
        let figure = Figure::new(900, 500).with_chart(chart.clone()).with_chart(chart);
        figure.save_png(&path).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(png_size(&bytes), (900, 1000));
        assert!(!dir.path().join(".sine.tmp.png").exists(), "the temporary file is left");
    }

    #[test]
    fn empty_and_degenerate_data_still_draw() {
        let dir = tempfile::tempdir().unwrap();
        let one = LineChart::new("", "", "").with_curve(Curve::new(
            "one",
            vec![(1.0, 2.0), (f64::NAN, 3.0)],
            CurveStyle::Line,
        ));
        Figure::new(400, 300).with_chart(one).save_png(&dir.path().join("one.png")).unwrap();
        let none = LineChart::new("none", "", "");
        Figure::new(400, 300).with_chart(none).save_png(&dir.path().join("none.png")).unwrap();
        Figure::new(400, 300).save_png(&dir.path().join("empty.png")).unwrap();
    }

    #[test]
    fn a_bad_file_name_or_folder_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let figure = Figure::new(400, 300).with_chart(LineChart::new("", "", ""));
        let err = figure.save_png(&dir.path().join("plot.txt")).unwrap_err();
        assert!(err.to_string().contains("plot.txt"), "{err}");
        let err = figure.save_png(&dir.path().join("missing/plot.png")).unwrap_err();
        assert!(err.to_string().contains("missing"), "{err}");
    }

    #[test]
    fn tick_texts_are_short_and_use_true_minus_signs() {
        assert_eq!(tick_text(0.5, 1.0, 5), "0.5");
        assert_eq!(tick_text(-0.4, 2.0, 5), "−0.4");
        assert_eq!(tick_text(2.0, 10.0, 5), "2");
        assert_eq!(tick_text(1e-17, 1.0, 5), "0");
        assert_eq!(tick_text(4e-6, 1e-5, 5), "4×10⁻⁶");
        assert_eq!(tick_text(1.5e-6, 4e-6, 8), "1.5×10⁻⁶");
        assert_eq!(tick_text(3e7, 1e8, 5), "3×10⁷");
    }
}
