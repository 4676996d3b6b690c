//! End-to-end tests of issue 14 ("nothing silent") on the `clr` binary: initial conditions
//! solved, corrected and refused; the force application of a clearance joint; unused inputs
//! refused; one tolerance rule.

mod common;

use std::path::{Path, PathBuf};

use common::clr;

/// A fresh scratch folder under the target dir.
fn scratch(name: &str) -> PathBuf {
    common::scratch_in("nothing_silent", name)
}

fn shipped_slider_crank() -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/slider_crank.toml");
    std::fs::read_to_string(p).unwrap()
}

/// The shipped slider–crank with `t_end` shortened and `edit` applied to its text.
fn slider_crank_file(dir: &Path, edit: impl Fn(String) -> String) -> String {
    let text = edit(shipped_slider_crank())
        .replace("t_end = 0.1\n", "t_end = 0.002\n")
        .replace("intervals = 1000\n", "intervals = 20\n");
    let p = dir.join("model.toml");
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

/// Run `file` into `dir/out`; (exit code, stderr, summary.json when written).
fn run(dir: &Path, file: &str, extra: &[&str]) -> (i32, String, Option<serde_json::Value>) {
    common::run_in(dir, file, extra)
}

/// The rod's angular velocity line of the shipped file (the second `angular_velocity`).
const ROD_OMEGA: &str = "angular_velocity = -87.26646259971649\n";

/// Left out, the rod's angular velocity is solved from the constraints: at θ = 0 the pin
/// velocity ω_c·r (vertical) must equal the rod's v_y + ω_r·(−L/2) with v_y = ω_c·r/2 given,
/// so ω_r = −ω_c·r/L (closed form; 5000 rpm, r = 0.05 m, L = 0.3 m → −87.2665 rad/s). The
/// given velocities are kept, the note names the solved coordinate.
#[test]
fn left_out_velocity_is_solved_from_the_constraints_and_reported() {
    let dir = scratch("solved");
    let file = slider_crank_file(&dir, |t| {
        assert!(t.contains(ROD_OMEGA));
        t.replacen(ROD_OMEGA, "", 1)
    });
    let (code, err, summary) = run(&dir, &file, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("solved from the constraints: rod.omega"),
        "{err}"
    );
    let s = summary.unwrap();
    let ic = &s["initial_conditions"]["bodies"];
    let omega_c = 5000.0 * 2.0 * std::f64::consts::PI / 60.0;
    let expect = -omega_c * 0.05 / 0.3;
    let rod = &ic["rod"]["omega"];
    assert_eq!(rod["status"], "solved");
    let got = rod["assembled"].as_f64().unwrap();
    assert!(
        (got - expect).abs() <= 1e-9 * expect.abs(),
        "{got} vs {expect}"
    );
    // the given crank speed and rod velocity stay (fixed coordinates, 1e-9 relative)
    for (body, c) in [("crank", "omega"), ("rod", "vy"), ("crank", "vy")] {
        let e = &ic[body][c];
        assert_eq!(e["status"], "given", "{body}.{c}: {e}");
    }
    assert_eq!(s["initial_conditions"]["solved"], 1);
    assert_eq!(s["initial_conditions"]["corrected"], 0);
}

/// A given value that does not satisfy the constraints is corrected and reported by default,
/// and refused with its location under `initial_conditions = "exact"`.
#[test]
fn inconsistent_given_velocity_is_reported_or_refused_in_exact_mode() {
    let dir = scratch("corrected");
    let wrong = "angular_velocity = -72.4\n";
    let file = slider_crank_file(&dir, |t| t.replacen(ROD_OMEGA, wrong, 1));
    let (code, err, summary) = run(&dir, &file, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("given values changed"), "{err}");
    assert!(err.contains("rod.omega"), "{err}");
    let s = summary.unwrap();
    assert!(s["initial_conditions"]["corrected"].as_u64().unwrap() >= 1);
    assert_eq!(
        s["initial_conditions"]["bodies"]["rod"]["omega"]["status"],
        "corrected"
    );

    let exact = slider_crank_file(&dir, |t| {
        t.replacen(ROD_OMEGA, wrong, 1).replacen(
            "[solver]\n",
            "[solver]\ninitial_conditions = \"exact\"\n",
            1,
        )
    });
    let (code, err, _) = run(&dir, &exact, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("initial_conditions = \"exact\""), "{err}");
    assert!(err.contains("field `body[1]."), "{err}");
    assert!(err.contains("rod.omega from -7.240000000e1"), "{err}");

    // the consistent shipped file passes in exact mode
    let fine = slider_crank_file(&dir, |t| {
        t.replacen(
            "[solver]\n",
            "[solver]\ninitial_conditions = \"exact\"\n",
            1,
        )
    });
    let (code, err, _) = run(&dir, &fine, &[]);
    assert_eq!(code, 0, "{err}");
}

/// A free journal spinning in a free housing, no gravity, no ground: the only external
/// moment is zero, so the angular momentum about the origin is conserved exactly by the
/// equations when action and reaction are collinear.
fn free_journal(application: &str) -> String {
    free_journal_with(
        application,
        0.009,
        r#"{ law = "hertz", stiffness = 1e9, restitution = 0.8, damping = "lankarani-nikravesh" }"#,
    )
}

/// [`free_journal`] with the journal radius (m) and the `normal` table given.
fn free_journal_with(application: &str, journal_radius: f64, normal: &str) -> String {
    format!(
        r#"[model]
name = "free_journal"

[[body]]
name = "housing"
mass = 1.0
inertia = 0.01
position = [0.0, 0.0]
angle = 0.0
velocity = [0.0, 0.0]
angular_velocity = 5.0

[[body]]
name = "pin"
mass = 0.2
inertia = 1e-4
position = [0.0008, 0.0]
angle = 0.0
velocity = [0.0, 0.5]
angular_velocity = -20.0

[[clearance]]
name = "C"
type = "revolute"
bearing = {{ body = "housing", at = [0.0, 0.0] }}
journal = {{ body = "pin", at = [0.0, 0.0] }}
bearing_radius = 0.01
journal_radius = {journal_radius}
force_application = "{application}"
normal = {normal}
friction = {{ law = "coulomb", mu = 0.3, v_reg = 1e-3 }}

[solver]
rtol = 1e-9
atol = 1e-12

[output]
t_end = 0.05
intervals = 200
"#
    )
}

/// Angular momentum about the origin of the recorded rows, kg·m²/s.
fn angular_momentum(csv: &str) -> Vec<f64> {
    let mut lines = csv.lines();
    let names: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|h| h.split(" [").next().unwrap().to_string())
        .collect();
    let k = |n: &str| names.iter().position(|c| c == n).unwrap();
    let bodies = [("housing", 1.0, 0.01), ("pin", 0.2, 1e-4)];
    lines
        .map(|l| {
            let r: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
            bodies
                .iter()
                .map(|(b, m, i)| {
                    let g = |c: &str| r[k(&format!("{b}.{c}"))];
                    i * g("omega") + m * (g("x") * g("vy") - g("y") * g("vx"))
                })
                .sum()
        })
        .collect()
}

