//! The paper systems of clr and the validation systems beside them, each a typed parameter
//! struct (serde, SI units) with documented defaults, a builder producing a `clr-mbd` model, and
//! the studies and metrics of its paper.
//!
//! Every built-in model is reachable by name through [`catalog`], which is what the `clr`
//! command and the Python package use: [`catalog::entries`] lists them,
//! [`catalog::default_parameters`] gives the resolved parameters as JSON (so a front end can
//! override any field), [`catalog::run`] simulates one and returns a [`RunOutput`], and
//! [`catalog::export`] gives the complete model of that run as data (a `clr_mbd::ModelDesc`
//! with its solver and output settings, writable as a model file).

pub mod catalog;
pub mod common;
pub mod described_metrics;
pub mod dual_guide;
pub mod dual_guide_map;
pub mod error;
pub mod findings;
pub mod flap;
pub mod flap_flex;
pub mod flap_flex_study;
pub mod flap_map;
pub mod flap_params;
pub mod flap_spatial;
pub mod guide;
pub mod guide_map;
pub mod journal_wear;
pub mod lubrication_wear;
pub mod lyapunov;
pub mod manipulator;
pub mod map_study;
pub mod output;
pub mod provenance;
pub mod slider_crank;
pub mod studies;

pub use error::ModelsError;
pub use output::{Metric, RunOutput, RunSettings, SolverKnobs};
