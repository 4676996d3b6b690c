//! Model files never panic: every line of the example files deleted in turn, and every number
//! replaced by hostile values (negative, zero, huge, NaN, infinity, a string, an array, a
//! table), gives either a valid model or a located error (file and line), never a panic.

use std::path::Path;

use clr_sim::spec::{load_str, Loaded};

const FILES: [&str; 7] = [
    "pendulum.toml",
    "wan_slider_crank.toml",
    "manipulator.toml",
    "journal_bearing.toml",
    "slider_crank.toml",
    "cantilever.toml",
    "slider_in_guide.toml",
];

const HOSTILE: [&str; 9] = [
    "-1.0", "0", "0.0", "1e308", "nan", "-inf", "\"x\"", "[1.0]", "{}",
];

/// Load (and build, when valid) one text; returns a description of what went wrong, if any.
fn check(name: &str, text: &str) -> Result<(), String> {
    let r = std::panic::catch_unwind(|| match load_str(name, text, &[]) {
        Ok(Loaded::Generic(spec)) => match spec.build() {
            Ok(_) => Ok(()),
            Err(e) if !e.message.is_empty() => Ok(()),
            Err(e) => Err(format!("empty build error {e:?}")),
        },
        Ok(Loaded::Spatial(spec)) => match spec.build() {
            Ok(_) => Ok(()),
            Err(e) if !e.message.is_empty() => Ok(()),
            Err(e) => Err(format!("empty build error {e:?}")),
        },
        Ok(Loaded::Builtin { .. }) => Ok(()),
        Err(e) if e.line.is_some() && !e.message.is_empty() => Ok(()),
        Err(e) => Err(format!("error without a line: {e}")),
    });
    match r {
        Ok(x) => x,
        Err(_) => Err("panicked".to_string()),
    }
}

/// Byte ranges of the numbers of a line (outside comments and strings).
fn numbers(line: &str) -> Vec<(usize, usize)> {
    let code = line.split('#').next().unwrap_or("");
    let b = code.as_bytes();
    let mut out = Vec::new();
    let mut k = 0;
    let mut in_str = false;
    while k < b.len() {
        let c = b[k];
        if c == b'"' {
            in_str = !in_str;
        }
        let starts = !in_str
            && (c.is_ascii_digit() || (c == b'-' && b.get(k + 1).is_some_and(u8::is_ascii_digit)))
            && (k == 0 || !(b[k - 1].is_ascii_alphanumeric() || b[k - 1] == b'_'));
        if starts {
            let s = k;
            k += 1;
            while k < b.len() && (b[k].is_ascii_alphanumeric() || b"+-._".contains(&b[k])) {
                k += 1;
            }
            out.push((s, k));
        } else {
            k += 1;
        }
    }
    out
}

#[test]
fn mutated_model_files_never_panic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let mut failures = Vec::new();
    let mut cases = 0;
    for f in FILES {
        let text = std::fs::read_to_string(dir.join(f)).unwrap();
        // the file itself is valid
        assert!(
            matches!(load_str(f, &text, &[]), Ok(Loaded::Generic(_))),
            "{f} is not valid"
        );
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let mut deleted = lines.clone();
            deleted.remove(i);
            cases += 1;
            if let Err(e) = check(f, &deleted.join("\n")) {
                failures.push(format!("{f}: line {} deleted: {e}", i + 1));
            }
            for (s, t) in numbers(line) {
                for h in HOSTILE {
                    let mut m = lines.clone();
                    let new = format!("{}{h}{}", &line[..s], &line[t..]);
                    m[i] = &new;
                    cases += 1;
                    if let Err(e) = check(f, &m.join("\n")) {
                        failures.push(format!("{f}:{}: `{new}`: {e}", i + 1));
                    }
                }
            }
        }
    }
    assert!(cases > 1000, "only {cases} mutations");
    eprintln!("{cases} mutated files checked");
    assert!(
        failures.is_empty(),
        "{} of {cases} mutations failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A file of the older format (a clearance joint without `type`) still reads, into the same
/// description as the current form, and the upgrade is reported as a note; `--rtol` also sets
/// `atol` = 1e-3·rtol as the built-in models do, and says so.
#[test]
fn older_files_are_upgraded_and_every_change_is_noted() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let text = std::fs::read_to_string(dir.join("slider_crank.toml")).unwrap();
    let old = text.replacen("name = \"B\"\ntype = \"revolute\"\n", "name = \"B\"\n", 1);
    assert_ne!(old, text, "the clearance's type line was not found");
    let read = |t: &str| match load_str("f.toml", t, &[]) {
        Ok(Loaded::Generic(s)) => s,
        other => panic!("{other:?}"),
    };
    let (new, upgraded) = (read(&text), read(&old));
    assert!(new.notes.is_empty(), "{:?}", new.notes);
    assert_eq!(upgraded.notes.len(), 1, "{:?}", upgraded.notes);
    assert!(
        upgraded.notes[0].contains("clearance[0]"),
        "{:?}",
        upgraded.notes
    );
    assert_eq!(
        toml::to_string(new.desc()).unwrap(),
        toml::to_string(upgraded.desc()).unwrap()
    );
    let mut s = read(&text);
    s.set_rtol(1e-6).unwrap();
    assert_eq!((s.options.rtol, s.options.atol), (1e-6, 1e-9));
    assert!(s.notes.iter().any(|n| n.contains("atol")), "{:?}", s.notes);
}

