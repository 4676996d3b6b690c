//! Jacobians of the generalized forces and constraints: ∂Q/∂q, ∂Q/∂q̇, Φ_q and (Φ_q q̇)_q,
//! assembled from the elements at (t, q, q̇).
//!
//! Analytic where the element provides it: ideal joints and drivers (Φ_q and (Φ_q q̇)_q of
//! Nikravesh 1988, eqs. 5.11–5.15 differentiated once more), translational and rotational
//! spring–dampers, time-only applied loads (whose generalized torque a×F still depends on θ),
//! gravity and ground-fixed beams (−K_ff, −C_ff). The remaining elements (clearance joints and
//! sliders, floating-frame bodies, node ties, user closures) are differentiated by central
//! differences of their own contribution (the fallback, listed by
//! [`Jacobians::fallback`]); the contact memory is restored after every perturbed evaluation.
//! The sparsity pattern of every element is the set of coordinate columns of its frames
//! ([`Model::element_columns`]).

use nalgebra::{Matrix2, Vector2};

use crate::runtime::{body_state, perp, rot, ConKind, ForceEl, Frame, GROUND_ID};
use crate::system::Model;

/// Jacobians at one state, row-major: `dq`, `dv` are n × n, `phi_q`, `phi_qqd_q` are m × n.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Jacobians {
    /// Number of coordinates n.
    pub n: usize,
    /// Number of constraint rows m.
    pub m: usize,
    /// ∂Q/∂q (N/m, N, N·m/m, N·m per rad as the columns' units).
    pub dq: Vec<f64>,
    /// ∂Q/∂q̇ (N·s/m, …).
    pub dv: Vec<f64>,
    /// Φ_q.
    pub phi_q: Vec<f64>,
    /// (Φ_q q̇)_q.
    pub phi_qqd_q: Vec<f64>,
    /// Names of the elements differentiated by central differences (no analytic form).
    pub fallback: Vec<String>,
}

impl Jacobians {
    fn sized(n: usize, m: usize) -> Self {
        Self {
            n,
            m,
            dq: vec![0.0; n * n],
            dv: vec![0.0; n * n],
            phi_q: vec![0.0; m * n],
            phi_qqd_q: vec![0.0; m * n],
            fallback: Vec::new(),
        }
    }
}

/// Scatter helper: adds ∂(generalized force of frame `b`)/∂(coordinates of frame `c`).
struct Sink<'a> {
    frames: &'a [Frame],
    n: usize,
    out: &'a mut [f64],
}

impl Sink<'_> {
    /// Add the 3×3 block `blk` (rows: x, y, θ of frame b; columns: x, y, θ of frame c).
    fn add(&mut self, b: usize, c: usize, blk: [[f64; 3]; 3]) {
        if b == GROUND_ID || c == GROUND_ID {
            return;
        }
        for (r, row) in self.frames[b].cols.iter().zip(blk) {
            let Some(r) = r else { continue };
            for (col, v) in self.frames[c].cols.iter().zip(row) {
                if let Some(col) = col {
                    self.out[r * self.n + col] += v;
                }
            }
        }
    }
}

/// d(Q_b)/d(x, y, θ or ẋ, ẏ, ω of frame c) for a force F on frame b at arm a_b, given
/// dF/dc (2×3) and, when b = c for position columns, the θ-dependence of the arm.
fn force_block(a_b: Vector2<f64>, df: [[f64; 3]; 2], f: Option<Vector2<f64>>) -> [[f64; 3]; 3] {
    let mut blk = [[0.0; 3]; 3];
    for col in 0..3 {
        let d = Vector2::new(df[0][col], df[1][col]);
        blk[0][col] = d.x;
        blk[1][col] = d.y;
        blk[2][col] = a_b.x * d.y - a_b.y * d.x;
    }
    if let Some(f) = f {
        // d(a × F)/dθ_b through the arm: (da/dθ) × F = perp(a) × F
        let pa = perp(a_b);
        blk[2][2] += pa.x * f.y - pa.y * f.x;
    }
    blk
}

