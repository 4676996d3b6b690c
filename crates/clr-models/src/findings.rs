//! Finding maps: over the plausible range of every reconstructed parameter of a model, where
//! does each published finding hold? (Issue 19.) This module is the model-independent engine.
//!
//! 1. Each reconstructed quantity is a [`Parameter`] with a range and the *reason* that range is
//!    plausible (the papers give no dimensions, so the range is the claim).
//! 2. [`Design::sobol`] spreads n points over the ranges: an Owen-scrambled Sobol sequence
//!    (Burley 2020, crate `sobol_burley`), uniform in the unit cube and mapped linearly or
//!    log-uniformly. [`Design::shard`] splits it like `clr sweep --shard I/N`.
//! 3. [`FindingMap::run`] evaluates every point in parallel. The model's evaluation returns one
//!    *margin* per finding: value − threshold, the inequality `verify` uses, so the finding holds
//!    when margin ≥ 0. A point whose evaluation fails is kept with its message.
//! 4. [`MapResult`] answers the questions: the fraction of the space where a finding holds (with
//!    a Wilson interval), the first-order Sobol indices of its margin, a one-level
//!    classification tree (decision stump) per parameter, the points where every finding holds
//!    (candidate reconstructions), and CSV, JSON and markdown output plus figures.
//!
//! Shards run on different machines are joined with [`MapResult::merge`] (a `MapResult` is
//! serde data, so each shard can write it as JSON).
//!
//! References: Wilson (1927), *Probable inference, the law of succession, and statistical
//! inference*, JASA 22:209–212; Hays (1963), *Statistics for Psychologists* (the ω² estimate);
//! Saltelli et al. (2008), *Global Sensitivity Analysis: The Primer*, Wiley; Plischke, Borgonovo
//! & Smith (2013), *Global sensitivity measures from given data*, EJOR 226:536–550; Burley
//! (2020), *Practical Hash-based Owen Scrambling*, JCGT 9(4).

use std::collections::HashSet;
use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use clr_plot::{Figure, PlotError};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Most points of one design: the length of `sobol_burley`'s sequence, 2^16.
pub const MAX_POINTS: usize = 1 << 16;
/// Most parameters of one design: the dimensions of `sobol_burley`'s sequence.
pub const MAX_PARAMETERS: usize = sobol_burley::NUM_DIMENSIONS as usize;
/// Φ⁻¹(0.975): the normal quantile of a two-sided 95 % interval.
const Z95: f64 = 1.959_963_984_540_054;
/// Fewest successful points for which first-order indices are estimated (2 bins of 4).
const MIN_POINTS_FOR_INDICES: usize = 8;
/// Candidate reconstructions listed in the markdown summary (all are in the CSV and JSON).
const MARKDOWN_CANDIDATES: usize = 20;

/// Errors of defining, running, merging or writing a finding map.
#[derive(Debug, thiserror::Error)]
pub enum FindingsError {
    /// A parameter's range or description is not usable.
    #[error("parameter `{name}`: {message}")]
    InvalidParameter {
        /// Parameter name.
        name: String,
        /// What is wrong and what to change.
        message: String,
    },
    /// The design cannot be built or sharded as asked.
    #[error("design: {0}")]
    InvalidDesign(String),
    /// The list of findings is not usable (empty, duplicate or unsafe ids).
    #[error("findings: {0}")]
    InvalidFindings(String),
    /// Results of shards that do not belong to one map.
    #[error("cannot merge finding-map results: {0}")]
    Merge(String),
    /// Writing an output file failed.
    #[error("{path}: {source}")]
    Io {
        /// File or directory.
        path: PathBuf,
        /// Underlying error.
        source: std::io::Error,
    },
    /// Drawing a figure failed.
    #[error(transparent)]
    Plot(#[from] PlotError),
}

/// How a parameter's range is sampled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Scale {
    /// Uniform in the value.
    Linear,
    /// Uniform in the logarithm of the value (log-uniform); for ranges spanning decades.
    Log,
}

/// One reconstructed parameter of a model and its plausible range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Parameter {
    /// Name, as the model's evaluation knows it (e.g. `"load_offset"`).
    pub name: String,
    /// Unit of `lo` and `hi` (e.g. `"m"`; `"-"` for a ratio).
    pub unit: String,
    /// Lower end of the range, in `unit`.
    pub lo: f64,
    /// Upper end of the range, in `unit`.
    pub hi: f64,
    /// How the range is sampled.
    pub scale: Scale,
    /// Why this range is plausible (a source, a design rule, a bound of the paper's figures).
    pub reason: String,
}

impl Parameter {
    /// A parameter, checked by [`Parameter::validate`].
    ///
    /// # Errors
    /// [`FindingsError::InvalidParameter`] as for [`Parameter::validate`].
    pub fn new(
        name: impl Into<String>,
        unit: impl Into<String>,
        lo: f64,
        hi: f64,
        scale: Scale,
        reason: impl Into<String>,
    ) -> Result<Self, FindingsError> {
        let p = Self {
            name: name.into(),
            unit: unit.into(),
            lo,
            hi,
            scale,
            reason: reason.into(),
        };
        p.validate()?;
        Ok(p)
    }

    /// Check the parameter: a name, finite `lo < hi`, `lo > 0` on a log scale, and a reason.
    /// (The fields are public, so [`Design::sobol`] checks again.)
    ///
    /// # Errors
    /// [`FindingsError::InvalidParameter`] saying what to change.
    pub fn validate(&self) -> Result<(), FindingsError> {
        let problem = if self.name.trim().is_empty() {
            Some("the name is empty".to_string())
        } else if !(self.lo.is_finite() && self.hi.is_finite()) {
            Some(format!("range [{}, {}] is not finite", self.lo, self.hi))
        } else if self.lo >= self.hi {
            Some(format!("range [{}, {}] needs lo < hi", self.lo, self.hi))
        } else if self.scale == Scale::Log && self.lo <= 0.0 {
            Some(format!("a log scale needs lo > 0, got lo = {}", self.lo))
        } else if self.reason.trim().is_empty() {
            Some("give the reason the range is plausible".to_string())
        } else {
            None
        };
        match problem {
            Some(message) => Err(FindingsError::InvalidParameter {
                name: self.name.clone(),
                message,
            }),
            None => Ok(()),
        }
    }

    /// The value (in `unit`) at unit-cube coordinate `u` ∈ [0, 1]: `lo` at 0, `hi` at 1,
    /// linear or geometric in between.
    pub fn value_at(&self, u: f64) -> f64 {
        match self.scale {
            Scale::Linear => self.lo + u * (self.hi - self.lo),
            Scale::Log => self.lo * (self.hi / self.lo).powf(u),
        }
    }

    /// The unit-cube coordinate of `value` (in `unit`): the inverse of [`Parameter::value_at`].
    pub fn coordinate_of(&self, value: f64) -> f64 {
        match self.scale {
            Scale::Linear => (value - self.lo) / (self.hi - self.lo),
            Scale::Log => (value / self.lo).ln() / (self.hi / self.lo).ln(),
        }
    }

    /// Axis or column label: `name (unit)`.
    pub fn label(&self) -> String {
        format!("{} ({})", self.name, self.unit)
    }
}

/// One point of a design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignPoint {
    /// Index in the whole design (0-based), kept through sharding.
    pub index: usize,
    /// Unit-cube coordinates, one per parameter, in [0, 1).
    pub unit: Vec<f64>,
    /// Physical values, one per parameter, in each parameter's unit.
    pub values: Vec<f64>,
}

/// A design of experiments: points over the ranges of a list of parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Design {
    parameters: Vec<Parameter>,
    size: usize,
    seed: u32,
    points: Vec<DesignPoint>,
}

impl Design {
    /// `n` points of the Owen-scrambled Sobol sequence of `sobol_burley` with scramble `seed`,
    /// mapped to the parameters' ranges (log-uniform for [`Scale::Log`]). When `n` is a power of
    /// two, each of the n equal slices of any one unit coordinate holds exactly one point (every
    /// one-dimensional projection of a Sobol net is a (0, m, 1)-net, and Owen scrambling keeps
    /// it; the first two coordinates even form a (0, m, 2)-net), so use powers of two: the
    /// first-order indices assume it. Coordinates have the sequence's f32 resolution (2⁻²⁴).
    ///
    /// # Errors
    /// An invalid or duplicate parameter, no parameter or more than [`MAX_PARAMETERS`], `n` = 0
    /// or `n` > [`MAX_POINTS`].
    pub fn sobol(parameters: &[Parameter], n: usize, seed: u32) -> Result<Self, FindingsError> {
        check_parameters(parameters)?;
        if n == 0 || n > MAX_POINTS {
            return Err(FindingsError::InvalidDesign(format!(
                "{n} points asked; give 1 to {MAX_POINTS}"
            )));
        }
        let points = (0..n).map(|k| sobol_point(parameters, k, seed)).collect();
        Ok(Self {
            parameters: parameters.to_vec(),
            size: n,
            seed,
            points,
        })
    }

