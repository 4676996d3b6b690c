//! The point folders of `clr sweep`: what each keeps (`--keep`), written under a temporary name
//! and renamed so that a folder `point-NNNNN` is complete or absent (a task killed mid-write
//! leaves only a `.point-NNNNN.partial-<pid>` folder, removed by the next run), and the
//! `point.json` record by which `--resume` recognises a finished point of the same sweep.

use std::path::{Path, PathBuf};

use clap::ValueEnum;
use clr_sim::report::SweepRow;
use serde::{Deserialize, Serialize};

use super::output::{write_run, Record};
use super::{CliError, RunArgs};
use crate::cli::job::Job;

/// What each sweep point keeps in its folder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, ValueEnum)]
pub(crate) enum Keep {
    /// `point.json` only: the point's values, status, wall time and metrics (about 2 kB).
    Metrics,
    /// And `summary.json` (settings, notes, warnings, metrics with their descriptions).
    Summary,
    /// And the time series `results.csv` and `impacts.csv` (megabytes per point).
    Series,
    /// And the figures and `report.html` (unless --no-report): what `clr run` writes.
    All,
}

/// The record `point.json` of a finished point: enough to rebuild its sweep.csv row and to tell
/// whether it belongs to the sweep being resumed.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub(crate) struct PointRecord {
    /// Index in the full product.
    pub point: usize,
    /// The varied values as given.
    pub values: Vec<String>,
    /// The hash of the point's resolved model (its values applied), `provenance::model_hash`.
    pub model_hash: String,
    /// The clr version that ran it.
    pub clr_version: String,
    /// `ok` or `failed`.
    pub status: String,
    /// Wall time, s.
    pub wall_s: f64,
    /// (name, unit, value as written by `{:e}`, which reads back to the same bits, NaN too).
    pub metrics: Vec<(String, String, String)>,
}

impl PointRecord {
    /// The record of a point just run.
    pub(crate) fn new(row: &SweepRow, model_hash: String) -> Self {
        Self {
            point: row.point,
            values: row.values.clone(),
            model_hash,
            clr_version: clr_models::provenance::CLR_VERSION.into(),
            status: row.status.clone(),
            wall_s: row.wall_s,
            metrics: (row.metrics.iter())
                .map(|(n, u, v)| (n.clone(), u.clone(), format!("{v:e}")))
                .collect(),
        }
    }

    /// Its sweep.csv row.
    pub(crate) fn row(&self) -> SweepRow {
        SweepRow {
            point: self.point,
            values: self.values.clone(),
            status: self.status.clone(),
            wall_s: self.wall_s,
            metrics: (self.metrics.iter())
                .map(|(n, u, v)| (n.clone(), u.clone(), v.parse().unwrap_or(f64::NAN)))
                .collect(),
        }
    }
}

/// The folder of point `k` in `out`.
pub(crate) fn folder(out: &Path, k: usize) -> PathBuf {
    out.join(format!("point-{k:05}"))
}

/// Why the finished folder of point `k` cannot be kept for this sweep, or its record.
pub(crate) fn finished(
    out: &Path,
    k: usize,
    values: &[String],
    model_hash: &str,
) -> Result<PointRecord, String> {
    let p = folder(out, k).join("point.json");
    let text = std::fs::read_to_string(&p).map_err(|_| "not run yet".to_string())?;
    let r: PointRecord = serde_json::from_str(&text)
        .map_err(|e| format!("{} unreadable ({e}): written by another clr?", p.display()))?;
    if r.point != k || r.values != values {
        return Err(format!(
            "its point.json is point {} with values {:?}, not {:?}: another sweep's folder",
            r.point, r.values, values
        ));
    }
    if r.clr_version != clr_models::provenance::CLR_VERSION {
        return Err(format!(
            "it ran with clr {}, this is clr {}",
            r.clr_version,
            clr_models::provenance::CLR_VERSION
        ));
    }
    if r.model_hash != model_hash {
        return Err(format!(
            "it ran another model (hash {} against {model_hash}): the model file or --set \
             changed since",
            r.model_hash
        ));
    }
    Ok(r)
}

/// Remove the half-written point folders a killed run left in `out`; their names.
pub(crate) fn remove_partial(out: &Path) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(out) else {
        return Vec::new();
    };
    let mut removed = Vec::new();
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        let half = name.starts_with(".point-") && name.contains(".partial");
        if half && std::fs::remove_dir_all(e.path()).is_ok() {
            removed.push(name);
        }
    }
    removed.sort();
    removed
}

/// The half-written point folders in `dir` (for `clr merge`'s warning).
pub(crate) fn partial(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = (std::fs::read_dir(dir).into_iter().flatten().flatten())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n.starts_with(".point-") && n.contains(".partial"))
        .collect();
    v.sort();
    v
}

