//! The built-in models, by name.

use crate::{ModelsError, RunOutput, RunSettings};

/// One built-in model.
#[derive(Debug, Clone, Copy)]
pub struct Entry {
    /// Name used on the command line (`clr run <name>`).
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
}

/// Every built-in model.
pub fn entries() -> Vec<Entry> {
    Vec::new()
}

fn unknown(name: &str) -> ModelsError {
    ModelsError::UnknownModel {
        name: name.to_string(),
        valid: entries()
            .iter()
            .map(|e| e.name)
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// The default parameters of a built-in model as JSON (every field resolved).
pub fn default_parameters(name: &str) -> Result<serde_json::Value, ModelsError> {
    Err(unknown(name))
}

/// Simulate a built-in model with the given parameters (as returned by
/// [`default_parameters`], possibly modified).
pub fn run(
    name: &str,
    _parameters: &serde_json::Value,
    _settings: &RunSettings,
) -> Result<RunOutput, ModelsError> {
    Err(unknown(name))
}
