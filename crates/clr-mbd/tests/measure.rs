//! `[[measure]]` against closed forms and independent formulations:
//!
//! - two bodies driven at constant speeds about one pin: position, velocity and acceleration of
//!   a point in the world and relative to the other body, the relative angle and its rates, and
//!   the distance to a point of the other body, against the closed forms of uniform rotation;
//! - a double pendulum: the velocity (acceleration) of a point, in the world and relative to a
//!   moving link, against central differences of its recorded position (velocity);
//! - a compound pendulum released from the horizontal: the pin reaction resolved in the rod's
//!   axes against Newton's law with ω² and α from the energy closed form;
//! - two free bodies joined by a spring–damper: linear momentum conserved to rounding and
//!   angular momentum to the integrator's tolerance, and equal to the sum from the body columns;
//! - the errors a user meets (a name clash, an unknown joint, a bad quantity, a misspelt key).

use clr_mbd::{ModelDesc, Results};

fn run(text: &str) -> Results {
    let desc = ModelDesc::from_toml_table(text.parse().unwrap()).unwrap();
    let mut m = desc.compile().unwrap();
    m.simulate(&desc.sim_options().unwrap()).unwrap()
}

fn col(r: &Results, name: &str) -> Vec<f64> {
    r.column(name)
        .unwrap_or_else(|| panic!("no column {name} in {:?}", r.columns))
}

fn compile_err(text: &str) -> String {
    match ModelDesc::from_toml_table(text.parse().unwrap()) {
        Err(e) => e.to_string(),
        Ok(d) => d.compile().err().expect("refused").to_string(),
    }
}

/// Crank (ω₁ = 7 rad/s) and disc (ω₂ = −3 rad/s) driven about one pin at the origin.
const TWO_ROTORS: &str = r#"
[[point]]
name = "origin"
body = "ground"
at = [0.0, 0.0]

[[body]]
name = "crank"
mass = 1.0
inertia = 0.1
position = [0.0, 0.0]
angle = 0.0

[[body]]
name = "disc"
mass = 2.0
inertia = 0.2
position = [0.0, 0.0]
angle = 0.0

[[joint]]
name = "pin_crank"
type = "revolute"
a = "origin"
b = { body = "crank", at = [0.0, 0.0] }

[[joint]]
name = "pin_disc"
type = "revolute"
a = "origin"
b = { body = "disc", at = [0.0, 0.0] }

[[driver]]
name = "motor_crank"
type = "angle"
body = "crank"
motion = { type = "linear", initial = 0.0, rate = 7.0 }

[[driver]]
name = "motor_disc"
type = "angle"
body = "disc"
motion = { type = "linear", initial = 0.0, rate = -3.0 }

[[measure]]
name = "tip"
type = "position"
at = { body = "crank", at = [0.5, 0.0] }

[[measure]]
name = "tip"
type = "velocity"
at = { body = "crank", at = [0.5, 0.0] }

[[measure]]
name = "tip"
type = "acceleration"
at = { body = "crank", at = [0.5, 0.0] }

[[measure]]
name = "seen"
type = "position"
at = { body = "crank", at = [0.5, 0.0] }
frame = "disc"

[[measure]]
name = "seen"
type = "velocity"
at = { body = "crank", at = [0.5, 0.0] }
frame = "disc"

[[measure]]
name = "seen"
type = "acceleration"
at = { body = "crank", at = [0.5, 0.0] }
frame = "disc"

[[measure]]
name = "rel"
type = "angle"
body = "crank"
relative_to = "disc"

[[measure]]
name = "rel"
type = "angular_velocity"
body = "crank"
relative_to = "disc"

[[measure]]
name = "rel"
type = "angular_acceleration"
body = "crank"
relative_to = "disc"

[[measure]]
name = "gap"
type = "distance"
a = { body = "crank", at = [0.5, 0.0] }
b = { body = "disc", at = [0.3, 0.0] }

