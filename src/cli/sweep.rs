//! `clr sweep` (cartesian product of parameter values, run with rayon, shardable) and
//! `clr merge` (join shard outputs).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use clr_models::provenance;
use clr_plot::Figure;
use clr_sim::report::{Report, SweepRow};
use clr_sim::spec::overrides_value;
use clr_sim::spec::sweep::{self, Axis};
use rayon::prelude::*;

use super::job::{execute, resolve, Job};
use super::output::Record;
use super::points::{self, Keep, PointRecord};
use super::progress::Progress;
use super::{assignments, CliError, RunArgs};

/// What `model_hash` of sweep.json is computed from, in its own words (docs/scaling.md).
const MODEL_HASH_OF: &str = "FNV-1a 64 of the canonical JSON of the resolved model before the \
varied values: a model file's description as run (--set, --t-end, --rtol and solver options \
applied), or a built-in's name, parameters and run description";

/// A sweep point: its index, its varied values as given and its job.
type Point = (usize, Vec<String>, Job);

/// One varied parameter.
struct Vary {
    name: String,
    values: Vec<String>,
}

fn parse_vary(text: &str) -> Result<Vary, CliError> {
    let Some((n, vs)) = text.split_once('=') else {
        return Err(CliError::Input(format!(
            "--vary {text}: expected name=v1,v2,... (e.g. --vary solver.rtol=1e-6,1e-8)"
        )));
    };
    let values: Vec<String> = vs.split(',').map(|v| v.trim().to_string()).collect();
    if n.trim().is_empty() || values.iter().any(String::is_empty) {
        return Err(CliError::Input(format!(
            "--vary {text}: the name or a value is empty"
        )));
    }
    Ok(Vary {
        name: n.trim().to_string(),
        values,
    })
}

