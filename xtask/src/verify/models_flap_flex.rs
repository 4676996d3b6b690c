//! Verification cases of clr-models: the flap linkage with flexible parts (floating-frame beams,
//! `clr_models::flap_flex`), ids `models.flap.flex.*`.

use std::path::Path;

use clr_models::flap::{self, FlapParams};
use clr_models::flap_flex;
use clr_models::flap_flex_study::{self, FlexStudyCase};
use clr_models::RunSettings;

use super::Filter;
use crate::report::Case;

const RECON: &str = "reconstructed flexible flap linkage (docs/models/flap.md; Wan et al. 2022 \
                     give only the parts' eigenfrequencies and the qualitative findings)";

fn flex_dir() -> std::path::PathBuf {
    crate::target_dir().join("models").join("flap").join("flex")
}

/// Output of the verify subset of the study (the full study's outputs stay in `flex_dir`).
fn flex_verify_dir() -> std::path::PathBuf {
    crate::target_dir()
        .join("models")
        .join("flap")
        .join("flex_verify")
}

/// Study base: 0.25 s ramp (excluded from the metrics) + 2 actuator periods (the flexible
/// four-joint runs take minutes at the rigid studies' 2.25 s), rtol 1e-8 as the rigid studies
/// (at 1e-7 NDF fails on the rigid three-joint case).
fn study_base() -> FlapParams {
    FlapParams {
        duration: clr_models::studies::FLAP_FLEX_STUDY_DURATION,
        ..Default::default()
    }
}

fn part_cases(filter: &Filter, out: &mut Vec<Case>) {
    let p = FlapParams::default();
    for k in 0..3 {
        let id = format!("models.flap.flex.reduced_frequency.{}", flap_flex::PARTS[k]);
        if !filter.wants(&id) {
            continue;
        }
        let case = Case::new(
            &id,
            "first frequency of the reduced floating body, pinned–roller (Hz)",
            "Hz",
            "independent formulation: the full 20-element clr-beam model calibrated to the \
             paper's first frequency (Wan et al. 2022 table), against the Craig–Bampton reduction \
             plus the frame rotation with the floating-frame invariants clr-mbd uses; tolerance \
             1 % (the reduced model leaves out the sections' rotary inertia)",
        );
        match flap_flex::flexible_body(&p, k).and_then(|b| {
            let f = b.reduced_first_frequency()?;
            Ok((f, b))
        }) {
            Ok((f, b)) => out.push(
                case.relative(f, b.calibration.frequencies_hz[0], 0.01)
                    .note(format!(
                        "{} reduced coordinates; beam mass ρAL = {:.4} kg",
                        b.reduced.stiffness.nrows(),
                        b.mass()
                    )),
            ),
            Err(e) => out.push(case.failed(0.0, e)),
        }
    }
}

fn kinematics_case(filter: &Filter, out: &mut Vec<Case>) {
    let id = "models.flap.flex.kinematics";
    if !filter.wants(id) {
        return;
    }
    let p = FlapParams {
        clearances: [0.0; 4],
        flexible: [true; 3],
        duration: 0.1,
        ..FlapParams::default()
    };
    let case = Case::new(
        id,
        "max |flap angle (three flexible parts, ideal joints) − closed-form rigid flap angle|",
        "rad",
        "independent formulation: closed-form rigid kinematics (circle intersections, \
         FlapParams::ideal_flap_angle) plus the static deflection of the parts under the hinge \
         load from beam formulas (flap_flex::static_deflection_angle); the parts start \
         undeformed under load, so the deviation must stay below twice the static estimate \
         (undamped step-response peak) and above 0.3 × it (the flexibility shows)",
    );
    let bound = match flap_flex::static_deflection_angle(&p) {
        Ok(b) => b,
        Err(e) => return out.push(case.failed(0.0, e)),
    };
    match flap::run("flap", &p, &RunSettings::default()) {
        Ok(o) => {
            let r = &o.results;
            let t = r.column("t").unwrap_or_default();
            let a = r.column("flap.angle").unwrap_or_default();
            let mut worst = 0.0f64;
            for k in 0..t.len() {
                let x = p.actuator(t[k])[0];
                let cf = p.ideal_flap_angle(x, p.aux_rod_length).unwrap_or(f64::NAN);
                worst = worst.max((a[k] - cf).abs());
            }
            let note = format!(
                "largest deviation {worst:.4e} rad over {} rows, 0.1 s; static estimate \
                 {bound:.4e} rad",
                t.len()
            );
            out.push(case.at_most(worst, 2.0 * bound).note(note.clone()));
            out.push(
                Case::new(
                    format!("{id}.shows"),
                    "same deviation, lower bound 0.3 × the static estimate",
                    "rad",
                    RECON,
                )
                .at_least(worst, 0.3 * bound)
                .note(note),
            );
        }
        Err(e) => out.push(case.failed(0.0, e.to_string())),
    }
}

