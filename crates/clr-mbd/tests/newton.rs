//! The integrator's reduced Newton systems (`clr_mbd::newton`, size n + m) against the dense
//! Newton matrix I − cJ of the whole first-order system (size 2n + 1), J by central differences
//! of the right-hand side: an independent formulation of the same linear system. The reduced
//! matrix leaves out the geometric stiffness (Φ_qᵀλ)_q, ∂γ/∂q and ∂M/∂q·a (module docs), terms
//! of relative size c²·(λ/L)/m ≈ 1e-8 at c = 1e-4 s on these models, so the two solutions agree
//! to the central differences' own error. Compared is the backward error of the reduced solution
//! in the dense system (tolerance 1e-5; measured 2e-7 … 1.4e-6 for c = 1e-6 … 1e-3 s).

use clr_contact::{FrictionLaw, JournalBearing, Material, NormalLaw};
use clr_mbd::newton::{Integrand, NewtonWs};
use clr_mbd::{
    JacobianMode, LinearSolver, Model, ModelBuilder, RevoluteClearanceSpec, RigidBody, SimOptions,
};
use clr_ode::linalg::DenseLu;
use clr_ode::OdeSystem;

/// A rod hanging from a clearance pin (steel Hertz, c = 0.5 mm, Coulomb friction), with a second
/// rod pinned to its end: n = 6, m = 2, the journal pressed 1 µm into the bearing and sliding.
fn double_pendulum_in_contact() -> (Model, Vec<f64>) {
    let jb = JournalBearing {
        bearing: Material::steel(),
        journal: Material::steel(),
        r_bearing: 10e-3,
        r_journal: 9.5e-3,
        length: 0.01,
    };
    let normal = NormalLaw::preset("Hertz", &jb, 0.9).unwrap();
    let mut b = ModelBuilder::new();
    b.gravity(0.0, -9.81)
        .body("rod", RigidBody::new(1.0, 0.16 / 12.0).at(0.2, 0.0, 0.0))
        .body(
            "tip",
            RigidBody::new(0.5, 0.02 / 12.0).at(
                0.4 + 0.1 * (-1.2f64).cos(),
                0.1 * (-1.2f64).sin(),
                -1.2,
            ),
        )
        .revolute_clearance(
            "pin",
            ("ground", [0.0, 0.0]),
            ("rod", [-0.2, 0.0]),
            RevoluteClearanceSpec {
                bearing_radius: 10e-3,
                journal_radius: 9.5e-3,
                normal: normal.into(),
                friction: FrictionLaw::coulomb(0.2, 1e-3).unwrap().into(),
            },
        )
        .revolute("elbow", ("rod", [0.2, 0.0]), ("tip", [-0.1, 0.0]));
    let mut m = b.build().unwrap();
    // the elbow closed by construction; the pin's journal centred before the shift below
    let mut y = m.given_state();
    let n = m.n_coordinates();
    // press the whole mechanism 1 µm beyond the clearance (downwards), rotating
    for k in [1, 4] {
        y[k] -= 0.5e-3 + 1e-6;
    }
    y[n + 2] = 3.0;
    y[n + 5] = -2.0;
    m.commit_contact_memory(&y);
    (m, y)
}

/// J of the whole first-order system by central differences (column-major).
fn dense_jacobian(m: &mut Model, t: f64, y: &[f64]) -> Vec<f64> {
    let d = m.dim();
    let mut jac = vec![0.0; d * d];
    let (mut fp, mut fm) = (vec![0.0; d], vec![0.0; d]);
    let mut yp = y.to_vec();
    for j in 0..d {
        let h = 1e-9 * y[j].abs().max(1e-1);
        yp[j] = y[j] + h;
        m.rhs(t, &yp, &mut fp);
        yp[j] = y[j] - h;
        m.rhs(t, &yp, &mut fm);
        yp[j] = y[j];
        for i in 0..d {
            jac[i + j * d] = (fp[i] - fm[i]) / (2.0 * h);
        }
    }
    jac
}

