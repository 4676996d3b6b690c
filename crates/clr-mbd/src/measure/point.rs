//! `position`, `velocity`, `acceleration`: the kinematics of a point on a body, a beam node or a
//! named point, in the world frame or relative to a body.
//!
//! In the world frame: r_P = r + A s, ṙ_P = ṙ + ω J A s, r̈_P = r̈ + α J A s − ω² A s (Nikravesh,
//! *Computer-Aided Analysis of Mechanical Systems*, 1988, eqs. 2.35–2.37). With
//! `frame = "<body>"`: the point's coordinates p in that body's drawing frame (origin and axes of
//! its `at` coordinates) and their time derivatives ṗ, p̈, what a sensor fixed to the body reads
//! (not the world velocity resolved in the body's axes).

use serde::{Deserialize, Serialize};

use super::runtime::{CompiledMeasure, MeasureEl, Quantity};
use crate::element::{Anchor, Compiler, Element};
use crate::error::MbdError;

/// A point kinematics measure; `Q` selects the quantity (0 position, 1 velocity, 2
/// acceleration): use the aliases [`Position`], [`Velocity`], [`Acceleration`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointMeasure<const Q: u8> {
    /// Unique measure name; the columns are `<name>.x`, `<name>.y` (position, m),
    /// `<name>.vx`, `<name>.vy` (velocity, m/s) or `<name>.ax`, `<name>.ay` (acceleration, m/s²).
    pub name: String,
    /// The point: a named point, `{ body, at = [x, y] }` (m, body frame) or `{ beam, node }`.
    pub at: Anchor,
    /// A body whose frame the coordinates are relative to (default: the world).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame: Option<String>,
}

/// Position of a point: `<name>.x`, `<name>.y`, m.
pub type Position = PointMeasure<0>;
/// Velocity of a point: `<name>.vx`, `<name>.vy`, m/s.
pub type Velocity = PointMeasure<1>;
/// Acceleration of a point: `<name>.ax`, `<name>.ay`, m/s².
pub type Acceleration = PointMeasure<2>;

impl<const Q: u8> PointMeasure<Q> {
    fn quantity() -> (Quantity, [&'static str; 2], &'static str) {
        match Q {
            0 => (Quantity::Position, ["x", "y"], "m"),
            1 => (Quantity::Velocity, ["vx", "vy"], "m/s"),
            _ => (Quantity::Acceleration, ["ax", "ay"], "m/s^2"),
        }
    }
}

impl<const Q: u8> Element for PointMeasure<Q> {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let at = c.anchor(&self.name, "at", &self.at)?;
        let frame = super::body_frame(c, &self.name, "frame", self.frame.as_deref())?;
        let (quantity, suffixes, unit) = Self::quantity();
        c.measures.push(CompiledMeasure {
            name: self.name.clone(),
            columns: suffixes
                .map(|s| (format!("{}.{s}", self.name), unit))
                .to_vec(),
            el: MeasureEl::Point {
                quantity,
                at,
                frame,
            },
        });
        Ok(())
    }

    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.at]
    }
}
