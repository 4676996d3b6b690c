//! Applied torque on a body as a function of time.

use serde::{Deserialize, Serialize};

use super::{ground_load, Compiler, Element};
use crate::error::MbdError;
use crate::input::TimeFnSlot;
use crate::runtime::{ForceEl, GROUND_ID};
use crate::timefn::TimeFn;

/// `type = "torque"`: τ(t) N·m on `body`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AppliedTorque {
    /// Unique name.
    pub name: String,
    /// The body.
    pub body: String,
    /// Torque, N·m.
    pub torque: TimeFn,
}

impl Element for AppliedTorque {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let i = c.body(&self.name, "body", &self.body)?;
        if i == GROUND_ID {
            return Err(ground_load(&self.name));
        }
        self.torque.validate(&format!("{}.torque", self.name))?;
        let f = self.torque.clone();
        c.forces.push(ForceEl::Torque {
            name: self.name.clone(),
            i,
            state_free: true,
            f: std::sync::Arc::new(move |t, _| f.eval(t)[0]),
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
