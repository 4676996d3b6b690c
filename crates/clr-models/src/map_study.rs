//! Running a model's finding map as a study (`clr study <model>_findings_map`): the parts every
//! map shares, so that a model's map module only defines its parameters, findings and
//! evaluation ([`MapDef`]).
//!
//! A map of 256 points takes hours on 2 cores, so a run must survive being stopped: every
//! evaluated point is appended to a checkpoint, `<name>_points.jsonl` in the output folder (one
//! JSON line per point after a header line naming the map), as soon as it is done. A later run
//! given that folder (or a folder holding a finished `<name>_result.json`) with `resume` takes
//! the points it finds there instead of evaluating them again, and says how many; failed points
//! are taken as failed unless the caller asks to retry them (`clr study --retry-failed`).
//! Shards (`--shard I/N`, points k with k mod N = I) run on several machines are joined with
//! [`MapDef::merge`].

use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::findings::{
    one_per_index, Design, FindingMap, FindingSpec, MapResult, Parameter, PointResult,
};

/// The definition of one model's finding map.
#[derive(Debug, Clone, Copy)]
pub struct MapDef {
    /// Study name (`clr study <name>`) and prefix of every output file.
    pub name: &'static str,
    /// Scramble seed of the design (fixed, so every machine of a sharded run draws the same
    /// points).
    pub seed: u32,
    /// Points of the study's design: a power of two (the one-dimensional stratification the
    /// first-order indices assume).
    pub default_points: usize,
    /// Simulation runs per design point (for the run count the study reports).
    pub runs_per_point: usize,
    /// The reconstructed parameters with their ranges and reasons.
    pub parameters: fn() -> Vec<Parameter>,
    /// The findings, in the order of the margins `evaluate` returns.
    pub findings: fn() -> Vec<FindingSpec>,
    /// Margins of the findings (holds when ≥ 0) at a point's physical values.
    pub evaluate: fn(&[f64]) -> Result<Vec<f64>, String>,
}

/// First line of a checkpoint: which map its points belong to, and what computed them
/// (absent from checkpoints of a clr that did not record it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct CheckpointHeader {
    map: String,
    parameters: Vec<Parameter>,
    findings: Vec<FindingSpec>,
    seed: u32,
    design_size: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    provenance: Option<MapProvenance>,
}

/// What computed a map's points: the clr version, the map's definition (hash of its name,
/// parameters, findings and seed: what its points depend on besides the code) and the shard.
/// In the checkpoint's header and, for a finished map, in `<name>_provenance.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct MapProvenance {
    clr_version: String,
    model_hash: String,
    /// `[I, N]` of a shard; absent for the whole map.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    shard: Option<[usize; 2]>,
}

impl MapDef {
    /// The design of `points` points.
    ///
    /// # Errors
    /// An invalid point count.
    pub fn design(&self, points: usize) -> Result<Design, String> {
        Design::sobol(&(self.parameters)(), points, self.seed).map_err(|e| e.to_string())
    }

    /// File of a map's full result (every point, serde JSON), from which shards are merged.
    pub fn result_file(&self, dir: &Path) -> PathBuf {
        dir.join(format!("{}_result.json", self.name))
    }

    /// File of the provenance of a finished map (clr version, hash of the map's definition,
    /// shard), which [`MapDef::merge`] compares across shards.
    pub fn provenance_file(&self, dir: &Path) -> PathBuf {
        dir.join(format!("{}_provenance.json", self.name))
    }

    /// File of the checkpoint written while a map runs.
    pub fn checkpoint_file(&self, dir: &Path) -> PathBuf {
        dir.join(format!("{}_points.jsonl", self.name))
    }

