//! `contact.spatial.shapes.*`: shape contact in the spatial engine (`[[shape]]` and
//! `[[clearance]] type = "contact"`, docs/spatial.md "Shape contact") against closed forms.
//! Sources and tolerances:
//!
//! * `.ball_cuboid_rebound.*`: a steel ball (R = 10 mm) dropped from h₀ = 0.1 m onto a ground
//!   cuboid (models/examples/spatial_ball_on_box.toml dropped straight down; its Coulomb friction
//!   then does nothing), Hertz with Flores damping at c_r = 0.8 (Flores, Machado, Silva & Martins, Multibody
//!   Syst. Dyn. 25 (2011) 357–375). A free impact of this law restitutes the law's exact
//!   effective restitution e (`NormalLaw::effective_restitution`, contact-laws.md §1.3: 0.7885 at
//!   c_r = 0.8), so the rebound heights are h_k = e^{2k} h₀. Measured h_k = v_{k+1}²/(2g) from the
//!   located impact velocities (impacts.csv) after k rebounds, and h₀ from the first. Tolerance
//!   2e-3 relative for k ≤ 3: gravity acts during the contact (t_c ≈ 67 µs), which the
//!   free-impact restitution leaves out; its impulse changes a rebound speed by at most
//!   g t_c/v ≈ 5e-4 relative, a height by twice that; measured 1.9e-4 per rebound (4.4e-4 at
//!   k = 2, 7.7e-4 at k = 3), growing with k as that effect does.
//! * `.incline_stop`: a box sliding down an incline of θ = 0.3 rad with initial speed v₀ = 1 m/s,
//!   Coulomb μ = 0.5 > tan θ, resting on its four bottom corners (checked: `C.contact` = 4 while
//!   it slides), stops after d = v₀²/(2g(μ cos θ − sin θ)) (constant deceleration; e.g. Meriam &
//!   Kraige, *Engineering Mechanics: Dynamics*, §3/4). Measured: the distance along the slope at
//!   1.5× the closed-form stopping time. Tolerance 1e-3 relative: the regularized Coulomb law
//!   (v_reg = 1e-5 m/s) creeps at v_reg tan θ/μ after the stop (1e-6 m over the remaining time)
//!   and the corners' normal forces settle from the static penetration within milliseconds.
//! * `.guide_stop`: a steel block (0.1256 kg) launched at v₀ = 0.5 m/s along a rectangular guide
//!   with 0.5 mm clearance on every side (models/examples/spatial_slider_in_guide.toml: the guide
//!   a compound of four cuboid plates, the block a cuboid: the spatial translational clearance
//!   joint built from shape contact), resting on the bottom plate, Coulomb μ = 0.3, stops after
//!   d = v₀²/(2μg) (the incline's closed form at θ = 0). Measured: block.x at the end of the run
//!   (0.3 s, 1.8× the stopping time). Tolerance 1e-3 relative, for the incline's reasons; the
//!   block rests on its four bottom corners (`.guide_stop.corners`), the other plates untouched.
//! * `.gear_ratio`: a friction-wheel pair (two parry capsules with parallel axes, r₁ = 50 mm
//!   driven to 10 rad/s by a revolute-angle driver, r₂ = 100 mm free on its revolute joint, axes
//!   0.15 m − δ₀ apart: the interference δ₀ = 20 µm preloads the contact; parry gives one point
//!   for parallel capsules), Coulomb μ = 0.3: after the slip phase the wheels roll,
//!   ω₂/ω₁ = −r₁/r₂ (the closed-form ratio of rolling contact). Friction wheels stand in for gear
//!   teeth (teeth as convex polyhedra would give the same mean ratio with the meshing ripple on
//!   top: not done). Parry cylinders were tried first: penetrating cylinders go through EPA, whose
//!   point jitters from call to call, and 0.05 s took over 100 s; capsules are exact. Measured: ω₂/ω₁ at
//!   t = 0.5 s. Tolerance 1e-3 relative: the rolling radii are those of the undeformed surfaces
//!   up to δ₀/r₂ = 2e-4, and the residual slip of the regularized law has decayed.

use clr_mbd::spatial::SpatialDesc;
use clr_mbd::{Results, SimOptions, SolverKind};

use super::Filter;
use crate::report::Case;

