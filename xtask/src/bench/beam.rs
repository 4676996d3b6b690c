//! `cargo xtask bench beam`: cost of clr-mbd's NDF on a rigid slider in clearance on a flexible
//! cantilever guide as the guide mesh is refined (issue 13: cost per step should grow at most
//! 2.5× per 4× elements with the analytic, sparse Newton matrix).
//!
//! Model: the built-in `guide`'s beam and slider (`clr_models::guide::GuideParams::default()`,
//! the same physical beam for every mesh: 1 m aluminium cantilever, section 20 × 30 mm,
//! E = 70 GPa, ρ = 2700 kg/m³, Rayleigh α = 6 s⁻¹, clamped at the root) meshed with 10, 40
//! and 160 Euler–Bernoulli elements; the 0.5 kg slider with 0.5 mm clearance to both faces
//! (Flores line law and area law, Ambrósio friction μ = 0.1) driven along the beam at 1 m/s
//! from 0.6 m, with gravity (0, −9.81 m/s²) added here (on the slider and, since issue 29, on
//! the beam: the timings measured before it had an unloaded beam). By default the lateral load
//! is off and the slider starts with its upper pad resting on the upper face (centre one
//! clearance below the axis), so it is in contact from the start and slides along the face
//! under its weight;
//! `--lateral-load F` instead keeps the built-in's start (slider centred, F N towards the upper
//! face: an impact at ≈ 1.7 ms). NDF at rtol 1e-6 (`--rtol`), atol = 1e-3·rtol, contact onsets
//! located (the built-in's run settings with NDF), highest order 5 (`--max-order`).
//!
//! Span: 0.5 ms by default (`--t-end`). The step count grows steeply with the mesh (0.5 ms:
//! ≈ 600, 3 600 and 63 000 accepted steps for 10, 40 and 160 elements), so issue 13's 20 ms
//! would take ≈ 2.5 million steps on the finest mesh (the step budget is 10⁶); the cost per step,
//! the quantity of the target, is measured over the shorter span.
//!
//! Per mesh: coordinates n, accepted and rejected steps, Newton iterations per step, Jacobian
//! evaluations, LU factorizations, wall time of `simulate` (median of `--runs` runs, default
//! 3; the model is compiled outside the timer; a run longer than 30 s is not repeated), cost per
//! step (µs), output times (51, equally spaced) with a loaded contact element, and the growth of
//! the cost per step from one mesh to the next (4× elements; target ≤ 2.5). `--elements
//! 10,40,160` sets the meshes.
//!
//! `--jacobian fd` runs the same with `JacobianMode::FiniteDifference` (forward differences of
//! the first-order system, dense LU of size 2n + 1) instead of the analytic default; `--both`
//! runs both. Output: `target/bench/beam.json` and `target/bench/beam.md`.

use std::fmt::Write as _;
use std::process::ExitCode;
use std::time::Instant;

use clr_mbd::desc::SolverMethod;
use clr_mbd::{JacobianMode, Results, SimOptions, SolverKind};
use clr_models::guide::GuideParams;
use serde::Serialize;

use super::ode::machine;
use super::{parse_next, parsed_or_report};

const MESHES: [usize; 3] = [10, 40, 160];
/// Default relative tolerance (atol = 1e-3·rtol, the built-ins' ratio).
const RTOL: f64 = 1e-6;
/// Issue 13's target for the growth of cost per step per 4× elements.
const GROWTH_TARGET: f64 = 2.5;
/// Output intervals over the run (for the contact check).
const OUTPUTS: usize = 50;
/// A run longer than this (s) is not repeated.
const REPEAT_LIMIT: f64 = 30.0;

