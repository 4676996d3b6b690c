//! The kinematic state of the bodies at one evaluation: positions, rotation matrices and
//! velocities, computed once per right-hand side from y and read by every element.

use nalgebra::{Matrix3, Vector3};

use super::frame::rotation;

/// Index of the ground in resolved spatial items.
pub(crate) const GROUND: usize = usize::MAX;

/// Pose and twist of one body (or the ground) at one state.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Kin {
    /// Centre of mass, m (world).
    pub r: Vector3<f64>,
    /// Rotation body → world.
    pub a: Matrix3<f64>,
    /// Velocity of the centre of mass, m/s (world).
    pub v: Vector3<f64>,
    /// Angular velocity, rad/s (world).
    pub w: Vector3<f64>,
}

impl Kin {
    /// The ground: at the origin, aligned with the world, at rest.
    pub(crate) const GROUND: Kin = Kin {
        r: Vector3::new(0.0, 0.0, 0.0),
        a: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        v: Vector3::new(0.0, 0.0, 0.0),
        w: Vector3::new(0.0, 0.0, 0.0),
    };

    /// World position of the body-frame point `s` (relative to the centre of mass), m.
    #[inline]
    pub(crate) fn point(&self, s: &Vector3<f64>) -> Vector3<f64> {
        self.r + self.a * s
    }

    /// Velocity of the material point at world position `p`, m/s.
    #[inline]
    pub(crate) fn point_velocity(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.v + self.w.cross(&(p - self.r))
    }
}

/// The bodies' kinematics, refreshed from y = (q, v, …): q = (r, p) per body (7 values), v =
/// (ṙ, ω_body) per body (6 values).
#[derive(Debug, Clone, Default)]
pub(crate) struct Kinematics {
    pub(crate) bodies: Vec<Kin>,
}

impl Kinematics {
    /// Refresh from the state y of `nb` bodies.
    pub(crate) fn update(&mut self, nb: usize, y: &[f64]) {
        self.bodies.resize(nb, Kin::GROUND);
        let (q, v) = y.split_at(7 * nb);
        for (k, b) in self.bodies.iter_mut().enumerate() {
            let qk = &q[7 * k..7 * k + 7];
            let vk = &v[6 * k..6 * k + 6];
            b.r = Vector3::new(qk[0], qk[1], qk[2]);
            b.a = rotation(&qk[3..7]);
            b.v = Vector3::new(vk[0], vk[1], vk[2]);
            b.w = b.a * Vector3::new(vk[3], vk[4], vk[5]);
        }
    }

    /// The body `k` (the ground for [`GROUND`]).
    #[inline]
    pub(crate) fn get(&self, k: usize) -> &Kin {
        if k == GROUND {
            &Kin::GROUND
        } else {
            &self.bodies[k]
        }
    }
}

/// Add the generalized force of the world force `f` (N) at world point `p` on body `k` into Q
/// (per body: force in world, moment in the body frame): Q_r += f, Q_ω += Aᵀ((p − r) × f).
#[inline]
pub(crate) fn add_force(
    q: &mut [f64],
    kin: &Kinematics,
    k: usize,
    p: &Vector3<f64>,
    f: &Vector3<f64>,
) {
    if k == GROUND {
        return;
    }
    let b = kin.get(k);
    let m = b.a.transpose() * (p - b.r).cross(f);
    let o = 6 * k;
    for c in 0..3 {
        q[o + c] += f[c];
        q[o + 3 + c] += m[c];
    }
}

/// Add the world torque `m` (N·m) on body `k` into Q.
#[inline]
pub(crate) fn add_torque(q: &mut [f64], kin: &Kinematics, k: usize, m: &Vector3<f64>) {
    if k == GROUND {
        return;
    }
    let mb = kin.get(k).a.transpose() * m;
    for c in 0..3 {
        q[6 * k + 3 + c] += mb[c];
    }
}
