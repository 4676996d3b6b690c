//! diffsol's BDF solver on the clr-ode benchmark problems, run by `cargo xtask bench ode`.
//!
//! The four stiff problems of the *Test Set for IVP Solvers* (Mazzia, Magherini, Iavernaro; Bari)
//! used by clr-ode's verification (`/shared/spec/verification.md`): HIRES, Robertson, stiff
//! Van der Pol (ε = 1e-6) and OREGO, each with its analytic Jacobian given to diffsol as the
//! Jacobian–vector product `J(y) v` (diffsol assembles the dense Jacobian from it column by
//! column). diffsol uses its nalgebra dense matrices and LU (`NalgebraMat`, `NalgebraLU`).
//!
//! Usage: `diffsol-peer [--rtol R]... [--min-time SECONDS]`. For each problem and relative
//! tolerance R the solve (solver construction with its consistent initialisation and initial
//! step, then steps to t_end) is repeated until at least `--min-time` seconds (default 0.5) and
//! 5 repetitions have passed, and one JSON object per line is printed on stdout:
//! `{"problem", "solver", "rtol", "atol", "wall_s", "f_evals", "steps", "y_end"}` with `wall_s` the
//! median solve time in seconds.
//!
//! Absolute tolerance: atol = rtol, except Robertson where atol = 1e-6·rtol (1e-12 at rtol 1e-6,
//! as in verification.md's peer note), because its y2 is of order 1e-13 near t_end. clr-ode and
//! SciPy are run with the same rule by the xtask.

use diffsol::{
    NalgebraLU, NalgebraMat, OdeBuilder, OdeEquations, OdeSolverMethod, OdeSolverStopReason, Op,
    Vector,
};
use std::time::Instant;

type M = NalgebraMat<f64>;
type Ls = NalgebraLU<f64>;

/// A benchmark problem: y' = f(y) (all four are autonomous), with J(y) v.
struct Problem {
    name: &'static str,
    y0: &'static [f64],
    t_end: f64,
    f: fn(&[f64], &mut [f64]),
    jv: fn(&[f64], &[f64], &mut [f64]),
}

// HIRES (Test Set `hires`, Schäfer 1975): 8 reactions of a plant photomorphogenesis model.
fn hires_f(y: &[f64], d: &mut [f64]) {
    d[0] = -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
    d[1] = 1.71 * y[0] - 8.75 * y[1];
    d[2] = -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
    d[3] = 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
    d[4] = -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
    d[5] = -280.0 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
    d[6] = 280.0 * y[5] * y[7] - 1.81 * y[6];
    d[7] = -280.0 * y[5] * y[7] + 1.81 * y[6];
}
fn hires_jv(y: &[f64], v: &[f64], d: &mut [f64]) {
    d[0] = -1.71 * v[0] + 0.43 * v[1] + 8.32 * v[2];
    d[1] = 1.71 * v[0] - 8.75 * v[1];
    d[2] = -10.03 * v[2] + 0.43 * v[3] + 0.035 * v[4];
    d[3] = 8.32 * v[1] + 1.71 * v[2] - 1.12 * v[3];
    d[4] = -1.745 * v[4] + 0.43 * v[5] + 0.43 * v[6];
    let r = 280.0 * (v[5] * y[7] + y[5] * v[7]);
    d[5] = -r + 0.69 * v[3] + 1.71 * v[4] - 0.43 * v[5] + 0.69 * v[6];
    d[6] = r - 1.81 * v[6];
    d[7] = -r + 1.81 * v[6];
}

