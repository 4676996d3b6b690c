//! `mbd.tolerance.*`: clr-mbd's NDF (analytic Jacobians in the reduced Newton system, the
//! default `JacobianMode::Analytic`) completes every built-in model of the catalog at tight
//! tolerances (issue 13).
//!
//! Each built-in is exported as `clr run <model>` builds it (`clr_models::catalog::export`
//! with its default parameters, `RunSettings::t_end` set to a short span and `rtol`), switched
//! to NDF, and integrated at rtol = 1e-6, 1e-7, 1e-8, 1e-9, 1e-10 with atol = 1e-3·rtol (the
//! built-ins' own ratio). The span is chosen per model (table in [`span`]) so that every run
//! includes contact (a loaded clearance or guide element at some accepted step, or a located
//! onset) and the group stays well under a minute in release on two cores. The case passes when
//! every tolerance completes without an integrator error; its value is the number of tolerances
//! that failed (≤ 0). The note lists per rtol: accepted steps, rejected steps, Newton iterations
//! per accepted step, Jacobian evaluations, LU factorizations, wall time, located onsets, and
//! the number of accepted steps with a loaded contact element.
//!
//! `mbd.tolerance.clearance_pendulum` runs with NDF the model of `mbd.energy.clearance` (which
//! uses DOPRI5; NDF used to stop on it with Newton failures, and this case replaces the example
//! that reproduced them): a rod (1 kg, I = 0.16/12 kg·m², 0.4 m) hanging from a
//! frictionless clearance pin (steel Hertz internal cylinder, bearing 10 mm, journal 9.5 mm,
//! c_e = 1: no damping), released horizontally, 1 s, NDF at (rtol, atol) = (1e-9, 1e-8),
//! (1e-9, 1e-9), (1e-10, 1e-10). A frictionless undamped system conserves its energy (closed
//! form): the value is the largest relative drift max|E − E₀| / max E_kin over the three runs
//! (columns `energy.total` and `energy.kinetic`, 101 output times plus every accepted step),
//! tolerance 1e-4 (the example reports 1.6e-6 at rtol = atol = 1e-9; a failed run fails the
//! case).
//!
//! `CLR_TOLERANCE_FD=1` runs every case with `JacobianMode::FiniteDifference` instead (a
//! diagnostic: does a failure come from the analytic Newton matrix?).

use std::time::Instant;

use clr_mbd::desc::SolverMethod;
use clr_mbd::{JacobianMode, Model, Results, SimOptions, SolverKind};
use clr_models::RunSettings;

use super::Filter;
use crate::report::Case;

/// Relative tolerances of the sweep (atol = 1e-3·rtol).
const RTOLS: [f64; 5] = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10];

/// Simulated span of each built-in, s: long enough for contact, short enough for the budget.
/// Unknown (new) built-ins get 10 ms.
fn span(model: &str) -> f64 {
    match model {
        // 5000 rpm: first impacts within the first milliseconds
        "slider_crank" => 0.01,
        // 600 rpm, 0.1 mm: the journal hits the bearing within the first milliseconds
        "wan_slider_crank" => 0.02,
        "flap" => 0.02,
        // lateral load 50 N presses the slider on the guide from the start
        "guide" => 0.01,
        "dual_guide" => 0.01,
        // free-floating base, slow arms: the first elbow impact comes at ≈ 69 ms
        "manipulator" => 0.1,
        _ => 0.01,
    }
}

/// The Jacobian mode of every run (`CLR_TOLERANCE_FD=1`: finite differences).
fn jacobian_mode() -> JacobianMode {
    if std::env::var_os("CLR_TOLERANCE_FD").is_some_and(|v| v == "1") {
        JacobianMode::FiniteDifference
    } else {
        JacobianMode::Analytic
    }
}

fn mode_label() -> &'static str {
    match jacobian_mode() {
        JacobianMode::Analytic => "analytic Jacobians",
        JacobianMode::FiniteDifference => "finite-difference Jacobians (CLR_TOLERANCE_FD=1)",
    }
}