    /// The points k with k mod n = i (shard I/N of `clr sweep --shard I/N`), k being the index
    /// in the whole design. Each shard spreads over every range (the sequence's index is
    /// scrambled), but analyse the merged result ([`MapResult::merge`]): only the whole design
    /// is a net.
    ///
    /// # Errors
    /// [`FindingsError::InvalidDesign`] unless 0 ≤ i < n.
    pub fn shard(&self, i: usize, n: usize) -> Result<Self, FindingsError> {
        if n == 0 || i >= n {
            return Err(FindingsError::InvalidDesign(format!(
                "shard {i}/{n}: expected I/N with 0 ≤ I < N"
            )));
        }
        let points = self
            .points
            .iter()
            .filter(|p| p.index % n == i)
            .cloned()
            .collect();
        Ok(Self {
            points,
            ..self.clone_header()
        })
    }

    /// The parameters, in the order of each point's coordinates.
    pub fn parameters(&self) -> &[Parameter] {
        &self.parameters
    }

    /// The points of this design (of this shard, after [`Design::shard`]).
    pub fn points(&self) -> &[DesignPoint] {
        &self.points
    }

    /// Number of points of the whole design (before sharding).
    pub fn size(&self) -> usize {
        self.size
    }

    /// The scramble seed.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    fn clone_header(&self) -> Self {
        Self {
            parameters: self.parameters.clone(),
            size: self.size,
            seed: self.seed,
            points: Vec::new(),
        }
    }
}

fn check_parameters(parameters: &[Parameter]) -> Result<(), FindingsError> {
    if parameters.is_empty() || parameters.len() > MAX_PARAMETERS {
        return Err(FindingsError::InvalidDesign(format!(
            "{} parameters; give 1 to {MAX_PARAMETERS}",
            parameters.len()
        )));
    }
    let mut names = HashSet::new();
    for p in parameters {
        p.validate()?;
        if !names.insert(p.name.as_str()) {
            return Err(FindingsError::InvalidParameter {
                name: p.name.clone(),
                message: "appears twice; give each parameter once".into(),
            });
        }
    }
    Ok(())
}

/// Point `k` of the scrambled sequence (k < 2^16 and dimensions ≤ 256 checked by the caller).
fn sobol_point(parameters: &[Parameter], k: usize, seed: u32) -> DesignPoint {
    let unit: Vec<f64> = (0..parameters.len())
        .map(|d| f64::from(sobol_burley::sample(k as u32, d as u32, seed)))
        .collect();
    let values = parameters
        .iter()
        .zip(&unit)
        .map(|(p, &u)| p.value_at(u))
        .collect();
    DesignPoint {
        index: k,
        unit,
        values,
    }
}

/// One published finding, evaluated as a margin (value − threshold, holds when ≥ 0).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FindingSpec {
    /// Short id, also used in file names and CSV columns: letters, digits, `_` and `-`.
    pub id: String,
    /// The finding in words, with its paper and the inequality of its margin.
    pub description: String,
}

impl FindingSpec {
    /// A finding (the id is checked when a [`FindingMap`] is built).
    pub fn new(id: impl Into<String>, description: impl Into<String>) -> Self {
        Self {
            id: id.into(),
            description: description.into(),
        }
    }
}

fn check_findings(findings: &[FindingSpec]) -> Result<(), FindingsError> {
    if findings.is_empty() {
        return Err(FindingsError::InvalidFindings("no finding given".into()));
    }
    let mut ids = HashSet::new();
    for f in findings {
        let safe = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
        if f.id.is_empty() || !f.id.chars().all(safe) {
            return Err(FindingsError::InvalidFindings(format!(
                "id `{}`: use letters, digits, `_` and `-` (it names files)",
                f.id
            )));
        }
        if !ids.insert(f.id.as_str()) {
            return Err(FindingsError::InvalidFindings(format!(
                "id `{}` appears twice",
                f.id
            )));
        }
    }
    Ok(())
}

/// A finding map ready to run: a design (or a shard of one) and the findings to evaluate.
#[derive(Debug, Clone)]
pub struct FindingMap {
    design: Design,
    findings: Vec<FindingSpec>,
}

/// The outcome of one evaluated point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PointResult {
    /// Index in the whole design.
    pub index: usize,
    /// Unit-cube coordinates, one per parameter.
    pub unit: Vec<f64>,
    /// Physical values, one per parameter.
    pub values: Vec<f64>,
    /// One finite margin per finding (holds when ≥ 0), or why the point has none: the
    /// evaluation's error, a panic, a wrong number of margins or a non-finite margin.
    pub outcome: Result<Vec<f64>, String>,
    /// Wall time of the evaluation, s.
    pub wall_s: f64,
}

impl FindingMap {
    /// A map of `findings` over `design` (a whole design or one shard).
    ///
    /// # Errors
    /// [`FindingsError::InvalidFindings`] for no finding, a duplicate id, or an id that is not
    /// letters, digits, `_` and `-`.
    pub fn new(design: Design, findings: Vec<FindingSpec>) -> Result<Self, FindingsError> {
        check_findings(&findings)?;
        Ok(Self { design, findings })
    }

    /// The design this map runs.
    pub fn design(&self) -> &Design {
        &self.design
    }

    /// The findings, in the order of the margins `eval` returns.
    pub fn findings(&self) -> &[FindingSpec] {
        &self.findings
    }

    /// Evaluate every point in parallel (rayon). `eval` gets the physical values (in the order
    /// of the design's parameters) and returns one margin per finding, in the order of
    /// [`FindingMap::findings`]. Nothing is dropped: errors, panics, wrong lengths and
    /// non-finite margins become the point's error message.
    pub fn run<E>(&self, eval: E) -> MapResult
    where
        E: Fn(&[f64]) -> Result<Vec<f64>, String> + Sync,
    {
        self.run_with_progress(eval, |_, _| {})
    }

    /// [`FindingMap::run`], calling `progress(done, total)` after each point (from worker
    /// threads, in completion order).
    pub fn run_with_progress<E, P>(&self, eval: E, progress: P) -> MapResult
    where
        E: Fn(&[f64]) -> Result<Vec<f64>, String> + Sync,
        P: Fn(usize, usize) + Sync,
    {
        self.run_reusing(eval, &[], |_, done, total| progress(done, total))
    }

    /// [`FindingMap::run`] that takes the outcome of every design point found among `earlier`
    /// (evaluating the others in design order, so that a stopped run has done a prefix)
    /// (the points of an interrupted run or of a smaller design of the same map, see
    /// [`FindingMap::reusable`]) instead of evaluating it again, and calls
    /// `on_point(result, done, to_evaluate)` after each point it evaluates (from worker
    /// threads, in completion order; a checkpoint writer). Reused points keep their outcome and
    /// wall time; the result is the same as a fresh run's up to the points' wall times.
    pub fn run_reusing<E, P>(&self, eval: E, earlier: &[PointResult], on_point: P) -> MapResult
    where
        E: Fn(&[f64]) -> Result<Vec<f64>, String> + Sync,
        P: Fn(&PointResult, usize, usize) + Sync,
    {
        let reused = self.reusable(earlier);
        let todo: Vec<&DesignPoint> = self
            .design
            .points
            .iter()
            .filter(|p| !reused.iter().any(|r| r.index == p.index))
            .collect();
        let total = todo.len();
        let done = AtomicUsize::new(0);
        // Points are handed to the workers in design order (par_bridge pulls them one at a
        // time), so a run stopped early leaves a prefix of the design, itself a balanced net,
        // rather than the first parts of as many blocks as there are threads.
        let mut points: Vec<PointResult> = todo
            .into_iter()
            .par_bridge()
            .map(|p| {
                let r = self.evaluate(p, &eval);
                on_point(&r, done.fetch_add(1, Ordering::Relaxed) + 1, total);
                r
            })
            .collect();
        points.extend(reused);
        points.sort_by_key(|p| p.index);
        MapResult {
            parameters: self.design.parameters.clone(),
            findings: self.findings.clone(),
            design_size: self.design.size,
            seed: self.design.seed,
            points,
        }
    }

