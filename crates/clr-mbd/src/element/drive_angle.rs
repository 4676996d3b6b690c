//! Angle drivers: θ_j − θ_i = f(t) (rad); `angle` drives an absolute angle (body i = ground).

use serde::{Deserialize, Serialize};

use super::{Compiler, Element};
use crate::error::MbdError;
use crate::input::TimeFnSlot;
use crate::runtime::{Con, GROUND};
use crate::timefn::TimeFn;

/// `type = "angle"`: θ = f(t) of `body`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveAngle {
    /// Unique name.
    pub name: String,
    /// Driven body.
    pub body: String,
    /// The prescribed angle, rad.
    pub motion: TimeFn,
}

/// `type = "relative_angle"`: θ_j − θ_i = f(t).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveRelativeAngle {
    /// Unique name.
    pub name: String,
    /// Body i.
    pub body_i: String,
    /// Body j.
    pub body_j: String,
    /// The prescribed relative angle, rad.
    pub motion: TimeFn,
}

/// Compile θ_j − θ_i = f(t); `fields` name the body fields (for error paths).
fn compile(
    c: &mut Compiler,
    name: &str,
    [(fi, bi), (fj, bj)]: [(&str, &str); 2],
    f: &TimeFn,
) -> Result<(), MbdError> {
    let i = c.body(name, fi, bi)?;
    let j = c.body(name, fj, bj)?;
    c.distinct(name, i, j)?;
    f.validate(&format!("{name}.motion"))?;
    let m = c.motion(f);
    c.cons.push(Con::angle(name, i, j, 0.0, Some(m)));
    Ok(())
}

impl Element for DriveAngle {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        compile(
            c,
            &self.name,
            [("ground", GROUND), ("body", &self.body)],
            &self.motion,
        )
    }
    fn time_fns(&mut self) -> Vec<TimeFnSlot<'_>> {
        vec![TimeFnSlot {
            field: "motion",
            unit: "rad",
            motion: true,
            f: &mut self.motion,
        }]
    }
}

impl Element for DriveRelativeAngle {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        compile(
            c,
            &self.name,
            [("body_i", &self.body_i), ("body_j", &self.body_j)],
            &self.motion,
        )
    }
    fn time_fns(&mut self) -> Vec<TimeFnSlot<'_>> {
        vec![TimeFnSlot {
            field: "motion",
            unit: "rad",
            motion: true,
            f: &mut self.motion,
        }]
    }
}
