//! `cargo xtask cluster-check`: bring up a single-node Slurm cluster on this machine (Debian's
//! `slurmctld`, `slurmd`, `slurm-client` and `munge`, installed with apt-get when missing), run
//! clr's cluster workflows on it and tear it down, leaving no daemon behind (issue 34):
//!
//! - the docs/scaling.md sweep as a job array with a dependent merge job: the merged sweep.csv
//!   equals a local `clr sweep` of the same points (wall times aside);
//! - a small finding map (4 points of `dual_guide_findings_map`) sharded the same way and merged:
//!   its points equal a local run's;
//! - a task killed mid-run, once by `scontrol requeue` (Slurm kills and requeues it, eligible
//!   again 2 min later unless, as here, `scontrol update StartTime=now`) and once by `scancel
//!   --signal=KILL` and resubmitted: it resumes (`--resume`) without redoing finished points,
//!   and the final sweep equals the local one;
//! - `clr_sim.sweep(..., executor=submitit.AutoExecutor)` (xtask/cluster/submitit_sweep.py)
//!   equals the threaded sweep bit for bit.
//!
//! The arrays and merge jobs are the scripts `clr slurm` writes and submits.
//!
//! Daemons are started by hand (there is no systemd here), with configuration, munge key, state
//! and logs under one temporary folder; `proctrack/linuxproc` and `task/none` avoid cgroups,
//! `batch_sched_delay=0,sched_min_interval=0` shortens array waves to about a second, there is
//! no accounting (`sacct` is off), and jobs are waited for by polling `squeue` (`sbatch --wait`
//! polls slowly).

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::{Duration, Instant};

const HELP: &str = "cargo xtask cluster-check: bring up a single-node Slurm cluster (apt-get \
install slurmctld slurmd slurm-client munge if missing; needs root), run a sweep as a job \
array with a dependent merge (clr slurm), a sharded finding map, a killed-and-requeued task and \
a submitit sweep from Python ($CLR_PYTHON or target/ci-pyenv), compare with local runs, tear the \
cluster down";

/// `cargo xtask cluster-check`.
pub fn run(args: &[String]) -> ExitCode {
    crate::command_without_arguments("cluster-check", HELP, args, || {
        let start = Instant::now();
        crate::system::apt_install(
            "cluster-check",
            &["slurmctld", "slurmd", "slurm-client", "munge"],
            &["slurmctld", "slurmd", "sbatch", "munged"],
        )?;
        let clr = crate::system::build_clr()?;
        let python = python();
        let mut cluster = Cluster::start()?;
        eprintln!(
            "cluster-check: cluster up in {:.1} s ({})",
            cluster.up_s, cluster.node
        );
        let checks = Checks {
            clr: &clr,
            python: python.as_deref(),
            cluster: &cluster,
            work: cluster.dir.join("work"),
        };
        let result = checks.all();
        let survivors = cluster.stop();
        result?;
        if !survivors.is_empty() {
            return Err(format!(
                "daemons outlived the teardown: {}",
                survivors.join(", ")
            ));
        }
        eprintln!(
            "cluster-check: all checks passed in {:.1} s",
            start.elapsed().as_secs_f64()
        );
        Ok(())
    })
}

/// Call `probe` every 20 ms until it returns `Ok`, at most `limit`; at the deadline, what the
/// last call returned as `Err` (what it saw). 20 ms: the kill check must act while the short
/// sweep of the killed task is still running.
fn poll(limit: Duration, mut probe: impl FnMut() -> Result<(), String>) -> Result<(), String> {
    let deadline = Instant::now() + limit;
    loop {
        match probe() {
            Ok(()) => return Ok(()),
            Err(seen) if Instant::now() > deadline => return Err(seen),
            Err(_) => std::thread::sleep(Duration::from_millis(20)),
        }
    }
}

