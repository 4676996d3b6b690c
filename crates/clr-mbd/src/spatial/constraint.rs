//! Spatial constraint primitives, from which every ideal joint and driver is built (Haug,
//! *Computer Aided Kinematics and Dynamics of Mechanical Systems*, 1989, §9.2–9.4: the spherical,
//! dot-1 and dot-2 conditions; Nikravesh 1988, §7.3). Each gives its rows of Φ, of the velocity
//! Jacobian G (Φ̇ = G v + Φ_t with v = (ṙ, ω_body) per body), Φ_t and γ = −Ġv − Φ_tt (the
//! right-hand side of G v̇ = γ).
//!
//! Written with world vectors: for a body-fixed vector b = A s, ḃ = ω × b with the world
//! angular velocity ω = A ω_body, and ω̇ = A ω̇_body, so a coefficient c of ω in Φ̇ is the
//! coefficient Aᵀc of ω_body, and the terms of Φ̈ without accelerations give γ.

use nalgebra::Vector3;

use super::kin::{Kin, Kinematics, GROUND};
use crate::timefn::TimeFn;

/// One primitive (its rows follow each other from [`Prim::rows`]).
#[derive(Debug, Clone)]
pub(crate) enum PrimKind {
    /// r_i + A_i s_i − r_j − A_j s_j = 0 (3 rows).
    Coincide { si: Vector3<f64>, sj: Vector3<f64> },
    /// (A_i a_i)·(A_j a_j) = 0 (1 row): the two body vectors stay perpendicular.
    Dot1 { ai: Vector3<f64>, aj: Vector3<f64> },
    /// (A_i a_i)·d − d₀ − f(t) = 0 with d = r_j + A_j s_j − r_i − A_i s_i (1 row): b's point
    /// keeps its distance along a's vector.
    Dot2 {
        ai: Vector3<f64>,
        si: Vector3<f64>,
        sj: Vector3<f64>,
        offset: f64,
        motion: Option<usize>,
    },
    /// (x_j·y_i) cos f(t) − (x_j·x_i) sin f(t) = 0 (1 row): sin(θ − f) with θ the turn of x_j
    /// from x_i about z_i = x_i × y_i.
    Angle {
        xi: Vector3<f64>,
        yi: Vector3<f64>,
        xj: Vector3<f64>,
        motion: usize,
    },
}

/// A primitive between bodies i and j (either may be the ground).
#[derive(Debug, Clone)]
pub(crate) struct Prim {
    /// Index of the joint or driver it belongs to.
    pub(crate) owner: usize,
    pub(crate) i: usize,
    pub(crate) j: usize,
    pub(crate) kind: PrimKind,
    /// First row in Φ.
    pub(crate) row: usize,
}

impl Prim {
    /// Number of rows.
    pub(crate) fn rows(&self) -> usize {
        match self.kind {
            PrimKind::Coincide { .. } => 3,
            _ => 1,
        }
    }
}

/// Rows of Φ, G (row-major, `nv` columns), Φ_t and γ of the constraints, written by
/// [`Prim::eval`].
pub(crate) struct Rows<'a> {
    pub(crate) phi: &'a mut [f64],
    pub(crate) g: &'a mut [f64],
    pub(crate) phit: &'a mut [f64],
    pub(crate) gamma: &'a mut [f64],
    pub(crate) nv: usize,
}

impl Rows<'_> {
    /// Put the coefficients of row `r` for body k: `t` of ṙ_k and `w` of the world ω_k.
    #[inline]
    fn put(&mut self, r: usize, k: usize, b: &Kin, t: Vector3<f64>, w: Vector3<f64>) {
        if k == GROUND {
            return;
        }
        let wb = b.a.transpose() * w;
        let o = r * self.nv + 6 * k;
        for c in 0..3 {
            self.g[o + c] += t[c];
            self.g[o + 3 + c] += wb[c];
        }
    }
}

/// Dot product p = a·b of a vector a on body i and b on body j (world), its rate and the
/// acceleration terms h (p̈ = G v̇ + h): the dot-1 condition's pieces.
struct Dot {
    p: f64,
    rate: f64,
    h: f64,
    /// Coefficient of ω_i (world); that of ω_j is its negative.
    wi: Vector3<f64>,
}

