//! Whole clr models from Python: [`JobCore`] (a resolved built-in or generic model, from a
//! name, a file, TOML text or the dict a `clr.Model` builds), `list_models`, the studies, and
//! what the builder checks itself against (`element_kinds`, `kind_fields`). Everything goes
//! through the library path of `clr run` (`clr_sim::spec::run::resolve` then `execute`), so a run
//! from Python and one from the command line with the same input give the same numbers bit for
//! bit.

use std::time::Instant;

use clr_sim::spec::run::{self, Job, Outcome};
use clr_sim::spec::Assignment;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert;
use crate::errors::{field_error, override_error, run_error, spec_error};

/// Every built-in model as `(name, description)`.
#[pyfunction]
pub(crate) fn list_models() -> Vec<(&'static str, &'static str)> {
    clr_models::catalog::entries()
        .iter()
        .map(|e| (e.name, e.description))
        .collect()
}

/// The outcome as a dict: `time` and every other column as float64 arrays, `units` (column →
/// unit, `time` → `s`), `metrics` (name → value), `metric_units`, `impacts` (list of dicts,
/// [`impacts_list`]), `notes` (what the run changed or chose for the user, one sentence each),
/// `warnings` (the plausibility checks' findings, dicts of `field` and `message`),
/// `initial_conditions` (JSON text: per body and coordinate fixed/solved/corrected with the given
/// and assembled values, as in summary.json), `parameters` (JSON text), `model`, `source` and `error` (`None`, or the solver's message when the results are partial).
pub(crate) fn outcome_dict<'py>(py: Python<'py>, o: Outcome) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let units = PyDict::new(py);
    let n = o.results.columns.len();
    let rows = o.results.len();
    for (k, (c, u)) in o.results.columns.iter().zip(&o.units).enumerate() {
        let key = if c == "t" { "time" } else { c.as_str() };
        let col: Vec<f64> = (0..rows).map(|r| o.results.data[r * n + k]).collect();
        let arr: Bound<'py, PyArray1<f64>> = col.into_pyarray(py);
        d.set_item(key, arr)?;
        units.set_item(key, u)?;
    }
    d.set_item("units", units)?;
    let metrics = PyDict::new(py);
    let metric_units = PyDict::new(py);
    for m in &o.metrics {
        metrics.set_item(&m.name, m.value)?;
        metric_units.set_item(&m.name, &m.unit)?;
    }
    d.set_item("metrics", metrics)?;
    d.set_item("metric_units", metric_units)?;
    d.set_item("impacts", impacts_list(py, &o.results.impacts)?)?;
    d.set_item("notes", o.notes.clone())?;
    let warnings = PyList::empty(py);
    for w in &o.results.warnings {
        let item = PyDict::new(py);
        item.set_item("field", &w.field)?;
        item.set_item("message", &w.message)?;
        warnings.append(item)?;
    }
    d.set_item("warnings", warnings)?;
    d.set_item(
        "initial_conditions",
        clr_sim::spec::run::initial_conditions_json(o.results.initial_conditions.as_ref())
            .to_string(),
    )?;
    d.set_item("parameters", o.parameters.to_string())?;
    d.set_item("model", o.model)?;
    d.set_item("source", o.source)?;
    d.set_item("error", o.error)?;
    Ok(d)
}

/// The located impacts as a list of dicts with the columns of `impacts.csv` (docs/cli.md):
/// `joint`, `onset_s`, `impact_velocity_m_per_s`, `peak_force_N`, `peak_force_time_s`,
/// `max_penetration_m`, `max_penetration_time_s`, `separation_s` and `duration_s` (`None` while
/// the contact lasts at the end of the run).
fn impacts_list<'py>(
    py: Python<'py>,
    impacts: &[clr_sim::mbd::Impact],
) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for i in impacts {
        let d = PyDict::new(py);
        d.set_item("joint", &i.joint)?;
        d.set_item("onset_s", i.onset)?;
        d.set_item("impact_velocity_m_per_s", i.impact_velocity)?;
        d.set_item("peak_force_N", i.peak_force)?;
        d.set_item("peak_force_time_s", i.peak_force_time)?;
        d.set_item("max_penetration_m", i.max_penetration)?;
        d.set_item("max_penetration_time_s", i.max_penetration_time)?;
        d.set_item("separation_s", i.separation)?;
        d.set_item("duration_s", i.duration)?;
        list.append(d)?;
    }
    Ok(list)
}

