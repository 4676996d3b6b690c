//! Pieces shared by the models: solver settings, contact-law parameters, units of the result
//! columns, derived columns, time-series metrics and study output (CSV, figures).

use std::path::Path;

use clr_contact::{DampingFactor, ElasticLaw, FrictionLaw, JournalBearing, Material, NormalLaw};
use clr_mbd::desc::{MaterialDesc, OutputSettings, SolverMethod, SolverSettings};
use clr_mbd::SolverKind;
use clr_mbd::{
    FrictionLawDesc, MbdError, Model, ModelBuilder, ModelDesc, NormalLawDesc, Results, SimOptions,
};
use serde::{Deserialize, Serialize};

use crate::{Metric, ModelsError, RunOutput, RunSettings};

/// Where the force pair of a revolute clearance joint acts (serialized `"common_point"`,
/// `"contact_points"`); see `clr_contact::ForceApplication`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum PairApplication {
    /// Both forces at the midpoint of the two contact points: conserves angular momentum.
    #[default]
    CommonPoint,
    /// Each force at its own body's contact point (Flores et al. 2004): the friction pair adds
    /// a moment δ·F_T.
    ContactPoints,
}

impl From<PairApplication> for clr_contact::ForceApplication {
    fn from(a: PairApplication) -> Self {
        match a {
            PairApplication::CommonPoint => Self::CommonPoint,
            PairApplication::ContactPoints => Self::ContactPoints,
        }
    }
}

/// Integrator choice of a model (serialized in lower case: `"dopri5"`, `"ndf"`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Solver {
    /// Dormand–Prince 5(4), explicit. The default of the clearance models: clr-ode's NDF
    /// stops with Newton failures on clearance impacts at tight tolerances (docs/mbd.md).
    Dopri5,
    /// Variable-order NDF (implicit).
    Ndf,
}

impl From<Solver> for SolverMethod {
    fn from(s: Solver) -> Self {
        match s {
            Solver::Dopri5 => SolverMethod::Dopri5,
            Solver::Ndf => SolverMethod::Ndf,
        }
    }
}

impl From<Solver> for SolverKind {
    fn from(s: Solver) -> Self {
        match s {
            Solver::Dopri5 => SolverKind::Dopri5,
            Solver::Ndf => SolverKind::Ndf,
        }
    }
}

/// Friction law of a clearance joint, tagged by `law` in JSON
/// (`{"law": "ambrosio", "mu": 0.01, "v0": 1e-4, "v1": 1e-3}`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "lowercase", deny_unknown_fields)]
pub enum FrictionParams {
    /// No friction.
    None,
    /// Coulomb, regularized below `v_reg` (m/s).
    Coulomb {
        /// Friction coefficient μ (–).
        mu: f64,
        /// Regularization velocity (m/s).
        v_reg: f64,
    },
    /// Ambrósio's modified Coulomb law: no friction below `v0`, full μ above `v1` (m/s).
    Ambrosio {
        /// Friction coefficient μ (–).
        mu: f64,
        /// Velocity below which friction is off (m/s).
        v0: f64,
        /// Velocity above which friction is μF_N (m/s).
        v1: f64,
    },
    /// Bai/Stribeck law with static and dynamic coefficients.
    Stribeck {
        /// Static coefficient μ_s (–).
        mu_s: f64,
        /// Dynamic coefficient μ_d (–).
        mu_d: f64,
        /// Critical velocity of static friction v_s (m/s).
        v_s: f64,
        /// Critical velocity of dynamic friction v_d (m/s).
        v_d: f64,
    },
}

