//! End-to-end tests of the `clr` binary: built-in models, export/reload, a generic model file
//! checked against a closed form, sweeps with shards and merge, plots, malformed files and
//! simulation failures (exit codes 0, 1, 2).

mod common;

use std::path::{Path, PathBuf};

use common::{clr, stderr};

fn data(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
        .display()
        .to_string()
}

/// A fresh scratch folder under the target dir.
fn scratch(name: &str) -> PathBuf {
    common::scratch_in("cli", name)
}

/// Header names (units stripped) and rows of a results.csv.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let names = lines
        .next()
        .unwrap()
        .split(',')
        .map(|h| h.split(" [").next().unwrap().to_string())
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse::<f64>().unwrap()).collect())
        .collect();
    (names, rows)
}

fn column(names: &[String], rows: &[Vec<f64>], name: &str) -> Vec<f64> {
    let k = names.iter().position(|n| n == name).unwrap();
    rows.iter().map(|r| r[k]).collect()
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn list_names_every_builtin() {
    let o = clr(&["list"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    for e in clr_models::catalog::entries() {
        assert!(text.contains(e.name), "`clr list` misses {}", e.name);
    }
}

/// Every built-in model runs for a short time, ends at the requested time, and records the
/// full default parameters.
#[test]
fn every_builtin_runs_briefly() {
    let entries = clr_models::catalog::entries();
    assert!(!entries.is_empty(), "the catalog lists no model");
    for e in entries {
        let out = scratch(&format!("builtin-{}", e.name));
        let t_end = 2e-3;
        let o = clr(&[
            "run",
            e.name,
            "--t-end",
            "2e-3",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
            "--no-figures",
        ]);
        assert!(o.status.success(), "{}: {}", e.name, stderr(&o));
        let (names, rows) = read_csv(&out.join("results.csv"));
        assert_eq!(names[0], "t");
        assert!(rows.len() >= 2, "{}: {} rows", e.name, rows.len());
        let t = column(&names, &rows, "t");
        assert!(
            (t[t.len() - 1] - t_end).abs() < 1e-12,
            "{}: last t {}",
            e.name,
            t[t.len() - 1]
        );
        let s = summary(&out);
        assert_eq!(s["status"], "ok");
        assert_eq!(
            s["parameters"],
            clr_models::catalog::default_parameters(e.name).unwrap(),
            "{}: summary.json must hold the full resolved parameters",
            e.name
        );
    }
}

/// `clr export --builtin` then `clr run file` reproduces `clr run <model>` bit for bit (with
/// overrides; the model-file form of `clr export` is checked in tests/export.rs).
#[test]
fn exported_file_reproduces_the_builtin_bit_for_bit() {
    let e = clr_models::catalog::entries()[0];
    let params = clr_models::catalog::default_parameters(e.name).unwrap();
    // override the first numeric parameter the model uses by 1.25 × its default
    let unused = clr_models::catalog::unused_parameters(e.name, &params).unwrap();
    let (key, value) = params
        .as_object()
        .unwrap()
        .iter()
        .filter(|(k, _)| !unused.iter().any(|(u, _)| u == k))
        .find_map(|(k, v)| {
            v.as_f64()
                .filter(|x| *x > 0.0)
                .map(|x| (k.clone(), x * 1.25))
        })
        .unwrap();
    let set = format!("{key}={value:e}");
    let dir = scratch("export");
    let file = dir.join("model.toml");
    let o = clr(&[
        "export",
        e.name,
        "--builtin",
        "--set",
        &set,
        "--out",
        file.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let a = dir.join("a");
    let b = dir.join("b");
    let common = ["--t-end", "3e-3", "--quiet", "--no-figures", "--out"];
    let o = clr(&[
        &["run", e.name, "--set", &set][..],
        &common[..],
        &[a.to_str().unwrap()],
    ]
    .concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let o = clr(&[
        &["run", file.to_str().unwrap()][..],
        &common[..],
        &[b.to_str().unwrap()],
    ]
    .concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let ra = std::fs::read(a.join("results.csv")).unwrap();
    let rb = std::fs::read(b.join("results.csv")).unwrap();
    assert!(ra.len() > 100);
    assert!(
        ra == rb,
        "results.csv differ between the built-in and its exported file"
    );
    assert_eq!(summary(&a)["parameters"], summary(&b)["parameters"]);
    assert_eq!(summary(&a)["parameters"][&key].as_f64(), Some(value));
}

/// Complete elliptic integral of the first kind K(k) by the arithmetic–geometric mean
/// (Abramowitz & Stegun 17.6): K = π / (2 AGM(1, √(1 − k²))).
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..40 {
        let (an, bn) = (0.5 * (a + b), (a * b).sqrt());
        a = an;
        b = bn;
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The pendulum file against the closed form of a compound pendulum's period,
/// T = 4 K(sin(θ0/2)) √(I_O/(m g d)) (e.g. Thornton & Marion, Classical Dynamics, §4.4), and
/// conservation of its energy.
#[test]
fn pendulum_file_matches_the_closed_form_period() {
    let out = scratch("pendulum");
    let o = clr(&[
        "run",
        &data("pendulum.toml"),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (names, rows) = read_csv(&out.join("results.csv"));
    let t = column(&names, &rows, "t");
    let th = column(&names, &rows, "rod.theta");
    let phi: Vec<f64> = th.iter().map(|x| x + std::f64::consts::FRAC_PI_2).collect();
    // crossings of φ = 0 in both directions, linearly interpolated (φ″ = 0 there)
    let mut up = Vec::new();
    let mut down = Vec::new();
    for k in 1..phi.len() {
        if phi[k - 1] * phi[k] < 0.0 {
            let tc = t[k - 1] + (t[k] - t[k - 1]) * phi[k - 1] / (phi[k - 1] - phi[k]);
            if phi[k] > 0.0 {
                up.push(tc)
            } else {
                down.push(tc)
            }
        }
    }
    let (m, l, g, theta0): (f64, f64, f64, f64) = (1.0, 1.0, 9.81, 0.5);
    let i_o = m * l * l / 3.0;
    let period = 4.0 * elliptic_k((theta0 / 2.0).sin()) * (i_o / (m * g * l / 2.0)).sqrt();
    assert!(
        up.len() >= 2 && down.len() >= 2,
        "crossings {up:?} {down:?}"
    );
    for tp in [up[1] - up[0], down[1] - down[0]] {
        assert!(
            ((tp - period) / period).abs() < 1e-6,
            "period {tp} s vs closed form {period} s"
        );
    }
    assert!((down[0] - period / 4.0).abs() < 1e-6 * period);
    let e = column(&names, &rows, "energy.total");
    let drift = e.iter().map(|x| (x - e[0]).abs()).fold(0.0, f64::max);
    assert!(drift < 1e-7 * e[0].abs(), "energy drift {drift} J");
    // figures of the main time histories
    for f in ["angles.svg", "angles.png", "energy.svg"] {
        assert!(out.join(f).is_file(), "missing {f}");
    }
}

/// A generic model with a clearance joint, a driver, a spring and friction: runs, draws the
/// contact figures, and its recorded eccentricity and penetration obey δ = |e| − c with the
/// radial clearance c = 0.0100 − 0.0099 m of the file.
#[test]
fn clearance_model_file_runs_with_orbit_figures() {
    let out = scratch("journal");
    let o = clr(&[
        "run",
        &data("journal_bearing.toml"),
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for f in [
        "contact_forces.svg",
        "contact_forces.png",
        "orbit_pin.svg",
        "orbit_pin.png",
    ] {
        assert!(out.join(f).is_file(), "missing {f}");
    }
    let (names, rows) = read_csv(&out.join("results.csv"));
    let ex = column(&names, &rows, "pin.ex");
    let ey = column(&names, &rows, "pin.ey");
    let pen = column(&names, &rows, "pin.penetration");
    let fnorm = column(&names, &rows, "pin.normal_force");
    let c = 0.0100 - 0.0099;
    for k in 0..ex.len() {
        assert!((ex[k].hypot(ey[k]) - c - pen[k]).abs() < 1e-12);
        if pen[k] <= 0.0 {
            assert_eq!(fnorm[k], 0.0, "force without contact at row {k}");
        }
    }
    assert!(
        pen.iter().any(|&p| p > 0.0),
        "the journal never touched the bearing"
    );
    let s = summary(&out);
    assert!(s["solver"]["contact_onsets"].as_u64().unwrap() > 0);
}

/// A sweep split into two shards and merged equals the same sweep run at once, point for point
/// (bit-identical results, whatever the thread count).
#[test]
fn sharded_sweep_merges_into_the_full_sweep() {
    let dir = scratch("sweep");
    let p = data("pendulum.toml");
    let base = [
        "sweep",
        p.as_str(),
        "--t-end",
        "0.3",
        "--vary",
        "body.rod.mass=1,2",
        "--vary",
        "solver.rtol=1e-8,1e-9",
        "--no-figures",
        "--keep",
        "series",
        "-q",
    ];
    let full = dir.join("full");
    let o = clr(&[&base[..], &["--jobs", "3", "--out", full.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let mut shards = Vec::new();
    for i in 0..2 {
        let d = dir.join(format!("shard{i}"));
        let s = format!("{i}/2");
        let o = clr(&[
            &base[..],
            &["--jobs", "1", "--shard", &s, "--out", d.to_str().unwrap()],
        ]
        .concat());
        assert!(o.status.success(), "{}", stderr(&o));
        shards.push(d);
    }
    let merged = dir.join("merged");
    let o = clr(&[
        "merge",
        shards[0].to_str().unwrap(),
        shards[1].to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // sweep.csv equal except the wall-time column
    let strip = |p: &Path| -> Vec<String> {
        std::fs::read_to_string(p.join("sweep.csv"))
            .unwrap()
            .lines()
            .map(|l| {
                let mut c: Vec<&str> = l.split(',').collect();
                c.remove(5);
                c.join(",")
            })
            .collect()
    };
    let a = strip(&full);
    assert_eq!(a.len(), 5, "header + 4 points");
    assert!(a[0].starts_with("point,folder,body.rod.mass,solver.rtol,status"));
    assert_eq!(a, strip(&merged));
    for k in 0..4 {
        let f = format!("point-{k:05}/results.csv");
        let shard = &shards[k % 2];
        assert!(
            std::fs::read(full.join(&f)).unwrap() == std::fs::read(shard.join(&f)).unwrap(),
            "{f} differs between the full sweep and its shard"
        );
    }
    // the overrides reached the model: a heavier rod has twice the potential energy
    let s0 = summary(&full.join("point-00000"));
    let s2 = summary(&full.join("point-00002"));
    assert_eq!(s0["parameters"]["body"][0]["mass"], 1.0);
    assert_eq!(s2["parameters"]["body"][0]["mass"], 2.0);
    // merging one shard only is incomplete: exit 1, the missing points named
    let o = clr(&[
        "merge",
        shards[0].to_str().unwrap(),
        "--out",
        dir.join("half").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("[1, 3]"), "{}", stderr(&o));
}

/// A sweep interrupted mid-run (two point folders never written, one half-written, one of a
/// different model) and run again with `--resume` keeps the finished point as it was, reruns
/// the others and ends with the sweep.csv of an uninterrupted run (wall times aside); `clr
/// merge` refuses the interrupted folder, saying to resume it.
#[test]
fn a_resumed_sweep_keeps_finished_points_and_equals_the_full_sweep() {
    let dir = scratch("sweep_resume");
    let p = data("pendulum.toml");
    let out = dir.join("out");
    let args = [
        "sweep",
        p.as_str(),
        "--t-end",
        "0.2",
        "--vary",
        "body.rod.mass=1,2,3,4",
        "--keep",
        "metrics",
        "--no-figures",
        "-q",
        "--out",
        out.to_str().unwrap(),
    ];
    let o = clr(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let full = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    // --keep metrics: the point folder holds its record only
    let files: Vec<_> = std::fs::read_dir(out.join("point-00000"))
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(files, ["point.json"]);
    let kept = std::fs::read(out.join("point-00000/point.json")).unwrap();
    // the interruption: no sweep.csv/json yet, points 1 and 3 absent, 3 half-written, 2 of
    // another model
    for f in ["sweep.csv", "sweep.json"] {
        std::fs::remove_file(out.join(f)).unwrap();
    }
    for k in [1, 3] {
        std::fs::remove_dir_all(out.join(format!("point-0000{k}"))).unwrap();
    }
    let half = out.join(".point-00003.partial-4242");
    std::fs::create_dir_all(&half).unwrap();
    std::fs::write(half.join("results.csv"), "t [s]\n0.0\n").unwrap();
    let two = out.join("point-00002/point.json");
    let text = std::fs::read_to_string(&two).unwrap();
    let hash = text.split("fnv1a64:").nth(1).unwrap()[..16].to_string();
    std::fs::write(&two, text.replace(&hash, "0123456789abcdef")).unwrap();
    let o = clr(&[
        "merge",
        out.to_str().unwrap(),
        "--out",
        dir.join("m").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--resume") && stderr(&o).contains(".point-00003.partial-4242"),
        "{}",
        stderr(&o)
    );
    let resume: Vec<&str> = args.iter().filter(|a| **a != "-q").copied().collect();
    let o = clr(&[&resume[..], &["--resume"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("1 point(s) finished already, 3 to run"), "{e}");
    assert!(e.contains("point-00002: it ran another model"), "{e}");
    assert!(e.contains("removed 1 half-written"), "{e}");
    assert!(!half.exists());
    assert_eq!(
        std::fs::read(out.join("point-00000/point.json")).unwrap(),
        kept
    );
    let strip = |t: &str| -> Vec<String> {
        t.lines()
            .map(|l| {
                let mut c: Vec<&str> = l.split(',').collect();
                c.remove(4);
                c.join(",")
            })
            .collect()
    };
    let again = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    assert_eq!(strip(&full), strip(&again));
}

/// `clr merge` checks each shard's point folders against its sweep.csv and sweep.json: a
/// folder holding another point or another model's point is refused by name; a folder the
/// shard does not list is named and not merged.
#[test]
fn merge_refuses_foreign_point_folders_and_names_stray_ones() {
    let dir = scratch("merge_points");
    let p = data("pendulum.toml");
    let shard = |i: usize| {
        let out = dir.join(format!("shard-{i}"));
        let shard = format!("{i}/2");
        let o = clr(&[
            "sweep",
            &p,
            "--t-end",
            "0.1",
            "--vary",
            "body.rod.mass=1,2,3,4",
            "--keep",
            "metrics",
            "--no-figures",
            "-q",
            "--shard",
            &shard,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let (s0, s1) = (shard(0), shard(1));
    let merge = || {
        let (a, b, m) = (s0.to_str().unwrap(), s1.to_str().unwrap(), dir.join("all"));
        clr(&["merge", a, b, "--out", m.to_str().unwrap()])
    };
    let o = merge();
    assert!(o.status.success(), "{}", stderr(&o));
    // a folder the shard does not list: named, merged without it
    std::fs::create_dir_all(s1.join("point-00099")).unwrap();
    let o = merge();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("does not list") && stderr(&o).contains("point-00099"));
    // point 1's folder copied over point 0's: another point
    let (zero, one) = (
        s0.join("point-00000/point.json"),
        s1.join("point-00001/point.json"),
    );
    let original = std::fs::read_to_string(&zero).unwrap();
    std::fs::copy(&one, &zero).unwrap();
    let o = merge();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("point-00000: point 1 with values [\"2\"]") && e.contains("--resume"),
        "{e}"
    );
    // the same point of another model (its hash changed)
    let hash = original.split("fnv1a64:").nth(1).unwrap()[..16].to_string();
    std::fs::write(&zero, original.replace(&hash, "0123456789abcdef")).unwrap();
    let e = stderr(&merge());
    assert!(
        e.contains("point-00000: model hash fnv1a64:0123456789abcdef (sweep.json: \"fnv1a64:"),
        "{e}"
    );
    // ... or of another clr
    let other = original.replace(
        &format!("\"clr_version\": \"{}\"", env!("CARGO_PKG_VERSION")),
        "\"clr_version\": \"0.0.1\"",
    );
    assert_ne!(other, original);
    std::fs::write(&zero, other).unwrap();
    let e = stderr(&merge());
    assert!(e.contains("point-00000: clr 0.0.1 (sweep.json: \""), "{e}");
}

/// Shards record the model they ran: two shards of one sweep run against different contents
/// of the same model file are refused by `clr merge` (exit 2, naming the shard, both hashes and
/// that shard's rerun); the same contents merge. A shard without provenance (sweep.json of an
/// older clr) is refused unless `--allow-unverified`, which names it.
#[test]
fn merge_refuses_shards_of_different_model_contents() {
    let dir = scratch("merge_provenance");
    let model = dir.join("pendulum.toml");
    let original = std::fs::read_to_string(data("pendulum.toml")).unwrap();
    let shard = |i: usize, name: &str| {
        let d = dir.join(name);
        let s = format!("{i}/2");
        let o = clr(&[
            "sweep",
            model.to_str().unwrap(),
            "--t-end",
            "0.05",
            "--vary",
            "body.rod.mass=1,2",
            "--shard",
            &s,
            "--no-figures",
            "--no-report",
            "-q",
            "--out",
            d.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        d
    };
    let merge = |dirs: &[&PathBuf], extra: &[&str]| {
        let mut a: Vec<&str> = vec!["merge"];
        a.extend(dirs.iter().map(|d| d.to_str().unwrap()));
        let out = dir.join("merged");
        a.extend(["--out", out.to_str().unwrap()]);
        a.extend(extra);
        clr(&a)
    };
    std::fs::write(&model, &original).unwrap();
    let a0 = shard(0, "a0");
    let a1 = shard(1, "a1");
    // the same file changed between the two shards: a stiffer-to-turn rod
    let changed = original.replacen("inertia = 0.08333333333333333", "inertia = 0.1", 1);
    assert_ne!(changed, original, "the test's edit must change the model");
    std::fs::write(&model, &changed).unwrap();
    let b1 = shard(1, "b1");
    let meta = |d: &Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(d.join("sweep.json")).unwrap()).unwrap()
    };
    let (ha, hb) = (
        meta(&a1)["model_hash"].clone(),
        meta(&b1)["model_hash"].clone(),
    );
    assert!(ha.as_str().unwrap().starts_with("fnv1a64:"), "{ha}");
    assert_eq!(meta(&a0)["model_hash"], ha, "one model, one hash");
    assert_ne!(ha, hb);
    assert_eq!(
        meta(&a0)["clr_version"].as_str(),
        Some(env!("CARGO_PKG_VERSION"))
    );
    let o = merge(&[&a0, &b1], &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    for part in [
        b1.display().to_string(),
        a0.display().to_string(),
        ha.as_str().unwrap().to_string(),
        hb.as_str().unwrap().to_string(),
        "re-run shard 1/2".to_string(),
    ] {
        assert!(e.contains(&part), "`{part}` missing from: {e}");
    }
    let o = merge(&[&a0, &a1], &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(meta(&dir.join("merged"))["model_hash"], ha);
    // a shard of an older clr: no provenance
    let mut old = meta(&a1);
    old.as_object_mut().unwrap().remove("model_hash");
    old.as_object_mut().unwrap().remove("clr_version");
    std::fs::write(a1.join("sweep.json"), old.to_string()).unwrap();
    let o = merge(&[&a0, &a1], &[]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains(&a1.display().to_string()) && e.contains("--allow-unverified"),
        "{e}"
    );
    let o = merge(&[&a0, &a1], &["--allow-unverified"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("without provenance"), "{}", stderr(&o));
    assert_eq!(
        meta(&dir.join("merged"))["unverified_shards"][0].as_str(),
        Some(a1.display().to_string().as_str())
    );
}

#[test]
fn plot_draws_named_columns_and_rejects_unknown_ones() {
    let out = scratch("plot");
    let o = clr(&[
        "run",
        &data("pendulum.toml"),
        "--t-end",
        "0.5",
        "--no-figures",
        "--series",
        "both",
        "-q",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let plot = |table: &std::path::Path, svg: &str| {
        let svg = out.join(svg);
        let (t, s) = (table.to_str().unwrap(), svg.to_str().unwrap());
        let o = clr(&[
            "plot",
            t,
            "--x",
            "time",
            "--y",
            "rod.theta,rod.omega",
            "--out",
            s,
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read_to_string(&svg).unwrap()
    };
    let csv = out.join("results.csv");
    let drawn = plot(&csv, "theta.svg");
    assert!(drawn.contains("<svg"));
    // results.parquet holds the same table: the same figure, its title (the file) aside
    let parquet = out.join("results.parquet");
    let drawn2 = plot(&parquet, "theta_parquet.svg");
    let title = |p: &std::path::Path| p.display().to_string();
    assert_eq!(drawn2.replace(&title(&parquet), &title(&csv)), drawn);
    let o = clr(&["plot", csv.to_str().unwrap(), "--y", "rod.thta"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("did you mean `rod.theta`"),
        "{}",
        stderr(&o)
    );
}

/// `--set` on a model file: the end time changes, and a wrong name gets a suggestion.
#[test]
fn overrides_on_a_model_file() {
    let out = scratch("set");
    let o = clr(&[
        "run",
        &data("pendulum.toml"),
        "--set",
        "output.t_end=0.25",
        "--set",
        "output.intervals=10",
        "--no-figures",
        "-q",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (names, rows) = read_csv(&out.join("results.csv"));
    assert_eq!(rows.len(), 11);
    assert_eq!(column(&names, &rows, "t")[10], 0.25);
    let o = clr(&[
        "run",
        &data("pendulum.toml"),
        "--set",
        "body.rdo.mass=2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("did you mean `rod`"), "{}", stderr(&o));
    let o = clr(&["run", "slider_crnk"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("did you mean `slider_crank`"),
        "{}",
        stderr(&o)
    );
}

/// A solver failure exits with 1, states the error and leaves the partial results.
#[test]
fn simulation_failure_exits_1_with_partial_results() {
    let out = scratch("fail");
    let o = clr(&[
        "run",
        &data("pendulum.toml"),
        "--set",
        "solver.max_steps=20",
        "--no-figures",
        "-q",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("step budget"), "{}", stderr(&o));
    let (names, rows) = read_csv(&out.join("results.csv"));
    assert!(rows.len() > 1);
    let t = column(&names, &rows, "t");
    assert!(t[t.len() - 1] < 3.5);
    assert_eq!(summary(&out)["status"], "failed");
    // the partial rows are the first rows of the complete run (an independent run with the
    // default step budget), in every column, bit for bit
    let full_out = scratch("fail-full");
    let o = clr(&[
        "run",
        &data("pendulum.toml"),
        "--no-figures",
        "-q",
        "--out",
        full_out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (full_names, full_rows) = read_csv(&full_out.join("results.csv"));
    assert_eq!(names, full_names);
    assert!(names.iter().any(|n| n == "energy.total") && names.iter().any(|n| n == "pin.Fx"));
    assert!(rows.len() < full_rows.len());
    assert_eq!(rows[..], full_rows[..rows.len()]);
}

/// A built-in model whose integrator fails exits with 1 and writes the rows computed up to the
/// failure in every column of a complete run (contact columns and energies included). The
/// failure is the step budget (`--max-steps 300`) of the Wan slider–crank with NDF at rtol 1e-8
/// (which used to stop there with Newton failures, fixed in issue 13); the rows are checked
/// against a complete run up to the failure time: the same columns, and the crank angle,
/// prescribed by the driver, equal to 1e-9 rad.
#[test]
fn builtin_failure_exits_1_with_partial_results_in_every_column() {
    let out = scratch("builtin-fail");
    let o = clr(&[
        "run",
        "wan_slider_crank",
        "--set",
        "solver=ndf",
        "--rtol",
        "1e-8",
        "--max-steps",
        "300",
        "--no-figures",
        "-q",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("step budget"), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("partial results up to t ="),
        "{}",
        stderr(&o)
    );
    let (names, rows) = read_csv(&out.join("results.csv"));
    assert!(rows.len() > 1, "{}", stderr(&o));
    let s = summary(&out);
    assert_eq!(s["status"], "failed");
    assert_eq!(s["parameters"]["solver"], "ndf", "{s}");
    let t = column(&names, &rows, "t");
    let t_fail = t[t.len() - 1];
    let ok = scratch("builtin-fail-ref");
    let o = clr(&[
        "run",
        "wan_slider_crank",
        "--t-end",
        &format!("{}", 2.0 * t_fail),
        "--no-figures",
        "-q",
        "--out",
        ok.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let (ref_names, ref_rows) = read_csv(&ok.join("results.csv"));
    // same columns up to the derived ones a complete run appends after its metrics
    assert!(names.len() <= ref_names.len());
    assert_eq!(names[..], ref_names[..names.len()]);
    assert!(
        names.iter().any(|n| n.ends_with(".normal_force")),
        "{names:?}"
    );
    assert!(names.iter().any(|n| n == "energy.total"));
    // the crank follows its driver: same angle at the same times (interpolated in the
    // reference run, which has its own step sequence)
    let (rt, rth) = (
        column(&ref_names, &ref_rows, "t"),
        column(&ref_names, &ref_rows, "crank.theta"),
    );
    let th = column(&names, &rows, "crank.theta");
    for (ti, thi) in t.iter().zip(&th) {
        let k = rt.partition_point(|&x| x < *ti).clamp(1, rt.len() - 1);
        let w = (ti - rt[k - 1]) / (rt[k] - rt[k - 1]);
        let r = rth[k - 1] + w * (rth[k] - rth[k - 1]);
        assert!((thi - r).abs() < 1e-9, "t = {ti}: {thi} vs {r}");
    }
}

/// Malformed files: exit code 2 and a message with file, line, field and the fix.
#[test]
fn malformed_files_exit_2_with_a_located_message() {
    let cases: &[(&str, &[&str])] = &[
        (
            "unknown_field.toml",
            &["unknown_field.toml:10:", "did you mean `mass`"],
        ),
        (
            "unknown_body.toml",
            &[":25:", "joint[0].b.body", "did you mean `rod`"],
        ),
        (
            "unknown_point.toml",
            &[":24:", "joint[0].a", "did you mean `pivot`"],
        ),
        (
            "unknown_joint_type.toml",
            &[":23:", "joint[0].type", "did you mean `revolute`"],
        ),
        (
            "unknown_damping.toml",
            &[
                ":51:",
                "clearance[0].normal.damping",
                "did you mean `lankarani-nikravesh`",
            ],
        ),
        ("unknown_friction.toml", &[":52:", "did you mean `coulomb`"]),
        (
            "zero_mass.toml",
            &[":10:", "body[0].mass", "must be positive"],
        ),
        (
            "missing_mass.toml",
            &[":8:", "body[0].mass", "missing value"],
        ),
        ("missing_t_end.toml", &["output.t_end", "missing value"]),
        ("wrong_type.toml", &[":10:", "mass", "expected f64"]),
        (
            "negative_clearance.toml",
            &[":50:", "clearance[0].journal_radius", "must be positive"],
        ),
        ("syntax.toml", &["syntax.toml:10:"]),
        ("not_toml.toml", &["not_toml.toml:1:"]),
        (
            "redundant.toml",
            &[":36:", "joint[1]", "redundant constraints"],
        ),
        (
            "unknown_builtin.toml",
            &[":2:", "did you mean `slider_crank`"],
        ),
        (
            "unknown_parameter.toml",
            &[":5:", "did you mean `crank_speed_rpm`"],
        ),
        ("parameter_type.toml", &[":5:", "expected a number"]),
        (
            "beam_bad_node.toml",
            &[":13:", "beam[0].supports[0].node", "nodes 0 to 10"],
        ),
        (
            "unknown_beam.toml",
            &[":21:", "force[0].beam", "did you mean `cant`"],
        ),
        (
            "slider_too_tall.toml",
            &[":21:", "clearance[0].slider_height", "must be positive"],
        ),
        (
            "anchor_typo.toml",
            &[":65:", "clearance[0].journal.att", "did you mean `at`"],
        ),
        (
            "translational_liu.toml",
            &[":22:", "clearance[0].normal.law", "needs a journal"],
        ),
        ("max_order.toml", &[":20:", "solver.max_order", "1 to 5"]),
    ];
    for (file, needles) in cases {
        let o = clr(&[
            "run",
            &data(&format!("bad/{file}")),
            "--out",
            scratch("bad").to_str().unwrap(),
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{file}: {err}");
        assert!(!err.contains("panicked"), "{file}: {err}");
        for n in *needles {
            assert!(err.contains(n), "{file}: expected `{n}` in: {err}");
        }
    }
}

/// Built-in models written as generic model files (tests/data/slider_crank.toml,
/// wan_slider_crank.toml, manipulator.toml: independent descriptions of the same mechanisms through the
/// model-file path) give the built-ins' time histories bit for bit, column by column.
#[test]
fn generic_files_equal_their_builtins() {
    for (model, file, t_end) in [
        ("slider_crank", "slider_crank.toml", "4e-3"),
        ("manipulator", "manipulator.toml", "0.1"),
        ("wan_slider_crank", "wan_slider_crank.toml", "0.01"),
    ] {
        let dir = scratch(&format!("generic-{model}"));
        let (a, b) = (dir.join("builtin"), dir.join("file"));
        let common = ["--t-end", t_end, "--quiet", "--no-figures", "--out"];
        let o = clr(&[&["run", model][..], &common[..], &[a.to_str().unwrap()]].concat());
        assert!(o.status.success(), "{}", stderr(&o));
        let file = data(file);
        let o = clr(&[
            &["run", file.as_str()][..],
            &common[..],
            &[b.to_str().unwrap()],
        ]
        .concat());
        assert!(o.status.success(), "{}", stderr(&o));
        let (na, ra) = read_csv(&a.join("results.csv"));
        let (nb, rb) = read_csv(&b.join("results.csv"));
        assert_eq!(ra.len(), rb.len(), "{model}");
        assert!(rb.len() > 5 && nb.len() > 40, "{model}: {} rows", rb.len());
        for name in &nb {
            let x = column(&na, &ra, name);
            let y = column(&nb, &rb, name);
            for (k, (p, q)) in x.iter().zip(&y).enumerate() {
                assert!(
                    p.to_bits() == q.to_bits(),
                    "{model} {name} row {k}: {p} vs {q}"
                );
            }
        }
    }
}

/// A damped cantilever of `[[beam]]` elements under a tip step load settles on the
/// Euler–Bernoulli static deflection P L³/(3 E I) (Timoshenko & Gere, Mechanics of Materials,
/// cantilever with an end load; the cubic Hermite element is exact for nodal loads).
#[test]
fn beam_file_settles_on_the_static_tip_deflection() {
    let out = scratch("cantilever");
    let o = clr(&[
        "run",
        &data("cantilever.toml"),
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (names, rows) = read_csv(&out.join("results.csv"));
    let v = column(&names, &rows, "cant.n10.v");
    let (p, l, e, w, h) = (10.0f64, 0.5f64, 2.07e11f64, 0.02f64, 0.01f64);
    let i = w * h.powi(3) / 12.0;
    let static_tip = -p * l.powi(3) / (3.0 * e * i);
    let last = v[v.len() - 1];
    assert!(
        ((last - static_tip) / static_tip).abs() < 1e-5,
        "{last} vs {static_tip}"
    );
    assert!(out.join("beam_deflection.svg").is_file());
}

/// A block dropped in a translational clearance comes to rest carrying its weight: the sum of
/// the corner normal forces equals m g (static equilibrium), and the block sits one clearance
/// (W − h)/2 = 1 mm below the guide axis, less the Hertz penetration (m g/2 per corner,
/// δ = (F/K)^(2/3)).
#[test]
fn translational_clearance_file_rests_on_its_weight() {
    let out = scratch("slider-guide");
    let o = clr(&[
        "run",
        &data("slider_in_guide.toml"),
        "--out",
        out.to_str().unwrap(),
        "-q",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (names, rows) = read_csv(&out.join("results.csv"));
    let f = column(&names, &rows, "guide.normal_force");
    let y = column(&names, &rows, "block.y");
    let mg = 2.0 * 9.81;
    assert!(
        (f[f.len() - 1] - mg).abs() < 1e-6 * mg,
        "{} vs {mg}",
        f[f.len() - 1]
    );
    let delta = (mg / 2.0 / 1e9f64).powf(2.0 / 3.0);
    let y_rest = -(0.020 - 0.018) / 2.0 - delta;
    assert!(
        (y[y.len() - 1] - y_rest).abs() < 1e-9,
        "{} vs {y_rest}",
        y[y.len() - 1]
    );
    assert!(!out.join("orbit_guide.svg").exists());
}

/// Every built-in exports (`--builtin`) to a file whose resolved parameters equal the defaults
/// exactly.
#[test]
fn every_builtin_exports_to_an_equal_file() {
    let dir = scratch("export-all");
    for e in clr_models::catalog::entries() {
        let file = dir.join(format!("{}.toml", e.name));
        let o = clr(&[
            "export",
            e.name,
            "--builtin",
            "--out",
            file.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}: {}", e.name, stderr(&o));
        match clr_sim::spec::load(&file, &[]) {
            Ok(clr_sim::spec::Loaded::Builtin { name, parameters }) => {
                assert_eq!(name, e.name);
                assert_eq!(
                    parameters,
                    clr_models::catalog::default_parameters(e.name).unwrap()
                );
            }
            other => panic!("{}: {other:?}", e.name),
        }
    }
}

#[test]
fn list_shows_the_paper_studies_and_an_unknown_study_names_the_valid_ones() {
    let out = clr(&["list"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for s in clr_models::studies::studies() {
        assert!(text.contains(s.name), "{} missing from `clr list`", s.name);
    }
    let out = clr(&["study", "no_such_study"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("guide_friction"), "{err}");
}

/// The integrator knobs of `clr run`: an order outside 1–5 is refused with exit code 2 and the
/// option named; `--jacobian finite-difference` with `--max-order 2` runs a built-in and a model
/// file, the file's summary echoing them in its resolved `[solver]`.
#[test]
fn integrator_knobs_reach_the_run() {
    let out = scratch("knobs-bad");
    let o = clr(&[
        "run",
        "slider_crank",
        "--max-order",
        "7",
        "-q",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--max-order 7"), "{}", stderr(&o));
    // NDF settings on a Dormand–Prince built-in are refused, not ignored (issue 14)
    let o = clr(&[
        "run",
        "slider_crank",
        "--max-order",
        "2",
        "-q",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--set solver=ndf"), "{}", stderr(&o));
    for target in ["slider_crank".to_string(), data("pendulum.toml")] {
        let out = scratch("knobs");
        let o = clr(&[
            "run",
            &target,
            "--t-end",
            "2e-3",
            "--set",
            if target.ends_with(".toml") {
                "solver.method=ndf"
            } else {
                "solver=ndf"
            },
            "--jacobian",
            "finite-difference",
            "--max-order",
            "2",
            "--no-figures",
            "-q",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{target}: {}", stderr(&o));
        if target.ends_with(".toml") {
            let s = summary(&out);
            assert_eq!(
                s["parameters"]["solver"]["jacobian"], "finite_difference",
                "{s}"
            );
            assert_eq!(s["parameters"]["solver"]["max_order"], 2, "{s}");
        }
    }
}

/// `clr run` on the clearance slider–crank model file writes `impacts.csv` (header and one row
/// per located impact, consistent with the rows of results.csv) and the per-joint `impacts`
/// summary in summary.json, which agrees with the CSV.
#[test]
fn run_writes_located_impacts() {
    let out = scratch("impacts");
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/slider_crank.toml");
    common::run_quietly(file.to_str().unwrap(), "0.03", &out);
    let text = std::fs::read_to_string(out.join("impacts.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "joint,onset_s,impact_velocity_m_per_s,peak_force_N,peak_force_time_s,\
         max_penetration_m,max_penetration_time_s,separation_s,duration_s"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(!rows.is_empty(), "no impact located");
    let num = |s: &str| s.parse::<f64>().unwrap();
    for r in &rows {
        assert_eq!((r.len(), r[0]), (9, "B"));
        let (onset, peak_t, sep) = (num(r[1]), num(r[4]), r[7]);
        assert!(num(r[3]) > 0.0 && num(r[5]) > 0.0);
        if !sep.is_empty() {
            assert!(onset <= peak_t && peak_t <= num(sep));
            assert!((num(r[8]) - (num(sep) - onset)).abs() <= 1e-12);
        }
    }
    let (names, data) = read_csv(&out.join("results.csv"));
    let row_peak = column(&names, &data, "B.normal_force")
        .into_iter()
        .fold(0.0, f64::max);
    let s = summary(&out);
    let b = &s["impacts"]["B"];
    assert_eq!(b["count"].as_u64().unwrap() as usize, rows.len());
    assert_eq!(b["first_impact_s"].as_f64().unwrap(), num(rows[0][1]));
    let largest = b["largest_peak_force_N"].as_f64().unwrap();
    assert!(
        largest >= row_peak * (1.0 - 1e-12),
        "{largest} < {row_peak}"
    );
    let metric = |name: &str| {
        s["metrics"]
            .as_array()
            .unwrap()
            .iter()
            .find(|m| m["name"] == name)
            .and_then(|m| m["value"].as_f64())
            .unwrap()
    };
    assert_eq!(metric("B.peak_normal_force"), largest);
    assert_eq!(metric("B.impacts") as usize, rows.len());
}

/// `clr animate` exports a run's animation as a GIF with fps × duration frames, refuses a run
/// folder without report.html, and says what to do when --mp4 finds no ffmpeg.
#[test]
fn animate_exports_the_run_as_a_gif() {
    let out = scratch("animate");
    let d = out.to_str().unwrap();
    let o = clr(&[
        "run",
        "slider_crank",
        "--t-end",
        "0.005",
        "--out",
        d,
        "--quiet",
        "--no-figures",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let gif = out.join("a.gif");
    let o = clr(&[
        "animate",
        d,
        "--gif",
        gif.to_str().unwrap(),
        "--fps",
        "10",
        "--duration",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("a.gif"), "{}", stderr(&o));
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::Indexed);
    let mut dec = opts.read_info(std::fs::File::open(&gif).unwrap()).unwrap();
    assert_eq!(dec.width(), 800);
    assert_eq!(dec.height() % 2, 0);
    let mut frames = 0;
    while dec.read_next_frame().unwrap().is_some() {
        frames += 1;
    }
    assert_eq!(frames, 10);

    // the report page itself is accepted too; no ffmpeg on PATH: a clear error, exit 2
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_clr"))
        .args(["animate", out.join("report.html").to_str().unwrap()])
        .args(["--mp4", out.join("a.mp4").to_str().unwrap()])
        .env("PATH", "")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("install ffmpeg") && stderr(&o).contains("--gif"),
        "{}",
        stderr(&o)
    );

    // a run without report.html
    let bare = scratch("animate-no-report");
    let o = clr(&[
        "run",
        "slider_crank",
        "--t-end",
        "0.001",
        "--out",
        bare.to_str().unwrap(),
        "--quiet",
        "--no-figures",
        "--no-report",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = clr(&[
        "animate",
        bare.to_str().unwrap(),
        "--gif",
        gif.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no report.html"), "{}", stderr(&o));
}

/// A ball (r = 10 mm, centre 15 mm up) dropping 5 mm onto a ground floor block
/// (x ∈ [−0.5, 0.5] m, y ∈ [−0.1, 0] m); little restitution: it rests on the floor from about
/// t = 0.06 s.
const BALL_DROP: &str = r#"
[model]
name = "drop"
gravity = [0.0, -9.81]

[[body]]
name = "ball"
mass = 0.0327
inertia = 1.308e-6
position = [0.0, 0.015]
angle = 0.0
velocity = [0.0, 0.0]
angular_velocity = 0.0

[[shape]]
name = "floor"
at = { body = "ground", at = [0.0, -0.05] }
geometry = { type = "cuboid", half_extents = [0.5, 0.05] }

[[shape]]
name = "sphere"
at = { body = "ball", at = [0.0, 0.0] }
geometry = { type = "ball", radius = 0.01 }

[[clearance]]
name = "drop"
type = "contact"
shapes = ["floor", "sphere"]
normal = { law = "hertz", stiffness = 1.5e10, damping = "hc-exact", restitution = 0.3 }

[output]
t_end = 0.1
intervals = 200
"#;

/// The frames of a GIF as full RGB images (each frame's changed rectangle laid over the
/// previous image; transparent pixels keep it).
fn gif_frames(path: &Path) -> (usize, usize, Vec<Vec<[u8; 3]>>) {
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut dec = opts.read_info(std::fs::File::open(path).unwrap()).unwrap();
    let (w, h) = (dec.width() as usize, dec.height() as usize);
    let mut image = vec![[0u8; 3]; w * h];
    let mut out = Vec::new();
    while let Some(f) = dec.read_next_frame().unwrap() {
        let (fl, ft, fw) = (f.left as usize, f.top as usize, f.width as usize);
        for (k, px) in f.buffer.chunks_exact(4).enumerate() {
            if px[3] > 0 {
                let (x, y) = (fl + k % fw, ft + k / fw);
                image[y * w + x] = [px[0], px[1], px[2]];
            }
        }
        out.push(image.clone());
    }
    (w, h, out)
}

/// `clr animate` draws the contact shapes moved with their parts: the ground floor grey, the
/// ball in the part colour where the drawing's transform puts them, and both edged red while
/// the contact element touches (not in the first frame, 5 mm apart; in the last, at rest).
#[test]
fn animate_draws_the_contact_shapes() {
    let out = scratch("animate-shapes");
    let model = out.join("drop.toml");
    std::fs::write(&model, BALL_DROP).unwrap();
    let d = out.join("run");
    let o = clr(&[
        "run",
        model.to_str().unwrap(),
        "--out",
        d.to_str().unwrap(),
        "--quiet",
        "--no-figures",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let gif = out.join("drop.gif");
    let o = clr(&[
        "animate",
        d.to_str().unwrap(),
        "--gif",
        gif.to_str().unwrap(),
        "--fps",
        "10",
        "--duration",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, frames) = gif_frames(&gif);
    assert_eq!(frames.len(), 10);
    // the view: the shapes' outlines over the frames span x ∈ [−0.5, 0.5] m,
    // y ∈ [−0.1, 0.025] m (the ball's top in the first frame); margin 32 px (4 % of 800);
    // scale (800 − 2·32) / 1 m = 736 px/m; the drawing 0.125·736 = 92 px high, the image the
    // least height, 200 px, the drawing centred in it: the bottom y = −0.1 m at 54 px up
    assert_eq!((w, h), (800, 200));
    let (scale, bottom) = (736.0, 54.0);
    let px = |x: f64, y: f64| {
        let c = 32.0 + (x + 0.5) * scale;
        let r = h as f64 - (bottom + (y + 0.1) * scale);
        (c.floor() as usize, r.floor() as usize)
    };
    let at = |f: usize, (x, y): (usize, usize)| frames[f][y * w + x];
    let white = [255u8, 255, 255];
    // first frame: the floor's centre (0, −0.05) grey (fill or hatch), the ball's centre
    // (0, 0.015) in the light part colour (blue), above the ball nothing
    let floor = at(0, px(0.0, -0.05));
    assert_ne!(floor, white, "no floor at its centre");
    let grey = |c: [u8; 3]| c.iter().max().unwrap() - c.iter().min().unwrap() < 30;
    assert!(grey(floor), "floor not grey: {floor:?}");
    let ball = at(0, px(0.0, 0.015));
    assert!(
        ball[2] as i32 > ball[0] as i32 + 30,
        "ball not in the part colour: {ball:?}"
    );
    assert_eq!(at(0, px(0.0, 0.035)), white, "something above the ball");
    // the floor does not move; the ball has come down 5 mm onto it by the last frame: the gap
    // between them in the first frame (y = 2 mm, pixel row 70, clear of the ball's edge ending
    // at 69.5 and the floor's starting at 71.6) is the ball in the last
    assert_eq!(at(9, px(0.0, -0.05)), floor);
    assert_eq!(at(0, px(0.0, 0.002)), white, "no gap under the ball");
    assert_ne!(at(9, px(0.0, 0.002)), white, "no ball at rest on the floor");
    // edged red (the contact colour) only while in contact
    let red = |f: usize| {
        frames[f]
            .iter()
            .filter(|c| c[0] > 180 && c[1] < 90 && c[2] < 90)
            .count()
    };
    assert_eq!(red(0), 0, "red edges 5 mm apart");
    assert!(red(9) > 100, "no red edge in contact: {}", red(9));
}

/// The finding-map options of `clr study` are refused, with the reason, for a study that is not
/// a finding map, --merge is refused beside --points/--shard, and --retry-failed without --resume
/// (every input used or refused).
#[test]
fn study_map_options_are_refused_where_they_do_not_apply() {
    let o = clr(&["study", "guide_friction", "--points", "3"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("finding maps only"), "{}", stderr(&o));
    let dir = scratch("map_merge_refused");
    let o = clr(&[
        "study",
        "guide_findings_map",
        "--points",
        "4",
        "--merge",
        dir.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("without --points"), "{}", stderr(&o));
    // --resume of a folder holding no map is refused before anything runs
    let o = clr(&[
        "study",
        "dual_guide_findings_map",
        "--points",
        "4",
        "--resume",
        dir.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("to resume from"), "{}", stderr(&o));
    // --retry-failed means nothing without --resume
    let o = clr(&["study", "flap_findings_map", "--retry-failed"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--resume"), "{}", stderr(&o));
}

/// `clr sweep` of a spatial model file: each point's results.csv is bit for bit the `clr run`
/// of the file with the same `--set` (the sweep clones the spatial description and applies the
/// override as the run does), and the points differ (the override is used).
#[test]
fn a_spatial_sweep_point_is_the_run_with_its_override() {
    let dir = scratch("spatial_sweep");
    let top = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models/examples/heavy_top.toml")
        .display()
        .to_string();
    let sweep = dir.join("sweep");
    let o = clr(&[
        "sweep",
        &top,
        "--t-end",
        "0.05",
        "--vary",
        "body.top.mass=0.5,0.8",
        "--no-figures",
        "--keep",
        "series",
        "-q",
        "--out",
        sweep.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut points = Vec::new();
    for (k, mass) in ["0.5", "0.8"].iter().enumerate() {
        let run = dir.join(format!("run{k}"));
        let set = format!("body.top.mass={mass}");
        let o = clr(&[
            "run",
            &top,
            "--t-end",
            "0.05",
            "--set",
            &set,
            "-q",
            "--out",
            run.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let point = std::fs::read(sweep.join(format!("point-{k:05}/results.csv"))).unwrap();
        assert!(
            point == std::fs::read(run.join("results.csv")).unwrap(),
            "point {k} differs from `clr run --set {set}`"
        );
        points.push(point);
    }
    assert!(points[0] != points[1], "the mass override was not used");
}

/// `clr slurm sweep <args> --help` shows the options of the sweep it forwards, without writing
/// or submitting anything.
#[test]
fn slurm_sweep_help_shows_the_sweep_options() {
    let o = clr(&["slurm", "sweep", "slider_crank", "--help"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("--vary") && out.contains("--keep"), "{out}");
    assert!(!std::path::Path::new("clr-sweep/slurm").exists());
}
