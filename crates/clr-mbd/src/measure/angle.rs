//! `angle`, `angular_velocity`, `angular_acceleration` of a body, absolute (from the world x
//! axis) or relative to another body: θ_body − θ_relative_to − offset and its derivatives.

use serde::{Deserialize, Serialize};

use super::runtime::{CompiledMeasure, MeasureEl, Quantity};
use crate::element::{Compiler, Element};
use crate::error::MbdError;
use crate::runtime::GROUND;

/// An angle measure; `Q` selects the quantity (0 angle, 1 angular velocity, 2 angular
/// acceleration): use the aliases [`Angle`], [`AngularVelocity`], [`AngularAcceleration`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AngleMeasure<const Q: u8> {
    /// Unique measure name; the column is `<name>.angle` (rad), `<name>.omega` (rad/s) or
    /// `<name>.alpha` (rad/s²).
    pub name: String,
    /// The rigid body.
    pub body: String,
    /// The body the angle is measured from (default: `ground`, i.e. the world x axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relative_to: Option<String>,
    /// Subtracted from the angle, rad (default 0; `angle` only): the angle of a reference
    /// position, so that the measure starts from 0 there.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub offset: f64,
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// Angle of a body: `<name>.angle`, rad.
pub type Angle = AngleMeasure<0>;
/// Angular velocity of a body: `<name>.omega`, rad/s.
pub type AngularVelocity = AngleMeasure<1>;
/// Angular acceleration of a body: `<name>.alpha`, rad/s².
pub type AngularAcceleration = AngleMeasure<2>;

impl<const Q: u8> Element for AngleMeasure<Q> {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let (quantity, suffix, unit) = match Q {
            0 => (Quantity::Position, "angle", "rad"),
            1 => (Quantity::Velocity, "omega", "rad/s"),
            _ => (Quantity::Acceleration, "alpha", "rad/s^2"),
        };
        if quantity != Quantity::Position && self.offset != 0.0 {
            return Err(MbdError::Invalid {
                path: format!("{}.offset", self.name),
                message: format!(
                    "an offset is subtracted from an angle only; `{suffix}` is a rate: leave \
                     `offset` out"
                ),
            });
        }
        if !self.offset.is_finite() {
            return Err(MbdError::InvalidParameter {
                item: self.name.clone(),
                what: "offset (rad)",
                value: self.offset,
                requirement: "must be finite",
            });
        }
        let body = c.body(&self.name, "body", &self.body)?;
        let relative = self.relative_to.as_deref().unwrap_or(GROUND);
        let relative_to = c.body(&self.name, "relative_to", relative)?;
        c.measures.push(CompiledMeasure {
            name: self.name.clone(),
            columns: vec![(format!("{}.{suffix}", self.name), unit)],
            el: MeasureEl::Angle {
                quantity,
                body,
                relative_to,
                offset: self.offset,
            },
        });
        Ok(())
    }
}
