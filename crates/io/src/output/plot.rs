//! The PNG plot of the CSV series: one panel per series stacked vertically, time on the x
//! axis, one coloured line per column with a legend, numeric tick labels drawn with the
//! built-in pixel font (no font file needed).

use super::files::{replace_with, temporary_path};
use super::font::{text_pixels, text_width, HEIGHT};
use super::series::{series_columns, SeriesSpec};
use super::OutputError;
use flexdem_geom::Real;
use plotters::prelude::*;
use std::path::Path;

/// Width of the image (pixels).
const WIDTH: i32 = 1100;
/// Height of one panel (pixels).
const PANEL_HEIGHT: i32 = 320;
/// Scale of the pixel font (each font pixel is this many image pixels wide).
const TEXT_SCALE: i32 = 2;
/// Margins of a panel's plot area: left (y tick labels), top (title), bottom (x tick labels).
const MARGIN_LEFT: i32 = 130;
const MARGIN_TOP: i32 = 34;
const MARGIN_BOTTOM: i32 = 52;
/// Fraction of the data range added below and above it on the y axis.
const Y_PADDING: Real = 0.05;
/// Number of tick intervals aimed at on each axis.
const TICKS: usize = 5;
/// Line colours, one per column (cycled).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// A linear map from a data interval to a pixel interval.
#[derive(Clone, Copy, Debug)]
struct Axis {
    lo: Real,
    hi: Real,
    pixel_lo: i32,
    pixel_hi: i32,
}

impl Axis {
    /// The pixel of value `v`.
    fn pixel(&self, v: Real) -> i32 {
        let f = (v - self.lo) / (self.hi - self.lo);
        (self.pixel_lo as Real + f * (self.pixel_hi - self.pixel_lo) as Real).round() as i32
    }
}

/// The finite range of `values`, widened when empty or a single value so it has a length.
fn data_range(values: impl Iterator<Item = Real>) -> (Real, Real) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((Real::INFINITY, Real::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return (-1.0, 1.0);
    }
    let width = hi - lo;
    if width > 1e-12 * lo.abs().max(hi.abs()) && width.is_finite() {
        return (lo, hi);
    }
    let pad = if lo.abs() > 0.0 { 0.1 * lo.abs() } else { 1.0 };
    (lo - pad, hi + pad)
}

/// A round tick spacing (1, 2 or 5 × 10^k) giving about 5 intervals over [lo, hi].
pub fn tick_step(lo: Real, hi: Real) -> Real {
    let raw = (hi - lo) / TICKS as Real;
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * magnitude)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * magnitude);
    if step.is_finite() && step > 0.0 {
        step
    } else {
        hi - lo
    }
}

/// The tick values in [lo, hi] at multiples of `step` (at most 2·5 + 3 of them).
pub fn ticks(lo: Real, hi: Real, step: Real) -> Vec<Real> {
    let first = (lo / step).ceil();
    (0..=2 * TICKS + 2)
        .map(|k| (first + k as Real) * step)
        .take_while(|&v| v <= hi + 1e-9 * step)
        .collect()
}

/// A tick label with as many digits as the spacing `step` needs: plain decimals for
/// moderate magnitudes, scientific notation otherwise.
pub fn tick_label(v: Real, step: Real) -> String {
    let v = if v.abs() < 1e-9 * step { 0.0 } else { v };
    let step_exp = step.abs().log10().floor() as i32;
    let big = v.abs().max(step.abs());
    if (1e-3..1e6).contains(&big) {
        format!("{:.*}", (-step_exp).max(0) as usize, v)
    } else {
        let v_exp = if v == 0.0 { step_exp } else { v.abs().log10().floor() as i32 };
        format!("{:.*e}", (v_exp - step_exp).max(0) as usize, v)
    }
}

