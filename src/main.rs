//! The `clr` command.
//!
//! The model runner (`clr run`, `clr sweep`, `clr plot`) needs the multibody engine and the
//! models, which are not built yet. Until then the command only reports its version and says
//! where the working parts are, instead of pretending to run anything.

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("--version") | Some("-V") => {
            println!("clr {}", env!("CARGO_PKG_VERSION"));
            ExitCode::SUCCESS
        }
        Some("--help") | Some("-h") | None => {
            println!(
                "clr {}: clearance-joint mechanism simulation\n\n\
                 The model commands (run, sweep, plot, list, export) are not available yet: they\n\
                 need the multibody engine (clr-mbd) and the models (clr-models).\n\
                 Working today: the libraries clr-ode, clr-contact and clr-beam, and\n\
                 `cargo xtask verify` which checks them against published references.",
                env!("CARGO_PKG_VERSION")
            );
            ExitCode::SUCCESS
        }
        Some(other) => {
            eprintln!(
                "clr: command `{other}` is not available yet (the model runner needs clr-mbd); \
                 run `cargo xtask verify` to check the libraries"
            );
            ExitCode::from(2)
        }
    }
}
