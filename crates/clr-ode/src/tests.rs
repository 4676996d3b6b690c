//! Unit tests of the solvers against closed forms.

use crate::*;

/// Harmonic oscillator y1' = y2, y2' = −y1, y(0) = (1, 0): closed form (cos t, −sin t).
fn oscillator() -> OdeFn<impl FnMut(f64, &[f64], &mut [f64])> {
    OdeFn::new(2, |_t, y: &[f64], dy: &mut [f64]| {
        dy[0] = y[1];
        dy[1] = -y[0];
    })
}

/// Free fall y'' = −g with a floor event y = 0 (falling, terminal).
fn ball() -> OdeFn<impl FnMut(f64, &[f64], &mut [f64])> {
    OdeFn::new(2, |_t, y: &[f64], dy: &mut [f64]| {
        dy[0] = y[1];
        dy[1] = -9.81;
    })
    .event(Direction::Falling, true, |_t, y: &[f64]| y[0])
}

#[test]
fn dopri5_oscillator_matches_closed_form() {
    let mut sys = oscillator();
    let sol = Dopri5::new(Options::default().rtol(1e-10).atol(1e-12))
        .solve(&mut sys, 0.0, &[1.0, 0.0], 10.0)
        .unwrap();
    assert_eq!(sol.stop, StopReason::EndReached);
    assert_eq!(sol.t_final, 10.0);
    assert!((sol.y_final[0] - 10f64.cos()).abs() < 1e-8);
    assert!((sol.y_final[1] + 10f64.sin()).abs() < 1e-8);
    let s = sol.stats;
    // 1 for f(t0), 1 for the initial-step estimate, 6 per attempt (FSAL)
    assert_eq!(s.f_evals, 6 * (s.accepted + s.rejected) + 2);
}

#[test]
fn dopri5_dense_output_at_requested_times() {
    let mut sys = oscillator();
    let times: Vec<f64> = (0..=40).map(|k| 0.25 * k as f64).collect();
    let sol = Dopri5::new(
        Options::default()
            .rtol(1e-9)
            .atol(1e-12)
            .output(Output::Times(times.clone())),
    )
    .solve(&mut sys, 0.0, &[1.0, 0.0], 10.0)
    .unwrap();
    assert_eq!(sol.t, times);
    for (t, y) in sol.iter() {
        // 4th-order interpolant between 5th-order steps: error within a small multiple of rtol
        assert!((y[0] - t.cos()).abs() < 2e-8, "t={t}");
    }
}

#[test]
fn dopri5_bouncing_ball_restarts() {
    let (g, e, h0) = (9.81, 0.8, 1.0);
    let mut sys = ball();
    let mut s = Dopri5::new(Options::default().rtol(1e-10).atol(1e-12));
    s.start(&mut sys, 0.0, &[h0, 0.0], 10.0).unwrap();
    let cap = s.work_capacity();
    let mut t_exact = (2.0 * h0 / g).sqrt();
    let mut v = (2.0 * g * h0).sqrt();
    for _ in 0..5 {
        let stop = s.advance(&mut sys).unwrap();
        assert_eq!(stop, StopReason::TerminalEvent(0));
        let ev = s.solution().events.last().unwrap().clone();
        assert!(
            (ev.t - t_exact).abs() < 1e-9 * t_exact,
            "{} vs {}",
            ev.t,
            t_exact
        );
        s.restart(&mut sys, ev.t, &[0.0, -e * ev.y[1]]).unwrap();
        assert_eq!(s.work_capacity(), cap);
        v *= e;
        t_exact += 2.0 * v / g;
    }
}

#[test]
fn invalid_input_is_typed() {
    let mut sys = oscillator();
    let mut s = Dopri5::new(Options::default());
    let bad = |r: Result<Solution, OdeError>| matches!(r, Err(OdeError::InvalidInput { .. }));
    assert!(bad(s.solve(&mut sys, 1.0, &[1.0, 0.0], 0.0)));
    assert!(bad(s.solve(&mut sys, 0.0, &[1.0], 1.0)));
    let mut empty = OdeFn::new(0, |_t, _y: &[f64], _d: &mut [f64]| {});
    assert!(bad(s.solve(&mut empty, 0.0, &[], 1.0)));
    let mut s = Dopri5::new(Options::default().rtol(-1.0));
    assert!(bad(s.solve(&mut sys, 0.0, &[1.0, 0.0], 1.0)));
    let mut s = Dopri5::new(Options::default().atol_vec(vec![1e-6]));
    assert!(bad(s.solve(&mut sys, 0.0, &[1.0, 0.0], 1.0)));
    // DOPRI5 has no mass matrix support: refused rather than ignored
    let mut dae = crate::test_models::Robertson::dae();
    assert!(bad(Dopri5::new(Options::default()).solve(
        &mut dae,
        0.0,
        &[1.0, 0.0, 0.0],
        1.0
    )));
}

