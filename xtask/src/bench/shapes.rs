//! `cargo xtask bench shapes`: a model with 100 shape contact pairs, most of them apart, against
//! the same model with only its pairs that touch (issue 18: the cost per step must follow the
//! pairs in contact, not the pairs apart).
//!
//! Model: `balls` steel balls (r = 10 mm, m = 32.7 g) in a row 0.5 m apart, each dropped from
//! 0.1 m onto its own floor block (Hertz K = 1.5·10¹⁰ N/m^1.5, Lankarani–Nikravesh damping,
//! c_e = 0.8): `balls` pairs that touch again and again. The full model adds every ball–ball
//! pair (45 for 10 balls) and pairs of each ball with far walls (up to 100 pairs in all): pairs
//! that never come within their prediction distance. Both models have the same bodies, the same
//! contacts and therefore the same steps; the difference in cost per step is what the pairs
//! apart cost (their broad phase: one bounding-box test per evaluation, plus their share of the
//! step bound of conservative advancement).
//!
//! Also measured, per pair and evaluation (the narrow phase the broad phase saves): clr-contact's
//! `contact_points` for a ball–ball pair 0.5 m apart against the box test that skips it.
//!
//! A third model makes every pair touch with the same dynamics: each ball's floor contact split
//! into 10 pairs against 10 coincident floors with a tenth of the stiffness each (the Hertz
//! and Lankarani–Nikravesh forces are linear in K, so they add up to the same force). The cost
//! per step over the first model, per added pair, is the cost of a touching pair, to set
//! beside that of a pair apart.
//!
//! NDF, rtol 1e-7, atol 1e-10, 0.5 s (several bounces per ball), median of `--runs` runs
//! (default 3). Output: target/bench/shapes.{json,md}.

use std::fmt::Write as _;
use std::hint::black_box;
use std::process::ExitCode;
use std::time::Instant;

use clr_contact::body::Vector2;
use clr_contact::{boxes_overlap, contact_points, BodyState, ContactShape, Shape};
use clr_mbd::ModelDesc;
use serde::Serialize;

use super::ode::machine;
use super::{parse_next, parsed_or_report};

/// Pairs in the full model.
const PAIRS: usize = 100;
/// Balls (and touching pairs).
const BALLS: usize = 10;

#[derive(Debug, Clone, Serialize)]
struct Row {
    model: String,
    pairs: usize,
    pairs_touching: usize,
    steps: usize,
    rejected: usize,
    f_evals: usize,
    onsets: usize,
    wall_s: f64,
    us_per_step: f64,
}

#[derive(Serialize)]
struct Report<'a> {
    machine: String,
    rows: &'a [Row],
    ratio_per_step: f64,
    apart_us_per_pair_step: f64,
    touching_us_per_pair_step: f64,
    narrow_phase_ns: f64,
    box_test_ns: f64,
}

