//! Project automation for clr, run as `cargo xtask <command>` (alias in `.cargo/config.toml`).
//!
//! - `cargo xtask verify [ID-PREFIX...]`: run verification cases, write `target/verify/report.{json,md}`,
//!   exit non-zero when a case fails;
//! - `cargo xtask bench [GROUP]`: side-by-side benchmarks against peer solvers, written to
//!   `target/bench/`;
//! - `cargo xtask figures [NAME...]`: regenerate the figures under `docs/figures/`;
//! - `cargo xtask fuzz [--cases N] [--seed S] [--threads T]`: fuzz the model-file path and the C
//!   ABI, write `target/fuzz/report.md` and reproducers in `target/fuzz/findings/`;
//! - `cargo xtask octave`: build the MATLAB/Octave MEX gateway `matlab/clr_mex.c` with Octave
//!   (installed with apt-get if missing), run its tests and the journal-impact example;
//! - `cargo xtask report-check`: render run reports in headless Chromium (installed with
//!   apt-get if missing), check them and write their screenshots to `docs/figures/`;
//! - `cargo xtask cluster-check`: run clr's cluster workflows on a single-node Slurm cluster
//!   brought up and torn down on this machine.

mod bench;
mod browser;
mod cluster;
mod figures;
mod fuzz;
mod minimal_slider_crank;
mod minimal_spatial_slider_crank;
mod octave;
mod report;
mod study_figures;
mod system;
mod verify;

use std::path::PathBuf;
use std::process::ExitCode;

/// Root of the workspace (parent of the xtask crate).
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives inside the workspace")
        .to_path_buf()
}

/// The cargo target directory (honours `CARGO_TARGET_DIR`).
pub fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| workspace_root().join("target"))
}

/// Run a command that takes no arguments: `--help` prints `help`, any other argument is refused
/// (exit code 2), and an error of `body` fails the command with its message.
pub fn command_without_arguments(
    name: &str,
    help: &str,
    args: &[String],
    body: impl FnOnce() -> Result<(), String>,
) -> ExitCode {
    if args.iter().any(|a| a == "-h" || a == "--help") {
        println!("{help}");
        return ExitCode::SUCCESS;
    }
    if let Some(a) = args.first() {
        eprintln!("{name}: unexpected argument `{a}`\n{help}");
        return ExitCode::from(2);
    }
    match body() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{name}: FAILED: {e}");
            ExitCode::FAILURE
        }
    }
}

const USAGE: &str = "usage: cargo xtask <verify [ID-PREFIX...] | bench [GROUP] | figures [NAME...] | fuzz [OPTIONS] | octave | report-check | cluster-check>
  verify   run verification cases (groups: ode, contact, beam); writes target/verify/report.{json,md}
  bench    benchmarks against peers (groups: ode, mbd, beam, shapes); writes target/bench/<group>.json
  figures  regenerate docs/figures/ (all, or the makers whose name starts with NAME)
  fuzz     fuzz the model files and the C ABI (--cases N, --seed S, --threads T; --help for all);
           writes target/fuzz/report.md and target/fuzz/findings/
  octave   build matlab/clr_mex.c with Octave's mkoctfile (apt-get install if missing), run
           matlab/test_clr.m and matlab/journal_impact.m, compare the restitution with Rust
  report-check  render report.html of three models in headless Chromium (apt-get install if
           missing), check for script errors and motion, write docs/figures/report_*.png
  cluster-check  bring up a single-node Slurm cluster (apt-get install if missing), run a sweep
           job array with a dependent merge, a sharded finding map and killed-and-requeued
           tasks against local runs, tear it down";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let rest = args.get(1..).unwrap_or(&[]);
    match args.first().map(String::as_str) {
        Some("verify") => verify::run(rest),
        Some("bench") => bench::run(rest),
        Some("figures") => figures::run(rest),
        Some("fuzz") => fuzz::run(rest),
        Some("octave") => octave::run(rest),
        Some("report-check") => browser::run(rest),
        Some("cluster-check") => cluster::run(rest),
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
