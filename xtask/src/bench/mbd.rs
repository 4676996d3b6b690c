//! `cargo xtask bench mbd`: the clearance slider–crank of issue 5 in clr (built-in
//! `slider_crank`, `SliderCrankParams::flores()`), Exudyn and SciPy, in one run.
//!
//! Mechanism: crank 0.05 m, rod 0.30 m, masses 0.343 / 1.072 / 0.347 kg, inertias 0.000216 /
//! 0.034 / 0.000115 kg·m², rod–slider clearance joint (bearing 10.0 mm, journal 9.5 mm, steel
//! Hertz internal cylinder, Lankarani–Nikravesh c_e = 0.9, no friction), crank 5000 rpm from
//! θ = 0, gravity, 0.1 s.
//!
//! - clr: NDF and DOPRI5 at rtol 1e-6, atol 1e-9 (the built-in's atol = 1e-3·rtol), onsets
//!   located as events (the default); the model is built outside the timer, `simulate` is timed
//!   (median of at least 5 solves and `--min-time` seconds).
//! - Exudyn: `bench/exudyn_slider_crank.py` (generalized-α, fixed h = 1e-5 and 1e-6, hollow
//!   sphere–sphere contact, Hunt–Crossley with e = (1 + c_e²)/2), only `SolveDynamic` timed.
//! - SciPy: `bench/scipy_slider_crank.py` (`solve_ivp` LSODA and BDF on the independent
//!   minimal-coordinate formulation with located onsets and separations), only the solve timed.
//!
//! Accuracy: the slider position at 5 and 10 ms against the independent formulation of
//! [`crate::minimal_slider_crank`] integrated by DOPRI5 at rtol 1e-12 (the reference of
//! `cargo xtask verify mbd.clearance_slider_crank.early`). After ~10 ms the motion is chaotic,
//! so the 0.1 s end state is not compared.
//!
//! Both peers run with the interpreter of `bench/.venv` (created and filled with SciPy by the ode
//! bench's code; `exudyn` is pip-installed into it when missing).
//!
//! Work–precision sweep (issue 13; `--no-sweep` skips it): clr NDF at rtol 1e-5 … 1e-10
//! (atol = 1e-3·rtol), Exudyn at h = 1e-5, 3e-6, 1e-6 (same settings as above), SciPy LSODA and
//! BDF at rtol 1e-6 … 1e-10 (atol = 1e-3·rtol; the rtol 1e-6 rows are those of the main table).
//! Every run is the whole 0.1 s benchmark run, timed as above; its accuracy is the slider error
//! at 10 ms. From the sweep: (a) at equal error at 10 ms (LSODA points with error ≤ 0.5 µm) the
//! clr NDF time against the SciPy LSODA time, with clr's time at LSODA's error interpolated
//! log-log between the two clr sweep points that bracket it (loosest bracketing pair), and, as
//! a check, the cheapest clr sweep point whose error is ≤ LSODA's; (b) clr NDF at rtol 1e-6
//! against Exudyn h = 1e-5: time ratio and accuracy ratio (and clr's interpolated time at
//! Exudyn's error).
//!
//! Output: `target/bench/mbd.json` `{"machine", "reference", "rows": [...], "sweep": [...],
//! "ratios": [...]}`, `target/bench/mbd.md` (the table with the time ratios to clr NDF, the
//! sweep table and the ratios) and the work–precision figure (error at 10 ms against wall
//! time, log-log) `target/bench/mbd_work_precision.{svg,png}` (with `--docs-figures` also
//! `docs/figures/bench_mbd_work_precision.{svg,png}`).

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

use clr_mbd::{SimOptions, SolverKind};
use clr_models::slider_crank::SliderCrankParams;
use clr_plot::Figure;
use serde::{Deserialize, Serialize};

use super::ode::machine;
use super::peers::ensure_venv;
use super::{parse_next, parsed_or_report, with_series};
use crate::minimal_slider_crank::minimal_slider_positions;

