//! Steps and time per step at the benchmark tolerances (rtol 1e-6; atol 1e-6, Robertson 1e-12):
//! `cargo run --release -p clr-ode --example steps` (env REPS = repetitions, PROBLEM = one name).

use clr_ode::test_models::{scd, Problem};
use clr_ode::{Ndf, Options, Output};

fn main() {
    let only = std::env::var("PROBLEM").ok();
    for p in Problem::ODES {
        if only.as_deref().is_some_and(|o| o != p.name()) {
            continue;
        }
        let atol = if p == Problem::Robertson { 1e-12 } else { 1e-6 };
        let mut sys = p.system();
        let mut s = Ndf::new(Options::default().rtol(1e-6).atol(atol).output(Output::End));
        let reps: usize = std::env::var("REPS")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(2000);
        let t0 = std::time::Instant::now();
        let mut sol = None;
        for _ in 0..reps {
            sol = Some(s.solve(&mut sys, 0.0, &p.y0(), p.t_end()).unwrap());
        }
        let dt = t0.elapsed().as_secs_f64() / reps as f64;
        let sol = sol.unwrap();
        println!(
            "{:10} scd {:5.2} {:6.1} µs/solve {:5.3} µs/step {:?}",
            p.name(),
            scd(&sol.y_final, p.reference()),
            dt * 1e6,
            dt * 1e6 / sol.stats.accepted as f64,
            sol.stats
        );
    }
}