#[derive(Debug, Clone, Serialize)]
struct Row {
    jacobian: &'static str,
    elements: usize,
    coordinates: usize,
    steps: usize,
    rejected: usize,
    newton_iters: usize,
    jac_evals: usize,
    lu_factorizations: usize,
    onsets: usize,
    /// Output times (of [`OUTPUTS`] + 1, equally spaced over the run) with a loaded contact
    /// element.
    outputs_in_contact: usize,
    /// Median wall time of `simulate`, s.
    wall_s: f64,
    runs: usize,
    /// wall_s / steps, µs.
    us_per_step: f64,
    /// us_per_step / us_per_step of the previous (4× coarser) mesh.
    growth: Option<f64>,
}

#[derive(Serialize)]
struct Report<'a> {
    machine: String,
    model: String,
    t_end: f64,
    rtol: f64,
    atol: f64,
    max_order: usize,
    growth_target: f64,
    rows: &'a [Row],
    notes: &'a [String],
}

struct Args {
    modes: Vec<JacobianMode>,
    runs: usize,
    t_end: f64,
    gravity: bool,
    rtol: f64,
    max_order: usize,
    /// `--scale-velocity-error`: the velocities' error estimate multiplied by min(h, 1).
    scale_velocity_error: bool,
    /// `Some(F)`: the built-in's start (slider centred, lateral load F N pressing it on the
    /// upper face: an impact at ≈ 1.7 ms); `None`: slider resting on the upper face, no load.
    lateral_load: Option<f64>,
    meshes: Vec<usize>,
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        modes: vec![JacobianMode::Analytic],
        runs: 3,
        t_end: 5e-4,
        gravity: true,
        rtol: RTOL,
        max_order: 5,
        scale_velocity_error: false,
        lateral_load: None,
        meshes: MESHES.to_vec(),
    };
    let mut both = false;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--jacobian" => {
                a.modes = vec![match it.next().map(String::as_str) {
                    Some("fd") | Some("finite-difference") => JacobianMode::FiniteDifference,
                    Some("analytic") => JacobianMode::Analytic,
                    _ => return Err("--jacobian needs `analytic` or `fd`".into()),
                }];
            }
            "--both" => both = true,
            "--no-gravity" => a.gravity = false,
            "--scale-velocity-error" => a.scale_velocity_error = true,
            "--max-order" => {
                a.max_order = parse_next(
                    &mut it,
                    |v: &usize| (1..=5).contains(v),
                    "--max-order needs an order 1…5",
                )?;
            }
            "--elements" => {
                a.meshes = it
                    .next()
                    .map(|v| v.split(',').filter_map(|e| e.trim().parse().ok()).collect())
                    .filter(|v: &Vec<usize>| !v.is_empty() && v.iter().all(|&e| e > 0))
                    .ok_or("--elements needs comma-separated element counts, e.g. 10,40,160")?;
            }
            "--lateral-load" => {
                a.lateral_load = Some(parse_next(
                    &mut it,
                    |v: &f64| *v >= 0.0,
                    "--lateral-load needs a force in N (≥ 0)",
                )?);
            }
            "--rtol" => {
                a.rtol = parse_next(
                    &mut it,
                    |v: &f64| *v > 0.0 && *v < 1.0,
                    "--rtol needs a number in (0, 1)",
                )?;
            }
            "--runs" => {
                a.runs = parse_next(
                    &mut it,
                    |v: &usize| *v >= 1,
                    "--runs needs a positive integer",
                )?;
            }
            "--t-end" => {
                a.t_end = parse_next(
                    &mut it,
                    |v: &f64| *v > 0.0 && *v <= 0.2,
                    "--t-end needs a time in (0, 0.2] s",
                )?;
            }
            other => return Err(format!("bench beam: unknown argument {other}")),
        }
    }
    if both {
        a.modes = vec![JacobianMode::Analytic, JacobianMode::FiniteDifference];
    }
    Ok(a)
}

fn mode_name(m: JacobianMode) -> &'static str {
    match m {
        JacobianMode::Analytic => "analytic",
        JacobianMode::FiniteDifference => "fd",
    }
}