/// `set=` overrides (dotted name → value; strings read as on the command line).
pub(crate) fn assignments(set: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<Assignment>> {
    let mut overrides = Vec::new();
    if let Some(set) = set {
        for (k, v) in set.iter() {
            let path: String = k.extract().map_err(|_| {
                override_error(
                    set.py(),
                    &k.to_string(),
                    "the keys of `set` must be dotted names like \"solver.rtol\"",
                )
            })?;
            let value = convert::value(&path, &v, true)?;
            overrides.push(Assignment { path, value });
        }
    }
    Ok(overrides)
}

/// A resolved model, ready to run: a built-in with its parameters or a checked generic model
/// (plain data, run without the GIL), with the end time (s) and relative tolerance it was
/// resolved with.
#[pyclass(frozen, module = "clr_sim._native")]
pub(crate) struct JobCore {
    pub(crate) job: Job,
    pub(crate) t_end: Option<f64>,
    pub(crate) rtol: Option<f64>,
}

impl JobCore {
    fn resolved(
        py: Python<'_>,
        r: Result<Job, run::RunError>,
        t_end: Option<f64>,
        rtol: Option<f64>,
    ) -> PyResult<Self> {
        r.map(|job| Self { job, t_end, rtol })
            .map_err(|e| run_error(py, &e))
    }
}

#[pymethods]
impl JobCore {
    /// A built-in model by name or a model file by path, as `clr run TARGET --set ...`.
    #[staticmethod]
    #[pyo3(signature = (target, set=None, t_end=None, rtol=None))]
    fn from_target(
        py: Python<'_>,
        target: &str,
        set: Option<&Bound<'_, PyDict>>,
        t_end: Option<f64>,
        rtol: Option<f64>,
    ) -> PyResult<Self> {
        let sets = assignments(set)?;
        let target = target.to_string();
        let r = py.detach(move || run::resolve(&target, &sets, t_end, rtol));
        Self::resolved(py, r, t_end, rtol)
    }

    /// A model from the text of a model file (either form); `label` names it in errors.
    #[staticmethod]
    #[pyo3(signature = (text, label, set=None, t_end=None, rtol=None))]
    fn from_text(
        py: Python<'_>,
        text: &str,
        label: &str,
        set: Option<&Bound<'_, PyDict>>,
        t_end: Option<f64>,
        rtol: Option<f64>,
    ) -> PyResult<Self> {
        let sets = assignments(set)?;
        let (text, label) = (text.to_string(), label.to_string());
        let r = py.detach(move || run::resolve_text(&label, &text, &sets, t_end, rtol));
        Self::resolved(py, r, t_end, rtol)
    }

    /// A model from the dict of a model file (`{"model": {...}, "body": [...], ...}`, what
    /// `clr.Model` builds); `label` names it in errors.
    #[staticmethod]
    #[pyo3(signature = (doc, label, set=None, t_end=None, rtol=None))]
    fn from_dict(
        py: Python<'_>,
        doc: &Bound<'_, PyDict>,
        label: &str,
        set: Option<&Bound<'_, PyDict>>,
        t_end: Option<f64>,
        rtol: Option<f64>,
    ) -> PyResult<Self> {
        let text = dict_to_toml(doc)?;
        Self::from_text(py, &text, label, set, t_end, rtol)
    }

    /// Check the element at `element` (`clearance[2]`, or a table: `solver`) of the model
    /// being built, `doc` (the model so far with that element in it), with the model-file
    /// reader in the context of the model so far: the same `clr_sim::spec::load_str` that reads
    /// files and `simulate()` uses.
    ///
    /// Returns `None` when the element reads; raises the reader's `FieldError` when the error
    /// is in the element itself (or its name is taken: a duplicate is placed at the item the
    /// reader claims second, which may be an earlier one); returns the reader's message (the
    /// check is left to the run) when the element names a body, point, beam or shape not yet
    /// defined (a model file may define its items in any order), or when the reader stops at
    /// another error first. Earlier elements still waiting for a name are left out of the
    /// checked copy ([`check_in_context`]).
    ///
    /// Two stand-ins let a model under construction read: a probe body when nothing moves
    /// yet, and `output.t_end` (1 s after the start) when it is not given yet; both are only
    /// in the checked copy.
    #[staticmethod]
    fn _check_element(
        py: Python<'_>,
        doc: &Bound<'_, PyDict>,
        element: &str,
        label: &str,
    ) -> PyResult<Option<String>> {
        let mut root = convert::table("", doc, false)?;
        probe_stand_ins(&mut root);
        let label = label.to_string();
        let element_owned = element.to_string();
        match py.detach(move || check_in_context(root, &element_owned, &label)) {
            Verdict::Reads => Ok(None),
            Verdict::Deferred(message) => Ok(Some(message)),
            Verdict::Refused(e) => Err(spec_error(py, &e)),
        }
    }

    /// `builtin` for a catalog model, `generic` for a model description.
    #[getter]
    fn kind(&self) -> &'static str {
        match self.job {
            Job::Builtin { .. } => "builtin",
            Job::Generic(_) => "generic",
            Job::Spatial(_) => "spatial",
        }
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> String {
        match &self.job {
            Job::Builtin { name, .. } => name.clone(),
            Job::Generic(s) => s.name.clone(),
            Job::Spatial(s) => s.name.clone(),
        }
    }

    /// What reading the model changed on its own, one sentence each.
    #[getter]
    fn notes(&self) -> Vec<String> {
        match &self.job {
            Job::Builtin { .. } => Vec::new(),
            Job::Generic(s) => s.notes.clone(),
            Job::Spatial(s) => s.notes.clone(),
        }
    }

    /// The feedback columns a state-dependent input function receives
    /// (`clr_mbd::Model::feedback_columns`); a generic model file only.
    fn feedback_columns(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        let Job::Generic(s) = &self.job else {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "inputs given as functions need a planar model file or Model (not a built-in \
                 name or a spatial model)",
            ));
        };
        let built = s
            .build()
            .map_err(|e| run_error(py, &run::RunError::from(e)))?;
        Ok(built.model.feedback_columns())
    }

    /// This job with the load input `name` made the Python callable `f(t, values)` (values: a
    /// tuple in the order of `feedback_columns`), called with the GIL at every evaluation of
    /// the forces. An
    /// exception inside is kept in `errors` (a list) and the value becomes NaN, which stops the
    /// run.
    fn with_input_function(
        &self,
        name: &str,
        f: Py<PyAny>,
        errors: Py<pyo3::types::PyList>,
    ) -> PyResult<JobCore> {
        let mut job = self.job.clone();
        let Job::Generic(s) = &mut job else {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "inputs given as functions need a planar model file or Model (not a built-in \
                 name or a spatial model)",
            ));
        };
        let func: clr_sim::mbd::input::InputFn = std::sync::Arc::new(move |t, values| {
            Python::attach(|py| {
                let args = (
                    t,
                    pyo3::types::PyTuple::new(py, values.iter().copied()).ok(),
                );
                match f.call1(py, args).and_then(|v| v.extract::<f64>(py)) {
                    Ok(v) => v,
                    Err(e) => {
                        let errs = errors.bind(py);
                        if errs.is_empty() {
                            let _ = errs.append(e.value(py));
                        }
                        f64::NAN
                    }
                }
            })
        });
        s.set_input_function(name, func);
        Ok(JobCore {
            job,
            t_end: self.t_end,
            rtol: self.rtol,
        })
    }

    /// The checked description as model-file text (every default written out), as `clr
    /// export` writes it; a built-in model as its `[model] builtin` form with every parameter.
    fn to_toml(&self, py: Python<'_>) -> PyResult<String> {
        match &self.job {
            Job::Generic(s) => s
                .desc()
                .to_toml()
                .map_err(|m| run_error(py, &run::RunError::Input(m))),
            Job::Spatial(s) => s
                .desc()
                .to_toml()
                .map_err(|m| run_error(py, &run::RunError::Input(m))),
            Job::Builtin {
                name, parameters, ..
            } => run::builtin_file_text(name, parameters).map_err(|e| run_error(py, &e)),
        }
    }

    /// Run it (without the GIL) as `clr run` does (`strict`: as `clr run --strict`); the
    /// outcome dict of [`outcome_dict`] with `wall_s`, the wall time (s).
    #[pyo3(signature = (strict = false))]
    fn run<'py>(&self, py: Python<'py>, strict: bool) -> PyResult<Bound<'py, PyDict>> {
        let start = Instant::now();
        let job = if strict {
            self.job.clone().strict()
        } else {
            self.job.clone()
        };
        let outcome = py
            .detach(|| run::execute(&job, self.t_end, self.rtol, None))
            .map_err(|e| run_error(py, &e))?;
        let d = outcome_dict(py, outcome)?;
        d.set_item("wall_s", start.elapsed().as_secs_f64())?;
        Ok(d)
    }
}