/// Parse `I/N` with 0 ≤ I < N.
pub(crate) fn parse_shard(s: &str) -> Result<(usize, usize), CliError> {
    let bad = || {
        CliError::Input(format!(
            "--shard {s}: expected I/N with 0 ≤ I < N (e.g. --shard 3/16; I is a Slurm \
             SLURM_ARRAY_TASK_ID of --array=0-15)"
        ))
    };
    let (i, n) = s.split_once('/').ok_or_else(bad)?;
    let i: usize = i.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

/// A sweep resolved and validated before anything runs: every point's model is built, so a bad
/// value in any point stops it (`clr sweep`, and `clr slurm sweep` before it writes a script).
pub(crate) struct Plan {
    varies: Vec<Vary>,
    /// Points of the whole product.
    pub total: usize,
    base_job: Job,
    /// The points of this shard.
    points: Vec<Point>,
    /// (I, N) of `--shard I/N`; (0, 1) without it.
    shard: (usize, usize),
}

/// Resolve and validate the sweep of `args` over `vary` (shard `shard` of it).
pub(crate) fn plan(args: &RunArgs, vary: &[String], shard: Option<&str>) -> Result<Plan, CliError> {
    let base = assignments(&args.set)?;
    let varies: Vec<Vary> = vary
        .iter()
        .map(|v| parse_vary(v))
        .collect::<Result<_, _>>()?;
    let (si, sn) = match shard {
        Some(s) => parse_shard(s)?,
        None => (0, 1),
    };
    let axes: Vec<Axis> = varies
        .iter()
        .map(|v| Axis {
            name: v.name.clone(),
            values: v.values.iter().map(|t| overrides_value(t)).collect(),
        })
        .collect();
    let total = sweep::total(&axes);
    // the target is read once; every point clones it and applies its values, so bad input
    // stops the sweep before anything runs
    let base_job = resolve(&args.target, &base, args.t_end, args.rtol)?.with_knobs(args.knobs())?;
    let points: Vec<Point> = sweep::points(&base_job, &axes, (si, sn), args.t_end, args.rtol)?
        .into_iter()
        .map(|p| {
            let labels = varies
                .iter()
                .zip(&p.choice)
                .map(|(v, &i)| v.values[i].clone())
                .collect();
            (p.index, labels, p.job)
        })
        .collect();
    Ok(Plan {
        varies,
        total,
        base_job,
        points,
        shard: (si, sn),
    })
}

pub(crate) fn sweep_command(
    args: &RunArgs,
    vary: &[String],
    jobs: Option<usize>,
    (shard, resume, keep): (Option<&str>, bool, Keep),
    out: &Path,
) -> Result<(), CliError> {
    let Plan {
        varies,
        total,
        base_job,
        points,
        shard: (si, sn),
    } = plan(args, vary, shard)?;
    let hash = |job: &Job| provenance::model_hash(&job.resolved_model(args.t_end, args.rtol));
    if !args.quiet {
        if let Job::Generic(s) = &base_job {
            for n in &s.notes {
                eprintln!("clr: note: {n}");
            }
        }
    }
    std::fs::create_dir_all(out)
        .map_err(|e| CliError::Input(format!("cannot create {}: {e}", out.display())))?;
    let removed = points::remove_partial(out);
    if !removed.is_empty() && !args.quiet {
        eprintln!(
            "clr: removed {} half-written point folder(s) of an interrupted run: {}",
            removed.len(),
            removed.join(", ")
        );
    }
    if let (Some(f), true, false) = (args.series, keep < Keep::Series, args.quiet) {
        eprintln!(
            "clr: note: --series {}: with --keep {} only the failed points keep their time \
             series (to diagnose them); give --keep series or all to keep every point's",
            format!("{f:?}").to_lowercase(),
            format!("{keep:?}").to_lowercase()
        );
    }
    // each point's model (its values applied), for clr merge's check of the point folders
    let point_hashes: serde_json::Map<String, serde_json::Value> = (points.iter())
        .map(|(k, _, job)| (k.to_string(), serde_json::Value::String(hash(job))))
        .collect();
    let hash_of = |k: usize| {
        let h = point_hashes.get(&k.to_string()).and_then(|h| h.as_str());
        h.unwrap_or_default().to_string()
    };
    let (kept, points) = if resume {
        resumed(out, points, &hash_of, args.quiet)
    } else {
        (Vec::new(), points)
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.unwrap_or(0))
        .build()
        .map_err(|e| CliError::Input(format!("--jobs: {e}")))?;
    let progress = Progress::new(args.quiet);
    let bar = progress.points(points.len() as u64);
    let rows: Vec<Result<SweepRow, CliError>> = pool.install(|| {
        points
            .par_iter()
            .map(|(k, values, job)| {
                let rec: Record =
                    execute(job, args.t_end, args.rtol, None).map_err(|e| match e {
                        CliError::Input(m) => CliError::Input(format!("sweep point {k}: {m}")),
                        other => other,
                    })?;
                let row = SweepRow {
                    point: *k,
                    values: values.clone(),
                    status: match &rec.error {
                        None => "ok".into(),
                        Some(_) => "failed".into(),
                    },
                    wall_s: rec.wall_s,
                    metrics: rec
                        .metrics
                        .iter()
                        .map(|m| (m.name.clone(), m.unit.clone(), m.value))
                        .collect(),
                };
                let record = PointRecord::new(&row, hash_of(*k));
                points::write_point(out, &rec, args, job, keep, &record)?;
                if let Some(b) = &bar {
                    b.inc(1);
                }
                Ok(row)
            })
            .collect()
    });
    progress.finish();
    let mut rows: Vec<SweepRow> = rows.into_iter().collect::<Result<_, _>>()?;
    rows.extend(kept);
    rows.sort_by_key(|r| r.point);
    let table = sweep_table(&varies, &rows);
    points::write_atomic(&out.join("sweep.csv"), &table)?;
    let meta = serde_json::json!({
        "target": args.target,
        "set": args.set,
        "vary": varies.iter().map(|v| serde_json::json!({"name": v.name, "values": v.values})).collect::<Vec<_>>(),
        "total_points": total,
        "model_hash": provenance::model_hash(&base_job.resolved_model(args.t_end, args.rtol)),
        "model_hash_of": MODEL_HASH_OF,
        "clr_version": provenance::CLR_VERSION,
        "shard": [si, sn],
        "points": rows.iter().map(|r| r.point).collect::<Vec<_>>(),
        "point_model_hashes": point_hashes,
    });
    points::write_atomic(
        &out.join("sweep.json"),
        &(serde_json::to_string_pretty(&meta).unwrap_or_default() + "\n"),
    )?;
    compare_figures(out, &table);
    let names: Vec<String> = varies.iter().map(|v| v.name.clone()).collect();
    // the points' reports exist with --keep all only
    let linked = keep == Keep::All && !args.no_report;
    let report = Report::sweep(&args.target, &names, &rows, linked);
    points::write_atomic(&out.join("report.html"), &report.html())?;
    let failed: Vec<usize> = rows
        .iter()
        .filter(|r| r.status != "ok")
        .map(|r| r.point)
        .collect();
    if !args.quiet {
        eprintln!(
            "clr: sweep of {} point(s) (shard {si}/{sn} of {total}) → {}",
            rows.len(),
            out.display()
        );
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(CliError::Simulation(format!(
            "{} sweep point(s) failed: {failed:?}; see point-NNNNN/summary.json",
            failed.len()
        )))
    }
}

/// Split `points` into the rows of those finished in `out` by a run of the same sweep and those
/// still to run, saying which folders are run again and why.
fn resumed(
    out: &Path,
    points: Vec<Point>,
    hash_of: &dyn Fn(usize) -> String,
    quiet: bool,
) -> (Vec<SweepRow>, Vec<Point>) {
    let (mut kept, mut todo, mut again) = (Vec::new(), Vec::new(), Vec::new());
    for (k, values, job) in points {
        match points::finished(out, k, &values, &hash_of(k)) {
            Ok(r) => kept.push(r.row()),
            Err(why) => {
                if points::folder(out, k).exists() {
                    again.push(format!("point-{k:05}: {why}"));
                }
                todo.push((k, values, job));
            }
        }
    }
    if !quiet {
        eprintln!(
            "clr: --resume: {} point(s) finished already, {} to run",
            kept.len(),
            todo.len()
        );
        for a in &again {
            eprintln!("clr: warning: run again, {a}");
        }
    }
    (kept, todo)
}

/// sweep.csv as text: `point,folder,<varied>...,status,wall_s,<metric [unit]>...`.
fn sweep_table(varies: &[Vary], rows: &[SweepRow]) -> String {
    let metrics = clr_sim::report::metric_names(rows);
    let mut s = String::from("point,folder");
    for v in varies {
        s.push(',');
        s.push_str(&v.name);
    }
    s.push_str(",status,wall_s [s]");
    for (n, u) in &metrics {
        s.push_str(&format!(",{n} [{u}]"));
    }
    s.push('\n');
    let mut rows: Vec<&SweepRow> = rows.iter().collect();
    rows.sort_by_key(|r| r.point);
    for r in rows {
        s.push_str(&format!("{},point-{:05}", r.point, r.point));
        for v in &r.values {
            s.push(',');
            s.push_str(v);
        }
        s.push_str(&format!(",{},{:e}", r.status, r.wall_s));
        for (n, _) in &metrics {
            match r.metrics.iter().find(|(m, _, _)| m == n) {
                Some((_, _, v)) => s.push_str(&format!(",{v:e}")),
                None => s.push(','),
            }
        }
        s.push('\n');
    }
    s
}

/// Comparison figures: every metric against the first varied parameter (one line per value of
/// the others), `compare_<metric>.svg/png`.
fn compare_figures(out: &Path, table: &str) {
    let mut lines = table.lines();
    let Some(header) = lines.next() else { return };
    let head: Vec<&str> = header.split(',').collect();
    let Some(status) = head.iter().position(|h| *h == "status") else {
        return;
    };
    let n_vary = status - 2;
    if n_vary == 0 {
        return;
    }
    // rows of another width (a damaged file given to `clr merge`) are not drawn
    let rows: Vec<Vec<&str>> = lines
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r.len() == head.len())
        .collect();
    let numeric_x = rows.iter().all(|r| r[2].parse::<f64>().is_ok());
    for (m, name) in head.iter().enumerate().skip(status + 2).take(16) {
        let mut groups: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
        for r in &rows {
            let Ok(y) = r[m].parse::<f64>() else { continue };
            let x = if numeric_x {
                r[2].parse::<f64>().unwrap_or(f64::NAN)
            } else {
                r[0].parse::<f64>().unwrap_or(f64::NAN)
            };
            let key: Vec<String> = (3..2 + n_vary)
                .map(|j| format!("{}={}", head[j], r[j]))
                .collect();
            groups.entry(key.join(" ")).or_default().push((x, y));
        }
        let x_label = if numeric_x {
            head[2].to_string()
        } else {
            format!("point (values of {})", head[2])
        };
        let mut f = Figure::new(format!("sweep: {name}"))
            .x_label(x_label)
            .y_label(name.to_string());
        for (k, mut pts) in groups {
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let label = if k.is_empty() { name.to_string() } else { k };
            f = f.series(label, pts, clr_plot::Style::LinePoints);
        }
        let stem: String = name
            .split(" [")
            .next()
            .unwrap_or(name)
            .chars()
            .map(|c| if c.is_alphanumeric() { c } else { '_' })
            .collect();
        if let Err(e) = f.save(out.join(format!("compare_{stem}"))) {
            eprintln!("clr: warning: {e}");
        }
    }
}

