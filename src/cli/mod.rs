//! Command-line parsing and dispatch.

mod animate;
mod job;
mod output;
mod parquet;
mod plot;
mod points;
mod progress;
mod series;
mod slurm;
mod sweep;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use clr_sim::spec::{parse_assignment, Assignment, SpecError};

/// clr: planar mechanisms with clearance joints, contact, friction and flexible links.
#[derive(Parser)]
#[command(name = "clr", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Settings shared by `run` and `sweep`.
#[derive(clap::Args, Clone)]
pub(crate) struct RunArgs {
    /// A built-in model name (see `clr list`) or a model file (`.toml`).
    pub target: String,
    /// Override a parameter: `name=value` (dotted path; repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// End time of the simulation, s.
    #[arg(long, value_name = "S")]
    pub t_end: Option<f64>,
    /// Relative tolerance of the integrator; the absolute one becomes 1e-3·rtol unless
    /// `--atol` is given.
    #[arg(long, value_name = "R")]
    pub rtol: Option<f64>,
    /// Absolute tolerance of the integrator, in the units of the coordinates and velocities
    /// (m, rad, m/s, rad/s).
    #[arg(long, value_name = "A")]
    pub atol: Option<f64>,
    /// Step budget of the integrator (accepted steps).
    #[arg(long, value_name = "N")]
    pub max_steps: Option<usize>,
    /// Highest NDF order (1–5).
    #[arg(long, value_name = "K")]
    pub max_order: Option<usize>,
    /// NDF's Newton matrix: `analytic` (the elements' Jacobians) or `finite-difference`.
    #[arg(long, value_enum, value_name = "MODE")]
    pub jacobian: Option<JacobianArg>,
    /// Scale the velocities' error estimate by min(h, 1) (fine beam meshes, lightly damped
    /// structures).
    #[arg(long)]
    pub scale_velocity_error: bool,
    /// Refuse the run when the plausibility checks warn (an initial penetration, units that
    /// look wrong, energy created, ...); the results of a finished run are still written.
    #[arg(long)]
    pub strict: bool,
    /// No progress bar.
    #[arg(long, short)]
    pub quiet: bool,
    /// Do not draw figures.
    #[arg(long)]
    pub no_figures: bool,
    /// Do not write report.html (the animated report).
    #[arg(long)]
    pub no_report: bool,
    /// The format of the time series and impacts: `csv` (results.csv, impacts.csv), `parquet`
    /// (results.parquet, impacts.parquet: compressed, columnar, read by pandas, polars, Arrow and
    /// MATLAB) or `both` [default: csv].
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub series: Option<SeriesFormat>,
}

/// `--series`: the files of the time series.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SeriesFormat {
    /// results.csv and impacts.csv.
    Csv,
    /// results.parquet and impacts.parquet.
    Parquet,
    /// Both.
    Both,
}

impl SeriesFormat {
    /// Whether the CSV files are written.
    pub(crate) fn csv(self) -> bool {
        self != SeriesFormat::Parquet
    }
    /// Whether the Parquet files are written.
    pub(crate) fn parquet(self) -> bool {
        self != SeriesFormat::Csv
    }
}

/// `--jacobian`.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub(crate) enum JacobianArg {
    /// The elements' analytic Jacobians in the reduced second-order Newton system.
    Analytic,
    /// Differences of the whole right-hand side.
    FiniteDifference,
}

impl RunArgs {
    /// The format of the time series: `--series`, CSV by default.
    pub(crate) fn series_format(&self) -> SeriesFormat {
        self.series.unwrap_or(SeriesFormat::Csv)
    }

    /// The integrator knobs given on the command line.
    pub(crate) fn knobs(&self) -> clr_models::SolverKnobs {
        clr_models::SolverKnobs {
            max_steps: self.max_steps,
            max_order: self.max_order,
            jacobian: self.jacobian.map(|j| match j {
                JacobianArg::Analytic => clr_mbd::JacobianMode::Analytic,
                JacobianArg::FiniteDifference => clr_mbd::JacobianMode::FiniteDifference,
            }),
            scale_velocity_error: self.scale_velocity_error,
            atol: self.atol,
            strict: self.strict,
        }
    }
}

