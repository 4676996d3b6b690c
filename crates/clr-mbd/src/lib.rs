//! # clr-mbd: planar constrained multibody dynamics with clearance joints
//!
//! Rigid bodies in absolute coordinates q = (x, y, θ) per body (centre of mass and angle),
//! ideal joints (revolute, translational, fixed), drivers (prescribed absolute or relative angle,
//! prescribed relative displacement), forces (gravity, spring–dampers, applied forces and
//! torques as closures, torques between bodies) and revolute clearance joints built on
//! `clr-contact`. The equations of motion with Lagrange multipliers and Baumgarte stabilization
//!
//! ```text
//! [ M   Φ_qᵀ ] [ q̈ ]   [ Q             ]
//! [ Φ_q  0   ] [ λ  ] = [ γ − 2αΦ̇ − β²Φ ]
//! ```
//!
//! (Nikravesh, *Computer-Aided Analysis of Mechanical Systems*, 1988, eq. 13.22) are solved by a
//! dense LU (clr-ode's `DenseLu`: a straight-line Doolittle loop up to 16 unknowns, faer's
//! partial-pivoting LU above) into preallocated storage, and integrated by clr-ode (NDF by
//! default, DOPRI5 on request) on y = (q, q̇).
//!
//! ```
//! use clr_mbd::{ModelBuilder, RigidBody, SimOptions, SolverKind};
//! // a 1 kg, 1 m rod pinned at one end, released horizontally
//! let mut b = ModelBuilder::new();
//! b.gravity(0.0, -9.81)
//!     .body("rod", RigidBody::new(1.0, 1.0 / 12.0).at(0.5, 0.0, 0.0))
//!     .revolute("pin", ("ground", [0.0, 0.0]), ("rod", [-0.5, 0.0]));
//! let mut model = b.build().unwrap();
//! let res = model.simulate(&SimOptions::span(0.0, 1.0, 10).tolerances(1e-9, 1e-11)).unwrap();
//! let e = res.column("energy.total").unwrap();
//! assert!((e[10] - e[0]).abs() < 1e-6);
//! ```

#![warn(missing_docs)]

mod beam_face;
mod broad_phase;
mod clearance;
mod contact_report;
pub mod cosim;
pub mod desc;
mod driver;
pub mod element;
pub mod error;
mod face_pair;
mod field;
mod flexible;
pub mod floating;
mod guide_exit;
mod ideal;
pub mod impacts;
mod init;
pub mod init_flex;
pub mod initial;
mod initial_data;
pub mod input;
pub mod jacobian;
pub mod linsys;
mod lugre;
pub mod measure;
pub mod model;
pub mod newton;
pub mod node_output;
mod options;
pub mod plausible;
mod rangespace;
pub mod results;
mod runtime;
mod shape_pair;
pub mod sim;
pub mod spatial;
pub mod system;
pub mod timefn;

pub use clr_contact::ForceApplication;
pub use desc::laws::{ContactFriction, FrictionLawDesc, FrictionSpec, NormalLawDesc, NormalSpec};
pub use desc::{BeamMesh, Body, FieldError, ModelDesc, Reduction};
pub use element::Anchor;
pub use error::MbdError;
pub use impacts::Impact;
pub use init::{
    BodyInitialState, CoordinateInitialState, InitialConditions, COORDINATE_NAMES,
    COORDINATE_UNITS, CORRECTION_TOL,
};
pub use jacobian::Jacobians;
pub use linsys::{LinearSolver, SPARSE_FROM};
pub use measure::Measure;
pub use model::{
    FlexibleGuideSpec, ModelBuilder, RevoluteClearanceSpec, TranslationalClearanceSpec,
};
pub use newton::JacobianMode;
pub use runtime::{RigidBody, GROUND};
pub use timefn::TimeFn;
/// The former name of [`TimeFn`] for drivers' motions.
pub type Motion = TimeFn;
pub use sim::{InitialConditionsMode, Results, SimOptions, SolverKind};
pub use system::{ContactReport, Energies, Model, DEFAULT_BAUMGARTE_ALPHA, DEFAULT_BAUMGARTE_BETA};

#[cfg(test)]
mod tests;