#[test]
fn reduced_newton_solve_matches_the_dense_newton_matrix() {
    let (mut m, y) = double_pendulum_in_contact();
    let d = m.dim();
    let t = 0.0;
    let mut f = vec![0.0; d];
    m.rhs(t, &y, &mut f);
    let f_n = m.contact_reports()[0].normal_force;
    eprintln!("F_N = {f_n} N");
    assert!(f_n > 1.0 && f_n < 100.0, "in contact: {f_n} N");
    let jac = dense_jacobian(&mut m, t, &y);
    for c in [1e-6, 1e-5, 1e-4, 1e-3] {
        let b: Vec<f64> = (0..d).map(|k| ((k as f64) * 1.3).sin() * 1e-3).collect();
        let mut lu = DenseLu::default();
        lu.resize(d);
        let a = lu.matrix_mut();
        for (k, v) in a.iter_mut().enumerate() {
            *v = -c * jac[k] + if k % (d + 1) == 0 { 1.0 } else { 0.0 };
        }
        lu.factor().unwrap();
        let mut dense = b.clone();
        lu.solve(&mut dense);
        let mut solutions = Vec::new();
        for ls in [LinearSolver::Dense, LinearSolver::Sparse] {
            let mut ws = NewtonWs::new(&m, JacobianMode::Analytic, ls);
            let mut ig = Integrand {
                model: &mut m,
                ws: &mut ws,
            };
            assert!(ig.has_newton_solver());
            assert!(ig.newton_jacobian(t, &y));
            assert!(ig.newton_factor(c));
            let mut x = b.clone();
            ig.newton_solve(&mut x);
            solutions.push(x);
        }
        // the dense and sparse factorizations of the reduced matrix agree to rounding
        let big = solutions[0].iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for (a, s) in solutions[0].iter().zip(&solutions[1]) {
            assert!((a - s).abs() <= 1e-12 * big, "dense {a} vs sparse {s}");
        }
        let reduced = solutions.swap_remove(0);
        // Backward error of the reduced solution in the dense system, row by row over q and
        // q̇ (the dissipated energy's row is taken as ΔE = r_E: module docs):
        // |(I − cJ) x − b|_i / (|I − cJ| |x| + |b|)_i. A forward comparison would amplify the
        // differences of J by the condition of I − cJ (≈ 10³ with the contact stiffness).
        let nq = 2 * m.n_coordinates();
        let mut worst = 0.0f64;
        for i in 0..nq {
            let (mut r, mut scale) = (-b[i], b[i].abs());
            for j in 0..d {
                let aij = -c * jac[i + j * d] + if i == j { 1.0 } else { 0.0 };
                r += aij * reduced[j];
                scale += (aij * reduced[j]).abs();
            }
            worst = worst.max(r.abs() / scale);
        }
        let forward = (0..nq)
            .map(|k| (reduced[k] - dense[k]).abs())
            .fold(0.0, f64::max)
            / dense[..nq].iter().fold(0.0f64, |a, x| a.max(x.abs()));
        eprintln!("c = {c:e}: backward error {worst:e}, forward difference {forward:e}");
        assert!(worst <= 1e-5, "c = {c:e}: backward error {worst:e}");
    }
}

/// The same run with the reduced analytic Newton matrix and with clr-ode's finite-difference
/// Jacobian: both are converged solutions of the same equations, so they agree to the
/// tolerance-scale error (rtol 1e-8, 10 ms of rattling in the clearance, started in contact).
#[test]
fn analytic_and_finite_difference_newton_give_the_same_motion() {
    let mut out = Vec::new();
    for (mode, ls) in [
        (JacobianMode::Analytic, LinearSolver::Dense),
        (JacobianMode::Analytic, LinearSolver::Sparse),
        (JacobianMode::FiniteDifference, LinearSolver::Dense),
    ] {
        let (mut m, y0) = double_pendulum_in_contact();
        let mut opts = SimOptions::span(0.0, 0.01, 5).tolerances(1e-8, 1e-11);
        opts.jacobian = mode;
        opts.linear_solver = ls;
        let r = m.simulate_from(&opts, &y0).unwrap();
        assert!(r.onsets > 0, "the journal hits the bearing again");
        out.push((r.column("tip.x").unwrap().to_vec(), r.stats));
    }
    eprintln!(
        "analytic {:?}\nanalytic, sparse {:?}\nfinite differences {:?}",
        out[0].1, out[1].1, out[2].1
    );
    for other in &out[1..] {
        for (a, f) in out[0].0.iter().zip(&other.0) {
            assert!((a - f).abs() < 1e-5, "{a} vs {f}");
        }
    }
}
