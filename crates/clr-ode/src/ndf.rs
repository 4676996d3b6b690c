//! The NDF/BDF solver of the ode15s family (Shampine & Reichelt, "The MATLAB ODE suite",
//! SIAM J. Sci. Comput. 18 (1997) 1–22, §2).
//!
//! - Quasi-constant step size: the backward differences D_j = ∇^j y_n (j = 0 … k+2) are kept
//!   for an equally spaced history and rescaled when h changes (D ← (R U)ᵀ D, Shampine &
//!   Reichelt §2.2, the matrices of SciPy's `_ivp/bdf.py`).
//! - k-step NDF: Σ_{j=1..k} γ_j ∇^j y_{n+1} − κ γ_k (y_{n+1} − y⁽⁰⁾_{n+1}) = h f(t_{n+1}, y_{n+1}),
//!   γ_j = Σ_{i=1..j} 1/i, κ = (−0.1850, −1/9, −0.0823, −0.0415, 0) (their Table 1; κ = 0 for BDF).
//!   With d = y_{n+1} − y⁽⁰⁾ and α_k = (1 − κ) γ_k this is M (d + ψ) = (h/α_k) f, with
//!   ψ = Σ γ_j D_j / α_k, solved by simplified Newton with the matrix M − (h/α_k) J.
//! - Local error estimate (κ γ_k + 1/(k+1)) d; orders k−1, k, k+1 compared after k+1 steps of
//!   constant size; step factor ≤ 10, rejection factor ≥ 0.2, safety 0.9·(2·4+1)/(2·4+iters).
//! - J is re-evaluated only when Newton converges too slowly with an old J; the LU of M − cJ is
//!   refactored only when c = h/α_k changes or J is new. Systems may factor and solve M − cJ
//!   themselves ([`OdeSystem::has_newton_solver`]).
//! - Newton stops when θ/(1 − θ)·‖Δ‖ is below the tolerance, θ the observed contraction rate. For
//!   an ODE (M = I) with `Options::newton_rate_reuse` the first iteration may already stop, with
//!   the θ measured in an earlier step with the same factorization (RADAU5, CVODE); a non-contracting
//!   correction far below the tolerance is the noise floor of f and accepted
//!   (`NOISE_FLOOR`).

use crate::linalg::DenseLu;
use crate::options::Formula;
use crate::solver::{initial_step, rms_scaled, Ctx, Failure, Method};
use crate::system::{MassKind, OdeSystem};

/// Highest order.
pub const MAX_ORDER: usize = 5;
const NEWTON_MAXITER: usize = 4;
const MIN_FACTOR: f64 = 0.2;
/// Newton stops when θ/(1 − θ)·‖Δ‖ < NEWTON_TOL (θ the observed contraction rate, ‖·‖ the RMS
/// norm in units of atol + rtol|y|). ode15s uses 0.33 in its max-norm, SciPy
/// max(10ε/rtol, min(0.03, √rtol)), diffsol 0.2; 0.1 keeps Robertson at 1e-7 and the other
/// Test Set problems above 5 digits with about 2.2 iterations per step.
const NEWTON_TOL: f64 = 0.1;
const MAX_FACTOR: f64 = 10.0;
/// A Newton correction that does not contract (rate ≥ 0.9) is accepted when its norm is below
/// this fraction of the Newton tolerance: it is then the noise floor of f, which can sit well
/// above the 100ε round-off floor of ode15s when f involves an ill-conditioned solve (the
/// accelerations of a flexible multibody model). CVODE accepts such iterates by bounding the
/// remaining error with ‖Δ‖·min(1, rate) (Hindmarsh et al., ACM TOMS 31 (2005), §2.1).
const NOISE_FLOOR: f64 = 1e-2;
/// Step increases below this factor (at unchanged order) are not taken: keeping h keeps the LU
/// of M − (h/α_k) J valid (the same hysteresis as CVODE's η threshold).
const MIN_INCREASE: f64 = 1.5;
/// NDF κ_k, k = 1…5 (Shampine & Reichelt 1997, Table 1).
const KAPPA_NDF: [f64; MAX_ORDER + 1] = [0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0];

