//! Line and scatter figures (SVG and PNG) for clr results.
//!
//! A [`Figure`] is a title, two axis labels and a list of [`Series`]; [`Figure::save`] writes
//! `<stem>.svg` and `<stem>.png`. The DejaVu Sans font is embedded (see
//! `assets/DejaVuSans.LICENSE`), so figures render on machines without fontconfig or FreeType.
//! Tick labels use a decimal point and, for large or small values, engineering notation with one
//! exponent per axis (see [`format_ticks`]).
//!
//! ```no_run
//! use clr_plot::Figure;
//! let pts: Vec<(f64, f64)> = (0..100).map(|i| (i as f64 * 0.01, (i as f64 * 0.1).sin())).collect();
//! Figure::new("Journal orbit")
//!     .x_label("time (s)")
//!     .y_label("displacement (m)")
//!     .line("x", pts)
//!     .save("target/figures/orbit")
//!     .unwrap();
//! ```

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

// Text sizes in pixels. Keep them EVEN. plotters 0.3.7 rasterises each glyph of the embedded
// font (its `ab_glyph` text path, used by the PNG backend; the SVG backend writes <text> and the
// viewer's font draws it) at row `(size / 2 + glyph_top) as i32 + row_in_glyph`, `glyph_top`
// being a whole number of pixels. With an odd size the sum ends in .5 and `as i32` truncates
// toward zero: glyphs reaching above mid-height (digits, letters: negative sum) move half a
// pixel down the screen, glyphs wholly below it ("." "," "_": positive sum) half a pixel up. The
// decimal point thus sat one pixel above the digits' baseline and "0.02" read as "0·02" at the
// former 13 px (labels and legend alike). With an even size the sum is whole and every glyph
// sits on one baseline (test `even_text_sizes_keep_the_point_on_the_baseline`).
/// Title text size (px).
const TITLE_PX: u32 = 20;
/// Tick labels, axis descriptions and legend text size (px).
const TEXT_PX: u32 = 14;
/// Most tick labels per axis (plotters' own default, made explicit because the label format is
/// derived from the very ticks plotters will draw).
const MAX_TICKS: usize = 11;

/// Errors raised while drawing or writing a figure.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The figure has no finite data point to draw.
    #[error("figure `{0}` has no finite data point: give at least one series with finite values")]
    NoData(String),
    /// Creating the output directory failed.
    #[error("cannot create directory {path}: {source}")]
    Io {
        /// Directory that could not be created.
        path: PathBuf,
        /// Underlying I/O error.
        source: std::io::Error,
    },
    /// The plotting backend failed (file not writable, encoder error).
    #[error("drawing {path} failed: {message}")]
    Backend {
        /// Output file.
        path: PathBuf,
        /// Backend message.
        message: String,
    },
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Straight segments between consecutive points.
    Line,
    /// A small circle at each point.
    Points,
    /// Segments plus circles.
    LinePoints,
}

/// One named set of (x, y) points.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry.
    pub label: String,
    /// Data, in the units of the figure's axes. Non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
}

/// A 2-D figure with any number of series, written as SVG and PNG.
#[derive(Debug, Clone)]
pub struct Figure {
    title: String,
    x_label: String,
    y_label: String,
    series: Vec<Series>,
    size: (u32, u32),
    log_x: bool,
    log_y: bool,
    equal_aspect: bool,
}

/// A series after axis transforms: label, finite points, style.
type Prepared = (String, Vec<(f64, f64)>, Style);
/// An axis range (min, max).
type Range = (f64, f64);

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