/// Output rows with a positive normal force in a contact element.
fn contact_rows(res: &Results) -> usize {
    let idx: Vec<usize> = res
        .columns
        .iter()
        .enumerate()
        .filter(|(_, c)| c.ends_with(".normal_force"))
        .map(|(k, _)| k)
        .collect();
    (0..res.len())
        .filter(|&r| idx.iter().any(|&k| res.row(r)[k] > 0.0))
        .count()
}

/// The guide model with `elements` elements and gravity, and its NDF run options.
fn model(
    elements: usize,
    a: &Args,
    mode: JacobianMode,
) -> Result<(clr_mbd::ModelDesc, SimOptions), String> {
    let (t_end, rtol) = (a.t_end, a.rtol);
    let p = GuideParams {
        elements,
        rtol,
        lateral_load: a.lateral_load.unwrap_or(0.0),
        solver: clr_models::common::Solver::Ndf,
        ..GuideParams::default()
    };
    let mut desc = p.desc("guide").map_err(|e| e.to_string())?;
    if a.gravity {
        desc.model.gravity = [0.0, -9.81];
    }
    if a.lateral_load.is_none() {
        // the upper pad resting on the upper face: slider centre one clearance below the axis
        for b in desc.bodies.iter_mut().filter(|b| b.name == "slider") {
            let x = b.position.map_or(0.0, |p| p[0]);
            b.position = Some([x, -p.clearance]);
        }
    }
    desc.solver.method = SolverMethod::Ndf;
    desc.solver.rtol = rtol;
    desc.solver.atol = Some(1e-3 * rtol);
    let mut opts = desc.sim_options().map_err(|e| e.to_string())?;
    opts.solver = SolverKind::Ndf;
    opts.t0 = 0.0;
    opts.t_end = t_end;
    opts.times = (0..=OUTPUTS)
        .map(|k| t_end * k as f64 / OUTPUTS as f64)
        .collect();
    opts.every_step = false;
    opts.jacobian = mode;
    opts.max_order = a.max_order;
    opts.scale_velocity_error = a.scale_velocity_error;
    Ok((desc, opts))
}

fn bench_mesh(elements: usize, a: &Args, mode: JacobianMode) -> Result<Row, String> {
    let (desc, opts) = model(elements, a, mode)?;
    let mut coordinates = 0;
    let mut walls = Vec::new();
    let mut last = None;
    while walls.len() < a.runs {
        let mut m = desc.compile().map_err(|e| e.to_string())?;
        coordinates = m.n_coordinates();
        let start = Instant::now();
        let r = m.simulate(&opts).map_err(|e| e.to_string())?;
        let wall = start.elapsed().as_secs_f64();
        walls.push(wall);
        last = Some(r);
        if wall > REPEAT_LIMIT {
            break;
        }
    }
    let r = last.ok_or("no run")?;
    walls.sort_by(f64::total_cmp);
    let wall_s = walls[walls.len() / 2];
    let steps = r.stats.accepted;
    Ok(Row {
        jacobian: mode_name(mode),
        elements,
        coordinates,
        steps,
        rejected: r.stats.rejected,
        newton_iters: r.stats.newton_iters,
        jac_evals: r.stats.jac_evals,
        lu_factorizations: r.stats.lu_factorizations,
        onsets: r.onsets,
        outputs_in_contact: contact_rows(&r),
        wall_s,
        runs: walls.len(),
        us_per_step: wall_s / steps.max(1) as f64 * 1e6,
        growth: None,
    })
}

