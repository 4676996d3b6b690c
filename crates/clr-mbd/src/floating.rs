//! Moving flexible bodies in a floating frame of reference (FFR), planar, with reduced (modal or
//! Craig–Bampton) elastic coordinates from clr-beam.
//!
//! # Formulation
//! A. A. Shabana, *Dynamics of Multibody Systems*, 4th ed., Cambridge 2020, ch. 5 (planar form
//! of §5.4–5.6). The body coordinates are q_b = (R_x, R_y, θ, q_f): the origin R (m) and angle θ
//! (rad) of the body frame and r reduced elastic coordinates q_f (the columns of the clr-beam
//! transformation T). A material point with undeformed body-frame position ū₀ and reduced shape
//! rows Φ (2 × r) is at
//!
//! ```text
//! r = R + A(θ) ū,   ū = ū₀ + Φ q_f.
//! ```
//!
//! With the invariants of the translational field (clr-beam `FloatingFrameInvariants`,
//! computed once: m, S̄₀ = ∫ρū₀, J₀ = ∫ρ|ū₀|², S̄_k = ∫ρφ_k, c_k = ∫ρ ū₀×φ_k, M_ff = ∫ρΦᵀΦ,
//! S̃_kl = ∫ρ φ_k×φ_l, plus I₁_k = ∫ρ ū₀·φ_k computed here from the consistent mass) and
//! S̄ = S̄₀ + Σ S̄_k q_k, Ĩv = (−v_y, v_x), the kinetic energy ½ q̇ᵀ M q̇ has the mass matrix
//! (Shabana 2020, eq. 5.38 planar)
//!
//! ```text
//! M_RR = m I,   M_Rθ = A Ĩ S̄,   M_Rf = A [S̄_1 … S̄_r],
//! M_θθ = J₀ + 2 I₁·q_f + q_fᵀ M_ff q_f,   M_θf,k = c_k + Σ_l q_l S̃_lk,   M_ff,
//! ```
//!
//! configuration dependent and assembled at every evaluation into the solver's preallocated
//! matrix. The quadratic-velocity vector Q_v = ∂T/∂q − Ṁ q̇ (eq. 5.42) is
//!
//! ```text
//! Q_v,R = θ̇² A S̄ − 2 θ̇ A Ĩ Σ S̄_k q̇_k,
//! Q_v,θ = −2 θ̇ (I₁ + M_ff q_f)·q̇_f,
//! Q_v,f = θ̇² (I₁ + M_ff q_f) + 2 θ̇ S̃ q̇_f,
//! ```
//!
//! gravity g gives Q_R = m g, Q_θ = g·(A Ĩ S̄), Q_f,k = g·(A S̄_k) (potential −g·(m R + A S̄)),
//! and the elastic forces are −K_ff q_f − D_ff q̇_f with the reduced stiffness and Rayleigh
//! damping of clr-beam. The rotary inertia of the cross-sections is left out consistently (the
//! invariants are those of the translational field), so the equations derive from one
//! Lagrangian and conserve T + V + U exactly without damping.
//!
//! # Reference conditions (which frame)
//! The body frame is the clr-beam model's own coordinate frame; the reduction must remove the
//! rigid-body motion. The supports set on the `BeamModel` are the reference conditions: a
//! clamp at node 0 with modal truncation (cantilever modes) or Craig–Bampton attaches the frame
//! tangentially at that node (Shabana's tangent frame). The reduced stiffness must be positive
//! definite (checked).
//!
//! # Attachment
//! At a reference node (all three DOF constrained in the beam model: it moves rigidly with the
//! frame) and at body-local points `Anchor::Local(name, ū₀)`, joints attach to the body frame
//! directly. At a deforming node (`Anchor::BeamNode(name, node)`, e.g. the free tip or a
//! Craig–Bampton interface node) the model gets three massless node-frame coordinates
//! (p_x, p_y, ψ) tied to the body by three constraints, named `<body>.node<k>`:
//! p − R − A(ū₀ + Φ_N q_f) = 0, ψ − θ − φ_θN·q_f = 0 (small elastic node rotation), with
//! γ = −θ̇² A ū + 2 θ̇ Ĩ A Φ_N q̇_f for the position rows; the augmented matrix stays regular
//! (the tie fixes the node coordinates). Joints and forces then attach to that node frame.

use clr_beam::{BeamModel, ReducedModel};
use nalgebra::Vector2;

use crate::error::MbdError;
use crate::runtime::{perp, rot};