    /// The points of `earlier` that are points of this design: same index, and the same unit
    /// coordinates and values within 1e-12 (relative for values; JSON keeps them to the last
    /// bit, the tolerance only absorbs a foreign writer's rounding). The caller checks that
    /// `earlier` comes from the same map (parameters, findings and seed, see
    /// [`MapResult::same_map_as`]); a Sobol design of n points is the first n points of any
    /// larger design with the same seed, so a 64-point map is reused by a 256-point one.
    ///
    /// Failed points are reused as failures: a point's evaluation is deterministic (the flap
    /// map's 8 failed points evaluated again failed at the same time t to the last digit), so
    /// evaluating it again only costs time. A caller that changed what a point does removes
    /// the failures from `earlier` first (`clr study --retry-failed`). Where a point stands in
    /// `earlier` twice, a successful outcome is preferred.
    pub fn reusable(&self, earlier: &[PointResult]) -> Vec<PointResult> {
        let close = |a: &[f64], b: &[f64]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(x, y)| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0))
        };
        let in_design = |r: &&PointResult| {
            self.design.points.iter().any(|p| {
                r.index == p.index && close(&r.unit, &p.unit) && close(&r.values, &p.values)
            })
        };
        one_per_index(earlier.iter().filter(in_design).cloned())
    }

    fn evaluate<E>(&self, p: &DesignPoint, eval: &E) -> PointResult
    where
        E: Fn(&[f64]) -> Result<Vec<f64>, String> + Sync,
    {
        let start = Instant::now();
        // A panic in one point must not lose a long run: it becomes that point's error.
        let raw = catch_unwind(AssertUnwindSafe(|| eval(&p.values))).unwrap_or_else(|payload| {
            Err(format!("evaluation panicked: {}", panic_text(&payload)))
        });
        PointResult {
            index: p.index,
            unit: p.unit.clone(),
            values: p.values.clone(),
            outcome: checked_margins(raw, &self.findings),
            wall_s: start.elapsed().as_secs_f64(),
        }
    }
}

/// Each index of `points` once, in index order: its successful outcome if it has one (a point
/// that failed in one run and succeeded in another, retried, run), else the first.
pub fn one_per_index(points: impl IntoIterator<Item = PointResult>) -> Vec<PointResult> {
    let mut kept: Vec<PointResult> = Vec::new();
    for p in points {
        match kept.iter_mut().find(|q| q.index == p.index) {
            Some(q) if q.outcome.is_err() && p.outcome.is_ok() => *q = p,
            Some(_) => {}
            None => kept.push(p),
        }
    }
    kept.sort_by_key(|p| p.index);
    kept
}

fn panic_text(payload: &Box<dyn std::any::Any + Send>) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(no message)".into())
}

/// The margins if there is one finite margin per finding; a NaN margin would count as neither
/// holding nor failing, so it is an error of the point instead.
fn checked_margins(
    raw: Result<Vec<f64>, String>,
    findings: &[FindingSpec],
) -> Result<Vec<f64>, String> {
    let m = raw?;
    if m.len() != findings.len() {
        return Err(format!(
            "evaluation returned {} margins for {} findings",
            m.len(),
            findings.len()
        ));
    }
    match findings.iter().zip(&m).find(|(_, v)| !v.is_finite()) {
        Some((f, v)) => Err(format!("margin of `{}` is {v}", f.id)),
        None => Ok(m),
    }
}

/// The fraction of successful points at which a finding holds, with its 95 % Wilson interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Fraction {
    /// Points at which the finding holds (margin ≥ 0).
    pub holds: usize,
    /// Successful points.
    pub points: usize,
    /// holds / points (NaN without points).
    pub estimate: f64,
    /// Lower end of the 95 % Wilson score interval.
    pub lo: f64,
    /// Upper end of the 95 % Wilson score interval.
    pub hi: f64,
}

/// The 95 % Wilson score interval (Wilson 1927) of a proportion with `k` successes in `n`
/// trials: (p̂ + z²/2n ± z √(p̂(1−p̂)/n + z²/4n²)) / (1 + z²/n). Unlike p̂ ± z√(p̂(1−p̂)/n) it
/// stays inside [0, 1] and keeps its coverage near 0 and 1 (a finding that holds almost
/// nowhere). It assumes independent points; a scrambled Sobol design estimates an indicator
/// with variance at most a dimension-dependent constant times, and in practice below, that of
/// independent points (Owen 1997), so read the interval as a guide. (0, 1) when n = 0.
pub fn wilson_interval(k: usize, n: usize) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (k, n) = (k as f64, n as f64);
    let p = k / n;
    let z2 = Z95 * Z95;
    let centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = Z95 / (1.0 + z2 / n) * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

/// How the points of a given-data estimate were drawn. It sets the sampling noise of the bin
/// means, hence the bias correction of [`first_order_index`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Sampling {
    /// Independent random points (plain Monte Carlo, or data from elsewhere).
    Independent,
    /// The points of a scrambled Sobol design ([`Design::sobol`]) of which the fraction
    /// `missing` ∈ [0, 1] is absent (failed, or in shards not yet merged).
    ScrambledNet {
        /// Fraction of the design's points absent from the data.
        missing: f64,
    },
}

impl Sampling {
    /// Sampling variance of a bin mean relative to that of independent points, φ.
    fn noise(self) -> f64 {
        match self {
            Self::Independent => 1.0,
            Self::ScrambledNet { missing } => missing.clamp(0.0, 1.0),
        }
    }
}

/// A first-order sensitivity index estimated from given data.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BinnedIndex {
    /// S_i = Var(E[Y|X_i]) / Var(Y), bias-corrected; may be slightly negative for an inert
    /// parameter.
    pub value: f64,
    /// Number of equal-count bins on X_i.
    pub bins: usize,
    /// Standard deviation of `value` for an inert parameter with independent points,
    /// √(2(M − 1)) / n. Values within about 3 of these are indistinguishable from 0. For a
    /// scrambled net this is an upper bound: the spread is far smaller (5·10⁻⁵ against 8·10⁻³
    /// for n = 1024, measured over 100 seeds).
    pub null_sd: f64,
}

/// First-order index of `y` on `x` by the binning (correlation-ratio) estimator from given data
/// (Saltelli et al. 2008; Plischke, Borgonovo & Smith 2013): sort by x, cut into M bins of
/// equal count, M the power of two nearest √n, and compare the spread of the bin means of y
/// with the spread of y. √n bins balance the two errors: binning loses the variation of
/// E[y|x] inside a bin (O(1/M²) relative for smooth E[y|x]), and few points per bin make noisy
/// bin means. A power of two makes the bins of a 2^m-point Sobol design its elementary
/// intervals.
///
/// Small-sample correction. With B = Σ n_m (ȳ_m − ȳ)², T the total sum of squares,
/// W = T − B and MS_W = W/(n − M), the raw ratio η² = B/T is biased upward because the bin
/// means scatter even for an inert x. For independent points, `E[B] = n V_b + (M − 1) σ̄²_w` and
/// `E[W] = (n − M) σ̄²_w` (equal-count bins stratify x), so B − (M − 1) MS_W and
/// T + MS_W estimate n V_b and n Var(y) without bias: the ANOVA ω² (Hays 1963). In a scrambled
/// net each bin's points are themselves a net in the other coordinates, so its mean has almost
/// no sampling error and η² needs no correction (the ω² correction would subtract
/// (M − 1)/n: −0.031 for an inert parameter at n = 1024, measured). When the fraction φ of the
/// net is missing, the bin means are those of a subsample of a set with exact means, with
/// variance φ σ²/n_m (finite-population correction 1 − f, Cochran 1977, *Sampling
/// Techniques*); hence
///
/// S = (B − φ (M − 1) MS_W) / (T + φ MS_W),  φ = 1 for [`Sampling::Independent`],
///
/// which is η² at φ = 0 and ω² at φ = 1. Missing points that are not random (an evaluation
/// failing in one corner) also shift what is estimated; report them.
///
/// `None` with fewer than 8 points or when y does not vary. Any increasing transform of x (unit
/// coordinate or physical value) gives the same result.
pub fn first_order_index(x: &[f64], y: &[f64], sampling: Sampling) -> Option<BinnedIndex> {
    let n = x.len().min(y.len());
    if n < MIN_POINTS_FOR_INDICES {
        return None;
    }
    let m = (1usize << ((n as f64).log2() / 2.0).round() as u32).clamp(2, n / 4);
    let order = argsort(&x[..n]);
    let mean = y[..n].iter().sum::<f64>() / n as f64;
    let total: f64 = y[..n].iter().map(|v| (v - mean).powi(2)).sum();
    if total <= 0.0 {
        return None;
    }
    let between: f64 = (0..m)
        .map(|b| {
            let bin = &order[b * n / m..(b + 1) * n / m];
            let bin_mean = bin.iter().map(|&k| y[k]).sum::<f64>() / bin.len() as f64;
            bin.len() as f64 * (bin_mean - mean).powi(2)
        })
        .sum();
    let ms_within = (total - between).max(0.0) / (n - m) as f64;
    let phi = sampling.noise();
    Some(BinnedIndex {
        value: (between - phi * (m - 1) as f64 * ms_within) / (total + phi * ms_within),
        bins: m,
        null_sd: (2.0 * (m - 1) as f64).sqrt() / n as f64,
    })
}