#[test]
fn step_budget_and_observer_stop() {
    let mut sys = oscillator();
    let r = Dopri5::new(Options::default().max_steps(3)).solve(&mut sys, 0.0, &[1.0, 0.0], 100.0);
    match r {
        Err(OdeError::StepBudget { solution, .. }) => {
            assert_eq!(solution.stats.accepted, 3);
            assert_eq!(solution.len(), 4);
        }
        other => panic!("expected StepBudget, got {other:?}"),
    }
    let mut calls = 0;
    let sol = Dopri5::new(Options::default())
        .solve_observed(&mut sys, 0.0, &[1.0, 0.0], 100.0, &mut |_t, _y: &[f64]| {
            calls += 1;
            if calls == 5 {
                Control::Stop
            } else {
                Control::Continue
            }
        })
        .unwrap();
    assert_eq!(sol.stop, StopReason::Observer);
    assert_eq!(sol.stats.accepted, 5);
}

#[test]
fn non_finite_rhs_is_an_error() {
    // y' = 1/(1 − t) blows up at t = 1
    let mut sys = OdeFn::new(1, |t, _y: &[f64], dy: &mut [f64]| {
        dy[0] = 1.0 / (1.0 - t).max(0.0)
    });
    let r = Dopri5::new(Options::default()).solve(&mut sys, 0.0, &[0.0], 2.0);
    assert!(
        matches!(
            r,
            Err(OdeError::NonFiniteRhs { .. }) | Err(OdeError::StepSizeUnderflow { .. })
        ),
        "{r:?}"
    );
    let sol = r.unwrap_err().into_solution();
    assert!(sol.t_final < 1.0 && sol.t_final > 0.9);
}

/// y' = λ (y − cos t) − sin t, y(0) = 1: closed form y = cos t for any λ (stiff for λ = −1e4).
fn stiff_cos(with_jac: bool) -> Box<dyn OdeSystem> {
    let lam = -1e4;
    let f = move |t: f64, y: &[f64], dy: &mut [f64]| dy[0] = lam * (y[0] - t.cos()) - t.sin();
    if with_jac {
        Box::new(OdeFn::new(1, f).jacobian(move |_t, _y: &[f64], j: &mut [f64]| j[0] = lam))
    } else {
        Box::new(OdeFn::new(1, f))
    }
}

#[test]
fn ndf_stiff_problem_matches_closed_form_with_and_without_jacobian() {
    for with_jac in [true, false] {
        let mut sys = stiff_cos(with_jac);
        let sol = Ndf::new(Options::default().rtol(1e-8).atol(1e-10))
            .solve(&mut sys, 0.0, &[1.0], 10.0)
            .unwrap();
        for (t, y) in sol.iter() {
            assert!((y[0] - t.cos()).abs() < 1e-6, "jac {with_jac} t {t}");
        }
        assert!(sol.stats.jac_evals >= 1 && sol.stats.lu_factorizations >= 1);
        // stiff: far fewer steps than the explicit stability limit 10 / (2/1e4) = 5e4
        assert!(sol.stats.accepted < 2000, "{:?}", sol.stats);
        if !with_jac {
            // finite differences: one f for the base point and one per column
            assert!(sol.stats.f_evals >= sol.stats.newton_iters + 2 * sol.stats.jac_evals);
        }
    }
}

#[test]
fn ndf_bdf_variant_and_per_component_atol() {
    let mut sys = oscillator();
    for opts in [
        Options::default()
            .rtol(1e-8)
            .atol_vec(vec![1e-10, 1e-10])
            .bdf(),
        Options::default().rtol(1e-8).atol(1e-10).max_order(2),
    ] {
        let sol = Ndf::new(opts)
            .solve(&mut sys, 0.0, &[1.0, 0.0], 5.0)
            .unwrap();
        assert!((sol.y_final[0] - 5f64.cos()).abs() < 1e-5);
    }
}