/// A floating-frame flexible body: the data computed once from the reduction, and its place in q.
pub(crate) struct FloatingBody {
    pub(crate) name: String,
    /// Index of R_x in q; then R_y, θ, q_f.
    pub(crate) offset: usize,
    /// Number of elastic coordinates r.
    pub(crate) r: usize,
    /// Initial (R_x, R_y, θ) and (Ṙ_x, Ṙ_y, θ̇).
    pub(crate) pose: [f64; 3],
    pub(crate) velocity: [f64; 3],
    /// Which of (R_x, R_y, θ, Ṙ_x, Ṙ_y, θ̇) the description gave (fixed in the assembly of
    /// initial conditions); the others are solved ([`crate::init_flex`]).
    pub(crate) fixed: [bool; 6],
    /// Frequencies (Hz) of the kept modes: the modes of the supported beam for modal
    /// truncation, the fixed-interface modes for Craig–Bampton (clr-beam `mode_omega` / 2π).
    pub(crate) mode_hz: Vec<f64>,
    /// Full beam DOF (3 · node + {0: u_x, 1: u_y, 2: θ_z}) of the first elastic coordinates
    /// when they are Craig–Bampton boundary DOF (empty for modal truncation).
    pub(crate) boundary_dofs: Vec<usize>,
    pub(crate) mass: f64,
    s0: Vector2<f64>,
    pub(crate) j0: f64,
    sf: Vec<Vector2<f64>>,
    rc: Vec<f64>,
    i1: Vec<f64>,
    /// Row-major r × r.
    mff: Vec<f64>,
    skew: Vec<f64>,
    k: Vec<f64>,
    d: Vec<f64>,
    /// Undeformed node positions in the body frame, m.
    pub(crate) nodes: Vec<[f64; 2]>,
    /// T rows, row-major (3 · nodes) × r.
    pub(crate) t: Vec<f64>,
    /// The path through all elements in the body frame (for a slider on this body's face), when
    /// the beam model's elements form one chain.
    pub(crate) path: Option<clr_beam::Path>,
    /// Deforming nodes with joints: (node, first column of its node-frame coordinates in q).
    pub(crate) ties: Vec<(usize, usize)>,
}

impl FloatingBody {
    pub(crate) fn new(
        name: &str,
        model: &BeamModel,
        red: &ReducedModel,
        pose: [f64; 3],
        velocity: [f64; 3],
    ) -> Result<Self, MbdError> {
        let bad = |what: &'static str, value: f64, requirement: &'static str| {
            MbdError::InvalidParameter {
                item: name.to_string(),
                what,
                value,
                requirement,
            }
        };
        if !pose.iter().chain(velocity.iter()).all(|v| v.is_finite()) {
            return Err(bad(
                "initial pose or velocity",
                f64::NAN,
                "every component must be finite",
            ));
        }
        let tm = &red.transformation;
        let (nd, r) = (model.n_dof(), tm.ncols());
        if tm.nrows() != nd || red.stiffness.nrows() != r || red.invariants.modal_mass.nrows() != r
        {
            return Err(bad(
                "reduced model size",
                tm.nrows() as f64,
                "the reduction must come from the same BeamModel (T has one row per beam DOF)",
            ));
        }
        let inv = &red.invariants;
        if !(inv.mass.is_finite() && inv.mass > 0.0) {
            return Err(MbdError::InvalidInertia {
                body: name.to_string(),
                what: "mass of the flexible body (kg)",
                value: inv.mass,
            });
        }
        let mt = model.consistent_mass_dense().map_err(|e| MbdError::Beam {
            item: name.to_string(),
            message: e.to_string(),
        })?;
        let nodes = model.nodes().to_vec();
        // I₁_k = q₀ᵀ M_t T_k, q₀ = (x, y, 0) per node
        let i1 = (0..r)
            .map(|k| {
                let mut s = 0.0;
                for a in 0..nd {
                    let q0a = if a % 3 < 2 { nodes[a / 3][a % 3] } else { 0.0 };
                    if q0a != 0.0 {
                        for b in 0..nd {
                            s += q0a * mt[(a, b)] * tm[(b, k)];
                        }
                    }
                }
                s
            })
            .collect();
        let flat = |m: &faer::Mat<f64>| {
            let mut v = vec![0.0; r * r];
            for i in 0..r {
                for j in 0..r {
                    v[i * r + j] = m[(i, j)];
                }
            }
            v
        };
        let k = flat(&red.stiffness);
        if !positive_definite(&k, r) {
            return Err(bad(
                "reduced stiffness",
                f64::NAN,
                "must be positive definite: constrain the beam model (e.g. clamp node 0) so the \
                 reduction holds no rigid-body motion; the body frame supplies it",
            ));
        }
        let mut t = vec![0.0; nd * r];
        for a in 0..nd {
            for c in 0..r {
                t[a * r + c] = tm[(a, c)];
            }
        }
        Ok(FloatingBody {
            name: name.to_string(),
            offset: 0,
            r,
            pose,
            velocity,
            fixed: [true; 6],
            mode_hz: red
                .mode_omega
                .iter()
                .map(|w| w / (2.0 * std::f64::consts::PI))
                .collect(),
            boundary_dofs: red.boundary_dofs.clone(),
            mass: inv.mass,
            s0: Vector2::new(inv.first_moment[0], inv.first_moment[1]),
            j0: inv.polar_inertia,
            sf: inv
                .shape_first_moment
                .iter()
                .map(|s| Vector2::new(s[0], s[1]))
                .collect(),
            rc: inv.rotation_coupling.clone(),
            i1,
            mff: flat(&inv.modal_mass),
            skew: flat(&inv.modal_skew),
            k,
            d: flat(&red.damping),
            nodes,
            t,
            path: model.path().ok(),
            ties: Vec::new(),
        })
    }

