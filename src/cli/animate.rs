//! `clr animate RUN_DIR --gif OUT.gif` / `--mp4 OUT.mp4`: the animation of a run exported to a
//! file for slides.
//!
//! The run's `report.html` holds the drawing data as JSON (`<script id="clr-data">`, the serde
//! form of `clr_sim::report::Report`); it is read here into the module's own `Deserialize` types and
//! every frame is drawn in Rust with tiny-skia (a pure-Rust 2-D rasterizer, anti-aliased) in a
//! simplified form of the page's drawing: ground symbols, rigid parts as outlines through their
//! attachment points (a rounded bar for two points, the convex hull for more, a block for one),
//! beams as deformed centrelines (deformation magnification), revolute clearance joints as
//! bearing and journal circles (clearance magnification), translational clearances as guide
//! lines and slider, sliders on beams, contact shapes (`[[shape]]`: their outlines moved with
//! their part as on the page, red while in contact), contact normal-force arrows and the time
//! (a built-in 5×7 bitmap font: no font dependency). The GIF is encoded by the `gif` crate with
//! a fixed palette (the drawing's colours and their anti-aliasing tints) and only the changed
//! rectangle of each frame; the MP4 pipes raw RGBA frames to `ffmpeg`.
//!
//! Binary-only: the `clr` library does not depend on tiny-skia or gif.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Deserialize;
use serde_json::Value;
use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Stroke, StrokeDash, Transform,
};

use clr_sim::report::spatial::{
    JournalDraw, Pose, ShapeDraw, SocketDraw, SpatialScene, SpatialView,
};

use super::CliError;

/// `clr animate`.
#[derive(clap::Args, Clone, Debug)]
#[command(group(
    clap::ArgGroup::new("output").required(true).multiple(true).args(["gif", "mp4"])
))]
pub(crate) struct AnimateArgs {
    /// A run's output folder (`clr run MODEL --out DIR`) or its report.html.
    pub run: PathBuf,
    /// Write an animated GIF (looping; no external program needed).
    #[arg(long, value_name = "OUT.gif")]
    pub gif: Option<PathBuf>,
    /// Write an MP4 (H.264) through `ffmpeg`, which must be on PATH.
    #[arg(long, value_name = "OUT.mp4")]
    pub mp4: Option<PathBuf>,
    /// Frames per second of the animation.
    #[arg(long, default_value_t = 25.0, value_name = "FPS")]
    pub fps: f64,
    /// Length of the whole animation, s (the run's frames are subsampled to fps × duration).
    #[arg(long, default_value_t = 8.0, value_name = "S")]
    pub duration: f64,
    /// Image width, px (the height follows from the drawing's aspect; both even).
    #[arg(long, default_value_t = 800, value_name = "PX")]
    pub width: u32,
    /// Clearance magnification (default: the clearance drawn as 8 % of the bearing radius,
    /// at least 1).
    #[arg(long, value_name = "M")]
    pub clearance_magnification: Option<f64>,
    /// Deformation magnification of beams (default: the largest displacement drawn as 5 % of
    /// the beam length, at least 1).
    #[arg(long, value_name = "M")]
    pub deformation_magnification: Option<f64>,
    /// First time shown, s (default: the run's start).
    #[arg(long, value_name = "S")]
    pub start: Option<f64>,
    /// Last time shown, s (default: the run's end).
    #[arg(long, value_name = "S")]
    pub end: Option<f64>,
    /// The view of a spatial (3-D) model's run: an orthographic projection from (1, 1, 1)
    /// (iso, the default), +z (front: the x-y plane), +y (top) or +x (side); y is up.
    #[arg(long, value_enum, value_name = "VIEW")]
    pub view: Option<ViewName>,
}

// ---------------------------------------------------------------------------------------------
// The report data (the serde form of clr_sim::report::Report, only what is drawn)

/// Numbers that may hold `null` (serde_json writes a NaN as `null`): read as NaN.
#[derive(Debug, Default, Clone)]
struct Nums(Vec<f64>);

impl<'de> Deserialize<'de> for Nums {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = Vec::<Option<f64>>::deserialize(d)?;
        Ok(Nums(v.into_iter().map(|x| x.unwrap_or(f64::NAN)).collect()))
    }
}

impl Nums {
    fn at(&self, k: usize) -> f64 {
        self.0.get(k).copied().unwrap_or(f64::NAN)
    }
}

#[derive(Debug, Deserialize)]
struct Page {
    #[serde(default)]
    kind: String,
    #[serde(default)]
    model: String,
    #[serde(default)]
    scene: Option<Scene>,
    #[serde(default)]
    scene_note: Option<String>,
    #[serde(default)]
    frames: Option<Frames>,
    /// A spatial model's drawing and frames (then `scene` is absent).
    #[serde(default)]
    spatial: Option<SpatialView>,
}

#[derive(Debug, Deserialize)]
struct Scene {
    #[serde(default)]
    parts: Vec<Part>,
    #[serde(default)]
    ground: Vec<[f64; 2]>,
    #[serde(default)]
    beams: Vec<Beam>,
    #[serde(default)]
    items: Vec<Item>,
    #[serde(default)]
    shapes: Vec<ContactShape>,
}

/// A contact shape (`[[shape]]`): outlines in its own frame, whose origin is the anchor `at`
/// and whose x axis is turned by `angle` from its part's (none for a beam face: drawn as its
/// beam).
#[derive(Debug, Deserialize)]
struct ContactShape {
    #[serde(default)]
    at: Option<At>,
    #[serde(default)]
    angle: Option<f64>,
    #[serde(default)]
    outlines: Vec<Outline>,
}

/// One line of a shape's outline in the shape frame: a polygon (`closed`) or an open chain.
#[derive(Debug, Deserialize)]
struct Outline {
    #[serde(default)]
    points: Vec<[f64; 2]>,
    #[serde(default)]
    closed: bool,
}

#[derive(Debug, Deserialize)]
struct Part {
    #[serde(default)]
    kind: String,
    #[serde(default)]
    com: [f64; 2],
    #[serde(default)]
    points: Vec<[f64; 2]>,
}

#[derive(Debug, Deserialize)]
struct Beam {
    #[serde(default = "ground_part")]
    part: i64,
    #[serde(default)]
    nodes: Vec<[f64; 2]>,
    #[serde(default)]
    depth: f64,
}

fn ground_part() -> i64 {
    -1
}

#[derive(Debug, Deserialize)]
struct Item {
    #[serde(default)]
    section: String,
    #[serde(default)]
    kind: String,
    #[serde(default)]
    name: String,
    #[serde(default)]
    anchors: BTreeMap<String, At>,
    #[serde(default)]
    bodies: BTreeMap<String, i64>,
    #[serde(default)]
    params: BTreeMap<String, Value>,
    /// The contact shapes it puts in contact (indices into `Scene::shapes`).
    #[serde(default)]
    shapes: Vec<usize>,
}

impl Item {
    fn param(&self, name: &str) -> Option<f64> {
        self.params.get(name)?.as_f64().filter(|v| v.is_finite())
    }
    fn vector(&self, name: &str) -> Option<[f64; 2]> {
        let a = self.params.get(name)?.as_array()?;
        Some([a.first()?.as_f64()?, a.get(1)?.as_f64()?])
    }
}

/// Where an element attaches: a point of a part (`-1`: the ground) in the part frame, or a node
/// of a beam.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(untagged)]
enum At {
    Part { part: i64, at: [f64; 2] },
    Node { beam: usize, node: usize },
}

#[derive(Debug, Deserialize)]
struct Frames {
    t: Nums,
    #[serde(default)]
    pose: Vec<Nums>,
    #[serde(default)]
    nodes: Vec<Nums>,
    #[serde(default)]
    contact: BTreeMap<String, BTreeMap<String, Nums>>,
}

/// The JSON text of the `<script id="clr-data">` element of a report page.
fn page_json(html: &str) -> Option<&str> {
    let tag = html.find("id=\"clr-data\"")?;
    let open = tag + html[tag..].find('>')? + 1;
    let close = open + html[open..].find("</script>")?;
    Some(&html[open..close])
}

/// Read a run's report (a folder holding `report.html`, or the page itself) and check that it
/// has an animation.
fn load(path: &Path) -> Result<(PathBuf, Page), String> {
    let give = "give the --out folder of `clr run MODEL --out DIR` (or its report.html)";
    let file = if path.is_dir() {
        let f = path.join("report.html");
        if !f.is_file() {
            return Err(format!(
                "{} holds no report.html (was the run made with --no-report?): {give}",
                path.display()
            ));
        }
        f
    } else {
        path.to_path_buf()
    };
    let html = std::fs::read_to_string(&file)
        .map_err(|e| format!("cannot read {}: {e}; {give}", file.display()))?;
    let page = parse_page(&html).map_err(|e| format!("{}: {e}; {give}", file.display()))?;
    check(&page, &file)?;
    Ok((file, page))
}

fn parse_page(html: &str) -> Result<Page, String> {
    let json =
        page_json(html).ok_or("not a clr report (it has no <script id=\"clr-data\"> element)")?;
    // the page writes "</" as "<\/", a valid JSON escape of "/": serde_json reads it back
    serde_json::from_str(json).map_err(|e| format!("cannot read the report data: {e}"))
}

/// Refuse a page without frames, saying what to give instead.
fn check(page: &Page, file: &Path) -> Result<(), String> {
    if page.kind == "sweep" {
        let dir = file.parent().unwrap_or(Path::new("."));
        return Err(format!(
            "{} is the report of a sweep, which has no animation: give the folder of one of its \
             points instead (e.g. `clr animate {}`, written unless the sweep ran with --no-report)",
            file.display(),
            dir.join("point-00000").display()
        ));
    }
    let frames = match &page.spatial {
        Some(s) => s.frames.t.len(),
        None => page.frames.as_ref().map_or(0, |f| f.t.0.len()),
    };
    if (page.scene.is_none() && page.spatial.is_none()) || frames == 0 {
        let why = match (&page.scene, &page.scene_note) {
            (None, Some(note)) => format!("the model has no drawing: {note}"),
            (None, None) => "the model has no drawing".to_string(),
            _ => "it holds no frames".to_string(),
        };
        return Err(format!(
            "{} has no animation ({why}): give the --out folder of a `clr run` of a built-in \
             model or a model file, whose report.html animates the mechanism",
            file.display()
        ));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Options

/// What the drawing needs besides the page (the options of `clr animate`, checked).
#[derive(Debug, Clone)]
pub(crate) struct Settings {
    /// Frames per second.
    pub(crate) fps: f64,
    /// Length of the animation, s.
    pub(crate) duration: f64,
    /// Image width, px (even).
    pub(crate) width: u32,
    /// Clearance magnification (`None`: automatic).
    pub(crate) clearance_magnification: Option<f64>,
    /// Deformation magnification of beams (`None`: automatic).
    pub(crate) deformation_magnification: Option<f64>,
    /// First time shown, s.
    pub(crate) start: Option<f64>,
    /// Last time shown, s.
    pub(crate) end: Option<f64>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            fps: 25.0,
            duration: 8.0,
            width: 800,
            clearance_magnification: None,
            deformation_magnification: None,
            start: None,
            end: None,
        }
    }
}

impl Settings {
    fn from_args(a: &AnimateArgs) -> Result<Self, String> {
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!("--{name} must be a positive number, not {v}"))
            }
        };
        positive("fps", a.fps)?;
        if a.fps > 100.0 {
            return Err(format!("--fps {} is above 100", a.fps));
        }
        positive("duration", a.duration)?;
        if !(64..=8192).contains(&a.width) {
            return Err(format!("--width {} must be from 64 to 8192 px", a.width));
        }
        if let Some(m) = a.clearance_magnification {
            positive("clearance-magnification", m)?;
        }
        if let Some(m) = a.deformation_magnification {
            positive("deformation-magnification", m)?;
        }
        for (name, v) in [("start", a.start), ("end", a.end)] {
            if v.is_some_and(|v| !v.is_finite()) {
                return Err(format!("--{name} must be a number"));
            }
        }
        if let (Some(s), Some(e)) = (a.start, a.end) {
            if s > e {
                return Err(format!("--start {s} is after --end {e}"));
            }
        }
        let frames = (a.fps * a.duration).round();
        if frames > 20_000.0 {
            return Err(format!(
                "--fps {} × --duration {} = {frames} frames: at most 20000",
                a.fps, a.duration
            ));
        }
        Ok(Settings {
            fps: a.fps,
            duration: a.duration,
            width: a.width + a.width % 2,
            clearance_magnification: a.clearance_magnification,
            deformation_magnification: a.deformation_magnification,
            start: a.start,
            end: a.end,
        })
    }
}

// ---------------------------------------------------------------------------------------------
// Colours

type Rgb = [u8; 3];

const BACKGROUND: Rgb = [255, 255, 255];
const INK: Rgb = [33, 37, 41];
const GREY: Rgb = [134, 142, 150];
const LIGHT: Rgb = [222, 226, 230];
const PART_FILL: Rgb = [165, 192, 230];
const PART_EDGE: Rgb = [37, 78, 140];
const BEAM_FILL: Rgb = [240, 190, 110];
const BEAM_EDGE: Rgb = [150, 95, 20];
const SLIDER_FILL: Rgb = [190, 170, 220];
const BEARING: Rgb = [46, 125, 50];
const JOURNAL_FILL: Rgb = [240, 150, 140];
const JOURNAL_EDGE: Rgb = [170, 40, 40];
const ARROW: Rgb = [214, 40, 40];
/// A contact shape on a part: the part fill at 70 % over the background (the page's light
/// fill), edged in `PART_EDGE`.
const SHAPE_FILL: Rgb = [192, 211, 238];
/// A contact shape on the ground: grey, hatched and edged in `GREY`.
const GROUND_FILL: Rgb = [206, 212, 218];

/// Every colour drawn; the GIF palette holds them and their blends with the colours they are
/// drawn over (anti-aliased edges).
const COLOURS: [Rgb; 15] = [
    BACKGROUND,
    INK,
    GREY,
    LIGHT,
    PART_FILL,
    PART_EDGE,
    BEAM_FILL,
    BEAM_EDGE,
    SLIDER_FILL,
    BEARING,
    JOURNAL_FILL,
    JOURNAL_EDGE,
    ARROW,
    SHAPE_FILL,
    GROUND_FILL,
];

fn paint(c: Rgb) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(c[0], c[1], c[2], 255);
    p.anti_alias = true;
    p
}

fn stroke(width: f64) -> Stroke {
    Stroke {
        width: width as f32,
        line_cap: LineCap::Round,
        line_join: LineJoin::Round,
        ..Stroke::default()
    }
}

// ---------------------------------------------------------------------------------------------
// Geometry of a frame

type P = [f64; 2];

fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1]]
}
fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1]]
}
fn mul(a: P, k: f64) -> P {
    [a[0] * k, a[1] * k]
}
fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}
fn rot(a: P, th: f64) -> P {
    let (s, c) = th.sin_cos();
    [c * a[0] - s * a[1], s * a[0] + c * a[1]]
}
fn norm(a: P) -> f64 {
    a[0].hypot(a[1])
}
fn finite(p: P) -> bool {
    p[0].is_finite() && p[1].is_finite()
}

/// One thing drawn in a frame, in world coordinates (m); sizes in pixels are chosen when drawn.
#[derive(Debug, Clone)]
enum Shape {
    /// A ground symbol at a point.
    Ground(P),
    /// An ideal translational joint on the ground: a dashed rail through a point.
    Rail { at: P, dir: P },
    /// A beam's deformed centreline, drawn `depth` wide.
    Beam { nodes: Vec<P>, depth: f64 },
    /// A rigid part through its attachment points; `bearing` is the largest bearing radius
    /// (m) on it (a one-point part is a block around it).
    Body {
        points: Vec<P>,
        theta: f64,
        bearing: f64,
    },
    /// A rectangle (slider) centred at `c`, axis at `angle`.
    Rect { c: P, angle: f64, size: [f64; 2] },
    /// A guide line of a translational clearance.
    Line { a: P, b: P },
    /// A revolute clearance: bearing circle (radius `r`) at `c`, journal (radius `rj`, already
    /// reduced by the magnified clearance) at `c + off` (`off` magnified); `force` ∈ (0, 1]
    /// of the largest normal force draws an arrow at the contact point.
    Bearing {
        c: P,
        r: f64,
        rj: f64,
        off: P,
        force: Option<f64>,
    },
    /// An ideal revolute joint.
    Pin(P),
    /// A contact normal force on the guide: from `tail` along the unit `dir`, `force` ∈ (0, 1]
    /// of the largest normal force.
    Arrow { tail: P, dir: P, force: f64 },
    /// A contact shape's outlines in the world, each with its `closed` flag (polygons filled);
    /// `ground`: fixed to the ground (grey, hatched), else moving with a part; `on`: in contact
    /// (edged red).
    Outline {
        lines: Vec<(Vec<P>, bool)>,
        ground: bool,
        on: bool,
    },
}

impl Shape {
    /// The points that bound the drawing.
    fn extent(&self, out: &mut Vec<P>) {
        match self {
            Shape::Ground(p) | Shape::Pin(p) => out.push(*p),
            Shape::Rail { .. } | Shape::Arrow { .. } => {}
            Shape::Beam { nodes, depth } => {
                let d = depth / 2.0;
                for p in nodes {
                    out.extend([add(*p, [d, d]), sub(*p, [d, d])]);
                }
            }
            Shape::Body { points, .. } => out.extend(points),
            Shape::Rect { c, angle, size } => out.extend(rect_corners(*c, *angle, *size)),
            Shape::Line { a, b } => out.extend([*a, *b]),
            Shape::Bearing { c, r, .. } => {
                out.extend([add(*c, [*r, *r]), sub(*c, [*r, *r])]);
            }
            Shape::Outline { lines, .. } => {
                for (pts, _) in lines {
                    out.extend(pts);
                }
            }
        }
    }
}

fn rect_corners(c: P, angle: f64, [l, h]: [f64; 2]) -> [P; 4] {
    [[-l, -h], [l, -h], [l, h], [-l, h]].map(|q| add(c, rot(mul(q, 0.5), angle)))
}

/// The frames of a page chosen and measured for export: what to draw where.
struct Animation<'a> {
    scene: &'a Scene,
    frames: &'a Frames,
    model: &'a str,
    /// Frame indices of the report shown, in order (one per output frame).
    picks: Vec<usize>,
    /// Clearance magnification.
    mc: f64,
    /// Deformation magnification.
    md: f64,
    /// Per rigid part: its distinct attachment points (part frame).
    outline: Vec<Vec<P>>,
    /// Per part: the largest bearing radius of a revolute clearance on it, m.
    bearing: Vec<f64>,
    /// Per part: it carries a contact shape with an outline (then the shape is its drawing:
    /// no block of its own for a one-point part, as on the page).
    shaped: Vec<bool>,
    /// Per contact shape: the `contact` elements that list it (indices into the items).
    shape_contacts: Vec<Vec<usize>>,
    /// Per item: for a translational clearance, the range of the slider along the guide (guide
    /// frame, m) over the frames shown.
    span: Vec<Option<(f64, f64)>>,
    /// Largest contact normal force over the frames shown, N.
    fmax: f64,
    /// Pixel mapping.
    view: View,
    /// Decimals of the time shown.
    decimals: usize,
}

/// An animation as `clr animate` writes it: frames of one size, each showing a report frame.
pub(crate) trait Movie {
    /// Image width and height, px (even).
    fn size(&self) -> (u32, u32);
    /// The report frame each output frame shows.
    fn picks(&self) -> &[usize];
    /// Output frame `i`.
    fn render(&self, i: usize) -> Pixmap;
}

impl Movie for Animation<'_> {
    fn size(&self) -> (u32, u32) {
        (self.view.width, self.view.height)
    }

    fn picks(&self) -> &[usize] {
        &self.picks
    }

    fn render(&self, i: usize) -> Pixmap {
        self.frame(i)
    }
}

/// The world → pixel mapping (y up in the world, down in the image).
#[derive(Debug, Clone, Copy)]
struct View {
    width: u32,
    height: u32,
    /// Pixels per metre.
    scale: f64,
    /// World point at pixel (left, bottom) of the drawing area.
    x0: f64,
    y0: f64,
    /// Pixel x of `x0` and pixel distance from the image bottom of `y0`.
    left: f64,
    bottom: f64,
}

impl View {
    fn px(&self, p: P) -> P {
        [
            self.left + (p[0] - self.x0) * self.scale,
            self.height as f64 - (self.bottom + (p[1] - self.y0) * self.scale),
        ]
    }

    /// Margin around the drawing, px (room for the texts).
    fn margin(width: u32) -> f64 {
        (0.04 * width as f64).round().max(24.0)
    }

    /// The mapping that fits the box around the finite points of `pts` (m; the origin without
    /// one) as [`View::fit`] does.
    fn fit_points(pts: Vec<P>, width: u32) -> View {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in pts.into_iter().filter(|p| finite(*p)) {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if !finite(lo) {
            (lo, hi) = ([0.0, 0.0], [0.0, 0.0]);
        }
        View::fit(lo, hi, width)
    }

    /// The mapping that fits the box `[lo, hi]` (m) into an image `width` px wide, with the
    /// height following the aspect (between a quarter of the width and 1.25 times it; even).
    fn fit(lo: P, hi: P, width: u32) -> View {
        let w = width as f64;
        let m = Self::margin(width);
        let (mut lo, mut hi) = (lo, hi);
        // a degenerate box (one point, or a straight line) gets a size
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let size = if size > 0.0 && size.is_finite() {
            size
        } else {
            0.1
        };
        for k in 0..2 {
            if hi[k] - lo[k] < 1e-6 * size {
                lo[k] -= 0.05 * size;
                hi[k] += 0.05 * size;
            }
        }
        let (dx, dy) = (hi[0] - lo[0], hi[1] - lo[1]);
        let mut scale = (w - 2.0 * m) / dx;
        let h_max = (1.25 * w).floor();
        if dy * scale + 2.0 * m > h_max {
            scale = (h_max - 2.0 * m) / dy;
        }
        let h_min = (w / 4.0).max(2.0 * m + 16.0);
        let mut height = (dy * scale + 2.0 * m).ceil().clamp(h_min, h_max) as u32;
        height += height % 2;
        View {
            width,
            height,
            scale,
            x0: lo[0],
            y0: lo[1],
            left: m + ((w - 2.0 * m) - dx * scale) / 2.0,
            bottom: m + ((height as f64 - 2.0 * m) - dy * scale) / 2.0,
        }
    }
}

/// Decimals of the time shown: enough to tell the frames `picks` of the times `t` (s) apart.
fn time_decimals(t: &[f64], picks: &[usize]) -> usize {
    let (ta, tb) = (t[picks[0]], t[picks[picks.len() - 1]]);
    let step = (tb - ta) / (picks.len().max(2) - 1) as f64;
    let scale = if step > 0.0 { step } else { tb.abs().max(1e-3) };
    (-scale.log10()).ceil().clamp(1.0, 9.0) as usize
}

/// Report frames at `count` equally spaced times over the frames inside [start, end] (the
/// nearest frame to each).
fn pick_frames(t: &[f64], start: Option<f64>, end: Option<f64>, count: usize) -> Vec<usize> {
    // a frame within rounding of an end of the window is in it
    let eps = t
        .last()
        .zip(t.first())
        .map_or(0.0, |(b, a)| 1e-9 * (b - a).abs());
    let lo = start.map_or(f64::NEG_INFINITY, |s| s - eps);
    let hi = end.map_or(f64::INFINITY, |e| e + eps);
    let inside: Vec<usize> = (0..t.len()).filter(|&k| t[k] >= lo && t[k] <= hi).collect();
    if inside.is_empty() || count == 0 {
        return Vec::new();
    }
    let (ta, tb) = (t[inside[0]], t[inside[inside.len() - 1]]);
    let mut out = Vec::with_capacity(count);
    let mut r = 0;
    for i in 0..count {
        let ti = if count == 1 {
            ta
        } else {
            ta + (tb - ta) * i as f64 / (count - 1) as f64
        };
        while r + 1 < inside.len() && (t[inside[r + 1]] - ti).abs() <= (t[inside[r]] - ti).abs() {
            r += 1;
        }
        out.push(inside[r]);
    }
    out
}

/// The part an anchor moves with (a beam node: its beam's body; −1: the ground or a ground
/// beam).
fn anchor_part(scene: &Scene, at: &At) -> i64 {
    match *at {
        At::Part { part, .. } => part,
        At::Node { beam, .. } => scene.beams.get(beam).map_or(-1, |b| b.part),
    }
}

impl<'a> Animation<'a> {
    /// Choose the frames, the magnifications and the view of a checked page.
    fn new(page: &'a Page, s: &Settings) -> Result<Self, String> {
        let (Some(scene), Some(frames)) = (&page.scene, &page.frames) else {
            return Err("the report has no animation".into());
        };
        let count = ((s.fps * s.duration).round() as usize).max(1);
        let picks = pick_frames(&frames.t.0, s.start, s.end, count);
        if picks.is_empty() {
            let t = &frames.t.0;
            return Err(format!(
                "no frame inside --start {} … --end {}: the run's frames span {} … {} s",
                s.start.map_or("-".into(), |v| v.to_string()),
                s.end.map_or("-".into(), |v| v.to_string()),
                t[0],
                t[t.len() - 1]
            ));
        }
        let outline = scene
            .parts
            .iter()
            .map(|p| {
                let mut pts: Vec<P> = Vec::new();
                for q in &p.points {
                    if finite(*q) && !pts.iter().any(|r| norm(sub(*r, *q)) < 1e-9) {
                        pts.push(*q);
                    }
                }
                pts
            })
            .collect();
        let mut bearing = vec![0.0f64; scene.parts.len()];
        for item in &scene.items {
            if item.section == "clearance" && item.kind == "revolute" {
                if let (Some(At::Part { part, .. }), Some(r)) =
                    (item.anchors.get("bearing"), item.param("bearing_radius"))
                {
                    if let Some(b) = bearing.get_mut(*part as usize) {
                        *b = b.max(r);
                    }
                }
            }
        }
        let mut shaped = vec![false; scene.parts.len()];
        for sh in &scene.shapes {
            if let Some(at) = sh.at.as_ref().filter(|_| !sh.outlines.is_empty()) {
                let k = anchor_part(scene, at);
                if k >= 0 {
                    if let Some(s) = shaped.get_mut(k as usize) {
                        *s = true;
                    }
                }
            }
        }
        let shape_contacts = (0..scene.shapes.len())
            .map(|i| {
                (0..scene.items.len())
                    .filter(|&k| {
                        scene.items[k].kind == "contact" && scene.items[k].shapes.contains(&i)
                    })
                    .collect()
            })
            .collect();
        let mut a = Animation {
            scene,
            frames,
            model: &page.model,
            picks,
            mc: 1.0,
            md: 1.0,
            outline,
            bearing,
            shaped,
            shape_contacts,
            span: Vec::new(),
            fmax: 0.0,
            view: View::fit([0.0, 0.0], [1.0, 1.0], s.width),
            decimals: 3,
        };
        let mut distinct = a.picks.clone();
        distinct.dedup();
        a.mc = s
            .clearance_magnification
            .unwrap_or_else(|| a.default_clearance_magnification());
        a.md = s
            .deformation_magnification
            .unwrap_or_else(|| a.default_deformation_magnification(&distinct));
        a.span = a.guide_spans(&distinct);
        a.fmax = a.largest_force(&distinct);
        // bounds of everything drawn over the frames shown
        let mut pts = Vec::new();
        for &f in &distinct {
            for sh in a.shapes(f) {
                sh.extent(&mut pts);
            }
        }
        a.view = View::fit_points(pts, s.width);
        a.decimals = time_decimals(&frames.t.0, &a.picks);
        Ok(a)
    }

    /// The clearance drawn as 8 % of the bearing radius (translational: the play W − h as 8 %
    /// of the slider height), the smallest over the joints, at least 1.
    fn default_clearance_magnification(&self) -> f64 {
        let mut m = f64::INFINITY;
        for item in &self.scene.items {
            if item.section != "clearance" {
                continue;
            }
            let r = match item.kind.as_str() {
                "revolute" => item
                    .param("bearing_radius")
                    .zip(item.param("journal_radius"))
                    .map(|(r, j)| 0.08 * r / (r - j)),
                "translational" => item
                    .param("guide_width")
                    .zip(item.param("slider_height"))
                    .map(|(w, h)| 0.08 * h / (w - h)),
                _ => None,
            };
            if let Some(r) = r.filter(|r| r.is_finite() && *r > 0.0) {
                m = m.min(r);
            }
        }
        if m.is_finite() {
            m.max(1.0)
        } else {
            1.0
        }
    }

    /// The largest beam displacement drawn as 5 % of the beam's length, the smallest over the
    /// beams, at least 1.
    fn default_deformation_magnification(&self, frames: &[usize]) -> f64 {
        let mut m = f64::INFINITY;
        for (b, beam) in self.scene.beams.iter().enumerate() {
            let (Some(first), Some(last)) = (beam.nodes.first(), beam.nodes.last()) else {
                continue;
            };
            let length = norm(sub(*last, *first));
            let Some(d) = self.frames.nodes.get(b) else {
                continue;
            };
            let nn = beam.nodes.len();
            let mut umax = 0.0f64;
            for &f in frames {
                for k in 0..nn {
                    let u = norm([d.at((f * nn + k) * 2), d.at((f * nn + k) * 2 + 1)]);
                    if u.is_finite() {
                        umax = umax.max(u);
                    }
                }
            }
            if umax > 0.0 && length > 0.0 {
                m = m.min(0.05 * length / umax);
            }
        }
        if m.is_finite() {
            m.max(1.0)
        } else {
            1.0
        }
    }