/// What the shard in `dir` records about its provenance (its sweep.json `meta`), for
/// `clr_models::provenance::check_shards`.
fn shard_provenance(dir: &Path, meta: &serde_json::Value) -> provenance::Shard {
    let text = |k: &str| meta[k].as_str().map(str::to_string);
    let spec = format!("{}/{}", meta["shard"][0], meta["shard"][1]);
    provenance::Shard {
        folder: dir.display().to_string(),
        rerun: format!(
            "clr sweep {} ... --shard {spec} --out {}",
            meta["target"].as_str().unwrap_or("<target>"),
            dir.display()
        ),
        spec,
        recorded: text("clr_version")
            .zip(text("model_hash"))
            .map(|(clr_version, model_hash)| provenance::Recorded {
                clr_version,
                model_hash,
            }),
    }
}

impl From<provenance::ProvenanceError> for CliError {
    fn from(e: provenance::ProvenanceError) -> Self {
        CliError::Input(e.to_string())
    }
}

/// Read the sweep.json of the shard folder `d`.
fn read_meta(d: &Path) -> Result<serde_json::Value, CliError> {
    let p = d.join("sweep.json");
    let text = std::fs::read_to_string(&p)
        .map_err(|e| CliError::Input(format!("cannot read {}: {e}", p.display())))?;
    let meta: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| CliError::Input(format!("{}: {e}", p.display())))?;
    if !meta.is_object() {
        return Err(CliError::Input(format!(
            "{}: not a sweep description (expected a JSON object written by clr sweep)",
            p.display()
        )));
    }
    Ok(meta)
}