impl FrictionParams {
    /// The law as model-file data (by name with its parameters).
    pub fn desc(&self) -> FrictionLawDesc {
        let mut d = FrictionLawDesc::none();
        match *self {
            FrictionParams::None => {}
            FrictionParams::Coulomb { mu, v_reg } => {
                d.law = "coulomb".into();
                d.mu = Some(mu);
                d.v_reg = Some(v_reg);
            }
            FrictionParams::Ambrosio { mu, v0, v1 } => {
                d.law = "ambrosio".into();
                d.mu = Some(mu);
                d.v0 = Some(v0);
                d.v1 = Some(v1);
            }
            FrictionParams::Stribeck {
                mu_s,
                mu_d,
                v_s,
                v_d,
            } => {
                d.law = "stribeck".into();
                d.mu_s = Some(mu_s);
                d.mu_d = Some(mu_d);
                d.v_s = Some(v_s);
                d.v_d = Some(v_d);
            }
        }
        d
    }

    /// The clr-contact law.
    ///
    /// # Errors
    /// The clr-contact message for invalid coefficients or velocities.
    pub fn law(&self) -> Result<FrictionLaw, String> {
        let r = match *self {
            FrictionParams::None => FrictionLaw::coulomb(0.0, 1.0),
            FrictionParams::Coulomb { mu, v_reg } => FrictionLaw::coulomb(mu, v_reg),
            FrictionParams::Ambrosio { mu, v0, v1 } => FrictionLaw::ambrosio(mu, v0, v1),
            FrictionParams::Stribeck {
                mu_s,
                mu_d,
                v_s,
                v_d,
            } => FrictionLaw::stribeck(mu_s, mu_d, v_s, v_d),
        };
        r.map_err(|e| format!("friction: {e}"))
    }
}

/// Normal law of a journal–bearing pair: one of the flap paper's presets
/// (`Hertz`, `LN`, `Gonthier`, `Bai`, `Wang`, `Modified`, see `NormalLaw::preset`) built from the
/// geometry and materials.
///
/// # Errors
/// The clr-contact message (unknown name, invalid geometry or restitution).
pub fn preset_law(
    name: &str,
    youngs_modulus: f64,
    poisson_ratio: f64,
    r_bearing: f64,
    r_journal: f64,
    length: f64,
    restitution: f64,
) -> Result<NormalLaw, String> {
    let mat = Material::new(youngs_modulus, poisson_ratio).map_err(|e| e.to_string())?;
    let jb = JournalBearing {
        bearing: mat,
        journal: mat,
        r_bearing,
        r_journal,
        length,
    };
    NormalLaw::preset(name, &jb, restitution).map_err(|e| format!("normal law: {e}"))
}

/// A flap-paper preset as model-file data: the radii come from the clearance joint, the
/// material (`youngs_modulus` Pa, `poisson_ratio`) is the same for bearing and journal.
pub fn preset_desc(
    name: &str,
    youngs_modulus: f64,
    poisson_ratio: f64,
    length: f64,
    restitution: f64,
) -> NormalLawDesc {
    NormalLawDesc {
        // only the Liu-based presets take L (a file refuses it for the others)
        length: clr_contact::normal::preset_uses_length(name).then_some(length),
        ..journal_preset_desc(name, youngs_modulus, poisson_ratio, restitution)
    }
}

/// [`preset_desc`] for a spatial journal clearance joint: no length, as the joint gives its
/// line laws its own contact length min(L_b, L_j) (clr-mbd spatial compile).
pub fn journal_preset_desc(
    name: &str,
    youngs_modulus: f64,
    poisson_ratio: f64,
    restitution: f64,
) -> NormalLawDesc {
    let mat = MaterialDesc {
        youngs_modulus,
        poisson_ratio,
    };
    NormalLawDesc {
        law: "preset".into(),
        preset: Some(name.into()),
        restitution,
        length: None,
        bearing_material: Some(mat),
        journal_material: Some(mat),
        ..NormalLawDesc::default()
    }
}

