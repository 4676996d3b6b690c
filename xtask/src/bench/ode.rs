//! `cargo xtask bench ode`: clr-ode's NDF against diffsol's BDF and SciPy's `solve_ivp` BDF.
//!
//! Problems: HIRES, Robertson, stiff Van der Pol (ε = 1e-6) and OREGO of the *Test Set for IVP
//! Solvers* (Mazzia, Magherini, Iavernaro), with their analytic Jacobians, at rtol 1e-6 and 1e-8.
//! Absolute tolerance atol = rtol, except Robertson: atol = 1e-6·rtol (its y2 is ~1e-13 near
//! t_end; 1e-12 at rtol 1e-6 as in verification.md's peer note). The same rule is used by all
//! three solvers and checked on the peers' rows.
//!
//! Timing: clr-ode (in this process) and the diffsol peer (a child process) alternate in
//! `--rounds` rounds (default 3), so that both see the same machine load; in each round a solve
//! is repeated at least 5 times and `--min-time`/rounds seconds (default 1 s in total), and a row
//! reports the median over rounds of the per-round median wall time. SciPy runs once afterwards
//! (at least 3 solves and 2×`--min-time` seconds per row); only its solve is timed. The peers run
//! in the same invocation. Accuracy is the mixed-error number of significant
//! correct digits `scd = −log10 max_i |y_i − ref_i| / (1 + |ref_i|)` of the state at t_end against
//! the Test Set reference (`clr_ode::test_models`).
//!
//! Output: `target/bench/ode.json` `{"machine", "rows": [{problem, solver, rtol, atol, wall_s,
//! f_evals, steps, scd, repeats}]}`, `target/bench/ode.md` (the table, with the time ratios
//! diffsol/clr and SciPy/clr, and the equal-accuracy comparison) and work–precision figures
//! `target/bench/ode_<problem>.{svg,png}` (also `docs/figures/bench_ode_<problem>.{svg,png}` with
//! `--docs-figures`).

use std::fmt::Write as _;
use std::process::ExitCode;

use clr_plot::Figure;
use serde::Serialize;

use super::clr;
use super::peers::{run_diffsol, run_scipy, PeerRow};
use super::row::{median, Row};
use super::{parsed_or_report, with_series};

#[derive(Serialize)]
struct Report<'a> {
    machine: String,
    rows: &'a [Row],
}

struct Args {
    rtols: Vec<f64>,
    min_time: f64,
    rounds: usize,
    docs_figures: bool,
    diffsol: bool,
    scipy: bool,
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        rtols: Vec::new(),
        min_time: 1.0,
        rounds: 3,
        docs_figures: false,
        diffsol: true,
        scipy: true,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = |flag: &str| -> Result<f64, String> {
            let v = it
                .next()
                .ok_or_else(|| format!("{flag} needs a value, e.g. {flag} 1e-6"))?;
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x > 0.0)
                .ok_or_else(|| format!("{flag} {v}: give a positive number"))
        };
        match arg.as_str() {
            "--rtol" => a.rtols.push(value("--rtol")?),
            "--min-time" => a.min_time = value("--min-time")?,
            "--rounds" => a.rounds = value("--rounds")?.round().max(1.0) as usize,
            "--docs-figures" => a.docs_figures = true,
            "--no-scipy" => a.scipy = false,
            "--no-diffsol" => a.diffsol = false,
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if a.rtols.is_empty() {
        a.rtols = vec![1e-6, 1e-8];
    }
    Ok(a)
}

/// Absolute tolerance paired with `rtol` (module documentation).
pub fn atol_for(problem: &str, rtol: f64) -> f64 {
    if problem == "robertson" {
        rtol * 1e-6
    } else {
        rtol
    }
}

pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".to_string());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_string))
        .map_or(String::new(), |l| {
            format!(", 1-min load average {l} at start")
        });
    format!(
        "{cpu}, {cores} cores, {} {}{load}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

fn peer_rows(
    who: &str,
    rows: Result<Vec<PeerRow>, String>,
    out: &mut Vec<Row>,
    notes: &mut Vec<String>,
) {
    match rows {
        Ok(rows) => {
            for PeerRow { mut row, y_end } in rows {
                let Some(reference) = clr::reference(&row.problem) else {
                    notes.push(format!("{who}: unknown problem {} ignored", row.problem));
                    continue;
                };
                let expected = atol_for(&row.problem, row.rtol);
                if (row.atol - expected).abs() > 1e-9 * expected {
                    notes.push(format!(
                        "{who}: {} at rtol {:e} used atol {:e}, not {expected:e}",
                        row.problem, row.rtol, row.atol
                    ));
                }
                row.scd = clr::scd(&y_end, reference);
                out.push(row);
            }
        }
        Err(e) => {
            let msg = format!("{who} not measured: {e}");
            eprintln!("bench ode: {msg}");
            notes.push(msg);
        }
    }
}

fn fmt_ms(s: f64) -> String {
    let ms = s * 1e3;
    if ms >= 100.0 {
        format!("{ms:.0}")
    } else if ms >= 1.0 {
        format!("{ms:.2}")
    } else {
        format!("{ms:.3}")
    }
}

/// The Markdown table: one line per (problem, rtol, solver) with the time relative to clr.
pub fn markdown(machine: &str, rows: &[Row], notes: &[String]) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "Machine: {machine}. Median wall time of one solve (ms); `time / clr` is the solver's median time over clr-ode NDF's in the same run.\n");
    let _ = writeln!(
        md,
        "| problem | rtol | atol | solver | time (ms) | steps | f evals | scd | time / clr |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        let clr = rows
            .iter()
            .find(|c| c.solver == clr::SOLVER && c.problem == r.problem && c.rtol == r.rtol);
        let ratio = clr.map_or("–".to_string(), |c| format!("{:.2}", r.wall_s / c.wall_s));
        let _ = writeln!(
            md,
            "| {} | {:.0e} | {:.0e} | {} | {} | {} | {} | {:.2} | {} |",
            r.problem,
            r.rtol,
            r.atol,
            r.solver,
            fmt_ms(r.wall_s),
            r.steps,
            r.f_evals,
            r.scd,
            ratio
        );
    }
    for n in notes {
        let _ = writeln!(md, "\nNote: {n}");
    }
    md
}

/// Tolerances of the work–precision sweep of clr-ode and diffsol: 1e-5 … 1e-10 by decades plus
/// the requested ones, loosest first.
fn sweep_rtols(requested: &[f64]) -> Vec<f64> {
    // literals, equal to what the peers parse from "1e-6" (10f64.powi(-6) may round differently)
    let mut v: Vec<f64> = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10].to_vec();
    for &r in requested {
        match v.iter_mut().find(|x| (**x / r - 1.0).abs() < 1e-9) {
            Some(x) => *x = r,
            None => v.push(r),
        }
    }
    v.sort_by(|a, b| b.total_cmp(a));
    v
}

/// Wall time of `solver` on `problem` at accuracy `scd`: the solver's sweep points are sorted by
/// scd and log10 time is interpolated linearly between the two neighbours that bracket `scd`;
/// `None` outside the range of scd the sweep reached.
pub fn time_at_scd(rows: &[Row], problem: &str, solver: &str, scd: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.problem == problem && r.solver == solver && r.scd.is_finite())
        .map(|r| (r.scd, r.wall_s.log10()))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts.windows(2).find_map(|w| {
        let ((s0, t0), (s1, t1)) = (w[0], w[1]);
        (s0 <= scd && scd <= s1 && s1 > s0)
            .then(|| 10f64.powf(t0 + (t1 - t0) * (scd - s0) / (s1 - s0)))
    })
}

/// For each clr-ode point at the requested tolerances: the time diffsol needs for the same scd
/// (interpolated on its sweep), and the ratio to clr-ode's time.
pub fn equal_accuracy_table(rows: &[Row], rtols: &[f64]) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\nAt equal accuracy: diffsol's time interpolated at clr-ode's scd on diffsol's \
         work–precision sweep (rtol 1e-5 … 1e-10; linear in scd vs log time).\n"
    );
    let _ = writeln!(
        md,
        "| problem | clr rtol | clr scd | clr (ms) | diffsol at same scd (ms) | diffsol / clr |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    for r in rows
        .iter()
        .filter(|r| r.solver == clr::SOLVER && rtols.contains(&r.rtol))
    {
        let d = time_at_scd(rows, &r.problem, "diffsol-bdf", r.scd);
        let (dt, ratio) = d.map_or(("–".to_string(), "–".to_string()), |d| {
            (fmt_ms(d), format!("{:.2}", d / r.wall_s))
        });
        let _ = writeln!(
            md,
            "| {} | {:.0e} | {:.2} | {} | {dt} | {ratio} |",
            r.problem,
            r.rtol,
            r.scd,
            fmt_ms(r.wall_s)
        );
    }
    md
}

/// Merge the rows of several rounds: one row per (problem, solver, rtol) with the median of the
/// rounds' median times and the total number of timed solves.
fn median_of_rounds(rows: Vec<Row>) -> Vec<Row> {
    let mut out: Vec<(Row, Vec<f64>)> = Vec::new();
    for r in rows {
        match out
            .iter_mut()
            .find(|(o, _)| o.problem == r.problem && o.solver == r.solver && o.rtol == r.rtol)
        {
            Some((o, times)) => {
                times.push(r.wall_s);
                o.repeats += r.repeats;
            }
            None => {
                let t = r.wall_s;
                out.push((r, vec![t]));
            }
        }
    }
    out.into_iter()
        .map(|(mut r, times)| {
            r.wall_s = median(times);
            r
        })
        .collect()
}

