//! Whole models at the C boundary: a model file (TOML text, `docs/model-file.md`) is loaded,
//! run and read back through the same path as `clr run` and the Python package
//! (`clr_sim::spec::load_str`, then `clr_sim::spec::run::execute`), so the numbers are the same bit for
//! bit.

use std::ffi::{c_char, CStr, CString};

use clr_sim::spec::run::{execute, Job, Outcome};
use clr_sim::spec::{load_str, Assignment};

use crate::error::{finite, guard, CapiError, ClrStatus};
use crate::ffi::{free_handle, new_handle};

/// Opaque handle of a model loaded from a model file, with the results of its last run.
pub struct ClrModel {
    job: Job,
    run: Option<Run>,
}

/// The results of one run, column by column.
struct Run {
    outcome: Outcome,
    columns: Vec<Vec<f64>>,
    /// Column names as C strings (for `clr_model_column_name`).
    column_names: Vec<CString>,
    /// Metric names as C strings (for `clr_model_metric_name`).
    metric_names: Vec<CString>,
}

/// A name as a C string (names never contain NUL; one that did would read as empty).
fn c_name(s: &str) -> CString {
    CString::new(s).unwrap_or_default()
}

/// File name used for the text in messages.
const SOURCE: &str = "<model text>";

/// End time put in place of a missing `[output] t_end`; `clr_model_run` sets the real one.
const PLACEHOLDER_T_END: f64 = 1.0;

/// # Safety
/// `p` is NULL or a NUL-terminated string.
unsafe fn c_str<'a>(name: &'static str, p: *const c_char) -> Result<&'a str, CapiError> {
    if p.is_null() {
        return Err(CapiError::Null(name));
    }
    CStr::from_ptr(p)
        .to_str()
        .map_err(|_| CapiError::Utf8(name))
}

impl ClrModel {
    /// Load and validate a model file's text (a generic model or `[model] builtin = "<name>"`).
    /// A missing `[output] t_end` is allowed: the end time is given to [`run`](Self::run).
    ///
    /// # Errors
    /// [`CapiError::Model`] with the file line and field of the problem.
    pub fn from_toml(text: &str) -> Result<Self, CapiError> {
        let loaded = match load_str(SOURCE, text, &[]) {
            Err(e) if e.field == "output.t_end" => {
                let t_end = Assignment {
                    path: "output.t_end".into(),
                    value: toml::Value::Float(PLACEHOLDER_T_END),
                };
                load_str(SOURCE, text, &[t_end])
            }
            r => r,
        }
        .map_err(|e| CapiError::Model(e.to_string()))?;
        let job = Job::from(loaded);
        Ok(Self { job, run: None })
    }

    /// Run from t = 0 to `t_end` (s, > 0); the results replace those of an earlier run. A solver
    /// failure keeps the rows recorded up to the failure.
    ///
    /// # Errors
    /// [`CapiError::Model`] for a model that cannot be built or a bad `t_end`;
    /// [`CapiError::Simulation`] when the solver failed (partial results are kept).
    pub fn run(&mut self, t_end: f64) -> Result<(), CapiError> {
        if t_end.is_nan() || t_end <= 0.0 {
            return Err(CapiError::Model(format!("t_end = {t_end} s must be > 0")));
        }
        let mut job = self.job.clone();
        if let Job::Generic(s) = &mut job {
            s.set_t_end(t_end)
                .map_err(|e| CapiError::Model(e.to_string()))?;
        }
        self.run = None;
        let outcome =
            execute(&job, Some(t_end), None, None).map_err(|e| CapiError::Model(e.to_string()))?;
        let r = &outcome.results;
        let w = r.columns.len();
        let columns = (0..w)
            .map(|k| r.data.chunks_exact(w).map(|row| row[k]).collect())
            .collect();
        let error = outcome.error.clone();
        let column_names = r.columns.iter().map(|c| c_name(c)).collect();
        let metric_names = outcome.metrics.iter().map(|m| c_name(&m.name)).collect();
        self.run = Some(Run {
            outcome,
            columns,
            column_names,
            metric_names,
        });
        match error {
            Some(message) => Err(CapiError::Simulation(message)),
            None => Ok(()),
        }
    }

