//! One run: resolve the target (built-in or file), simulate, write the outputs.

use std::path::Path;
use std::time::Instant;

use clr::spec::{self, apply_json_override, Assignment, Loaded, ModelSpec, SpecError};
use clr_models::{Metric, RunSettings};

use super::output::{self, Record};
use super::progress::Progress;
use super::{assignments, CliError, RunArgs};

/// A resolved target, ready to run (plain data: `Send`).
#[derive(Debug, Clone)]
pub(crate) enum Job {
    /// A catalog model with its full parameters.
    Builtin {
        name: String,
        parameters: serde_json::Value,
    },
    /// A validated generic model file.
    Generic(Box<ModelSpec>),
}

/// True when `target` names a model file rather than a built-in model.
fn is_file(target: &str) -> bool {
    target.ends_with(".toml") || Path::new(target).is_file()
}

/// Resolve a target with its overrides, end time and tolerance.
pub(crate) fn resolve(
    target: &str,
    overrides: &[Assignment],
    t_end: Option<f64>,
    rtol: Option<f64>,
) -> Result<Job, CliError> {
    let mut job = if is_file(target) {
        match spec::load(Path::new(target), overrides)? {
            Loaded::Builtin { name, parameters } => Job::Builtin { name, parameters },
            Loaded::Generic(s) => Job::Generic(s),
        }
    } else {
        let mut parameters = clr_models::catalog::default_parameters(target).map_err(|_| {
            let names: Vec<&str> = clr_models::catalog::entries()
                .iter()
                .map(|e| e.name)
                .collect();
            CliError::Input(format!(
                "unknown built-in model `{target}`; {} (or give a model file ending in .toml)",
                spec::locate::suggestion(target, names.iter().copied())
            ))
        })?;
        for a in overrides {
            apply_json_override(&mut parameters, a)?;
        }
        Job::Builtin {
            name: target.to_string(),
            parameters,
        }
    };
    if let Some(t) = t_end {
        if !(t.is_finite() && t > 0.0) {
            return Err(SpecError::plain("--t-end", "", format!("{t} s must be > 0")).into());
        }
    }
    if let Some(r) = rtol {
        if !(r.is_finite() && r > 0.0) {
            return Err(SpecError::plain("--rtol", "", format!("{r} must be > 0")).into());
        }
    }
    if let Job::Generic(s) = &mut job {
        if let Some(t) = t_end {
            s.set_t_end(t)?;
        }
        if let Some(r) = rtol {
            s.set_rtol(r)?;
        }
    }
    Ok(job)
}

/// Run a job. A simulation failure still returns a [`Record`] (with `error` set and the
/// partial results); only bad input is an `Err`.
pub(crate) fn execute(
    job: &Job,
    t_end: Option<f64>,
    rtol: Option<f64>,
    progress: Option<&Progress>,
) -> Result<Record, CliError> {
    let start = Instant::now();
    match job {
        Job::Builtin { name, parameters } => {
            let mut settings = RunSettings {
                t_end,
                rtol,
                progress: None,
            };
            if let Some(p) = progress {
                settings.progress = Some(p.callback(t_end));
            }
            let guard = progress.map(|p| p.spinner());
            let r = clr_models::catalog::run(name, parameters, &settings);
            drop(guard);
            let wall = start.elapsed().as_secs_f64();
            match r {
                Ok(o) => Ok(Record::from_output(o, "builtin", wall, None)),
                Err(clr_models::ModelsError::Simulation {
                    message, partial, ..
                }) => match partial {
                    Some(o) => Ok(Record::from_output(*o, "builtin", wall, Some(message))),
                    None => Ok(Record::empty(name, parameters.clone(), wall, message)),
                },
                Err(e) => Err(CliError::Input(e.to_string())),
            }
        }
        Job::Generic(s) => {
            let built = s.build()?;
            let mut model = built.model;
            let guard = progress.map(|p| p.spinner());
            let r = model.simulate(&built.options);
            drop(guard);
            let wall = start.elapsed().as_secs_f64();
            match r {
                Ok(res) => {
                    let metrics = generic_metrics(&res, s);
                    Ok(Record::from_results(
                        &s.name,
                        &s.file,
                        res,
                        metrics,
                        s.resolved.clone(),
                        wall,
                        None,
                    )
                    .without_orbits(s))
                }
                Err(clr_mbd::MbdError::Solver(e)) => {
                    let msg = format!(
                        "{e} (in the model file these are [solver] max_steps, rtol, atol, \
                         method)"
                    );
                    let res = partial_results(&model, s, e.solution());
                    Ok(Record::from_results(
                        &s.name,
                        &s.file,
                        res,
                        Vec::new(),
                        s.resolved.clone(),
                        wall,
                        Some(msg),
                    )
                    .without_orbits(s))
                }
                Err(e) => Err(s.model_error(&e).into()),
            }
        }
    }
}

