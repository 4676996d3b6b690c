//! `cargo xtask bench spatial`: a pendulum hanging in a spherical clearance joint (issue 31),
//! clr's spatial engine against Exudyn's hollow-sphere contact (`ObjectContactSphereSphere`
//! with `isHollowSphere1`, the pip package, `bench/exudyn_sphere_pendulum.py`) with the same
//! law and parameters, in one run; and the clearance slider–crank with a spatial revolute
//! clearance joint against the planar engine on the same mechanism (issue 32,
//! [`super::spatial_crank`]).
//!
//! Model (every number in the peer script's docstring): socket of radius 10 mm on the ground,
//! ball of 9.5 mm at the pendulum's reference point B; pendulum 1 kg, centre of mass 0.2 m from
//! B along its −z axis, principal inertia (0.004, 0.004, 0.0002) kg·m²; started tilted 30° about
//! x with ω = (0, 0, 3) rad/s and B at rest in the centred socket; gravity 9.81 m/s² along −z.
//! Hertz sphere-in-sphere stiffness K = (4/3)E*√(R_sR_b/(R_s − R_b)) (steel), exponent 1.5,
//! Lankarani–Nikravesh damping with c_e = 0.9 (Exudyn: impact model 1 with e = (1 + c_e²)/2),
//! impact-velocity floor 1e-4 m/s in both, no friction.
//!
//! Window: 0.1 s, the contact-rich start (about 30 impacts while the ball chatters down into
//! persistent contact). Beyond it both codes keep the impact velocity of the last onset as
//! the damping's δ̇⁻ for the whole persistent contact, and that value changes with the step,
//! so positions later in the run do not converge cleanly with the step in either code (the
//! peer's notes); the window is where the comparison is meaningful.
//!
//! Reference: clr with DOPRI5 at rtol 1e-12 (a different integrator from the NDF runs
//! measured), whose agreement with Exudyn's finest step is reported. Error: the largest
//! distance of the centre of mass from the reference at t = 0.02, 0.05 and 0.09 s. The
//! work–precision comparison interpolates clr NDF's wall time at each Exudyn point's error
//! (log–log, as `bench mbd`).

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use clr_mbd::spatial::SpatialDesc;
use clr_mbd::{SimOptions, SolverKind};
use serde::{Deserialize, Serialize};

use super::mbd::{clr_time_interpolated, ensure_exudyn, run_peer};
use super::ode::machine;
use super::peers::ensure_venv;

/// Output times of the comparison, s.
const TIMES: [f64; 3] = [0.02, 0.05, 0.09];
/// End of the window, s.
const T_END: f64 = 0.1;
/// clr NDF tolerances of the sweep.
const SWEEP: [f64; 6] = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
/// Exudyn's step sizes, s.
const EXUDYN_H: &str = "1e-4,3e-5,1e-5,3e-6,1e-6";

/// The pendulum as a spatial model file.
const MODEL: &str = r#"
[model]
name = "sphere_pendulum"
space = "spatial"
gravity = [0.0, 0.0, -9.81]
[[body]]
name = "pendulum"
mass = 1.0
principal_inertia = [0.004, 0.004, 0.0002]
centre_of_mass = [0.0, 0.0, -0.2]
position = [0.0, 0.0, 0.0]
orientation = { axis = [1.0, 0.0, 0.0], angle = 0.5235987755982988 }
velocity = [0.0, 0.0, 0.0]
velocity_frame = "world"
angular_velocity = [0.0, 0.0, 3.0]
angular_velocity_frame = "world"
[[clearance]]
name = "socket"
type = "spherical"
socket = { body = "ground", at = [0.0, 0.0, 0.0] }
ball = { body = "pendulum", at = [0.0, 0.0, 0.0] }
socket_radius = 0.010
ball_radius = 0.0095
normal = { law = "hertz-internal-sphere", damping = "lankarani-nikravesh", restitution = 0.9, min_impact_velocity = 1e-4, bearing_material = { youngs_modulus = 207e9, poisson_ratio = 0.3 }, journal_material = { youngs_modulus = 207e9, poisson_ratio = 0.3 } }
[output]
t_end = 0.1
intervals = 10
"#;

