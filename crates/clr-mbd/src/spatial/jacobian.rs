//! Analytic element Jacobians of the spatial model, for the reduced Newton systems of
//! [`super::newton`].
//!
//! Positions are varied in the 6 velocity coordinates of each body, x = (δr, δθ): δr the
//! world displacement of the centre of mass and δθ a body-frame rotation, A → A(I + [δθ]×)
//! (the quaternion p → p + ½ p ⊗ (0, δθ)). With these the position Jacobian of the
//! constraints is the velocity Jacobian G itself (Haug 1989, §9.2: the virtual rotation
//! δπ′ of the body frame), and every derivative below is taken in (x, v), v = (ṙ, ω_body).
//!
//! Every element (the gyroscopic moment −ω × Jω, the spring–dampers, actuators, rotational
//! springs, bushings, applied forces and torques, the spherical clearance contact with
//! stateless friction, the spatial revolute/cylindrical clearance joint (clr-contact's
//! `journal` geometry and forces, generic over `journal::Real`, which the dual numbers
//! implement), and the constraint primitives' Φ_t, G·u and γ) is re-evaluated in
//! first-order dual numbers over the 24 directions (x_i, x_j, v_i, v_j) of its two bodies
//! ([`crate::jacobian::dual`]): the gradients are the exact partial derivatives of the same
//! formulas the right-hand side applies, the contact laws entering through clr-contact's
//! closed-form derivatives (`NormalLaw::force_with_derivatives`,
//! `FrictionLaw::force_with_derivatives`). Two pieces have no dual form and are written from
//! their closed forms: the rotation vector of the bushing, δφ = J_r⁻¹(φ)δψ with the inverse
//! right Jacobian of SO(3) (Solà, Deray & Atchuthan, *A micro Lie theory for state estimation
//! in robotics*, arXiv:1812.01537, eq. 144), and atan2 of the joint angle. The impact velocity
//! δ̇⁻ of the contact memory is held fixed (contact state, as in the planar
//! [`crate::jacobian`]). Fixed-size arrays throughout: nothing here allocates.
//!
//! LuGre friction has no analytic rows (its bristle states are integrated): models with it use
//! the solver's finite-difference Newton matrix, as the planar engine does.

use std::ops::{Add, Mul, Neg, Sub};

use nalgebra::{Matrix3, Vector3};

use super::constraint::{Prim, PrimKind};
use super::force::{vec_of, wrap, Force3};
use super::frame::log_map;
use super::journal::Journal;
use super::kin::{Kin, Kinematics, GROUND};
use super::sphere::Sphere;
use crate::desc::laws::ContactFriction;
use crate::jacobian::dual::D;
use crate::timefn::TimeFn;
use clr_contact::journal::{JournalState, V3 as CV3};
use clr_contact::ContactMemory;

/// Directions of one element: x_i (0..6), x_j (6..12), v_i (12..18), v_j (18..24).
const N: usize = 24;
type S = D<N>;

/// A 3-vector of dual numbers.
#[derive(Debug, Clone, Copy)]
struct V3([S; 3]);

impl V3 {
    fn cst(v: Vector3<f64>) -> Self {
        V3([S::cst(v.x), S::cst(v.y), S::cst(v.z)])
    }
    /// Value v with the unit gradients of directions k0..k0+3.
    fn var(v: Vector3<f64>, k0: usize) -> Self {
        V3([S::var(v.x, k0), S::var(v.y, k0 + 1), S::var(v.z, k0 + 2)])
    }
    fn dot(self, o: V3) -> S {
        self.0[0] * o.0[0] + self.0[1] * o.0[1] + self.0[2] * o.0[2]
    }
    fn cross(self, o: V3) -> V3 {
        let (a, b) = (self.0, o.0);
        V3([
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ])
    }
    fn scale(self, k: S) -> V3 {
        V3(self.0.map(|c| c * k))
    }
    fn norm(self) -> S {
        self.dot(self).sqrt()
    }
    /// m · self for a constant matrix m.
    fn rot(m: &Matrix3<f64>, v: V3) -> V3 {
        let row = |r: usize| v.0[0] * m[(r, 0)] + v.0[1] * m[(r, 1)] + v.0[2] * m[(r, 2)];
        V3([row(0), row(1), row(2)])
    }
    fn cmul(self, k: &Vector3<f64>) -> V3 {
        V3([self.0[0] * k.x, self.0[1] * k.y, self.0[2] * k.z])
    }
}

