//! Translational spring–damper between two anchors: tension f = k(l − l0) + c·l̇ along the line
//! between them.

use serde::{Deserialize, Serialize};

use super::{non_negative, Anchor, Compiler, Element};
use crate::error::MbdError;
use crate::runtime::ForceEl;

/// `type = "spring_damper"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringDamper {
    /// Unique name.
    pub name: String,
    /// First anchor.
    pub a: Anchor,
    /// Second anchor.
    pub b: Anchor,
    /// Stiffness k, N/m (default 0).
    #[serde(default)]
    pub stiffness: f64,
    /// Damping c, N·s/m (default 0).
    #[serde(default)]
    pub damping: f64,
    /// Free length l0, m (default 0).
    #[serde(default)]
    pub free_length: f64,
}

impl Element for SpringDamper {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let (i, si) = c.anchor(name, "a", &self.a)?;
        let (j, sj) = c.anchor(name, "b", &self.b)?;
        c.distinct(name, i, j)?;
        non_negative(name, "stiffness k (N/m)", self.stiffness)?;
        non_negative(name, "damping c (N·s/m)", self.damping)?;
        non_negative(name, "free length l0 (m)", self.free_length)?;
        c.forces.push(ForceEl::Spring {
            name: name.clone(),
            i,
            si,
            j,
            sj,
            k: self.stiffness,
            c: self.damping,
            l0: self.free_length,
            push: None,
        });
        Ok(())
    }
    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.a, &self.b]
    }
}
