//! `cargo xtask bench`: clr side by side with peer solvers, in one run.

mod beam;
mod clr;
mod mbd;
mod ode;
mod peers;
mod row;
mod shapes;
mod spatial;
mod spatial_crank;

use std::process::ExitCode;
use std::str::FromStr;

use clr_plot::Figure;

const USAGE: &str =
    "usage: cargo xtask bench ode [--rtol R]... [--min-time SECONDS] [--rounds N] [--docs-figures] [--no-scipy] [--no-diffsol]
  ode   clr-ode NDF vs diffsol BDF vs SciPy solve_ivp BDF on HIRES, Robertson, stiff Van der Pol
        and OREGO at rtol 1e-6 and 1e-8 (default), plus a clr/diffsol work-precision sweep
        (rtol 1e-5 ... 1e-10) for the equal-accuracy comparison; writes target/bench/ode.json,
        target/bench/ode.md and work-precision figures target/bench/ode_<problem>.{svg,png}
        (with --docs-figures also docs/figures/bench_ode_<problem>.{svg,png})
       cargo xtask bench mbd [--min-time SECONDS] [--exudyn-h H1,H2] [--no-scipy] [--no-exudyn]
                             [--no-sweep] [--docs-figures]
  mbd   clearance slider–crank of issue 5: clr (NDF, DOPRI5 at rtol 1e-6) vs Exudyn
        (generalized-α, h = 1e-5 and 1e-6) vs SciPy solve_ivp LSODA/BDF; wall time and slider
        error at 5/10 ms against the independent formulation; plus a work–precision sweep (clr
        NDF rtol 1e-5 ... 1e-10, Exudyn h = 1e-5, 3e-6, 1e-6, SciPy LSODA/BDF rtol 1e-6 ... 1e-10;
        error at 10 ms) with the equal-error ratios of issue 13; writes target/bench/mbd.{json,md}
        and target/bench/mbd_work_precision.{svg,png} (with --docs-figures also
        docs/figures/bench_mbd_work_precision.{svg,png})
       cargo xtask bench beam [--jacobian analytic|fd] [--both] [--runs N] [--t-end SECONDS]
                              [--elements 10,40,160] [--rtol R] [--max-order K]
                              [--lateral-load N] [--no-gravity] [--scale-velocity-error]
  beam  slider in clearance on a flexible cantilever guide (the built-in guide's beam and
        slider, resting on the upper face under gravity, driven at 1 m/s) meshed with 10, 40 and
        160 elements, NDF rtol 1e-6, 0.5 ms: steps, wall time, cost per step, Jacobians, LU
        factorizations and the growth of cost per step per 4x elements (issue 13: <= 2.5x);
        --jacobian fd uses finite-difference Newton matrices, --both runs both,
        --scale-velocity-error scales the velocities' error by min(h, 1); writes
        target/bench/beam.{json,md}
       cargo xtask bench shapes [--runs N]
  shapes  100 shape contact pairs (10 balls bouncing on floors, 90 pairs apart) against the
        same model with its 10 touching pairs only: cost per step and its ratio (the broad
        phase), and the narrow-phase and box-test costs of one pair apart; writes
        target/bench/shapes.{json,md}
       cargo xtask bench spatial [--min-time SECONDS] [--exudyn-h H1,H2,...] [--no-exudyn]
  spatial  pendulum in a spherical clearance joint over 0.1 s: clr spatial NDF (rtol 1e-5 ...
        1e-10) vs Exudyn's hollow-sphere contact (generalized-α, h 1e-4 ... 1e-6), centre-of-mass
        error against clr DOPRI5 at rtol 1e-12, equal-error time ratios; and the clearance
        slider-crank with a spatial revolute clearance joint against the planar engine (per-step
        and per-RHS cost, ratio spatial/planar); writes target/bench/spatial.{json,md}";

pub fn run(args: &[String]) -> ExitCode {
    match args.first().map(String::as_str) {
        Some("ode") => ode::run(&args[1..]),
        Some("mbd") => mbd::run(&args[1..]),
        Some("beam") => beam::run(&args[1..]),
        Some("shapes") => shapes::run(&args[1..]),
        Some("spatial") => spatial::run(&args[1..]),
        Some("-h") | Some("--help") | Some("help") => {
            println!("{USAGE}");
            ExitCode::SUCCESS
        }
        _ => {
            eprintln!("{USAGE}");
            ExitCode::from(2)
        }
    }
}

/// The next command-line value parsed as `T` when `accept` holds for it, otherwise `msg` (a
/// missing value, one that does not parse, and one out of range all get the same message).
fn parse_next<'a, T: FromStr>(
    it: &mut impl Iterator<Item = &'a String>,
    accept: impl Fn(&T) -> bool,
    msg: &str,
) -> Result<T, String> {
    it.next()
        .and_then(|v| v.parse().ok())
        .filter(|v| accept(v))
        .ok_or_else(|| msg.to_string())
}

/// The parsed arguments, or `None` after printing `prefix` and the error to stderr (the caller
/// then exits with 2, the usage-error code of every bench).
fn parsed_or_report<A>(parsed: Result<A, String>, prefix: &str) -> Option<A> {
    parsed.map_err(|e| eprintln!("{prefix}{e}")).ok()
}

/// `fig` with one work–precision series of `pts` = (setting, x, y), ordered loosest setting
/// first so the line runs from cheap to accurate; two points or fewer are drawn as markers,
/// since a line through them would suggest a trend they cannot show.
fn with_series(fig: Figure, label: &str, mut pts: Vec<(f64, f64, f64)>) -> Figure {
    pts.sort_by(|a, b| b.0.total_cmp(&a.0));
    let xy = pts.iter().map(|p| (p.1, p.2)).collect();
    if pts.len() > 2 {
        fig.line(label, xy)
    } else {
        fig.points(label, xy)
    }
}