impl Add for V3 {
    type Output = V3;
    fn add(self, o: V3) -> V3 {
        V3([self.0[0] + o.0[0], self.0[1] + o.0[1], self.0[2] + o.0[2]])
    }
}
impl Sub for V3 {
    type Output = V3;
    fn sub(self, o: V3) -> V3 {
        self + -o
    }
}
impl Neg for V3 {
    type Output = V3;
    fn neg(self) -> V3 {
        V3(self.0.map(|c| -c))
    }
}
impl Mul<f64> for V3 {
    type Output = V3;
    fn mul(self, k: f64) -> V3 {
        V3(self.0.map(|c| c * k))
    }
}

/// atan2(y, x) with its gradient.
fn atan2(y: S, x: S) -> S {
    let r2 = x.v * x.v + y.v * y.v;
    let mut out = S::cst(y.v.atan2(x.v));
    for k in 0..N {
        out.g[k] = (x.v * y.g[k] - y.v * x.g[k]) / r2;
    }
    out
}

/// One body's kinematics in dual numbers, seeded in slot 0 (i) or 1 (j).
#[derive(Debug, Clone, Copy)]
struct DKin {
    r: V3,
    a: Matrix3<f64>,
    /// World rotation A δθ of the perturbation (value 0).
    dphi: V3,
    v: V3,
    w: V3,
}

impl DKin {
    /// Seed body `k` of `kin` in `slot`, with velocities (ṙ, ω_body) `vel` (the state's when
    /// None). The ground is constant.
    fn seed(kin: &Kinematics, k: usize, slot: usize, vel: Option<[Vector3<f64>; 2]>) -> Self {
        let b: &Kin = kin.get(k);
        let (v, wb) = match vel {
            Some([v, w]) if k != GROUND => (v, w),
            _ => (b.v, b.a.transpose() * b.w),
        };
        if k == GROUND {
            return DKin {
                r: V3::cst(b.r),
                a: b.a,
                dphi: V3::cst(Vector3::zeros()),
                v: V3::cst(v),
                w: V3::cst(b.a * wb),
            };
        }
        let dphi = V3::rot(&b.a, V3::var(Vector3::zeros(), 6 * slot + 3));
        let wb = V3::var(wb, 12 + 6 * slot + 3);
        let mut d = DKin {
            r: V3::var(b.r, 6 * slot),
            a: b.a,
            dphi,
            v: V3::var(v, 12 + 6 * slot),
            w: V3::cst(Vector3::zeros()),
        };
        d.w = d.vec(wb);
        d
    }
    /// World form A u of a body-frame vector u.
    fn vec(&self, u: V3) -> V3 {
        let au = V3::rot(&self.a, u);
        au + self.dphi.cross(au)
    }
    fn vecc(&self, s: &Vector3<f64>) -> V3 {
        self.vec(V3::cst(*s))
    }
    fn point(&self, s: &Vector3<f64>) -> V3 {
        self.r + self.vecc(s)
    }
    fn point_velocity(&self, p: V3) -> V3 {
        self.v + self.w.cross(p - self.r)
    }
    /// Body-frame form Aᵀ m of a world vector m.
    fn in_body(&self, m: V3) -> V3 {
        V3::rot(&self.a.transpose(), m - self.dphi.cross(m))
    }
}

/// The pair of bodies of an element, seeded.
struct Pair {
    bodies: [usize; 2],
    k: [DKin; 2],
}

impl Pair {
    fn new(kin: &Kinematics, i: usize, j: usize, vel: Option<&[f64]>) -> Self {
        let of = |k: usize| {
            vel.filter(|_| k != GROUND).map(|u| {
                [
                    Vector3::new(u[6 * k], u[6 * k + 1], u[6 * k + 2]),
                    Vector3::new(u[6 * k + 3], u[6 * k + 4], u[6 * k + 5]),
                ]
            })
        };
        Self::with(kin, [i, j], [of(i), of(j)])
    }
    /// The pair with the velocities (ṙ, ω_body) of each body given (the state's when None).
    fn with(kin: &Kinematics, bodies: [usize; 2], vel: [Option<[Vector3<f64>; 2]>; 2]) -> Self {
        Pair {
            bodies,
            k: [
                DKin::seed(kin, bodies[0], 0, vel[0]),
                DKin::seed(kin, bodies[1], 1, vel[1]),
            ],
        }
    }
}

