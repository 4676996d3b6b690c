//! Verification cases of the shape contact element (`[[shape]]` + `[[clearance]] type =
//! "contact"`: clr-mbd `shape_pair`, geometry from parry2d-f64 through clr-contact `shapes`,
//! involute teeth from clr-contact `gears`). Each case runs a whole model file (the TOML text is
//! written here) and compares it with a closed form:
//!
//! * `contact.shapes.ball_drop.h1/h2/h3`: rebound heights of a ball on a plane with a
//!   restitution-exact law, h_k = e^{2k} h₀ (contact-laws.md §1.3);
//! * `contact.shapes.incline.stop_distance`: a block launched down an incline with Coulomb
//!   friction μ > tan α stops after d = v₀²/(2g(μ cos α − sin α)) (work–energy);
//! * `contact.shapes.cam.lift`, `.min_force`, `.lift_off`: a flat-faced follower on an eccentric
//!   disc cam follows the harmonic lift y = y_mid + e sin ωt, is pressed by the force Newton's
//!   law gives, and lifts off above ω* = √((F0 + m g + k e)/(m e)) at the angle
//!   sin φ* = (F0 + m g)/(m e ω² − k e), delayed by the Hertz contact's lag;
//! * `contact.shapes.gear.ratio`: an involute gear pair under load turns at ω2/ω1 = −z1/z2
//!   (conjugate action; Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd ed. 2004,
//!   ch. 10).
//!
//! Every number of the models is either one of the constants below (each with its origin) or
//! derived from them where the model text is written.

use clr_contact::InvoluteGear;
use clr_mbd::{ModelDesc, Results};

use super::Filter;
use crate::report::Case;

/// Gravitational acceleration of every model here, m/s² (standard value, written into
/// `[model] gravity`).
const G: f64 = 9.81;

/// The cases of this module that `filter` asks for (group `contact`, ids `contact.shapes.*`);
/// each model runs only when one of its cases is wanted.
pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    if filter.wants("contact.shapes.ball_drop") {
        out.extend(ball_drop_cases());
    }
    if filter.wants("contact.shapes.incline") {
        out.push(incline_case());
    }
    if filter.wants("contact.shapes.cam") {
        out.extend(cam_cases(filter));
    }
    if filter.wants("contact.shapes.gear") {
        out.push(gear_case());
    }
    out
}

/// Build and simulate a model file's text (as `clr run` does for a generic file).
fn run(text: &str) -> Result<Results, String> {
    let table: toml::Table = toml::from_str(text).map_err(|e| format!("TOML: {e}"))?;
    let desc = ModelDesc::from_toml_table(table).map_err(|e| e.to_string())?;
    let mut model = desc.compile().map_err(|e| e.to_string())?;
    let opts = desc.sim_options().map_err(|e| e.to_string())?;
    model.simulate(&opts).map_err(|e| e.to_string())
}

/// A result column by name, or a message naming the missing column.
fn col(res: &Results, name: &str) -> Result<Vec<f64>, String> {
    res.column(name)
        .ok_or_else(|| format!("the results have no column `{name}`"))
}

/// Time where `v` first crosses `level` from above after `t_min`, by linear interpolation
/// between the output rows.
fn first_fall_below(t: &[f64], v: &[f64], level: f64, t_min: f64) -> Option<f64> {
    (1..t.len()).find_map(|k| {
        (t[k - 1] >= t_min && v[k - 1] > level && v[k] <= level).then(|| {
            let f = (v[k - 1] - level) / (v[k - 1] - v[k]);
            t[k - 1] + f * (t[k] - t[k - 1])
        })
    })
}

// ---------------------------------------------------------------------------------------------
// 1. Ball drop: rebound heights
// ---------------------------------------------------------------------------------------------

/// Drop height of the ball's lowest point above the floor, m (the model of
/// crates/clr-mbd/tests/shape_contact.rs).
const BALL_H0: f64 = 0.1;
/// Coefficient of restitution (steel on steel, typical; any value in (0, 1] works).
const BALL_E: f64 = 0.8;
/// Ball radius, m, and mass, kg: a steel ball of 10 mm radius (ρ = 7800 kg/m³: 4/3 π r³ ρ).
const BALL_R: f64 = 0.01;
const BALL_M: f64 = 0.0327;
/// Hertz stiffness of the ball on the floor, N/m^1.5: (4/3) E* √R with E* = 1.137e11 Pa (steel
/// on steel, E = 207 GPa, ν = 0.3) and R = 10 mm gives 1.52e10.
const BALL_K: f64 = 1.5e10;

/// The ball-drop model file: a ball released at rest with its lowest point BALL_H0 above a
/// ground block.
fn ball_model() -> String {
    format!(
        r#"
[model]
name = "ball_drop"
gravity = [0.0, {gy:?}]

[[body]]
name = "ball"
mass = {BALL_M:?}
inertia = 1.308e-6    # (2/5) m r², kg·m²
position = [0.0, {y0:?}]    # lowest point h0 above the floor
angle = 0.0
velocity = [0.0, 0.0]    # released from rest
angular_velocity = 0.0

[[shape]]
name = "floor"
at = {{ body = "ground", at = [0.0, -0.05] }}    # top face at y = 0
geometry = {{ type = "cuboid", half_extents = [0.5, 0.05] }}

[[shape]]
name = "sphere"
at = {{ body = "ball", at = [0.0, 0.0] }}
geometry = {{ type = "ball", radius = {BALL_R:?} }}

[[clearance]]
name = "drop"
type = "contact"
shapes = ["floor", "sphere"]
normal = {{ law = "hertz", stiffness = {BALL_K:?}, damping = "hc-exact", restitution = {BALL_E:?} }}

[solver]
rtol = 1e-9     # integration error far below the gravity effect of the tolerance
atol = 1e-12

[output]
t_end = 0.9         # three rebounds (impacts at 0.14, 0.37, 0.55 s, apex 3 at 0.63 s)
intervals = 9000    # 0.1 ms rows for the apex fit
"#,
        gy = -G,
        y0 = BALL_R + BALL_H0
    )
}