    /// Full nodal displacements and velocities in the body frame, u = T q_f and u̇ = T q̇_f
    /// (3 per node), written into `u`, `ud` (length 3 · nodes; no allocation).
    pub(crate) fn full_displacements(&self, q: &[f64], qd: &[f64], u: &mut [f64], ud: &mut [f64]) {
        let (o, r) = (self.offset + 3, self.r);
        let (qf, qfd) = (&q[o..o + r], &qd[o..o + r]);
        for (a, (ua, uda)) in u.iter_mut().zip(ud.iter_mut()).enumerate() {
            let row = &self.t[a * r..(a + 1) * r];
            let (mut x, mut v) = (0.0, 0.0);
            for k in 0..r {
                x += row[k] * qf[k];
                v += row[k] * qfd[k];
            }
            *ua = x;
            *uda = v;
        }
    }

    /// Add the generalized forces of a world force `f` (N) applied at the material point with
    /// world position `point` (m) whose body-frame displacement rows are `row` (a clr-beam
    /// `LoadRow` of full body-frame DOF, linearized at the current deformation): by virtual work
    /// with δr = δR + δθ Ĩ(r − R) + A δū, δū = row·T δq_f (Shabana 2020, eq. 5.4 varied),
    /// Q_R += f, Q_θ += (r − R) × f, Q_f += Tᵀ rowᵀ Aᵀ f.
    pub(crate) fn add_point_force(
        &self,
        q: &[f64],
        point: Vector2<f64>,
        row: &clr_beam::LoadRow,
        f: Vector2<f64>,
        out: &mut [f64],
    ) {
        let (o, r) = (self.offset, self.r);
        let arm = point - Vector2::new(q[o], q[o + 1]);
        out[o] += f.x;
        out[o + 1] += f.y;
        out[o + 2] += arm.x * f.y - arm.y * f.x;
        let fl = rot(-q[o + 2], f);
        for k in 0..6 {
            let g = row.fx[k] * fl.x + row.fy[k] * fl.y;
            if g == 0.0 {
                continue;
            }
            let trow = &self.t[row.dofs[k] * r..(row.dofs[k] + 1) * r];
            for (c, tc) in trow.iter().enumerate() {
                out[o + 3 + c] += tc * g;
            }
        }
    }

    /// Number of coordinates 3 + r.
    pub(crate) fn n_coords(&self) -> usize {
        3 + self.r
    }

    /// True when node `n` moves rigidly with the frame (its rows of T are zero).
    pub(crate) fn is_reference_node(&self, n: usize) -> bool {
        n < self.nodes.len()
            && self.t[3 * n * self.r..3 * (n + 1) * self.r]
                .iter()
                .all(|&v| v == 0.0)
    }

    /// Column names: `name.x`, `name.y`, `name.theta`, `name.q<k>`.
    pub(crate) fn coord_names(&self) -> Vec<String> {
        let mut c: Vec<String> = ["x", "y", "theta"]
            .iter()
            .map(|s| format!("{}.{s}", self.name))
            .collect();
        c.extend((0..self.r).map(|k| format!("{}.q{k}", self.name)));
        c
    }

