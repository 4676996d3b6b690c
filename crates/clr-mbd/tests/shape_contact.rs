//! Shape contact pairs (`[[shape]]` + `[[clearance]] type = "contact"`) in whole models,
//! against closed forms, and their analytic Jacobians against central differences of the whole
//! model (the method and tolerance of `jacobian_contact.rs`).

use clr_mbd::{Model, ModelDesc};
use clr_ode::OdeSystem;

fn model(text: &str) -> ModelDesc {
    ModelDesc::from_toml_table(toml::from_str(text).unwrap()).unwrap()
}

/// A steel ball (r = 10 mm, m = 32.7 g) dropped from h₀ above a ground block.
fn ball_drop(h0: f64, restitution: f64, law: &str) -> String {
    format!(
        r#"
[model]
name = "ball_drop"
gravity = [0.0, -9.81]

[[body]]
name = "ball"
mass = 0.0327
inertia = 1.308e-6
position = [0.0, {y0}]
angle = 0.0
velocity = [0.0, 0.0]
angular_velocity = 0.0

[[shape]]
name = "floor"
at = {{ body = "ground", at = [0.0, -0.05] }}
geometry = {{ type = "cuboid", half_extents = [0.5, 0.05] }}

[[shape]]
name = "sphere"
at = {{ body = "ball", at = [0.0, 0.0] }}
geometry = {{ type = "ball", radius = 0.01 }}

[[clearance]]
name = "drop"
type = "contact"
shapes = ["floor", "sphere"]
normal = {{ law = "hertz", stiffness = 1.5e10, damping = "{law}", restitution = {restitution} }}

[solver]
rtol = 1e-9
atol = 1e-12

[output]
t_end = 0.9
intervals = 9000
"#,
        y0 = 0.01 + h0
    )
}

/// Rebound heights of a ball on a plane with a restitution-exact law: h_k = e^{2k} h₀
/// (free flight v² = 2gh, each impact multiplies the rebound speed by e exactly: contact-laws.md
/// §1.3, "HC-exact"). Gravity acts during the ~0.1 ms contact and shifts the exit speed by about
/// g·t_c/v ≈ 1e-3 relative; the apex is read from 0.1 ms samples (parabola vertex of the three
/// samples around the maximum). Tolerance 3e-3 relative.
#[test]
fn ball_drop_rebounds_follow_restitution() {
    let (h0, e) = (0.1, 0.8);
    let desc = model(&ball_drop(h0, e, "hc-exact"));
    let mut m = desc.compile().unwrap();
    let res = m.simulate(&desc.sim_options().unwrap()).unwrap();
    let y = res.column("ball.y").unwrap();
    let t = res.column("t").unwrap();
    let mut apexes = Vec::new();
    for k in 1..y.len() - 1 {
        if y[k] > y[k - 1] && y[k] >= y[k + 1] && t[k] > 0.01 {
            // parabola through the three samples
            let (a, b, c) = (y[k - 1], y[k], y[k + 1]);
            let top = b + (a - c).powi(2) / (8.0 * (2.0 * b - a - c));
            apexes.push(top - 0.01);
        }
    }
    eprintln!(
        "y: {:?} … {:?}; steps {:?}",
        &y[..3],
        &y[y.len() - 3..],
        res.stats
    );
    assert!(apexes.len() >= 3, "{apexes:?} impacts {:?}", res.impacts);
    for (k, h) in apexes.iter().take(3).enumerate() {
        let expected = e.powi(2 * (k as i32 + 1)) * h0;
        let rel = (h - expected).abs() / expected;
        eprintln!(
            "bounce {}: h = {h:.6e}, e^2k h0 = {expected:.6e}, rel {rel:.2e}",
            k + 1
        );
        assert!(rel < 3e-3, "bounce {}: {h} vs {expected}", k + 1);
    }
    assert!(res.impacts.len() >= 3);
    // no impact of zero duration beside the real one (an onset located at a step end used to
    // read δ ≤ 0 at the next step's start): every impact lasts about the Hertz contact time
    for imp in &res.impacts {
        let d = imp.duration.unwrap_or(f64::INFINITY);
        assert!(d > 1e-5 && imp.peak_force > 1.0, "{imp:?}");
    }
}

