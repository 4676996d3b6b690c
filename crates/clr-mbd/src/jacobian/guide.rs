//! Analytic ∂Q/∂q and ∂Q/∂q̇ of a rigid slider on the face of a flexible beam (multipoint
//! line/area contact), the beam ground-fixed or a floating-frame body.
//!
//! Every slider candidate (corners and face points, clr-contact's `MultipointDetector`) is
//! re-evaluated in dual numbers over 24 directions: the slider's q, q̇ (0..6), the floating
//! frame's R, θ and rates (6..12, constant for a ground-fixed beam) and the six full DOF of the
//! beam element under the candidate and their rates (12..24). Per candidate P:
//!
//! - the face point r(s) = r₀(s) + d(s) + e n(α + θ(s)) with d, θ interpolated by the element's
//!   shape rows (clr-beam [`ShapeRows`], the Euler–Bernoulli kinematics of `Path::surface`),
//!   mapped by the floating frame as r = R + A r̄ (Shabana 2020, eq. 5.4);
//! - the projection s* solves g(s) = (P − r(s))·t(s) = 0 (the detector's closest-point
//!   equation), so ∂s*/∂x = −(∂g/∂x)/(∂g/∂s) by the implicit function theorem (0 when s* is
//!   clamped at an end of the face);
//! - the signed gap (P − r(s*))·n_g(s*), δ = −gap, the guide velocity at s*, and the load row
//!   of `Path::surface_load_row` at s* (it depends on s* and on θ).
//!
//! An active point then gives F_N(δ, δ̇; l), F_T(v_T, F_N) ([`super::contact::law_forces`]), the
//! force −F_N n + F_T t on the slider and its opposite on the beam as work-equivalent nodal
//! loads (and on the floating frame). With an area law the contact length l is the point's
//! wetted length, a function of the neighbouring candidates' projections: ∂F_N/∂l
//! (`NormalLaw::contact_length_derivative`) is chained through clr-contact's
//! `MultipointDetector::tributary_partials` to those candidates' gradients, which are in other
//! elements' DOF (an outer product of this point's rows with their columns).

use clr_beam::{Face, Path, ShapeRows};
use clr_contact::multipoint::ContactPoint;
use clr_contact::{BodyState, ContactMemory, MultipointDetector, NormalLaw};
use nalgebra::Vector2;

use super::contact::{law_forces, Out};
use super::dual::{DBody, D, V};
use crate::clearance::Clearance;

/// Directions: slider q, q̇; guide frame q, q̇; element DOF u_e, u̇_e.
const N: usize = 24;
const SLIDER: usize = 0;
const FRAME: usize = 6;
const ELEM: usize = 12;
const ELEM_RATE: usize = 18;

/// How the beam's full DOF (3 per node, in the beam's own frame) map to columns of q.
#[derive(Clone, Copy)]
pub(super) enum BeamMap<'a> {
    /// Ground-fixed beam: full DOF d is column `offset + free_index[d]` (`None`: constrained).
    Fixed {
        offset: usize,
        free_index: &'a [Option<usize>],
    },
    /// Floating body: full DOF d is Σ_k T[d, k] q_f,k, q_f at `offset..offset + r`.
    Floating {
        offset: usize,
        r: usize,
        t: &'a [f64],
    },
}

impl BeamMap<'_> {
    /// Call `f(column, weight)` for the columns of q that full DOF `dof` depends on.
    fn each(&self, dof: usize, mut f: impl FnMut(usize, f64)) {
        match *self {
            BeamMap::Fixed { offset, free_index } => {
                if let Some(k) = free_index[dof] {
                    f(offset + k, 1.0);
                }
            }
            BeamMap::Floating { offset, r, t } => {
                for (k, &w) in t[dof * r..(dof + 1) * r].iter().enumerate() {
                    if w != 0.0 {
                        f(offset + k, w);
                    }
                }
            }
        }
    }
}