const PREFIX: &str = "contact.spatial.shapes";
const G: f64 = 9.81;

type Family = (&'static str, fn(&mut Vec<Case>));

const FAMILIES: &[Family] = &[
    ("ball_cuboid_rebound", rebound_cases),
    ("incline_stop", incline_case),
    ("gear_ratio", gear_case),
    ("guide_stop", guide_case),
];

/// The `contact.spatial.shapes.*` cases.
pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    for (name, run) in FAMILIES {
        if filter.wants(&format!("{PREFIX}.{name}")) {
            run(&mut out);
        }
    }
    out
}

/// Compile a spatial model file's text and run it with NDF at `rtol` over [0, t_end].
fn run(text: &str, t_end: f64, n: usize, rtol: f64) -> Result<Results, String> {
    let table: toml::Table = text.parse().map_err(|e| format!("model text: {e}"))?;
    let desc = SpatialDesc::from_toml_table(table).map_err(|e| e.to_string())?;
    let mut m = desc.compile().map_err(|e| e.to_string())?;
    let opts = SimOptions::span(0.0, t_end, n)
        .tolerances(rtol, rtol * 1e-3)
        .solver(SolverKind::Ndf);
    m.simulate(&opts).map_err(|e| e.to_string())
}

fn col(res: &Results, name: &str) -> Vec<f64> {
    res.column(name).unwrap_or_default()
}

/// Value of column `name` at the output row nearest `t`.
fn at(res: &Results, name: &str, t: f64) -> f64 {
    let ts = col(res, "t");
    let k = ts
        .iter()
        .enumerate()
        .min_by(|a, b| (a.1 - t).abs().total_cmp(&(b.1 - t).abs()))
        .map_or(0, |(k, _)| k);
    col(res, name).get(k).copied().unwrap_or(f64::NAN)
}

// ---------------------------------------------------------------------------------------------

/// The shipped example, dropped straight down (its sideways velocity removed).
const REBOUND_FILE: &str = include_str!("../../../models/examples/spatial_ball_on_box.toml");

fn rebound_text() -> String {
    REBOUND_FILE.replacen(
        "velocity = [0.2, 0.0, 0.0]",
        "velocity = [0.0, 0.0, 0.0]",
        1,
    )
}

fn rebound_cases(out: &mut Vec<Case>) {
    let id = format!("{PREFIX}.ball_cuboid_rebound");
    let src = "h_k = e^{2k} h0, e the Flores law's exact effective restitution at c_r = 0.8 \
               (Flores et al. 2011; contact-laws.md §1.3); 2e-3 relative (gravity during the \
               contact, module docs)";
    let h0 = 0.1;
    let law = clr_contact::ElasticLaw::hertz(1.5e10)
        .and_then(|el| clr_contact::NormalLaw::new(el, clr_contact::DampingFactor::Flores, 0.8));
    let e = match law {
        Ok(l) => l.effective_restitution(),
        Err(err) => {
            out.push(Case::new(&id, "rebound height", "m", src).failed(h0, err.to_string()));
            return;
        }
    };
    let res = match run(&rebound_text(), 0.75, 150, 1e-9) {
        Ok(r) => r,
        Err(err) => {
            out.push(Case::new(&id, "rebound height", "m", src).failed(h0, err));
            return;
        }
    };
    let v: Vec<f64> = res.impacts.iter().map(|i| i.impact_velocity).collect();
    if v.len() < 4 {
        out.push(
            Case::new(&id, "rebound height", "m", src)
                .failed(h0, format!("{} impacts, 4 expected", v.len())),
        );
        return;
    }
    out.push(
        Case::new(
            format!("{id}.h0"),
            "drop height from the first impact velocity",
            "m",
            src,
        )
        .relative(v[0] * v[0] / (2.0 * G), h0, 1e-6)
        .note("free fall: v1²/(2g) = h0 to the integration tolerance"),
    );
    for (k, vk) in v.iter().enumerate().take(4).skip(1) {
        let h = vk * vk / (2.0 * G);
        out.push(
            Case::new(
                format!("{id}.h{k}"),
                format!("rebound height {k}"),
                "m",
                src,
            )
            .relative(h, e.powi(2 * k as i32) * h0, 2e-3)
            .note(format!(
                "e = {e:.6}; nominal c_r^(2k) h0 = {:.6e} m",
                0.8f64.powi(2 * k as i32) * h0
            )),
        );
    }
}

