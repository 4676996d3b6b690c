//! clr: simulation of planar mechanisms with clearance joints, contact, friction and flexible
//! links.
//!
//! This facade re-exports the workspace crates under short names:
//!
//! | module | crate | contents |
//! |---|---|---|
//! | [`ode`] | `clr-ode` | NDF/BDF and Dormand–Prince integrators with events |
//! | [`contact`] | `clr-contact` | normal-force and friction laws, clearance-joint kinematics |
//! | [`beam`] | `clr-beam` | planar Euler–Bernoulli finite elements, modes, reduction |
//! | [`mbd`] | `clr-mbd` | constrained multibody dynamics |
//! | [`models`] | `clr-models` | the paper systems |
//!
//! and two modules of its own: [`spec`] (model files, runs and sweeps as `clr run` and `clr
//! sweep` do them) and [`report`] (the animated HTML report of a run).

pub use clr_beam as beam;
pub use clr_contact as contact;
pub use clr_mbd as mbd;
pub use clr_models as models;
pub use clr_ode as ode;
pub mod fmu;
pub mod report;
pub mod spec;