/// One row of the table.
#[derive(Debug, Clone, Serialize)]
struct Row {
    solver: String,
    /// clr's rtol (None for the peer).
    rtol: Option<f64>,
    setting: String,
    wall_s: f64,
    repeats: usize,
    steps: usize,
    onsets: Option<usize>,
    /// Largest centre-of-mass distance from the reference over [`TIMES`], m.
    error: f64,
}

/// A row of the peer script.
#[derive(Debug, Deserialize)]
struct PeerRow {
    h: f64,
    wall_s: f64,
    repeats: usize,
    steps: usize,
    #[serde(default)]
    onsets: Option<usize>,
    com: Vec<[f64; 3]>,
}

/// (median wall s, repeats, steps, onsets, centre of mass at [`TIMES`]) of one clr setting.
type ClrRun = (f64, usize, usize, usize, Vec<[f64; 3]>);

/// Centre of mass at [`TIMES`] from one clr run with (solver, rtol); (wall s, steps, onsets,
/// positions), the model compiled outside the timer, median over repeats.
fn clr_run(solver: SolverKind, rtol: f64, min_time: f64) -> Result<ClrRun, String> {
    let desc = SpatialDesc::from_toml_table(MODEL.parse().map_err(|e| format!("{e}"))?)
        .map_err(|e| e.to_string())?;
    let mut opts = SimOptions::default()
        .times(TIMES.to_vec())
        .tolerances(rtol, 1e-3 * rtol)
        .solver(solver);
    opts.t_end = T_END;
    let mut walls = Vec::new();
    loop {
        let mut m = desc.compile().map_err(|e| e.to_string())?;
        let start = Instant::now();
        let r = m.simulate(&opts).map_err(|e| e.to_string())?;
        walls.push(start.elapsed().as_secs_f64());
        let total: f64 = walls.iter().sum();
        if walls.len() >= 200 || (walls.len() >= 3 && total >= min_time) {
            let col = |c: &str| r.column(&format!("pendulum.{c}")).unwrap_or_default();
            let (x, y, z) = (col("x"), col("y"), col("z"));
            let com = (0..x.len()).map(|k| [x[k], y[k], z[k]]).collect();
            let n = walls.len();
            walls.sort_by(f64::total_cmp);
            return Ok((walls[n / 2], n, r.stats.accepted, r.onsets, com));
        }
    }
}

fn distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
        })
        .fold(if a.len() == b.len() { 0.0 } else { f64::NAN }, f64::max)
}

fn markdown(machine: &str, rows: &[Row], ratios: &[String], notes: &[String]) -> String {
    let mut s = format!(
        "# bench spatial: pendulum in a spherical clearance joint, 0.1 s\n\nMachine: \
         {machine}. Error: largest centre-of-mass distance from the reference (clr DOPRI5, \
         rtol 1e-12) at t = 0.02, 0.05, 0.09 s.\n\n| solver | setting | wall (ms) | repeats | \
         steps | onsets | error (m) |\n|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {:.3} | {} | {} | {} | {:.2e} |\n",
            r.solver,
            r.setting,
            r.wall_s * 1e3,
            r.repeats,
            r.steps,
            r.onsets.map_or("–".into(), |n| n.to_string()),
            r.error
        ));
    }
    s.push_str("\nEqual-error ratios (clr NDF time interpolated log–log at the peer's error):\n\n");
    for r in ratios {
        s.push_str(&format!("- {r}\n"));
    }
    for n in notes {
        s.push_str(&format!("\nNote: {n}\n"));
    }
    s
}