    /// [x, y, θ] of part `part`'s centre of mass in frame `f` (the ground: 0).
    fn pose(&self, part: i64, f: usize) -> [f64; 3] {
        if part < 0 {
            return [0.0; 3];
        }
        match self.frames.pose.get(part as usize) {
            Some(p) => [p.at(3 * f), p.at(3 * f + 1), p.at(3 * f + 2)],
            None => [f64::NAN; 3],
        }
    }

    /// World position of point `at` of part `part` (its frame) in frame `f`.
    fn world(&self, part: i64, at: P, f: usize) -> P {
        if part < 0 {
            return at;
        }
        let com = self
            .scene
            .parts
            .get(part as usize)
            .map_or([0.0, 0.0], |p| p.com);
        let [x, y, th] = self.pose(part, f);
        add([x, y], rot(sub(at, com), th))
    }

    /// World position of node `k` of beam `b` in frame `f`, the displacement magnified.
    fn node(&self, b: usize, k: usize, f: usize) -> P {
        let Some(beam) = self.scene.beams.get(b) else {
            return [f64::NAN; 2];
        };
        let Some(&n) = beam.nodes.get(k) else {
            return [f64::NAN; 2];
        };
        let nn = beam.nodes.len();
        let u = self.frames.nodes.get(b).map_or([0.0, 0.0], |d| {
            [d.at((f * nn + k) * 2), d.at((f * nn + k) * 2 + 1)]
        });
        let u = if finite(u) { u } else { [0.0, 0.0] };
        add(self.world(beam.part, n, f), mul(u, self.md))
    }

    fn anchor(&self, at: &At, f: usize) -> P {
        match *at {
            At::Part { part, at } => self.world(part, at, f),
            At::Node { beam, node } => self.node(beam, node, f),
        }
    }

    /// Rotation of the frame an anchor is given in (a beam node: its body's frame).
    fn anchor_theta(&self, at: &At, f: usize) -> f64 {
        self.pose(anchor_part(self.scene, at), f)[2]
    }

    /// The outlines of contact shape `i` in the world in frame `f`, as the page moves them:
    /// origin at its anchor (a beam node with the magnified displacement), x axis at the
    /// anchor frame's rotation + the shape's angle; none for a shape without a frame.
    fn shape_outline(&self, i: usize, f: usize) -> Option<Shape> {
        let sh = self.scene.shapes.get(i)?;
        let at = sh.at.as_ref()?;
        if sh.outlines.is_empty() {
            return None;
        }
        let o = self.anchor(at, f);
        let th = self.anchor_theta(at, f) + sh.angle.filter(|a| a.is_finite()).unwrap_or(0.0);
        let lines = sh
            .outlines
            .iter()
            .map(|ol| {
                let pts = ol.points.iter().map(|q| add(o, rot(*q, th))).collect();
                (pts, ol.closed)
            })
            .collect();
        // in contact: a `contact` element listing it touches (the page's test: active contact
        // points or a normal force)
        let on = self.shape_contacts[i].iter().any(|&k| {
            let item = &self.scene.items[k];
            self.contact(item, "contact", f) > 0.0 || self.normal_force(item, f) > 0.0
        });
        Some(Shape::Outline {
            lines,
            ground: anchor_part(self.scene, at) < 0,
            on,
        })
    }

    fn contact(&self, item: &Item, column: &str, f: usize) -> f64 {
        self.frames
            .contact
            .get(&item.name)
            .and_then(|c| c.get(column))
            .map_or(f64::NAN, |v| v.at(f))
    }

    /// Normal force of a clearance in frame `f` (0 out of contact or unknown).
    fn normal_force(&self, item: &Item, f: usize) -> f64 {
        let n = self.contact(item, "normal_force", f);
        if n.is_finite() && n > 0.0 {
            n
        } else {
            0.0
        }
    }

    /// The largest normal force of the clearances drawn with force arrows (not the shape
    /// contacts: no arrow of theirs is drawn).
    fn largest_force(&self, frames: &[usize]) -> f64 {
        let mut m = 0.0f64;
        let arrows = ["revolute", "translational", "slider_on_beam"];
        for item in self
            .scene
            .items
            .iter()
            .filter(|i| i.section == "clearance" && arrows.contains(&i.kind.as_str()))
        {
            for &f in frames {
                m = m.max(self.normal_force(item, f));
            }
        }
        m
    }

    /// The guide frame of a translational clearance in frame `f`: origin, axis, normal.
    fn guide_frame(&self, item: &Item, f: usize) -> Option<(P, P, P)> {
        let g = item.anchors.get("guide")?;
        let origin = self.anchor(g, f);
        let angle = self.anchor_theta(g, f) + item.param("guide_angle").unwrap_or(0.0);
        let axis = rot([1.0, 0.0], angle);
        Some((origin, axis, rot(axis, std::f64::consts::FRAC_PI_2)))
    }

    fn guide_spans(&self, frames: &[usize]) -> Vec<Option<(f64, f64)>> {
        self.scene
            .items
            .iter()
            .map(|item| {
                if item.section != "clearance" || item.kind != "translational" {
                    return None;
                }
                let slider = item.anchors.get("slider")?;
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for &f in frames {
                    let (o, axis, _) = self.guide_frame(item, f)?;
                    let s = dot(sub(self.anchor(slider, f), o), axis);
                    if s.is_finite() {
                        lo = lo.min(s);
                        hi = hi.max(s);
                    }
                }
                let l = item.param("slider_length").unwrap_or(0.0);
                (lo <= hi).then_some((lo - l, hi + l))
            })
            .collect()
    }

    /// Everything drawn in frame `f`, in drawing order.
    fn shapes(&self, f: usize) -> Vec<Shape> {
        let scene = self.scene;
        let mut out = Vec::new();
        let mut arrows = Vec::new();
        // contact shapes on the ground (or a ground beam) under everything, on parts over them
        let (ground_shapes, part_shapes): (Vec<Shape>, Vec<Shape>) = (0..scene.shapes.len())
            .filter_map(|i| self.shape_outline(i, f))
            .partition(|s| matches!(s, Shape::Outline { ground: true, .. }));
        out.extend(ground_shapes);
        // rails of ideal translational joints on the ground
        for item in &scene.items {
            if item.section == "joint" && item.kind == "translational" {
                let (Some(a), Some(b)) = (item.anchors.get("a"), item.anchors.get("b")) else {
                    continue;
                };
                let on_ground = |at: &At| matches!(at, At::Part { part, .. } if *part < 0);
                let ground = if on_ground(a) {
                    a
                } else if on_ground(b) {
                    b
                } else {
                    continue;
                };
                let dir = item.vector("axis").unwrap_or([1.0, 0.0]);
                if norm(dir) > 0.0 {
                    out.push(Shape::Rail {
                        at: self.anchor(ground, f),
                        dir: mul(dir, 1.0 / norm(dir)),
                    });
                }
            }
        }
        for (b, beam) in scene.beams.iter().enumerate() {
            out.push(Shape::Beam {
                nodes: (0..beam.nodes.len()).map(|k| self.node(b, k, f)).collect(),
                depth: beam.depth,
            });
        }
        let mut ground: Vec<P> = Vec::new();
        for g in &scene.ground {
            if finite(*g) && !ground.iter().any(|h| norm(sub(*h, *g)) < 1e-9) {
                ground.push(*g);
            }
        }
        out.extend(ground.into_iter().map(Shape::Ground));
        for (i, part) in scene.parts.iter().enumerate() {
            if part.kind == "flexible"
                || self.outline[i].is_empty()
                || (self.shaped[i] && self.outline[i].len() == 1)
            {
                continue;
            }
            out.push(Shape::Body {
                points: self.outline[i]
                    .iter()
                    .map(|q| self.world(i as i64, *q, f))
                    .collect(),
                theta: self.pose(i as i64, f)[2],
                bearing: self.bearing[i],
            });
        }
        out.extend(part_shapes);
        let mut pins = Vec::new();
        for (k, item) in scene.items.iter().enumerate() {
            match (item.section.as_str(), item.kind.as_str()) {
                ("joint", "revolute") => {
                    if let Some(a) = item.anchors.get("a").or_else(|| item.anchors.get("b")) {
                        pins.push(Shape::Pin(self.anchor(a, f)));
                    }
                }
                ("clearance", "revolute") => {
                    if let Some(s) = self.revolute_clearance(item, f) {
                        out.push(s);
                    }
                }
                ("clearance", "translational") => {
                    self.translational_clearance(item, self.span[k], f, &mut out, &mut arrows);
                }
                ("clearance", "slider_on_beam") => {
                    self.slider_on_beam(item, f, &mut out, &mut arrows);
                }
                _ => {}
            }
        }
        out.extend(pins);
        out.extend(arrows);
        out
    }

    fn revolute_clearance(&self, item: &Item, f: usize) -> Option<Shape> {
        let bearing = item.anchors.get("bearing")?;
        let r = item.param("bearing_radius")?;
        let rj = item.param("journal_radius").unwrap_or(r);
        let c = self.anchor(bearing, f);
        // eccentricity: the recorded one (bearing frame) or the anchors' distance
        let (ex, ey) = (self.contact(item, "ex", f), self.contact(item, "ey", f));
        let e = if ex.is_finite() && ey.is_finite() {
            rot([ex, ey], self.anchor_theta(bearing, f))
        } else {
            let j = item.anchors.get("journal")?;
            sub(self.anchor(j, f), c)
        };
        let force = self.normal_force(item, f);
        Some(Shape::Bearing {
            c,
            r,
            rj: (r - self.mc * (r - rj)).max(0.0),
            off: mul(e, self.mc),
            force: (force > 0.0 && self.fmax > 0.0).then(|| force / self.fmax),
        })
    }

