//! Analytic ∂Q/∂q and ∂Q/∂q̇ of the rigid contact elements: the revolute clearance joint, the
//! translational clearance joint (slider corners against the guide faces) and shape contact
//! pairs.
//!
//! Each element's generalized forces are re-evaluated in first-order dual numbers
//! ([`super::dual`]) seeded with the coordinates and velocities of its two frames, following the
//! kinematics clr-contact evaluates (same formulas, same order), so the gradients are the exact
//! partial derivatives of the forces the model applies. The laws enter through their closed-form
//! derivatives ([`law_forces`]); the impact velocity δ̇⁻ of the contact memory is a constant.

use clr_contact::translational::{GuideSide, TranslationalClearance};
use clr_contact::RevoluteClearance;
use clr_contact::{
    BodyState, ContactMemory, Feature, ForceApplication, FrictionLaw, NormalLaw, ShapeContactPoint,
};
use nalgebra::Vector2;

use super::dual::{DBody, D, V};
use crate::clearance::Clearance;
use crate::runtime::{Frame, GROUND_ID};
use crate::shape_pair::ShapePair;

/// Directions of a two-frame element: frame i (q then q̇) at 0..6, frame j at 6..12.
const N: usize = 12;

/// ∂Q/∂q and ∂Q/∂q̇ under assembly (row-major n × n) with the frames that place rows and
/// columns in q.
pub(super) struct Out<'a> {
    pub(super) frames: &'a [Frame],
    pub(super) n: usize,
    pub(super) dq: &'a mut [f64],
    pub(super) dv: &'a mut [f64],
}

impl Out<'_> {
    /// Add `w`·g to row `row`: g is a gradient over frames seeded as `seeds` = (frame, first
    /// direction), each frame's q at directions o..o + 3 (→ ∂Q/∂q) and q̇ at o + 3..o + 6
    /// (→ ∂Q/∂q̇). Ground seeds and constrained DOF of beam-node frames have no column.
    pub(super) fn add_row<const M: usize>(
        &mut self,
        row: usize,
        w: f64,
        g: &[f64; M],
        seeds: &[(usize, usize)],
    ) {
        for &(k, o) in seeds {
            if k == GROUND_ID {
                continue;
            }
            for (d, c) in self.frames[k].cols.iter().enumerate() {
                if let Some(c) = c {
                    self.dq[row * self.n + c] += w * g[o + d];
                    self.dv[row * self.n + c] += w * g[o + 3 + d];
                }
            }
        }
    }

    /// Add the gradients of the generalized force `f` = (f_x, f_y, m) on frame `b`.
    pub(super) fn add_frame<const M: usize>(
        &mut self,
        b: usize,
        f: &[D<M>; 3],
        seeds: &[(usize, usize)],
    ) {
        if b == GROUND_ID {
            return;
        }
        for (d, r) in self.frames[b].cols.iter().enumerate() {
            if let Some(r) = *r {
                self.add_row(r, 1.0, &f[d].g, seeds);
            }
        }
    }
}

/// (F_N, F_T, ∂F_T/∂F_N) with F_N, F_T as duals, from the penetration δ, its rate δ̇ = v_N and
/// the slip v_T: F_N = F_e(δ)(1 + χδ̇/δ̇⁻) with ∂F_N/∂δ, ∂F_N/∂δ̇ from
/// [`NormalLaw::force_with_derivatives`] (δ̇⁻ = `vm` held fixed: it is contact memory, not a
/// function of the state) and F_T = μ(v_T)F_N with ∂F_T/∂v_T, ∂F_T/∂F_N from
/// [`FrictionLaw::force_with_derivatives`]. The values are bit for bit those of `force`.
pub(super) fn law_forces<const M: usize>(
    normal: &NormalLaw,
    friction: &FrictionLaw,
    [delta, vn, vt]: [D<M>; 3],
    vm: f64,
) -> (D<M>, D<M>, f64) {
    let (f, f_d, f_v) = normal.force_with_derivatives(delta.v, vn.v, vm);
    let f_n = delta.chain(f, f_d) + vn.chain(0.0, f_v);
    let (t, t_v, t_n) = friction.force_with_derivatives(vt.v, f);
    let f_t = vt.chain(t, t_v) + f_n.chain(0.0, t_n);
    (f_n, f_t, t_n)
}