fn argsort(x: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..x.len()).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
    order
}

/// Which side of a stump's threshold the finding holds on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Side {
    /// Holds when the parameter is below the threshold.
    Below,
    /// Holds when the parameter is above the threshold.
    Above,
}

/// A decision stump (one-level classification tree) for where a finding holds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Stump {
    /// Threshold, in the unit of the values it was fitted on: midway between the two adjacent
    /// sample values it separates.
    pub threshold: f64,
    /// The side on which the finding is predicted to hold.
    pub side: Side,
    /// Fraction of points classified correctly.
    pub accuracy: f64,
    /// Accuracy of the constant guess (the more frequent class), to compare with.
    pub baseline: f64,
}

impl Stump {
    /// "holds when `name` < t unit" (or >).
    pub fn describe(&self, name: &str, unit: &str) -> String {
        let op = match self.side {
            Side::Below => "<",
            Side::Above => ">",
        };
        format!("holds when {name} {op} {} {unit}", fmt_num(self.threshold))
    }
}

/// The single threshold on `x` that best separates the points where a finding holds from the
/// others (highest accuracy, the lowest threshold among ties). `None` with fewer than 2 points,
/// when x does not vary, or when the finding holds everywhere or nowhere (nothing to split).
pub fn best_stump(x: &[f64], holds: &[bool]) -> Option<Stump> {
    let n = x.len().min(holds.len());
    let total_holds = holds[..n].iter().filter(|&&h| h).count();
    if n < 2 || total_holds == 0 || total_holds == n {
        return None;
    }
    let order = argsort(&x[..n]);
    let mut best: Option<(usize, Side, usize)> = None; // (split position j, side, correct)
    let mut holds_below = 0;
    for j in 1..n {
        holds_below += usize::from(holds[order[j - 1]]);
        // Points with equal x cannot be put on different sides.
        if x[order[j - 1]] == x[order[j]] {
            continue;
        }
        let fails_above = (n - j) - (total_holds - holds_below);
        let below = holds_below + fails_above;
        for (side, correct) in [(Side::Below, below), (Side::Above, n - below)] {
            if best.is_none_or(|(_, _, c)| correct > c) {
                best = Some((j, side, correct));
            }
        }
    }
    best.map(|(j, side, correct)| Stump {
        threshold: 0.5 * (x[order[j - 1]] + x[order[j]]),
        side,
        accuracy: correct as f64 / n as f64,
        baseline: total_holds.max(n - total_holds) as f64 / n as f64,
    })
}

/// How one parameter decides one finding.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Decisive {
    /// Parameter name.
    pub parameter: String,
    /// Position of the parameter in the design.
    pub position: usize,
    /// First-order index of the finding's margin on this parameter.
    pub index: Option<BinnedIndex>,
    /// Best threshold on the parameter (in its unit) for the holding indicator.
    pub stump: Option<Stump>,
}

/// A point at which every finding holds: a candidate reconstruction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Candidate {
    /// Index in the whole design.
    pub index: usize,
    /// Physical values, one per parameter.
    pub values: Vec<f64>,
    /// Margins, one per finding (all ≥ 0).
    pub margins: Vec<f64>,
}

impl Summary {
    /// One line on finding `id` for a verify note: where it holds (count, fraction and 95 %
    /// Wilson interval) and its deciding parameters, those whose first-order index exceeds 3
    /// null standard deviations, with their best single split when it classifies better than
    /// the constant guess; "none distinguishable" when no index does. `None` for an unknown
    /// finding id.
    pub fn finding_line(&self, id: &str) -> Option<String> {
        let f = self.findings.iter().find(|f| f.finding.id == id)?;
        let fr = &f.fraction;
        let deciding: Vec<String> = f
            .decisive
            .iter()
            .filter_map(|d| {
                let i = d.index?;
                (i.value > 3.0 * i.null_sd).then(|| {
                    let split = match d.stump {
                        Some(t) if t.accuracy > t.baseline => format!(
                            ", {}",
                            t.describe(&d.parameter, &self.parameters[d.position].unit)
                        ),
                        // a split no better than "always the more frequent class" says
                        // nothing about where the finding holds
                        Some(_) => ", no single split predicts it".to_string(),
                        None => String::new(),
                    };
                    format!("{} (S₁ = {:.2}{split})", d.parameter, i.value)
                })
            })
            .collect();
        Some(format!(
            "holds at {} of {} points of the plausible space ({:.0} %, 95 % CI {:.0}–{:.0} %); \
             deciding parameters: {}",
            fr.holds,
            fr.points,
            100.0 * fr.estimate,
            100.0 * fr.lo,
            100.0 * fr.hi,
            if deciding.is_empty() {
                "none distinguishable from inert".to_string()
            } else {
                deciding.join("; ")
            }
        ))
    }
}

/// The result of a finding map (or of one shard of it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MapResult {
    /// The design's parameters.
    pub parameters: Vec<Parameter>,
    /// The findings, in the order of each point's margins.
    pub findings: Vec<FindingSpec>,
    /// Number of points of the whole design.
    pub design_size: usize,
    /// The design's scramble seed.
    pub seed: u32,
    /// The evaluated points, in design order.
    pub points: Vec<PointResult>,
}

impl MapResult {
    /// Join the results of the shards of one map (see [`Design::shard`]); points in design
    /// order. Missing shards are allowed (see [`MapResult::is_complete`]).
    ///
    /// # Errors
    /// [`FindingsError::Merge`] for no part, parts of different maps (parameters, findings,
    /// design size or seed differ) or a point present twice.
    pub fn merge(parts: impl IntoIterator<Item = MapResult>) -> Result<Self, FindingsError> {
        let mut parts = parts.into_iter();
        let mut all = parts
            .next()
            .ok_or_else(|| FindingsError::Merge("no part given".into()))?;
        let mut seen: HashSet<usize> = all.points.iter().map(|p| p.index).collect();
        for part in parts {
            if !all.same_map(&part) {
                return Err(FindingsError::Merge(
                    "parts differ in parameters, findings, design size or seed".into(),
                ));
            }
            for p in part.points {
                if !seen.insert(p.index) {
                    return Err(FindingsError::Merge(format!("point {} twice", p.index)));
                }
                all.points.push(p);
            }
        }
        all.points.sort_by_key(|p| p.index);
        Ok(all)
    }

    /// Whether `other` is a result of the same map as this one (parameters, findings and seed;
    /// the design size may differ), so that its points can be reused
    /// ([`FindingMap::reusable`]).
    pub fn same_map_as(&self, other: &Self) -> bool {
        self.parameters == other.parameters
            && self.findings == other.findings
            && self.seed == other.seed
    }

    fn same_map(&self, other: &Self) -> bool {
        self.same_map_as(other) && self.design_size == other.design_size
    }

    /// Whether every point of the design is present.
    pub fn is_complete(&self) -> bool {
        self.points.len() == self.design_size
    }

    /// The points whose evaluation failed.
    pub fn failures(&self) -> Vec<&PointResult> {
        self.points.iter().filter(|p| p.outcome.is_err()).collect()
    }

    /// The successful points with their margins.
    fn successes(&self) -> impl Iterator<Item = (&PointResult, &[f64])> {
        self.points
            .iter()
            .filter_map(|p| p.outcome.as_deref().ok().map(|m| (p, m)))
    }