    fn translational_clearance(
        &self,
        item: &Item,
        span: Option<(f64, f64)>,
        f: usize,
        out: &mut Vec<Shape>,
        arrows: &mut Vec<Shape>,
    ) {
        let (Some(slider), Some((o, axis, n))) =
            (item.anchors.get("slider"), self.guide_frame(item, f))
        else {
            return;
        };
        let w = item.param("guide_width").unwrap_or(0.0);
        let l = item.param("slider_length").unwrap_or(0.0);
        let h = item.param("slider_height").unwrap_or(0.0);
        // the play (W − h)/2, the slider's offset and tilt in the guide magnified
        let half = h / 2.0 + self.mc * (w - h) / 2.0;
        let s = self.anchor(slider, f);
        let (along, across) = (dot(sub(s, o), axis), dot(sub(s, o), n));
        let guide_angle = axis[1].atan2(axis[0]);
        let mut tilt =
            self.anchor_theta(slider, f) + item.param("slider_angle").unwrap_or(0.0) - guide_angle;
        tilt =
            (tilt + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
        if tilt.abs() < 0.5 {
            tilt *= self.mc;
        }
        let (lo, hi) = span.unwrap_or((along - l, along + l));
        for side in [-1.0, 1.0] {
            let off = add(o, mul(n, side * half));
            out.push(Shape::Line {
                a: add(off, mul(axis, lo)),
                b: add(off, mul(axis, hi)),
            });
        }
        let c = add(add(o, mul(axis, along)), mul(n, self.mc * across));
        out.push(Shape::Rect {
            c,
            angle: guide_angle + tilt,
            size: [l, h],
        });
        let force = self.normal_force(item, f);
        if force > 0.0 && self.fmax > 0.0 {
            let side = if across >= 0.0 { 1.0 } else { -1.0 };
            arrows.push(Shape::Arrow {
                tail: add(add(o, mul(axis, along)), mul(n, side * half)),
                dir: mul(n, side),
                force: force / self.fmax,
            });
        }
    }

    fn slider_on_beam(&self, item: &Item, f: usize, out: &mut Vec<Shape>, arrows: &mut Vec<Shape>) {
        let Some(slider) = item.anchors.get("slider") else {
            return;
        };
        let c = self.anchor(slider, f);
        let l = item.param("slider_length").unwrap_or(0.0);
        let h = item.param("slider_height").unwrap_or(0.0);
        let angle = self.anchor_theta(slider, f) + item.param("slider_angle").unwrap_or(0.0);
        out.push(Shape::Rect {
            c,
            angle,
            size: [l, h],
        });
        let force = self.normal_force(item, f);
        let beam = item.bodies.get("beam").copied().unwrap_or(-1);
        if force <= 0.0 || self.fmax <= 0.0 || beam < 0 {
            return;
        }
        // the beam axis at the slider: the nearest segment of the deformed centreline
        let b = beam as usize;
        let nn = self.scene.beams.get(b).map_or(0, |x| x.nodes.len());
        let mut best = (f64::INFINITY, [1.0, 0.0]);
        for k in 1..nn {
            let (p, q) = (self.node(b, k - 1, f), self.node(b, k, f));
            let d = sub(q, p);
            let len2 = dot(d, d);
            if len2 <= 0.0 {
                continue;
            }
            let s = (dot(sub(c, p), d) / len2).clamp(0.0, 1.0);
            let dist = norm(sub(c, add(p, mul(d, s))));
            if dist < best.0 {
                best = (dist, mul(d, 1.0 / len2.sqrt()));
            }
        }
        let left = rot(best.1, std::f64::consts::FRAC_PI_2);
        // upper face: the slider is on the left of the axis and pushes the beam to the right
        let side = match item.params.get("face").and_then(Value::as_str) {
            Some("lower") => -1.0,
            _ => 1.0,
        };
        arrows.push(Shape::Arrow {
            tail: sub(c, mul(left, side * h / 2.0)),
            dir: mul(left, -side),
            force: force / self.fmax,
        });
    }

    // -----------------------------------------------------------------------------------------
    // Drawing

    /// Width of the parts' bars, px.
    fn bar(&self) -> f64 {
        (self.view.width as f64 / 100.0).max(4.0)
    }

    /// Output frame `i` drawn.
    fn frame(&self, i: usize) -> Pixmap {
        let f = self.picks[i];
        let v = &self.view;
        let mut pm = Pixmap::new(v.width, v.height).expect("the image size is checked");
        pm.fill(Color::from_rgba8(
            BACKGROUND[0],
            BACKGROUND[1],
            BACKGROUND[2],
            255,
        ));
        for s in self.shapes(f) {
            self.draw(&mut pm, &s);
        }
        let scale = ((v.width as f64 / 400.0).round() as u32).max(1);
        let pad = 3 * scale as i64;
        let t = self.frames.t.at(f);
        text(
            &mut pm,
            &format!("t = {:.*} s", self.decimals, t),
            pad,
            pad,
            scale,
            false,
        );
        text(&mut pm, self.model, v.width as i64 - pad, pad, scale, true);
        let mut legend = Vec::new();
        if self.mc > 1.0 && self.scene.items.iter().any(|i| i.section == "clearance") {
            legend.push(format!("clearance x{}", short(self.mc)));
        }
        if self.md > 1.0 && !self.scene.beams.is_empty() {
            legend.push(format!("deformation x{}", short(self.md)));
        }
        if self.fmax > 0.0 {
            legend.push(format!("longest arrow = {} N", short(self.fmax)));
        }
        if !legend.is_empty() {
            let y = v.height as i64 - pad - 7 * scale as i64;
            text(&mut pm, &legend.join("   "), pad, y, scale, false);
        }
        pm
    }

    fn draw(&self, pm: &mut Pixmap, s: &Shape) {
        let v = &self.view;
        let bar = self.bar();
        let id = Transform::identity();
        match s {
            Shape::Ground(p) => {
                let [x, y] = v.px(*p);
                let g = 0.9 * bar;
                polygon(
                    pm,
                    &[[x, y], [x + g, y + 1.5 * g], [x - g, y + 1.5 * g]],
                    LIGHT,
                    INK,
                    1.2,
                );
                let yb = y + 1.5 * g;
                polyline(pm, &[[x - 1.7 * g, yb], [x + 1.7 * g, yb]], INK, 1.5);
                for k in 0..5 {
                    let xs = x - 1.5 * g + 0.75 * g * k as f64;
                    polyline(pm, &[[xs, yb], [xs - 0.6 * g, yb + 0.7 * g]], INK, 1.0);
                }
            }
            Shape::Rail { at, dir } => {
                let reach = (v.width + v.height) as f64 / v.scale * 2.0;
                let a = v.px(sub(*at, mul(*dir, reach)));
                let b = v.px(add(*at, mul(*dir, reach)));
                if finite(a) && finite(b) {
                    let mut st = stroke(1.5);
                    st.line_cap = LineCap::Butt;
                    st.dash = StrokeDash::new(vec![8.0, 5.0], 0.0);
                    if let Some(path) = path(&[a, b], false) {
                        pm.stroke_path(&path, &paint(GREY), &st, id, None);
                    }
                }
            }
            Shape::Beam { nodes, depth } => {
                let pts: Vec<P> = nodes.iter().map(|p| v.px(*p)).collect();
                let w = (depth * v.scale).max(3.0);
                polyline(pm, &pts, BEAM_EDGE, w + 2.0);
                polyline(pm, &pts, BEAM_FILL, w);
                polyline(pm, &pts, BEAM_EDGE, 1.0);
            }
            Shape::Body {
                points,
                theta,
                bearing,
            } => {
                let pts: Vec<P> = points.iter().map(|p| v.px(*p)).collect();
                if pts.len() == 1 {
                    let half = (1.5 * bar).max(1.35 * bearing * v.scale);
                    let corners: Vec<P> = rect_corners([0.0, 0.0], *theta, [2.0 * half; 2])
                        .iter()
                        .map(|q| [pts[0][0] + q[0], pts[0][1] - q[1]])
                        .collect();
                    polygon(pm, &corners, PART_FILL, PART_EDGE, 1.5);
                } else {
                    let h = hull(pts);
                    polyline_closed(pm, &h, PART_EDGE, bar + 3.0);
                    polyline_closed(pm, &h, PART_FILL, bar);
                    if h.len() >= 3 {
                        if let Some(path) = path(&h, true) {
                            pm.fill_path(&path, &paint(PART_FILL), FillRule::Winding, id, None);
                        }
                    }
                }
            }
            Shape::Rect { c, angle, size } => {
                let pts: Vec<P> = rect_corners(*c, *angle, *size)
                    .iter()
                    .map(|p| v.px(*p))
                    .collect();
                polygon(pm, &pts, SLIDER_FILL, INK, 1.2);
            }
            Shape::Line { a, b } => polyline(pm, &[v.px(*a), v.px(*b)], INK, 2.0),
            Shape::Bearing {
                c,
                r,
                rj,
                off,
                force,
            } => {
                // a joint smaller than 8 px on screen is enlarged (with its clearance)
                let k = (8.0 / (r * v.scale)).max(1.0);
                let cp = v.px(*c);
                let rb = r * v.scale * k;
                circle(pm, cp, rb, Some(BACKGROUND), Some((BEARING, 2.0)));
                let jo = [off[0] * v.scale * k, -off[1] * v.scale * k];
                let jc = add(cp, jo);
                circle(
                    pm,
                    jc,
                    (rj * v.scale * k).max(1.5),
                    Some(JOURNAL_FILL),
                    Some((JOURNAL_EDGE, 1.2)),
                );
                circle(pm, jc, 1.5, Some(JOURNAL_EDGE), None);
                if let Some(frac) = force {
                    let e = norm(jo);
                    if e > 0.0 {
                        let dir = mul(jo, 1.0 / e);
                        arrow(pm, add(cp, mul(dir, rb)), dir, frac * self.arrow_length());
                    }
                }
            }
            Shape::Pin(p) => {
                let r = (0.35 * bar).max(2.5);
                circle(pm, v.px(*p), r, Some(BACKGROUND), Some((INK, 1.5)));
            }
            Shape::Arrow { tail, dir, force } => {
                arrow(
                    pm,
                    v.px(*tail),
                    [dir[0], -dir[1]],
                    force * self.arrow_length(),
                );
            }
            Shape::Outline { lines, ground, on } => {
                let lines: Vec<(Vec<P>, bool)> = lines
                    .iter()
                    .map(|(pts, closed)| (pts.iter().map(|p| v.px(*p)).collect(), *closed))
                    .collect();
                let (fill, edge) = if *ground {
                    (GROUND_FILL, GREY)
                } else {
                    (SHAPE_FILL, PART_EDGE)
                };
                // the closed outlines filled as one path (the parts of a compound overlap
                // without a seam), a ground shape hatched at 45° every 7 px inside them
                if let Some(area) = closed_path(&lines) {
                    pm.fill_path(&area, &paint(fill), FillRule::Winding, id, None);
                    if *ground {
                        hatch(pm, &area, &lines);
                    }
                }
                let edge = if *on { ARROW } else { edge };
                for (pts, closed) in &lines {
                    let width = match (*on, *closed) {
                        (true, _) => 2.2,
                        (false, true) => 1.5,
                        (false, false) => 2.0,
                    };
                    if let Some(p) = path(pts, *closed && pts.len() >= 3) {
                        pm.stroke_path(&p, &paint(edge), &stroke(width), id, None);
                    }
                }
            }
        }
    }

    /// Length of the arrow of the largest normal force, px.
    fn arrow_length(&self) -> f64 {
        0.08 * self.view.width as f64
    }
}

/// A magnification or force in a few digits.
fn short(x: f64) -> String {
    if x >= 100.0 {
        return format!("{x:.0}");
    }
    let s = if x >= 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    };
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn path(pts: &[P], close: bool) -> Option<tiny_skia::Path> {
    if pts.is_empty() || !pts.iter().all(|p| finite(*p)) {
        return None;
    }
    let mut pb = PathBuilder::new();
    pb.move_to(pts[0][0] as f32, pts[0][1] as f32);
    for p in &pts[1..] {
        pb.line_to(p[0] as f32, p[1] as f32);
    }
    if pts.len() == 1 {
        pb.line_to(pts[0][0] as f32, pts[0][1] as f32);
    }
    if close {
        pb.close();
    }
    pb.finish()
}

/// The closed outlines of `lines` (pixels) as one path of polygons; none without one.
fn closed_path(lines: &[(Vec<P>, bool)]) -> Option<tiny_skia::Path> {
    let mut pb = PathBuilder::new();
    for (pts, _) in lines
        .iter()
        .filter(|(pts, closed)| *closed && pts.len() >= 3)
    {
        if !pts.iter().all(|p| finite(*p)) {
            continue;
        }
        pb.move_to(pts[0][0] as f32, pts[0][1] as f32);
        for p in &pts[1..] {
            pb.line_to(p[0] as f32, p[1] as f32);
        }
        pb.close();
    }
    pb.finish()
}

/// Hatch the inside of `area` (the closed outlines of `lines`, pixels): grey lines at 45° every
/// 7 px across their box (only the part on the image).
fn hatch(pm: &mut Pixmap, area: &tiny_skia::Path, lines: &[(Vec<P>, bool)]) {
    let (mut x0, mut y0, mut x1, mut y1) = (
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    );
    for (pts, _) in lines.iter().filter(|(_, closed)| *closed) {
        for p in pts.iter().filter(|p| finite(**p)) {
            (x0, y0) = (x0.min(p[0]), y0.min(p[1]));
            (x1, y1) = (x1.max(p[0]), y1.max(p[1]));
        }
    }
    let (x0, y0) = (x0.max(-10.0), y0.max(-10.0));
    let (x1, y1) = (
        x1.min(pm.width() as f64 + 10.0),
        y1.min(pm.height() as f64 + 10.0),
    );
    if !(x1 > x0 && y1 > y0) {
        return;
    }
    let Some(mut mask) = tiny_skia::Mask::new(pm.width(), pm.height()) else {
        return;
    };
    mask.fill_path(area, FillRule::Winding, true, Transform::identity());
    let mut pb = PathBuilder::new();
    let mut d = x0 - (y1 - y0);
    while d < x1 {
        pb.move_to(d as f32, y1 as f32);
        pb.line_to((d + (y1 - y0)) as f32, y0 as f32);
        d += 7.0;
    }
    if let Some(p) = pb.finish() {
        let mut st = stroke(1.0);
        st.line_cap = LineCap::Butt;
        pm.stroke_path(&p, &paint(GREY), &st, Transform::identity(), Some(&mask));
    }
}

fn polyline(pm: &mut Pixmap, pts: &[P], c: Rgb, width: f64) {
    if let Some(p) = path(pts, false) {
        pm.stroke_path(&p, &paint(c), &stroke(width), Transform::identity(), None);
    }
}

fn polyline_closed(pm: &mut Pixmap, pts: &[P], c: Rgb, width: f64) {
    if let Some(p) = path(pts, pts.len() >= 3) {
        pm.stroke_path(&p, &paint(c), &stroke(width), Transform::identity(), None);
    }
}

fn polygon(pm: &mut Pixmap, pts: &[P], fill: Rgb, edge: Rgb, width: f64) {
    if let Some(p) = path(pts, true) {
        let id = Transform::identity();
        pm.fill_path(&p, &paint(fill), FillRule::Winding, id, None);
        pm.stroke_path(&p, &paint(edge), &stroke(width), id, None);
    }
}

fn circle(pm: &mut Pixmap, c: P, r: f64, fill: Option<Rgb>, edge: Option<(Rgb, f64)>) {
    if !finite(c) || !r.is_finite() || r <= 0.0 {
        return;
    }
    let Some(p) = PathBuilder::from_circle(c[0] as f32, c[1] as f32, r as f32) else {
        return;
    };
    let id = Transform::identity();
    if let Some(fill) = fill {
        pm.fill_path(&p, &paint(fill), FillRule::Winding, id, None);
    }
    if let Some((e, w)) = edge {
        pm.stroke_path(&p, &paint(e), &stroke(w), id, None);
    }
}

/// An arrow from `tail` along the unit `dir` (pixel axes), `length` px long.
fn arrow(pm: &mut Pixmap, tail: P, dir: P, length: f64) {
    arrow_in(pm, tail, dir, length, ARROW);
}

/// [`arrow`] in colour `c`.
fn arrow_in(pm: &mut Pixmap, tail: P, dir: P, length: f64, c: Rgb) {
    if !finite(tail) || !finite(dir) || !length.is_finite() || length <= 0.0 {
        return;
    }
    let head = length.min(10.0);
    let tip = add(tail, mul(dir, length));
    let base = sub(tip, mul(dir, head));
    if length > head {
        polyline(pm, &[tail, base], c, 2.5);
    }
    let n = [-dir[1], dir[0]];
    let w = 0.45 * head;
    polygon(
        pm,
        &[tip, add(base, mul(n, w)), sub(base, mul(n, w))],
        c,
        c,
        1.0,
    );
}

/// Convex hull (counter-clockwise in a right-handed frame), collinear points dropped; fewer than
/// three distinct points come back as they are.
fn hull(mut p: Vec<P>) -> Vec<P> {
    p.retain(|q| finite(*q));
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup_by(|a, b| (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9);
    if p.len() < 3 {
        return p;
    }
    let cross = |o: P, a: P, b: P| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let chain = |pts: &mut dyn Iterator<Item = P>| {
        let mut h: Vec<P> = Vec::new();
        for q in pts {
            while h.len() >= 2 && cross(h[h.len() - 2], h[h.len() - 1], q) <= 0.0 {
                h.pop();
            }
            h.push(q);
        }
        h.pop();
        h
    };
    let mut lower = chain(&mut p.iter().copied());
    let upper = chain(&mut p.iter().rev().copied());
    lower.extend(upper);
    lower
}

// ---------------------------------------------------------------------------------------------
// Text: a 5×7 bitmap font (rows top to bottom, bit 4 the leftmost column)

const FONT: &[(char, [u8; 7])] = &[
    ('0', [0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e]),
    ('1', [0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e]),
    ('2', [0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f]),
    ('3', [0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e]),
    ('4', [0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02]),
    ('5', [0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e]),
    ('6', [0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e]),
    ('7', [0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08]),
    ('8', [0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e]),
    ('9', [0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c]),
    ('.', [0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c]),
    (',', [0x00, 0x00, 0x00, 0x00, 0x0c, 0x04, 0x08]),
    (':', [0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00]),
    ('=', [0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00]),
    ('-', [0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00]),
    ('+', [0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00]),
    ('_', [0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1f]),
    ('/', [0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00]),
    ('(', [0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02]),
    (')', [0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08]),
    (' ', [0x00; 7]),
    ('N', [0x11, 0x19, 0x15, 0x13, 0x11, 0x11, 0x11]),
    ('a', [0x00, 0x00, 0x0e, 0x01, 0x0f, 0x11, 0x0f]),
    ('b', [0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1e]),
    ('c', [0x00, 0x00, 0x0e, 0x10, 0x10, 0x11, 0x0e]),
    ('d', [0x01, 0x01, 0x0d, 0x13, 0x11, 0x11, 0x0f]),
    ('e', [0x00, 0x00, 0x0e, 0x11, 0x1f, 0x10, 0x0e]),
    ('f', [0x06, 0x09, 0x08, 0x1c, 0x08, 0x08, 0x08]),
    ('g', [0x00, 0x0f, 0x11, 0x11, 0x0f, 0x01, 0x0e]),
    ('h', [0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11]),
    ('i', [0x04, 0x00, 0x0c, 0x04, 0x04, 0x04, 0x0e]),
    ('j', [0x02, 0x00, 0x06, 0x02, 0x02, 0x12, 0x0c]),
    ('k', [0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12]),
    ('l', [0x0c, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e]),
    ('m', [0x00, 0x00, 0x1a, 0x15, 0x15, 0x11, 0x11]),
    ('n', [0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11]),
    ('o', [0x00, 0x00, 0x0e, 0x11, 0x11, 0x11, 0x0e]),
    ('p', [0x00, 0x00, 0x1e, 0x11, 0x1e, 0x10, 0x10]),
    ('q', [0x00, 0x00, 0x0d, 0x13, 0x0f, 0x01, 0x01]),
    ('r', [0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10]),
    ('s', [0x00, 0x00, 0x0e, 0x10, 0x0e, 0x01, 0x1e]),
    ('t', [0x08, 0x08, 0x1c, 0x08, 0x08, 0x09, 0x06]),
    ('u', [0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0d]),
    ('v', [0x00, 0x00, 0x11, 0x11, 0x11, 0x0a, 0x04]),
    ('w', [0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0a]),
    ('x', [0x00, 0x00, 0x11, 0x0a, 0x04, 0x0a, 0x11]),
    ('y', [0x00, 0x00, 0x11, 0x11, 0x0f, 0x01, 0x0e]),
    ('z', [0x00, 0x00, 0x1f, 0x02, 0x04, 0x08, 0x1f]),
];

/// The glyph of a character (capitals without a glyph drawn as small letters; unknown
/// characters as a box).
fn glyph(c: char) -> [u8; 7] {
    let find = |c: char| FONT.iter().find(|(g, _)| *g == c);
    find(c)
        .or_else(|| find(c.to_ascii_lowercase()))
        .map_or([0x1f, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1f], |(_, b)| *b)
}

/// Write `s` with its top-left corner at pixel (x, y) (`right`: its top-right corner), each
/// font pixel `scale` px wide, in ink on a background box.
fn text(pm: &mut Pixmap, s: &str, x: i64, y: i64, scale: u32, right: bool) {
    let sc = scale as i64;
    let n = s.chars().count() as i64;
    if n == 0 {
        return;
    }
    let w = (6 * n - 1) * sc;
    let x = if right { x - w } else { x };
    let (width, height) = (pm.width() as i64, pm.height() as i64);
    let mut put = |px: i64, py: i64, c: Rgb| {
        if (0..width).contains(&px) && (0..height).contains(&py) {
            let k = ((py * width + px) * 4) as usize;
            pm.data_mut()[k..k + 4].copy_from_slice(&[c[0], c[1], c[2], 255]);
        }
    };
    for py in y - sc..y + 8 * sc {
        for px in x - sc..x + w + sc {
            put(px, py, BACKGROUND);
        }
    }
    for (i, ch) in s.chars().enumerate() {
        let g = glyph(ch);
        for (row, bits) in g.iter().enumerate() {
            for col in 0..5 {
                if bits & (0x10 >> col) != 0 {
                    for dy in 0..sc {
                        for dx in 0..sc {
                            let px = x + (6 * i as i64 + col) * sc + dx;
                            put(px, y + row as i64 * sc + dy, INK);
                        }
                    }
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// GIF

/// A fixed palette: the drawing's 15 colours, two blends of each with the background
/// (anti-aliased edges) and a transparent entry last. (Blends over the part and beam fills too
/// made the slider–crank GIF 9 % and the dual guide's 28 % larger for little gain.)
struct Palette {
    rgb: Vec<Rgb>,
    /// Nearest entry per 5-bit RGB cell.
    lut: Vec<u8>,
    /// The entry exactly equal to a colour of the cell, when there is one.
    exact: Vec<Option<u8>>,
    transparent: u8,
}

impl Palette {
    fn new() -> Self {
        let mut rgb: Vec<Rgb> = COLOURS.to_vec();
        let blend = |a: Rgb, b: Rgb, s: f64| -> Rgb {
            [0, 1, 2].map(|k| (a[k] as f64 * (1.0 - s) + b[k] as f64 * s).round() as u8)
        };
        for &c in &COLOURS[1..] {
            for s in [1.0 / 3.0, 2.0 / 3.0] {
                let b = blend(c, BACKGROUND, s);
                if !rgb.contains(&b) {
                    rgb.push(b);
                }
            }
        }
        rgb.truncate(255);
        let cell = |c: Rgb| {
            ((c[0] as usize >> 3) << 10) | ((c[1] as usize >> 3) << 5) | (c[2] as usize >> 3)
        };
        let mut exact = vec![None; 1 << 15];
        for (k, c) in rgb.iter().enumerate() {
            exact[cell(*c)].get_or_insert(k as u8);
        }
        let lut = (0..1usize << 15)
            .map(|i| {
                let q = [(i >> 10) & 31, (i >> 5) & 31, i & 31].map(|v| (v << 3 | 4) as f64);
                let mut best = (f64::INFINITY, 0u8);
                for (k, c) in rgb.iter().enumerate() {
                    let d: f64 = (0..3)
                        .map(|j| {
                            let w = [3.0, 4.0, 2.0][j];
                            w * (q[j] - c[j] as f64).powi(2)
                        })
                        .sum();
                    if d < best.0 {
                        best = (d, k as u8);
                    }
                }
                best.1
            })
            .collect();
        let transparent = rgb.len() as u8;
        rgb.push([0, 0, 0]);
        Palette {
            rgb,
            lut,
            exact,
            transparent,
        }
    }

    /// Palette indices of an opaque RGBA image.
    fn index(&self, rgba: &[u8], out: &mut Vec<u8>) {
        out.clear();
        out.extend(rgba.chunks_exact(4).map(|p| {
            let c =
                ((p[0] as usize >> 3) << 10) | ((p[1] as usize >> 3) << 5) | (p[2] as usize >> 3);
            match self.exact[c] {
                Some(k) if self.rgb[k as usize] == [p[0], p[1], p[2]] => k,
                _ => self.lut[c],
            }
        }));
    }

    fn bytes(&self) -> Vec<u8> {
        self.rgb.iter().flatten().copied().collect()
    }
}

/// Writes the frames of a looping GIF, each frame as the rectangle that changed.
struct GifSink<W: Write> {
    enc: gif::Encoder<W>,
    palette: Palette,
    prev: Vec<u8>,
    cur: Vec<u8>,
    width: usize,
    height: usize,
    fps: f64,
    frame: usize,
}

impl<W: Write> GifSink<W> {
    fn new(w: W, width: u32, height: u32, fps: f64) -> Result<Self, String> {
        let palette = Palette::new();
        let mut enc = gif::Encoder::new(w, width as u16, height as u16, &palette.bytes())
            .map_err(|e| e.to_string())?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(|e| e.to_string())?;
        Ok(GifSink {
            enc,
            palette,
            prev: Vec::new(),
            cur: Vec::new(),
            width: width as usize,
            height: height as usize,
            fps,
            frame: 0,
        })
    }

    fn push(&mut self, pm: &Pixmap) -> Result<(), String> {
        let (w, h) = (self.width, self.height);
        self.palette.index(pm.data(), &mut self.cur);
        // delays in 1/100 s, rounded so that they add up to the frame times
        let at = |k: usize| (k as f64 * 100.0 / self.fps).round() as i64;
        let delay = (at(self.frame + 1) - at(self.frame)).clamp(1, 65535) as u16;
        let mut frame = gif::Frame {
            delay,
            dispose: gif::DisposalMethod::Keep,
            ..gif::Frame::default()
        };
        let buffer: Vec<u8>;
        if self.prev.is_empty() {
            frame.width = w as u16;
            frame.height = h as u16;
            frame.buffer = Cow::Borrowed(&self.cur);
        } else {
            // the rectangle that changed; unchanged pixels in it are transparent
            let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
            for y in 0..h {
                let row = y * w;
                let (a, b) = (&self.prev[row..row + w], &self.cur[row..row + w]);
                if a == b {
                    continue;
                }
                let first = (0..w).find(|&x| a[x] != b[x]).unwrap_or(0);
                let last = (0..w).rev().find(|&x| a[x] != b[x]).unwrap_or(0);
                x0 = x0.min(first);
                x1 = x1.max(last + 1);
                y0 = y0.min(y);
                y1 = y1.max(y + 1);
            }
            if x1 <= x0 {
                (x0, y0, x1, y1) = (0, 0, 1, 1);
            }
            let t = self.palette.transparent;
            buffer = (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| y * w + x))
                .map(|k| {
                    if self.prev[k] == self.cur[k] {
                        t
                    } else {
                        self.cur[k]
                    }
                })
                .collect();
            frame.left = x0 as u16;
            frame.top = y0 as u16;
            frame.width = (x1 - x0) as u16;
            frame.height = (y1 - y0) as u16;
            frame.transparent = Some(t);
            frame.buffer = Cow::Borrowed(&buffer);
        }
        self.enc.write_frame(&frame).map_err(|e| e.to_string())?;
        std::mem::swap(&mut self.prev, &mut self.cur);
        self.frame += 1;
        Ok(())
    }

    fn finish(self) -> Result<W, String> {
        self.enc.into_inner().map_err(|e| e.to_string())
    }
}

// ---------------------------------------------------------------------------------------------
// MP4 through ffmpeg

struct Mp4Sink {
    child: std::process::Child,
    path: PathBuf,
}

impl Mp4Sink {
    fn new(path: &Path, width: u32, height: u32, fps: f64) -> Result<Self, String> {
        let child = std::process::Command::new("ffmpeg")
            .args(["-hide_banner", "-loglevel", "error", "-y"])
            .args(["-f", "rawvideo", "-pix_fmt", "rgba"])
            .args(["-s", &format!("{width}x{height}")])
            .args(["-framerate", &fps.to_string(), "-i", "-"])
            .args([
                "-c:v",
                "libx264",
                "-pix_fmt",
                "yuv420p",
                "-movflags",
                "+faststart",
            ])
            .arg(path)
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::null())
            .spawn()
            .map_err(|e| {
                if e.kind() == std::io::ErrorKind::NotFound {
                    "--mp4 needs ffmpeg, which is not on PATH: install ffmpeg (e.g. `apt install \
                     ffmpeg`, `brew install ffmpeg`) or write a GIF with --gif, which needs no \
                     external program"
                        .to_string()
                } else {
                    format!("cannot start ffmpeg: {e}")
                }
            })?;
        Ok(Mp4Sink {
            child,
            path: path.to_path_buf(),
        })
    }

    fn push(&mut self, pm: &Pixmap) -> Result<(), String> {
        let stdin = self.child.stdin.as_mut().ok_or("ffmpeg has no input")?;
        // the background is opaque: premultiplied RGBA is plain RGBA
        stdin
            .write_all(pm.data())
            .map_err(|e| format!("ffmpeg stopped reading the frames ({e}); see its message above"))
    }

    fn finish(mut self) -> Result<(), String> {
        drop(self.child.stdin.take());
        let status = self.child.wait().map_err(|e| e.to_string())?;
        if status.success() {
            Ok(())
        } else {
            Err(format!(
                "ffmpeg failed ({status}) writing {}; see its message above",
                self.path.display()
            ))
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The command

// ---------------------------------------------------------------------------------------------
// Spatial scenes (`--view`): an orthographic projection drawn with the 2-D primitives above.
// A hand projection (no 3-D library): bodies as thick lines through their attachment points,
// joints as dots with their axes, sockets as circles with the ball offset magnified, journals
// as their bore (a band with round ends) and the journal with its radial offset and tilt
// magnified, contact force arrows, the traced point's path; everything sorted far to near (painter's order).

/// A named view of a spatial scene (world y up, as on the 3-D page).
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum ViewName {
    /// From (1, 1, 1), y up.
    #[default]
    Iso,
    /// From +z: x right, y up (the plane of a planar model).
    Front,
    /// From +y: x right, −z up.
    Top,
    /// From +x: −z right, y up.
    Side,
}

impl ViewName {
    /// Unit world directions of the image's right, its up and towards the viewer (a
    /// right-handed triple: right × up = towards).
    fn axes(self) -> [[f64; 3]; 3] {
        let (a, b, c) = (
            std::f64::consts::FRAC_1_SQRT_2,
            1.0 / 6f64.sqrt(),
            1.0 / 3f64.sqrt(),
        );
        match self {
            // z up (gravity along −z in spatial model files); rows: screen right, screen up,
            // towards the viewer
            ViewName::Iso => [[-a, a, 0.0], [-b, -b, 2.0 * b], [c, c, c]],
            ViewName::Front => [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]],
            ViewName::Top => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            ViewName::Side => [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]],
        }
    }

    fn label(self) -> &'static str {
        match self {
            ViewName::Iso => "iso",
            ViewName::Front => "front",
            ViewName::Top => "top",
            ViewName::Side => "side",
        }
    }
}

/// Colours of the bodies in turn (all in the GIF palette).
const BODY_COLOURS: [Rgb; 4] = [PART_EDGE, BEARING, BEAM_EDGE, JOURNAL_EDGE];

/// One thing drawn in a spatial frame (pixels), at its depth towards the viewer (m).
enum Mark {
    Line(Vec<P>, Rgb, f64),
    Fill(Vec<P>, Rgb),
    Dot(P, f64, Rgb, Rgb),
    Arrow(P, P, f64, Rgb),
}

/// A spatial scene's frames drawn from a named view.
pub(crate) struct SpatialAnimation {
    view: SpatialView,
    model: String,
    name: ViewName,
    picks: Vec<usize>,
    /// Clearance magnification.
    mag: f64,
    /// Largest contact force over the frames shown, N.
    fmax: f64,
    px: View,
    decimals: usize,
    /// The contact shapes, with their edges found once.
    shapes: Vec<ShapeMesh>,
}

/// A contact shape's surface for drawing: the triangles in its body's frame, their normals, and
/// the edges with the triangles beside them (the silhouette and the creases are drawn).
struct ShapeMesh {
    body: Option<String>,
    /// Vertices in the body's centre-of-mass frame, m.
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[usize; 3]>,
    /// Unit outward normals of the triangles, body frame.
    normals: Vec<[f64; 3]>,
    /// (vertex a, vertex b, triangle on one side, triangle on the other side if any, a crease:
    /// the normals differ by more than 20°).
    edges: Vec<(usize, usize, usize, Option<usize>, bool)>,
}

impl ShapeMesh {
    fn new(s: &ShapeDraw) -> Self {
        let place = Pose {
            x: s.at,
            q: s.rotation,
        };
        let vertices: Vec<[f64; 3]> = (s.vertices.chunks_exact(3))
            .map(|v| place.point([0, 1, 2].map(|k| f64::from(v[k]))))
            .collect();
        let n = vertices.len();
        let triangles: Vec<[usize; 3]> = (s.triangles.chunks_exact(3))
            .map(|t| [0, 1, 2].map(|k| t[k] as usize))
            .filter(|t| t.iter().all(|&k| k < n))
            .collect();
        let normals = (triangles.iter())
            .map(|t| {
                let [a, b, c] = t.map(|k| vertices[k]);
                unit3(cross3(sub3(b, a), sub3(c, a)))
            })
            .collect::<Vec<_>>();
        let mut sides: std::collections::BTreeMap<(usize, usize), Vec<usize>> =
            std::collections::BTreeMap::new();
        for (i, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                sides.entry((a.min(b), a.max(b))).or_default().push(i);
            }
        }
        let crease = 20f64.to_radians().cos();
        let edges = (sides.into_iter())
            .map(|((a, b), ts)| {
                let other = ts.get(1).copied();
                let sharp = other.is_some_and(|o| dot3(normals[ts[0]], normals[o]) < crease);
                (a, b, ts[0], other, sharp)
            })
            .collect();
        ShapeMesh {
            body: s.body.clone(),
            vertices,
            triangles,
            normals,
            edges,
        }
    }
}

/// The animation of `scene` over `results` seen from `view` (what `clr animate --view` draws
/// for a spatial page), for a caller that holds the results rather than a report page.
///
/// # Errors
/// The scene does not fit the results, or no frame is inside `--start … --end`.
#[allow(dead_code)] // for the spatial run's `clr run` (issue 31); the tests call it meanwhile
pub(crate) fn animate_spatial(
    scene: SpatialScene,
    results: &clr_mbd::Results,
    view: ViewName,
    settings: &Settings,
    model: &str,
) -> Result<SpatialAnimation, String> {
    let t = results.column("t").unwrap_or_default();
    let rows = clr_sim::report::frames::select(&t, 20_000);
    let sv = SpatialView::new(scene, results, &rows).map_err(|e| e.to_string())?;
    SpatialAnimation::new(sv, model, view, settings)
}

impl SpatialAnimation {
    /// Choose the frames, the magnification and the pixel mapping.
    fn new(view: SpatialView, model: &str, name: ViewName, s: &Settings) -> Result<Self, String> {
        let count = ((s.fps * s.duration).round() as usize).max(1);
        let picks = pick_frames(&view.frames.t, s.start, s.end, count);
        if picks.is_empty() {
            return Err("no frame of the spatial run inside --start … --end".into());
        }
        // as on the page: the clearance drawn as 8 % of the socket (bore) radius, at least 1
        let sockets = (view.scene.sockets.iter()).map(|k| (k.socket_radius, k.ball_radius));
        let bores = (view.scene.journals.iter()).map(|j| (j.bearing_radius, j.journal_radius));
        let auto = sockets
            .chain(bores)
            .filter(|(r, ri)| r > ri)
            .map(|(r, ri)| 0.08 * r / (r - ri))
            .fold(f64::INFINITY, f64::min);
        let mag =
            s.clearance_magnification
                .unwrap_or(if auto.is_finite() { auto.max(1.0) } else { 1.0 });
        let shapes = view.scene.shapes.iter().map(ShapeMesh::new).collect();
        let mut a = SpatialAnimation {
            view,
            model: model.to_string(),
            name,
            picks,
            mag,
            fmax: 0.0,
            px: View::fit([0.0, 0.0], [1.0, 1.0], s.width),
            decimals: 3,
            shapes,
        };
        let mut pts = Vec::new();
        for &f in &a.picks {
            for s in 0..a.view.scene.sockets.len() {
                let v = a.view.frames.socket(s, f);
                a.fmax = a.fmax.max(v[3].abs()).max(norm3([v[4], v[5], v[6]]));
            }
            for j in 0..a.view.scene.journals.len() {
                let v = a.view.frames.journal(j, f);
                a.fmax = v.iter().fold(a.fmax, |m, x| m.max(x.abs()));
            }
            pts.extend(a.world_points(f).into_iter().map(|p| a.project(p)));
        }
        a.px = View::fit_points(pts, s.width);
        a.decimals = time_decimals(&a.view.frames.t, &a.picks);
        Ok(a)
    }

    /// The image plane coordinates (m) of a world point.
    fn project(&self, p: [f64; 3]) -> P {
        let [r, u, _] = self.name.axes();
        [dot3(p, r), dot3(p, u)]
    }

    fn depth(&self, p: [f64; 3]) -> f64 {
        dot3(p, self.name.axes()[2])
    }

    fn pose(&self, body: Option<&str>, f: usize) -> Pose {
        self.view.frames.pose_of(self.view.body(body), f)
    }

    /// Every world point drawn in frame `f` (for the bounds): body points and centres, joints,
    /// socket centres with their radius, the trace.
    fn world_points(&self, f: usize) -> Vec<[f64; 3]> {
        let sc = &self.view.scene;
        let mut out = Vec::new();
        for (k, b) in sc.bodies.iter().enumerate() {
            let pose = self.view.frames.pose_of(Some(k), f);
            out.push(pose.x);
            out.extend(b.points.iter().map(|&p| pose.point(p)));
        }
        for j in &sc.joints {
            out.push(self.pose(j.body.as_deref(), f).point(j.at));
        }
        for k in &sc.sockets {
            let c = self.pose(k.socket_body.as_deref(), f).point(k.socket_at);
            out.extend([-1.0, 1.0].map(|s| c.map(|v| v + s * k.socket_radius)));
        }
        for m in &self.shapes {
            let pose = self.pose(m.body.as_deref(), f);
            out.extend(m.vertices.iter().map(|&v| pose.point(v)));
        }
        for j in &sc.journals {
            let (c, u) = self.bore(j, f);
            for s in [-1.0, 1.0] {
                let end = axpy(c, 0.5 * s * j.bearing_length, u);
                out.extend([-1.0, 1.0].map(|s| end.map(|v| v + s * j.bearing_radius)));
            }
        }
        out.extend(
            self.view
                .frames
                .trace
                .chunks_exact(3)
                .map(|c| [0, 1, 2].map(|k| f64::from(c[k]))),
        );
        out
    }

    /// Pixels of a world point.
    fn to_px(&self, p: [f64; 3]) -> P {
        self.px.px(self.project(p))
    }

    /// Pixels of a world direction (unit in the image, or zero).
    fn dir_px(&self, d: [f64; 3]) -> P {
        let q = self.project(d);
        let n = norm(q);
        if n > 0.0 {
            [q[0] / n, -q[1] / n]
        } else {
            [0.0, 0.0]
        }
    }

    /// What frame `f` draws, with depths.
    fn marks(&self, f: usize) -> Vec<(f64, Mark)> {
        let sc = &self.view.scene;
        let mut out = Vec::new();
        let o = [0.0; 3];
        let axis = 0.12 * self.px.width as f64 / self.px.scale;
        for (k, c) in [JOURNAL_EDGE, BEARING, PART_EDGE].into_iter().enumerate() {
            let e = std::array::from_fn(|i| if i == k { axis } else { 0.0 });
            out.push((
                self.depth(e) / 2.0,
                Mark::Line(vec![self.to_px(o), self.to_px(e)], c, 1.5),
            ));
        }
        for (k, b) in sc.bodies.iter().enumerate() {
            let pose = self.view.frames.pose_of(Some(k), f);
            let c = BODY_COLOURS[k % BODY_COLOURS.len()];
            let pts: Vec<[f64; 3]> = b.points.iter().map(|&p| pose.point(p)).collect();
            // a closed loop through three or more points, a bar through two
            let segments = if pts.len() >= 3 {
                pts.len()
            } else {
                pts.len().saturating_sub(1)
            };
            for i in 0..segments {
                let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
                let d = 0.5 * (self.depth(a) + self.depth(b));
                out.push((d, Mark::Line(vec![self.to_px(a), self.to_px(b)], c, 6.0)));
            }
            for &p in &pts {
                let r = if pts.len() == 1 { 7.0 } else { 4.0 };
                out.push((self.depth(p), Mark::Dot(self.to_px(p), r, c, c)));
            }
            out.push((
                self.depth(pose.x),
                Mark::Dot(self.to_px(pose.x), 3.5, INK, INK),
            ));
        }
        for j in &sc.joints {
            let pose = self.pose(j.body.as_deref(), f);
            let at = pose.point(j.at);
            let p = self.to_px(at);
            if let Some(a) = j.axis {
                let d = self.dir_px(pose.direction(a));
                let l = 18.0;
                let line = vec![sub(p, mul(d, l)), add(p, mul(d, l))];
                out.push((self.depth(at), Mark::Line(line, INK, 1.5)));
            }
            out.push((self.depth(at), Mark::Dot(p, 5.0, LIGHT, INK)));
        }
        for (i, k) in sc.sockets.iter().enumerate() {
            out.extend(self.socket_marks(i, k, f));
        }
        for (i, j) in sc.journals.iter().enumerate() {
            out.extend(self.journal_marks(i, j, f));
        }
        for m in &self.shapes {
            out.extend(self.shape_marks(m, f));
        }
        out
    }

    /// A contact shape: its triangles filled, its silhouette and creases drawn. A shape on the
    /// ground (a floor, a guide) is scenery, drawn behind everything (depth −∞): one of its large
    /// triangles would otherwise sort in front of what stands on it.
    fn shape_marks(&self, m: &ShapeMesh, f: usize) -> Vec<(f64, Mark)> {
        let pose = self.pose(m.body.as_deref(), f);
        let world: Vec<[f64; 3]> = m.vertices.iter().map(|&v| pose.point(v)).collect();
        let towards = self.name.axes()[2];
        let facing: Vec<bool> = (m.normals.iter())
            .map(|&n| dot3(pose.direction(n), towards) >= 0.0)
            .collect();
        let ground = m.body.is_none();
        let (fill, edge) = if ground {
            (GROUND_FILL, GREY)
        } else {
            (SHAPE_FILL, PART_EDGE)
        };
        let depth = |p: [f64; 3]| {
            if ground {
                f64::NEG_INFINITY
            } else {
                self.depth(p)
            }
        };
        let mut out = Vec::new();
        for (i, t) in m.triangles.iter().enumerate() {
            if !facing[i] {
                continue;
            }
            let c = t.map(|k| world[k]);
            let centre = [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0);
            let pts = c.iter().map(|&p| self.to_px(p)).collect();
            out.push((depth(centre), Mark::Fill(pts, fill)));
        }
        for &(a, b, t, other, crease) in &m.edges {
            let silhouette = other.is_none_or(|o| facing[o] != facing[t]);
            let seen = facing[t] || other.is_some_and(|o| facing[o]);
            if silhouette || (crease && seen) {
                let mid = [0, 1, 2].map(|k| 0.5 * (world[a][k] + world[b][k]));
                let line = vec![self.to_px(world[a]), self.to_px(world[b])];
                // just in front of the triangles beside it
                out.push((depth(mid) + 1e-9, Mark::Line(line, edge, 1.5)));
            }
        }
        out
    }

    /// The bore centre and unit axis of journal `j` in frame `f` (world).
    fn bore(&self, j: &JournalDraw, f: usize) -> ([f64; 3], [f64; 3]) {
        let pose = self.pose(j.bearing_body.as_deref(), f);
        (
            pose.point(j.bearing_at),
            unit3(pose.direction(j.bearing_axis)),
        )
    }

    /// The journal's end centres in frame `f` (low, high along the bore axis), each with its
    /// radial offset from the bore axis magnified by `m` (world).
    fn journal_ends(&self, j: &JournalDraw, f: usize, m: f64) -> [[f64; 3]; 2] {
        let (c, u) = self.bore(j, f);
        let pose = self.pose(j.journal_body.as_deref(), f);
        let o = pose.point(j.journal_at);
        let mut a = unit3(pose.direction(j.journal_axis));
        if dot3(a, u) < 0.0 {
            a = a.map(|x| -x);
        }
        [-0.5, 0.5].map(|s| {
            let d = sub3(axpy(o, s * j.journal_length, a), c);
            let z = dot3(d, u);
            let radial = sub3(d, u.map(|x| x * z));
            axpy(axpy(c, z, u), m, radial)
        })
    }

    /// A journal joint: the bore as a band with round ends, the journal inside it with its radial
    /// offset and tilt magnified, and the group forces as arrows at the journal's ends (radial A
    /// and thrust − at the low end, radial B and thrust + at the high end).
    fn journal_marks(&self, i: usize, j: &JournalDraw, f: usize) -> Vec<(f64, Mark)> {
        let v = self.view.frames.journal(i, f);
        let (c, u) = self.bore(j, f);
        let cl = (j.bearing_radius - j.journal_radius).max(0.0);
        let m = if cl > 0.0 { self.mag } else { 1.0 };
        let grow = (8.0 / (j.bearing_radius * self.px.scale)).max(1.0);
        let rs = j.bearing_radius * self.px.scale * grow;
        let rj = ((j.bearing_radius - m * cl) * self.px.scale * grow).max(0.15 * rs);
        let d = self.depth(c);
        let rims = [-0.5, 0.5].map(|s| axpy(c, s * j.bearing_length, u));
        let rims_px = rims.map(|p| self.to_px(p));
        let mut out = vec![
            (d - 2e-9, band(rims_px, GREY, 2.0 * rs + 3.0)),
            (d - 1.5e-9, band(rims_px, LIGHT, 2.0 * rs)),
        ];
        let ends = self.journal_ends(j, f, m);
        let ends_px = ends.map(|p| self.to_px(p));
        let on = v.iter().any(|&x| x > 0.0);
        let edge = if on { ARROW } else { JOURNAL_EDGE };
        out.push((d - 1e-9, band(ends_px, edge, 2.0 * rj + 2.0)));
        out.push((d, band(ends_px, JOURNAL_FILL, 2.0 * rj)));
        if !(on && self.fmax > 0.0) {
            return out;
        }
        let per_n = 0.15 * self.px.width.min(self.px.height) as f64 / self.fmax;
        let axial = self.dir_px(u);
        for (k, end) in ends.iter().enumerate() {
            // radial: towards the bore axis (the force on the journal), from the journal's rim
            let z = dot3(sub3(*end, c), u);
            let out_dir = self.dir_px(sub3(*end, axpy(c, z, u)));
            if v[k] > 0.0 && norm(out_dir) > 0.0 {
                let tail = add(ends_px[k], mul(out_dir, rj));
                let arrow = Mark::Arrow(tail, mul(out_dir, -1.0), v[k] * per_n, ARROW);
                out.push((d + 1e-9, arrow));
            }
            // thrust − pushes the journal along +u at its low end, thrust + along −u at its high
            let sign = if k == 0 { 1.0 } else { -1.0 };
            if v[2 + k] > 0.0 && norm(axial) > 0.0 {
                let dir = mul(axial, sign);
                let arrow = Mark::Arrow(ends_px[k], dir, v[2 + k] * per_n, ARROW);
                out.push((d + 1e-9, arrow));
            }
        }
        out
    }

    /// A socket (circle), its ball at the magnified offset and the contact force arrows.
    fn socket_marks(&self, i: usize, k: &SocketDraw, f: usize) -> Vec<(f64, Mark)> {
        let v = self.view.frames.socket(i, f);
        let centre = self.pose(k.socket_body.as_deref(), f).point(k.socket_at);
        let c = (k.socket_radius - k.ball_radius).max(0.0);
        let m = if c > 0.0 { self.mag } else { 1.0 };
        // too small to see: drawn at 8 px at least, offsets scaled alike (as the page does)
        let grow = (8.0 / (k.socket_radius * self.px.scale)).max(1.0);
        let rs = k.socket_radius * self.px.scale * grow;
        let rb = ((k.socket_radius - m * c) * self.px.scale * grow).max(0.15 * rs);
        let e = [v[0], v[1], v[2]];
        let p = self.to_px(centre);
        let q = self.project(e);
        let b = [
            p[0] + m * grow * q[0] * self.px.scale,
            p[1] - m * grow * q[1] * self.px.scale,
        ];
        let on = v[7] > 0.5 || v[3] > 0.0;
        let d = self.depth(centre);
        let mut out = vec![
            (d - 1e-9, Mark::Dot(p, rs, BACKGROUND, GREY)),
            (
                d,
                Mark::Dot(b, rb, JOURNAL_FILL, if on { ARROW } else { JOURNAL_EDGE }),
            ),
        ];
        let n = self.dir_px(e);
        // no arrows where e points at the viewer (no direction in the image)
        if on && self.fmax > 0.0 && norm(n) > 0.0 {
            let tail = add(b, mul(n, rb));
            let per_n = 0.15 * self.px.width.min(self.px.height) as f64 / self.fmax;
            let normal = Mark::Arrow(tail, mul(n, -1.0), v[3] * per_n, ARROW);
            out.push((d + 1e-9, normal));
            let ft = [v[4], v[5], v[6]];
            let t = self.dir_px(ft);
            if norm(t) > 0.0 {
                let friction = Mark::Arrow(tail, t, norm3(ft) * per_n, BEAM_EDGE);
                out.push((d + 1e-9, friction));
            }
        }
        out
    }

    fn draw_mark(pm: &mut Pixmap, m: &Mark) {
        match m {
            Mark::Line(pts, c, w) => polyline(pm, pts, *c, *w),
            // the fill's own colour as a thin edge closes the cracks between triangles
            Mark::Fill(pts, c) => polygon(pm, pts, *c, *c, 0.75),
            Mark::Dot(p, r, fill, edge) => circle(pm, *p, *r, Some(*fill), Some((*edge, 1.5))),
            Mark::Arrow(tail, dir, len, c) => arrow_in(pm, *tail, *dir, *len, *c),
        }
    }
}

impl Movie for SpatialAnimation {
    fn size(&self) -> (u32, u32) {
        (self.px.width, self.px.height)
    }

    fn picks(&self) -> &[usize] {
        &self.picks
    }

    fn render(&self, i: usize) -> Pixmap {
        let f = self.picks[i];
        let v = &self.px;
        let mut pm = Pixmap::new(v.width, v.height).expect("the image size is checked");
        pm.fill(Color::from_rgba8(
            BACKGROUND[0],
            BACKGROUND[1],
            BACKGROUND[2],
            255,
        ));
        let trace: Vec<P> = (self.view.frames.trace.chunks_exact(3))
            .map(|c| self.to_px([0, 1, 2].map(|k| f64::from(c[k]))))
            .collect();
        polyline(&mut pm, &trace, SLIDER_FILL, 1.5);
        let mut marks = self.marks(f);
        marks.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, m) in &marks {
            Self::draw_mark(&mut pm, m);
        }
        let scale = ((v.width as f64 / 400.0).round() as u32).max(1);
        let pad = 3 * scale as i64;
        let t = self.view.frames.t[f];
        text(
            &mut pm,
            &format!("t = {:.*} s", self.decimals, t),
            pad,
            pad,
            scale,
            false,
        );
        text(&mut pm, &self.model, v.width as i64 - pad, pad, scale, true);
        let mut legend = vec![format!("{} view", self.name.label())];
        let joints = self.view.scene.sockets.len() + self.view.scene.journals.len();
        if self.mag > 1.0 && joints > 0 {
            legend.push(format!("clearance x{}", short(self.mag)));
        }
        if self.fmax > 0.0 {
            legend.push(format!("longest arrow = {} N", short(self.fmax)));
        }
        let y = v.height as i64 - pad - 7 * scale as i64;
        text(&mut pm, &legend.join("   "), pad, y, scale, false);
        pm
    }
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm3(a: [f64; 3]) -> f64 {
    dot3(a, a).sqrt()
}

/// A cylinder seen from the side: a round-ended band of `width` px between its end centres; a
/// disc when it is seen along its axis (a zero-length stroke draws nothing).
fn band(ends: [P; 2], c: Rgb, width: f64) -> Mark {
    if norm(sub(ends[1], ends[0])) < 0.5 {
        Mark::Dot(ends[0], 0.5 * width, c, c)
    } else {
        Mark::Line(ends.to_vec(), c, width)
    }
}

fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a + k·b.
fn axpy(a: [f64; 3], k: f64, b: [f64; 3]) -> [f64; 3] {
    [a[0] + k * b[0], a[1] + k * b[1], a[2] + k * b[2]]
}

/// a / |a| (a itself when zero).
fn unit3(a: [f64; 3]) -> [f64; 3] {
    let n = norm3(a);
    if n > 0.0 {
        a.map(|x| x / n)
    } else {
        a
    }
}

fn size_text(bytes: u64) -> String {
    if bytes >= 1 << 20 {
        format!("{:.1} MB", bytes as f64 / (1u64 << 20) as f64)
    } else {
        format!("{:.0} kB", (bytes as f64 / 1024.0).max(1.0))
    }
}

/// `clr animate`.
pub(crate) fn animate_command(a: &AnimateArgs) -> Result<(), CliError> {
    let settings = Settings::from_args(a).map_err(CliError::Input)?;
    let (file, page) = load(&a.run).map_err(CliError::Input)?;
    let anim: Box<dyn Movie> = match &page.spatial {
        Some(sv) => Box::new(
            SpatialAnimation::new(
                sv.clone(),
                &page.model,
                a.view.unwrap_or_default(),
                &settings,
            )
            .map_err(CliError::Input)?,
        ),
        None => {
            if a.view.is_some() {
                eprintln!(
                    "clr: note: --view is for spatial models: {} is a planar model, drawn in its \
                     plane",
                    file.display()
                );
            }
            Box::new(Animation::new(&page, &settings).map_err(CliError::Input)?)
        }
    };
    let started = Instant::now();
    let (w, h) = anim.size();
    let n = anim.picks().len();
    let mut distinct = anim.picks().to_vec();
    distinct.dedup();
    if distinct.len() == 1 && n > 1 {
        eprintln!(
            "clr: note: {} holds one frame in the window (a `clr view` page shows the initial \
             state): the animation is a still picture",
            file.display()
        );
    } else if (distinct.len() as f64) < 0.9 * n as f64 {
        eprintln!(
            "clr: note: {} holds {} frames in the window for {n} frames of animation: frames \
             are shown more than once (a lower --fps or a shorter --duration avoids it)",
            file.display(),
            distinct.len()
        );
    }
    if a.gif.is_some() && settings.fps > 50.0 {
        eprintln!(
            "clr: note: most GIF viewers show frames shorter than 0.02 s for 0.1 s: --fps {} \
             plays slower there (50 at most keeps the timing)",
            settings.fps
        );
    }
    let io_err = |p: &Path, e: std::io::Error| CliError::Input(format!("{}: {e}", p.display()));
    for out in a.gif.iter().chain(&a.mp4) {
        if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| io_err(dir, e))?;
        }
    }
    let mut mp4 = match &a.mp4 {
        Some(p) => Some(Mp4Sink::new(p, w, h, settings.fps).map_err(CliError::Input)?),
        None => None,
    };
    let mut gif = match &a.gif {
        Some(p) => {
            let f = std::fs::File::create(p).map_err(|e| io_err(p, e))?;
            let sink = GifSink::new(std::io::BufWriter::new(f), w, h, settings.fps)
                .map_err(|e| CliError::Input(format!("{}: {e}", p.display())))?;
            Some(sink)
        }
        None => None,
    };
    let terminal = std::io::stderr().is_terminal();
    let mut shown = Instant::now();
    let mut progress = false;
    for i in 0..n {
        let pm = anim.render(i);
        if let Some(g) = gif.as_mut() {
            g.push(&pm).map_err(CliError::Input)?;
        }
        if let Some(m) = mp4.as_mut() {
            m.push(&pm).map_err(CliError::Input)?;
        }
        let every = if terminal { 0.25 } else { 10.0 };
        if started.elapsed().as_secs_f64() > 1.0 && shown.elapsed().as_secs_f64() > every {
            shown = Instant::now();
            progress = true;
            if terminal {
                eprint!("\rclr: animate: frame {} of {n}", i + 1);
            } else {
                eprintln!("clr: animate: frame {} of {n}", i + 1);
            }
        }
    }
    if progress && terminal {
        eprint!("\r{:60}\r", "");
    }
    if let (Some(g), Some(p)) = (gif, &a.gif) {
        let mut w = g
            .finish()
            .map_err(|e| CliError::Input(format!("{}: {e}", p.display())))?;
        w.flush().map_err(|e| io_err(p, e))?;
    }
    if let Some(m) = mp4 {
        m.finish().map_err(CliError::Input)?;
    }
    let secs = started.elapsed().as_secs_f64();
    for out in a.gif.iter().chain(&a.mp4) {
        let bytes = std::fs::metadata(out).map(|m| m.len()).unwrap_or(0);
        eprintln!(
            "clr: wrote {}: {n} frames, {w}×{h} px, {} fps, {} ({secs:.1} s)",
            out.display(),
            settings.fps,
            size_text(bytes)
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// A report page around `data` (as `Report::html` writes it).
    fn html(data: &Value) -> String {
        let data = serde_json::to_string(data).unwrap().replace("</", "<\\/");
        format!(
            "<!DOCTYPE html>\n<html><head><title>t</title></head><body>\n\
             <script id=\"clr-data\" type=\"application/json\">{data}</script>\n\
             <script>\nconsole.log('</b>')\n</script>\n</body></html>\n"
        )
    }

    /// One rigid bar, 1 m long, pinned to the ground at its end (0, 0); its centre of mass is
    /// at the bar's middle (body frame: pin at [0, 0], end at [1, 0], com [0.5, 0]); it turns
    /// by 0, 45° and 90° over the three frames.
    fn bar_page() -> Value {
        let angles = [
            0.0f64,
            std::f64::consts::FRAC_PI_4,
            std::f64::consts::FRAC_PI_2,
        ];
        let pose: Vec<f64> = angles
            .iter()
            .flat_map(|&a| [0.5 * a.cos(), 0.5 * a.sin(), a])
            .collect();
        json!({
            "kind": "run",
            "model": "bar </script>",
            "source": "builtin",
            "description": "",
            "scene": {
                "parts": [{"name": "bar", "kind": "rigid", "com": [0.5, 0.0],
                           "pose0": [0.0, 0.0, 0.0], "points": [[0.5, 0.0], [0.0, 0.0], [1.0, 0.0]]}],
                "ground": [[0.0, 0.0]],
                "beams": [],
                "items": [{"section": "joint", "kind": "revolute", "name": "O",
                           "anchors": {"a": {"part": -1, "at": [0.0, 0.0]},
                                       "b": {"part": 0, "at": [0.0, 0.0]}},
                           "bodies": {}, "params": {}}],
                "gravity": [0.0, -9.81]
            },
            "scene_note": null,
            "frames": {"t": [0.0, 0.01, 0.02], "pose": [pose], "nodes": [], "contact": {}},
            "plots": [], "metrics": [], "impacts": [], "notes": [],
            "initial_conditions": null, "error": null, "sweep": null
        })
    }

    fn settings(width: u32, frames: usize) -> Settings {
        Settings {
            fps: frames as f64,
            duration: 1.0,
            width,
            ..Settings::default()
        }
    }

    fn is_background(pm: &Pixmap, p: P) -> bool {
        let px = pm.pixel(p[0].floor() as u32, p[1].floor() as u32).unwrap();
        [px.red(), px.green(), px.blue()] == BACKGROUND
    }

    #[test]
    fn the_bar_is_drawn_where_its_end_is() {
        let page = parse_page(&html(&bar_page())).unwrap();
        assert_eq!(page.model, "bar </script>");
        let anim = Animation::new(&page, &settings(400, 3)).unwrap();
        assert_eq!(anim.picks, vec![0, 1, 2]);
        // bounds: the bar's points over the frames span [0, 1] × [0, 1]; margin 24 px (4 % of
        // 400 px, at least 24); scale (400 − 2·24)/1 px/m; height 1·352 + 2·24 = 400
        let (m, s) = (24.0, 352.0);
        assert_eq!((anim.view.width, anim.view.height), (400, 400));
        let to_px = |x: f64, y: f64| [m + x * s, 400.0 - (m + y * s)];
        let frames: Vec<Pixmap> = (0..3).map(|i| anim.render(i)).collect();
        for (i, pm) in frames.iter().enumerate() {
            assert_eq!((pm.width(), pm.height()), (400, 400));
            let a = [
                0.0,
                std::f64::consts::FRAC_PI_4,
                std::f64::consts::FRAC_PI_2,
            ][i];
            // the end point (1, 0) of the body frame is at (cos a, sin a)
            let end = to_px(a.cos(), a.sin());
            assert!(
                !is_background(pm, end),
                "frame {i}: nothing at the bar's end {end:?}"
            );
            // the middle of the bar
            let mid = to_px(0.5 * a.cos(), 0.5 * a.sin());
            assert!(
                !is_background(pm, mid),
                "frame {i}: nothing at the bar's middle"
            );
            // the end has moved: the other frames' end points are empty here
            for (j, b) in [
                0.0,
                std::f64::consts::FRAC_PI_4,
                std::f64::consts::FRAC_PI_2,
            ]
            .iter()
            .enumerate()
            {
                if j != i {
                    let other = to_px(b.cos(), b.sin());
                    assert!(
                        is_background(pm, other),
                        "frame {i}: end of frame {j} drawn"
                    );
                }
            }
        }
    }

    #[test]
    fn the_gif_has_the_frames_and_size() {
        let page = parse_page(&html(&bar_page())).unwrap();
        let anim = Animation::new(&page, &settings(300, 7)).unwrap();
        assert_eq!(anim.picks, vec![0, 0, 1, 1, 1, 2, 2]);
        let (w, h) = (anim.view.width, anim.view.height);
        assert_eq!(w, 300);
        assert_eq!(h % 2, 0);
        let mut sink = GifSink::new(Vec::new(), w, h, 7.0).unwrap();
        for i in 0..anim.picks.len() {
            sink.push(&anim.render(i)).unwrap();
        }
        let bytes = sink.finish().unwrap();
        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::Indexed);
        let mut dec = opts.read_info(bytes.as_slice()).unwrap();
        assert_eq!((dec.width() as u32, dec.height() as u32), (w, h));
        assert_eq!(dec.repeat(), gif::Repeat::Infinite);
        let mut count = 0;
        let mut delay = 0;
        while let Some(f) = dec.read_next_frame().unwrap() {
            count += 1;
            delay += f.delay as u32;
        }
        assert_eq!(count, 7);
        assert_eq!(delay, 100, "7 frames at 7 fps last 1 s");
    }

    #[test]
    fn the_journal_sits_at_the_magnified_eccentricity() {
        // a bearing on the ground at (0, 0), R = 10 mm, c = 0.5 mm; the journal on the bar;
        // ex, ey in the bearing's frame (the ground: world)
        let mut page = bar_page();
        page["scene"]["items"] = json!([{
            "section": "clearance", "kind": "revolute", "name": "B",
            "anchors": {"bearing": {"part": -1, "at": [0.0, 0.0]},
                        "journal": {"part": 0, "at": [0.0, 0.0]}},
            "bodies": {}, "params": {"bearing_radius": 0.01, "journal_radius": 0.0095}
        }]);
        page["frames"]["contact"] = json!({"B": {
            "ex": [0.0005, 0.0, -0.0005], "ey": [0.0, 0.0005, 0.0],
            "normal_force": [10.0, 0.0, 5.0]
        }});
        let page = parse_page(&html(&page)).unwrap();
        let anim = Animation::new(&page, &settings(400, 3)).unwrap();
        // default: the clearance drawn as 8 % of R: m = 0.08 · 10 / 0.5 = 1.6
        assert!((anim.mc - 1.6).abs() < 1e-12);
        assert_eq!(anim.fmax, 10.0);
        match &anim
            .shapes(1)
            .iter()
            .find(|s| matches!(s, Shape::Bearing { .. }))
        {
            Some(Shape::Bearing {
                c,
                r,
                rj,
                off,
                force,
            }) => {
                assert_eq!(*c, [0.0, 0.0]);
                assert_eq!(*r, 0.01);
                assert!((rj - (0.01 - 1.6 * 0.0005)).abs() < 1e-15);
                assert!((off[0]).abs() < 1e-15 && (off[1] - 1.6 * 0.0005).abs() < 1e-15);
                assert_eq!(*force, None);
            }
            other => panic!("{other:?}"),
        }
        // a contact force arrow in frame 0 (the largest force), none in frame 1
        let arrows = |i: usize| {
            let pm = anim.render(i);
            pm.pixels()
                .iter()
                .filter(|p| [p.red(), p.green(), p.blue()] == ARROW)
                .count()
        };
        assert!(arrows(0) > 30, "{}", arrows(0));
        assert_eq!(arrows(1), 0);
    }

    #[test]
    fn a_shape_moves_with_its_part_and_is_red_in_contact() {
        // a square on the bar's end, its frame turned by 0.5 rad from the bar's; a contact
        // element lists it and touches in frame 1 only
        let mut page = bar_page();
        page["scene"]["shapes"] = json!([{
            "name": "tab", "at": {"part": 0, "at": [1.0, 0.0]}, "angle": 0.5, "kind": "cuboid",
            "outlines": [{"points": [[0.0, 0.0], [0.1, 0.0], [0.1, 0.1], [0.0, 0.1]],
                          "closed": true}]
        }]);
        page["scene"]["items"] = json!([{
            "section": "clearance", "kind": "contact", "name": "C", "anchors": {},
            "bodies": {}, "params": {}, "shapes": [0]
        }]);
        page["frames"]["contact"] =
            json!({"C": {"contact": [0.0, 1.0, 0.0], "normal_force": [0.0, 5.0, 0.0]}});
        let page = parse_page(&html(&page)).unwrap();
        let anim = Animation::new(&page, &settings(400, 3)).unwrap();
        // no force arrow is drawn for a shape contact: no arrow scale
        assert_eq!(anim.fmax, 0.0);
        for f in 0..3 {
            let a = std::f64::consts::FRAC_PI_4 * f as f64;
            let shapes = anim.shapes(f);
            // the bar (three points) is still drawn
            assert!(shapes.iter().any(|s| matches!(s, Shape::Body { .. })));
            let Some(Shape::Outline { lines, ground, on }) =
                shapes.iter().find(|s| matches!(s, Shape::Outline { .. }))
            else {
                panic!("frame {f}: no shape");
            };
            assert!(!ground);
            assert_eq!(*on, f == 1, "frame {f}");
            assert_eq!(lines.len(), 1);
            assert!(lines[0].1);
            // the page's transform: origin at the anchor, x axis at θ + angle
            let o = [a.cos(), a.sin()];
            for (p, q) in lines[0]
                .0
                .iter()
                .zip([[0.0, 0.0], [0.1, 0.0], [0.1, 0.1], [0.0, 0.1]])
            {
                let (s, c) = (a + 0.5).sin_cos();
                let w = [o[0] + c * q[0] - s * q[1], o[1] + s * q[0] + c * q[1]];
                assert!(norm(sub(*p, w)) < 1e-12, "frame {f}: {p:?} vs {w:?}");
            }
        }
        // the view holds the shape: its far corner in frame 0 is drawn
        let corner = rot([0.1, 0.1], 0.5);
        let far = anim.view.px(add([1.0, 0.0], mul(corner, 0.9)));
        assert!(!is_background(&anim.render(0), far));
        // edged red in contact only
        let red = |i: usize| {
            let pm = anim.render(i);
            pm.pixels()
                .iter()
                .filter(|p| [p.red(), p.green(), p.blue()] == ARROW)
                .count()
        };
        assert_eq!(red(0), 0);
        assert!(red(1) > 20, "{}", red(1));
    }

    #[test]
    fn a_page_without_frames_is_refused() {
        let dir = Path::new("/some/sweep/report.html");
        let mut sweep = bar_page();
        sweep["kind"] = json!("sweep");
        sweep["scene"] = Value::Null;
        sweep["frames"] = Value::Null;
        let e = check(&parse_page(&html(&sweep)).unwrap(), dir).unwrap_err();
        assert!(e.contains("report of a sweep"), "{e}");
        assert!(e.contains("point-00000"), "{e}");
        let mut bare = bar_page();
        bare["scene"] = Value::Null;
        bare["frames"] = Value::Null;
        bare["scene_note"] = json!("the model is a built-in without a description");
        let e = check(&parse_page(&html(&bare)).unwrap(), dir).unwrap_err();
        assert!(e.contains("has no animation"), "{e}");
        assert!(e.contains("without a description"), "{e}");
        assert!(e.contains("clr run"), "{e}");
        let e = parse_page("<html>no data</html>").unwrap_err();
        assert!(e.contains("not a clr report"), "{e}");
    }

    #[test]
    fn frames_are_picked_at_equal_times_in_the_window() {
        let t: Vec<f64> = (0..101).map(|k| k as f64 * 0.01).collect();
        assert_eq!(pick_frames(&t, None, None, 5), vec![0, 25, 50, 75, 100]);
        assert_eq!(pick_frames(&t, Some(0.5), Some(0.7), 3), vec![50, 60, 70]);
        assert_eq!(pick_frames(&t, Some(2.0), None, 3), Vec::<usize>::new());
        assert_eq!(pick_frames(&t, None, None, 1), vec![0]);
    }

    #[test]
    fn the_hull_keeps_the_outer_points() {
        let h = hull(vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [0.5, 0.2],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.5, 0.5],
        ]);
        assert_eq!(h.len(), 4);
        let h = hull(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]);
        assert_eq!(h, vec![[0.0, 0.0], [2.0, 0.0]]);
    }

