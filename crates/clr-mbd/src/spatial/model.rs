//! The compiled spatial model and its right-hand side: the Newton–Euler equations of the bodies
//! with Lagrange multipliers and Baumgarte stabilization, in the same form as the planar
//! [`Model`](crate::Model) (Nikravesh 1988, eqs. 11.20 and 13.22):
//!
//! ```text
//! [ M   Gᵀ ] [ v̇ ]   [ Q                          ]
//! [ G   0  ] [ λ ] = [ γ − 2α(Gv + Φ_t) − β²Φ      ]
//! ```
//!
//! with v = (ṙ, ω_body) per body, M = diag(m I, J) constant (J the inertia tensor at the centre
//! of mass in the body frame), Q = (Σf, Σm_body − ω × Jω) the applied forces with the
//! gyroscopic moment, and G the velocity Jacobian of the constraints. The first-order state is
//! y = (q, v, E_d, W_in, z): q = (r, p) per body with the quaternion p integrated as
//! ṗ = ½ p ⊗ (0, ω) ([`super::frame`]), then the dissipated energy, the input work and the
//! LuGre bristle vectors (3 per spherical joint with LuGre friction).
//!
//! The augmented equations are solved through the block-diagonal mass matrix (the range-space
//! method of [`crate::rangespace`]): x = M⁻¹Q, Y = M⁻¹Gᵀ, (GY)λ = Gx − b, v̇ = x − Yλ, with M⁻¹
//! constant per body.

use clr_contact::ContactMemory;
use clr_ode::linalg::DenseLu;
use nalgebra::{Matrix3, Vector3};

use super::constraint::{Prim, Rows};
use super::force::Force3;
use super::journal::{Journal, JournalReport};
use super::kin::Kinematics;
use super::shape_contact::{ShapeContact3, ShapeReport3};
use super::sphere::{Sphere, SphereReport};
use crate::timefn::TimeFn;

/// Rate k (1/s) of the norm-restoring term k(1 − ‖p‖²)p added to every quaternion rate: the
/// exact flow keeps ‖p‖ = 1, and the term makes that manifold attractive without changing the
/// motion (every use normalizes p). Measured on models/examples/heavy_top.toml (NDF, rtol 1e-8,
/// 2 s): largest |‖p‖ − 1| 3.2e-7, 7.8e-8, 1.7e-8, 2.3e-9 and 5.3e-9 for k = 0, 1, 10, 100 and
/// 1000 1/s, with 4962, 5023, 4972, 4914 and 5029 steps (1000 needs 45 Jacobians instead of
/// 11–15: the term's eigenvalue −2k starts to be stiff). 10 leaves explicit DOPRI5 steps up to
/// about 0.16 s stable and costs nothing measurable. The analytic Newton matrix leaves out the
/// term's derivative −2k ppᵀ (on ‖p‖ = 1): a backward error of 2ck, 2e-2 at c = 1e-3 s, which
/// simplified Newton absorbs.
pub(crate) const NORM_RATE: f64 = 10.0;

/// Mass properties of a spatial body.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Inertia3 {
    pub(crate) mass: f64,
    /// Inertia tensor at the centre of mass, body frame, kg·m².
    pub(crate) j: Matrix3<f64>,
    pub(crate) j_inv: Matrix3<f64>,
}

/// A joint or driver: its rows and the bodies its reaction is reported on.
#[derive(Debug, Clone)]
pub(crate) struct Owner {
    pub(crate) name: String,
    pub(crate) driver: bool,
    pub(crate) i: usize,
    pub(crate) j: usize,
    /// Rows [first, end).
    pub(crate) rows: (usize, usize),
}

/// A built spatial model: a clr-ode [`OdeSystem`] on y = (q, v, E_d, W_in, z) (module docs).
/// Build it with [`SpatialDesc::compile`](super::SpatialDesc::compile) and run it with
/// [`SpatialModel::simulate`].
pub struct SpatialModel {
    pub(crate) names: Vec<String>,
    pub(crate) bodies: Vec<Inertia3>,
    /// Which of (position, orientation, velocity, angular velocity) each body was given.
    pub(crate) fixed: Vec<[bool; 4]>,
    /// The initial state as given (before assembly).
    pub(crate) y_given: Vec<f64>,
    pub(crate) prims: Vec<Prim>,
    pub(crate) owners: Vec<Owner>,
    pub(crate) motions: Vec<TimeFn>,
    pub(crate) forces: Vec<(String, Force3)>,
    pub(crate) spheres: Vec<Sphere>,
    /// Revolute and cylindrical clearance joints.
    pub(crate) journals: Vec<Journal>,
    /// The journals' tracked contact groups (journal, group), after the balls in the contact
    /// probes and events.
    pub(crate) journal_points: Vec<(usize, usize)>,
    /// Shape contacts (`[[clearance]] type = "contact"`), tracked after the journals' groups.
    pub(crate) shape_contacts: Vec<ShapeContact3>,
    pub(crate) memory: ContactMemory,
    pub(crate) gravity: Vector3<f64>,
    pub(crate) alpha: f64,
    pub(crate) beta: f64,
    pub(crate) events_on: bool,
    /// What compiling decided, in words.
    pub(crate) notes: Vec<String>,
    /// Findings on the description's values (Young's moduli out of range), reported with the
    /// run's other plausibility warnings.
    pub(crate) input_warnings: Vec<crate::initial_data::Warning>,
    /// The points of the `[[measure]]` items, for the plausibility check of their lengths:
    /// (field, body index, point relative to the centre of mass in the body frame, m).
    pub(crate) measure_points: Vec<(String, usize, Vector3<f64>)>,
    pub(crate) m: usize,
    pub(crate) n_bristle: usize,
    /// Rate k (1/s) of the norm-restoring term k(1 − ‖p‖²)p added to ṗ.
    pub(crate) norm_rate: f64,
    pub(crate) ws: Workspace,
}

