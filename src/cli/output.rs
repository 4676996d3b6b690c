//! What a run writes: results.csv (or results.parquet), summary.json and figures.

use std::io::Write;
use std::path::Path;

use clr_plot::Figure;
use clr_sim::spec::run::{Job, Outcome};

use super::series::{Table, IMPACTS_HEADER};
use super::{CliError, RunArgs};

/// The outcome of one run (`clr_sim::spec::run::Outcome`, whose fields it derefs to) and its wall
/// time.
pub(crate) struct Record {
    /// Model, source, results, units, metrics, parameters, error.
    pub outcome: Outcome,
    /// Wall time of the simulation, s.
    pub wall_s: f64,
}

impl std::ops::Deref for Record {
    type Target = Outcome;
    fn deref(&self) -> &Outcome {
        &self.outcome
    }
}

impl Record {
    /// A record of a library run outcome and its wall time (s).
    pub(crate) fn new(outcome: Outcome, wall_s: f64) -> Self {
        Self { outcome, wall_s }
    }
}

fn io(path: &Path, e: std::io::Error) -> CliError {
    CliError::Input(format!("cannot write {}: {e}", path.display()))
}

/// Write `results.csv`: a header of `name [unit]` and one row per output time, every value in
/// Rust's shortest round-trip form (so two equal runs give identical files).
pub(crate) fn write_csv(path: &Path, rec: &Record) -> Result<(), CliError> {
    let f = std::fs::File::create(path).map_err(|e| io(path, e))?;
    let mut w = std::io::BufWriter::new(f);
    let header: Vec<String> = rec
        .results
        .columns
        .iter()
        .zip(&rec.units)
        .map(|(c, u)| format!("{c} [{u}]"))
        .collect();
    let mut body = header.join(",");
    body.push('\n');
    w.write_all(body.as_bytes()).map_err(|e| io(path, e))?;
    let mut line = String::new();
    for r in 0..rec.results.len() {
        line.clear();
        for (k, v) in rec.results.row(r).iter().enumerate() {
            if k > 0 {
                line.push(',');
            }
            line.push_str(&format!("{v:e}"));
        }
        line.push('\n');
        w.write_all(line.as_bytes()).map_err(|e| io(path, e))?;
    }
    w.flush().map_err(|e| io(path, e))
}

/// Read a CSV written by [`write_csv`] (or any CSV of numbers with a header).
pub(crate) fn read_csv(path: &Path) -> Result<Table, CliError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::Input(format!("cannot read {}: {e}", path.display())))?;
    let mut lines = text.lines();
    let header = lines
        .next()
        .ok_or_else(|| CliError::Input(format!("{}: the file is empty", path.display())))?;
    let (mut names, mut units) = (Vec::new(), Vec::new());
    for h in header.split(',') {
        let h = h.trim();
        match h.rsplit_once(" [") {
            Some((n, u)) if u.ends_with(']') => {
                names.push(n.to_string());
                units.push(u.trim_end_matches(']').to_string());
            }
            _ => {
                names.push(h.to_string());
                units.push(String::new());
            }
        }
    }
    let mut rows = Vec::new();
    for (i, l) in lines.enumerate() {
        if l.trim().is_empty() {
            continue;
        }
        let row: Result<Vec<f64>, _> = l.split(',').map(|v| v.trim().parse::<f64>()).collect();
        let row = row.map_err(|_| {
            CliError::Input(format!(
                "{}:{}: not a row of numbers",
                path.display(),
                i + 2
            ))
        })?;
        if row.len() != names.len() {
            return Err(CliError::Input(format!(
                "{}:{}: {} values for {} columns",
                path.display(),
                i + 2,
                row.len(),
                names.len()
            )));
        }
        rows.push(row);
    }
    Ok(Table { names, units, rows })
}

/// One metric of summary.json, its fields in the order a reader wants them.
#[derive(serde::Serialize)]
struct MetricOut<'a> {
    name: &'a str,
    value: Option<f64>,
    unit: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    window: Option<&'a str>,
    description: &'a str,
}

