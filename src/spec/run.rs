//! One run of a built-in model or a model file, as `clr run` does it, without writing files:
//! [`resolve`] a target (a catalog name or a `.toml` path) with `--set` overrides, then
//! [`execute`] it into an [`Outcome`] (time histories, units, metrics, resolved parameters).
//! The command-line tool and the Python package both go through these two functions, so a
//! run from either gives the same numbers bit for bit.

use std::path::Path;

use clr_models::output::WHOLE_RUN;
use clr_models::{Metric, RunOutput, RunSettings};

use super::{apply_json_override, Assignment, Loaded, ModelSpec, SpecError};

/// Why a target could not be resolved or run (bad input; a solver failure is not an error but
/// an [`Outcome`] with `error` set).
#[derive(Debug, Clone, thiserror::Error)]
pub enum RunError {
    /// A model file or override error with its place.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// Any other bad input (unknown model name, invalid parameters of a built-in).
    #[error("{0}")]
    Input(String),
}

/// A resolved target, ready to run (plain data: `Send`).
#[derive(Debug, Clone)]
pub enum Job {
    /// A catalog model with its full parameters.
    Builtin {
        /// Catalog name.
        name: String,
        /// Full resolved parameters (defaults with the overrides applied).
        parameters: serde_json::Value,
        /// Integrator knobs of the run ([`Job::with_knobs`]).
        knobs: clr_models::SolverKnobs,
    },
    /// A validated generic model file.
    Generic(Box<ModelSpec>),
    /// A validated spatial model file.
    Spatial(Box<super::SpatialSpec>),
}

/// The outcome of one run, from a built-in model or a model file.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Model name.
    pub model: String,
    /// `builtin` or the model file path.
    pub source: String,
    /// Time histories (column `t` in s first).
    pub results: clr_mbd::Results,
    /// Unit of each column of `results`, in the same order.
    pub units: Vec<String>,
    /// Scalar metrics.
    pub metrics: Vec<Metric>,
    /// Full resolved parameters.
    pub parameters: serde_json::Value,
    /// The solver's error when the run failed (results are then partial).
    pub error: Option<String>,
    /// Clearance joints that get no orbit figure (translational ones).
    pub no_orbit: Vec<String>,
    /// What reading the model changed on its own (an older file format upgraded, `atol` set
    /// with `--rtol`), one sentence each.
    pub notes: Vec<String>,
    /// The meaning, unit and mode frequencies of the elastic coordinates of every flexible
    /// body and beam of a model file (empty for built-in models).
    pub flexible: Vec<clr_mbd::node_output::FlexibleCoordinates>,
    /// The `[solver]` settings the run used (`rtol`, `atol` in the units of q and q̇, `method`,
    /// `max_steps`, …: with `--rtol`, `--atol` and the other knobs applied); `Null` when a
    /// built-in's run cannot be written as a description.
    pub solver_settings: serde_json::Value,
    /// The built-in's own values of the parameters a run setting replaced in `parameters`
    /// (`rtol` when `--rtol` is given), by name; empty for model files, whose `parameters`
    /// already hold the values used.
    pub builtin_defaults: serde_json::Map<String, serde_json::Value>,
}

/// Load a model with `load` (from a file or text, with the given overrides); a generic model
/// without `[output] t_end` takes `t_end` (the `--t-end` option) instead of being refused.
fn load_with(
    load: impl Fn(&[Assignment]) -> Result<Loaded, SpecError>,
    overrides: &[Assignment],
    t_end: Option<f64>,
) -> Result<Loaded, SpecError> {
    match (load(overrides), t_end) {
        (Err(e), Some(t)) if e.field == "output.t_end" && t.is_finite() && t > 0.0 => {
            let mut sets = overrides.to_vec();
            sets.push(Assignment {
                path: "output.t_end".into(),
                value: toml::Value::Float(t),
            });
            load(&sets)
        }
        (r, _) => r,
    }
}

impl From<Loaded> for Job {
    fn from(l: Loaded) -> Self {
        loaded_job(l)
    }
}

fn loaded_job(l: Loaded) -> Job {
    match l {
        Loaded::Builtin { name, parameters } => Job::Builtin {
            name,
            parameters,
            knobs: Default::default(),
        },
        Loaded::Generic(s) => Job::Generic(s),
        Loaded::Spatial(s) => Job::Spatial(s),
    }
}

