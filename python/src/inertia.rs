//! `clr_sim.inertia`: mass properties of common parts, computed by the model-file reader's own
//! code (clr-mbd `desc::inertia` through `Body::resolve`), so a part built in Python and a
//! `[[body]]` with the same `shape`, `material`/`density` and `between` get the same numbers
//! bit for bit and the same refusals.

use clr_sim::mbd::{Body, MbdError, ModelDesc};
use clr_sim::spec::SpecError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A refusal as `clr_sim.errors.FieldError` at the argument it names (`width`, `material`).
fn field_error(py: Python<'_>, field: &str, message: &str) -> PyErr {
    crate::errors::spec_error(py, &SpecError::plain("clr_sim.inertia", field, message))
}

/// The mass properties of the `[[body]]` table `table` (a dict with `shape` and `material`
/// or `density`, optionally `between`), as a dict: `mass` (kg), `inertia` (kg·m², about the
/// centre of mass and the body z axis), `centre_of_mass` (m, in the body frame), `length` (m,
/// the length used, `None` for a box or disc) and, with `between`, `position` (m) and `angle`
/// (rad) of the body frame.
#[pyfunction]
pub(crate) fn part<'py>(
    py: Python<'py>,
    table: &Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut item = crate::convert::value("part", table.as_any(), false)?;
    if let toml::Value::Table(t) = &mut item {
        t.insert("name".into(), toml::Value::String("part".into()));
    }
    // read as the model file's `[[body]]` is read, for the same field paths and messages
    let mut file = toml::Table::new();
    file.insert("body".into(), toml::Value::Array(vec![item]));
    let body: Body = match ModelDesc::from_toml_table(file) {
        Ok(mut d) => d.bodies.remove(0),
        Err(e) => {
            let field = e.path.rsplit('.').next().unwrap_or("").to_string();
            return Err(field_error(py, &field, &e.message));
        }
    };
    let r = body.resolve().map_err(|e| match &e {
        MbdError::Invalid { path, message } => {
            let field = path.rsplit('.').next().unwrap_or(path);
            field_error(py, field, message)
        }
        other => field_error(py, "part", &other.to_string()),
    })?;
    let d = PyDict::new(py);
    d.set_item("mass", r.mass)?;
    d.set_item("inertia", r.inertia)?;
    d.set_item("centre_of_mass", r.centre_of_mass.to_vec())?;
    d.set_item("length", r.length)?;
    if body.between.is_some() {
        d.set_item("position", r.position.map(|p| p.to_vec()))?;
        d.set_item("angle", r.angle)?;
    }
    Ok(d)
}

/// The named materials: (name, density in kg/m³, grade and source).
#[pyfunction]
pub(crate) fn materials() -> Vec<(&'static str, f64, &'static str)> {
    clr_sim::mbd::desc::inertia::MATERIALS
        .iter()
        .map(|m| (m.name, m.density, m.source))
        .collect()
}

/// Register `part` and `materials` in the extension module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(part, m)?)?;
    m.add_function(wrap_pyfunction!(materials, m)?)?;
    Ok(())
}
