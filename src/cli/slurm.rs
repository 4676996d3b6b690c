//! `clr slurm [options] sweep|study ...`: write the sbatch scripts of a sweep or a finding map
//! run as a Slurm job array (one shard per task, each resuming what a requeued or resubmitted
//! task already finished) and of the merge job that depends on the array, show them, and submit
//! them (`--dry-run` only writes them). The scripts are the ones docs/scaling.md teaches, so a
//! user can edit and resubmit them by hand.

use std::path::{Path, PathBuf};
use std::process::Command;

use clap::{Parser, Subcommand};

use super::{sweep, CliError};

/// `clr slurm`: the scheduler's options and what to run.
#[derive(clap::Args, Debug)]
pub(crate) struct SlurmArgs {
    #[command(flatten)]
    opts: Options,
    /// What to run.
    #[command(subcommand)]
    what: SlurmWhat,
}

/// The scheduler's options of `clr slurm`, given before or after `sweep` or `study`.
#[derive(clap::Args, Debug, Clone, Default)]
struct Options {
    /// Array tasks, one shard each (default: one per point, at most 16).
    #[arg(long, global = true, value_name = "N")]
    tasks: Option<usize>,
    /// CPUs of each task: the sweep's --jobs, the finding map's threads (default: a sweep's
    /// --jobs, else 1).
    #[arg(long, global = true, value_name = "C")]
    cpus_per_task: Option<usize>,
    /// Wall-time limit of each task in Slurm's form: minutes, MM:SS, HH:MM:SS, D-HH or
    /// D-HH:MM:SS (default: the partition's).
    #[arg(long, global = true, value_name = "TIME")]
    time: Option<String>,
    /// Slurm partition (default: the cluster's).
    #[arg(long, global = true)]
    partition: Option<String>,
    /// Slurm account to charge.
    #[arg(long, global = true)]
    account: Option<String>,
    /// A further `#SBATCH` option for both scripts, e.g. `--sbatch=--qos=long` or
    /// `--sbatch=--mem-per-cpu=2G` (repeatable).
    #[arg(
        long = "sbatch",
        global = true,
        value_name = "OPTION",
        allow_hyphen_values = true
    )]
    extra: Vec<String>,
    /// Write and show the scripts, submit nothing.
    #[arg(long, global = true)]
    dry_run: bool,
}

impl Options {
    /// The options given after `sweep` (which takes every following word as its own): taken
    /// out of `tokens` and combined with those given before it (a value after `sweep` wins).
    fn with_trailing(&self, tokens: &[String]) -> Result<(Options, Vec<String>), CliError> {
        const VALUED: [&str; 6] = [
            "--tasks",
            "--cpus-per-task",
            "--time",
            "--partition",
            "--account",
            "--sbatch",
        ];
        let (mut own, mut rest) = (vec!["clr-slurm".to_string()], Vec::new());
        let mut it = tokens.iter();
        while let Some(t) = it.next() {
            let valued = VALUED
                .iter()
                .find(|o| t == *o || t.starts_with(&format!("{o}=")));
            match valued {
                Some(o) if t == o => {
                    own.push(t.clone());
                    own.extend(it.next().cloned());
                }
                Some(_) => own.push(t.clone()),
                None if t == "--dry-run" => own.push(t.clone()),
                None => rest.push(t.clone()),
            }
        }
        let after = OptionsOnly::try_parse_from(own)
            .map_err(|e| CliError::Input(format!("clr slurm: {}", e.render())))?
            .opts;
        let mut extra = self.extra.clone();
        extra.extend(after.extra);
        let merged = Options {
            tasks: after.tasks.or(self.tasks),
            cpus_per_task: after.cpus_per_task.or(self.cpus_per_task),
            time: after.time.or_else(|| self.time.clone()),
            partition: after.partition.or_else(|| self.partition.clone()),
            account: after.account.or_else(|| self.account.clone()),
            extra,
            dry_run: after.dry_run || self.dry_run,
        };
        Ok((merged, rest))
    }
}

/// The scheduler's options alone (to read those given after `sweep`).
#[derive(Parser, Debug)]
struct OptionsOnly {
    #[command(flatten)]
    opts: Options,
}

