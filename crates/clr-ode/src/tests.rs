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
