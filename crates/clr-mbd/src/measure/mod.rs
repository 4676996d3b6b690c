//! `[[measure]]`: named outputs a model asks for, written as result columns with units after
//! the columns every run writes (Exudyn's sensors, Adams' requests and measures).
//!
//! Each kind is one module: its data (the model-file form), its validation against the model
//! (bodies, points, joints and columns it names must exist) and its runtime form
//! ([`runtime::MeasureEl`]). A measure is evaluated at every recorded row from the state and
//! the accelerations of that row (the same evaluation that writes the body columns), so a point's
//! velocity is the exact time derivative of its position, not a difference quotient.
//!
//! Column names are `<name>.<suffix>` with a suffix per quantity that fixes the unit
//! ([`crate::results::unit_of`]): `x y` m, `vx vy` m/s, `ax ay` m/s², `angle` rad, `omega` rad/s,
//! `alpha` rad/s², `distance` m, `distance_rate` m/s, `Fx Fy` N, `M` N·m, `px py` kg·m/s, `L`
//! kg·m²/s, `energy` J, and the contact quantities of [`crate::Results`]. A measure whose column
//! would repeat a column the run already writes (a measure named like a body, say) is refused.
//!
//! Kinds (`type`):
//! - `position`, `velocity`, `acceleration` of a point ([`point`]), in the world frame or, with
//!   `frame = "<body>"`, relative to that body: the point's coordinates in the body's frame and
//!   their time derivatives (what a sensor fixed to that body reads);
//! - `angle`, `angular_velocity`, `angular_acceleration` of a body, absolute or relative to
//!   another ([`angle`]);
//! - `distance` between two points and its rate ([`distance`]);
//! - `reaction` of a joint or driver, in the world frame or a body's ([`copy`]);
//! - `contact`: one quantity of a contact element ([`copy`]);
//! - `energy`: one energy term ([`copy`]);
//! - `momentum`: linear and angular momentum of rigid bodies about a world point ([`momentum`]),
//!   optionally with the magnitudes they are made of;
//! - `combination`: a sum of factors times columns or products of columns, of the run and of
//!   earlier measures ([`combination`]);
//! - `deviation` of columns from the ideal-joint twin ([`deviation`]), written after the twin
//!   has run by whoever runs it ([`crate::desc::twin::deviation_columns`]; `clr run` does).

pub mod angle;
pub mod combination;
pub mod copy;
pub mod deviation;
pub mod distance;
pub mod momentum;
pub mod point;
pub(crate) mod runtime;

use serde::{Deserialize, Serialize};

use crate::element::{section, Anchor, Compiler, Element};
use crate::error::MbdError;

section! {
    /// `[[measure]]`: named outputs written as result columns (module docs).
    Measure {
        /// Position of a point, m.
        Position(point::Position) = "position",
        /// Velocity of a point, m/s.
        Velocity(point::Velocity) = "velocity",
        /// Acceleration of a point, m/s².
        Acceleration(point::Acceleration) = "acceleration",
        /// Angle of a body, rad.
        Angle(angle::Angle) = "angle",
        /// Angular velocity of a body, rad/s.
        AngularVelocity(angle::AngularVelocity) = "angular_velocity",
        /// Angular acceleration of a body, rad/s².
        AngularAcceleration(angle::AngularAcceleration) = "angular_acceleration",
        /// Distance between two points, m, and its rate, m/s.
        Distance(distance::Distance) = "distance",
        /// Reaction of a joint or driver, N and N·m.
        Reaction(copy::Reaction) = "reaction",
        /// One quantity of a contact element.
        Contact(copy::Contact) = "contact",
        /// One energy term, J.
        Energy(copy::Energy) = "energy",
        /// Linear and angular momentum of rigid bodies.
        Momentum(momentum::Momentum) = "momentum",
        /// A sum of factors times columns or products of columns.
        Combination(combination::Combination) = "combination",
        /// Deviation of columns from the ideal-joint twin.
        Deviation(deviation::Deviation) = "deviation",
    }
}

/// Refuse a blank measure name (it would write columns `.x`).
pub(crate) fn named(name: &str, k: usize) -> Result<(), MbdError> {
    if name.trim().is_empty() || name.contains(char::is_whitespace) {
        return Err(MbdError::Invalid {
            path: format!("measure[{k}].name"),
            message: format!(
                "the measure name `{name}` is blank or holds spaces: its columns are \
                 `<name>.<quantity>`, so give a name without spaces"
            ),
        });
    }
    Ok(())
}

/// The frame (body) a `frame = "<body>"` field names: its frame index and the arm of its
/// drawing-frame origin from its reference point (−centre of mass), or `None` for the world.
pub(crate) fn body_frame(
    c: &Compiler,
    item: &str,
    field: &str,
    body: Option<&str>,
) -> Result<Option<(usize, nalgebra::Vector2<f64>)>, MbdError> {
    body.map(|b| c.anchor(item, field, &Anchor::Local(b.to_string(), [0.0, 0.0])))
        .transpose()
}