    fn last_run(&self) -> Result<&Run, CapiError> {
        self.run.as_ref().ok_or_else(|| {
            CapiError::Model("the model has not been run yet; call clr_model_run first".into())
        })
    }

    /// The column `name` (e.g. `t` in s, `rod.theta` in rad, `pin.normal_force` in N) of the last
    /// run, one value per output row.
    ///
    /// # Errors
    /// [`CapiError::Model`] before the first run; [`CapiError::UnknownName`] listing the
    /// columns.
    pub fn column(&self, name: &str) -> Result<&[f64], CapiError> {
        let run = self.last_run()?;
        let names = &run.outcome.results.columns;
        names
            .iter()
            .position(|c| c == name)
            .map(|k| run.columns[k].as_slice())
            .ok_or_else(|| CapiError::UnknownName {
                what: "column",
                name: name.to_string(),
                valid: names.join(", "),
            })
    }

    /// The scalar metric `name` of the last run, in its SI unit.
    ///
    /// # Errors
    /// [`CapiError::Model`] before the first run; [`CapiError::UnknownName`] listing the
    /// metrics.
    pub fn metric(&self, name: &str) -> Result<f64, CapiError> {
        let run = self.last_run()?;
        let metrics = &run.outcome.metrics;
        metrics
            .iter()
            .find(|m| m.name == name)
            .map(|m| m.value)
            .ok_or_else(|| CapiError::UnknownName {
                what: "metric",
                name: name.to_string(),
                valid: metrics
                    .iter()
                    .map(|m| m.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// The names of the last run's columns (`columns = true`) or metrics, in order.
    ///
    /// # Errors
    /// [`CapiError::Model`] before the first run.
    fn names(&self, columns: bool) -> Result<&[CString], CapiError> {
        let run = self.last_run()?;
        Ok(if columns {
            &run.column_names
        } else {
            &run.metric_names
        })
    }

    /// Number of impacts (contact onsets of clearance joints) recorded in the last run.
    ///
    /// # Errors
    /// [`CapiError::Model`] before the first run.
    pub fn impact_count(&self) -> Result<usize, CapiError> {
        Ok(self.last_run()?.outcome.results.impacts.len())
    }
}

/// Create a model from the text of a model file (TOML, `docs/model-file.md`: a generic model or
/// `[model] builtin = "<name>"`), validated as `clr run` validates it. `[output] t_end` may be
/// missing: the end time is given to `clr_model_run`. On success `*out` receives a new handle to
/// free with `clr_model_free`. A malformed file gives `CLR_STATUS_MODEL_ERROR` and a message with
/// the line and field.
///
/// # Safety
/// `text` is NULL or a NUL-terminated UTF-8 string; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_model_from_toml(
    text: *const c_char,
    out: *mut *mut ClrModel,
) -> ClrStatus {
    new_handle(out, || ClrModel::from_toml(c_str("text", text)?))
}

/// Simulate the model from t = 0 to `t_end` (s, > 0) with the solver settings of its file; the
/// results replace those of an earlier run. `CLR_STATUS_SIMULATION_FAILED` when the solver
/// failed: the rows recorded up to the failure stay readable. The run may take from milliseconds
/// to minutes depending on the model.
///
/// # Safety
/// `model` is NULL or a live handle not used by another thread during the call.
#[no_mangle]
pub unsafe extern "C" fn clr_model_run(model: *mut ClrModel, t_end: f64) -> ClrStatus {
    guard(|| {
        let model = model.as_mut().ok_or(CapiError::Null("model"))?;
        model.run(finite("t_end (s)", t_end)?)
    })
}

/// The column `name` of the last run (e.g. "t" in s, `"<body>.x"` in m, `"<body>.theta"` in rad,
/// `"<clearance>.normal_force"` in N; units as in `docs/model-file.md`): `*out_ptr` receives a
/// pointer to `*out_len` doubles, one per output row, owned by the handle and valid until the
/// next `clr_model_run` or `clr_model_free`. `CLR_STATUS_UNKNOWN_NAME` (the message lists the
/// columns) for an unknown name, `CLR_STATUS_MODEL_ERROR` before the first run.
///
/// # Safety
/// `model` is NULL or a live handle; `name` is NULL or a NUL-terminated string; `out_ptr` and
/// `out_len` are NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_model_column(
    model: *const ClrModel,
    name: *const c_char,
    out_ptr: *mut *const f64,
    out_len: *mut usize,
) -> ClrStatus {
    guard(|| {
        if out_ptr.is_null() {
            return Err(CapiError::Null("out_ptr"));
        }
        if out_len.is_null() {
            return Err(CapiError::Null("out_len"));
        }
        let model = model.as_ref().ok_or(CapiError::Null("model"))?;
        let column = model.column(c_str("name", name)?)?;
        out_ptr.write(column.as_ptr());
        out_len.write(column.len());
        Ok(())
    })
}

/// The scalar metric `name` of the last run (e.g. `"<clearance>.peak_normal_force"` in N), in SI.
/// `CLR_STATUS_UNKNOWN_NAME` (the message lists the metrics) for an unknown name,
/// `CLR_STATUS_MODEL_ERROR` before the first run.
///
/// # Safety
/// `model` is NULL or a live handle; `name` is NULL or a NUL-terminated string; `out` is NULL or
/// writable.
#[no_mangle]
pub unsafe extern "C" fn clr_model_metric(
    model: *const ClrModel,
    name: *const c_char,
    out: *mut f64,
) -> ClrStatus {
    guard(|| {
        let model = with_out(model, out)?;
        out.write(model.metric(c_str("name", name)?)?);
        Ok(())
    })
}

/// Number of impacts (contact onsets of the clearance joints, –) in the last run.
/// `CLR_STATUS_MODEL_ERROR` before the first run.
///
/// # Safety
/// `model` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_model_impact_count(
    model: *const ClrModel,
    out: *mut usize,
) -> ClrStatus {
    guard(|| {
        let model = with_out(model, out)?;
        out.write(model.impact_count()?);
        Ok(())
    })
}

/// Number of columns (`kind` 0) or metrics (`kind` 1) of the last run, –: the names are read
/// with `clr_model_name`. `CLR_STATUS_MODEL_ERROR` before the first run or for a `kind` other
/// than 0 or 1.
///
/// # Safety
/// `model` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_model_name_count(
    model: *const ClrModel,
    kind: i32,
    out: *mut usize,
) -> ClrStatus {
    guard(|| {
        let model = with_out(model, out)?;
        out.write(model.names(name_kind(kind)?)?.len());
        Ok(())
    })
}