/// ∂Q/∂x and ∂Q/∂v (row-major nv × nv) being accumulated.
pub(crate) struct QBlocks<'a> {
    pub(crate) qx: &'a mut [f64],
    pub(crate) qv: &'a mut [f64],
    pub(crate) nv: usize,
}

/// Add the gradient `g` of an element quantity into `row` of an x block and a v block.
fn scatter(g: &[f64; N], bodies: [usize; 2], x: &mut [f64], v: &mut [f64]) {
    for (s, &b) in bodies.iter().enumerate() {
        if b == GROUND {
            continue;
        }
        for d in 0..6 {
            x[6 * b + d] += g[6 * s + d];
            v[6 * b + d] += g[12 + 6 * s + d];
        }
    }
}

impl QBlocks<'_> {
    /// Add the gradients of Q_k (6 entries) of body `slot` of the pair.
    fn add(&mut self, p: &Pair, slot: usize, q: [S; 6]) {
        let k = p.bodies[slot];
        if k == GROUND {
            return;
        }
        let nv = self.nv;
        for (c, qc) in q.iter().enumerate() {
            let row = (6 * k + c) * nv;
            let (x, v) = (&mut self.qx[row..row + nv], &mut self.qv[row..row + nv]);
            scatter(&qc.g, p.bodies, x, v);
        }
    }
    /// A world force f at the world point at on body `slot` (as [`super::kin::add_force`]).
    fn force(&mut self, p: &Pair, slot: usize, at: V3, f: V3) {
        let m = p.k[slot].in_body((at - p.k[slot].r).cross(f));
        self.add(p, slot, [f.0[0], f.0[1], f.0[2], m.0[0], m.0[1], m.0[2]]);
    }
    /// A world torque m on body `slot` (as [`super::kin::add_torque`]).
    fn torque(&mut self, p: &Pair, slot: usize, m: V3) {
        let mb = p.k[slot].in_body(m);
        let z = S::cst(0.0);
        self.add(p, slot, [z, z, z, mb.0[0], mb.0[1], mb.0[2]]);
    }

    /// The gyroscopic moment −ω × Jω of body k (body frame): only ∂/∂ω.
    pub(crate) fn gyroscopic(&mut self, kin: &Kinematics, k: usize, j: &Matrix3<f64>) {
        let p = Pair::new(kin, k, GROUND, None);
        let wb = p.k[0].in_body(p.k[0].w);
        let m = -wb.cross(V3::rot(j, wb));
        let z = S::cst(0.0);
        self.add(&p, 0, [z, z, z, m.0[0], m.0[1], m.0[2]]);
    }
}

