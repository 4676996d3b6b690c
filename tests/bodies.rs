//! Issue 30, bodies from what users know and clearance 0 as the ideal joint, end to end
//! through the library (`clr_sim::spec::run`):
//! - the trial's four-bar written with `shape`, `material` and `between`
//!   (tests/data/four_bar_helpers.toml, nothing computed by hand) gives the results of the file
//!   with hand-computed masses, inertias and positions (tests/data/four_bar_hand.toml);
//! - what a body may not combine is refused at its field;
//! - a sweep of the journal radius that includes the bearing radius (clearance 0) runs, and its
//!   0 point is the same model with B written as an ideal revolute `[[joint]]`, bit for bit.

use std::sync::atomic::{AtomicBool, AtomicUsize};

use clr_sim::spec::run::{execute, resolve_text, Job};
use clr_sim::spec::sweep::{points, run_points, Axis};

const HAND: &str = include_str!("data/four_bar_hand.toml");
const HELPERS: &str = include_str!("data/four_bar_helpers.toml");

fn job(text: &str) -> Job {
    resolve_text("<test>", text, &[], None, None).expect("the model reads")
}

fn run(text: &str) -> clr_sim::mbd::Results {
    let o = execute(&job(text), None, None, None).expect("it runs");
    assert!(o.error.is_none(), "{:?}", o.error);
    o.results
}

/// Every column of `a` and `b` equal bit for bit (the same names, rows and values).
fn same_bits(a: &clr_sim::mbd::Results, b: &clr_sim::mbd::Results) -> bool {
    a.columns == b.columns
        && a.data.len() == b.data.len()
        && a.data
            .iter()
            .zip(&b.data)
            .all(|(x, y)| x.to_bits() == y.to_bits())
}

/// Written with `shape`, `material = "steel"` and `between`, the four-bar gets the masses,
/// inertias, positions and angles of the hand computation (the same formulas: m = ρLwt,
/// I = m(L² + w²)/12, midpoints and atan2 of the joint coordinates), so the two files are the
/// same model and their results are equal bit for bit: the largest difference is 0.
///
/// Why no looser tolerance: at the run's rtol = 1e-6, values that differ by one rounding (the
/// trial's script multiplied ρ·w·t·L and placed the centres at A + (L/2)(cos θ, sin θ)) change
/// the integrator's step sequence through the contact at B and move the contact force by ~1e-4
/// of its peak: a comparison of results at rounding level needs equal inputs, which the
/// helpers give. That the helpers' inputs equal such another hand computation to rounding is
/// checked on the inputs (below).
#[test]
fn the_four_bar_from_the_helpers_gives_the_hand_computed_results() {
    let (hand, helpers) = (run(HAND), run(HELPERS));
    assert!(same_bits(&helpers, &hand), "the helpers changed the run");
    // every computed value is reported once, in the run's notes
    let notes = helpers.notes.join("\n");
    for body in ["crank", "coupler", "rocker"] {
        let line = helpers
            .notes
            .iter()
            .filter(|n| n.starts_with(&format!("body `{body}`: bar")))
            .collect::<Vec<_>>();
        assert_eq!(line.len(), 1, "{notes}");
        for what in [
            "mass = ",
            "inertia = ",
            "centre of mass",
            "position = ",
            "angle = ",
        ] {
            assert!(line[0].contains(what), "{what} missing: {}", line[0]);
        }
    }
    assert!(notes.contains("mass = 5.495e-1 kg"), "{notes}");
}