/// The sliding-guide laws as model-file data: the edge line law (`flores-line`) and the area law
/// (`area`) of a slider face on a guide of the same material.
///
/// # Errors
/// What is wrong with a parameter (the laws are built once to check them).
pub fn guide_law_descs(
    youngs_modulus: f64,
    poisson_ratio: f64,
    edge_radius: f64,
    width: f64,
    layer_depth: f64,
    restitution: f64,
) -> Result<(NormalLawDesc, NormalLawDesc), String> {
    let mat = MaterialDesc {
        youngs_modulus,
        poisson_ratio,
    };
    let line = NormalLawDesc {
        law: "flores-line".into(),
        restitution,
        slider_material: Some(mat),
        guide_material: Some(mat),
        edge_radius: Some(edge_radius),
        width: Some(width),
        ..NormalLawDesc::default()
    };
    let area = NormalLawDesc {
        law: "area".into(),
        layer_depth: Some(layer_depth),
        ..line.clone()
    };
    // built once here for the parameter-level message (the model builds them again)
    line.build("normal", None).map_err(|e| e.message)?;
    area.build("area_normal", None).map_err(|e| e.message)?;
    Ok((line, area))
}

/// Lankarani–Nikravesh law with a given Hertz constant K (N/m^1.5):
/// F = Kδ^{3/2}(1 + 3(1 − c_e²)/4 · δ̇/δ̇⁻) (Lankarani & Nikravesh, J. Mech. Des. 112 (1990)).
///
/// # Errors
/// The clr-contact message for K ≤ 0 or c_e outside (0, 1].
pub fn ln_law(k: f64, restitution: f64) -> Result<NormalLaw, String> {
    let el = ElasticLaw::hertz(k).map_err(|e| format!("normal law: {e}"))?;
    NormalLaw::new(el, DampingFactor::LankaraniNikravesh, restitution)
        .map_err(|e| format!("normal law: {e}"))
}

/// Check that `v` is finite and > 0; the error says what to change.
pub(crate) fn positive(field: &str, v: f64) -> Result<(), String> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(format!("`{field}` = {v} must be a positive finite number"))
    }
}

/// Check that `v` is finite and ≥ 0.
pub(crate) fn non_negative(field: &str, v: f64) -> Result<(), String> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(format!("`{field}` = {v} must be a finite number ≥ 0"))
    }
}

/// Deserialize model parameters, mapping serde errors to [`ModelsError::InvalidParameters`].
pub(crate) fn parse<T: serde::de::DeserializeOwned>(
    model: &str,
    value: &serde_json::Value,
) -> Result<T, ModelsError> {
    serde_json::from_value(value.clone()).map_err(|e| invalid(model, e.to_string()))
}

/// An [`ModelsError::InvalidParameters`].
pub(crate) fn invalid(model: &str, message: impl Into<String>) -> ModelsError {
    ModelsError::InvalidParameters {
        model: model.to_string(),
        message: message.into(),
    }
}

/// Map a clr-mbd error of a build to [`ModelsError::Build`].
pub(crate) fn build_error(model: &str, e: MbdError) -> ModelsError {
    ModelsError::Build {
        model: model.to_string(),
        source: Box::new(e),
    }
}

/// Map a clr-mbd error of a simulation to [`ModelsError::Simulation`]. For an integrator
/// failure `partial` holds the rows clr-mbd recorded up to it (every column of a complete
/// simulation, with units), the metrics `steps` and `contact_onsets` up to the failure (the
/// model's own metrics need the complete run and derived columns, so they are absent) and
/// `parameters` = null (the caller has them); other errors have no partial results.
pub(crate) fn sim_error(model: &str, e: MbdError) -> ModelsError {
    let message = e.to_string();
    let partial = e
        .into_partial()
        .map(|r| Box::new(output(model, r, Vec::new(), serde_json::Value::Null)));
    ModelsError::Simulation {
        model: model.to_string(),
        message,
        partial,
    }
}