/// The model text: `BALLS` balls on floors, plus `extra` pairs apart. With `split` > 1 each
/// ball's floor contact is `split` pairs against `split` coincident floors, each with
/// 1/`split` of the stiffness: forces linear in K add up to the same dynamics, with `split`
/// times the touching pairs.
fn model_text(extra: usize, split: usize) -> String {
    let mut s = String::from(
        "[model]\nname = \"balls\"\ngravity = [0.0, -9.81]\n[solver]\nrtol = 1e-7\natol = 1e-10\n\
         [output]\nt_end = 0.5\nintervals = 50\n",
    );
    let law = "{ law = \"hertz\", stiffness = 1.5e10, damping = \"lankarani-nikravesh\", \
               restitution = 0.8 }";
    let floor_law = format!(
        "{{ law = \"hertz\", stiffness = {}, damping = \"lankarani-nikravesh\", \
         restitution = 0.8 }}",
        1.5e10 / split as f64
    );
    for k in 0..BALLS {
        let x = 0.5 * k as f64;
        let _ = write!(
            s,
            "[[body]]\nname = \"b{k}\"\nmass = 0.0327\ninertia = 1.308e-6\n\
             position = [{x}, {y}]\n\
             [[shape]]\nname = \"s{k}\"\nat = {{ body = \"b{k}\", at = [0.0, 0.0] }}\n\
             geometry = {{ type = \"ball\", radius = 0.01 }}\n",
            // staggered heights so the impacts do not coincide
            y = 0.11 + 0.01 * k as f64,
        );
        for m in 0..split {
            let _ = write!(
                s,
                "[[shape]]\nname = \"f{k}_{m}\"\nat = {{ body = \"ground\", at = [{x}, -0.05] }}\n\
                 geometry = {{ type = \"cuboid\", half_extents = [0.1, 0.05] }}\n\
                 [[clearance]]\nname = \"c{k}_{m}\"\ntype = \"contact\"\n\
                 shapes = [\"f{k}_{m}\", \"s{k}\"]\nnormal = {floor_law}\n"
            );
        }
    }
    let mut added = 0;
    'pairs: for i in 0..BALLS {
        for j in i + 1..BALLS {
            if added == extra {
                break 'pairs;
            }
            let _ = write!(
                s,
                "[[clearance]]\nname = \"bb{i}_{j}\"\ntype = \"contact\"\n\
                 shapes = [\"s{i}\", \"s{j}\"]\nnormal = {law}\n"
            );
            added += 1;
        }
    }
    // the rest: each ball against a wall 2 m above its floor
    let mut k = 0;
    while added < extra {
        let b = k % BALLS;
        let _ = write!(
            s,
            "[[shape]]\nname = \"w{k}\"\nat = {{ body = \"ground\", at = [{}, 2.0] }}\n\
             geometry = {{ type = \"cuboid\", half_extents = [0.1, 0.05] }}\n\
             [[clearance]]\nname = \"cw{k}\"\ntype = \"contact\"\nshapes = [\"w{k}\", \"s{b}\"]\n\
             normal = {law}\n",
            0.5 * b as f64
        );
        added += 1;
        k += 1;
    }
    s
}

fn bench_model(name: &str, (extra, split): (usize, usize), runs: usize) -> Result<Row, String> {
    let table: toml::Table =
        toml::from_str(&model_text(extra, split)).map_err(|e| e.to_string())?;
    let desc = ModelDesc::from_toml_table(table).map_err(|e| e.to_string())?;
    let opts = desc.sim_options().map_err(|e| e.to_string())?;
    let mut walls = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let mut m = desc.compile().map_err(|e| e.to_string())?;
        let start = Instant::now();
        let r = m.simulate(&opts).map_err(|e| e.to_string())?;
        walls.push(start.elapsed().as_secs_f64());
        last = Some(r);
    }
    let r = last.ok_or("no run")?;
    walls.sort_by(f64::total_cmp);
    let wall_s = walls[walls.len() / 2];
    Ok(Row {
        model: name.to_string(),
        pairs: BALLS * split + extra,
        pairs_touching: BALLS * split,
        steps: r.stats.accepted,
        rejected: r.stats.rejected,
        f_evals: r.stats.f_evals,
        onsets: r.onsets,
        wall_s,
        us_per_step: wall_s / r.stats.accepted.max(1) as f64 * 1e6,
    })
}

/// (narrow phase, box test) per call in ns for two balls 0.5 m apart.
fn per_pair_costs() -> (f64, f64) {
    let ball = ContactShape::new(Shape::Ball { radius: 0.01 }).expect("valid ball");
    let a = BodyState::fixed(Vector2::new(0.0, 0.1), 0.0);
    let b = BodyState::fixed(Vector2::new(0.5, 0.1), 0.0);
    let mut ws = clr_contact::ShapeContactWorkspace::new();
    let n = 200_000;
    let start = Instant::now();
    for _ in 0..n {
        let p = contact_points(&ball, black_box(&a), &ball, black_box(&b), 1e-3, &mut ws);
        black_box(p.map(|p| p.len()).unwrap_or(0));
    }
    let narrow = start.elapsed().as_secs_f64() / n as f64 * 1e9;
    let start = Instant::now();
    for _ in 0..n {
        let hit = boxes_overlap(&ball.aabb(black_box(&a)), &ball.aabb(black_box(&b)), 1e-3);
        black_box(hit);
    }
    let boxes = start.elapsed().as_secs_f64() / n as f64 * 1e9;
    (narrow, boxes)
}