// ---------------------------------------------------------------------------------------------

/// The incline model: ramp and box turned by θ about y (downhill along the turned x axis), the
/// box started at its static corner penetration with speed v0 downhill.
fn incline_text(theta: f64, mu: f64, v0: f64) -> String {
    let (m, k, h) = (1.0, 1e9, 0.02);
    // static corner penetration: K δ^1.5 = m g cos θ / 4
    let delta = (m * G * theta.cos() / 4.0 / k).powf(2.0 / 3.0);
    let (s, c) = theta.sin_cos();
    // box centre: ramp top (local z = 0.05) + half height − δ, along the ramp normal
    let zl = 0.05 + h - delta;
    let (px, pz) = (s * zl, c * zl);
    let (vx, vz) = (v0 * c, -v0 * s);
    format!(
        r#"
[model]
space = "spatial"
gravity = [0.0, 0.0, -{G}]
[[body]]
name = "box"
mass = {m}
principal_inertia = [8.6667e-4, 8.6667e-4, 1.6667e-3]
position = [{px}, 0.0, {pz}]
orientation = {{ axis = [0.0, 1.0, 0.0], angle = {theta} }}
velocity = [{vx}, 0.0, {vz}]
velocity_frame = "world"
angular_velocity = [0.0, 0.0, 0.0]
angular_velocity_frame = "world"
[[shape]]
name = "ramp"
at = {{ body = "ground" }}
orientation = {{ axis = [0.0, 1.0, 0.0], angle = {theta} }}
geometry = {{ type = "cuboid", half_extents = [2.0, 0.5, 0.05] }}
[[shape]]
name = "block"
at = {{ body = "box" }}
geometry = {{ type = "cuboid", half_extents = [0.05, 0.05, {h}] }}
[[clearance]]
name = "slide"
type = "contact"
shapes = ["ramp", "block"]
normal = {{ law = "hertz", stiffness = {k}, damping = "flores", restitution = 0.5 }}
friction = {{ law = "coulomb", mu = {mu}, v_reg = 1e-5 }}
"#
    )
}

fn incline_case(out: &mut Vec<Case>) {
    let id = format!("{PREFIX}.incline_stop");
    let src = "d = v0²/(2g(μ cos θ − sin θ)) (constant deceleration); 1e-3 relative (module docs)";
    let (theta, mu, v0) = (0.3f64, 0.5f64, 1.0f64);
    let decel = G * (mu * theta.cos() - theta.sin());
    let (d, t_stop) = (v0 * v0 / (2.0 * decel), v0 / decel);
    let res = match run(&incline_text(theta, mu, v0), 1.5 * t_stop, 300, 1e-8) {
        Ok(r) => r,
        Err(e) => {
            out.push(Case::new(&id, "stopping distance", "m", src).failed(d, e));
            return;
        }
    };
    let (s, c) = theta.sin_cos();
    let along = |t: f64| at(&res, "box.x", t) * c - at(&res, "box.z", t) * s;
    let dist = along(1.5 * t_stop) - along(0.0);
    let points = at(&res, "slide.contact", 0.5 * t_stop);
    out.push(
        Case::new(&id, "stopping distance", "m", src)
            .relative(dist, d, 1e-3)
            .note(format!(
                "stopping time {t_stop:.4} s; active corner points while sliding: {points}"
            )),
    );
    out.push(
        Case::new(
            format!("{id}.corners"),
            "contact points while sliding",
            "-",
            "a box flat on a plane rests on its four bottom corners",
        )
        .absolute(points, 4.0, 0.0),
    );
}

// ---------------------------------------------------------------------------------------------

/// The shipped slider-in-guide example as it is.
const GUIDE_FILE: &str = include_str!("../../../models/examples/spatial_slider_in_guide.toml");