/// Simulate `m` with `opts`, forwarding the simulated time (s) to `settings.progress` about
/// every 1 % of the span (`clr_mbd::Model::simulate_with`); errors as [`sim_error`].
pub(crate) fn simulate(
    m: &mut Model,
    opts: &SimOptions,
    settings: &RunSettings,
    model: &str,
) -> Result<Results, ModelsError> {
    let r = match &settings.progress {
        Some(p) => m.simulate_with(opts, &|t| p(t)),
        None => m.simulate(opts),
    };
    r.map_err(|e| sim_error(model, e))
}

/// How a built-in run records its rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Record {
    /// After every accepted step (peaks of impact forces are missed by coarse output grids).
    EveryStep,
    /// About every `dt` s over [0, t_end]: round(t_end/dt) intervals, at least one.
    Every(f64),
}

/// A built-in's description from its builder: the model's name in `[model]` and its default
/// run in `solver` and `output`: end time `t_end` (s), relative tolerance `rtol`, absolute
/// tolerance rtol·10⁻³, the integrator `solver`, no step bound, a budget of 10⁶ steps, no
/// projection, located contact onsets, every accepted step recorded from t = 0. The Baumgarte
/// coefficients recorded in the description are kept. Compiling it and simulating with
/// [`ModelDesc::sim_options`] is the built-in run without run settings.
pub(crate) fn finish_desc(
    b: ModelBuilder,
    model: &str,
    t_end: f64,
    rtol: f64,
    solver: Solver,
) -> ModelDesc {
    let mut d = b.into_desc();
    d.model.name = Some(model.to_string());
    builtin_run(&mut d.solver, &mut d.output, t_end, rtol, solver);
    d
}

/// The default run of a built-in, planar ([`finish_desc`]) or spatial (the spatial flap and
/// the spatial Wan slider–crank): `solver` at relative tolerance `rtol` and absolute tolerance
/// rtol·10⁻³, no step bound, a budget of 10⁶ steps, no projection, located contact onsets;
/// every accepted step recorded over [0, `t_end`] (s). The Baumgarte coefficients and the other
/// knobs are left as they are.
pub(crate) fn builtin_run(
    s: &mut SolverSettings,
    output: &mut OutputSettings,
    t_end: f64,
    rtol: f64,
    solver: Solver,
) {
    s.method = solver.into();
    s.rtol = rtol;
    s.atol = Some(rtol * 1e-3);
    s.h_max = None;
    s.max_steps = 1_000_000;
    s.projection = None;
    s.contact_events = true;
    *output = OutputSettings {
        t_start: 0.0,
        t_end: Some(t_end),
        intervals: 0,
        every_step: true,
        nodes: Default::default(),
    };
}

/// The run a built-in simulates: its description from `desc` (see [`finish_desc`]) with the
/// end time and tolerance of `settings` when given (atol = rtol·10⁻³ as in the default run) and
/// the recording `record`.
///
/// # Errors
/// Invalid run settings, or the error of `desc`.
pub(crate) fn run_desc(
    model: &str,
    settings: &RunSettings,
    record: Record,
    desc: impl FnOnce() -> Result<ModelDesc, ModelsError>,
) -> Result<ModelDesc, ModelsError> {
    check_settings(model, settings)?;
    let mut d = desc()?;
    if let Some(t) = settings.t_end {
        d.output.t_end = Some(t);
    }
    if let Some(r) = settings.rtol {
        d.solver.rtol = r;
        d.solver.atol = Some(r * 1e-3);
    }
    settings.knobs.apply(&mut d.solver);
    let intervals = match record {
        Record::EveryStep => 0,
        Record::Every(dt) => {
            let t_end = d.output.t_end.unwrap_or(0.0);
            ((t_end / dt).round() as usize).max(1)
        }
    };
    d.output.intervals = intervals;
    d.output.every_step = record == Record::EveryStep;
    Ok(d)
}

/// Compile a description into the runtime model ([`ModelsError::Build`] on failure).
pub(crate) fn compile(model: &str, desc: &ModelDesc) -> Result<Model, ModelsError> {
    desc.compile().map_err(|e| build_error(model, e))
}

