//! Verification case of the guide's finding map (issue 19, `clr_models::guide_map`): one point of
//! the map, evaluated by the map's own code, against the closed form of docs/models/guide.md
//! (friction findings): without a second load path and with a load moment below W·L/2 the pad
//! stays on one face, so the mean friction is μW whatever the clearance, and the margin of the
//! finding "friction decreases with clearance" is 0 within that tolerance.

use super::Filter;
use crate::report::Case;

/// The point, chosen before any run: inside every range of `guide_map::parameters`, no second
/// load path (support_log10_stiffness 2.5 < 3) and e = 0.01 m < L/2 = 0.04 m.
fn point() -> clr_models::guide_map::MapPoint {
    clr_models::guide_map::MapPoint {
        load_offset: 0.01,
        slider_length: 0.08,
        pad_height: 0.012,
        clearance_min: 0.2e-3,
        clearance_ratio: 5.0,
        guide_depth: 0.035,
        support_log10_stiffness: 2.5,
        speed: 0.5,
    }
}

/// Integration sensitivity of the guide's friction measures (|Δμ_eq| = 0.27 % between rtol 1e-4
/// and 1e-5, docs/models/guide.md, rounded up): verify's own.
const INTEGRATION_SENSITIVITY: f64 = 0.003;

pub fn cases(filter: &Filter) -> Vec<Case> {
    use clr_models::common::FrictionParams;
    use clr_models::guide::FRICTION_DURATION;
    use clr_models::guide_map::{self, parameters, point_runs};
    if !filter.wants("models.guide.map") {
        return Vec::new();
    }
    let p = point();
    let base = p.base();
    let mu = match base.friction {
        FrictionParams::Ambrosio { mu, .. } => mu,
        _ => f64::NAN,
    };
    let (w, m, t) = (base.lateral_load, base.slider_mass, FRICTION_DURATION);
    // Tolerance δ of F̄ = μW (relative). Over [0, T] the slider's lateral momentum balance gives
    // ∫ΣF_N dt = W·T + m·v_y(T) with the pad on one face (F_lower = 0), and with |v_T| ≥ v₁
    // (sliding at 0.125–0.5 m/s) Σ|F_T| = μ ΣF_N, so F̄/(μW) − 1 = m·v_y(T)/(W·T). The load's
    // work bounds the lateral speed: ½ m v² ≤ W·(c + y_st/2) (drop across the clearance, then
    // the guide's deflection; the guide's own mass and all dissipation left out, so an upper
    // bound), y_st = W x³/(3EI) the static deflection of the cantilever under the load at the
    // farthest slider position x = start + v·T, c the largest clearance; plus the integration
    // sensitivity.
    let c = p.clearances()[3];
    let ei = base.youngs_modulus * base.guide_width * base.guide_depth.powi(3) / 12.0;
    let x = base.start + p.speed * t;
    let y_st = w * x.powi(3) / (3.0 * ei);
    let v_hat = (2.0 * w * (c + 0.5 * y_st) / m).sqrt();
    let delta = m * v_hat / (w * t) + INTEGRATION_SENSITIVITY;
    let src = format!(
        "closed form of docs/models/guide.md (friction findings): k = 0 and W·e < W·L/2 keep \
         the pad on one face, so the mean friction is μW at every clearance; tolerance δ = \
         m·v̂/(W·T) + {INTEGRATION_SENSITIVITY} = {delta:.4} (lateral momentum m·v_y(T) with \
         |v_y| ≤ v̂ = √(2W(c₃ + y_st/2)/m) = {v_hat:.3} m/s from the load's work, y_st = \
         W x³/(3EI) = {:.3} mm at x = {x:.2} m; plus verify's integration sensitivity)",
        y_st * 1e3
    );
    let inside = parameters()
        .iter()
        .zip(p.values())
        .all(|(q, v)| (0.0..=1.0).contains(&q.coordinate_of(v)));
    let spec = |id: &str, what: &str| Case::new(id, what, "-", src.clone());
    let id_f = "models.guide.map.mean_friction";
    let id_m = "models.guide.map.clearance_friction_margin";
    let start = std::time::Instant::now();
    let runs = match point_runs(&p) {
        Ok(r) => r,
        Err(e) => {
            return vec![spec(id_f, "map point").failed(0.0, e)];
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let ratios: Vec<f64> = runs
        .runs
        .iter()
        .map(|r| r.metric("mean_friction_force") / (mu * w))
        .collect();
    let worst = ratios.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
    let margins = runs.margins();
    let listed = |x: &[f64]| {
        x.iter()
            .map(|v| format!("{v:.4}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    println!(
        "models.guide.map point: {wall:.1} s wall ({} runs in parallel)",
        runs.runs.len()
    );
    vec![
        spec(
            id_f,
            "largest |F̄/(μW) − 1| over the 8 runs of one map point (k = 0, e < L/2)",
        )
        .absolute(if inside { worst } else { f64::NAN }, 0.0, delta)
        .note(format!(
            "F̄/(μW) of {}: {}; point inside every range: {inside}; {wall:.1} s wall",
            runs.runs
                .iter()
                .map(|r| r.name.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            listed(&ratios)
        )),
        spec(
            id_m,
            "margin of `clearance_friction` (smallest decrease of F̄ over c₀–c₃ / F̄₀) at that \
             point: 0 in closed form, within 2δ/(1 − δ)",
        )
        .absolute(margins[0], 0.0, 2.0 * delta / (1.0 - delta))
        .note(format!(
            "margins ({}): {}; clearances {} mm",
            guide_map::findings()
                .iter()
                .map(|f| f.id.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            listed(&margins),
            listed(&p.clearances().map(|c| c * 1e3))
        )),
    ]
}