#[test]
fn ndf_dense_output_and_h_max() {
    let mut sys = oscillator();
    let times: Vec<f64> = (0..=50).map(|k| 0.1 * k as f64).collect();
    let sol = Ndf::new(
        Options::default()
            .rtol(1e-9)
            .atol(1e-11)
            .h_max(0.05)
            .output(Output::Times(times.clone())),
    )
    .solve(&mut sys, 0.0, &[1.0, 0.0], 5.0)
    .unwrap();
    assert_eq!(sol.t, times);
    for (t, y) in sol.iter() {
        assert!(
            (y[0] - t.cos()).abs() < 1e-6 && (y[1] + t.sin()).abs() < 1e-6,
            "t={t}"
        );
    }
    // h_max = 0.05 over 5 s: at least 100 steps
    assert!(sol.stats.accepted >= 100);
}

#[test]
fn ndf_robertson_dae_conserves_mass_and_matches_reference() {
    use crate::test_models::{scd, Problem, Robertson};
    let mut sys = Robertson::dae();
    let sol = Ndf::new(Options::default().rtol(1e-6).atol(1e-10))
        .solve(&mut sys, 0.0, &Robertson::Y0, Robertson::T_END)
        .unwrap();
    for (_, y) in sol.iter() {
        assert!((y[0] + y[1] + y[2] - 1.0).abs() < 1e-9);
    }
    let s = scd(&sol.y_final, Problem::RobertsonDae.reference());
    assert!(s > 5.0, "scd {s}");
}

#[test]
fn ndf_state_dependent_mass() {
    // (1 + y²) y' = −(1 + y²) y: the same solution as y' = −y, y = e^{−t}
    let mut sys = OdeFn::new(1, |_t, y: &[f64], dy: &mut [f64]| {
        dy[0] = -(1.0 + y[0] * y[0]) * y[0]
    })
    .mass_fn(|_t, y: &[f64], m: &mut [f64]| m[0] = 1.0 + y[0] * y[0]);
    let sol = Ndf::new(Options::default().rtol(1e-8).atol(1e-10))
        .solve(&mut sys, 0.0, &[2.0], 3.0)
        .unwrap();
    assert!((sol.y_final[0] - 2.0 * (-3f64).exp()).abs() < 1e-6);
}

#[test]
fn non_terminal_events_are_recorded_in_order() {
    // y1 = cos t crosses zero at π/2 + kπ; both directions, not terminal
    for use_ndf in [true, false] {
        let mut sys = oscillator().event(Direction::Both, false, |_t, y: &[f64]| y[0]);
        let opts = Options::default().rtol(1e-10).atol(1e-12);
        let sol = if use_ndf {
            Ndf::new(opts).solve(&mut sys, 0.0, &[1.0, 0.0], 10.0)
        } else {
            Dopri5::new(opts).solve(&mut sys, 0.0, &[1.0, 0.0], 10.0)
        }
        .unwrap();
        assert_eq!(sol.stop, StopReason::EndReached);
        assert_eq!(sol.events.len(), 3);
        assert_eq!(sol.stats.events, 3);
        for (k, e) in sol.events.iter().enumerate() {
            let exact = std::f64::consts::FRAC_PI_2 + k as f64 * std::f64::consts::PI;
            assert!(
                (e.t - exact).abs() < 1e-7,
                "ndf {use_ndf}: {} vs {exact}",
                e.t
            );
        }
    }
}

#[test]
fn ndf_bouncing_ball_restarts_without_reallocation() {
    let (g, e, h0) = (9.81, 0.8, 1.0);
    let mut sys = ball();
    let mut s = Ndf::new(Options::default().rtol(1e-10).atol(1e-12));
    s.start(&mut sys, 0.0, &[h0, 0.0], 10.0).unwrap();
    let cap = s.work_capacity();
    let mut t_exact = (2.0 * h0 / g).sqrt();
    let mut v = (2.0 * g * h0).sqrt();
    for _ in 0..5 {
        assert_eq!(s.advance(&mut sys).unwrap(), StopReason::TerminalEvent(0));
        let (t, vy) = (s.solution().t_final, s.solution().y_final[1]);
        assert!((t - t_exact).abs() < 1e-9 * t_exact, "{t} vs {t_exact}");
        s.restart(&mut sys, t, &[0.0, -e * vy]).unwrap();
        assert_eq!(s.work_capacity(), cap);
        v *= e;
        t_exact += 2.0 * v / g;
    }
    assert_eq!(s.stats().events, 5);
}