    /// S̄ = S̄₀ + Σ S̄_k q_k (kg·m, body frame).
    fn first_moment(&self, qf: &[f64]) -> Vector2<f64> {
        self.sf
            .iter()
            .zip(qf)
            .fold(self.s0, |s, (sk, q)| s + sk * *q)
    }

    /// (I₁ + M_ff q_f)_k.
    fn i1_mq(&self, qf: &[f64], k: usize) -> f64 {
        let row = &self.mff[k * self.r..(k + 1) * self.r];
        self.i1[k] + row.iter().zip(qf).map(|(a, b)| a * b).sum::<f64>()
    }

    /// Add this body's mass matrix blocks through `sink(row, col, value)` (coordinates of q).
    pub(crate) fn add_mass(&self, q: &[f64], sink: &mut dyn FnMut(usize, usize, f64)) {
        let (o, r) = (self.offset, self.r);
        let th = q[o + 2];
        let qf = &q[o + 3..o + 3 + r];
        let mut put = |i: usize, j: usize, v: f64| {
            sink(o + i, o + j, v);
            if i != j {
                sink(o + j, o + i, v);
            }
        };
        put(0, 0, self.mass);
        put(1, 1, self.mass);
        let mrt = perp(rot(th, self.first_moment(qf)));
        put(0, 2, mrt.x);
        put(1, 2, mrt.y);
        let mut mtt = self.j0;
        for k in 0..r {
            let ask = rot(th, self.sf[k]);
            put(0, 3 + k, ask.x);
            put(1, 3 + k, ask.y);
            mtt += qf[k] * (self.i1[k] + self.i1_mq(qf, k));
            let mut mtf = self.rc[k];
            for (l, ql) in qf.iter().enumerate() {
                mtf += ql * self.skew[l * r + k];
            }
            put(2, 3 + k, mtf);
            for l in k..r {
                put(3 + k, 3 + l, self.mff[k * r + l]);
            }
        }
        put(2, 2, mtt);
    }

    /// Add Q_v, gravity and the elastic and damping forces to `out`; returns the dissipated
    /// power q̇_fᵀ D q̇_f (W).
    pub(crate) fn forces(&self, q: &[f64], qd: &[f64], g: Vector2<f64>, out: &mut [f64]) -> f64 {
        let (o, r) = (self.offset, self.r);
        let (th, w) = (q[o + 2], qd[o + 2]);
        let (qf, qfd) = (&q[o + 3..o + 3 + r], &qd[o + 3..o + 3 + r]);
        let as_ = rot(th, self.first_moment(qf));
        let asfd = rot(
            th,
            self.sf
                .iter()
                .zip(qfd)
                .fold(Vector2::zeros(), |s, (sk, v)| s + sk * *v),
        );
        let fr = w * w * as_ - 2.0 * w * perp(asfd) + self.mass * g;
        out[o] += fr.x;
        out[o + 1] += fr.y;
        let mut qt = g.dot(&perp(as_));
        let mut p = 0.0;
        for k in 0..r {
            let im = self.i1_mq(qf, k);
            qt -= 2.0 * w * im * qfd[k];
            let mut f = w * w * im + g.dot(&rot(th, self.sf[k]));
            for l in 0..r {
                f += 2.0 * w * self.skew[k * r + l] * qfd[l];
                f -= self.k[k * r + l] * qf[l];
                let dv = self.d[k * r + l] * qfd[l];
                f -= dv;
                p += qfd[k] * dv;
            }
            out[o + 3 + k] += f;
        }
        out[o + 2] += qt;
        p
    }

    /// (kinetic ½q̇ᵀMq̇, gravitational −g·(mR + AS̄), elastic ½q_fᵀKq_f), J.
    pub(crate) fn energies(&self, q: &[f64], qd: &[f64], g: Vector2<f64>) -> [f64; 3] {
        let (o, r) = (self.offset, self.r);
        let (th, w) = (q[o + 2], qd[o + 2]);
        let (qf, qfd) = (&q[o + 3..o + 3 + r], &qd[o + 3..o + 3 + r]);
        let rd = Vector2::new(qd[o], qd[o + 1]);
        let s = self.first_moment(qf);
        let mut mtt = self.j0;
        let mut t = 0.5 * self.mass * rd.norm_squared() + w * rd.dot(&perp(rot(th, s)));
        let mut u = 0.0;
        for k in 0..r {
            mtt += qf[k] * (self.i1[k] + self.i1_mq(qf, k));
            let mut mtf = self.rc[k];
            for l in 0..r {
                mtf += qf[l] * self.skew[l * r + k];
                t += 0.5 * qfd[k] * self.mff[k * r + l] * qfd[l];
                u += 0.5 * qf[k] * self.k[k * r + l] * qf[l];
            }
            t += rd.dot(&rot(th, self.sf[k])) * qfd[k] + w * mtf * qfd[k];
        }
        t += 0.5 * mtt * w * w;
        let pos = Vector2::new(q[o], q[o + 1]);
        let v = -g.dot(&(self.mass * pos + rot(th, s)));
        [t, v, u]
    }