    /// Fraction of the successful points at which finding `f` (its position) holds.
    ///
    /// # Panics
    /// If `f` is not a finding's position.
    pub fn fraction_holding(&self, f: usize) -> Fraction {
        assert!(
            f < self.findings.len(),
            "finding {f} of {}",
            self.findings.len()
        );
        let (holds, points) = self.successes().fold((0, 0), |(h, n), (_, m)| {
            (h + usize::from(m[f] >= 0.0), n + 1)
        });
        let (lo, hi) = wilson_interval(holds, points);
        Fraction {
            holds,
            points,
            estimate: holds as f64 / points as f64,
            lo,
            hi,
        }
    }

    /// First-order indices of finding `f`'s margin, one per parameter (see
    /// [`first_order_index`]), over the successful points.
    ///
    /// # Panics
    /// If `f` is not a finding's position.
    pub fn first_order_indices(&self, f: usize) -> Vec<Option<BinnedIndex>> {
        let y: Vec<f64> = self.successes().map(|(_, m)| m[f]).collect();
        let sampling = Sampling::ScrambledNet {
            missing: 1.0 - y.len() as f64 / self.design_size.max(1) as f64,
        };
        (0..self.parameters.len())
            .map(|i| {
                let x: Vec<f64> = self.successes().map(|(p, _)| p.unit[i]).collect();
                first_order_index(&x, &y, sampling)
            })
            .collect()
    }

    /// The best stump of finding `f`'s holding indicator on parameter `i` (threshold in the
    /// parameter's unit), over the successful points.
    ///
    /// # Panics
    /// If `f` or `i` is out of range.
    pub fn stump(&self, f: usize, i: usize) -> Option<Stump> {
        let (x, holds): (Vec<f64>, Vec<bool>) = self
            .successes()
            .map(|(p, m)| (p.values[i], m[f] >= 0.0))
            .unzip();
        best_stump(&x, &holds)
    }

    /// The parameters that decide finding `f`, the most important first: ranked by the
    /// first-order index of its margin (undefined indices last), each with its best stump.
    ///
    /// # Panics
    /// If `f` is not a finding's position.
    pub fn decisive(&self, f: usize) -> Vec<Decisive> {
        let mut d: Vec<Decisive> = self
            .first_order_indices(f)
            .into_iter()
            .enumerate()
            .map(|(i, index)| Decisive {
                parameter: self.parameters[i].name.clone(),
                position: i,
                index,
                stump: self.stump(f, i),
            })
            .collect();
        let key = |x: &Decisive| x.index.map_or(f64::NEG_INFINITY, |s| s.value);
        d.sort_by(|a, b| key(b).total_cmp(&key(a)));
        d
    }

    /// The points at which every finding holds, in design order.
    pub fn candidates(&self) -> Vec<Candidate> {
        self.successes()
            .filter(|(_, m)| m.iter().all(|&v| v >= 0.0))
            .map(|(p, m)| Candidate {
                index: p.index,
                values: p.values.clone(),
                margins: m.to_vec(),
            })
            .collect()
    }
}

/// The summary of one finding.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FindingSummary {
    /// The finding.
    pub finding: FindingSpec,
    /// Where it holds.
    pub fraction: Fraction,
    /// Its deciding parameters, the most important first.
    pub decisive: Vec<Decisive>,
}

/// The summary of a map: what the docs page of a model's map reports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// The parameters with their ranges and reasons.
    pub parameters: Vec<Parameter>,
    /// Points of the whole design.
    pub design_size: usize,
    /// The design's scramble seed.
    pub seed: u32,
    /// Points evaluated (fewer than `design_size` for a shard or a partial merge).
    pub points: usize,
    /// Points whose evaluation failed (excluded from fractions and indices).
    pub failed: usize,
    /// Per finding.
    pub findings: Vec<FindingSummary>,
    /// Points at which every finding holds.
    pub candidates: Vec<Candidate>,
}

impl MapResult {
    /// Fractions, indices, stumps and candidates of every finding.
    pub fn summary(&self) -> Summary {
        let findings = (0..self.findings.len())
            .map(|f| FindingSummary {
                finding: self.findings[f].clone(),
                fraction: self.fraction_holding(f),
                decisive: self.decisive(f),
            })
            .collect();
        Summary {
            parameters: self.parameters.clone(),
            design_size: self.design_size,
            seed: self.seed,
            points: self.points.len(),
            failed: self.failures().len(),
            findings,
            candidates: self.candidates(),
        }
    }

    /// One CSV row per point: `index`, each parameter in its unit (`name (unit)`), each margin
    /// (`margin_<id>`), `all_hold` (1/0, empty when failed), `wall_s` and `error` (empty when
    /// the point succeeded). Fields with commas, quotes or line breaks are quoted (RFC 4180).
    pub fn csv(&self) -> String {
        let mut header = vec!["index".to_string()];
        header.extend(self.parameters.iter().map(Parameter::label));
        header.extend(self.findings.iter().map(|f| format!("margin_{}", f.id)));
        header.extend(["all_hold", "wall_s", "error"].map(String::from));
        let mut out = csv_line(&header);
        for p in &self.points {
            out.push_str(&csv_line(&self.csv_row(p)));
        }
        out
    }

    fn csv_row(&self, p: &PointResult) -> Vec<String> {
        let mut row = vec![p.index.to_string()];
        row.extend(p.values.iter().map(|v| format!("{v:e}")));
        match &p.outcome {
            Ok(m) => {
                row.extend(m.iter().map(|v| format!("{v:e}")));
                row.push(u8::from(m.iter().all(|&v| v >= 0.0)).to_string());
            }
            Err(_) => row.extend(vec![String::new(); self.findings.len() + 1]),
        }
        row.push(format!("{:e}", p.wall_s));
        row.push(p.outcome.as_ref().err().cloned().unwrap_or_default());
        row
    }

    /// One figure per finding: the points where it holds and where it fails (and where the
    /// evaluation failed) over its two most important parameters (log axes for log-scale
    /// parameters); with a single parameter, the margin over it.
    ///
    /// # Panics
    /// If `f` is not a finding's position.
    pub fn figure(&self, f: usize) -> Figure {
        let id = &self.findings[f].id;
        let top: Vec<usize> = self.decisive(f).iter().map(|d| d.position).collect();
        let (x, y) = (top[0], top.get(1).copied());
        let coord = |p: &PointResult, m: Option<&[f64]>| {
            let yv = match (y, m) {
                (Some(j), _) => p.values[j],
                (None, Some(m)) => m[f],
                (None, None) => 0.0,
            };
            (p.values[x], yv)
        };
        let mut series: [(&str, Vec<(f64, f64)>); 3] = [
            ("holds", vec![]),
            ("fails", vec![]),
            ("evaluation failed", vec![]),
        ];
        for p in &self.points {
            let m = p.outcome.as_deref().ok();
            let s = match m {
                Some(m) if m[f] >= 0.0 => 0,
                Some(_) => 1,
                None => 2,
            };
            series[s].1.push(coord(p, m));
        }
        let px = &self.parameters[x];
        let mut fig = Figure::new(format!("{id}: where the finding holds")).x_label(px.label());
        fig = match y {
            Some(j) => fig.y_label(self.parameters[j].label()),
            None => fig.y_label(format!("margin of {id}")),
        };
        if px.scale == Scale::Log {
            fig = fig.log_x();
        }
        if y.is_some_and(|j| self.parameters[j].scale == Scale::Log) {
            fig = fig.log_y();
        }
        for (label, pts) in series.into_iter().filter(|(_, p)| !p.is_empty()) {
            fig = fig.points(label, pts);
        }
        fig
    }

    /// Write `dir/<name>.csv`, `dir/<name>_summary.json`, `dir/<name>_summary.md` and
    /// `dir/<name>_<finding id>.{svg,png}`; returns the paths written.
    ///
    /// # Errors
    /// [`FindingsError::Io`] or [`FindingsError::Plot`].
    pub fn write(&self, dir: &Path, name: &str) -> Result<Vec<PathBuf>, FindingsError> {
        let io = |path: &Path| {
            let path = path.to_path_buf();
            move |source| FindingsError::Io { path, source }
        };
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let summary = self.summary();
        let json = serde_json::to_string_pretty(&summary)
            .map_err(|e| io(dir)(std::io::Error::other(e)))?;
        let mut written = Vec::new();
        for (suffix, text) in [
            (".csv", self.csv()),
            ("_summary.json", json),
            ("_summary.md", summary.to_markdown()),
        ] {
            let path = dir.join(format!("{name}{suffix}"));
            crate::common::write_atomic(&path, text).map_err(io(&path))?;
            written.push(path);
        }
        for (f, spec) in self.findings.iter().enumerate() {
            let (svg, png) = self
                .figure(f)
                .save(dir.join(format!("{name}_{}", spec.id)))?;
            written.extend([svg, png]);
        }
        Ok(written)
    }
}