#[test]
fn ndf_newton_failure_is_typed_and_per_step() {
    // 0 = y² + 1 has no real solution: Newton cannot converge
    let mut sys =
        OdeFn::new(1, |_t, y: &[f64], dy: &mut [f64]| dy[0] = y[0] * y[0] + 1.0).mass(vec![0.0]);
    let r = Ndf::new(Options::default().max_newton_failures(5)).solve(&mut sys, 0.0, &[1.0], 1.0);
    match r {
        Err(OdeError::NewtonFailure {
            failures, solution, ..
        }) => {
            assert_eq!(failures, 6);
            assert_eq!(solution.stats.accepted, 0);
            assert_eq!(solution.len(), 1);
        }
        other => panic!("expected NewtonFailure, got {other:?}"),
    }
}

#[test]
fn ndf_non_finite_jacobian_and_rhs() {
    let mut sys = OdeFn::new(1, |_t, y: &[f64], dy: &mut [f64]| dy[0] = -y[0])
        .jacobian(|_t, _y: &[f64], j: &mut [f64]| j[0] = f64::NAN);
    let r = Ndf::new(Options::default()).solve(&mut sys, 0.0, &[1.0], 1.0);
    assert!(
        matches!(r, Err(OdeError::NonFiniteJacobian { .. })),
        "{r:?}"
    );
    let mut sys = OdeFn::new(1, |_t, _y: &[f64], dy: &mut [f64]| dy[0] = f64::INFINITY);
    let r = Ndf::new(Options::default()).solve(&mut sys, 0.0, &[1.0], 1.0);
    assert!(matches!(r, Err(OdeError::NonFiniteRhs { .. })), "{r:?}");
    let mut sys = OdeFn::new(2, |_t, _y: &[f64], dy: &mut [f64]| dy[0] = 0.0).mass(vec![1.0]);
    let r = Ndf::new(Options::default()).solve(&mut sys, 0.0, &[1.0, 1.0], 1.0);
    assert!(matches!(r, Err(OdeError::InvalidInput { .. })), "{r:?}");
}

/// Observed order of fixed-step, fixed-order runs on y' = −y (exact history e^{−t}):
/// log2(err(h) / err(h/2)) within 0.2 of k.
#[test]
fn fixed_order_ndf_and_bdf_orders() {
    for bdf in [false, true] {
        for k in 1..=5usize {
            let mut errs = [0.0; 2];
            for (m, h) in [0.02, 0.01].into_iter().enumerate() {
                let mut sys = OdeFn::new(1, |_t, y: &[f64], dy: &mut [f64]| dy[0] = -y[0])
                    .jacobian(|_t, _y: &[f64], j: &mut [f64]| j[0] = -1.0);
                let mut opts = Options::default()
                    .rtol(1e-13)
                    .atol(1e-15)
                    .fixed_step(h)
                    .max_order(k)
                    .output(Output::End);
                if bdf {
                    opts = opts.bdf();
                }
                let past: Vec<f64> = (0..=k).map(|i| (i as f64 * h).exp()).collect();
                let mut s = Ndf::new(opts);
                s.start_with_history(&mut sys, 0.0, &past, h, 1.0).unwrap();
                s.advance(&mut sys).unwrap();
                errs[m] = (s.solution().y_final[0] - (-1f64).exp()).abs();
            }
            let p = (errs[0] / errs[1]).log2();
            assert!((p - k as f64).abs() < 0.2, "bdf {bdf} k {k}: order {p}");
        }
    }
}

#[test]
fn terminal_event_cuts_requested_output_and_observer_sees_event_state() {
    // y1 = cos t falls through zero at π/2
    let mut sys = oscillator().event(Direction::Falling, true, |_t, y: &[f64]| y[0]);
    let times = vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5];
    let mut last = (0.0, 1.0);
    let sol = Ndf::new(
        Options::default()
            .rtol(1e-9)
            .atol(1e-12)
            .output(Output::Times(times)),
    )
    .solve_observed(&mut sys, 0.0, &[1.0, 0.0], 3.0, &mut |t, y: &[f64]| {
        last = (t, y[0]);
        Control::Continue
    })
    .unwrap();
    assert_eq!(sol.stop, StopReason::TerminalEvent(0));
    assert_eq!(sol.t, vec![0.0, 0.5, 1.0, 1.5]);
    let half_pi = std::f64::consts::FRAC_PI_2;
    assert!((sol.t_final - half_pi).abs() < 1e-8);
    assert_eq!(last.0, sol.t_final);
    assert!(last.1.abs() < 1e-8);
}

