//! The built model: constraint equations, forces, the augmented equations of motion and their
//! first-order form for clr-ode.
//!
//! Coordinates q = (x_k, y_k, θ_k) for every rigid body k (centre of mass and angle). The
//! equations of motion with Lagrange multipliers and Baumgarte stabilization (J. Baumgarte,
//! Comput. Methods Appl. Mech. Eng. 1 (1972) 1–16; P.E. Nikravesh, *Computer-Aided Analysis of
//! Mechanical Systems*, Prentice Hall 1988, eqs. 6.13 and 13.22):
//!
//! ```text
//! [ M   Φ_qᵀ ] [ q̈ ]   [ Q                 ]
//! [ Φ_q  0   ] [ λ  ] = [ γ − 2αΦ̇ − β²Φ     ]
//! ```
//!
//! with γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt. The first-order system is y = (q, q̇, E_d, W_in, z),
//! ẏ = (q̇, q̈, P_diss, P_in, ż): after q and q̇ two energy quadratures, the energy dissipated
//! E_d and the work done on the system W_in (see [`Model`]), then the LuGre bristle states.
//!
//! Sign of the driver power: the equations read M q̈ = Q − Φ_qᵀλ, so the generalized
//! constraint force is −Φ_qᵀλ and its power is −λᵀΦ_q q̇. On the constraint manifold
//! Φ̇ = Φ_q q̇ + Φ_t = 0 this is λᵀΦ_t: zero for joints (Φ_t = 0) and, for a driver
//! θ_j − θ_i − f(t) = 0 (Φ_t = −ḟ), −λḟ = M_j ḟ with M_j = −λ the driver's reaction moment on
//! body j (reaction forces −Φ_qᵀλ: Nikravesh 1988, ch. 6; E.J. Haug, *Computer Aided Kinematics
//! and Dynamics of Mechanical Systems*, Allyn and Bacon 1989). The work W_in integrates
//! −λ_r (Φ_q q̇)_r over the rows of the drivers only: the power of their reaction forces at the
//! velocities the bodies actually have, so the work of joint reactions through
//! Baumgarte-corrected violations (−λ_r Φ̇_r, zero on the manifold) is left in the balance
//! error rather than hidden in W_in.

use clr_contact::ContactMemory;

use crate::timefn::TimeFn;

use crate::beam_face::{GuideBeam, GuideRef};
use crate::clearance::Clearance;
pub use crate::contact_report::ContactReport;
use crate::flexible::FlexBeam;
use crate::floating::FloatingBody;
use clr_ode::{Direction, OdeSystem};
use nalgebra::Vector2;

use crate::error::MbdError;
use crate::runtime::{
    add_gen, body_state, frame_rates, perp, put, rot, Con, ConKind, ForceEl, Frame, RigidBody,
    GROUND_ID,
};

/// Default Baumgarte coefficient α (1/s) multiplying 2Φ̇ (Flores et al., *Kinematics and
/// Dynamics of Multibody Systems with Imperfect Joints*, Springer 2008, §2.6, use α = β = 5).
pub const DEFAULT_BAUMGARTE_ALPHA: f64 = 5.0;
/// Default Baumgarte coefficient β (1/s) with β² multiplying Φ (see
/// [`DEFAULT_BAUMGARTE_ALPHA`]).
pub const DEFAULT_BAUMGARTE_BETA: f64 = 5.0;

/// Check Baumgarte coefficients α, β (1/s): finite and not negative.
pub(crate) fn check_baumgarte(alpha: f64, beta: f64) -> Result<(), MbdError> {
    for (what, v) in [("Baumgarte α (1/s)", alpha), ("Baumgarte β (1/s)", beta)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(MbdError::InvalidParameter {
                item: "model".into(),
                what,
                value: v,
                requirement: "must be finite and not negative",
            });
        }
    }
    Ok(())
}

/// Energies at one state, J.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energies {
    /// Kinetic energy ½ q̇ᵀ M q̇.
    pub kinetic: f64,
    /// Gravitational potential −Σ m g·r (zero at the origin).
    pub potential: f64,
    /// Elastic energy of springs and contact elastic parts ∫F_e dδ.
    pub elastic: f64,
}

impl Energies {
    /// Kinetic + potential + elastic.
    pub fn total(&self) -> f64 {
        self.kinetic + self.potential + self.elastic
    }
}