/// Why a Newton solve failed (for the error reported after the per-step limit).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum NewtonFail {
    Slow,
    NonFiniteRhs,
    NonFiniteJacobian,
    Singular,
}

/// The NDF/BDF method state. All buffers are sized by `resize`; `step` does not allocate.
#[derive(Debug, Default)]
pub struct NdfMethod {
    n: usize,
    t: f64,
    t_old: f64,
    /// |h| for the next step (units of t).
    h_abs: f64,
    /// the step just taken (for dense output).
    h_last: f64,
    order: usize,
    max_order: usize,
    n_equal_steps: usize,
    /// History length fixed by `load_history` (fixed-order runs).
    fixed_order: bool,
    gamma: [f64; MAX_ORDER + 2],
    alpha: [f64; MAX_ORDER + 2],
    error_const: [f64; MAX_ORDER + 2],
    /// U_k = R_k(1) for each order (constant).
    u: [[[f64; MAX_ORDER + 1]; MAX_ORDER + 1]; MAX_ORDER + 1],
    newton_tol: f64,
    /// D_0 … D_{MAX_ORDER+2}, each of length n (row-major).
    d: Vec<f64>,
    d_tmp: Vec<f64>,
    y_pred: Vec<f64>,
    psi: Vec<f64>,
    dd: Vec<f64>,
    y_new: Vec<f64>,
    f: Vec<f64>,
    dy: Vec<f64>,
    scale: Vec<f64>,
    work: Vec<f64>,
    jac: Vec<f64>,
    mass: Vec<f64>,
    mass_kind: MassKind,
    /// The system solves its own Newton systems ([`OdeSystem::has_newton_solver`]).
    own_solver: bool,
    lu: DenseLu,
    lu_valid: bool,
    jac_current: bool,
    /// Contraction rate of the last Newton iteration that measured one with the current
    /// factorization (`None` after a refactorization).
    rate: Option<f64>,
    last_error_norm: f64,
    last_safety: f64,
    /// Order and step ratio chosen after the last step, applied when the next step begins.
    pending: Option<(usize, f64)>,
}

#[inline]
fn row(d: &[f64], n: usize, k: usize) -> &[f64] {
    &d[k * n..(k + 1) * n]
}

/// The (k+1) × (k+1) matrix R of Shampine & Reichelt §2.2 for a step ratio `factor`
/// (R_{ij} = Π_{m=1..i} (m − 1 − factor·j)/m, R_{0j} = 1).
fn compute_r(order: usize, factor: f64, r: &mut [[f64; MAX_ORDER + 1]; MAX_ORDER + 1]) {
    for j in 0..=order {
        r[0][j] = 1.0;
    }
    for i in 1..=order {
        r[i][0] = 0.0;
        for j in 1..=order {
            let m = (i as f64 - 1.0 - factor * j as f64) / i as f64;
            r[i][j] = r[i - 1][j] * m;
        }
    }
}

impl NdfMethod {
    /// Current order k (1–5).
    pub fn order(&self) -> usize {
        self.order
    }

    /// Step size proposed for the next step (units of t).
    pub fn next_step_size(&self) -> f64 {
        self.h_abs
    }

    fn set_coefficients(&mut self, formula: Formula) {
        let kappa = match formula {
            Formula::Ndf => KAPPA_NDF,
            Formula::Bdf => [0.0; MAX_ORDER + 1],
        };
        self.gamma[0] = 0.0;
        for k in 1..=MAX_ORDER + 1 {
            self.gamma[k] = self.gamma[k - 1] + 1.0 / k as f64;
        }
        for k in 1..=MAX_ORDER {
            compute_r(k, 1.0, &mut self.u[k]);
        }
        for k in 0..=MAX_ORDER + 1 {
            let kap = if k <= MAX_ORDER { kappa[k] } else { 0.0 };
            self.alpha[k] = (1.0 - kap) * self.gamma[k];
            self.error_const[k] = kap * self.gamma[k] + 1.0 / (k as f64 + 1.0);
        }
    }

