//! Ideal revolute joint: the anchor points coincide (2 equations, Nikravesh 1988, eq. 5.11).

use serde::{Deserialize, Serialize};

use super::{Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::runtime::Con;

/// `type = "revolute"`: anchors `a` (on body i) and `b` (on body j) coincide.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Revolute {
    /// Unique name.
    pub name: String,
    /// Anchor on body i.
    pub a: Anchor,
    /// Anchor on body j.
    pub b: Anchor,
}

impl Element for Revolute {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let (i, si) = c.anchor(&self.name, "a", &self.a)?;
        let (j, sj) = c.anchor(&self.name, "b", &self.b)?;
        c.distinct(&self.name, i, j)?;
        c.cons.push(Con::coincide(&self.name, i, si, j, sj));
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.a, &self.b]
    }
}