    /// (ū, φ_θ·q_f): body-frame position of node `n` (m) and its elastic rotation (rad).
    pub(crate) fn node_local(&self, n: usize, qf: &[f64]) -> (Vector2<f64>, f64) {
        let r = self.r;
        let mut u = Vector2::new(self.nodes[n][0], self.nodes[n][1]);
        let mut psi = 0.0;
        for (k, qk) in qf.iter().enumerate() {
            u.x += self.t[3 * n * r + k] * qk;
            u.y += self.t[(3 * n + 1) * r + k] * qk;
            psi += self.t[(3 * n + 2) * r + k] * qk;
        }
        (u, psi)
    }

    /// Node frame of node `n`: (p_x, p_y, ψ) and its rate, p = R + A ū, ψ = θ + φ_θ·q_f.
    pub(crate) fn node_frame(&self, n: usize, q: &[f64], qd: &[f64]) -> ([f64; 3], [f64; 3]) {
        let (o, r) = (self.offset, self.r);
        let (th, w) = (q[o + 2], qd[o + 2]);
        let (u, psi) = self.node_local(n, &q[o + 3..o + 3 + r]);
        let (ud, psid) = self.node_local_rate(n, &qd[o + 3..o + 3 + r]);
        let au = rot(th, u);
        let p = Vector2::new(q[o], q[o + 1]) + au;
        let v = Vector2::new(qd[o], qd[o + 1]) + w * perp(au) + rot(th, ud);
        ([p.x, p.y, th + psi], [v.x, v.y, w + psid])
    }

    /// (Φ_N q̇_f, φ_θ·q̇_f): the elastic part of a node's body-frame velocity.
    fn node_local_rate(&self, n: usize, qfd: &[f64]) -> (Vector2<f64>, f64) {
        let (u, psi) = self.node_local(n, qfd);
        (u - Vector2::new(self.nodes[n][0], self.nodes[n][1]), psi)
    }

    /// The node tie Φ = (p − R − A ū, ψ − θ − φ_θ·q_f) of node `n` whose frame coordinates are
    /// at `col`: writes Φ, Φ̇, γ (the acceleration right-hand side, −θ̇² A ū + 2 θ̇ Ĩ A Φ_N q̇_f
    /// for the position rows, 0 for the angle) and the Jacobian rows (`phiq`: 3 rows of n).
    pub(crate) fn tie(
        &self,
        n: usize,
        col: usize,
        q: &[f64],
        qd: &[f64],
        [phi, phid, gamma]: [&mut [f64]; 3],
        phiq: &mut [f64],
    ) {
        let (o, r) = (self.offset, self.r);
        let nq = phiq.len() / 3;
        let (th, w) = (q[o + 2], qd[o + 2]);
        let (p, v) = self.node_frame(n, q, qd);
        for d in 0..3 {
            phi[d] = q[col + d] - p[d];
            phid[d] = qd[col + d] - v[d];
            phiq[d * nq + col + d] += 1.0;
            phiq[d * nq + o + d] -= 1.0;
        }
        let (u, _) = self.node_local(n, &q[o + 3..o + 3 + r]);
        let (ud, _) = self.node_local_rate(n, &qd[o + 3..o + 3 + r]);
        let au = rot(th, u);
        let g = -w * w * au + 2.0 * w * perp(rot(th, ud));
        gamma[0] = g.x;
        gamma[1] = g.y;
        gamma[2] = 0.0;
        let pa = perp(au);
        phiq[o + 2] -= pa.x;
        phiq[nq + o + 2] -= pa.y;
        for k in 0..r {
            let phik = rot(
                th,
                Vector2::new(self.t[3 * n * r + k], self.t[(3 * n + 1) * r + k]),
            );
            phiq[o + 3 + k] -= phik.x;
            phiq[nq + o + 3 + k] -= phik.y;
            phiq[2 * nq + o + 3 + k] -= self.t[(3 * n + 2) * r + k];
        }
    }

