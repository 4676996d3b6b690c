//! Applied force at an anchor: world-frame components given as functions of time.

use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

use super::{ground_load, Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::input::TimeFnSlot;
use crate::runtime::{ForceEl, GROUND_ID};
use crate::timefn::TimeFn;

/// `type = "force"`: F = (f_x(t), f_y(t)) N in world axes at `at`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AppliedForce {
    /// Unique name.
    pub name: String,
    /// Point of application.
    pub at: Anchor,
    /// x component, N (default 0).
    #[serde(default = "zero")]
    pub fx: TimeFn,
    /// y component, N (default 0).
    #[serde(default = "zero")]
    pub fy: TimeFn,
}

pub(crate) fn zero() -> TimeFn {
    TimeFn::Constant { value: 0.0 }
}

impl Element for AppliedForce {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let (i, si) = c.anchor(&self.name, "at", &self.at)?;
        if i == GROUND_ID {
            return Err(ground_load(&self.name));
        }
        self.fx.validate(&format!("{}.fx", self.name))?;
        self.fy.validate(&format!("{}.fy", self.name))?;
        let (fx, fy) = (self.fx.clone(), self.fy.clone());
        c.forces.push(ForceEl::Force {
            name: self.name.clone(),
            i,
            si,
            state_free: true,
            f: std::sync::Arc::new(move |t, _| Vector2::new(fx.eval(t)[0], fy.eval(t)[0])),
        });
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.at]
    }
    fn time_fns(&mut self) -> Vec<TimeFnSlot<'_>> {
        vec![
            TimeFnSlot {
                field: "fx",
                unit: "N",
                motion: false,
                f: &mut self.fx,
            },
            TimeFnSlot {
                field: "fy",
                unit: "N",
                motion: false,
                f: &mut self.fy,
            },
        ]
    }
}
