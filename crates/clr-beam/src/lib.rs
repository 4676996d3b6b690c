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
//!
//! ```
//! use clr_beam::{BeamModel, Loads, Material, Section, Support};
//! // Steel cantilever, 1 m, 20 mm × 10 mm, 20 elements; nodes 0..=20 from the clamp.
//! let sec = Section::rectangular(0.02, 0.01)?;
//! let mut beam = BeamModel::straight([0.0, 0.0], [1.0, 0.0], 20, Material::steel(), sec)?;
//! beam.support(0, Support::Clamped)?;
//! let modes = beam.modes(3)?;
//! // ω₁ = 1.8751² √(EI/(ρA L⁴)) (Blevins 1979 Table 8-1)
//! let ei = 207e9 * sec.second_moment;
//! let w1 = 1.875104069f64.powi(2) * (ei / (7800.0 * sec.area)).sqrt();
//! assert!((modes.omega[0] / w1 - 1.0).abs() < 1e-6);
//! // Tip load −100 N: tip deflection P L³/(3EI), deformed shape queried at s = 0.5 m.
//! let sol = beam.solve_static(&Loads::new().nodal(20, [0.0, -100.0, 0.0]))?;
//! assert!((sol.displacements[61] / (-100.0 / (3.0 * ei)) - 1.0).abs() < 1e-10);
//! let zero = vec![0.0; beam.n_dof()];
//! let mid = beam.path()?.point(0.5, &sol.displacements, &zero)?;
//! assert!((mid.bending_moment - (-50.0)).abs() < 1e-8);
//! # Ok::<(), clr_beam::BeamError>(())
//! ```

#![warn(missing_docs)]

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
pub use query::{BeamPoint, Face, LoadRow, Path, ShapeRows, SurfacePoint};
pub use reduction::{FloatingFrameInvariants, ReducedModel};
pub use section::{Material, Section};
pub use transient::TransientSystem;