/// Storage of one evaluation, sized at compile time (no allocation in the right-hand side).
#[derive(Debug, Default)]
pub(crate) struct Workspace {
    pub(crate) kin: Kinematics,
    pub(crate) phi: Vec<f64>,
    /// G, row-major m × nv.
    pub(crate) g: Vec<f64>,
    pub(crate) phit: Vec<f64>,
    pub(crate) gamma: Vec<f64>,
    /// Q, then v̇.
    pub(crate) qf: Vec<f64>,
    /// Y = M⁻¹Gᵀ, row-major nv × m.
    pub(crate) y: Vec<f64>,
    pub(crate) w: DenseLu,
    pub(crate) lambda: Vec<f64>,
    pub(crate) reports: Vec<SphereReport>,
    pub(crate) journal_reports: Vec<JournalReport>,
    /// The state the impact tracker last asked gaps at ([`crate::impacts::ContactProbe`]), and
    /// each journal's group gaps there (`None`: not evaluated yet).
    pub(crate) gap_state: Vec<f64>,
    pub(crate) gap_cache: Vec<Option<[(f64, f64); clr_contact::journal::GROUPS]>>,
    pub(crate) shape_reports: Vec<ShapeReport3>,
    pub(crate) zdot: Vec<f64>,
    pub(crate) p_diss: f64,
    pub(crate) p_in: f64,
    pub(crate) solve_ok: bool,
    /// The reduced Newton systems ([`super::newton`] fills them).
    pub(crate) newton: super::newton_ws::SpatialNewton,
}

impl SpatialModel {
    /// Number of bodies.
    pub fn n_bodies(&self) -> usize {
        self.bodies.len()
    }
    /// Body names in state order (body k owns q[7k..7k+7] and v[6k..6k+6]).
    pub fn body_names(&self) -> &[String] {
        &self.names
    }
    /// Number of constraint equations.
    pub fn n_constraints(&self) -> usize {
        self.m
    }
    /// Number of position coordinates (7 per body).
    pub fn n_q(&self) -> usize {
        7 * self.bodies.len()
    }
    /// Number of velocity coordinates (6 per body).
    pub fn n_v(&self) -> usize {
        6 * self.bodies.len()
    }
    /// Mass (kg) and inertia tensor at the centre of mass in the body frame (kg·m²) of body k.
    pub fn body_inertia(&self, k: usize) -> (f64, Matrix3<f64>) {
        (self.bodies[k].mass, self.bodies[k].j)
    }
    /// Set the Baumgarte coefficients α, β (1/s, ≥ 0, finite).
    ///
    /// # Errors
    /// [`crate::MbdError::InvalidParameter`] for negative or non-finite values.
    pub fn set_baumgarte(&mut self, alpha: f64, beta: f64) -> Result<(), crate::MbdError> {
        crate::system::check_baumgarte(alpha, beta)?;
        self.alpha = alpha;
        self.beta = beta;
        Ok(())
    }

    pub(crate) fn bristle_offset(&self) -> usize {
        self.n_q() + self.n_v() + 2
    }