    /// Rescale D_0…D_order for a step-size ratio `factor` (D ← (R U)ᵀ D).
    fn change_d(&mut self, factor: f64) {
        let n = self.n;
        let k = self.order;
        // R(factor) for all orders at once: entries (i, j) ≤ k are those of order k, and U_k is
        // zero beyond k, so RU restricted to 0..=k is the order-k product. Fixed 6 × 6 loops
        // unroll without bounds checks.
        let mut r = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
        r[0] = [1.0; MAX_ORDER + 1];
        for i in 1..=MAX_ORDER {
            let inv = 1.0 / i as f64;
            for j in 0..=MAX_ORDER {
                r[i][j] = r[i - 1][j] * ((i as f64 - 1.0 - factor * j as f64) * inv);
            }
        }
        let u = &self.u[k];
        let mut ru = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
        for i in 0..=MAX_ORDER {
            for m in 0..=MAX_ORDER {
                let rim = r[i][m];
                for j in 0..=MAX_ORDER {
                    ru[i][j] += rim * u[m][j];
                }
            }
        }
        // D_new[j] = Σ_i RU[i][j] D[i]
        let src = &self.d[..(k + 1) * n];
        let tmp = &mut self.d_tmp[..(k + 1) * n];
        for (out, ru_j) in tmp.chunks_exact_mut(n).zip(0..=MAX_ORDER) {
            out.fill(0.0);
            for (d_i, ru_i) in src.chunks_exact(n).zip(ru.iter()) {
                let c = ru_i[ru_j];
                for (o, s) in out.iter_mut().zip(d_i) {
                    *o += c * s;
                }
            }
        }
        self.d[..(k + 1) * n].copy_from_slice(tmp);
    }

