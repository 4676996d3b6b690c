//! The spherical clearance joint: a ball of radius R_b on body j in a socket of radius R_s on
//! body i (Flores, Ambrósio, Claro & Lankarani, J. Comput. Nonlinear Dyn. 1 (2006) 240–247).
//!
//! With the centres p_i (socket) and p_j (ball), e = p_j − p_i, the radial clearance
//! c = R_s − R_b, the penetration δ = ‖e‖ − c and the normal n = e/‖e‖. The contact points are
//! Q_i = p_i + R_s n on the socket and Q_j = p_j + R_b n on the ball; their relative velocity
//! v = Q̇_j − Q̇_i gives the approach rate δ̇ = v·n and the slip v_t = v − δ̇ n, a vector in the
//! tangent plane. The normal force F_N(δ, δ̇, δ̇⁻) is any clr-contact law; friction acts against
//! v_t with the magnitude of the planar law at |v_t| (or the LuGre law with a bristle vector z in
//! the tangent plane). As in the planar joint's default, the force pair acts at the midpoint of
//! Q_i and Q_j (collinear action and reaction: angular momentum is kept exactly). Orientation
//! does not change the gap. With the motion in a plane this is, term by term, the planar
//! revolute clearance joint (clr-contact `revolute`), which `contact.spatial.sphere.planar`
//! checks.

use nalgebra::Vector3;

use clr_contact::{ContactMemory, NormalLaw};

use super::kin::{add_force, Kinematics};
use crate::desc::laws::ContactFriction;

/// A compiled spherical clearance joint.
#[derive(Debug, Clone)]
pub(crate) struct Sphere {
    pub(crate) name: String,
    /// Socket body and centre (centre-of-mass frame), m.
    pub(crate) i: usize,
    pub(crate) si: Vector3<f64>,
    /// Ball body and centre, m.
    pub(crate) j: usize,
    pub(crate) sj: Vector3<f64>,
    pub(crate) r_socket: f64,
    pub(crate) r_ball: f64,
    pub(crate) law: NormalLaw,
    pub(crate) friction: Option<ContactFriction>,
    /// Index of its point in the contact memory.
    pub(crate) memory: usize,
    /// Offset of its bristle vector (3 states) in the bristle block, if LuGre.
    pub(crate) bristle: Option<usize>,
}

/// What the joint gives at one state (the `C.*` columns).
#[derive(Debug, Clone, Copy, Default)]
pub struct SphereReport {
    /// Penetration δ, m (> 0 in contact).
    pub penetration: f64,
    /// δ̇, m/s.
    pub rate: f64,
    /// Normal force F_N ≥ 0, N.
    pub normal_force: f64,
    /// Friction force on the ball (world), N.
    pub friction: Vector3<f64>,
    /// e = p_ball − p_socket (world), m.
    pub eccentricity: Vector3<f64>,
    /// Power dissipated by contact damping and friction, W.
    pub dissipated: f64,
    /// Elastic energy ∫F_e dδ, J.
    pub elastic_energy: f64,
}

/// The geometry at one state.
struct Geometry {
    e: Vector3<f64>,
    delta: f64,
    n: Vector3<f64>,
    /// Slip of the contact points and the approach rate.
    v: Vector3<f64>,
    rate: f64,
    /// Midpoint of the contact points (where the pair acts).
    mid: Vector3<f64>,
}

impl Sphere {
    /// Radial clearance c = R_s − R_b, m.
    pub(crate) fn clearance(&self) -> f64 {
        self.r_socket - self.r_ball
    }

    fn geometry(&self, kin: &Kinematics) -> Geometry {
        let (ki, kj) = (kin.get(self.i), kin.get(self.j));
        let (pi, pj) = (ki.point(&self.si), kj.point(&self.sj));
        let e = pj - pi;
        let len = e.norm();
        let n = if len > 0.0 { e / len } else { Vector3::x() };
        let (qi, qj) = (pi + self.r_socket * n, pj + self.r_ball * n);
        let v = kj.point_velocity(&qj) - ki.point_velocity(&qi);
        Geometry {
            e,
            delta: len - self.clearance(),
            n,
            rate: v.dot(&n),
            v,
            mid: 0.5 * (qi + qj),
        }
    }

    /// Penetration δ (m): the event function of contact onsets.
    pub(crate) fn gap(&self, kin: &Kinematics) -> f64 {
        let (ki, kj) = (kin.get(self.i), kin.get(self.j));
        (kj.point(&self.sj) - ki.point(&self.si)).norm() - self.clearance()
    }

    /// Penetration and its rate (m, m/s), for committing the contact memory.
    pub(crate) fn gap_rate(&self, kin: &Kinematics) -> (f64, f64) {
        let g = self.geometry(kin);
        (g.delta, g.rate)
    }

    /// Apply the contact forces into Q (when `q` is given) and report; `z` is the bristle vector
    /// (LuGre) and `z_dot` receives its rate.
    pub(crate) fn apply(
        &self,
        kin: &Kinematics,
        memory: &mut ContactMemory,
        z: Vector3<f64>,
        z_dot: &mut Vector3<f64>,
        q: Option<&mut [f64]>,
    ) -> SphereReport {
        let g = self.geometry(kin);
        let mut rep = SphereReport {
            penetration: g.delta,
            rate: g.rate,
            eccentricity: g.e,
            ..Default::default()
        };
        let vdm = memory.impact_velocity(self.memory, g.delta, g.rate);
        let slip = g.v - g.rate * g.n;
        let speed = slip.norm();
        if g.delta <= 0.0 {
            // open: the bristles rest (the driver resets them to 0 at the next onset)
            return rep;
        }
        // LuGre bristles in the tangent plane: ż = v_t − σ₀|v_t|z/g(|v_t|) (the vector form of
        // Canudas de Wit et al. 1995, with z projected on the current tangent plane)
        if let Some(ContactFriction::LuGre(l)) = &self.friction {
            let zt = z - g.n * g.n.dot(&z);
            *z_dot = slip - zt * (speed - l.z_dot(speed, 1.0));
        }
        let fn_ = self.law.force(g.delta, g.rate, vdm);
        let ft = match &self.friction {
            None => Vector3::zeros(),
            Some(ContactFriction::Static(f)) if speed > 0.0 => slip * (f.force(speed, fn_) / speed),
            Some(ContactFriction::Static(_)) => Vector3::zeros(),
            Some(ContactFriction::LuGre(l)) if fn_ > 0.0 => {
                let zt = z - g.n * g.n.dot(&z);
                -(zt * l.coefficient(0.0, 1.0, 0.0)
                    + *z_dot * l.coefficient(0.0, 0.0, 1.0)
                    + slip * l.coefficient(1.0, 0.0, 0.0))
                    * fn_
            }
            Some(ContactFriction::LuGre(_)) => Vector3::zeros(),
        };
        let f_ball = -fn_ * g.n + ft;
        rep.normal_force = fn_;
        rep.friction = ft;
        rep.elastic_energy = self.law.elastic_energy(g.delta);
        // dissipation: minus the power of the pair at its point of action, minus the elastic
        // storage F_e δ̇ (as the planar joint, clearance::revolute_dissipated_power)
        let (ki, kj) = (kin.get(self.i), kin.get(self.j));
        let v_mid = kj.point_velocity(&g.mid) - ki.point_velocity(&g.mid);
        rep.dissipated = -f_ball.dot(&v_mid) - self.law.elastic_force(g.delta) * g.rate;
        if let Some(q) = q {
            add_force(q, kin, self.j, &g.mid, &f_ball);
            add_force(q, kin, self.i, &g.mid, &(-f_ball));
        }
        rep
    }
}
