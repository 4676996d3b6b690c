//! Criterion benchmark: NDF on HIRES, Robertson, stiff Van der Pol and OREGO at rtol = 1e-6
//! (atol 1e-6, Robertson atol 1e-12 as in the diffsol comparison of docs/performance.md), and
//! the cost of a restart. Run with `cargo bench -p clr-ode`.

use clr_ode::test_models::{Hires, Orego, Problem, Robertson, VanDerPol};
use clr_ode::{Direction, Ndf, OdeFn, OdeSystem, Options, Output, StopReason};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn opts(p: Problem) -> Options {
    let atol = if p == Problem::Robertson { 1e-12 } else { 1e-6 };
    Options::default().rtol(1e-6).atol(atol).output(Output::End)
}

fn bench_problem<S: OdeSystem>(c: &mut Criterion, p: Problem, mut sys: S) {
    let mut solver = Ndf::new(opts(p));
    let y0 = p.y0();
    c.bench_function(&format!("ndf/{}", p.name()), |b| {
        b.iter(|| {
            let sol = solver
                .solve(&mut sys, 0.0, black_box(&y0), p.t_end())
                .expect("test problem solves");
            black_box(sol.y_final[0])
        })
    });
}

fn testset(c: &mut Criterion) {
    bench_problem(c, Problem::Hires, Hires);
    bench_problem(c, Problem::Robertson, Robertson::ode());
    bench_problem(c, Problem::VanDerPol, VanDerPol::stiff());
    bench_problem(c, Problem::Orego, Orego);
}

/// 100 bounces of a ball (terminal event, restart): the per-restart overhead.
fn restarts(c: &mut Criterion) {
    let mut ball = OdeFn::new(2, |_t, y: &[f64], dy: &mut [f64]| {
        dy[0] = y[1];
        dy[1] = -9.81;
    })
    .jacobian(|_t, _y: &[f64], j: &mut [f64]| j[2] = 1.0)
    .event(Direction::Falling, true, |_t, y: &[f64]| y[0]);
    let mut s = Ndf::new(Options::default().rtol(1e-6).atol(1e-9).output(Output::End));
    c.bench_function("ndf/bouncing_ball_100_restarts", |b| {
        b.iter(|| {
            s.start(&mut ball, 0.0, &[1.0, 0.0], 1e3).expect("valid");
            for _ in 0..100 {
                if s.advance(&mut ball).expect("bounce") != StopReason::TerminalEvent(0) {
                    break;
                }
                let (t, v) = (s.solution().t_final, s.solution().y_final[1]);
                s.restart(&mut ball, t, &[0.0, -0.95 * v]).expect("restart");
            }
            black_box(s.stats().accepted)
        })
    });
}

criterion_group!(benches, testset, restarts);
criterion_main!(benches);