/// The dict of a model file as TOML text (model-file structure; `None` values left out).
fn dict_to_toml(doc: &Bound<'_, PyDict>) -> PyResult<String> {
    let table = convert::table("", doc, false)?;
    toml::to_string(&toml::Value::Table(table))
        .map_err(|e| field_error(doc.py(), "", &format!("cannot be written as TOML: {e}")))
}

/// The probe body of [`JobCore::_check_element`] (a name no model uses).
const PROBE_BODY: &str = "__clr_sim_probe_body__";

/// Stand-ins that let a model under construction read: a free body when nothing moves yet,
/// and an end time when `[output]` has none yet (1 s after `t_start`).
fn probe_stand_ins(root: &mut toml::Table) {
    let moves = ["body", "beam", "flexible_body"].iter().any(|s| {
        root.get(*s)
            .and_then(toml::Value::as_array)
            .is_some_and(|a| !a.is_empty())
    });
    if !moves {
        let zeros = |n: usize| toml::Value::Array(vec![0.0.into(); n]);
        let mut body = toml::Table::new();
        body.insert("name".into(), PROBE_BODY.into());
        body.insert("mass".into(), 1.0.into());
        if is_spatial(root) {
            // a unit sphere's inertia at the body origin, aligned with the world
            body.insert(
                "principal_inertia".into(),
                toml::Value::Array(vec![1.0.into(); 3]),
            );
            body.insert("position".into(), zeros(3));
        } else {
            body.insert("inertia".into(), 1.0.into());
            body.insert("position".into(), zeros(2));
            body.insert("angle".into(), 0.0.into());
        }
        root.insert(
            "body".into(),
            toml::Value::Array(vec![toml::Value::Table(body)]),
        );
    }
    let output = root
        .entry("output")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
    if let Some(out) = output.as_table_mut() {
        if !out.contains_key("t_end") {
            let start = match out.get("t_start") {
                Some(toml::Value::Float(f)) if f.is_finite() => *f,
                Some(toml::Value::Integer(i)) => *i as f64,
                _ => 0.0,
            };
            out.insert("t_end".into(), (start + 1.0).into());
        }
    }
}