/// As [`resolve`] for the text `src` of a model file (either form); `file` names it in
/// messages.
///
/// # Errors
/// As [`resolve`].
pub fn resolve_text(
    file: &str,
    src: &str,
    overrides: &[Assignment],
    t_end: Option<f64>,
    rtol: Option<f64>,
) -> Result<Job, RunError> {
    let loaded = load_with(|o| super::load_str(file, src, o), overrides, t_end)?;
    finish(loaded_job(loaded), t_end, rtol)
}

/// True when `target` names a model file rather than a built-in model.
pub fn is_file(target: &str) -> bool {
    target.ends_with(".toml") || Path::new(target).is_file()
}

/// Resolve a target (a built-in name or a model file path) with its overrides, end time (s)
/// and relative tolerance.
///
/// # Errors
/// [`RunError`] for an unknown name (the message lists the valid ones), a malformed file
/// (file:line: field), a bad override, or a non-positive `t_end`/`rtol`.
pub fn resolve(
    target: &str,
    overrides: &[Assignment],
    t_end: Option<f64>,
    rtol: Option<f64>,
) -> Result<Job, RunError> {
    let job = if is_file(target) {
        loaded_job(load_with(
            |o| super::load(Path::new(target), o),
            overrides,
            t_end,
        )?)
    } else {
        let mut parameters = clr_models::catalog::default_parameters(target).map_err(|_| {
            let names: Vec<&str> = clr_models::catalog::entries()
                .iter()
                .map(|e| e.name)
                .collect();
            RunError::Input(format!(
                "unknown built-in model `{target}`; {} (or give a model file ending in .toml)",
                super::locate::suggestion(target, names.iter().copied())
            ))
        })?;
        for a in overrides {
            apply_json_override(&mut parameters, a)?;
        }
        super::builtin::refuse_unused("--set", "", target, &parameters, None, overrides)?;
        Job::Builtin {
            name: target.to_string(),
            parameters,
            knobs: Default::default(),
        }
    };
    finish(job, t_end, rtol)
}

/// Check `t_end` (s) and `rtol` and set them on a generic model.
fn finish(mut job: Job, t_end: Option<f64>, rtol: Option<f64>) -> Result<Job, RunError> {
    if let Some(t) = t_end {
        if !(t.is_finite() && t > 0.0) {
            return Err(SpecError::plain("--t-end", "", format!("{t} s must be > 0")).into());
        }
    }
    if let Some(r) = rtol {
        if !(r.is_finite() && r > 0.0) {
            return Err(SpecError::plain("--rtol", "", format!("{r} must be > 0")).into());
        }
    }
    match &mut job {
        Job::Generic(s) => {
            if let Some(t) = t_end {
                s.set_t_end(t)?;
            }
            if let Some(r) = rtol {
                s.set_rtol(r)?;
            }
        }
        Job::Spatial(s) => {
            if let Some(t) = t_end {
                s.set_t_end(t)?;
            }
            if let Some(r) = rtol {
                s.set_rtol(r)?;
            }
        }
        Job::Builtin { .. } => {}
    }
    Ok(job)
}

/// The model file of a built-in model with its full parameters (`clr export --builtin`).
///
/// # Errors
/// [`RunError::Input`] for parameters the catalog refuses.
pub fn builtin_file_text(name: &str, parameters: &serde_json::Value) -> Result<String, RunError> {
    #[derive(serde::Serialize)]
    struct ModelPart<'a> {
        builtin: &'a str,
    }
    #[derive(serde::Serialize)]
    struct File<'a> {
        model: ModelPart<'a>,
        parameters: &'a serde_json::Value,
    }
    // parameters the others make unused are left out (a file giving them is refused); they
    // keep their defaults, so the file still reproduces the run
    let unused = clr_models::catalog::unused_parameters(name, parameters)
        .map_err(|e| RunError::Input(e.to_string()))?;
    let mut parameters = parameters.clone();
    if let Some(obj) = parameters.as_object_mut() {
        for (p, _) in &unused {
            obj.remove(*p);
        }
    }
    let left_out = if unused.is_empty() {
        String::new()
    } else {
        let list: Vec<String> = unused
            .iter()
            .map(|(p, why)| format!("#   {p}: {why}\n"))
            .collect();
        format!(
            "# Not written, because these settings do not use them:\n{}",
            list.concat()
        )
    };
    let body = toml::to_string(&File {
        model: ModelPart { builtin: name },
        parameters: &parameters,
    })
    .map_err(|e| {
        RunError::Input(format!(
            "the parameters of `{name}` cannot be written as TOML ({e}); report this"
        ))
    })?;
    Ok(format!(
        "# clr model file: the built-in model `{name}` with every parameter resolved.\n\
         # `clr run <this file>` reproduces `clr run {name}` (with the same --set) bit for bit.\n\
         # Edit any value under [parameters]; units as in docs/model-file.md.\n{left_out}\n{body}"
    ))
}