#[test]
fn public_dense_output_is_valid_between_advances() {
    // stop after every step and interpolate in the middle of the step just taken
    for use_ndf in [true, false] {
        let mut sys = oscillator();
        let opts = Options::default().rtol(1e-9).atol(1e-12);
        let mut worst: f64 = 0.0;
        macro_rules! walk {
            ($s:expr) => {{
                let s = &mut $s;
                s.start(&mut sys, 0.0, &[1.0, 0.0], 5.0).unwrap();
                let mut t_prev = 0.0;
                let mut y = [0.0; 2];
                while s
                    .advance_observed(&mut sys, &mut |_t, _y: &[f64]| Control::Stop)
                    .unwrap()
                    == StopReason::Observer
                {
                    let tm = 0.5 * (t_prev + s.t());
                    s.interpolate(tm, &mut y);
                    worst = worst.max((y[0] - tm.cos()).abs());
                    t_prev = s.t();
                }
            }};
        }
        if use_ndf {
            walk!(Ndf::new(opts));
        } else {
            walk!(Dopri5::new(opts));
        }
        assert!(worst < 1e-7, "ndf {use_ndf}: {worst}");
    }
}

mod properties {
    use crate::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]

        /// y' = λ y, y(0) = y0: closed form y0 e^{λ t}. Both solvers stay within a small multiple
        /// of the requested tolerance over stiff and non-stiff rates (DOPRI5 only non-stiff).
        #[test]
        fn linear_decay_matches_closed_form(log_rate in -1.0f64..4.0, y0 in 0.1f64..10.0) {
            let lam = -(10f64.powf(log_rate));
            let t_end = 5.0 / lam.abs();
            let exact = y0 * (lam * t_end).exp();
            let mut sys = OdeFn::new(1, move |_t, y: &[f64], dy: &mut [f64]| dy[0] = lam * y[0])
                .jacobian(move |_t, _y: &[f64], j: &mut [f64]| j[0] = lam);
            let opts = Options::default().rtol(1e-8).atol(1e-10).output(Output::End);
            let y = Ndf::new(opts.clone()).solve(&mut sys, 0.0, &[y0], t_end).unwrap().y_final[0];
            prop_assert!((y - exact).abs() < 1e-6 * y0, "ndf {y} vs {exact}");
            if log_rate < 2.0 {
                let y = Dopri5::new(opts).solve(&mut sys, 0.0, &[y0], t_end).unwrap().y_final[0];
                prop_assert!((y - exact).abs() < 1e-6 * y0, "dopri5 {y} vs {exact}");
            }
        }
    }
}

/// Undamped oscillators ẍ_j + ω_j² x_j = (ω_j² − 1) sin t, ω_j = 1, 1e2, 1e4, x(0) = 0,
/// ẋ(0) = 1: closed form x_j = sin t (the stiff modes follow the forcing, no free oscillation).
/// With the velocities' error scaled by h and orders ≤ 2 the solver steps over the stiff modes:
/// order 2 at rtol 1e-6 needs h ≈ (6·rtol)^(1/3) ≈ 0.02, a few hundred steps over 5 s.
#[test]
fn h_scaled_velocity_error_steps_over_undamped_stiff_modes() {
    let w = [1.0f64, 1e2, 1e4];
    let m = w.len();
    let mut sys = OdeFn::new(2 * m, move |t, y: &[f64], dy: &mut [f64]| {
        for j in 0..m {
            dy[j] = y[m + j];
            dy[m + j] = -w[j] * w[j] * y[j] + (w[j] * w[j] - 1.0) * t.sin();
        }
    })
    .jacobian(move |_t, _y: &[f64], jac: &mut [f64]| {
        for j in 0..m {
            jac[j + (m + j) * 2 * m] = 1.0;
            jac[(m + j) + j * 2 * m] = -w[j] * w[j];
        }
    });
    let opts = Options::default()
        .rtol(1e-6)
        .atol(1e-8)
        .max_order(2)
        .h_scaled_error(m..2 * m)
        .max_steps(3000);
    let sol = Ndf::new(opts)
        .solve(&mut sys, 0.0, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 5.0)
        .unwrap();
    for k in 0..sol.len() {
        for j in 0..m {
            // velocity errors accumulate into positions, ≈ N·rtol (see docs/ode.md)
            assert!((sol.state(k)[j] - sol.t[k].sin()).abs() < 1e-3);
        }
    }
    assert!(sol.stats.accepted < 1000, "{:?}", sol.stats);
    // a range outside the state is refused with a typed error
    let bad =
        Ndf::new(Options::default().h_scaled_error(3..7)).solve(&mut sys, 0.0, &[0.0; 6], 1.0);
    assert!(matches!(bad, Err(OdeError::InvalidInput { .. })));
}