/// The guide of one element at the evaluated state.
pub(super) struct Guide<'a> {
    pub(super) cl: &'a Clearance,
    pub(super) path: &'a Path,
    pub(super) face: Face,
    pub(super) area: Option<NormalLaw>,
    /// Full-DOF displacements and velocities of the beam in its own frame.
    pub(super) u: &'a [f64],
    pub(super) ud: &'a [f64],
    /// States of the slider and of the guide frame (the ground for a fixed beam).
    pub(super) slider: BodyState,
    pub(super) frame: BodyState,
    pub(super) map: BeamMap<'a>,
}

/// One slider candidate at its projection on the face, as duals.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cand {
    dofs: [usize; 6],
    s: D<N>,
    gap: D<N>,
    /// Slider point, guide point r(s*), guide normal into the gap, guide material velocity.
    p: V<N>,
    r: V<N>,
    ng: V<N>,
    vel: V<N>,
    /// Load row of `Path::surface_load_row` at s* (x and y force coefficients).
    fx: [D<N>; 6],
    fy: [D<N>; 6],
}

impl Default for Cand {
    fn default() -> Self {
        let z = V::cst(Vector2::zeros());
        Self {
            dofs: [0; 6],
            s: D::cst(f64::NAN),
            gap: D::cst(0.0),
            p: z,
            r: z,
            ng: z,
            vel: z,
            fx: [D::cst(0.0); 6],
            fy: [D::cst(0.0); 6],
        }
    }
}

/// The face at s* + ds in world axes: point, normal into the gap, tangent, material velocity
/// and load row.
struct Surf<const M: usize> {
    r: V<M>,
    ng: V<M>,
    t: V<M>,
    vel: V<M>,
    fx: [D<M>; 6],
    fy: [D<M>; 6],
}

/// Row · x with the row taken at s* + ds: row·x + ds·(drow·x) (first order in ds).
fn lin<const M: usize>(row: &[f64; 6], drow: &[f64; 6], x: &[D<M>; 6], ds: D<M>) -> D<M> {
    let slope: f64 = drow.iter().zip(x).map(|(a, b)| a * b.v).sum();
    D::dot(row, x) + ds * slope
}

/// `Path::surface` and `Path::surface_load_row` at s* + ds from the element rows (face sign
/// `sign`, offset e = sign·h/2): φ = α + θ, n = (−sin φ, cos φ), r̄ = r₀ + d + e n, face normal
/// sign·n, t = (cos φ, sin φ), velocity ḋ − e θ̇ t, load row x − e cos φ·slope, y − e sin φ·slope;
/// then through the frame: r = R + A r̄, ṙ = Ṙ + ω k̂ × A r̄ + A r̄̇.
fn surface<const M: usize>(
    rows: &ShapeRows,
    sign: f64,
    ds: D<M>,
    [u, ud]: [&[D<M>; 6]; 2],
    frame: &DBody<M>,
) -> Surf<M> {
    let (st, ct) = lin(&rows.slope, &rows.curvature, u, ds).sin_cos();
    let [ca, sa] = rows.axis;
    let (cp, sp) = (ct * ca - st * sa, ct * sa + st * ca);
    let e = sign * 0.5 * rows.depth;
    let (tan, nrm) = (V::new(cp, sp), V::new(-sp, cp));
    let reference = V::new(ds * ca + rows.reference[0], ds * sa + rows.reference[1]);
    let d = V::new(lin(&rows.x, &rows.dx, u, ds), lin(&rows.y, &rows.dy, u, ds));
    let r_bar = reference + d + nrm * e;
    let rate = lin(&rows.slope, &rows.curvature, ud, ds);
    let d_rate = V::new(
        lin(&rows.x, &rows.dx, ud, ds),
        lin(&rows.y, &rows.dy, ud, ds),
    );
    let vel_bar = d_rate - tan.scale(rate) * e;
    let row = |r: &[f64; 6], dr: &[f64; 6], c: D<M>| {
        core::array::from_fn(|j| {
            ds * dr[j] + r[j] - c * (ds * rows.curvature[j] + rows.slope[j]) * e
        })
    };
    let ar = r_bar.rot(frame.th);
    Surf {
        r: frame.r + ar,
        ng: (nrm * sign).rot(frame.th),
        t: tan.rot(frame.th),
        vel: frame.v + ar.perp().scale(frame.w) + vel_bar.rot(frame.th),
        fx: row(&rows.x, &rows.dx, cp),
        fy: row(&rows.y, &rows.dy, sp),
    }
}

