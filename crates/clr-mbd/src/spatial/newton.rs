//! The reduced Newton systems of the spatial model: what NDF solves at every iteration,
//! (I − cJ)Δy = r with J = ∂f/∂y, in a system of size 6n_b + m instead of 13n_b + 2 (the
//! planar engine's reduction, [`crate::newton`], carried to bodies with quaternions).
//!
//! The first-order system is q̇ = T(q)v, v̇ = a(q, v): T the identity for r and
//! ṗ = ½ p ⊗ (0, ω) = ½L(p)ω for the quaternion. Position increments are expressed in the 6
//! velocity coordinates of each body, δx = (δr, δθ) with δθ the body-frame rotation
//! (p + Δp = p ⊗ (1, ½δθ) + p η): the forces and constraints depend on p only through the
//! rotation, so a is blind to the norm direction η and a_p = a_θ · 2Lᵀ(p)/‖p‖²; the 6
//! coordinates make Φ_x = G (no separate Φ_q of 4 quaternion columns and no norm row), and
//! the reduced matrix has exactly the planar form. The quaternion rows are then solved in
//! closed form: with s = c/2 and R(ω)y = y ⊗ (0, ω) (skew, R² = −‖ω‖²),
//! (I − sR)⁻¹ = (I + sR)/(1 + s²‖ω‖²), so
//!
//! ```text
//! Δp = (I + sR)(r_p + ½cL(p)Δω)/(1 + s²‖ω‖²),     δθ = ρ_θ + c D Δω,
//! ρ_θ = 2Lᵀ(p)(I + sR) r_p / (‖p‖²(1 + s²‖ω‖²)),   D = (I − s[ω]×)/(1 + s²‖ω‖²)
//! ```
//!
//! (δθ = 2LᵀΔp/‖p‖², with LᵀRL = ‖p‖²[·]×ω and LᵀRp = ‖p‖²ω), and for the centre of mass
//! δr = r_r + cΔṙ (D = I, ρ = r_r). The term s[ω]× is the derivative of the quaternion rate
//! with respect to p: kept, since spinning bodies (the heavy top: cω ≈ 0.1 at its steps) would
//! otherwise lose Newton's rate. Linearizing the augmented equations M a + Gᵀλ = Q,
//! G a = b as the planar module does gives, with Q_x, b_x, b_v the element derivatives of
//! [`super::jacobian`] and D the block-diagonal of the D's (identity on translations):
//!
//! ```text
//! [ M − c Q_v − c² Q_x D          Gᵀ ] [ Δv ]   [ M r_v + c Q_x ρ ]
//! [ G − c b_v − c² b_x D          0  ] [ cμ ] = [ G r_v + c b_x ρ ]
//! ```
//!
//! with b = γ − 2α(Gv + Φ_t) − β²Φ, b_v = γ_v − 2αG, b_x = γ_x − 2α((Gv)_x + Φ_t,x) − β²G
//! − (Ga)_x (the last from differentiating G a = b). Unlike the planar matrix, ∂γ/∂x is
//! included (it comes free with the dual numbers). Left out: the geometric stiffness (Gᵀλ)_x
//! (it scales with the multipliers and enters with c² against M; simplified Newton pays it in
//! iterations, not accuracy). E_d and W_in are passive quadratures: ΔE = r_E, ΔW = r_W.
//! Models with LuGre bristle states use the solver's finite-difference Newton matrix.

use nalgebra::{Matrix3, Vector3};

use super::jacobian::{QBlocks, RowBlocks};
use super::model::SpatialModel;
use super::newton_ws::SpatialNewton;

/// L(p)ᵀ y: the body-frame vector of a quaternion increment y (L(p)x = p ⊗ (0, x)).
fn l_t(p: &[f64; 4], y: &[f64; 4]) -> Vector3<f64> {
    Vector3::new(
        -p[1] * y[0] + p[0] * y[1] + p[3] * y[2] - p[2] * y[3],
        -p[2] * y[0] - p[3] * y[1] + p[0] * y[2] + p[1] * y[3],
        -p[3] * y[0] + p[2] * y[1] - p[1] * y[2] + p[0] * y[3],
    )
}

/// (I + sR(ω)) y with R(ω)y = y ⊗ (0, ω).
fn i_plus_sr(s: f64, w: &Vector3<f64>, y: &[f64; 4]) -> [f64; 4] {
    let yv = Vector3::new(y[1], y[2], y[3]);
    let v = y[0] * w + yv.cross(w);
    [
        y[0] - s * yv.dot(w),
        y[1] + s * v.x,
        y[2] + s * v.y,
        y[3] + s * v.z,
    ]
}