impl Force3 {
    /// Add ∂Q/∂x and ∂Q/∂v of the element (the dual form of [`Force3::apply`]).
    pub(crate) fn jacobian(&self, kin: &Kinematics, t: f64, out: &mut QBlocks) {
        match self {
            Force3::Line {
                i,
                si,
                j,
                sj,
                k,
                c,
                l0,
                push,
            } => {
                let p = Pair::new(kin, *i, *j, None);
                let (pi, pj) = (p.k[0].point(si), p.k[1].point(sj));
                let d = pj - pi;
                let l = d.norm();
                if l.v <= 0.0 {
                    return;
                }
                let u = d.scale(S::cst(1.0) / l);
                let ld = u.dot(p.k[1].point_velocity(pj) - p.k[0].point_velocity(pi));
                let tension = match push {
                    Some(f) => S::cst(-f.eval(t)[0]),
                    None => (l + -*l0) * *k + ld * *c,
                };
                out.force(&p, 0, pi, u.scale(tension));
                out.force(&p, 1, pj, -u.scale(tension));
            }
            Force3::Rotational {
                i,
                j,
                xi,
                yi,
                xj,
                k,
                c,
                theta0,
            } => {
                let p = Pair::new(kin, *i, *j, None);
                let (th, z) = joint_angle(&p, xi, yi, xj);
                let thd = z.dot(p.k[1].w - p.k[0].w);
                let wrapped = th + (wrap(th.v - theta0) - (th.v - theta0) - theta0);
                let tau = wrapped * -*k - thd * *c;
                out.torque(&p, 1, z.scale(tau));
                out.torque(&p, 0, -z.scale(tau));
            }
            Force3::Bushing {
                i,
                si,
                j,
                sj,
                rel0,
                kt,
                ct,
                kr,
                cr,
            } => {
                let p = Pair::new(kin, *i, *j, None);
                let (ki, kj) = (&p.k[0], &p.k[1]);
                let (pi, pj) = (ki.point(si), kj.point(sj));
                let dx = ki.in_body(pj - pi);
                let dv = ki.in_body(kj.point_velocity(pj) - ki.point_velocity(pi));
                let dphi = bushing_rotation(&p, rel0);
                let dw = ki.in_body(kj.w - ki.w);
                let f = ki.vec(-dx.cmul(kt) - dv.cmul(ct));
                let m = ki.vec(-dphi.cmul(kr) - dw.cmul(cr));
                out.force(&p, 1, pj, f);
                out.force(&p, 0, pj, -f);
                out.torque(&p, 1, m);
                out.torque(&p, 0, -m);
            }
            Force3::Point {
                i,
                si,
                body_frame,
                f,
            } => {
                let p = Pair::new(kin, *i, GROUND, None);
                let at = p.k[0].point(si);
                let fw = vec_of(f, t);
                let fw = if *body_frame {
                    p.k[0].vecc(&fw)
                } else {
                    V3::cst(fw)
                };
                out.force(&p, 0, at, fw);
            }
            Force3::Torque { i, body_frame, m } => {
                let p = Pair::new(kin, *i, GROUND, None);
                let mw = vec_of(m, t);
                let mw = if *body_frame {
                    p.k[0].vecc(&mw)
                } else {
                    V3::cst(mw)
                };
                out.torque(&p, 0, mw);
            }
        }
    }
}

/// The joint angle θ of x_j about z_i from x_i and z_i (world), in dual numbers.
fn joint_angle(p: &Pair, xi: &Vector3<f64>, yi: &Vector3<f64>, xj: &Vector3<f64>) -> (S, V3) {
    let xjw = p.k[1].vecc(xj);
    let (xiw, yiw) = (p.k[0].vecc(xi), p.k[0].vecc(yi));
    (atan2(xjw.dot(yiw), xjw.dot(xiw)), xiw.cross(yiw))
}

/// The bushing's rotation vector φ = log(A_iᵀ A_j rel0ᵀ) with its gradient: a right
/// perturbation ψ of R = A_iᵀ A_j rel0ᵀ moves φ by J_r⁻¹(φ)ψ (module docs); δθ_j gives
/// ψ = rel0 δθ_j and δθ_i gives ψ = −Rᵀ δθ_i.
fn bushing_rotation(p: &Pair, rel0: &Matrix3<f64>) -> V3 {
    let r = p.k[0].a.transpose() * p.k[1].a * rel0.transpose();
    let phi = log_map(&r);
    let th = phi.norm();
    let k = phi.cross_matrix();
    let c2 = if th < 1e-4 {
        1.0 / 12.0 + th * th / 720.0
    } else {
        1.0 / (th * th) - (1.0 + th.cos()) / (2.0 * th * th.sin())
    };
    let jinv = Matrix3::identity() + 0.5 * k + c2 * k * k;
    let (gj, gi) = (jinv * rel0, -jinv * r.transpose());
    let mut out = V3::cst(phi);
    for (slot, gm) in [(0, gi), (1, gj)] {
        if p.bodies[slot] == GROUND {
            continue;
        }
        for c in 0..3 {
            for d in 0..3 {
                out.0[c].g[6 * slot + 3 + d] = gm[(c, d)];
            }
        }
    }
    out
}