/// Write point `k`'s folder with what `keep` says (everything for a failed point, to diagnose
/// it), `point.json` last, under a temporary name renamed into place.
pub(crate) fn write_point(
    out: &Path,
    rec: &Record,
    args: &RunArgs,
    job: &Job,
    keep: Keep,
    record: &PointRecord,
) -> Result<(), CliError> {
    let k = record.point;
    let tmp = out.join(format!(".point-{k:05}.partial-{}", std::process::id()));
    let io = |p: &Path, e: std::io::Error| CliError::Input(format!("{}: {e}", p.display()));
    let _ = std::fs::remove_dir_all(&tmp);
    let keep = if rec.error.is_some() { Keep::All } else { keep };
    if keep >= Keep::Series {
        let mut a = args.clone();
        a.no_figures |= keep < Keep::All;
        let report = (keep == Keep::All && !args.no_report).then_some(job);
        write_run(&tmp, rec, &a, report)?;
    } else {
        std::fs::create_dir_all(&tmp).map_err(|e| io(&tmp, e))?;
        if keep == Keep::Summary {
            super::output::write_summary(&tmp, rec, args)?;
        }
    }
    let p = tmp.join("point.json");
    let text = serde_json::to_string_pretty(record).unwrap_or_default() + "\n";
    std::fs::write(&p, text).map_err(|e| io(&p, e))?;
    let dest = folder(out, k);
    if dest.exists() {
        std::fs::remove_dir_all(&dest).map_err(|e| io(&dest, e))?;
    }
    std::fs::rename(&tmp, &dest).map_err(|e| io(&dest, e))
}

/// Write `text` to `path` under a temporary name and rename it into place
/// ([`clr_models::common::write_atomic`]).
pub(crate) fn write_atomic(path: &Path, text: &str) -> Result<(), CliError> {
    clr_models::common::write_atomic(path, text)
        .map_err(|e| CliError::Input(format!("cannot write {}: {e}", path.display())))
}

/// What `clr merge` found among the point folders of one shard folder.
#[derive(Debug, Default)]
pub(crate) struct Audit {
    /// Folders `point-k` whose k the shard's sweep.csv does not list (another sweep's, or
    /// copied in): not merged.
    pub stray: Vec<String>,
    /// Listed points whose folder has no point.json (written before clr wrote one).
    pub unrecorded: Vec<String>,
    /// Listed points whose folder is missing (removed since the sweep ran).
    pub missing: Vec<String>,
    /// Listed points whose point.json disagrees with the shard's sweep.csv or sweep.json:
    /// what differs.
    pub foreign: Vec<String>,
}

/// Check the point folders of shard folder `dir` against the points its sweep.csv lists,
/// `listed[k] = (varied values, status)`, and its sweep.json `meta` (clr version, and each
/// point's model hash when recorded).
pub(crate) fn audit(
    dir: &Path,
    listed: &std::collections::BTreeMap<usize, (Vec<String>, String)>,
    meta: &serde_json::Value,
) -> Audit {
    let mut a = Audit::default();
    let folders: Vec<String> = (std::fs::read_dir(dir).into_iter().flatten().flatten())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n.starts_with("point-"))
        .collect();
    for name in &folders {
        let k = name.trim_start_matches("point-").parse::<usize>();
        if !k.is_ok_and(|k| listed.contains_key(&k)) {
            a.stray.push(name.clone());
        }
    }
    for (&k, (values, status)) in listed {
        let name = format!("point-{k:05}");
        if !folders.contains(&name) {
            a.missing.push(name);
            continue;
        }
        let Ok(text) = std::fs::read_to_string(folder(dir, k).join("point.json")) else {
            a.unrecorded.push(name);
            continue;
        };
        let Ok(r) = serde_json::from_str::<PointRecord>(&text) else {
            a.foreign.push(format!("{name}: point.json unreadable"));
            continue;
        };
        let mut why = Vec::new();
        if r.point != k || &r.values != values || &r.status != status {
            why.push(format!(
                "point {} with values {:?}, {} (sweep.csv: point {k} with {values:?}, {status})",
                r.point, r.values, r.status
            ));
        }
        if meta["clr_version"]
            .as_str()
            .is_some_and(|v| v != r.clr_version)
        {
            why.push(format!(
                "clr {} (sweep.json: {})",
                r.clr_version, meta["clr_version"]
            ));
        }
        let recorded = &meta["point_model_hashes"][k.to_string()];
        if recorded.as_str().is_some_and(|h| h != r.model_hash) {
            why.push(format!(
                "model hash {} (sweep.json: {recorded})",
                r.model_hash
            ));
        }
        if !why.is_empty() {
            a.foreign.push(format!("{name}: {}", why.join("; ")));
        }
    }
    a
}