/// A built multibody model and its solver workspace. It is a clr-ode [`OdeSystem`] on
/// y = (q, q̇, E_d, W_in, z) of dimension 2·[`Model::n_coordinates`] + 2 +
/// [`Model::n_bristle_states`]; use [`Model::initial_state`] for a consistent start, or
/// [`Model::simulate`](crate::Model::simulate) for the full driver. After q and q̇ the state
/// carries the dissipated energy E_d (J; y[2n]), the input work W_in (J; y[2n + 1]: the work done
/// on the system by drivers and applied loads since t0) and, with LuGre friction in clearance
/// joints, one bristle deflection z (m, starting at 0) per LuGre contact point, element by
/// element in definition order (1 per revolute, 4 per translational clearance joint; see
/// [`OdeSystem::dim`]).
pub struct Model {
    pub(crate) body_names: Vec<String>,
    pub(crate) bodies: Vec<RigidBody>,
    /// Which coordinates (x, y, θ, v_x, v_y, ω) of each rigid body the user fixed; the others
    /// are solved by the assembly of initial conditions ([`Model::initial_state`]).
    pub(crate) fixed: Vec<[bool; 6]>,
    pub(crate) beams: Vec<FlexBeam>,
    /// Floating-frame flexible bodies (coordinates after the beams).
    pub(crate) floating: Vec<FloatingBody>,
    /// Nodes of beams and floating bodies recorded as output columns
    /// ([`Model::set_output_nodes`]).
    pub(crate) node_outputs: Vec<crate::initial_data::NodeOutput>,
    /// Attachment frames: rigid bodies first (index = body index), then beam nodes.
    pub(crate) frames: Vec<Frame>,
    pub(crate) points: Vec<(String, usize, Vector2<f64>)>,
    pub(crate) cons: Vec<Con>,
    pub(crate) motions: Vec<TimeFn>,
    pub(crate) forces: Vec<ForceEl>,
    pub(crate) clearances: Vec<Clearance>,
    /// Initial offsets of contact elements given in the description, by element name: the
    /// revolute journal centre from the bearing centre in the bearing body's frame, or the
    /// translational slider centre across the guide (y), m ([`crate::ideal`]).
    pub(crate) initial_offsets: std::collections::HashMap<String, Vector2<f64>>,
    /// What compiling the description computed or decided, in words (in every run's notes,
    /// after those of the initial conditions).
    pub(crate) notes: Vec<String>,
    /// The `[[measure]]` items, written after the run's own columns ([`crate::measure`]).
    pub(crate) measures: Vec<crate::measure::runtime::CompiledMeasure>,
    /// Findings of the plausibility checks of the description's values (materials, laws),
    /// reported by every run ([`crate::plausible`]).
    pub(crate) input_warnings: Vec<crate::initial_data::Warning>,
    /// The `[[input]]` cells the elements are bound to ([`Model::inputs`]).
    pub(crate) inputs: crate::input::InputBank,
    /// Inputs given as functions of time and the feedback measures
    /// ([`Model::set_input_function`]).
    pub(crate) feedback: crate::input::Feedback,
    pub(crate) gravity: Vector2<f64>,
    pub(crate) memory: ContactMemory,
    pub(crate) alpha: f64,
    pub(crate) beta: f64,
    pub(crate) events_on: bool,
    pub(crate) n: usize,
    pub(crate) m: usize,
    // workspace (sized in `assemble`, reused by every evaluation)
    /// Factorization of the augmented matrix G (dense or sparse, [`crate::LinearSolver`]).
    pub(crate) g: crate::linsys::Factorization,
    /// Range-space solve of the augmented equations (the default path, [`crate::rangespace`]).
    pub(crate) range_space: crate::rangespace::RangeSpace,
    pub(crate) phi: Vec<f64>,
    /// Φ_q, row-major m × n.
    pub(crate) phiq: Vec<f64>,
    pub(crate) phid: Vec<f64>,
    /// Φ_t (∂Φ/∂t) of the last constraint evaluation: −ḟ(t) on driver rows, 0 elsewhere.
    pub(crate) phit: Vec<f64>,
    pub(crate) gamma: Vec<f64>,
    pub(crate) qf: Vec<f64>,
    /// [q̈; λ] of the last evaluation.
    pub(crate) sol: Vec<f64>,
    pub(crate) contacts: Vec<ContactReport>,
    /// Bounding-circle tests of the shape contact pairs (refreshed by each evaluation).
    pub(crate) broad: crate::broad_phase::BroadPhase,
    pub(crate) solve_ok: bool,
    /// Power dissipated by dampers, contact damping and friction at the last evaluation, W.
    pub(crate) p_diss: f64,
    /// Power of the applied loads (forces, torques, actuator forces, nodal loads, bushings and
    /// custom loads) at the last evaluation of the forces, W; the drivers' power comes from the
    /// multipliers ([`Model::driver_power`]).
    pub(crate) p_loads: f64,
    /// LuGre bristle states of the clearance joints (loaded from y by `rhs`).
    pub(crate) bristles: crate::lugre::state::Bristles,
}

impl Model {
    /// Number of coordinates n = 3 × (number of rigid bodies).
    pub fn n_coordinates(&self) -> usize {
        self.n
    }

    /// Number of constraint equations m (joints and drivers).
    pub fn n_constraints(&self) -> usize {
        self.m
    }

