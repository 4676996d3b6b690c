//! The Newton systems of the implicit integrator in second-order form, from the analytic
//! Jacobians of the elements ([`crate::jacobian`]).
//!
//! The first-order system is y = (q, v, E_d) with q̇ = v, v̇ = a(q, v) from the augmented
//! equations (see [`crate::system`]):
//!
//! ```text
//! G [a; λ] = [Q(t, q, v); b(t, q, v)],   G = [M Φ_qᵀ; Φ_q 0],
//! b = γ − 2αΦ̇ − β²Φ,  γ = −(Φ_q v)_q v − …
//! ```
//!
//! NDF asks for solutions of (I − cJ) Δy = r. Eliminating Δq = r_q + cΔv and writing the
//! solution of the linearized augmented equations with an auxiliary multiplier μ gives a system
//! of size n + m instead of 2n + 1 (the same reduction as the iteration matrix of implicit
//! integrators in second-order form, e.g. Géradin & Cardona, *Flexible Multibody Dynamics*,
//! Wiley 2001, §11.3, and the HHT/generalized-α matrices of Negrut, Rampalli, Ottarsson & Sajdak,
//! J. Comput. Nonlinear Dyn. 2 (2007) 73–85, eq. 16):
//!
//! ```text
//! [ M − c Q_v − c² Q_q          Φ_qᵀ ] [ Δv ]   [ M r_v + c Q_q r_q  ]
//! [ Φ_q − c b_v − c² b_q        0    ] [ cμ ] = [ Φ_q r_v + c b_q r_q ]
//! ```
//!
//! with b_v = −2(Φ_q v)_q − 2αΦ_q and b_q = −2α(Φ_q v)_q − β²Φ_q − (Φ_q a)_q (the last term
//! from differentiating Φ_q a = b). E_d is a passive integral (nothing depends on it): its row is
//! taken as ΔE = r_E, which simplified Newton corrects at the next iteration.
//!
//! Left out (the matrix is an approximation, as simplified Newton allows): the derivatives of
//! M(q) of floating-frame bodies times a, the geometric stiffness (Φ_qᵀλ)_q and ∂γ/∂q. They
//! scale with the accelerations, the multipliers and the squared velocities, and enter with c²
//! against M: they matter only for steps long against the mechanism's own time scales, where
//! they cost Newton iterations (counted in the run statistics), not accuracy.
//!
//! Models with LuGre bristle states use the solver's own finite-difference Jacobian of the
//! whole first-order system (their ż rows are not in [`crate::Jacobians`]), as does
//! [`crate::JacobianMode::FiniteDifference`].

use clr_ode::linalg::DenseLu;

use crate::jacobian::Jacobians;
use crate::system::Model;

/// How the NDF integrator obtains its Newton matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum JacobianMode {
    /// The elements' analytic Jacobians in the reduced second-order system of size n + m (see
    /// the module docs of `newton`); the default. Models with LuGre bristle states fall back to
    /// [`JacobianMode::FiniteDifference`] (reported in the run's notes).
    #[default]
    Analytic,
    /// Forward differences of the whole first-order right-hand side by clr-ode (2n + 2
    /// evaluations, each with an augmented solve) and a dense LU of size 2n + 1 + bristles: the
    /// independent check, and the method of clr before the analytic Newton matrix.
    FiniteDifference,
}

/// Workspace of the reduced Newton systems: the Jacobians kept between factorizations, the mass
/// matrix, the coefficient c and the LU of the (n + m) matrix. Sized once per model; nothing
/// here allocates after the first use.
#[derive(Debug, Default)]
pub(crate) struct NewtonWs {
    pub(crate) mode: JacobianMode,
    jac: Jacobians,
    /// M(q), column-major n × n.
    mass: Vec<f64>,
    /// b_q (m × n, row-major).
    b_q: Vec<f64>,
    /// (Φ_q a)_q scratch (m × n, row-major).
    phi_a_q: Vec<f64>,
    /// Accelerations a at the Jacobian's state.
    acc: Vec<f64>,
    /// Right-hand side / solution of the reduced system (n + m).
    rhs: Vec<f64>,
    lu: DenseLu,
    c: f64,
}

impl Model {
    /// Whether the integrator uses the reduced analytic Newton systems.
    pub(crate) fn uses_reduced_newton(&self) -> bool {
        self.newton.mode == JacobianMode::Analytic && self.bristles.len() == 0
    }