/// Compile a description and take its simulation options (an invalid `[solver]` or
/// `[output]` is [`ModelsError::InvalidParameters`]).
pub(crate) fn compile_run(
    model: &str,
    desc: &ModelDesc,
) -> Result<(Model, SimOptions), ModelsError> {
    let opts = desc
        .sim_options()
        .map_err(|e| invalid(model, e.to_string()))?;
    Ok((compile(model, desc)?, opts))
}

/// Check run settings that apply to every model.
pub(crate) fn check_settings(model: &str, settings: &RunSettings) -> Result<(), ModelsError> {
    settings.knobs.validate().map_err(|m| invalid(model, m))?;
    if let Some(t) = settings.t_end {
        positive("t_end (s)", t).map_err(|m| invalid(model, m))?;
    }
    if let Some(r) = settings.rtol {
        if !(r.is_finite() && r > 0.0 && r < 1.0) {
            return Err(invalid(
                model,
                format!("rtol = {r} must be in (0, 1), e.g. 1e-8"),
            ));
        }
    }
    Ok(())
}

pub use clr_mbd::results::unit_of;

/// Units of every column of `results`.
pub fn units(results: &Results) -> Vec<String> {
    results
        .columns
        .iter()
        .map(|c| results.unit(c).to_string())
        .collect()
}

/// A column that must exist (the models only ask for columns they created).
pub(crate) fn col(results: &Results, name: &str) -> Vec<f64> {
    results.column(name).unwrap_or_default()
}

/// Append derived columns (same number of rows) to results.
pub(crate) fn append_columns(results: &mut Results, new: Vec<(String, Vec<f64>)>) {
    results.append_columns(new);
}

/// Largest |v| over rows with t ≥ t_from.
pub fn peak_abs(t: &[f64], v: &[f64], t_from: f64) -> f64 {
    t.iter()
        .zip(v)
        .filter(|(&ti, _)| ti >= t_from)
        .map(|(_, x)| x.abs())
        .fold(0.0, f64::max)
}

/// The located peak normal force (N) and penetration (m) of clearance joint `joint` over its
/// impacts whose extremum lies at or after `t_from` (s), each no smaller than the largest row
/// value `rows` = (force, penetration) after `t_from` (a contact already closed at t0 has no
/// located onset, and the rows cover it). clr-mbd locates the extrema on the dense output
/// (`clr_mbd::Impact`), so the result does not depend on where the output rows fall.
pub fn located_peaks(res: &Results, joint: &str, t_from: f64, rows: (f64, f64)) -> (f64, f64) {
    let window = (t_from, f64::INFINITY);
    (
        located_extreme(res, joint, "normal_force", window, rows.0),
        located_extreme(res, joint, "penetration", window, rows.1),
    )
}

/// The largest of `rows` and the located peaks of `quantity` (`normal_force` or `penetration`)
/// of contact element `joint`'s impacts whose extremum lies in `window` (s); `rows` for any
/// other quantity.
pub fn located_extreme(
    res: &Results,
    joint: &str,
    quantity: &str,
    window: (f64, f64),
    rows: f64,
) -> f64 {
    let inside = |at: f64| at >= window.0 && at <= window.1;
    let of_joint = res.impacts.iter().filter(|i| i.joint == joint);
    match quantity {
        "normal_force" => of_joint
            .filter(|i| inside(i.peak_force_time))
            .map(|i| i.peak_force)
            .fold(rows, f64::max),
        "penetration" => of_joint
            .filter(|i| inside(i.max_penetration_time))
            .map(|i| i.max_penetration)
            .fold(rows, f64::max),
        _ => rows,
    }
}

/// Largest v (signed) over rows with t ≥ t_from; 0 when every value is negative.
pub fn peak_max(t: &[f64], v: &[f64], t_from: f64) -> f64 {
    t.iter()
        .zip(v)
        .filter(|(&ti, _)| ti >= t_from)
        .map(|(_, &x)| x)
        .fold(0.0, f64::max)
}