impl SpatialNewton {
    fn size(&mut self, nb: usize, m: usize) {
        let nv = 6 * nb;
        for v in [&mut self.q, &mut self.acc, &mut self.rho] {
            v.resize(nv, 0.0);
        }
        for v in [
            &mut self.qx,
            &mut self.qv,
            &mut self.qxd,
            &mut self.gtl_x,
            &mut self.qx_eff,
        ] {
            v.resize(nv * nv, 0.0);
        }
        for v in [
            &mut self.g,
            &mut self.gv_x,
            &mut self.ga_x,
            &mut self.phit_x,
            &mut self.gamma_x,
            &mut self.gamma_v,
            &mut self.bx,
            &mut self.bv,
            &mut self.bxd,
        ] {
            v.resize(m * nv, 0.0);
        }
        self.quat.resize(nb, [0.0; 4]);
        self.omega.resize(nb, Vector3::zeros());
        self.rhs.resize(nv + m, 0.0);
        self.lu.resize(nv + m);
    }

    /// D of body k for s = c/2.
    fn d(&self, k: usize, s: f64) -> Matrix3<f64> {
        let w = self.omega[k];
        (Matrix3::identity() - s * w.cross_matrix()) / (1.0 + s * s * w.norm_squared())
    }
}

/// out = a · D (columns of the rotations of each body multiplied by D_k), a row-major
/// `rows` × nv.
fn times_d(nw: &SpatialNewton, a: &[f64], out: &mut [f64], rows: usize, s: f64) {
    let nv = 6 * nw.omega.len();
    out.copy_from_slice(&a[..rows * nv]);
    for k in 0..nw.omega.len() {
        let d = nw.d(k, s);
        for r in 0..rows {
            let o = r * nv + 6 * k + 3;
            let row = Vector3::new(a[o], a[o + 1], a[o + 2]);
            let x = d.transpose() * row;
            out[o..o + 3].copy_from_slice(x.as_slice());
        }
    }
}

impl SpatialModel {
    /// Evaluate Q, a, G and every element derivative at (t, y) into `nw`; false when the
    /// augmented solve failed or a derivative is not finite.
    pub(crate) fn newton_blocks(&mut self, nw: &mut SpatialNewton, t: f64, y: &[f64]) -> bool {
        let (nb, m) = (self.bodies.len(), self.m);
        let (nq, nv) = (7 * nb, 6 * nb);
        nw.size(nb, m);
        self.evaluate(t, y);
        nw.q.copy_from_slice(&self.ws.qf);
        nw.g.copy_from_slice(&self.ws.g);
        self.solve(&y[nq..nq + nv]);
        nw.acc.copy_from_slice(&self.ws.qf);
        for k in 0..nb {
            let p = &y[7 * k + 3..7 * k + 7];
            nw.quat[k] = [p[0], p[1], p[2], p[3]];
            nw.omega[k] = Vector3::new(y[nq + 6 * k + 3], y[nq + 6 * k + 4], y[nq + 6 * k + 5]);
        }
        self.element_blocks(nw, t);
        for ((e, q), g) in nw.qx_eff.iter_mut().zip(&nw.qx).zip(&nw.gtl_x) {
            *e = q - g;
        }
        let (al, be) = (self.alpha, self.beta);
        for k in 0..m * nv {
            nw.bv[k] = nw.gamma_v[k] - 2.0 * al * nw.g[k];
            nw.bx[k] = nw.gamma_x[k]
                - 2.0 * al * (nw.gv_x[k] + nw.phit_x[k])
                - be * be * nw.g[k]
                - nw.ga_x[k];
        }
        let finite = [&nw.qx, &nw.qv, &nw.bx, &nw.bv]
            .iter()
            .all(|l| l.iter().all(|e| e.is_finite()));
        self.ws.solve_ok && finite
    }

