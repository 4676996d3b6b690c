//! Torque between two bodies (a joint motor): +τ(t) on body j, −τ(t) on body i.

use serde::{Deserialize, Serialize};

use super::{Compiler, Element};
use crate::error::MbdError;
use crate::input::TimeFnSlot;
use crate::runtime::ForceEl;
use crate::timefn::TimeFn;

/// `type = "torque_between"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TorqueBetween {
    /// Unique name.
    pub name: String,
    /// Body i (reaction −τ).
    pub body_i: String,
    /// Body j (action +τ).
    pub body_j: String,
    /// Torque, N·m.
    pub torque: TimeFn,
}

impl Element for TorqueBetween {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let i = c.body(&self.name, "body_i", &self.body_i)?;
        let j = c.body(&self.name, "body_j", &self.body_j)?;
        c.distinct(&self.name, i, j)?;
        self.torque.validate(&format!("{}.torque", self.name))?;
        let f = self.torque.clone();
        c.forces.push(ForceEl::PairTorque {
            name: self.name.clone(),
            i,
            j,
            state_free: true,
            f: std::sync::Arc::new(move |t, _, _| f.eval(t)[0]),
        });
        Ok(())
    }
    fn time_fns(&mut self) -> Vec<TimeFnSlot<'_>> {
        vec![TimeFnSlot {
            field: "torque",
            unit: "N·m",
            motion: false,
            f: &mut self.torque,
        }]
    }
}
