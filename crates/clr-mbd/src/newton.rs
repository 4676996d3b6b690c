//! The Newton systems of the implicit integrator in second-order form, from the analytic
//! Jacobians of the elements ([`crate::jacobian`]).
//!
//! The first-order system is y = (q, v, E_d, W_in) with q̇ = v, v̇ = a(q, v) from the augmented
//! equations (see [`crate::system`]):
//!
//! ```text
//! G [a; λ] = [Q(t, q, v); b(t, q, v)],   G = [M Φ_qᵀ; Φ_q 0],
//! b = γ − 2αΦ̇ − β²Φ,  γ = −(Φ_q v)_q v − …
//! ```
//!
//! NDF asks for solutions of (I − cJ) Δy = r. Eliminating Δq = r_q + cΔv and writing the
//! solution of the linearized augmented equations with an auxiliary multiplier μ gives a system
//! of size n + m instead of 2n + 2 (the same reduction as the iteration matrix of implicit
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
//! from differentiating Φ_q a = b). E_d and W_in are passive quadratures (nothing depends on
//! them): their rows are taken as ΔE = r_E and ΔW = r_W (left in place by the solve), which
//! simplified Newton corrects at the next iteration.
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

use clr_ode::{Direction, OdeSystem};

use crate::jacobian::Jacobians;
use crate::linsys::Factorization;
use crate::system::Model;

/// How the NDF integrator obtains its Newton matrix (`[solver] jacobian` in model files:
/// `analytic`, `finite_difference`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JacobianMode {
    /// The elements' analytic Jacobians in the reduced second-order system of size n + m (see
    /// the module docs of `newton`); the default. Models with LuGre bristle states fall back to
    /// [`JacobianMode::FiniteDifference`] (reported in the run's notes).
    #[default]
    Analytic,
    /// Forward differences of the whole first-order right-hand side by clr-ode (2n + 3
    /// evaluations, each with an augmented solve) and a dense LU of size 2n + 2 + bristles: the
    /// independent check, and the method of clr before the analytic Newton matrix.
    FiniteDifference,
}

/// Workspace of the reduced Newton systems: the Jacobians kept between factorizations, the
/// non-zeros of the blocks of the reduced matrix, the coefficient c and the factorization of the
/// (n + m) matrix. Owned by the integration driver (not by the [`Model`], which stays the
/// problem), sized at the first use; after that nothing here allocates except when the sparse
/// pattern grows.
#[derive(Debug, Default)]
pub struct NewtonWs {
    mode: JacobianMode,
    jac: Jacobians,
    /// (Φ_q a)_q scratch (m × n, row-major).
    phi_a_q: Vec<f64>,
    /// Accelerations a at the Jacobian's state.
    acc: Vec<f64>,
    /// Non-zeros (row, col, value) of M, Q_q, Q_v (n × n), Φ_q, b_v, b_q (m × n).
    mass: Vec<(usize, usize, f64)>,
    dq: Vec<(usize, usize, f64)>,
    dv: Vec<(usize, usize, f64)>,
    phi_q: Vec<(usize, usize, f64)>,
    b_v: Vec<(usize, usize, f64)>,
    b_q: Vec<(usize, usize, f64)>,
    /// Right-hand side / solution of the reduced system (n + m).
    rhs: Vec<f64>,
    fact: Factorization,
    c: f64,
}

impl NewtonWs {
    /// A workspace for `model` with the Newton matrix `mode` and the factorization
    /// `linear_solver` (sparse from n + m ≥ [`crate::SPARSE_FROM`] with `Auto`).
    pub fn new(model: &Model, mode: JacobianMode, linear_solver: crate::LinearSolver) -> Self {
        let mut ws = Self {
            mode,
            ..Default::default()
        };
        ws.fact.sparse = linear_solver.is_sparse(model.n + model.m);
        ws
    }

    /// Whether the integrator uses the reduced analytic Newton systems for `model`: not with
    /// [`JacobianMode::FiniteDifference`], nor with LuGre bristle states (their ż rows are not in
    /// [`Jacobians`]), nor with inputs that are functions of the state (their derivatives are
    /// not known).
    pub fn is_reduced(&self, model: &Model) -> bool {
        self.mode == JacobianMode::Analytic
            && model.bristles.len() == 0
            && model.feedback.is_empty()
    }
}

/// The model as the integrator sees it: the [`Model`]'s right-hand side and events, and the
/// reduced Newton systems of a [`NewtonWs`] ([`OdeSystem::has_newton_solver`]). Built for each
/// call into the solver; the Jacobian it keeps lives in the workspace, so it is reused across
/// steps as before.
pub struct Integrand<'a> {
    /// The problem.
    pub model: &'a mut Model,
    /// The Newton workspace.
    pub ws: &'a mut NewtonWs,
}

impl OdeSystem for Integrand<'_> {
    fn dim(&self) -> usize {
        self.model.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        self.model.rhs(t, y, dydt)
    }
    fn has_newton_solver(&self) -> bool {
        self.ws.is_reduced(self.model)
    }
    fn newton_jacobian(&mut self, t: f64, y: &[f64]) -> bool {
        self.model.reduced_jacobian(self.ws, t, y)
    }
    fn newton_factor(&mut self, c: f64) -> bool {
        self.model.reduced_factor(self.ws, c)
    }
    fn newton_solve(&mut self, b: &mut [f64]) {
        self.model.reduced_solve(self.ws, b)
    }
    fn n_events(&self) -> usize {
        self.model.n_events()
    }
    fn events(&mut self, t: f64, y: &[f64], g: &mut [f64]) {
        self.model.events(t, y, g)
    }
    fn event_direction(&self, i: usize) -> Direction {
        self.model.event_direction(i)
    }
    fn event_terminal(&self, i: usize) -> bool {
        self.model.event_terminal(i)
    }
    fn max_step(&mut self, t: f64, y: &[f64]) -> f64 {
        self.model.max_step(t, y)
    }
}