[solver]
rtol = 1e-10
atol = 1e-12

[output]
t_end = 1.0
intervals = 200
"#;

#[test]
fn point_angle_and_distance_of_uniform_rotation_equal_the_closed_forms() {
    let r = run(TWO_ROTORS);
    let (l, l2, w1, w2) = (0.5, 0.3, 7.0, -3.0);
    let t = col(&r, "t");
    let c = |n: &str| col(&r, n);
    let (big_w, mut worst) = (w1 - w2, 0.0f64);
    let mut check = |got: f64, want: f64, scale: f64| worst = worst.max((got - want).abs() / scale);
    for (k, &t) in t.iter().enumerate() {
        let (s1, c1) = (w1 * t).sin_cos();
        // uniform rotation: r = L(cos, sin), v = Lω(−sin, cos), a = −Lω²(cos, sin)
        check(c("tip.x")[k], l * c1, l);
        check(c("tip.y")[k], l * s1, l);
        check(c("tip.vx")[k], -l * w1 * s1, l * w1);
        check(c("tip.vy")[k], l * w1 * c1, l * w1);
        check(c("tip.ax")[k], -l * w1 * w1 * c1, l * w1 * w1);
        check(c("tip.ay")[k], -l * w1 * w1 * s1, l * w1 * w1);
        // seen from the disc the tip turns at Ω = ω₁ − ω₂ (relative kinematics)
        let (s, co) = (big_w * t).sin_cos();
        check(c("seen.x")[k], l * co, l);
        check(c("seen.y")[k], l * s, l);
        check(c("seen.vx")[k], -l * big_w * s, l * big_w);
        check(c("seen.vy")[k], l * big_w * co, l * big_w);
        check(c("seen.ax")[k], -l * big_w * big_w * co, l * big_w * big_w);
        check(c("seen.ay")[k], -l * big_w * big_w * s, l * big_w * big_w);
        check(c("rel.angle")[k], big_w * t, 1.0);
        check(c("rel.omega")[k], big_w, big_w);
        check(c("rel.alpha")[k], 0.0, big_w * big_w);
        // law of cosines and its derivative
        let d = (l * l + l2 * l2 - 2.0 * l * l2 * co).sqrt();
        check(c("gap.distance")[k], d, l);
        check(c("gap.distance_rate")[k], l * l2 * big_w * s / d, l * big_w);
    }
    // the drivers hold θ exactly at position level and the rates follow from the linear
    // velocity and acceleration equations: measured 1.9e-15 relative, tolerance 1e-12
    assert!(worst < 1e-12, "largest relative error {worst:e}");
}

const DOUBLE_PENDULUM: &str = r#"
[model]
gravity = [0.0, -9.81]

[[point]]
name = "pivot"
body = "ground"
at = [0.0, 0.0]

[[body]]
name = "upper"
mass = 1.0
inertia = 0.0833
position = [0.5, 0.0]
angle = 0.0
velocity = [0.0, 0.0]
angular_velocity = 0.0

[[body]]
name = "lower"
mass = 0.5
inertia = 0.02
position = [1.0, -0.4]
angle = -1.5707963267948966
velocity = [0.0, 0.0]
angular_velocity = 0.0

[[joint]]
name = "shoulder"
type = "revolute"
a = "pivot"
b = { body = "upper", at = [-0.5, 0.0] }

[[joint]]
name = "elbow"
type = "revolute"
a = { body = "upper", at = [0.5, 0.0] }
b = { body = "lower", at = [-0.4, 0.0] }

[[measure]]
name = "hand"
type = "position"
at = { body = "lower", at = [0.4, 0.05] }

[[measure]]
name = "hand"
type = "velocity"
at = { body = "lower", at = [0.4, 0.05] }

[[measure]]
name = "hand"
type = "acceleration"
at = { body = "lower", at = [0.4, 0.05] }

