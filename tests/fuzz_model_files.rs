//! A quick run of the model-file fuzzer of `cargo xtask fuzz` (docs/fuzzing.md): 3000 mutated
//! model files with a fixed seed, parsed, validated and built, every 50th accepted one
//! simulated for at most 1e-3 s and 2000 steps. No panic, and every rejection is placed at a
//! line or a field.
//!
//! The generator and the case runner are the xtask's own files, included as modules: they
//! depend only on `clr` and its dependencies, so the test and `cargo xtask fuzz` generate and
//! judge the same inputs without a shared crate or a copy.

#[path = "../xtask/src/fuzz/case.rs"]
mod case;
#[path = "../xtask/src/fuzz/mutate.rs"]
mod mutate;

use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

const CASES: u64 = 3000;
const SEED: u64 = 20_240_607;

fn seeds() -> Vec<mutate::Seed> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut s = mutate::seeds_from_dirs(&[
        root.join("models"),
        root.join("tests/data"),
        root.join("tests/data/bad"),
    ]);
    for (name, text) in case::builtin_seeds() {
        s.push(mutate::Seed::new(&name, text));
    }
    s
}

#[test]
fn mutated_model_files_never_panic_and_every_error_is_located() {
    let seeds = seeds();
    assert!(seeds.len() >= 20, "{} seeds", seeds.len());
    case::quiet_panics();
    // CLR_FUZZ_TRACE=1: one thread, each case's index printed before it runs (to find a case
    // that aborts the process)
    let trace = std::env::var_os("CLR_FUZZ_TRACE").is_some();
    let threads = if trace { 1 } else { 2 };
    let (tx, rx) = mpsc::channel();
    for w in 0..threads {
        let tx = tx.clone();
        let seeds = seeds.clone();
        std::thread::spawn(move || {
            let mut i = w;
            while i < CASES {
                let input = mutate::generate(&seeds, SEED, i);
                let limits = case::Limits {
                    simulate: i.is_multiple_of(50),
                    ..case::Limits::default()
                };
                if trace {
                    eprintln!("case {i}");
                }
                let v = case::run(&input.text, &limits);
                if tx.send((i, v, input)).is_err() {
                    return;
                }
                i += threads;
            }
        });
    }
    drop(tx);
    let mut findings = Vec::new();
    let (mut accepted, mut rejected) = (0, 0);
    loop {
        // a hang guard, not a speed test: a simulated dual-guide case takes up to ~15 s on a
        // loaded 2-core machine (docs/fuzzing.md), so only a case silent for 300 s fails
        match rx.recv_timeout(Duration::from_secs(300)) {
            Ok((i, v, input)) => {
                match &v {
                    case::Verdict::Accepted { .. } | case::Verdict::SolverFailure(_) => {
                        accepted += 1
                    }
                    case::Verdict::Rejected => rejected += 1,
                    _ => {}
                }
                if v.is_finding() && findings.len() < 10 {
                    findings.push(format!(
                        "case {i} ({} with {:?}): {v:?}\n--- input ---\n{}",
                        input.seed,
                        input.mutations,
                        input.text.chars().take(3000).collect::<String>()
                    ));
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
            Err(mpsc::RecvTimeoutError::Timeout) => {
                panic!("a case ran for more than 300 s (replay with `cargo xtask fuzz --seed {SEED} --case I` around the last cases)")
            }
        }
    }
    assert!(
        findings.is_empty(),
        "{} findings (first ones below; replay one with `cargo xtask fuzz --seed {SEED} --case I --simulate-every 50`):\n{}",
        findings.len(),
        findings.join("\n\n")
    );
    assert!(
        accepted > 30 && rejected > 1000,
        "{accepted} accepted, {rejected} rejected"
    );
    eprintln!("{CASES} cases: {accepted} accepted, {rejected} rejected with a location");
}

/// The bugs the fuzzer found, one file each in tests/data/bad/: each is now refused with the
/// line and field of the value to change (docs/fuzzing.md lists them).
#[test]
fn fuzz_findings_are_refused_at_their_place() {
    let cases: [(&str, Option<usize>, &str, &str); 6] = [
        ("fuzz_empty.toml", None, "body", "nothing that moves"),
        (
            "fuzz_builtin_parameter.toml",
            Some(7),
            "parameters.end",
            "puts the slider",
        ),
        (
            "fuzz_beam_elements.toml",
            Some(7),
            "beam[0].elements",
            "more than the 1000 elements",
        ),
        (
            "fuzz_builtin_rtol.toml",
            Some(6),
            "parameters",
            "solver.atol",
        ),
        (
            "fuzz_builtin_elements.toml",
            Some(7),
            "parameters.elements",
            "elements a beam may have",
        ),
        (
            "fuzz_blank_name.toml",
            Some(15),
            "joint[0].name",
            "is blank",
        ),
    ];
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/bad");
    for (file, line, field, needle) in cases {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let e = match clr_sim::spec::load_str(file, &text, &[]) {
            Err(e) => e,
            Ok(_) => panic!("{file}: accepted"),
        };
        assert_eq!(e.line, line, "{file}: {e}");
        assert_eq!(e.field, field, "{file}: {e}");
        assert!(e.message.contains(needle), "{file}: {e}");
        assert!(
            case::run(&text, &case::Limits::default()) == case::Verdict::Rejected,
            "{file}"
        );
    }
}
