//! The error type of clr-models.

use crate::output::RunOutput;

/// Errors of building or running a built-in model.
#[derive(Debug, thiserror::Error)]
pub enum ModelsError {
    /// No built-in model has this name.
    #[error("unknown model `{name}`; built-in models: {valid}")]
    UnknownModel {
        /// The name that was asked for.
        name: String,
        /// Comma-separated list of valid names.
        valid: String,
    },
    /// The parameters do not describe a valid model (wrong field, type or value).
    #[error("invalid parameters for model `{model}`: {message}")]
    InvalidParameters {
        /// Model name.
        model: String,
        /// What is wrong and what to change.
        message: String,
    },
    /// The multibody model could not be built.
    #[error("model `{model}`: {source}")]
    Build {
        /// Model name.
        model: String,
        /// Underlying error.
        #[source]
        source: Box<clr_mbd::MbdError>,
    },
    /// The simulation failed; `partial` holds what was computed up to the failure.
    #[error("simulation of `{model}` failed: {message}")]
    Simulation {
        /// Model name.
        model: String,
        /// The solver's message.
        message: String,
        /// Results up to the failure, when any.
        partial: Option<Box<RunOutput>>,
    },
}
