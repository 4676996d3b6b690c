//! The typed Python errors (`clr.errors`) raised from Rust: every one carries the field path of
//! what to change (`body[1].mass`, `clearance.B.journal_radius`, `model`).

use clr_sim::spec::run::RunError;
use clr_sim::spec::SpecError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use pyo3::IntoPyObjectExt;

/// An instance of `clr.errors.<class>` built with `message` and keyword attributes.
fn make(py: Python<'_>, class: &str, message: &str, kw: &[(&str, Option<Py<PyAny>>)]) -> PyErr {
    let build = || -> PyResult<PyErr> {
        let cls = py.import("clr_sim.errors")?.getattr(class)?;
        let kwargs = PyDict::new(py);
        for (k, v) in kw {
            kwargs.set_item(k, v)?;
        }
        Ok(PyErr::from_value(cls.call((message,), Some(&kwargs))?))
    };
    build().unwrap_or_else(|e| e)
}

fn obj<'py, T: IntoPyObject<'py>>(py: Python<'py>, v: T) -> Option<Py<PyAny>> {
    v.into_py_any(py).ok()
}

/// `clr.errors.OverrideError` at `path` (a `set=`/sweep key or a value that cannot be a model
/// value).
pub(crate) fn override_error(py: Python<'_>, path: &str, message: &str) -> PyErr {
    make(py, "OverrideError", message, &[("field", obj(py, path))])
}

/// `clr.errors.FieldError` at `path` (a field of a model built in Python whose value cannot be
/// written to a model file).
pub(crate) fn field_error(py: Python<'_>, path: &str, message: &str) -> PyErr {
    make(py, "FieldError", message, &[("field", obj(py, path))])
}

/// A model-file error as `FieldError` (file, line, column and field), or `OverrideError` when it
/// came from an override (`--set`/`set=`/a sweep value: its `file` is `--set` or names the
/// override, `--set 'path=value'`).
pub(crate) fn spec_error(py: Python<'_>, e: &SpecError) -> PyErr {
    let class = if e.file.starts_with("--set") {
        "OverrideError"
    } else {
        "FieldError"
    };
    make(
        py,
        class,
        &e.message,
        &[
            ("field", obj(py, e.field.as_str())),
            ("file", obj(py, e.file.as_str())),
            ("line", e.line.and_then(|l| obj(py, l))),
            ("column", e.column.and_then(|c| obj(py, c))),
        ],
    )
}

/// A [`RunError`] as its typed Python error: a field error, an unknown built-in model
/// (`UnknownModelError`, field `model`), or invalid built-in parameters (`ModelError`, field
/// `parameters`).
pub(crate) fn run_error(py: Python<'_>, e: &RunError) -> PyErr {
    match e {
        RunError::Spec(s) => spec_error(py, s),
        RunError::Input(m) if m.starts_with("unknown built-in model") => {
            make(py, "UnknownModelError", m, &[("field", obj(py, "model"))])
        }
        RunError::Input(m) => make(py, "ModelError", m, &[("field", obj(py, "parameters"))]),
    }
}

/// `clr.errors.ContactError` at the law argument or parameter `field`.
pub(crate) fn contact_error(py: Python<'_>, field: &str, message: &str) -> PyErr {
    make(py, "ContactError", message, &[("field", obj(py, field))])
}