/// The name of column (`kind` 0) or metric (`kind` 1) number `index` (0-based) of the last run:
/// `*out` receives a NUL-terminated string owned by the handle, valid until the next
/// `clr_model_run` or `clr_model_free`. `CLR_STATUS_MODEL_ERROR` for an index past the count,
/// a `kind` other than 0 or 1, or before the first run.
///
/// # Safety
/// `model` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_model_name(
    model: *const ClrModel,
    kind: i32,
    index: usize,
    out: *mut *const c_char,
) -> ClrStatus {
    guard(|| {
        let model = with_out(model, out)?;
        let names = model.names(name_kind(kind)?)?;
        let name = names.get(index).ok_or_else(|| {
            CapiError::Model(format!(
                "name index {index} is past the {} names of the run",
                names.len()
            ))
        })?;
        out.write(name.as_ptr());
        Ok(())
    })
}

/// The model behind the handle, after checking the output pointer (a NULL names itself).
///
/// # Safety
/// `model` is NULL or a live handle.
unsafe fn with_out<'a, T>(model: *const ClrModel, out: *mut T) -> Result<&'a ClrModel, CapiError> {
    if out.is_null() {
        return Err(CapiError::Null("out"));
    }
    model.as_ref().ok_or(CapiError::Null("model"))
}

/// `kind` 0 (columns) or 1 (metrics) of `clr_model_name_count`/`clr_model_name`.
fn name_kind(kind: i32) -> Result<bool, CapiError> {
    match kind {
        0 => Ok(true),
        1 => Ok(false),
        k => Err(CapiError::Model(format!(
            "kind = {k}: give 0 for the columns or 1 for the metrics"
        ))),
    }
}