/// summary.json: a struct rather than a JSON map so that its keys keep this order (serde_json
/// sorts the keys of a map): what a reader looks for first (status, metrics, the run's size and
/// settings) before the long per-body blocks.
#[derive(serde::Serialize)]
struct Summary<'a> {
    model: &'a str,
    source: &'a str,
    status: &'static str,
    error: Option<&'a str>,
    metrics: Vec<MetricOut<'a>>,
    notes: &'a [String],
    warnings: &'a [clr_mbd::plausible::Warning],
    rows: usize,
    t_last: Option<f64>,
    simulated_time_s: Option<f64>,
    wall_time_s: f64,
    t_end_requested: Option<f64>,
    rtol_requested: Option<f64>,
    solver_settings: &'a serde_json::Value,
    #[serde(skip_serializing_if = "no_defaults")]
    builtin_defaults: &'a serde_json::Map<String, serde_json::Value>,
    solver: serde_json::Value,
    impacts: serde_json::Value,
    parameters: &'a serde_json::Value,
    flexible_bodies: serde_json::Value,
    initial_conditions: serde_json::Value,
}

/// True when no built-in parameter was replaced (`builtin_defaults` is then left out).
fn no_defaults(m: &&serde_json::Map<String, serde_json::Value>) -> bool {
    m.is_empty()
}

/// The simulated span of a run (s): last minus first output time.
pub(crate) fn simulated_time(rec: &Record) -> Option<f64> {
    let t = rec.results.column("t")?;
    Some(t.last()? - t.first()?)
}

/// The summary of a run as pretty JSON text (layout in docs/cli.md#summaryjson).
fn summary_text(
    rec: &Record,
    t_end: Option<f64>,
    rtol: Option<f64>,
) -> Result<String, serde_json::Error> {
    let s = &rec.results.stats;
    let finite = |x: f64| if x.is_finite() { Some(x) } else { None };
    let summary = Summary {
        model: &rec.model,
        source: &rec.source,
        status: if rec.error.is_some() { "failed" } else { "ok" },
        error: rec.error.as_deref(),
        metrics: rec
            .metrics
            .iter()
            .map(|m| MetricOut {
                name: &m.name,
                value: finite(m.value),
                unit: &m.unit,
                window: m.window.as_deref(),
                description: &m.description,
            })
            .collect(),
        notes: &rec.notes,
        warnings: &rec.results.warnings,
        rows: rec.results.len(),
        t_last: rec.results.column("t").and_then(|t| t.last().copied()),
        simulated_time_s: simulated_time(rec),
        wall_time_s: rec.wall_s,
        t_end_requested: t_end,
        rtol_requested: rtol,
        solver_settings: &rec.solver_settings,
        builtin_defaults: &rec.builtin_defaults,
        solver: serde_json::json!({
            "accepted_steps": s.accepted,
            "rejected_steps": s.rejected,
            "f_evals": s.f_evals,
            "jacobians": s.jac_evals,
            "lu_factorizations": s.lu_factorizations,
            "newton_iterations": s.newton_iters,
            "events": s.events,
            "contact_onsets": rec.results.onsets,
            "projections": rec.results.projections,
            "max_position_violation": finite(rec.results.max_position_violation),
        }),
        impacts: impacts_summary(&rec.results.impacts),
        parameters: &rec.parameters,
        flexible_bodies: clr_sim::spec::run::flexible_json(&rec.flexible),
        initial_conditions: clr_sim::spec::run::initial_conditions_json(
            rec.results.initial_conditions.as_ref(),
        ),
    };
    serde_json::to_string_pretty(&summary)
}

/// Write the located impacts, one row each in onset order; an empty cell for the separation and
/// duration of an impact still under way at the end of the run.
pub(crate) fn write_impacts(path: &Path, impacts: &[clr_mbd::Impact]) -> Result<(), CliError> {
    let opt = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
    let mut text = format!("{IMPACTS_HEADER}\n");
    for i in impacts {
        text.push_str(&format!(
            "{},{:e},{:e},{:e},{:e},{:e},{:e},{},{}\n",
            i.joint,
            i.onset,
            i.impact_velocity,
            i.peak_force,
            i.peak_force_time,
            i.max_penetration,
            i.max_penetration_time,
            opt(i.separation),
            opt(i.duration)
        ));
    }
    std::fs::write(path, text).map_err(|e| io(path, e))
}

