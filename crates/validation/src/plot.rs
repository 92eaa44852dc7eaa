//! PNG line and point plots of the report, drawn with plotters' bitmap backend and the pixel
//! font of `flexdem-io` (no font file, no system font library).

use crate::ValidationError;
use flexdem_io::output::font::{text_pixels, text_width, HEIGHT as FONT_HEIGHT};
use flexdem_io::output::{tick_label, tick_step, ticks};
use plotters::prelude::*;
use std::path::Path;

/// Width of every plot (pixels).
pub const PLOT_WIDTH: u32 = 900;
/// Height of every plot (pixels).
pub const PLOT_HEIGHT: u32 = 500;
/// Scale of the pixel font (each font pixel is this many image pixels wide).
const TEXT_SCALE: i32 = 2;
/// Fraction of the data range added on each side of both axes.
const PADDING: f64 = 0.04;
/// Dash and gap lengths of [`CurveStyle::Dashed`] (pixels).
const DASH: f64 = 9.0;
const GAP: f64 = 6.0;
/// Curve colours, one per curve (cycled).
const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(127, 127, 127),
    RGBColor(23, 190, 207),
];

/// How a curve is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveStyle {
    /// A solid line through the points in order.
    Line,
    /// A dashed line through the points in order.
    Dashed,
    /// A marker at each point, no line.
    Points,
}

/// One data set of a plot.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Its legend text.
    pub label: String,
    /// Its (x, y) points; non-finite points are skipped (and break a line).
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

/// What a plot shows.
#[derive(Clone, Copy, Debug)]
pub struct PlotSpec<'a> {
    /// Title, drawn above the plot.
    pub title: &'a str,
    /// Label of the x axis, drawn below it.
    pub x_label: &'a str,
    /// Label of the y axis, drawn above it at the left.
    pub y_label: &'a str,
    /// The data, drawn in order (later curves on top).
    pub curves: &'a [Curve],
}

/// A linear map from a data interval to a pixel interval.
#[derive(Clone, Copy, Debug)]
struct Axis {
    lo: f64,
    hi: f64,
    pixel_lo: i32,
    pixel_hi: i32,
}