/// Commit the memory at (q, q̇), evaluate, and compare the analytic Jacobians with the best
/// central differences (normwise by column and row, as in `jacobian_contact.rs`).
fn jacobian_error(m: &mut Model, q: &[f64], qd: &[f64]) -> f64 {
    let mut y: Vec<f64> = q.iter().chain(qd).copied().collect();
    y.resize(m.dim(), 0.0);
    m.commit_contact_memory(&y);
    let mut dy = vec![0.0; m.dim()];
    m.rhs(0.0, &y, &mut dy);
    let a = m.jacobians(0.0, q, qd);
    let (f, _) = m.jacobians_fd_best(0.0, q, qd);
    let n = q.len();
    let err = |a: &[f64], f: &[f64]| {
        let big = f.iter().fold(0.0f64, |x, v| x.max(v.abs()));
        let mut worst = 0.0f64;
        for c in 0..n {
            let col = |x: &[f64]| (0..n).map(|r| x[r * n + c].powi(2)).sum::<f64>().sqrt();
            let diff: f64 = (0..n)
                .map(|r| (a[r * n + c] - f[r * n + c]).powi(2))
                .sum::<f64>()
                .sqrt();
            worst = worst.max(diff / col(f).max(1e-8 * big).max(1e-300));
        }
        worst
    };
    if std::env::var("DEBUG_JAC").is_ok() {
        for r in 0..n {
            eprintln!(
                "dv row {r}: a {:?}\n           f {:?}",
                &a.dv[r * n..(r + 1) * n],
                &f.dv[r * n..(r + 1) * n]
            );
        }
    }
    eprintln!("dq {:e} dv {:e}", err(&a.dq, &f.dq), err(&a.dv, &f.dv));
    let e = err(&a.dq, &f.dq).max(err(&a.dv, &f.dv));
    eprintln!("jacobian column error {e:e}");
    e
}

fn two_bodies(shape_a: &str, shape_b: &str, friction: &str) -> ModelDesc {
    model(&format!(
        r#"
[[body]]
name = "a"
mass = 2.0
inertia = 0.01
[[body]]
name = "b"
mass = 1.0
inertia = 0.002
position = [0.0, 0.1]
[[shape]]
name = "A"
at = {{ body = "a", at = [0.01, -0.02] }}
angle = 0.2
geometry = {shape_a}
[[shape]]
name = "B"
at = {{ body = "b", at = [0.0, 0.0] }}
geometry = {shape_b}
[[clearance]]
name = "pair"
type = "contact"
shapes = ["A", "B"]
normal = {{ law = "hertz", stiffness = 1e9, damping = "lankarani-nikravesh", restitution = 0.7 }}
friction = {friction}
"#
    ))
}