[[measure]]
name = "local"
type = "position"
at = { body = "lower", at = [0.4, 0.05] }
frame = "upper"

[[measure]]
name = "local"
type = "velocity"
at = { body = "lower", at = [0.4, 0.05] }
frame = "upper"

[[measure]]
name = "local"
type = "acceleration"
at = { body = "lower", at = [0.4, 0.05] }
frame = "upper"

[solver]
rtol = 1e-11
atol = 1e-13

[output]
t_end = 0.5
intervals = 5000
"#;

#[test]
fn point_rates_equal_central_differences_of_the_recorded_motion() {
    let r = run(DOUBLE_PENDULUM);
    let t = col(&r, "t");
    let h = t[1] - t[0];
    // central differences on a uniform grid of h = 1e-4 s: truncation h²/6·|x'''| (|x'''| up
    // to ~1e3 m/s³ here, so ~2e-6) plus the dense output's interpolation error (rtol 1e-11)
    // amplified by 1/h; measured 2.2e-6 of the largest rate, tolerance 1e-5
    let mut worst = 0.0f64;
    for (p, v) in [
        ("hand.x", "hand.vx"),
        ("hand.y", "hand.vy"),
        ("hand.vx", "hand.ax"),
        ("hand.vy", "hand.ay"),
        ("local.x", "local.vx"),
        ("local.y", "local.vy"),
        ("local.vx", "local.ax"),
        ("local.vy", "local.ay"),
    ] {
        let (x, dx) = (col(&r, p), col(&r, v));
        let scale = dx.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(scale > 0.1, "{v} moves: {scale}");
        for k in 1..t.len() - 1 {
            let fd = (x[k + 1] - x[k - 1]) / (2.0 * h);
            worst = worst.max((fd - dx[k]).abs() / scale);
        }
    }
    assert!(worst < 1e-5, "largest relative difference {worst:e}");
    // in the upper link's frame the hand keeps its distance from the elbow (a rigid lower link):
    // |p − p_elbow| = |(0.4, 0.05) − (−0.4, 0)|
    let (lx, ly) = (col(&r, "local.x"), col(&r, "local.y"));
    let want = (0.8f64.powi(2) + 0.05f64.powi(2)).sqrt();
    for k in 0..t.len() {
        let d = (lx[k] - 0.5).hypot(ly[k]);
        assert!((d - want).abs() < 1e-8, "row {k}: {d} vs {want}");
    }
}

#[test]
fn pin_reaction_in_the_rod_axes_follows_newtons_law() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/pendulum.toml"
    ))
    .unwrap()
    .replace("t_end = 3.5\nintervals = 3500", "t_end = 1.0\nintervals = 400")
        + "\n[[measure]]\nname = \"pin_rod\"\ntype = \"reaction\"\njoint = \"pin\"\nframe = \"rod\"\n";
    let r = run(&text);
    let (m, ic, d, g) = (1.0, 1.0 / 12.0, 0.5, 9.81);
    let io = ic + m * d * d;
    let th = col(&r, "rod.theta");
    let th0 = th[0];
    let (fx, fy) = (col(&r, "pin_rod.Fx"), col(&r, "pin_rod.Fy"));
    let mut worst = 0.0f64;
    for k in 0..th.len() {
        // the centre of mass at pivot + d(cos θ, sin θ): energy ½ I_O ω² = m g d (sin θ₀ − sin θ),
        // I_O α = −m g d cos θ; its acceleration in the rod axes (−ω² d, α d); the rod's weight
        // in its axes m(−g sin θ, −g cos θ); the pin force F = m a − weight
        let w2 = 2.0 * m * g * d * (th0.sin() - th[k].sin()) / io;
        let alpha = -m * g * d * th[k].cos() / io;
        let want = [
            -m * w2 * d + m * g * th[k].sin(),
            m * alpha * d + m * g * th[k].cos(),
        ];
        worst = worst.max((fx[k] - want[0]).abs().max((fy[k] - want[1]).abs()) / (m * g));
    }
    // energy conserved to the integrator's tolerance (rtol 1e-10): measured 2.2e-10 of m g,
    // tolerance 1e-8
    assert!(worst < 1e-8, "largest error {worst:e} of m g");
    // and the world components rotate into these: |F| is the same
    let (wx, wy) = (col(&r, "pin.Fx"), col(&r, "pin.Fy"));
    for k in 0..th.len() {
        assert!((wx[k].hypot(wy[k]) - fx[k].hypot(fy[k])).abs() < 1e-12 * m * g * 10.0);
    }
}