    /// The spinning top of `clr_sim::report::spatial` drawn from each view: the image has the
    /// asked width and an even height, every frame has ink, and the ball of the socket is drawn
    /// where the hand projection puts it: socket (0.5, 0, 0) + m·e with e = 0.8 mm
    /// (sin 2πt, −cos 2πt, 0) and m the automatic magnification 0.08·R/c = 1.6.
    #[test]
    fn a_spatial_run_is_drawn_from_each_view() {
        let (scene, results) = clr_sim::report::spatial::spinning_top(101);
        for view in [
            ViewName::Iso,
            ViewName::Front,
            ViewName::Top,
            ViewName::Side,
        ] {
            let anim =
                animate_spatial(scene.clone(), &results, view, &settings(320, 5), "top").unwrap();
            let (w, h) = anim.size();
            assert_eq!(w, 320, "{view:?}");
            assert!(h % 2 == 0 && (80..=400).contains(&h), "{view:?}: {h}");
            assert_eq!(anim.picks(), &[0, 25, 50, 75, 100]);
            assert!((anim.mag - 1.6).abs() < 1e-12);
            for i in 0..5 {
                let pm = anim.render(i);
                let ink = pm
                    .pixels()
                    .iter()
                    .filter(|p| p.red() < 200 || p.blue() < 200)
                    .count();
                assert!(ink > 500, "{view:?} frame {i}: {ink} pixels drawn");
                let t = i as f64 / 4.0;
                let phi = 2.0 * std::f64::consts::PI * t;
                let e = [0.8e-3 * phi.sin(), -0.8e-3 * phi.cos(), 0.0];
                let [r, u, _] = view.axes();
                let world = [0.5 + 1.6 * e[0], 1.6 * e[1], 0.0];
                let b = anim.px.px([dot3(world, r), dot3(world, u)]);
                // 4 px beside the centre across the normal-force arrow, which runs through it
                let n = anim.dir_px(e);
                let b = add(b, mul([-n[1], n[0]], 4.0));
                let px = pm.pixel(b[0] as u32, b[1] as u32).unwrap();
                assert_eq!(
                    [px.red(), px.green(), px.blue()],
                    JOURNAL_FILL,
                    "{view:?} frame {i}: no ball at {b:?}"
                );
            }
        }
    }