/// Analytic Jacobian of a ball (B) pressed into a cuboid face (A) with sliding friction, and of
/// two balls: exact feature models (module docs of the contact Jacobian), tolerance 1e-6 as in
/// `jacobian_contact.rs` (central differences agree to 1e-8–1e-7 at micrometre penetrations).
#[test]
fn jacobian_of_ball_pairs_matches_central_differences() {
    let friction = r#"{ law = "ambrosio", mu = 0.3, v0 = 1e-2, v1 = 2.0 }"#;
    for (a, b, bq) in [
        (
            r#"{ type = "cuboid", half_extents = [0.1, 0.05] }"#,
            r#"{ type = "ball", radius = 0.02 }"#,
            [0.03, 0.0],
        ),
        (
            r#"{ type = "ball", radius = 0.05 }"#,
            r#"{ type = "ball", radius = 0.02 }"#,
            [0.02, 0.0],
        ),
    ] {
        let desc = two_bodies(a, b, friction);
        let mut m = desc.compile().unwrap();
        // body a at the origin turned by 0.1 rad (shape A turned 0.3 rad in all); B penetrates
        // A by 5 µm, offset along A's face by bq[0]
        let th: f64 = 0.3;
        let c = [
            0.01 * 0.1f64.cos() + 0.02 * 0.1f64.sin(),
            0.01 * 0.1f64.sin() - 0.02 * 0.1f64.cos(),
        ];
        let d = 0.05 + 0.02 - 5e-6;
        let (nrm, tan) = ([-th.sin(), th.cos()], [th.cos(), th.sin()]);
        let mut o = [nrm[0] * d + tan[0] * bq[0], nrm[1] * d + tan[1] * bq[0]];
        if a.contains("ball") {
            // two balls: the centre distance itself is r_A + r_B − 5 µm
            let len = o[0].hypot(o[1]);
            o = [o[0] * d / len, o[1] * d / len];
        }
        let pb = [c[0] + o[0], c[1] + o[1] + bq[1]];
        let q = [0.0, 0.0, 0.1, pb[0], pb[1], 0.4];
        let qd = [0.01, -0.02, 0.3, 0.2, -0.05, -1.0];
        let e = jacobian_error(&mut m, &q, &qd);
        assert!(e < 1e-6, "{a} vs {b}: {e:e}");
    }
}

/// A ball resting on the upper face of a flexible cantilever (`beam_face` shape, clamped at
/// x = 0, 10 Euler–Bernoulli elements): at rest the face carries the ball's weight P = m g at
/// x = a, so the beam's deflection there is P a³/(3EI) (Euler–Bernoulli cantilever, point load;
/// the cubic elements reproduce it exactly at a node, a = 0.4 m is node 8) plus that of the
/// beam's own weight w = ρAg, w a²(6L² − 4La + a²)/(24EI) (Roark 8th ed. Table 8.1 case 2a;
/// exact at a node with consistent loads), and the contact normal force is P. Damped (Rayleigh α near critical for the first mode, a dissipative law),
/// 0.3 s from rest with the ball touching. Tolerance 1e-3 relative: the contact point sits where
/// the deformed face's normal passes through the ball centre, r·θ ≈ 9e-5 m beside x = a (slope
/// θ = P a²/(2EI) ≈ 4.5e-3), which moves the deflection at a by θ·rθ ≈ 3.4e-4 relative
/// (measured 3.9e-4 with the beam's weight, 4.0e-4 without); the force is P to 3e-5.
#[test]
fn ball_resting_on_a_beam_face_loads_the_beam() {
    let (m, r, a): (f64, f64, f64) = (2.0, 0.02, 0.4);
    let (e, w, h): (f64, f64, f64) = (2.07e11, 0.02, 0.01);
    let text = format!(
        r#"
[model]
name = "ball_on_beam"
gravity = [0.0, -9.81]
[[beam]]
name = "cant"
start = [0.0, 0.0]
end = [0.5, 0.0]
elements = 10
material = {{ youngs_modulus = {e}, density = 7850.0, poisson_ratio = 0.3 }}
section = {{ shape = "rectangular", width = {w}, depth = {h} }}
supports = [{{ node = 0, type = "clamped" }}]
rayleigh = [400.0, 1e-5]
[[body]]
name = "ball"
mass = {m}
inertia = 3.2e-4
position = [{a}, {y0}]
angle = 0.0
velocity = [0.0, 0.0]
angular_velocity = 0.0
[[shape]]
name = "face"
geometry = {{ type = "beam_face", beam = "cant", face = "upper" }}
[[shape]]
name = "round"
at = {{ body = "ball", at = [0.0, 0.0] }}
geometry = {{ type = "ball", radius = {r} }}
[[clearance]]
name = "rest"
type = "contact"
shapes = ["face", "round"]
normal = {{ law = "hertz", stiffness = 1e10, damping = "lankarani-nikravesh", restitution = 0.5 }}
friction = {{ law = "coulomb", mu = 0.3, v_reg = 1e-4 }}
[[joint]]
name = "guide"
type = "translational"
a = {{ body = "ground", at = [{a}, 0.0] }}
b = {{ body = "ball", at = [0.0, 0.0] }}
axis = [0.0, 1.0]
[solver]
rtol = 1e-8
atol = 1e-11
[output]
t_end = 0.3
intervals = 30
"#,
        y0 = 0.5 * h + r
    );
    let desc = model(&text);
    let mut mdl = desc.compile().unwrap();
    let res = mdl.simulate(&desc.sim_options().unwrap()).unwrap();
    let i = w * h.powi(3) / 12.0;
    let p = m * 9.81;
    let (l, wb) = (0.5, 7850.0 * w * h * 9.81);
    let expected = -p * a.powi(3) / (3.0 * e * i)
        - wb * a * a * (6.0 * l * l - 4.0 * l * a + a * a) / (24.0 * e * i);
    let v = res.column("cant.n8.v").unwrap();
    let f = res.column("rest.normal_force").unwrap();
    let last = v.len() - 1;
    eprintln!(
        "deflection {:.6e} vs {expected:.6e}; force {} vs {p}",
        v[last], f[last]
    );
    assert!((v[last] / expected - 1.0).abs() < 1e-3);
    assert!((f[last] / p - 1.0).abs() < 1e-3);
}