/// One run's statistics.
struct Run {
    steps: usize,
    rejected: usize,
    newton: usize,
    jac: usize,
    lu: usize,
    wall_ms: f64,
    onsets: usize,
    /// Recorded rows with a loaded contact element.
    contact_rows: usize,
    /// Time of the first such row, s.
    first_contact: Option<f64>,
}

/// Rows (every accepted step) where some `*.contact` column is set or some `*.normal_force`
/// is positive, and the time of the first.
fn contact_rows(res: &Results) -> (usize, Option<f64>) {
    let idx: Vec<usize> = res
        .columns
        .iter()
        .enumerate()
        .filter(|(_, c)| c.ends_with(".contact") || c.ends_with(".normal_force"))
        .map(|(k, _)| k)
        .collect();
    let t = res.index("t");
    let rows: Vec<usize> = (0..res.len())
        .filter(|&r| {
            let row = res.row(r);
            idx.iter().any(|&k| row[k] > 0.0)
        })
        .collect();
    let first = rows.first().and_then(|&r| t.map(|k| res.row(r)[k]));
    (rows.len(), first)
}

/// Integrate built-in `model` over [0, t_end] with NDF at (rtol, 1e-3·rtol).
fn run_builtin(model: &str, t_end: f64, rtol: f64) -> Result<Run, String> {
    let settings = RunSettings {
        t_end: Some(t_end),
        rtol: Some(rtol),
        progress: None,
        ..Default::default()
    };
    let mut desc = clr_models::catalog::export(model, &serde_json::json!({}), &settings)
        .map_err(|e| e.to_string())?;
    desc.solver.method = SolverMethod::Ndf;
    desc.solver.rtol = rtol;
    desc.solver.atol = Some(1e-3 * rtol);
    let mut opts = desc.sim_options().map_err(|e| e.to_string())?;
    opts.solver = SolverKind::Ndf;
    opts.every_step = true;
    opts.jacobian = jacobian_mode();
    let mut m = desc.compile().map_err(|e| e.to_string())?;
    timed_run(&mut m, &opts).map(|(_, run)| run)
}

/// Integrate `m` with `opts`, timing only the solve; its results and statistics.
fn timed_run(m: &mut Model, opts: &SimOptions) -> Result<(Results, Run), String> {
    let start = Instant::now();
    let res = m.simulate(opts).map_err(|e| e.to_string())?;
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let (contact_rows, first_contact) = contact_rows(&res);
    let run = Run {
        steps: res.stats.accepted,
        rejected: res.stats.rejected,
        newton: res.stats.newton_iters,
        jac: res.stats.jac_evals,
        lu: res.stats.lu_factorizations,
        wall_ms,
        onsets: res.onsets,
        contact_rows,
        first_contact,
    };
    Ok((res, run))
}

fn describe(rtol: f64, atol: f64, r: &Run) -> String {
    format!(
        "rtol {rtol:.0e} atol {atol:.0e}: {} steps, {} rejected, {:.2} Newton it/step, {} Jacobians, \
         {} LU, {:.1} ms, {} onsets, {} steps in contact{}",
        r.steps,
        r.rejected,
        r.newton as f64 / r.steps.max(1) as f64,
        r.jac,
        r.lu,
        r.wall_ms,
        r.onsets,
        r.contact_rows,
        r.first_contact
            .map_or(String::new(), |t| format!(" (first at {:.3} ms)", t * 1e3))
    )
}