/// Revolute clearance joint: journal (frame j) in bearing (frame i). Kinematics of Flores,
/// Ambrósio, Claro & Lankarani, Comput. Struct. 82 (2004) 1359, and Flores et al. 2008 (*Kinematics
/// and Dynamics of Multibody Systems with Imperfect Joints*, ch. 4): e = r_j^P − r_i^P,
/// n = e/|e|, δ = |e| − c, contact points r_k^Q = r_k^P + R_k n, relative velocity
/// v = ṙ_j^Q − ṙ_i^Q, δ̇ = v·n, v_T = v·t (t = k̂ × n); f_j = −F_N n + F_T t at the contact
/// points or at their midpoint (`ForceApplication`), f_i = −f_j (Lankarani & Nikravesh, J. Mech.
/// Des. 112 (1990) 369 for the normal law). Nothing without penetration.
pub(super) fn revolute(
    cl: &Clearance,
    g: &RevoluteClearance,
    application: ForceApplication,
    [si, sj]: [&BodyState; 2],
    memory: &mut ContactMemory,
    out: &mut Out,
) {
    let bi = DBody::<N>::seed(si, Some(0));
    let bj = DBody::<N>::seed(sj, Some(6));
    // a lubricated joint: the film force, then the dry laws weighted by w(h_min)
    let weight = cl
        .film
        .as_ref()
        .map(|film| film_force(cl, film, g, [si, sj], [&bi, &bj], out));
    let pi = bi.point(g.bearing_centre());
    let pj = bj.point(g.journal_centre());
    let e = pj - pi;
    let len = e.norm();
    // the no-contact branch (also where n is undefined, e = 0): Q = 0, derivatives 0
    if !(len.v > f64::MIN_POSITIVE && len.v.is_finite()) || len.v - g.clearance() <= 0.0 {
        return;
    }
    let delta = len + -g.clearance();
    let n = e.scale(D::cst(1.0) / len);
    let t = n.perp();
    let qi = pi + n * g.bearing_radius();
    let qj = pj + n * g.journal_radius();
    let v = bj.point_velocity(qj) - bi.point_velocity(qi);
    let (vn, vt) = (v.dot(n), v.dot(t));
    let vm = memory.impact_velocity(cl.mem, delta.v, vn.v);
    let (f_n, f_t, _) = law_forces(&cl.normal, &cl.friction, [delta, vn, vt], vm);
    let mut fj = n.scale(-f_n) + t.scale(f_t);
    if let Some(w) = weight {
        fj = fj.scale(w);
    }
    let (ai, aj) = match application {
        ForceApplication::ContactPoints => (qi, qj),
        ForceApplication::CommonPoint => {
            let mid = (qi + qj) * 0.5;
            (mid, mid)
        }
    };
    let seeds = [(cl.i, 0), (cl.j, 6)];
    out.add_frame(cl.i, &[-fj.x, -fj.y, (ai - bi.r).cross(-fj)], &seeds);
    out.add_frame(cl.j, &[fj.x, fj.y, (aj - bj.r).cross(fj)], &seeds);
}

/// The oil film of a lubricated revolute joint (clr-contact `HydrodynamicBearing`, the same
/// kinematics as `HydrodynamicBearing::kinematics`): ε = |e|/c, ε̇ = ė·n/c, γ̇ = (ė·t)/|e|,
/// Ω = ω_i + ω_j − 2γ̇, carried as dual numbers; the film force F(ε, ε̇, Ω) enters through its
/// exact local partials (`HydrodynamicBearing::film_force`: the ε column is zero where the
/// force is frozen beyond ε_t), F = F_r n + F_t t on the journal at its centre and −F on the
/// bearing on the same line, and the shear torque ±T_j ([`shear_torque`]) on journal and
/// bearing. Returns the dry laws' weight w(h_min) as a dual number.
fn film_force(
    cl: &Clearance,
    film: &crate::clearance::Film,
    g: &RevoluteClearance,
    [si, sj]: [&BodyState; 2],
    [bi, bj]: [&DBody<N>; 2],
    out: &mut Out,
) -> D<N> {
    let c = film.bearing.clearance();
    let pi = bi.point(g.bearing_centre());
    let pj = bj.point(g.journal_centre());
    let e = pj - pi;
    let len = e.norm();
    let h_min = -len + c;
    let tr = &film.transition;
    let weight = variation(h_min) * tr.dry_weight_derivative(h_min.v) + tr.dry_weight(h_min.v);
    let seeds = [(cl.i, 0), (cl.j, 6)];
    // at coincident centres the line of centres (and γ̇) is undefined: the force is that of
    // clr-contact's evaluation, its derivatives there are left out (a simplified Newton
    // matrix); the Petroff torque T_C(0, ω_j − ω_i) keeps its ω-derivative
    if !(len.v > f64::MIN_POSITIVE && len.v.is_finite()) {
        let (tc, _, d_w) = film
            .bearing
            .couette_torque(0.0, sj.angular_velocity - si.angular_velocity);
        let torque = variation(bj.w - bi.w) * d_w + tc;
        out.add_frame(cl.i, &[D::cst(0.0), D::cst(0.0), -torque], &seeds);
        out.add_frame(cl.j, &[D::cst(0.0), D::cst(0.0), torque], &seeds);
        return weight;
    }
    let n = e.scale(D::cst(1.0) / len);
    let t = n.perp();
    let e_dot = bj.point_velocity(pj) - bi.point_velocity(pi);
    let eps = len * (1.0 / c);
    let rate = e_dot.dot(n) * (1.0 / c);
    let omega = bi.w + bj.w - (e_dot.dot(t) / len) * 2.0;
    // the force and its local partials at this state, as the right-hand side evaluates them
    let kin = film
        .bearing
        .kinematics(g.bearing_centre(), g.journal_centre(), si, sj);
    let (f, jac, eps_eff) = film.bearing.film_force(&kin, tr);
    let comp = |v: f64, de: f64, dr: f64, dw: f64| {
        variation(eps) * de + variation(rate) * dr + variation(omega) * dw + v
    };
    let fr = comp(
        f.radial,
        jac.d_eccentricity_ratio.radial,
        jac.d_eccentricity_rate.radial,
        jac.d_wedge_speed.radial,
    );
    let ft = comp(
        f.tangential,
        jac.d_eccentricity_ratio.tangential,
        jac.d_eccentricity_rate.tangential,
        jac.d_wedge_speed.tangential,
    );
    let fj = n.scale(fr) + t.scale(ft);
    let torque = shear_torque(film, (eps, eps_eff), bj.w - bi.w, ft, &kin);
    out.add_frame(
        cl.i,
        &[-fj.x, -fj.y, (pj - bi.r).cross(-fj) - torque],
        &seeds,
    );
    out.add_frame(cl.j, &[fj.x, fj.y, (pj - bj.r).cross(fj) + torque], &seeds);
    weight
}