    /// The points evaluated earlier in the folders `resume` (each folder's finished result, or
    /// else its checkpoint), for [`MapDef::run`]; without the failed ones if `retry_failed`
    /// (when what a point does has changed since, e.g. a larger step budget), so that the run
    /// evaluates them again.
    ///
    /// # Errors
    /// A folder with neither, an unreadable file, or points of another map (parameters,
    /// findings or seed differ).
    pub fn earlier_points(
        &self,
        resume: &[PathBuf],
        retry_failed: bool,
    ) -> Result<Vec<PointResult>, String> {
        let mut earlier = Vec::new();
        for d in resume {
            earlier.extend(self.read_points(d)?);
        }
        if retry_failed {
            earlier.retain(|p| p.outcome.is_ok());
        }
        Ok(earlier)
    }

    /// Run the map of `points` points (or shard `I/N` of it) into `dir`, reusing the points of
    /// `earlier` (failed ones as failed) that belong to this design
    /// ([`MapDef::earlier_points`]; points of a different design size of this map are reused
    /// where they coincide), printing progress to stderr and appending every evaluated point to
    /// the checkpoint in `dir`. Writes the engine's outputs (`<name>.csv`, `_summary.json`,
    /// `_summary.md`, one figure per finding) and the full result `<name>_result.json`.
    ///
    /// # Errors
    /// An invalid point count or shard, an output error, or every point failing.
    pub fn run(
        &self,
        dir: &Path,
        points: usize,
        shard: Option<(usize, usize)>,
        earlier: &[PointResult],
    ) -> Result<MapResult, String> {
        let mut design = self.design(points)?;
        if let Some((i, n)) = shard {
            design = design.shard(i, n).map_err(|e| e.to_string())?;
        }
        let map = FindingMap::new(design, (self.findings)()).map_err(|e| e.to_string())?;
        let reused = map.reusable(earlier);
        if !earlier.is_empty() {
            let failed = reused.iter().filter(|p| p.outcome.is_err()).count();
            eprintln!(
                "{}: resuming: {reused} of the {} points to run taken from {} earlier points, \
                 {failed} of them failed and taken as failed (--retry-failed evaluates them \
                 again; points of other designs are evaluated)",
                self.name,
                map.design().points().len(),
                earlier.len(),
                reused = reused.len()
            );
        }
        let checkpoint = self.open_checkpoint(dir, points, shard)?;
        // The reused points go into the new checkpoint too, so that it alone holds everything
        // of this run when it is resumed in turn.
        if let Ok(mut f) = checkpoint.lock() {
            for p in &reused {
                let line = serde_json::to_string(p).map_err(|e| e.to_string())?;
                writeln!(f, "{line}").map_err(|e| format!("checkpoint: {e}"))?;
            }
        }
        let start = Instant::now();
        let result = map.run_reusing(self.evaluate, &reused, |p, done, total| {
            let line = serde_json::to_string(p).unwrap_or_default();
            if let Ok(mut f) = checkpoint.lock() {
                // A failed checkpoint write loses only the resumability of this point.
                if let Err(e) = writeln!(f, "{line}").and_then(|()| f.flush()) {
                    eprintln!("{}: checkpoint not written: {e}", self.name);
                }
            }
            let eta = start.elapsed().as_secs_f64() / done as f64 * (total - done) as f64;
            eprintln!(
                "{}: {done}/{total} points, {:.0} s, about {eta:.0} s left{}",
                self.name,
                start.elapsed().as_secs_f64(),
                match &p.outcome {
                    Ok(_) => String::new(),
                    Err(e) => format!(" (point {} failed: {e})", p.index),
                }
            );
        });
        self.write(dir, &result)?;
        self.write_provenance(dir, shard)?;
        if !result.points.is_empty() && result.failures().len() == result.points.len() {
            return Err(format!(
                "every point failed, e.g. {:?}",
                result.points[0].outcome
            ));
        }
        Ok(result)
    }