impl Sphere {
    /// Add ∂Q/∂x and ∂Q/∂v of the contact pair (the dual form of [`Sphere::apply`], stateless
    /// friction; nothing for LuGre, whose models use finite differences).
    pub(crate) fn jacobian(&self, kin: &Kinematics, memory: &mut ContactMemory, out: &mut QBlocks) {
        let p = Pair::new(kin, self.i, self.j, None);
        let (ki, kj) = (&p.k[0], &p.k[1]);
        let (pi, pj) = (ki.point(&self.si), kj.point(&self.sj));
        let e = pj - pi;
        let len = e.norm();
        if len.v <= 0.0 || len.v - self.clearance() <= 0.0 {
            return;
        }
        let n = e.scale(S::cst(1.0) / len);
        let (qi, qj) = (pi + n * self.r_socket, pj + n * self.r_ball);
        let v = kj.point_velocity(qj) - ki.point_velocity(qi);
        let rate = v.dot(n);
        let delta = len + -self.clearance();
        let vdm = memory.impact_velocity(self.memory, delta.v, rate.v);
        let (f, fd, fr) = self.law.force_with_derivatives(delta.v, rate.v, vdm);
        let mut fn_ = S::cst(f);
        for k in 0..N {
            fn_.g[k] = fd * delta.g[k] + fr * rate.g[k];
        }
        let slip = v - n.scale(rate);
        let speed = slip.norm();
        let ft = match &self.friction {
            Some(ContactFriction::Static(law)) if speed.v > 0.0 => {
                let (phi, dphi_ds, dphi_df) = law.force_with_derivatives(speed.v, fn_.v);
                let mut mag = S::cst(phi);
                for k in 0..N {
                    mag.g[k] = dphi_ds * speed.g[k] + dphi_df * fn_.g[k];
                }
                slip.scale(mag / speed)
            }
            _ => V3::cst(Vector3::zeros()),
        };
        let f_ball = -n.scale(fn_) + ft;
        let mid = (qi + qj) * 0.5;
        out.force(&p, 1, mid, f_ball);
        out.force(&p, 0, mid, -f_ball);
    }
}

impl Journal {
    /// Add ∂Q/∂x and ∂Q/∂v of the journal joint (the dual form of [`Journal::apply`]): the
    /// joint's world state built from the seeded pair, clr-contact's geometry and forces run in
    /// the dual numbers (its deepest points, wetted-region ends and journal ends follow the
    /// implicit-function rule of their Newton and fixed-point solves, the laws enter through
    /// their closed-form derivatives), the impact velocities δ̇⁻ held fixed. A state out of the
    /// joint's range adds nothing (the right-hand side is NaN there and the step is rejected).
    pub(crate) fn jacobian(&self, kin: &Kinematics, memory: &mut ContactMemory, out: &mut QBlocks) {
        let p = Pair::new(kin, self.i, self.j, None);
        let (ki, kj) = (&p.k[0], &p.k[1]);
        let (ob, oj) = (ki.point(&self.si), kj.point(&self.sj));
        let c = |v: V3| CV3(v.0);
        let state = JournalState {
            bearing_centre: c(ob),
            bearing_axis: c(ki.vecc(&self.ui)),
            bearing_velocity: c(ki.point_velocity(ob)),
            bearing_angular_velocity: c(ki.w),
            journal_centre: c(oj),
            journal_axis: c(kj.vecc(&self.uj)),
            journal_velocity: c(kj.point_velocity(oj)),
            journal_angular_velocity: c(kj.w),
        };
        let Ok(geo) = self.joint.geometry(&state) else {
            return;
        };
        let f = geo.forces_with_memory(&self.laws, memory, self.memory);
        let (mut force, mut mj, mut mi) = (f.force, f.journal_moment, f.bearing_moment);
        // the film's loads, generic in the same dual numbers (clr-contact journal_film)
        // at an exactly centred and aligned journal |e| has no derivative (non-finite dual
        // parts): Newton then goes without the film's block for that iteration
        let film = self.film.as_ref().map(|film| film.loads(&state));
        if let Some(Ok(l)) = film.filter(|l| l.as_ref().is_ok_and(finite_gradient)) {
            force = force + l.force;
            mj = mj + l.journal_moment;
            mi = mi + l.bearing_moment;
        }
        let force = V3(force.0);
        out.force(&p, 1, oj, force);
        out.torque(&p, 1, V3(mj.0));
        out.force(&p, 0, ob, -force);
        out.torque(&p, 0, V3(mi.0));
    }
}