/// The film's shear torque on the journal, T_j = T_C(ε, ω_j − ω_i) − (εc/2)F_t (clr-contact
/// `HydrodynamicBearing::shear_torques`), as a dual number: the Couette part through its local
/// partials (`couette_torque`), the pressure part as the product of duals. Beyond ε_t both are
/// evaluated at the frozen ε_t (no ε dependence), as the right-hand side does.
fn shear_torque(
    film: &crate::clearance::Film,
    (eps, eps_eff): (D<N>, f64),
    relative_w: D<N>,
    ft: D<N>,
    kin: &clr_contact::lubrication::FilmKinematics,
) -> D<N> {
    let clamped = eps_eff < kin.eccentricity_ratio;
    let eps = if clamped { D::cst(eps_eff) } else { eps };
    let (tc, d_eps, d_w) = film
        .bearing
        .couette_torque(eps_eff, kin.relative_angular_velocity);
    let couette = variation(eps) * d_eps + variation(relative_w) * d_w + tc;
    couette - eps * ft * (0.5 * film.bearing.clearance())
}

/// The derivative part of `x` (value 0): `variation(x) * k + v` is the first-order expansion
/// v + k·dx of a function whose partial with respect to x is k.
fn variation(x: D<N>) -> D<N> {
    x + -x.v
}

/// Translational clearance joint: slider (frame j) between the faces y = ±W/2 of the guide
/// frame on frame i (Flores, Ambrósio, Claro & Lankarani, J. Comput. Nonlinear Dyn. 3 (2008)
/// 011007): per penetrating corner p, y = (p − o)·a_y, δ = y − W/2 (upper, n = a_y) or
/// −W/2 − y (lower, n = −a_y), guide point p − δn, v = ṗ − ṙ_guide(p − δn), δ̇ = v·n,
/// v_T = v·t; −F_N n + F_T t on the slider at p, the opposite on the guide at p − δn.
#[allow(clippy::too_many_arguments)]
pub(super) fn translational(
    cl: &Clearance,
    geometry: &TranslationalClearance,
    (origin, angle, width): (Vector2<f64>, f64, f64),
    [si, sj]: [&BodyState; 2],
    memory: &mut ContactMemory,
    out: &mut Out,
) {
    // which corners touch and on which face: the branch of the evaluation at this state
    let contact = geometry.contact(si, sj);
    let bi = DBody::<N>::seed(si, Some(0));
    let bj = DBody::<N>::seed(sj, Some(6));
    let o = bi.point(origin);
    let ay = V::cst(Vector2::new(-angle.sin(), angle.cos())).rot(bi.th);
    let half = 0.5 * width;
    let seeds = [(cl.i, 0), (cl.j, 6)];
    for c in contact.active() {
        let p = bj.point(geometry.slider().body_corner(c.corner));
        let y = (p - o).dot(ay);
        let (delta, n) = match c.side {
            GuideSide::Upper => (y + -half, ay),
            GuideSide::Lower => (-y + -half, -ay),
        };
        let gp = p - n.scale(delta);
        let v = bj.point_velocity(p) - bi.point_velocity(gp);
        let t = n.perp();
        let (vn, vt) = (v.dot(n), v.dot(t));
        let vm = memory.impact_velocity(cl.mem + c.corner, delta.v, vn.v);
        let (f_n, f_t, _) = law_forces(&cl.normal, &cl.friction, [delta, vn, vt], vm);
        let f = n.scale(-f_n) + t.scale(f_t);
        out.add_frame(cl.j, &[f.x, f.y, (p - bj.r).cross(f)], &seeds);
        out.add_frame(cl.i, &[-f.x, -f.y, (gp - bi.r).cross(-f)], &seeds);
    }
}

