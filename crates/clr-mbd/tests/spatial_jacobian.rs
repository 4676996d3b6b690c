//! The spatial model's analytic Newton matrix in use: against the finite-difference one in
//! whole runs, and its reduced solve against the first-order Newton matrix. The element blocks
//! themselves (every force, constraint primitive and the spherical contact, against central
//! differences) are the verify cases `mbd.jacobian.spatial.*` (xtask/src/verify/
//! spatial_jacobian.rs), on the same two models (tests/data/spatial_*.toml).

use clr_mbd::spatial::{SpatialDesc, SpatialModel};

fn setup(text: &str, baumgarte: Option<(f64, f64)>) -> (SpatialModel, Vec<f64>) {
    let d = SpatialDesc::from_toml_table(text.parse().unwrap()).unwrap();
    let mut m = d.compile().unwrap();
    if let Some((a, b)) = baumgarte {
        m.set_baumgarte(a, b).unwrap();
    }
    let (mut y, _) = m.initial_state(0.0).unwrap();
    // arbitrary velocities (the derivatives hold at any state)
    let (nq, nv) = (m.n_q(), m.n_v());
    for k in 0..nv {
        y[nq + k] += 0.3 * ((k as f64) * 1.7).sin() + 0.1;
    }
    (m, y)
}

const TWO_BODIES: &str = include_str!("data/spatial_two_bodies.toml");

const SOCKET: &str = include_str!("data/spatial_socket.toml");

/// Run `text` with the analytic and the finite-difference Newton matrix: the same results
/// within the integration tolerance (both converge Newton to the same corrector tolerance;
/// the difference is bounded by the local error control, `factor`·rtol of the state's scale),
/// and fewer right-hand-side evaluations with the analytic matrix (no 13n_b + 3 evaluations
/// per Jacobian). Returns the (analytic, finite-difference) statistics.
fn same_run(text: &str, factor: f64) -> (clr_ode::Stats, clr_ode::Stats) {
    let d = SpatialDesc::from_toml_table(text.parse().unwrap()).unwrap();
    let mut o = d.sim_options().unwrap();
    let mut run = |mode| {
        o.jacobian = mode;
        d.compile().unwrap().simulate(&o).unwrap()
    };
    let a = run(clr_mbd::JacobianMode::Analytic);
    let f = run(clr_mbd::JacobianMode::FiniteDifference);
    assert!(
        !a.notes.iter().any(|n| n.contains("finite diff")),
        "{:?}",
        a.notes
    );
    let (ya, yf) = (&a.y_final, &f.y_final);
    let scale = yf.iter().fold(1.0f64, |s, x| s.max(x.abs()));
    let diff = ya
        .iter()
        .zip(yf)
        .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()));
    eprintln!(
        "analytic {:?}\nfinite difference {:?}\nlargest difference of the final states {diff:.2e}",
        a.stats, f.stats
    );
    assert!(
        diff < factor * o.rtol * scale,
        "final states differ by {diff:e}"
    );
    assert!(a.stats.f_evals < f.stats.f_evals);
    (a.stats, f.stats)
}

/// The heavy top (models/examples/heavy_top.toml: one body, a spherical joint, spin 120 rad/s).
#[test]
fn heavy_top_analytic_newton_matrix_matches_finite_differences() {
    same_run(
        include_str!("../../../models/examples/heavy_top.toml"),
        100.0,
    );
}

/// A pendulum hanging in a spherical clearance joint with friction, released swinging: up to
/// the end of its second impact (onset, sliding contact, separation), at rtol 1e-9. Later, the
/// two runs' different local errors are amplified impact by impact (at 0.2 s, 9 against 10
/// onsets); the contact blocks themselves are checked against central differences above.
#[test]
fn clearance_pendulum_analytic_newton_matrix_matches_finite_differences() {
    let text = |t_end: f64| {
        format!(
            "{SOCKET}friction = {{ law = \"coulomb\", mu = 0.1, v_reg = 1e-3 }}\n\
             [solver]\nrtol = 1e-9\n[output]\nt_end = {t_end}\nintervals = 20\n"
        )
    };
    let d = SpatialDesc::from_toml_table(text(0.2).parse().unwrap()).unwrap();
    let r = d
        .compile()
        .unwrap()
        .simulate(&d.sim_options().unwrap())
        .unwrap();
    assert!(
        r.impacts.len() >= 2,
        "the pendulum must hit its socket twice"
    );
    let end = r.impacts[1].separation.expect("second impact ends");
    // through impacts the two runs' local errors are amplified (measured: 2.0e-3 at rtol 1e-6,
    // 2.5e-7 at rtol 1e-9, so both converge to one solution): 1e4·rtol at rtol 1e-9
    same_run(&text(end + 1e-3), 1e4);
}

