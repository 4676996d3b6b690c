//! Floating-frame flexible body (Shabana 2020 ch. 5; formulation in [`crate::floating`]): a
//! straight beam mesh in the body frame (its supports are the reference conditions, e.g. a
//! clamp at node 0), reduced by modal truncation or Craig–Bampton, with an initial frame pose
//! and velocity. As for a rigid [`Body`](crate::desc::Body), a pose or velocity that is given
//! is fixed (kept unless the joints cannot be closed otherwise, every change reported) and one
//! left out is solved by the assembly; the elastic coordinates start at rest and undeformed
//! and the assembly never moves them ([`crate::init_flex`]).

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
    /// Initial frame pose (R_x m, R_y m, θ rad); left out: solved by the assembly from
    /// [0, 0, 0].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pose: Option<[f64; 3]>,
    /// Initial frame velocity (Ṙ_x m/s, Ṙ_y m/s, θ̇ rad/s); left out: solved by the assembly
    /// from [0, 0, 0].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<[f64; 3]>,
}

impl FlexibleBody {
    /// Build and reduce the beam; `path` names this entry in messages.
    pub(crate) fn compile(&self, path: &str) -> Result<FloatingBody, MbdError> {
        let model = self.beam.build(&format!("{path}.beam"))?;
        let red = self
            .reduction
            .reduce(&model, &format!("{path}.reduction"))?;
        let mut fb = FloatingBody::new(
            &self.name,
            &model,
            &red,
            self.pose.unwrap_or_default(),
            self.velocity.unwrap_or_default(),
        )?;
        fb.fixed = self.fixed_coordinates();
        Ok(fb)
    }

    /// Which frame coordinates (R_x, R_y, θ, Ṙ_x, Ṙ_y, θ̇) the description fixes: the pose
    /// when given, the velocity when given (the frame origin is the reference, so unlike a rigid
    /// body's centre of mass neither depends on the other).
    pub fn fixed_coordinates(&self) -> [bool; 6] {
        let (p, v) = (self.pose.is_some(), self.velocity.is_some());
        [p, p, p, v, v, v]
    }
}
