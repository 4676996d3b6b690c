//! The slider–crank part of `cargo xtask bench spatial` (issue 32): the clearance slider–crank
//! of the planar reductions (verify/spatial.rs: 5000 rpm, steel, Lankarani–Nikravesh c_e = 0.9,
//! no friction, radial clearance 0.5 mm at the rod–slider pin) run in the same process by the
//! planar engine (its revolute clearance joint), the spatial engine with a spatial revolute
//! clearance joint (journal and bore 10 mm long, axial end play 0.1 mm: 4 contact groups, Gauss
//! quadrature along the wetted length) and, for scale, the spatial engine with the ball-in-socket
//! joint of `mbd.spatial.planar_reduction`. The models are the verify cases' own
//! ([`crate::verify::spatial`]), not copies.
//!
//! Measured: median wall time of the simulation over repeats (models compiled outside the
//! timer), steps, right-hand-side evaluations; per-step cost = wall / accepted steps, per-RHS cost
//! = wall / RHS evaluations (for NDF this includes the Newton matrices and solves, for DOPRI5
//! it is the right-hand side alone); and the ratios spatial/planar. The slider position at the
//! end checks that the runs compute the same motion (the spatial journal reduces to the planar
//! joint without tilt, `mbd.spatial.revolute_clearance.planar_reduction`).

use std::time::Instant;

use clr_mbd::spatial::SpatialDesc;
use clr_mbd::{Results, SimOptions, SolverKind};
use serde::Serialize;

use crate::verify::spatial::{
    journal_slider_crank_text, planar_slider_crank_model, slider_crank_text,
};

/// Simulated span, s (0.83 crank turns at 5000 rpm, with the start's impacts).
const T_END: f64 = 0.01;

/// Solver settings of the comparison: NDF (clr's default, analytic Newton matrices) at two
/// tolerances and DOPRI5 (explicit: its per-RHS cost is the right-hand side alone).
const SETTINGS: [(SolverKind, &str, f64); 3] = [
    (SolverKind::Ndf, "NDF", 1e-6),
    (SolverKind::Ndf, "NDF", 1e-9),
    (SolverKind::Dopri5, "DOPRI5", 1e-9),
];

/// The three models of one run.
const MODELS: [&str; 3] = ["planar", "spatial-journal", "spatial-sphere"];

/// One row of the slider–crank table.
#[derive(Debug, Clone, Serialize)]
pub(super) struct CrankRow {
    model: String,
    solver: String,
    rtol: f64,
    wall_s: f64,
    repeats: usize,
    steps: usize,
    rhs: usize,
    jacobians: usize,
    onsets: usize,
    /// Wall time per accepted step and per right-hand-side evaluation, µs.
    per_step_us: f64,
    per_rhs_us: f64,
    /// Ratios of the two to the planar run at the same setting (1 for the planar row).
    step_ratio: f64,
    rhs_ratio: f64,
    /// Slider position at [`T_END`], m.
    slider_x: f64,
}

/// One simulation of `model` with `opts` (the model built outside the timer): (wall s, results).
fn once(model: &str, omega: f64, opts: &SimOptions) -> Result<(f64, Results), String> {
    if model == "planar" {
        let mut m = planar_slider_crank_model(omega)?;
        let start = Instant::now();
        let r = m.simulate(opts).map_err(|e| e.to_string())?;
        return Ok((start.elapsed().as_secs_f64(), r));
    }
    let text = if model == "spatial-journal" {
        journal_slider_crank_text(omega)
    } else {
        slider_crank_text(omega)
    };
    let table: toml::Table = text.parse().map_err(|e| format!("model text: {e}"))?;
    let desc = SpatialDesc::from_toml_table(table).map_err(|e| e.to_string())?;
    let mut m = desc.compile().map_err(|e| e.to_string())?;
    let start = Instant::now();
    let r = m.simulate(opts).map_err(|e| e.to_string())?;
    Ok((start.elapsed().as_secs_f64(), r))
}