fn parse_runs(args: &[String]) -> Result<usize, String> {
    let mut runs = 3;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--runs" => runs = parse_next(&mut it, |&r: &usize| r > 0, "--runs needs N ≥ 1")?,
            other => return Err(format!("unknown argument `{other}` (expected --runs N)")),
        }
    }
    Ok(runs)
}

pub fn run(args: &[String]) -> ExitCode {
    let Some(runs) = parsed_or_report(parse_runs(args), "bench shapes: ") else {
        return ExitCode::from(2);
    };
    let mut rows = Vec::new();
    let split = PAIRS / BALLS;
    for (name, layout) in [
        ("touching pairs only", (0, 1)),
        ("100 pairs, 90 apart", (PAIRS - BALLS, 1)),
        ("100 pairs, all touching", (0, split)),
    ] {
        eprintln!("bench shapes: {name}");
        match bench_model(name, layout, runs) {
            Ok(r) => rows.push(r),
            Err(e) => {
                eprintln!("bench shapes: {name} failed: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    let (narrow, boxes) = per_pair_costs();
    let ratio = rows[1].us_per_step / rows[0].us_per_step;
    // the added cost per pair per step: apart (row 1) and touching (row 2) over the base
    let extra_pairs = (PAIRS - BALLS) as f64;
    let apart_us = (rows[1].us_per_step - rows[0].us_per_step) / extra_pairs;
    let touching_us = (rows[2].us_per_step - rows[0].us_per_step) / extra_pairs;
    let mut md = format!(
        "# bench shapes\n\nMachine: {}\n\n| model | pairs | touching | steps | rejected | \
         f evals | onsets | wall (ms) | µs/step |\n|---|---|---|---|---|---|---|---|---|\n",
        machine()
    );
    for r in &rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {:.1} | {:.2} |",
            r.model,
            r.pairs,
            r.pairs_touching,
            r.steps,
            r.rejected,
            r.f_evals,
            r.onsets,
            r.wall_s * 1e3,
            r.us_per_step
        );
    }
    let _ = writeln!(
        md,
        "\nAdded cost per pair and step: a pair apart {apart_us:.3} µs, a touching pair \
         {touching_us:.3} µs (**{:.1}×** a pair apart).",
        touching_us / apart_us
    );
    let _ = writeln!(
        md,
        "\nCost per step, 100 pairs / touching pairs only: **{ratio:.2}** ({} pairs apart).\n\
         Per pair and evaluation: narrow phase of two balls 0.5 m apart {narrow:.0} ns, the box \
         test that skips it {boxes:.0} ns ({:.1}× cheaper).",
        PAIRS - BALLS,
        narrow / boxes
    );
    print!("{md}");
    let dir = crate::target_dir().join("bench");
    let report = Report {
        machine: machine(),
        rows: &rows,
        ratio_per_step: ratio,
        apart_us_per_pair_step: apart_us,
        touching_us_per_pair_step: touching_us,
        narrow_phase_ns: narrow,
        box_test_ns: boxes,
    };
    let written = std::fs::create_dir_all(&dir)
        .map_err(|e| e.to_string())
        .and_then(|()| serde_json::to_string_pretty(&report).map_err(|e| e.to_string()))
        .and_then(|j| std::fs::write(dir.join("shapes.json"), j).map_err(|e| e.to_string()))
        .and_then(|()| std::fs::write(dir.join("shapes.md"), &md).map_err(|e| e.to_string()));
    match written {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("bench shapes: cannot write target/bench: {e}");
            ExitCode::FAILURE
        }
    }
}