    /// The element derivatives (Q_x, Q_v and the constraint rows' gradients) into `nw`.
    fn element_blocks(&mut self, nw: &mut SpatialNewton, t: f64) {
        let nv = 6 * self.bodies.len();
        let kin = &self.ws.kin;
        nw.qx.fill(0.0);
        nw.qv.fill(0.0);
        let mut q = QBlocks {
            qx: &mut nw.qx,
            qv: &mut nw.qv,
            nv,
        };
        for (k, b) in self.bodies.iter().enumerate() {
            q.gyroscopic(kin, k, &b.j);
        }
        for (_, f) in &self.forces {
            f.jacobian(kin, t, &mut q);
        }
        for s in &self.spheres {
            s.jacobian(kin, &mut self.memory, &mut q);
        }
        for jn in &self.journals {
            jn.jacobian(kin, &mut self.memory, &mut q);
        }
        let mut rows = RowBlocks {
            gv_x: &mut nw.gv_x,
            ga_x: &mut nw.ga_x,
            phit_x: &mut nw.phit_x,
            gamma_x: &mut nw.gamma_x,
            gamma_v: &mut nw.gamma_v,
            gtl_x: &mut nw.gtl_x,
            nv,
        };
        for v in [
            &mut rows.gv_x,
            &mut rows.ga_x,
            &mut rows.phit_x,
            &mut rows.gamma_x,
            &mut rows.gamma_v,
            &mut rows.gtl_x,
        ] {
            v.fill(0.0);
        }
        for p in &self.prims {
            p.jacobian(kin, t, &self.motions, (&nw.acc, &self.ws.lambda), &mut rows);
        }
    }

    /// [`clr_ode::OdeSystem::newton_jacobian`]: the blocks at (t, y).
    pub(crate) fn reduced_jacobian(&mut self, t: f64, y: &[f64]) -> bool {
        let mut nw = std::mem::take(&mut self.ws.newton);
        let ok = self.newton_blocks(&mut nw, t, y);
        self.ws.newton = nw;
        ok
    }

    /// [`clr_ode::OdeSystem::newton_factor`]: form and factor
    /// [M − cQ_v − c²Q_x D, Gᵀ; G − c b_v − c² b_x D, 0] (column-major).
    pub(crate) fn reduced_factor(&mut self, c: f64) -> bool {
        let (nv, m) = (self.n_v(), self.m);
        let nm = nv + m;
        let nw = &mut self.ws.newton;
        nw.c = c;
        let (s, c2) = (0.5 * c, c * c);
        let mut qxd = std::mem::take(&mut nw.qxd);
        let mut bxd = std::mem::take(&mut nw.bxd);
        times_d(nw, &nw.qx_eff, &mut qxd, nv, s);
        times_d(nw, &nw.bx, &mut bxd, m, s);
        let a = nw.lu.matrix_mut();
        a.fill(0.0);
        for r in 0..nv {
            for col in 0..nv {
                let k = r * nv + col;
                a[r + col * nm] = -c * nw.qv[k] - c2 * qxd[k];
            }
        }
        for (k, b) in self.bodies.iter().enumerate() {
            for d in 0..3 {
                let t = 6 * k + d;
                a[t + t * nm] += b.mass;
                for e in 0..3 {
                    let (r, col) = (6 * k + 3 + d, 6 * k + 3 + e);
                    a[r + col * nm] += b.j[(d, e)];
                }
            }
        }
        for r in 0..m {
            for col in 0..nv {
                let k = r * nv + col;
                a[nv + r + col * nm] = nw.g[k] - c * nw.bv[k] - c2 * bxd[k];
                a[col + (nv + r) * nm] = nw.g[k];
            }
        }
        nw.qxd = qxd;
        nw.bxd = bxd;
        nw.lu.factor().is_ok()
    }