    fn eval_jacobian<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        ctx: &mut Ctx,
        t: f64,
        y_is_pred: bool,
    ) -> bool {
        let n = self.n;
        ctx.stats.jac_evals += 1;
        let y: &[f64] = if y_is_pred { &self.y_pred } else { &self.y_new };
        if self.own_solver {
            return sys.newton_jacobian(t, y);
        }
        self.jac.fill(0.0);
        if sys.has_jacobian() {
            sys.jacobian(t, y, &mut self.jac);
        } else {
            // forward differences with increments δ_j = √ε · max(|y_j|, atol_j / rtol)
            let (f0, rest) = self.work.split_at_mut(n);
            let (yp, f1) = rest.split_at_mut(n);
            sys.rhs(t, y, f0);
            ctx.stats.f_evals += 1;
            yp[..n].copy_from_slice(y);
            let sq = f64::EPSILON.sqrt();
            for j in 0..n {
                let mut delta = sq * y[j].abs().max(ctx.atol[j] / ctx.rtol);
                if delta == 0.0 || !delta.is_finite() {
                    delta = sq;
                }
                let yj = yp[j];
                yp[j] = yj + delta;
                let delta = yp[j] - yj;
                sys.rhs(t, yp, f1);
                ctx.stats.f_evals += 1;
                yp[j] = yj;
                for i in 0..n {
                    self.jac[i + j * n] = (f1[i] - f0[i]) / delta;
                }
            }
        }
        self.jac.iter().all(|v| v.is_finite())
    }

    /// Build and factor M − cJ (by the system when it has its own Newton solver).
    fn factor<S: OdeSystem>(&mut self, sys: &mut S, ctx: &mut Ctx, c: f64) -> bool {
        self.rate = None;
        if self.own_solver {
            ctx.stats.lu_factorizations += 1;
            self.lu_valid = sys.newton_factor(c);
            return self.lu_valid;
        }
        let n = self.n;
        let a = self.lu.matrix_mut();
        for (aij, jij) in a.iter_mut().zip(&self.jac) {
            *aij = -c * jij;
        }
        if self.mass_kind == MassKind::Identity {
            for i in 0..n {
                a[i + i * n] += 1.0;
            }
        } else {
            for (aij, mij) in a.iter_mut().zip(&self.mass) {
                *aij += mij;
            }
        }
        ctx.stats.lu_factorizations += 1;
        self.lu_valid = self.lu.factor().is_ok();
        self.lu_valid
    }

    /// Simplified Newton for M (d + ψ) = c f(t_new, y_pred + d). Returns (converged, iterations).
    fn newton<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        ctx: &mut Ctx,
        t_new: f64,
        c: f64,
    ) -> (Result<(), NewtonFail>, usize) {
        let n = self.n;
        self.dd.fill(0.0);
        self.y_new.copy_from_slice(&self.y_pred);
        let mut dy_norm_old = -1.0;
        let identity = self.mass_kind == MassKind::Identity;
        let reuse = ctx.opts.newton_rate_reuse;
        let mut result = Err(NewtonFail::Slow);
        let mut iters = 0;
        // Round-off floor (ode15s, Shampine & Reichelt 1997): a correction this small is pure
        // rounding error; its ratio to the previous one is then meaningless (≈ 1 when the
        // predictor is exact, e.g. polynomial free flight), so it counts as converged instead
        // of tripping the divergence test.
        let min_norm = 100.0 * f64::EPSILON * rms_scaled(&self.y_pred, &self.scale);
        for k in 0..NEWTON_MAXITER {
            iters = k + 1;
            sys.rhs(t_new, &self.y_new, &mut self.f);
            ctx.stats.f_evals += 1;
            if !self.f.iter().all(|v| v.is_finite()) {
                result = Err(NewtonFail::NonFiniteRhs);
                break;
            }
            if identity {
                for (((dy, f), psi), dd) in
                    self.dy.iter_mut().zip(&self.f).zip(&self.psi).zip(&self.dd)
                {
                    *dy = c * f - psi - dd;
                }
            } else {
                // c f − M (ψ + d)
                for i in 0..n {
                    self.work[i] = self.psi[i] + self.dd[i];
                    self.dy[i] = c * self.f[i];
                }
                for j in 0..n {
                    let w = self.work[j];
                    if w != 0.0 {
                        for i in 0..n {
                            self.dy[i] -= self.mass[i + j * n] * w;
                        }
                    }
                }
            }
            if self.own_solver {
                sys.newton_solve(&mut self.dy);
            } else {
                self.lu.solve(&mut self.dy);
            }
            let dy_norm = rms_scaled(&self.dy, &self.scale);
            if !dy_norm.is_finite() {
                break;
            }
            if dy_norm <= min_norm {
                for ((y, dd), dy) in self.y_new.iter_mut().zip(self.dd.iter_mut()).zip(&self.dy) {
                    *y += dy;
                    *dd += dy;
                }
                result = Ok(());
                break;
            }
            let rate = if dy_norm_old >= 0.0 {
                dy_norm / dy_norm_old
            } else {
                -1.0
            };
            if rate >= 0.0 {
                self.rate = Some(rate);
            } else if let Some(r) = self.rate.filter(|&r| r < 0.9 && identity && reuse) {
                // first iteration: the rate measured with this factorization in an earlier step
                // predicts the remaining error (Hairer & Wanner's reuse of θ in RADAU5, CVODE's
                // crate), so a small enough first correction is accepted at once. Not with a
                // mass matrix: the algebraic components of an index-1 DAE need the converged
                // iterate (Robertson as a DAE loses every digit otherwise)
                if r / (1.0 - r) * dy_norm < self.newton_tol {
                    for ((y, dd), dy) in self.y_new.iter_mut().zip(self.dd.iter_mut()).zip(&self.dy)
                    {
                        *y += dy;
                        *dd += dy;
                    }
                    result = Ok(());
                    break;
                }
            }
            if rate >= 0.9 && dy_norm <= NOISE_FLOOR * self.newton_tol {
                // not contracting, but far below the tolerance: the corrections are the rounding
                // noise of f itself (accelerations from an ill-conditioned augmented solve), not
                // a divergence; accept as CVODE does (its test bounds the error by
                // ‖Δ‖·min(1, rate)), instead of halving h down to the step floor
                for ((y, dd), dy) in self.y_new.iter_mut().zip(self.dd.iter_mut()).zip(&self.dy) {
                    *y += dy;
                    *dd += dy;
                }
                result = Ok(());
                break;
            }
            if rate >= 0.0
                && (rate >= 0.9
                    || rate.powi((NEWTON_MAXITER - k) as i32) / (1.0 - rate) * dy_norm
                        > self.newton_tol)
            {
                break;
            }
            for ((y, dd), dy) in self.y_new.iter_mut().zip(self.dd.iter_mut()).zip(&self.dy) {
                *y += dy;
                *dd += dy;
            }
            // converged when the remaining error θ/(1 − θ)·‖Δ‖ is below the tolerance
            if dy_norm == 0.0 || (rate >= 0.0 && rate / (1.0 - rate) * dy_norm < self.newton_tol) {
                result = Ok(());
                break;
            }
            dy_norm_old = dy_norm;
        }
        ctx.stats.newton_iters += iters;
        (result, iters)
    }

    /// Fixed-order start from an equally spaced history (see [`crate::Ndf::start_with_history`]):
    /// `past` holds y(t), y(t − h), …, y(t − k h) flat.
    pub(crate) fn load_history(&mut self, past: &[f64], h: f64, k: usize) {
        let n = self.n;
        self.d.fill(0.0);
        // repeated backward differencing of the rows r_i = y(t − i h)
        self.d_tmp[..(k + 1) * n].copy_from_slice(&past[..(k + 1) * n]);
        self.d[..n].copy_from_slice(&past[..n]);
        for j in 1..=k {
            for i in 0..=k - j {
                for m in 0..n {
                    self.d_tmp[i * n + m] -= self.d_tmp[(i + 1) * n + m];
                }
            }
            self.d[j * n..(j + 1) * n].copy_from_slice(&self.d_tmp[..n]);
        }
        self.order = k;
        self.h_abs = h;
        self.fixed_order = true;
        self.lu_valid = false;
        self.pending = None;
    }
}