#[derive(Subcommand)]
enum Command {
    /// List the built-in models.
    List,
    /// Run one model: writes results.csv, summary.json and figures into --out.
    Run {
        #[command(flatten)]
        args: RunArgs,
        /// Output folder.
        #[arg(long, default_value = "clr-out")]
        out: PathBuf,
    },
    /// Draw a model at t0 (initial conditions assembled, not simulated) into an HTML page.
    View {
        /// A built-in model name or a model file.
        target: String,
        /// Override a parameter: `name=value` (repeatable), as for `clr run`.
        #[arg(long, value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// The page to write.
        #[arg(long, default_value = "clr-view.html")]
        out: PathBuf,
        /// No notes on standard error.
        #[arg(long)]
        quiet: bool,
    },
    /// Run the cartesian product of parameter values (in parallel).
    Sweep {
        #[command(flatten)]
        args: RunArgs,
        /// A varied parameter: `name=v1,v2,...` (repeatable; the product is run).
        #[arg(long, value_name = "NAME=V1,V2,...", required = true)]
        vary: Vec<String>,
        /// Worker threads (default: all cores).
        #[arg(long, value_name = "N")]
        jobs: Option<usize>,
        /// Run only shard I of N (I from 0 to N−1): points k with k mod N = I.
        #[arg(long, value_name = "I/N")]
        shard: Option<String>,
        /// Keep the points already finished in --out by a run of the same sweep (same values
        /// and model), run the others (a requeued cluster task resumes with it).
        #[arg(long)]
        resume: bool,
        /// What each point folder keeps: metrics (point.json only), summary (and
        /// summary.json), series (and the time series and impacts, in the --series format)
        /// or all (and figures and
        /// report.html, as `clr run`); a failed point keeps all.
        #[arg(long, value_enum, default_value = "summary")]
        keep: points::Keep,
        /// Output folder.
        #[arg(long, default_value = "clr-sweep")]
        out: PathBuf,
    },
    /// Join the outputs of sweep shards into one sweep.csv with comparison figures.
    Merge {
        /// Shard output folders.
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// Output folder of the merged sweep.
        #[arg(long, default_value = "clr-sweep-merged")]
        out: PathBuf,
        /// Merge shards whose sweep.json has no provenance (written before clr recorded the
        /// model hash and version); they are named in a warning and in the merged sweep.json.
        #[arg(long)]
        allow_unverified: bool,
    },
    /// Run a paper study (see `clr list`): CSV per run, summary.csv and figures into --out.
    Study {
        /// Study name.
        name: String,
        /// Output folder (default: clr-study/<name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Finding maps only: evaluate the first N points of the design (default: the study's).
        #[arg(long, value_name = "N")]
        points: Option<usize>,
        /// Finding maps only: this shard I/N of the design (the points k with k mod N = I; a
        /// Slurm array task id as I), to be joined with --merge.
        #[arg(long, value_name = "I/N")]
        shard: Option<String>,
        /// Finding maps only: merge these shard folders into --out instead of running. A folder
        /// of a stopped run contributes the points of its checkpoint, so the summary of a map
        /// still running or stopped says how many of the design's points it has.
        #[arg(long, value_name = "DIR", num_args = 1..)]
        merge: Vec<PathBuf>,
        /// Finding maps only: take the points already evaluated in these folders (the
        /// checkpoint `<name>_points.jsonl` of a stopped run, or a finished map of any size of
        /// the same map; the --out folder itself is allowed) instead of running them again.
        /// Failed points are taken as failed: a point's evaluation is deterministic.
        #[arg(long, value_name = "DIR", num_args = 1..)]
        resume: Vec<PathBuf>,
        /// Finding maps, with --resume: evaluate the failed points again (after a change to
        /// what a point does, e.g. a larger step budget), instead of taking them as failed.
        #[arg(long, requires = "resume")]
        retry_failed: bool,
        /// Finding maps only, with --merge: merge shard folders that record no provenance
        /// (written before clr recorded its version and the map's hash); they are named in a
        /// warning.
        #[arg(long, requires = "merge")]
        allow_unverified: bool,
    },
    /// Write, show and submit a Slurm job array of a sweep or finding map with a dependent
    /// merge job: `clr slurm [--tasks N --cpus-per-task C --time T ...] sweep|study ...`
    /// (docs/scaling.md).
    Slurm(slurm::SlurmArgs),
    /// Export the animation of a run (its report.html) as a GIF or, through ffmpeg, an MP4.
    Animate(animate::AnimateArgs),
    /// Plot columns of a results.csv or results.parquet.
    Plot {
        /// A results.csv or results.parquet written by `clr run`.
        csv: PathBuf,
        /// Column on the x axis (`time` is an alias of `t`).
        #[arg(long, default_value = "t")]
        x: String,
        /// Columns on the y axis, comma-separated.
        #[arg(long, value_delimiter = ',', required = true)]
        y: Vec<String>,
        /// Output file (.svg, .png, or a stem for both).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Write a built-in model as a model file (its complete clr-mbd model with the run settings)
    /// whose run reproduces `clr run <name>` bit for bit.
    Export {
        /// Built-in model name.
        model: String,
        /// Override a parameter: `name=value` (repeatable).
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// End time written into the file's [output], s (as `clr run --t-end`).
        #[arg(long, value_name = "S")]
        t_end: Option<f64>,
        /// Relative tolerance written into the file's [solver] (as `clr run --rtol`).
        #[arg(long, value_name = "R")]
        rtol: Option<f64>,
        /// Write the short built-in form instead: `[model] builtin = "<name>"` and every
        /// parameter under `[parameters]`.
        #[arg(long)]
        builtin: bool,
        /// Output file (default: standard output).
        #[arg(long, short = 'o', value_name = "FILE")]
        out: Option<PathBuf>,
    },
    /// Write a co-simulation FMU (FMI 3.0) of a planar model file or built-in model: its
    /// `[[input]]`s as inputs, its `[[measure]]` columns (or the columns named) as outputs and
    /// the fields named with --parameter as parameters (docs/fmu.md).
    Fmu {
        /// Model file, or a built-in model name (its exported file).
        model: String,
        /// The FMU to write (e.g. model.fmu).
        #[arg(long, short = 'o', value_name = "FILE")]
        out: PathBuf,
        /// Output columns, comma-separated (default: the [[measure]] columns, or every
        /// column in a model without measures).
        #[arg(long, value_delimiter = ',', value_name = "COLUMNS")]
        outputs: Option<Vec<String>>,
        /// A model-file field made an FMU parameter, as a --set path (repeatable), e.g.
        /// `clearance.B.clearance`; fixed: set before the end of initialization.
        #[arg(long = "parameter", value_name = "PATH")]
        parameters: Vec<String>,
        /// The default experiment's communication step, s (default: the file's output
        /// interval).
        #[arg(long, value_name = "S")]
        step_size: Option<f64>,
        /// FMI version: 3 (default) or 2 (for masters that read only FMI 2.0).
        #[arg(long, value_name = "2|3", default_value = "3")]
        fmi_version: u8,
    },
}

/// A failure of a command, with its exit code.
#[derive(Debug)]
pub(crate) enum CliError {
    /// Bad input: exit code 2.
    Input(String),
    /// Simulation failure (partial results written): exit code 1.
    Simulation(String),
}

impl From<SpecError> for CliError {
    fn from(e: SpecError) -> Self {
        CliError::Input(e.to_string())
    }
}

pub(crate) fn assignments(set: &[String]) -> Result<Vec<Assignment>, CliError> {
    set.iter()
        .map(|s| parse_assignment(s).map_err(CliError::from))
        .collect()
}

pub(crate) fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    let r = match cli.command {
        Command::List => {
            list();
            Ok(())
        }
        Command::Run { args, out } => job::run_command(&args, &out),
        Command::Sweep {
            args,
            vary,
            jobs,
            shard,
            resume,
            keep,
            out,
        } => sweep::sweep_command(&args, &vary, jobs, (shard.as_deref(), resume, keep), &out),
        Command::Merge {
            dirs,
            out,
            allow_unverified,
        } => sweep::merge_command(&dirs, &out, allow_unverified),
        Command::View {
            target,
            set,
            out,
            quiet,
        } => job::view_command(&target, &set, &out, quiet),
        Command::Study {
            name,
            out,
            points,
            shard,
            merge,
            resume,
            retry_failed,
            allow_unverified,
        } => study_command(
            &name,
            out,
            &MapOptions {
                points,
                shard: shard.as_deref(),
                merge: &merge,
                resume: &resume,
                retry_failed,
                allow_unverified,
            },
        ),
        Command::Slurm(a) => slurm::slurm_command(&a),
        Command::Animate(a) => animate::animate_command(&a),
        Command::Plot { csv, x, y, out } => plot::plot_command(&csv, &x, &y, out.as_deref()),
        Command::Export {
            model,
            set,
            t_end,
            rtol,
            builtin,
            out,
        } => job::export_command(
            &model,
            &set,
            &job::ExportForm {
                t_end,
                rtol,
                builtin,
            },
            out.as_deref(),
        ),
        Command::Fmu {
            model,
            out,
            outputs,
            parameters,
            step_size,
            fmi_version,
        } => job::fmu_command(&model, &out, outputs, parameters, step_size, fmi_version),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::Input(m)) => {
            eprintln!("clr: error: {m}");
            ExitCode::from(2)
        }
        Err(CliError::Simulation(m)) => {
            eprintln!("clr: simulation failed: {m}");
            ExitCode::from(1)
        }
    }
}