const FREE_PAIR: &str = r#"
[[body]]
name = "a"
mass = 1.5
inertia = 0.02
position = [0.0, 0.0]
angle = 0.0
velocity = [0.3, -0.2]
angular_velocity = 2.0

[[body]]
name = "b"
mass = 0.7
inertia = 0.01
position = [0.4, 0.1]
angle = 0.5
velocity = [-0.1, 0.6]
angular_velocity = -1.0

[[force]]
name = "link"
type = "spring_damper"
a = { body = "a", at = [0.05, 0.0] }
b = { body = "b", at = [-0.05, 0.02] }
stiffness = 200.0
damping = 0.5
free_length = 0.3

[[measure]]
name = "momentum"
type = "momentum"
about = [0.1, -0.2]

[solver]
rtol = 1e-10
atol = 1e-12

[output]
t_end = 1.0
intervals = 100
"#;

#[test]
fn momentum_of_a_free_pair_is_conserved_and_equals_the_body_sum() {
    let r = run(FREE_PAIR);
    let (px, py, l) = (
        col(&r, "momentum.px"),
        col(&r, "momentum.py"),
        col(&r, "momentum.L"),
    );
    // p = Σ m v from the body columns, L about (0.1, −0.2) = Σ I ω + m (r − O) × v
    let c = |n: &str| col(&r, n);
    for k in [0, 57, px.len() - 1] {
        let mut want = [0.0; 3];
        for (b, m, i) in [("a", 1.5, 0.02), ("b", 0.7, 0.01)] {
            let (x, y, vx, vy) = (
                c(&format!("{b}.x"))[k] - 0.1,
                c(&format!("{b}.y"))[k] + 0.2,
                c(&format!("{b}.vx"))[k],
                c(&format!("{b}.vy"))[k],
            );
            want[0] += m * vx;
            want[1] += m * vy;
            want[2] += i * c(&format!("{b}.omega"))[k] + m * (x * vy - y * vx);
        }
        for (got, want) in [px[k], py[k], l[k]].iter().zip(want) {
            assert!((got - want).abs() < 1e-14, "row {k}: {got} vs {want}");
        }
    }
    // internal forces only: p is a linear invariant, kept to rounding by the integrator; L is
    // quadratic, kept to the integrator's tolerance (measured: p 1.6e-15, L 9.4e-11 kg·m²/s)
    let drift = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max((x - v[0]).abs()));
    assert!(
        drift(&px) < 1e-12 && drift(&py) < 1e-12,
        "{} {}",
        drift(&px),
        drift(&py)
    );
    assert!(drift(&l) < 1e-9, "angular momentum drift {:e}", drift(&l));
}