/// Per clearance joint with impacts: count, first onset (s), the largest peak normal force (N)
/// with its time (s), and the largest penetration (m).
fn impacts_summary(impacts: &[clr_mbd::Impact]) -> serde_json::Value {
    let mut per: serde_json::Map<String, serde_json::Value> = serde_json::Map::new();
    let mut joints: Vec<&str> = impacts.iter().map(|i| i.joint.as_str()).collect();
    joints.dedup();
    joints.sort_unstable();
    joints.dedup();
    for j in joints {
        let mine = || impacts.iter().filter(move |i| i.joint == j);
        let Some(peak) = mine().max_by(|a, b| a.peak_force.total_cmp(&b.peak_force)) else {
            continue;
        };
        let pen = mine().fold(f64::NEG_INFINITY, |a, i| a.max(i.max_penetration));
        let first = mine().fold(f64::INFINITY, |a, i| a.min(i.onset));
        per.insert(
            j.to_string(),
            serde_json::json!({
                "window": clr_models::output::WHOLE_RUN,
                "count": mine().count(),
                "first_impact_s": first,
                "largest_peak_force_N": peak.peak_force,
                "largest_peak_force_time_s": peak.peak_force_time,
                "largest_penetration_m": pen,
            }),
        );
    }
    serde_json::Value::Object(per)
}

/// Write results.csv, summary.json and (optionally) the figures into `dir`.
pub(crate) fn write_run(
    dir: &Path,
    rec: &Record,
    args: &RunArgs,
    report: Option<&Job>,
) -> Result<(), CliError> {
    let (t_end, rtol, figures) = (args.t_end, args.rtol, !args.no_figures);
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    if let Some(clr_sim::spec::run::Job::Spatial(s)) = report {
        write_spatial_report(&dir.join("report.html"), rec, s)?;
    } else if let Some(job) = report {
        let desc = job.desc(t_end, rtol);
        write_report(
            &dir.join("report.html"),
            rec,
            desc.as_ref().map_err(Clone::clone),
        )?;
    }
    write_series(dir, rec, args.series_format())?;
    write_summary(dir, rec, args)?;
    if figures {
        for w in run_figures(dir, rec) {
            eprintln!("clr: warning: {w}");
        }
    }
    Ok(())
}

/// Write the time series and impacts into `dir` in the chosen format(s).
pub(crate) fn write_series(
    dir: &Path,
    rec: &Record,
    format: super::SeriesFormat,
) -> Result<(), CliError> {
    if format.csv() {
        write_csv(&dir.join("results.csv"), rec)?;
        write_impacts(&dir.join("impacts.csv"), &rec.results.impacts)?;
    }
    if format.parquet() {
        super::parquet::write_results(&dir.join("results.parquet"), &rec.results, &rec.units)?;
        super::parquet::write_impacts(&dir.join("impacts.parquet"), &rec.results.impacts)?;
    }
    Ok(())
}

/// Write the run's `summary.json` into `dir`.
pub(crate) fn write_summary(dir: &Path, rec: &Record, args: &RunArgs) -> Result<(), CliError> {
    let p = dir.join("summary.json");
    let text = summary_text(rec, args.t_end, args.rtol)
        .map_err(|e| CliError::Input(format!("summary: {e}")))?;
    std::fs::write(&p, text + "\n").map_err(|e| io(&p, e))
}

/// Write the run's `report.html` (the animated mechanism, metrics, impacts and figures; one
/// self-contained file).
fn write_report(
    path: &Path,
    rec: &Record,
    desc: Result<&clr_mbd::ModelDesc, String>,
) -> Result<(), CliError> {
    let input = clr_sim::report::Input {
        model: &rec.model,
        source: &rec.source,
        description: "",
        desc,
        results: &rec.results,
        metrics: &rec.metrics,
        notes: &rec.notes,
        error: rec.error.as_deref(),
    };
    let report = clr_sim::report::Report::new("run", &input, clr_sim::report::Limits::default());
    std::fs::write(path, report.html()).map_err(|e| io(path, e))
}

/// Write the 3-D `report.html` of a spatial run.
fn write_spatial_report(
    path: &Path,
    rec: &Record,
    spec: &clr_sim::spec::SpatialSpec,
) -> Result<(), CliError> {
    let input = clr_sim::report::Input {
        model: &rec.model,
        source: &rec.source,
        description: "",
        desc: Err(String::new()),
        results: &rec.results,
        metrics: &rec.metrics,
        notes: &rec.notes,
        error: rec.error.as_deref(),
    };
    let scene = clr_sim::report::spatial::SpatialScene::from_desc(spec.desc());
    let report =
        clr_sim::report::Report::spatial("run", &input, scene, clr_sim::report::Limits::default())
            .map_err(|e| CliError::Input(format!("report.html: {e}")))?;
    std::fs::write(path, report.html()).map_err(|e| io(path, e))
}

fn pairs(x: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
    x.iter().copied().zip(y.iter().copied()).collect()
}

