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
//! Output: `target/bench/mbd.json` `{"machine", "reference", "rows": [...]}` and
//! `target/bench/mbd.md` (the table with the time ratios to clr NDF).

use std::fmt::Write as _;
use std::path::Path;
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

use clr_mbd::{SimOptions, SolverKind};
use clr_models::slider_crank::SliderCrankParams;
use serde::{Deserialize, Serialize};

use super::ode::machine;
use super::peers::ensure_venv;
use crate::minimal_slider_crank::minimal_slider_positions;

/// Output times: the two compared instants and the end of the run, s.
const TIMES: [f64; 3] = [0.005, 0.010, 0.1];
/// clr tolerances (issue 5: rtol 1e-6; atol as the built-in model's default 1e-3·rtol).
const RTOL: f64 = 1e-6;
const ATOL: f64 = 1e-9;
/// Input coefficient of restitution of the benchmark.
const C_E: f64 = 0.9;

/// One row of the table.
#[derive(Debug, Clone, Serialize)]
struct Row {
    solver: String,
    /// "rtol 1e-6" or "h 1e-5".
    setting: String,
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

#[derive(Serialize)]
struct Report<'a> {
    machine: String,
    reference: Reference,
    rows: &'a [Row],
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
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        min_time: 1.0,
        scipy: true,
        exudyn: true,
        exudyn_steps: "1e-5,1e-6".to_string(),
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--min-time" => {
                a.min_time = it
                    .next()
                    .and_then(|v| v.parse().ok())
                    .filter(|v: &f64| *v >= 0.0)
                    .ok_or("--min-time needs a non-negative number of seconds")?;
            }
            "--exudyn-h" => {
                a.exudyn_steps = it
                    .next()
                    .cloned()
                    .ok_or("--exudyn-h needs comma-separated step sizes, e.g. 1e-5,1e-6")?;
            }
            "--no-scipy" => a.scipy = false,
            "--no-exudyn" => a.exudyn = false,
            other => return Err(format!("bench mbd: unknown argument {other}")),
        }
    }
    Ok(a)
}

/// Median-timed clr solve with `solver`; the model is rebuilt before every solve, outside the
/// timer. Returns (median wall s, repeats, steps, onsets, x at 5 and 10 ms).
fn clr_run(
    solver: SolverKind,
    min_time: f64,
) -> Result<(f64, usize, usize, usize, [f64; 2]), String> {
    let p = SliderCrankParams::flores();
    let mut opts = SimOptions::default()
        .times(TIMES.to_vec())
        .tolerances(RTOL, ATOL)
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

/// Run a Python peer script of `bench/` with the venv interpreter and parse its JSON lines.
fn run_peer(
    root: &Path,
    python: &Path,
    script: &str,
    args: &[&str],
) -> Result<Vec<PeerRow>, String> {
    eprintln!("bench mbd: running bench/{script}");
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
    let rows: Vec<PeerRow> = String::from_utf8_lossy(&out.stdout)
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
fn ensure_exudyn(python: &Path) -> Result<(), String> {
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

pub fn run(args: &[String]) -> ExitCode {
    let a = match parse_args(args) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
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
        match clr_run(kind, a.min_time) {
            Ok((wall_s, repeats, steps, onsets, x)) => rows.push(Row {
                solver: name.to_string(),
                setting: format!("rtol {RTOL:e}, atol {ATOL:e}"),
                wall_s,
                repeats,
                steps: Some(steps),
                onsets: Some(onsets),
                x,
                error: [(x[0] - x_ref[0]).abs(), (x[1] - x_ref[1]).abs()],
            }),
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
    if let Some(python) = &python {
        let mut peer = |who: &str, r: Result<Vec<PeerRow>, String>| match r {
            Ok(list) => {
                for p in list {
                    match peer_row(p, x_ref) {
                        Ok(row) => rows.push(row),
                        Err(e) => notes.push(e),
                    }
                }
            }
            Err(e) => notes.push(format!("{who} not measured: {e}")),
        };
        if a.exudyn {
            let r = ensure_exudyn(python).and_then(|()| {
                run_peer(
                    &root,
                    python,
                    "exudyn_slider_crank.py",
                    &["--h", &a.exudyn_steps, "--min-time", &min_time],
                )
            });
            peer("Exudyn", r);
        }
        if a.scipy {
            let r = run_peer(
                &root,
                python,
                "scipy_slider_crank.py",
                &["--rtol", "1e-6", "--atol", "1e-9", "--min-time", &min_time],
            );
            peer("SciPy", r);
        }
    }
    let md = markdown(&machine, &reference, &rows, &notes);
    print!("{md}");
    let dir = crate::target_dir().join("bench");
    let report = Report {
        machine,
        reference,
        rows: &rows,
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
