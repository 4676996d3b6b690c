//! `mbd.spatial.slider_crank`: the spatial slider–crank of `models/examples/
//! spatial_slider_crank.toml` (crank on a revolute joint, rod with a spherical and a universal
//! joint, slider on a line out of the crank's plane, free under gravity) run by clr's spatial
//! engine at rtol 1e-10, against the independent formulation in the crank angle alone
//! ([`crate::minimal_spatial_slider_crank`]).

use clr_mbd::spatial::SpatialDesc;

use super::Filter;
use crate::minimal_spatial_slider_crank as minimal;
use crate::report::Case;

/// The example file, run as shipped apart from the tolerances and output times.
const MODEL: &str = include_str!("../../../models/examples/spatial_slider_crank.toml");
/// Output times, s (about 1.5 crank turns).
const TIMES: [f64; 5] = [0.2, 0.4, 0.6, 0.8, 1.0];
/// RK4 step of the reference, s; the reference error is estimated by the run at twice the step
/// (RK4: error(2h) − error(h) ≈ 15·error(h)).
const H_REF: f64 = 2e-5;
/// Tolerance on the slider position, m: clr's integration error at rtol 1e-10 and the
/// reference's RK4 error (≲ 1e-12 m at H_REF) both lie well below it.
const TOL: f64 = 1e-8;

const SRC: &str = "independent formulation in the crank angle alone (closed-form loop \
                   kinematics with the universal joint fixing the rod spin, Lagrange's equation, \
                   derivatives on Taylor jets, RK4 h = 2e-5 s; \
                   xtask/src/minimal_spatial_slider_crank.rs); tolerance 1e-8 m";

pub fn cases(filter: &Filter) -> Vec<Case> {
    let ids: Vec<String> = TIMES
        .iter()
        .map(|t| format!("mbd.spatial.slider_crank.t{:.0}ms", t * 1e3))
        .collect();
    if !ids.iter().any(|id| filter.wants(id)) {
        return Vec::new();
    }
    match (reference(), clr_run(false)) {
        (Ok((xr, err_ref)), Ok((xc, note))) => {
            // the finding of docs/verification.md: the crank speed alone given, the assembly
            // moves it by ~1e-7 of itself
            let solved = clr_run(true).map(|(x, _)| x);
            ids.iter()
                .enumerate()
                .map(|(k, id)| {
                    let variant = match &solved {
                        Ok(x) => format!("{:.3e} m", (x[k] - xr[k]).abs()),
                        Err(e) => format!("failed ({e})"),
                    };
                    Case::new(
                        id,
                        "slider position, clr spatial engine (NDF rtol 1e-10) vs minimal formulation",
                        "m",
                        SRC,
                    )
                    .absolute(xc[k], xr[k], TOL)
                    .note(format!(
                        "error {:.3e} m; reference RK4 error estimate {err_ref:.1e} m; {note}; \
                         with only the crank speed given (other velocities solved): error {variant}",
                        (xc[k] - xr[k]).abs()
                    ))
                })
                .collect()
        }
        (r, c) => {
            let why = format!("reference: {:?}; clr: {:?}", r.err(), c.err());
            ids.iter()
                .map(|id| Case::new(id, "slider position", "m", SRC).failed(0.0, why.clone()))
                .collect()
        }
    }
}

/// The reference slider positions and the largest RK4 error estimate (Richardson, h vs 2h), m.
fn reference() -> Result<(Vec<f64>, f64), String> {
    let fine = minimal::slider_positions(&TIMES, H_REF)?;
    let coarse = minimal::slider_positions(&TIMES, 2.0 * H_REF)?;
    let err = fine
        .iter()
        .zip(&coarse)
        .map(|(f, c)| (f - c).abs() / 15.0)
        .fold(0.0, f64::max);
    Ok((fine, err))
}

/// clr's slider positions at [`TIMES`] and a note (steps, energy drift, crank turns).
fn clr_run(solve_velocities: bool) -> Result<(Vec<f64>, String), String> {
    let table: toml::Table = MODEL.parse().map_err(|e| format!("{e}"))?;
    let mut desc = SpatialDesc::from_toml_table(table).map_err(|e| e.to_string())?;
    desc.solver.rtol = 1e-10;
    desc.solver.atol = Some(1e-13);
    if solve_velocities {
        for b in &mut desc.bodies {
            (b.velocity, b.velocity_frame) = (None, None);
            if b.name != "crank" {
                (b.angular_velocity, b.angular_velocity_frame) = (None, None);
            }
        }
    }
    let opts = desc
        .sim_options()
        .map_err(|e| e.to_string())?
        .times(TIMES.to_vec());
    let res = desc
        .compile()
        .map_err(|e| e.to_string())?
        .simulate(&opts)
        .map_err(|e| e.to_string())?;
    let (t, x_all) = (res.column("t"), res.column("slider.x"));
    let (t, x_all) = t.zip(x_all).ok_or("no column t or slider.x")?;
    let x = TIMES
        .iter()
        .map(|tk| {
            t.iter()
                .position(|ti| (ti - tk).abs() < 1e-12)
                .map(|i| x_all[i])
                .ok_or(format!("no output row at t = {tk} s"))
        })
        .collect::<Result<Vec<f64>, String>>()?;
    let e = res.column("energy.total").unwrap_or_default();
    let drift = e.iter().map(|v| (v - e[0]).abs()).fold(0.0, f64::max);
    let ys = minimal::states(&TIMES, H_REF)?;
    let e0 = minimal::energy([minimal::phi0(), minimal::OMEGA0]);
    let drift_ref = ys
        .iter()
        .map(|y| (minimal::energy(*y) - e0).abs())
        .fold(0.0, f64::max);
    Ok((
        x,
        format!(
            "clr: {} steps, energy drift {drift:.1e} J; minimal: energy drift {drift_ref:.1e} J \
             of {e0:.3} J; the crank turns {:.2} times",
            res.stats.accepted,
            minimal::turns(ys[ys.len() - 1])
        ),
    ))
}