impl Guide<'_> {
    fn sign(&self) -> f64 {
        match self.face {
            Face::Upper => 1.0,
            Face::Lower => -1.0,
        }
    }

    /// Candidate at body-frame point `c` projected at arc coordinate `s` (clamped at an end
    /// of the face when `clamped`).
    fn candidate(&self, c: Vector2<f64>, s: f64, clamped: bool) -> Option<Cand> {
        let rows = self.path.shape_rows(s).ok()?;
        let u = core::array::from_fn(|j| D::var(self.u[rows.dofs[j]], ELEM + j));
        let ud = core::array::from_fn(|j| D::var(self.ud[rows.dofs[j]], ELEM_RATE + j));
        let slider = DBody::<N>::seed(&self.slider, Some(SLIDER));
        let frame = DBody::<N>::seed(&self.frame, Some(FRAME));
        let p = slider.point(c);
        let sign = self.sign();
        let ds = if clamped {
            D::cst(0.0)
        } else {
            // g(s*, x) = (P − r)·t = 0: ds*/dx = −g_x/g_s, g_s from a one-direction pass in s
            let at = surface(&rows, sign, D::cst(0.0), [&u, &ud], &frame);
            let g_x = (p - at.r).dot(at.t);
            let cst = |x: &[D<N>; 6]| x.map(|d| D::<1>::cst(d.v));
            let frame1 = DBody::<1>::seed(&self.frame, None);
            let at1 = surface(&rows, sign, D::var(0.0, 0), [&cst(&u), &cst(&ud)], &frame1);
            let g_s = (V::cst(p.val()) - at1.r).dot(at1.t).g[0];
            D {
                v: 0.0,
                g: g_x.g.map(|x| -x / g_s),
            }
        };
        let at = surface(&rows, sign, ds, [&u, &ud], &frame);
        Some(Cand {
            dofs: rows.dofs,
            s: ds + s,
            gap: (p - at.r).dot(at.ng),
            p,
            r: at.r,
            ng: at.ng,
            vel: at.vel,
            fx: at.fx,
            fy: at.fy,
        })
    }

    /// Every slider candidate of `det` at its last projection, into `cands`.
    pub(super) fn candidates(&self, det: &MultipointDetector, cands: &mut Vec<Cand>) {
        cands.clear();
        let end = self.path.length();
        for id in 0..det.candidate_count() {
            // a candidate past an end of the face at the point it was clipped to (held fixed
            // on the slider: the motion of the clipped point along the outline, O(tilt), is
            // left out of the Newton matrix)
            let cand = match (det.contact_body_point(id), det.projection(id)) {
                (Some(c), Some((s, _, _))) if s.is_finite() => {
                    self.candidate(c, s, s <= 0.0 || s >= end)
                }
                _ => None,
            };
            cands.push(cand.unwrap_or_default());
        }
    }

    /// Generalized forces of the force `f` on the slider at candidate `c` and of −f on the
    /// beam at r(s*): slider (f, (P − r_j) × f); frame (−f, (r − R) × (−f)); beam rows
    /// x_j·F̄ + y_j·F̄ with F̄ = Aᵀ(−f) (`FloatingBody::add_point_force`; A = I for a fixed beam).
    fn loads(&self, c: &Cand, f: V<N>) -> [D<N>; 12] {
        let slider = DBody::<N>::seed(&self.slider, Some(SLIDER));
        let frame = DBody::<N>::seed(&self.frame, Some(FRAME));
        let g = -f;
        let gl = g.rot(-frame.th);
        let mut q = [D::cst(0.0); 12];
        q[..3].copy_from_slice(&[f.x, f.y, (c.p - slider.r).cross(f)]);
        q[3..6].copy_from_slice(&[g.x, g.y, (c.r - frame.r).cross(g)]);
        for j in 0..6 {
            q[6 + j] = c.fx[j] * gl.x + c.fy[j] * gl.y;
        }
        q
    }

    /// Add the gradients of `q` (from [`Guide::loads`], rows in the element of `rows_of`), with
    /// the element directions of `cols_of`.
    fn add(&self, out: &mut Out, q: &[D<N>; 12], rows_of: &Cand, cols_of: &Cand) {
        let seeds = [(self.cl.j, SLIDER), (self.cl.i, FRAME)];
        let row = |out: &mut Out, r: usize, rw: f64, g: &[f64; N]| {
            out.add_row(r, rw, g, &seeds);
            for (j, &dof) in cols_of.dofs.iter().enumerate() {
                self.map.each(dof, |c, cw| {
                    out.dq[r * out.n + c] += rw * cw * g[ELEM + j];
                    out.dv[r * out.n + c] += rw * cw * g[ELEM_RATE + j];
                });
            }
        };
        for (frame, part) in [(self.cl.j, 0), (self.cl.i, 3)] {
            if frame == crate::runtime::GROUND_ID {
                continue;
            }
            for d in 0..3 {
                if let Some(r) = out.frames[frame].cols[d] {
                    row(out, r, 1.0, &q[part + d].g);
                }
            }
        }
        for (j, &dof) in rows_of.dofs.iter().enumerate() {
            self.map.each(dof, |r, rw| row(out, r, rw, &q[6 + j].g));
        }
    }

    /// ∂Q/∂q, ∂Q/∂q̇ of the active point `pt` (its candidate duals in `cands`), with the
    /// impact velocity of memory slot `mem + id` held fixed.
    pub(super) fn point(
        &self,
        det: &MultipointDetector,
        pt: &ContactPoint,
        cands: &[Cand],
        memory: &mut ContactMemory,
        out: &mut Out,
    ) {
        let Some(c) = cands.get(pt.id).filter(|c| c.s.v.is_finite()) else {
            return;
        };
        let slider = DBody::<N>::seed(&self.slider, Some(SLIDER));
        let delta = -c.gap;
        let n = -c.ng;
        let t = n.perp();
        let v = slider.point_velocity(c.p) - c.vel;
        let (vn, vt) = (v.dot(n), v.dot(t));
        let vm = memory.impact_velocity(self.cl.mem + pt.id, delta.v, vn.v);
        let (law, w) = crate::clearance::point_law(self.area, self.cl.normal, pt);
        let (f_n, f_t, t_n) = law_forces(&law, &self.cl.friction, [delta, vn, vt], vm);
        // the weight of a point clipped at a guide end held fixed (friction ∝ F_N)
        let (f_n, f_t) = if w == 1.0 {
            (f_n, f_t)
        } else {
            (f_n * w, f_t * w)
        };
        self.add(out, &self.loads(c, n.scale(-f_n) + t.scale(f_t)), c, c);
        // the wetted length l: ∂Q/∂l = (∂Q/∂F_N)(∂F_N/∂l) with F_T following F_N (∂F_T/∂F_N)
        let f_l = law.contact_length_derivative(delta.v, vn.v, vm);
        if self.area.is_none() || f_l == 0.0 {
            return;
        }
        let unit = V::cst(-n.val() + t.val() * t_n);
        let dq_dl = self.loads(c, unit).map(|d| d.v * f_l);
        det.tributary_partials(pt.id, |b, dl_ds, dl_dgap| {
            let Some(cb) = cands.get(b).filter(|c| c.s.v.is_finite()) else {
                return;
            };
            let gl = cb.s.g.map(|x| x * dl_ds);
            let gl: [f64; N] = core::array::from_fn(|k| gl[k] + cb.gap.g[k] * dl_dgap);
            let outer = dq_dl.map(|w| D {
                v: 0.0,
                g: gl.map(|x| x * w),
            });
            self.add(out, &outer, c, cb);
        });
    }
}
