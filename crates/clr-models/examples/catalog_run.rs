//! Run built-in models with their default parameters and print the metrics and wall time:
//! `cargo run --release -p clr-models --example catalog_run [name ...]`.

use clr_models::{catalog, RunSettings};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let names: Vec<String> = if args.is_empty() {
        catalog::entries()
            .iter()
            .map(|e| e.name.to_string())
            .collect()
    } else {
        args
    };
    for name in names {
        let start = std::time::Instant::now();
        let p = match catalog::default_parameters(&name) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("{e}");
                continue;
            }
        };
        match catalog::run(&name, &p, &RunSettings::default()) {
            Ok(out) => {
                println!(
                    "{name}: {} rows, {:.2} s",
                    out.results.len(),
                    start.elapsed().as_secs_f64()
                );
                for m in &out.metrics {
                    println!("  {} = {:.6e} {}", m.name, m.value, m.unit);
                }
            }
            Err(e) => println!("{name}: {e}"),
        }
    }
}