#[test]
fn measures_are_refused_with_what_to_change() {
    let base = TWO_ROTORS.split("[[measure]]").next().unwrap().to_string();
    let with = |m: &str| format!("{base}\n[[measure]]\n{m}\n[output]\nt_end = 0.1\n");
    // a measure named like a body would write its columns again
    let e = compile_err(&with(
        "name = \"crank\"\ntype = \"position\"\nat = \"origin\"",
    ));
    assert!(e.contains("crank.x") && e.contains("another name"), "{e}");
    let e = compile_err(&with(
        "name = \"r\"\ntype = \"reaction\"\njoint = \"pin_crnk\"",
    ));
    assert!(e.contains("pin_crnk") && e.contains("`pin_crank`"), "{e}");
    let e = compile_err(&with(
        "name = \"c\"\ntype = \"contact\"\nelement = \"B\"\nquantity = \"force\"",
    ));
    assert!(e.contains("normal_force"), "{e}");
    let e = compile_err(&with(
        "name = \"w\"\ntype = \"angular_velocity\"\nbody = \"crank\"\noffset = 1.0",
    ));
    assert!(
        e.contains("measure[0].offset") && e.contains("unknown field"),
        "{e}"
    );
    let e = compile_err(&with(
        "name = \"p\"\ntype = \"position\"\nat = \"origin\"\nframe = \"disk\"",
    ));
    assert!(e.contains("disk") && e.contains("p.frame"), "{e}");
    let e = compile_err(&with("name = \"p\"\ntype = \"position\"\natt = \"origin\""));
    assert!(e.contains("measure[0]") && e.contains("att"), "{e}");
    let e = compile_err(&with("name = \"e\"\ntype = \"energy\"\nterm = \"kinetik\""));
    assert!(e.contains("kinetik") && e.contains("work_in"), "{e}");
}

#[test]
fn measures_survive_the_model_file_round_trip() {
    let desc = ModelDesc::from_toml_table(TWO_ROTORS.parse().unwrap()).unwrap();
    let again = ModelDesc::from_toml_table(desc.to_toml().unwrap().parse().unwrap()).unwrap();
    assert_eq!(desc.measures, again.measures);
    assert_eq!(desc.measures.len(), 10);
}

