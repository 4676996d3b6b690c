//! Jacobians of the generalized forces and constraints: ∂Q/∂q, ∂Q/∂q̇, Φ_q and (Φ_q q̇)_q,
//! assembled from the elements at (t, q, q̇).
//!
//! Analytic:
//! - ideal joints and drivers: Φ_q and (Φ_q q̇)_q (Nikravesh 1988, eqs. 5.11–5.15 differentiated
//!   once more); the node ties of floating bodies ([`crate::floating`]);
//! - translational and rotational spring–dampers, time-only applied loads (whose generalized
//!   torque a×F still depends on θ), gravity, ground-fixed beams (−K_ff, −C_ff);
//! - floating-frame bodies: the quadratic-velocity vector, gravity, elastic and damping forces
//!   in the floating frame (Shabana 2020, eqs. 5.38–5.42 differentiated);
//! - contact elements with stateless friction: the revolute clearance joint, the translational
//!   clearance joint (corner contacts) and the slider on a flexible beam face (multipoint
//!   contact, ground-fixed or floating beam, line and area laws). Their forces are re-evaluated
//!   in first-order dual numbers (`dual`, `contact`, `guide`): the gradients are the exact
//!   partial derivatives of what the model applies, the laws entering through clr-contact's
//!   closed-form derivatives. The impact velocity δ̇⁻ of the contact memory is a constant (it is
//!   state of the contact, not a function of q, q̇), so at a point whose onset is still
//!   tentative (closed in the committed memory) the derivative differs from a difference
//!   quotient, which would also vary the tentative δ̇⁻; at committed contacts the two agree.
//!
//! Central differences (the fallback, listed by [`Jacobians::fallback`]) for the elements
//! without an analytic form, each over its own contribution and the columns it touches, with
//! the contact memory restored after every perturbed evaluation:
//! - applied loads given as Rust closures of the state (`custom` forces and torques): their
//!   derivatives are unknown to the model;
//! - clearance joints with LuGre friction: their forces are evaluated by `crate::lugre` with the
//!   bristle states of the last evaluation held fixed, and that module documents them as
//!   differenced here (an analytic form would follow the `contact` submodule with clr-contact's
//!   `LuGre::force_with_derivatives`);
//! - a slider on a beam face with the reverse check (guide samples > 0): a sample's arc
//!   coordinate and its wetted length follow the corner projections through a piecewise
//!   interpolation and the neighbour rule, whose derivatives clr-contact does not provide (the
//!   candidates' wetted lengths it does: `MultipointDetector::tributary_partials`).
//!
//! The fallback's step is 10⁻⁶·max(1, |x|): coarse against the penetrations of stiff contacts
//! (micrometres and less), so a fallback contact element is only as accurate as h/δ allows.
//!
//! Non-smooth points, where the analytic form gives one side's derivative and a difference
//! quotient whose stencil straddles the point averages both: contact onset (δ = 0), the clamp
//! F_N = 0 of the damped laws, the kinks of the regularized friction laws (see
//! `FrictionLaw::force_with_derivatives`), a slider candidate at a beam node (the Hermite
//! interpolation is C¹: the s-derivatives of the load rows jump there) and a projection at an
//! end of the face.
//!
//! The sparsity pattern of every element is the set of coordinate columns of its frames
//! ([`Model::element_columns`]). [`Model::jacobians_into`] reuses its output and scratch space
//! (no allocation in the analytic part). The independent checks: [`Model::jacobians_fd`] and
//! [`Model::jacobians_fd_step`] difference the whole model with one step,
//! [`Model::jacobians_fd_best`] picks the step per column from a ladder (contact states);
//! [`Model::commit_contact_memory`] commits the impact velocities at a chosen state first, as
//! the integrator does after an accepted step.

mod contact;
pub(crate) mod dual;
mod guide;

use clr_contact::{BodyState, ContactMemory};
use nalgebra::{Matrix2, Vector2};

use crate::beam_face::{GuideBeam, GuideRef};
use crate::clearance::{Clearance, ClearanceKind};
use crate::contact_report::ContactReport;
use crate::runtime::{add_gen, body_state, perp, rot, ConKind, ForceEl, Frame, GROUND_ID};
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
    /// Scratch space of the analytic contact Jacobians, reused by [`Model::jacobians_into`].
    ws: Workspace,
}

impl Jacobians {
    fn sized(n: usize, m: usize) -> Self {
        let mut j = Self::default();
        j.resize(n, m);
        j
    }