/// Whether the model being built says `[model] space = "spatial"` (as the reader decides).
fn is_spatial(root: &toml::Table) -> bool {
    root.get("model")
        .and_then(|m| m.get("space"))
        .and_then(toml::Value::as_str)
        == Some("spatial")
}

/// What the reader says of one element in the context of the model so far.
enum Verdict {
    /// The element reads.
    Reads,
    /// Left to the run, with the reader's message: the element names an item not defined yet,
    /// or the reader stopped at another error first.
    Deferred(String),
    /// The element's own error, placed at its field.
    Refused(clr_sim::spec::SpecError),
}

/// `section[k]` of a field path (`joint[1].b.body` → `("joint", 1)`).
fn item_of(field: &str) -> Option<(String, usize)> {
    let (section, rest) = field.split_once('[')?;
    let (k, _) = rest.split_once(']')?;
    Some((section.to_string(), k.parse().ok()?))
}

/// Whether `field` is the element at `element` (`clearance[2]`, `solver`) or inside it.
fn within(field: &str, element: &str) -> bool {
    field == element
        || field.starts_with(&format!("{element}."))
        || field.starts_with(&format!("{element}["))
}

/// Check the element at `element` of `root` (the model so far with it, stand-ins added) with
/// the model-file reader. An earlier item that still names something not defined would stop
/// the reader before this element's compiled checks: it is left out of the checked copy and
/// the copy read again (an element naming a left-out item is then itself left to the run).
fn check_in_context(mut root: toml::Table, element: &str, label: &str) -> Verdict {
    let mut probe = element.to_string();
    loop {
        let text = match toml::to_string(&root) {
            Ok(t) => t,
            Err(e) => return Verdict::Deferred(format!("cannot be written as TOML: {e}")),
        };
        let Err(mut e) = clr_sim::spec::load_str(label, &text, &[]) else {
            return Verdict::Reads;
        };
        let duplicate = item_name(&root, &probe)
            .is_some_and(|n| e.message.starts_with(&format!("duplicate name `{n}`")));
        let reference = names_an_undefined_item(root.clone(), &e.message);
        if within(&e.field, &probe) || duplicate {
            if reference {
                return Verdict::Deferred(e.to_string());
            }
            if let Some(rest) = e.field.strip_prefix(probe.as_str()) {
                e.field = format!("{element}{rest}");
            }
            return Verdict::Refused(e);
        }
        let earlier = item_of(&e.field);
        let Some((section, k)) = earlier.filter(|_| reference) else {
            return Verdict::Deferred(e.to_string());
        };
        let Some(items) = root.get_mut(&section).and_then(toml::Value::as_array_mut) else {
            return Verdict::Deferred(e.to_string());
        };
        if k >= items.len() {
            return Verdict::Deferred(e.to_string());
        }
        items.remove(k);
        if let Some((s, j)) = item_of(&probe) {
            if s == section && k < j {
                probe = format!("{s}[{}]", j - 1);
            }
        }
    }
}