    /// Evaluate the Jacobians, M and b_q at (t, y) for the following factorizations.
    pub(crate) fn reduced_jacobian(&mut self, t: f64, y: &[f64]) -> bool {
        let (n, m) = (self.n, self.m);
        let mut ws = std::mem::take(&mut self.newton);
        ws.mass.resize(n * n, 0.0);
        ws.b_q.resize(m * n, 0.0);
        ws.phi_a_q.resize(m * n, 0.0);
        ws.acc.resize(n, 0.0);
        ws.rhs.resize(n + m, 0.0);
        ws.lu.resize(n + m);
        let (q, v) = (&y[..n], &y[n..2 * n]);
        let ok = self.solve_accelerations(t, q, v);
        ws.acc.copy_from_slice(&self.sol[..n]);
        self.jacobians_into(t, q, v, &mut ws.jac);
        self.mass_into(q, &mut ws.mass);
        ws.phi_a_q.fill(0.0);
        self.analytic_constraints(q, &ws.acc, &mut ws.phi_a_q);
        let (al, be) = (self.alpha, self.beta);
        for ((bq, pvq), (pq, paq)) in ws
            .b_q
            .iter_mut()
            .zip(&ws.jac.phi_qqd_q)
            .zip(ws.jac.phi_q.iter().zip(&ws.phi_a_q))
        {
            *bq = -2.0 * al * pvq - be * be * pq - paq;
        }
        let finite = [&ws.jac.dq, &ws.jac.dv, &ws.mass, &ws.b_q]
            .iter()
            .all(|v| v.iter().all(|x| x.is_finite()));
        self.newton = ws;
        ok && finite
    }

    /// Form and factor the reduced matrix for the coefficient c.
    pub(crate) fn reduced_factor(&mut self, c: f64) -> bool {
        let (n, m) = (self.n, self.m);
        let nm = n + m;
        let al = self.alpha;
        let ws = &mut self.newton;
        ws.c = c;
        let Jacobians {
            dq,
            dv,
            phi_q,
            phi_qqd_q,
            ..
        } = &ws.jac;
        let a = ws.lu.matrix_mut();
        for col in 0..n {
            let out = &mut a[col * nm..col * nm + n];
            for (r, o) in out.iter_mut().enumerate() {
                *o = ws.mass[r + col * n] - c * dv[r * n + col] - c * c * dq[r * n + col];
            }
            for r in 0..m {
                let b_v = -2.0 * phi_qqd_q[r * n + col] - 2.0 * al * phi_q[r * n + col];
                a[n + r + col * nm] = phi_q[r * n + col] - c * b_v - c * c * ws.b_q[r * n + col];
            }
        }
        for r in 0..m {
            let col = &mut a[(n + r) * nm..(n + r + 1) * nm];
            for (k, o) in col[..n].iter_mut().enumerate() {
                *o = phi_q[r * n + k];
            }
            col[n..].fill(0.0);
        }
        ws.lu.factor().is_ok()
    }

    /// Solve (I − cJ) Δy = b in place through the reduced system.
    pub(crate) fn reduced_solve(&mut self, b: &mut [f64]) {
        let n = self.n;
        let ws = &mut self.newton;
        let c = ws.c;
        let (rq, rest) = b.split_at_mut(n);
        let rv = &mut rest[..n];
        let Jacobians { dq, phi_q, .. } = &ws.jac;
        let (top, bottom) = ws.rhs.split_at_mut(n);
        for (r, t) in top.iter_mut().enumerate() {
            let mut s = 0.0;
            for k in 0..n {
                s += ws.mass[r + k * n] * rv[k] + c * dq[r * n + k] * rq[k];
            }
            *t = s;
        }
        for (r, o) in bottom.iter_mut().enumerate() {
            let mut s = 0.0;
            for k in 0..n {
                s += phi_q[r * n + k] * rv[k] + c * ws.b_q[r * n + k] * rq[k];
            }
            *o = s;
        }
        ws.lu.solve(&mut ws.rhs);
        rv.copy_from_slice(&ws.rhs[..n]);
        for (q, v) in rq.iter_mut().zip(rv.iter()) {
            *q += c * v;
        }
    }

    /// The mass matrix M(q) (column-major n × n, overwritten).
    pub(crate) fn mass_into(&self, q: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        crate::system::add_mass(&self.bodies, &self.beams, &self.floating, q, out, self.n);
    }
}