fn list() {
    let entries = clr_models::catalog::entries();
    println!("Built-in models (clr run <name>, clr export <name>):");
    let w = entries.iter().map(|e| e.name.len()).max().unwrap_or(0);
    for e in &entries {
        println!("  {:w$}  {}", e.name, e.description);
    }
    if entries.is_empty() {
        println!("  (none yet)");
    }
    println!("Model files: clr run path/to/model.toml (format: docs/model-file.md)");
    let studies = clr_models::studies::studies();
    println!("Paper studies (clr study <name>):");
    let w = studies.iter().map(|s| s.name.len()).max().unwrap_or(0);
    for s in &studies {
        println!("  {:w$}  [{}] {}", s.name, s.model, s.description);
    }
}

/// The options of `clr study` that apply to finding maps only.
struct MapOptions<'a> {
    points: Option<usize>,
    shard: Option<&'a str>,
    merge: &'a [PathBuf],
    resume: &'a [PathBuf],
    retry_failed: bool,
    allow_unverified: bool,
}

impl MapOptions<'_> {
    fn any(&self) -> bool {
        self.points.is_some()
            || self.shard.is_some()
            || !self.merge.is_empty()
            || !self.resume.is_empty()
    }
}

fn study_command(name: &str, out: Option<PathBuf>, opts: &MapOptions) -> Result<(), CliError> {
    let study = clr_models::studies::find(name).map_err(CliError::Input)?;
    let dir = out.unwrap_or_else(|| PathBuf::from("clr-study").join(name));
    std::fs::create_dir_all(&dir)
        .map_err(|e| CliError::Input(format!("cannot create {}: {e}", dir.display())))?;
    match (study.map, opts.any()) {
        (Some(map), true) => return map_study(name, &dir, map, opts),
        (None, true) => {
            return Err(CliError::Input(format!(
                "--points, --shard, --merge and --resume apply to finding maps only; `{name}` \
                 is not one (see `clr list`)"
            )))
        }
        _ => {}
    }
    eprintln!(
        "clr: study {name} ({}) → {}",
        study.description,
        dir.display()
    );
    let start = std::time::Instant::now();
    let runs = (study.run)(&dir).map_err(CliError::Simulation)?;
    eprintln!(
        "clr: study {name}: {runs} runs in {:.1} s; summary.csv and figures in {}",
        start.elapsed().as_secs_f64(),
        dir.display()
    );
    Ok(())
}