/// Time-weighted mean of v over [t_from, t_end] (trapezoidal rule, uneven rows allowed).
pub fn time_mean(t: &[f64], v: &[f64], t_from: f64) -> f64 {
    let (mut s, mut span) = (0.0, 0.0);
    for k in 1..t.len() {
        if t[k - 1] < t_from {
            continue;
        }
        let dt = t[k] - t[k - 1];
        s += 0.5 * (v[k] + v[k - 1]) * dt;
        span += dt;
    }
    if span > 0.0 {
        s / span
    } else {
        0.0
    }
}

/// Time-weighted RMS of v over [t_from, t_end] (trapezoidal rule on v²).
pub fn time_rms(t: &[f64], v: &[f64], t_from: f64) -> f64 {
    let sq: Vec<f64> = v.iter().map(|x| x * x).collect();
    time_mean(t, &sq, t_from).sqrt()
}

pub use clr_mbd::measure::deviation::interp;

/// Write `contents` to `path` under a temporary name in the same folder (`.<name>.partial-<pid>`)
/// and rename it into place, so that a reader, or a run resumed after a kill, finds the old
/// file or the new one, never a part of it.
///
/// # Errors
/// The I/O error of the write or the rename.
pub fn write_atomic(path: &Path, contents: impl AsRef<[u8]>) -> std::io::Result<()> {
    let name = path
        .file_name()
        .map_or("out".into(), |n| n.to_string_lossy());
    let tmp = path.with_file_name(format!(".{name}.partial-{}", std::process::id()));
    std::fs::write(&tmp, contents)?;
    std::fs::rename(&tmp, path)
}

/// Write results as CSV into `dir/name.csv` (creating `dir`).
///
/// # Errors
/// The I/O message.
pub fn write_results_csv(results: &Results, dir: &Path, name: &str) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    results
        .write_csv(&dir.join(format!("{name}.csv")))
        .map_err(|e| e.to_string())
}

/// Save figure `f` as `dir/name` (the figure writes its .svg and .png), with the error as text.
///
/// # Errors
/// The figure could not be written.
pub fn save_figure(f: clr_plot::Figure, dir: &Path, name: &str) -> Result<(), String> {
    f.save(dir.join(name))
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// Write a tidy table (header + rows) as CSV.
///
/// # Errors
/// The I/O message.
pub fn write_table_csv(path: &Path, header: &[&str], rows: &[Vec<String>]) -> Result<(), String> {
    use std::io::Write;
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).map_err(|e| format!("{}: {e}", d.display()))?;
    }
    let mut f = std::io::BufWriter::new(
        std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?,
    );
    let w = |f: &mut std::io::BufWriter<std::fs::File>, s: String| {
        writeln!(f, "{s}").map_err(|e| format!("{}: {e}", path.display()))
    };
    w(&mut f, header.join(","))?;
    for r in rows {
        w(&mut f, r.join(","))?;
    }
    f.flush().map_err(|e| format!("{}: {e}", path.display()))
}

/// Pairs (x, y) thinned to at most `max` points (every k-th row, keeping the last), for figures.
pub fn thin(x: &[f64], y: &[f64], max: usize) -> Vec<(f64, f64)> {
    let n = x.len().min(y.len());
    let step = n.div_ceil(max.max(1)).max(1);
    let mut v: Vec<(f64, f64)> = (0..n).step_by(step).map(|k| (x[k], y[k])).collect();
    if n > 0 && (n - 1) % step != 0 {
        v.push((x[n - 1], y[n - 1]));
    }
    v
}