fn builtin_case(model: &str) -> Case {
    let id = format!("mbd.tolerance.{model}");
    let t_end = span(model);
    let case = Case::new(
        id.clone(),
        format!(
            "tolerances of rtol 1e-6…1e-10 (atol 1e-3·rtol) where NDF fails or the run has no \
             contact, first {:.0} ms",
            t_end * 1e3
        ),
        "-",
        "issue 13: no Newton failure on any built-in model at rtol 1e-6…1e-10",
    );
    let start = Instant::now();
    let mut parts = Vec::new();
    let mut failures = 0usize;
    for rtol in RTOLS {
        match run_builtin(model, t_end, rtol) {
            Ok(r) => {
                if r.contact_rows == 0 && r.onsets == 0 {
                    failures += 1;
                    parts.push(format!(
                        "{} — no contact in the span",
                        describe(rtol, 1e-3 * rtol, &r)
                    ));
                } else {
                    parts.push(describe(rtol, 1e-3 * rtol, &r));
                }
            }
            Err(e) => {
                failures += 1;
                parts.push(format!("rtol {rtol:.0e}: FAILED: {e}"));
            }
        }
    }
    let note = format!(
        "NDF ({}), 0–{:.0} ms; {}; {:.1} s",
        mode_label(),
        t_end * 1e3,
        parts.join("; "),
        start.elapsed().as_secs_f64()
    );
    println!("{id}: {note}");
    case.at_most(failures as f64, 0.0).note(note)
}

/// The rod on a frictionless Hertz clearance pin ([`super::mbd::clearance_pendulum`]); energy
/// drift of one run (max|E − E₀| / max E_kin) and its statistics.
fn pendulum(rtol: f64, atol: f64) -> Result<(f64, Run), String> {
    // the model of `mbd.energy.clearance`, so both cases check the same pendulum
    let mut m = super::mbd::clearance_pendulum()?;
    let mut opts = SimOptions::span(0.0, 1.0, 100)
        .tolerances(rtol, atol)
        .solver(SolverKind::Ndf);
    opts.every_step = true;
    opts.jacobian = jacobian_mode();
    let (res, run) = timed_run(&mut m, &opts)?;
    let e = res.column("energy.total").ok_or("no energy.total column")?;
    let ek = res
        .column("energy.kinetic")
        .ok_or("no energy.kinetic column")?
        .into_iter()
        .fold(0.0, f64::max);
    let drift = e.iter().map(|v| (v - e[0]).abs()).fold(0.0, f64::max) / ek;
    Ok((drift, run))
}

fn pendulum_case() -> Case {
    const TOL: f64 = 1e-4;
    let case = Case::new(
        "mbd.tolerance.clearance_pendulum",
        "largest relative energy drift max|E − E0| / max E_kin of NDF runs of the \
         frictionless clearance pendulum of mbd.energy.clearance at \
         (rtol, atol) = (1e-9, 1e-8), (1e-9, 1e-9), (1e-10, 1e-10), 1 s",
        "-",
        "closed form: a frictionless undamped system conserves energy (issue 13: NDF completes \
         the clearance pendulum at tight tolerances)",
    );
    let start = Instant::now();
    let mut worst = 0.0f64;
    let mut parts = Vec::new();
    let mut failed = false;
    for (rtol, atol) in [(1e-9, 1e-8), (1e-9, 1e-9), (1e-10, 1e-10)] {
        match pendulum(rtol, atol) {
            Ok((drift, r)) => {
                worst = worst.max(drift);
                parts.push(format!("{}, drift {drift:.2e}", describe(rtol, atol, &r)));
            }
            Err(e) => {
                failed = true;
                parts.push(format!("rtol {rtol:.0e} atol {atol:.0e}: FAILED: {e}"));
            }
        }
    }
    let note = format!(
        "NDF ({}); {}; {:.1} s",
        mode_label(),
        parts.join("; "),
        start.elapsed().as_secs_f64()
    );
    println!("mbd.tolerance.clearance_pendulum: {note}");
    let value = if failed { f64::NAN } else { worst };
    case.at_most(value, TOL).note(note)
}

pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    for e in clr_models::catalog::entries() {
        let id = format!("mbd.tolerance.{}", e.name);
        if filter.wants(&id) {
            out.push(builtin_case(e.name));
        }
    }
    if filter.wants("mbd.tolerance.clearance_pendulum") {
        out.push(pendulum_case());
    }
    out
}