    /// Body names in coordinate order (body k owns q[3k..3k+3]).
    pub fn body_names(&self) -> &[String] {
        &self.body_names
    }

    /// The `[[input]]`s of the description this model was compiled from: set a cell to change
    /// what the elements bound to it see from the next evaluation on ([`crate::input`]).
    pub fn inputs(&self) -> &crate::input::InputBank {
        &self.inputs
    }

    /// Index of a body by name (`None` for unknown names and for the ground).
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.body_names.iter().position(|b| b == name)
    }

    /// Mass (kg) and centroidal inertia (kg·m²) of body k.
    pub fn body_inertia(&self, k: usize) -> (f64, f64) {
        (self.bodies[k].mass, self.bodies[k].inertia)
    }

    /// Set the Baumgarte coefficients α, β (1/s, ≥ 0; defaults [`DEFAULT_BAUMGARTE_ALPHA`],
    /// [`DEFAULT_BAUMGARTE_BETA`]). α = β = 0 integrates the plain index-1 form.
    ///
    /// # Errors
    /// [`MbdError::InvalidParameter`] for negative or non-finite values.
    pub fn set_baumgarte(&mut self, alpha: f64, beta: f64) -> Result<(), MbdError> {
        check_baumgarte(alpha, beta)?;
        self.alpha = alpha;
        self.beta = beta;
        Ok(())
    }

    /// Choose dense or sparse factorizations of the augmented matrix (default
    /// [`crate::LinearSolver::Auto`]: sparse from n + m ≥ [`crate::SPARSE_FROM`]; the Newton
    /// matrix follows the same setting through [`crate::newton::NewtonWs::new`]).
    pub fn set_linear_solver(&mut self, s: crate::LinearSolver) {
        self.g.sparse = s.is_sparse(self.n + self.m);
    }

    /// Whether the augmented matrix is factored sparse.
    pub fn linear_solver_is_sparse(&self) -> bool {
        self.g.sparse
    }

    /// Locate contact onsets as terminal events (default on): see
    /// [`Model::simulate`](crate::Model::simulate).
    pub fn set_contact_events(&mut self, on: bool) {
        self.events_on = on;
    }

    /// Initial state as given to the builder (not yet consistent): y = (q, q̇, E_d, W_in, z)
    /// with the dissipated energy E_d = 0, the input work W_in = 0 and undeflected LuGre
    /// bristles z = 0.
    pub fn given_state(&self) -> Vec<f64> {
        let n = self.n;
        let mut y = vec![0.0; self.dim()];
        for (k, b) in self.bodies.iter().enumerate() {
            y[3 * k] = b.position[0];
            y[3 * k + 1] = b.position[1];
            y[3 * k + 2] = b.angle;
            y[n + 3 * k] = b.velocity[0];
            y[n + 3 * k + 1] = b.velocity[1];
            y[n + 3 * k + 2] = b.angular_velocity;
        }
        for f in &self.floating {
            y[f.offset..f.offset + 3].copy_from_slice(&f.pose);
            y[n + f.offset..n + f.offset + 3].copy_from_slice(&f.velocity);
            for &(node, col) in &f.ties {
                let (p, v) = f.node_frame(node, &y[..n], &y[n..2 * n]);
                y[col..col + 3].copy_from_slice(&p);
                y[n + col..n + col + 3].copy_from_slice(&v);
            }
        }
        y
    }

    /// Evaluate Φ, Φ_q, Φ̇ and γ at (t, q, q̇) into the workspace.
    pub(crate) fn eval_constraints(&mut self, t: f64, q: &[f64], qd: &[f64]) {
        let n = self.n;
        self.phiq.fill(0.0);
        for c in &self.cons {
            let r = c.row;
            match c.kind {
                ConKind::Coincide { i, si, j, sj } => {
                    let bi = body_state(&self.frames, i, q, qd);
                    let bj = body_state(&self.frames, j, q, qd);
                    let ai = rot(bi.angle, si);
                    let aj = rot(bj.angle, sj);
                    let phi = bi.position + ai - bj.position - aj;
                    let phid = bi.velocity + bi.angular_velocity * perp(ai)
                        - bj.velocity
                        - bj.angular_velocity * perp(aj);
                    let g = bi.angular_velocity.powi(2) * ai - bj.angular_velocity.powi(2) * aj;
                    for d in 0..2 {
                        self.phi[r + d] = phi[d];
                        self.phid[r + d] = phid[d];
                        self.gamma[r + d] = g[d];
                    }
                    let (pi, pj) = (perp(ai), perp(aj));
                    put(&self.frames, &mut self.phiq, n, r, i, [1.0, 0.0, pi.x]);
                    put(&self.frames, &mut self.phiq, n, r + 1, i, [0.0, 1.0, pi.y]);
                    put(&self.frames, &mut self.phiq, n, r, j, [-1.0, 0.0, -pj.x]);
                    put(
                        &self.frames,
                        &mut self.phiq,
                        n,
                        r + 1,
                        j,
                        [0.0, -1.0, -pj.y],
                    );
                }
                ConKind::FloatNode { f, node, col, .. } => {
                    let rows = r..r + 3;
                    self.floating[f].tie(
                        node,
                        col,
                        q,
                        qd,
                        [
                            &mut self.phi[rows.clone()],
                            &mut self.phid[rows.clone()],
                            &mut self.gamma[rows],
                        ],
                        &mut self.phiq[r * n..(r + 3) * n],
                    );
                }
                ConKind::Angle {
                    i,
                    j,
                    offset,
                    motion,
                } => {
                    let bi = body_state(&self.frames, i, q, qd);
                    let bj = body_state(&self.frames, j, q, qd);
                    let f = match motion {
                        Some(k) => self.motions[k].eval(t),
                        None => [offset, 0.0, 0.0],
                    };
                    self.phi[r] = bj.angle - bi.angle - f[0];
                    self.phid[r] = bj.angular_velocity - bi.angular_velocity - f[1];
                    self.phit[r] = -f[1];
                    self.gamma[r] = f[2];
                    put(&self.frames, &mut self.phiq, n, r, i, [0.0, 0.0, -1.0]);
                    put(&self.frames, &mut self.phiq, n, r, j, [0.0, 0.0, 1.0]);
                }
                ConKind::Project {
                    i,
                    si,
                    j,
                    sj,
                    w,
                    motion,
                } => {
                    let bi = body_state(&self.frames, i, q, qd);
                    let bj = body_state(&self.frames, j, q, qd);
                    let f = match motion {
                        Some(k) => self.motions[k].eval(t),
                        None => [0.0; 3],
                    };
                    let (wi, omi) = (bi.angle, bi.angular_velocity);
                    let omj = bj.angular_velocity;
                    let ai = rot(wi, si);
                    let aj = rot(bj.angle, sj);
                    let nv = rot(wi, w);
                    let d = bj.position + aj - bi.position - ai;
                    let dd = bj.velocity + omj * perp(aj) - bi.velocity - omi * perp(ai);
                    self.phi[r] = nv.dot(&d) - f[0];
                    self.phid[r] = omi * perp(nv).dot(&d) + nv.dot(&dd) - f[1];
                    self.phit[r] = -f[1];
                    self.gamma[r] = omi * omi * nv.dot(&d) - 2.0 * omi * perp(nv).dot(&dd)
                        + omj * omj * nv.dot(&aj)
                        - omi * omi * nv.dot(&ai)
                        + f[2];
                    let ti = perp(nv).dot(&d) - nv.dot(&perp(ai));
                    put(&self.frames, &mut self.phiq, n, r, i, [-nv.x, -nv.y, ti]);
                    put(
                        &self.frames,
                        &mut self.phiq,
                        n,
                        r,
                        j,
                        [nv.x, nv.y, nv.dot(&perp(aj))],
                    );
                }
            }
        }
    }

    /// Generalized forces Q at (t, q, q̇) into the workspace; contact reports updated. Uses the
    /// contact memory (tentative onsets for contacts closed in the committed memory).
    pub(crate) fn eval_forces(&mut self, t: f64, q: &[f64], qd: &[f64]) {
        if !self.feedback.is_empty() {
            self.feedback
                .update(t, (&self.frames, q, qd), &self.measures, &self.inputs);
        }
        self.qf.fill(0.0);
        for (k, b) in self.bodies.iter().enumerate() {
            self.qf[3 * k] += b.mass * self.gravity.x;
            self.qf[3 * k + 1] += b.mass * self.gravity.y;
        }
        let qf = &mut self.qf;
        let (mut p_diss, mut p_loads) = (0.0, 0.0);
        for f in &self.forces {
            let (d, l) = f.eval(&self.frames, t, q, qd, qf);
            p_diss += d;
            p_loads += l;
        }
        self.broad.update(&self.frames, q);
        for (k, cl) in self.clearances.iter_mut().enumerate() {
            if self.broad.apart[k] {
                self.contacts[k] = cl.apart_report();
                continue;
            }
            let bi = body_state(&self.frames, cl.i, q, qd);
            let bj = body_state(&self.frames, cl.j, q, qd);
            let frames = &self.frames;
            self.contacts[k] = if let Some(b) = cl.flex_beam() {
                let j = cl.j;
                let guide = guide_ref(&self.beams, &self.floating, b);
                cl.apply_flex(guide, q, qd, &bj, &mut self.memory, qf, |qf, g| {
                    add_gen(frames, qf, j, g)
                })
            } else if let Some(lugre) = &cl.lugre {
                crate::lugre::force::apply(
                    cl,
                    lugre,
                    k,
                    &bi,
                    &bj,
                    &mut self.memory,
                    &mut self.bristles,
                    |b, g| add_gen(frames, qf, b, g),
                )
            } else {
                cl.apply(&bi, &bj, &mut self.memory, |b, g| add_gen(frames, qf, b, g))
            };
            p_diss += self.contacts[k].dissipated_power;
        }
        for b in &self.beams {
            let (d, l) = b.forces(t, q, qd, &mut self.qf);
            p_diss += d;
            p_loads += l;
        }
        // floating bodies: gravity (in the potential energy), inertia terms (in the kinetic
        // energy) and modal damping; no applied loads of their own
        for f in &self.floating {
            p_diss += f.forces(q, qd, self.gravity, &mut self.qf);
        }
        self.p_diss = p_diss;
        self.p_loads = p_loads;
    }

    /// Power of the drivers' reaction forces at the last solve, W: −Σ λ_r (Φ_q q̇)_r over the
    /// rows of prescribed-motion constraints (`angle`, `relative_angle`, `displacement`
    /// drivers), with (Φ_q q̇)_r = Φ̇_r − Φ_t,r. Equal to λᵀΦ_t on the constraint manifold (sign
    /// derivation in the module docs). Needs `sol` and the constraint workspace of the same
    /// (t, q, q̇).
    pub(crate) fn driver_power(&self) -> f64 {
        let n = self.n;
        let mut p = 0.0;
        for c in &self.cons {
            if let ConKind::Angle {
                motion: Some(_), ..
            }
            | ConKind::Project {
                motion: Some(_), ..
            } = c.kind
            {
                let r = c.row;
                p -= self.sol[n + r] * (self.phid[r] - self.phit[r]);
            }
        }
        p
    }

    /// Power put into the system at the last evaluation, W: applied loads and drivers
    /// (dW_in/dt).
    pub(crate) fn input_power(&self) -> f64 {
        self.p_loads + self.driver_power()
    }

    /// Index in y of the dissipated energy E_d (J); the input work W_in (J) follows it.
    pub(crate) fn energy_offset(&self) -> usize {
        2 * self.n
    }

    /// Index in y of the first LuGre bristle state, after (q, q̇, E_d, W_in).
    pub(crate) fn bristle_offset(&self) -> usize {
        2 * self.n + 2
    }

    /// Solve the augmented system at (t, q, q̇): afterwards `sol` = [q̈; λ]. Returns false when
    /// the matrix is singular (then `sol` is NaN).
    pub(crate) fn solve_accelerations(&mut self, t: f64, q: &[f64], qd: &[f64]) -> bool {
        self.eval_constraints(t, q, qd);
        self.eval_forces(t, q, qd);
        self.load_augmented_rhs();
        let parts = (&self.bodies[..], &self.beams[..], &self.floating[..]);
        if self
            .range_space
            .solve(parts, q, &self.phiq, &mut self.sol)
            .is_ok()
        {
            self.solve_ok = true;
            return true;
        }
        // no range-space form (W = Φ_q M⁻¹ Φ_qᵀ singular: redundant constraints, or a block of M
        // not positive definite): the augmented matrix, which reports the singularity itself
        self.load_augmented_rhs();
        if self.factor_augmented(q).is_err() {
            self.sol.fill(f64::NAN);
            self.solve_ok = false;
            return false;
        }
        if self.g.sparse {
            self.g.growing.solve(&mut self.sol);
        } else {
            self.g.dense.solve(&mut self.sol);
        }
        self.solve_ok = true;
        true
    }

    /// `sol` ← [Q; γ − 2αΦ̇ − β²Φ].
    pub(crate) fn load_augmented_rhs(&mut self) {
        let (n, m) = (self.n, self.m);
        self.sol[..n].copy_from_slice(&self.qf);
        let (al, be) = (self.alpha, self.beta);
        for r in 0..m {
            self.sol[n + r] = self.gamma[r] - 2.0 * al * self.phid[r] - be * be * self.phi[r];
        }
    }

    /// Assemble and factor G = [M Φ_qᵀ; Φ_q 0] at q (Φ_q from the last constraint evaluation),
    /// dense or sparse ([`crate::LinearSolver`]).
    pub(crate) fn factor_augmented(&mut self, q: &[f64]) -> Result<(), clr_ode::linalg::Singular> {
        let (n, m) = (self.n, self.m);
        let nm = n + m;
        let (bodies, beams, floating) = (&self.bodies, &self.beams, &self.floating);
        let g = &mut self.g;
        if g.sparse {
            let s = &mut g.growing;
            s.begin(nm);
            add_mass(bodies, beams, floating, q, &mut |r, c, v| s.add(r, c, v));
            for (k, &v) in self.phiq.iter().enumerate() {
                if v != 0.0 {
                    let (r, c) = (k / n, k % n);
                    s.add(n + r, c, v);
                    s.add(c, n + r, v);
                }
            }
            return s.factor();
        }
        g.dense.resize(nm);
        let a = g.dense.matrix_mut();
        a.fill(0.0);
        add_mass(bodies, beams, floating, q, &mut |r, c, v| {
            a[r + c * nm] += v
        });
        for (k, &v) in self.phiq.iter().enumerate() {
            if v != 0.0 {
                let (r, c) = (k / n, k % n);
                a[(n + r) + c * nm] = v;
                a[c + (n + r) * nm] = v;
            }
        }
        g.dense.factor()
    }

    /// Accelerations q̈ of the last evaluation (units of q per s²).
    pub(crate) fn accelerations(&self) -> &[f64] {
        &self.sol[..self.n]
    }

    /// Lagrange multipliers λ of the last evaluation.
    pub(crate) fn multipliers(&self) -> &[f64] {
        &self.sol[self.n..]
    }

    /// Energies at (q, q̇) (kinetic, gravitational, elastic), J.
    pub fn energies(&self, q: &[f64], qd: &[f64]) -> Energies {
        let mut e = Energies::default();
        for (k, b) in self.bodies.iter().enumerate() {
            let v2 = qd[3 * k].powi(2) + qd[3 * k + 1].powi(2);
            e.kinetic += 0.5 * (b.mass * v2 + b.inertia * qd[3 * k + 2].powi(2));
            e.potential -= b.mass * (self.gravity.x * q[3 * k] + self.gravity.y * q[3 * k + 1]);
        }
        for b in &self.beams {
            let [ek, ep, ee] = b.energies(q, qd);
            e.kinetic += ek;
            e.potential += ep;
            e.elastic += ee;
        }
        for f in &self.floating {
            let [ek, ep, ee] = f.energies(q, qd, self.gravity);
            e.kinetic += ek;
            e.potential += ep;
            e.elastic += ee;
        }
        for f in &self.forces {
            match f {
                ForceEl::Spring {
                    i,
                    si,
                    j,
                    sj,
                    k,
                    l0,
                    ..
                } => {
                    let bi = body_state(&self.frames, *i, q, qd);
                    let bj = body_state(&self.frames, *j, q, qd);
                    let l = (bj.point(*sj) - bi.point(*si)).norm();
                    e.elastic += 0.5 * k * (l - l0).powi(2);
                }
                ForceEl::RotSpring {
                    i, j, k, angle0, ..
                } => {
                    let bi = body_state(&self.frames, *i, q, qd);
                    let bj = body_state(&self.frames, *j, q, qd);
                    e.elastic += 0.5 * k * (bj.angle - bi.angle - angle0).powi(2);
                }
                _ => {}
            }
        }
        for cl in &self.clearances {
            let bi = body_state(&self.frames, cl.i, q, qd);
            let bj = body_state(&self.frames, cl.j, q, qd);
            e.elastic += cl.elastic_energy(&bi, &bj);
        }
        e
    }

    /// Names of the joints and drivers (one per named item, in definition order).
    pub fn joint_names(&self) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for c in &self.cons {
            if out.last() != Some(&c.name) {
                out.push(c.name.clone());
            }
        }
        out
    }

    /// Reaction (F_x, F_y in N, moment in N·m about the centre of mass) that joint or driver
    /// `name` exerts on its second body (on its first body when the second is the ground), from
    /// the multipliers of the last evaluation: the generalized constraint force −Φ_qᵀλ restricted
    /// to that body's coordinates.
    pub(crate) fn reaction(&self, first_con: usize) -> [f64; 3] {
        let name = &self.cons[first_con].name;
        let (i, j) = self.cons[first_con].bodies();
        let b = if j != GROUND_ID { j } else { i };
        let mut out = [0.0; 3];
        if b == GROUND_ID {
            return out;
        }
        let n = self.n;
        let lam = self.multipliers();
        for c in self.cons[first_con..]
            .iter()
            .take_while(|c| &c.name == name)
        {
            for (r, l) in lam.iter().enumerate().skip(c.row).take(c.rows()) {
                for (col, o) in self.frames[b].cols.iter().zip(out.iter_mut()) {
                    if let Some(col) = col {
                        *o -= self.phiq[r * n + col] * l;
                    }
                }
            }
        }
        out
    }

    /// Indices of the first primitive constraint of each named joint or driver.
    pub(crate) fn joint_starts(&self) -> Vec<usize> {
        let mut out = Vec::new();
        for (k, c) in self.cons.iter().enumerate() {
            if k == 0 || self.cons[k - 1].name != c.name {
                out.push(k);
            }
        }
        out
    }

    /// Labels of constraint rows, `item (equation)`.
    pub(crate) fn row_labels(&self) -> Vec<String> {
        let mut out = Vec::with_capacity(self.m);
        for c in &self.cons {
            for r in 0..c.rows() {
                out.push(c.label(r));
            }
        }
        out
    }

    /// Names of the revolute clearance joints.
    pub fn clearance_names(&self) -> Vec<String> {
        self.clearances.iter().map(|c| c.name.clone()).collect()
    }

    /// Names of the force elements.
    pub fn force_names(&self) -> Vec<String> {
        self.forces.iter().map(|f| f.name().to_string()).collect()
    }

    /// Named points: (name, body index or `None` for the ground, local coordinates in m).
    pub fn points(&self) -> Vec<(String, Option<usize>, [f64; 2])> {
        self.points
            .iter()
            .map(|(n, b, l)| (n.clone(), (*b != GROUND_ID).then_some(*b), [l.x, l.y]))
            .collect()
    }

    /// Sample every beam-face contact pair at (q, q̇) (their gap and energy are those of the last
    /// update).
    pub(crate) fn refresh_faces(&mut self, q: &[f64], qd: &[f64]) {
        for k in 0..self.clearances.len() {
            self.refresh_face(k, q, qd);
        }
    }

    /// Sample clearance `k` at (q, q̇) if it is a beam-face contact pair.
    pub(crate) fn refresh_face(&mut self, k: usize, q: &[f64], qd: &[f64]) {
        let cl = &mut self.clearances[k];
        let Some(b) = cl.flex_beam() else {
            return;
        };
        let bj = body_state(&self.frames, cl.j, q, qd);
        let guide = guide_ref(&self.beams, &self.floating, b);
        cl.refresh_face(guide, q, qd, &bj);
    }

    /// Reports of the clearance joints at the last evaluation.
    pub fn contact_reports(&self) -> &[ContactReport] {
        &self.contacts
    }

    /// Commit the contact memory at an accepted state (rule 1 of clr-contact's memory).
    pub(crate) fn commit_contacts(&mut self, y: &[f64]) {
        let n = self.n;
        let (q, qd) = y.split_at(n);
        self.broad.update(&self.frames, q);
        for (k, cl) in self.clearances.iter_mut().enumerate() {
            if self.broad.apart[k] {
                cl.commit_apart(&mut self.memory);
                continue;
            }
            let bi = body_state(&self.frames, cl.i, q, qd);
            let bj = body_state(&self.frames, cl.j, q, qd);
            if let Some(b) = cl.flex_beam() {
                let guide = guide_ref(&self.beams, &self.floating, b);
                cl.commit_flex(guide, q, qd, &bj, &mut self.memory);
                continue;
            }
            if cl.commit_shapes(&bi, &bj, &mut self.memory) {
                continue;
            }
            for p in 0..cl.points() {
                let (d, r) = cl.gap(&bi, &bj, p);
                self.memory.commit(cl.mem + p, d, r);
            }
        }
    }
}