impl Model {
    /// Columns of q each force element, clearance joint and constraint touches (its sparsity
    /// pattern: the element's contributions to ∂Q/∂q, ∂Q/∂q̇ and Φ_q lie in the rows and
    /// columns of these frames), by element name.
    pub fn element_columns(&self) -> Vec<(String, Vec<usize>)> {
        let cols = |ids: &[usize]| -> Vec<usize> {
            let mut v: Vec<usize> = ids
                .iter()
                .filter(|&&k| k != GROUND_ID)
                .flat_map(|&k| self.frames[k].cols.iter().flatten().copied())
                .collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        let mut out = Vec::new();
        for f in &self.forces {
            let ids = match f {
                ForceEl::Spring { i, j, .. }
                | ForceEl::RotSpring { i, j, .. }
                | ForceEl::PairTorque { i, j, .. } => vec![*i, *j],
                ForceEl::Force { i, .. } | ForceEl::Torque { i, .. } => vec![*i],
            };
            out.push((f.name().to_string(), cols(&ids)));
        }
        for c in &self.clearances {
            let mut v = cols(&[c.i, c.j]);
            if let Some(b) = c.flex_beam() {
                v.extend(self.guide_columns(b));
                v.sort_unstable();
                v.dedup();
            }
            out.push((c.name.clone(), v));
        }
        for c in &self.cons {
            let (i, j) = c.bodies();
            out.push((c.name.clone(), cols(&[i, j])));
        }
        out
    }

    /// ∂Q/∂q, ∂Q/∂q̇, Φ_q and (Φ_q q̇)_q at (t, q, q̇): analytic where the elements provide it,
    /// central differences of the other elements' own contributions (see the module docs).
    /// Leaves the model's contact memory and reports as they were.
    pub fn jacobians(&mut self, t: f64, q: &[f64], qd: &[f64]) -> Jacobians {
        let (n, m) = (self.n, self.m);
        let mut jac = Jacobians::sized(n, m);
        self.analytic_forces(t, q, qd, &mut jac);
        self.eval_constraints(t, q, qd);
        jac.phi_q.copy_from_slice(&self.phiq);
        let float_rows = self.analytic_constraints(q, qd, &mut jac.phi_qqd_q);
        // the rest: central differences of (Q − Q_analytic), only over the columns the
        // non-analytic elements touch (none: nothing to difference)
        let names = self.fallback_names();
        let cols = self.fallback_columns(&names);
        if !cols.is_empty() {
            let mut qa = vec![0.0; n];
            let mut rest = |model: &mut Model, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]| {
                model.eval_forces(t, q, qd);
                model.analytic_force_values(t, q, qd, &mut qa);
                for ((o, f), a) in out.iter_mut().zip(&model.qf).zip(&qa) {
                    *o = f - a;
                }
            };
            self.central(t, q, qd, false, &cols, &mut jac.dq, &mut rest);
            self.central(t, q, qd, true, &cols, &mut jac.dv, &mut rest);
        }
        if !float_rows.is_empty() {
            let rows = |model: &mut Model, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]| {
                model.eval_constraints(t, q, qd);
                for (r, o) in out.iter_mut().enumerate() {
                    *o = (0..model.n)
                        .map(|c| model.phiq[r * model.n + c] * qd[c])
                        .sum();
                }
            };
            let fd = self.central_m(t, q, qd, rows);
            for &r in &float_rows {
                jac.phi_qqd_q[r * n..(r + 1) * n].copy_from_slice(&fd[r * n..(r + 1) * n]);
            }
        }
        jac.fallback = names;
        self.eval_constraints(t, q, qd);
        jac
    }

    /// The whole Jacobians by central differences of Q and Φ_q q̇ (the independent check of
    /// [`Model::jacobians`]; Φ_q is the model's own).
    pub fn jacobians_fd(&mut self, t: f64, q: &[f64], qd: &[f64]) -> Jacobians {
        let (n, m) = (self.n, self.m);
        let mut jac = Jacobians::sized(n, m);
        let whole = &mut |model: &mut Model, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]| {
            model.eval_forces(t, q, qd);
            out.copy_from_slice(&model.qf);
        };
        let all: Vec<usize> = (0..n).collect();
        self.central(t, q, qd, false, &all, &mut jac.dq, whole);
        self.central(t, q, qd, true, &all, &mut jac.dv, whole);
        let rows = |model: &mut Model, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]| {
            model.eval_constraints(t, q, qd);
            for (r, o) in out.iter_mut().enumerate() {
                *o = (0..model.n)
                    .map(|c| model.phiq[r * model.n + c] * qd[c])
                    .sum();
            }
        };
        jac.phi_qqd_q = self.central_m(t, q, qd, rows);
        self.eval_constraints(t, q, qd);
        jac.phi_q.copy_from_slice(&self.phiq);
        jac
    }

    /// Columns of q touched by the elements without an analytic Jacobian (closures, contact
    /// elements with their guide beams, floating bodies with all their coordinates).
    fn fallback_columns(&self, names: &[String]) -> Vec<usize> {
        let mut v: Vec<usize> = self
            .element_columns()
            .into_iter()
            .filter(|(name, _)| names.contains(name))
            .flat_map(|(_, c)| c)
            .collect();
        for f in &self.floating {
            v.extend(f.offset..f.offset + f.n_coords());
        }
        v.sort_unstable();
        v.dedup();
        v
    }

    fn fallback_names(&self) -> Vec<String> {
        let mut v: Vec<String> = self
            .forces
            .iter()
            .filter(|f| !is_analytic(f))
            .map(|f| f.name().to_string())
            .collect();
        v.extend(self.clearances.iter().map(|c| c.name.clone()));
        v.extend(self.floating.iter().map(|f| f.name.clone()));
        v.extend(
            self.cons
                .iter()
                .filter(|c| matches!(c.kind, ConKind::FloatNode { .. }))
                .map(|c| c.name.clone()),
        );
        v
    }

    /// Add central differences of `f` (n outputs) over the columns `cols` of q (or q̇ when
    /// `vel`) into `out` (n × n), step 1e-6·max(1, |x|) (relative truncation error O(h²)), with
    /// the contact memory and reports restored after each evaluation (a perturbed evaluation
    /// must not record contact onsets).
    #[allow(clippy::too_many_arguments)]
    fn central(
        &mut self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        vel: bool,
        cols: &[usize],
        out: &mut [f64],
        f: &mut impl FnMut(&mut Model, f64, &[f64], &[f64], &mut [f64]),
    ) {
        let n = self.n;
        let (mut qp, mut vp) = (q.to_vec(), qd.to_vec());
        let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
        let memory = self.memory.clone();
        let reports = self.contacts.clone();
        for &c in cols {
            let x = if vel { qd[c] } else { q[c] };
            let h = 1e-6 * x.abs().max(1.0);
            for (v, buf) in [(x + h, &mut fp), (x - h, &mut fm)] {
                if vel {
                    vp[c] = v;
                } else {
                    qp[c] = v;
                }
                f(self, t, &qp, &vp, buf);
                self.memory.clone_from(&memory);
            }
            if vel {
                vp[c] = x;
            } else {
                qp[c] = x;
            }
            for r in 0..n {
                out[r * n + c] += (fp[r] - fm[r]) / (2.0 * h);
            }
        }
        self.contacts = reports;
    }

    /// As [`Model::central`] over q for m outputs.
    fn central_m(
        &mut self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        f: impl Fn(&mut Model, f64, &[f64], &[f64], &mut [f64]),
    ) -> Vec<f64> {
        let (n, m) = (self.n, self.m);
        let mut out = vec![0.0; m * n];
        let mut qp = q.to_vec();
        let (mut fp, mut fm) = (vec![0.0; m], vec![0.0; m]);
        for c in 0..n {
            let h = 1e-6 * q[c].abs().max(1.0);
            qp[c] = q[c] + h;
            f(self, t, &qp, qd, &mut fp);
            qp[c] = q[c] - h;
            f(self, t, &qp, qd, &mut fm);
            qp[c] = q[c];
            for r in 0..m {
                out[r * n + c] = (fp[r] - fm[r]) / (2.0 * h);
            }
        }
        out
    }

    /// Generalized forces of the analytically differentiated elements only.
    fn analytic_force_values(&self, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for (k, b) in self.bodies.iter().enumerate() {
            out[3 * k] += b.mass * self.gravity.x;
            out[3 * k + 1] += b.mass * self.gravity.y;
        }
        for f in self.forces.iter().filter(|f| is_analytic(f)) {
            f.eval(&self.frames, t, q, qd, out);
        }
        for b in &self.beams {
            b.forces(t, q, qd, out);
        }
    }

    /// Analytic ∂Q/∂q and ∂Q/∂q̇ of springs, rotational springs, time-only loads and beams.
    fn analytic_forces(&self, t: f64, q: &[f64], qd: &[f64], jac: &mut Jacobians) {
        let n = self.n;
        for f in self.forces.iter().filter(|f| is_analytic(f)) {
            match f {
                ForceEl::Spring {
                    i,
                    si,
                    j,
                    sj,
                    k,
                    c,
                    l0,
                    push,
                    ..
                } => {
                    // an actuator's pushing force lowers the tension (its u(q) still turns)
                    let pushing = push.as_ref().map_or(0.0, |f| f(t));
                    let kcl = [*k, *c, *l0, pushing];
                    self.spring_jacobian(q, qd, (*i, *si), (*j, *sj), kcl, jac);
                }
                ForceEl::RotSpring { i, j, k, c, .. } => {
                    // τ_j = −k(θ_j − θ_i − θ0) − c(ω_j − ω_i), τ_i = −τ_j
                    let mut sq = Sink {
                        frames: &self.frames,
                        n,
                        out: &mut jac.dq,
                    };
                    let t = |v: f64| [[0.0; 3], [0.0; 3], [0.0, 0.0, v]];
                    sq.add(*j, *j, t(-k));
                    sq.add(*j, *i, t(*k));
                    sq.add(*i, *j, t(*k));
                    sq.add(*i, *i, t(-k));
                    let mut sv = Sink {
                        frames: &self.frames,
                        n,
                        out: &mut jac.dv,
                    };
                    sv.add(*j, *j, t(-c));
                    sv.add(*j, *i, t(*c));
                    sv.add(*i, *j, t(*c));
                    sv.add(*i, *i, t(-c));
                }
                ForceEl::Force { i, si, f, .. } => {
                    // F(t) at arm a = A s: only the torque a × F depends on θ
                    let bi = body_state(&self.frames, *i, q, qd);
                    let force = f(t, &bi);
                    let blk = force_block(rot(bi.angle, *si), [[0.0; 3]; 2], Some(force));
                    Sink {
                        frames: &self.frames,
                        n,
                        out: &mut jac.dq,
                    }
                    .add(*i, *i, blk);
                }
                // a time-only torque does not depend on the state
                _ => {}
            }
        }
        for b in &self.beams {
            let (o, nf) = (b.offset, b.n_free());
            for r in 0..nf {
                for c in 0..nf {
                    jac.dq[(o + r) * n + o + c] -= b.k[r * nf + c];
                    jac.dv[(o + r) * n + o + c] -= b.c[r * nf + c];
                }
            }
        }
    }

    /// Spring–damper between P_i = r_i + A_i s_i and P_j: F_i = T u, F_j = −T u with
    /// d = P_j − P_i, l = |d|, u = d/l, T = k(l − l0) + c u·(Ṗ_j − Ṗ_i).
    fn spring_jacobian(
        &self,
        q: &[f64],
        qd: &[f64],
        (i, si): (usize, Vector2<f64>),
        (j, sj): (usize, Vector2<f64>),
        [k, c, l0, pushing]: [f64; 4],
        jac: &mut Jacobians,
    ) {
        let n = self.n;
        let bi = body_state(&self.frames, i, q, qd);
        let bj = body_state(&self.frames, j, q, qd);
        let (ai, aj) = (rot(bi.angle, si), rot(bj.angle, sj));
        let d = bj.position + aj - bi.position - ai;
        let l = d.norm();
        if l <= f64::MIN_POSITIVE {
            return;
        }
        let u = d / l;
        let v = bj.velocity + bj.angular_velocity * perp(aj)
            - bi.velocity
            - bi.angular_velocity * perp(ai);
        let tension = k * (l - l0) + c * u.dot(&v) - pushing;
        let proj = (Matrix2::identity() - u * u.transpose()) / l;
        // ∂(T u)/∂d and ∂(T u)/∂v
        let dt_dd = k * u + c * proj * v;
        let g_d = u * dt_dd.transpose() + tension * proj;
        let g_v = c * u * u.transpose();
        // ∂d/∂(x, y, θ) and ∂v/∂(x, y, θ), ∂v/∂(ẋ, ẏ, ω) of frame j (frame i: negated)
        let frame = |a: Vector2<f64>, w: f64, sign: f64| {
            let dd = [
                Vector2::new(sign, 0.0),
                Vector2::new(0.0, sign),
                sign * perp(a),
            ];
            let dvq = [Vector2::zeros(), Vector2::zeros(), -sign * w * a];
            (dd, dvq, dd)
        };
        let fi = tension * u;
        for (b, ab, sgn_b) in [(i, ai, 1.0), (j, aj, -1.0)] {
            for (cfr, ac, wc, sgn_c) in [
                (i, ai, bi.angular_velocity, -1.0),
                (j, aj, bj.angular_velocity, 1.0),
            ] {
                let (dd, dvq, dvv) = frame(ac, wc, sgn_c);
                let mut dfq = [[0.0; 3]; 2];
                let mut dfv = [[0.0; 3]; 2];
                for col in 0..3 {
                    let gq = sgn_b * (g_d * dd[col] + g_v * dvq[col]);
                    let gv = sgn_b * (g_v * dvv[col]);
                    dfq[0][col] = gq.x;
                    dfq[1][col] = gq.y;
                    dfv[0][col] = gv.x;
                    dfv[1][col] = gv.y;
                }
                let own = (b == cfr).then_some(sgn_b * fi);
                Sink {
                    frames: &self.frames,
                    n,
                    out: &mut jac.dq,
                }
                .add(b, cfr, force_block(ab, dfq, own));
                Sink {
                    frames: &self.frames,
                    n,
                    out: &mut jac.dv,
                }
                .add(b, cfr, force_block(ab, dfv, None));
            }
        }
    }

    /// (Φ_q q̇)_q of joints and drivers into `out` (m × n); returns the rows left to the
    /// fallback (node ties of floating bodies).
    fn analytic_constraints(&self, q: &[f64], qd: &[f64], out: &mut [f64]) -> Vec<usize> {
        let n = self.n;
        let mut fallback = Vec::new();
        let put = |out: &mut [f64], r: usize, k: usize, v: [f64; 3]| {
            if k != GROUND_ID {
                for (c, vd) in self.frames[k].cols.iter().zip(v) {
                    if let Some(c) = c {
                        out[r * n + c] += vd;
                    }
                }
            }
        };
        for con in &self.cons {
            let r = con.row;
            match con.kind {
                ConKind::Coincide { i, si, j, sj } => {
                    // Φ_q q̇ = ṙ_i + ω_i Ĩ A_i s_i − ṙ_j − ω_j Ĩ A_j s_j; ∂/∂θ = −ω A s
                    let bi = body_state(&self.frames, i, q, qd);
                    let bj = body_state(&self.frames, j, q, qd);
                    let (ai, aj) = (rot(bi.angle, si), rot(bj.angle, sj));
                    let (wi, wj) = (bi.angular_velocity, bj.angular_velocity);
                    for d in 0..2 {
                        put(out, r + d, i, [0.0, 0.0, -wi * ai[d]]);
                        put(out, r + d, j, [0.0, 0.0, wj * aj[d]]);
                    }
                }
                ConKind::Angle { .. } => {}
                ConKind::Project {
                    i, si, j, sj, w, ..
                } => {
                    // g = ω_i Ĩn·d + n·v, n = A_i w, d = P_j − P_i, v = Ṗ_j − Ṗ_i:
                    // ∂g/∂r_i = −ω_i Ĩn, ∂g/∂r_j = ω_i Ĩn, ∂g/∂θ_i = −ω_i n·d + Ĩn·v,
                    // ∂g/∂θ_j = (ω_i − ω_j) n·A_j s_j
                    let bi = body_state(&self.frames, i, q, qd);
                    let bj = body_state(&self.frames, j, q, qd);
                    let (ai, aj) = (rot(bi.angle, si), rot(bj.angle, sj));
                    let (wi, wj) = (bi.angular_velocity, bj.angular_velocity);
                    let nv = rot(bi.angle, w);
                    let pn = perp(nv);
                    let d = bj.position + aj - bi.position - ai;
                    let v = bj.velocity + wj * perp(aj) - bi.velocity - wi * perp(ai);
                    put(
                        out,
                        r,
                        i,
                        [-wi * pn.x, -wi * pn.y, -wi * nv.dot(&d) + pn.dot(&v)],
                    );
                    put(out, r, j, [wi * pn.x, wi * pn.y, (wi - wj) * nv.dot(&aj)]);
                }
                ConKind::FloatNode { .. } => fallback.extend(r..r + 3),
            }
        }
        fallback
    }
}

