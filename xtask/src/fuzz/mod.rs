//! `cargo xtask fuzz [--cases N] [--seed S] [--threads T] [--simulate-every K] [--timeout SECS]
//! [--capi N] [--case I]`: structure-aware fuzzing of the model-file path (docs/fuzzing.md).
//!
//! Each case is a seed model file (`models/`, `tests/data/`, `tests/data/bad/` and the
//! built-in form of every catalog model) with 1–4 random mutations ([`mutate`]), run through
//! the public API of `clr` as `clr run` does ([`case`]): parse, validate, build, and for every
//! K-th case a short simulation with a step budget. Panics are caught, a per-case watchdog flags
//! hangs, and an error that names neither a line nor a field is a finding. The C ABI is fuzzed
//! after the model files ([`capi`]). The report goes to `target/fuzz/report.md`, one
//! reproducer per finding (reduced line by line) to `target/fuzz/findings/`.

pub mod capi;
pub mod case;
pub mod mutate;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::process::ExitCode;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use case::{Limits, Verdict};
use mutate::{Input, Seed};

/// Options of a run.
#[derive(Debug, Clone)]
struct Options {
    cases: u64,
    seed: u64,
    threads: usize,
    simulate_every: u64,
    timeout: f64,
    capi: u64,
    replay: Option<u64>,
}

const HELP: &str =
    "usage: cargo xtask fuzz [--cases N] [--seed S] [--threads T] [--simulate-every K]
                        [--timeout SECS] [--capi N] [--case I]
  --cases N           model files to generate and run (default 1000000)
  --seed S            seed of the run (default 1); case I of seed S is always the same input
  --threads T         worker threads (default: the number of cores)
  --simulate-every K  simulate every K-th case (1e-3 s, 2000 steps at most) when it is accepted;
                      the others are parsed, validated and built only (default 5)
  --timeout SECS      a case running longer is a hang (default 10)
  --capi N            random scenarios of the C ABI, a dozen calls each (default 100000)
  --case I            run case I alone and print its input and verdict";

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        cases: 1_000_000,
        seed: 1,
        threads: std::thread::available_parallelism().map_or(2, |n| n.get()),
        simulate_every: 5,
        timeout: 10.0,
        capi: 100_000,
        replay: None,
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut val = |name: &str| -> Result<String, String> {
            it.next().cloned().ok_or(format!("{name} needs a value"))
        };
        let num = |name: &str, v: String| -> Result<u64, String> {
            v.replace('_', "")
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x >= 0.0 && x.fract() == 0.0)
                .map(|x| x as u64)
                .ok_or(format!("{name} {v}: expected a whole number"))
        };
        match a.as_str() {
            "--cases" => o.cases = num(a, val(a)?)?,
            "--seed" => o.seed = num(a, val(a)?)?,
            "--threads" => o.threads = num(a, val(a)?)?.max(1) as usize,
            "--simulate-every" => o.simulate_every = num(a, val(a)?)?,
            "--timeout" => {
                o.timeout = val(a)?
                    .parse()
                    .ok()
                    .filter(|t: &f64| *t > 0.0)
                    .ok_or("--timeout needs a positive number of seconds")?
            }
            "--capi" => o.capi = num(a, val(a)?)?,
            "--case" => o.replay = Some(num(a, val(a)?)?),
            "-h" | "--help" => return Err(String::new()),
            other => return Err(format!("unknown option `{other}`")),
        }
    }
    Ok(o)
}

/// Every seed: the shipped model files and the built-in form of each catalog model.
pub fn seeds() -> Vec<Seed> {
    let root = crate::workspace_root();
    let mut s = mutate::seeds_from_dirs(&[
        root.join("models"),
        root.join("tests/data"),
        root.join("tests/data/bad"),
    ]);
    for (name, text) in case::builtin_seeds() {
        s.push(Seed::new(&name, text));
    }
    s
}

/// Whether case `i` is simulated when accepted.
fn limits(i: u64, every: u64) -> Limits {
    Limits {
        simulate: every > 0 && i.is_multiple_of(every),
        ..Limits::default()
    }
}