/// A block sliding on a floor into a wall, floor and wall parts of one compound: its lower
/// corner is the block-side point of a floor contact and of a wall contact at once. Each point
/// keeps its own impact memory (the slots are matched by point and normal), so the wall impact
/// returns c_e = 0.5 of the impact speed exactly (restitution-exact law, no friction: the floor
/// does not act along x). Tolerance 1e-4 relative: the horizontal velocity after the impact
/// against −c_e·v₀ (the run's error control, rtol 1e-7). Before the fix the wall took the
/// floor's δ̇⁻ at random: 0.18 instead of 0.5, and 471 000 steps.
#[test]
fn a_corner_on_floor_and_wall_keeps_each_contacts_memory() {
    let text = r#"
[model]
gravity = [0.0, -9.81]
[[body]]
name = "block"
mass = 0.5
inertia = 8.333e-5
position = [0.079, 0.0099994]
velocity = [0.3, 0.0]
angle = 0.0
angular_velocity = 0.0
[[shape]]
name = "housing"
at = { body = "ground", at = [0.0, 0.0] }
geometry = { type = "compound", parts = [
  { at = [0.0, -0.005], geometry = { type = "cuboid", half_extents = [0.11, 0.005] } },
  { at = [0.105, 0.02], geometry = { type = "cuboid", half_extents = [0.005, 0.03] } } ] }
[[shape]]
name = "box"
at = { body = "block", at = [0.0, 0.0] }
geometry = { type = "cuboid", half_extents = [0.02, 0.01] }
[[clearance]]
name = "c"
type = "contact"
shapes = ["housing", "box"]
normal = { law = "hertz", stiffness = 5e9, damping = "hc-exact", restitution = 0.5 }
[solver]
rtol = 1e-7
atol = 1e-10
[output]
t_end = 0.01
intervals = 100
"#;
    let desc = model(text);
    let mut m = desc.compile().unwrap();
    let res = m.simulate(&desc.sim_options().unwrap()).unwrap();
    let vx = res.column("block.vx").unwrap();
    let ratio = -vx[vx.len() - 1] / 0.3;
    eprintln!("rebound ratio {ratio}, steps {}", res.stats.accepted);
    assert!((ratio / 0.5 - 1.0).abs() < 1e-4, "{ratio}");
}