/// Work–precision figure of one problem: scd against median solve time for each solver (lines
/// over the tolerance sweep, loosest first), saved as `<stem>.svg` and `<stem>.png`.
fn figure(rows: &[Row], problem: &str, stem: &std::path::Path) -> Result<(), String> {
    let mut fig = Figure::new(format!("{problem}: accuracy against solve time"))
        .x_label("median solve time (ms)")
        .y_label("scd (significant correct digits at t_end)")
        .log_x();
    for (solver, label) in [
        (clr::SOLVER, "clr-ode NDF"),
        ("diffsol-bdf", "diffsol BDF"),
        ("scipy-bdf", "SciPy BDF"),
    ] {
        let pts: Vec<(f64, f64, f64)> = rows
            .iter()
            .filter(|r| r.problem == problem && r.solver == solver)
            .map(|r| (r.rtol, r.wall_s * 1e3, r.scd))
            .collect();
        if !pts.is_empty() {
            fig = with_series(fig, label, pts);
        }
    }
    fig.save(stem).map(|_| ()).map_err(|e| e.to_string())
}

pub fn run(args: &[String]) -> ExitCode {
    let Some(args) = parsed_or_report(parse_args(args), "cargo xtask bench ode: ") else {
        return ExitCode::from(2);
    };
    let root = crate::workspace_root();
    let machine = machine();
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    let mut failed = false;

    // clr-ode and diffsol alternate in rounds so that both see the same machine load; each row
    // is then the median of its per-round medians.
    let sweep = sweep_rtols(&args.rtols);
    let per_round = args.min_time / args.rounds as f64;
    let mut timed_rows = Vec::new();
    for round in 1..=args.rounds {
        eprintln!(
            "bench ode: round {round}/{}: clr-ode NDF (in process)",
            args.rounds
        );
        for &rtol in &sweep {
            for name in clr::PROBLEMS {
                let atol = atol_for(name, rtol);
                match clr::bench(name, rtol, atol, per_round) {
                    Ok(row) => timed_rows.push(row),
                    Err(e) => {
                        let msg = format!("clr-ode {name} at rtol {rtol:e} failed: {e}");
                        eprintln!("bench ode: {msg}");
                        if round == 1 {
                            notes.push(msg);
                        }
                        failed = true;
                    }
                }
            }
        }
        if args.diffsol {
            let mut round_notes = Vec::new();
            peer_rows(
                "diffsol",
                run_diffsol(&root, &sweep, per_round),
                &mut timed_rows,
                &mut round_notes,
            );
            if round == 1 {
                notes.append(&mut round_notes);
            }
        }
    }
    if !args.diffsol {
        notes.push("diffsol skipped (--no-diffsol)".to_string());
    }
    rows.extend(median_of_rounds(timed_rows));
    if args.scipy {
        peer_rows(
            "SciPy",
            run_scipy(&root, &args.rtols, 2.0 * args.min_time),
            &mut rows,
            &mut notes,
        );
    } else {
        notes.push("SciPy skipped (--no-scipy)".to_string());
    }

    // Group by rtol, then problem in the order of clr::PROBLEMS, then solver.
    let order = |r: &Row| {
        let p = clr::PROBLEMS
            .iter()
            .position(|p| *p == r.problem)
            .unwrap_or(usize::MAX);
        let s = [clr::SOLVER, "diffsol-bdf", "scipy-bdf"]
            .iter()
            .position(|s| *s == r.solver)
            .unwrap_or(usize::MAX);
        (p, s)
    };
    rows.sort_by(|a, b| {
        b.rtol
            .total_cmp(&a.rtol)
            .then_with(|| order(a).cmp(&order(b)))
    });

    let main_rows: Vec<Row> = rows
        .iter()
        .filter(|r| args.rtols.contains(&r.rtol))
        .cloned()
        .collect();
    let mut md = markdown(&machine, &main_rows, &notes);
    md.push_str(&equal_accuracy_table(&rows, &args.rtols));
    let dir = crate::target_dir().join("bench");
    let report = Report {
        machine: machine.clone(),
        rows: &rows,
    };
    let written = serde_json::to_string_pretty(&report)
        .map_err(std::io::Error::other)
        .and_then(|json| {
            std::fs::create_dir_all(&dir)?;
            std::fs::write(dir.join("ode.json"), json)
        })
        .and_then(|()| std::fs::write(dir.join("ode.md"), &md));
    let mut fig_dirs = vec![(dir.clone(), "ode_")];
    if args.docs_figures {
        fig_dirs.push((root.join("docs").join("figures"), "bench_ode_"));
    }
    for (fig_dir, prefix) in &fig_dirs {
        for p in clr::PROBLEMS {
            if let Err(e) = figure(&rows, p, &fig_dir.join(format!("{prefix}{p}"))) {
                eprintln!("bench ode: figure {p} in {}: {e}", fig_dir.display());
            }
        }
    }
    print!("{md}");
    if let Err(e) = written {
        eprintln!("bench ode: could not write {}: {e}", dir.display());
        return ExitCode::FAILURE;
    }
    eprintln!(
        "bench ode: wrote {0}/ode.json and {0}/ode.md",
        dir.display()
    );
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
