//! Ideal translational (prismatic) joint: the anchor on body j stays on the line through the
//! anchor on body i along `axis`, and the relative angle keeps its initial value (2 equations,
//! Nikravesh 1988, eq. 5.15).

use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

use super::{unit_axis, Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::runtime::Con;

/// `type = "translational"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Translational {
    /// Unique name.
    pub name: String,
    /// Anchor on body i (on the sliding line).
    pub a: Anchor,
    /// Anchor on body j.
    pub b: Anchor,
    /// Sliding axis in body i's frame (any length > 0).
    pub axis: [f64; 2],
}

impl Element for Translational {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let (i, si) = c.anchor(&self.name, "a", &self.a)?;
        let (j, sj) = c.anchor(&self.name, "b", &self.b)?;
        c.distinct(&self.name, i, j)?;
        let u = unit_axis(&self.name, self.axis)?;
        let w = Vector2::new(-u.y, u.x);
        c.cons.push(Con::project(&self.name, i, si, j, sj, w, None));
        let a0 = c.angle0(j) - c.angle0(i);
        c.cons.push(Con::angle(&self.name, i, j, a0, None));
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.a, &self.b]
    }
}