/// `clr merge DIR... --out DIR [--allow-unverified]`.
pub(crate) fn merge_command(
    dirs: &[PathBuf],
    out: &Path,
    allow_unverified: bool,
) -> Result<(), CliError> {
    let read = |p: PathBuf| {
        std::fs::read_to_string(&p)
            .map_err(|e| CliError::Input(format!("cannot read {}: {e}", p.display())))
    };
    for d in dirs {
        unfinished(d)?;
    }
    let metas: Vec<serde_json::Value> = dirs
        .iter()
        .map(|d| read_meta(d))
        .collect::<Result<_, _>>()?;
    let shards: Vec<provenance::Shard> = dirs
        .iter()
        .zip(&metas)
        .map(|(d, m)| shard_provenance(d, m))
        .collect();
    let unverified = provenance::check_shards(&shards, "sweep", allow_unverified)?;
    let mut header: Option<String> = None;
    let mut meta0: Option<serde_json::Value> = None;
    let mut rows: BTreeMap<usize, (String, PathBuf)> = BTreeMap::new();
    let mut hashes = serde_json::Map::new();
    for (d, meta) in dirs.iter().zip(metas) {
        match &meta0 {
            None => meta0 = Some(meta.clone()),
            Some(m0) => {
                for key in ["target", "set", "vary", "total_points"] {
                    if m0[key] != meta[key] {
                        return Err(CliError::Input(format!(
                            "{}: `{key}` differs from {}'s; merge only shards of one sweep",
                            d.display(),
                            dirs[0].display()
                        )));
                    }
                }
            }
        }
        let text = read(d.join("sweep.csv"))?;
        if let Some(h) = meta["point_model_hashes"].as_object() {
            hashes.extend(h.clone());
        }
        // each listed point's varied values and status, for the check of its folder
        let varied = meta["vary"].as_array().map_or(0, Vec::len);
        let mut listed = BTreeMap::new();
        let mut lines = text.lines();
        let h = lines.next().unwrap_or("").to_string();
        for l in lines.filter(|l| !l.trim().is_empty()) {
            let cells: Vec<&str> = l.split(',').collect();
            let bad = || CliError::Input(format!("{}: bad row `{l}`", d.display()));
            let k: usize = cells[0].parse().map_err(|_| bad())?;
            let status = cells.get(2 + varied).ok_or_else(bad)?;
            let values = cells[2..2 + varied].iter().map(|v| v.to_string()).collect();
            listed.insert(k, (values, status.to_string()));
            let total = meta["total_points"].as_u64().unwrap_or(0) as usize;
            if k >= total {
                return Err(CliError::Input(format!(
                    "{}: point {k} is outside the sweep's {total} points",
                    d.display()
                )));
            }
            if let Some((_, first)) = rows.get(&k) {
                return Err(CliError::Input(format!(
                    "point {k} appears in both {} and {}; give each shard once",
                    first.display(),
                    d.display()
                )));
            }
            // align the metric columns with the first header
            let line = match &header {
                Some(h0) if *h0 != h => realign(&h, h0, l)?,
                _ => l.to_string(),
            };
            rows.insert(k, (line, d.clone()));
        }
        audit_points(d, &listed, &meta)?;
        if header.is_none() {
            header = Some(h);
        }
    }
    let meta0 = meta0.unwrap_or_default();
    let header = header.unwrap_or_default();
    let total = meta0["total_points"].as_u64().unwrap_or(0) as usize;
    let mut text = header.clone();
    text.push('\n');
    for (line, _) in rows.values() {
        text.push_str(line);
        text.push('\n');
    }
    std::fs::create_dir_all(out)
        .map_err(|e| CliError::Input(format!("cannot create {}: {e}", out.display())))?;
    points::write_atomic(&out.join("sweep.csv"), &text)?;
    let mut meta = meta0.clone();
    if !unverified.is_empty() {
        eprintln!(
            "clr: warning: merged without provenance (--allow-unverified): {}; nothing shows \
             that they ran the same model as the others",
            unverified.join(", ")
        );
        // `model_hash` and `clr_version` then hold for the other shards only
        meta["unverified_shards"] = serde_json::json!(unverified);
    }
    meta["shard"] = serde_json::json!([0, 1]);
    meta["points"] = serde_json::json!(rows.keys().collect::<Vec<_>>());
    meta["point_model_hashes"] = serde_json::Value::Object(hashes);
    meta["merged_from"] = serde_json::json!(dirs
        .iter()
        .map(|d| d.display().to_string())
        .collect::<Vec<_>>());
    points::write_atomic(
        &out.join("sweep.json"),
        &(serde_json::to_string_pretty(&meta).unwrap_or_default() + "\n"),
    )?;
    compare_figures(out, &text);
    let missing: Vec<usize> = (0..total).filter(|k| !rows.contains_key(k)).collect();
    eprintln!(
        "clr: merged {} of {total} point(s) from {} folder(s) → {}",
        rows.len(),
        dirs.len(),
        out.display()
    );
    if missing.is_empty() {
        Ok(())
    } else {
        Err(CliError::Simulation(format!(
            "the merge is incomplete: points {missing:?} are in no shard (rerun their shards)"
        )))
    }
}