/// Draws `text` with its top-left corner at `origin` in `color`.
fn draw_text<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    text: &str,
    origin: (i32, i32),
    color: &RGBColor,
) -> Result<(), String> {
    for (x, y) in text_pixels(text, origin, TEXT_SCALE) {
        let square = Rectangle::new([(x, y), (x + TEXT_SCALE, y + TEXT_SCALE)], color.filled());
        area.draw(&square).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Draws the panel of `spec` (columns `first..first + count` of `rows`) with its top at `top`.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    spec: &SeriesSpec,
    first: usize,
    rows: &[Vec<Real>],
    top: i32,
    right: i32,
) -> Result<(), String> {
    let columns = series_columns(spec);
    let left = MARGIN_LEFT;
    let (upper, lower) = (top + MARGIN_TOP, top + PANEL_HEIGHT - MARGIN_BOTTOM);
    let value = |row: &Vec<Real>, k: usize| row.get(k).copied().unwrap_or(Real::NAN);
    let (t0, t1) = data_range(rows.iter().map(|r| value(r, 0)));
    let (y0, y1) = data_range(
        rows.iter().flat_map(|r| (first..first + columns.len()).map(move |k| value(r, k))),
    );
    // a margin so lines at the extremes stay off the frame
    let (y0, y1) = (y0 - Y_PADDING * (y1 - y0), y1 + Y_PADDING * (y1 - y0));
    let x_axis = Axis { lo: t0, hi: t1, pixel_lo: left, pixel_hi: right };
    let y_axis = Axis { lo: y0, hi: y1, pixel_lo: lower, pixel_hi: upper };
    let black = RGBColor(0, 0, 0);
    let grid = RGBColor(225, 225, 225);
    draw_text(area, &spec.name, (left, top + 10), &black)?;
    let text_h = HEIGHT * TEXT_SCALE;
    let x_step = tick_step(t0, t1);
    for t in ticks(t0, t1, x_step) {
        let x = x_axis.pixel(t);
        area.draw(&PathElement::new(vec![(x, upper), (x, lower)], grid))
            .map_err(|e| e.to_string())?;
        let label = tick_label(t, x_step);
        let w = text_width(&label, TEXT_SCALE);
        draw_text(area, &label, (x - w / 2, lower + 8), &black)?;
    }
    draw_text(area, "time (s)", ((left + right) / 2 - 48, lower + 14 + text_h), &black)?;
    let y_step = tick_step(y0, y1);
    for v in ticks(y0, y1, y_step) {
        let y = y_axis.pixel(v);
        area.draw(&PathElement::new(vec![(left, y), (right, y)], grid))
            .map_err(|e| e.to_string())?;
        let label = tick_label(v, y_step);
        let w = text_width(&label, TEXT_SCALE);
        draw_text(area, &label, (left - 8 - w, y - text_h / 2), &black)?;
    }
    area.draw(&Rectangle::new([(left, upper), (right, lower)], black.stroke_width(1)))
        .map_err(|e| e.to_string())?;
    for (c, column) in columns.iter().enumerate() {
        let color = PALETTE[c % PALETTE.len()];
        let mut segment: Vec<(i32, i32)> = Vec::new();
        for row in rows.iter().chain(std::iter::once(&vec![])) {
            let (t, v) = (value(row, 0), value(row, first + c));
            if t.is_finite() && v.is_finite() {
                segment.push((x_axis.pixel(t), y_axis.pixel(v)));
            } else if !segment.is_empty() {
                let points = std::mem::take(&mut segment);
                if points.len() == 1 {
                    let (x, y) = points[0];
                    area.draw(&Rectangle::new([(x - 2, y - 2), (x + 2, y + 2)], color.filled()))
                        .map_err(|e| e.to_string())?;
                }
                area.draw(&PathElement::new(points, color.stroke_width(2)))
                    .map_err(|e| e.to_string())?;
            }
        }
        let y = upper + 6 + c as i32 * (text_h + 8);
        let x = right + 16;
        area.draw(&Rectangle::new([(x, y + 4), (x + 20, y + 9)], color.filled()))
            .map_err(|e| e.to_string())?;
        draw_text(area, &column[spec.name.len() + 1..], (x + 28, y), &black)?;
    }
    Ok(())
}

/// Draws the series `rows` (time, step, then the columns of `series` in order, as recorded by
/// [`crate::output::Output`]) to the PNG `path`, one panel per series. Written to a
/// temporary file first and renamed, like every output file.
pub fn plot_series(
    path: &Path,
    series: &[SeriesSpec],
    rows: &[Vec<Real>],
) -> Result<(), OutputError> {
    let fail = |message: String| OutputError::Plot { path: path.to_path_buf(), message };
    if series.is_empty() {
        return Err(fail("no series to plot".into()));
    }
    let temp = temporary_path(path);
    let height = PANEL_HEIGHT * series.len() as i32;
    let drawn = (|| -> Result<(), String> {
        let root = BitMapBackend::new(&temp, (WIDTH as u32, height as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let legend_width = series
            .iter()
            .flat_map(|spec| {
                series_columns(spec)
                    .into_iter()
                    .map(move |c| text_width(&c[spec.name.len() + 1..], TEXT_SCALE))
            })
            .max()
            .unwrap_or(0);
        let right = WIDTH - legend_width - 60;
        let mut first = 2;
        for (k, spec) in series.iter().enumerate() {
            draw_panel(&root, spec, first, rows, k as i32 * PANEL_HEIGHT, right)?;
            first += series_columns(spec).len();
        }
        root.present().map_err(|e| e.to_string())
    })();
    if let Err(message) = drawn {
        let _ = std::fs::remove_file(&temp);
        return Err(fail(message));
    }
    replace_with(&temp, path)
}