impl Axis {
    /// The pixel of value `v` (as a real number, for dashes).
    fn pixel(&self, v: f64) -> f64 {
        let f = (v - self.lo) / (self.hi - self.lo);
        self.pixel_lo as f64 + f * (self.pixel_hi - self.pixel_lo) as f64
    }
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

type Area<'b> = DrawingArea<BitMapBackend<'b>, plotters::coord::Shift>;

/// Draws `text` with its top-left corner at `origin`.
fn draw_text(
    area: &Area<'_>,
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

/// The pieces of the polyline `pixels` that are drawn as dashes ([`DASH`] on, [`GAP`] off,
/// the pattern running on across vertices).
fn dashes(pixels: &[(f64, f64)]) -> Vec<Vec<(i32, i32)>> {
    let round = |p: (f64, f64)| (p.0.round() as i32, p.1.round() as i32);
    let mut pieces = Vec::new();
    let mut current: Vec<(i32, i32)> = Vec::new();
    // position within the pattern: [0, DASH) on, [DASH, DASH + GAP) off
    let mut phase = 0.0;
    for w in pixels.windows(2) {
        let (a, b) = (w[0], w[1]);
        let length = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let at = |s: f64| {
            let f = if length > 0.0 { s / length } else { 0.0 };
            (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1))
        };
        let mut s = 0.0;
        while s < length {
            let on = phase < DASH;
            let left = if on { DASH - phase } else { DASH + GAP - phase };
            let step = left.min(length - s);
            if on {
                if current.is_empty() {
                    current.push(round(at(s)));
                }
                current.push(round(at(s + step)));
            }
            s += step;
            phase += step;
            if phase >= DASH && !current.is_empty() {
                pieces.push(std::mem::take(&mut current));
            }
            if phase >= DASH + GAP {
                phase = 0.0;
            }
        }
    }
    if current.len() > 1 {
        pieces.push(current);
    }
    pieces
}

/// Draws one curve in `color`.
fn draw_curve(
    area: &Area<'_>,
    curve: &Curve,
    x: Axis,
    y: Axis,
    color: RGBColor,
) -> Result<(), String> {
    let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for &(px, py) in &curve.points {
        if px.is_finite() && py.is_finite() {
            if let Some(run) = runs.last_mut() {
                run.push((x.pixel(px), y.pixel(py)));
            }
        } else if runs.last().is_some_and(|run| !run.is_empty()) {
            runs.push(Vec::new());
        }
    }
    let round = |p: &(f64, f64)| (p.0.round() as i32, p.1.round() as i32);
    for run in runs.iter().filter(|r| !r.is_empty()) {
        match curve.style {
            CurveStyle::Line => {
                let path: Vec<_> = run.iter().map(round).collect();
                area.draw(&PathElement::new(path, color.stroke_width(2)))
                    .map_err(|e| e.to_string())?;
            }
            CurveStyle::Dashed => {
                for piece in dashes(run) {
                    area.draw(&PathElement::new(piece, color.stroke_width(2)))
                        .map_err(|e| e.to_string())?;
                }
            }
            CurveStyle::Points => {
                for p in run {
                    area.draw(&Circle::new(round(p), 4, color.filled()))
                        .map_err(|e| e.to_string())?;
                }
            }
        }
    }
    Ok(())
}

/// The legend's top-left corner: the corner of the plot area `[left, right] × [top, bottom]`
/// whose `width × height` box covers the fewest data points.
fn legend_corner(
    spec: &PlotSpec<'_>,
    x: Axis,
    y: Axis,
    (left, right, top, bottom): (i32, i32, i32, i32),
    (width, height): (i32, i32),
) -> (i32, i32) {
    let corners = [
        (right - width - 6, top + 6),
        (left + 6, top + 6),
        (right - width - 6, bottom - height - 6),
        (left + 6, bottom - height - 6),
    ];
    let covered = |&(cx, cy): &(i32, i32)| {
        spec.curves
            .iter()
            .flat_map(|c| c.points.iter())
            .filter(|&&(px, py)| {
                let (u, v) = (x.pixel(px), y.pixel(py));
                u >= cx as f64
                    && u <= (cx + width) as f64
                    && v >= cy as f64
                    && v <= (cy + height) as f64
            })
            .count()
    };
    corners.into_iter().min_by_key(covered).unwrap_or(corners[0])
}

/// Draws the plot of `spec` into the BitMap area.
fn draw(area: &Area<'_>, spec: &PlotSpec<'_>) -> Result<(), String> {
    area.fill(&WHITE).map_err(|e| e.to_string())?;
    let black = RGBColor(0, 0, 0);
    let grid = RGBColor(225, 225, 225);
    let text_h = FONT_HEIGHT * TEXT_SCALE;
    let points = || spec.curves.iter().flat_map(|c| c.points.iter());
    let (x0, x1) = padded_range(points().map(|p| p.0));
    let (y0, y1) = padded_range(points().map(|p| p.1));
    let (x_step, y_step) = (tick_step(x0, x1), tick_step(y0, y1));
    let y_ticks: Vec<(f64, String)> =
        ticks(y0, y1, y_step).into_iter().map(|v| (v, tick_label(v, y_step))).collect();
    let label_w = y_ticks.iter().map(|(_, l)| text_width(l, TEXT_SCALE)).max().unwrap_or(0);
    let (width, height) = (PLOT_WIDTH as i32, PLOT_HEIGHT as i32);
    let (left, right) = (label_w + 20, width - 24);
    let (top, bottom) = (2 * text_h + 28, height - 2 * text_h - 30);
    let x = Axis { lo: x0, hi: x1, pixel_lo: left, pixel_hi: right };
    let y = Axis { lo: y0, hi: y1, pixel_lo: bottom, pixel_hi: top };
    let title_w = text_width(spec.title, TEXT_SCALE);
    draw_text(area, spec.title, ((width - title_w) / 2, 8), &black)?;
    draw_text(area, spec.y_label, (left, top - text_h - 8), &black)?;
    for t in ticks(x0, x1, x_step) {
        let px = x.pixel(t).round() as i32;
        area.draw(&PathElement::new(vec![(px, top), (px, bottom)], grid))
            .map_err(|e| e.to_string())?;
        let label = tick_label(t, x_step);
        draw_text(area, &label, (px - text_width(&label, TEXT_SCALE) / 2, bottom + 8), &black)?;
    }
    let x_label_w = text_width(spec.x_label, TEXT_SCALE);
    draw_text(area, spec.x_label, ((left + right - x_label_w) / 2, bottom + text_h + 18), &black)?;
    for (v, label) in &y_ticks {
        let py = y.pixel(*v).round() as i32;
        area.draw(&PathElement::new(vec![(left, py), (right, py)], grid))
            .map_err(|e| e.to_string())?;
        draw_text(
            area,
            label,
            (left - 8 - text_width(label, TEXT_SCALE), py - text_h / 2),
            &black,
        )?;
    }
    area.draw(&Rectangle::new([(left, top), (right, bottom)], black.stroke_width(1)))
        .map_err(|e| e.to_string())?;
    for (k, curve) in spec.curves.iter().enumerate() {
        draw_curve(area, curve, x, y, PALETTE[k % PALETTE.len()])?;
    }
    // legend: a white box with one row per curve
    let labelled: Vec<(usize, &Curve)> =
        spec.curves.iter().enumerate().filter(|(_, c)| !c.label.is_empty()).collect();
    if labelled.is_empty() {
        return Ok(());
    }
    let row_h = text_h + 8;
    let box_w =
        44 + labelled.iter().map(|(_, c)| text_width(&c.label, TEXT_SCALE)).max().unwrap_or(0);
    let box_h = row_h * labelled.len() as i32 + 8;
    let (bx, by) = legend_corner(spec, x, y, (left, right, top, bottom), (box_w, box_h));
    area.draw(&Rectangle::new([(bx, by), (bx + box_w, by + box_h)], WHITE.filled()))
        .map_err(|e| e.to_string())?;
    area.draw(&Rectangle::new([(bx, by), (bx + box_w, by + box_h)], grid.stroke_width(1)))
        .map_err(|e| e.to_string())?;
    for (row, (k, curve)) in labelled.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let cy = by + 6 + row as i32 * row_h + text_h / 2;
        let sample = Curve {
            label: String::new(),
            points: vec![(0.0, 0.0), (1.0, 0.0)],
            style: curve.style,
        };
        let sx = Axis { lo: 0.0, hi: 1.0, pixel_lo: bx + 6, pixel_hi: bx + 32 };
        let sy = Axis { lo: -1.0, hi: 1.0, pixel_lo: cy, pixel_hi: cy };
        if curve.style == CurveStyle::Points {
            area.draw(&Circle::new((bx + 19, cy), 4, color.filled())).map_err(|e| e.to_string())?;
        } else {
            draw_curve(area, &sample, sx, sy, color)?;
        }
        draw_text(area, &curve.label, (bx + 38, cy - text_h / 2), &black)?;
    }
    Ok(())
}