    /// [`clr_ode::OdeSystem::newton_solve`]: Δy from r in place (module docs).
    pub(crate) fn reduced_solve(&mut self, b: &mut [f64]) {
        let (nb, m) = (self.bodies.len(), self.m);
        let (nq, nv) = (7 * nb, 6 * nb);
        let nw = &mut self.ws.newton;
        let (c, s) = (nw.c, 0.5 * nw.c);
        for k in 0..nb {
            let (p, w) = (&nw.quat[k], nw.omega[k]);
            let den = (p.iter().map(|x| x * x).sum::<f64>()) * (1.0 + s * s * w.norm_squared());
            let rp = [b[7 * k + 3], b[7 * k + 4], b[7 * k + 5], b[7 * k + 6]];
            let th = 2.0 * l_t(p, &i_plus_sr(s, &w, &rp)) / den;
            nw.rho[6 * k..6 * k + 3].copy_from_slice(&b[7 * k..7 * k + 3]);
            nw.rho[6 * k + 3..6 * k + 6].copy_from_slice(th.as_slice());
        }
        let rv = &b[nq..nq + nv];
        nw.rhs.fill(0.0);
        for (k, bd) in self.bodies.iter().enumerate() {
            let w = bd.j * Vector3::new(rv[6 * k + 3], rv[6 * k + 4], rv[6 * k + 5]);
            for d in 0..3 {
                nw.rhs[6 * k + d] = bd.mass * rv[6 * k + d];
                nw.rhs[6 * k + 3 + d] = w[d];
            }
        }
        for r in 0..nv {
            let row = &nw.qx_eff[r * nv..(r + 1) * nv];
            nw.rhs[r] += c * row.iter().zip(&nw.rho).map(|(a, b)| a * b).sum::<f64>();
        }
        for r in 0..m {
            let (g, bx) = (&nw.g[r * nv..(r + 1) * nv], &nw.bx[r * nv..(r + 1) * nv]);
            nw.rhs[nv + r] = g.iter().zip(rv).map(|(a, b)| a * b).sum::<f64>()
                + c * bx.iter().zip(&nw.rho).map(|(a, b)| a * b).sum::<f64>();
        }
        nw.lu.solve(&mut nw.rhs);
        b[nq..nq + nv].copy_from_slice(&nw.rhs[..nv]);
        for k in 0..nb {
            let (p, w) = (&nw.quat[k], nw.omega[k]);
            for d in 0..3 {
                b[7 * k + d] += c * nw.rhs[6 * k + d];
            }
            let dw = Vector3::new(nw.rhs[6 * k + 3], nw.rhs[6 * k + 4], nw.rhs[6 * k + 5]);
            let mut lp = [0.0; 4];
            // ½ L(p) Δω
            super::frame::quaternion_rate(p, &dw, &mut lp);
            let y = [0, 1, 2, 3].map(|i| b[7 * k + 3 + i] + c * lp[i]);
            let out = i_plus_sr(s, &w, &y);
            let den = 1.0 + s * s * w.norm_squared();
            for i in 0..4 {
                b[7 * k + 3 + i] = out[i] / den;
            }
        }
    }
}

/// The element derivatives of a spatial model at one state, as the reduced Newton matrix uses
/// them (dense row-major; nv = 6 per body, positions varied as (δr, δθ_body), velocities
/// (ṙ, ω_body); [`SpatialModel::linearization`]). For checks against difference quotients.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialLinearization {
    /// Number of velocity coordinates nv and constraint rows m.
    pub nv: usize,
    /// Constraint rows.
    pub m: usize,
    /// Generalized forces Q (N, N·m body frame), nv.
    pub q: Vec<f64>,
    /// Accelerations a from the augmented equations (m/s², rad/s²), nv.
    pub acc: Vec<f64>,
    /// Velocity Jacobian G (m × nv), also ∂Φ/∂x.
    pub g: Vec<f64>,
    /// b = γ − 2α(Gv + Φ_t) − β²Φ, the right-hand side of G a = b (m/s²; evaluated as G a).
    pub b: Vec<f64>,
    /// ∂Q/∂x and ∂Q/∂v (nv × nv).
    pub qx: Vec<f64>,
    /// ∂Q/∂v (nv × nv).
    pub qv: Vec<f64>,
    /// ∂b/∂x at fixed v (m × nv; the (Ga)_x term of the Newton matrix not included).
    pub bx: Vec<f64>,
    /// ∂b/∂v (m × nv).
    pub bv: Vec<f64>,
    /// ∂(G a)/∂x at the fixed accelerations `acc` (m × nv).
    pub ga_x: Vec<f64>,
}

impl SpatialModel {
    /// The derivatives of the model's forces and constraint rows at (t, y) (allocates; the
    /// integrator keeps its own workspace).
    pub fn linearization(&mut self, t: f64, y: &[f64]) -> SpatialLinearization {
        let mut nw = SpatialNewton::default();
        self.newton_blocks(&mut nw, t, y);
        let nv = self.n_v();
        // b = G a: the second row of the augmented equations, satisfied by the solve
        let b = (0..self.m)
            .map(|r| {
                let g = &nw.g[r * nv..(r + 1) * nv];
                g.iter().zip(&nw.acc).map(|(a, b)| a * b).sum()
            })
            .collect();
        let bx = nw.bx.iter().zip(&nw.ga_x).map(|(b, g)| b + g).collect();
        SpatialLinearization {
            nv,
            m: self.m,
            q: nw.q,
            acc: nw.acc,
            g: nw.g,
            b,
            qx: nw.qx,
            qv: nw.qv,
            bx,
            bv: nw.bv,
            ga_x: nw.ga_x,
        }
    }
}

impl SpatialModel {
    /// Commit the contact memory of the spherical clearance joints at the state y (the impact
    /// velocities δ̇⁻ the laws use), as the integrator does after an accepted step: then the
    /// forces at nearby states use the same δ̇⁻, and their derivatives agree with difference
    /// quotients.
    pub fn commit_contact_memory(&mut self, y: &[f64]) {
        self.commit_contacts(y);
    }
}
