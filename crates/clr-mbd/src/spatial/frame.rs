//! Rotations of spatial bodies: the orientation state, its kinematic map and the rotation
//! matrix, in the form the spatial engine integrates (see [the module docs](super) for why).
//!
//! A body's orientation is the quaternion p = (p₀, p₁, p₂, p₃) (scalar first) of its rotation
//! from the body frame to the world frame, carried as four plain ODE states with
//!
//! ```text
//! ṗ = ½ p ⊗ (0, ω)        (ω the angular velocity in the body frame)
//! ```
//!
//! (Nikravesh 1988, eq. 6.93 in the body-frame form; Chrono and Multibody.jl keep the same pair
//! of states). Its norm is kept by the exact flow but not by the integrator: every use goes
//! through the normalized p/‖p‖ ([`rotation`]), so the physics never sees the drift; a term
//! k(1 − ‖p‖²)p with k = 10/s pulls the norm back (the model's `NORM_RATE`), and the drift is
//! measured and reported after each run (`violation.quaternion`, run notes).

use nalgebra::{Matrix3, Vector3};

/// Rotation matrix (body → world) of the quaternion p (any non-zero norm; normalized here).
/// Nikravesh 1988, eq. 6.19: A = (2p₀² − 1)I + 2(e eᵀ + p₀ ẽ) for the unit quaternion (p₀, e).
#[inline]
pub fn rotation(p: &[f64]) -> Matrix3<f64> {
    let n2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3];
    let s = 2.0 / n2;
    let (w, x, y, z) = (p[0], p[1], p[2], p[3]);
    Matrix3::new(
        1.0 - s * (y * y + z * z),
        s * (x * y - w * z),
        s * (x * z + w * y),
        s * (x * y + w * z),
        1.0 - s * (x * x + z * z),
        s * (y * z - w * x),
        s * (x * z - w * y),
        s * (y * z + w * x),
        1.0 - s * (x * x + y * y),
    )
}

/// The quaternion rate ṗ = ½ p ⊗ (0, ω) for the body-frame angular velocity ω (rad/s), written
/// into `out` (4 values, 1/s).
#[inline]
pub fn quaternion_rate(p: &[f64], w: &Vector3<f64>, out: &mut [f64]) {
    out[0] = -0.5 * (p[1] * w.x + p[2] * w.y + p[3] * w.z);
    out[1] = 0.5 * (p[0] * w.x + p[2] * w.z - p[3] * w.y);
    out[2] = 0.5 * (p[0] * w.y + p[3] * w.x - p[1] * w.z);
    out[3] = 0.5 * (p[0] * w.z + p[1] * w.y - p[2] * w.x);
}

/// Unit quaternion (scalar first) of a rotation matrix (Shepperd's method: the largest of the
/// four squared components is taken first, so no division by a small number).
pub fn quaternion_of(a: &Matrix3<f64>) -> [f64; 4] {
    let tr = a.trace();
    let cands = [tr, a[(0, 0)], a[(1, 1)], a[(2, 2)]];
    let k = (0..4).fold(0, |b, i| if cands[i] > cands[b] { i } else { b });
    let mut q = match k {
        0 => {
            let s = (1.0 + tr).sqrt() * 2.0;
            [
                0.25 * s,
                (a[(2, 1)] - a[(1, 2)]) / s,
                (a[(0, 2)] - a[(2, 0)]) / s,
                (a[(1, 0)] - a[(0, 1)]) / s,
            ]
        }
        1 => {
            let s = (1.0 + a[(0, 0)] - a[(1, 1)] - a[(2, 2)]).sqrt() * 2.0;
            [
                (a[(2, 1)] - a[(1, 2)]) / s,
                0.25 * s,
                (a[(0, 1)] + a[(1, 0)]) / s,
                (a[(0, 2)] + a[(2, 0)]) / s,
            ]
        }
        2 => {
            let s = (1.0 + a[(1, 1)] - a[(0, 0)] - a[(2, 2)]).sqrt() * 2.0;
            [
                (a[(0, 2)] - a[(2, 0)]) / s,
                (a[(0, 1)] + a[(1, 0)]) / s,
                0.25 * s,
                (a[(1, 2)] + a[(2, 1)]) / s,
            ]
        }
        _ => {
            let s = (1.0 + a[(2, 2)] - a[(0, 0)] - a[(1, 1)]).sqrt() * 2.0;
            [
                (a[(1, 0)] - a[(0, 1)]) / s,
                (a[(0, 2)] + a[(2, 0)]) / s,
                (a[(1, 2)] + a[(2, 1)]) / s,
                0.25 * s,
            ]
        }
    };
    // one sign for the same rotation: scalar part not negative
    if q[0] < 0.0 {
        q.iter_mut().for_each(|c| *c = -*c);
    }
    q
}