fn is_analytic(f: &ForceEl) -> bool {
    !matches!(
        f,
        ForceEl::Force {
            state_free: false,
            ..
        } | ForceEl::Torque {
            state_free: false,
            ..
        } | ForceEl::PairTorque {
            state_free: false,
            ..
        }
    )
}

impl Model {
    /// Coordinate columns of the flexible body carrying a slider's guide face.
    fn guide_columns(&self, b: crate::clearance::GuideBeam) -> Vec<usize> {
        match b {
            crate::clearance::GuideBeam::Fixed(k) => {
                let fb = &self.beams[k];
                (fb.offset..fb.offset + fb.n_free()).collect()
            }
            crate::clearance::GuideBeam::Floating(k) => {
                let f = &self.floating[k];
                (f.offset..f.offset + f.n_coords()).collect()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{ModelBuilder, RigidBody, TimeFn};

    /// The analytic Jacobians equal central differences of the whole system (independent of the
    /// analytic forms): a two-body chain with a revolute joint, a spring–damper, a rotational
    /// spring–damper, a displacement driver (projection constraint), a time-only force and a
    /// torque, at a moving state. Tolerance 1e-6 of the largest entry (central-difference
    /// truncation with h = 1e-6·max(1, |x|)).
    #[test]
    fn analytic_jacobians_match_central_differences() {
        let mut b = ModelBuilder::new();
        b.gravity(0.0, -9.81)
            .body("a", RigidBody::new(2.0, 0.3).at(0.5, 0.1, 0.3))
            .body("b", RigidBody::new(1.0, 0.1).at(1.4, 0.4, -0.2))
            .revolute("pin", ("ground", [0.0, 0.0]), ("a", [-0.5, 0.0]))
            .spring_damper(
                "s",
                ("a", [0.3, 0.1]),
                ("b", [-0.2, 0.05]),
                800.0,
                12.0,
                0.4,
            )
            .rotational_spring_damper("r", "a", "b", 30.0, 0.7, 0.1)
            .drive_displacement(
                "d",
                ("a", [0.5, 0.0]),
                ("b", [0.0, 0.0]),
                [0.6, 0.8],
                TimeFn::harmonic(0.5, 0.1, 3.0, 0.0),
            )
            .force(
                "f",
                ("b", [0.3, -0.1]),
                TimeFn::constant(4.0),
                TimeFn::harmonic(0.0, 2.0, 5.0, 0.0),
            )
            .torque("t", "b", TimeFn::constant(1.5));
        let mut m = b.build().unwrap();
        let q = [0.5, 0.1, 0.3, 1.4, 0.4, -0.2];
        let qd = [0.2, -0.4, 1.1, -0.3, 0.5, -0.9];
        let a = m.jacobians(0.13, &q, &qd);
        let f = m.jacobians_fd(0.13, &q, &qd);
        assert!(a.fallback.is_empty(), "{:?}", a.fallback);
        for (name, x, y) in [
            ("dQ/dq", &a.dq, &f.dq),
            ("dQ/dqd", &a.dv, &f.dv),
            ("(Phi_q qd)_q", &a.phi_qqd_q, &f.phi_qqd_q),
        ] {
            let scale = y.iter().fold(1e-12_f64, |s, v| s.max(v.abs()));
            for (k, (u, v)) in x.iter().zip(y.iter()).enumerate() {
                assert!((u - v).abs() <= 1e-6 * scale, "{name}[{k}]: {u} vs {v}");
            }
        }
    }

    /// With a contact element (differenced over its own columns only) and a body it does not
    /// touch, the assembled Jacobians still equal central differences of the whole system:
    /// a rod hanging on a revolute clearance joint (journal 0.1 mm into the bearing wall, sliding
    /// with Coulomb friction) and a free mass on a spring to ground. Same tolerance as above.
    #[test]
    fn fallback_columns_cover_the_contact_element() {
        use crate::{FrictionLawDesc, NormalLawDesc, RevoluteClearanceSpec};
        let friction = FrictionLawDesc {
            law: "coulomb".into(),
            mu: Some(0.1),
            v_reg: Some(1e-3),
            ..FrictionLawDesc::none()
        };
        let mut b = ModelBuilder::new();
        b.gravity(0.0, -9.81)
            .body("rod", RigidBody::new(1.0, 0.08).at(0.5, 0.0, 0.0))
            .body("mass", RigidBody::new(0.5, 0.01).at(2.0, 0.0, 0.0))
            .revolute_clearance(
                "bearing",
                ("ground", [0.0, 0.0]),
                ("rod", [-0.5, 0.0]),
                RevoluteClearanceSpec {
                    bearing_radius: 0.010,
                    journal_radius: 0.009,
                    normal: NormalLawDesc::hertz(1e9, 0.9).into(),
                    friction: friction.into(),
                },
            )
            .spring_damper(
                "s",
                ("ground", [2.0, 1.0]),
                ("mass", [0.0, 0.0]),
                100.0,
                1.0,
                0.8,
            );
        let mut m = b.build().unwrap();
        // journal centre 1.1 mm from the bearing centre: 0.1 mm penetration
        let q = [0.5011, 0.0, 0.0, 2.0, 0.1, 0.3];
        let qd = [0.01, 0.02, 0.3, 0.1, -0.2, 0.0];
        let a = m.jacobians(0.0, &q, &qd);
        let f = m.jacobians_fd(0.0, &q, &qd);
        assert_eq!(a.fallback, vec!["bearing".to_string()]);
        // the contact is active: its stiffness dominates ∂Q/∂q (the spring's is 100 N/m)
        assert!(f.dq.iter().any(|v| v.abs() > 1e5));
        for (name, x, y) in [("dQ/dq", &a.dq, &f.dq), ("dQ/dqd", &a.dv, &f.dv)] {
            let scale = y.iter().fold(1e-12_f64, |s, v| s.max(v.abs()));
            for (k, (u, v)) in x.iter().zip(y.iter()).enumerate() {
                assert!((u - v).abs() <= 1e-6 * scale, "{name}[{k}]: {u} vs {v}");
            }
        }
    }
}
