//! Displacement driver (an actuator): the projection of (P_j − P_i) on the unit `axis` fixed on
//! body i equals f(t) (m).

use serde::{Deserialize, Serialize};

use super::{unit_axis, Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::input::TimeFnSlot;
use crate::runtime::Con;
use crate::timefn::TimeFn;

/// `type = "displacement"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveDisplacement {
    /// Unique name.
    pub name: String,
    /// Anchor on body i.
    pub a: Anchor,
    /// Anchor on body j.
    pub b: Anchor,
    /// Axis in body i's frame (any length > 0).
    pub axis: [f64; 2],
    /// The prescribed displacement, m.
    pub motion: TimeFn,
}

impl Element for DriveDisplacement {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let (i, si) = c.anchor(&self.name, "a", &self.a)?;
        let (j, sj) = c.anchor(&self.name, "b", &self.b)?;
        c.distinct(&self.name, i, j)?;
        let u = unit_axis(&self.name, self.axis)?;
        self.motion.validate(&format!("{}.motion", self.name))?;
        let m = c.motion(&self.motion);
        c.cons
            .push(Con::project(&self.name, i, si, j, sj, u, Some(m)));
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.a, &self.b]
    }
    fn time_fns(&mut self) -> Vec<TimeFnSlot<'_>> {
        vec![TimeFnSlot {
            field: "motion",
            unit: "m",
            motion: true,
            f: &mut self.motion,
        }]
    }
}