/// Add the non-zeros of the mass matrix M(q) through `sink(row, col, value)`: rigid bodies
/// (m, m, I on the diagonal), ground-fixed beams (their constant M_ff) and floating-frame bodies
/// (their state-dependent blocks).
pub(crate) fn add_mass(
    bodies: &[RigidBody],
    beams: &[FlexBeam],
    floating: &[FloatingBody],
    q: &[f64],
    sink: &mut dyn FnMut(usize, usize, f64),
) {
    for (k, b) in bodies.iter().enumerate() {
        sink(3 * k, 3 * k, b.mass);
        sink(3 * k + 1, 3 * k + 1, b.mass);
        sink(3 * k + 2, 3 * k + 2, b.inertia);
    }
    for fb in beams {
        let o = fb.offset;
        for (r, c, v) in fb.m.entries() {
            sink(o + r, o + c, v);
        }
    }
    for f in floating {
        f.add_mass(q, sink);
    }
}

#[inline]
pub(crate) fn guide_ref<'a>(
    beams: &'a [FlexBeam],
    floating: &'a [FloatingBody],
    b: GuideBeam,
) -> GuideRef<'a> {
    match b {
        GuideBeam::Fixed(k) => GuideRef::Fixed(&beams[k]),
        GuideBeam::Floating(k) => GuideRef::Floating(&floating[k]),
    }
}