/// The bodies of the helpers file against the trial script's own hand computation
/// (tests/user_model.rs: m = 7850·0.02·0.01·L, centres A + (L/2)(cos θ, sin θ) from the
/// closed-form angles, θ₄ from the rocker's closed form) with the width term of the bar
/// added: masses and inertias equal to a few roundings (4e-16 relative), positions and angles
/// to 1e-14 (m, rad): the script's closed-form angles are written with 15 significant digits.
#[test]
fn the_helpers_values_equal_the_trials_hand_computation_to_rounding() {
    const TH3: f64 = 0.548_147_899_238_721;
    const TH4: f64 = 1.915_155_650_511_03;
    let Job::Generic(spec) = job(HELPERS) else {
        panic!("a model file resolves to a generic job")
    };
    let hand = |l: f64, centre: [f64; 2], angle: f64| {
        let m = 7850.0 * 0.02 * 0.01 * l;
        (m, m * (l * l + 0.02 * 0.02) / 12.0, centre, angle)
    };
    let expected = [
        hand(0.1, [0.0, 0.05], std::f64::consts::FRAC_PI_2),
        hand(0.35, [0.175 * TH3.cos(), 0.1 + 0.175 * TH3.sin()], TH3),
        hand(0.3, [0.4 + 0.15 * TH4.cos(), 0.15 * TH4.sin()], TH4),
    ];
    for (b, (m, i, c, a)) in spec.desc().bodies.iter().zip(expected) {
        let r = b.resolve().unwrap();
        let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
        assert!(
            rel(r.mass, m) <= 4e-16,
            "{}: mass {} vs {m}",
            b.name,
            r.mass
        );
        assert!(
            rel(r.inertia, i) <= 4e-16,
            "{}: inertia {} vs {i}",
            b.name,
            r.inertia
        );
        let p = r.position.unwrap();
        let (dp, da) = (
            (p[0] - c[0]).abs().max((p[1] - c[1]).abs()),
            (r.angle.unwrap() - a).abs(),
        );
        eprintln!(
            "{}: mass {:.1e}, inertia {:.1e} relative; position {dp:.1e} m, angle {da:.1e} rad",
            b.name,
            rel(r.mass, m),
            rel(r.inertia, i)
        );
        assert!(dp <= 1e-14, "{}: {p:?} vs {c:?}", b.name);
        assert!(da <= 1e-14, "{}: angle {} vs {a}", b.name, r.angle.unwrap());
        assert_eq!(r.centre_of_mass, [0.0, 0.0]);
    }
}

/// The slender-rod inertia of the trial's hand script (I = mL²/12, no width term) is not the
/// inertia of a 20 mm wide bar: the helper's m(L² + w²)/12 is 4 % larger for the 0.1 m crank.
#[test]
fn the_bar_inertia_has_its_width_term() {
    let p = clr_sim::mbd::desc::inertia::cuboid(0.1, 0.02, 0.01, 7850.0).unwrap();
    let slender = p.mass * 0.1 * 0.1 / 12.0;
    assert!((p.inertia / slender - 1.04).abs() < 1e-12);
}

