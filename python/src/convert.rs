//! Python values to TOML values: the model description built in Python (dicts, lists, numbers,
//! strings; numpy scalars and arrays) becomes the TOML document a model file holds, so a model
//! built in Python and the same model read from its file are the same description.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::errors::{field_error, override_error};

/// The error of a value that cannot be a model value: a `FieldError` in a model built in
/// Python (`as_text = false`), an `OverrideError` in `set=` and sweep values (`as_text = true`).
fn refused(py: Python<'_>, path: &str, message: &str, as_text: bool) -> PyErr {
    if as_text {
        override_error(py, path, message)
    } else {
        field_error(py, path, message)
    }
}

/// `v` as a TOML value; `path` names it in errors (`body[0].mass`). Strings are taken as they
/// are (`as_text = false`) or read as `--set` reads them (`as_text = true`: `"1e-6"` is a float).
///
/// `None` is not a TOML value: dicts drop keys whose value is `None` ([`table`]); anywhere else
/// it is refused.
pub(crate) fn value(path: &str, v: &Bound<'_, PyAny>, as_text: bool) -> PyResult<toml::Value> {
    let py = v.py();
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() || (!v.is_instance_of::<PyFloat>() && v.hasattr("__index__")?) {
        return match v.extract::<i64>() {
            Ok(i) => Ok(toml::Value::Integer(i)),
            Err(_) => Err(refused(
                py,
                path,
                "the integer does not fit in 64 bits",
                as_text,
            )),
        };
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if let Ok(s) = v.cast::<PyString>() {
        let s = s.to_cow()?;
        return Ok(if as_text {
            clr_sim::spec::overrides_value(&s)
        } else {
            toml::Value::String(s.into_owned())
        });
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return Ok(toml::Value::Table(table(path, d, as_text)?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() || v.hasattr("tolist")? {
        let items = if v.hasattr("tolist")? && !v.is_instance_of::<PyList>() {
            v.call_method0("tolist")?
        } else {
            v.clone()
        };
        if items.is_instance_of::<PyList>() || items.is_instance_of::<PyTuple>() {
            let list = items
                .try_iter()?
                .enumerate()
                .map(|(i, x)| value(&format!("{path}[{i}]"), &x?, as_text))
                .collect::<PyResult<Vec<_>>>()?;
            return Ok(toml::Value::Array(list));
        }
        // a 0-d numpy array: its `tolist()` is a scalar
        return value(path, &items, as_text);
    }
    if let Ok(f) = v.extract::<f64>() {
        return Ok(toml::Value::Float(f));
    }
    let what = if v.is_none() {
        "None (not given) cannot stand in a list".to_string()
    } else {
        format!("a {} cannot be a model value", v.get_type().name()?)
    };
    Err(refused(
        py,
        path,
        &format!("{what}; give a number, bool, string, list or dict"),
        as_text,
    ))
}

/// A dict with string keys as a TOML table (keys whose value is `None` are left out: that is
/// how Python says "not given").
pub(crate) fn table(
    path: &str,
    d: &Bound<'_, PyDict>,
    as_text: bool,
) -> PyResult<toml::map::Map<String, toml::Value>> {
    let mut t = toml::map::Map::new();
    for (k, v) in d.iter() {
        let key: String = k.extract().map_err(|_| {
            refused(
                d.py(),
                path,
                &format!("the key {k} is not a string; model keys are field names"),
                as_text,
            )
        })?;
        if v.is_none() {
            continue;
        }
        let sub = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        t.insert(key, value(&sub, &v, as_text)?);
    }
    Ok(t)
}
