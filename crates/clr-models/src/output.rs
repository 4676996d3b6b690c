//! What running a model returns: time histories, scalar metrics and the resolved parameters.

use serde::Serialize;

/// Settings of one run that are not model parameters.
#[derive(Default)]
pub struct RunSettings {
    /// End time (s); `None` uses the model's default duration.
    pub t_end: Option<f64>,
    /// Relative tolerance of the integrator; `None` uses the model's default.
    pub rtol: Option<f64>,
    /// Called now and then with the current simulated time (s), for progress display.
    pub progress: Option<Box<dyn Fn(f64) + Send + Sync>>,
}

/// A named scalar result of a run (peak contact force, path error, momentum drift, …).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Metric {
    /// Identifier, snake_case (e.g. `peak_contact_force`).
    pub name: String,
    /// Value in SI units.
    pub value: f64,
    /// Unit of `value` (e.g. `"N"`, `"m/s^2"`, `"-"`).
    pub unit: String,
    /// One-line description.
    pub description: String,
}

impl Metric {
    /// A metric with its unit and description.
    pub fn new(name: &str, value: f64, unit: &str, description: &str) -> Self {
        Self {
            name: name.into(),
            value,
            unit: unit.into(),
            description: description.into(),
        }
    }
}

/// The outcome of one run of a model.
#[derive(Debug)]
pub struct RunOutput {
    /// Model name (catalog name, or the file name for model files).
    pub model: String,
    /// Time histories as recorded by clr-mbd (columns with names; units in [`RunOutput::units`]).
    pub results: clr_mbd::Results,
    /// Unit of each column of `results`, in the same order as `results.columns()`.
    pub units: Vec<String>,
    /// Scalar metrics of the run.
    pub metrics: Vec<Metric>,
    /// The full resolved parameters that produced this run.
    pub parameters: serde_json::Value,
}
