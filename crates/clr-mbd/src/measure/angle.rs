//! `angle`, `angular_velocity`, `angular_acceleration` of a body, absolute (from the world x
//! axis) or relative to another body: θ_body − θ_relative_to − offset and its derivatives.

use serde::{Deserialize, Serialize};

use super::runtime::{CompiledMeasure, MeasureEl, Quantity};
use crate::element::{Compiler, Element};
use crate::error::MbdError;
use crate::runtime::GROUND;

/// Angle of a body: `<name>.angle`, rad.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Angle {
    /// Unique measure name.
    pub name: String,
    /// The rigid body.
    pub body: String,
    /// The body the angle is measured from (default: `ground`, i.e. the world x axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relative_to: Option<String>,
    /// Subtracted from the angle, rad (default 0): the angle of a reference position, so that
    /// the measure starts from 0 there.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub offset: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// A rate of an angle; `Q` selects it (1 angular velocity, 2 angular acceleration): use the
/// aliases [`AngularVelocity`], [`AngularAcceleration`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AngleRate<const Q: u8> {
    /// Unique measure name; the column is `<name>.omega` (rad/s) or `<name>.alpha` (rad/s²).
    pub name: String,
    /// The rigid body.
    pub body: String,
    /// The body the rate is relative to (default: `ground`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relative_to: Option<String>,
}

/// Angular velocity of a body: `<name>.omega`, rad/s.
pub type AngularVelocity = AngleRate<1>;
/// Angular acceleration of a body: `<name>.alpha`, rad/s².
pub type AngularAcceleration = AngleRate<2>;

impl Element for Angle {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        if !self.offset.is_finite() {
            return Err(MbdError::InvalidParameter {
                item: self.name.clone(),
                what: "offset (rad)",
                value: self.offset,
                requirement: "must be finite",
            });
        }
        let m = (&self.name, &self.body, self.relative_to.as_deref());
        push(c, m, (Quantity::Position, "angle", "rad"), self.offset)
    }
}

impl<const Q: u8> Element for AngleRate<Q> {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let column = match Q {
            1 => (Quantity::Velocity, "omega", "rad/s"),
            _ => (Quantity::Acceleration, "alpha", "rad/s^2"),
        };
        let m = (&self.name, &self.body, self.relative_to.as_deref());
        push(c, m, column, 0.0)
    }
}

/// Push the measure (name, body, relative_to) of `quantity` with its column (suffix, unit).
fn push(
    c: &mut Compiler,
    (name, body, relative_to): (&String, &String, Option<&str>),
    (quantity, suffix, unit): (Quantity, &str, &'static str),
    offset: f64,
) -> Result<(), MbdError> {
    let body = c.body(name, "body", body)?;
    let relative_to = c.body(name, "relative_to", relative_to.unwrap_or(GROUND))?;
    c.measures.push(CompiledMeasure {
        name: name.clone(),
        columns: vec![(format!("{name}.{suffix}"), unit)],
        el: MeasureEl::Angle {
            quantity,
            body,
            relative_to,
            offset,
        },
    });
    Ok(())
}
