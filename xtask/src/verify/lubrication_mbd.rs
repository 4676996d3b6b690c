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
//!
//! The drive torque (the driver's reaction moment) is the film's shear torque on the journal:
//! at the loaded equilibrium T = 2πμr³Lω/(c√(1 − ε²)) + (e/2)·W sin φ (Couette plus
//! pressure-induced shear; Hamrock, Schmid & Jacobson 2004, ch. 10) with ε, φ of the Ocvirk
//! equilibrium above, and with no load (ε = 0) Petroff's T = 2πμr³Lω/c (N.P. Petroff 1883).

use clr_sim::spec::run::{execute, resolve_text};

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
    let mut out = Vec::new();
    if filter.wants("lubrication.mbd.steady_load") {
        out.extend(steady_load());
    }
    if filter.wants("lubrication.mbd.petroff") {
        out.push(petroff());
    }
    out
}

/// Petroff's torque 2πμr³Lω/c scaled by 1/√(1 − ε²), N·m.
fn couette_torque(eps: f64) -> f64 {
    let c = R_BEARING - R_JOURNAL;
    2.0 * std::f64::consts::PI * VISCOSITY * R_JOURNAL.powi(3) * LENGTH * OMEGA
        / (c * (1.0 - eps * eps).sqrt())
}

/// The unloaded journal (ε = 0): drive torque against Petroff's law.
fn petroff() -> Case {
    let reference = couette_torque(0.0);
    let case = Case::new(
        "lubrication.mbd.petroff",
        "drive torque of an unloaded lubricated journal at ω = 200 rad/s (ε = 0)",
        "N·m",
        "Petroff's law T = 2πμr³Lω/c (N.P. Petroff 1883; Hamrock, Schmid & Jacobson 2004, \
         ch. 10); the journal stays centred, so the tolerance 1e-9 relative is round-off",
    );
    match run(0.0) {
        Ok(o) if o.error.is_none() => {
            let m = o.results.column("spin.M").unwrap_or_default();
            let t = m.last().copied().unwrap_or(f64::NAN);
            case.relative(t, reference, 1e-9)
                .note(format!("spin.M at {T_END} s: {t:.9e} N·m"))
        }
        Ok(o) => case.failed(reference, format!("the run failed: {:?}", o.error)),
        Err(e) => case.failed(reference, format!("the model did not build: {e}")),
    }
}

fn run(load: f64) -> Result<clr_sim::spec::run::Outcome, String> {
    resolve_text("<lubricated journal>", &model(load), &[], None, None)
        .map_err(|e| e.to_string())
        .and_then(|job| execute(&job, None, None, None).map_err(|e| e.to_string()))
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

/// The rig (tests/data/lubricated_journal.toml: the constants above, NDF rtol 1e-9, 0.3 s) with
/// a constant downward load (N) on the journal centre when `load` is not 0.
fn model(load: f64) -> String {
    let rig = include_str!("../../../tests/data/lubricated_journal.toml");
    if load == 0.0 {
        return rig.to_string();
    }
    format!(
        "{rig}\n[[force]]\nname = \"load\"\ntype = \"force\"\n\
         at = {{ body = \"journal\", at = [0.0, 0.0] }}\n\
         fy = {{ type = \"constant\", value = {fy} }}\n",
        fy = -load
    )
}

fn steady_load() -> Vec<Case> {
    let eps_ref = ocvirk_eccentricity(LOAD);
    let eps0 = eps_ref.max(1e-3);
    let phi_ref = (std::f64::consts::PI * (1.0 - eps0 * eps0).sqrt() / (4.0 * eps0)).atan();
    let torque_ref =
        couette_torque(eps_ref) + 0.5 * eps_ref * (R_BEARING - R_JOURNAL) * LOAD * phi_ref.sin();
    let mut torque = f64::NAN;
    let (eps, phi, note) = match run(LOAD) {
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
            let spin = o.results.column("spin.M").unwrap_or_default();
            torque = spin.last().copied().unwrap_or(f64::NAN);
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
        .note(note.clone()),
        Case::new(
            "lubrication.mbd.steady_load.drive_torque",
            "drive torque of the loaded journal at equilibrium",
            "N·m",
            "T = 2πμr³Lω/(c√(1−ε²)) + (e/2)·W sin φ at the Ocvirk equilibrium ε, φ (Hamrock, \
             Schmid & Jacobson 2004, ch. 10 and §12.3); tolerance 1 % as ε and φ",
        )
        .relative(torque, torque_ref, 0.01)
        .note(format!(
            "spin.M {torque:.6e} N·m vs {torque_ref:.6e} N·m (Couette {:.6e}); {note}",
            couette_torque(eps_ref)
        )),
    ]
}