/// Write `dir/summary.csv` of a study: the key columns of each run (`key_header`, then
/// `wall_s`), then one column per metric name in first-seen order over all runs (NaN where a run
/// lacks a metric).
///
/// # Errors
/// The I/O message.
pub(crate) fn write_study_summary(
    dir: &Path,
    key_header: &[&str],
    runs: &[(Vec<String>, f64, &[crate::Metric])],
) -> Result<(), String> {
    let mut names: Vec<&str> = Vec::new();
    for (_, _, metrics) in runs {
        for m in metrics.iter() {
            if !names.contains(&m.name.as_str()) {
                names.push(&m.name);
            }
        }
    }
    let mut header = key_header.to_vec();
    header.push("wall_s");
    header.extend(names.iter().copied());
    let rows: Vec<Vec<String>> = runs
        .iter()
        .map(|(keys, wall_s, metrics)| {
            let mut r = keys.clone();
            r.push(format!("{wall_s:.3}"));
            r.extend(names.iter().map(|n| {
                let v = metrics
                    .iter()
                    .find(|m| m.name == *n)
                    .map_or(f64::NAN, |m| m.value);
                format!("{v:e}")
            }));
            r
        })
        .collect();
    write_table_csv(&dir.join("summary.csv"), &header, &rows)
}