impl Job {
    /// This job refusing plausibility warnings (`clr run --strict`, Python `strict=True`).
    pub fn strict(mut self) -> Job {
        match &mut self {
            Job::Builtin { knobs, .. } => knobs.strict = true,
            Job::Generic(s) => s.set_strict(),
            Job::Spatial(s) => s.set_strict(),
        }
        self
    }

    /// This job with the integrator knobs of `clr run` (`--max-steps`, `--max-order`,
    /// `--jacobian`, `--scale-velocity-error`): written into a model file's `[solver]`, kept for
    /// a built-in model's run.
    ///
    /// # Errors
    /// [`RunError::Input`] for a value out of range (a step budget of 0, an order outside 1–5).
    pub fn with_knobs(mut self, knobs: clr_models::SolverKnobs) -> Result<Job, RunError> {
        knobs.validate().map_err(RunError::Input)?;
        match &mut self {
            Job::Builtin {
                knobs: k,
                parameters,
                name,
            } => {
                let ndf = knobs.ndf_options();
                if parameters.get("solver").and_then(|s| s.as_str()) == Some("dopri5")
                    && !ndf.is_empty()
                {
                    return Err(RunError::Input(format!(
                        "{}: model `{name}` runs with Dormand–Prince (its `solver` parameter is \
                         \"dopri5\"), which does not use NDF settings; add `--set solver=ndf` \
                         or leave the option out",
                        ndf.join(", ")
                    )));
                }
                *k = knobs;
            }
            Job::Generic(s) => s.set_knobs(&knobs)?,
            Job::Spatial(s) => s.set_knobs(&knobs)?,
        }
        Ok(self)
    }

    /// This job with more assignments (a sweep point): a built-in's parameters or a model
    /// file's description are cloned and changed, not read again; then `t_end` (s) and `rtol`
    /// as in [`resolve`].
    ///
    /// # Errors
    /// [`RunError`] for an assignment that does not apply or a value that is refused.
    pub fn with_overrides(
        &self,
        overrides: &[Assignment],
        t_end: Option<f64>,
        rtol: Option<f64>,
    ) -> Result<Job, RunError> {
        Ok(match self {
            Job::Builtin {
                name,
                parameters,
                knobs,
            } => {
                let mut parameters = parameters.clone();
                for a in overrides {
                    apply_json_override(&mut parameters, a)?;
                }
                super::builtin::refuse_unused("--set", "", name, &parameters, None, overrides)?;
                Job::Builtin {
                    name: name.clone(),
                    parameters,
                    knobs: *knobs,
                }
            }
            Job::Generic(s) => {
                let mut s = s.with_overrides(overrides)?;
                if let Some(t) = t_end {
                    s.set_t_end(t)?;
                }
                if let Some(r) = rtol {
                    s.set_rtol(r)?;
                }
                Job::Generic(Box::new(s))
            }
            Job::Spatial(s) => {
                let s = s.with_overrides(overrides)?;
                finish(Job::Spatial(Box::new(s)), t_end, rtol)?
            }
        })
    }