/// Median wall time over repeats (at least 3, until `min_time` s are spent), repeats and the
/// last results.
fn timed(
    model: &str,
    omega: f64,
    opts: &SimOptions,
    min_time: f64,
) -> Result<(f64, usize, Results), String> {
    let mut walls = Vec::new();
    loop {
        let (w, r) = once(model, omega, opts)?;
        walls.push(w);
        let total: f64 = walls.iter().sum();
        if walls.len() >= 200 || (walls.len() >= 3 && total >= min_time) {
            let n = walls.len();
            walls.sort_by(f64::total_cmp);
            return Ok((walls[n / 2], n, r));
        }
    }
}

/// The rows of every model and setting, planar first in each setting; notes of failures.
pub(super) fn rows(min_time: f64) -> (Vec<CrankRow>, Vec<String>) {
    let omega = 5000.0 * std::f64::consts::PI / 30.0;
    let (mut rows, mut notes) = (Vec::new(), Vec::new());
    for (solver, name, rtol) in SETTINGS {
        let opts = SimOptions::span(0.0, T_END, 10)
            .tolerances(rtol, 1e-3 * rtol)
            .solver(solver);
        let mut planar: Option<(f64, f64)> = None;
        for model in MODELS {
            eprintln!("bench spatial: slider–crank {model} {name} rtol {rtol:e}");
            let (wall_s, repeats, r) = match timed(model, omega, &opts, min_time) {
                Ok(x) => x,
                Err(e) => {
                    notes.push(format!("slider–crank {model} {name} rtol {rtol:e}: {e}"));
                    continue;
                }
            };
            let (steps, rhs) = (r.stats.accepted, r.stats.f_evals);
            let per_step_us = 1e6 * wall_s / steps.max(1) as f64;
            let per_rhs_us = 1e6 * wall_s / rhs.max(1) as f64;
            if model == "planar" {
                planar = Some((per_step_us, per_rhs_us));
            }
            let (step_ratio, rhs_ratio) = planar.map_or((f64::NAN, f64::NAN), |(s, f)| {
                (per_step_us / s, per_rhs_us / f)
            });
            let slider_x = r
                .column("slider.x")
                .and_then(|x| x.last().copied())
                .unwrap_or(f64::NAN);
            rows.push(CrankRow {
                model: model.into(),
                solver: name.into(),
                rtol,
                wall_s,
                repeats,
                steps,
                rhs,
                jacobians: r.stats.jac_evals,
                onsets: r.onsets,
                per_step_us,
                per_rhs_us,
                step_ratio,
                rhs_ratio,
                slider_x,
            });
        }
    }
    (rows, notes)
}

/// The markdown section of the slider–crank rows.
pub(super) fn markdown(rows: &[CrankRow]) -> String {
    let mut s = format!(
        "\n## Clearance slider–crank, planar against spatial, {:.0} ms\n\n5000 rpm, steel LN \
         c_e = 0.9, radial clearance 0.5 mm at the rod–slider pin; spatial-journal: spatial \
         revolute clearance joint (10 mm long, end play 0.1 mm), spatial-sphere: ball in socket. \
         Ratios: per-step and per-RHS cost over the planar run's at the same setting.\n\n\
         | model | solver | rtol | wall (ms) | repeats | steps | RHS | Jacobians | onsets | \
         µs/step | µs/RHS | step ratio | RHS ratio | slider x (m) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        T_END * 1e3
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {:.0e} | {:.2} | {} | {} | {} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2} \
             | {:.9} |\n",
            r.model,
            r.solver,
            r.rtol,
            r.wall_s * 1e3,
            r.repeats,
            r.steps,
            r.rhs,
            r.jacobians,
            r.onsets,
            r.per_step_us,
            r.per_rhs_us,
            r.step_ratio,
            r.rhs_ratio,
            r.slider_x
        ));
    }
    s
}