/// Free a model and its results. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `model` is NULL or a handle from `clr_model_from_toml` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_model_free(model: *mut ClrModel) {
    free_handle(model)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clr_sim::spec::Loaded;
    use std::ffi::CString;

    const PENDULUM: &str = include_str!("../../../tests/data/pendulum.toml");

    #[test]
    fn pendulum_runs_like_clr_run() {
        let text = CString::new(PENDULUM).unwrap();
        let mut h: *mut ClrModel = std::ptr::null_mut();
        assert_eq!(
            unsafe { clr_model_from_toml(text.as_ptr(), &mut h) },
            ClrStatus::Ok
        );
        let (mut p, mut n) = (std::ptr::null::<f64>(), 0usize);
        let col = CString::new("rod.theta").unwrap();
        assert_eq!(
            unsafe { clr_model_column(h, col.as_ptr(), &mut p, &mut n) },
            ClrStatus::ModelError
        );
        assert_eq!(unsafe { clr_model_run(h, 0.5) }, ClrStatus::Ok);
        assert_eq!(
            unsafe { clr_model_column(h, col.as_ptr(), &mut p, &mut n) },
            ClrStatus::Ok
        );
        let theta = unsafe { std::slice::from_raw_parts(p, n) };
        // the same run through the command-line path
        let loaded = load_str("x", PENDULUM, &[]).unwrap();
        let Loaded::Generic(mut s) = loaded else {
            panic!("generic model expected")
        };
        s.set_t_end(0.5).unwrap();
        let reference = execute(&Job::Generic(s), Some(0.5), None, None).unwrap();
        let expected = reference.results.column("rod.theta").unwrap();
        assert_eq!(theta.len(), expected.len());
        assert!(theta
            .iter()
            .zip(&expected)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        let mut count = 99usize;
        assert_eq!(
            unsafe { clr_model_impact_count(h, &mut count) },
            ClrStatus::Ok
        );
        assert_eq!(count, 0);
        // the names are listed in the order and spelling of the results
        for (kind, names) in [
            (0, reference.results.columns.clone()),
            (
                1,
                reference.metrics.iter().map(|m| m.name.clone()).collect(),
            ),
        ] {
            let mut k = 0usize;
            assert_eq!(
                unsafe { clr_model_name_count(h, kind, &mut k) },
                ClrStatus::Ok
            );
            assert_eq!(k, names.len());
            for (i, want) in names.iter().enumerate() {
                let mut ptr = std::ptr::null::<c_char>();
                assert_eq!(
                    unsafe { clr_model_name(h, kind, i, &mut ptr) },
                    ClrStatus::Ok
                );
                assert_eq!(unsafe { CStr::from_ptr(ptr) }.to_str().unwrap(), want);
            }
            let mut ptr = std::ptr::null::<c_char>();
            assert_eq!(
                unsafe { clr_model_name(h, kind, k, &mut ptr) },
                ClrStatus::ModelError
            );
        }
        assert_eq!(
            unsafe { clr_model_name_count(h, 2, &mut count) },
            ClrStatus::ModelError
        );
        let bad = CString::new("rod.nope").unwrap();
        assert_eq!(
            unsafe { clr_model_column(h, bad.as_ptr(), &mut p, &mut n) },
            ClrStatus::UnknownName
        );
        let mut m = 0.0;
        assert_eq!(
            unsafe { clr_model_metric(h, bad.as_ptr(), &mut m) },
            ClrStatus::UnknownName
        );
        assert_eq!(unsafe { clr_model_run(h, -1.0) }, ClrStatus::ModelError);
        unsafe { clr_model_free(h) };
    }

    #[test]
    fn malformed_text_is_a_model_error_with_its_place() {
        let text = CString::new("[model]\nname = 3\n").unwrap();
        let mut h: *mut ClrModel = std::ptr::null_mut();
        assert_eq!(
            unsafe { clr_model_from_toml(text.as_ptr(), &mut h) },
            ClrStatus::ModelError
        );
        assert!(h.is_null());
        assert_eq!(
            unsafe { clr_model_from_toml(std::ptr::null(), &mut h) },
            ClrStatus::NullPointer
        );
    }
}