    /// The model description this job runs (for drawing it): a model file's own, or a
    /// built-in model's complete multibody model (`clr_models::catalog::export`, what `clr
    /// export` writes) with the end time (s) and tolerance of the run.
    ///
    /// # Errors
    /// Why there is none, as a sentence (a built-in whose parameters the export refuses).
    pub fn desc(
        &self,
        t_end: Option<f64>,
        rtol: Option<f64>,
    ) -> Result<clr_mbd::ModelDesc, String> {
        match self {
            Job::Generic(s) => Ok(s.desc().clone()),
            Job::Spatial(_) => {
                Err("a spatial model is drawn in 3-D (the planar drawing does not apply)".into())
            }
            Job::Builtin {
                name, parameters, ..
            } => {
                let settings = RunSettings {
                    t_end,
                    rtol,
                    ..Default::default()
                };
                clr_models::catalog::export(name, parameters, &settings)
                    .map_err(|e| format!("`{name}` cannot be drawn: {e}"))
            }
        }
    }

    /// The resolved model this job runs, as JSON for its provenance hash
    /// (`clr_models::provenance::model_hash`): a model file's description as run (every
    /// default filled in, the `--set` values, `--t-end`, `--rtol` and solver options applied;
    /// the file's path and comments are not part of it), or a built-in's name, resolved
    /// parameters and the description of its run with the end time (s), tolerance and knobs.
    pub fn resolved_model(&self, t_end: Option<f64>, rtol: Option<f64>) -> serde_json::Value {
        match self {
            Job::Generic(s) => serde_json::json!({ "model_file": s.resolved }),
            Job::Spatial(s) => serde_json::json!({ "model_file": s.resolved }),
            Job::Builtin {
                name,
                parameters,
                knobs,
            } => {
                let settings = run_settings(t_end, rtol, *knobs, None);
                let run = clr_models::catalog::export(name, parameters, &settings)
                    .ok()
                    .and_then(|d| serde_json::to_value(d).ok());
                serde_json::json!({ "builtin": name, "parameters": parameters, "run": run })
            }
        }
    }

    /// The simulated span [t0, t_end] (s) of this job run with the `t_end` of [`resolve`]: a
    /// model file's output span, or for a built-in model [0, t_end] with the override or the
    /// model's duration (its `duration` parameter, or the guide's stroke over speed); `None`
    /// when the duration of a built-in model is not known this way.
    pub fn time_span(&self, t_end: Option<f64>) -> Option<(f64, f64)> {
        match self {
            Job::Generic(s) => Some((s.options.t0, s.options.t_end)),
            Job::Spatial(s) => Some((s.options.t0, s.options.t_end)),
            Job::Builtin {
                name, parameters, ..
            } => {
                let end = t_end.or_else(|| {
                    if name == "guide" {
                        serde_json::from_value::<clr_models::guide::GuideParams>(parameters.clone())
                            .ok()
                            .map(|p| p.duration())
                    } else {
                        parameters
                            .get("duration")
                            .and_then(serde_json::Value::as_f64)
                    }
                })?;
                (end.is_finite() && end > 0.0).then_some((0.0, end))
            }
        }
    }
}

/// What an outcome of a model file records of it (planar or spatial).
#[derive(Clone, Copy)]
struct Meta<'a> {
    name: &'a String,
    file: &'a String,
    notes: &'a [String],
    resolved: &'a serde_json::Value,
    clearances: &'a [(String, Option<f64>)],
}

impl<'a> From<&'a ModelSpec> for Meta<'a> {
    fn from(s: &'a ModelSpec) -> Self {
        Self {
            name: &s.name,
            file: &s.file,
            notes: &s.notes,
            resolved: &s.resolved,
            clearances: &s.clearances,
        }
    }
}

impl<'a> From<&'a super::SpatialSpec> for Meta<'a> {
    fn from(s: &'a super::SpatialSpec) -> Self {
        Self {
            name: &s.name,
            file: &s.file,
            notes: &s.notes,
            resolved: &s.resolved,
            clearances: &s.clearances,
        }
    }
}

impl Outcome {
    fn from_output(o: RunOutput, error: Option<String>) -> Self {
        let units = if o.units.len() == o.results.columns.len() {
            o.units
        } else {
            o.results
                .columns
                .iter()
                .map(|c| o.results.unit(c).to_string())
                .collect()
        };
        let notes = o.results.notes.clone();
        Self {
            model: o.model,
            source: "builtin".into(),
            results: o.results,
            units,
            metrics: o.metrics,
            parameters: o.parameters,
            error,
            no_orbit: Vec::new(),
            notes,
            flexible: Vec::new(),
            solver_settings: serde_json::Value::Null,
            builtin_defaults: serde_json::Map::new(),
        }
    }