impl OdeSystem for Model {
    /// 2n + 2 + m: y = (q, q̇, E_d, W_in, z_1 … z_m), E_d the energy dissipated by dampers,
    /// contact damping and friction (J) and W_in the work done on the system by drivers and
    /// applied loads (J), both integrated alongside as quadratures, and z the bristle
    /// deflections (m) of the m LuGre contact points ([`Model::n_bristle_states`]; the `lugre`
    /// layout in the docs of [`Model`]).
    fn dim(&self) -> usize {
        self.bristle_offset() + self.bristles.len()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let n = self.n;
        self.load_bristles(y);
        let (q, qd) = (&y[..n], &y[n..2 * n]);
        self.solve_accelerations(t, q, qd);
        dydt[..n].copy_from_slice(qd);
        dydt[n..2 * n].copy_from_slice(&self.sol[..n]);
        dydt[2 * n] = self.p_diss;
        dydt[2 * n + 1] = self.input_power();
        dydt[self.bristle_offset()..].copy_from_slice(self.bristle_rates());
    }

    fn n_events(&self) -> usize {
        if self.events_on {
            self.clearances.iter().map(Clearance::event_points).sum()
        } else {
            0
        }
    }

    /// One event per contact point (1 per revolute, 4 corners per translational clearance joint,
    /// none for a slider on a flexible guide):
    /// its signed penetration δ (m); a rising crossing is a contact onset.
    fn events(&mut self, _t: f64, y: &[f64], g: &mut [f64]) {
        let n = self.n;
        let (q, qd) = y.split_at(n);
        let mut ev = 0;
        self.broad.update(&self.frames, q);
        self.refresh_faces(q, qd);
        for (k, cl) in self.clearances.iter().enumerate() {
            if self.broad.apart[k] {
                g[ev] = cl.apart_report().penetration;
                ev += 1;
                continue;
            }
            let bi = body_state(&self.frames, cl.i, q, qd);
            let bj = body_state(&self.frames, cl.j, q, qd);
            for p in 0..cl.event_points() {
                g[ev] = cl.gap(&bi, &bj, p).0;
                ev += 1;
            }
        }
    }