/// Metrics of the cases whose study satisfies `keep`, one line each.
fn summary(cases: &[FlexStudyCase], keep: impl Fn(&str) -> bool) -> String {
    cases
        .iter()
        .filter(|c| keep(&c.case.study))
        .map(|c| {
            format!(
                "{} {}: osc peak {:.4e} / RMS {:.4e} rad/s², angle error {:.3e} rad, peak F \
                 {:.4e} N, spread {:.3e}",
                c.case.study,
                c.case.label,
                c.case.metric("flap_acceleration_oscillation_peak"),
                c.case.metric("flap_acceleration_oscillation_rms"),
                c.case.metric("flap_angle_error_max"),
                c.case.metric("peak_contact_force"),
                c.case.metric("poincare_spread")
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn study_cases(filter: &Filter, out: &mut Vec<Case>) {
    if !filter.wants("models.flap.flex.study") {
        return;
    }
    let start = std::time::Instant::now();
    // All cases, the bodies study's f2 and f3 included: with NDF's analytic Newton matrix
    // they take about 5e4 steps (5–7 s); with the finite-difference Jacobian they took 5.4e5 /
    // 4.2e5 steps (321 s / 571 s: the step collapsed in persistent J4 contact, docs/models/flap.md).
    let configs = flap_flex_study::configurations();
    let cases = match flap_flex_study::study_of(&flex_verify_dir(), &study_base(), configs) {
        Ok(c) => c,
        Err(e) => {
            out.push(Case::new("models.flap.flex.study", "studies", "-", RECON).failed(0.0, e));
            return;
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let rms = |s: &str, x: f64| {
        flap_flex_study::find(&cases, s, x).map_or(f64::NAN, |c| {
            c.case.metric("flap_acceleration_oscillation_rms")
        })
    };
    let gap = |findings: &[&str]| {
        super::maps::gap(
            "docs/models/flap.md#flexible-body-findings",
            &clr_models::flap_map::MAP,
            "docs/models/flap.md#finding-map",
            findings,
        )
    };
    // finding 1: one flexible body lowers the clearance-induced oscillation
    let (r0, r1) = (rms("bodies", 0.0), rms("bodies", 1.0));
    let c = Case::new(
        "models.flap.flex.study.suspension",
        "RMS flap acceleration oscillation, flexible auxiliary rod (J4 clearance 0.1 mm)",
        "rad/s^2",
        "finding of Wan et al. 2022 (abstract): a flexible body acts like a suspension and \
         lowers the clearance-induced oscillation against the rigid system; inequality RMS(1 \
         flexible body) ≤ RMS(rigid)",
    )
    .at_most(r1, r0)
    .note(format!(
        "rigid {r0:.4e}, flexible aux rod {r1:.4e} rad/s²; {}",
        summary(&cases, |st| st == "bodies")
    ));
    out.push(c.known_gap(&gap(&["suspension"])));
    // finding 2: the reduction shrinks as clearance joints are added; two series (the paper's
    // order of adding joints is not known)
    for (series, id, what) in [
        (
            "joints_j4",
            "models.flap.flex.study.suspension_weakens",
            "J(5−n)..J4 (n = 1 is the bodies study's J4)",
        ),
        (
            "joints",
            "models.flap.flex.study.suspension_weakens.j1_first",
            "J1..Jn (the order of the rigid number study)",
        ),
    ] {
        let (d1, d4) = (
            flap_flex_study::reduction(&cases, series, 1),
            flap_flex_study::reduction(&cases, series, 4),
        );
        let c = Case::new(
            id,
            format!("reduction 1 − RMS(flexible rod)/RMS(rigid), four clearance joints, {what}"),
            "-",
            "finding of Wan et al. 2022 (abstract): the suspension effect of one flexible body \
             weakens as the number of clearance joints grows; inequality reduction(4 joints) ≤ \
             reduction(1 joint)",
        )
        .at_most(d4, d1)
        .note(format!(
            "reductions n = 1..4: {}; {}",
            (1..=4)
                .map(|n| format!("{:.4}", flap_flex_study::reduction(&cases, series, n)))
                .collect::<Vec<_>>()
                .join(", "),
            summary(&cases, |st| st == series || st == format!("{series}_rigid"))
        ));
        out.push(c.known_gap(&gap(&["suspension_weakens"])));
    }
    // finding 3: four clearance joints with three flexible bodies are the most irregular
    let spread = |s: &str, x: f64| {
        flap_flex_study::find(&cases, s, x).map_or(f64::NAN, |c| c.case.metric("poincare_spread"))
    };
    let spread_all = spread("all", 4.0);
    let (other, label) = cases
        .iter()
        .filter(|c| c.case.study != "all" && c.case.study != "reversing")
        .map(|c| {
            (
                c.case.metric("poincare_spread"),
                format!("{} {}", c.case.study, c.case.label),
            )
        })
        .fold((f64::NEG_INFINITY, String::new()), |a, b| {
            if b.0 > a.0 {
                b
            } else {
                a
            }
        });
    let c = Case::new(
        "models.flap.flex.study.most_irregular",
        "Poincaré-section spread, four clearance joints with three flexible bodies (30 N·m)",
        "-",
        "finding of Wan et al. 2022 (abstract): several flexible bodies coupled with impacts in \
         several clearance joints push the system towards chaos; inequality spread(4 joints, 3 \
         flexible) ≥ the largest spread of every other case with the 30 N·m hinge moment",
    )
    .at_least(spread_all, other)
    .note(format!(
        "4 joints + 3 flexible: {spread_all:.4e}; largest other: {other:.4e} ({label}); {}",
        summary(&cases, |st| st != "reversing")
    ));
    out.push(c.known_gap(&gap(&IRREGULAR)));
    let (s0, s3) = (spread("reversing", 0.0), spread("reversing", 3.0));
    let c = Case::new(
        "models.flap.flex.study.most_irregular.reversing",
        "Poincaré-section spread, four clearance joints, three flexible bodies, zero mean hinge \
         moment",
        "-",
        "finding of Wan et al. 2022 (abstract), with impacts (zero mean hinge moment): \
         inequality spread(3 flexible) ≥ spread(rigid)",
    )
    .at_least(s3, s0)
    .note(format!(
        "spread rigid {s0:.4e}, 3 flexible {s3:.4e}; {}",
        summary(&cases, |st| st == "reversing")
    ));
    out.push(c.known_gap(&gap(&IRREGULAR)));
    println!(
        "models.flap.flex study: {wall:.1} s wall ({} runs in parallel, 1.25 s simulated each, \
         rtol 1e-8)",
        cases.len()
    );
}

/// The flap map's two measures of the irregularity finding (`most_irregular` and `.reversing`).
pub(crate) const IRREGULAR: [&str; 2] = ["most_irregular_spread", "most_irregular_divergence"];

pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    part_cases(filter, &mut out);
    kinematics_case(filter, &mut out);
    study_cases(filter, &mut out);
    out
}

/// Figures of docs/models/flap.md (flexible parts): the study figures under
/// target/models/flap/flex (run the study when they are missing) copied to
/// `models-flap-flex-<name>.{svg,png}`.
pub fn figures(dir: &Path) -> Result<(), String> {
    let fdir = flex_dir();
    if !fdir.join("summary.csv").exists() {
        flap_flex_study::study(&fdir, &study_base())?;
    }
    crate::study_figures::copy_study_figures(
        &fdir,
        &[
            "bodies_oscillation",
            "joints_oscillation",
            "joints_reduction",
            "poincare_spread",
            "orbits_all",
            "poincare_all",
        ],
        dir,
        "models-flap-flex-",
    )
}