    fn from_results(
        s: Meta<'_>,
        results: clr_mbd::Results,
        metrics: Vec<Metric>,
        error: Option<String>,
    ) -> Self {
        let units = results
            .columns
            .iter()
            .map(|c| results.unit(c).to_string())
            .collect();
        let notes = s.notes.iter().chain(&results.notes).cloned().collect();
        Self {
            model: s.name.clone(),
            source: s.file.clone(),
            results,
            units,
            metrics,
            parameters: s.resolved.clone(),
            error,
            solver_settings: s.resolved["solver"].clone(),
            builtin_defaults: serde_json::Map::new(),
            // translational clearances of a model file have no orbit
            no_orbit: s
                .clearances
                .iter()
                .filter(|(_, radial)| radial.is_none())
                .map(|(n, _)| n.clone())
                .collect(),
            notes,
            flexible: Vec::new(),
        }
    }

    /// This outcome with the elastic coordinates of its model: their units replace the
    /// name-based ones of their columns (a Craig–Bampton boundary coordinate is in m or rad).
    fn with_flexible(mut self, flexible: Vec<clr_mbd::node_output::FlexibleCoordinates>) -> Self {
        for c in flexible.iter().flat_map(|f| &f.coordinates) {
            if let Some(k) = self.results.index(&c.column) {
                if let Some(u) = self.units.get_mut(k) {
                    *u = c.unit.to_string();
                }
            }
        }
        self.flexible = flexible;
        self
    }

    fn empty(model: &str, parameters: serde_json::Value, error: String) -> Self {
        Self {
            model: model.to_string(),
            source: "builtin".into(),
            results: clr_mbd::Results {
                columns: vec!["t".into()],
                max_position_violation: f64::NAN,
                ..Default::default()
            },
            units: vec!["s".into()],
            metrics: Vec::new(),
            parameters,
            error: Some(error),
            no_orbit: Vec::new(),
            notes: Vec::new(),
            flexible: Vec::new(),
            solver_settings: serde_json::Value::Null,
            builtin_defaults: serde_json::Map::new(),
        }
    }

    /// This built-in outcome with the settings its run used: `solver_settings` from the
    /// description of the run (`clr_models::catalog::export` with the same settings, what the
    /// run compiles), and a `parameters.rtol` replaced by the tolerance `--rtol` gave, the
    /// built-in's own value kept in `builtin_defaults`.
    fn with_settings_used(mut self, name: &str, settings: &RunSettings) -> Self {
        if let Ok(d) = clr_models::catalog::export(name, &self.parameters, settings) {
            self.solver_settings = serde_json::to_value(&d.solver).unwrap_or_default();
        }
        let used = settings.rtol.map(serde_json::Value::from);
        if let (Some(used), Some(own)) = (used, self.parameters.get_mut("rtol")) {
            if *own != used {
                self.builtin_defaults
                    .insert("rtol".into(), std::mem::replace(own, used));
            }
        }
        self
    }
}