/// Output times: the two compared instants and the end of the run, s.
const TIMES: [f64; 3] = [0.005, 0.010, 0.1];
/// clr tolerances (issue 5: rtol 1e-6; atol as the built-in model's default 1e-3·rtol).
const RTOL: f64 = 1e-6;
const ATOL: f64 = 1e-9;
/// Input coefficient of restitution of the benchmark.
const C_E: f64 = 0.9;
/// Work–precision sweep: clr NDF rtols (atol = 1e-3·rtol).
const SWEEP_CLR: [f64; 6] = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
/// Work–precision sweep: SciPy rtols (atol = 1e-3·rtol).
const SWEEP_SCIPY: [f64; 5] = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
/// Work–precision sweep: Exudyn fixed steps, s.
const SWEEP_EXUDYN: [f64; 3] = [1e-5, 3e-6, 1e-6];
/// Error level of issue 13's equal-accuracy comparison with LSODA, m.
const EQUAL_ERROR: f64 = 0.5e-6;

/// One row of the table.
#[derive(Debug, Clone, Serialize)]
struct Row {
    solver: String,
    /// "rtol 1e-6" or "h 1e-5".
    setting: String,
    /// Relative tolerance (adaptive solvers).
    #[serde(skip_serializing_if = "Option::is_none")]
    rtol: Option<f64>,
    /// Fixed step, s (Exudyn).
    #[serde(skip_serializing_if = "Option::is_none")]
    h: Option<f64>,
    /// Median wall time of one solve (s).
    wall_s: f64,
    repeats: usize,
    /// Accepted steps (fixed steps for Exudyn; `None` where the solver does not report them).
    steps: Option<usize>,
    /// Located contact onsets (`None` where not applicable).
    onsets: Option<usize>,
    /// Slider position at 5 ms and 10 ms, m.
    x: [f64; 2],
    /// |x − x_ref| at 5 ms and 10 ms, m.
    error: [f64; 2],
}

#[derive(Serialize)]
struct Reference {
    method: &'static str,
    x: [f64; 2],
    onsets: usize,
}

/// A ratio of the sweep (issue 13).
#[derive(Debug, Clone, Serialize)]
struct Ratio {
    /// What is compared.
    what: String,
    /// The ratio (clr / peer for times, peer / clr for errors).
    value: f64,
    /// The numbers it comes from and how.
    detail: String,
}

#[derive(Serialize)]
struct Report<'a> {
    machine: String,
    reference: Reference,
    rows: &'a [Row],
    /// Work–precision sweep (slider error at 10 ms against wall time of the 0.1 s run).
    sweep: &'a [Row],
    ratios: &'a [Ratio],
    notes: &'a [String],
}

/// A row printed by one of the Python peers.
#[derive(Debug, Deserialize)]
struct PeerRow {
    solver: String,
    #[serde(default)]
    rtol: Option<f64>,
    #[serde(default)]
    h: Option<f64>,
    wall_s: f64,
    repeats: usize,
    #[serde(default)]
    steps: Option<usize>,
    #[serde(default)]
    onsets: Option<usize>,
    x: Vec<f64>,
}

struct Args {
    min_time: f64,
    scipy: bool,
    exudyn: bool,
    exudyn_steps: String,
    sweep: bool,
    docs_figures: bool,
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        min_time: 1.0,
        scipy: true,
        exudyn: true,
        exudyn_steps: "1e-5,1e-6".to_string(),
        sweep: true,
        docs_figures: false,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--min-time" => {
                a.min_time = parse_next(
                    &mut it,
                    |v: &f64| *v >= 0.0,
                    "--min-time needs a non-negative number of seconds",
                )?;
            }
            "--exudyn-h" => {
                a.exudyn_steps = it
                    .next()
                    .cloned()
                    .ok_or("--exudyn-h needs comma-separated step sizes, e.g. 1e-5,1e-6")?;
            }
            "--no-scipy" => a.scipy = false,
            "--no-exudyn" => a.exudyn = false,
            "--no-sweep" => a.sweep = false,
            "--docs-figures" => a.docs_figures = true,
            other => return Err(format!("bench mbd: unknown argument {other}")),
        }
    }
    Ok(a)
}