    /// World position of node `n` (m): R + A(ū₀ + Φ q_f).
    pub(crate) fn node_position(&self, n: usize, q: &[f64]) -> Vector2<f64> {
        let (o, r) = (self.offset, self.r);
        let mut u = Vector2::new(self.nodes[n][0], self.nodes[n][1]);
        for k in 0..r {
            u.x += self.t[3 * n * r + k] * q[o + 3 + k];
            u.y += self.t[(3 * n + 1) * r + k] * q[o + 3 + k];
        }
        Vector2::new(q[o], q[o + 1]) + rot(q[o + 2], u)
    }
}

/// Analytic Jacobians of the floating-frame terms (used by [`crate::Model::jacobians`]).
impl FloatingBody {
    /// Add ∂/∂q and ∂/∂q̇ of [`FloatingBody::forces`] (Q_v, gravity, −K_ff q_f − D_ff q̇_f; the
    /// module docs' formulas differentiated) to the row-major n × n `dq`, `dv`. Q does not
    /// depend on R. With a = A S̄, b = A Σ S̄_k q̇_k, (I₁ + M_ff q_f)_k = i_k:
    /// ∂Q_R/∂θ = θ̇² Ĩa + 2θ̇ b, ∂Q_R/∂q_l = θ̇² A S̄_l, ∂Q_R/∂θ̇ = 2θ̇ a − 2Ĩb,
    /// ∂Q_R/∂q̇_l = −2θ̇ Ĩ A S̄_l; ∂Q_θ/∂θ = −g·a, ∂Q_θ/∂q_l = g·Ĩ A S̄_l − 2θ̇ Σ_k M_kl q̇_k,
    /// ∂Q_θ/∂θ̇ = −2 Σ i_k q̇_k, ∂Q_θ/∂q̇_l = −2θ̇ i_l; ∂Q_f,k/∂θ = g·Ĩ A S̄_k,
    /// ∂Q_f,k/∂q_l = θ̇² M_kl − K_kl, ∂Q_f,k/∂θ̇ = 2θ̇ i_k + 2 Σ_l S̃_kl q̇_l,
    /// ∂Q_f,k/∂q̇_l = 2θ̇ S̃_kl − D_kl (n: the number of coordinates).
    pub(crate) fn force_jacobian(
        &self,
        q: &[f64],
        qd: &[f64],
        g: Vector2<f64>,
        n: usize,
        [dq, dv]: [&mut [f64]; 2],
    ) {
        let (o, r) = (self.offset, self.r);
        let (th, w) = (q[o + 2], qd[o + 2]);
        let (qf, qfd) = (&q[o + 3..o + 3 + r], &qd[o + 3..o + 3 + r]);
        let a = rot(th, self.first_moment(qf));
        let b = rot(
            th,
            self.sf
                .iter()
                .zip(qfd)
                .fold(Vector2::zeros(), |s, (sk, v)| s + sk * *v),
        );
        let at = |i: usize, j: usize| (o + i) * n + o + j;
        let (qr, vr) = (w * w * perp(a) + 2.0 * w * b, 2.0 * w * a - 2.0 * perp(b));
        for d in 0..2 {
            dq[at(d, 2)] += qr[d];
            dv[at(d, 2)] += vr[d];
        }
        dq[at(2, 2)] -= g.dot(&a);
        let mut sum_iq = 0.0;
        for k in 0..r {
            let ask = rot(th, self.sf[k]);
            let ik = self.i1_mq(qf, k);
            sum_iq += ik * qfd[k];
            for d in 0..2 {
                dq[at(d, 3 + k)] += w * w * ask[d];
                dv[at(d, 3 + k)] -= 2.0 * w * perp(ask)[d];
            }
            let mq: f64 = (0..r).map(|l| self.mff[l * r + k] * qfd[l]).sum();
            dq[at(2, 3 + k)] += g.dot(&perp(ask)) - 2.0 * w * mq;
            dv[at(2, 3 + k)] -= 2.0 * w * ik;
            dq[at(3 + k, 2)] += g.dot(&perp(ask));
            let sq: f64 = (0..r).map(|l| self.skew[k * r + l] * qfd[l]).sum();
            dv[at(3 + k, 2)] += 2.0 * w * ik + 2.0 * sq;
            for l in 0..r {
                dq[at(3 + k, 3 + l)] += w * w * self.mff[k * r + l] - self.k[k * r + l];
                dv[at(3 + k, 3 + l)] += 2.0 * w * self.skew[k * r + l] - self.d[k * r + l];
            }
        }
        dv[at(2, 2)] -= 2.0 * sum_iq;
    }