    /// Write a map's outputs and full result into `dir`.
    ///
    /// # Errors
    /// An output error.
    pub fn write(&self, dir: &Path, result: &MapResult) -> Result<(), String> {
        result.write(dir, self.name).map_err(|e| e.to_string())?;
        let json = serde_json::to_string(result).map_err(|e| e.to_string())?;
        let path = self.result_file(dir);
        crate::common::write_atomic(&path, json).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Merge the results of shards run into `shard_dirs` and write the merged map into `out`.
    /// A folder without a finished result contributes the points of its checkpoint
    /// ([`MapDef::stopped_result`]), so the map of a stopped run can be summarized: its
    /// summary then says how many of the design's points it has. Shards computed by different
    /// clr versions or map definitions are refused, and so are shards that record neither
    /// (written by an older clr) unless `allow_unverified`, which names them on stderr.
    ///
    /// # Errors
    /// A folder with neither a result nor a checkpoint, an unreadable file, shards of
    /// different maps or provenance (`crate::provenance::ProvenanceError`'s message), or an
    /// output error.
    pub fn merge(
        &self,
        shard_dirs: &[PathBuf],
        out: &Path,
        allow_unverified: bool,
    ) -> Result<MapResult, String> {
        let shards = shard_dirs
            .iter()
            .map(|d| self.shard_provenance(d))
            .collect::<Result<Vec<_>, String>>()?;
        let unverified = crate::provenance::check_shards(&shards, "finding map", allow_unverified)
            .map_err(|e| e.to_string())?;
        if !unverified.is_empty() {
            eprintln!(
                "{}: merged without provenance (--allow-unverified): {}; nothing shows that \
                 they ran the same map with the same clr as the others",
                self.name,
                unverified.join(", ")
            );
        }
        let parts = shard_dirs
            .iter()
            .map(|d| {
                let result = self.result_file(d);
                if result.exists() {
                    self.read_result(&result)
                } else {
                    self.stopped_result(d)
                }
            })
            .collect::<Result<Vec<_>, String>>()?;
        let merged = MapResult::merge(parts).map_err(|e| e.to_string())?;
        self.write(out, &merged)?;
        Ok(merged)
    }

    /// The study `clr study <name>`: the whole map of [`MapDef::default_points`] points into
    /// `dir`; returns the number of simulation runs.
    ///
    /// # Errors
    /// See [`MapDef::run`].
    pub fn study(&self, dir: &Path) -> Result<usize, String> {
        self.run(dir, self.default_points, None, &[])
            .map(|r| r.points.len() * self.runs_per_point)
    }

    /// The result of a run stopped before it finished: the points of the checkpoint in `dir`
    /// (and of the one it replaced), each index once (its successful outcome if it has one),
    /// in design order, for the design size named in the checkpoint's header.
    ///
    /// # Errors
    /// No checkpoint, an unreadable one, or one of another map.
    pub fn stopped_result(&self, dir: &Path) -> Result<MapResult, String> {
        let path = self.checkpoint_file(dir);
        let mut first = String::new();
        File::open(&path)
            .and_then(|f| BufReader::new(f).read_line(&mut first))
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let header: CheckpointHeader =
            serde_json::from_str(&first).map_err(|e| format!("{}: header: {e}", path.display()))?;
        let mut points = one_per_index(self.read_points(dir)?);
        points.retain(|p| p.index < header.design_size);
        Ok(MapResult {
            parameters: header.parameters,
            findings: header.findings,
            design_size: header.design_size,
            seed: header.seed,
            points,
        })
    }

    fn header(&self, design_size: usize, shard: Option<(usize, usize)>) -> CheckpointHeader {
        CheckpointHeader {
            map: self.name.to_string(),
            parameters: (self.parameters)(),
            findings: (self.findings)(),
            seed: self.seed,
            design_size,
            provenance: Some(self.provenance(shard)),
        }
    }

    /// The provenance of this map's points computed now, as shard `shard`.
    fn provenance(&self, shard: Option<(usize, usize)>) -> MapProvenance {
        let definition = serde_json::json!({
            "map": self.name,
            "parameters": (self.parameters)(),
            "findings": (self.findings)(),
            "seed": self.seed,
        });
        MapProvenance {
            clr_version: crate::provenance::CLR_VERSION.to_string(),
            model_hash: crate::provenance::model_hash(&definition),
            shard: shard.map(|(i, n)| [i, n]),
        }
    }

    fn write_provenance(&self, dir: &Path, shard: Option<(usize, usize)>) -> Result<(), String> {
        let path = self.provenance_file(dir);
        let json =
            serde_json::to_string_pretty(&self.provenance(shard)).map_err(|e| e.to_string())?;
        crate::common::write_atomic(&path, json + "\n")
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    /// What the shard folder `dir` records about its provenance: `<name>_provenance.json` of a
    /// finished map, else its checkpoint's header.
    fn shard_provenance(&self, dir: &Path) -> Result<crate::provenance::Shard, String> {
        let recorded: Option<MapProvenance> = if self.result_file(dir).exists() {
            let path = self.provenance_file(dir);
            match std::fs::read_to_string(&path) {
                Ok(text) => Some(
                    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?,
                ),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
                Err(e) => return Err(format!("{}: {e}", path.display())),
            }
        } else {
            let path = self.checkpoint_file(dir);
            let mut first = String::new();
            File::open(&path)
                .and_then(|f| BufReader::new(f).read_line(&mut first))
                .map_err(|e| format!("{}: {e}", path.display()))?;
            let h: CheckpointHeader = serde_json::from_str(&first)
                .map_err(|e| format!("{}: header: {e}", path.display()))?;
            h.provenance
        };
        let shard = recorded.as_ref().and_then(|p| p.shard);
        let (spec, option) = match shard {
            Some([i, n]) => (format!("{i}/{n}"), format!(" --shard {i}/{n}")),
            None => ("(the whole map)".to_string(), String::new()),
        };
        Ok(crate::provenance::Shard {
            folder: dir.display().to_string(),
            spec,
            rerun: format!("clr study {}{option} --out {}", self.name, dir.display()),
            recorded: recorded.map(|p| crate::provenance::Recorded {
                clr_version: p.clr_version,
                model_hash: p.model_hash,
            }),
        })
    }

    /// A fresh checkpoint in `dir` (an earlier one is renamed `.previous`: it may be the folder
    /// being resumed, whose points were read before this is called).
    fn open_checkpoint(
        &self,
        dir: &Path,
        points: usize,
        shard: Option<(usize, usize)>,
    ) -> Result<Mutex<File>, String> {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let path = self.checkpoint_file(dir);
        if path.exists() {
            let old = path.with_extension("jsonl.previous");
            std::fs::rename(&path, &old).map_err(|e| format!("{}: {e}", path.display()))?;
        }
        let mut f = OpenOptions::new()
            .create(true)
            .write(true)
            .truncate(true)
            .open(&path)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let header =
            serde_json::to_string(&self.header(points, shard)).map_err(|e| e.to_string())?;
        writeln!(f, "{header}").map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(Mutex::new(f))
    }

    fn read_result(&self, path: &Path) -> Result<MapResult, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// The points stored in `dir`: its finished result if there is one, else its checkpoint
    /// (and the checkpoint it replaced, `.previous`). Refuses results of another map.
    fn read_points(&self, dir: &Path) -> Result<Vec<PointResult>, String> {
        let result = self.result_file(dir);
        let mine = self.header(0, None);
        let same = |parameters: &[Parameter], findings: &[FindingSpec], seed: u32| {
            parameters == mine.parameters.as_slice()
                && findings == mine.findings.as_slice()
                && seed == mine.seed
        };
        if result.exists() {
            let r = self.read_result(&result)?;
            if !same(&r.parameters, &r.findings, r.seed) {
                return Err(foreign(&result, self.name));
            }
            return Ok(r.points);
        }
        let mut points = Vec::new();
        let mut found = false;
        for path in [
            self.checkpoint_file(dir),
            self.checkpoint_file(dir).with_extension("jsonl.previous"),
        ] {
            if !path.exists() {
                continue;
            }
            found = true;
            let lines = BufReader::new(File::open(&path).map_err(|e| format!("{e}"))?).lines();
            for (k, line) in lines.enumerate() {
                let line = line.map_err(|e| format!("{}: {e}", path.display()))?;
                if k == 0 {
                    let h: CheckpointHeader = serde_json::from_str(&line)
                        .map_err(|e| format!("{}: header: {e}", path.display()))?;
                    if !same(&h.parameters, &h.findings, h.seed) {
                        return Err(foreign(&path, self.name));
                    }
                    continue;
                }
                match serde_json::from_str::<PointResult>(&line) {
                    Ok(p) => points.push(p),
                    // The last line of a run stopped while writing; the point runs again.
                    Err(e) => eprintln!(
                        "{}: {} line {}: not a point ({e}); ignored",
                        self.name,
                        path.display(),
                        k + 1
                    ),
                }
            }
        }
        if !found {
            return Err(format!(
                "{}: neither {} nor {} to resume from",
                dir.display(),
                result.display(),
                self.checkpoint_file(dir).display()
            ));
        }
        Ok(points)
    }
}

fn foreign(path: &Path, name: &str) -> String {
    format!(
        "{}: points of another map (parameters, findings or seed differ from {name}'s); give a \
         folder written by this map",
        path.display()
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::findings::Scale;

    fn params() -> Vec<Parameter> {
        vec![
            Parameter::new("a", "-", 0.0, 1.0, Scale::Linear, "test range").unwrap(),
            Parameter::new("b", "-", 1.0, 10.0, Scale::Log, "test range").unwrap(),
        ]
    }
    fn findings() -> Vec<FindingSpec> {
        vec![FindingSpec::new("a_large", "a ≥ 0.5")]
    }
    // Fails on the points with a < 0.1, so that a resumed run has failures to take or retry.
    fn eval(x: &[f64]) -> Result<Vec<f64>, String> {
        if x[0] < 0.1 {
            Err("small a".into())
        } else {
            Ok(vec![x[0] - 0.5])
        }
    }
    const DEF: MapDef = MapDef {
        name: "test_map",
        seed: 7,
        default_points: 16,
        runs_per_point: 1,
        parameters: params,
        findings,
        evaluate: eval,
    };

    // A 16-point run resumed from an 8-point run's checkpoint equals a fresh 16-point run
    // (outcomes; wall times differ), and a checkpoint of another map is refused.
    #[test]
    fn resume_from_a_smaller_design_equals_a_fresh_run() {
        let base = std::env::temp_dir().join(format!("clr-map-study-{}", std::process::id()));
        let (small, big, fresh) = (base.join("small"), base.join("big"), base.join("fresh"));
        DEF.run(&small, 8, None, &[]).unwrap();
        // only the checkpoint: as if the run had been stopped before writing its result
        std::fs::remove_file(DEF.result_file(&small)).unwrap();
        let cp = std::fs::read_to_string(DEF.checkpoint_file(&small)).unwrap();
        assert_eq!(cp.lines().count(), 9);
        let earlier = DEF
            .earlier_points(std::slice::from_ref(&small), false)
            .unwrap();
        assert!(
            earlier.iter().any(|p| p.outcome.is_err()),
            "no failure to reuse"
        );
        let resumed = DEF.run(&big, 16, None, &earlier).unwrap();
        let new = DEF.run(&fresh, 16, None, &[]).unwrap();
        let outcomes = |r: &MapResult| {
            r.points
                .iter()
                .map(|p| (p.index, p.outcome.clone()))
                .collect::<Vec<_>>()
        };
        assert_eq!(outcomes(&resumed), outcomes(&new));
        // every point of the small run, failed or not, was taken, not evaluated again (same
        // wall time), and the new checkpoint holds all 16
        for e in &earlier {
            assert_eq!(
                resumed.points[e.index].wall_s, e.wall_s,
                "point {}",
                e.index
            );
        }
        // asked to retry, the failures are evaluated again (a new wall time), the rest reused
        let retried = DEF
            .earlier_points(std::slice::from_ref(&small), true)
            .unwrap();
        let again = DEF.run(&base.join("again"), 16, None, &retried).unwrap();
        assert_eq!(outcomes(&again), outcomes(&new));
        for e in &earlier {
            let r = &again.points[e.index];
            assert_eq!(r.wall_s == e.wall_s, e.outcome.is_ok(), "point {}", e.index);
        }
        let lines = std::fs::read_to_string(DEF.checkpoint_file(&big))
            .unwrap()
            .lines()
            .count();
        assert_eq!(lines, 17);
        // the stopped 8-point run, merged from its checkpoint alone, is the 8-point map
        let stopped = DEF
            .merge(std::slice::from_ref(&small), &base.join("m"), false)
            .unwrap();
        assert_eq!(stopped.design_size, 8);
        assert_eq!(outcomes(&stopped), outcomes(&new)[..8].to_vec());
        // resumed into its own folder, the 16-point run's points stand in the new checkpoint
        // and in the `.previous` one; the stopped result counts each once
        let own = DEF
            .earlier_points(std::slice::from_ref(&big), false)
            .unwrap();
        DEF.run(&big, 16, None, &own).unwrap();
        let twice = DEF.stopped_result(&big).unwrap();
        assert_eq!(outcomes(&twice), outcomes(&new));
        let other = MapDef { seed: 8, ..DEF };
        let err = other.earlier_points(&[small], false).unwrap_err();
        assert!(err.contains("another map"), "{err}");
        let _ = std::fs::remove_dir_all(&base);
    }

    // Shards record their provenance: two shards of one clr merge; a shard whose recorded
    // definition hash differs is refused by name with its rerun, and one that records nothing
    // (an older clr) is refused unless allowed. A stopped shard is read from its checkpoint.
    #[test]
    fn merge_refuses_shards_of_other_provenance() {
        let base = std::env::temp_dir().join(format!("clr-map-prov-{}", std::process::id()));
        let (a, b) = (base.join("a"), base.join("b"));
        DEF.run(&a, 8, Some((0, 2)), &[]).unwrap();
        DEF.run(&b, 8, Some((1, 2)), &[]).unwrap();
        let out = base.join("m");
        assert_eq!(
            DEF.merge(&[a.clone(), b.clone()], &out, false)
                .unwrap()
                .points
                .len(),
            8
        );
        // the checkpoint records it too: b as if stopped
        std::fs::remove_file(DEF.result_file(&b)).unwrap();
        assert!(DEF.merge(&[a.clone(), b.clone()], &out, false).is_ok());
        let cp = DEF.checkpoint_file(&b);
        let text = std::fs::read_to_string(&cp).unwrap();
        let hash = DEF.provenance(None).model_hash;
        std::fs::write(&cp, text.replacen(&hash, "fnv1a64:0000000000000000", 1)).unwrap();
        let e = DEF.merge(&[a.clone(), b.clone()], &out, false).unwrap_err();
        assert!(
            e.starts_with(&format!(
                "{}: model_hash fnv1a64:0000000000000000",
                b.display()
            )),
            "{e}"
        );
        assert!(
            e.contains("re-run shard 1/2 (`clr study test_map --shard 1/2 --out"),
            "{e}"
        );
        // a finished shard of an older clr: no provenance file
        std::fs::remove_file(DEF.provenance_file(&a)).unwrap();
        let e = DEF
            .merge(std::slice::from_ref(&a), &out, false)
            .unwrap_err();
        assert!(e.contains("--allow-unverified"), "{e}");
        assert!(DEF.merge(&[a], &out, true).is_ok());
        let _ = std::fs::remove_dir_all(&base);
    }
}
