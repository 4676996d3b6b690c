//! Rigid bodies: validation of a [`Body`] and its runtime form (centre-of-mass coordinates).

use nalgebra::Vector2;

use crate::desc::parts::Body;
use crate::error::MbdError;
use crate::runtime::{rot, RigidBody};

/// Check `b` and return its runtime form (pose and velocity of the centre of mass), the
/// centre-of-mass offset in the body frame and what was computed from its shape and `between`
/// points, in words ([`Body::resolve`]).
pub(crate) fn compile(b: &Body) -> Result<(RigidBody, Vector2<f64>, Option<String>), MbdError> {
    let r = b.resolve()?;
    for (what, v) in [
        ("mass (kg)", r.mass),
        (
            "moment of inertia about the centre of mass (kg·m²)",
            r.inertia,
        ),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(MbdError::InvalidInertia {
                body: b.name.clone(),
                what,
                value: v,
            });
        }
    }
    let position = r.position.unwrap_or_default();
    let angle = r.angle.unwrap_or_default();
    let velocity = b.velocity.unwrap_or_default();
    let omega = b.angular_velocity.unwrap_or_default();
    let finite = position
        .iter()
        .chain(velocity.iter())
        .chain(r.centre_of_mass.iter())
        .all(|v| v.is_finite())
        && angle.is_finite()
        && omega.is_finite();
    if !finite {
        return Err(MbdError::InvalidParameter {
            item: b.name.clone(),
            what: "initial pose, velocity or centre of mass",
            value: f64::NAN,
            requirement: "every component must be finite",
        });
    }
    let com = Vector2::new(r.centre_of_mass[0], r.centre_of_mass[1]);
    // r_G = r_O + A c,  v_G = v_O + ω Ĩ A c
    let arm = rot(angle, com);
    let p = Vector2::new(position[0], position[1]) + arm;
    let v = Vector2::new(velocity[0] - omega * arm.y, velocity[1] + omega * arm.x);
    Ok((
        RigidBody::new(r.mass, r.inertia)
            .at(p.x, p.y, angle)
            .moving(v.x, v.y, omega),
        com,
        r.note,
    ))
}