fn csv_line(fields: &[String]) -> String {
    let quoted: Vec<String> = fields
        .iter()
        .map(|s| {
            if s.contains([',', '"', '\n', '\r']) {
                format!("\"{}\"", s.replace('"', "\"\""))
            } else {
                s.clone()
            }
        })
        .collect();
    quoted.join(",") + "\n"
}

/// A number with 4 significant digits, in scientific notation outside [10⁻³, 10⁴).
fn fmt_num(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e4).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.3e}")
    }
}

impl Summary {
    /// The summary as markdown: the parameter table, then per finding its fraction, interval,
    /// indices and stumps, then the candidate reconstructions (at most 20 listed).
    pub fn to_markdown(&self) -> String {
        let mut s = format!(
            "Finding map over {} of {} design points (Owen-scrambled Sobol, seed {}); {} failed \
             and are left out of the fractions and indices.\n\n",
            self.points, self.design_size, self.seed, self.failed
        );
        s.push_str(&self.parameters_markdown());
        for f in &self.findings {
            s.push_str(&self.finding_markdown(f));
        }
        s.push_str(&self.candidates_markdown());
        s
    }

    fn parameters_markdown(&self) -> String {
        let mut s = String::from(
            "| parameter | unit | range | scale | why plausible |\n|---|---|---|---|---|\n",
        );
        for p in &self.parameters {
            let _ = writeln!(
                s,
                "| {} | {} | {} – {} | {:?} | {} |",
                p.name,
                p.unit,
                fmt_num(p.lo),
                fmt_num(p.hi),
                p.scale,
                p.reason
            );
        }
        s
    }

    fn finding_markdown(&self, f: &FindingSummary) -> String {
        let fr = &f.fraction;
        let mut s = format!(
            "\n### `{}`: {}\n\nHolds at {} of {} points: {:.3} \
             (95 % Wilson interval {:.3} – {:.3}).\n\n",
            f.finding.id, f.finding.description, fr.holds, fr.points, fr.estimate, fr.lo, fr.hi
        );
        s.push_str(
            "| parameter | first-order index of the margin | best single split \
             | accuracy (constant guess) |\n|---|---|---|---|\n",
        );
        for d in &f.decisive {
            let unit = &self.parameters[d.position].unit;
            let index = d.index.map_or("–".into(), |i| format!("{:.3}", i.value));
            let (split, acc) = d.stump.map_or(("–".into(), "–".into()), |t| {
                let acc = format!("{:.3} ({:.3})", t.accuracy, t.baseline);
                (t.describe(&d.parameter, unit), acc)
            });
            let _ = writeln!(s, "| {} | {index} | {split} | {acc} |", d.parameter);
        }
        if let Some(i) = f.decisive.iter().find_map(|d| d.index) {
            let _ = writeln!(
                s,
                "\nIndices from {} equal-count bins; below about {:.3} (3 null standard \
                 deviations) a parameter is indistinguishable from inert.",
                i.bins,
                3.0 * i.null_sd
            );
        }
        s
    }