/// tests/data/`file` as a table, with its `[output]` replaced by `output`.
fn data_file(file: &str, output: &str) -> toml::Table {
    let path = format!("{}/../../tests/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let mut doc: toml::Table = std::fs::read_to_string(path).unwrap().parse().unwrap();
    doc.insert(
        "output".into(),
        output.parse::<toml::Table>().unwrap().into(),
    );
    doc
}

#[test]
fn deviation_from_the_ideal_twin_equals_the_closed_form_slider_error() {
    // tests/data/slider_crank.toml (Flores: r = 0.05 m, l = 0.3 m, 5000 rpm, c = 0.5 mm) with
    // the slider's deviation from the ideal twin; the twin is the ideal slider–crank, whose
    // slider follows x(θ) = r cos θ + √(l² − r² sin² θ), θ = ωt, in closed form
    let mut doc = data_file("slider_crank.toml", "t_end = 0.01\nintervals = 1000\n");
    // with a metric of the twin's slider.x (the deviation is named like the body: the twin
    // still writes the body's columns)
    let extra: toml::Table = "[[measure]]\nname = \"slider\"\ntype = \"deviation\"\nof = [\"slider.x\"]\n\n[[metric]]\nname = \"ideal_x\"\nof = \"slider.x\"\nstatistic = \"max\"\ntwin = true\n\n[twin]\nintervals = 10000\n"
        .parse()
        .unwrap();
    doc.extend(extra);
    let desc = ModelDesc::from_toml_table(doc).unwrap();
    // the twin has no contact columns: a twin metric of one is refused
    let mut contact = desc.clone();
    contact.metrics[0].of = Some(clr_mbd::desc::metric::Columns::One("B.normal_force".into()));
    let e = contact.compile().err().expect("refused").to_string();
    assert!(
        e.contains("ideal twin writes no column `B.normal_force`"),
        "{e}"
    );
    let opts = desc.sim_options().unwrap();
    let mut r = desc.compile().unwrap().simulate(&opts).unwrap();
    clr_mbd::desc::twin::run_twin(&desc, &opts, &mut r).unwrap();
    let (t, x, e) = (col(&r, "t"), col(&r, "slider.x"), col(&r, "slider.error"));
    let (rc, l, w) = (0.05, 0.3, 5000.0 * std::f64::consts::PI / 30.0);
    let mut worst = 0.0f64;
    for k in 0..t.len() {
        let th = w * t[k];
        let ideal = rc * th.cos() + (l * l - (rc * th.sin()).powi(2)).sqrt();
        worst = worst.max((e[k] - (x[k] - ideal)).abs());
    }
    // the twin's own integration error plus linear interpolation over h = 1e-6 s (h²/8·|ẍ| with
    // |ẍ| ≤ rω²(1 + r/l) ≈ 1.6e4 m/s²: 2e-9 m), against a deviation of order c = 5e-4 m;
    // measured 4.0e-9 m (the file's rtol 1e-7), tolerance 2e-8 m
    assert!(worst < 2e-8, "largest difference {worst:e} m");
    assert!(
        e.iter().fold(0.0f64, |a, v| a.max(v.abs())) > 1e-4,
        "the clearance shows"
    );
    assert_eq!(r.unit("slider.error"), "m");
    assert!(
        r.notes.iter().any(|n| n.contains("ideal twin")),
        "{:?}",
        r.notes
    );
}

#[test]
fn the_twin_leaves_out_combinations_of_the_clearance_columns_it_lacks() {
    // Wan's slider–crank (Ambrósio friction in B): the moment δ·F_T of B's friction pair (a
    // product of B's columns) and a combination of it have nothing to read in the ideal twin,
    // where B is an ideal joint: the twin leaves both out and runs; a combination of columns
    // the twin writes stays. In the run the product equals B.penetration · B.friction_force to
    // the bit (one multiplication).
    let mut doc = data_file("wan_slider_crank.toml", "t_end = 0.02\nintervals = 200\n");
    let extra: toml::Table = r#"
[[measure]]
name = "offset"
type = "combination"
terms = [{ of = ["B.penetration", "B.friction_force"] }]
unit = "N*m"

[[measure]]
name = "twice"
type = "combination"
terms = [{ of = "offset.value", factor = 2.0 }]

[[measure]]
name = "reach"
type = "combination"
terms = [{ of = "slider.x" }, { of = "crank.x", factor = -1.0 }]

[[measure]]
name = "slider"
type = "deviation"
of = ["slider.x"]
"#
    .parse()
    .unwrap();
    doc.extend(extra);
    let desc = ModelDesc::from_toml_table(doc).unwrap();
    let (twin, _) = desc.ideal_twin();
    let kept: Vec<&str> = twin.measures.iter().map(|m| m.name()).collect();
    assert_eq!(kept, ["reach"]);
    let opts = desc.sim_options().unwrap();
    let mut r = desc.compile().unwrap().simulate(&opts).unwrap();
    let twin = clr_mbd::desc::twin::run_twin(&desc, &opts, &mut r)
        .unwrap()
        .expect("the twin ran");
    assert!(twin.column("reach.value").is_some() && twin.column("offset.value").is_none());
    let (d, f, m) = (
        col(&r, "B.penetration"),
        col(&r, "B.friction_force"),
        col(&r, "offset.value"),
    );
    for k in 0..d.len() {
        assert_eq!((d[k] * f[k]).to_bits(), m[k].to_bits(), "row {k}");
    }
    assert!(f.iter().any(|f| *f != 0.0), "friction acts");
    assert!(col(&r, "slider.error").iter().all(|e| e.is_finite()));
}

#[test]
fn a_deviation_of_a_contact_quantity_is_refused_before_the_run() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/slider_crank.toml"
    ))
    .unwrap()
        + "\n[[measure]]\nname = \"f\"\ntype = \"deviation\"\nof = [\"B.normal_force\"]\n";
    let e = compile_err(&text);
    assert!(e.contains("f.of") && e.contains("contact quantity"), "{e}");
    let e = compile_err(&text.replace("B.normal_force", "sldr.x"));
    assert!(e.contains("no such column"), "{e}");
}

