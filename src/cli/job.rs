//! One run: resolve the target (built-in or file), simulate, write the outputs.

use std::path::Path;
use std::time::Instant;

use clr_sim::spec::run::{self, is_file};
use clr_sim::spec::Assignment;

use super::output::{self, Record};
use super::progress::Progress;
use super::{assignments, CliError, RunArgs};

pub(crate) use clr_sim::spec::run::Job;

impl From<run::RunError> for CliError {
    fn from(e: run::RunError) -> Self {
        CliError::Input(e.to_string())
    }
}

/// Resolve a target with its overrides, end time and tolerance (`clr_sim::spec::run::resolve`).
pub(crate) fn resolve(
    target: &str,
    overrides: &[Assignment],
    t_end: Option<f64>,
    rtol: Option<f64>,
) -> Result<Job, CliError> {
    Ok(run::resolve(target, overrides, t_end, rtol)?)
}

/// Run a job (`clr_sim::spec::run::execute`) with a progress bar over simulated time (when
/// `progress` is given) and its wall time. A simulation failure still returns a [`Record`]
/// (with `error` set and the partial results); only bad input is an `Err`.
pub(crate) fn execute(
    job: &Job,
    t_end: Option<f64>,
    rtol: Option<f64>,
    progress: Option<&Progress>,
) -> Result<Record, CliError> {
    let start = Instant::now();
    let (callback, guard) = match progress {
        Some(p) => {
            let (cb, guard) = p.run(job.time_span(t_end));
            (Some(cb), Some(guard))
        }
        None => (None, None),
    };
    let o = run::execute(job, t_end, rtol, callback);
    drop(guard);
    Ok(Record::new(o?, start.elapsed().as_secs_f64()))
}

