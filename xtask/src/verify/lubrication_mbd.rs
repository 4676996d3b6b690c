//! The lubricated revolute clearance joint in a whole model (clr-mbd with clr-contact's
//! `HydrodynamicBearing`): a journal spinning at a constant speed in a fixed bearing under a
//! constant load settles where the film carries the load — the equilibrium eccentricity ratio
//! and attitude angle of the short-bearing (Ocvirk) theory (Ocvirk 1952, NACA TN 2808;
//! Hamrock, Schmid & Jacobson, Fundamentals of Fluid Film Lubrication, 2nd ed. 2004, §12.3):
//!
//! W = μ U L³ ε / (4c²(1 − ε²)²) · √(16ε² + π²(1 − ε²)),  tan φ = π√(1 − ε²) / (4ε),
//!
//! with U = ω r (journal surface speed), c the radial clearance, L the length. The dynamic
//! run knows nothing of these relations: it integrates the journal's translation under the
//! film force (wedge and squeeze terms) until the squeeze film has damped the transient.
//! Parameters (reconstructed test rig, not from a paper): R = 10 mm, r = 9.9 mm, L = 10 mm
//! (L/D = 0.5), μ = 0.05 Pa·s, ω = 200 rad/s, W = 60 N (ε ≈ 0.8: the short-bearing rigid
//! rotor is stable for every mass above ε ≈ 0.76, so the journal settles instead of whirling).

use clr::spec::run::{execute, resolve_text};

use super::Filter;
use crate::report::Case;

const R_BEARING: f64 = 0.01;
const R_JOURNAL: f64 = 0.0099;
const LENGTH: f64 = 0.01;
const VISCOSITY: f64 = 0.05;
const OMEGA: f64 = 200.0;
const LOAD: f64 = 60.0;
const T_END: f64 = 0.3;

const SOURCE: &str = "Ocvirk short-bearing equilibrium: W = μUL³ε/(4c²(1−ε²)²)·√(16ε²+π²(1−ε²)), \
                      tan φ = π√(1−ε²)/(4ε) (Hamrock, Schmid & Jacobson 2004, §12.3)";

pub fn cases(filter: &Filter) -> Vec<Case> {
    if !filter.wants("lubrication.mbd") {
        return Vec::new();
    }
    steady_load()
}

/// The load capacity (N) of the short bearing at eccentricity ratio ε.
fn ocvirk_load(eps: f64) -> f64 {
    let c = R_BEARING - R_JOURNAL;
    let u = OMEGA * R_JOURNAL;
    let s = 1.0 - eps * eps;
    VISCOSITY * u * LENGTH.powi(3) * eps / (4.0 * c * c * s * s)
        * (16.0 * eps * eps + std::f64::consts::PI.powi(2) * s).sqrt()
}

/// ε with W(ε) = `load`, by bisection (W grows monotonically from 0 to ∞ on [0, 1)).
fn ocvirk_eccentricity(load: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0 - 1e-12);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if ocvirk_load(mid) < load {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

fn model() -> String {
    format!(
        r#"
[model]
name = "lubricated_journal"

[[body]]
name = "journal"
mass = 1.0
inertia = 1e-4
position = [0.0, 0.0]
angle = 0.0
velocity = [0.0, 0.0]
angular_velocity = {OMEGA}

[[driver]]
name = "spin"
type = "angle"
body = "journal"
motion = {{ type = "linear", initial = 0.0, rate = {OMEGA} }}

[[force]]
name = "load"
type = "force"
at = {{ body = "journal", at = [0.0, 0.0] }}
fy = {{ type = "constant", value = {fy} }}

[[clearance]]
name = "J"
type = "revolute"
bearing = {{ body = "ground", at = [0.0, 0.0] }}
journal = {{ body = "journal", at = [0.0, 0.0] }}
bearing_radius = {R_BEARING}
journal_radius = {R_JOURNAL}
normal = {{ law = "hertz", stiffness = 1e10, restitution = 0.9, damping = "lankarani-nikravesh" }}
lubrication = {{ model = "short_bearing", viscosity = {VISCOSITY}, length = {LENGTH}, film_threshold = 1e-6 }}

[solver]
method = "ndf"
rtol = 1e-9

[output]
t_end = {T_END}
intervals = 300
"#,
        fy = -LOAD
    )
}

fn steady_load() -> Vec<Case> {
    let eps_ref = ocvirk_eccentricity(LOAD);
    let eps0 = eps_ref.max(1e-3);
    let phi_ref = (std::f64::consts::PI * (1.0 - eps0 * eps0).sqrt() / (4.0 * eps0)).atan();
    let run = resolve_text("<lubricated journal>", &model(), &[], None, None)
        .map_err(|e| e.to_string())
        .and_then(|job| execute(&job, None, None, None).map_err(|e| e.to_string()));
    let (eps, phi, note) = match run {
        Ok(o) if o.error.is_none() => {
            let ex = o.results.column("J.ex").unwrap_or_default();
            let ey = o.results.column("J.ey").unwrap_or_default();
            let (x, y) = (
                *ex.last().unwrap_or(&f64::NAN),
                *ey.last().unwrap_or(&f64::NAN),
            );
            let e = x.hypot(y);
            let c = R_BEARING - R_JOURNAL;
            // attitude angle: between the load line (−y) and the line of centres
            let phi = (-y / e).clamp(-1.0, 1.0).acos();
            let film = o.results.column("J.film_force").unwrap_or_default();
            (
                e / c,
                phi,
                format!(
                    "journal at ({x:e}, {y:e}) m after {T_END} s; film force {:.4} N (load {LOAD} N); \
                     side of the line of centres: {} (journal spinning counter-clockwise)",
                    film.last().copied().unwrap_or(f64::NAN),
                    if x > 0.0 { "+x" } else { "−x" }
                ),
            )
        }
        Ok(o) => (f64::NAN, f64::NAN, format!("the run failed: {:?}", o.error)),
        Err(e) => (f64::NAN, f64::NAN, format!("the model did not build: {e}")),
    };
    vec![
        Case::new(
            "lubrication.mbd.steady_load.eccentricity",
            "equilibrium eccentricity ratio ε of a loaded spinning journal",
            "-",
            SOURCE,
        )
        .relative(eps, eps_ref, 0.01)
        .note(note.clone()),
        Case::new(
            "lubrication.mbd.steady_load.attitude",
            "equilibrium attitude angle φ",
            "rad",
            SOURCE,
        )
        .relative(phi, phi_ref, 0.01)
        .note(note),
    ]
}