    /// Evaluate kinematics, forces and constraint rows at (t, y); the accelerations are then
    /// solved by [`SpatialModel::solve`].
    pub(crate) fn evaluate(&mut self, t: f64, y: &[f64]) {
        let nb = self.bodies.len();
        let nv = 6 * nb;
        let ws = &mut self.ws;
        ws.kin.update(nb, y);
        ws.qf.fill(0.0);
        ws.p_diss = 0.0;
        ws.p_in = 0.0;
        for (k, b) in self.bodies.iter().enumerate() {
            let wb = Vector3::new(
                y[7 * nb + 6 * k + 3],
                y[7 * nb + 6 * k + 4],
                y[7 * nb + 6 * k + 5],
            );
            let gyro = wb.cross(&(b.j * wb));
            for c in 0..3 {
                ws.qf[6 * k + c] += b.mass * self.gravity[c];
                ws.qf[6 * k + 3 + c] -= gyro[c];
            }
        }
        for (_, f) in &self.forces {
            let s = f.apply(&ws.kin, t, &mut ws.qf);
            ws.p_diss += s.p_diss;
            ws.p_in += s.p_in;
        }
        let zoff = 7 * nb + nv + 2;
        for (s, sp) in self.spheres.iter().enumerate() {
            let (z, zd) = match sp.bristle {
                Some(o) => (
                    Vector3::new(y[zoff + o], y[zoff + o + 1], y[zoff + o + 2]),
                    o,
                ),
                None => (Vector3::zeros(), usize::MAX),
            };
            let mut zdot = Vector3::zeros();
            ws.reports[s] = sp.apply(&ws.kin, &mut self.memory, z, &mut zdot, Some(&mut ws.qf));
            ws.p_diss += ws.reports[s].dissipated;
            if zd != usize::MAX {
                ws.zdot[zd..zd + 3].copy_from_slice(zdot.as_slice());
            }
        }
        for (k, jn) in self.journals.iter().enumerate() {
            ws.journal_reports[k] = jn.apply(&ws.kin, &mut self.memory, Some(&mut ws.qf));
            ws.p_diss += ws.journal_reports[k].dissipated;
        }
        for (k, c) in self.shape_contacts.iter().enumerate() {
            ws.shape_reports[k] = c.apply(&ws.kin, &mut self.memory, Some(&mut ws.qf));
            ws.p_diss += ws.shape_reports[k].dissipated;
        }
        ws.g.fill(0.0);
        let mut rows = Rows {
            phi: &mut ws.phi,
            g: &mut ws.g,
            phit: &mut ws.phit,
            gamma: &mut ws.gamma,
            nv,
        };
        for p in &self.prims {
            p.eval(&ws.kin, t, &self.motions, &mut rows);
        }
    }

    /// Solve the augmented equations for v̇ (in `ws.qf`) and λ, with the velocities v.
    pub(crate) fn solve(&mut self, v: &[f64]) {
        let nb = self.bodies.len();
        let nv = 6 * nb;
        let m = self.m;
        let ws = &mut self.ws;
        // x = M⁻¹Q
        for (k, b) in self.bodies.iter().enumerate() {
            apply_minv(b, &mut ws.qf[6 * k..6 * k + 6]);
        }
        if m == 0 {
            ws.solve_ok = true;
            return;
        }
        // Y = M⁻¹Gᵀ (row-major nv × m), W = G Y
        for r in 0..m {
            for k in 0..nb {
                let mut col = [0.0; 6];
                col.copy_from_slice(&ws.g[r * nv + 6 * k..r * nv + 6 * k + 6]);
                apply_minv(&self.bodies[k], &mut col);
                for (c, v) in col.iter().enumerate() {
                    ws.y[(6 * k + c) * m + r] = *v;
                }
            }
        }
        let wm = ws.w.matrix_mut();
        for r in 0..m {
            for s in 0..m {
                let mut acc = 0.0;
                for c in 0..nv {
                    acc += ws.g[r * nv + c] * ws.y[c * m + s];
                }
                wm[s * m + r] = acc;
            }
        }
        // right-hand side G x − b, b = γ − 2α(Gv + Φ_t) − β²Φ
        for r in 0..m {
            let row = &ws.g[r * nv..(r + 1) * nv];
            let gv: f64 = row.iter().zip(v).map(|(a, b)| a * b).sum();
            let gx: f64 = row.iter().zip(&ws.qf).map(|(a, b)| a * b).sum();
            let b = ws.gamma[r]
                - 2.0 * self.alpha * (gv + ws.phit[r])
                - self.beta * self.beta * ws.phi[r];
            ws.lambda[r] = gx - b;
        }
        ws.solve_ok = ws.w.factor().is_ok();
        if !ws.solve_ok {
            ws.qf.fill(f64::NAN);
            return;
        }
        ws.w.solve(&mut ws.lambda);
        for c in 0..nv {
            let mut acc = 0.0;
            for r in 0..m {
                acc += ws.y[c * m + r] * ws.lambda[r];
            }
            ws.qf[c] -= acc;
        }
    }

    /// Power of the drivers' reactions at the current velocities, W: −Σ λ_r (G v)_r over the
    /// driver rows (as the planar [`Model`](crate::Model)).
    pub(crate) fn driver_power(&self, v: &[f64]) -> f64 {
        let nv = v.len();
        let mut p = 0.0;
        for o in self.owners.iter().filter(|o| o.driver) {
            for r in o.rows.0..o.rows.1 {
                let gv: f64 = self.ws.g[r * nv..(r + 1) * nv]
                    .iter()
                    .zip(v)
                    .map(|(a, b)| a * b)
                    .sum();
                p -= self.ws.lambda[r] * gv;
            }
        }
        p
    }
}

/// v ← M⁻¹ v for one body's 6 entries.
#[inline]
fn apply_minv(b: &Inertia3, v: &mut [f64]) {
    v[..3].iter_mut().for_each(|c| *c /= b.mass);
    let w = b.j_inv * Vector3::new(v[3], v[4], v[5]);
    v[3..6].copy_from_slice(w.as_slice());
}