impl Figure {
    /// A new empty figure, 800 × 560 pixels.
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            x_label: String::new(),
            y_label: String::new(),
            series: Vec::new(),
            size: (800, 560),
            log_x: false,
            log_y: false,
            equal_aspect: false,
        }
    }

    /// Label of the horizontal axis (include the unit, e.g. `"time (s)"`).
    pub fn x_label(mut self, label: impl Into<String>) -> Self {
        self.x_label = label.into();
        self
    }

    /// Label of the vertical axis (include the unit).
    pub fn y_label(mut self, label: impl Into<String>) -> Self {
        self.y_label = label.into();
        self
    }

    /// Size in pixels (PNG) or user units (SVG).
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    /// Plot log10 of x (non-positive x are skipped); the axis label says so.
    pub fn log_x(mut self) -> Self {
        self.log_x = true;
        self
    }

    /// Plot log10 of y (non-positive y are skipped); the axis label says so.
    pub fn log_y(mut self) -> Self {
        self.log_y = true;
        self
    }

    /// Same scale on both axes (orbits inside a clearance circle, mode shapes).
    pub fn equal_aspect(mut self) -> Self {
        self.equal_aspect = true;
        self
    }

    /// Add a series drawn as a line.
    pub fn line(self, label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self.series(label, points, Style::Line)
    }

    /// Add a series drawn as markers.
    pub fn points(self, label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self.series(label, points, Style::Points)
    }

    /// Add a series with an explicit style.
    pub fn series(
        mut self,
        label: impl Into<String>,
        points: Vec<(f64, f64)>,
        style: Style,
    ) -> Self {
        self.series.push(Series {
            label: label.into(),
            points,
            style,
        });
        self
    }

    fn transformed(&self) -> Vec<Prepared> {
        self.series
            .iter()
            .map(|s| {
                let pts = s
                    .points
                    .iter()
                    .filter(|(x, y)| (!self.log_x || *x > 0.0) && (!self.log_y || *y > 0.0))
                    .map(|&(x, y)| {
                        (
                            if self.log_x { x.log10() } else { x },
                            if self.log_y { y.log10() } else { y },
                        )
                    })
                    .filter(|(x, y)| x.is_finite() && y.is_finite())
                    .collect();
                (s.label.clone(), pts, s.style)
            })
            .collect()
    }

    fn ranges(&self, data: &[Prepared]) -> Option<(Range, Range)> {
        let mut xr = (f64::INFINITY, f64::NEG_INFINITY);
        let mut yr = (f64::INFINITY, f64::NEG_INFINITY);
        for (_, pts, _) in data {
            for &(x, y) in pts {
                xr = (xr.0.min(x), xr.1.max(x));
                yr = (yr.0.min(y), yr.1.max(y));
            }
        }
        if !xr.0.is_finite() {
            return None;
        }
        let pad = |r: (f64, f64)| {
            let span = r.1 - r.0;
            let m = if span > 0.0 {
                0.05 * span
            } else {
                0.5 * r.0.abs().max(1e-12)
            };
            (r.0 - m, r.1 + m)
        };
        let (mut xr, mut yr) = (pad(xr), pad(yr));
        if self.equal_aspect {
            let (w, h) = (self.size.0 as f64, self.size.1 as f64);
            let per_px = ((xr.1 - xr.0) / w).max((yr.1 - yr.0) / h);
            let (cx, cy) = (0.5 * (xr.0 + xr.1), 0.5 * (yr.0 + yr.1));
            xr = (cx - 0.5 * per_px * w, cx + 0.5 * per_px * w);
            yr = (cy - 0.5 * per_px * h, cy + 0.5 * per_px * h);
        }
        Some((xr, yr))
    }

    fn axis_label(label: &str, log: bool) -> String {
        if log {
            format!("log10 {label}")
        } else {
            label.to_string()
        }
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: DrawingArea<DB, Shift>,
        data: &[Prepared],
        xr: Range,
        yr: Range,
    ) -> Result<(), String> {
        let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
        root.fill(&WHITE).map_err(e)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", TITLE_PX))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .map_err(e)?;
        let x_format = TickFormat::for_ticks(&axis_ticks(xr));
        let y_format = TickFormat::for_ticks(&axis_ticks(yr));
        let x_label = |v: &f64| x_format.format(*v);
        let y_label = |v: &f64| y_format.format(*v);
        chart
            .configure_mesh()
            .x_desc(Self::axis_label(&self.x_label, self.log_x))
            .y_desc(Self::axis_label(&self.y_label, self.log_y))
            .x_labels(MAX_TICKS)
            .y_labels(MAX_TICKS)
            .x_label_formatter(&x_label)
            .y_label_formatter(&y_label)
            .label_style(("sans-serif", TEXT_PX))
            .draw()
            .map_err(e)?;
        for (i, (label, pts, style)) in data.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            if matches!(style, Style::Line | Style::LinePoints) {
                chart
                    .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
                    .map_err(e)?
                    .label(label.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
            }
            if matches!(style, Style::Points | Style::LinePoints) {
                let ann = chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                    .map_err(e)?;
                if *style == Style::Points {
                    ann.label(label.as_str())
                        .legend(move |(x, y)| Circle::new((x + 9, y), 3, color.filled()));
                }
            }
        }
        if data.iter().any(|(l, _, _)| !l.is_empty()) {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", TEXT_PX))
                .draw()
                .map_err(e)?;
        }
        root.present().map_err(e)
    }

    /// Write `<stem>.svg` and `<stem>.png`, creating the parent directory. Returns both paths.
    pub fn save(&self, stem: impl AsRef<Path>) -> Result<(PathBuf, PathBuf), PlotError> {
        let stem = stem.as_ref();
        let svg = stem.with_extension("svg");
        let png = stem.with_extension("png");
        self.save_svg(&svg)?;
        self.save_png(&png)?;
        Ok((svg, png))
    }

    /// Write an SVG file.
    pub fn save_svg(&self, path: impl AsRef<Path>) -> Result<(), PlotError> {
        let path = path.as_ref();
        let (data, xr, yr) = self.prepare(path)?;
        let root = SVGBackend::new(path, self.size).into_drawing_area();
        self.draw(root, &data, xr, yr)
            .map_err(|message| PlotError::Backend {
                path: path.to_path_buf(),
                message,
            })
    }

    /// Write a PNG file.
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), PlotError> {
        let path = path.as_ref();
        let (data, xr, yr) = self.prepare(path)?;
        let root = BitMapBackend::new(path, self.size).into_drawing_area();
        self.draw(root, &data, xr, yr)
            .map_err(|message| PlotError::Backend {
                path: path.to_path_buf(),
                message,
            })
    }

    #[allow(clippy::type_complexity)]
    fn prepare(
        &self,
        path: &Path,
    ) -> Result<
        (
            Vec<(String, Vec<(f64, f64)>, Style)>,
            (f64, f64),
            (f64, f64),
        ),
        PlotError,
    > {
        register_font();
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|source| PlotError::Io {
                path: dir.to_path_buf(),
                source,
            })?;
        }
        let data = self.transformed();
        let (xr, yr) = self
            .ranges(&data)
            .ok_or_else(|| PlotError::NoData(self.title.clone()))?;
        Ok((data, xr, yr))
    }
}