/// The Python of the submitit check: `$CLR_PYTHON`, else .ci/run's `target/ci-pyenv`, if it
/// imports clr_sim and submitit.
fn python() -> Option<PathBuf> {
    let candidate = std::env::var_os("CLR_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| crate::target_dir().join("ci-pyenv/bin/python"));
    let ok = Command::new(&candidate)
        .args(["-c", "import clr_sim, submitit"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    ok.then_some(candidate)
}

/// A running single-node cluster; dropping it stops every daemon and job and removes its
/// folder.
struct Cluster {
    dir: PathBuf,
    conf: PathBuf,
    node: String,
    up_s: f64,
}

impl Cluster {
    fn start() -> Result<Self, String> {
        let t0 = Instant::now();
        let dir = std::env::temp_dir().join(format!("clr-cluster-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        for sub in ["etc", "state", "spool", "log", "run", "munge", "work"] {
            std::fs::create_dir_all(dir.join(sub))
                .map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        let mut c = Cluster {
            conf: dir.join("etc/slurm.conf"),
            dir,
            node: String::new(),
            up_s: 0.0,
        };
        // from here on, a failure still tears down what started
        c.munge()?;
        c.configure()?;
        c.daemons()?;
        c.up_s = t0.elapsed().as_secs_f64();
        Ok(c)
    }

    fn path(&self, p: &str) -> String {
        self.dir.join(p).display().to_string()
    }

    /// munged with its own key and socket; the socket's folder must be 0755 for clients.
    fn munge(&self) -> Result<(), String> {
        use std::os::unix::fs::PermissionsExt;
        let key: Vec<u8> = (0..1024u32)
            .map(|k| (k.wrapping_mul(2_654_435_761) >> 13) as u8 ^ std::process::id() as u8)
            .collect();
        let key_file = self.dir.join("munge/munge.key");
        std::fs::write(&key_file, key).map_err(|e| e.to_string())?;
        let perm =
            |p: &Path, mode| std::fs::set_permissions(p, std::fs::Permissions::from_mode(mode));
        perm(&key_file, 0o400).map_err(|e| e.to_string())?;
        perm(&self.dir.join("munge"), 0o755).map_err(|e| e.to_string())?;
        let (key, sock, log, pid, seed) = (
            self.path("munge/munge.key"),
            self.path("munge/munge.socket.2"),
            self.path("log/munged.log"),
            self.path("run/munged.pid"),
            self.path("munge/munged.seed"),
        );
        run_ok(Command::new("munged").args([
            "--force",
            &format!("--key-file={key}"),
            &format!("--socket={sock}"),
            &format!("--log-file={log}"),
            &format!("--pid-file={pid}"),
            &format!("--seed-file={seed}"),
        ]))
    }

    /// slurm.conf with the node line of `slurmd -C`, at 127.0.0.1 (the host name may not
    /// resolve on a CI machine).
    fn configure(&mut self) -> Result<(), String> {
        let out = run_out(Command::new("slurmd").arg("-C"))?;
        let line = out.lines().next().unwrap_or("").to_string();
        let name = line
            .strip_prefix("NodeName=")
            .and_then(|r| r.split_whitespace().next())
            .ok_or_else(|| format!("slurmd -C printed no node line: {out}"))?
            .to_string();
        self.node = line.clone();
        let d = |p: &str| self.path(p);
        let conf = format!(
            "ClusterName=clrcheck\nSlurmctldHost={name}(127.0.0.1)\nAuthType=auth/munge\n\
             AuthInfo=socket={sock}\nCredType=cred/munge\nSlurmUser=root\nSlurmdUser=root\n\
             SlurmctldPort=16817\nSlurmdPort=16818\nStateSaveLocation={state}\n\
             SlurmdSpoolDir={spool}\nSlurmctldPidFile={cpid}\nSlurmdPidFile={dpid}\n\
             SlurmctldLogFile={clog}\nSlurmdLogFile={dlog}\nProctrackType=proctrack/linuxproc\n\
             TaskPlugin=task/none\nJobAcctGatherType=jobacct_gather/none\n\
             AccountingStorageType=accounting_storage/none\nSchedulerType=sched/backfill\n\
             SelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n\
             SchedulerParameters=batch_sched_delay=0,sched_min_interval=0\nReturnToService=2\n\
             MpiDefault=none\n{line} NodeAddr=127.0.0.1 State=UNKNOWN\n\
             PartitionName=main Nodes={name} Default=YES MaxTime=INFINITE State=UP\n",
            sock = d("munge/munge.socket.2"),
            state = d("state"),
            spool = d("spool"),
            cpid = d("run/slurmctld.pid"),
            dpid = d("run/slurmd.pid"),
            clog = d("log/slurmctld.log"),
            dlog = d("log/slurmd.log"),
        );
        std::fs::write(&self.conf, conf).map_err(|e| e.to_string())
    }

    fn cmd(&self, program: &str) -> Command {
        let mut c = Command::new(program);
        c.env("SLURM_CONF", &self.conf);
        c
    }

    /// slurmctld and slurmd, then wait until the node has registered and is idle (right after
    /// a start the node can read `idle` before slurmd has registered: its `slurmd` version
    /// shows once it has).
    fn daemons(&self) -> Result<(), String> {
        run_ok(self.cmd("slurmctld").arg("-i"))?;
        run_ok(&mut self.cmd("slurmd"))?;
        poll(Duration::from_secs(30), || {
            let node = run_out(self.cmd("scontrol").args(["show", "node"])).unwrap_or_default();
            let registered = node.contains("Version=") && !node.contains("Version=(null)");
            (registered && node.contains("State=IDLE"))
                .then_some(())
                .ok_or(node)
        })
        .map_err(|node| format!("the node did not come up in 30 s:\n{node}{}", self.logs()))
    }

    fn logs(&self) -> String {
        let tail = |p: &str| {
            let t = std::fs::read_to_string(self.dir.join(p)).unwrap_or_default();
            let lines: Vec<&str> = t.lines().collect();
            lines[lines.len().saturating_sub(15)..].join("\n")
        };
        format!(
            "\n--- slurmctld.log\n{}\n--- slurmd.log\n{}",
            tail("log/slurmctld.log"),
            tail("log/slurmd.log")
        )
    }

    /// Submit the script `file`, return the job id.
    fn sbatch(&self, file: &Path) -> Result<String, String> {
        let out = run_out(self.cmd("sbatch").arg("--parsable").arg(file))?;
        Ok(out.trim().split(';').next().unwrap_or("").to_string())
    }

    /// Wait until job `id` is pending again (a requeued job is first completing).
    fn until_pending(&self, id: &str) -> Result<(), String> {
        let pending = |q: &str| q.trim() == "PENDING";
        self.squeue_until(
            &[id],
            Duration::from_secs(30),
            &pending,
            "not pending again",
        )
    }

    /// Wait until no job of `ids` is in the queue, at most `limit`.
    fn wait(&self, ids: &[&str], limit: Duration) -> Result<(), String> {
        let gone = |q: &str| q.trim().is_empty();
        self.squeue_until(ids, limit, &gone, "still queued")
    }

    /// Poll `squeue` (the states of `ids`) until `done` holds for its output, at most `limit`
    /// (`sbatch --wait` polls slowly); `what` says what the jobs are at the deadline.
    fn squeue_until(
        &self,
        ids: &[&str],
        limit: Duration,
        done: &dyn Fn(&str) -> bool,
        what: &str,
    ) -> Result<(), String> {
        let jobs = ids.join(",");
        poll(limit, || {
            let q = run_out(self.cmd("squeue").args(["-h", "-o", "%T", "-j", &jobs]))
                .unwrap_or_default();
            done(&q).then_some(()).ok_or(q)
        })
        .map_err(|q| format!("jobs {jobs} {what} after {limit:?}: {q}{}", self.logs()))
    }
}

impl Cluster {
    /// Cancel every job, stop the daemons (SIGTERM, SIGKILL after 5 s) and remove the folder;
    /// the daemons still alive after that, in words.
    fn stop(&mut self) -> Vec<String> {
        let _ = self.cmd("scancel").args(["--full", "-u", "root"]).status();
        let mut survivors = Vec::new();
        for daemon in ["slurmd", "slurmctld", "munged"] {
            let file = self.dir.join(format!("run/{daemon}.pid"));
            if let Some(pid) = stop(&file) {
                survivors.push(format!("{daemon} (pid {pid})"));
            }
        }
        let _ = std::fs::remove_dir_all(&self.dir);
        survivors
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        if self.dir.exists() {
            self.stop();
        }
    }
}

/// SIGTERM the daemon of pid file `p`, SIGKILL it after 5 s; its pid if it is still alive.
fn stop(p: &Path) -> Option<i32> {
    let pid = std::fs::read_to_string(p)
        .ok()?
        .trim()
        .parse::<i32>()
        .ok()?;
    // a zombie (exited, not reaped: PID 1 of a container may not reap) counts as stopped
    let alive = || {
        std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok_and(|s| {
            s.rsplit(')')
                .next()
                .is_some_and(|r| !r.trim_start().starts_with('Z'))
        })
    };
    let _ = Command::new("kill").arg(pid.to_string()).status();
    let deadline = Instant::now() + Duration::from_secs(5);
    while alive() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(50));
    }
    if alive() {
        let _ = Command::new("kill").args(["-9", &pid.to_string()]).status();
        std::thread::sleep(Duration::from_millis(200));
    }
    alive().then_some(pid)
}

fn run_ok(c: &mut Command) -> Result<(), String> {
    run_out(c).map(|_| ())
}

fn run_out(c: &mut Command) -> Result<String, String> {
    let o = c
        .stdin(Stdio::null())
        .output()
        .map_err(|e| format!("{:?}: {e}", c.get_program()))?;
    if o.status.success() {
        Ok(String::from_utf8_lossy(&o.stdout).into_owned())
    } else {
        Err(format!(
            "{:?} {:?}: {}{}",
            c.get_program(),
            c.get_args().collect::<Vec<_>>(),
            String::from_utf8_lossy(&o.stderr),
            String::from_utf8_lossy(&o.stdout)
        ))
    }
}

/// The workflows run on the cluster.
struct Checks<'a> {
    clr: &'a Path,
    /// A Python that imports clr_sim and submitit.
    python: Option<&'a Path>,
    cluster: &'a Cluster,
    work: PathBuf,
}

/// The docs/scaling.md sweep, shortened: 4 × 2 points of 0.01 s.
const SWEEP: &str = "slider_crank --t-end 0.01 --vary crank_speed_rpm=2000,3000,4000,5000 \
--vary restitution=0.5,0.9 --no-figures --quiet";

impl Checks<'_> {
    fn all(&self) -> Result<(), String> {
        let local = self.work.join("local");
        let t = Instant::now();
        run_ok(
            Command::new(self.clr)
                .args(["sweep"])
                .args(SWEEP.split(' '))
                .arg("--out")
                .arg(&local),
        )?;
        eprintln!(
            "cluster-check: local sweep {:.1} s",
            t.elapsed().as_secs_f64()
        );
        self.array_and_merge(&local)?;
        self.killed_and_resumed(&local)?;
        self.finding_map()?;
        self.submitit()
    }

    /// `clr_sim.sweep(..., executor=submitit.AutoExecutor)` on this cluster equals the threaded
    /// sweep, bit for bit (xtask/cluster/submitit_sweep.py).
    fn submitit(&self) -> Result<(), String> {
        let t = Instant::now();
        let python = self.python.ok_or_else(|| {
            "no Python with clr_sim and submitit for the submitit check: set CLR_PYTHON, or \
             create target/ci-pyenv as .ci/run does (pip install ./python submitit)"
                .to_string()
        })?;
        let script = crate::workspace_root().join("xtask/cluster/submitit_sweep.py");
        let folder = self.work.join("submitit");
        let printed = run_out(
            self.cluster
                .cmd(&python.display().to_string())
                .arg(&script)
                .arg(&folder)
                .current_dir(&self.work),
        )?;
        eprintln!(
            "cluster-check: submitit: {} ({:.1} s)",
            printed.trim(),
            t.elapsed().as_secs_f64()
        );
        Ok(())
    }

    /// The sweep as a 4-task array with a dependent merge job, both written and submitted by
    /// `clr slurm sweep`.
    fn array_and_merge(&self, local: &Path) -> Result<(), String> {
        let t = Instant::now();
        let out = self.work.join("array");
        let (jid, mid) = self.clr_slurm(&["--tasks", "4", "sweep"], SWEEP, &out)?;
        self.cluster.wait(&[&jid, &mid], Duration::from_secs(120))?;
        same_sweep(local, &out.join("all"))?;
        eprintln!(
            "cluster-check: clr slurm sweep: job array of 4 shards + dependent merge = local \
             sweep ({:.1} s)",
            t.elapsed().as_secs_f64()
        );
        Ok(())
    }

    /// Run `clr slurm <slurm> <args> --out <out>` in the work folder; what it printed.
    fn run_clr_slurm(&self, slurm: &[&str], args: &str, out: &Path) -> Result<String, String> {
        run_out(
            self.cluster
                .cmd(&self.clr.display().to_string())
                .arg("slurm")
                .args(slurm)
                .args(args.split(' '))
                .arg("--out")
                .arg(out)
                .current_dir(&self.work),
        )
    }

    /// Run `clr slurm <slurm> <args> --out <out>` (which writes and submits the array and the
    /// merge job); their job ids.
    fn clr_slurm(
        &self,
        slurm: &[&str],
        args: &str,
        out: &Path,
    ) -> Result<(String, String), String> {
        let printed = self.run_clr_slurm(slurm, args, out)?;
        let id = |what: &str| {
            (printed.lines())
                .find_map(|l| l.strip_prefix(what))
                .map(|j| j.trim().to_string())
                .ok_or_else(|| format!("clr slurm printed no `{what}<id>` line:\n{printed}"))
        };
        Ok((id("array job ")?, id("merge job ")?))
    }

    /// One shard task killed twice mid-run (requeued by Slurm, then SIGKILLed and resubmitted):
    /// it resumes without redoing the finished points.
    fn killed_and_resumed(&self, local: &Path) -> Result<(), String> {
        let t = Instant::now();
        let out = self.work.join("killed");
        // the array script of `clr slurm --tasks 1 --dry-run`, submitted here; not --quiet: the
        // log says what --resume kept
        let slurm = ["--tasks", "1", "--dry-run", "sweep"];
        self.run_clr_slurm(&slurm, &SWEEP.replace(" --quiet", ""), &out)?;
        let script = out.join("slurm/array.sbatch");
        let sweep = out.join("shard-0");
        // kill `jid` once `n` point folders are finished; the bytes of the first
        let kill_after = |jid: &str, n: usize, how: &[&str]| -> Result<Vec<u8>, String> {
            poll(Duration::from_secs(60), || {
                let done = finished(&sweep);
                (done >= n).then_some(()).ok_or(format!("{done}"))
            })
            .map_err(|done| {
                format!(
                    "{done} of {n} points finished in 60 s{}",
                    self.cluster.logs()
                )
            })?;
            run_ok(self.cluster.cmd(how[0]).args(&how[1..]).arg(jid))?;
            std::fs::read(sweep.join("point-00000/point.json")).map_err(|e| e.to_string())
        };
        let jid = self.cluster.sbatch(&script)?;
        let first = kill_after(&jid, 1, &["scontrol", "requeue"])?;
        // requeued: Slurm makes it eligible 2 min later; the administrator's `StartTime=now`
        // lets it run again at once
        self.cluster.until_pending(&jid)?;
        run_ok(self.cluster.cmd("scontrol").args([
            "update",
            &format!("jobid={jid}"),
            "StartTime=now",
        ]))?;
        self.cluster.wait(&[&jid], Duration::from_secs(120))?;
        let log = std::fs::read_to_string(out.join(format!("slurm/logs/clr-sweep-{jid}_0.out")))
            .unwrap_or_default();
        if !log.contains("finished already") {
            return Err(format!("the requeued task did not resume:\n{log}"));
        }
        let kept =
            std::fs::read(sweep.join("point-00000/point.json")).map_err(|e| e.to_string())?;
        if kept != first {
            return Err("point 0 was run again after the requeue".into());
        }
        same_sweep(local, &sweep)?;
        // again from scratch, killed by SIGKILL and resubmitted by hand
        std::fs::remove_dir_all(&sweep).map_err(|e| e.to_string())?;
        let jid = self.cluster.sbatch(&script)?;
        let first2 = kill_after(&jid, 2, &["scancel", "--signal=KILL", "--full"])?;
        self.cluster.wait(&[&jid], Duration::from_secs(60))?;
        let again = self.cluster.sbatch(&script)?;
        self.cluster.wait(&[&again], Duration::from_secs(120))?;
        let kept =
            std::fs::read(sweep.join("point-00000/point.json")).map_err(|e| e.to_string())?;
        if kept != first2 {
            return Err("point 0 was run again after the SIGKILL".into());
        }
        same_sweep(local, &sweep)?;
        eprintln!(
            "cluster-check: requeued and SIGKILLed tasks resumed, finished points kept ({:.1} s)",
            t.elapsed().as_secs_f64()
        );
        Ok(())
    }

    /// 4 points of the dual guide's finding map in 2 shards, merged, against a local run.
    fn finding_map(&self) -> Result<(), String> {
        let t = Instant::now();
        let out = self.work.join("map");
        let name = "dual_guide_findings_map";
        let local = out.join("local");
        run_ok(
            Command::new(self.clr)
                .args(["study", name, "--points", "4", "--out"])
                .arg(&local),
        )?;
        let (jid, mid) = self.clr_slurm(
            &["--tasks", "2", "study"],
            &format!("{name} --points 4"),
            &out,
        )?;
        self.cluster.wait(&[&jid, &mid], Duration::from_secs(300))?;
        let csv = format!("{name}.csv");
        let (a, b) = (
            std::fs::read_to_string(local.join(&csv)).map_err(|e| format!("local {csv}: {e}"))?,
            std::fs::read_to_string(out.join("all").join(&csv)).map_err(|e| {
                let log = std::fs::read_to_string(
                    out.join(format!("slurm/logs/clr-{name}-merge-{mid}.out")),
                )
                .unwrap_or_default();
                format!("merged {csv}: {e}; the merge job wrote:\n{log}")
            })?,
        );
        if without_wall(&a) != without_wall(&b) {
            return Err(format!(
                "the merged map differs from the local one:\n{a}\n---\n{b}"
            ));
        }
        eprintln!(
            "cluster-check: finding map in 2 shards + merge = local map ({:.1} s)",
            t.elapsed().as_secs_f64()
        );
        Ok(())
    }
}

/// The finished point folders of a sweep folder.
fn finished(dir: &Path) -> usize {
    (std::fs::read_dir(dir).into_iter().flatten().flatten())
        .filter(|e| e.file_name().to_string_lossy().starts_with("point-"))
        .count()
}

/// The lines of a CSV without its wall-time columns (`wall_s`).
fn without_wall(text: &str) -> Vec<String> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let keep: Vec<bool> = header.iter().map(|h| !h.starts_with("wall")).collect();
    std::iter::once(text.lines().next().unwrap_or(""))
        .chain(lines)
        .map(|l| {
            (l.split(',').zip(&keep))
                .filter(|(_, k)| **k)
                .map(|(c, _)| c)
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect()
}

/// Two sweep folders' sweep.csv agree but for the wall times.
fn same_sweep(a: &Path, b: &Path) -> Result<(), String> {
    let read = |d: &Path| {
        std::fs::read_to_string(d.join("sweep.csv")).map_err(|e| format!("{}: {e}", d.display()))
    };
    let (x, y) = (read(a)?, read(b)?);
    if without_wall(&x) != without_wall(&y) {
        return Err(format!(
            "{} differs from {} (wall times aside):\n{x}\n---\n{y}",
            b.display(),
            a.display()
        ));
    }
    Ok(())
}
