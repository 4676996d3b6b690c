//! Run the NDF solver on the Test Set problems and print scd and statistics:
//! `cargo run --release -p clr-ode --example testset`.

use clr_ode::test_models::{scd, Problem};
use clr_ode::{Ndf, Options, Output};

fn main() {
    for p in [
        Problem::Hires,
        Problem::Robertson,
        Problem::RobertsonDae,
        Problem::VanDerPol,
        Problem::Orego,
    ] {
        for tol in [1e-4, 1e-7, 1e-10] {
            let mut sys = p.system();
            let opts = Options::default().rtol(tol).atol(tol).output(Output::End);
            let t0 = std::time::Instant::now();
            let r = Ndf::new(opts).solve(&mut sys, 0.0, &p.y0(), p.t_end());
            let dt = t0.elapsed().as_secs_f64();
            match r {
                Ok(sol) => println!(
                    "{:14} tol {tol:.0e}: scd {:5.2}  {:?}  {:.3} ms",
                    p.name(),
                    scd(&sol.y_final, p.reference()),
                    sol.stats,
                    dt * 1e3
                ),
                Err(e) => println!("{:14} tol {tol:.0e}: {e}", p.name()),
            }
        }
    }
}