    /// Size for n coordinates and m constraint rows and zero every entry (allocates only when
    /// the sizes grow).
    fn resize(&mut self, n: usize, m: usize) {
        (self.n, self.m) = (n, m);
        for (v, len) in [
            (&mut self.dq, n * n),
            (&mut self.dv, n * n),
            (&mut self.phi_q, m * n),
            (&mut self.phi_qqd_q, m * n),
        ] {
            v.clear();
            v.resize(len, 0.0);
        }
    }
}

/// Scratch space of [`Model::jacobians_into`]: the contact memory and reports saved around the
/// evaluation, and the candidate duals of a slider on a beam. Not part of the value of a
/// [`Jacobians`] (any two workspaces compare equal).
#[derive(Debug, Clone, Default)]
struct Workspace {
    memory: Option<ContactMemory>,
    reports: Vec<ContactReport>,
    cands: Vec<guide::Cand>,
}

impl PartialEq for Workspace {
    fn eq(&self, _: &Self) -> bool {
        true
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
        let mut jac = Jacobians::default();
        self.jacobians_into(t, q, qd, &mut jac);
        jac
    }

    /// As [`Model::jacobians`], into `jac` (resized to this model): with a `jac` kept between
    /// calls the analytic part allocates nothing (its scratch space lives in `jac`); the
    /// fallback names are rebuilt only when the fallback is not empty.
    pub fn jacobians_into(&mut self, t: f64, q: &[f64], qd: &[f64], jac: &mut Jacobians) {
        let (n, m) = (self.n, self.m);
        jac.resize(n, m);
        self.save_contacts(&mut jac.ws);
        // detection, reports and tentative onsets at (q, q̇): the state the derivatives are of
        self.eval_forces(t, q, qd);
        self.analytic_forces(t, q, qd, jac);
        self.analytic_contacts(q, qd, jac);
        for f in &self.floating {
            f.force_jacobian(q, qd, self.gravity, n, [&mut jac.dq, &mut jac.dv]);
        }
        self.eval_constraints(t, q, qd);
        jac.phi_q.copy_from_slice(&self.phiq);
        self.analytic_constraints(q, qd, &mut jac.phi_qqd_q);
        jac.fallback.clear();
        if self.has_fallback() {
            jac.fallback = self.fallback_names();
            let cols = self.fallback_columns(&jac.fallback);
            let mut rest = |model: &mut Model, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]| {
                model.fallback_forces(t, q, qd, out);
            };
            self.central(t, q, qd, (false, 1e-6), &cols, &mut jac.dq, &mut rest);
            self.central(t, q, qd, (true, 1e-6), &cols, &mut jac.dv, &mut rest);
        }
        self.restore_contacts(&jac.ws);
    }

    /// Commit the contact memory at the state y = (q, q̇, …) as the integration driver does after
    /// an accepted step (clr-contact's memory rules 1 and 4): a contact open at y records its
    /// onset (impact velocity δ̇⁻) unless it had one, a closed one is reset. For external
    /// drivers, and to compare [`Model::jacobians`] with [`Model::jacobians_fd`] at a chosen
    /// state: with δ̇⁻ committed it is a constant of both (module docs).
    pub fn commit_contact_memory(&mut self, y: &[f64]) {
        self.commit_contacts(y);
    }

    fn save_contacts(&self, ws: &mut Workspace) {
        match &mut ws.memory {
            Some(mem) => mem.clone_from(&self.memory),
            None => ws.memory = Some(self.memory.clone()),
        }
        ws.reports.clone_from(&self.contacts);
    }

    fn restore_contacts(&mut self, ws: &Workspace) {
        if let Some(mem) = &ws.memory {
            self.memory.clone_from(mem);
        }
        self.contacts.clone_from(&ws.reports);
    }

    /// Analytic ∂Q/∂q, ∂Q/∂q̇ of the contact elements (not those on the fallback), at the state
    /// of the last force evaluation (detectors) and (q, q̇).
    fn analytic_contacts(&mut self, q: &[f64], qd: &[f64], jac: &mut Jacobians) {
        let Model {
            clearances,
            frames,
            beams,
            floating,
            memory,
            n,
            ..
        } = self;
        let mut out = contact::Out {
            frames,
            n: *n,
            dq: &mut jac.dq,
            dv: &mut jac.dv,
        };
        for cl in clearances.iter().filter(|c| clearance_is_analytic(c)) {
            let bi = body_state(frames, cl.i, q, qd);
            let bj = body_state(frames, cl.j, q, qd);
            match &cl.kind {
                ClearanceKind::Revolute(g, app) => {
                    contact::revolute(cl, g, *app, [&bi, &bj], memory, &mut out)
                }
                ClearanceKind::Translational {
                    geometry,
                    origin,
                    angle,
                    width,
                } => {
                    let frame = (*origin, *angle, *width);
                    contact::translational(cl, geometry, frame, [&bi, &bj], memory, &mut out)
                }
                ClearanceKind::FlexGuide(g) => {
                    let (map, frame) = match g.beam {
                        GuideBeam::Fixed(k) => (
                            guide::BeamMap::Fixed {
                                offset: beams[k].offset,
                                free_index: &beams[k].free_index,
                            },
                            BodyState::default(),
                        ),
                        GuideBeam::Floating(k) => (
                            guide::BeamMap::Floating {
                                offset: floating[k].offset + 3,
                                r: floating[k].r,
                                t: &floating[k].t,
                            },
                            bi,
                        ),
                    };
                    let guide = guide::Guide {
                        cl,
                        path: &g.path,
                        face: g.face,
                        area: g.area_normal,
                        u: &g.qfull,
                        ud: &g.qdfull,
                        slider: bj,
                        frame,
                        map,
                    };
                    guide.candidates(&g.detector, &mut jac.ws.cands);
                    for pt in g.detector.points() {
                        guide.point(&g.detector, pt, &jac.ws.cands, memory, &mut out);
                    }
                }
                ClearanceKind::Shapes(p) => contact::shapes(cl, p, [&bi, &bj], memory, &mut out),
                ClearanceKind::FacePair(_) => {}
            }
        }
    }

    /// Generalized forces of the fallback elements only (closures, LuGre clearances, sliders
    /// with guide samples) at (t, q, q̇), into `out` (n).
    fn fallback_forces(&mut self, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for f in self.forces.iter().filter(|f| !is_analytic(f)) {
            f.eval(&self.frames, t, q, qd, out);
        }
        let Model {
            clearances,
            frames,
            beams,
            floating,
            memory,
            bristles,
            ..
        } = self;
        for (k, cl) in clearances.iter_mut().enumerate() {
            if clearance_is_analytic(cl) {
                continue;
            }
            let bi = body_state(frames, cl.i, q, qd);
            let bj = body_state(frames, cl.j, q, qd);
            if let Some(b) = cl.flex_beam() {
                let guide = match b {
                    GuideBeam::Fixed(k) => GuideRef::Fixed(&beams[k]),
                    GuideBeam::Floating(k) => GuideRef::Floating(&floating[k]),
                };
                let j = cl.j;
                cl.apply_flex(guide, q, qd, &bj, memory, out, |qf, g| {
                    add_gen(frames, qf, j, g)
                });
            } else if let Some(lugre) = &cl.lugre {
                let add = |b, g| add_gen(frames, out, b, g);
                crate::lugre::force::apply(cl, lugre, k, &bi, &bj, memory, bristles, add);
            } else {
                cl.apply(&bi, &bj, memory, |b, g| add_gen(frames, out, b, g));
            }
        }
    }

    /// The whole Jacobians by central differences of Q and Φ_q q̇ (the independent check of
    /// [`Model::jacobians`]; Φ_q is the model's own), step 10⁻⁶·max(1, |x|).
    pub fn jacobians_fd(&mut self, t: f64, q: &[f64], qd: &[f64]) -> Jacobians {
        self.jacobians_fd_step(t, q, qd, 1e-6)
    }

    /// As [`Model::jacobians_fd`] with the relative step h = `step`·max(1, |x|) of every
    /// coordinate and velocity x. At a contact the step must stay well below the penetration
    /// (micrometres and less for stiff laws: with h/δ = 10⁻² a Hertz force has a relative
    /// truncation error near 4·10⁻⁶) and above the rounding of the positions (~10⁻¹⁶ m per m).
    /// The contact memory and reports are left as they were.
    pub fn jacobians_fd_step(&mut self, t: f64, q: &[f64], qd: &[f64], step: f64) -> Jacobians {
        let (n, m) = (self.n, self.m);
        let mut jac = Jacobians::sized(n, m);
        let whole = &mut |model: &mut Model, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]| {
            model.eval_forces(t, q, qd);
            out.copy_from_slice(&model.qf);
        };
        let all: Vec<usize> = (0..n).collect();
        self.central(t, q, qd, (false, step), &all, &mut jac.dq, whole);
        self.central(t, q, qd, (true, step), &all, &mut jac.dv, whole);
        let rows = |model: &mut Model, t: f64, q: &[f64], qd: &[f64], out: &mut [f64]| {
            model.eval_constraints(t, q, qd);
            for (r, o) in out.iter_mut().enumerate() {
                *o = (0..model.n)
                    .map(|c| model.phiq[r * model.n + c] * qd[c])
                    .sum();
            }
        };
        jac.phi_qqd_q = self.central_m(t, q, qd, step, rows);
        self.eval_constraints(t, q, qd);
        jac.phi_q.copy_from_slice(&self.phiq);
        jac
    }

    /// Central differences of the whole model on a ladder of relative steps 10⁻⁴ … 10⁻¹⁰: per
    /// column of each matrix, the three neighbouring steps that agree best (the largest of their
    /// two differences is smallest). Returns the middle step's differences and, entry by entry,
    /// the larger of the two differences: an estimate of their own error. The truncation error
    /// falls with the step and the rounding error grows; they cross where neighbouring steps
    /// agree (three, not two: rounding noise is quantized, and two noisy quotients can agree by
    /// chance). The independent check of [`Model::jacobians`] at contact states, where no single
    /// step fits every column: penetrations from 10⁻⁹ to 10⁻⁴ m need h well below δ, while large
    /// contact forces and damping (F_e χ/δ̇⁻ with δ̇⁻ at its floor) and the projections of a
    /// multipoint contact (converged to 10⁻¹³ m) put rounding noise of ε|Q|/h into the small
    /// columns. Costs seven [`Model::jacobians_fd_step`].
    pub fn jacobians_fd_best(&mut self, t: f64, q: &[f64], qd: &[f64]) -> (Jacobians, Jacobians) {
        let ladder: Vec<Jacobians> = (4..=10)
            .map(|k| self.jacobians_fd_step(t, q, qd, 10f64.powi(-k)))
            .collect();
        let (mut best, mut spread) = (ladder[0].clone(), ladder[0].clone());
        let n = self.n;
        let pick =
            |get: &dyn Fn(&Jacobians) -> &Vec<f64>, out: &mut Vec<f64>, err: &mut Vec<f64>| {
                let rows = out.len() / n.max(1);
                let at = |k: usize, r: usize, c: usize| get(&ladder[k])[r * n + c];
                for c in 0..n {
                    // the larger of the two differences of steps k, k + 1, k + 2 in column c
                    let spread_of = |k: usize| -> f64 {
                        let d = |i: usize| {
                            (0..rows)
                                .map(|r| (at(i, r, c) - at(i + 1, r, c)).powi(2))
                                .sum::<f64>()
                        };
                        d(k).max(d(k + 1))
                    };
                    let k = (0..ladder.len() - 2)
                        .min_by(|&i, &j| spread_of(i).total_cmp(&spread_of(j)))
                        .unwrap_or(0);
                    for r in 0..rows {
                        let (a, b, e) = (at(k, r, c), at(k + 1, r, c), at(k + 2, r, c));
                        out[r * n + c] = b;
                        err[r * n + c] = (a - b).abs().max((b - e).abs());
                    }
                }
            };
        pick(&|j| &j.dq, &mut best.dq, &mut spread.dq);
        pick(&|j| &j.dv, &mut best.dv, &mut spread.dv);
        pick(
            &|j| &j.phi_qqd_q,
            &mut best.phi_qqd_q,
            &mut spread.phi_qqd_q,
        );
        (best, spread)
    }

    /// Columns of q touched by the elements on the fallback (closures, contact elements with
    /// their guide beams).
    fn fallback_columns(&self, names: &[String]) -> Vec<usize> {
        let mut v: Vec<usize> = self
            .element_columns()
            .into_iter()
            .filter(|(name, _)| names.contains(name))
            .flat_map(|(_, c)| c)
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    fn has_fallback(&self) -> bool {
        self.forces.iter().any(|f| !is_analytic(f))
            || self.clearances.iter().any(|c| !clearance_is_analytic(c))
    }

    fn fallback_names(&self) -> Vec<String> {
        let forces = self.forces.iter().filter(|f| !is_analytic(f));
        let contacts = self.clearances.iter().filter(|c| !clearance_is_analytic(c));
        forces
            .map(|f| f.name().to_string())
            .chain(contacts.map(|c| c.name.clone()))
            .collect()
    }

    /// Add central differences of `f` (n outputs) over the columns `cols` of q (or q̇ when
    /// `vel`) into `out` (n × n), step h = `step`·max(1, |x|) (relative truncation error
    /// O(h²)), with the contact memory and reports restored after each evaluation (a perturbed
    /// evaluation must not record contact onsets).
    #[allow(clippy::too_many_arguments)]
    fn central(
        &mut self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        (vel, step): (bool, f64),
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
            let h = step * x.abs().max(1.0);
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
        step: f64,
        f: impl Fn(&mut Model, f64, &[f64], &[f64], &mut [f64]),
    ) -> Vec<f64> {
        let (n, m) = (self.n, self.m);
        let mut out = vec![0.0; m * n];
        let mut qp = q.to_vec();
        let (mut fp, mut fm) = (vec![0.0; m], vec![0.0; m]);
        for c in 0..n {
            let h = step * q[c].abs().max(1.0);
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
            let o = b.offset;
            for (r, c, v) in b.k.entries() {
                jac.dq[(o + r) * n + o + c] -= v;
            }
            for (r, c, v) in b.c.entries() {
                jac.dv[(o + r) * n + o + c] -= v;
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

    /// (Φ_q q̇)_q of joints, drivers and node ties into `out` (m × n).
    pub(crate) fn analytic_constraints(&self, q: &[f64], qd: &[f64], out: &mut [f64]) {
        let n = self.n;
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
                ConKind::FloatNode { f, node, .. } => {
                    self.floating[f].tie_rate_jacobian(node, q, qd, &mut out[r * n..(r + 3) * n])
                }
            }
        }
    }
}

/// A contact element with an analytic Jacobian: stateless friction, and for a slider on a
/// beam no reverse-check samples (module docs).
fn clearance_is_analytic(c: &Clearance) -> bool {
    c.lugre.is_none()
        && match &c.kind {
            ClearanceKind::FlexGuide(g) => g.detector.point_count() == g.detector.candidate_count(),
            // the analytic contact Jacobian is that of a circular bearing; a worn profile's
            // curvature terms are not in it yet, so a worn joint takes central differences
            ClearanceKind::Revolute(g, _) => g.profile().is_none_or(|p| p.max_depth() == 0.0),
            ClearanceKind::Translational { .. } | ClearanceKind::Shapes(_) => true,
            // central differences over the beam's and the body's coordinates
            ClearanceKind::FacePair(_) => false,
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
    fn guide_columns(&self, b: GuideBeam) -> Vec<usize> {
        match b {
            GuideBeam::Fixed(k) => {
                let fb = &self.beams[k];
                (fb.offset..fb.offset + fb.n_free()).collect()
            }
            GuideBeam::Floating(k) => {
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

    /// A closure on the fallback (differenced over its own columns only) beside an analytic
    /// contact element and a body the closure does not touch: the assembled Jacobians still
    /// equal central differences of the whole system. A rod hanging on a revolute clearance
    /// joint (journal 0.1 mm into the bearing wall, sliding with Coulomb friction, impact
    /// velocity committed) and a free mass on a spring to ground, pushed by a closure of its
    /// state. Central differences with a relative step 1e-8 (h/δ = 1e-4: Hertz truncation
    /// ~4e-10); tolerance 1e-6 of the largest entry (rounding of the positions, ~1e-16 m, over
    /// h = 1e-8 m, and the closure's own O(h²)).
    #[test]
    fn fallback_columns_cover_the_closure() {
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
            )
            .applied_force("push", ("mass", [0.1, 0.0]), |_, s| {
                nalgebra::Vector2::new(-3.0 * s.position.x * s.angle, s.velocity.y.powi(2))
            });
        let mut m = b.build().unwrap();
        // journal centre 1.1 mm from the bearing centre: 0.1 mm penetration
        let q = [0.5011, 0.0, 0.0, 2.0, 0.1, 0.3];
        let qd = [0.01, 0.02, 0.3, 0.1, -0.2, 0.0];
        let y: Vec<f64> = q.iter().chain(&qd).copied().collect();
        m.commit_contact_memory(&y);
        let a = m.jacobians(0.0, &q, &qd);
        let f = m.jacobians_fd_step(0.0, &q, &qd, 1e-8);
        assert_eq!(a.fallback, vec!["push".to_string()]);
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