/// Whether every derivative of the film's loads is finite.
fn finite_gradient<const N: usize>(l: &clr_contact::journal_film::FilmLoads<D<N>>) -> bool {
    [&l.force, &l.journal_moment, &l.bearing_moment]
        .iter()
        .flat_map(|v| v.0.iter())
        .all(|d| d.v.is_finite() && d.g.iter().all(|x| x.is_finite()))
}

/// The x- and v-gradients of the constraint rows at one state (row-major m × nv each).
pub(crate) struct RowBlocks<'a> {
    /// ∂(G v)/∂x at the state's v.
    pub(crate) gv_x: &'a mut [f64],
    /// ∂(G a)/∂x at the given a.
    pub(crate) ga_x: &'a mut [f64],
    /// ∂Φ_t/∂x.
    pub(crate) phit_x: &'a mut [f64],
    /// ∂γ/∂x and ∂γ/∂v.
    pub(crate) gamma_x: &'a mut [f64],
    pub(crate) gamma_v: &'a mut [f64],
    /// ∂(Gᵀλ)/∂x at the multipliers λ (nv × nv): the geometric stiffness.
    pub(crate) gtl_x: &'a mut [f64],
    pub(crate) nv: usize,
}

/// One row's G·u (without Φ_t), Φ_t and γ in dual numbers.
#[derive(Clone, Copy)]
struct RowD {
    gu: S,
    phit: S,
    gamma: S,
}

/// Dot product a·b of vectors on bodies i and j, its rate (at the pair's velocities) and the
/// acceleration terms h (as `constraint::dot`).
fn ddot(a: V3, b: V3, p: &Pair) -> (S, S, S) {
    let (wi, wj) = (p.k[0].w, p.k[1].w);
    let (ad, bd) = (wi.cross(a), wj.cross(b));
    (
        a.dot(b),
        ad.dot(b) + a.dot(bd),
        wi.cross(ad).dot(b) + ad.dot(bd) * 2.0 + a.dot(wj.cross(bd)),
    )
}

impl Prim {
    /// Rows of the primitive in dual numbers at the pair's velocities (G u with u those
    /// velocities, Φ_t, γ); `n` rows are written into `out`.
    fn rows_dual(&self, p: &Pair, t: f64, motions: &[TimeFn], out: &mut [RowD; 3]) {
        let (ki, kj) = (&p.k[0], &p.k[1]);
        let z = S::cst(0.0);
        match &self.kind {
            PrimKind::Coincide { si, sj } => {
                let (bi, bj) = (ki.vecc(si), kj.vecc(sj));
                let gu = ki.v + ki.w.cross(bi) - kj.v - kj.w.cross(bj);
                let gam = -(ki.w.cross(ki.w.cross(bi)) - kj.w.cross(kj.w.cross(bj)));
                for (c, o) in out.iter_mut().enumerate() {
                    *o = RowD {
                        gu: gu.0[c],
                        phit: z,
                        gamma: gam.0[c],
                    };
                }
            }
            PrimKind::Dot1 { ai, aj } => {
                let (_, rate, h) = ddot(ki.vecc(ai), kj.vecc(aj), p);
                out[0] = RowD {
                    gu: rate,
                    phit: z,
                    gamma: -h,
                };
            }
            PrimKind::Dot2 {
                ai, si, sj, motion, ..
            } => {
                let f = motion.map_or([0.0; 3], |m| motions[m].eval(t));
                let a = ki.vecc(ai);
                let (bi, bj) = (ki.vecc(si), kj.vecc(sj));
                let d = kj.r + bj - ki.r - bi;
                let ad = ki.w.cross(a);
                let dd = kj.v + kj.w.cross(bj) - ki.v - ki.w.cross(bi);
                let acc = kj.w.cross(kj.w.cross(bj)) - ki.w.cross(ki.w.cross(bi));
                let h = ki.w.cross(ad).dot(d) + ad.dot(dd) * 2.0 + a.dot(acc);
                out[0] = RowD {
                    gu: ad.dot(d) + a.dot(dd),
                    phit: S::cst(-f[1]),
                    gamma: -h + f[2],
                };
            }
            PrimKind::Angle { xi, yi, xj, motion } => {
                let [f, fd, fdd] = motions[*motion].eval(t);
                let (s, c) = f.sin_cos();
                let xjw = kj.vecc(xj);
                let (p1, r1, h1) = ddot(ki.vecc(yi), xjw, p);
                let (p2, r2, h2) = ddot(ki.vecc(xi), xjw, p);
                let (cd, sd) = (-s * fd, c * fd);
                let (cdd, sdd) = (-c * fd * fd - s * fdd, -s * fd * fd + c * fdd);
                out[0] = RowD {
                    gu: r1 * c - r2 * s,
                    phit: p1 * cd - p2 * sd,
                    gamma: -(h1 * c - h2 * s + (r1 * cd - r2 * sd) * 2.0 + p1 * cdd - p2 * sdd),
                };
            }
        }
    }