/// A finding map run in part, as a shard, resumed, or merged from shard folders.
fn map_study(
    name: &str,
    dir: &std::path::Path,
    map: clr_models::studies::MapStudy,
    opts: &MapOptions,
) -> Result<(), CliError> {
    let start = std::time::Instant::now();
    if !opts.merge.is_empty() {
        if opts.points.is_some() || opts.shard.is_some() || !opts.resume.is_empty() {
            return Err(CliError::Input(
                "--merge joins finished shards: give it without --points, --shard or --resume"
                    .into(),
            ));
        }
        let n = map
            .merge(opts.merge, dir, opts.allow_unverified)
            .map_err(CliError::Input)?
            .points
            .len();
        eprintln!(
            "clr: study {name}: merged {n} points into {}",
            dir.display()
        );
        return Ok(());
    }
    let points = opts.points.unwrap_or(map.default_points);
    let shard = opts.shard.map(sweep::parse_shard).transpose()?;
    eprintln!(
        "clr: study {name}: {points} design points{} → {} (checkpoint {})",
        shard.map_or(String::new(), |(i, n)| format!(", shard {i}/{n}")),
        dir.display(),
        map.checkpoint_file(dir).display()
    );
    let earlier = map
        .earlier_points(opts.resume, opts.retry_failed)
        .map_err(CliError::Input)?;
    let n = map
        .run(dir, points, shard, &earlier)
        .map_err(CliError::Simulation)?
        .points
        .len();
    eprintln!(
        "clr: study {name}: {n} points in {:.1} s; summary and figures in {}",
        start.elapsed().as_secs_f64(),
        dir.display()
    );
    Ok(())
}