/// The RunOutput of a finished simulation; appends the solver metrics every model reports
/// (`steps`, `contact_onsets`).
pub(crate) fn output(
    model: &str,
    results: Results,
    mut metrics: Vec<crate::Metric>,
    parameters: serde_json::Value,
) -> RunOutput {
    metrics.extend(crate::output::energy_metrics(&results));
    metrics.push(crate::Metric::new(
        "steps",
        results.stats.accepted as f64,
        "-",
        "accepted integrator steps",
    ));
    metrics.push(crate::Metric::new(
        "contact_onsets",
        results.onsets as f64,
        "-",
        "contact onsets located as events",
    ));
    // a built-in's metrics are taken over the recorded run unless its model names a later
    // window (a transient it skips), so every one says which
    for m in metrics.iter_mut().filter(|m| m.window.is_none()) {
        m.window = Some(crate::output::WHOLE_RUN.to_string());
    }
    RunOutput {
        model: model.to_string(),
        units: units(&results),
        results,
        metrics,
        parameters,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_statistics_of_a_sine() {
        // mean of sin² over whole periods is 1/2 (closed form); RMS of sin is 1/√2
        let t: Vec<f64> = (0..=4000).map(|k| k as f64 * 1e-3).collect();
        let v: Vec<f64> = t
            .iter()
            .map(|&x| (2.0 * std::f64::consts::PI * x).sin())
            .collect();
        assert!((time_rms(&t, &v, 0.0) - 0.5f64.sqrt()).abs() < 1e-6);
        assert!(time_mean(&t, &v, 0.0).abs() < 1e-9);
        assert!((peak_abs(&t, &v, 0.0) - 1.0).abs() < 1e-5);
        // linear interpolation is exact on a straight line
        let lin: Vec<f64> = t.iter().map(|&x| 3.0 * x - 1.0).collect();
        assert!((interp(&t, &lin, 1.23456) - (3.0 * 1.23456 - 1.0)).abs() < 1e-12);
    }

    /// A slider-crank with a clearance joint stopped by a tiny step budget: `sim_error` keeps
    /// the rows of the complete run (compared against an independent complete run with the same
    /// settings, bit for bit), their units and the step count; `simulate` forwards the progress
    /// hook up to the end time.
    #[test]
    fn failed_simulation_keeps_partial_results_and_progress_reaches_t_end() {
        use std::sync::{Arc, Mutex};
        let p = crate::slider_crank::SliderCrankParams {
            duration: 0.005,
            ..Default::default()
        };
        let seen = Arc::new(Mutex::new(Vec::new()));
        let s2 = seen.clone();
        let settings = RunSettings {
            progress: Some(Box::new(move |t| s2.lock().unwrap().push(t))),
            ..Default::default()
        };
        let desc = p.desc("t").unwrap();
        let (mut m, mut opts) = compile_run("t", &desc).unwrap();
        let full = simulate(&mut m, &opts, &settings, "t").unwrap();
        let seen = seen.lock().unwrap().clone();
        assert!(seen.windows(2).all(|w| w[1] > w[0]));
        assert_eq!(seen.last().copied(), Some(opts.t_end));
        opts.max_steps = full.stats.accepted / 3;
        let err = simulate(&mut compile("t", &desc).unwrap(), &opts, &settings, "t").unwrap_err();
        let ModelsError::Simulation {
            message, partial, ..
        } = err
        else {
            panic!("expected a simulation error, got {err}");
        };
        assert!(message.contains("step budget"), "{message}");
        let o = partial.expect("partial results of a solver failure");
        assert_eq!(o.results.columns, full.columns);
        assert_eq!(o.units, units(&full));
        assert!(o.results.len() > 1 && o.results.len() < full.len());
        for r in 0..o.results.len() {
            assert_eq!(o.results.row(r), full.row(r), "row {r}");
        }
        let steps = o.metrics.iter().find(|m| m.name == "steps").unwrap();
        assert_eq!(steps.value, opts.max_steps as f64);
    }

    #[test]
    fn units_follow_the_column_names() {
        assert_eq!(unit_of("t"), "s");
        assert_eq!(unit_of("slider.ax"), "m/s^2");
        assert_eq!(unit_of("B.normal_force"), "N");
        assert_eq!(unit_of("O.M"), "N*m");
        assert_eq!(unit_of("energy.total"), "J");
        assert_eq!(unit_of("crank.theta"), "rad");
        assert_eq!(unit_of("guide.n6.v"), "m");
        assert_eq!(unit_of("guide.n12.u"), "m");
        assert_eq!(unit_of("guide.n6.theta"), "rad");
        assert_eq!(unit_of("guide.q1"), "-");
    }
}

/// One run of a parameter study: its name, parameters, metrics and wall time.
#[derive(Debug, Clone)]
pub struct StudyRun<P> {
    /// Run name (e.g. `elastic`, `c0.50mm`).
    pub name: String,
    /// The parameters.
    pub params: P,
    /// Metrics of the model's `run`.
    pub metrics: Vec<Metric>,
    /// Wall time, s.
    pub wall_s: f64,
}

impl<P> StudyRun<P> {
    /// A metric by name (NaN when absent).
    pub fn metric(&self, name: &str) -> f64 {
        crate::output::metric_value(&self.metrics, name)
    }
}

/// Run named parameter sets in parallel (rayon) with `run`, write every run's CSV
/// (`<name>.csv`) and `summary.csv` (metrics and wall time) under `dir`; the runs in input order
/// and their results.
///
/// # Errors
/// The first failing run (message prefixed with its name), or an output error.
pub fn run_study<P: Send + Sync>(
    dir: &Path,
    runs: Vec<(String, P)>,
    run: impl Fn(&P) -> Result<RunOutput, ModelsError> + Sync,
) -> Result<(Vec<StudyRun<P>>, Vec<Results>), String> {
    use rayon::prelude::*;
    let out: Vec<Result<(StudyRun<P>, Results), String>> = runs
        .into_par_iter()
        .map(|(name, params)| {
            let start = std::time::Instant::now();
            let o = run(&params).map_err(|e| format!("{name}: {e}"))?;
            Ok((
                StudyRun {
                    name,
                    params,
                    metrics: o.metrics,
                    wall_s: start.elapsed().as_secs_f64(),
                },
                o.results,
            ))
        })
        .collect();
    let mut done = Vec::new();
    let mut results = Vec::new();
    for r in out {
        let (s, res) = r?;
        write_results_csv(&res, dir, &s.name)?;
        done.push(s);
        results.push(res);
    }
    let rows: Vec<_> = done
        .iter()
        .map(|r| (vec![r.name.clone()], r.wall_s, r.metrics.as_slice()))
        .collect();
    write_study_summary(dir, &["run"], &rows)?;
    Ok((done, results))
}