/// The name of the item at `element` (`clearance[2]`) in `root`.
fn item_name<'a>(root: &'a toml::Table, element: &str) -> Option<&'a str> {
    let (section, rest) = element.split_once('[')?;
    let k: usize = rest.strip_suffix(']')?.parse().ok()?;
    root.get(section)?.as_array()?.get(k)?.get("name")?.as_str()
}

/// Whether the reader's error `message` for the description in `root` is that an item names a
/// body, beam, point or shape that is not defined (the one kind of error a model under
/// construction may have for now: the named item can still be added).
fn names_an_undefined_item(root: toml::Table, message: &str) -> bool {
    use clr_sim::mbd::MbdError as E;
    if is_spatial(&root) {
        return spatial_names_an_undefined_item(root, message);
    }
    let Ok(desc) = clr_sim::mbd::ModelDesc::from_toml_table(root) else {
        return false;
    };
    let e = match desc.compile() {
        Err(e) if e.to_string().ends_with(message) => e,
        _ => return false,
    };
    match e {
        E::UnknownBody { .. } | E::UnknownPoint { .. } => true,
        E::Invalid { path, message } => {
            (path.contains(".shapes[") && message.starts_with("no [[shape]] named"))
                || (path.starts_with("output.nodes.")
                    && message.contains("is not a flexible body or beam"))
                // a measure or metric naming a column of an item (joint, contact element,
                // measure) not defined yet
                || message.starts_with("the model writes no column")
                // an input referred to before its [[input]], or declared before its user
                || message.starts_with("no [[input]] is named")
                || message.contains("is declared but nothing refers to it")
                || message.starts_with("the run writes no column")
                || message.ends_with("the run writes no such column")
        }
        _ => false,
    }
}

/// [`names_an_undefined_item`] of a spatial model: a body, a joint that a driver or a
/// rotational spring–damper names (`clr_mbd::spatial` compile, `unknown joint`), or a shape that
/// a contact names.
fn spatial_names_an_undefined_item(root: toml::Table, message: &str) -> bool {
    use clr_sim::mbd::MbdError as E;
    let Ok(desc) = clr_sim::mbd::spatial::SpatialDesc::from_toml_table(root) else {
        return false;
    };
    match desc.compile() {
        Err(e) if e.to_string().ends_with(message) => match e {
            E::UnknownBody { .. } => true,
            E::Invalid { path, message } => {
                (path.ends_with(".joint") && message.starts_with("unknown joint"))
                    || (path.contains(".shapes[") && message.starts_with("no [[shape]] named"))
            }
            _ => false,
        },
        _ => false,
    }
}