/// Draw the run's figures; returns warnings for figures that could not be drawn.
fn run_figures(dir: &Path, rec: &Record) -> Vec<String> {
    let r = &rec.results;
    let mut warn = Vec::new();
    let Some(t) = r.column("t") else {
        return warn;
    };
    if t.len() < 2 {
        return warn;
    }
    let mut save = |f: Figure, stem: &str| {
        if let Err(e) = f.save(dir.join(stem)) {
            warn.push(e.to_string());
        }
    };
    let bodies: Vec<&str> = r
        .columns
        .iter()
        .filter_map(|c| c.strip_suffix(".alpha"))
        .collect();
    if !bodies.is_empty() {
        let mut f = Figure::new(format!("{}: body angles", rec.model))
            .x_label("time (s)")
            .y_label("angle (rad)");
        let mut fx = Figure::new(format!("{}: body positions", rec.model))
            .x_label("time (s)")
            .y_label("centre of mass (m)");
        for b in bodies.iter().take(8) {
            if let Some(th) = r.column(&format!("{b}.theta")) {
                f = f.line(*b, pairs(&t, &th));
            }
            for c in ["x", "y"] {
                if let Some(v) = r.column(&format!("{b}.{c}")) {
                    fx = fx.line(format!("{b}.{c}"), pairs(&t, &v));
                }
            }
        }
        save(f, "angles");
        save(fx, "positions");
    }
    if r.index("energy.total").is_some() {
        let mut f = Figure::new(format!("{}: energy", rec.model))
            .x_label("time (s)")
            .y_label("energy (J)");
        for c in ["kinetic", "potential", "elastic", "total"] {
            if let Some(v) = r.column(&format!("energy.{c}")) {
                f = f.line(c, pairs(&t, &v));
            }
        }
        save(f, "energy");
    }
    let clearances: Vec<&str> = r
        .columns
        .iter()
        .filter_map(|c| c.strip_suffix(".normal_force"))
        .collect();
    if !clearances.is_empty() {
        let mut f = Figure::new(format!("{}: contact forces", rec.model))
            .x_label("time (s)")
            .y_label("normal force (N)");
        for c in &clearances {
            if let Some(v) = r.column(&format!("{c}.normal_force")) {
                f = f.line(*c, pairs(&t, &v));
            }
        }
        save(f, "contact_forces");
    }
    // beams: deflection of the last node of each
    let mut tips: Vec<(&str, &str)> = Vec::new();
    for c in &r.columns {
        if let Some(stem) = c.strip_suffix(".v") {
            if let Some((beam, node)) = stem.rsplit_once(".n") {
                if node.parse::<usize>().is_ok() {
                    match tips.iter_mut().find(|(b, _)| *b == beam) {
                        Some(t) => t.1 = c,
                        None => tips.push((beam, c)),
                    }
                }
            }
        }
    }
    if !tips.is_empty() {
        let mut f = Figure::new(format!("{}: beam deflection", rec.model))
            .x_label("time (s)")
            .y_label("transverse displacement v (m)");
        for (_, col) in &tips {
            if let Some(v) = r.column(col) {
                f = f.line(*col, pairs(&t, &v));
            }
        }
        save(f, "beam_deflection");
    }
    for c in &clearances {
        if rec.no_orbit.iter().any(|n| n == c) {
            continue;
        }
        let (Some(ex), Some(ey), Some(pen)) = (
            r.column(&format!("{c}.ex")),
            r.column(&format!("{c}.ey")),
            r.column(&format!("{c}.penetration")),
        ) else {
            continue;
        };
        // radial clearance from δ = |e| − c (the same on every row of a revolute clearance;
        // translational clearances record other quantities and get no orbit)
        let radial = (ex[0].hypot(ey[0]) - pen[0]).abs();
        let revolute = ex
            .iter()
            .zip(&ey)
            .zip(&pen)
            .all(|((x, y), p)| (x.hypot(*y) - p - radial).abs() <= 1e-9 * radial.max(1e-12));
        if !revolute || radial == 0.0 {
            continue;
        }
        let circle: Vec<(f64, f64)> = (0..=200)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 200.0;
                (radial * a.cos(), radial * a.sin())
            })
            .collect();
        let f = Figure::new(format!("{}: journal centre orbit in `{c}`", rec.model))
            .x_label("e_x (m, bearing frame)")
            .y_label("e_y (m, bearing frame)")
            .equal_aspect()
            .line("clearance circle", circle)
            .line("journal centre", pairs(&ex, &ey));
        let stem = format!("orbit_{}", c.replace(|ch: char| !ch.is_alphanumeric(), "_"));
        save(f, &stem);
    }
    warn
}
