//! Planar Euler–Bernoulli beam finite elements, modal analysis and reduction.
//!
//! - [`element`]: the 2-node frame element (axial + Hermite bending, DOF u, v, θ per node).
//! - [`BeamModel`]: meshes of straight beams and frames, supports, assembly (dense or sparse),
//!   statics and reactions.
//! - [`modal`]: the generalized eigenproblem K φ = ω² M φ (lowest modes, mass normalized).
//! - [`reduction`]: modal truncation and Craig–Bampton, floating-frame invariants.
//! - [`query`]: displacement, slope, curvature, moment, surface point and normal at arc length s.
//! - [`transient`]: M, C, K as a first-order system for an ODE integrator.
//!
//! Units are SI throughout. See `docs/beam.md` for conventions and verification.

pub mod element;
mod error;
pub mod modal;
mod model;
pub mod query;
pub mod reduction;
mod section;
pub mod transient;

pub use element::{FrameElement, MassKind};
pub use error::BeamError;
pub use modal::{EigenMethod, Modes};
pub use model::{BeamModel, DofMap, Loads, SparseMatrix, StaticSolution, Support};
pub use query::{BeamPoint, Face, LoadRow, Path, SurfacePoint};
pub use reduction::{FloatingFrameInvariants, ReducedModel};
pub use section::{Material, Section};
pub use transient::TransientSystem;