/// The reduced solve (spatial::newton) against the dense first-order matrix I − cJ of central
/// differences of the whole right-hand side (J on y = (q, v, E_d, W_in), the quaternion rows
/// included): the backward error max|(I − cJ)Δy − r|/max|r| over the rows of q and v, for
/// c = 1e-6 … 1e-3 s (the E_d, W_in rows are passive and left out; the quaternion norm term's
/// derivative, which the Newton matrix leaves out, is taken out of the reference). The reduction is exact
/// up to the difference quotients' error (about 1e-9 here), so the bound is 1e-7: measured
/// 1.6e-12 … 1.7e-9 on the heavy top.
#[test]
fn reduced_solve_inverts_the_first_order_newton_matrix() {
    use clr_ode::OdeSystem;
    let top = include_str!("../../../models/examples/heavy_top.toml");
    let rev = format!(
        "{TWO_BODIES}[[joint]]\nname = \"j\"\ntype = \"revolute\"\n\
         a = {{ body = \"ground\", at = [0.0, 0.0, 0.0], axis = [0.0, 0.6, 0.8] }}\n\
         b = {{ body = \"a\", at = [0.0, 0.05, 0.02] }}\n\
         [[force]]\ntype = \"spring_damper\"\nname = \"s\"\n\
         a = {{ body = \"a\", at = [0.1, 0.0, 0.05] }}\nb = {{ body = \"b\", at = [0.0, 0.05, 0.02] }}\n\
         stiffness = 300.0\ndamping = 4.0\nfree_length = 0.2\n"
    );
    for text in [top, rev.as_str()] {
        let (mut m, y) = setup(text, Some((5.0, 7.0)));
        let n = m.dim();
        let t = 0.1;
        let mut jac = vec![0.0; n * n];
        let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
        for c in 0..n {
            let h = 1e-7 * y[c].abs().max(1.0);
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[c] += h;
            ym[c] -= h;
            m.rhs(t, &yp, &mut fp);
            m.rhs(t, &ym, &mut fm);
            for r in 0..n {
                jac[r * n + c] = (fp[r] - fm[r]) / (2.0 * h);
            }
        }
        // the Newton matrix leaves out the derivative of the quaternion norm term k(1 − ‖p‖²)p
        // (k = spatial::model::NORM_RATE = 10 1/s): its backward error would be 2ck, which
        // simplified Newton absorbs; take it out of the reference to test the rest exactly
        let k_norm = 10.0;
        for b in 0..m.n_bodies() {
            let o = 7 * b + 3;
            let p = &y[o..o + 4];
            let n2: f64 = p.iter().map(|x| x * x).sum();
            for i in 0..4 {
                for j in 0..4 {
                    let d = if i == j { 1.0 - n2 } else { 0.0 } - 2.0 * p[i] * p[j];
                    jac[(o + i) * n + o + j] -= k_norm * d;
                }
            }
        }
        assert!(m.newton_jacobian(t, &y));
        for c in [1e-6, 1e-5, 1e-4, 1e-3] {
            assert!(m.newton_factor(c));
            let r: Vec<f64> = (0..n).map(|k| ((k as f64) * 0.37).sin()).collect();
            let mut dy = r.clone();
            m.newton_solve(&mut dy);
            let mut worst = 0.0f64;
            // the rows of (q, v); E_d and W_in are passive (ΔE = r_E, ΔW = r_W)
            for i in 0..m.n_q() + m.n_v() {
                let mut acc = dy[i];
                for k in 0..n {
                    acc -= c * jac[i * n + k] * dy[k];
                }
                worst = worst.max((acc - r[i]).abs());
            }
            let rn = r.iter().fold(0.0f64, |s, x| s.max(x.abs()));
            eprintln!("c = {c:e}: backward error {:.1e}", worst / rn);
            assert!(
                worst / rn < 1e-7,
                "c = {c:e}: backward error {:e}",
                worst / rn
            );
        }
    }
}

/// The journal example (models/examples/spatial_revolute_clearance.toml: a pendulum on a pin
/// with clearance in a bearing misaligned by 0.1°) over its first 10 ms: the pin drops onto the
/// bore (first onset at about 4.5 ms) and the journal tilts onto the rims. The analytic Newton
/// blocks of the journal joint (checked element-wise against central differences in xtask's
/// `mbd.jacobian.spatial.revolute_clearance.*`) in a whole run against the finite-difference
/// matrix: the same final state to 10·rtol of its scale (both runs converge to the same
/// corrector tolerance; through the impact their local errors are amplified, as above; measured
/// 2.5e-6 at rtol 1e-6), with fewer right-hand sides (measured 471 against 708) and no
/// finite-difference note.
#[test]
fn journal_example_analytic_newton_matrix_matches_finite_differences() {
    let example = include_str!("../../../models/examples/spatial_revolute_clearance.toml");
    assert!(example.contains("t_end = 0.3\nintervals = 300"));
    let text = example.replace(
        "t_end = 0.3\nintervals = 300",
        "t_end = 0.01\nintervals = 10",
    );
    same_run(&text, 10.0);
}
