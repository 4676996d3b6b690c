//! `cargo xtask octave`: build the C ABI, compile the MEX gateway `matlab/clr_mex.c` with GNU
//! Octave's `mkoctfile --mex`, run `matlab/test_clr.m` and the example `matlab/journal_impact.m`,
//! and compare the restitution Octave's ode15s measures with the one clr-ode measures on the same
//! impact (the verification case `contact.restitution.ln`). Not part of `cargo test` or CI.
//!
//! Installs Octave with apt-get when `mkoctfile` is missing (needs root). See docs/matlab.md.

use std::path::Path;
use std::process::{Command, ExitCode};
use std::time::Instant;

use clr_contact::normal::{JournalBearing, NormalLaw};
use clr_ode::{Direction, Dopri5, OdeFn, Options, Output};

use crate::{target_dir, workspace_root};

/// Allowed |e_octave − e_rust|.
const TOLERANCE: f64 = 1e-4;

const HELP: &str = "usage: cargo xtask octave
  Builds the C ABI (cargo build --release -p clr-contact-capi), installs GNU Octave with apt-get
  when mkoctfile is missing, compiles matlab/clr_mex.c into target/octave/clr_mex.mex, runs
  matlab/test_clr.m and matlab/journal_impact.m in octave, and compares the journal-impact
  restitution with the Rust (clr-ode) value (tolerance 1e-4). Exits non-zero on any failure.";

pub fn run(args: &[String]) -> ExitCode {
    crate::command_without_arguments("octave", HELP, args, run_all)
}

/// Run a command, echoing it; its output goes to the terminal.
fn status(cmd: &mut Command) -> Result<(), String> {
    println!("$ {cmd:?}");
    let st = cmd
        .status()
        .map_err(|e| format!("could not start {cmd:?}: {e}"))?;
    if st.success() {
        Ok(())
    } else {
        Err(format!("{cmd:?} exited with {st}"))
    }
}

