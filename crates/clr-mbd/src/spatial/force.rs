//! Runtime forms of the spatial force elements and their generalized forces, power and elastic
//! energy.

use nalgebra::Vector3;

use super::frame::log_map;
use super::kin::{add_force, add_torque, Kinematics};
use crate::timefn::TimeFn;

/// A compiled force element.
#[derive(Debug, Clone)]
pub(crate) enum Force3 {
    /// Spring–damper (k, c, ℓ₀) or actuator (`push`) between two points.
    Line {
        i: usize,
        si: Vector3<f64>,
        j: usize,
        sj: Vector3<f64>,
        k: f64,
        c: f64,
        l0: f64,
        push: Option<TimeFn>,
    },
    /// Rotational spring–damper about a joint axis: the joint frames (x_i, y_i on i; x_j on j,
    /// body frames) as the angle driver's.
    Rotational {
        i: usize,
        j: usize,
        xi: Vector3<f64>,
        yi: Vector3<f64>,
        xj: Vector3<f64>,
        k: f64,
        c: f64,
        theta0: f64,
    },
    /// Six-axis bushing; `rel0` the initial relative rotation Aᵢᵀ A_j.
    Bushing {
        i: usize,
        si: Vector3<f64>,
        j: usize,
        sj: Vector3<f64>,
        rel0: nalgebra::Matrix3<f64>,
        kt: Vector3<f64>,
        ct: Vector3<f64>,
        kr: Vector3<f64>,
        cr: Vector3<f64>,
    },
    /// Applied force at a body point, components in the world or body frame.
    Point {
        i: usize,
        si: Vector3<f64>,
        body_frame: bool,
        f: [TimeFn; 3],
    },
    /// Applied torque, components in the world or body frame.
    Torque {
        i: usize,
        body_frame: bool,
        m: [TimeFn; 3],
    },
}

/// What the force elements give at one state.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ForceSums {
    /// Power dissipated by dampers, W (≥ 0).
    pub(crate) p_diss: f64,
    /// Power of applied loads and actuators, W.
    pub(crate) p_in: f64,
}

/// The world or body components of a vector of time functions at t.
pub(crate) fn vec_of(f: &[TimeFn; 3], t: f64) -> Vector3<f64> {
    Vector3::new(f[0].eval(t)[0], f[1].eval(t)[0], f[2].eval(t)[0])
}

impl Force3 {
    /// Add the element's generalized forces into Q; returns (dissipated, input) power.
    pub(crate) fn apply(&self, kin: &Kinematics, t: f64, q: &mut [f64]) -> ForceSums {
        let mut s = ForceSums::default();
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
                let (ki, kj) = (kin.get(*i), kin.get(*j));
                let (pi, pj) = (ki.point(si), kj.point(sj));
                let d = pj - pi;
                let l = d.norm();
                if l <= 0.0 {
                    return s;
                }
                let u = d / l;
                let ld = u.dot(&(kj.point_velocity(&pj) - ki.point_velocity(&pi)));
                // tension > 0 pulls the ends together
                let tension = match push {
                    Some(f) => {
                        let f = f.eval(t)[0];
                        s.p_in = f * ld;
                        -f
                    }
                    None => {
                        s.p_diss = c * ld * ld;
                        k * (l - l0) + c * ld
                    }
                };
                add_force(q, kin, *i, &pi, &(tension * u));
                add_force(q, kin, *j, &pj, &(-tension * u));
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
                let (th, z) = joint_angle(kin, (*i, xi, yi), (*j, xj));
                let thd = z.dot(&(kin.get(*j).w - kin.get(*i).w));
                let tau = -k * wrap(th - theta0) - c * thd;
                s.p_diss = c * thd * thd;
                add_torque(q, kin, *j, &(tau * z));
                add_torque(q, kin, *i, &(-tau * z));
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
                let (ki, kj) = (kin.get(*i), kin.get(*j));
                let (pi, pj) = (ki.point(si), kj.point(sj));
                let at = ki.a.transpose();
                let dx = at * (pj - pi);
                let dv = at * (kj.point_velocity(&pj) - ki.point_velocity(&pi));
                let dphi = log_map(&(at * kj.a * rel0.transpose()));
                let dw = at * (kj.w - ki.w);
                let f = ki.a * (-kt.component_mul(&dx) - ct.component_mul(&dv));
                let m = ki.a * (-kr.component_mul(&dphi) - cr.component_mul(&dw));
                s.p_diss = ct.dot(&dv.component_mul(&dv)) + cr.dot(&dw.component_mul(&dw));
                add_force(q, kin, *j, &pj, &f);
                add_force(q, kin, *i, &pj, &(-f));
                add_torque(q, kin, *j, &m);
                add_torque(q, kin, *i, &(-m));
            }
            Force3::Point {
                i,
                si,
                body_frame,
                f,
            } => {
                let ki = kin.get(*i);
                let p = ki.point(si);
                let mut fw = vec_of(f, t);
                if *body_frame {
                    fw = ki.a * fw;
                }
                s.p_in = fw.dot(&ki.point_velocity(&p));
                add_force(q, kin, *i, &p, &fw);
            }
            Force3::Torque { i, body_frame, m } => {
                let ki = kin.get(*i);
                let mut mw = vec_of(m, t);
                if *body_frame {
                    mw = ki.a * mw;
                }
                s.p_in = mw.dot(&ki.w);
                add_torque(q, kin, *i, &mw);
            }
        }
        s
    }

    /// Elastic energy stored in the element, J (springs, rotational springs, bushings).
    pub(crate) fn elastic_energy(&self, kin: &Kinematics) -> f64 {
        match self {
            Force3::Line {
                i,
                si,
                j,
                sj,
                k,
                l0,
                push: None,
                ..
            } => {
                let l = (kin.get(*j).point(sj) - kin.get(*i).point(si)).norm();
                0.5 * k * (l - l0) * (l - l0)
            }
            Force3::Rotational {
                i,
                j,
                xi,
                yi,
                xj,
                k,
                theta0,
                ..
            } => {
                let d = wrap(joint_angle(kin, (*i, xi, yi), (*j, xj)).0 - theta0);
                0.5 * k * d * d
            }
            Force3::Bushing {
                i,
                si,
                j,
                sj,
                rel0,
                kt,
                kr,
                ..
            } => {
                let (ki, kj) = (kin.get(*i), kin.get(*j));
                let at = ki.a.transpose();
                let dx = at * (kj.point(sj) - ki.point(si));
                let dphi = log_map(&(at * kj.a * rel0.transpose()));
                0.5 * (kt.dot(&dx.component_mul(&dx)) + kr.dot(&dphi.component_mul(&dphi)))
            }
            _ => 0.0,
        }
    }
}

/// An angle difference into (−π, π].
pub(crate) fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let r = a.rem_euclid(t);
    if r > std::f64::consts::PI {
        r - t
    } else {
        r
    }
}

/// The turn θ (rad, in (−π, π]) of x_j about z_i = x_i × y_i from x_i, and z_i (world): the
/// joint angle of a revolute or cylindrical joint with the frames of its driver.
fn joint_angle(
    kin: &Kinematics,
    (i, xi, yi): (usize, &Vector3<f64>, &Vector3<f64>),
    (j, xj): (usize, &Vector3<f64>),
) -> (f64, Vector3<f64>) {
    let (ai, xjw) = (kin.get(i).a, kin.get(j).a * xj);
    let (xiw, yiw) = (ai * xi, ai * yi);
    (xjw.dot(&yiw).atan2(xjw.dot(&xiw)), xiw.cross(&yiw))
}