/// The tick values plotters labels on an axis spanning `range` (same call as its mesh).
fn axis_ticks(range: Range) -> Vec<f64> {
    RangedCoordf64::from(range.0..range.1).key_points(MAX_TICKS)
}

/// Largest magnitude still written as a plain decimal ("9500"); from 1e4 on, "10e3".
const PLAIN_BELOW: f64 = 1e4;
/// Most decimals of a plain label ("0.005"); finer steps switch to "…e-6".
const PLAIN_DECIMALS: usize = 3;
/// Cap on the decimals of a mantissa (only reached by nonsense input).
const MAX_DECIMALS: usize = 12;

/// How every tick label of one axis is written: `mantissa` with a fixed number of `decimals`,
/// followed by `e<exponent>` unless the exponent is 0.
///
/// Choice of notation. Plain decimals while they stay short: magnitudes below 1e4 whose ticks
/// need at most 3 decimals ("0.02", "0.005", "-2500"). Otherwise engineering notation with ONE
/// exponent per axis, a multiple of 3 chosen so the largest label's mantissa is in [1, 1000):
/// "12.5e3", "-120e-6", "0.5e-3" next to "1.0e-3"; decimals are shared along the axis; an exact
/// (or round-off) zero is always "0". The exponent is written on every label rather than once as
/// an axis multiplier ("force (N) ×1e3") because a multiplier is ambiguous to read (is the value
/// the label times 1e3, or was the quantity scaled by 1e3?) and is easily missed when a figure
/// is cropped or quoted, whereas "250e-6" is a self-contained number a reader can copy, and
/// its multiple-of-3 exponent maps directly onto the SI prefix (e-6 → µ, e3 → k). SI prefix
/// letters themselves ("250µ", "1.2k") are avoided: next to units they collide ("250m" could be
/// milli or metres) and "µ" is not on a keyboard. ASCII '-' and 'e' keep labels identical in the
/// PNG and the SVG and searchable in the SVG text.
#[derive(Debug, Clone, Copy, PartialEq)]
struct TickFormat {
    exponent: i32,
    decimals: usize,
    /// Magnitudes at or below this are ticks at zero up to round-off (plotters' tick
    /// arithmetic leaves e.g. 2.7e-21 where 0 was meant); they print as "0", never "-0.0".
    zero: f64,
}

