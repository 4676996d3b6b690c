//! Spatial shape contact (`[[shape]]`, `[[clearance]] type = "contact"` in a spatial model):
//! refusals at the field, and a short drop of a ball on a ground box against free fall and the
//! energy balance. The long checks (rebound heights, incline, wheel ratio) are the verify cases
//! `contact.spatial.shapes.*`.

use clr_mbd::spatial::SpatialDesc;
use clr_mbd::{SimOptions, SolverKind};

/// The shipped example, dropped from 20 mm straight down.
fn base() -> String {
    include_str!("../../../models/examples/spatial_ball_on_box.toml")
        .replacen(
            "position = [0.0, 0.0, 0.11]",
            "position = [0.0, 0.0, 0.03]",
            1,
        )
        .replacen(
            "velocity = [0.2, 0.0, 0.0]",
            "velocity = [0.0, 0.0, 0.0]",
            1,
        )
}

/// The path and message of reading and compiling `text`.
fn error(text: &str) -> (String, String) {
    let desc = match SpatialDesc::from_toml_table(text.parse().expect("toml")) {
        Ok(d) => d,
        Err(e) => return (e.path, e.message),
    };
    match desc.compile() {
        Ok(_) => panic!("compiled: {text}"),
        Err(clr_mbd::MbdError::Invalid { path, message }) => (path, message),
        Err(clr_mbd::MbdError::Contact { item, source }) => (item, source.to_string()),
        Err(e) => (String::new(), e.to_string()),
    }
}

#[test]
fn refusals_name_the_field() {
    let cases: [(&str, &str, &str, &str); 7] = [
        // (replace, with, expected path, expected words)
        (
            r#"shapes = ["floor", "sphere"]"#,
            r#"shapes = ["flor", "sphere"]"#,
            "drop.shapes[0]",
            "did you mean `floor`",
        ),
        (
            r#"shapes = ["floor", "sphere"]"#,
            r#"shapes = ["sphere", "sphere"]"#,
            "drop.shapes",
            "same body",
        ),
        (
            r#"type = "ball", radius = 0.01"#,
            r#"type = "ball", radius = -0.01"#,
            "sphere.geometry",
            "radius",
        ),
        (
            r#"type = "ball", radius = 0.01"#,
            r#"type = "ball", radius = 0.01, radus = 1.0"#,
            "shape[1].geometry",
            "radus",
        ),
        (
            r#"law = "coulomb", mu = 0.2, v_reg = 1e-4"#,
            r#"law = "lugre", mu_s = 0.2, mu_c = 0.1, v_s = 1e-3, sigma0 = 1e5, sigma1 = 300, sigma2 = 0.4"#,
            "drop.friction.law",
            "LuGre",
        ),
        (
            r#"law = "hertz", stiffness"#,
            r#"law = "liu", stiffness"#,
            "drop.normal.law",
            "hertz, power or linear",
        ),
        (
            r#"at = { body = "ball", at = [0.0, 0.0, 0.0] }"#,
            r#"at = { body = "ball", at = [0.0, 0.0, 0.0], axis = [0.0, 0.0, 1.0] }"#,
            "sphere.at.axis",
            "orientation",
        ),
    ];
    let base = base();
    for (from, to, path, words) in cases {
        assert!(base.contains(from), "{from}");
        let (p, m) = error(&base.replacen(from, to, 1));
        assert_eq!(p, path, "{m}");
        assert!(m.contains(words), "{p}: {m}");
    }
}

/// A ball dropped from 20 mm above the box: the first located impact velocity is √(2gh) (free
/// fall, to the integration tolerance: 1e-6 relative), the ball rebounds, and the energy balance
/// closes to 1e-6 of the initial energy (exact δ̇ of the signed distance, module docs of
/// `spatial/shape_contact.rs`).
#[test]
fn ball_drop_impact_velocity_and_energy() {
    let desc = SpatialDesc::from_toml_table(base().parse().expect("toml")).expect("desc");
    let mut m = desc.compile().expect("compile");
    let opts = SimOptions::span(0.0, 0.08, 40)
        .tolerances(1e-9, 1e-12)
        .solver(SolverKind::Ndf);
    let r = m.simulate(&opts).expect("run");
    let v = r.impacts.first().expect("an impact").impact_velocity;
    let exact = (2.0f64 * 9.81 * 0.02).sqrt();
    assert!((v - exact).abs() < 1e-6 * exact, "{v} vs {exact}");
    let vz = r.column("ball.vz").expect("vz");
    assert!(*vz.last().expect("rows") > 0.0, "the ball rebounds");
    let bal = r.column("energy.balance").expect("balance");
    let drift = bal.iter().map(|b| (b - bal[0]).abs()).fold(0.0, f64::max);
    assert!(drift < 1e-6 * bal[0], "energy drift {drift} J");
    assert!(r.columns.iter().any(|c| c == "drop.ez"));
}

/// A ball radius written in millimetres (10 for 10 mm) on the example's 32.7 g ball is flagged at
/// the shape's geometry: its bounding radius √3·10 m is 2.7e3 times the ball's radius of gyration
/// √(2/5)·0.01 m
/// (threshold `MAX_SHAPE_TO_GYRATION` = 30); the metre value (2.7) is not.
#[test]
fn a_shape_size_in_millimetres_is_flagged() {
    let mm = base()
        .replacen("radius = 0.01 }", "radius = 10.0 }", 1)
        .replacen(
            "position = [0.0, 0.0, 0.03]",
            "position = [0.0, 0.0, 10.03]",
            1,
        );
    let opts = SimOptions::span(0.0, 1e-3, 2);
    let warnings = |text: &str| {
        let desc = SpatialDesc::from_toml_table(text.parse().expect("toml")).expect("desc");
        let r = desc
            .compile()
            .expect("compile")
            .simulate(&opts)
            .expect("run");
        r.warnings
    };
    let w = warnings(&mm);
    let found = w
        .iter()
        .find(|w| w.field == "sphere.geometry")
        .unwrap_or_else(|| panic!("no size finding in {w:?}"));
    assert!(
        found.message.contains("(10 mm is 0.01)"),
        "{}",
        found.message
    );
    let si = warnings(&base());
    assert!(!si.iter().any(|w| w.field == "sphere.geometry"), "{si:?}");
}