/// The coordinates and velocities the integrator had computed before a failure, as results
/// (columns `t`, `B.x B.y B.theta B.vx B.vy B.omega` per body).
fn partial_results(
    model: &clr_mbd::Model,
    s: &ModelSpec,
    sol: &clr_ode::Solution,
) -> clr_mbd::Results {
    // rigid-body coordinates come first in q (beam coordinates follow and are not written)
    let n = model.n_coordinates();
    let nb = s.body_names().len();
    let mut columns = vec!["t".to_string()];
    for b in s.body_names() {
        for c in ["x", "y", "theta", "vx", "vy", "omega"] {
            columns.push(format!("{b}.{c}"));
        }
    }
    let mut data = Vec::new();
    for k in 0..sol.len() {
        let y = sol.state(k);
        data.push(sol.t[k]);
        for b in 0..nb {
            data.extend_from_slice(&y[3 * b..3 * b + 3]);
            data.extend_from_slice(&y[n + 3 * b..n + 3 * b + 3]);
        }
    }
    clr_mbd::Results {
        columns,
        data,
        stats: sol.stats,
        onsets: 0,
        projections: 0,
        max_position_violation: f64::NAN,
        y_final: sol.y_final.clone(),
    }
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// Metrics of a generic model run, computed from its recorded columns.
fn generic_metrics(r: &clr_mbd::Results, s: &ModelSpec) -> Vec<Metric> {
    let mut m = Vec::new();
    for (c, radial) in &s.clearances {
        if let Some(f) = r.column(&format!("{c}.normal_force")) {
            m.push(Metric::new(
                &format!("{c}.peak_normal_force"),
                max_abs(&f),
                "N",
                "largest normal contact force at the output times",
            ));
        }
        if let Some(p) = r.column(&format!("{c}.penetration")) {
            m.push(Metric::new(
                &format!("{c}.max_penetration"),
                p.iter().fold(f64::NEG_INFINITY, |a, &x| a.max(x)),
                "m",
                "largest penetration (negative: never in contact) at the output times",
            ));
        }
        if let Some(radial) = radial {
            m.push(Metric::new(
                &format!("{c}.radial_clearance"),
                *radial,
                "m",
                "bearing radius minus journal radius",
            ));
        }
        if let Some(f) = r.column(&format!("{c}.Fx")) {
            m.push(Metric::new(
                &format!("{c}.peak_reaction"),
                max_abs(&f),
                "N",
                "",
            ));
        }
    }
    if let Some(e) = r.column("energy.total") {
        let e0 = e.first().copied().unwrap_or(0.0);
        let drift = e.iter().fold(0.0f64, |a, &x| a.max((x - e0).abs()));
        m.push(Metric::new(
            "energy_change",
            drift,
            "J",
            "largest |E(t) − E(0)| of the total mechanical energy (work of drivers, damping \
             and contact included)",
        ));
    }
    m.push(Metric::new(
        "contact_onsets",
        r.onsets as f64,
        "-",
        "contact onsets located as events",
    ));
    m.push(Metric::new(
        "max_position_violation",
        r.max_position_violation,
        "m or rad",
        "largest constraint violation after accepted steps",
    ));
    m
}

/// `clr run`.
pub(crate) fn run_command(args: &RunArgs, out: &Path) -> Result<(), CliError> {
    let sets = assignments(&args.set)?;
    let job = resolve(&args.target, &sets, args.t_end, args.rtol)?;
    let progress = Progress::new(args.quiet);
    let rec = execute(&job, args.t_end, args.rtol, Some(&progress))?;
    progress.finish();
    output::write_run(out, &rec, args.t_end, args.rtol, !args.no_figures)?;
    if !args.quiet {
        eprintln!(
            "clr: {} → {} ({} rows, {:.2} s)",
            rec.model,
            out.display(),
            rec.results.len(),
            rec.wall_s
        );
    }
    match &rec.error {
        None => Ok(()),
        Some(e) => Err(CliError::Simulation(format!(
            "{e}; partial results up to t = {} s written to {}",
            rec.results
                .column("t")
                .and_then(|t| t.last().copied())
                .unwrap_or(0.0),
            out.display()
        ))),
    }
}

/// `clr export`.
pub(crate) fn export_command(
    model: &str,
    set: &[String],
    out: Option<&Path>,
) -> Result<(), CliError> {
    if is_file(model) {
        return Err(CliError::Input(format!(
            "`{model}` is a file; export writes a built-in model (see `clr list`) as a file"
        )));
    }
    let sets = assignments(set)?;
    let Job::Builtin { name, parameters } = resolve(model, &sets, None, None)? else {
        return Err(CliError::Input("export takes a built-in model name".into()));
    };
    let text = export_text(&name, &parameters)?;
    match out {
        Some(p) => std::fs::write(p, text)
            .map_err(|e| CliError::Input(format!("cannot write {}: {e}", p.display()))),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

/// The model file of a built-in model with its full parameters.
pub(crate) fn export_text(name: &str, parameters: &serde_json::Value) -> Result<String, CliError> {
    #[derive(serde::Serialize)]
    struct ModelPart<'a> {
        builtin: &'a str,
    }
    #[derive(serde::Serialize)]
    struct File<'a> {
        model: ModelPart<'a>,
        parameters: &'a serde_json::Value,
    }
    let body = toml::to_string(&File {
        model: ModelPart { builtin: name },
        parameters,
    })
    .map_err(|e| {
        CliError::Input(format!(
            "the parameters of `{name}` cannot be written as TOML ({e}); report this"
        ))
    })?;
    Ok(format!(
        "# clr model file: the built-in model `{name}` with every parameter resolved.\n\
         # `clr run <this file>` reproduces `clr run {name}` (with the same --set) bit for bit.\n\
         # Edit any value under [parameters]; units as in docs/model-file.md.\n\n{body}"
    ))
}

impl Record {
    /// Mark the translational clearances of a model file (no orbit figure for them).
    fn without_orbits(mut self, s: &ModelSpec) -> Self {
        self.no_orbit = s
            .clearances
            .iter()
            .filter(|(_, radial)| radial.is_none())
            .map(|(n, _)| n.clone())
            .collect();
        self
    }
}