    fn candidates_markdown(&self) -> String {
        let mut s = format!(
            "\n### Candidate reconstructions\n\n{} points at which every finding holds.\n",
            self.candidates.len()
        );
        if self.candidates.is_empty() {
            return s;
        }
        let names: Vec<String> = self.parameters.iter().map(Parameter::label).collect();
        let _ = write!(
            s,
            "\n| point | {} |\n|---|{}\n",
            names.join(" | "),
            "---|".repeat(names.len())
        );
        for c in self.candidates.iter().take(MARKDOWN_CANDIDATES) {
            let vals: Vec<String> = c.values.iter().map(|&v| fmt_num(v)).collect();
            let _ = writeln!(s, "| {} | {} |", c.index, vals.join(" | "));
        }
        if self.candidates.len() > MARKDOWN_CANDIDATES {
            let _ = writeln!(
                s,
                "\n… and {} more (column `all_hold` of the CSV).",
                self.candidates.len() - MARKDOWN_CANDIDATES
            );
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn linear(names: &[&str], lo: f64, hi: f64) -> Vec<Parameter> {
        names
            .iter()
            .map(|n| Parameter::new(*n, "-", lo, hi, Scale::Linear, "test range").unwrap())
            .collect()
    }

    fn one_finding(id: &str) -> Vec<FindingSpec> {
        vec![FindingSpec::new(id, "test finding")]
    }

    /// Map of `eval` (one margin) over a Sobol design of `parameters`.
    fn map(parameters: &[Parameter], n: usize, eval: impl Fn(&[f64]) -> f64 + Sync) -> MapResult {
        let design = Design::sobol(parameters, n, 7).unwrap();
        FindingMap::new(design, one_finding("f"))
            .unwrap()
            .run(|x| Ok(vec![eval(x)]))
    }

    // Points are evaluated in design order: when the point of index j is the p-th to finish
    // (from 0), at least j + 1 points have been handed out and at most one per worker is
    // unfinished, so j ≤ p + workers − 1. Splitting the list into one block per worker, as a
    // plain parallel iterator does, finishes index 32 of 64 among the first.
    #[test]
    fn a_run_evaluates_points_in_design_order() {
        let workers = 2;
        let design = Design::sobol(&linear(&["x"], 0.0, 1.0), 64, 7).unwrap();
        let fm = FindingMap::new(design, one_finding("f")).unwrap();
        let order = std::sync::Mutex::new(Vec::new());
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(workers)
            .build()
            .unwrap();
        pool.install(|| {
            fm.run_reusing(
                // about a millisecond of work per point, so that the second worker joins in
                // before the first has run through the list
                |x| {
                    Ok(vec![
                        (0..100_000).fold(x[0], |a, k| (a + f64::from(k)).sin())
                    ])
                },
                &[],
                |p, _, _| order.lock().unwrap().push(p.index),
            )
        });
        let order = order.into_inner().unwrap();
        assert_eq!(order.len(), 64);
        for (pos, &j) in order.iter().enumerate() {
            assert!(j < pos + workers, "point {j} finished {pos}th: {order:?}");
        }
    }

    // A failed point is reused as failed; a point standing twice (a failed and a successful
    // outcome, as after a retried run) is reused with its successful outcome.
    #[test]
    fn failed_points_are_reused_and_a_success_wins() {
        let design = Design::sobol(&linear(&["x"], 0.0, 1.0), 4, 7).unwrap();
        let fm = FindingMap::new(design, one_finding("f")).unwrap();
        let fresh = fm.run(|x| Ok(vec![x[0]]));
        let failed = |i: usize| PointResult {
            outcome: Err("budget".into()),
            ..fresh.points[i].clone()
        };
        let earlier = [failed(0), fresh.points[0].clone(), failed(1)];
        let reused = fm.reusable(&earlier);
        assert_eq!(reused.len(), 2);
        assert_eq!(reused[0].outcome, fresh.points[0].outcome);
        assert_eq!(reused[1].outcome, Err("budget".into()));
    }

    fn index_values(r: &MapResult) -> Vec<f64> {
        r.first_order_indices(0)
            .iter()
            .map(|s| s.unwrap().value)
            .collect()
    }

    // (a) Y = a1 X1 + a2 X2 with X3 inert, all U(0, 1): Var(E[Y|Xi]) = ai²/12, so
    // S_i = ai² / (a1² + a2²) exactly (Saltelli et al. 2008, linear additive model):
    // S = (0.2, 0.8, 0) for a = (1, 2). Tolerance 2e-3: binning with M = 32 bins loses
    // S_i/M² ≤ 8e-4 (E[Y|Xi] is linear inside a bin), and over 100 seeds the estimates
    // spread by sd 1.2e-4, so 2e-3 leaves 10 sd.
    #[test]
    fn linear_model_indices_are_the_shares_of_squared_coefficients() {
        let r = map(&linear(&["x1", "x2", "x3"], 0.0, 1.0), 1024, |x| {
            x[0] + 2.0 * x[1]
        });
        let s = index_values(&r);
        for (est, exact) in s.iter().zip([0.2, 0.8, 0.0]) {
            assert!((est - exact).abs() < 2e-3, "S = {s:?}, exact (0.2, 0.8, 0)");
        }
        let ranked: Vec<String> = r.decisive(0).into_iter().map(|d| d.parameter).collect();
        assert_eq!(ranked, ["x2", "x1", "x3"]);
    }

    // The verify line of a finding: margin x1 − 0.25 holds on 3/4 of U(0, 1) (exactly 768 of
    // 1024 net points: each quarter slice holds 256), x1 alone decides it (S₁ = 1 for a margin
    // that depends on x1 only), and the split is at 0.25 within one point spacing 1/1024.
    #[test]
    fn finding_line_states_fraction_and_deciding_parameter() {
        let r = map(&linear(&["x1", "x2"], 0.0, 1.0), 1024, |x| x[0] - 0.25);
        let line = r.summary().finding_line("f").unwrap();
        assert!(
            line.starts_with("holds at 768 of 1024 points of the plausible space (75 %"),
            "{line}"
        );
        assert!(
            line.contains("deciding parameters: x1 (S₁ = 1.00, holds when x1 > 0.25"),
            "{line}"
        );
        assert!(!line.contains("x2"), "{line}");
        assert!(r.summary().finding_line("g").is_none());
    }

    // A finding that holds on a middle band, 0.1 − |x1 − 0.5| ≥ 0: x1 alone decides it
    // (S₁ = 1), but one threshold cannot cut a band out, so every split does worse than "fails
    // everywhere" (80 %) and the line names no split. The band [409.6, 614.4]/1024 holds the
    // one point of each of the 204 slices 410–613 of the net, and perhaps those of the two
    // slices it cuts: 204–206 points.
    #[test]
    fn finding_line_names_no_split_that_loses_to_the_constant_guess() {
        let r = map(&linear(&["x1", "x2"], 0.0, 1.0), 1024, |x| {
            0.1 - (x[0] - 0.5).abs()
        });
        let line = r.summary().finding_line("f").unwrap();
        let holds: usize = line["holds at ".len()..]
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!((204..=206).contains(&holds), "{line}");
        assert!(
            line.contains("x1 (S₁ = 1.00, no single split predicts it)"),
            "{line}"
        );
    }

    /// Xorshift64 numbers in [0, 1): independent-looking points without a dependency.
    fn xorshift(seed: u64) -> impl FnMut() -> f64 {
        let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    // The ω² correction for independent points, same linear model. Over 20 samples of
    // n = 1024 the mean of the inert S3 must be 0 within 3 standard errors (single-sample sd
    // √(2·31)/1024 ≈ 7.7e-3, so 3 · 7.7e-3/√20 ≈ 5.2e-3), while the uncorrected η² sits near
    // (M − 1)/(n − 1) = 0.030: the correction is what makes it 0.
    #[test]
    fn independent_points_need_the_omega_squared_correction() {
        let (mut corrected, mut raw) = (0.0, 0.0);
        for rep in 0..20 {
            let mut rnd = xorshift(rep + 1);
            let x: Vec<[f64; 3]> = (0..1024).map(|_| [rnd(), rnd(), rnd()]).collect();
            let y: Vec<f64> = x.iter().map(|x| x[0] + 2.0 * x[1]).collect();
            let x3: Vec<f64> = x.iter().map(|x| x[2]).collect();
            let net = Sampling::ScrambledNet { missing: 0.0 };
            corrected += first_order_index(&x3, &y, Sampling::Independent)
                .unwrap()
                .value
                / 20.0;
            raw += first_order_index(&x3, &y, net).unwrap().value / 20.0;
        }
        assert!(corrected.abs() < 5.2e-3, "mean corrected S3 = {corrected}");
        assert!((raw - 31.0 / 1023.0).abs() < 5.2e-3, "mean raw η² = {raw}");
    }

    // (b) Ishigami function, a = 7, b = 0.1, X ~ U(−π, π)³ (Ishigami & Homma 1990):
    // V1 = (1 + bπ⁴/5)²/2, V2 = a²/8, V3 = 0, V = a²/8 + bπ⁴/5 + b²π⁸/18 + 1/2, giving
    // S1 = 0.3139, S2 = 0.4424, S3 = 0 (Saltelli et al. 2008). Tolerance 5e-3 at n = 4096
    // (M = 64): the binning loss E[g_i'²] h²/12 / V is ≤ 1.5e-3 (h = 2π/64; for X2,
    // E[g2'²] = a²/2), and over 100 seeds the estimates spread by sd ≤ 8e-4 (4 sd = 3.2e-3).
    #[test]
    fn ishigami_indices_match_the_closed_form() {
        let (a, b) = (7.0, 0.1);
        let v1 = 0.5 * (1.0 + b * PI.powi(4) / 5.0).powi(2);
        let v = a * a / 8.0 + b * PI.powi(4) / 5.0 + b * b * PI.powi(8) / 18.0 + 0.5;
        let exact = [v1 / v, a * a / 8.0 / v, 0.0];
        assert!((exact[0] - 0.3139).abs() < 5e-5 && (exact[1] - 0.4424).abs() < 5e-5);
        let r = map(&linear(&["x1", "x2", "x3"], -PI, PI), 4096, |x| {
            x[0].sin() + a * x[1].sin().powi(2) + b * x[2].powi(4) * x[0].sin()
        });
        let s = index_values(&r);
        for (est, ex) in s.iter().zip(exact) {
            assert!((est - ex).abs() < 5e-3, "S = {s:?}, exact {exact:?}");
        }
    }

    // (c) margin = X1 − 0.3, X1 ~ U(0, 1): holds on a length 0.7. The 256 points put one point
    // in each slice [k/256, (k+1)/256) (a net), so the count is 0.7 · 256 = 179.2 within 1;
    // the Wilson interval (half-width ≈ 0.056) must contain 0.7.
    #[test]
    fn fraction_holding_matches_the_length_where_the_margin_is_positive() {
        let r = map(&linear(&["x1", "x2"], 0.0, 1.0), 256, |x| x[0] - 0.3);
        let f = r.fraction_holding(0);
        assert_eq!(f.points, 256);
        assert!((f.holds as f64 - 179.2).abs() <= 1.0, "{f:?}");
        assert!(f.lo < 0.7 && 0.7 < f.hi, "{f:?}");
    }

    // Wilson intervals of Newcombe (1998, Statistics in Medicine 17:857, Table I, "score
    // method"), given to 4 decimals: tolerance 5e-5 (half the last digit).
    #[test]
    fn wilson_interval_matches_newcombe() {
        let cases = [
            (81, 263, 0.2553, 0.3662),
            (15, 148, 0.0624, 0.1605),
            (0, 20, 0.0, 0.1611),
            (1, 29, 0.0061, 0.1718),
        ];
        for (k, n, lo, hi) in cases {
            let (l, h) = wilson_interval(k, n);
            assert!(
                (l - lo).abs() < 5e-5 && (h - hi).abs() < 5e-5,
                "{k}/{n}: {l} {h}"
            );
        }
    }

    // (d) The stump of margin = X1 − 0.3 separates perfectly: holds when x1 > t with t midway
    // between the two samples around 0.3. With one point per slice of width 1/n these are
    // less than 2/n apart, so |t − 0.3| < 1/n. On the inert x2 no split beats much the
    // constant guess (0.7).
    #[test]
    fn stump_recovers_the_threshold() {
        let n = 256;
        let r = map(&linear(&["x1", "x2"], 0.0, 1.0), n, |x| x[0] - 0.3);
        let t = r.stump(0, 0).unwrap();
        assert_eq!((t.side, t.accuracy), (Side::Above, 1.0));
        assert!((t.threshold - 0.3).abs() < 1.0 / n as f64, "{t:?}");
        assert_eq!(
            t.describe("x1", "-"),
            format!("holds when x1 > {:.4} -", t.threshold)
        );
        let inert = r.stump(0, 1).unwrap();
        assert!(
            (inert.baseline - 0.7).abs() < 0.01 && inert.accuracy < 0.75,
            "{inert:?}"
        );
    }

    // (e) Shards k mod N = I partition the design; their results merge back into the whole.
    #[test]
    fn shards_partition_the_design_and_merge_back() {
        let design = Design::sobol(&linear(&["x1", "x2"], 0.0, 1.0), 100, 3).unwrap();
        let shards: Vec<Design> = (0..3).map(|i| design.shard(i, 3).unwrap()).collect();
        let mut indices: Vec<usize> = shards
            .iter()
            .enumerate()
            .flat_map(|(i, s)| {
                s.points()
                    .iter()
                    .inspect(move |p| assert_eq!(p.index % 3, i))
            })
            .map(|p| p.index)
            .collect();
        assert_eq!(indices.len(), 100);
        indices.sort_unstable();
        assert_eq!(indices, (0..100).collect::<Vec<_>>());
        assert!(design.shard(3, 3).is_err() && design.shard(0, 0).is_err());

        let eval = |x: &[f64]| Ok(vec![x[0] - x[1]]);
        let whole = FindingMap::new(design.clone(), one_finding("f"))
            .unwrap()
            .run(eval);
        let parts = shards
            .into_iter()
            .map(|s| FindingMap::new(s, one_finding("f")).unwrap().run(eval));
        let merged = MapResult::merge(parts.rev()).unwrap();
        assert!(merged.is_complete());
        let key = |r: &MapResult| -> Vec<_> {
            r.points
                .iter()
                .map(|p| (p.index, p.outcome.clone()))
                .collect()
        };
        assert_eq!(key(&merged), key(&whole));
        assert!(MapResult::merge([whole.clone(), whole]).is_err());
    }

    // (f) Log scale on [1e-3, 10]: value_at is lo·(hi/lo)^u, so u = 1/2 is the geometric mean
    // 0.1 and log10 of the values is uniform on [−3, 1]. With one point per slice of u (n =
    // 1024) the sample median has |u − 1/2| ≤ 1/n, i.e. it is 0.1 within a factor
    // (10⁴)^(1/1024) ≈ 1.009, and a quarter of the points lie below 10⁻² (count within 1).
    #[test]
    fn log_scale_is_log_uniform() {
        let p = Parameter::new("k", "N/m", 1e-3, 10.0, Scale::Log, "four decades").unwrap();
        assert!((p.value_at(0.5) - 0.1).abs() < 1e-15 && p.value_at(0.0) == 1e-3);
        assert!((p.coordinate_of(p.value_at(0.3)) - 0.3).abs() < 1e-12);
        let d = Design::sobol(&[p], 1024, 11).unwrap();
        let mut v: Vec<f64> = d.points().iter().map(|q| q.values[0]).collect();
        v.sort_by(f64::total_cmp);
        let median = 0.5 * (v[511] + v[512]);
        assert!((median / 0.1).ln().abs() < 1.009f64.ln(), "median {median}");
        let below = v.iter().filter(|&&x| x < 1e-2).count() as f64;
        assert!((below - 256.0).abs() <= 1.0, "{below} below 1e-2");
    }

    // (g) Failed evaluations are kept with their message: an error, a panic, a wrong number of
    // margins and a NaN margin. They are left out of the fractions and shown in the CSV.
    #[test]
    fn failing_points_are_kept_with_their_message() {
        let design = Design::sobol(&linear(&["x1"], 0.0, 1.0), 64, 1).unwrap();
        let r = FindingMap::new(design, one_finding("f"))
            .unwrap()
            .run(|x| match x[0] {
                u if u < 0.1 => Err("solver diverged, step \"7\"".into()),
                u if u < 0.2 => panic!("boom"),
                u if u < 0.3 => Ok(vec![1.0, 2.0]),
                u if u < 0.4 => Ok(vec![f64::NAN]),
                u => Ok(vec![u - 0.5]),
            });
        assert_eq!(r.points.len(), 64);
        let errors: Vec<&str> = r
            .failures()
            .iter()
            .map(|p| p.outcome.as_ref().unwrap_err().as_str())
            .collect();
        assert!((20..=28).contains(&errors.len()), "{errors:?}");
        for needle in ["diverged", "panicked: boom", "2 margins for 1", "is NaN"] {
            assert!(
                errors.iter().any(|e| e.contains(needle)),
                "{needle}: {errors:?}"
            );
        }
        assert_eq!(r.fraction_holding(0).points, 64 - errors.len());
        assert!(r.csv().contains("\"solver diverged, step \"\"7\"\"\""));
    }

    // (h) Invalid parameters are refused, by the constructor and by the design.
    #[test]
    fn invalid_parameters_are_refused() {
        let bad = [
            (1.0, 1.0, Scale::Linear, "r"),
            (2.0, 1.0, Scale::Linear, "r"),
            (f64::NAN, 1.0, Scale::Linear, "r"),
            (0.0, f64::INFINITY, Scale::Linear, "r"),
            (0.0, 1.0, Scale::Log, "r"),
            (-1.0, 1.0, Scale::Log, "r"),
            (0.0, 1.0, Scale::Linear, "  "),
        ];
        for (lo, hi, scale, reason) in bad {
            let e = Parameter::new("p", "m", lo, hi, scale, reason);
            assert!(
                matches!(e, Err(FindingsError::InvalidParameter { .. })),
                "{lo} {hi}"
            );
        }
        let mut p = linear(&["a"], 0.0, 1.0).remove(0);
        assert!(Design::sobol(&[p.clone(), p.clone()], 8, 0).is_err());
        assert!(Design::sobol(&[p.clone()], 0, 0).is_err());
        assert!(Design::sobol(&[p.clone()], MAX_POINTS + 1, 0).is_err());
        p.lo = 2.0; // public fields: the design checks again
        assert!(Design::sobol(&[p], 8, 0).is_err());
        let d = Design::sobol(&linear(&["a"], 0.0, 1.0), 8, 0).unwrap();
        for ids in [vec![], vec!["a", "a"], vec!["a b"]] {
            let f = ids.iter().map(|i| FindingSpec::new(*i, "")).collect();
            assert!(FindingMap::new(d.clone(), f).is_err(), "{ids:?}");
        }
    }

    #[test]
    fn progress_counts_every_point() {
        let design = Design::sobol(&linear(&["a"], 0.0, 1.0), 50, 0).unwrap();
        let calls = AtomicUsize::new(0);
        let last = AtomicUsize::new(0);
        FindingMap::new(design, one_finding("f"))
            .unwrap()
            .run_with_progress(
                |_| Ok(vec![0.0]),
                |done, total| {
                    assert_eq!(total, 50);
                    calls.fetch_add(1, Ordering::Relaxed);
                    last.fetch_max(done, Ordering::Relaxed);
                },
            );
        assert_eq!((calls.into_inner(), last.into_inner()), (50, 50));
    }

    // Two findings, x1 ≥ 0.3 and x2 ≤ 0.6 (x2 on a log scale): the candidates are exactly the
    // points where both hold, and every output file is written.
    #[test]
    fn candidates_and_outputs() {
        let params = vec![
            Parameter::new("x1", "m", 0.0, 1.0, Scale::Linear, "test").unwrap(),
            Parameter::new("x2", "s", 0.01, 1.0, Scale::Log, "test").unwrap(),
            Parameter::new("x3", "-", 0.0, 1.0, Scale::Linear, "test").unwrap(),
        ];
        let findings = vec![
            FindingSpec::new("a", "x1 at least 0.3"),
            FindingSpec::new("b", "x2 at most 0.6 s"),
        ];
        let design = Design::sobol(&params, 256, 5).unwrap();
        let r = FindingMap::new(design, findings)
            .unwrap()
            .run(|x| Ok(vec![x[0] - 0.3, 0.6 - x[1]]));
        let c = r.candidates();
        let expected = r
            .points
            .iter()
            .filter(|p| p.values[0] >= 0.3 && p.values[1] <= 0.6)
            .count();
        assert_eq!(c.len(), expected);
        assert!(c.iter().all(|c| c.margins.iter().all(|&m| m >= 0.0)));
        let summary = r.summary();
        assert_eq!(summary.findings[1].decisive[0].parameter, "x2");
        assert!(summary.to_markdown().contains("holds when x2 < 0.6"));

        let dir = std::env::temp_dir().join(format!("clr-findings-test-{}", std::process::id()));
        let written = r.write(&dir, "toy").unwrap();
        assert_eq!(written.len(), 3 + 2 * 2);
        assert!(written
            .iter()
            .all(|p| p.metadata().is_ok_and(|m| m.len() > 0)));
        let csv = std::fs::read_to_string(dir.join("toy.csv")).unwrap();
        assert_eq!(csv.lines().count(), 257);
        assert!(csv.starts_with("index,x1 (m),x2 (s),x3 (-),margin_a,margin_b,all_hold"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
