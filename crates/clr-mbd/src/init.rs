//! Consistent initial conditions, coordinate projection and the redundancy check.
//!
//! Positions: Newton's iteration on Φ(q, t) = 0 with the mass-weighted minimum-norm update
//! Δq = −W Φ_qᵀ (Φ_q W Φ_qᵀ)⁻¹ Φ, W = M⁻¹ (the correction of least kinetic metric; E. Bayo &
//! R. Ledesma, Nonlinear Dyn. 9 (1996) 113–130, and W. Blajer, Multibody Syst. Dyn. 7 (2002)
//! 265–284, use the same projector). Velocities: one linear solve of Φ_q q̇ = −Φ_t with the same
//! projector applied to the given velocities.
//! Rank deficiency of Φ_q is detected by modified Gram–Schmidt on the rows of Φ_q W^{1/2}
//! (Golub & Van Loan, *Matrix Computations*, 4th ed., §5.2.8) before any solve.

use clr_ode::linalg::DenseLu;

use crate::error::MbdError;
use crate::system::Model;

/// Relative tolerance of the rank test: a row whose Gram–Schmidt residual is below this
/// fraction of its norm is a combination of the rows before it.
const RANK_TOL: f64 = 1e-9;
/// Largest number of Newton iterations of the position assembly.
const MAX_NEWTON: usize = 50;

impl Model {
    /// W^{1/2} for coordinate c (inverse square root of its mass or inertia).
    fn w_sqrt(&self, c: usize) -> f64 {
        if let Some(b) = self.bodies.get(c / 3) {
            return 1.0 / if c % 3 == 2 { b.inertia } else { b.mass }.sqrt();
        }
        // beam DOF: the diagonal of its mass matrix (constraints never involve them yet)
        for fb in &self.beams {
            let (o, nf) = (fb.offset, fb.n_free());
            if (o..o + nf).contains(&c) {
                let a = c - o;
                return 1.0 / fb.m.get(a, a).abs().max(f64::MIN_POSITIVE).sqrt();
            }
        }
        1.0
    }

    /// Check that Φ_q(q, t) has full row rank; otherwise report the dependent equations.
    ///
    /// # Errors
    /// [`MbdError::RedundantConstraints`] with the equations involved.
    pub fn check_rank(&mut self, t: f64, q: &[f64]) -> Result<(), MbdError> {
        let (n, m) = (self.n, self.m);
        let zeros = vec![0.0; n];
        self.eval_constraints(t, q, &zeros);
        let mut basis: Vec<Vec<f64>> = Vec::new();
        let mut basis_row: Vec<usize> = Vec::new();
        let labels = self.row_labels();
        let mut dependent = Vec::new();
        for r in 0..m {
            let mut v: Vec<f64> = (0..n)
                .map(|c| self.phiq[r * n + c] * self.w_sqrt(c))
                .collect();
            let norm0 = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            let mut used = Vec::new();
            for (b, &br) in basis.iter().zip(basis_row.iter()) {
                let p: f64 = b.iter().zip(v.iter()).map(|(x, y)| x * y).sum();
                if p.abs() > RANK_TOL * norm0 {
                    used.push(br);
                }
                for (vi, bi) in v.iter_mut().zip(b.iter()) {
                    *vi -= p * bi;
                }
            }
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            if norm <= RANK_TOL * norm0.max(f64::MIN_POSITIVE) {
                let others: Vec<&str> = used.iter().map(|&k| labels[k].as_str()).collect();
                dependent.push(format!(
                    "{} depends on [{}]",
                    labels[r],
                    if others.is_empty() {
                        "nothing: the equation is empty".to_string()
                    } else {
                        others.join(", ")
                    }
                ));
            } else {
                v.iter_mut().for_each(|x| *x /= norm);
                basis.push(v);
                basis_row.push(r);
            }
        }
        if dependent.is_empty() {
            Ok(())
        } else {
            Err(MbdError::RedundantConstraints {
                rank: basis.len(),
                rows: m,
                involved: dependent.join("; "),
            })
        }
    }