fn markdown(machine: &str, a: &Args, rows: &[Row], notes: &[String]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Slider in clearance on a flexible cantilever guide (built-in `guide`'s beam and \
         slider: 1 m aluminium 20 × 30 mm, slider driven at 1 m/s, {}{}), refined mesh, \
         {} ms, NDF rtol {:e} atol {:e}, highest order {}{}. Machine: {machine}.\n",
        match a.lateral_load {
            Some(f) => format!("starting centred, {f} N lateral load"),
            None => "resting on the upper face, no lateral load".to_string(),
        },
        if a.gravity {
            ", gravity"
        } else {
            ", no gravity"
        },
        a.t_end * 1e3,
        a.rtol,
        1e-3 * a.rtol,
        a.max_order,
        if a.scale_velocity_error {
            ", velocity error scaled by min(h, 1)"
        } else {
            ""
        }
    );
    let _ = writeln!(
        s,
        "| Jacobian | elements | n | steps | rejected | Newton it/step | Jacobians | LU | outputs in contact (of {}) | wall time (ms) | cost/step (µs) | growth per 4× elements (target ≤ {GROWTH_TARGET}) |",
        OUTPUTS + 1
    );
    let _ = writeln!(
        s,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {:.2} | {} | {} | {} | {:.1} (median of {}) | {:.1} | {} |",
            r.jacobian,
            r.elements,
            r.coordinates,
            r.steps,
            r.rejected,
            r.newton_iters as f64 / r.steps.max(1) as f64,
            r.jac_evals,
            r.lu_factorizations,
            r.outputs_in_contact,
            r.wall_s * 1e3,
            r.runs,
            r.us_per_step,
            r.growth.map_or("–".to_string(), |g| format!(
                "{g:.2}{}",
                if g <= GROWTH_TARGET { "" } else { " (over)" }
            ))
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
    let Some(a) = parsed_or_report(parse_args(args), "") else {
        return ExitCode::from(2);
    };
    let machine = machine();
    let mut rows: Vec<Row> = Vec::new();
    let mut notes = Vec::new();
    let mut failed = false;
    for &mode in &a.modes {
        let mut prev: Option<f64> = None;
        for &elements in &a.meshes {
            eprintln!(
                "bench beam: {} Jacobian, {elements} elements",
                mode_name(mode)
            );
            match bench_mesh(elements, &a, mode) {
                Ok(mut r) => {
                    r.growth = prev.map(|p| r.us_per_step / p);
                    prev = Some(r.us_per_step);
                    if r.outputs_in_contact == 0 {
                        notes.push(format!(
                            "{} Jacobian, {elements} elements: no output time in contact",
                            r.jacobian
                        ));
                    }
                    eprintln!(
                        "bench beam:   n = {}, {} steps, {:.1} ms, {:.1} µs/step",
                        r.coordinates,
                        r.steps,
                        r.wall_s * 1e3,
                        r.us_per_step
                    );
                    rows.push(r);
                }
                Err(e) => {
                    failed = true;
                    prev = None;
                    notes.push(format!(
                        "{} Jacobian, {elements} elements failed: {e}",
                        mode_name(mode)
                    ));
                }
            }
        }
    }
    let md = markdown(&machine, &a, &rows, &notes);
    print!("{md}");
    let dir = crate::target_dir().join("bench");
    let report = Report {
        machine,
        model: format!(
            "built-in guide's beam and slider (GuideParams::default), elements varied, {}, {}",
            match a.lateral_load {
                Some(f) => format!("slider starting centred, lateral load {f} N"),
                None => "slider resting on the upper face, no lateral load".to_string(),
            },
            if a.gravity { "gravity" } else { "no gravity" }
        ),
        t_end: a.t_end,
        rtol: a.rtol,
        atol: 1e-3 * a.rtol,
        max_order: a.max_order,
        growth_target: GROWTH_TARGET,
        rows: &rows,
        notes: &notes,
    };
    let written = std::fs::create_dir_all(&dir)
        .map_err(|e| e.to_string())
        .and_then(|()| serde_json::to_string_pretty(&report).map_err(|e| e.to_string()))
        .and_then(|json| std::fs::write(dir.join("beam.json"), json).map_err(|e| e.to_string()))
        .and_then(|()| std::fs::write(dir.join("beam.md"), &md).map_err(|e| e.to_string()));
    match written {
        Ok(()) => eprintln!("bench beam: wrote {}/beam.{{json,md}}", dir.display()),
        Err(e) => {
            eprintln!("bench beam: could not write {}: {e}", dir.display());
            return ExitCode::FAILURE;
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