#[test]
fn an_angle_offset_in_degrees_and_a_point_in_millimetres_are_flagged() {
    // a usual mistake: offset = 90 (degrees) and a point at 500 (mm) on a 0.5 m crank
    let base = TWO_ROTORS.split("[[measure]]").next().unwrap().to_string();
    let text = format!(
        "{base}\n[[measure]]\nname = \"a\"\ntype = \"angle\"\nbody = \"crank\"\noffset = 90.0\n\
         \n[[measure]]\nname = \"p\"\ntype = \"position\"\nat = {{ body = \"crank\", at = [500.0, 0.0] }}\n\
         \n[output]\nt_end = 0.01\nintervals = 2\n"
    );
    let r = run(&text);
    let fields: Vec<&str> = r.warnings.iter().map(|w| w.field.as_str()).collect();
    assert!(
        fields.contains(&"a.offset") && fields.contains(&"p.at"),
        "{fields:?}"
    );
}

/// [`FREE_PAIR`] with the momentum scales and combinations: the kinetic energy as a sum of
/// products of the velocity columns, the summed |v_x| of both bodies, and a combination of an
/// earlier measure's column.
fn free_pair_combined() -> String {
    let (head, tail) = FREE_PAIR.split_once("[solver]").unwrap();
    let head = head.replace("about = [0.1, -0.2]", "about = [0.1, -0.2]\nscales = true");
    format!(
        r#"{head}
[[measure]]
name = "kinetic"
type = "combination"
unit = "J"
terms = [
  {{ of = ["a.vx", "a.vx"], factor = 0.75 }}, {{ of = ["a.vy", "a.vy"], factor = 0.75 }},
  {{ of = ["a.omega", "a.omega"], factor = 0.01 }},
  {{ of = ["b.vx", "b.vx"], factor = 0.35 }}, {{ of = ["b.vy", "b.vy"], factor = 0.35 }},
  {{ of = ["b.omega", "b.omega"], factor = 0.005 }},
]

[[measure]]
name = "speed_x"
type = "combination"
terms = [{{ of = "a.vx", abs = true }}, {{ of = "b.vx", abs = true, factor = 2.0 }}]

[[measure]]
name = "half_px"
type = "combination"
terms = [{{ of = "momentum.px", factor = 0.5 }}]

[solver]{tail}"#
    )
}

#[test]
fn combinations_and_momentum_scales_equal_their_sums_of_the_body_columns() {
    let r = run(&free_pair_combined());
    let c = |n: &str| col(&r, n);
    // independent formulation: the engine's own kinetic energy column (½ m v² + ½ I ω² per
    // body, computed from the mass matrix) against the sum of products of the velocity columns;
    // rounding only (measured 4.4e-16 relative)
    let (kin, e) = (c("kinetic.value"), c("energy.kinetic"));
    for k in 0..kin.len() {
        assert!(
            (kin[k] - e[k]).abs() <= 1e-13 * e[k].abs(),
            "row {k}: {} vs {}",
            kin[k],
            e[k]
        );
    }
    assert_eq!(r.unit("kinetic.value"), "J");
    assert_eq!(r.unit("speed_x.value"), "m/s");
    assert_eq!(r.unit("momentum.L_scale"), "kg*m^2/s");
    let (ps, ls, sx, half, px) = (
        c("momentum.p_scale"),
        c("momentum.L_scale"),
        c("speed_x.value"),
        c("half_px.value"),
        c("momentum.px"),
    );
    for k in [0, 41, ps.len() - 1] {
        let (mut p, mut l) = (0.0, 0.0);
        for (b, m, i) in [("a", 1.5, 0.02), ("b", 0.7, 0.01)] {
            let at = |s: &str| c(&format!("{b}.{s}"))[k];
            let (x, y, vx, vy) = (at("x") - 0.1, at("y") + 0.2, at("vx"), at("vy"));
            p += m * vx.hypot(vy);
            l += (i * at("omega")).abs() + (m * (x * vy - y * vx)).abs();
        }
        // the same sums in another order: rounding of terms of order 1 kg·m/s (1e-14)
        assert!(
            (ps[k] - p).abs() < 1e-14 && (ls[k] - l).abs() < 1e-14,
            "row {k}"
        );
        let want = c("a.vx")[k].abs() + 2.0 * c("b.vx")[k].abs();
        assert!((sx[k] - want).abs() < 1e-15, "row {k}");
        assert_eq!(half[k], 0.5 * px[k]);
    }
}

