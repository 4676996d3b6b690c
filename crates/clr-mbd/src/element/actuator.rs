//! Point-to-point actuator between two anchors: an axial force F(t) along the line between
//! them (positive pushes the anchors apart, i.e. extends the actuator), with an optional
//! viscous damping c·l̇ of the rod in its cylinder. The form of a hydraulic or electric linear
//! actuator driven by force (a displacement-driven actuator is a `displacement` driver).

use serde::{Deserialize, Serialize};

use super::{non_negative, Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::input::TimeFnSlot;
use crate::runtime::ForceEl;
use crate::timefn::TimeFn;

/// `type = "actuator"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Actuator {
    /// Unique name.
    pub name: String,
    /// First anchor (cylinder end).
    pub a: Anchor,
    /// Second anchor (rod end).
    pub b: Anchor,
    /// Axial force F(t), N; positive extends the actuator (pushes a and b apart).
    pub force: TimeFn,
    /// Viscous damping c of the extension rate, N·s/m (default 0).
    #[serde(default)]
    pub damping: f64,
}

impl Element for Actuator {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (i, si) = c.anchor(name, "a", &self.a)?;
        let (j, sj) = c.anchor(name, "b", &self.b)?;
        c.distinct(name, i, j)?;
        non_negative(name, "damping c (N·s/m)", self.damping)?;
        self.force.validate(&format!("{name}.force"))?;
        // a spring–damper without stiffness whose tension is lowered by the pushing force
        let f = self.force.clone();
        c.forces.push(ForceEl::Spring {
            name: name.clone(),
            i,
            si,
            j,
            sj,
            k: 0.0,
            c: self.damping,
            l0: 0.0,
            push: Some(std::sync::Arc::new(move |t| f.eval(t)[0])),
        });
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.a, &self.b]
    }
    fn time_fns(&mut self) -> Vec<TimeFnSlot<'_>> {
        vec![TimeFnSlot {
            field: "force",
            unit: "N",
            motion: false,
            f: &mut self.force,
        }]
    }
}