    /// Factor S = Φ_q W Φ_qᵀ (m × m) from the current Φ_q.
    fn factor_s(&self, lu: &mut DenseLu) -> bool {
        let (n, m) = (self.n, self.m);
        lu.resize(m);
        let s = lu.matrix_mut();
        for a in 0..m {
            for b in 0..m {
                let mut v = 0.0;
                for c in 0..n {
                    let w = self.w_sqrt(c);
                    v += self.phiq[a * n + c] * self.phiq[b * n + c] * w * w;
                }
                s[a + b * m] = v;
            }
        }
        lu.factor().is_ok()
    }

    /// x ← x − W Φ_qᵀ S⁻¹ r (r overwritten).
    fn correct(&self, lu: &mut DenseLu, r: &mut [f64], x: &mut [f64]) {
        let n = self.n;
        lu.solve(r);
        for (c, xc) in x.iter_mut().enumerate() {
            let w = self.w_sqrt(c).powi(2);
            let mut v = 0.0;
            for (a, ra) in r.iter().enumerate() {
                v += self.phiq[a * n + c] * ra;
            }
            *xc -= w * v;
        }
    }

    /// Project y = (q, q̇, …) onto Φ = 0 (Newton) and Φ̇ = 0 (one linear solve) at time t.
    /// Returns the number of Newton iterations.
    ///
    /// # Errors
    /// [`MbdError::Assembly`] when Newton does not reach `tol` (‖Φ‖∞ in m or rad), and
    /// [`MbdError::RedundantConstraints`] when Φ_q loses rank.
    pub fn project(&mut self, t: f64, y: &mut [f64], tol: f64) -> Result<usize, MbdError> {
        let (n, m) = (self.n, self.m);
        if m == 0 {
            return Ok(0);
        }
        let mut lu = DenseLu::default();
        let zeros = vec![0.0; n];
        let mut r = vec![0.0; m];
        let mut it = 0;
        loop {
            let (q, _) = y.split_at_mut(n);
            self.eval_constraints(t, q, &zeros);
            let res = self.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if res <= tol {
                break;
            }
            if it >= MAX_NEWTON || !res.is_finite() {
                let (k, _) = self
                    .phi
                    .iter()
                    .enumerate()
                    .fold((0, 0.0f64), |(bk, bv), (k, v)| {
                        if v.abs() > bv {
                            (k, v.abs())
                        } else {
                            (bk, bv)
                        }
                    });
                return Err(MbdError::Assembly {
                    t,
                    residual: res,
                    iterations: it,
                    worst: self.row_labels()[k].clone(),
                });
            }
            if !self.factor_s(&mut lu) {
                self.check_rank(t, &y[..n])?;
                return Err(MbdError::Assembly {
                    t,
                    residual: res,
                    iterations: it,
                    worst: "singular constraint Jacobian".into(),
                });
            }
            r.copy_from_slice(&self.phi);
            self.correct(&mut lu, &mut r, q);
            it += 1;
        }
        // velocities: Φ̇(q, q̇) = Φ_q q̇ + Φ_t is affine in q̇, so one correction is exact
        let (q, rest) = y.split_at_mut(n);
        let qd = &mut rest[..n];
        self.eval_constraints(t, q, qd);
        if !self.factor_s(&mut lu) {
            self.check_rank(t, q)?;
        }
        r.copy_from_slice(&self.phid);
        self.correct(&mut lu, &mut r, qd);
        Ok(it)
    }

    /// A consistent initial state y0 = (q, q̇) at t0 from the poses and velocities given to the
    /// builder: rank check, Newton on positions to ‖Φ‖∞ ≤ 1e-12, then velocities.
    ///
    /// # Errors
    /// [`MbdError::RedundantConstraints`] or [`MbdError::Assembly`].
    pub fn initial_state(&mut self, t0: f64) -> Result<Vec<f64>, MbdError> {
        let mut y = self.given_state();
        let n = self.n;
        self.check_rank(t0, &y[..n])?;
        self.project(t0, &mut y, 1e-12)?;
        Ok(y)
    }

    /// Constraint violations (‖Φ‖∞ in m or rad, ‖Φ̇‖∞ in m/s or rad/s) at (t, y).
    pub fn violation(&mut self, t: f64, y: &[f64]) -> (f64, f64) {
        let n = self.n;
        let (q, qd) = y.split_at(n);
        self.eval_constraints(t, q, qd);
        let a = self.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let b = self.phid.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        (a, b)
    }
}