    fn event_direction(&self, _i: usize) -> Direction {
        Direction::Rising
    }

    /// The smallest conservative-advancement bound of the shape contact pairs (none without
    /// them): no step can carry two shapes through each other unseen by the event functions.
    /// Costs one evaluation of the accelerations per step when the model has shape pairs.
    fn max_step(&mut self, t: f64, y: &[f64]) -> f64 {
        use crate::clearance::ClearanceKind;
        let shapes = |c: &Clearance| matches!(c.kind, ClearanceKind::Shapes(_));
        if !self.clearances.iter().any(shapes) {
            return f64::INFINITY;
        }
        let n = self.n;
        self.load_bristles(y);
        let (q, qd) = (&y[..n], &y[n..2 * n]);
        self.solve_accelerations(t, q, qd);
        let qdd = &self.sol[..n];
        let mut h = f64::INFINITY;
        for cl in self.clearances.iter() {
            let ClearanceKind::Shapes(p) = &cl.kind else {
                continue;
            };
            let bi = body_state(&self.frames, cl.i, q, qd);
            let bj = body_state(&self.frames, cl.j, q, qd);
            let acc = [
                frame_rates(&self.frames, cl.i, qdd),
                frame_rates(&self.frames, cl.j, qdd),
            ];
            h = h.min(p.max_step([&bi, &bj], acc));
        }
        h
    }