fn dot(a: Vector3<f64>, b: Vector3<f64>, ki: &Kin, kj: &Kin) -> Dot {
    let ad = ki.w.cross(&a);
    let bd = kj.w.cross(&b);
    let axb = a.cross(&b);
    Dot {
        p: a.dot(&b),
        rate: ad.dot(&b) + a.dot(&bd),
        h: ki.w.cross(&ad).dot(&b) + 2.0 * ad.dot(&bd) + a.dot(&kj.w.cross(&bd)),
        wi: axb,
    }
}

impl Prim {
    /// Evaluate the rows at time t (G rows must be zero on entry).
    pub(crate) fn eval(&self, kin: &Kinematics, t: f64, motions: &[TimeFn], out: &mut Rows) {
        let (ki, kj) = (kin.get(self.i), kin.get(self.j));
        let r = self.row;
        match &self.kind {
            PrimKind::Coincide { si, sj } => {
                let (bi, bj) = (ki.a * si, kj.a * sj);
                let phi = ki.r + bi - kj.r - bj;
                let gam = -(ki.w.cross(&ki.w.cross(&bi)) - kj.w.cross(&kj.w.cross(&bj)));
                for c in 0..3 {
                    let e = Vector3::ith(c, 1.0);
                    out.phi[r + c] = phi[c];
                    out.phit[r + c] = 0.0;
                    out.gamma[r + c] = gam[c];
                    out.put(r + c, self.i, ki, e, bi.cross(&e));
                    out.put(r + c, self.j, kj, -e, -bj.cross(&e));
                }
            }
            PrimKind::Dot1 { ai, aj } => {
                let d = dot(ki.a * ai, kj.a * aj, ki, kj);
                out.phi[r] = d.p;
                out.phit[r] = 0.0;
                out.gamma[r] = -d.h;
                out.put(r, self.i, ki, Vector3::zeros(), d.wi);
                out.put(r, self.j, kj, Vector3::zeros(), -d.wi);
            }
            PrimKind::Dot2 {
                ai,
                si,
                sj,
                offset,
                motion,
            } => {
                let f = motion.map_or([0.0; 3], |m| motions[m].eval(t));
                let a = ki.a * ai;
                let (bi, bj) = (ki.a * si, kj.a * sj);
                let d = kj.r + bj - ki.r - bi;
                let ad = ki.w.cross(&a);
                let dd = kj.v + kj.w.cross(&bj) - ki.v - ki.w.cross(&bi);
                let acc = kj.w.cross(&kj.w.cross(&bj)) - ki.w.cross(&ki.w.cross(&bi));
                let h = ki.w.cross(&ad).dot(&d) + 2.0 * ad.dot(&dd) + a.dot(&acc);
                out.phi[r] = a.dot(&d) - offset - f[0];
                out.phit[r] = -f[1];
                out.gamma[r] = -h + f[2];
                out.put(r, self.i, ki, -a, a.cross(&(d + bi)));
                out.put(r, self.j, kj, a, bj.cross(&a));
            }
            PrimKind::Angle { xi, yi, xj, motion } => {
                let [f, fd, fdd] = motions[*motion].eval(t);
                let (s, c) = f.sin_cos();
                let xjw = kj.a * xj;
                let d1 = dot(ki.a * yi, xjw, ki, kj);
                let d2 = dot(ki.a * xi, xjw, ki, kj);
                let (cd, sd) = (-s * fd, c * fd);
                let (cdd, sdd) = (-c * fd * fd - s * fdd, -s * fd * fd + c * fdd);
                out.phi[r] = c * d1.p - s * d2.p;
                out.phit[r] = cd * d1.p - sd * d2.p;
                out.gamma[r] =
                    -(c * d1.h - s * d2.h + 2.0 * (cd * d1.rate - sd * d2.rate) + cdd * d1.p
                        - sdd * d2.p);
                let wi = c * d1.wi - s * d2.wi;
                out.put(r, self.i, ki, Vector3::zeros(), wi);
                out.put(r, self.j, kj, Vector3::zeros(), -wi);
            }
        }
    }
}
