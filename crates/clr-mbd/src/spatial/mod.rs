//! # Spatial mechanisms
//!
//! Rigid bodies in space with ideal joints, drivers, force elements and the spherical clearance
//! joint, integrated by the same clr-ode integrators and the same driver pieces as the planar
//! [`Model`](crate::Model) (integrator set-up, impact tracking, contact memory, result
//! columns; docs/spatial.md).
//!
//! Layers, as the planar engine's: [`desc`] (plain data read from a model file with
//! `[model] space = "spatial"`), `compile` (validation and the runtime form), `constraint`,
//! `force`, `sphere` (the element runtimes), `model` (the augmented equations), `init`
//! (consistent initial conditions), `sim` and `output` (the run and its columns), below them
//! `frame` (rotations) and `kin` (body kinematics at one state).
//!
//! ## Rotations
//! A body carries its centre of mass r, the quaternion p of its orientation (scalar first) and
//! the velocities (ṙ, ω) with ω in the body frame: 7 + 6 states, integrated as a plain ODE with
//! ṗ = ½ p ⊗ (0, ω). The alternatives were weighed as docs/spatial.md records: Euler parameters
//! with ‖p‖ = 1 as a constraint add one algebraic row per body and make M depend on p; a rotation
//! vector is singular at ‖θ‖ = π and its reparametrization breaks the multistep history of NDF.
//! The quaternion ODE has no singular orientation, keeps M = diag(mI, J) constant (so the
//! range-space solve factors nothing per body), and its norm drift is harmless because every use
//! normalizes p; the drift is measured and reported (`violation.quaternion`, run notes).

pub mod desc;

mod compile;
mod constraint;
mod force;
pub mod frame;
mod init;
mod jacobian;
mod journal;
mod kin;
pub mod measure;
mod model;
mod newton;
mod newton_ws;
mod output;
mod plausible;
mod shape_compile;
mod shape_contact;
mod sim;
mod sphere;
mod system;

pub use compile::ShapeSurface;
pub use desc::{
    ClearanceKind, DistanceMeasure, DriverKind, End, Geometry3, JointKind, JournalClearanceDesc,
    JournalLubricationDesc, Orientation, Part3, PointMeasure, ShapeContactDesc3, Space,
    SpatialBody, SpatialClearance, SpatialDesc, SpatialDriver, SpatialForce, SpatialInfo,
    SpatialJoint, SpatialMeasure, SpatialShape, SphericalClearance, VectorFrame,
};
pub use journal::JournalReport;
pub use model::SpatialModel;
pub use newton::SpatialLinearization;
pub use shape_contact::ShapeReport3;
pub use sphere::SphereReport;

impl SpatialDesc {
    /// Validate every item and build the runtime model.
    ///
    /// # Errors
    /// A typed [`MbdError`](crate::MbdError) naming the item and field.
    pub fn compile(&self) -> Result<SpatialModel, crate::MbdError> {
        let model = compile::compile(self)?;
        let mut columns = model.columns();
        measure::check(self, &columns)?;
        columns.extend(self.measures.iter().flat_map(SpatialMeasure::columns));
        self.check_metrics(&columns)?;
        Ok(model)
    }

    /// `res` with the columns of the `[[measure]]` items appended ([`measure`]: computed from
    /// the recorded body columns, row by row), as a run of the model file writes it.
    pub fn with_measures(&self, mut res: crate::Results) -> crate::Results {
        if !self.measures.is_empty() {
            res.append_columns(measure::evaluate(self, &res));
        }
        res
    }

    /// Check the `[[metric]]` items against the columns the model writes, as a planar file's
    /// (`crate::desc::metric`); `twin` is refused: a spatial file has no ideal-joint twin.
    fn check_metrics(&self, columns: &[String]) -> Result<(), crate::MbdError> {
        if let Some(k) = self.metrics.iter().position(|m| m.twin) {
            return Err(crate::MbdError::Invalid {
                path: format!("metric[{k}].twin"),
                message: "a spatial model file has no ideal-joint twin ([twin] is planar only): \
                          take the metric of this run's columns (remove `twin`)"
                    .into(),
            });
        }
        crate::desc::metric::check(&self.metrics, columns, &[])
    }
}