/// Rotation matrix exp([φ]×) of the rotation vector φ (rad), Rodrigues' formula.
pub fn exp_map(phi: &Vector3<f64>) -> Matrix3<f64> {
    let th = phi.norm();
    let k = phi.cross_matrix();
    if th < 1e-8 {
        return Matrix3::identity() + k + 0.5 * k * k;
    }
    Matrix3::identity() + (th.sin() / th) * k + ((1.0 - th.cos()) / (th * th)) * k * k
}

/// Rotation vector φ (rad, ‖φ‖ ≤ π) of a rotation matrix: the inverse of [`exp_map`].
pub fn log_map(a: &Matrix3<f64>) -> Vector3<f64> {
    let q = quaternion_of(a);
    let v = Vector3::new(q[1], q[2], q[3]);
    let s = v.norm();
    if s < 1e-12 {
        return 2.0 * v;
    }
    let th = 2.0 * s.atan2(q[0]);
    v * (th / s)
}

/// A unit vector perpendicular to the unit vector `u` (the world axis least aligned with `u`,
/// made perpendicular): the reference direction of joint frames built from an axis alone.
pub fn perpendicular(u: &Vector3<f64>) -> Vector3<f64> {
    let a = u.abs();
    let e = if a.x <= a.y && a.x <= a.z {
        Vector3::x()
    } else if a.y <= a.z {
        Vector3::y()
    } else {
        Vector3::z()
    };
    (e - u * u.dot(&e)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quaternion of a rotation matrix and back: A(q(A)) = A to round-off, for rotations
    /// near each of Shepperd's four branches (closed form: exp_map of a rotation vector).
    #[test]
    fn quaternion_round_trip() {
        for phi in [
            Vector3::new(0.1, -0.2, 0.3),
            Vector3::new(3.0, 0.1, 0.0),
            Vector3::new(0.0, 3.1, 0.2),
            Vector3::new(0.1, 0.0, -3.1),
        ] {
            let a = exp_map(&phi);
            let back = rotation(&quaternion_of(&a));
            assert!((a - back).abs().max() < 1e-14, "{phi}");
            assert!((log_map(&a) - phi).norm() < 1e-12, "{phi}");
        }
    }

    /// ṗ = ½ p ⊗ (0, ω) against the derivative of A: Ȧ = A [ω]× (body-frame ω), by central
    /// differences of A(p + h ṗ) (tolerance: the O(h²) truncation at h = 1e-6).
    #[test]
    fn quaternion_rate_gives_body_angular_velocity() {
        let p = quaternion_of(&exp_map(&Vector3::new(0.4, -0.7, 1.1)));
        let w = Vector3::new(0.3, -1.2, 2.0);
        let mut pd = [0.0; 4];
        quaternion_rate(&p, &w, &mut pd);
        let h = 1e-6;
        let pp: Vec<f64> = (0..4).map(|i| p[i] + h * pd[i]).collect();
        let pm: Vec<f64> = (0..4).map(|i| p[i] - h * pd[i]).collect();
        let adot = (rotation(&pp) - rotation(&pm)) / (2.0 * h);
        let expect = rotation(&p) * w.cross_matrix();
        assert!((adot - expect).abs().max() < 1e-8);
    }
}