/// `force_application` per clearance joint: `common_point` conserves the angular momentum of a
/// free system with friction (collinear action and reaction; to 1e-9 of its value, the
/// integration tolerance), `contact_points` (Flores et al. 2004) lets the friction pair,
/// δ apart, change it; both are echoed in summary.json.
#[test]
fn force_application_per_joint_common_point_conserves_angular_momentum() {
    let mut drift = Vec::new();
    for app in ["common_point", "contact_points"] {
        let dir = scratch(app);
        let file = dir.join("model.toml");
        std::fs::write(&file, free_journal(app)).unwrap();
        let (code, err, summary) = run(&dir, file.to_str().unwrap(), &[]);
        assert_eq!(code, 0, "{err}");
        let s = summary.unwrap();
        assert_eq!(s["parameters"]["clearance"][0]["force_application"], app);
        let onsets = s["solver"]["contact_onsets"].as_u64().unwrap();
        assert!(onsets >= 2, "{app}: {onsets} onsets");
        let l = angular_momentum(&std::fs::read_to_string(dir.join("out/results.csv")).unwrap());
        let l0 = l[0];
        drift.push(l.iter().fold(0.0f64, |a, x| a.max((x - l0).abs())) / l0.abs());
    }
    assert!(drift[0] < 1e-9, "common_point drift {:e}", drift[0]);
    assert!(
        drift[1] > 100.0 * drift[0].max(1e-12),
        "contact_points drift {:e} vs common_point {:e}",
        drift[1],
        drift[0]
    );
}

