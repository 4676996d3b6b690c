//! Whole clr models from Python: `list_models` and `run_model`, through the same library path
//! as `clr run` (`clr::spec::run::resolve` then `execute`), so a run from Python and one from
//! the command line with the same input give the same numbers bit for bit.

use clr::spec::run::{self, Outcome};
use clr::spec::{overrides_value, Assignment};
use numpy::{IntoPyArray, PyArray1};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

create_exception!(
    _native,
    ModelError,
    PyValueError,
    "Invalid model name, model file or override; the message says what to change."
);

/// Every built-in model as `(name, description)`.
#[pyfunction]
pub(crate) fn list_models() -> Vec<(&'static str, &'static str)> {
    clr_models::catalog::entries()
        .iter()
        .map(|e| (e.name, e.description))
        .collect()
}

/// A Python override value as the TOML value `clr run --set` would parse: bool, int, float,
/// lists of these, or a string (parsed as TOML text when it is one, else a bare word).
fn toml_value(path: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(v.extract().map_err(|_| {
            ModelError::new_err(format!(
                "set[{path:?}]: the integer does not fit in 64 bits"
            ))
        })?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(overrides_value(&s.to_cow()?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items = v
            .try_iter()?
            .map(|x| toml_value(path, &x?))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(toml::Value::Array(items));
    }
    // numpy scalars and other numbers
    if let Ok(f) = v.extract::<f64>() {
        return Ok(toml::Value::Float(f));
    }
    Err(ModelError::new_err(format!(
        "set[{path:?}]: a {} cannot be a parameter value; give a number, bool, string or list",
        v.get_type().name()?
    )))
}

/// The outcome as a dict: `time` and every other column as float64 arrays, `units` (column →
/// unit, `time` → `s`), `metrics` (name → value), `metric_units`, `impacts` (list of dicts,
/// [`impacts_list`]), `notes` (what the run changed or chose for the user, one sentence each),
/// `initial_conditions` (JSON text: per body and coordinate fixed/solved/corrected with the given
/// and assembled values, as in summary.json), `parameters` (JSON text), `model`, `source` and `error` (`None`, or the solver's message when the results are partial).
fn outcome_dict<'py>(py: Python<'py>, o: Outcome) -> PyResult<Bound<'py, PyDict>> {
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
    d.set_item(
        "initial_conditions",
        clr::spec::run::initial_conditions_json(o.results.initial_conditions.as_ref()).to_string(),
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
    impacts: &[clr::mbd::Impact],
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

/// Run a built-in model (by name) or a model file (a path ending in `.toml`, or any existing
/// file) as `clr run` does, with `set` overrides (dotted name → value), end time `t_end` (s) and
/// relative tolerance `rtol`; the simulation runs without the GIL.
#[pyfunction]
#[pyo3(signature = (target, set=None, t_end=None, rtol=None))]
pub(crate) fn run_model<'py>(
    py: Python<'py>,
    target: &str,
    set: Option<&Bound<'py, PyDict>>,
    t_end: Option<f64>,
    rtol: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut overrides = Vec::new();
    if let Some(set) = set {
        for (k, v) in set.iter() {
            let path: String = k.extract().map_err(|_| {
                ModelError::new_err("the keys of `set` must be dotted names like \"solver.rtol\"")
            })?;
            let value = toml_value(&path, &v)?;
            overrides.push(Assignment { path, value });
        }
    }
    let target = target.to_string();
    let outcome = py
        .detach(move || {
            let job = run::resolve(&target, &overrides, t_end, rtol)?;
            run::execute(&job, t_end, rtol, None)
        })
        .map_err(|e| ModelError::new_err(e.to_string()))?;
    outcome_dict(py, outcome)
}