    /// (Φ_q q̇)_q of the node tie of node `node` ([`FloatingBody::tie`]) added to its 3 rows
    /// `out` (row-major, n columns): the position rows are ṗ − Ṙ − θ̇ Ĩ A ū − A Φ_N q̇_f, so
    /// ∂/∂θ = θ̇ A ū − Ĩ A Φ_N q̇_f and ∂/∂q_f,k = −θ̇ Ĩ A Φ_N,k; the angle row is linear in q̇
    /// with constant coefficients (0).
    pub(crate) fn tie_rate_jacobian(&self, node: usize, q: &[f64], qd: &[f64], out: &mut [f64]) {
        let nq = out.len() / 3;
        let (o, r) = (self.offset, self.r);
        let (th, w) = (q[o + 2], qd[o + 2]);
        let (u, _) = self.node_local(node, &q[o + 3..o + 3 + r]);
        let (ud, _) = self.node_local_rate(node, &qd[o + 3..o + 3 + r]);
        let d_th = w * rot(th, u) - perp(rot(th, ud));
        for d in 0..2 {
            out[d * nq + o + 2] += d_th[d];
        }
        for k in 0..r {
            let phik = Vector2::new(self.t[3 * node * r + k], self.t[(3 * node + 1) * r + k]);
            let dk = -w * perp(rot(th, phik));
            for d in 0..2 {
                out[d * nq + o + 3 + k] += dk[d];
            }
        }
    }
}

/// Cholesky test of a symmetric row-major n × n matrix (build time only).
fn positive_definite(a: &[f64], n: usize) -> bool {
    let mut l = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= l[i * n + k] * l[j * n + k];
            }
            if i == j {
                if !(s > 0.0 && s.is_finite()) {
                    return false;
                }
                l[i * n + i] = s.sqrt();
            } else {
                l[i * n + j] = s / l[j * n + j];
            }
        }
    }
    true
}

#[cfg(test)]
pub(crate) mod tests {
    use crate::desc::beam::{BeamMaterial, MassKindDesc, SectionDesc, SupportDesc, SupportKind};
    use crate::{BeamMesh, MbdError, ModelBuilder, Reduction, SimOptions, SolverKind};

    /// A 1 m arm of 4 elements, section 0.01 × 0.01 m, of `material`, with `supports`.
    pub(crate) fn arm_mesh(material: BeamMaterial, supports: Vec<SupportDesc>) -> BeamMesh {
        BeamMesh {
            start: [0.0, 0.0],
            end: [1.0, 0.0],
            elements: 4,
            material,
            section: SectionDesc::Rectangular {
                width: 0.01,
                depth: 0.01,
            },
            supports,
            rayleigh: [0.0, 0.0],
            mass: MassKindDesc::Consistent,
        }
    }

    /// The arm clamped at node 0, reduced on its 2 lowest cantilever modes, and the mass of the
    /// reduced model (kg).
    pub(crate) fn arm(e: f64) -> (BeamMesh, Reduction, f64) {
        let material = BeamMaterial {
            youngs_modulus: e,
            density: 7850.0,
            poisson_ratio: 0.3,
        };
        let mesh = arm_mesh(
            material,
            vec![SupportDesc {
                node: 0,
                kind: SupportKind::Clamped,
            }],
        );
        let red = Reduction::Modal { modes: 2 };
        let m = red
            .reduce(&mesh.build("arm").unwrap(), "arm")
            .unwrap()
            .invariants
            .mass;
        (mesh, red, m)
    }