/// Check the point folders of shard folder `d` against the points its sweep.csv lists
/// (`listed[k]` = varied values, status) and its sweep.json (`meta`): refuse the shard when a
/// point folder holds another point, model or clr version than the shard lists; name the folders
/// it does not list, those without a record and those missing.
fn audit_points(
    d: &Path,
    listed: &BTreeMap<usize, (Vec<String>, String)>,
    meta: &serde_json::Value,
) -> Result<(), CliError> {
    let a = points::audit(d, listed, meta);
    let warn = |what: &str, names: &[String]| {
        if !names.is_empty() {
            eprintln!(
                "clr: warning: {}: {} point folder(s) {what}: {}",
                d.display(),
                names.len(),
                names.join(", ")
            );
        }
    };
    warn(
        "that its sweep.csv does not list (left by another sweep or copied in; not merged)",
        &a.stray,
    );
    warn(
        "without point.json (written by an older clr; not checked)",
        &a.unrecorded,
    );
    warn("listed in its sweep.csv but removed since", &a.missing);
    if a.foreign.is_empty() {
        return Ok(());
    }
    Err(CliError::Input(format!(
        "{}: {} point folder(s) do not hold the point its sweep.csv lists, so they are not this \
         sweep's results (copied from another sweep, or changed since):\n  {}\nrun the shard \
         again with --resume (those points run again), then merge",
        d.display(),
        a.foreign.len(),
        a.foreign.join("\n  ")
    )))
}

