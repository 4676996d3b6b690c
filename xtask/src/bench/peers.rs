//! Running the peer solvers of `cargo xtask bench ode` as child processes.
//!
//! - diffsol: `cargo run --release -p diffsol-peer` (the workspace member `bench/diffsol-peer`,
//!   outside `default-members`, so only this command compiles it);
//! - SciPy: `bench/scipy_ode.py` run with the interpreter of a local virtual environment
//!   `bench/.venv`, created with `python3 -m venv` and filled with `pip install scipy numpy` when
//!   SciPy cannot be imported from it.
//!
//! Both print one JSON object per line: `{problem, solver, rtol, atol, wall_s, f_evals, steps,
//! y_end}` (plus `repeats`), `wall_s` being the median solve time in seconds.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use serde::Deserialize;

use super::row::Row;

/// One row printed by a peer program: the common fields of a benchmark row (its `scd` is
/// computed afterwards from `y_end`) and the state at t_end.
#[derive(Debug, Clone, Deserialize)]
pub struct PeerRow {
    #[serde(flatten)]
    pub row: Row,
    pub y_end: Vec<f64>,
}

fn tolerance_args(rtols: &[f64], min_time: f64) -> Vec<String> {
    let mut args = Vec::new();
    for r in rtols {
        args.push("--rtol".to_string());
        args.push(format!("{r:e}"));
    }
    args.push("--min-time".to_string());
    args.push(format!("{min_time}"));
    args
}

/// Parse the JSON lines of a peer's standard output.
fn parse_rows(who: &str, stdout: &[u8]) -> Result<Vec<PeerRow>, String> {
    String::from_utf8_lossy(stdout)
        .lines()
        .filter(|l| l.trim_start().starts_with('{'))
        .map(|l| {
            serde_json::from_str::<PeerRow>(l)
                .map_err(|e| format!("{who}: unreadable row {l}: {e}"))
        })
        .collect()
}

/// Run the diffsol peer (building it first, in release mode).
pub fn run_diffsol(root: &Path, rtols: &[f64], min_time: f64) -> Result<Vec<PeerRow>, String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    eprintln!(
        "bench ode: building and running the diffsol peer (cargo run --release -p diffsol-peer)"
    );
    let out = Command::new(cargo)
        .current_dir(root)
        .args(["run", "--quiet", "--release", "-p", "diffsol-peer", "--"])
        .args(tolerance_args(rtols, min_time))
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("diffsol peer: could not start cargo: {e}"))?;
    let rows = parse_rows("diffsol peer", &out.stdout)?;
    if !out.status.success() {
        eprintln!(
            "bench ode: the diffsol peer exited with {} ({} rows kept)",
            out.status,
            rows.len()
        );
    }
    Ok(rows)
}

fn venv_python(venv: &Path) -> PathBuf {
    venv.join("bin").join("python")
}

fn has_scipy(python: &Path) -> bool {
    Command::new(python)
        .args(["-c", "import scipy, numpy"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Make sure `bench/.venv` exists and can import scipy and numpy; returns its interpreter.
pub fn ensure_venv(root: &Path) -> Result<PathBuf, String> {
    let venv = root.join("bench").join(".venv");
    let python = venv_python(&venv);
    if python.exists() && has_scipy(&python) {
        return Ok(python);
    }
    if !python.exists() {
        eprintln!(
            "bench ode: creating the SciPy virtual environment {}",
            venv.display()
        );
        let status = Command::new("python3")
            .args(["-m", "venv"])
            .arg(&venv)
            .status()
            .map_err(|e| {
                format!("`python3 -m venv` could not be started ({e}); install Python 3")
            })?;
        if !status.success() {
            return Err(format!(
                "`python3 -m venv {}` failed ({status}); on Debian/Ubuntu install python3-venv",
                venv.display()
            ));
        }
    }
    eprintln!(
        "bench ode: installing scipy and numpy into {} with pip",
        venv.display()
    );
    let status = Command::new(&python)
        .args(["-m", "pip", "install", "--quiet", "scipy", "numpy"])
        .status()
        .map_err(|e| format!("pip could not be started ({e})"))?;
    if !status.success() || !has_scipy(&python) {
        return Err(format!(
            "`pip install scipy numpy` into {} failed ({status}); check the network or install \
             scipy there by hand",
            venv.display()
        ));
    }
    Ok(python)
}

/// Run `bench/scipy_ode.py` in the local virtual environment (created when missing).
pub fn run_scipy(root: &Path, rtols: &[f64], min_time: f64) -> Result<Vec<PeerRow>, String> {
    let python = ensure_venv(root)?;
    eprintln!("bench ode: running SciPy solve_ivp(method=\"BDF\") (bench/scipy_ode.py)");
    let out = Command::new(&python)
        .current_dir(root)
        .arg(root.join("bench").join("scipy_ode.py"))
        .args(tolerance_args(rtols, min_time))
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| {
            format!(
                "SciPy script could not be started with {}: {e}",
                python.display()
            )
        })?;
    let rows = parse_rows("SciPy script", &out.stdout)?;
    if !out.status.success() {
        eprintln!(
            "bench ode: the SciPy script exited with {} ({} rows kept)",
            out.status,
            rows.len()
        );
    }
    Ok(rows)
}