/// Run the benchmark (`--min-time S`, `--exudyn-h LIST`, `--no-exudyn`).
pub fn run(args: &[String]) -> ExitCode {
    let mut min_time = 0.5;
    let mut exudyn = true;
    let mut steps = EXUDYN_H.to_string();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--min-time" => match it.next().and_then(|v| v.parse().ok()) {
                Some(v) => min_time = v,
                None => {
                    eprintln!("--min-time needs seconds");
                    return ExitCode::from(2);
                }
            },
            "--exudyn-h" => match it.next() {
                Some(v) => steps = v.clone(),
                None => {
                    eprintln!("--exudyn-h needs a comma-separated list of steps (s)");
                    return ExitCode::from(2);
                }
            },
            "--no-exudyn" => exudyn = false,
            other => {
                eprintln!("bench spatial: unknown option {other}");
                return ExitCode::from(2);
            }
        }
    }
    let root = crate::workspace_root();
    let reference = match clr_run(SolverKind::Dopri5, 1e-12, 0.0) {
        Ok(r) => r.4,
        Err(e) => {
            eprintln!("bench spatial: the reference run failed: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    for rtol in SWEEP {
        eprintln!("bench spatial: clr NDF rtol {rtol:e}");
        match clr_run(SolverKind::Ndf, rtol, min_time) {
            Ok((wall_s, repeats, steps, onsets, com)) => rows.push(Row {
                solver: "clr-ndf".into(),
                rtol: Some(rtol),
                setting: format!("rtol {rtol:.0e}"),
                wall_s,
                repeats,
                steps,
                onsets: Some(onsets),
                error: distance(&com, &reference),
            }),
            Err(e) => notes.push(format!("clr NDF at rtol {rtol:e} failed: {e}")),
        }
    }
    if exudyn {
        if let Err(e) = peer_rows(&root, &steps, min_time, &reference, &mut rows) {
            notes.push(format!("Exudyn not measured: {e}"));
        }
    }
    let ratios = ratios(&rows);
    let (crank, crank_notes) = super::spatial_crank::rows(min_time);
    notes.extend(crank_notes);
    let out = root.join("target").join("bench");
    let mut md = markdown(&machine(), &rows, &ratios, &notes);
    md.push_str(&super::spatial_crank::markdown(&crank));
    let json = serde_json::json!({
        "rows": rows,
        "ratios": ratios,
        "slider_crank": crank,
        "notes": notes
    });
    let written = std::fs::create_dir_all(&out)
        .and_then(|()| std::fs::write(out.join("spatial.md"), &md))
        .and_then(|()| std::fs::write(out.join("spatial.json"), json.to_string()));
    if let Err(e) = written {
        eprintln!("bench spatial: cannot write target/bench: {e}");
        return ExitCode::FAILURE;
    }
    println!("{md}");
    ExitCode::SUCCESS
}

fn peer_rows(
    root: &Path,
    steps: &str,
    min_time: f64,
    reference: &[[f64; 3]],
    rows: &mut Vec<Row>,
) -> Result<(), String> {
    let python = ensure_venv(root)?;
    ensure_exudyn(&python)?;
    let times = TIMES.map(|t| t.to_string()).join(",");
    let t_end = T_END.to_string();
    let min_time = (2.0 * min_time).to_string();
    let list: Vec<PeerRow> = run_peer(
        root,
        &python,
        "exudyn_sphere_pendulum.py",
        &[
            "--h",
            steps,
            "--times",
            &times,
            "--t-end",
            &t_end,
            "--min-impact-velocity",
            "1e-4",
            "--min-time",
            &min_time,
            "--onsets",
        ],
    )?;
    for p in list {
        rows.push(Row {
            solver: "exudyn-genalpha".into(),
            rtol: None,
            setting: format!("h {:.0e}", p.h),
            wall_s: p.wall_s,
            repeats: p.repeats,
            steps: p.steps,
            onsets: p.onsets,
            error: distance(&p.com, reference),
        });
    }
    Ok(())
}

/// clr NDF's time at each Exudyn point's error, over the peer's time.
fn ratios(rows: &[Row]) -> Vec<String> {
    let mut pts: Vec<(f64, f64, f64)> = rows
        .iter()
        .filter(|r| r.solver == "clr-ndf")
        .map(|r| (r.rtol.unwrap_or(f64::NAN), r.wall_s, r.error))
        .collect();
    // loosest first, as `bench mbd`'s sweep
    pts.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut out = Vec::new();
    for p in rows.iter().filter(|r| r.solver.starts_with("exudyn")) {
        match clr_time_interpolated(&pts, p.error) {
            Some((t, _, _)) => out.push(format!(
                "Exudyn {}: error {:.2e} m in {:.1} ms; clr NDF reaches it in {:.2} ms: clr/Exudyn \
                 time {:.4} ({:.0}× faster)",
                p.setting,
                p.error,
                p.wall_s * 1e3,
                t * 1e3,
                t / p.wall_s,
                p.wall_s / t
            )),
            None => out.push(format!(
                "Exudyn {}: error {:.2e} m in {:.1} ms, outside clr's sweep range (no \
                 interpolated time)",
                p.setting,
                p.error,
                p.wall_s * 1e3
            )),
        }
    }
    out
}