/// Duration of a Hertz impact of mass m at speed v on stiffness K (no damping), s:
/// t_c = 2.94 δ_m/v with δ_m = (5 m v²/(4K))^{2/5} (Johnson, *Contact Mechanics*, 1985, §11.4).
fn hertz_contact_time(m: f64, k: f64, v: f64) -> f64 {
    2.94 * (5.0 * m * v * v / (4.0 * k)).powf(0.4) / v
}

/// `contact.shapes.ball_drop.h1/h2/h3`: the first three rebound heights.
fn ball_drop_cases() -> Vec<Case> {
    let src = "rebound heights h_k = e^{2k} h₀ of a restitution-exact law (\"hc-exact\": \
               contact-laws.md §1.3; free flight v² = 2gh)";
    let ids = ["h1", "h2", "h3"];
    // The apexes (ball height minus radius) after each impact: the vertex of the parabola through
    // the three output rows around each maximum (free flight is exactly a parabola); 0.01 s skips
    // the start.
    let apexes = run(&ball_model()).and_then(|res| {
        let (t, y) = (col(&res, "t")?, col(&res, "ball.y")?);
        let mut h = Vec::new();
        for k in 1..y.len() - 1 {
            if y[k] > y[k - 1] && y[k] >= y[k + 1] && t[k] > 0.01 {
                let (a, b, c) = (y[k - 1], y[k], y[k + 1]);
                h.push(b + (a - c).powi(2) / (8.0 * (2.0 * b - a - c)) - BALL_R);
            }
        }
        let durations: Vec<f64> = res.impacts.iter().filter_map(|i| i.duration).collect();
        Ok((h, durations, res.stats.accepted))
    });
    // Tolerance: gravity acts during each contact (t_c ≈ 65–75 µs), which the free-impact
    // closed form leaves out; its impulse g·t_c changes the rebound speed v by at most g·t_c,
    // so each impact can change the rebound height (∝ v²) by at most 2 g t_c/v relative, and
    // h_k carries the sum over impacts 1…k. t_c from the elastic Hertz duration (the damped
    // contact lasts a few % longer; the bound is not tight: the measured errors are about 5
    // times smaller). The integration (rtol 1e-9) and the apex fit (exact for a parabola) add
    // < 1e-6.
    let mut tol = Vec::new();
    let mut sum = 0.0;
    for k in 0..3 {
        let v = BALL_E.powi(k) * (2.0 * G * BALL_H0).sqrt();
        sum += 2.0 * G * hertz_contact_time(BALL_M, BALL_K, v) / v;
        tol.push(sum);
    }
    ids.iter()
        .enumerate()
        .map(|(k, id)| {
            let reference = BALL_E.powi(2 * (k as i32 + 1)) * BALL_H0;
            let case = Case::new(
                format!("contact.shapes.ball_drop.{id}"),
                format!("rebound height after impact {} of a ball on a plane", k + 1),
                "m",
                src,
            );
            match &apexes {
                Ok((h, durations, steps)) if h.len() > k => {
                    case.relative(h[k], reference, tol[k]).note(format!(
                        "h0 = {BALL_H0} m, e = {BALL_E}, K = {BALL_K:e} N/m^1.5; relative error \
                         {:.2e}; contact durations {:?} s; {steps} steps",
                        (h[k] - reference) / reference,
                        durations
                            .iter()
                            .take(3)
                            .map(|d| format!("{d:.3e}"))
                            .collect::<Vec<_>>()
                    ))
                }
                Ok((h, ..)) => case.failed(reference, format!("only {} rebounds found", h.len())),
                Err(e) => case.failed(reference, e.clone()),
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// 2. Block on an incline: stopping distance
// ---------------------------------------------------------------------------------------------

/// Incline angle α, rad (11.5°, assumed).
const INC_ALPHA: f64 = 0.2;
/// Coulomb friction coefficient (assumed; > tan α = 0.203 so that the block stops).
const INC_MU: f64 = 0.4;
/// Launch speed down the incline, m/s (assumed).
const INC_V0: f64 = 1.0;
/// Regularization velocity of the Coulomb law, m/s (the law's default 1e-4).
const INC_VREG: f64 = 1e-4;
/// Block mass, kg, and half sizes, m (steel block 40 × 20 mm, assumed).
const INC_M: f64 = 0.5;
const INC_HX: f64 = 0.02;
const INC_HY: f64 = 0.01;
/// Hertz stiffness of each block corner on the incline, N/m^1.5 (assumed; it only sets the
/// compliance counted in the tolerance).
const INC_K: f64 = 1e10;

/// The incline model file: a block sliding down a ground cuboid turned by −α, launched at
/// INC_V0 from its static penetration on two corners.
fn incline_model() -> String {
    let (s, c) = INC_ALPHA.sin_cos();
    // Down-slope unit tangent t = (cos α, −sin α), outward normal of the incline n = (sin α, cos α)
    // (the ground cuboid turned by −α, its top face through the origin).
    let (tx, ty, nx, ny) = (c, -s, s, c);
    // Each of the two lower corners carries m g cos α/2; start at that static penetration.
    let d0 = (INC_M * G * c / 2.0 / INC_K).powf(2.0 / 3.0);
    // Start 0.5 m up the slope from the origin (the stop comes 0.26 m further down).
    let s0 = -0.5;
    let (x0, y0) = (s0 * tx + nx * (INC_HY - d0), s0 * ty + ny * (INC_HY - d0));
    format!(
        r#"
[model]
name = "incline"
gravity = [0.0, {gy:?}]

[[body]]
name = "block"
mass = {INC_M:?}
inertia = {inertia:?}
position = [{x0:?}, {y0:?}]
angle = {a:?}
velocity = [{vx:?}, {vy:?}]
angular_velocity = 0.0

[[shape]]
name = "slope"
at = {{ body = "ground", at = [{gx:?}, {gyy:?}] }}    # top face through the origin
angle = {a:?}
geometry = {{ type = "cuboid", half_extents = [2.0, 0.05] }}    # 4 m long, 0.1 m thick

[[shape]]
name = "base"
at = {{ body = "block", at = [0.0, 0.0] }}
geometry = {{ type = "cuboid", half_extents = [{INC_HX:?}, {INC_HY:?}] }}

[[clearance]]
name = "contact"
type = "contact"
shapes = ["slope", "base"]
# restitution 0.5 (assumed): it only damps the start's small heave/pitch vibration
normal = {{ law = "hertz", stiffness = {INC_K:?}, damping = "hc-exact", restitution = 0.5 }}
friction = {{ law = "coulomb", mu = {INC_MU:?}, v_reg = {INC_VREG:?} }}

[solver]
rtol = 1e-8
atol = 1e-11

[output]
t_end = 0.6         # the rigid block stops at v0/a_d = 0.527 s
intervals = 20000   # 30 µs rows: 5.7e-5 m/s of speed change per row (a_d = 1.89 m/s²)
"#,
        gy = -G,
        inertia = INC_M * (4.0 * INC_HX * INC_HX + 4.0 * INC_HY * INC_HY) / 12.0,
        a = -INC_ALPHA,
        vx = INC_V0 * tx,
        vy = INC_V0 * ty,
        gx = -0.05 * nx,
        gyy = -0.05 * ny
    )
}

/// `contact.shapes.incline.stop_distance`.
fn incline_case() -> Case {
    let (s, c) = INC_ALPHA.sin_cos();
    let decel = G * (INC_MU * c - s);
    let reference = INC_V0 * INC_V0 / (2.0 * decel);
    // The regularized law never sticks (below v_reg it creeps at v_reg tan α/μ), so the stop is
    // where the speed first falls below v_th = 10 v_reg; above v_reg the law is exactly Coulomb,
    // so the rigid block is then d(v_th) = (v0² − v_th²)/(2 a_d) down the slope.
    let v_th = 10.0 * INC_VREG;
    // Tolerance (relative): (i) the regularization: (v_th/v0)² = 1e-6; (ii) the compliance: the
    // work–energy balance leaves out the contacts' elastic energy and the heave/pitch vibration
    // the sudden friction moment excites at the start and at the stop; each is of the order of
    // the elastic energy stored at the static penetration, E_el = 2·(2/5) N δ0 (two corners,
    // N = m g cos α/2, δ0 = (N/K)^{2/3}), so 4 E_el/(½ m v0²) covers both; (iii) integration at
    // rtol 1e-8: ≈ 1e-8 of the block's 0.5 m distance from the origin, 2e-8 of d (included as
    // 1e-7).
    let n = INC_M * G * c / 2.0;
    let e_el = 2.0 * 0.4 * n * (n / INC_K).powf(2.0 / 3.0);
    let tol = (v_th / INC_V0).powi(2) + 4.0 * e_el / (0.5 * INC_M * INC_V0 * INC_V0) + 1e-7;
    let case = Case::new(
        "contact.shapes.incline.stop_distance",
        "sliding distance of a block launched down an incline with Coulomb friction",
        "m",
        "work–energy: d = v0²/(2g(μ cos α − sin α)) (rigid block, μ > tan α)",
    );
    let measured = run(&incline_model()).and_then(|res| {
        let t = col(&res, "t")?;
        let (x, y) = (col(&res, "block.x")?, col(&res, "block.y")?);
        let (vx, vy) = (col(&res, "block.vx")?, col(&res, "block.vy")?);
        let along = |k: usize| (x[k] - x[0]) * c - (y[k] - y[0]) * s;
        let speed: Vec<f64> = (0..t.len()).map(|k| vx[k] * c - vy[k] * s).collect();
        let t_stop = first_fall_below(&t, &speed, v_th, 0.0)
            .ok_or_else(|| format!("the speed never fell below {v_th} m/s"))?;
        let k = t.partition_point(|&ti| ti < t_stop).max(1);
        let f = (t_stop - t[k - 1]) / (t[k] - t[k - 1]);
        let d = along(k - 1) + f * (along(k) - along(k - 1));
        let creep = *speed.last().unwrap_or(&f64::NAN);
        Ok((d, t_stop, creep, res.stats.accepted))
    });
    match measured {
        Ok((d, t_stop, creep, steps)) => case.relative(d, reference, tol).note(format!(
            "α = {INC_ALPHA} rad, μ = {INC_MU}, v0 = {INC_V0} m/s, v_reg = {INC_VREG} m/s; speed \
             below {v_th} m/s at t = {t_stop:.5} s (rigid: {:.5} s); relative error {:.2e} \
             (−(v_th/v0)² = {:.1e}); creep speed at the end {creep:.3e} m/s (v_reg tan α/μ = \
             {:.3e}); {steps} steps",
            INC_V0 / decel,
            (d - reference) / reference,
            -(v_th / INC_V0).powi(2),
            INC_VREG * INC_ALPHA.tan() / INC_MU
        )),
        Err(e) => case.failed(reference, e),
    }
}

// ---------------------------------------------------------------------------------------------
// 3. Eccentric cam and flat-faced follower
// ---------------------------------------------------------------------------------------------

/// Disc radius R and eccentricity e of the cam, m (the example models/examples/cam_follower.toml).
const CAM_R: f64 = 0.03;
const CAM_E: f64 = 0.005;
/// Half thickness of the follower block, m (its lower face touches the cam).
const CAM_H: f64 = 0.005;
/// Follower mass, kg; return-spring stiffness, N/m; spring preload at mid-stroke, N (as the
/// example).
const CAM_M: f64 = 0.2;
const CAM_K: f64 = 2000.0;
const CAM_F0: f64 = 20.0;
/// Height of the spring's ground anchor, m (any height above the follower).
const CAM_YA: f64 = 0.2;
/// Hertz stiffness of the disc on the follower face, N/m^1.5 (assumed; it only sets the
/// compliance that the cases account for).
const CAM_KH: f64 = 1e10;

/// The follower's weight plus the spring preload at mid-stroke, N.
fn cam_w() -> f64 {
    CAM_M * G + CAM_F0
}

/// Rigid-body contact force at cam angle φ (from mid-stroke, rising), N: Newton's law on the
/// follower (derivation in `cam_cases`), N = m g + F0 + (k e − m e ω²) sin φ.
fn cam_rigid_force(omega: f64, phi: f64) -> f64 {
    cam_w() + (CAM_K * CAM_E - CAM_M * CAM_E * omega * omega) * phi.sin()
}

/// The cam model at speed `omega` (rad/s), run to `t_end` s with `intervals` output rows:
/// the cam's eccentricity along +x at t = 0 (mid-stroke, rising), the follower started on the
/// quasi-static state of the Hertz contact (module note in `cam_cases`). Undamped Hertz law
/// (`damping = "none"`): the closed forms are for a rigid contact; the elastic part is the only
/// compliance, and a damping term (which divides by the floored impact velocity of a contact
/// that exists from the start) would change the contact force.
fn cam_model(omega: f64, t_end: f64, intervals: usize) -> String {
    let n0 = cam_w(); // φ = 0: no acceleration, spring at its preload
    let d0 = (n0 / CAM_KH).powf(2.0 / 3.0);
    let ndot0 = (CAM_K * CAM_E - CAM_M * CAM_E * omega * omega) * omega;
    let y0 = CAM_R + CAM_H - d0;
    let v0 = CAM_E * omega - 2.0 / 3.0 * d0 * ndot0 / n0;
    let free_length = CAM_F0 / CAM_K + CAM_YA - (CAM_R + CAM_H);
    format!(
        r#"
[model]
name = "cam"
gravity = [0.0, {gy:?}]

[[body]]
name = "cam"
mass = 0.5          # kg, and inertia kg·m²: irrelevant, the cam's angle is driven
inertia = 2.5e-4
position = [0.0, 0.0]
angle = 0.0
angular_velocity = {omega:?}

[[body]]
name = "follower"
mass = {CAM_M:?}
inertia = 1.083e-4  # kg·m², m (L² + h²)/12 of 80 × 10 mm: irrelevant, the guide holds the angle
position = [0.0, {y0:?}]
angle = 0.0
velocity = [0.0, {v0:?}]
angular_velocity = 0.0

[[joint]]
name = "pivot"
type = "revolute"
a = {{ body = "ground", at = [0.0, 0.0] }}
b = {{ body = "cam", at = [0.0, 0.0] }}

[[joint]]
name = "guide"
type = "translational"
a = {{ body = "ground", at = [0.0, 0.0] }}
b = {{ body = "follower", at = [0.0, 0.0] }}
axis = [0.0, 1.0]

[[driver]]
name = "drive"
type = "angle"
body = "cam"
motion = {{ type = "linear", initial = 0.0, rate = {omega:?} }}

[[force]]
name = "spring"
type = "spring_damper"
a = {{ body = "ground", at = [0.0, {CAM_YA:?}] }}
b = {{ body = "follower", at = [0.0, 0.0] }}
stiffness = {CAM_K:?}
free_length = {free_length:?}

[[shape]]
name = "profile"
at = {{ body = "cam", at = [{CAM_E:?}, 0.0] }}
geometry = {{ type = "ball", radius = {CAM_R:?} }}

[[shape]]
name = "face"
at = {{ body = "follower", at = [0.0, 0.0] }}
geometry = {{ type = "cuboid", half_extents = [0.04, {CAM_H:?}] }}    # ±40 mm > ±e sideways travel

[[clearance]]
name = "contact"
type = "contact"
shapes = ["profile", "face"]
# undamped: the restitution is unused (1.0 = elastic)
normal = {{ law = "hertz", stiffness = {CAM_KH:?}, damping = "none", restitution = 1.0 }}

[solver]
rtol = 1e-10    # integration error ~1e-12 m against a compliance of ~1e-6 m
atol = 1e-13

[output]
t_end = {t_end:?}
intervals = {intervals}
"#,
        gy = -G
    )
}

/// The lag constant c of the similarity solution of a Hertz contact unloading at a constant
/// rate: with m δ̈ + K δ^{3/2} = −ṅ (t − t*) (the rigid contact force falling through 0 at t*)
/// and δ = δ_s x, t − t* = τ s, τ = (m^{3/2}/(K ṅ^{1/2}))^{2/7}, δ_s = ṅ τ³/m, the penetration
/// obeys x'' + x^{3/2} = −s with x ≈ (−s)^{2/3} (quasi-static) as s → −∞; it reaches 0 at s = c.
/// RK4 from s = −200 (the start's residual oscillation has died to < 1e-4 in c there: c = 0.48197,
/// 0.48204, 0.48209 from −100, −200, −400) with a step of 2e-3 (c unchanged to 1e-8 at 1e-3).
fn hertz_lag_constant() -> f64 {
    let f = |s: f64, x: f64| -s - x.max(0.0).powf(1.5);
    let (mut s, h) = (-200.0f64, 2e-3);
    let (mut x, mut v) = ((-s).powf(2.0 / 3.0), -2.0 / 3.0 * (-s).powf(-1.0 / 3.0));
    loop {
        let (k1x, k1v) = (v, f(s, x));
        let (k2x, k2v) = (v + 0.5 * h * k1v, f(s + 0.5 * h, x + 0.5 * h * k1x));
        let (k3x, k3v) = (v + 0.5 * h * k2v, f(s + 0.5 * h, x + 0.5 * h * k2x));
        let (k4x, k4v) = (v + h * k3v, f(s + h, x + h * k3x));
        let xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if xn <= 0.0 {
            return s + h * x / (x - xn);
        }
        (s, x, v) = (s + h, xn, vn);
    }
}

/// Lift-off angle (rad) of an independent one-degree-of-freedom model of the same follower:
/// m ÿ = K δ^{3/2} − m g − F0 − k (y − y_mid), δ = y_mid + e sin ωt − y, integrated by RK4 with a
/// 0.1 µs step from the same initial state as `cam_model`; the first δ = 0 crossing. A
/// cross-check for the note (same physics, no multibody code, no contact geometry).
fn cam_one_dof_lift_off(omega: f64) -> f64 {
    let y_mid = CAM_R + CAM_H;
    let n0 = cam_w();
    let d0 = (n0 / CAM_KH).powf(2.0 / 3.0);
    let ndot0 = (CAM_K * CAM_E - CAM_M * CAM_E * omega * omega) * omega;
    let (mut t, mut y, mut v, h) = (
        0.0f64,
        y_mid - d0,
        CAM_E * omega - 2.0 / 3.0 * d0 * ndot0 / n0,
        1e-7,
    );
    let depth = |t: f64, y: f64| y_mid + CAM_E * (omega * t).sin() - y;
    let acc = |t: f64, y: f64| {
        (CAM_KH * depth(t, y).max(0.0).powf(1.5) - n0 - CAM_K * (y - y_mid)) / CAM_M
    };
    // at most 10 revolutions
    while t < 20.0 * std::f64::consts::PI / omega {
        let (k1y, k1v) = (v, acc(t, y));
        let (k2y, k2v) = (v + 0.5 * h * k1v, acc(t + 0.5 * h, y + 0.5 * h * k1y));
        let (k3y, k3v) = (v + 0.5 * h * k2v, acc(t + 0.5 * h, y + 0.5 * h * k2y));
        let (k4y, k4v) = (v + h * k3v, acc(t + h, y + h * k3y));
        let yn = y + h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y);
        let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        let (d, dn) = (depth(t, y), depth(t + h, yn));
        if d > 0.0 && dn <= 0.0 {
            return omega * (t + h * d / (d - dn));
        }
        (t, y, v) = (t + h, yn, vn);
    }
    f64::NAN
}

/// Newton's law on the follower (mass m, upward y, in contact: y = y_mid + e sin φ, φ = ωt from
/// mid-stroke rising, so ÿ = −e ω² sin φ): contact force N ≥ 0 up, weight m g and spring force
/// F0 + k (y − y_mid) down, m ÿ = N − m g − F0 − k e sin φ, hence
/// N(φ) = m g + F0 + (k e − m e ω²) sin φ. With m e ω² > k e, N is smallest at sin φ = 1 and
/// stays positive iff m e ω² < F0 + m g + k e: ω* = √((F0 + m g + k e)/(m e)). Above ω*, N
/// first vanishes at sin φ* = (F0 + m g)/(m e ω² − k e), φ* ∈ (0, π/2).
///
/// Compliance: with a Hertz contact the follower rides (N/K)^{2/3} below the rigid lift. Started
/// on that quasi-static state (δ0 = (N(0)/K)^{2/3}, δ̇0 = (2/3) δ0 Ṅ(0)/N(0)), it stays on it up
/// to its inertia on the contact spring: a relative (ω/ω_c)² of the variation, with
/// ω_c = √(1.5 K δ^{1/2}/m) the follower's frequency on the contact (at 0.95 ω*: ≈ 1.2e4 rad/s
/// at the largest force, ≈ 7e3 rad/s at the smallest, so (ω/ω_c)² ≈ 2e-4 … 6e-4); near
/// lift-off the contact stiffness vanishes and the separation lags φ* by c ω τ
/// (`hertz_lag_constant`).
fn cam_cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    let omega_star = ((CAM_F0 + CAM_M * G + CAM_K * CAM_E) / (CAM_M * CAM_E)).sqrt();
    if filter.wants("contact.shapes.cam.lift") || filter.wants("contact.shapes.cam.min_force") {
        out.extend(cam_below_cases(0.95 * omega_star));
    }
    if filter.wants("contact.shapes.cam.lift_off") {
        out.push(cam_lift_off_case(1.3 * omega_star));
    }
    out
}

/// One revolution at ω = 0.95 ω* (in contact throughout): the lift against the rigid lift and
/// the smallest contact force against Newton's law.
fn cam_below_cases(omega: f64) -> Vec<Case> {
    let period = 2.0 * std::f64::consts::PI / omega;
    // 4000 output rows per revolution: 1.6e-3 rad of cam angle, the lift's extremes to 1e-6 e
    let measured = run(&cam_model(omega, period, 4000)).and_then(|res| {
        let t = col(&res, "t")?;
        let y = col(&res, "follower.y")?;
        let n = col(&res, "contact.normal_force")?;
        let rigid = |t: f64| CAM_R + CAM_H + CAM_E * (omega * t).sin();
        let dev = t
            .iter()
            .zip(&y)
            .map(|(&ti, &yi)| (yi - rigid(ti)).abs())
            .fold(0.0f64, f64::max);
        let n_min = n.iter().copied().fold(f64::INFINITY, f64::min);
        Ok((dev, n_min, res.stats.accepted))
    });
    // The largest Hertz compliance over the revolution: at the largest rigid contact force
    // m g + F0 + |k e − m e ω²| (sin φ = ∓1).
    let n_max = cam_w() + (CAM_K * CAM_E - CAM_M * CAM_E * omega * omega).abs();
    let compliance = (n_max / CAM_KH).powf(2.0 / 3.0);
    let n_min_ref = cam_rigid_force(omega, std::f64::consts::FRAC_PI_2);
    let lift = Case::new(
        "contact.shapes.cam.lift",
        "largest departure of the follower from the eccentric-cam lift y_mid + e sin ωt, / e",
        "-",
        "flat face on an eccentric disc: y = y_mid + e sin ωt exactly; the Hertz contact lowers \
         it by (N/K)^{2/3}, largest at the largest contact force N_max = m g + F0 + |k e − m e ω²|",
    );
    let force = Case::new(
        "contact.shapes.cam.min_force",
        "smallest contact force over a revolution at 0.95 ω* (no lift-off)",
        "N",
        "Newton's law on the follower: N_min = F0 + m g + k e − m e ω² (> 0 below ω*)",
    );
    match measured {
        // Tolerance 1e-3 relative of the compliance: the follower leaves the quasi-static state by
        // (ω/ω_c)² ≈ 2e-4 of the compliance variation where the compliance is largest
        // (`cam_cases`), and the integration error at rtol 1e-10 is ~1e-12 m against a
        // compliance of 2.6e-6 m.
        Ok((dev, n_min, steps)) => vec![
            lift.relative(dev / CAM_E, compliance / CAM_E, 1e-3)
                .note(format!(
                    "ω = 0.95 ω* = {omega:.3} rad/s, one revolution; max |y − y_rigid| = {dev:.4e} \
                     m, (N_max/K)^(2/3) = {compliance:.4e} m (N_max = {n_max:.3} N); e = {CAM_E} \
                     m, ball (exact circle) profile; {steps} steps"
                )),
            // Tolerance 1e-2 relative: the contact force follows the rigid one up to the
            // follower's inertia on the contact spring, (ω/ω_c)² ≈ 6e-4 (ω_c ≈ 7e3 rad/s at the
            // smallest force, `cam_cases`) of the force variation |k e − m e ω²| ≈ 19 N, i.e.
            // ≈ 0.011 N or 0.4 % of N_min ≈ 3.1 N; 1e-2 is 2.5 times that.
            force.relative(n_min, n_min_ref, 1e-2).note(format!(
                "ω = {omega:.3} rad/s; ω* = {:.3} rad/s",
                omega / 0.95
            )),
        ],
        Err(e) => vec![
            lift.failed(compliance / CAM_E, e.clone()),
            force.failed(n_min_ref, e),
        ],
    }
}

/// At ω = 1.3 ω*: the cam angle where the follower leaves the cam.
fn cam_lift_off_case(omega: f64) -> Case {
    let a = CAM_M * CAM_E * omega * omega - CAM_K * CAM_E;
    let phi_star = (cam_w() / a).asin();
    // The lag of the Hertz contact (`hertz_lag_constant`): the rigid force falls through zero at
    // the rate ṅ = A ω cos φ*, A = m e ω² − k e.
    let ndot = a * omega * phi_star.cos();
    let tau = (CAM_M.powf(1.5) / (CAM_KH * ndot.sqrt())).powf(2.0 / 7.0);
    let c = hertz_lag_constant();
    let lag = c * omega * tau;
    let reference = phi_star + lag;
    let t_star = phi_star / omega;
    let case = Case::new(
        "contact.shapes.cam.lift_off",
        "cam angle (from mid-stroke) where the follower lifts off, at 1.3 ω*",
        "rad",
        "Newton's law on the follower: sin φ* = (F0 + m g)/(m e ω² − k e), plus the Hertz lag \
         c·ω·τ, τ = (m^{3/2}/(K ṅ^{1/2}))^{2/7}, ṅ = (m e ω² − k e) ω cos φ*, c = 0.482 \
         (similarity solution of m δ̈ + K δ^{3/2} = −ṅ t)",
    );
    // Run to 1.5 t* (past the lift-off, t* + lag ≈ 1.04 t*), output rows every 1e-3 of t*
    // (interpolation error of the crossing far below the tolerance).
    let measured = run(&cam_model(omega, 1.5 * t_star, 1500)).and_then(|res| {
        let t = col(&res, "t")?;
        let pen = col(&res, "contact.penetration")?;
        let t_sep = first_fall_below(&t, &pen, 0.0, 0.0)
            .ok_or_else(|| "the follower did not lift off".to_string())?;
        Ok((omega * t_sep, res.stats.accepted))
    });
    match measured {
        // Tolerance 10 % of the lag: the similarity solution takes the rigid force as linear in
        // t and the start at s → −∞; over the few τ of the lag the force's slope changes by
        // tan φ*·ωτ ≈ 2.6 % per τ, and the start at s0 = −t*/τ ≈ −12 changes c by ≈ 1 %.
        Ok((phi, steps)) => case
            .relative(phi, reference, 0.1 * lag / reference)
            .note(format!(
            "ω = 1.3 ω* = {omega:.3} rad/s; rigid φ* = {phi_star:.5} rad, lag c ω τ = {lag:.5} rad \
             (c = {c:.5}, τ = {tau:.3e} s); measured − rigid = {:.5} rad; independent 1-DOF \
             Newton model (RK4, 0.1 µs): {:.6} rad; {steps} steps",
            phi - phi_star,
            cam_one_dof_lift_off(omega)
        )),
        Err(e) => case.failed(reference, e),
    }
}

// ---------------------------------------------------------------------------------------------
// 4. Gear pair: speed ratio
// ---------------------------------------------------------------------------------------------

/// Module, m, and tooth numbers (the example models/examples/gear_pair_backlash.toml).
const GEAR_M: f64 = 0.002;
const GEAR_Z1: u32 = 20;
const GEAR_Z2: u32 = 40;
/// Circumferential backlash of the pair, m (each gear thinned by half of it).
const GEAR_J: f64 = 1e-4;
/// Drive speed of gear 1, rad/s (assumed: 477 rpm, mesh frequency 159 Hz).
const GEAR_W1: f64 = 50.0;
/// Resisting torque on gear 2, N·m (assumed: 53 N of tooth force along the line of action).
const GEAR_T: f64 = 2.0;
/// Tooth contact stiffness per contact point, N/m: ISO 6336-1 single-pair stiffness
/// c' ≈ 14 N/(mm·µm) for a 10 mm face width (as the example).
const GEAR_K: f64 = 1.4e8;

/// The two gears as clr-contact builds them (the model file's `involute_gear` shapes).
fn gear_geometry() -> (InvoluteGear, InvoluteGear) {
    (
        InvoluteGear::new(GEAR_M, GEAR_Z1).with_backlash(0.5 * GEAR_J),
        InvoluteGear::new(GEAR_M, GEAR_Z2).with_backlash(0.5 * GEAR_J),
    )
}

/// The gear model: gear 1 driven at GEAR_W1 from θ1 = 0, gear 2 loaded by +GEAR_T (counter-
/// clockwise, against its clockwise rotation), started on its drive flanks: θ2 = π − π/z2 + u,
/// u = j/(2 r_p2) (the drive flanks of exact involutes touch, clr-contact gears.rs tests) plus
/// the static deflection F/(k r_b2). Run for `periods` mesh periods with 100 output rows each.
fn gear_model(periods: usize) -> String {
    let (g1, g2) = gear_geometry();
    let (z1, z2) = (f64::from(GEAR_Z1), f64::from(GEAR_Z2));
    let a = 0.5 * GEAR_M * (z1 + z2);
    let (rp2, rb2) = (g2.pitch_radius(), g2.base_radius());
    let u = GEAR_J / (2.0 * rp2) + GEAR_T / rb2 / GEAR_K / rb2;
    let th2 = std::f64::consts::PI - std::f64::consts::PI / z2 + u;
    // steel discs of the pitch diameter, 10 mm wide (ρ = 7850 kg/m³): m = ρ π r² b, I = m r²/2
    let disc = |r: f64| {
        let m = 7850.0 * std::f64::consts::PI * r * r * 0.01;
        (m, 0.5 * m * r * r)
    };
    let ((m1, i1), (m2, i2)) = (disc(g1.pitch_radius()), disc(rp2));
    let period = 2.0 * std::f64::consts::PI / (z1 * GEAR_W1);
    format!(
        r#"
[model]
name = "gears"

[[body]]
name = "gear1"
mass = {m1:?}
inertia = {i1:?}
position = [0.0, 0.0]
angle = 0.0
angular_velocity = {GEAR_W1:?}

[[body]]
name = "gear2"
mass = {m2:?}
inertia = {i2:?}
position = [{a:?}, 0.0]
angle = {th2:?}
angular_velocity = {w2:?}

[[joint]]
name = "bearing1"
type = "revolute"
a = {{ body = "ground", at = [0.0, 0.0] }}
b = {{ body = "gear1", at = [0.0, 0.0] }}

[[joint]]
name = "bearing2"
type = "revolute"
a = {{ body = "ground", at = [{a:?}, 0.0] }}
b = {{ body = "gear2", at = [0.0, 0.0] }}

[[driver]]
name = "motor"
type = "angle"
body = "gear1"
motion = {{ type = "linear", initial = 0.0, rate = {GEAR_W1:?} }}

[[force]]
name = "load"
type = "torque"
body = "gear2"
torque = {{ type = "constant", value = {GEAR_T:?} }}

[[shape]]
name = "teeth1"
at = {{ body = "gear1", at = [0.0, 0.0] }}
geometry = {{ type = "involute_gear", module = {GEAR_M:?}, teeth = {GEAR_Z1}, backlash = {bl:?} }}

[[shape]]
name = "teeth2"
at = {{ body = "gear2", at = [0.0, 0.0] }}
geometry = {{ type = "involute_gear", module = {GEAR_M:?}, teeth = {GEAR_Z2}, backlash = {bl:?} }}

[[clearance]]
name = "mesh"
type = "contact"
shapes = ["teeth1", "teeth2"]
# restitution 0.5 (assumed); with the default min_impact_velocity (1e-4 m/s) the damping of the
# persistent mesh contact is strong, which settles the start transient within the first period
normal = {{ law = "linear", stiffness = {GEAR_K:?}, damping = "hc-exact", restitution = 0.5 }}

[solver]
rtol = 1e-6     # integration error far below the chord-error tolerance
atol = 1e-9

[output]
t_end = {t_end:?}
intervals = {intervals}
"#,
        w2 = -GEAR_W1 * z1 / z2,
        bl = 0.5 * GEAR_J,
        t_end = periods as f64 * period,
        intervals = 100 * periods
    )
}

/// `contact.shapes.gear.ratio`.
fn gear_case() -> Case {
    let (g1, g2) = gear_geometry();
    let (z1, z2) = (f64::from(GEAR_Z1), f64::from(GEAR_Z2));
    let reference = -z1 / z2;
    let rb2 = g2.base_radius();
    // Mean over mesh periods 2 and 3 (the first holds the start transient: the polygon teeth
    // start up to the chord error apart and the load is applied at once).
    let (first, periods) = (1usize, 3usize);
    let window = (periods - first) as f64 * 2.0 * std::f64::consts::PI / z1;
    // Tolerance (relative): with the transmission error TE = θ2 + (z1/z2) θ1 (up to a constant),
    // the mean ratio over the window is −z1/z2 + ΔTE/Δθ1, so the relative error is
    // ΔTE/((z1/z2) Δθ1). |ΔTE| is bounded by the spread of TE: the polygon flanks lie inside the
    // involutes by 0 … e_i (chord error), which moves the touch angle of gear 2 by at most
    // (e1 + e2)/r_b2 (clr-contact gears.rs, test `mesh_backlash_ratio_and_line_of_action` (b));
    // the tooth deflection F/k along the line of action (F = T/r_b2; one contact point taking
    // all of it; ×2 for the dynamic overshoot of a suddenly applied load) moves it by at most
    // 2F/(k r_b2). (Over whole mesh periods the periodic parts of TE cancel: the measured error
    // is far smaller.)
    let chord = g1.max_chord_error() + g2.max_chord_error();
    let deflection = 2.0 * GEAR_T / rb2 / GEAR_K;
    let tol = (chord + deflection) / rb2 / (window * z1 / z2);
    let case = Case::new(
        "contact.shapes.gear.ratio",
        "mean speed ratio ω2/ω1 of an involute gear pair under load, over whole mesh periods",
        "-",
        "conjugate action of involute profiles: ω2/ω1 = −z1/z2 (Litvin & Fuentes, Gear Geometry \
         and Applied Theory, 2004, ch. 10)",
    );
    let measured = run(&gear_model(periods)).and_then(|res| {
        let th1 = col(&res, "gear1.theta")?;
        let th2 = col(&res, "gear2.theta")?;
        // rows at whole mesh periods: 100 per period
        let (ka, kb) = (100 * first, 100 * periods);
        if th1.len() <= kb {
            return Err(format!("{} output rows, expected {}", th1.len(), kb + 1));
        }
        let ratio = (th2[kb] - th2[ka]) / (th1[kb] - th1[ka]);
        let te: Vec<f64> = (ka..=kb)
            .map(|k| (th2[k] - th2[ka]) + z1 / z2 * (th1[k] - th1[ka]))
            .collect();
        let ripple = te.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - te.iter().copied().fold(f64::INFINITY, f64::min);
        let points = col(&res, "mesh.contact")?;
        let most = points[ka..=kb].iter().copied().fold(0.0f64, f64::max);
        Ok((ratio, ripple, most, res.stats.accepted))
    });
    match measured {
        Ok((ratio, ripple, most, steps)) => case.relative(ratio, reference, tol).note(format!(
            "m = {GEAR_M} m, z1 = {GEAR_Z1}, z2 = {GEAR_Z2}, ω1 = {GEAR_W1} rad/s, load {GEAR_T} \
             N·m, 24 points per flank (chord errors e1 + e2 = {chord:.3e} m); relative error \
             {:.2e}; \
             transmission-error ripple over periods 2–3: {ripple:.3e} rad of gear 2 \
             ({:.3e} m along the line of action; bound (e1 + e2 + 2F/k)/r_b2 = {:.3e} rad); up to \
             {most} active contact points; {steps} steps",
            (ratio - reference) / reference,
            ripple * rb2,
            (chord + deflection) / rb2
        )),
        Err(e) => case.failed(reference, e),
    }
}
