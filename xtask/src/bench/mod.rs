//! `cargo xtask bench`: clr side by side with peer solvers, in one run.

use std::process::ExitCode;

pub fn run(args: &[String]) -> ExitCode {
    match args.first().map(String::as_str) {
        _ => {
            eprintln!("cargo xtask bench: no benchmark group is available yet");
            ExitCode::from(2)
        }
    }
}