/// Run a job with the end time (s) and relative tolerance of [`resolve`]; `progress` is
/// called now and then with the simulated time (s) (about every 1 % of the span, see
/// `clr_mbd::Model::simulate_with`; built-in models that simulate twice, an ideal reference
/// then the clearance run, report both passes). A simulation failure still returns an
/// [`Outcome`] (with `error` set and the rows recorded up to the failure, in every column of a
/// complete run); only bad input is an `Err`.
///
/// # Errors
/// [`RunError`] when the model cannot be built from its parameters.
pub fn execute(
    job: &Job,
    t_end: Option<f64>,
    rtol: Option<f64>,
    progress: Option<Box<dyn Fn(f64) + Send + Sync>>,
) -> Result<Outcome, RunError> {
    match job {
        Job::Builtin {
            name,
            parameters,
            knobs,
        } => {
            let settings = run_settings(t_end, rtol, *knobs, progress);
            // the settings without the progress hook, to describe the run afterwards
            let described = run_settings(t_end, rtol, *knobs, None);
            let outcome = match clr_models::catalog::run(name, parameters, &settings) {
                Ok(o) => Ok(Outcome::from_output(o, None)),
                Err(clr_models::ModelsError::Simulation {
                    message, partial, ..
                }) => match partial {
                    Some(mut o) => {
                        // clr-models leaves the parameters of partial results to the caller
                        if o.parameters.is_null() {
                            o.parameters = parameters.clone();
                        }
                        Ok(Outcome::from_output(*o, Some(message)))
                    }
                    None => Ok(Outcome::empty(name, parameters.clone(), message)),
                },
                Err(e) => Err(RunError::Input(e.to_string())),
            };
            outcome.map(|o| o.with_settings_used(name, &described))
        }
        Job::Spatial(s) => Ok(execute_spatial(s, progress)?),
        Job::Generic(s) => {
            let built = s.build()?;
            let mut model = built.model;
            let flexible = model.flexible_coordinates();
            let hook = |t: f64| {
                if let Some(p) = &progress {
                    p(t);
                }
            };
            let mut twin = None;
            let run = model
                .simulate_with(&built.options, &hook)
                .and_then(|mut r| {
                    twin = clr_mbd::desc::twin::run_twin(s.desc(), &built.options, &mut r)?;
                    Ok(r)
                })
                .map_err(|e| match e {
                    clr_mbd::MbdError::Failed {
                        source,
                        mut partial,
                        cause,
                    } => {
                        // the rows of a failed run get the deviation columns too (every column
                        // of a complete run); a twin that cannot run leaves them NaN
                        match clr_mbd::desc::twin::run_twin(s.desc(), &built.options, &mut partial)
                        {
                            Ok(t) => twin = t,
                            Err(e) => partial
                                .notes
                                .push(format!("deviation measures: not written ({e})")),
                        }
                        clr_mbd::MbdError::Failed {
                            source,
                            partial,
                            cause,
                        }
                    }
                    e => e,
                });
            match run {
                Ok(res) => {
                    let metrics =
                        file_metrics(&res, twin.as_ref(), &s.desc().metrics, s.as_ref().into());
                    Ok(Outcome::from_results(s.as_ref().into(), res, metrics, None)
                        .with_flexible(flexible))
                }
                Err(clr_mbd::MbdError::Failed {
                    source,
                    partial,
                    cause,
                }) => {
                    let msg = format!(
                        "{source} (in the model file these are [solver] max_steps, rtol, atol, \
                         method){cause}"
                    );
                    let metrics = file_metrics(
                        &partial,
                        twin.as_ref(),
                        &s.desc().metrics,
                        s.as_ref().into(),
                    );
                    Ok(
                        Outcome::from_results(s.as_ref().into(), *partial, metrics, Some(msg))
                            .with_flexible(flexible),
                    )
                }
                Err(
                    e @ (clr_mbd::MbdError::Implausible {
                        partial: Some(_), ..
                    }
                    | clr_mbd::MbdError::Stopped { .. }),
                ) => {
                    let msg = e.to_string();
                    let partial = e.into_partial().unwrap_or_default();
                    let metrics = file_metrics(
                        &partial,
                        twin.as_ref(),
                        &s.desc().metrics,
                        s.as_ref().into(),
                    );
                    Ok(
                        Outcome::from_results(s.as_ref().into(), partial, metrics, Some(msg))
                            .with_flexible(flexible),
                    )
                }
                Err(e) => Err(s.model_error(&e).into()),
            }
        }
    }
}

/// Run a spatial model file (as a generic one: a failed run is an [`Outcome`] with `error`).
fn execute_spatial(
    s: &super::SpatialSpec,
    progress: Option<Box<dyn Fn(f64) + Send + Sync>>,
) -> Result<Outcome, RunError> {
    let (mut model, options) = s.build()?;
    let hook = |t: f64| {
        if let Some(p) = &progress {
            p(t);
        }
    };
    let (res, msg) = match model.simulate_with(&options, &hook) {
        Ok(res) => (s.desc().with_measures(res), None),
        Err(clr_mbd::MbdError::Failed {
            source,
            partial,
            cause,
        }) => (
            s.desc().with_measures(*partial),
            Some(format!(
                "{source} (in the model file these are [solver] max_steps, rtol, atol, \
                 method){cause}"
            )),
        ),
        Err(
            e @ (clr_mbd::MbdError::Implausible {
                partial: Some(_), ..
            }
            | clr_mbd::MbdError::Stopped { .. }),
        ) => {
            let msg = e.to_string();
            (
                s.desc().with_measures(e.into_partial().unwrap_or_default()),
                Some(msg),
            )
        }
        Err(e) => return Err(s.model_error(&e).into()),
    };
    let metrics = file_metrics(&res, None, &s.desc().metrics, s.into());
    Ok(Outcome::from_results(s.into(), res, metrics, msg))
}

