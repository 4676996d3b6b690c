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
    /// Integrator knobs beyond the tolerance (`None` keeps the model's settings).
    pub knobs: SolverKnobs,
}

/// Integrator settings a run may override (`clr run --max-steps`, `--max-order`,
/// `--jacobian`, `--scale-velocity-error`, `--atol`); each `None`/`false` keeps the model's own value.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolverKnobs {
    /// Step budget (accepted steps, ≥ 1).
    pub max_steps: Option<usize>,
    /// Highest NDF order, 1–5.
    pub max_order: Option<usize>,
    /// How NDF forms its Newton matrix.
    pub jacobian: Option<clr_mbd::JacobianMode>,
    /// Scale the velocities' error estimate by min(h, 1) (`clr_mbd::SimOptions::scale_velocity_error`).
    pub scale_velocity_error: bool,
    /// Absolute tolerance in the units of q and q̇ (`clr run --atol`); `None` keeps the rule
    /// atol = 1e-3·rtol (or the model file's own `atol` when `--rtol` is not given).
    pub atol: Option<f64>,
    /// Turn plausibility warnings into errors (`clr run --strict`, Python `strict=True`;
    /// `clr_mbd::SimOptions::strict`).
    pub strict: bool,
}

impl SolverKnobs {
    /// Check the values.
    ///
    /// # Errors
    /// A message naming the option and the accepted range.
    pub fn validate(&self) -> Result<(), String> {
        if self.max_steps == Some(0) {
            return Err("--max-steps must be at least 1".into());
        }
        if let Some(k) = self.max_order {
            if !(1..=5).contains(&k) {
                return Err(format!("--max-order {k}: the NDF orders are 1 to 5"));
            }
        }
        if let Some(a) = self.atol {
            if !(a.is_finite() && a > 0.0) {
                return Err(format!(
                    "--atol {a}: give a positive absolute tolerance (units of the coordinates \
                     and velocities: m, rad, m/s, rad/s)"
                ));
            }
        }
        Ok(())
    }

    /// The command-line options of NDF-only knobs that are set (`--max-order`, `--jacobian`,
    /// `--scale-velocity-error`), which a Dormand–Prince run refuses.
    pub fn ndf_options(&self) -> Vec<&'static str> {
        let mut v = Vec::new();
        if self.max_order.is_some() {
            v.push("--max-order");
        }
        if self.jacobian.is_some() {
            v.push("--jacobian");
        }
        if self.scale_velocity_error {
            v.push("--scale-velocity-error");
        }
        v
    }

    /// Write the knobs that are set into `solver`.
    pub fn apply(&self, solver: &mut clr_mbd::desc::SolverSettings) {
        if let Some(n) = self.max_steps {
            solver.max_steps = n;
        }
        if let Some(k) = self.max_order {
            solver.max_order = k;
        }
        if let Some(j) = self.jacobian {
            solver.jacobian = j;
        }
        if self.scale_velocity_error {
            solver.scale_velocity_error = true;
        }
        if let Some(a) = self.atol {
            solver.atol = Some(a);
        }
        if self.strict {
            solver.strict = true;
        }
    }
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
    /// The part of the run the value is taken over, in words with its bounds in s (e.g.
    /// [`WHOLE_RUN`], or `t ≥ 0.0120 s (after the first crank revolution)`); `None` for a value
    /// that is not taken over time (a dimension of the model).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window: Option<String>,
}

/// The window of a metric taken over every recorded row of the run.
pub const WHOLE_RUN: &str = "whole run";

impl Metric {
    /// A metric with its unit and description, without a window ([`Metric::over`] gives it).
    pub fn new(name: &str, value: f64, unit: &str, description: &str) -> Self {
        Self {
            name: name.into(),
            value,
            unit: unit.into(),
            description: description.into(),
            window: None,
        }
    }

    /// This metric taken over `window` (see [`Metric::window`]).
    #[must_use]
    pub fn over(mut self, window: impl Into<String>) -> Self {
        self.window = Some(window.into());
        self
    }
}

/// The window `t ≥ t_from` (s) of metrics that skip a transient, `what` saying what the
/// transient is (e.g. `the first crank revolution`); [`WHOLE_RUN`] when `t_from` ≤ 0.
pub fn window_after(t_from: f64, what: &str) -> String {
    if t_from > 0.0 {
        format!("t ≥ {t_from:.4} s (after {what})")
    } else {
        WHOLE_RUN.to_string()
    }
}

/// The energy metrics of a run from its `energy.total` and `energy.balance` columns (J), over
/// the whole run: the same for built-in models and model files.
pub fn energy_metrics(r: &clr_mbd::Results) -> Vec<Metric> {
    let mut m = Vec::new();
    // the largest distance from the first row's value; NaN rows are skipped by `max`
    let drift = |v: &[f64]| {
        let v0 = v.first().copied().unwrap_or(0.0);
        v.iter().fold(0.0f64, |a, &x| a.max((x - v0).abs()))
    };
    if let Some(e) = r.column("energy.total") {
        m.push(
            Metric::new(
                "energy_change",
                drift(&e),
                "J",
                "largest |E(t) − E(0)| of the mechanical energy E = kinetic + gravitational + \
                 elastic (springs, beams, contact); it changes by the work of drivers and applied \
                 loads and by dissipation (dampers, contact damping, friction), which it does not \
                 subtract: see energy_balance_error",
            )
            .over(WHOLE_RUN),
        );
    }
    if let Some(b) = r.column("energy.balance") {
        m.push(
            Metric::new(
                "energy_balance_error",
                drift(&b),
                "J",
                "largest |B(t) − B(0)| of the energy balance B = E + dissipated − work in (work \
                 of drivers and applied loads): zero but for the integration error and the work \
                 of joint reactions through constraint violations",
            )
            .over(WHOLE_RUN),
        );
    }
    m
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

/// The value of the metric `name` among `metrics`, NaN when absent (so that a misspelt name
/// fails every comparison instead of passing one).
pub fn metric_value(metrics: &[Metric], name: &str) -> f64 {
    metrics
        .iter()
        .find(|m| m.name == name)
        .map_or(f64::NAN, |m| m.value)
}

impl RunOutput {
    /// The value of the metric `name` ([`metric_value`]).
    pub fn metric(&self, name: &str) -> f64 {
        metric_value(&self.metrics, name)
    }
}