impl TickFormat {
    /// The format for an axis whose labelled ticks are `ticks` (any order; non-finite ignored).
    fn for_ticks(ticks: &[f64]) -> Self {
        let mut t: Vec<f64> = ticks.iter().copied().filter(|v| v.is_finite()).collect();
        t.sort_by(f64::total_cmp);
        let largest = t.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        // Resolution: the smallest step between ticks, or the value itself for a lone tick.
        let step = t
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|d| *d > 0.0)
            .fold(f64::INFINITY, f64::min);
        let step = if step.is_finite() { step } else { largest };
        if largest == 0.0 {
            return Self {
                exponent: 0,
                decimals: 0,
                zero: 0.0,
            };
        }
        let tol = 1e-6 * step;
        let plain = decimals_needed(&t, 0, tol);
        if largest < PLAIN_BELOW && plain <= PLAIN_DECIMALS {
            return Self {
                exponent: 0,
                decimals: plain,
                zero: tol,
            };
        }
        // The 1e-9 nudge keeps 0.001 computed as 0.000999… in the e-3 decade.
        let exponent = 3 * ((largest * (1.0 + 1e-9)).log10() / 3.0).floor() as i32;
        Self {
            exponent,
            decimals: decimals_needed(&t, exponent, tol),
            zero: tol,
        }
    }

    /// The label of one tick value.
    fn format(&self, value: f64) -> String {
        if !value.is_finite() {
            return value.to_string();
        }
        let mantissa = value / 10f64.powi(self.exponent);
        let scale = 10f64.powi(self.decimals as i32);
        if value.abs() <= self.zero || (mantissa * scale).round() == 0.0 {
            return "0".to_string();
        }
        let text = format!("{mantissa:.*}", self.decimals);
        if self.exponent == 0 {
            text
        } else {
            format!("{text}e{}", self.exponent)
        }
    }
}

/// Fewest decimals (up to [`MAX_DECIMALS`]) that write every `ticks / 10^exponent` to within
/// `tol` (in the units of the ticks).
fn decimals_needed(ticks: &[f64], exponent: i32, tol: f64) -> usize {
    let unit = 10f64.powi(exponent);
    (0..=MAX_DECIMALS)
        .find(|&d| {
            let scale = 10f64.powi(d as i32);
            ticks.iter().all(|&v| {
                let m = v / unit;
                ((m * scale).round() / scale - m).abs() * unit <= tol
            })
        })
        .unwrap_or(MAX_DECIMALS)
}

/// Tick labels for the values `ticks` of one axis, as clr-plot draws them.
///
/// All labels of an axis share one notation: plain decimals with a common number of decimals
/// while magnitudes stay below 1e4 and at most 3 decimals are needed (`0.02`, `0.005`,
/// `-2500`); otherwise engineering notation with a single exponent that is a multiple of 3,
/// chosen so the largest label's mantissa is in [1, 1000) (`12.5e3`, `-120e-6`). Zero, and
/// round-off residue standing for zero, is written `0`. On a log axis the ticks are the base-10
/// exponents (the axis is labelled `log10 …`), so they print as plain numbers (`-6`, `-5.5`).
///
/// ```
/// assert_eq!(clr_plot::format_ticks(&[0.0, 0.01, 0.02]), ["0", "0.01", "0.02"]);
/// assert_eq!(clr_plot::format_ticks(&[0.0, 5000.0, 10000.0, 15000.0]), ["0", "5e3", "10e3", "15e3"]);
/// assert_eq!(clr_plot::format_ticks(&[-100e-6, -50e-6, 0.0, 50e-6]), ["-100e-6", "-50e-6", "0", "50e-6"]);
/// ```
pub fn format_ticks(ticks: &[f64]) -> Vec<String> {
    let format = TickFormat::for_ticks(ticks);
    ticks.iter().map(|&v| format.format(v)).collect()
}