#[test]
fn combinations_are_refused_with_what_to_change() {
    let text = free_pair_combined();
    // a product needs its unit; a unit in millimetres is not one clr knows
    let e = compile_err(&text.replace("unit = \"J\"\n", ""));
    assert!(e.contains("kinetic.unit") && e.contains("products"), "{e}");
    // terms of different units without the sum's unit
    let e = compile_err(&text.replace("of = \"b.vx\", abs", "of = \"b.omega\", abs"));
    assert!(
        e.contains("speed_x.unit") && e.contains("b.omega (rad/s)"),
        "{e}"
    );
    let e = compile_err(&text.replace("unit = \"J\"", "unit = \"mJ\""));
    assert!(e.contains("`mJ`") && e.contains("kg*m^2/s"), "{e}");
    // a column of a later measure, or a misspelt one, is not there yet
    let e = compile_err(&text.replace("of = [\"a.vx\", \"a.vx\"]", "of = \"speed_x.value\""));
    assert!(
        e.contains("kinetic.terms[0].of") && e.contains("before this one"),
        "{e}"
    );
    let e = compile_err(&text.replace("of = \"a.vx\", abs", "of = \"a.vxx\", abs"));
    assert!(e.contains("`a.vxx`") && e.contains("a.vx"), "{e}");
    let e = compile_err(&text.replace("factor = 2.0", "factor = nan"));
    assert!(e.contains("terms[1].factor"), "{e}");
}

#[test]
fn metrics_are_refused_with_what_to_change() {
    let with = |m: &str| format!("{FREE_PAIR}\n[[metric]]\nname = \"m\"\n{m}\n");
    let cases = [
        // an oscillation without its window, a window it does not use
        (
            "of = \"a.x\"\nstatistic = \"oscillation\"",
            "metric[0].window",
        ),
        (
            "of = \"a.x\"\nstatistic = \"peak\"\nwindow = 0.1",
            "only `oscillation`",
        ),
        ("of = \"a.x\"\nstatistic = \"spread\"", "metric[0].period"),
        // both sources, or a metric not defined before
        (
            "of = \"a.x\"\nmetrics = [\"q\"]\nstatistic = \"max\"",
            "not both",
        ),
        ("metrics = [\"q\"]\nstatistic = \"max\"", "no metric `q`"),
        (
            "metrics = [\"q\"]\nstatistic = \"drift\"",
            "cannot combine metrics",
        ),
        (
            "of = \"a.x\"\nstatistic = \"peak\"\nper = \"q\"",
            "metric[0].per",
        ),
        (
            "of = [\"a.x\", \"b.x\"]\nstatistic = \"final\"",
            "takes one column",
        ),
        ("of = \"a.x\"\nstatistic = \"peak\"\nunit = \"mm\"", "`mm`"),
        // the twin of a model without a clearance joint writes the same columns; a misspelt
        // column is named with the similar ones
        (
            "of = \"a.xx\"\nstatistic = \"peak\"\ntwin = true",
            "ideal twin writes no column",
        ),
    ];
    for (m, want) in cases {
        let e = compile_err(&with(m));
        assert!(e.contains(want), "{m}: {e}");
    }
}