/// What `clr slurm` runs.
#[derive(Subcommand, Debug)]
enum SlurmWhat {
    /// A `clr sweep`, its arguments as for `clr sweep` but --shard (the script sets it): shards
    /// in OUT/shard-I, merged into OUT/all.
    Sweep {
        /// The arguments of `clr sweep`: target, --vary, --set, --keep, --series, --out, ...
        #[arg(
            trailing_var_arg = true,
            allow_hyphen_values = true,
            num_args = 1..,
            value_name = "SWEEP ARGS"
        )]
        args: Vec<String>,
    },
    /// A finding map of `clr study` (see `clr list`): shards in OUT/shard-I, merged into OUT/all.
    Study {
        /// Finding-map study name.
        name: String,
        /// Evaluate the first N points of the design (default: the study's).
        #[arg(long, value_name = "N")]
        points: Option<usize>,
        /// Output folder (default: clr-study/<name>).
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

/// The scripts of one submission.
#[derive(Debug, PartialEq)]
struct Scripts {
    /// Folder of the shards, the merged result (`all`) and `slurm/` (scripts and logs).
    out: PathBuf,
    /// Array tasks.
    tasks: usize,
    /// Points in all.
    points: usize,
    /// The array script.
    array: String,
    /// The merge script.
    merge: String,
}

/// Tasks by default: one per point, at most this many.
const DEFAULT_TASKS: usize = 16;

pub(crate) fn slurm_command(a: &SlurmArgs) -> Result<(), CliError> {
    let cwd = std::env::current_dir()
        .map_err(|e| CliError::Input(format!("cannot read the current folder: {e}")))?;
    let clr = std::env::current_exe()
        .map_err(|e| CliError::Input(format!("cannot locate this clr: {e}")))?;
    let (opts, scripts) = match &a.what {
        SlurmWhat::Sweep { args } => {
            let (opts, tokens) = a.opts.with_trailing(args)?;
            if tokens.iter().any(|t| t == "--help" || t == "-h") {
                // the sweep's own options, which `clr slurm sweep` forwards
                let mut cmd = <super::Cli as clap::CommandFactory>::command();
                if let Some(sweep) = cmd.find_subcommand_mut("sweep") {
                    let _ = sweep.print_help();
                }
                return Ok(());
            }
            let scripts = sweep_scripts(&opts, &tokens, &cwd, &clr)?;
            (opts, scripts)
        }
        SlurmWhat::Study { name, points, out } => {
            let scripts = study_scripts(&a.opts, name, *points, out.as_deref(), &cwd, &clr)?;
            (a.opts.clone(), scripts)
        }
    };
    let dir = scripts.out.join("slurm");
    let logs = dir.join("logs");
    std::fs::create_dir_all(&logs)
        .map_err(|e| CliError::Input(format!("cannot create {}: {e}", logs.display())))?;
    let (array, merge) = (dir.join("array.sbatch"), dir.join("merge.sbatch"));
    for (p, text) in [(&array, &scripts.array), (&merge, &scripts.merge)] {
        super::points::write_atomic(p, text)?;
    }
    println!("# {}\n{}", array.display(), scripts.array);
    println!("# {}\n{}", merge.display(), scripts.merge);
    eprintln!(
        "clr: wrote {} ({} tasks over {} points) and {}",
        array.display(),
        scripts.tasks,
        scripts.points,
        merge.display()
    );
    if opts.dry_run {
        eprintln!(
            "clr: --dry-run: nothing submitted; submit with\n  jid=$(sbatch --parsable {})\n  \
             sbatch --dependency=afterany:$jid {}",
            array.display(),
            merge.display()
        );
        return Ok(());
    }
    let jid = submit(&array, None)?;
    let mid = submit(&merge, Some(&jid))?;
    println!("array job {jid}\nmerge job {mid}");
    eprintln!(
        "clr: submitted the array job {jid} ({} tasks) and the merge job {mid}, which runs once \
         every task has ended; the merged result goes to {}.\n  follow: squeue -j {jid},{mid}; \
         logs in {}\n  a task that failed or ran out of time: sbatch --array=<its ids> {} (it \
         resumes), then sbatch {}",
        scripts.tasks,
        scripts.out.join("all").display(),
        logs.display(),
        array.display(),
        merge.display()
    );
    Ok(())
}

/// `sbatch --parsable script` (after job `after` ends, if any): the job id.
fn submit(script: &Path, after: Option<&str>) -> Result<String, CliError> {
    let mut c = Command::new("sbatch");
    c.arg("--parsable");
    if let Some(j) = after {
        c.arg(format!("--dependency=afterany:{j}"));
    }
    let o = c.arg(script).output().map_err(|e| {
        CliError::Input(format!(
            "cannot run sbatch ({e}): run clr slurm on a machine that submits Slurm jobs (a \
             login node), or submit the script written in {} yourself",
            script.display()
        ))
    })?;
    let text = String::from_utf8_lossy(&o.stdout);
    // --parsable prints `jobid` or `jobid;cluster`
    let id = text.trim().split(';').next().unwrap_or("").to_string();
    if !o.status.success() || id.is_empty() || !id.bytes().all(|b| b.is_ascii_digit()) {
        return Err(CliError::Input(format!(
            "sbatch refused {}: {}{}",
            script.display(),
            String::from_utf8_lossy(&o.stderr).trim(),
            text.trim()
        )));
    }
    Ok(id)
}

/// The scripts of a sweep: its arguments checked as `clr sweep` checks them, every point resolved.
fn sweep_scripts(
    a: &Options,
    tokens: &[String],
    cwd: &Path,
    clr: &Path,
) -> Result<Scripts, CliError> {
    let argv = ["clr", "sweep"].into_iter().map(String::from);
    let cli = super::Cli::try_parse_from(argv.chain(tokens.iter().cloned()))
        .map_err(|e| CliError::Input(format!("clr slurm sweep: {}", e.render())))?;
    let super::Command::Sweep {
        args,
        vary,
        jobs,
        shard,
        out,
        ..
    } = cli.command
    else {
        return Err(CliError::Input("clr slurm sweep: not a sweep".into()));
    };
    if shard.is_some() {
        return Err(CliError::Input(
            "clr slurm sweep sets --shard itself (one shard per array task): remove --shard".into(),
        ));
    }
    let total = sweep::plan(&args, &vary, None)?.total;
    let cpus = cpus(a.cpus_per_task, jobs)?;
    let tasks = tasks(a.tasks, total, "a sweep")?;
    let out = cwd.join(out);
    let kept = forwarded(tokens);
    let run = format!(
        "{} sweep {} \\\n    --jobs \"$SLURM_CPUS_PER_TASK\" --shard \"$SLURM_ARRAY_TASK_ID/$N\" \
         --resume \\\n    --out \"$OUT/shard-$SLURM_ARRAY_TASK_ID\"",
        quote(&clr.display().to_string()),
        kept.iter().map(|t| quote(t)).collect::<Vec<_>>().join(" "),
    );
    let head = Head::new(a, cwd, cpus)?;
    let array = head.array("clr-sweep", tasks, &out, &run);
    let merge = head.merge(
        "clr-sweep-merge",
        &out,
        &format!(
            "{} merge \"$OUT\"/shard-{{0..{}}} --out \"$OUT/all\"",
            quote(&clr.display().to_string()),
            tasks - 1
        ),
    );
    Ok(Scripts {
        out,
        tasks,
        points: total,
        array,
        merge,
    })
}

/// The scripts of a finding map.
fn study_scripts(
    a: &Options,
    name: &str,
    points: Option<usize>,
    out: Option<&Path>,
    cwd: &Path,
    clr: &Path,
) -> Result<Scripts, CliError> {
    let study = clr_models::studies::find(name).map_err(CliError::Input)?;
    let Some(map) = study.map else {
        return Err(CliError::Input(format!(
            "`{name}` is not a finding map: it runs as one job (`clr study {name}`); clr slurm \
             study shards the finding maps of `clr list`"
        )));
    };
    let points = points.unwrap_or(map.default_points);
    map.design(points).map_err(CliError::Input)?;
    let cpus = cpus(a.cpus_per_task, None)?;
    let tasks = tasks(a.tasks, points, "a map design")?;
    let out = cwd.join(out.map_or_else(|| PathBuf::from("clr-study").join(name), PathBuf::from));
    let clr = quote(&clr.display().to_string());
    // a requeued or resubmitted task takes the points of its checkpoint (or finished result)
    let checkpoint = file_name(&map.checkpoint_file(Path::new("")));
    let result = file_name(&map.result_file(Path::new("")));
    let run = format!(
        "DIR=\"$OUT/shard-$SLURM_ARRAY_TASK_ID\"\nRESUME=()\n\
         if [ -e \"$DIR/{checkpoint}\" ] || [ -e \"$DIR/{result}\" ]; then RESUME=(--resume \
         \"$DIR\"); fi\n\
         # the map's threads: the task's CPUs, not the node's\n\
         export RAYON_NUM_THREADS=\"$SLURM_CPUS_PER_TASK\"\n\
         {clr} study {name} --points {points} --shard \"$SLURM_ARRAY_TASK_ID/$N\" \
         --out \"$DIR\" \"${{RESUME[@]}}\""
    );
    let head = Head::new(a, cwd, cpus)?;
    let array = head.array(&format!("clr-{name}"), tasks, &out, &run);
    let merge = head.merge(
        &format!("clr-{name}-merge"),
        &out,
        &format!(
            "{clr} study {name} --merge \"$OUT\"/shard-{{0..{}}} --out \"$OUT/all\"",
            tasks - 1
        ),
    );
    Ok(Scripts {
        out,
        tasks,
        points,
        array,
        merge,
    })
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
}

/// The CPUs per task from `--cpus-per-task` and the sweep's `--jobs`.
fn cpus(cpus: Option<usize>, jobs: Option<usize>) -> Result<usize, CliError> {
    match (cpus, jobs) {
        (Some(0), _) | (None, Some(0)) => Err(CliError::Input(
            "--cpus-per-task: at least 1 CPU per task".into(),
        )),
        (Some(c), Some(j)) if c != j => Err(CliError::Input(format!(
            "--cpus-per-task {c} and the sweep's --jobs {j} differ: each task runs the sweep \
             with --jobs equal to its CPUs; give one of the two"
        ))),
        (c, j) => Ok(c.or(j).unwrap_or(1)),
    }
}

/// The array's tasks: `asked`, or one per point up to [`DEFAULT_TASKS`].
fn tasks(asked: Option<usize>, points: usize, what: &str) -> Result<usize, CliError> {
    match asked {
        Some(0) => Err(CliError::Input("--tasks: at least 1".into())),
        Some(n) if n > points => Err(CliError::Input(format!(
            "--tasks {n} for {what} of {points} point{}: a task would have no point; give at \
             most {points}",
            if points == 1 { "" } else { "s" }
        ))),
        Some(n) => Ok(n),
        None => Ok(points.clamp(1, DEFAULT_TASKS)),
    }
}

/// The sweep's tokens as forwarded into the script: without --out, --jobs and --resume, which
/// the script sets per task.
fn forwarded(tokens: &[String]) -> Vec<String> {
    let mut kept = Vec::new();
    let mut it = tokens.iter();
    while let Some(t) = it.next() {
        match t.as_str() {
            "--out" | "--jobs" => {
                it.next();
            }
            "--resume" => {}
            _ if t.starts_with("--out=") || t.starts_with("--jobs=") => {}
            _ => kept.push(t.clone()),
        }
    }
    kept
}

/// A wall-time limit in one of Slurm's forms (minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM,
/// D-HH:MM:SS, or UNLIMITED), as given; refused otherwise (a `2h` would be refused by sbatch
/// only after the scripts are written).
fn slurm_time(t: &str) -> Result<&str, CliError> {
    let numbers = |s: &str, most: usize| {
        let parts: Vec<&str> = s.split(':').collect();
        parts.len() <= most
            && parts
                .iter()
                .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
    };
    let ok = match t.split_once('-') {
        _ if t.eq_ignore_ascii_case("unlimited") || t.eq_ignore_ascii_case("infinite") => true,
        Some((d, rest)) => numbers(d, 1) && numbers(rest, 3),
        None => numbers(t, 3),
    };
    if ok {
        Ok(t)
    } else {
        Err(CliError::Input(format!(
            "--time {t}: not a Slurm time; write minutes (90), HH:MM:SS (02:00:00) or \
             D-HH:MM:SS (1-12:00:00)"
        )))
    }
}

/// `text` as one shell word: as is when it is made of safe characters, else single-quoted.
fn quote(text: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "_-./=,:+@%".contains(c);
    if !text.is_empty() && text.chars().all(safe) {
        text.to_string()
    } else {
        format!("'{}'", text.replace('\'', "'\\''"))
    }
}

/// The `#SBATCH` lines both scripts share.
struct Head {
    lines: Vec<String>,
    cpus: usize,
}

impl Head {
    fn new(a: &Options, cwd: &Path, cpus: usize) -> Result<Self, CliError> {
        // the model file and other relative paths are read from where clr slurm ran
        let mut lines = vec![format!("--chdir={}", quote(&cwd.display().to_string()))];
        if let Some(t) = &a.time {
            lines.push(format!("--time={}", slurm_time(t)?));
        }
        if let Some(p) = &a.partition {
            lines.push(format!("--partition={}", quote(p)));
        }
        if let Some(acc) = &a.account {
            lines.push(format!("--account={}", quote(acc)));
        }
        for e in &a.extra {
            if !e.starts_with('-') || e.contains('\n') {
                return Err(CliError::Input(format!(
                    "--sbatch {e:?}: expected one sbatch option such as --qos=long or \
                     --mem-per-cpu=2G"
                )));
            }
            lines.push(e.clone());
        }
        Ok(Self { lines, cpus })
    }

    fn preamble(&self, name: &str, log: &str, extra: &[String]) -> String {
        let mut s = String::from("#!/bin/bash\n");
        let mut opts = vec![format!("--job-name={name}")];
        opts.extend(extra.iter().cloned());
        opts.push(format!("--output={log}"));
        opts.extend(self.lines.iter().cloned());
        for o in opts {
            s.push_str(&format!("#SBATCH {o}\n"));
        }
        s
    }

    /// The array script: task I runs `run` on shard I of N; requeued (preempted, node failure)
    /// it starts again and resumes.
    fn array(&self, name: &str, tasks: usize, out: &Path, run: &str) -> String {
        let log = quote(&out.join("slurm/logs/%x-%A_%a.out").display().to_string());
        let extra = vec![
            format!("--array=0-{}", tasks - 1),
            format!("--cpus-per-task={}", self.cpus),
            "--requeue".into(),
            "--open-mode=append".into(),
        ];
        let mut s = self.preamble(name, &log, &extra);
        s.push_str(&format!(
            "# Written by clr {} (clr slurm): shard $SLURM_ARRAY_TASK_ID of {tasks}. A requeued or\n\
             # resubmitted task resumes: the points it finished are kept, not run again.\n\
             set -euo pipefail\nN={tasks}\nOUT={}\n{run}\n",
            clr_models::provenance::CLR_VERSION,
            quote(&out.display().to_string()),
        ));
        s
    }

    /// The merge script, submitted with `--dependency=afterany:<array job>`.
    fn merge(&self, name: &str, out: &Path, run: &str) -> String {
        let log = quote(&out.join("slurm/logs/%x-%j.out").display().to_string());
        let mut s = self.preamble(name, &log, &["--cpus-per-task=1".to_string()]);
        s.push_str(&format!(
            "# Written by clr {} (clr slurm): joins the shards once every array task has ended\n\
             # (afterany); it names the missing points of a shard that failed or ran out of time.\n\
             set -euo pipefail\nOUT={}\n{run}\n",
            clr_models::provenance::CLR_VERSION,
            quote(&out.display().to_string()),
        ));
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(argv: &[&str]) -> SlurmArgs {
        let all = ["clr", "slurm"].iter().chain(argv).copied();
        match super::super::Cli::try_parse_from(all).unwrap().command {
            super::super::Command::Slurm(a) => a,
            _ => unreachable!("clr slurm parses as Slurm"),
        }
    }

    fn sweep(argv: &[&str]) -> Result<Scripts, CliError> {
        let a = parse(argv);
        let SlurmWhat::Sweep { args } = &a.what else {
            unreachable!("a sweep")
        };
        let (opts, tokens) = a.opts.with_trailing(args)?;
        sweep_scripts(
            &opts,
            &tokens,
            Path::new("/work dir"),
            Path::new("/opt/clr/bin/clr"),
        )
    }

    /// The array script shards the sweep over the tasks with --resume, keeps every sweep option
    /// but those the script sets (--out, --jobs), and quotes what the shell would split; options
    /// of clr slurm are taken before and after `sweep`.
    #[test]
    fn sweep_script_shards_resumes_and_forwards_the_sweep() {
        let s = sweep(&[
            "--time",
            "1:00:00",
            "sweep",
            "slider_crank",
            "--vary",
            "restitution=0.5,0.7,0.9",
            "--set",
            "crank_mass=0.5",
            "--jobs",
            "2",
            "--out",
            "res",
            "--keep",
            "metrics",
            "--tasks",
            "3",
            "--sbatch=--qos=long",
        ])
        .unwrap();
        assert_eq!((s.tasks, s.points), (3, 3));
        assert_eq!(s.out, Path::new("/work dir/res"));
        for line in [
            "#SBATCH --array=0-2\n",
            "#SBATCH --cpus-per-task=2\n",
            "#SBATCH --requeue\n",
            "#SBATCH --time=1:00:00\n",
            "#SBATCH --qos=long\n",
            "#SBATCH --chdir='/work dir'\n",
            "#SBATCH --output='/work dir/res/slurm/logs/%x-%A_%a.out'\n",
            "N=3\nOUT='/work dir/res'\n",
            "/opt/clr/bin/clr sweep slider_crank --vary restitution=0.5,0.7,0.9 --set \
             crank_mass=0.5 --keep metrics \\\n    --jobs \"$SLURM_CPUS_PER_TASK\" --shard \
             \"$SLURM_ARRAY_TASK_ID/$N\" --resume \\\n    --out \"$OUT/shard-$SLURM_ARRAY_TASK_ID\"\n",
        ] {
            assert!(s.array.contains(line), "no {line:?} in\n{}", s.array);
        }
        assert!(s
            .array
            .starts_with("#!/bin/bash\n#SBATCH --job-name=clr-sweep\n"));
        assert!(s
            .merge
            .contains("clr merge \"$OUT\"/shard-{0..2} --out \"$OUT/all\"\n"));
        assert!(!s.merge.contains("--array"), "{}", s.merge);
    }

    /// Mistakes are refused before anything is written, each saying what to change.
    #[test]
    fn mistakes_are_refused_with_what_to_change() {
        let err = |argv: &[&str]| match sweep(argv) {
            Err(CliError::Input(m)) => m,
            other => panic!("{argv:?}: {other:?}"),
        };
        let base = ["sweep", "slider_crank", "--vary", "restitution=0.5,0.7"];
        let with = |extra: &[&'static str]| {
            let mut v = base.to_vec();
            v.extend_from_slice(extra);
            err(&v)
        };
        assert!(with(&["--tasks", "3"]).contains("give at most 2"));
        assert!(with(&["--tasks", "0"]).contains("at least 1"));
        assert!(with(&["--time", "2h"]).contains("HH:MM:SS"));
        assert!(with(&["--shard", "0/2"]).contains("remove --shard"));
        assert!(with(&["--jobs", "4", "--cpus-per-task", "2"]).contains("give one of the two"));
        assert!(with(&["--sbatch", "qos=long"]).contains("one sbatch option"));
        assert!(err(&["sweep", "slider_crank", "--vary", "restitutio=0.5"]).contains("restitution"));
        assert!(err(&["sweep", "slider_crank"]).contains("--vary"));
    }

    /// A finding map: the task resumes from its checkpoint when it has one, and its threads are
    /// the task's CPUs; a study that is not a map is refused.
    #[test]
    fn study_script_resumes_from_the_checkpoint() {
        let opts = Options {
            tasks: Some(2),
            cpus_per_task: Some(4),
            ..Default::default()
        };
        let (cwd, clr) = (Path::new("/w"), Path::new("/bin/clr"));
        let s = study_scripts(&opts, "dual_guide_findings_map", Some(4), None, cwd, clr).unwrap();
        assert_eq!(s.out, Path::new("/w/clr-study/dual_guide_findings_map"));
        for line in [
            "if [ -e \"$DIR/dual_guide_findings_map_points.jsonl\" ] || [ -e \
             \"$DIR/dual_guide_findings_map_result.json\" ]; then RESUME=(--resume \"$DIR\"); fi\n",
            "export RAYON_NUM_THREADS=\"$SLURM_CPUS_PER_TASK\"\n",
            "/bin/clr study dual_guide_findings_map --points 4 --shard \
             \"$SLURM_ARRAY_TASK_ID/$N\" --out \"$DIR\" \"${RESUME[@]}\"\n",
        ] {
            assert!(s.array.contains(line), "no {line:?} in\n{}", s.array);
        }
        assert!(s.merge.contains(
            "/bin/clr study dual_guide_findings_map --merge \"$OUT\"/shard-{0..1} --out \
             \"$OUT/all\"\n"
        ));
        let e = study_scripts(&opts, "flap_clearance", None, None, cwd, clr);
        assert!(matches!(e, Err(CliError::Input(m)) if m.contains("not a finding map")));
    }

    #[test]
    fn quoting_and_times() {
        assert_eq!(quote("a=b,c"), "a=b,c");
        assert_eq!(quote("two words"), "'two words'");
        assert_eq!(quote("it's"), "'it'\\''s'");
        assert_eq!(quote(""), "''");
        for t in [
            "90",
            "30:00",
            "02:00:00",
            "1-12",
            "1-12:00",
            "1-12:00:00",
            "UNLIMITED",
        ] {
            assert!(slurm_time(t).is_ok(), "{t}");
        }
        for t in ["2h", "1:2:3:4", "-1", "1-", ":30", "1.5"] {
            assert!(slurm_time(t).is_err(), "{t}");
        }
    }
}