/// A system that solves its own Newton systems ([`OdeSystem::has_newton_solver`]): Robertson's
/// problem with the Newton matrix I − cJ formed and factored by the system from its analytic J.
/// The same arithmetic as the solver's dense path, so the two runs take the same steps and end
/// at the same state; the Test Set reference checks both.
struct OwnNewton {
    inner: test_models::Robertson,
    jac: [f64; 9],
    lu: linalg::DenseLu,
    factored: usize,
}

impl OdeSystem for OwnNewton {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.inner.rhs(t, y, dy)
    }
    fn has_newton_solver(&self) -> bool {
        true
    }
    fn newton_jacobian(&mut self, t: f64, y: &[f64]) -> bool {
        self.jac = [0.0; 9];
        self.inner.jacobian(t, y, &mut self.jac);
        true
    }
    fn newton_factor(&mut self, c: f64) -> bool {
        self.factored += 1;
        self.lu.resize(3);
        let a = self.lu.matrix_mut();
        for (k, (a, j)) in a.iter_mut().zip(&self.jac).enumerate() {
            *a = -c * j + if k % 4 == 0 { 1.0 } else { 0.0 };
        }
        self.lu.factor().is_ok()
    }
    fn newton_solve(&mut self, b: &mut [f64]) {
        self.lu.solve(b)
    }
}

#[test]
fn ndf_uses_the_systems_own_newton_solver() {
    let p = test_models::Problem::Robertson;
    let opts = Options::default().rtol(1e-6).atol_vec(vec![1e-12; 3]);
    let mut own = OwnNewton {
        inner: test_models::Robertson::ode(),
        jac: [0.0; 9],
        lu: Default::default(),
        factored: 0,
    };
    let a = Ndf::new(opts.clone())
        .solve(&mut own, 0.0, &p.y0(), p.t_end())
        .unwrap();
    let mut dense = test_models::Robertson::ode();
    let b = Ndf::new(opts)
        .solve(&mut dense, 0.0, &p.y0(), p.t_end())
        .unwrap();
    assert_eq!(a.stats, b.stats);
    assert_eq!(own.factored, a.stats.lu_factorizations);
    let (ya, yb) = (a.state(a.len() - 1), b.state(b.len() - 1));
    assert_eq!(ya, yb);
    assert!(test_models::scd(ya, p.reference()) > 10.0);
}

/// Co-simulation stepping: `extend_to` the next communication point, 100 points of 0.1 s, with
/// no restart. Each stop lands exactly on its point, and the state there matches the closed form
/// (cos t, −sin t) within the tolerance of one run (reference: the closed form; tolerance 1e-6 at
/// rtol 1e-8 over 10 s, as the whole-run test above allows).
fn communication_steps<M: solver::Method>(s: &mut Solver<M>) {
    let mut sys = oscillator();
    s.start(&mut sys, 0.0, &[1.0, 0.0], 0.1).unwrap();
    for k in 1..=100 {
        let tc = 0.1 * k as f64;
        s.extend_to(tc).unwrap();
        assert_eq!(s.advance(&mut sys).unwrap(), StopReason::EndReached);
        assert_eq!(s.t(), tc, "a stop lands on its communication point");
        let y = s.y();
        assert!((y[0] - tc.cos()).abs() < 1e-6 && (y[1] + tc.sin()).abs() < 1e-6);
    }
    assert!(
        s.extend_to(5.0).is_err(),
        "an end before the current time is refused"
    );
}

#[test]
fn extend_to_communication_points_keeps_history_and_accuracy() {
    let opts = Options::default()
        .rtol(1e-8)
        .atol(1e-10)
        .output(Output::End);
    let mut ndf = Ndf::new(opts.clone());
    communication_steps(&mut ndf);
    // one start, no restart: the NDF kept a higher order across the points
    assert!(ndf.method().order() > 1);
    communication_steps(&mut Dopri5::new(opts));
}