fn register_font() {
    REGISTER.call_once(|| {
        // Registration only fails for a malformed font; the embedded one is known good.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::style::text_anchor::{HPos, Pos, VPos};

    #[test]
    fn writes_svg_and_png_with_text() {
        let dir = std::env::temp_dir().join(format!("clr-plot-test-{}", std::process::id()));
        let (svg, png) = Figure::new("sine")
            .x_label("t (s)")
            .y_label("y (m)")
            .line(
                "sin",
                (0..50)
                    .map(|i| (i as f64, (i as f64 * 0.2).sin()))
                    .collect(),
            )
            .points(
                "cos",
                (0..50)
                    .map(|i| (i as f64, (i as f64 * 0.2).cos()))
                    .collect(),
            )
            .save(dir.join("fig"))
            .unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("<svg") && text.contains("sine"));
        assert!(std::fs::metadata(&png).unwrap().len() > 1000);
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn empty_figure_is_an_error() {
        let err = Figure::new("empty")
            .save_svg("/tmp/never-written.svg")
            .unwrap_err();
        assert!(matches!(err, PlotError::NoData(_)));
    }

    fn labels(ticks: &[f64]) -> Vec<String> {
        format_ticks(ticks)
    }

    #[test]
    fn plain_decimals_for_moderate_values() {
        assert_eq!(labels(&[0.02]), ["0.02"]);
        assert_eq!(labels(&[-0.001]), ["-0.001"]);
        assert_eq!(labels(&[0.0]), ["0"]);
        assert_eq!(
            labels(&[0.0, 0.01, 0.02, 0.03]),
            ["0", "0.01", "0.02", "0.03"]
        );
        // Decimals are shared along the axis: 0.010, not 0.01 next to 0.005.
        assert_eq!(
            labels(&[0.0, 0.005, 0.01, 0.015]),
            ["0", "0.005", "0.010", "0.015"]
        );
        assert_eq!(
            labels(&[-1.0, -0.5, 0.0, 0.5]),
            ["-1.0", "-0.5", "0", "0.5"]
        );
        assert_eq!(labels(&[2000.0, 4000.0, 8000.0]), ["2000", "4000", "8000"]);
        assert_eq!(labels(&[9999.5, 10000.0 - 0.25]), ["9999.50", "9999.75"]);
    }

    #[test]
    fn engineering_notation_for_large_values() {
        assert_eq!(labels(&[12500.0]), ["12.5e3"]);
        assert_eq!(labels(&[10000.0]), ["10e3"]);
        assert_eq!(
            labels(&[0.0, 2500.0, 5000.0, 7500.0, 10000.0, 12500.0]),
            ["0", "2.5e3", "5.0e3", "7.5e3", "10.0e3", "12.5e3"]
        );
        assert_eq!(labels(&[0.0, 5e6, 1e7]), ["0", "5e6", "10e6"]);
        assert_eq!(labels(&[-2e9, 0.0, 2e9]), ["-2e9", "0", "2e9"]);
    }

    #[test]
    fn engineering_notation_for_small_values() {
        assert_eq!(labels(&[250e-6]), ["250e-6"]);
        assert_eq!(labels(&[1.5e-9]), ["1.5e-9"]);
        assert_eq!(
            labels(&[-0.001, -0.0005, 0.0, 0.0005, 0.001]),
            ["-1.0e-3", "-0.5e-3", "0", "0.5e-3", "1.0e-3"]
        );
        assert_eq!(
            labels(&[0.0010, 0.0015, 0.0020]),
            ["1.0e-3", "1.5e-3", "2.0e-3"]
        );
    }

    #[test]
    fn ticks_spanning_zero_print_a_clean_zero() {
        // What plotters' tick arithmetic really yields around zero: round-off residue.
        let ticks = [-1.2e-4, -8e-5, -4e-5, 2.7e-21, 4e-5, 8e-5];
        assert_eq!(
            labels(&ticks),
            ["-120e-6", "-80e-6", "-40e-6", "0", "40e-6", "80e-6"]
        );
        assert_eq!(labels(&[-0.1, -1e-18, 0.1]), ["-0.1", "0", "0.1"]);
        assert_eq!(labels(&[-0.0]), ["0"]);
        assert!(labels(&[-5.0, -0.0, 5.0])
            .iter()
            .all(|l| !l.starts_with("-0")));
    }

    #[test]
    fn log_axis_ticks_are_plain_exponents() {
        assert_eq!(
            labels(&[-6.0, -5.5, -5.0, -4.5, -4.0]),
            ["-6.0", "-5.5", "-5.0", "-4.5", "-4.0"]
        );
        assert_eq!(
            labels(&[-12.0, -10.0, -8.0, -6.0]),
            ["-12", "-10", "-8", "-6"]
        );
        assert_eq!(labels(&[0.0, 1.0, 2.0, 3.0]), ["0", "1", "2", "3"]);
    }

    #[test]
    fn labels_of_real_axes_are_distinct_short_and_exact() {
        let ranges = [
            (-0.000_15, 0.000_15),
            (-0.0001, 0.000_12),
            (0.0, 0.05),
            (-1.0, 1.0),
            (0.0, 15_000.0),
            (9_000.0, 13_000.0),
            (-11.6, -3.4),
            (1e-9, 7e-9),
            (0.999, 1.001),
            (3.0e5, 3.2e5),
            (-2.5e7, 1.0e6),
        ];
        for r in ranges {
            let ticks = axis_ticks(r);
            let text = format_ticks(&ticks);
            assert!(ticks.len() >= 2, "{r:?}: {ticks:?}");
            for (i, (t, l)) in ticks.iter().zip(&text).enumerate() {
                assert!(l.len() <= 8, "{r:?}: label {l} too long");
                assert!(l.is_ascii() && !l.contains('\u{b7}'), "{r:?}: {l}");
                let back: f64 = l.parse().unwrap();
                let step = ticks[1] - ticks[0];
                assert!((back - t).abs() <= 1e-6 * step, "{r:?}: {t} -> {l}");
                assert!(!text[..i].contains(l), "{r:?}: duplicate {l} in {text:?}");
            }
            let exps: Vec<&str> = text
                .iter()
                .filter(|l| *l != "0")
                .map(|l| l.split_once('e').map_or("", |(_, e)| e))
                .collect();
            assert!(exps.windows(2).all(|w| w[0] == w[1]), "{r:?}: {text:?}");
        }
    }

    /// Lowest pixel row at least half inked when `text` is drawn at `size` px, top-left
    /// anchored at (10, 10), into a PNG-backend buffer.
    fn lowest_inked_row(text: &str, size: u32) -> usize {
        register_font();
        let (w, h) = (60usize, 60usize);
        let mut buf = vec![255u8; w * h * 3];
        {
            let root =
                BitMapBackend::with_buffer(&mut buf, (w as u32, h as u32)).into_drawing_area();
            let style = TextStyle::from(("sans-serif", size).into_font())
                .pos(Pos::new(HPos::Left, VPos::Top));
            root.draw(&Text::new(text, (10, 10), style)).unwrap();
            root.present().unwrap();
        }
        (0..h)
            .rev()
            .find(|&y| (0..w).any(|x| buf[(y * w + x) * 3] < 128))
            .expect("text drew nothing")
    }

    #[test]
    fn even_text_sizes_keep_the_point_on_the_baseline() {
        for size in [TEXT_PX, TITLE_PX] {
            assert_eq!(
                size % 2,
                0,
                "odd text size {size} lifts '.' off the baseline"
            );
            assert_eq!(
                lowest_inked_row(".", size),
                lowest_inked_row("0", size),
                "'.' and '0' do not share a baseline at {size} px"
            );
        }
    }

    #[test]
    fn log_axes_skip_non_positive_values() {
        let fig = Figure::new("log")
            .log_x()
            .log_y()
            .line("a", vec![(0.0, 1.0), (10.0, 100.0)]);
        let data = fig.transformed();
        assert_eq!(data[0].1, vec![(1.0, 2.0)]);
    }
}
