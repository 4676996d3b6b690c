//! The `clr` command: run built-in models and model files, sweep parameters, plot results.
//!
//! Exit codes: 0 success, 1 simulation failure (partial results written, error stated),
//! 2 bad input (command line, model file, parameters).

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    cli::main()
}