fn guide_case(out: &mut Vec<Case>) {
    let id = format!("{PREFIX}.guide_stop");
    let src = "d = v0²/(2μg) (constant deceleration); 1e-3 relative (module docs)";
    let (mu, v0) = (0.3, 0.5);
    let d = v0 * v0 / (2.0 * mu * G);
    let res = match run(GUIDE_FILE, 0.3, 300, 1e-8) {
        Ok(r) => r,
        Err(e) => {
            out.push(Case::new(&id, "stopping distance", "m", src).failed(d, e));
            return;
        }
    };
    let dist = at(&res, "block.x", 0.3) - at(&res, "block.x", 0.0);
    let points = at(&res, "guide_contact.contact", 0.5 * v0 / (mu * G));
    out.push(
        Case::new(&id, "stopping distance in the guide", "m", src)
            .relative(dist, d, 1e-3)
            .note(format!("active corner points while sliding: {points}")),
    );
    out.push(
        Case::new(
            format!("{id}.corners"),
            "contact points while sliding",
            "-",
            "a block flat on the guide's bottom plate rests on its four bottom corners",
        )
        .absolute(points, 4.0, 0.0),
    );
}

// ---------------------------------------------------------------------------------------------

fn gear_text() -> String {
    let (r1, r2, d0) = (0.05, 0.1, 2e-5);
    let x2 = r1 + r2 - d0;
    let half_pi = std::f64::consts::FRAC_PI_2;
    // capsules along the shape x axis, turned onto the world z axis
    format!(
        r#"
[model]
space = "spatial"
[[body]]
name = "w1"
mass = 1.0
principal_inertia = [1e-3, 1e-3, 1.25e-3]
position = [0.0, 0.0, 0.0]
[[body]]
name = "w2"
mass = 2.0
principal_inertia = [6e-3, 6e-3, 1e-2]
position = [{x2}, 0.0, 0.0]
angular_velocity = [0.0, 0.0, 0.0]
angular_velocity_frame = "world"
[[joint]]
name = "j1"
type = "revolute"
a = {{ body = "ground", at = [0.0, 0.0, 0.0], axis = [0.0, 0.0, 1.0] }}
b = {{ body = "w1", at = [0.0, 0.0, 0.0] }}
[[joint]]
name = "j2"
type = "revolute"
a = {{ body = "ground", at = [{x2}, 0.0, 0.0], axis = [0.0, 0.0, 1.0] }}
b = {{ body = "w2", at = [0.0, 0.0, 0.0] }}
[[driver]]
name = "spin"
type = "revolute_angle"
joint = "j1"
motion = {{ type = "ramp", rate = 10.0, duration = 0.05 }}
[[shape]]
name = "wheel1"
at = {{ body = "w1" }}
orientation = {{ axis = [0.0, 1.0, 0.0], angle = -{half_pi} }}
geometry = {{ type = "capsule", half_length = 0.01, radius = {r1} }}
[[shape]]
name = "wheel2"
at = {{ body = "w2" }}
orientation = {{ axis = [0.0, 1.0, 0.0], angle = -{half_pi} }}
geometry = {{ type = "capsule", half_length = 0.01, radius = {r2} }}
[[clearance]]
name = "mesh"
type = "contact"
shapes = ["wheel1", "wheel2"]
normal = {{ law = "hertz", stiffness = 1e9, damping = "flores", restitution = 0.5 }}
friction = {{ law = "coulomb", mu = 0.3, v_reg = 1e-4 }}
"#
    )
}

fn gear_case(out: &mut Vec<Case>) {
    let id = format!("{PREFIX}.gear_ratio");
    let src = "rolling contact ω2/ω1 = −r1/r2 (friction wheels standing in for gear teeth); \
               1e-3 relative (module docs)";
    let ratio = -0.5;
    let res = match run(&gear_text(), 0.5, 100, 1e-8) {
        Ok(r) => r,
        Err(e) => {
            out.push(Case::new(&id, "ω2/ω1", "-", src).failed(ratio, e));
            return;
        }
    };
    let (w1, w2) = (at(&res, "w1.wz", 0.5), at(&res, "w2.wz", 0.5));
    let n = at(&res, "mesh.normal_force", 0.5);
    out.push(
        Case::new(&id, "ω2/ω1", "-", src)
            .relative(w2 / w1, ratio, 1e-3)
            .note(format!(
                "ω1 = {w1:.6} rad/s, ω2 = {w2:.6} rad/s, normal force {n:.3} N, points {}",
                at(&res, "mesh.contact", 0.5)
            )),
    );
}