/// Median-timed clr solve with `solver` at (rtol, atol); the model is rebuilt before every
/// solve, outside the timer. Returns (median wall s, repeats, steps, onsets, x at 5 and 10 ms).
fn clr_run(
    solver: SolverKind,
    rtol: f64,
    atol: f64,
    min_time: f64,
) -> Result<(f64, usize, usize, usize, [f64; 2]), String> {
    let p = SliderCrankParams::flores();
    let mut opts = SimOptions::default()
        .times(TIMES.to_vec())
        .tolerances(rtol, atol)
        .solver(solver);
    opts.t_end = p.duration;
    let mut walls = Vec::new();
    loop {
        let mut m = p.build("slider_crank").map_err(|e| e.to_string())?;
        let start = Instant::now();
        let res = m.simulate(&opts).map_err(|e| e.to_string())?;
        walls.push(start.elapsed().as_secs_f64());
        let total: f64 = walls.iter().sum();
        if walls.len() >= 1000 || (walls.len() >= 5 && total >= min_time) {
            let x = res.column("slider.x").ok_or("no slider.x column")?;
            let n = walls.len();
            walls.sort_by(f64::total_cmp);
            return Ok((
                walls[n / 2],
                n,
                res.stats.accepted,
                res.onsets,
                [x[0], x[1]],
            ));
        }
    }
}

/// Table row of a [`clr_run`] result (median wall s, repeats, steps, onsets, x at 5 and 10 ms)
/// of `solver` at `rtol`, described by `setting`, with its error against `x_ref`.
fn clr_row(
    solver: &str,
    setting: String,
    rtol: f64,
    (wall_s, repeats, steps, onsets, x): (f64, usize, usize, usize, [f64; 2]),
    x_ref: [f64; 2],
) -> Row {
    Row {
        solver: solver.to_string(),
        setting,
        rtol: Some(rtol),
        h: None,
        wall_s,
        repeats,
        steps: Some(steps),
        onsets: Some(onsets),
        x,
        error: [(x[0] - x_ref[0]).abs(), (x[1] - x_ref[1]).abs()],
    }
}

/// Run a Python peer script of `bench/` with the venv interpreter and parse its JSON lines.
pub(super) fn run_peer<T: serde::de::DeserializeOwned>(
    root: &Path,
    python: &Path,
    script: &str,
    args: &[&str],
) -> Result<Vec<T>, String> {
    eprintln!("bench: running bench/{script}");
    let out = Command::new(python)
        .current_dir(root)
        .arg(root.join("bench").join(script))
        .args(args)
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| {
            format!(
                "{script} could not be started with {}: {e}",
                python.display()
            )
        })?;
    let rows: Vec<T> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter(|l| l.trim_start().starts_with('{'))
        .map(|l| serde_json::from_str(l).map_err(|e| format!("{script}: unreadable row {l}: {e}")))
        .collect::<Result<_, _>>()?;
    if !out.status.success() || rows.is_empty() {
        return Err(format!(
            "{script} exited with {} and {} rows",
            out.status,
            rows.len()
        ));
    }
    Ok(rows)
}