/// Run a command and capture its stdout (stderr is passed through).
fn output(cmd: &mut Command) -> Result<String, String> {
    println!("$ {cmd:?}");
    let out = cmd
        .stderr(std::process::Stdio::inherit())
        .output()
        .map_err(|e| format!("could not start {cmd:?}: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    print!("{text}");
    if out.status.success() {
        Ok(text)
    } else {
        Err(format!("{cmd:?} exited with {}", out.status))
    }
}

fn have(program: &str) -> bool {
    Command::new(program)
        .arg("--version")
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false)
}

/// Install Octave and mkoctfile with apt-get; returns the time it took (s).
fn install_octave() -> Result<f64, String> {
    println!(
        "mkoctfile not found: installing GNU Octave and its headers with apt-get \
         (packages octave, liboctave-dev; needs root)"
    );
    let start = Instant::now();
    status(Command::new("apt-get").args(["update", "-qq"]))?;
    status(
        Command::new("apt-get")
            .env("DEBIAN_FRONTEND", "noninteractive")
            .args([
                "install",
                "-y",
                "--no-install-recommends",
                "octave",
                "liboctave-dev",
            ]),
    )?;
    if !have("mkoctfile") {
        return Err("mkoctfile still missing after apt-get install".into());
    }
    Ok(start.elapsed().as_secs_f64())
}

/// Escape a path for a single-quoted Octave string.
fn octave_str(p: &Path) -> String {
    p.display().to_string().replace('\'', "''")
}

/// The restitution clr-ode measures on the journal–bearing impact of `journal_impact.m`
/// (same law, mass, velocity; Dormand–Prince, rtol 1e-12, as `contact.restitution.ln`).
fn rust_restitution() -> Result<(f64, f64), String> {
    const MASS: f64 = 1.0;
    const V0: f64 = 0.5;
    const C_E: f64 = 0.5;
    let jb = JournalBearing::flap_paper_test();
    let c = jb.clearance();
    let law = NormalLaw::preset("LN", &jb, C_E).map_err(|e| e.to_string())?;
    // Free flight is exact: contact at x = c with δ̇⁻ = V0.
    let v_in = V0;
    let mut contact = OdeFn::new(2, move |_t, y: &[f64], dy: &mut [f64]| {
        dy[0] = y[1];
        dy[1] = -law.force(y[0] - c, y[1], v_in) / MASS;
    })
    .event(Direction::Falling, true, move |_t, y: &[f64]| y[0] - c);
    let opts = Options::default()
        .rtol(1e-12)
        .atol_vec(vec![1e-17, 1e-13])
        .output(Output::End);
    let t0 = c / V0;
    let sol = Dopri5::new(opts)
        .solve(&mut contact, t0, &[c, v_in], t0 + 2e-3)
        .map_err(|e| format!("contact phase: {e}"))?;
    let end = sol
        .events
        .first()
        .ok_or("contact phase: no separation within 2 ms")?;
    Ok((-end.y[1] / v_in, law.effective_restitution()))
}

/// The number after `key` on a line of `text` (e.g. "restitution = 0.72").
fn parse_value(text: &str, key: &str) -> Option<f64> {
    text.lines()
        .filter_map(|l| l.trim().strip_prefix(key))
        .filter_map(|rest| rest.trim().strip_prefix('='))
        .find_map(|v| v.trim().parse().ok())
}

fn run_all() -> Result<(), String> {
    let root = workspace_root();
    let out_dir = target_dir().join("octave");
    let lib_dir = target_dir().join("release");
    let include = root.join("crates/clr-contact-capi/include");
    let matlab = root.join("matlab");

    // 1. Octave.
    let install_time = if have("mkoctfile") {
        println!("mkoctfile found; not installing Octave");
        None
    } else {
        Some(install_octave()?)
    };
    let version = Command::new("octave")
        .args(["--no-gui", "--version"])
        .output()
        .map_err(|e| format!("could not start octave: {e}"))?;
    let version = String::from_utf8_lossy(&version.stdout)
        .lines()
        .next()
        .unwrap_or("unknown")
        .to_string();

    // 2. The C ABI (cdylib target/release/libclr_contact_capi.so).
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    status(Command::new(cargo).current_dir(&root).args([
        "build",
        "--release",
        "-p",
        "clr-contact-capi",
    ]))?;
    let so = lib_dir.join("libclr_contact_capi.so");
    if !so.exists() {
        return Err(format!("{} not built", so.display()));
    }

    // 3. The gateway.
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let mex = out_dir.join("clr_mex.mex");
    status(
        Command::new("mkoctfile")
            .arg("--mex")
            .arg(format!("-I{}", include.display()))
            .arg(format!("-L{}", lib_dir.display()))
            .arg("-lclr_contact_capi")
            .arg(format!("-Wl,-rpath,{}", lib_dir.display()))
            .arg("-o")
            .arg(&mex)
            .arg(matlab.join("clr_mex.c")),
    )?;

    // 4. Tests and example.
    let prelude = format!(
        "addpath('{}'); addpath('{}'); ",
        octave_str(&out_dir),
        octave_str(&matlab)
    );
    let octave = |script: &str| {
        output(
            Command::new("octave")
                .current_dir(&root)
                .args(["--no-gui", "--quiet", "--no-window-system", "--eval"])
                .arg(format!("{prelude}{script}")),
        )
    };
    let tests = octave("test_clr");
    let example = octave("journal_impact")?;
    let e_octave = parse_value(&example, "restitution")
        .ok_or("journal_impact.m printed no `restitution = <value>` line")?;
    let (e_rust, e_closed) = rust_restitution()?;
    let diff = e_octave - e_rust;

    println!();
    println!("== cargo xtask octave report ==");
    println!("octave:               {version}");
    match install_time {
        Some(t) => println!("install:              apt-get, {t:.0} s"),
        None => println!("install:              already installed"),
    }
    println!("gateway:              {}", mex.display());
    println!(
        "test_clr.m:           {}",
        if tests.is_ok() { "passed" } else { "FAILED" }
    );
    println!("restitution, Octave:  {e_octave:.10} (ode15s + clr_mex normal_force)");
    println!("restitution, Rust:    {e_rust:.10} (clr-ode Dopri5, rtol 1e-12)");
    println!("closed form:          {e_closed:.10}");
    println!("difference:           {diff:.2e} (tolerance {TOLERANCE:.0e})");
    tests?;
    if diff.abs() > TOLERANCE {
        return Err(format!(
            "restitution differs by {diff:.2e} (> {TOLERANCE:.0e})"
        ));
    }
    println!("octave: all passed");
    Ok(())
}