/// The run settings of a built-in: end time (s), tolerance, knobs and progress hook.
fn run_settings(
    t_end: Option<f64>,
    rtol: Option<f64>,
    knobs: clr_models::SolverKnobs,
    progress: Option<Box<dyn Fn(f64) + Send + Sync>>,
) -> RunSettings {
    RunSettings {
        t_end,
        rtol,
        progress,
        knobs,
    }
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// The metrics of a model file's run (planar or spatial): its `[[metric]]` items, then the generic ones
/// ([`generic_metrics`]) whose names the file does not take: a `[[metric]]` may redefine one
/// (docs/model-file.md).
fn file_metrics<'a>(
    r: &clr_mbd::Results,
    twin: Option<&clr_mbd::Results>,
    descs: &[clr_mbd::desc::metric::MetricDesc],
    meta: Meta<'a>,
) -> Vec<Metric> {
    let mut out = clr_models::described_metrics::evaluate(descs, r, twin);
    for m in generic_metrics(r, meta) {
        if !out.iter().any(|o| o.name == m.name) {
            out.push(m);
        }
    }
    out
}

/// Metrics of a generic model run, computed from its recorded columns.
fn generic_metrics(r: &clr_mbd::Results, s: Meta<'_>) -> Vec<Metric> {
    let mut m = Vec::new();
    for (c, radial) in s.clearances {
        let start = m.len();
        // a spatial journal's impacts are its contact groups' (`c.radial_a`, …)
        let group = format!("{c}.");
        let impacts = || {
            r.impacts
                .iter()
                .filter(|i| &i.joint == c || i.joint.starts_with(&group))
        };
        if let Some(f) = r.column(&format!("{c}.normal_force")) {
            m.push(Metric::new(
                &format!("{c}.peak_normal_force"),
                impacts().fold(max_abs(&f), |a, i| a.max(i.peak_force)),
                "N",
                "largest normal contact force, located on the dense output over the impacts \
                 (the output rows where larger, e.g. a contact at t0)",
            ));
        }
        if let Some(p) = r.column(&format!("{c}.penetration")) {
            let rows = p.iter().fold(f64::NEG_INFINITY, |a, &x| a.max(x));
            m.push(Metric::new(
                &format!("{c}.max_penetration"),
                impacts().fold(rows, |a, i| a.max(i.max_penetration)),
                "m",
                "largest penetration, located on the dense output over the impacts (the \
                 output rows where larger; negative: never in contact)",
            ));
        }
        m.push(Metric::new(
            &format!("{c}.impacts"),
            impacts().count() as f64,
            "-",
            "impacts (located contact onsets to separation) of the clearance joint (of all its \
             contact groups for a spatial journal)",
        ));
        if let Some(first) = impacts().map(|i| i.onset).reduce(f64::min) {
            m.push(Metric::new(
                &format!("{c}.first_impact"),
                first,
                "s",
                "onset time of the first impact",
            ));
        }
        // a model file's metrics skip no transient
        for x in &mut m[start..] {
            x.window = Some(WHOLE_RUN.to_string());
        }
        if let Some(radial) = radial {
            m.push(Metric::new(
                &format!("{c}.radial_clearance"),
                *radial,
                "m",
                "bearing radius minus journal radius",
            ));
        }
        if let Some(f) = r.column(&format!("{c}.Fx")) {
            m.push(
                Metric::new(&format!("{c}.peak_reaction"), max_abs(&f), "N", "").over(WHOLE_RUN),
            );
        }
    }
    m.extend(clr_models::output::energy_metrics(r));
    // as every built-in reports it, so an exported built-in's file reports it too
    m.push(
        Metric::new(
            "steps",
            r.stats.accepted as f64,
            "-",
            "accepted integrator steps",
        )
        .over(WHOLE_RUN),
    );
    m.push(
        Metric::new(
            "contact_onsets",
            r.onsets as f64,
            "-",
            "contact onsets located as events",
        )
        .over(WHOLE_RUN),
    );
    m.push(
        Metric::new(
            "max_position_violation",
            r.max_position_violation,
            "m or rad",
            "largest constraint violation after accepted steps",
        )
        .over(WHOLE_RUN),
    );
    m
}