/// The kind of a finding and its signature (findings with one signature are one bug).
fn signature(v: &Verdict) -> Option<(&'static str, String)> {
    let first_line = |m: &str| m.lines().next().unwrap_or("").to_string();
    match v {
        Verdict::Panic(m) => Some(("panic", first_line(m))),
        Verdict::Unlocated(m) => {
            // numbers vary from case to case: keep the words
            let words: String = first_line(m)
                .chars()
                .map(|c| if c.is_ascii_digit() { '#' } else { c })
                .take(120)
                .collect();
            Some(("error without a location", words))
        }
        _ => None,
    }
}

#[derive(Debug, Default)]
struct Stats {
    done: u64,
    accepted: u64,
    simulated: u64,
    rejected: u64,
    unlocated: u64,
    solver_failures: u64,
    panics: u64,
    hangs: u64,
    /// signature → (kind, count, first case index, message)
    findings: BTreeMap<(String, String), (u64, u64, String)>,
    /// Time spent generating inputs and running them (s, all threads).
    gen_secs: f64,
    run_secs: f64,
    /// The slowest cases: (seconds, case index), slowest first.
    slowest: Vec<(f64, u64)>,
}

impl Stats {
    fn add(&mut self, i: u64, v: &Verdict, secs: f64) {
        self.done += 1;
        if self.slowest.len() < 10 || secs > self.slowest[self.slowest.len() - 1].0 {
            self.slowest.push((secs, i));
            self.slowest.sort_by(|a, b| b.0.total_cmp(&a.0));
            self.slowest.truncate(10);
        }
        match v {
            Verdict::Accepted { simulated } => {
                self.accepted += 1;
                self.simulated += u64::from(*simulated);
            }
            Verdict::Rejected => self.rejected += 1,
            Verdict::Unlocated(_) => self.unlocated += 1,
            Verdict::SolverFailure(_) => {
                self.accepted += 1;
                self.simulated += 1;
                self.solver_failures += 1;
            }
            Verdict::Panic(_) => self.panics += 1,
        }
        if let Some((kind, sig)) = signature(v) {
            let msg = match v {
                Verdict::Panic(m) | Verdict::Unlocated(m) => m.clone(),
                _ => String::new(),
            };
            let e = self
                .findings
                .entry((kind.to_string(), sig))
                .or_insert((0, i, msg));
            e.0 += 1;
            if i < e.1 {
                e.1 = i;
            }
        }
    }

    fn line(&self, total: u64, rate: f64) -> String {
        format!(
            "fuzz: {}/{} cases ({:.1} %), {:.0}/s: accepted {} (simulated {}, solver failures {}), \
             rejected {}, without location {}, panics {}, over the timeout {}",
            self.done,
            total,
            100.0 * self.done as f64 / total.max(1) as f64,
            rate,
            self.accepted,
            self.simulated,
            self.solver_failures,
            self.rejected,
            self.unlocated,
            self.panics,
            self.hangs
        )
    }
}

/// A worker's current case: 0 idle, `i + 1` running case `i`, with `HUNG` set once the
/// watchdog reported it.
const HUNG: u64 = 1 << 63;

struct Slot {
    state: AtomicU64,
    started: Mutex<Instant>,
}

struct Shared {
    seeds: Vec<Seed>,
    opts: Options,
    next: AtomicU64,
    stats: Mutex<Stats>,
    slots: Mutex<Vec<Arc<Slot>>>,
}

fn spawn_worker(sh: &Arc<Shared>) {
    let slot = Arc::new(Slot {
        state: AtomicU64::new(0),
        started: Mutex::new(Instant::now()),
    });
    sh.slots.lock().expect("slots").push(slot.clone());
    let sh = sh.clone();
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(move || loop {
            let i = sh.next.fetch_add(1, Ordering::Relaxed);
            if i >= sh.opts.cases {
                return;
            }
            let g = Instant::now();
            let input = mutate::generate(&sh.seeds, sh.opts.seed, i);
            let gen_secs = g.elapsed().as_secs_f64();
            let t = Instant::now();
            *slot.started.lock().expect("slot") = t;
            slot.state.store(i + 1, Ordering::SeqCst);
            let v = case::run(&input.text, &limits(i, sh.opts.simulate_every));
            let secs = t.elapsed().as_secs_f64();
            if slot
                .state
                .compare_exchange(i + 1, 0, Ordering::SeqCst, Ordering::SeqCst)
                .is_err()
            {
                // reported as a hang meanwhile: a replacement took over
                return;
            }
            let mut stats = sh.stats.lock().expect("stats");
            stats.add(i, &v, secs);
            stats.gen_secs += gen_secs;
            stats.run_secs += secs;
        })
        .expect("spawn a fuzz worker");
}

