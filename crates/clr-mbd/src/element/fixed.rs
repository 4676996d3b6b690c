//! Fixed joint: the anchors coincide and the relative angle keeps its initial value
//! (3 equations).

use serde::{Deserialize, Serialize};

use super::{Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::runtime::Con;

/// `type = "fixed"`: anchors coincide, relative angle frozen at its initial value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fixed {
    /// Unique name.
    pub name: String,
    /// Anchor on body i.
    pub a: Anchor,
    /// Anchor on body j.
    pub b: Anchor,
}

impl Element for Fixed {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let (i, si) = c.anchor(&self.name, "a", &self.a)?;
        let (j, sj) = c.anchor(&self.name, "b", &self.b)?;
        c.distinct(&self.name, i, j)?;
        c.cons.push(Con::coincide(&self.name, i, si, j, sj));
        let a0 = c.angle0(j) - c.angle0(i);
        c.cons.push(Con::angle(&self.name, i, j, a0, None));
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.a, &self.b]
    }
}
