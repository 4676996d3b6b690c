//! Built-ins are files: for every built-in model, `clr export <name>` writes its complete
//! multibody model with the run settings (a `clr_mbd::ModelDesc` as TOML), and running that
//! file the way `clr run FILE` does gives the state of `clr run <name>` bit for bit (f64 bits
//! of every clr-mbd column both runs record: time, coordinates, velocities, and also
//! accelerations, contact and reaction forces; the final state; the step count). Every
//! built-in's derived columns and metrics are measures and metrics of its description, so its
//! file reproduces every column (with its unit) and every metric too. The shipped files
//! `models/<name>.toml` are the current exports.

mod common;

use std::path::{Path, PathBuf};

use clr_sim::spec::run::{execute, resolve, Outcome};
use clr_sim::spec::{parse_assignment, Assignment};
use common::clr;

fn scratch(name: &str) -> PathBuf {
    common::scratch_in("export", name)
}

/// Overrides that shorten each built-in to a few milliseconds of simulated time (each run under
/// 1 s in a test build) with contact forces in every model and contact onsets in the revolute
/// clearance joints: the end time through the model's own parameters (`duration`, or the guide's stroke
/// `end`, its run lasting |end − start| / speed = 0.02 s).
fn short(name: &str) -> Vec<&'static str> {
    match name {
        "slider_crank" => vec!["duration=2e-2"],
        // its transient (one revolution at 600 rpm, 0.1 s) shortened into the 0.02 s run
        "wan_slider_crank" => vec!["duration=2e-2", "transient_revolutions=0.1"],
        "flap" => vec!["duration=2e-2"],
        "guide" => vec!["end=0.62"],
        "dual_guide" => vec!["duration=2e-2"],
        "manipulator" => vec!["duration=0.5"],
        other => panic!("no short run for the new built-in `{other}`: add one here"),
    }
}

/// Run a target (built-in name or file) as `clr run` does (`resolve` then `execute`, no
/// `--t-end`/`--rtol`).
fn run(target: &str, sets: &[Assignment]) -> Outcome {
    let job = resolve(target, sets, None, None).unwrap_or_else(|e| panic!("{target}: {e}"));
    let o = execute(&job, None, None, None).unwrap_or_else(|e| panic!("{target}: {e}"));
    assert!(o.error.is_none(), "{target}: {:?}", o.error);
    o
}

/// Export `name` with the overrides into `dir`, run the file and the built-in, and compare.
fn check(name: &str, label: &str, sets: &[&str]) {
    let dir = scratch(label);
    let file = dir.join(format!("{label}.toml"));
    let mut args = vec!["export", name];
    for s in sets {
        args.extend(["--set", s]);
    }
    args.extend(["-o", file.to_str().unwrap()]);
    let o = clr(&args);
    assert!(
        o.status.success(),
        "{label}: export failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(
        text.starts_with("# clr model file: the built-in model"),
        "{label}: header"
    );
    for s in sets {
        assert!(
            text.contains(&format!("--set {s}")),
            "{label}: header misses {s}"
        );
    }
    // the file is a model description, not the built-in form
    let desc: clr_mbd::ModelDesc = toml::from_str(&text)
        .unwrap_or_else(|e| panic!("{label}: not a ModelDesc: {}", e.message()));
    assert!(
        desc.output.every_step && desc.output.intervals == 0,
        "{label}"
    );

    let from_file = run(file.to_str().unwrap(), &[]);
    let assignments: Vec<Assignment> = sets.iter().map(|s| parse_assignment(s).unwrap()).collect();
    let builtin = run(name, &assignments);

    let (a, b) = (&builtin.results, &from_file.results);
    // the file's run records the clr-mbd columns; the built-in appends derived ones
    assert!(
        b.columns.len() <= a.columns.len() && a.columns[..b.columns.len()] == b.columns[..],
        "{label}: the built-in's columns do not start with the file's:\n{:?}\n{:?}",
        a.columns,
        b.columns
    );
    let states = b
        .columns
        .iter()
        .filter(|c| {
            c.as_str() == "t"
                || [
                    ".x", ".y", ".theta", ".vx", ".vy", ".omega", ".u", ".v", ".ex", ".ey",
                ]
                .iter()
                .any(|s| c.ends_with(s))
        })
        .count();
    assert!(states > 6, "{label}: only {states} state columns");
    assert_eq!(a.len(), b.len(), "{label}: rows");
    assert!(a.len() > 100, "{label}: only {} rows", a.len());
    let peak = b
        .columns
        .iter()
        .filter(|c| c.ends_with(".normal_force"))
        .flat_map(|c| b.column(c).unwrap())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    eprintln!(
        "{label}: {} rows, {} onsets, peak normal force {peak:e} N",
        a.len(),
        a.onsets
    );
    let time = b.column("t").unwrap();
    for c in &b.columns {
        let (x, y) = (a.column(c).unwrap(), b.column(c).unwrap());
        for r in 0..x.len() {
            assert!(
                x[r].to_bits() == y[r].to_bits(),
                "{label}: column {c} row {r} (t = {} s): built-in {:e} vs file {:e}",
                time[r],
                x[r],
                y[r]
            );
        }
    }
    assert_eq!(a.y_final.len(), b.y_final.len(), "{label}: final state");
    for (k, (x, y)) in a.y_final.iter().zip(&b.y_final).enumerate() {
        assert_eq!(x.to_bits(), y.to_bits(), "{label}: final state {k}");
    }
    assert_eq!(a.stats.accepted, b.stats.accepted, "{label}: steps");
    assert_eq!(a.onsets, b.onsets, "{label}: contact onsets");
    let lost = derived_lost(&builtin, &from_file);
    assert!(lost.is_empty(), "{label}: {}", lost.join("; "));
}