    fn event_terminal(&self, _i: usize) -> bool {
        true
    }
}

impl Model {
    /// The measure columns a state-dependent input function receives, in order: the
    /// position- and velocity-level `[[measure]]` columns (points, angles, distances and their
    /// rates).
    pub fn feedback_columns(&self) -> Vec<String> {
        self.measures
            .iter()
            .filter(|m| crate::input::is_feedback(m))
            .flat_map(|m| m.columns.iter().map(|(c, _)| c.clone()))
            .collect()
    }

    /// Make the load input `name` the function `f(t, feedback)` of time (s) and the values of
    /// [`Model::feedback_columns`] at the evaluated state, called at every evaluation of the
    /// forces (a controller or a custom force). NDF then differences the whole right-hand side
    /// for its Newton matrix (noted in the run's notes): the function's derivatives are not
    /// known.
    ///
    /// # Errors
    /// [`MbdError::Options`] for an unknown input or a driver's motion (which needs the
    /// derivatives of its function).
    pub fn set_input_function(
        &mut self,
        name: &str,
        f: crate::input::InputFn,
    ) -> Result<(), MbdError> {
        let cells = self.inputs.cells();
        let Some(k) = cells.iter().position(|c| c.name() == name) else {
            let names: Vec<&str> = cells.iter().map(|c| c.name()).collect();
            return Err(MbdError::Options(format!(
                "no input `{name}`{}",
                crate::field::suggestion(name, names.iter().copied())
            )));
        };
        if cells[k].is_motion() {
            return Err(MbdError::Options(format!(
                "input `{name}` drives a motion, whose first and second derivatives the \
                 integrator needs: a function of the state can drive loads only (a force, \
                 torque or actuator force)"
            )));
        }
        let measures = (0..self.measures.len())
            .filter(|&i| crate::input::is_feedback(&self.measures[i]))
            .collect();
        self.feedback.set(k, f, measures);
        Ok(())
    }
}
