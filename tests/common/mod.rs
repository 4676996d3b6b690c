//! Helpers shared by the end-to-end tests of the `clr` binary (each test crate uses a part).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Run the `clr` binary with `args`.
pub fn clr(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_clr"))
        .args(args)
        .output()
        .expect("the clr binary runs")
}

/// A fresh scratch folder `group/name` under the target dir.
pub fn scratch_in(group: &str, name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(group)
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Standard error of a finished command, as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `clr run TARGET --t-end T --out OUT --quiet --no-figures`, asserting that it succeeds.
pub fn run_quietly(target: &str, t_end: &str, out: &Path) -> Output {
    let o = clr(&[
        "run",
        target,
        "--t-end",
        t_end,
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--no-figures",
    ]);
    assert!(o.status.success(), "clr run {target}: {}", stderr(&o));
    o
}

/// `clr run FILE --out DIR/out --no-figures EXTRA…`: (exit code, stderr, summary.json when
/// written).
pub fn run_in(dir: &Path, file: &str, extra: &[&str]) -> (i32, String, Option<serde_json::Value>) {
    let out = dir.join("out");
    let _ = std::fs::remove_dir_all(&out);
    let mut args = vec!["run", file, "--out", out.to_str().unwrap(), "--no-figures"];
    args.extend_from_slice(extra);
    let o = clr(&args);
    let summary = std::fs::read_to_string(out.join("summary.json"))
        .ok()
        .map(|t| serde_json::from_str(&t).unwrap());
    (o.status.code().unwrap_or(-1), stderr(&o), summary)
}
