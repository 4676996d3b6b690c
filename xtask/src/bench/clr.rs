//! The clr-ode side of `cargo xtask bench ode`: the NDF solver in this process on the Test Set
//! problems of `clr_ode::test_models` (concrete system types, analytic Jacobians).

use clr_ode::test_models::{self, Hires, Orego, Problem, Robertson, VanDerPol};
use clr_ode::{Ndf, OdeSystem, Options, Output};

use super::row::{timed, Row};

/// Solver label of clr-ode's NDF in the rows.
pub const SOLVER: &str = "clr-ndf";

/// Benchmark problem names, in table order (the names of `test_models::Problem::ODES`).
pub const PROBLEMS: [&str; 4] = ["hires", "robertson", "vdpol", "orego"];

fn problem(name: &str) -> Option<Problem> {
    Problem::ODES.into_iter().find(|p| p.name() == name)
}

/// Test Set reference y(t_end) of the problem called `name`.
pub fn reference(name: &str) -> Option<&'static [f64]> {
    problem(name).map(Problem::reference)
}

/// Mixed-error significant correct digits (Test Set definition, `test_models::scd`).
pub fn scd(y: &[f64], reference: &[f64]) -> f64 {
    test_models::scd(y, reference)
}

/// One solve from t = 0 to t_end with a fresh solver (its construction is timed, as the peers'
/// is), recording only the final state.
fn solve<S: OdeSystem>(
    mut sys: S,
    p: Problem,
    opts: &Options,
) -> Result<(usize, usize, Vec<f64>), String> {
    let y0 = p.y0();
    let mut solver = Ndf::new(opts.clone());
    let sol = solver
        .solve(&mut sys, 0.0, &y0, p.t_end())
        .map_err(|e| e.to_string())?;
    Ok((sol.stats.f_evals, sol.stats.accepted, sol.y_final))
}

/// Median-timed NDF solve of problem `name` at (rtol, atol).
pub fn bench(name: &str, rtol: f64, atol: f64, min_time: f64) -> Result<Row, String> {
    let p = problem(name).ok_or_else(|| format!("unknown problem {name}"))?;
    let opts = Options::default().rtol(rtol).atol(atol).output(Output::End);
    let (wall_s, repeats, (f_evals, steps, y_end)) = timed(min_time, || match p {
        Problem::Hires => solve(Hires, p, &opts),
        Problem::Robertson => solve(Robertson::ode(), p, &opts),
        Problem::VanDerPol => solve(VanDerPol::stiff(), p, &opts),
        Problem::Orego => solve(Orego, p, &opts),
        Problem::RobertsonDae => solve(Robertson::dae(), p, &opts),
    })?;
    Ok(Row {
        problem: name.to_string(),
        solver: SOLVER.to_string(),
        rtol,
        atol,
        wall_s,
        f_evals,
        steps,
        scd: scd(&y_end, p.reference()),
        repeats,
    })
}