// Robertson (1966) chemical kinetics.
fn rober_f(y: &[f64], d: &mut [f64]) {
    d[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
    d[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1];
    d[2] = 3e7 * y[1] * y[1];
}
fn rober_jv(y: &[f64], v: &[f64], d: &mut [f64]) {
    let a = 1e4 * (v[1] * y[2] + y[1] * v[2]);
    let b = 6e7 * y[1] * v[1];
    d[0] = -0.04 * v[0] + a;
    d[1] = 0.04 * v[0] - a - b;
    d[2] = b;
}

// Van der Pol, stiff form of the Test Set: y1' = y2, y2' = ((1 − y1²) y2 − y1)/ε.
const VDP_EPS: f64 = 1e-6;
fn vdp_f(y: &[f64], d: &mut [f64]) {
    d[0] = y[1];
    d[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / VDP_EPS;
}
fn vdp_jv(y: &[f64], v: &[f64], d: &mut [f64]) {
    d[0] = v[1];
    d[1] = ((-2.0 * y[0] * y[1] - 1.0) * v[0] + (1.0 - y[0] * y[0]) * v[1]) / VDP_EPS;
}

// OREGO (Oregonator, Field & Noyes 1974), Test Set `orego`.
fn orego_f(y: &[f64], d: &mut [f64]) {
    d[0] = 77.27 * (y[1] + y[0] * (1.0 - 8.375e-6 * y[0] - y[1]));
    d[1] = (y[2] - (1.0 + y[0]) * y[1]) / 77.27;
    d[2] = 0.161 * (y[0] - y[2]);
}
fn orego_jv(y: &[f64], v: &[f64], d: &mut [f64]) {
    d[0] = 77.27 * ((1.0 - 2.0 * 8.375e-6 * y[0] - y[1]) * v[0] + (1.0 - y[0]) * v[1]);
    d[1] = (-y[1] * v[0] - (1.0 + y[0]) * v[1] + v[2]) / 77.27;
    d[2] = 0.161 * (v[0] - v[2]);
}

const PROBLEMS: [Problem; 4] = [
    Problem {
        name: "hires",
        y0: &[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057],
        t_end: 321.8122,
        f: hires_f,
        jv: hires_jv,
    },
    Problem {
        name: "robertson",
        y0: &[1.0, 0.0, 0.0],
        t_end: 1e11,
        f: rober_f,
        jv: rober_jv,
    },
    Problem {
        name: "vdpol",
        y0: &[2.0, 0.0],
        t_end: 2.0,
        f: vdp_f,
        jv: vdp_jv,
    },
    Problem {
        name: "orego",
        y0: &[1.0, 2.0, 3.0],
        t_end: 360.0,
        f: orego_f,
        jv: orego_jv,
    },
];

/// Absolute tolerance paired with `rtol` for problem `name` (see the module documentation).
fn atol_for(name: &str, rtol: f64) -> f64 {
    if name == "robertson" {
        rtol * 1e-6
    } else {
        rtol
    }
}

/// Result of one solve.
struct Run {
    wall_s: f64,
    f_evals: usize,
    steps: usize,
    y_end: Vec<f64>,
}

fn solve_once(p: &Problem, rtol: f64, atol: f64) -> Result<Run, String> {
    let (f, jv, y0) = (p.f, p.jv, p.y0);
    let problem = OdeBuilder::<M>::new()
        .rtol(rtol)
        .atol(vec![atol; y0.len()])
        .rhs_implicit(
            move |x: &[f64], _p: &[f64], _t: f64, y: &mut [f64]| f(x, y),
            move |x: &[f64], _p: &[f64], _t: f64, v: &[f64], y: &mut [f64]| jv(x, v, y),
        )
        .init(
            move |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(y0),
            y0.len(),
        )
        .build()
        .map_err(|e| format!("{}: building the diffsol problem failed: {e}", p.name))?;
    let calls_before = problem.eqn.rhs().statistics().number_of_calls;
    let start = Instant::now();
    let mut solver = problem
        .bdf::<Ls>()
        .map_err(|e| format!("{}: creating the BDF solver failed: {e}", p.name))?;
    solver
        .set_stop_time(p.t_end)
        .map_err(|e| format!("{}: set_stop_time failed: {e}", p.name))?;
    loop {
        match solver.step() {
            Ok(OdeSolverStopReason::TstopReached) => break,
            Ok(_) => {}
            Err(e) => return Err(format!("{}: diffsol BDF failed: {e}", p.name)),
        }
    }
    let wall_s = start.elapsed().as_secs_f64();
    let steps = solver.get_statistics().number_of_steps;
    let y_end = solver.state().y.clone_as_vec();
    drop(solver);
    let f_evals = problem.eqn.rhs().statistics().number_of_calls - calls_before;
    Ok(Run {
        wall_s,
        f_evals,
        steps,
        y_end,
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn parse_args() -> Result<(Vec<f64>, f64), String> {
    let mut rtols = Vec::new();
    let mut min_time = 0.5;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = |flag: &str| -> Result<f64, String> {
            let v = args
                .next()
                .ok_or_else(|| format!("{flag} needs a value, e.g. {flag} 1e-6"))?;
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x > 0.0)
                .ok_or_else(|| format!("{flag} {v}: give a positive number"))
        };
        match a.as_str() {
            "--rtol" => rtols.push(value("--rtol")?),
            "--min-time" => min_time = value("--min-time")?,
            other => {
                return Err(format!(
                    "unknown argument {other}; usage: diffsol-peer [--rtol R]... [--min-time S]"
                ))
            }
        }
    }
    if rtols.is_empty() {
        rtols.push(1e-6);
    }
    Ok((rtols, min_time))
}

fn main() {
    let (rtols, min_time) = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("diffsol-peer: {e}");
            std::process::exit(2);
        }
    };
    let mut failed = false;
    for &rtol in &rtols {
        for p in &PROBLEMS {
            let atol = atol_for(p.name, rtol);
            let mut times = Vec::new();
            let mut total = 0.0;
            let mut last = None;
            while times.len() < 5 || (total < min_time && times.len() < 10_000) {
                match solve_once(p, rtol, atol) {
                    Ok(run) => {
                        total += run.wall_s;
                        times.push(run.wall_s);
                        last = Some(run);
                    }
                    Err(e) => {
                        eprintln!("diffsol-peer: {e}");
                        failed = true;
                        break;
                    }
                }
            }
            let Some(run) = last else { continue };
            let row = serde_json::json!({
                "problem": p.name,
                "solver": "diffsol-bdf",
                "rtol": rtol,
                "atol": atol,
                "wall_s": median(times.clone()),
                "repeats": times.len(),
                "f_evals": run.f_evals,
                "steps": run.steps,
                "y_end": run.y_end,
            });
            println!("{row}");
        }
    }
    if failed {
        std::process::exit(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clr_ode::test_models::Problem as ClrProblem;

    /// The peer's f and J·v against clr-ode's own Test Set models (written independently in
    /// `clr_ode::test_models`): same right-hand side and same Jacobian at a generic state, so
    /// that both solvers integrate the same problems.
    #[test]
    fn problems_match_clr_ode_test_models() {
        for p in &PROBLEMS {
            let clr = ClrProblem::ODES
                .into_iter()
                .find(|c| c.name() == p.name)
                .expect("every peer problem is a clr-ode test model");
            assert_eq!(clr.y0(), p.y0, "{}: y0", p.name);
            assert_eq!(clr.t_end(), p.t_end, "{}: t_end", p.name);
            let n = p.y0.len();
            let mut sys = clr.system();
            // a state near y0 with every component non-zero
            let y: Vec<f64> =
                p.y0.iter()
                    .enumerate()
                    .map(|(i, v)| v * (1.0 + 0.1 * i as f64) + 1e-3 * (i + 1) as f64)
                    .collect();
            let (mut f_peer, mut f_clr) = (vec![0.0; n], vec![0.0; n]);
            (p.f)(&y, &mut f_peer);
            sys.rhs(0.0, &y, &mut f_clr);
            let mut jac = vec![0.0; n * n];
            sys.jacobian(0.0, &y, &mut jac);
            for i in 0..n {
                let tol = 1e-12 * (1.0 + f_clr[i].abs());
                assert!((f_peer[i] - f_clr[i]).abs() <= tol, "{}: f[{i}]", p.name);
            }
            // J·e_j is column j of clr-ode's column-major Jacobian
            let (mut e, mut col) = (vec![0.0; n], vec![0.0; n]);
            for j in 0..n {
                e.fill(0.0);
                e[j] = 1.0;
                (p.jv)(&y, &e, &mut col);
                for i in 0..n {
                    let c = jac[i + j * n];
                    assert!(
                        (col[i] - c).abs() <= 1e-12 * (1.0 + c.abs()),
                        "{}: J[{i},{j}] peer {} vs clr-ode {c}",
                        p.name,
                        col[i]
                    );
                }
            }
        }
    }
}
