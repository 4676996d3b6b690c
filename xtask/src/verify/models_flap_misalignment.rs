//! Verification cases of the spatial flap (`clr_models::flap_spatial`, study
//! `flap_misalignment`), ids `models.flap_misalignment.*`:
//! - `planar_reduction.*`: with aligned bearings nothing excites out-of-plane motion, so the
//!   spatial linkage (spatial revolute clearance joint J4 of 0.1 mm, relaxed ideal joints in the
//!   closed loops) must reproduce the planar flap (independent formulation: the planar engine
//!   and its planar revolute clearance joint) over 0.5 s at rtol 1e-8. Tolerances: the peak
//!   contact force 1e-6 relative (a force level set by the hinge load, reached by both within
//!   the integration error), the flap angle error 1e-4 (a difference of two angles 200× smaller
//!   than the swing) and the acceleration oscillation RMS 1e-3 (a difference of accelerations
//!   300× smaller than the peak acceleration, so the integration error is amplified the most).
//! - `edge_loading.rim_share`: with the bore turned 0.1° across the link, the gap along J4's
//!   contact line varies by L·sin α = 26 µm over the 15 mm bearing, far more than any
//!   penetration (a few µm), so only the rim region at one end can touch: the larger region's
//!   share of the radial load is 1 (closed form), tolerance 1e-9.
//! - `edge_loading.play`: the journal then leans on one rim: its centre stops short of the wall
//!   by the rim's lean (L/2)·sin α less the extra rim penetration δ_rim − δ₀, so the flap angle
//!   error drops by Δθ = ((L/2) sin α − (δ_rim − δ₀))/l, l = 0.12 m the auxiliary lever arm that
//!   turns J4's play into flap angle (closed form with the two runs' peak penetrations).
//!   Tolerance 5 % of the drop: the peak penetrations are taken at the load peak, the error's
//!   maximum at a nearby time.

use clr_models::flap::{self, FlapParams};
use clr_models::flap_spatial::{self, Misalignment, TiltAxis};
use clr_models::{Metric, RunSettings};

use super::Filter;
use crate::report::Case;

const SOURCE: &str = "planar flap (clr_models::flap, planar engine) as the independent \
                      formulation; docs/models/flap.md#misalignment";

fn value(m: &[Metric], name: &str) -> f64 {
    clr_models::output::metric_value(m, name)
}

/// The cases (module docs).
pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    if !filter.wants("models.flap_misalignment") {
        return out;
    }
    let p = FlapParams {
        duration: 0.5,
        ..Default::default()
    };
    let settings = RunSettings::default();
    let runs = (|| {
        let ideal = flap::run_ideal_reference("flap", &p, &settings)?;
        let planar = flap::run("flap", &p, &settings)?;
        let aligned = flap_spatial::run("flap", &p, Misalignment::NONE, &ideal)?;
        let across = Misalignment {
            angle: 0.1f64.to_radians(),
            about: TiltAxis::AcrossLink,
        };
        let tilted = flap_spatial::run("flap", &p, across, &ideal)?;
        Ok::<_, clr_models::ModelsError>((planar, aligned, tilted))
    })();
    let (planar, aligned, tilted) = match runs {
        Ok(r) => r,
        Err(e) => {
            out.push(
                Case::new("models.flap_misalignment", "runs", "-", SOURCE)
                    .failed(0.0, e.to_string()),
            );
            return out;
        }
    };
    for (id, metric, unit, tol) in [
        ("contact_force", "J4_peak_contact_force", "N", 1e-6),
        ("angle_error", "flap_angle_error_max", "rad", 1e-4),
        (
            "oscillation_rms",
            "flap_acceleration_oscillation_rms",
            "rad/s^2",
            1e-3,
        ),
    ] {
        let (s, r) = (
            value(&aligned.metrics, metric),
            value(&planar.metrics, metric),
        );
        out.push(
            Case::new(
                format!("models.flap_misalignment.planar_reduction.{id}"),
                format!(
                    "{metric}, aligned spatial flap (J4 0.1 mm, 0.5 s) against the planar flap"
                ),
                unit,
                SOURCE,
            )
            .relative(s, r, tol)
            .note(format!(
                "spatial {s:.9e}, planar {r:.9e}; steps {} against {}",
                value(&aligned.metrics, "steps"),
                value(&planar.metrics, "steps")
            )),
        );
    }
    out.push(play_case(
        &p,
        &aligned.metrics,
        &tilted.metrics,
        0.1f64.to_radians(),
    ));
    let share = value(&tilted.metrics, "J4_rim_share");
    out.push(
        Case::new(
            "models.flap_misalignment.edge_loading.rim_share",
            "share of J4's radial load on its more loaded rim region, bore turned 0.1° across the link",
            "-",
            "closed form: the gap along the contact line varies by L·sin α = 26 µm, more than \
             the penetration, so one rim region carries the load",
        )
        .absolute(share, 1.0, 1e-9)
        .note(format!(
            "peak penetration {:.3e} m against {:.3e} m aligned; tilt {:.4e} rad",
            value(&tilted.metrics, "J4_peak_penetration"),
            value(&aligned.metrics, "J4_peak_penetration"),
            value(&tilted.metrics, "J4_max_tilt")
        )),
    );
    out
}

/// Figures of docs/models/flap.md#misalignment: the study figures under
/// target/models/flap/misalignment (the study is run when they are missing, about 10 min on 2
/// cores) copied to `models-flap-<name>.{svg,png}`.
pub fn figures(dir: &std::path::Path) -> Result<(), String> {
    let sdir = crate::target_dir()
        .join("models")
        .join("flap")
        .join("misalignment");
    if !sdir.join("summary.csv").exists() {
        flap_spatial::study(&sdir)?;
    }
    crate::study_figures::copy_study_figures(
        &sdir,
        &[
            "misalignment_size",
            "misalignment_position",
            "misalignment_penetration",
            "misalignment_rim_share",
        ],
        dir,
        "models-flap-",
    )
}

/// `edge_loading.play` (module docs).
fn play_case(p: &FlapParams, aligned: &[Metric], tilted: &[Metric], alpha: f64) -> Case {
    let lean = 0.5 * p.axial_length * alpha.sin();
    let extra = value(tilted, "J4_peak_penetration") - value(aligned, "J4_peak_penetration");
    let predicted = (lean - extra) / p.aux_lever_arm_length;
    let drop = value(aligned, "flap_angle_error_max") - value(tilted, "flap_angle_error_max");
    Case::new(
        "models.flap_misalignment.edge_loading.play",
        "drop of the largest flap angle error, J4 bore turned 0.1° across the link",
        "rad",
        "closed form: the rim's lean (L/2)·sin α less the extra rim penetration, over the \
         auxiliary lever arm",
    )
    .relative(drop, predicted, 0.05)
    .note(format!(
        "lean {lean:.4e} m, extra penetration {extra:.4e} m, drop {drop:.4e} rad against {predicted:.4e} rad"
    ))
}
