//! Floating-frame flexible body (Shabana 2020 ch. 5; formulation in [`crate::floating`]): a
//! straight beam mesh in the body frame (its supports are the reference conditions, e.g. a
//! clamp at node 0), reduced by modal truncation or Craig–Bampton, with an initial frame pose
//! and velocity; elastic coordinates start at rest and undeformed.

use serde::{Deserialize, Serialize};

use crate::desc::beam::{BeamMesh, Reduction};
use crate::error::MbdError;
use crate::floating::FloatingBody;

/// `[[flexible_body]]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlexibleBody {
    /// Unique name (its coordinates are `name.x`, `name.y`, `name.theta`, `name.q<k>`).
    pub name: String,
    /// The beam mesh in the body frame (m).
    pub beam: BeamMesh,
    /// Reduction of the elastic field.
    pub reduction: Reduction,
    /// Initial frame pose (R_x m, R_y m, θ rad).
    #[serde(default)]
    pub pose: [f64; 3],
    /// Initial frame velocity (Ṙ_x m/s, Ṙ_y m/s, θ̇ rad/s).
    #[serde(default)]
    pub velocity: [f64; 3],
}

impl FlexibleBody {
    /// Build and reduce the beam; `path` names this entry in messages.
    pub(crate) fn compile(&self, path: &str) -> Result<FloatingBody, MbdError> {
        let model = self.beam.build(&format!("{path}.beam"))?;
        let red = self
            .reduction
            .reduce(&model, &format!("{path}.reduction"))?;
        FloatingBody::new(&self.name, &model, &red, self.pose, self.velocity)
    }
}