/// The initial-conditions report as JSON (the `initial_conditions` of summary.json): per body and coordinate whether it was fixed (given)
/// or solved, the given and assembled values and the correction, in the units named; the
/// frames of floating flexible bodies likewise under `flexible_bodies`.
pub fn initial_conditions_json(ic: Option<&clr_mbd::InitialConditions>) -> serde_json::Value {
    let Some(ic) = ic else {
        return serde_json::Value::Null;
    };
    let states =
        |list: &[clr_mbd::BodyInitialState]| -> serde_json::Map<String, serde_json::Value> {
            list.iter()
                .map(|b| {
                    let coords: serde_json::Map<String, serde_json::Value> = b
                        .coordinates
                        .iter()
                        .zip(
                            clr_mbd::COORDINATE_NAMES
                                .iter()
                                .zip(clr_mbd::COORDINATE_UNITS),
                        )
                        .map(|(c, (name, unit))| {
                            let v = serde_json::json!({
                                "status": if !c.fixed { "solved" } else if c.is_corrected() {
                                    "corrected" } else { "given" },
                                "given": c.given,
                                "assembled": c.assembled,
                                "correction": c.correction(),
                                "unit": unit,
                            });
                            (name.to_string(), v)
                        })
                        .collect();
                    (b.body.clone(), serde_json::Value::Object(coords))
                })
                .collect()
        };
    let solved: Vec<serde_json::Value> = ic
        .solved_coordinates
        .iter()
        .map(|c| {
            serde_json::json!({
                "coordinate": format!("{}.{}", c.body, c.coordinate),
                "value": c.value,
                "unit": clr_mbd::initial::unit_of(c.coordinate),
                "from": c.from,
                "undetermined": c.undetermined,
            })
        })
        .collect();
    let counterparts: Vec<serde_json::Value> = ic
        .counterparts
        .iter()
        .map(|c| {
            serde_json::json!({
                "element": c.element,
                "positions": c.positions,
                "velocities": c.velocities,
                "offset": c.offset,
                "offset_unit": "m",
                "dropped_rows": c.dropped,
            })
        })
        .collect();
    let mut json = serde_json::json!({
        "position_newton_iterations": ic.newton_iterations,
        "solved": ic.solved().len(),
        "corrected": ic.corrected().len(),
        "bodies": states(&ic.bodies),
        "solved_coordinates": solved,
        "ideal_counterparts": counterparts,
    });
    // the frame origins of floating flexible bodies (their elastic coordinates are never moved)
    if !ic.flexible.is_empty() {
        json["flexible_bodies"] = serde_json::Value::Object(states(&ic.flexible));
    }
    json
}

/// The elastic coordinates of the flexible bodies and beams as JSON (the `flexible_bodies` of
/// summary.json): per body its kind, reduction, the column, meaning and unit of every elastic
/// coordinate and the frequencies (Hz) of the kept modes.
pub fn flexible_json(flexible: &[clr_mbd::node_output::FlexibleCoordinates]) -> serde_json::Value {
    let bodies: serde_json::Map<String, serde_json::Value> = flexible
        .iter()
        .map(|f| {
            let coordinates: Vec<serde_json::Value> = f
                .coordinates
                .iter()
                .map(|c| {
                    serde_json::json!({
                        "column": c.column, "meaning": c.meaning, "unit": c.unit,
                    })
                })
                .collect();
            let v = serde_json::json!({
                "kind": f.kind,
                "reduction": f.reduction,
                "coordinates": coordinates,
                "mode_frequencies_hz": f.mode_frequencies_hz,
            });
            (f.body.clone(), v)
        })
        .collect();
    serde_json::Value::Object(bodies)
}

pub use clr_mbd::results::unit_of;