    /// `t` and the pose columns of `body`.
    fn pose_columns(body: &str) -> Vec<String> {
        let mut columns = vec!["t".to_string()];
        columns.extend(["x", "y", "z", "qw", "qx", "qy", "qz"].map(|c| format!("{body}.{c}")));
        columns
    }

    /// Results of one row.
    fn one_row(columns: Vec<String>, row: &[f64]) -> clr_mbd::Results {
        clr_mbd::Results {
            columns,
            data: row.to_vec(),
            ..clr_mbd::Results::default()
        }
    }

    /// The example's journal joint drawn from the side (y right, z up): the journal sits against
    /// the bore at −y, so with the automatic magnification m = 0.08·R/c = 8 the drawn gap of
    /// 2·m·c lies at +y. The pixel at y = R − m·c (mid-gap) shows the bore's inside, its mirror
    /// at y = −(R − m·c) the journal; the radial contact force is drawn in the force colour.
    #[test]
    fn a_journal_is_drawn_with_its_offset_magnified() {
        let text = include_str!("../../models/examples/spatial_revolute_clearance.toml");
        let d = clr_mbd::spatial::SpatialDesc::from_toml_table(text.parse().unwrap()).unwrap();
        let scene = SpatialScene::from_desc(&d);
        let (r, c) = (0.010, 1e-4);
        let mut columns = pose_columns("pendulum");
        columns.extend(clr_sim::report::spatial::JOURNAL_VALUES.map(|v| format!("pin.{v}")));
        // the centre of mass 0.1 m along x from the pin, the pin at y = −c (on the bore)
        let row = [0.0, 0.1, -c, 0.0, 1.0, 0.0, 0.0, 0.0, 5.0, 5.0, 0.0, 0.0];
        let results = one_row(columns, &row);
        let anim =
            animate_spatial(scene, &results, ViewName::Side, &settings(320, 1), "pin").unwrap();
        assert!((anim.mag - 8.0).abs() < 1e-9, "{}", anim.mag);
        let pm = anim.render(0);
        let colour = |y: f64| {
            let p = anim.px.px([y, 0.0]);
            let px = pm.pixel(p[0].round() as u32, p[1].round() as u32).unwrap();
            [px.red(), px.green(), px.blue()]
        };
        let m = anim.mag;
        assert_eq!(colour(r - m * c), LIGHT, "the gap at +y");
        assert_eq!(colour(-(r - m * c)), JOURNAL_FILL, "the journal at −y");
        let red = pm
            .pixels()
            .iter()
            .filter(|p| [p.red(), p.green(), p.blue()] == ARROW)
            .count();
        assert!(red > 50, "{red} pixels in the force colour");
    }