/// `clr run`.
pub(crate) fn run_command(args: &RunArgs, out: &Path) -> Result<(), CliError> {
    let sets = assignments(&args.set)?;
    let job = resolve(&args.target, &sets, args.t_end, args.rtol)?.with_knobs(args.knobs())?;
    let progress = Progress::new(args.quiet);
    let rec = execute(&job, args.t_end, args.rtol, Some(&progress))?;
    progress.finish();
    for n in &rec.notes {
        eprintln!("clr: note: {n}");
    }
    for w in &rec.results.warnings {
        eprintln!("clr: warning: {w}");
    }
    output::write_run(out, &rec, args, (!args.no_report).then_some(&job))?;
    if !args.quiet {
        eprintln!(
            "clr: {} → {} ({})",
            rec.model,
            out.display(),
            run_size(&rec)
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

/// The size of a run in words: rows, simulated span and wall time, each named (a bare
/// `0.04 s` reads as simulated time), e.g. `6128 rows, simulated 0.1 s in 0.04 s wall`.
pub(crate) fn run_size(rec: &Record) -> String {
    let simulated = output::simulated_time(rec).unwrap_or(0.0);
    format!(
        "{} rows, simulated {} s in {:.2} s wall",
        rec.results.len(),
        significant(simulated),
        rec.wall_s
    )
}

/// `x` with four significant digits, trailing zeros dropped (`0.1`, `0.0125`, `2.5e-5`).
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let magnitude = x.abs().log10().floor() as i32;
    if !(-4..6).contains(&magnitude) {
        return format!("{x:.3e}");
    }
    let decimals = (3 - magnitude).max(0) as usize;
    let text = format!("{x:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// What `clr export` writes besides the model: the run settings of the model file form, or the
/// built-in form.
pub(crate) struct ExportForm {
    /// `--t-end`, s.
    pub t_end: Option<f64>,
    /// `--rtol`.
    pub rtol: Option<f64>,
    /// `--builtin`: `[model] builtin` with `[parameters]`.
    pub builtin: bool,
}

/// `clr export`.
pub(crate) fn export_command(
    model: &str,
    set: &[String],
    form: &ExportForm,
    out: Option<&Path>,
) -> Result<(), CliError> {
    if is_file(model) {
        return Err(CliError::Input(format!(
            "`{model}` is a file; export writes a built-in model (see `clr list`) as a file"
        )));
    }
    let sets = assignments(set)?;
    let Job::Builtin {
        name, parameters, ..
    } = resolve(model, &sets, None, None)?
    else {
        return Err(CliError::Input("export takes a built-in model name".into()));
    };
    let text = if form.builtin {
        if form.t_end.is_some() || form.rtol.is_some() {
            return Err(CliError::Input(
                "--t-end and --rtol are run settings, which the built-in form (--builtin) does \
                 not hold; give them to `clr run`, or export without --builtin"
                    .into(),
            ));
        }
        export_text(&name, &parameters)?
    } else {
        desc_text(&name, &parameters, set, form)?
    };
    match out {
        Some(p) => std::fs::write(p, text)
            .map_err(|e| CliError::Input(format!("cannot write {}: {e}", p.display()))),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

/// `clr fmu`: the FMU of a model file, or of a built-in model's exported file.
pub(crate) fn fmu_command(
    model: &str,
    out: &Path,
    outputs: Option<Vec<String>>,
    parameters: Vec<String>,
    step_size: Option<f64>,
    fmi_version: u8,
) -> Result<(), CliError> {
    use clr_sim::fmu::FmiVersion;
    let fmi_version = match fmi_version {
        2 => FmiVersion::V2,
        3 => FmiVersion::V3,
        v => {
            return Err(CliError::Input(format!(
                "--fmi-version {v}: give 3 (FMI 3.0, the default) or 2 (FMI 2.0)"
            )))
        }
    };
    let req = &clr_sim::fmu::FmuRequest {
        fmi_version,
        outputs,
        parameters,
        step_size,
    };
    let (file, src) = if is_file(model) {
        let src = std::fs::read_to_string(model)
            .map_err(|e| CliError::Input(format!("cannot read {model}: {e}")))?;
        (model.to_string(), src)
    } else {
        let Job::Builtin {
            name, parameters, ..
        } = resolve(model, &[], None, None)?
        else {
            return Err(CliError::Input(format!("`{model}` is not a model file")));
        };
        let form = ExportForm {
            t_end: None,
            rtol: None,
            builtin: false,
        };
        (
            format!("{name}.toml"),
            desc_text(&name, &parameters, &[], &form)?,
        )
    };
    let library = clr_sim::fmu::find_library().map_err(|e| CliError::Input(e.to_string()))?;
    let c = clr_sim::fmu::write(out, (&file, &src), req, &library)
        .map_err(|e| CliError::Input(e.to_string()))?;
    let names = |v: &[clr_sim::fmu::VariableConfig]| {
        v.iter()
            .map(|x| x.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    eprintln!(
        "clr: wrote {} (FMI {} co-simulation, model `{}`)\n  inputs ({}): {}\n  outputs ({}): \
         {}\n  parameters ({}): {}\n  default experiment: {} s to {} s, step {} s, tolerance {}",
        out.display(),
        if fmi_version == FmiVersion::V2 {
            "2.0"
        } else {
            "3.0"
        },
        c.model_name,
        c.inputs.len(),
        names(&c.inputs),
        c.outputs.len(),
        names(&c.outputs),
        c.parameters.len(),
        c.parameters
            .iter()
            .map(|p| p.path.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        c.experiment[0],
        c.experiment[1],
        c.experiment[2],
        c.experiment[3],
    );
    Ok(())
}

/// The complete model of a built-in run as a model file (`clr_models::catalog::export`), with
/// a header naming the built-in, the overrides `set` and run settings it came from, and every
/// parameter (commented out).
pub(crate) fn desc_text(
    name: &str,
    parameters: &serde_json::Value,
    set: &[String],
    form: &ExportForm,
) -> Result<String, CliError> {
    let settings = clr_models::RunSettings {
        t_end: form.t_end,
        rtol: form.rtol,
        progress: None,
        ..Default::default()
    };
    let desc = clr_models::catalog::export(name, parameters, &settings)
        .map_err(|e| CliError::Input(e.to_string()))?;
    let body = desc.to_toml().map_err(|e| {
        CliError::Input(format!(
            "`{name}` with these parameters cannot be written as a model file: {e}"
        ))
    })?;
    let params = toml::to_string(parameters).map_err(|e| {
        CliError::Input(format!(
            "the parameters of `{name}` cannot be written as TOML ({e}); report this"
        ))
    })?;
    let mut options = String::new();
    for a in set {
        options.push_str(&format!(" --set {a}"));
    }
    if let Some(t) = form.t_end {
        options.push_str(&format!(" --t-end {t}"));
    }
    if let Some(r) = form.rtol {
        options.push_str(&format!(" --rtol {r}"));
    }
    let mut text = format!(
        "# clr model file: the built-in model `{name}` as its complete multibody model, with the\n\
         # run settings in [solver] and [output]. Written by `clr export {name}{options}`.\n\
         # `clr run <this file>` simulates exactly what `clr run {name}{options}` simulates:\n\
         # the same clr-mbd columns bit for bit (the built-in run adds derived columns and its\n\
         # own metrics). SI units, angles in rad (docs/model-file.md).\n\
         #\n\
         # The parameters of `{name}` it was built from (`clr export --builtin` writes them as a\n\
         # built-in model file):\n#\n"
    );
    for line in params.lines() {
        if line.is_empty() {
            text.push_str("#\n");
        } else {
            text.push_str(&format!("#   {line}\n"));
        }
    }
    text.push('\n');
    text.push_str(&body);
    Ok(text)
}

/// The model file of a built-in model with its full parameters (`clr export --builtin`).
pub(crate) fn export_text(name: &str, parameters: &serde_json::Value) -> Result<String, CliError> {
    Ok(run::builtin_file_text(name, parameters)?)
}

/// `clr view` of a spatial model: its 3-D page at t0.
fn view_spatial(s: &clr_sim::spec::SpatialSpec, out: &Path, quiet: bool) -> Result<(), CliError> {
    let (mut model, options) = s.build()?;
    let results = model
        .initial_results(options.t0)
        .map_err(|e| CliError::from(s.model_error(&e)))?;
    let notes: Vec<String> = s.notes.iter().chain(&results.notes).cloned().collect();
    let input = clr_sim::report::Input {
        model: &s.name,
        source: &s.file,
        description: &s.description,
        desc: Err(String::new()),
        results: &results,
        metrics: &[],
        notes: &notes,
        error: None,
    };
    let scene = clr_sim::report::spatial::SpatialScene::from_desc(s.desc());
    let report = clr_sim::report::Report::spatial("view", &input, scene, Default::default())
        .map_err(|e| CliError::Input(format!("{}: {e}", s.file)))?;
    std::fs::write(out, report.html())
        .map_err(|e| CliError::Input(format!("cannot write {}: {e}", out.display())))?;
    if !quiet {
        for n in &notes {
            eprintln!("clr: note: {n}");
        }
        eprintln!("clr: {} at t0 → {}", s.name, out.display());
    }
    Ok(())
}

/// `clr view`: the mechanism at t0 (consistent initial conditions assembled, not simulated) as
/// `report.html`, with what the assembly changed.
pub(crate) fn view_command(
    target: &str,
    set: &[String],
    out: &Path,
    quiet: bool,
) -> Result<(), CliError> {
    let sets = assignments(set)?;
    let job = resolve(target, &sets, None, None)?;
    if let Job::Spatial(s) = &job {
        return view_spatial(s, out, quiet);
    }
    let desc = job.desc(None, None).map_err(CliError::Input)?;
    let results = clr_sim::report::initial_state(&desc, desc.output.t_start)
        .map_err(|e| CliError::Input(format!("{target}: {e}")))?;
    let mut notes: Vec<String> = match &job {
        Job::Generic(s) => s.notes.clone(),
        Job::Spatial(s) => s.notes.clone(),
        Job::Builtin { .. } => Vec::new(),
    };
    if let Some(ic) = &results.initial_conditions {
        notes.extend(ic.notes());
    }
    let name = desc
        .model
        .name
        .clone()
        .unwrap_or_else(|| target.to_string());
    let source = if is_file(target) { target } else { "builtin" };
    let input = clr_sim::report::Input {
        model: &name,
        source,
        description: desc.model.description.as_deref().unwrap_or(""),
        desc: Ok(&desc),
        results: &results,
        metrics: &[],
        notes: &notes,
        error: None,
    };
    let report = clr_sim::report::Report::new("view", &input, clr_sim::report::Limits::default());
    std::fs::write(out, report.html())
        .map_err(|e| CliError::Input(format!("cannot write {}: {e}", out.display())))?;
    if !quiet {
        for n in &notes {
            eprintln!("clr: note: {n}");
        }
        eprintln!("clr: {name} at t0 → {}", out.display());
    }
    Ok(())
}