/// What the file's run does not reproduce of the built-in's: every column of the built-in (its
/// unit and f64 bits in every row) and every metric (value bits and unit), in words.
fn derived_lost(builtin: &Outcome, file: &Outcome) -> Vec<String> {
    let (a, b) = (&builtin.results, &file.results);
    let mut lost = Vec::new();
    for (k, c) in a.columns.iter().enumerate() {
        let Some(j) = b.columns.iter().position(|x| x == c) else {
            lost.push(format!("column {c} missing"));
            continue;
        };
        if builtin.units[k] != file.units[j] {
            lost.push(format!(
                "column {c}: unit {} vs {}",
                builtin.units[k], file.units[j]
            ));
        }
        let (x, y) = (a.column(c).unwrap(), b.column(c).unwrap());
        if let Some(r) = (0..x.len()).find(|&r| x[r].to_bits() != y[r].to_bits()) {
            lost.push(format!("column {c} row {r}: {:e} vs {:e}", x[r], y[r]));
        }
    }
    for m in &builtin.metrics {
        match file.metrics.iter().find(|f| f.name == m.name) {
            None => lost.push(format!("metric {} missing", m.name)),
            Some(f) if f.value.to_bits() != m.value.to_bits() || f.unit != m.unit => {
                lost.push(format!(
                    "metric {}: {:e} {} vs {:e} {}",
                    m.name, m.value, m.unit, f.value, f.unit
                ))
            }
            Some(_) => {}
        }
    }
    lost
}

/// Every built-in (and the flap with its three flexible parts, the guide with its lateral
/// support) exported and rerun bit for bit.
#[test]
fn every_exported_builtin_reproduces_its_run_bit_for_bit() {
    let mut cases: Vec<(String, String, Vec<&'static str>)> = clr_models::catalog::entries()
        .iter()
        .map(|e| (e.name.to_string(), e.name.to_string(), short(e.name)))
        .collect();
    cases.push((
        "flap".into(),
        "flap_flexible".into(),
        vec!["duration=3e-3", "flexible=[true,true,true]"],
    ));
    // the guide's lateral-support what-if (a bushing) is data too
    cases.push((
        "guide".into(),
        "guide_support".into(),
        vec!["end=0.62", "lateral_support_stiffness=1e5"],
    ));
    for (name, label, sets) in &cases {
        check(name, label, sets);
    }
}

/// `models/<name>.toml` is what `clr export <name>` writes today.
#[test]
fn shipped_model_files_are_current_exports() {
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    for e in clr_models::catalog::entries() {
        let file = models.join(format!("{}.toml", e.name));
        let shipped = std::fs::read_to_string(&file)
            .unwrap_or_else(|err| panic!("{}: {err}", file.display()));
        let o = clr(&["export", e.name]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(
            shipped == String::from_utf8_lossy(&o.stdout),
            "{} is not the current export; regenerate it with `cargo run --release -- export {} \
             -o models/{}.toml`",
            file.display(),
            e.name,
            e.name
        );
    }
}
