//! Rotational spring–damper between two bodies (or a body and the ground): torque on body j
//! τ = −k(θ_j − θ_i − θ0) − c(ω_j − ω_i), −τ on body i.

use serde::{Deserialize, Serialize};

use super::{non_negative, Compiler, Element};
use crate::error::MbdError;
use crate::runtime::ForceEl;

/// `type = "rotational_spring_damper"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotationalSpringDamper {
    /// Unique name.
    pub name: String,
    /// Body i (or `ground`).
    pub body_i: String,
    /// Body j.
    pub body_j: String,
    /// Stiffness k, N·m/rad (default 0).
    #[serde(default)]
    pub stiffness: f64,
    /// Damping c, N·m·s/rad (default 0).
    #[serde(default)]
    pub damping: f64,
    /// Free relative angle θ0, rad (default 0).
    #[serde(default)]
    pub free_angle: f64,
}

impl Element for RotationalSpringDamper {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let name = &self.name;
        let i = c.body(name, "body_i", &self.body_i)?;
        let j = c.body(name, "body_j", &self.body_j)?;
        c.distinct(name, i, j)?;
        non_negative(name, "stiffness k (N·m/rad)", self.stiffness)?;
        non_negative(name, "damping c (N·m·s/rad)", self.damping)?;
        if !self.free_angle.is_finite() {
            return Err(MbdError::InvalidParameter {
                item: name.clone(),
                what: "free angle θ0 (rad)",
                value: self.free_angle,
                requirement: "must be finite",
            });
        }
        c.forces.push(ForceEl::RotSpring {
            name: name.clone(),
            i,
            j,
            k: self.stiffness,
            c: self.damping,
            angle0: self.free_angle,
        });
        Ok(())
    }
}