/// Warn of the half-written point folders of shard folder `d`; refuse a shard that did not
/// finish (no sweep.csv or sweep.json), saying how to finish it.
fn unfinished(d: &Path) -> Result<(), CliError> {
    let half = points::partial(d);
    if !half.is_empty() {
        eprintln!(
            "clr: warning: {} holds {} half-written point folder(s) ({}), left by a task \
             killed mid-write: they are not merged",
            d.display(),
            half.len(),
            half.join(", ")
        );
    }
    if !(d.join("sweep.csv").exists() && d.join("sweep.json").exists()) {
        return Err(CliError::Input(format!(
            "{}: no sweep.csv or sweep.json: the shard did not finish; run it again with \
             --resume (its finished points are kept)",
            d.display()
        )));
    }
    Ok(())
}

/// Reorder the cells of `line` (written under `from`) to the columns of `to`.
fn realign(from: &str, to: &str, line: &str) -> Result<String, CliError> {
    let f: Vec<&str> = from.split(',').collect();
    let cells: Vec<&str> = line.split(',').collect();
    let mut outv = Vec::new();
    for col in to.split(',') {
        match f.iter().position(|c| *c == col) {
            Some(i) => outv.push(cells.get(i).copied().unwrap_or("")),
            None => outv.push(""),
        }
    }
    if f.iter().any(|c| !to.split(',').any(|t| t == *c)) {
        return Err(CliError::Input(format!(
            "shard columns differ: `{from}` vs `{to}`; merge only shards of one sweep"
        )));
    }
    Ok(outv.join(","))
}