/// The paper studies as `(name, model, description)`.
#[pyfunction]
pub(crate) fn list_studies() -> Vec<(&'static str, &'static str, &'static str)> {
    clr_models::studies::studies()
        .iter()
        .map(|s| (s.name, s.model, s.description))
        .collect()
}

/// Run the paper study `name` into the folder `out` (CSV per run, summary.csv, figures), as
/// `clr study`; returns the number of runs. Runs without the GIL.
#[pyfunction]
pub(crate) fn run_study(py: Python<'_>, name: &str, out: std::path::PathBuf) -> PyResult<usize> {
    let study = clr_models::studies::find(name).map_err(|m| {
        run_error(
            py,
            &run::RunError::Input(format!("unknown built-in model study: {m}")),
        )
    })?;
    py.detach(|| {
        std::fs::create_dir_all(&out)
            .map_err(|e| format!("cannot create {}: {e}", out.display()))?;
        (study.run)(&out)
    })
    .map_err(pyo3::exceptions::PyRuntimeError::new_err)
}

/// The reader's message for the probe model `text` (empty if it reads).
fn probe_message(text: &str) -> String {
    match clr_sim::spec::load_str("<probe>", text, &[]) {
        Err(e) => e.message,
        Ok(_) => String::new(),
    }
}

/// The comma-separated names after `marker` in `message`.
fn names_after(message: &str, marker: &str) -> Option<Vec<String>> {
    message
        .split_once(marker)
        .map(|(_, list)| list.split(", ").map(|f| f.trim().to_string()).collect())
}

const PROBE: &str = "zz_probe_field_zz";

/// The headers of a probe item in `section`: `[solver]`, `[[body]]`, or the tables inside a
/// shape (`shape.geometry`, the parts of a compound `shape.geometry.parts`); `None` for any
/// other dotted name.
fn probe_header(section: &str) -> Option<String> {
    Some(match section {
        "model" | "twin" | "solver" | "output" => format!("[{section}]"),
        "shape.geometry" => "[[shape]]\n[shape.geometry]".to_string(),
        "shape.geometry.parts" => {
            "[[shape]]\n[shape.geometry]\ntype = \"compound\"\n[[shape.geometry.parts]]".to_string()
        }
        s if s.contains('.') => return None,
        s => format!("[[{s}]]"),
    })
}

/// The engine a probe is for: `space` of [`element_kinds`] and [`kind_fields`] (`None` or
/// `"planar"`, or `"spatial"`).
fn is_spatial_space(space: Option<&str>) -> PyResult<bool> {
    match space {
        None | Some("planar") => Ok(false),
        Some("spatial") => Ok(true),
        Some(other) => Err(pyo3::exceptions::PyValueError::new_err(format!(
            "unknown space `{other}`: give \"planar\" or \"spatial\""
        ))),
    }
}

/// The first lines of a spatial probe file.
const SPATIAL_HEADER: &str = "[model]\nspace = \"spatial\"\n";

/// The names the reader lists in `message`: its own lists (`valid fields here: a, b`,
/// `valid: a, b`), or serde's (`expected one of `a`, `b`, `c``, `expected `a` or `b`` for two,
/// `expected `a`` for one).
fn expected_names(message: &str) -> Option<Vec<String>> {
    let list = names_after(message, "valid fields here: ")
        .or_else(|| names_after(message, "valid: "))
        .or_else(|| names_after(message, "expected one of "))
        .or_else(|| names_after(message, "expected "))?;
    Some(
        list.iter()
            .flat_map(|n| n.split(" or "))
            .map(|n| n.trim_matches('`').to_string())
            .collect(),
    )
}

