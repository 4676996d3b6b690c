//! A worn bearing in a whole model: the clearance slider–crank (tests/data/slider_crank.toml)
//! with `bearing_wear` all zeros runs bit for bit as the circular joint (issue 17's requirement;
//! the contact-level check is the verify case `wear.profile.zero`), and a uniform wear depth h
//! behaves as a circular bearing of radius R_i + h (the same geometry; equal to rounding, so
//! compared at 1e-9 of the eccentricity scale).

use clr_sim::spec::run::{execute, resolve_text};

const SLIDER_CRANK: &str = include_str!("data/slider_crank.toml");

/// The model with `extra` appended to its clearance joint B (the file's last `[[clearance]]`
/// table before `[clearance.normal]`), the bearing radius `radius` (m) and, with `fixed_law`, a
/// Hertz law of given stiffness (the file's preset law takes its stiffness from the radii,
/// which would differ between a worn and a larger bearing).
fn with_b(extra: &str, radius: Option<&str>, fixed_law: bool) -> String {
    let mut text = SLIDER_CRANK.replace(
        "friction = { law = \"none\" }\n",
        &format!("friction = {{ law = \"none\" }}\n{extra}\n"),
    );
    if let Some(r) = radius {
        text = text.replace("bearing_radius = 0.01 ", &format!("bearing_radius = {r} "));
    }
    if fixed_law {
        let at = text.find("[clearance.normal]").unwrap();
        let end = text[at..].find("\n\n").map_or(text.len(), |k| at + k);
        text.replace_range(
            at..end,
            "[clearance.normal]\nlaw = \"hertz\"\nstiffness = 1e10\nrestitution = 0.9\ndamping = \"lankarani-nikravesh\"",
        );
    }
    assert_ne!(text, SLIDER_CRANK);
    text
}

fn run(text: &str) -> clr_sim::mbd::Results {
    let job = resolve_text("<test>", text, &[], Some(0.01), None).expect("the model reads");
    let o = execute(&job, Some(0.01), None, None).expect("it runs");
    assert!(o.error.is_none(), "{:?}", o.error);
    o.results
}

#[test]
fn a_bearing_with_zero_wear_runs_bit_for_bit_as_the_circular_joint() {
    let circular = run(SLIDER_CRANK);
    let zeros = format!("bearing_wear = [{}]", vec!["0.0"; 24].join(", "));
    let worn = run(&with_b(&zeros, None, false));
    assert_eq!(circular.columns, worn.columns);
    assert_eq!(circular.data.len(), worn.data.len());
    let same = circular
        .data
        .iter()
        .zip(&worn.data)
        .all(|(a, b)| a.to_bits() == b.to_bits());
    assert!(same, "a zero wear profile changed the run");
}

#[test]
fn a_uniformly_worn_bearing_is_a_larger_circle() {
    let h = 2e-5; // m
    let uniform = format!("bearing_wear = [{}]", vec![format!("{h:e}"); 16].join(", "));
    let worn = run(&with_b(&uniform, None, true));
    let larger = run(&with_b("", Some(&format!("{}", 0.01 + h)), true));
    let ex = |r: &clr_sim::mbd::Results| r.column("B.ex").unwrap();
    let (a, b) = (ex(&worn), ex(&larger));
    // the same contact geometry through different arithmetic: the runs agree to the
    // integrator's tolerance scale, not bit for bit (rtol 1e-7 on a 0.5 mm eccentricity)
    let tol = 1e-9;
    let n = a.len().min(b.len());
    let worst = (0..n).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max);
    assert!(worst < tol, "largest difference of B.ex {worst:e} m");
}