/// Shape contact pair (`crate::shape_pair`): at each penetrating point, f = F_N n + F_T t on B at
/// p_B and −f on A at p_A, with δ, n, p_A, p_B carried as dual numbers through a local model of
/// the two features that touch ([`point_geometry`]). The points, their features and slots are
/// those the force evaluation finds at this state; the feature pair is held fixed, as parry's
/// answer is piecewise in it.
pub(super) fn shapes(
    cl: &Clearance,
    pair: &ShapePair,
    [si, sj]: [&BodyState; 2],
    memory: &mut ContactMemory,
    out: &mut Out,
) {
    let bi = DBody::<N>::seed(si, Some(0));
    let bj = DBody::<N>::seed(sj, Some(6));
    let seeds = [(cl.i, 0), (cl.j, 6)];
    pair.with_points(si, sj, |kept| {
        for k in kept.iter().filter(|k| k.point.depth > 0.0) {
            let (delta, n, pa, pb) = point_geometry(&k.point, [si, sj], [&bi, &bj]);
            let v = bj.point_velocity(pb) - bi.point_velocity(pa);
            let t = n.perp();
            let (vn, vt) = (-v.dot(n), v.dot(t));
            let vm = memory.impact_velocity(cl.mem + k.slot, delta.v, vn.v);
            let (f_n, f_t, _) = law_forces(&cl.normal, &cl.friction, [delta, vn, vt], vm);
            let f = n.scale(f_n) + t.scale(f_t);
            out.add_frame(cl.j, &[f.x, f.y, (pb - bj.r).cross(f)], &seeds);
            out.add_frame(cl.i, &[-f.x, -f.y, (pa - bi.r).cross(-f)], &seeds);
        }
    });
}

/// (δ, n, p_A, p_B) of one contact point as functions of the two frames' coordinates. The core
/// features (`point_a − r_A n` on A, `point_b + r_B n` on B: a polygon vertex, a ball centre, a
/// point of a face) move as material points of their bodies, and
/// * two rounded vertices (balls): n along the line of centres, δ = r_A + r_B − |c_B − c_A|;
/// * a vertex of A on a face of B: n turns with B, δ = (c_A − c_B)·n + r_A + r_B;
/// * otherwise (a vertex of B on a face of A, or features parry did not name): n turns with A,
///   the same δ.
///
/// This is the exact signed distance of a vertex–face or ball–ball pair near the state, so
/// ∂Q/∂q is exact there; for a face sliding past a vertex of the same body it is first-order
/// (∂δ/∂q holds for any pair by the envelope theorem, the turning of n differs). ∂Q/∂q̇ is exact.
fn point_geometry(
    p: &ShapeContactPoint,
    [si, sj]: [&BodyState; 2],
    [bi, bj]: [&DBody<N>; 2],
) -> (D<N>, V<N>, V<N>, V<N>) {
    let (ra, rb, n0) = (p.radius_a, p.radius_b, p.normal);
    let ca = bi.point(si.to_local(p.point_a - n0 * ra));
    let cb = bj.point(sj.to_local(p.point_b + n0 * rb));
    let (va, vb) = (
        p.feature_a == Feature::Vertex,
        p.feature_b == Feature::Vertex,
    );
    if va && vb && ra + rb > 0.0 {
        let d = cb - ca;
        let len = d.norm();
        let n = d.scale(D::cst(1.0) / len);
        return (-len + (ra + rb), n, ca + n * ra, cb - n * rb);
    }
    let owner = if va && !vb { (sj, bj) } else { (si, bi) };
    let n = V::cst(clr_contact::body::rotate(-owner.0.angle, n0)).rot(owner.1.th);
    let delta = (ca - cb).dot(n) + (ra + rb);
    if va && !vb {
        let pa = ca + n * ra;
        (delta, n, pa, pa - n.scale(delta))
    } else {
        let pb = cb - n * rb;
        (delta, n, pb + n.scale(delta), pb)
    }
}