/// Every section of a model file, in the order the reader lists them, with its element kinds
/// (`type` values; empty for the sections without one), then the tagged tables inside items
/// (`shape.geometry` with its geometry types), for the builder's consistency check. With
/// `space = "spatial"`, those of a spatial model file (no tagged tables inside items).
#[pyfunction]
#[pyo3(signature = (space=None))]
pub(crate) fn element_kinds(space: Option<&str>) -> PyResult<Vec<(String, Vec<String>)>> {
    if is_spatial_space(space)? {
        return spatial_element_kinds();
    }
    use clr_sim::mbd::element::{Clearance, Driver, Force, Joint};
    use clr_sim::mbd::Measure;
    let tagged: [(&str, &[&str]); 5] = [
        ("joint", Joint::KINDS),
        ("driver", Driver::KINDS),
        ("force", Force::KINDS),
        ("clearance", Clearance::KINDS),
        ("measure", Measure::KINDS),
    ];
    let probe = |text: &str, marker: &str, what: &str| {
        let message = probe_message(text);
        names_after(&message, marker).ok_or_else(|| {
            pyo3::exceptions::PyValueError::new_err(format!("no list of {what}: {message}"))
        })
    };
    let sections = probe(&format!("{PROBE} = 0\n"), "valid fields here: ", "sections")?;
    let mut out: Vec<(String, Vec<String>)> = sections
        .into_iter()
        .map(|s| {
            let kinds = tagged
                .iter()
                .find(|(t, _)| *t == s)
                .map(|(_, k)| k.iter().map(|k| k.to_string()).collect())
                .unwrap_or_default();
            (s, kinds)
        })
        .collect();
    let geometries = probe(
        &format!("[[shape]]\n[shape.geometry]\ntype = \"{PROBE}\"\n"),
        "valid: ",
        "geometry types",
    )?;
    out.push(("shape.geometry".to_string(), geometries));
    Ok(out)
}

/// [`element_kinds`] of a spatial model file, as the spatial reader (serde) lists its sections
/// and the `type` values of joints, drivers, forces and clearances.
fn spatial_element_kinds() -> PyResult<Vec<(String, Vec<String>)>> {
    let probe = |text: &str, what: &str| {
        let message = probe_message(&format!("{PROBE} = 0\n{SPATIAL_HEADER}{text}"));
        expected_names(&message).ok_or_else(|| {
            pyo3::exceptions::PyValueError::new_err(format!("no list of {what}: {message}"))
        })
    };
    let sections = probe("", "sections")?;
    let mut out = Vec::new();
    for s in sections {
        let kinds = if ["joint", "driver", "force", "clearance", "measure"].contains(&s.as_str()) {
            let message = probe_message(&format!("{SPATIAL_HEADER}[[{s}]]\ntype = \"{PROBE}\"\n"));
            expected_names(&message).ok_or_else(|| {
                pyo3::exceptions::PyValueError::new_err(format!("no kinds of [[{s}]]: {message}"))
            })?
        } else {
            Vec::new()
        };
        out.push((s, kinds));
    }
    Ok(out)
}

/// The fields an item of `section` (of kind `kind` for the sections with a `type`) accepts, as
/// the model-file reader lists them: the builder's methods are checked against these. Besides
/// the sections, `shape.geometry` (with its `type` as `kind`) and `shape.geometry.parts` (a
/// part of a compound geometry). With `space = "spatial"`, those of a spatial model file
/// (without `type`, which the builder's method gives).
#[pyfunction]
#[pyo3(signature = (section, kind=None, space=None))]
pub(crate) fn kind_fields(
    section: &str,
    kind: Option<&str>,
    space: Option<&str>,
) -> PyResult<Vec<String>> {
    let item = match kind {
        Some(k) => format!("type = \"{k}\"\n{PROBE} = 0\n"),
        None => format!("{PROBE} = 0\n"),
    };
    if is_spatial_space(space)? {
        let text = match section {
            "model" => format!("{SPATIAL_HEADER}{item}"),
            "solver" | "output" => format!("{SPATIAL_HEADER}[{section}]\n{item}"),
            s => format!("{SPATIAL_HEADER}[[{s}]]\n{item}"),
        };
        let message = probe_message(&text);
        let names = expected_names(&message).ok_or_else(|| {
            pyo3::exceptions::PyValueError::new_err(format!(
                "no field list for spatial [{section}] {kind:?}: {message}"
            ))
        })?;
        return Ok(names.into_iter().filter(|n| n != "type").collect());
    }
    let header = probe_header(section).ok_or_else(|| {
        pyo3::exceptions::PyValueError::new_err(format!("no probe for [{section}]"))
    })?;
    let message = probe_message(&format!("{header}\n{item}"));
    names_after(&message, "valid fields here: ").ok_or_else(|| {
        pyo3::exceptions::PyValueError::new_err(format!(
            "no field list for [{section}] {kind:?}: {message}"
        ))
    })
}
