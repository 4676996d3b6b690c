//! Line and scatter figures (SVG and PNG) for clr results.
//!
//! A [`Figure`] is a title, two axis labels and a list of [`Series`]; [`Figure::save`] writes
//! `<stem>.svg` and `<stem>.png`. The DejaVu Sans font is embedded (see
//! `assets/DejaVuSans.LICENSE`), so figures render on machines without fontconfig or FreeType.
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

use plotters::coord::Shift;
use plotters::prelude::*;

static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

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
            .caption(&self.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc(Self::axis_label(&self.x_label, self.log_x))
            .y_desc(Self::axis_label(&self.y_label, self.log_y))
            .label_style(("sans-serif", 13))
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
                .label_font(("sans-serif", 13))
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

fn register_font() {
    REGISTER.call_once(|| {
        // Registration only fails for a malformed font; the embedded one is known good.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

#[cfg(test)]
mod tests {
    use super::*;

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