/// Inputs that nothing would use are refused at their field: NDF settings under
/// `method = "dopri5"` (from the file and from `--set`).
#[test]
fn settings_the_method_does_not_use_are_refused() {
    let dir = scratch("unused");
    let file = slider_crank_file(&dir, |t| {
        t.replacen("[solver]\n", "[solver]\nmax_order = 5\n", 1)
    });
    let (code, err, _) = run(&dir, &file, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("solver.max_order"), "{err}");
    assert!(err.contains("does not use"), "{err}");
    let file = slider_crank_file(&dir, |t| t);
    let (code, err, _) = run(&dir, &file, &["--set", "solver.jacobian=finite_difference"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("solver.jacobian"), "{err}");
}

/// A parameter the chosen law does not use is refused at its field; the stiffness a law
/// derives from materials and radii is echoed under `derived`, against the closed form of
/// Flores et al. (2004) K = (4/3)E*√(R_iR_j/(R_i − R_j)) (steel, 10 / 9.9 mm: 1.50888205e11
/// N/m^1.5, docs/contact-laws; 1e-8 relative).
#[test]
fn unused_law_parameter_is_refused_and_derived_stiffness_is_echoed() {
    let dir = scratch("law");
    let steel = "{ youngs_modulus = 207e9, poisson_ratio = 0.3 }";
    let normal = |extra: &str| {
        format!(
            "{{ law = \"hertz-internal-cylinder\", restitution = 0.8, damping = \
             \"lankarani-nikravesh\", bearing_material = {steel}, journal_material = {steel}{extra} }}"
        )
    };
    let file = dir.join("model.toml");
    let text = free_journal_with("common_point", 0.0099, &normal(", stiffness = 1e5"))
        .replace("t_end = 0.05", "t_end = 0.001");
    std::fs::write(&file, text).unwrap();
    let (code, err, _) = run(&dir, file.to_str().unwrap(), &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("clearance[0].normal.stiffness"), "{err}");
    assert!(err.contains("does not use `stiffness`"), "{err}");

    // the Hertz-type presets have no axial length: `length` is refused for `LN`, used by `Modified`
    let preset = |label: &str| {
        format!(
            "{{ law = \"preset\", preset = \"{label}\", restitution = 0.8, length = 0.01, \
             bearing_material = {steel}, journal_material = {steel} }}"
        )
    };
    for (label, ok) in [("LN", false), ("Modified", true)] {
        // the pin 0.08 mm off centre: inside the 0.1 mm clearance of this journal
        let text = free_journal_with("common_point", 0.0099, &preset(label))
            .replace("t_end = 0.05", "t_end = 0.001")
            .replace("position = [0.0008, 0.0]", "position = [0.00008, 0.0]");
        std::fs::write(&file, text).unwrap();
        let (code, err, _) = run(&dir, file.to_str().unwrap(), &[]);
        assert_eq!(code == 0, ok, "{label}: {err}");
        if !ok {
            assert!(err.contains("clearance[0].normal.length"), "{err}");
        }
    }

    let text = free_journal_with("common_point", 0.0099, &normal(""))
        .replace("t_end = 0.05", "t_end = 0.001")
        .replace("position = [0.0008, 0.0]", "position = [0.00008, 0.0]");
    std::fs::write(&file, text).unwrap();
    let (code, err, summary) = run(&dir, file.to_str().unwrap(), &[]);
    assert_eq!(code, 0, "{err}");
    let d = &summary.unwrap()["parameters"]["derived"]["C.normal"];
    let k = d["stiffness"].as_f64().unwrap();
    assert!((k / 1.50888205e11 - 1.0).abs() < 1e-8, "K = {k}");
    assert_eq!(d["exponent"].as_f64(), Some(1.5));
}

/// One tolerance rule: without `atol` a file runs at atol = 1e-3·rtol (echoed as derived);
/// `--rtol` replaces a file's `atol` by the rule with a note; `--atol` sets it.
#[test]
fn one_tolerance_rule_for_files_and_the_command_line() {
    let dir = scratch("tolerance");
    let file = dir.join("model.toml");
    let text = free_journal("common_point")
        .replace("atol = 1e-12\n", "")
        .replace("t_end = 0.05", "t_end = 0.001");
    std::fs::write(&file, &text).unwrap();
    let (code, err, summary) = run(&dir, file.to_str().unwrap(), &[]);
    assert_eq!(code, 0, "{err}");
    let s = summary.unwrap();
    let atol = &s["parameters"]["derived"]["solver.atol"]["value"];
    assert!(
        (atol.as_f64().unwrap() / 1e-12 - 1.0).abs() < 1e-12,
        "{atol}"
    );

    let with_atol = text.replace("rtol = 1e-9\n", "rtol = 1e-9\natol = 1e-10\n");
    std::fs::write(&file, &with_atol).unwrap();
    let (code, err, s) = run(&dir, file.to_str().unwrap(), &["--rtol", "1e-6"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("also sets atol = 1e-3·rtol = 1e-9"), "{err}");
    let solver = &s.unwrap()["parameters"]["solver"];
    assert_eq!(solver["atol"].as_f64(), Some(1e-3 * 1e-6));
    let (code, err, s) = run(
        &dir,
        file.to_str().unwrap(),
        &["--rtol", "1e-7", "--atol", "3e-11"],
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        s.unwrap()["parameters"]["solver"]["atol"].as_f64(),
        Some(3e-11)
    );
}

/// impacts.csv against a closed form: a 1 kg journal (free, no gravity) crosses the 0.1 mm
/// radial clearance of a ground-fixed bearing at v0 = 0.5 m/s and hits a linear, undamped
/// contact spring K = 1e7 N/m: the contact is half a period of an undamped oscillator, so
/// onset = c/v0, duration = π√(m/K), δ_max = v0√(m/K), F_max = K·δ_max and the impact velocity
/// is v0 (tolerances 1e-6 relative, 1e-4 on the duration, as clr-mbd's unit test).
#[test]
fn impacts_csv_matches_the_closed_form_of_a_single_journal_impact() {
    let dir = scratch("impacts");
    let (m, k, v0, c) = (1.0f64, 1e7f64, 0.5f64, 1e-4f64);
    let text = format!(
        r#"[[body]]
name = "journal"
mass = {m}
inertia = 1e-3
position = [0.0, 0.0]
angle = 0.0
velocity = [{v0}, 0.0]
angular_velocity = 0.0

[[clearance]]
name = "C"
type = "revolute"
bearing = {{ body = "ground", at = [0.0, 0.0] }}
journal = {{ body = "journal", at = [0.0, 0.0] }}
bearing_radius = 0.01
journal_radius = {jr}
normal = {{ law = "linear", stiffness = {k}, restitution = 1.0, damping = "none" }}

[solver]
method = "dopri5"
rtol = 1e-12
atol = 1e-15

[output]
t_end = 0.0015
intervals = 10
"#,
        jr = 0.01 - c
    );
    let file = dir.join("model.toml");
    std::fs::write(&file, text).unwrap();
    let (code, err, summary) = run(&dir, file.to_str().unwrap(), &[]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(dir.join("out/impacts.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').skip(1).map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 1, "{csv}");
    let r = &rows[0];
    let w = (k / m).sqrt();
    let expect = [
        (r[0], c / v0, 1e-6, "onset"),
        (r[1], v0, 1e-6, "impact velocity"),
        (r[2], k * v0 / w, 1e-6, "peak force"),
        (r[4], v0 / w, 1e-6, "max penetration"),
        (r[7], std::f64::consts::PI / w, 1e-4, "duration"),
    ];
    for (got, want, tol, what) in expect {
        assert!(
            (got / want - 1.0).abs() < tol,
            "{what}: {got:e} vs {want:e}"
        );
    }
    let s = summary.unwrap();
    assert_eq!(s["impacts"]["C"]["count"], 1, "{}", s["impacts"]);
}

/// A built-in parameter the model's other parameters make unused is refused where it is given:
/// `axial_length` with the slider–crank's `LN` preset (only Wang and Modified use it), by
/// `--set` and in a built-in file; `clr export --builtin` leaves it out, with the reason.
#[test]
fn unused_builtin_parameter_is_refused() {
    let dir = scratch("builtin_unused");
    let out = dir.join("out");
    let o = clr(&[
        "run",
        "slider_crank",
        "--set",
        "axial_length=0.02",
        "-q",
        "--out",
    ]
    .into_iter()
    .chain([out.to_str().unwrap()])
    .collect::<Vec<_>>());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("`axial_length` is not used"), "{err}");
    let file = dir.join("b.toml");
    std::fs::write(
        &file,
        "[model]\nbuiltin = \"slider_crank\"\n\n[parameters]\naxial_length = 0.02\n",
    )
    .unwrap();
    let (code, err, _) = run(&dir, file.to_str().unwrap(), &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("b.toml:5:"), "{err}");
    assert!(err.contains("parameters.axial_length"), "{err}");
    let o = clr(&["export", "slider_crank", "--builtin"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("#   axial_length: normal_law = \"LN\""),
        "{text}"
    );
    assert!(!text.contains("\naxial_length ="), "{text}");
}

/// `--series parquet` on a sweep whose points keep no series (`--keep summary`) is not dropped
/// in silence: a note says that only failed points keep series, and what to give instead.
#[test]
fn series_format_without_kept_series_is_noted() {
    let dir = scratch("series_note");
    let file = slider_crank_file(&dir, |t| t);
    let out = dir.join("sweep");
    let o = clr(&[
        "sweep",
        &file,
        "--vary",
        "solver.rtol=1e-6",
        "--series",
        "parquet",
        "--no-figures",
        "--out",
        out.to_str().unwrap(),
    ]);
    let e = String::from_utf8_lossy(&o.stderr).to_string();
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("--series parquet: with --keep summary only the failed points keep"),
        "{e}"
    );
    assert!(!out.join("point-00000/results.parquet").exists());
}
