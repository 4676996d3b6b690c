//! Steps of the NDF solver on an undamped FE cantilever (clr-beam, 20 elements, steel strip
//! 20 × 10 mm × 1 m, tip step load from rest): `cargo run --release -p clr-ode --example
//! beam_undamped` (env T_END = end time in s, default 0.14; BETA = Rayleigh β in s, default 0; ORDERS = max
//! orders, default 5,2; SCALED = h-scaled velocity error; DOPRI = also Dopri5; BDF = plain BDF).

use clr_beam::{BeamModel, Loads, Material, Section, Support, TransientSystem};
use clr_ode::{Dopri5, Ndf, OdeFn, OdeSystem, Options, Output};

fn env(name: &str, default: f64) -> f64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn main() {
    let t_end = env("T_END", 0.14);
    let beta = env("BETA", 0.0);
    let n = 20;
    let mat = Material::new(210e9, 7850.0, 0.3).unwrap();
    let sec = Section::rectangular(0.02, 0.01).unwrap();
    let mut b = BeamModel::straight([0.0, 0.0], [1.0, 0.0], n, mat, sec).unwrap();
    b.support(0, Support::Clamped).unwrap();
    b.set_rayleigh(0.0, beta);
    let loads = Loads::new().nodal(n, [0.0, -10.0, 0.0]);
    let sys = TransientSystem::new(&b)
        .unwrap()
        .with_load_pattern(&b, &loads, |_| 1.0)
        .unwrap();
    let tip = sys.free_index(3 * n + 1).unwrap();
    // the Jacobian is constant: evaluate it once
    let dim = sys.dim();
    let mut jac = vec![0.0; dim * dim];
    sys.jacobian(&mut jac);
    let mut sys = sys;
    let mut ode = OdeFn::new(dim, move |t, y: &[f64], dy: &mut [f64]| sys.rhs(t, y, dy))
        .jacobian(move |_t, _y: &[f64], j: &mut [f64]| j.copy_from_slice(&jac));
    let y0 = vec![0.0; ode.dim()];
    let orders: Vec<usize> = std::env::var("ORDERS")
        .unwrap_or_else(|_| "5,2".into())
        .split(',')
        .filter_map(|v| v.parse().ok())
        .collect();
    let nf = ode.dim() / 2;
    for (rtol, atol) in [(1e-6, 1e-10), (1e-8, 1e-12)] {
        for &max_order in &orders {
            {
                let bdf = std::env::var("BDF").is_ok();
                let mut o = Options::default()
                    .rtol(rtol)
                    .atol(atol)
                    .max_order(max_order)
                    .max_steps(2_000_000)
                    .output(Output::End);
                if bdf {
                    o = o.bdf();
                }
                if std::env::var("SCALED").is_ok() {
                    o = o.h_scaled_error(nf..2 * nf);
                }
                let mut s = Ndf::new(o);
                let t0 = std::time::Instant::now();
                match s.solve(&mut ode, 0.0, &y0, t_end) {
                    Ok(sol) => println!(
                        "rtol {rtol:.0e} {} max_order {max_order}: tip {:.6e} m, {:.2} s, {:?}",
                        if bdf { "BDF" } else { "NDF" },
                        sol.y_final[tip],
                        t0.elapsed().as_secs_f64(),
                        sol.stats
                    ),
                    Err(e) => println!("rtol {rtol:.0e} max_order {max_order}: {e}"),
                }
            }
        }
    }
    if std::env::var("DOPRI").is_ok() {
        let mut s = Dopri5::new(
            Options::default()
                .rtol(1e-6)
                .atol(1e-10)
                .max_steps(4_000_000)
                .output(Output::End),
        );
        match s.solve(&mut ode, 0.0, &y0, t_end) {
            Ok(sol) => println!("dopri5: tip {:.6e}, {:?}", sol.y_final[tip], sol.stats),
            Err(e) => println!("dopri5: {e}"),
        }
    }
}