impl Method for NdfMethod {
    const SUPPORTS_MASS: bool = true;
    const STIFF: bool = true;

    fn resize(&mut self, n: usize) {
        self.n = n;
        self.d.resize((MAX_ORDER + 3) * n, 0.0);
        self.d_tmp.resize((MAX_ORDER + 3) * n, 0.0);
        for v in [
            &mut self.y_pred,
            &mut self.psi,
            &mut self.dd,
            &mut self.y_new,
            &mut self.f,
            &mut self.dy,
            &mut self.scale,
        ] {
            v.resize(n, 0.0);
        }
        self.work.resize(3 * n, 0.0);
        self.jac.resize(n * n, 0.0);
        self.mass.resize(n * n, 0.0);
        self.lu.resize(n);
    }

    fn capacity(&self) -> usize {
        [
            &self.d,
            &self.d_tmp,
            &self.y_pred,
            &self.psi,
            &self.dd,
            &self.y_new,
            &self.f,
            &self.dy,
            &self.scale,
            &self.work,
            &self.jac,
            &self.mass,
        ]
        .iter()
        .map(|v| v.capacity())
        .sum::<usize>()
            + self.lu.capacity()
    }

    fn init<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        ctx: &mut Ctx,
        t: f64,
        y: &[f64],
        t_end: f64,
    ) -> Result<(), Failure> {
        let n = self.n;
        let opts = ctx.opts;
        self.set_coefficients(opts.formula);
        self.max_order = opts.max_order.clamp(1, MAX_ORDER);
        self.newton_tol = NEWTON_TOL;
        self.t = t;
        self.t_old = t;
        self.h_last = 0.0;
        self.order = 1;
        self.n_equal_steps = 0;
        self.fixed_order = false;
        self.lu_valid = false;
        self.jac_current = false;
        self.last_error_norm = 0.0;
        self.last_safety = 0.9;
        self.pending = None;
        self.d.fill(0.0);
        self.d[..n].copy_from_slice(y);
        self.y_new.copy_from_slice(y);
        self.y_pred.copy_from_slice(y);
        // f(t0, y0)
        sys.rhs(t, y, &mut self.f);
        ctx.stats.f_evals += 1;
        if !self.f.iter().all(|v| v.is_finite()) {
            return Err(Failure::NonFiniteRhs { t });
        }
        self.mass_kind = sys.mass_kind();
        self.own_solver = sys.has_newton_solver();
        if self.mass_kind != MassKind::Identity {
            self.mass.fill(0.0);
            sys.mass(t, y, &mut self.mass);
        }
        if !self.eval_jacobian(sys, ctx, t, true) {
            return Err(Failure::NonFiniteJacobian { t });
        }
        self.jac_current = true;
        // initial slope y0' (D_1 = h y0')
        let mut slope_ok = true;
        if self.mass_kind != MassKind::Identity {
            // y0' from (M − δJ) y0' = f0 with a small δ: for a consistent index-1 DAE this gives
            // the consistent slope of the differential and algebraic components.
            let jmax = self.jac.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let delta = f64::EPSILON.sqrt() / jmax.max(1.0);
            if self.factor(sys, ctx, delta) {
                self.dy.copy_from_slice(&self.f);
                if self.own_solver {
                    sys.newton_solve(&mut self.dy);
                } else {
                    self.lu.solve(&mut self.dy);
                }
                self.f.copy_from_slice(&self.dy);
            } else {
                self.f.fill(0.0);
                slope_ok = false;
            }
            self.lu_valid = false;
        }
        let h = match opts.h0 {
            Some(h) => h.min(opts.h_max).min(t_end - t),
            None if !slope_ok => (1e-6 * (t_end - t)).min(opts.h_max),
            None => {
                let identity = self.mass_kind == MassKind::Identity;
                let stats = &mut *ctx.stats;
                let lu = &mut self.lu;
                let own = self.own_solver;
                let (yp0, work) = (&self.f, &mut self.work);
                let slope = |t: f64, y: &[f64], yp: &mut [f64]| {
                    sys.rhs(t, y, yp);
                    stats.f_evals += 1;
                    if !identity && own {
                        sys.newton_solve(yp);
                    } else if !identity {
                        // slope (M − δJ)⁻¹ f with the factorization made above
                        lu.solve(yp);
                    }
                    yp.iter().all(|v| v.is_finite())
                };
                initial_step(
                    slope, t, y, yp0, 1, ctx.rtol, ctx.atol, opts.h_max, t_end, work,
                )
            }
        };
        self.h_abs = h;
        for i in 0..n {
            self.d[n + i] = h * self.f[i];
        }
        Ok(())
    }

    fn step<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        ctx: &mut Ctx,
        t_end: f64,
    ) -> Result<(), Failure> {
        let n = self.n;
        let opts = ctx.opts;
        let fixed = opts.fixed_step;
        let t = self.t;
        if t >= t_end {
            // nothing left to integrate; the driver never asks for this
            return Err(Failure::Underflow {
                t,
                h: 0.0,
                h_min: 0.0,
            });
        }
        if let Some((order, factor)) = self.pending.take() {
            self.order = order;
            if factor != 1.0 {
                self.change_d(factor);
            }
        }
        let floor = opts.h_min.max(10.0 * crate::dopri5::ulp(t));
        let h_max = opts.h_max.min(sys.max_step(t, &self.d[..n]).max(floor));
        if self.h_abs > h_max {
            let f = h_max / self.h_abs;
            self.change_d(f);
            self.h_abs = h_max;
            self.n_equal_steps = 0;
            self.lu_valid = false;
        } else if self.h_abs < floor && !fixed {
            let f = floor / self.h_abs;
            self.change_d(f);
            self.h_abs = floor;
            self.n_equal_steps = 0;
            self.lu_valid = false;
        }
        let mut failures = 0usize;
        loop {
            if self.h_abs < floor && !fixed {
                return Err(Failure::Underflow {
                    t,
                    h: self.h_abs,
                    h_min: floor,
                });
            }
            let mut h = self.h_abs;
            let mut t_new = t + h;
            if t_new >= t_end || t_end - t_new <= 1e-8 * h {
                t_new = t_end;
                let h_cut = t_end - t;
                if h_cut != h {
                    self.change_d(h_cut / h);
                    self.n_equal_steps = 0;
                    self.lu_valid = false;
                }
                h = h_cut;
                self.h_abs = h;
            }
            let k = self.order;
            // predictor y⁽⁰⁾ = Σ_{j≤k} D_j, ψ = Σ_{j=1..k} γ_j D_j / α_k
            self.y_pred.copy_from_slice(row(&self.d, n, 0));
            self.psi.fill(0.0);
            for j in 1..=k {
                let g = self.gamma[j] / self.alpha[k];
                let dj = row(&self.d, n, j);
                for i in 0..n {
                    self.y_pred[i] += dj[i];
                    self.psi[i] += g * dj[i];
                }
            }
            for i in 0..n {
                self.scale[i] = ctx.atol[i] + ctx.rtol * self.y_pred[i].abs();
            }
            let c = h / self.alpha[k];
            if self.mass_kind == MassKind::StateDependent {
                self.mass.fill(0.0);
                sys.mass(t_new, &self.y_pred, &mut self.mass);
                self.lu_valid = false;
            }
            let mut outcome;
            let mut iters;
            loop {
                if !self.lu_valid && !self.factor(sys, ctx, c) {
                    outcome = Err(NewtonFail::Singular);
                    iters = 0;
                } else {
                    (outcome, iters) = self.newton(sys, ctx, t_new, c);
                }
                if outcome.is_ok() || self.jac_current {
                    break;
                }
                if !self.eval_jacobian(sys, ctx, t_new, true) {
                    outcome = Err(NewtonFail::NonFiniteJacobian);
                    break;
                }
                self.jac_current = true;
                self.lu_valid = false;
            }
            if let Err(why) = outcome {
                failures += 1;
                ctx.stats.rejected += 1;
                if fixed || failures > opts.max_newton_failures {
                    return Err(match why {
                        NewtonFail::NonFiniteRhs => Failure::NonFiniteRhs { t: t_new },
                        NewtonFail::NonFiniteJacobian => Failure::NonFiniteJacobian { t: t_new },
                        NewtonFail::Slow | NewtonFail::Singular => {
                            Failure::Newton { t, h, failures }
                        }
                    });
                }
                self.h_abs *= 0.5;
                self.change_d(0.5);
                self.n_equal_steps = 0;
                self.lu_valid = false;
                continue;
            }
            let safety =
                0.9 * (2 * NEWTON_MAXITER + 1) as f64 / (2 * NEWTON_MAXITER + iters) as f64;
            for i in 0..n {
                self.scale[i] = ctx.atol[i] + ctx.rtol * self.y_new[i].abs();
            }
            if let Some(r) = &opts.h_scaled_error {
                let hs = h.min(1.0);
                for s in &mut self.scale[r.clone()] {
                    *s /= hs;
                }
            }
            let ec = self.error_const[k];
            let mut acc = 0.0;
            for i in 0..n {
                let e = ec * self.dd[i] / self.scale[i];
                acc += e * e;
            }
            let error_norm = (acc / n as f64).sqrt();
            if fixed || error_norm <= 1.0 {
                self.last_error_norm = error_norm;
                self.last_safety = safety;
                self.t_old = t;
                self.t = t_new;
                self.h_last = h;
                break;
            }
            ctx.stats.rejected += 1;
            let factor = MIN_FACTOR.max(safety * error_norm.powf(-1.0 / (k as f64 + 1.0)));
            self.h_abs *= factor;
            self.change_d(factor);
            self.n_equal_steps = 0;
            self.lu_valid = false;
        }
        // update the differences: D_{k+2} = d − D_{k+1}, D_{k+1} = d, D_j += D_{j+1}
        let k = self.order;
        self.n_equal_steps += 1;
        self.jac_current = false;
        {
            let d = &mut self.d[..(k + 3) * n];
            let (lo, hi) = d.split_at_mut((k + 2) * n);
            let dk1 = &mut lo[(k + 1) * n..];
            for ((a, b), e) in hi.iter_mut().zip(dk1.iter_mut()).zip(&self.dd) {
                *a = e - *b;
                *b = *e;
            }
            for j in (0..=k).rev() {
                let (lo, hi) = d.split_at_mut((j + 1) * n);
                for (a, b) in lo[j * n..].iter_mut().zip(&hi[..n]) {
                    *a += b;
                }
            }
        }
        Ok(())
    }

    fn t_old(&self) -> f64 {
        self.t_old
    }

    fn t(&self) -> f64 {
        self.t
    }

    fn y(&self) -> &[f64] {
        row(&self.d, self.n, 0)
    }

    /// Dense output from the difference array (Shampine & Reichelt §2.2: the interpolating
    /// polynomial through the last k+1 equally spaced solution values).
    fn interpolate(&self, t: f64, out: &mut [f64]) {
        let n = self.n;
        let h = self.h_last;
        out.copy_from_slice(row(&self.d, n, 0));
        if h <= 0.0 {
            return;
        }
        let mut p = 1.0;
        for j in 0..self.order {
            let x = (t - (self.t - h * j as f64)) / (h * (j as f64 + 1.0));
            p *= x;
            let dj = row(&self.d, n, j + 1);
            for i in 0..n {
                out[i] += dj[i] * p;
            }
        }
    }

    fn finish_step(&mut self, ctx: &mut Ctx) {
        let n = self.n;
        let k = self.order;
        if ctx.opts.fixed_step {
            if !self.fixed_order && k < self.max_order {
                self.pending = Some((k + 1, 1.0));
            }
            return;
        }
        if self.n_equal_steps < k + 1 {
            return;
        }
        let norm_of = |j: usize, c: f64, scale: &[f64], d: &[f64]| {
            let dj = row(d, n, j);
            let mut acc = 0.0;
            for i in 0..n {
                let e = c * dj[i] / scale[i];
                acc += e * e;
            }
            (acc / n as f64).sqrt()
        };
        let em = if k > 1 {
            norm_of(k, self.error_const[k - 1], &self.scale, &self.d)
        } else {
            f64::INFINITY
        };
        let ep = if k < self.max_order {
            norm_of(k + 2, self.error_const[k + 1], &self.scale, &self.d)
        } else {
            f64::INFINITY
        };
        let factors = [
            em.powf(-1.0 / k as f64),
            self.last_error_norm.powf(-1.0 / (k as f64 + 1.0)),
            ep.powf(-1.0 / (k as f64 + 2.0)),
        ];
        let mut best = 1;
        for (i, f) in factors.iter().enumerate() {
            if *f > factors[best] {
                best = i;
            }
        }
        let factor = MAX_FACTOR.min(self.last_safety * factors[best]);
        if best == 1 && (1.0..MIN_INCREASE).contains(&factor) {
            // a small increase does not pay for the rescaling and the new LU: keep h and k,
            // and look again after k + 1 more steps
            self.n_equal_steps = 0;
            return;
        }
        // applied at the start of the next step, so that the dense output of the step just taken
        // stays valid until then
        self.pending = Some((k + best - 1, factor));
        self.h_abs *= factor;
        self.n_equal_steps = 0;
        self.lu_valid = false;
    }
}

impl crate::Solver<NdfMethod> {
    /// Start a fixed-order run from an equally spaced history, for order studies: `past` holds
    /// y(t0), y(t0 − h), …, y(t0 − k h) flat (k + 1 states, 1 ≤ k ≤ 5), and the method runs at
    /// order k. With [`crate::Options::fixed_step`] (step `h`) every step has size h and order k.
    pub fn start_with_history<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        t0: f64,
        past: &[f64],
        h: f64,
        t_end: f64,
    ) -> Result<(), crate::OdeError> {
        let n = sys.dim();
        let states = past.len().checked_div(n).unwrap_or(0);
        if n == 0 || past.len() % n != 0 || !(2..=MAX_ORDER + 1).contains(&states) {
            return Err(crate::solver::invalid(format!(
                "the history must hold 2 to {} states of dimension {n}; it has {} values",
                MAX_ORDER + 1,
                past.len()
            )));
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(crate::solver::invalid(format!(
                "history spacing h = {h} must be positive"
            )));
        }
        self.start(sys, t0, &past[..n], t_end)?;
        self.method_mut().load_history(past, h, states - 1);
        Ok(())
    }
}