/// A sweep point is the base model's description cloned and changed, not the file read again:
/// after the file is gone, points still resolve, and each changes only its own copy.
#[test]
fn sweep_points_clone_the_description_without_reading_the_file() {
    use clr_sim::spec::run::{resolve, Job};
    use clr_sim::spec::{parse_assignment, Assignment};
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pendulum.toml");
    let dir = std::env::temp_dir().join(format!("clr-sweep-clone-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("pendulum.toml");
    std::fs::copy(&src, &file).unwrap();
    let base = resolve(file.to_str().unwrap(), &[], Some(0.1), None).unwrap();
    std::fs::remove_file(&file).unwrap();
    let set = |text: &str| -> Vec<Assignment> { vec![parse_assignment(text).unwrap()] };
    let mass = |j: &Job| match j {
        Job::Generic(s) => s.desc().bodies[0].mass.unwrap_or(f64::NAN),
        _ => panic!("a model file resolves to a generic job"),
    };
    let a = base
        .with_overrides(&set("body.rod.mass=2"), Some(0.1), None)
        .unwrap();
    let b = base
        .with_overrides(&set("body.rod.mass=3"), Some(0.1), None)
        .unwrap();
    assert_eq!((mass(&base), mass(&a), mass(&b)), (1.0, 2.0, 3.0));
    // a refused value is still located and named
    let e = base
        .with_overrides(&set("body.rod.mas=2"), Some(0.1), None)
        .unwrap_err();
    assert!(e.to_string().contains("did you mean `mass`"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `law = "lugre"` in a model file: `tests/data/lugre_block.toml` loads through `load_str`,
/// builds and runs (a block pushed past breakaway: bristles deflect by about F/(σ0·m g) while it
/// sticks, then it slides with the Coulomb level of friction), and no line deleted or number
/// replaced by a hostile value makes it panic.
#[test]
fn lugre_model_file_parses_and_runs() {
    let f = "lugre_block.toml";
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(f),
    )
    .unwrap();
    let spec = match load_str(f, &text, &[]) {
        Ok(Loaded::Generic(s)) => s,
        other => panic!("{other:?}"),
    };
    let mut built = spec.build().unwrap();
    assert_eq!(built.model.n_bristle_states(), 4);
    let r = built.model.simulate(&built.options).unwrap();
    let col = |c: &str| r.column(c).unwrap_or_else(|| panic!("no column {c}"));
    let (t, z, push) = (col("t"), col("guide.lugre_z"), 1.962);
    // sticking at 10 ms (F = push/2 < μ_s m g): z follows F/(σ0 m g) within 20 % (measured
    // −11 %: part of F goes into the bristle damping σ1·ż·F_N while loading, and the pre-sliding
    // oscillator, ζ ≈ 0.15, rings)
    let k = t.iter().position(|&t| (t - 0.01).abs() < 1e-9).unwrap();
    let z_stick = 0.5 * push / (1e5 * 9.81);
    assert!(
        (z[k] - z_stick).abs() < 0.2 * z_stick,
        "z = {} vs {z_stick}",
        z[k]
    );
    // sliding at the end, friction at μ_c + (μ_s − μ_c)e^{−(v/v_s)²} of the normal force
    let vx = *col("block.vx").last().unwrap();
    let mu =
        -col("guide.friction_force").last().unwrap() / col("guide.normal_force").last().unwrap();
    let mu_ss = 0.10 + 0.05 * (-(vx / 1e-3).powi(2)).exp();
    eprintln!(
        "lugre_block: z(10 ms) = {:e} vs {z_stick:e}; final vx = {vx}, μ = {mu} vs {mu_ss}",
        z[k]
    );
    assert!(vx > 1e-3, "not sliding: vx = {vx}");
    assert!((mu - mu_ss).abs() < 1e-3, "μ = {mu} vs {mu_ss}");
    assert!(
        z.iter().all(|z| z.abs() <= 0.15 / 1e5 * (1.0 + 1e-9)),
        "{z:?}"
    );
    // the bristle states have no analytic Jacobian rows: the run says it differenced instead
    assert!(
        r.notes.iter().any(|n| n.contains("finite_difference")),
        "{:?}",
        r.notes
    );
    // hostile edits never panic
    let lines: Vec<&str> = text.lines().collect();
    let mut failures = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let mut deleted = lines.clone();
        deleted.remove(i);
        if let Err(e) = check(f, &deleted.join("\n")) {
            failures.push(format!("line {} deleted: {e}", i + 1));
        }
        for (s, e) in numbers(line) {
            for h in HOSTILE {
                let new = format!("{}{h}{}", &line[..s], &line[e..]);
                let mut m = lines.clone();
                m[i] = &new;
                if let Err(e) = check(f, &m.join("\n")) {
                    failures.push(format!("{}: `{new}`: {e}", i + 1));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `[solver] jacobian`, `max_order` and `linear_solver` reach the run: the pendulum of
/// tests/data/pendulum.toml with the finite-difference Newton matrix, order ≤ 2 and sparse
/// factorizations takes more steps than with the defaults and ends at the same state (both
/// within the closed-form period's tolerance of the file: rtol 1e-10), with no note (nothing
/// was chosen for the user).
#[test]
fn solver_settings_reach_the_run() {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pendulum.toml"),
    )
    .unwrap()
    .replace("t_end = 3.5", "t_end = 0.5");
    let run = |extra: &str| {
        let t = text.replace("atol = 1e-12", &format!("atol = 1e-12\n{extra}"));
        let spec = match load_str("pendulum.toml", &t, &[]) {
            Ok(Loaded::Generic(s)) => s,
            other => panic!("{other:?}"),
        };
        let mut built = spec.build().unwrap();
        built.model.simulate(&built.options).unwrap()
    };
    let base = run("");
    let other = run("jacobian = \"finite_difference\"\nmax_order = 2\nlinear_solver = \"sparse\"");
    assert!(
        other.stats.accepted > 2 * base.stats.accepted,
        "{:?} vs {:?}",
        other.stats,
        base.stats
    );
    assert!(base.notes.is_empty() && other.notes.is_empty());
    let th = |r: &clr_mbd::Results| *r.column("rod.theta").unwrap().last().unwrap();
    assert!(
        (th(&base) - th(&other)).abs() < 1e-7,
        "{} vs {}",
        th(&base),
        th(&other)
    );
}

fn data_text(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(name)).unwrap()
}

/// A damping factor given as the normal law (`law = "lankarani-nikravesh"`, as papers name
/// "Hertz with Lankarani–Nikravesh damping") is refused with how to write it: the damping
/// factor's name in `damping` beside an elastic law, and the preset that is the same law.
#[test]
fn a_damping_factor_given_as_the_law_says_where_it_goes() {
    let text = data_text("tests/data/slider_crank.toml");
    assert!(text.contains("law = \"preset\"\npreset = \"LN\""));
    for given in ["lankarani-nikravesh", "ln", "Lankarani_Nikravesh"] {
        let t = text.replace(
            "law = \"preset\"\npreset = \"LN\"",
            &format!("law = \"{given}\""),
        );
        let e = match load_str("sc.toml", &t, &[]) {
            Err(e) => e,
            Ok(_) => panic!("law = {given:?} was accepted"),
        };
        let m = e.to_string();
        assert_eq!(e.field, "clearance[0].normal.law", "{m}");
        for part in [
            "`lankarani-nikravesh` is a damping factor, not an elastic law",
            "law = \"hertz\" with stiffness = K (N/m^1.5) and damping = \"lankarani-nikravesh\"",
            "law = \"preset\" with preset = \"LN\"",
        ] {
            assert!(m.contains(part), "`{part}` missing from: {m}");
        }
        // the hint is exactly right: the law it names is accepted
        let fixed = t.replace(
            &format!("law = \"{given}\""),
            "law = \"hertz-internal-cylinder\"\ndamping = \"lankarani-nikravesh\"",
        );
        assert!(load_str("sc.toml", &fixed, &[]).is_ok(), "{fixed}");
    }
}

/// A value a `--set` brings is refused at that `--set`, not at the file's line of the value it
/// replaced; the file's own errors keep their line whatever the overrides.
#[test]
fn set_errors_name_the_set_argument() {
    use clr_sim::spec::parse_assignment;
    let text = data_text("tests/data/slider_crank.toml");
    let err = |sets: &[&str], t: &str| {
        let a: Vec<_> = sets.iter().map(|s| parse_assignment(s).unwrap()).collect();
        match load_str("sc.toml", t, &a) {
            Err(e) => e,
            Ok(_) => panic!("{sets:?} accepted"),
        }
    };
    // a value of the wrong type, and one the model refuses when compiled
    for (set, message) in [
        ("clearance.B.bearing_radius=abc", "expected f64"),
        (
            "clearance.B.journal_radius=0.02",
            "make journal_radius smaller",
        ),
    ] {
        let e = err(&["solver.rtol=1e-8", set], &text);
        let m = e.to_string();
        assert_eq!(e.file, format!("--set '{set}'"), "{m}");
        assert!(e.line.is_none() && m.contains(message), "{m}");
        assert!(
            m.starts_with(&format!("--set '{set}': field `clearance[0]")),
            "{m}"
        );
    }
    // the file's own error stays at its line
    let broken = text.replace("journal_radius = 0.0095", "journal_radius = 0.02");
    let e = err(&["solver.rtol=1e-8"], &broken);
    assert_eq!(e.file, "sc.toml", "{e}");
    assert!(e.line.is_some(), "{e}");
}

/// No note of a run has a run of spaces (a string continuation that kept the next line's
/// indentation once put 18 in one): the shipped model files, the flexible slider–crank, and a
/// pendulum whose given velocity the assembly corrects (the note that had them).
#[test]
fn notes_have_no_runs_of_spaces() {
    use clr_sim::spec::run::{execute, resolve, resolve_text};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<_> = std::fs::read_dir(root.join("models"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files.push(root.join("tests/data/flexible_slider_crank.toml"));
    let mut notes = Vec::new();
    for f in &files {
        let job = resolve(f.to_str().unwrap(), &[], Some(1e-4), None).unwrap();
        let o = execute(&job, Some(1e-4), None, None).unwrap();
        let warnings = o.results.warnings.iter().map(ToString::to_string);
        notes.extend(
            o.notes
                .iter()
                .cloned()
                .chain(warnings)
                .map(|n| (f.clone(), n)),
        );
    }
    // a pendulum released with an angular velocity its pin does not allow with its given
    // centre velocity: the assembly changes a given value and says so
    let text = data_text("tests/data/pendulum.toml")
        .replace("angular_velocity = 0.0", "angular_velocity = 1.0");
    let job = resolve_text("pendulum.toml", &text, &[], Some(1e-3), None).unwrap();
    let o = execute(&job, Some(1e-3), None, None).unwrap();
    let corrected = o
        .notes
        .iter()
        .find(|n| n.contains("given values changed"))
        .unwrap_or_else(|| panic!("no correction note in {:?}", o.notes));
    assert!(
        corrected.contains("constraints (initial_conditions"),
        "{corrected}"
    );
    notes.extend(o.notes.iter().map(|n| (root.join("pendulum"), n.clone())));
    for (f, n) in &notes {
        assert!(
            !n.contains("  "),
            "{}: note with a run of spaces: {n:?}",
            f.display()
        );
    }
}

/// A misspelt field or element type in a spatial model file is refused at its line with the
/// closest valid name, as in planar files.
#[test]
fn spatial_typos_get_a_suggestion() {
    let top = include_str!("../models/examples/heavy_top.toml");
    for (from, to, want) in [
        (
            "principal_inertia =",
            "principle_inertia =",
            "did you mean `principal_inertia`?",
        ),
        (
            "type = \"spherical\"",
            "type = \"sperical\"",
            "did you mean `spherical`?",
        ),
    ] {
        let text = top.replacen(from, to, 1);
        let Err(e) = load_str("top.toml", &text, &[]) else {
            panic!("`{to}` was accepted");
        };
        assert!(e.message.contains(want), "{e}");
        assert!(e.line.is_some(), "{e}");
    }
}

/// A shape clr-contact refuses (here a compound nested in a compound) is placed at its
/// `[[shape]]`'s line, with clr-contact's reason and without the item name repeated.
#[test]
fn a_refused_spatial_shape_is_placed_at_its_line() {
    let text = include_str!("../models/examples/spatial_ball_on_box.toml").replacen(
        "geometry = { type = \"cuboid\", half_extents = [0.5, 0.5, 0.05] }",
        "geometry = { type = \"compound\", parts = [{ at = [0.0, 0.0, 0.0], geometry = { type = \
         \"compound\", parts = [] } }] }",
        1,
    );
    // refused when read (the reader compiles) or when built
    let e = match load_str("ball.toml", &text, &[]) {
        Err(e) => e,
        Ok(Loaded::Spatial(spec)) => match spec.build() {
            Err(e) => e,
            Ok(_) => panic!("a nested compound was accepted"),
        },
        Ok(_) => panic!("not read as a spatial model"),
    };
    assert_eq!(e.line, Some(21), "{e}");
    assert!(e.message.contains("compound parts must be"), "{e}");
    assert!(!e.message.starts_with("floor.geometry"), "{e}");
}

/// A spatial body thrown up, no joint: `[[metric]]` items of a spatial file against the closed
/// form of free fall (z = v0·t − g t²/2, vz = v0 − g t). The integrator reproduces a quadratic
/// up to its error control (rtol 1e-10 here), so the values agree to 1e-8 relative; the time
/// and height of the top are taken on the rows (every 1 ms), so within g/2·(0.5 ms)² of the
/// closed form and 0.5 ms of its time. A twin metric and an unknown column are refused.
#[test]
fn spatial_metrics_against_free_fall() {
    use clr_sim::spec::run::{execute, resolve_text};
    let (g, v0, t_end) = (9.81, 2.0, 0.5);
    let text = format!(
        "[model]\nname = \"throw\"\nspace = \"spatial\"\ngravity = [0.0, 0.0, -{g}]\n\n\
         [[body]]\nname = \"ball\"\nmass = 0.2\nprincipal_inertia = [1e-4, 1e-4, 1e-4]\n\
         velocity = [0.0, 0.0, {v0}]\nvelocity_frame = \"world\"\n\n\
         [[metric]]\nname = \"vz_end\"\nof = \"ball.vz\"\nstatistic = \"final\"\n\n\
         [[metric]]\nname = \"rise\"\nof = \"ball.z\"\nstatistic = \"change\"\n\n\
         [[metric]]\nname = \"vz_integral\"\nof = \"ball.vz\"\nstatistic = \"integral\"\n\n\
         [[metric]]\nname = \"top\"\nof = \"ball.z\"\nstatistic = \"max\"\n\n\
         [[metric]]\nname = \"top_time\"\nof = \"ball.z\"\nstatistic = \"time_of_max\"\n\n\
         [solver]\nrtol = 1e-10\n\n[output]\nt_end = {t_end}\nintervals = 500\n"
    );
    let job = resolve_text("throw.toml", &text, &[], None, None).unwrap();
    let o = execute(&job, None, None, None).unwrap();
    let m = |name: &str| {
        let m = o.metrics.iter().find(|m| m.name == name).unwrap();
        (m.value, m.unit.clone())
    };
    let near = |name: &str, want: f64, tol: f64, unit: &str| {
        let (v, u) = m(name);
        assert!((v - want).abs() <= tol, "{name} = {v}, closed form {want}");
        assert_eq!(u, unit, "{name}");
    };
    let fall = v0 * t_end - g * t_end * t_end / 2.0;
    near(
        "vz_end",
        v0 - g * t_end,
        1e-8 * (v0 - g * t_end).abs(),
        "m/s",
    );
    near("rise", fall, 1e-8 * fall.abs(), "m");
    near("vz_integral", fall, 1e-8 * fall.abs(), "m");
    let (t_top, h) = (v0 / g, 0.5e-3);
    near("top", v0 * v0 / (2.0 * g), g / 2.0 * h * h + 1e-9, "m");
    near("top_time", t_top, h, "s");

    let twin = text.replace(
        "statistic = \"final\"\n",
        "statistic = \"final\"\ntwin = true\n",
    );
    let Err(e) = load_str("throw.toml", &twin, &[]) else {
        panic!("a twin metric was accepted in a spatial file");
    };
    assert!(e.message.contains("no ideal-joint twin"), "{e}");
    assert!(e.line.is_some(), "{e}");
    let typo = text.replace(
        "of = \"ball.vz\"\nstatistic = \"final\"",
        "of = \"ball.wz2\"\nstatistic = \"final\"",
    );
    let Err(e) = load_str("throw.toml", &typo, &[]) else {
        panic!("an unknown column was accepted");
    };
    assert!(
        e.message.contains("ball.wz2") && e.message.contains("ball.wz"),
        "{e}"
    );
}

/// `[[measure]]` of a spatial file against closed forms: a rotor spinning freely at ω about its
/// symmetry axis z (no gravity) and a cart translating at u along x whose centre of mass sits
/// 0.2 m from its frame origin. A point L along the rotor's x axis moves on a circle; the
/// cart's origin seen from the rotor's frame is R_z(−ωt)·(u t, 1, 0), differentiated once and
/// twice by hand; the distance between the two points and its rate follow. The integrator runs
/// at rtol 1e-10; the kinematics are exact functions of the recorded columns, so the measures
/// agree with the closed forms to 1e-7.
#[test]
fn spatial_measures_against_rotation_and_translation() {
    use clr_sim::spec::run::{execute, resolve_text};
    let (w, u, l) = (10.0_f64, 0.3_f64, 0.5_f64);
    let text = format!(
        "[model]\nname = \"kin\"\nspace = \"spatial\"\n\n\
         [[body]]\nname = \"rotor\"\nmass = 1.0\nprincipal_inertia = [1e-3, 1e-3, 2e-3]\n\
         angular_velocity = [0.0, 0.0, {w}]\nangular_velocity_frame = \"world\"\n\
         velocity = [0.0, 0.0, 0.0]\nvelocity_frame = \"world\"\n\n\
         [[body]]\nname = \"cart\"\nmass = 2.0\nprincipal_inertia = [1e-3, 1e-3, 1e-3]\n\
         centre_of_mass = [0.2, 0.0, 0.0]\nposition = [0.0, 1.0, 0.0]\n\
         velocity = [{u}, 0.0, 0.0]\nvelocity_frame = \"world\"\n\
         angular_velocity = [0.0, 0.0, 0.0]\nangular_velocity_frame = \"world\"\n\n\
         [[measure]]\ntype = \"position\"\nname = \"tip\"\nat = {{ body = \"rotor\", at = [{l}, 0.0, 0.0] }}\n\n\
         [[measure]]\ntype = \"velocity\"\nname = \"tip\"\nat = {{ body = \"rotor\", at = [{l}, 0.0, 0.0] }}\n\n\
         [[measure]]\ntype = \"acceleration\"\nname = \"tip\"\nat = {{ body = \"rotor\", at = [{l}, 0.0, 0.0] }}\n\n\
         [[measure]]\ntype = \"position\"\nname = \"seen\"\nat = {{ body = \"cart\" }}\nframe = \"rotor\"\n\n\
         [[measure]]\ntype = \"velocity\"\nname = \"seen\"\nat = {{ body = \"cart\" }}\nframe = \"rotor\"\n\n\
         [[measure]]\ntype = \"acceleration\"\nname = \"seen\"\nat = {{ body = \"cart\" }}\nframe = \"rotor\"\n\n\
         [[measure]]\ntype = \"distance\"\nname = \"gap\"\na = {{ body = \"rotor\", at = [{l}, 0.0, 0.0] }}\nb = {{ body = \"cart\" }}\n\n\
         [[measure]]\ntype = \"distance\"\nname = \"same\"\na = {{ body = \"cart\" }}\nb = {{ body = \"cart\" }}\n\n\
         [[metric]]\nname = \"gap_max\"\nof = \"gap.distance\"\nstatistic = \"max\"\n\n\
         [solver]\nrtol = 1e-10\n\n[output]\nt_end = 0.5\nintervals = 200\n"
    );
    let job = resolve_text("kin.toml", &text, &[], None, None).unwrap();
    let o = execute(&job, None, None, None).unwrap();
    assert!(o.error.is_none(), "{:?}", o.error);
    let col = |c: &str| {
        o.results
            .column(c)
            .unwrap_or_else(|| panic!("no column {c}"))
    };
    let unit = |c: &str| o.units[o.results.columns.iter().position(|n| n == c).unwrap()].clone();
    assert_eq!(
        [
            unit("tip.x"),
            unit("tip.vx"),
            unit("seen.az"),
            unit("gap.distance_rate")
        ],
        ["m", "m/s", "m/s^2", "m/s"]
    );
    let t = col("t");
    let mut worst = 0.0_f64;
    let mut check = |c: &str, f: &dyn Fn(f64) -> f64| {
        for (k, v) in col(c).iter().enumerate() {
            let e = (v - f(t[k])).abs();
            assert!(e <= 1e-7, "{c} at t = {}: {v} against {}", t[k], f(t[k]));
            worst = worst.max(e);
        }
    };
    let (s, c) = (|t: f64| (w * t).sin(), |t: f64| (w * t).cos());
    check("tip.x", &|t| l * c(t));
    check("tip.y", &|t| l * s(t));
    check("tip.vx", &|t| -l * w * s(t));
    check("tip.vy", &|t| l * w * c(t));
    check("tip.ax", &|t| -l * w * w * c(t));
    check("tip.ay", &|t| -l * w * w * s(t));
    check("tip.z", &|_| 0.0);
    check("seen.x", &|t| u * t * c(t) + s(t));
    check("seen.y", &|t| -u * t * s(t) + c(t));
    check("seen.vx", &|t| u * c(t) - u * t * w * s(t) + w * c(t));
    check("seen.vy", &|t| -u * s(t) - u * t * w * c(t) - w * s(t));
    check("seen.ax", &|t| {
        -2.0 * u * w * s(t) - u * t * w * w * c(t) - w * w * s(t)
    });
    check("seen.ay", &|t| {
        -2.0 * u * w * c(t) + u * t * w * w * s(t) - w * w * c(t)
    });
    let gap = |t: f64| ((u * t - l * c(t)).powi(2) + (1.0 - l * s(t)).powi(2)).sqrt();
    check("gap.distance", &gap);
    check("gap.distance_rate", &|t| {
        let (dx, dy) = (u * t - l * c(t), 1.0 - l * s(t));
        (dx * (u + l * w * s(t)) + dy * (-l * w * c(t))) / gap(t)
    });
    assert!(worst > 0.0, "the columns are not all exact");
    // a point's distance from itself: 0, and its rate 0 (not 0/0), as the planar measure
    for c in ["same.distance", "same.distance_rate"] {
        assert!(col(c).iter().all(|v| *v == 0.0), "{c}");
    }
    let m = o.metrics.iter().find(|m| m.name == "gap_max").unwrap();
    assert_eq!(
        m.value,
        col("gap.distance").iter().fold(f64::MIN, |a, v| a.max(*v))
    );

    // a point given in millimetres (500 for 0.5 m) runs, with a warning at its field; the
    // point in metres raises none (the reach is 30 times the mechanism's size, as planar)
    let far = |o: &clr_sim::spec::run::Outcome| {
        (o.results.warnings.iter().map(ToString::to_string))
            .find(|w| w.contains("lengths are in metres"))
    };
    assert_eq!(far(&o), None);
    let mm = text.replacen(
        &format!("at = [{l}, 0.0, 0.0]"),
        "at = [500.0, 0.0, 0.0]",
        1,
    );
    let job = resolve_text("kin.toml", &mm, &[], None, None).unwrap();
    let w = far(&execute(&job, None, None, None).unwrap()).expect("no warning for 500 m");
    assert!(w.contains("tip.at") && w.contains("5.000e2 m"), "{w}");

    // refusals at their line: an unknown body, a frame that is no body, an axis, a name
    // whose column the run writes already
    for (from, to, want) in [
        (
            "at = { body = \"cart\" }\nframe",
            "at = { body = \"crt\" }\nframe",
            "no body `crt`",
        ),
        (
            "frame = \"rotor\"",
            "frame = \"rotr\"",
            "no body `rotr` to take the frame of",
        ),
        (
            "b = { body = \"cart\" }",
            "b = { body = \"cart\", axis = [1.0, 0.0, 0.0] }",
            "no axis",
        ),
        ("name = \"tip\"", "name = \"cart\"", "writes already"),
    ] {
        let bad = text.replacen(from, to, 1);
        let Err(e) = load_str("kin.toml", &bad, &[]) else {
            panic!("`{to}` was accepted");
        };
        assert!(e.message.contains(want), "{to}: {e}");
        assert!(e.line.is_some(), "{e}");
    }
}