fn refused(text: &str) -> String {
    match resolve_text("<test>", text, &[], None, None)
        .and_then(|j| execute(&j, None, None, None).map(|_| ()))
    {
        Ok(()) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Replace the crank's body table of the helpers file by `crank`.
fn with_crank(crank: &str) -> String {
    let old = "shape = { bar = { width = 0.02, thickness = 0.01 } }\nmaterial = \"steel\"\n\
               between = [[0.0, 0.0], [0.0, 0.1]]\n";
    assert!(HELPERS.contains(old));
    HELPERS.replacen(old, crank, 1)
}

#[test]
fn what_a_body_may_not_combine_is_refused_at_its_field() {
    let shape = "shape = { bar = { width = 0.02, thickness = 0.01 } }\n";
    let between = "between = [[0.0, 0.0], [0.0, 0.1]]\n";
    let cases = [
        (
            format!("{shape}material = \"steel\"\n{between}mass = 0.157\n"),
            ["body[0].mass", "both given"],
        ),
        (
            format!("{shape}material = \"stel\"\n{between}"),
            ["body[0].material", "did you mean `steel`"],
        ),
        (
            format!("{shape}material = \"steel\"\ndensity = 7850.0\n{between}"),
            ["body[0].density", "both given"],
        ),
        (
            format!("{shape}density = 7850.0\n{between}position = [0.0, 0.05]\n"),
            ["body[0].position", "both given"],
        ),
        (
            format!(
                "shape = {{ bar = {{ length = 0.12, width = 0.02, thickness = 0.01 }} }}\n\
                 material = \"steel\"\n{between}"
            ),
            ["body[0].shape.bar.length", "differs from the distance"],
        ),
        (
            format!("{shape}material = \"steel\"\nposition = [0.0, 0.05]\nangle = 1.5\n"),
            ["body[0].shape.bar.length", "needs its `length`"],
        ),
        (
            format!("mass = 0.157\ninertia = 1e-4\nmaterial = \"steel\"\n{between}"),
            ["body[0].material", "only with `shape`"],
        ),
        (
            format!("{shape}material = \"steel\"\nbetween = [[0.0, 0.1], [0.0, 0.1]]\n"),
            ["body[0].between", "the same"],
        ),
    ];
    for (crank, expected) in cases {
        let e = refused(&with_crank(&crank));
        for x in expected {
            assert!(e.contains(x), "`{x}` not in: {e}\nfor\n{crank}");
        }
    }
}

/// The hand file with B written as an ideal revolute joint, the last `[[joint]]`.
fn with_ideal_b() -> String {
    let start = HAND.find("[[clearance]]").unwrap();
    let end = HAND.find("[solver]").unwrap();
    let mut text = HAND.to_string();
    text.replace_range(start..end, "");
    let joint = "[[joint]]\nname = \"B\"\ntype = \"revolute\"\n\
                 a = { body = \"rocker\", at = [0.15, 0.0] }\n\
                 b = { body = \"coupler\", at = [0.175, 0.0] }\n\n[[driver]]";
    text.replacen("[[driver]]", joint, 1)
}

/// `--vary clearance.B.journal_radius=0.01,0.0099` (clearance 0 and 0.1 mm) runs; the 0 point
/// says in its notes that B ran as an ideal revolute joint and its results are those of the
/// file with B as a `[[joint]]`, bit for bit (the same rows in the same order).
#[test]
fn a_sweep_with_clearance_0_holds_its_ideal_reference() {
    let axes = [Axis {
        name: "clearance.B.journal_radius".into(),
        values: vec![toml::Value::Float(0.01), toml::Value::Float(0.0099)],
    }];
    let pts = points(&job(HAND), &axes, (0, 1), None, None).expect("the points build");
    let (done, cancel) = (AtomicUsize::new(0), AtomicBool::new(false));
    let runs = run_points(&pts, None, None, Some(1), &done, &cancel).unwrap();
    let outcome = |k: usize| {
        let (o, _) = runs[k].as_ref().unwrap().as_ref().expect("the point runs");
        assert!(o.error.is_none(), "{:?}", o.error);
        // summary.json's derived values name the contact law only where a contact acts
        let derived = &o.parameters["derived"];
        assert_eq!(derived.get("B.normal").is_some(), k == 1, "{derived}");
        o.results.clone()
    };
    let (zero, clearance) = (outcome(0), outcome(1));
    assert!(
        zero.notes.iter().any(|n| n.starts_with(
            "clearance `B` is 0 (journal_radius = bearing_radius = 0.01 m): run as an ideal \
             revolute joint"
        )),
        "{:?}",
        zero.notes
    );
    assert!(zero.column("B.Fx").is_some() && zero.column("B.normal_force").is_none());
    assert!(clearance.column("B.normal_force").is_some());
    let ideal = run(&with_ideal_b());
    assert_eq!(zero.columns, ideal.columns);
    assert_eq!(zero.data.len(), ideal.data.len());
    let same = zero
        .data
        .iter()
        .zip(&ideal.data)
        .all(|(a, b)| a.to_bits() == b.to_bits());
    assert!(same, "clearance 0 differs from the ideal joint");
}

/// A translational clearance joint of clearance 0 (slider_height = guide_width) runs as the
/// ideal translational joint: the block of tests/data/slider_in_guide.toml, dropped inside a
/// guide as wide as itself, stays where it is put across the guide and slides freely along it.
#[test]
fn a_guide_without_clearance_is_an_ideal_translational_joint() {
    let text = include_str!("data/slider_in_guide.toml");
    let o = resolve_text(
        "<test>",
        text,
        &[clr_sim::spec::parse_assignment("clearance.guide.slider_height=0.02").unwrap()],
        Some(0.05),
        None,
    );
    let o = execute(&o.expect("reads"), Some(0.05), None, None).expect("runs");
    assert!(o.error.is_none(), "{:?}", o.error);
    let notes = o.results.notes.join("\n");
    assert!(
        notes.contains("run as an ideal translational joint"),
        "{notes}"
    );
    assert!(
        o.results.column("guide.Fx").is_some(),
        "{:?}",
        o.results.columns
    );
}

/// What needs a clearance is refused with clearance 0 (at its field), and a negative
/// clearance stays refused.
#[test]
fn clearance_0_refuses_what_needs_a_clearance() {
    let zero = HAND.replace("journal_radius = 0.0099", "journal_radius = 0.01");
    let with = |extra: &str| {
        zero.replace(
            "friction = { law = \"coulomb\", mu = 0.1 }\n",
            &format!("friction = {{ law = \"coulomb\", mu = 0.1 }}\n{extra}\n"),
        )
    };
    for (extra, field) in [
        (
            "initial_eccentricity = [1e-5, 0.0]",
            "clearance[0].initial_eccentricity",
        ),
        (
            "lubrication = { model = \"short_bearing\", viscosity = 0.04, length = 0.02, \
             film_threshold = 1e-6 }",
            "clearance[0].lubrication",
        ),
    ] {
        let e = refused(&with(extra));
        assert!(
            e.contains(field) && e.contains("ideal revolute joint"),
            "{e}"
        );
    }
    let e = refused(&HAND.replace("journal_radius = 0.0099", "journal_radius = 0.0101"));
    assert!(
        e.contains("clearance[0].journal_radius") && e.contains("must be positive"),
        "{e}"
    );
}
