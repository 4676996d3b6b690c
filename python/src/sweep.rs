//! `clr.sweep`: the points of `clr_sim::spec::sweep` run on Rust threads without the GIL, while the
//! Python side polls the count of finished points for its progress display (terminal or
//! Jupyter) and stays interruptible (Ctrl-C cancels the points not yet started).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

use clr_sim::spec::sweep::{self, Axis, PointRun};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert;
use crate::errors::run_error;
use crate::models::{outcome_dict, JobCore};

/// What the worker thread shares with Python.
#[derive(Default)]
struct Shared {
    done: AtomicUsize,
    cancel: AtomicBool,
    runs: Mutex<Option<Result<Vec<Option<PointRun>>, clr_sim::spec::run::RunError>>>,
    finished: Condvar,
}

/// A sweep running in the background: every point of the cartesian product of `axes` over a
/// resolved model, checked before the first runs.
#[pyclass(module = "clr_sim._native")]
pub(crate) struct SweepRun {
    shared: Arc<Shared>,
    total: usize,
    indices: Vec<usize>,
    values: Vec<Vec<toml::Value>>,
    taken: bool,
}

fn toml_to_py<'py>(py: Python<'py>, v: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        toml::Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        toml::Value::Float(f) => f.into_pyobject(py)?.into_any(),
        toml::Value::String(s) => s.into_pyobject(py)?.into_any(),
        toml::Value::Array(a) => {
            let l = PyList::empty(py);
            for x in a {
                l.append(toml_to_py(py, x)?)?;
            }
            l.into_any()
        }
        other => other.to_string().into_pyobject(py)?.into_any(),
    })
}

#[pymethods]
impl SweepRun {
    /// Start the sweep of `job` over `axes` (`[(dotted name, [values])]`, the last varying
    /// fastest, as `clr sweep --vary`) on `jobs` threads (`None`: one per core). Every point is
    /// built and checked first: bad input raises before anything runs.
    #[new]
    #[pyo3(signature = (job, axes, jobs=None))]
    fn new(
        py: Python<'_>,
        job: &JobCore,
        axes: Vec<(String, Bound<'_, PyAny>)>,
        jobs: Option<usize>,
    ) -> PyResult<Self> {
        let axes = axes
            .iter()
            .map(|(name, vals)| {
                let values = vals
                    .try_iter()?
                    .enumerate()
                    .map(|(i, v)| convert::value(&format!("{name}[{i}]"), &v?, true))
                    .collect::<PyResult<Vec<_>>>()?;
                Ok(Axis {
                    name: name.clone(),
                    values,
                })
            })
            .collect::<PyResult<Vec<_>>>()?;
        let (t_end, rtol) = (job.t_end, job.rtol);
        let points = py
            .detach(|| sweep::points(&job.job, &axes, (0, 1), t_end, rtol))
            .map_err(|e| run_error(py, &e))?;
        let shared = Arc::new(Shared::default());
        let run = Self {
            shared: shared.clone(),
            total: points.len(),
            indices: points.iter().map(|p| p.index).collect(),
            values: points.iter().map(|p| p.values.clone()).collect(),
            taken: false,
        };
        std::thread::spawn(move || {
            let r = sweep::run_points(&points, t_end, rtol, jobs, &shared.done, &shared.cancel);
            *shared.runs.lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
            shared.finished.notify_all();
        });
        Ok(run)
    }

    /// The number of points.
    #[getter]
    fn total(&self) -> usize {
        self.total
    }

    /// The number of finished points.
    fn done(&self) -> usize {
        self.shared.done.load(Ordering::Relaxed)
    }

    /// Wait up to `timeout` s (without the GIL) for the sweep to finish; true when it has.
    fn wait(&self, py: Python<'_>, timeout: f64) -> bool {
        let timeout = Duration::from_secs_f64(timeout.clamp(0.0, 3600.0));
        py.detach(|| {
            let guard = self.shared.runs.lock().unwrap_or_else(|e| e.into_inner());
            let (guard, _) = self
                .shared
                .finished
                .wait_timeout_while(guard, timeout, |r| r.is_none())
                .unwrap_or_else(|e| e.into_inner());
            guard.is_some()
        })
    }

    /// Skip the points not yet started (those running finish).
    fn cancel(&self) {
        self.shared.cancel.store(true, Ordering::Relaxed);
    }

    /// The points as `(index, values, outcome)` in point order, `outcome` the dict of a single
    /// run (with `wall_s`) or `None` for a point skipped by [`SweepRun::cancel`]; waits for the
    /// end. Can be taken once.
    fn results<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        while !self.wait(py, 0.2) {
            py.check_signals()?;
        }
        if self.taken {
            return Err(pyo3::exceptions::PyRuntimeError::new_err(
                "the results of this sweep were already taken",
            ));
        }
        self.taken = true;
        let runs = self
            .shared
            .runs
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
            .unwrap_or_else(|| Ok(Vec::new()))
            .map_err(|e| run_error(py, &e))?;
        let out = PyList::empty(py);
        for ((k, values), run) in self.indices.iter().zip(&self.values).zip(runs) {
            let vals = PyList::empty(py);
            for v in values {
                vals.append(toml_to_py(py, v)?)?;
            }
            let outcome: Option<Bound<'py, PyDict>> = match run {
                None => None,
                Some(Ok((o, wall))) => {
                    let d = outcome_dict(py, o)?;
                    d.set_item("wall_s", wall)?;
                    Some(d)
                }
                Some(Err(e)) => return Err(run_error(py, &e)),
            };
            out.append((k, vals, outcome))?;
        }
        Ok(out)
    }
}