/// Make sure `exudyn` can be imported from the venv (pip-installing it otherwise).
pub(super) fn ensure_exudyn(python: &Path) -> Result<(), String> {
    let importable = || {
        Command::new(python)
            .args(["-c", "import exudyn"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if importable() {
        return Ok(());
    }
    eprintln!("bench mbd: installing exudyn into bench/.venv with pip");
    let status = Command::new(python)
        .args(["-m", "pip", "install", "--quiet", "exudyn"])
        .status()
        .map_err(|e| format!("pip could not be started ({e})"))?;
    if !status.success() || !importable() {
        return Err(format!(
            "`pip install exudyn` into bench/.venv failed ({status}); install it there by hand"
        ));
    }
    Ok(())
}

fn peer_row(r: PeerRow, x_ref: [f64; 2]) -> Result<Row, String> {
    if r.x.len() < 2 {
        return Err(format!("{}: fewer than two output positions", r.solver));
    }
    let setting = match (r.rtol, r.h) {
        (_, Some(h)) => format!("h {h:e} (fixed)"),
        (Some(rtol), None) => format!("rtol {rtol:e}"),
        (None, None) => String::new(),
    };
    Ok(Row {
        solver: r.solver,
        setting,
        rtol: if r.h.is_some() { None } else { r.rtol },
        h: r.h,
        wall_s: r.wall_s,
        repeats: r.repeats,
        steps: r.steps,
        onsets: r.onsets,
        x: [r.x[0], r.x[1]],
        error: [(r.x[0] - x_ref[0]).abs(), (r.x[1] - x_ref[1]).abs()],
    })
}

fn fmt_opt(v: Option<usize>) -> String {
    v.map_or("–".to_string(), |v| v.to_string())
}

fn markdown(machine: &str, reference: &Reference, rows: &[Row], notes: &[String]) -> String {
    let base = rows
        .iter()
        .find(|r| r.solver == "clr-ndf")
        .map(|r| r.wall_s);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Clearance slider–crank of issue 5 (5000 rpm, c = 0.5 mm, L–N c_e = 0.9, 0.1 s). \
         Machine: {machine}.\n\nReference: {} (x(5 ms) = {:.9} m, x(10 ms) = {:.9} m, {} onsets \
         to 10 ms).\n",
        reference.method, reference.x[0], reference.x[1], reference.onsets
    );
    let _ = writeln!(
        s,
        "| solver | setting | wall time (ms) | steps | onsets | error at 5 ms (µm) | error at 10 ms (µm) | time / clr NDF |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let ratio = base.map_or("–".to_string(), |b| format!("{:.1}", r.wall_s / b));
        let _ = writeln!(
            s,
            "| {} | {} | {:.2} | {} | {} | {:.3} | {:.3} | {} |",
            r.solver,
            r.setting,
            r.wall_s * 1e3,
            fmt_opt(r.steps),
            fmt_opt(r.onsets),
            r.error[0] * 1e6,
            r.error[1] * 1e6,
            ratio
        );
    }
    if !notes.is_empty() {
        let _ = writeln!(s);
        for n in notes {
            let _ = writeln!(s, "- {n}");
        }
    }
    s
}

/// Comma-separated step sizes (unparsable entries are dropped).
fn parse_steps(list: &str) -> Vec<f64> {
    list.split(',')
        .filter_map(|s| s.trim().parse().ok())
        .collect()
}

/// clr NDF sweep points (rtol, wall s, error at 10 ms), loosest first.
fn clr_points(sweep: &[Row]) -> Vec<(f64, f64, f64)> {
    let mut pts: Vec<(f64, f64, f64)> = sweep
        .iter()
        .filter(|r| r.solver == "clr-ndf")
        .map(|r| (r.rtol.unwrap_or(f64::NAN), r.wall_s, r.error[1]))
        .collect();
    pts.sort_by(|a, b| b.0.total_cmp(&a.0));
    pts
}

/// clr NDF's time at error `err` (m, at 10 ms), interpolated log-log between the loosest pair
/// of consecutive sweep points whose errors bracket it: (time s, the two rtols).
pub(super) fn clr_time_interpolated(pts: &[(f64, f64, f64)], err: f64) -> Option<(f64, f64, f64)> {
    pts.windows(2).find_map(|w| {
        let ((ra, ta, ea), (rb, tb, eb)) = (w[0], w[1]);
        if !(ea > 0.0 && eb > 0.0 && err > 0.0) || err < ea.min(eb) || err > ea.max(eb) {
            return None;
        }
        let s = if ea == eb {
            0.0
        } else {
            (err.ln() - ea.ln()) / (eb.ln() - ea.ln())
        };
        Some(((ta.ln() + s * (tb.ln() - ta.ln())).exp(), ra, rb))
    })
}

/// The cheapest clr NDF sweep point with error at 10 ms ≤ `err`: (time s, rtol, error m).
fn clr_time_cheapest(pts: &[(f64, f64, f64)], err: f64) -> Option<(f64, f64, f64)> {
    pts.iter()
        .filter(|p| p.2 <= err)
        .map(|&(r, t, e)| (t, r, e))
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// The ratios of issue 13 from the sweep (module docs).
fn sweep_ratios(sweep: &[Row], rows: &[Row], notes: &mut Vec<String>) -> Vec<Ratio> {
    let pts = clr_points(sweep);
    let mut out = Vec::new();
    // (a) equal error with LSODA
    let mut lsoda: Vec<&Row> = sweep
        .iter()
        .filter(|r| r.solver == "scipy-lsoda" && r.error[1] <= EQUAL_ERROR)
        .collect();
    lsoda.sort_by(|a, b| b.rtol.unwrap_or(0.0).total_cmp(&a.rtol.unwrap_or(0.0)));
    if lsoda.is_empty() && sweep.iter().any(|r| r.solver == "scipy-lsoda") {
        notes.push(format!(
            "no SciPy LSODA sweep point reaches an error at 10 ms ≤ {} µm",
            EQUAL_ERROR * 1e6
        ));
    }
    for l in lsoda {
        let e = l.error[1];
        let rtol = l.rtol.unwrap_or(f64::NAN);
        if let Some((t, ra, rb)) = clr_time_interpolated(&pts, e) {
            out.push(Ratio {
                what: format!(
                    "clr NDF time / SciPy LSODA time at equal error at 10 ms (LSODA rtol \
                     {rtol:.0e}, error {:.3} µm), clr interpolated log-log",
                    e * 1e6
                ),
                value: t / l.wall_s,
                detail: format!(
                    "clr {:.3} ms (between its rtol {ra:.0e} and {rb:.0e} points) vs LSODA {:.3} ms",
                    t * 1e3,
                    l.wall_s * 1e3
                ),
            });
        }
        if let Some((t, r, ec)) = clr_time_cheapest(&pts, e) {
            out.push(Ratio {
                what: format!(
                    "clr NDF time / SciPy LSODA time at equal error at 10 ms (LSODA rtol \
                     {rtol:.0e}, error {:.3} µm), cheapest clr point with error ≤ LSODA's",
                    e * 1e6
                ),
                value: t / l.wall_s,
                detail: format!(
                    "clr rtol {r:.0e}: {:.3} ms, error {:.3} µm vs LSODA {:.3} ms",
                    t * 1e3,
                    ec * 1e6,
                    l.wall_s * 1e3
                ),
            });
        } else {
            notes.push(format!(
                "no clr NDF sweep point reaches LSODA's error {:.4} µm (rtol {rtol:.0e}; the smallest clr error is {:.4} µm)",
                e * 1e6,
                pts.iter().map(|p| p.2).fold(f64::INFINITY, f64::min) * 1e6
            ));
        }
    }
    // (b) clr NDF rtol 1e-6 against Exudyn h = 1e-5
    let clr = rows.iter().find(|r| r.solver == "clr-ndf");
    let exu = sweep
        .iter()
        .chain(rows)
        .find(|r| r.solver.starts_with("exudyn") && r.h.is_some_and(|h| (h - 1e-5).abs() < 1e-12));
    if let (Some(c), Some(x)) = (clr, exu) {
        out.push(Ratio {
            what: "clr NDF (rtol 1e-6) time / Exudyn (h = 1e-5) time".into(),
            value: c.wall_s / x.wall_s,
            detail: format!(
                "clr {:.3} ms vs Exudyn {:.3} ms",
                c.wall_s * 1e3,
                x.wall_s * 1e3
            ),
        });
        out.push(Ratio {
            what: "Exudyn (h = 1e-5) error / clr NDF (rtol 1e-6) error at 10 ms (accuracy ratio)"
                .into(),
            value: x.error[1] / c.error[1],
            detail: format!(
                "Exudyn {:.3} µm vs clr {:.3} µm (at 5 ms: {:.3} vs {:.3} µm)",
                x.error[1] * 1e6,
                c.error[1] * 1e6,
                x.error[0] * 1e6,
                c.error[0] * 1e6
            ),
        });
        if let Some((t, ra, rb)) = clr_time_interpolated(&pts, x.error[1]) {
            out.push(Ratio {
                what: "clr NDF time / Exudyn (h = 1e-5) time at Exudyn's error at 10 ms, clr \
                       interpolated log-log"
                    .into(),
                value: t / x.wall_s,
                detail: format!(
                    "clr {:.3} ms (between its rtol {ra:.0e} and {rb:.0e} points) vs Exudyn {:.3} ms",
                    t * 1e3,
                    x.wall_s * 1e3
                ),
            });
        }
    }
    out
}

/// The sweep table and the ratios, as Markdown.
fn sweep_markdown(sweep: &[Row], ratios: &[Ratio]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\nWork–precision sweep (issue 13): wall time of the whole 0.1 s run against the slider \
         error at 10 ms. clr NDF rtol 1e-5 … 1e-10, SciPy LSODA/BDF rtol 1e-6 … 1e-10 (atol = \
         1e-3·rtol for both), Exudyn generalized-α at fixed h.\n"
    );
    let _ = writeln!(
        s,
        "| solver | setting | wall time (ms) | steps | onsets | error at 5 ms (µm) | error at 10 ms (µm) |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|");
    for r in sweep {
        let _ = writeln!(
            s,
            "| {} | {} | {:.2} | {} | {} | {:.4} | {:.4} |",
            r.solver,
            r.setting,
            r.wall_s * 1e3,
            fmt_opt(r.steps),
            fmt_opt(r.onsets),
            r.error[0] * 1e6,
            r.error[1] * 1e6
        );
    }
    if !ratios.is_empty() {
        let _ = writeln!(s);
        for r in ratios {
            let _ = writeln!(s, "- {}: **{:.3}** ({})", r.what, r.value, r.detail);
        }
    }
    s
}

/// Work–precision figure: error at 10 ms against wall time, log-log, one series per solver.
fn figure(sweep: &[Row], stem: &Path) -> Result<(), String> {
    let mut fig = Figure::new("Clearance slider–crank: slider error at 10 ms against wall time")
        .x_label("median wall time of the 0.1 s run (ms)")
        .y_label("|x − x_ref| at 10 ms (µm)")
        .log_x()
        .log_y();
    let mut any = false;
    for (solver, label) in [
        ("clr-ndf", "clr NDF (rtol 1e-5…1e-10)"),
        ("exudyn-genalpha", "Exudyn gen.-α (h 1e-5, 3e-6, 1e-6)"),
        ("scipy-lsoda", "SciPy LSODA (rtol 1e-6…1e-10)"),
        ("scipy-bdf", "SciPy BDF (rtol 1e-6…1e-10)"),
    ] {
        let pts: Vec<(f64, f64, f64)> = sweep
            .iter()
            .filter(|r| r.solver == solver && r.error[1] > 0.0)
            .map(|r| {
                (
                    r.rtol.or(r.h).unwrap_or(0.0),
                    r.wall_s * 1e3,
                    r.error[1] * 1e6,
                )
            })
            .collect();
        if pts.is_empty() {
            continue;
        }
        any = true;
        fig = with_series(fig, label, pts);
    }
    if !any {
        return Err("no sweep point".into());
    }
    fig.save(stem).map(|_| ()).map_err(|e| e.to_string())
}

pub fn run(args: &[String]) -> ExitCode {
    let Some(a) = parsed_or_report(parse_args(args), "") else {
        return ExitCode::from(2);
    };
    let root = crate::workspace_root();
    let machine = machine();
    let omega = SliderCrankParams::flores().omega();
    let (x_ref, onsets_ref) = match minimal_slider_positions(omega, C_E, &TIMES[..2]) {
        Ok((x, n)) => ([x[0], x[1]], n),
        Err(e) => {
            eprintln!("bench mbd: the reference solve failed: {e}");
            return ExitCode::FAILURE;
        }
    };
    let reference = Reference {
        method: "independent minimal-coordinate formulation (xtask/src/minimal_slider_crank.rs), \
                 DOPRI5 rtol 1e-12, located onsets",
        x: x_ref,
        onsets: onsets_ref,
    };
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    for (name, kind) in [
        ("clr-ndf", SolverKind::Ndf),
        ("clr-dopri5", SolverKind::Dopri5),
    ] {
        eprintln!("bench mbd: {name}");
        match clr_run(kind, RTOL, ATOL, a.min_time) {
            Ok(run) => rows.push(clr_row(
                name,
                format!("rtol {RTOL:e}, atol {ATOL:e}"),
                RTOL,
                run,
                x_ref,
            )),
            Err(e) => notes.push(format!("{name} failed: {e}")),
        }
    }
    let min_time = format!("{}", 2.0 * a.min_time);
    let python = if a.scipy || a.exudyn {
        match ensure_venv(&root) {
            Ok(p) => Some(p),
            Err(e) => {
                notes.push(format!("Python peers skipped: {e}"));
                None
            }
        }
    } else {
        None
    };
    let mut sweep = Vec::new();
    if a.sweep {
        for rtol in SWEEP_CLR {
            let atol = 1e-3 * rtol;
            eprintln!("bench mbd: sweep clr-ndf rtol {rtol:e}");
            match clr_run(SolverKind::Ndf, rtol, atol, a.min_time) {
                Ok(run) => sweep.push(clr_row(
                    "clr-ndf",
                    format!("rtol {rtol:.0e}, atol {atol:.0e}"),
                    rtol,
                    run,
                    x_ref,
                )),
                Err(e) => notes.push(format!("sweep: clr-ndf at rtol {rtol:e} failed: {e}")),
            }
        }
    }
    let main_h = parse_steps(&a.exudyn_steps);
    let same = |x: f64, y: f64| (x - y).abs() <= 1e-9 * y.abs();
    if let Some(python) = &python {
        let mut peer = |who: &str, r: Result<Vec<PeerRow>, String>| match r {
            Ok(list) => {
                let mut out = Vec::new();
                for p in list {
                    match peer_row(p, x_ref) {
                        Ok(row) => out.push(row),
                        Err(e) => notes.push(e),
                    }
                }
                out
            }
            Err(e) => {
                notes.push(format!("{who} not measured: {e}"));
                Vec::new()
            }
        };
        if a.exudyn {
            // one run of the script for the main table's and the sweep's step sizes
            let mut steps = main_h.clone();
            if a.sweep {
                for h in SWEEP_EXUDYN {
                    if !steps.iter().any(|&s| same(s, h)) {
                        steps.push(h);
                    }
                }
            }
            let steps = steps
                .iter()
                .map(|h| format!("{h:e}"))
                .collect::<Vec<_>>()
                .join(",");
            let r = ensure_exudyn(python).and_then(|()| {
                run_peer(
                    &root,
                    python,
                    "exudyn_slider_crank.py",
                    &["--h", &steps, "--min-time", &min_time],
                )
            });
            for row in peer("Exudyn", r) {
                let h = row.h.unwrap_or(f64::NAN);
                if a.sweep && SWEEP_EXUDYN.iter().any(|&s| same(s, h)) {
                    sweep.push(row.clone());
                }
                if main_h.iter().any(|&s| same(s, h)) {
                    rows.push(row);
                }
            }
        }
        if a.scipy {
            // the sweep's rtol 1e-6 (atol 1e-9) is the main table's setting
            let rtols = if a.sweep {
                SWEEP_SCIPY
                    .iter()
                    .map(|r| format!("{r:e}"))
                    .collect::<Vec<_>>()
                    .join(",")
            } else {
                format!("{RTOL:e}")
            };
            let r = run_peer(
                &root,
                python,
                "scipy_slider_crank.py",
                &[
                    "--rtols",
                    &rtols,
                    "--atol-ratio",
                    "1e-3",
                    "--min-time",
                    &min_time,
                ],
            );
            for row in peer("SciPy", r) {
                let rtol = row.rtol.unwrap_or(f64::NAN);
                if a.sweep {
                    sweep.push(row.clone());
                }
                if same(rtol, RTOL) {
                    rows.push(row);
                }
            }
        }
    }
    let ratios = if a.sweep {
        sweep_ratios(&sweep, &rows, &mut notes)
    } else {
        Vec::new()
    };
    let mut md = markdown(&machine, &reference, &rows, &notes);
    if a.sweep {
        md.push_str(&sweep_markdown(&sweep, &ratios));
    }
    print!("{md}");
    let dir = crate::target_dir().join("bench");
    if a.sweep {
        let mut stems = vec![dir.join("mbd_work_precision")];
        if a.docs_figures {
            stems.push(
                root.join("docs")
                    .join("figures")
                    .join("bench_mbd_work_precision"),
            );
        }
        for stem in stems {
            if let Some(parent) = stem.parent() {
                let _ = std::fs::create_dir_all(parent);
            }
            match figure(&sweep, &stem) {
                Ok(()) => eprintln!("bench mbd: wrote {}.{{svg,png}}", stem.display()),
                Err(e) => eprintln!("bench mbd: figure {}: {e}", stem.display()),
            }
        }
    }
    let report = Report {
        machine,
        reference,
        rows: &rows,
        sweep: &sweep,
        ratios: &ratios,
        notes: &notes,
    };
    let written = std::fs::create_dir_all(&dir)
        .map_err(|e| e.to_string())
        .and_then(|()| serde_json::to_string_pretty(&report).map_err(|e| e.to_string()))
        .and_then(|json| std::fs::write(dir.join("mbd.json"), json).map_err(|e| e.to_string()))
        .and_then(|()| std::fs::write(dir.join("mbd.md"), &md).map_err(|e| e.to_string()));
    match written {
        Ok(()) => {
            eprintln!("bench mbd: wrote {}/mbd.{{json,md}}", dir.display());
            if rows.iter().any(|r| r.solver.starts_with("clr")) {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Err(e) => {
            eprintln!("bench mbd: could not write {}: {e}", dir.display());
            ExitCode::FAILURE
        }
    }
}