/// Run each flagged case alone with 30× the timeout: (cases with no result in that time, finished
/// cases with their wall time in s). A case still running is left behind in its thread.
fn confirm_hangs(seeds: &[Seed], o: &Options, flagged: &[u64]) -> (Vec<u64>, Vec<(u64, f64)>) {
    let (mut hung, mut slow) = (Vec::new(), Vec::new());
    for &i in flagged {
        let text = mutate::generate(seeds, o.seed, i).text;
        let lim = limits(i, o.simulate_every);
        let (tx, rx) = std::sync::mpsc::channel();
        let t = Instant::now();
        let spawned = std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn(move || {
                let _ = case::run(&text, &lim);
                let _ = tx.send(());
            });
        let limit = Duration::from_secs_f64(30.0 * o.timeout);
        match spawned.ok().and_then(|_| rx.recv_timeout(limit).ok()) {
            Some(()) => slow.push((i, t.elapsed().as_secs_f64())),
            None => hung.push(i),
        }
        eprintln!(
            "fuzz: flagged case {i} re-run alone: {:.1} s",
            t.elapsed().as_secs_f64()
        );
    }
    (hung, slow)
}

/// Reduce a failing input line by line while it keeps the same signature (at most `budget`
/// runs; hangs are not reduced).
fn reduce(text: &str, i: u64, every: u64, sig: &(&'static str, String), budget: usize) -> String {
    let same = |t: &str| signature(&case::run(t, &limits(i, every))).as_ref() == Some(sig);
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut runs = 0;
    let mut chunk = (lines.len() / 2).max(1);
    while chunk >= 1 && runs < budget {
        let mut k = 0;
        let mut changed = false;
        while k < lines.len() && runs < budget {
            let mut trial = lines.clone();
            trial.drain(k..(k + chunk).min(lines.len()));
            runs += 1;
            if same(&trial.join("\n")) {
                lines = trial;
                changed = true;
            } else {
                k += chunk;
            }
        }
        if !changed {
            if chunk == 1 {
                break;
            }
            chunk /= 2;
        }
    }
    let mut out = lines.join("\n");
    out.push('\n');
    out
}

fn replay(seeds: &[Seed], o: &Options, i: u64) -> ExitCode {
    let input = mutate::generate(seeds, o.seed, i);
    println!("# case {i} of seed {}: {} with", o.seed, input.seed);
    for m in &input.mutations {
        println!("#   {m}");
    }
    println!("{}", input.text);
    case::quiet_panics();
    let v = case::run(&input.text, &limits(i, o.simulate_every));
    println!("# verdict: {v:?}");
    if v.is_finding() {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

fn header(input: &Input, i: u64, o: &Options, what: &str) -> String {
    let mut s = format!(
        "# fuzz finding: {what}\n# case {i} of `cargo xtask fuzz --seed {}` (replay: `cargo xtask fuzz --seed {} --case {i}`)\n# seed file {}, mutations:\n",
        o.seed, o.seed, input.seed
    );
    for m in &input.mutations {
        let m: String = m.chars().take(200).collect();
        let _ = writeln!(s, "#   {}", m.replace('\n', " "));
    }
    s.push_str("# reduced line by line to the lines that keep the finding:\n");
    s
}

/// `cargo xtask fuzz`.
pub fn run(args: &[String]) -> ExitCode {
    let o = match parse_args(args) {
        Ok(o) => o,
        Err(e) => {
            if e.is_empty() {
                println!("{HELP}");
                return ExitCode::SUCCESS;
            }
            eprintln!("xtask fuzz: {e}\n{HELP}");
            return ExitCode::from(2);
        }
    };
    let seeds = seeds();
    if let Some(i) = o.replay {
        return replay(&seeds, &o, i);
    }
    let out_dir = crate::target_dir().join("fuzz");
    let findings_dir = out_dir.join("findings");
    let _ = std::fs::remove_dir_all(&findings_dir);
    if let Err(e) = std::fs::create_dir_all(&findings_dir) {
        eprintln!("xtask fuzz: cannot create {}: {e}", findings_dir.display());
        return ExitCode::FAILURE;
    }
    println!(
        "fuzz: {} cases from {} seeds, seed {}, {} threads, simulating every {}-th accepted case (1e-3 s, 2000 steps at most), hang after {} s",
        o.cases,
        seeds.len(),
        o.seed,
        o.threads,
        o.simulate_every,
        o.timeout
    );
    case::quiet_panics();
    let start = Instant::now();
    let sh = Arc::new(Shared {
        seeds,
        opts: o.clone(),
        next: AtomicU64::new(0),
        stats: Mutex::new(Stats::default()),
        slots: Mutex::new(Vec::new()),
    });
    for _ in 0..o.threads {
        spawn_worker(&sh);
    }
    let mut hangs: Vec<u64> = Vec::new();
    let mut last_print = Instant::now();
    loop {
        std::thread::sleep(Duration::from_millis(200));
        // the watchdog
        let slots: Vec<Arc<Slot>> = sh.slots.lock().expect("slots").clone();
        for s in &slots {
            let st = s.state.load(Ordering::SeqCst);
            if st == 0 || st & HUNG != 0 {
                continue;
            }
            let age = s.started.lock().expect("slot").elapsed().as_secs_f64();
            if age > o.timeout
                && s.state
                    .compare_exchange(st, st | HUNG, Ordering::SeqCst, Ordering::SeqCst)
                    .is_ok()
            {
                let i = st - 1;
                hangs.push(i);
                let mut stats = sh.stats.lock().expect("stats");
                stats.done += 1;
                stats.hangs += 1;
                drop(stats);
                eprintln!("fuzz: case {i} runs for more than {} s: a hang", o.timeout);
                spawn_worker(&sh);
            }
        }
        let stats = sh.stats.lock().expect("stats");
        let done = stats.done;
        if last_print.elapsed() > Duration::from_secs(5) {
            let rate = done as f64 / start.elapsed().as_secs_f64();
            eprintln!("{}", stats.line(o.cases, rate));
            last_print = Instant::now();
        }
        if done >= o.cases {
            break;
        }
    }
    let wall = start.elapsed().as_secs_f64();
    let mut stats = std::mem::take(&mut *sh.stats.lock().expect("stats"));
    eprintln!("{}", stats.line(o.cases, stats.done as f64 / wall));
    // a case over the timeout under load is only flagged: run it again alone with a 30× longer
    // limit; one that finishes is slow (its step budget bounds it), one that does not is a hang
    let (hangs, slow) = confirm_hangs(&sh.seeds, &o, &hangs);
    stats.hangs = hangs.len() as u64;

    // the C ABI
    let capi_start = Instant::now();
    let capi_stats = capi::run(o.seed, o.capi);
    let capi_wall = capi_start.elapsed().as_secs_f64();

    let mut report = String::new();
    let _ = writeln!(report, "# Fuzz report\n");
    let _ = writeln!(
        report,
        "`cargo xtask fuzz --cases {} --seed {} --threads {} --simulate-every {}` ({} seed files; docs/fuzzing.md).\n",
        o.cases,
        o.seed,
        o.threads,
        o.simulate_every,
        sh.seeds.len()
    );
    let _ = writeln!(report, "## Model files\n\n| | count |\n|---|---:|");
    for (k, v) in [
        ("cases", stats.done),
        ("accepted", stats.accepted),
        (
            "  of them simulated (1e-3 s, ≤ 2000 steps)",
            stats.simulated,
        ),
        (
            "  of them solver failures reported as errors",
            stats.solver_failures,
        ),
        ("rejected with a location (line or field)", stats.rejected),
        ("**rejected without a location**", stats.unlocated),
        ("**panics**", stats.panics),
        (
            "flagged over the timeout while running",
            (hangs.len() + slow.len()) as u64,
        ),
        (
            "**hangs** (no result within 30× the timeout, run alone)",
            stats.hangs,
        ),
    ] {
        let _ = writeln!(report, "| {k} | {v} |");
    }
    let _ = writeln!(
        report,
        "\nWall time: {wall:.1} s ({:.0} cases/s on {} threads).\n",
        stats.done as f64 / wall.max(1e-9),
        o.threads
    );
    let _ = writeln!(
        report,
        "Thread time: {:.1} s generating inputs, {:.1} s running them.\n",
        stats.gen_secs, stats.run_secs
    );
    if !slow.is_empty() {
        let _ = writeln!(
            report,
            "Flagged cases that finished when run alone (slow, not hung):\n"
        );
        for (i, secs) in &slow {
            let _ = writeln!(report, "- case {i}: {secs:.1} s");
        }
        let _ = writeln!(report);
    }
    let _ = writeln!(report, "Slowest cases (replay with `--case I`):\n");
    for (secs, i) in &stats.slowest {
        let input = mutate::generate(&sh.seeds, o.seed, *i);
        let what: Vec<String> = input
            .mutations
            .iter()
            .map(|m| m.chars().take(80).collect())
            .collect();
        let _ = writeln!(
            report,
            "- case {i}: {secs:.2} s ({}{}; {})",
            input.seed,
            if limits(*i, o.simulate_every).simulate {
                ", simulated when accepted"
            } else {
                ""
            },
            what.join("; ").replace('`', "'")
        );
    }
    let _ = writeln!(report, "\n## Findings\n");
    if stats.findings.is_empty() && hangs.is_empty() {
        let _ = writeln!(report, "None.\n");
    }
    let mut n = 0;
    for ((kind, _sig), (count, i, msg)) in &stats.findings {
        n += 1;
        let input = mutate::generate(&sh.seeds, o.seed, *i);
        let v = case::run(&input.text, &limits(*i, o.simulate_every));
        let reduced = match signature(&v) {
            Some(sig) => reduce(&input.text, *i, o.simulate_every, &sig, 400),
            None => input.text.clone(),
        };
        let file = findings_dir.join(format!("{n:03}-{}.toml", kind.replace(' ', "-")));
        let text = format!("{}{}", header(&input, *i, &o, kind), reduced);
        let _ = std::fs::write(&file, text);
        let msg: String = msg.chars().take(400).collect();
        let _ = writeln!(
            report,
            "- {kind} ({count} cases, first case {i}): `{}` — reproducer `{}`",
            msg.replace('`', "'").replace('\n', " "),
            file.strip_prefix(crate::workspace_root())
                .unwrap_or(&file)
                .display()
        );
    }
    for i in &hangs {
        n += 1;
        let input = mutate::generate(&sh.seeds, o.seed, *i);
        let file = findings_dir.join(format!("{n:03}-hang.toml"));
        let _ = std::fs::write(
            &file,
            format!("{}{}", header(&input, *i, &o, "hang"), input.text),
        );
        let _ = writeln!(
            report,
            "- hang (case {i}, over {} s) — reproducer `{}`",
            o.timeout,
            file.strip_prefix(crate::workspace_root())
                .unwrap_or(&file)
                .display()
        );
    }
    let _ = writeln!(
        report,
        "\n## C ABI (clr-contact-capi)\n\n{} random scenarios, {} calls: {} succeeded, {} returned an error status; {} findings (panics caught at the boundary, success with a NaN result from inputs within ±1e6); {} NaN results from extreme inputs (IEEE overflow, e.g. a journal centre at 1e30 m: r × F = ∞ − ∞), not counted as findings; {capi_wall:.1} s.\n",
        o.capi,
        capi_stats.calls,
        capi_stats.ok,
        capi_stats.errors,
        capi_stats.finding_count,
        capi_stats.overflow
    );
    for f in &capi_stats.findings {
        let _ = writeln!(report, "- {}", f.replace('\n', " "));
    }
    let path = out_dir.join("report.md");
    let _ = std::fs::write(&path, &report);
    println!("{report}");
    println!("written to {}", path.display());
    let bad = stats.unlocated + stats.panics + stats.hangs + capi_stats.finding_count;
    if bad > 0 {
        // a hung worker may still be running: do not wait for it
        std::process::exit(1);
    }
    ExitCode::SUCCESS
}