    /// Add the x- and v-gradients of the primitive's rows (G v, G a, Φ_t, γ) into `out`.
    pub(crate) fn jacobian(
        &self,
        kin: &Kinematics,
        t: f64,
        motions: &[TimeFn],
        (acc, lambda): (&[f64], &[f64]),
        out: &mut RowBlocks,
    ) {
        let z = S::cst(0.0);
        let mut at_v = [RowD {
            gu: z,
            phit: z,
            gamma: z,
        }; 3];
        let mut at_a = at_v;
        self.rows_dual(&Pair::new(kin, self.i, self.j, None), t, motions, &mut at_v);
        let pa = Pair::new(kin, self.i, self.j, Some(acc));
        self.rows_dual(&pa, t, motions, &mut at_a);
        let nv = out.nv;
        let bodies = [self.i, self.j];
        for k in 0..self.rows() {
            let o = (self.row + k) * nv;
            let row = o..o + nv;
            scatter_x(&at_v[k].gu.g, bodies, &mut out.gv_x[row.clone()]);
            scatter_x(&at_a[k].gu.g, bodies, &mut out.ga_x[row.clone()]);
            scatter_x(&at_v[k].phit.g, bodies, &mut out.phit_x[row.clone()]);
            scatter(
                &at_v[k].gamma.g,
                bodies,
                &mut out.gamma_x[row.clone()],
                &mut out.gamma_v[row],
            );
        }
        self.geometric_stiffness(kin, t, motions, lambda, out);
    }

    /// Add ∂(Gᵀλ)/∂x: row 6b + d of Gᵀλ is Σ_r λ_r G[r, 6b + d], and G[r, 6b + d] is the rate
    /// G u of the rows at the unit velocity u = e_{6b+d}, whose x-gradient the dual numbers give.
    fn geometric_stiffness(
        &self,
        kin: &Kinematics,
        t: f64,
        motions: &[TimeFn],
        lambda: &[f64],
        out: &mut RowBlocks,
    ) {
        let nv = out.nv;
        let bodies = [self.i, self.j];
        let z = S::cst(0.0);
        let mut rows = [RowD {
            gu: z,
            phit: z,
            gamma: z,
        }; 3];
        for (slot, &b) in bodies.iter().enumerate() {
            if b == GROUND {
                continue;
            }
            for d in 0..6 {
                let mut u = [Vector3::zeros(); 2];
                u[d / 3][d % 3] = 1.0;
                let mut vel = [Some([Vector3::zeros(); 2]); 2];
                vel[slot] = Some(u);
                self.rows_dual(&Pair::with(kin, bodies, vel), t, motions, &mut rows);
                let o = (6 * b + d) * nv;
                for (k, row) in rows.iter().enumerate().take(self.rows()) {
                    let l = lambda[self.row + k];
                    let g = row.gu.g.map(|x| x * l);
                    scatter_x(&g, bodies, &mut out.gtl_x[o..o + nv]);
                }
            }
        }
    }
}

/// Add only the x part of a gradient.
fn scatter_x(g: &[f64; N], bodies: [usize; 2], x: &mut [f64]) {
    for (s, &b) in bodies.iter().enumerate() {
        if b == GROUND {
            continue;
        }
        for d in 0..6 {
            x[6 * b + d] += g[6 * s + d];
        }
    }
}
