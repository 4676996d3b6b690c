//! Sweeps: the cartesian product of parameter values over one resolved [`Job`], point by point
//! as `clr sweep` runs them. The command-line tool and the Python package (`clr.sweep`) both
//! take their points from [`points`], so a sweep from either runs the same jobs and gives the
//! same numbers bit for bit.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use rayon::prelude::*;

use super::run::{execute, Job, Outcome, RunError};
use super::Assignment;

/// One varied parameter: a dotted path as `--set` takes it (`solver.rtol`,
/// `clearance.B.journal_radius`, a built-in's parameter) and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Dotted parameter path.
    pub name: String,
    /// Its values, in the order they are swept.
    pub values: Vec<toml::Value>,
}

/// One point of a sweep: its index in the full product, the value of every axis, and the job
/// with those values applied.
#[derive(Debug, Clone)]
pub struct Point {
    /// Index in the full cartesian product (the last axis varies fastest).
    pub index: usize,
    /// For each axis, the index of its value.
    pub choice: Vec<usize>,
    /// One value per axis.
    pub values: Vec<toml::Value>,
    /// The base job with the values applied.
    pub job: Job,
}

/// The number of points of the full product of `axes`.
pub fn total(axes: &[Axis]) -> usize {
    axes.iter().map(|a| a.values.len()).product()
}

/// Index → one value index per axis (the last varies fastest).
fn combination(mut k: usize, axes: &[Axis]) -> Vec<usize> {
    let mut idx = vec![0; axes.len()];
    for (j, a) in axes.iter().enumerate().rev() {
        idx[j] = k % a.values.len();
        k /= a.values.len();
    }
    idx
}

/// Refuse axes a sweep cannot run: none at all, an axis without values, the same path twice.
fn check_axes(axes: &[Axis]) -> Result<(), RunError> {
    if axes.is_empty() {
        return Err(RunError::Input(
            "a sweep needs at least one varied parameter (name = [values])".into(),
        ));
    }
    for (i, a) in axes.iter().enumerate() {
        if a.name.trim().is_empty() {
            return Err(RunError::Input(format!(
                "varied parameter {i} has an empty name; give a dotted path like solver.rtol"
            )));
        }
        if a.values.is_empty() {
            return Err(RunError::Input(format!(
                "varied parameter `{}` has no values; give at least one",
                a.name
            )));
        }
        if axes[..i].iter().any(|b| b.name == a.name) {
            return Err(RunError::Input(format!(
                "`{}` is varied twice; give all its values in one list",
                a.name
            )));
        }
    }
    Ok(())
}

/// The points of shard `shard = (i, n)` (points k with k mod n = i; `(0, 1)` for all), each the
/// base job with its values applied and `t_end` (s) and `rtol` as `clr run` takes them. Every
/// point is built and checked before anything runs, so bad input stops a sweep at once.
///
/// # Errors
/// [`RunError`] for axes that cannot be swept, a shard with i ≥ n, or a value a point refuses
/// (the message names the point).
pub fn points(
    base: &Job,
    axes: &[Axis],
    shard: (usize, usize),
    t_end: Option<f64>,
    rtol: Option<f64>,
) -> Result<Vec<Point>, RunError> {
    check_axes(axes)?;
    let (si, sn) = shard;
    if sn == 0 || si >= sn {
        return Err(RunError::Input(format!(
            "shard {si}/{sn}: expected I/N with 0 ≤ I < N"
        )));
    }
    (0..total(axes))
        .filter(|k| k % sn == si)
        .map(|k| {
            let choice = combination(k, axes);
            let values: Vec<toml::Value> = axes
                .iter()
                .zip(&choice)
                .map(|(a, &i)| a.values[i].clone())
                .collect();
            let sets: Vec<Assignment> = axes
                .iter()
                .zip(&values)
                .map(|(a, v)| Assignment {
                    path: a.name.clone(),
                    value: v.clone(),
                })
                .collect();
            let job = base
                .with_overrides(&sets, t_end, rtol)
                .map_err(|e| point_error(k, e))?;
            Ok(Point {
                index: k,
                choice,
                values,
                job,
            })
        })
        .collect()
}

/// The error of point `k`, naming it (a field error keeps its field).
fn point_error(k: usize, e: RunError) -> RunError {
    match e {
        RunError::Spec(mut s) => {
            s.message = format!("sweep point {k}: {}", s.message);
            RunError::Spec(s)
        }
        RunError::Input(m) => RunError::Input(format!("sweep point {k}: {m}")),
    }
}

/// A finished point: its outcome and wall time (s), or the input error that stopped it.
pub type PointRun = Result<(Outcome, f64), RunError>;

/// Run `points` on `jobs` threads (`None`: one per core) with the `t_end` (s) and `rtol` they
/// were built with, in point order. `done` counts finished points (for a progress display);
/// when `cancel` becomes true, points not yet started are skipped (`None`). A simulation
/// failure is an [`Outcome`] with `error` set, like a single run.
///
/// # Errors
/// [`RunError::Input`] when the thread pool cannot be created.
pub fn run_points(
    points: &[Point],
    t_end: Option<f64>,
    rtol: Option<f64>,
    jobs: Option<usize>,
    done: &AtomicUsize,
    cancel: &AtomicBool,
) -> Result<Vec<Option<PointRun>>, RunError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.unwrap_or(0))
        .build()
        .map_err(|e| RunError::Input(format!("jobs: cannot start the threads: {e}")))?;
    Ok(pool.install(|| {
        points
            .par_iter()
            .map(|p| {
                if cancel.load(Ordering::Relaxed) {
                    return None;
                }
                let start = std::time::Instant::now();
                let o = execute(&p.job, t_end, rtol, None)
                    .map(|o| (o, start.elapsed().as_secs_f64()))
                    .map_err(|e| point_error(p.index, e));
                done.fetch_add(1, Ordering::Relaxed);
                Some(o)
            })
            .collect()
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis(name: &str, n: usize) -> Axis {
        Axis {
            name: name.into(),
            values: (0..n).map(|i| toml::Value::Integer(i as i64)).collect(),
        }
    }

    /// The last axis varies fastest, as `clr sweep` documents (docs/cli.md).
    #[test]
    fn the_last_axis_varies_fastest() {
        let axes = [axis("a", 2), axis("b", 3)];
        assert_eq!(total(&axes), 6);
        let got: Vec<Vec<usize>> = (0..6).map(|k| combination(k, &axes)).collect();
        assert_eq!(
            got,
            vec![
                vec![0, 0],
                vec![0, 1],
                vec![0, 2],
                vec![1, 0],
                vec![1, 1],
                vec![1, 2]
            ]
        );
    }

    /// Empty sweeps, empty axes and repeated paths are refused with what to change.
    #[test]
    fn axes_that_cannot_be_swept_are_refused() {
        assert!(check_axes(&[]).is_err());
        let e = check_axes(&[axis("a", 0)]).unwrap_err().to_string();
        assert!(e.contains("`a` has no values"), "{e}");
        let e = check_axes(&[axis("a", 1), axis("a", 2)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("varied twice"), "{e}");
        assert!(check_axes(&[axis("a", 1), axis("b", 2)]).is_ok());
    }
}