/// The non-zeros of a row-major matrix with `cols` columns into `out`.
fn nonzeros(a: &[f64], cols: usize, out: &mut Vec<(usize, usize, f64)>) {
    out.clear();
    for (k, &v) in a.iter().enumerate() {
        if v != 0.0 {
            out.push((k / cols, k % cols, v));
        }
    }
}

impl Model {
    /// Evaluate the Jacobians, M, b_v and b_q at (t, y) into `ws` for the following
    /// factorizations.
    fn reduced_jacobian(&mut self, ws: &mut NewtonWs, t: f64, y: &[f64]) -> bool {
        let (n, m) = (self.n, self.m);
        ws.phi_a_q.resize(m * n, 0.0);
        ws.acc.resize(n, 0.0);
        ws.rhs.resize(n + m, 0.0);
        let (q, v) = (&y[..n], &y[n..2 * n]);
        let ok = self.solve_accelerations(t, q, v);
        ws.acc.copy_from_slice(&self.sol[..n]);
        self.jacobians_into(t, q, v, &mut ws.jac);
        ws.mass.clear();
        let mass = &mut ws.mass;
        crate::system::add_mass(
            &self.bodies,
            &self.beams,
            &self.floating,
            q,
            &mut |r, c, v| mass.push((r, c, v)),
        );
        ws.phi_a_q.fill(0.0);
        self.analytic_constraints(q, &ws.acc, &mut ws.phi_a_q);
        nonzeros(&ws.jac.dq, n, &mut ws.dq);
        nonzeros(&ws.jac.dv, n, &mut ws.dv);
        nonzeros(&ws.jac.phi_q, n, &mut ws.phi_q);
        let (al, be) = (self.alpha, self.beta);
        ws.b_v.clear();
        ws.b_q.clear();
        for k in 0..m * n {
            let (pq, pvq, paq) = (ws.jac.phi_q[k], ws.jac.phi_qqd_q[k], ws.phi_a_q[k]);
            let (r, c) = (k / n, k % n);
            let bv = -2.0 * pvq - 2.0 * al * pq;
            let bq = -2.0 * al * pvq - be * be * pq - paq;
            if bv != 0.0 {
                ws.b_v.push((r, c, bv));
            }
            if bq != 0.0 {
                ws.b_q.push((r, c, bq));
            }
        }
        let finite = [&ws.mass, &ws.dq, &ws.dv, &ws.b_v, &ws.b_q]
            .iter()
            .all(|l| l.iter().all(|e| e.2.is_finite()));
        ok && finite
    }

    /// Form and factor the reduced matrix for the coefficient c:
    /// [M − cQ_v − c²Q_q, Φ_qᵀ; Φ_q − c b_v − c² b_q, 0].
    fn reduced_factor(&self, ws: &mut NewtonWs, c: f64) -> bool {
        let (n, m) = (self.n, self.m);
        let nm = n + m;
        ws.c = c;
        let c2 = c * c;
        let blocks = [
            (&ws.mass, 0, 1.0),
            (&ws.dv, 0, -c),
            (&ws.dq, 0, -c2),
            (&ws.phi_q, n, 1.0),
            (&ws.b_v, n, -c),
            (&ws.b_q, n, -c2),
        ];
        let fact = &mut ws.fact;
        if fact.sparse {
            let g = &mut fact.growing;
            g.begin(nm);
            for (list, row0, f) in blocks {
                for &(r, col, v) in list {
                    g.add(row0 + r, col, f * v);
                }
            }
            for &(r, col, v) in &ws.phi_q {
                g.add(col, n + r, v);
            }
            g.factor().is_ok()
        } else {
            fact.dense.resize(nm);
            let a = fact.dense.matrix_mut();
            a.fill(0.0);
            for (list, row0, f) in blocks {
                for &(r, col, v) in list {
                    a[row0 + r + col * nm] += f * v;
                }
            }
            for &(r, col, v) in &ws.phi_q {
                a[col + (n + r) * nm] += v;
            }
            fact.dense.factor().is_ok()
        }
    }

    /// Solve (I − cJ) Δy = b in place through the reduced system: Δv and cμ from
    /// [M r_v + c Q_q r_q; Φ_q r_v + c b_q r_q], then Δq = r_q + cΔv, ΔE = r_E, ΔW = r_W.
    fn reduced_solve(&self, ws: &mut NewtonWs, b: &mut [f64]) {
        let n = self.n;
        let c = ws.c;
        let (rq, rest) = b.split_at_mut(n);
        let rv = &mut rest[..n];
        ws.rhs.fill(0.0);
        for &(r, col, v) in &ws.mass {
            ws.rhs[r] += v * rv[col];
        }
        for &(r, col, v) in &ws.dq {
            ws.rhs[r] += c * v * rq[col];
        }
        for &(r, col, v) in &ws.phi_q {
            ws.rhs[n + r] += v * rv[col];
        }
        for &(r, col, v) in &ws.b_q {
            ws.rhs[n + r] += c * v * rq[col];
        }
        if ws.fact.sparse {
            ws.fact.growing.solve(&mut ws.rhs);
        } else {
            ws.fact.dense.solve(&mut ws.rhs);
        }
        rv.copy_from_slice(&ws.rhs[..n]);
        for (q, v) in rq.iter_mut().zip(rv.iter()) {
            *q += c * v;
        }
    }
}