    /// A pinned flexible arm released horizontally: T + V + U is conserved (closed form, no
    /// damping) and, with a stiff beam, the kinetic energy after the fall matches the rigid rod's
    /// ½ (mL²/3) ω² with ω the frame rate (independent closed form; the elastic share is tiny).
    #[test]
    fn floating_pendulum_conserves_energy_and_is_rigid_when_stiff() {
        let (beam, red, m) = arm(2e13);
        let mut b = ModelBuilder::new();
        b.gravity(0.0, -9.81)
            .floating_beam("arm", beam, red, [0.0; 3], [0.0; 3])
            .revolute("pin", ("ground", [0.0, 0.0]), ("arm", 0usize));
        let mut model = b.build().unwrap();
        assert_eq!(model.n_coordinates(), 5);
        let res = model
            .simulate(
                &SimOptions::span(0.0, 0.3, 3)
                    .tolerances(1e-9, 1e-12)
                    .solver(SolverKind::Dopri5),
            )
            .unwrap();
        let e = res.column("energy.total").unwrap();
        let ek = res.column("energy.kinetic").unwrap();
        let th = res.row(3)[res.index("arm.theta").unwrap()];
        assert_eq!(model.energies(&[0.0; 5], &[0.0; 5]).kinetic, 0.0);
        let scale = m * 9.81 * 0.5;
        assert!(ek[3] > 0.3 * scale, "the arm falls: {}", ek[3]);
        assert!((e[3] - e[0]).abs() < 1e-8 * scale, "drift {}", e[3] - e[0]);
        // rigid limit: the kinetic energy equals the potential energy lost, m g (L/2) sin(−θ)
        let ek_rigid = -m * 9.81 * 0.5 * th.sin();
        assert!(
            (ek[3] - ek_rigid).abs() < 1e-4 * ek_rigid,
            "{} vs {}",
            ek[3],
            ek_rigid
        );
    }

    /// A rigid bob pinned at the deforming tip node of the arm (a node tie): T + V + U is
    /// conserved, and with a stiff arm the bob follows the rigid double pendulum (an independent
    /// model of rigid bodies, same masses and inertias) to 1e-4 of L after 0.3 s.
    #[test]
    fn joint_at_a_deforming_node_conserves_energy_and_tends_to_rigid() {
        let run = |flexible: bool| {
            let (beam, red, m) = arm(2e13);
            let mut b = ModelBuilder::new();
            b.gravity(0.0, -9.81);
            if flexible {
                b.floating_beam("arm", beam, red, [0.0; 3], [0.0; 3])
                    .revolute("pin", ("ground", [0.0, 0.0]), ("arm", 0usize))
                    .revolute("tip", ("arm", 4usize), ("bob", [-0.25, 0.0]));
            } else {
                b.body("arm", crate::RigidBody::new(m, m / 12.0).at(0.5, 0.0, 0.0))
                    .revolute("pin", ("ground", [0.0, 0.0]), ("arm", [-0.5, 0.0]))
                    .revolute("tip", ("arm", [0.5, 0.0]), ("bob", [-0.25, 0.0]));
            }
            b.body(
                "bob",
                crate::RigidBody::new(0.5, 0.5 * 0.25 / 12.0).at(1.25, 0.0, 0.0),
            );
            let mut model = b.build().unwrap();
            let res = model
                .simulate(&SimOptions::span(0.0, 0.3, 3).tolerances(1e-9, 1e-12))
                .unwrap();
            let e = res.column("energy.total").unwrap();
            let row = res.row(3);
            let xy = [res.index("bob.x").unwrap(), res.index("bob.y").unwrap()];
            (e[3] - e[0], [row[xy[0]], row[xy[1]]], m)
        };
        let (drift, pf, m) = run(true);
        let (_, pr, _) = run(false);
        assert!(drift.abs() < 1e-8 * (m + 0.5) * 9.81, "drift {drift}");
        let d = ((pf[0] - pr[0]).powi(2) + (pf[1] - pr[1]).powi(2)).sqrt();
        assert!(d < 1e-4, "bob distance to the rigid double pendulum {d}");
        assert!(pr[1] < -0.2, "the bob falls: {}", pr[1]);
    }

    #[test]
    fn free_free_reduction_and_unknown_node_are_rejected() {
        // clr-beam's `Material::steel()`, no supports (free–free)
        let mat = clr_beam::Material::steel();
        let steel = BeamMaterial {
            youngs_modulus: mat.youngs_modulus,
            density: mat.density,
            poisson_ratio: mat.poisson_ratio,
        };
        let beam = arm_mesh(steel, Vec::new());
        let red = Reduction::Modal { modes: 4 };
        let mut b = ModelBuilder::new();
        b.floating_beam("arm", beam, red, [0.0; 3], [0.0; 3]);
        assert!(matches!(
            b.build(),
            Err(MbdError::InvalidParameter {
                what: "reduced stiffness",
                ..
            })
        ));
        let (beam, red, _) = arm(2e11);
        let mut b = ModelBuilder::new();
        b.floating_beam("arm", beam, red, [0.0; 3], [0.0; 3])
            .revolute("pin", ("ground", [1.0, 0.0]), ("arm", 5usize));
        assert!(matches!(
            b.build(),
            Err(MbdError::InvalidParameter {
                what: "floating-body node index",
                ..
            })
        ));
    }
}
