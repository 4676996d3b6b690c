//! The run report: one self-contained `report.html` (no network: data, script and style
//! inline) with the mechanism animated from the recorded output beside its metrics, impact
//! table and figures, for every built-in model and any model file; `clr view` draws the same
//! page at t0 without simulating, and a sweep links its points' reports.
//!
//! Layers: [`scene`] (the drawing, from the plain model description), [`frames`] (what moves,
//! from the result columns, decimated), [`Report`] (everything the page shows, serialized as
//! JSON into the page) and the renderer `assets/report.js`, which draws on a canvas.

pub mod frames;
pub mod scene;
pub mod spatial;
mod sweep;

use clr_mbd::{Model, ModelDesc, Results};
use clr_models::Metric;
use serde::Serialize;

pub use frames::{Frames, Plot};
pub use scene::Scene;
pub use spatial::{SpatialError, SpatialScene, SpatialView};
pub use sweep::{metric_names, SweepRow};

/// Size limits of a report.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Animation frames at most.
    pub frames: usize,
    /// Points per figure line at most (peaks kept).
    pub points: usize,
}

impl Default for Limits {
    /// 2000 frames and 4000 points per line: a 10 s run of the largest built-in stays near
    /// 2 MB (docs/cli.md).
    fn default() -> Self {
        Self {
            frames: 2000,
            points: 4000,
        }
    }
}

/// One metric as the page lists it.
#[derive(Debug, Clone, Serialize)]
pub struct MetricRow {
    /// Name.
    pub name: String,
    /// Value (SI).
    pub value: f64,
    /// Unit.
    pub unit: String,
    /// What it is.
    pub description: String,
}

/// Everything the page shows.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// `run` (an animation), `view` (the initial state only) or `sweep`.
    pub kind: &'static str,
    /// Model name.
    pub model: String,
    /// `builtin` or the model file.
    pub source: String,
    /// One line.
    pub description: String,
    /// The drawing, when the model has a description (every built-in and model file).
    pub scene: Option<Scene>,
    /// Why there is no drawing, when there is none.
    pub scene_note: Option<String>,
    /// The animation frames.
    pub frames: Option<Frames>,
    /// Figures with the time cursor.
    pub plots: Vec<Plot>,
    /// Scalar metrics.
    pub metrics: Vec<MetricRow>,
    /// Located impacts (the columns of impacts.csv).
    pub impacts: Vec<serde_json::Value>,
    /// What the run or reading the model changed on its own.
    pub notes: Vec<String>,
    /// The initial-conditions report (as in summary.json).
    pub initial_conditions: serde_json::Value,
    /// The solver's error when the run stopped early.
    pub error: Option<String>,
    /// For a sweep: the table and the links to the points' reports.
    pub sweep: Option<serde_json::Value>,
    /// For a spatial model: the 3-D drawing and its frames (then `scene` is `None`); left out
    /// of the page's data when absent, so that planar pages are unchanged.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spatial: Option<SpatialView>,
}

/// What a report is made from.
pub struct Input<'a> {
    /// Model name.
    pub model: &'a str,
    /// `builtin` or the file.
    pub source: &'a str,
    /// One line.
    pub description: &'a str,
    /// The description run (for the drawing), or why there is none.
    pub desc: Result<&'a ModelDesc, String>,
    /// The recorded output.
    pub results: &'a Results,
    /// Metrics.
    pub metrics: &'a [Metric],
    /// Notes.
    pub notes: &'a [String],
    /// The solver's error, if any.
    pub error: Option<&'a str>,
}

impl Report {
    /// The report of a run (`kind = "run"`) or of an initial state (`"view"`).
    pub fn new(kind: &'static str, input: &Input<'_>, limits: Limits) -> Self {
        let (scene, scene_note, model) = match input.desc {
            Ok(d) => {
                let model = if d.flexible_bodies.is_empty() {
                    None
                } else {
                    d.compile().ok()
                };
                (Some(Scene::from_desc(d)), None, model)
            }
            Err(ref why) => (None, Some(why.clone()), None),
        };
        let t = input.results.column("t").unwrap_or_default();
        let rows = frames::select(&t, limits.frames);
        let frames = scene
            .as_ref()
            .map(|s| Frames::new(s, input.results, &rows, model.as_ref()));
        let plots = scene
            .as_ref()
            .map(|s| frames::plots(s, input.results, limits.points))
            .unwrap_or_default();
        Report {
            kind,
            model: input.model.to_string(),
            source: input.source.to_string(),
            description: input.description.to_string(),
            scene,
            scene_note,
            frames,
            plots,
            metrics: input
                .metrics
                .iter()
                .map(|m| MetricRow {
                    name: m.name.clone(),
                    value: m.value,
                    unit: m.unit.clone(),
                    description: m.description.clone(),
                })
                .collect(),
            impacts: input.results.impacts.iter().map(impact_json).collect(),
            notes: input.notes.to_vec(),
            initial_conditions: crate::spec::run::initial_conditions_json(
                input.results.initial_conditions.as_ref(),
            ),
            error: input.error.map(str::to_string),
            sweep: None,
            spatial: None,
        }
    }

    /// The self-contained page.
    pub fn html(&self) -> String {
        let data = serde_json::to_string(self).unwrap_or_else(|_| "null".into());
        // the data sits in a <script> element: a "</" inside a string would end it
        let data = data.replace("</", "<\\/");
        let title = html_escape(&format!("clr — {}", self.model));
        // a spatial page adds the 3-D renderer (three.js and report3d.js) before report.js,
        // which hands the stage to it; a planar page is left as it was
        let (css3d, js3d) = match self.spatial {
            Some(_) => (spatial::CSS, spatial::scripts()),
            None => ("", String::new()),
        };
        format!(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
             <title>{title}</title>\n<style>\n{css}{css3d}\n</style>\n</head>\n<body>\n\
             <script id=\"clr-data\" type=\"application/json\">{data}</script>\n\
             {js3d}<script>\n{js}\n</script>\n</body>\n</html>\n",
            css = include_str!("assets/report.css"),
            js = include_str!("assets/report.js"),
        )
    }
}

/// An impact as the page lists it (the columns of impacts.csv).
fn impact_json(i: &clr_mbd::Impact) -> serde_json::Value {
    serde_json::json!({
        "joint": i.joint,
        "onset_s": i.onset,
        "impact_velocity_m_per_s": i.impact_velocity,
        "peak_force_N": i.peak_force,
        "peak_force_time_s": i.peak_force_time,
        "max_penetration_m": i.max_penetration,
        "max_penetration_time_s": i.max_penetration_time,
        "separation_s": i.separation,
        "duration_s": i.duration,
    })
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The initial state of `desc` at its `t0` (assembled with its `[solver]` settings) as a
/// one-row result (for `clr view`), with the compiled model's notes.
///
/// # Errors
/// The model's compile, settings or assembly error, as text.
pub fn initial_state(desc: &ModelDesc, t0: f64) -> Result<Results, String> {
    let mut model: Model = desc.compile().map_err(|e| e.to_string())?;
    let mut opts = desc.sim_options().map_err(|e| e.to_string())?;
    opts.t0 = t0;
    model.initial_results(&opts).map_err(|e| e.to_string())
}