    /// The ball-on-box example's shapes drawn from the top (x right, y up): the ball's disc
    /// (radius 10 mm, seen at 0.6 R beside its centre, clear of the centre-of-mass dot) in the
    /// shape fill, the floor's top face around it in the ground fill, the floor's outline (its
    /// silhouette: the box's top rim at x = ±0.5 m) in grey.
    #[test]
    fn contact_shapes_are_drawn_as_their_surfaces() {
        let text = include_str!("../../models/examples/spatial_ball_on_box.toml");
        let d = clr_mbd::spatial::SpatialDesc::from_toml_table(text.parse().unwrap()).unwrap();
        let scene = SpatialScene::from_desc(&d);
        assert_eq!(scene.shapes.len(), 2);
        let row = [0.0, 0.2, 0.1, 0.05, 1.0, 0.0, 0.0, 0.0];
        let results = one_row(pose_columns("ball"), &row);
        let anim =
            animate_spatial(scene, &results, ViewName::Top, &settings(400, 1), "ball").unwrap();
        let pm = anim.render(0);
        let colour = |x: f64, y: f64| {
            let p = anim.px.px([x, y]);
            let px = pm.pixel(p[0].round() as u32, p[1].round() as u32).unwrap();
            [px.red(), px.green(), px.blue()]
        };
        // within 4 levels: the anti-aliased seams between a shape's triangles
        let near = |x: f64, y: f64, want: Rgb, what: &str| {
            let got = colour(x, y);
            let off = (0..3).map(|k| got[k].abs_diff(want[k])).max().unwrap_or(0);
            assert!(off <= 4, "{what}: {got:?} instead of {want:?}");
        };
        near(0.2 + 0.006, 0.1, SHAPE_FILL, "the ball");
        near(0.2 + 0.03, 0.1, GROUND_FILL, "the floor beside it");
        near(-0.3, -0.2, GROUND_FILL, "the floor");
        near(0.5, -0.2, GREY, "the floor's rim");
    }

    #[test]
    fn a_spatial_page_is_animated_from_its_data() {
        let (scene, results) = clr_sim::report::spatial::spinning_top(41);
        let input = clr_sim::report::Input {
            model: "top",
            source: "test",
            description: "",
            desc: Err("spatial".into()),
            results: &results,
            metrics: &[],
            notes: &[],
            error: None,
        };
        let limits = clr_sim::report::Limits::default();
        let report = clr_sim::report::Report::spatial("run", &input, scene, limits).unwrap();
        let page = parse_page(&report.html()).unwrap();
        check(&page, Path::new("report.html")).unwrap();
        let sv = page.spatial.unwrap();
        assert_eq!(sv.frames.t.len(), 41);
        let anim = SpatialAnimation::new(sv, "top", ViewName::Top, &settings(200, 3)).unwrap();
        assert_eq!(anim.picks(), &[0, 20, 40]);
    }
}