/// Draws the curves of `spec` into the PNG `path` ([`PLOT_WIDTH`] × [`PLOT_HEIGHT`] pixels):
/// axes fitted to the finite data, round ticks, a legend in the emptiest corner. Written to
/// a temporary file `.NAME.tmp.png` next to `path` first and renamed over it.
pub fn plot_xy(path: &Path, spec: &PlotSpec<'_>) -> Result<(), ValidationError> {
    let fail = |message: String| ValidationError::Plot { path: path.to_path_buf(), message };
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let Some(stem) = name.strip_suffix(".png") else {
        return Err(fail("the file name must end in .png".into()));
    };
    let temp = path.with_file_name(format!(".{stem}.tmp.png"));
    let drawn = (|| -> Result<(), String> {
        let area = BitMapBackend::new(&temp, (PLOT_WIDTH, PLOT_HEIGHT)).into_drawing_area();
        draw(&area, spec)?;
        area.present().map_err(|e| e.to_string())
    })();
    if let Err(message) = drawn {
        let _ = std::fs::remove_file(&temp);
        return Err(fail(message));
    }
    std::fs::rename(&temp, path).map_err(|source| {
        let _ = std::fs::remove_file(&temp);
        ValidationError::Io { path: path.to_path_buf(), source }
    })
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

    #[test]
    fn dashes_alternate_on_and_off() {
        let pieces = dashes(&[(0.0, 0.0), (100.0, 0.0)]);
        // 100 px with a 15 px period: 7 dashes (the last one partial)
        assert_eq!(pieces.len(), 7);
        assert_eq!(pieces[0], vec![(0, 0), (9, 0)]);
        assert_eq!(pieces[1][0], (15, 0));
    }
}
