//! Verification cases of clr-models: the catalog's slider–cranks against Wan et al. (2022) and a
//! closed-form bound, and the dual manipulator's published findings (Kuang, Bai, Wei 2026) with
//! the momentum-conservation physics check. Studies write CSV and figures under
//! `target/models/<system>/`.

use std::path::Path;

// relative decrease (x₀ − x_last)/x₀ of a series, shared with the guide's finding map
use clr_models::guide_map::relative_drop;
use clr_models::manipulator::{self, CaseResult};
use clr_models::slider_crank::{self, SliderCrankParams};
use clr_models::{RunOutput, RunSettings};

use super::Filter;
use crate::report::Case;
use crate::study_figures::copy_study_figures;

/// The known-gap link of guide friction finding `finding` (an id of
/// `clr_models::guide_map::findings`): the page's analysis and the finding map.
fn guide_friction_gap(finding: &str) -> String {
    super::maps::gap(
        "docs/models/guide.md#friction-findings",
        &clr_models::guide_map::MAP,
        "docs/models/guide.md#finding-map",
        &[finding],
    )
}

fn metric(out: &RunOutput, name: &str) -> f64 {
    out.metric(name)
}

fn slider_crank_cases(filter: &Filter, out: &mut Vec<Case>) {
    if filter.wants("models.slider_crank.deviation_bound") {
        let p = SliderCrankParams::flores();
        let case = Case::new(
            "models.slider_crank.deviation_bound",
            "max |x_slider − x_ideal| − (c + δ_max), default slider_crank run",
            "m",
            "closed form: the ideal crank and rod put the slider at x = r cos θ + √(l² − r² \
             sin² θ); the clearance joint lets it move by at most the radial play c plus the \
             penetration δ_max (rod-angle effect < c·(r/l)², inside the 1 % margin); x_ideal \
             from the ideal-joint twin, which follows the closed form to 8.1e-8 m",
        );
        match slider_crank::run("slider_crank", &p, &RunSettings::default()) {
            Ok(o) => {
                let c = p.bearing_radius - p.journal_radius;
                // the whole run counts here (penetration over the whole run, not after the transient)
                let pen = o
                    .results
                    .column("B.penetration")
                    .unwrap_or_default()
                    .into_iter()
                    .fold(0.0, f64::max);
                let dev = metric(&o, "max_slider_deviation");
                out.push(case.at_most(dev - (c + pen) * 1.01, 0.0).note(format!(
                    "deviation {dev:.4e} m, c = {c:.1e} m, δ_max = {pen:.3e} m; peak contact \
                     force {:.4e} N, peak slider acceleration {:.4e} m/s², {} steps",
                    metric(&o, "peak_contact_force"),
                    metric(&o, "peak_slider_acceleration"),
                    metric(&o, "steps")
                )));
            }
            Err(e) => out.push(case.failed(0.0, e.to_string())),
        }
    }
    let paper = [
        (0.1e-3, 283.1, "c0.1"),
        (0.3e-3, 318.2, "c0.3"),
        (0.5e-3, 371.8, "c0.5"),
    ];
    for (c, reference, tag) in paper {
        let id = format!("models.wan_slider_crank.peak.{tag}");
        if !filter.wants(&id) {
            continue;
        }
        let p = SliderCrankParams {
            journal_radius: 10e-3 - c,
            ..SliderCrankParams::wan()
        };
        let case = Case::new(
            &id,
            "peak slider acceleration after the first revolution (catalog wan_slider_crank)",
            "m/s²",
            "Wan et al., Machines 10 (2022) 1098, slider–crank table (simulated peak); \
             reconstruction: 600 rpm, rod–slider clearance, L = 15 mm; tolerance 15 %",
        );
        match slider_crank::run("wan_slider_crank", &p, &RunSettings::default()) {
            Ok(o) => {
                let peak = metric(&o, "peak_slider_acceleration");
                out.push(case.relative(peak, reference, 0.15).note(format!(
                    "measured {peak:.1} m/s², paper {reference} m/s²; {} steps, {} onsets",
                    metric(&o, "steps"),
                    metric(&o, "contact_onsets")
                )));
            }
            Err(e) => out.push(case.failed(reference, e.to_string())),
        }
    }
}

fn manipulator_dir() -> std::path::PathBuf {
    crate::target_dir().join("models").join("manipulator")
}

fn manipulator_cases(filter: &Filter, out: &mut Vec<Case>) {
    if !filter.wants("models.manipulator") {
        return;
    }
    let src_paper = "Kuang, Bai, Wei, Aerospace 13 (2026) 75, abstract: clearances degrade motion \
                     accuracy; cases 1–5 as tabulated (paper-systems.md §2)";
    let start = std::time::Instant::now();
    let cases = match manipulator::study(&manipulator_dir(), None) {
        Ok(c) => c,
        Err(e) => {
            out.push(
                Case::new("models.manipulator.study", "study of cases", "-", src_paper)
                    .failed(0.0, e),
            );
            return;
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let get = |n: &str| -> &CaseResult { cases.iter().find(|c| c.name == n).unwrap_or(&cases[0]) };
    // momentum conservation
    for c in &cases {
        for (kind, name, scale) in [
            ("linear", "linear_momentum_drift", "linear_momentum_scale"),
            (
                "angular",
                "angular_momentum_drift",
                "angular_momentum_scale",
            ),
        ] {
            out.push(
                Case::new(
                    format!("models.manipulator.momentum.{}.{kind}", c.name),
                    format!("max |{kind} momentum − initial| / momentum scale"),
                    "-",
                    "closed form: a free-floating system under internal forces only (joint \
                     reactions, contact and friction forces, joint torques) keeps its momentum \
                     (here 0); tolerance 1e-8 of the momentum scale max Σ m|v| (Σ |Iω| + m|r×v|)",
                )
                .at_most(c.metric(name), 1e-8)
                .note(format!(
                    "drift {:.3e} of scale {:.4e}; {} steps; case wall time {:.2} s (force pair \
                     at a common point; see the .contact_points_offset cases for the published \
                     form)",
                    c.metric(name),
                    c.metric(scale),
                    c.metric("steps"),
                    c.wall_s
                )),
            );
        }
    }
    // With the published contact-point form of the force pair (Flores et al. 2004) the friction
    // pair is offset by δ and adds a torque δ·F_T: the angular-momentum change must then equal
    // its integral. Checked on the single-clearance cases, where it is largest.
    for n in ["case1", "case2"] {
        let id = format!("models.manipulator.momentum.{n}.contact_points_offset");
        if !filter.wants(&id) {
            continue;
        }
        let case = Case::new(
            &id,
            "L(t_end) − L(0) with the contact-point force pair, against ∫ Σ δ·F_T dt",
            "kg·m²/s",
            "independent prediction: with each force at its own contact point (δ apart along \
             n) the friction pair has the net torque δ·F_T; integrated over the recorded steps \
             (trapezoid); tolerance 1e-3 relative + 1e-10",
        );
        let run = manipulator::ManipulatorParams::case(n).and_then(|p| {
            let p = manipulator::ManipulatorParams {
                force_application: clr_models::common::PairApplication::ContactPoints,
                ..p
            };
            manipulator::run("manipulator", &p, &RunSettings::default()).map_err(|e| e.to_string())
        });
        match run {
            Ok(o) => {
                let (dl, imp) = (
                    metric(&o, "angular_momentum_change"),
                    metric(&o, "friction_offset_impulse"),
                );
                out.push(
                    case.absolute(dl, imp, 1e-3 * imp.abs() + 1e-10)
                        .note(format!(
                    "ΔL = {dl:.6e}, ∫δF_T dt = {imp:.6e} kg·m²/s: the published force-pair form \
                     breaks angular momentum by exactly this modelling torque; the default \
                     common-point form conserves it (the .angular cases)"
                )),
                );
            }
            Err(e) => out.push(case.failed(0.0, e)),
        }
    }
    let floor = get("ideal").metric("path_error_max");
    let clearance_of = |n: &str| -> f64 {
        manipulator::ManipulatorParams::case(n)
            .map(|p| p.clearances.iter().cloned().fold(0.0, f64::max))
            .unwrap_or(f64::NAN)
    };
    for n in ["case1", "case2", "case3", "case4", "case5"] {
        let c = get(n);
        let e = c.metric("path_error_max");
        let cl = clearance_of(n);
        out.push(
            Case::new(
                format!("models.manipulator.deviates.{n}"),
                "largest end-effector path error against the ideal case",
                "m",
                format!(
                    "{src_paper}; finding: every clearance case deviates from the ideal; \
                     threshold a tenth of the clearance"
                ),
            )
            .at_least(e, 0.1 * cl)
            .note(format!(
                "{n}: max error {e:.4e} m, RMS {:.4e} m (clearance {cl:.2e} m); numerical floor \
                 (ideal run against its own reference) {floor:.2e} m",
                c.metric("path_error_rms")
            )),
        );
    }
    let pair = |id: &str, small: &str, large: &str, what: &str, out: &mut Vec<Case>| {
        let (a, b) = (get(small), get(large));
        let (ra, rb) = (a.metric("path_error_rms"), b.metric("path_error_rms"));
        out.push(
            Case::new(
                id,
                format!("RMS path error {large} − {small}"),
                "m",
                format!("{src_paper}; finding: {what}"),
            )
            .at_least(rb - ra, 0.0)
            .note(format!(
                "RMS over both end effectors {small} {ra:.4e} m < {large} {rb:.4e} m; per arm \
                 {small} {:.4e} / {:.4e} m, {large} {:.4e} / {:.4e} m; max {:.4e} m vs {:.4e} m",
                a.metric("path_error_rms_arm1"),
                a.metric("path_error_rms_arm2"),
                b.metric("path_error_rms_arm1"),
                b.metric("path_error_rms_arm2"),
                a.metric("path_error_max"),
                b.metric("path_error_max")
            )),
        );
    };
    pair(
        "models.manipulator.grows.case4_case3",
        "case4",
        "case3",
        "error grows with clearance (0.25 mm < 0.5 mm)",
        out,
    );
    pair(
        "models.manipulator.grows.case3_case5",
        "case3",
        "case5",
        "error grows with clearance (0.5 mm < 1.0 mm)",
        out,
    );
    pair(
        "models.manipulator.two_joints.case1_case3",
        "case1",
        "case3",
        "two clearance joints (case 3) deviate more than one (case 1)",
        out,
    );
    println!("models.manipulator study: {wall:.1} s wall (6 cases in parallel)");
}

fn flap_eigen_cases(filter: &Filter, out: &mut Vec<Case>) {
    use clr_models::flap::{FlexiblePart, PAPER_FREQUENCIES};
    for (part, (_, paper)) in FlexiblePart::paper_parts().iter().zip(PAPER_FREQUENCIES) {
        let id = format!("models.flap.eigen.{}", part.name);
        if !filter.wants(&id) {
            continue;
        }
        match part.calibrate() {
            Ok(c) => {
                let f = &c.frequencies_hz;
                let modes = (1..5)
                    .map(|k| format!("mode {}: {:.1} Hz (paper {})", k + 1, f[k], paper[k]))
                    .collect::<Vec<_>>()
                    .join(", ");
                out.push(
                    Case::new(
                        format!("{id}.mode1"),
                        "first computed eigenfrequency after section calibration",
                        "Hz",
                        "Wan et al., Machines 10 (2022) 1098, eigenfrequency table (first mode); \
                         planar Euler–Bernoulli beam, pinned + axial roller, steel, width 15 mm, \
                         depth calibrated; tolerance 1e-8",
                    )
                    .relative(f[0], paper[0], 1e-8)
                    .note(format!(
                        "length {} m, calibrated depth {:.4} mm; {modes}; a planar beam has no \
                         out-of-plane or torsion modes, so modes 2–5 are not expected to match",
                        part.length,
                        c.depth * 1e3
                    )),
                );
                let cf = part.closed_form_f1(c.depth);
                out.push(
                    Case::new(
                        format!("{id}.closed_form"),
                        "first frequency, clr-beam (20 elements) vs Euler–Bernoulli closed form",
                        "Hz",
                        "closed form f1 = (π/2L²)√(EI/ρA) of a pinned–pinned beam; tolerance 1e-4 \
                         (discretization with 20 cubic elements)",
                    )
                    .relative(f[0], cf, 1e-4)
                    .note(format!("clr-beam {:.3} Hz, closed form {cf:.3} Hz", f[0])),
                );
            }
            Err(e) => out.push(
                Case::new(
                    format!("{id}.mode1"),
                    "first eigenfrequency",
                    "Hz",
                    "Wan et al. 2022",
                )
                .failed(paper[0], e),
            ),
        }
    }
}

fn flap_dir() -> std::path::PathBuf {
    crate::target_dir().join("models").join("flap")
}

/// Study base of the flap verify cases and figures: 0.25 s ramp (excluded) + 4 actuator periods.
fn flap_study_base() -> clr_models::flap::FlapParams {
    clr_models::flap::FlapParams {
        duration: clr_models::studies::FLAP_STUDY_DURATION,
        ..Default::default()
    }
}

fn flap_linkage_cases(filter: &Filter, out: &mut Vec<Case>) {
    use clr_models::flap::{self, FlapParams};
    let recon = "reconstructed rigid flap linkage (docs/models/flap.md; Wan et al. 2022 give only \
                 x = 10 mm, 2 Hz, L = 15 mm, c_r = 0.46, c_f = 0.01)";
    if filter.wants("models.flap.kinematics") {
        let p = FlapParams {
            clearances: [0.0; 4],
            duration: 1.0,
            ..Default::default()
        };
        let case = Case::new(
            "models.flap.kinematics",
            "max |flap angle (clr-mbd, ideal joints) − closed-form flap angle|",
            "rad",
            format!(
                "independent formulation: two circle intersections (actuator length about C0 and \
                 O1 → lever angle; rod length about J3 and O2 → flap angle), \
                 FlapParams::ideal_flap_angle; {recon}; tolerance 1e-7 rad (constraint drift \
                 and integration error)"
            ),
        );
        match flap::run("flap", &p, &RunSettings::default()) {
            Ok(o) => {
                let r = &o.results;
                let t = r.column("t").unwrap_or_default();
                let a = r.column("flap.angle").unwrap_or_default();
                let mut worst = 0.0f64;
                let mut amp = 0.0f64;
                for k in 0..t.len() {
                    let x = p.actuator(t[k])[0];
                    let cf = p
                        .ideal_flap_angle(x, p.aux_rod_length)
                        .unwrap_or(f64::INFINITY);
                    worst = worst.max((a[k] - cf).abs());
                    amp = amp.max(cf.abs());
                }
                out.push(case.absolute(worst, 0.0, 1e-7).note(format!(
                    "largest deviation {worst:.3e} rad over {} rows; flap amplitude {amp:.4} rad",
                    t.len()
                )));
            }
            Err(e) => out.push(case.failed(0.0, e.to_string())),
        }
    }
    if filter.wants("models.flap.envelope") {
        let p = FlapParams {
            clearances: [0.0, 0.0, 0.0, 0.5e-3],
            duration: 1.0,
            ..Default::default()
        };
        let case = Case::new(
            "models.flap.envelope.J4",
            "largest excursion of the flap angle outside the rod-length envelope",
            "rad",
            format!(
                "closed form: with only J4 a clearance joint (0.5 mm), |J4 − J3| stays within \
                 l ± (c + δ_max), so the flap angle lies between the ideal angles for those rod \
                 lengths; {recon}; tolerance 1e-9 rad"
            ),
        );
        match flap::run("flap", &p, &RunSettings::default()) {
            Ok(o) => out.push(envelope_case(case, &p, &o)),
            Err(e) => out.push(case.failed(0.0, e.to_string())),
        }
    }
    if !filter.wants("models.flap.study") {
        return;
    }
    let start = std::time::Instant::now();
    let cases = match flap::study(&flap_dir(), &flap_study_base()) {
        Ok(c) => c,
        Err(e) => {
            out.push(Case::new("models.flap.study", "studies", "-", recon).failed(0.0, e));
            return;
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let get = |s: &str, l: &str| cases.iter().find(|c| c.study == s && c.label == l);
    let (Some(small), Some(large)) = (get("size", "c0.05mm"), get("size", "c0.5mm")) else {
        return;
    };
    let summary = |study: &str| {
        cases
            .iter()
            .filter(|c| c.study == study)
            .map(|c| {
                format!(
                    "{}: osc peak {:.4e} / RMS {:.4e} rad/s², angle error {:.3e} rad, peak F \
                     {:.4e} N, spread {:.3e}",
                    c.label,
                    c.metric("flap_acceleration_oscillation_peak"),
                    c.metric("flap_acceleration_oscillation_rms"),
                    c.metric("flap_angle_error_max"),
                    c.metric("peak_contact_force"),
                    c.metric("poincare_spread")
                )
            })
            .collect::<Vec<_>>()
            .join("; ")
    };
    let (rs, rl) = (
        small.metric("flap_acceleration_oscillation_rms"),
        large.metric("flap_acceleration_oscillation_rms"),
    );
    out.push(
        Case::new(
            "models.flap.study.size_oscillation",
            "RMS flap acceleration oscillation, 0.5 mm − 0.05 mm clearance in J4",
            "rad/s²",
            format!(
                "finding of this model (not a published number): a larger clearance gives a \
                 larger clearance-induced acceleration oscillation; {recon}"
            ),
        )
        .at_least(rl - rs, 0.0)
        .note(format!(
            "0.05 mm {rs:.4e} rad/s² < 0.5 mm {rl:.4e} rad/s²; {}",
            summary("size")
        )),
    );
    let (es, el) = (
        small.metric("flap_angle_error_max"),
        large.metric("flap_angle_error_max"),
    );
    out.push(
        Case::new(
            "models.flap.study.size_angle_error",
            "largest flap angle error, 0.5 mm − 0.05 mm clearance in J4",
            "rad",
            format!(
                "closed-form expectation: the loaded J4 journal sits on the bearing wall, so the \
                 flap angle error is about (c + δ)/(aux lever arm length) and grows with c; \
                 {recon}"
            ),
        )
        .at_least(el - es, 0.0)
        .note(format!("0.05 mm {es:.4e} rad < 0.5 mm {el:.4e} rad")),
    );
    if let (Some(loaded), Some(rev)) = (get("number", "n4"), get("load", "reversing_n4")) {
        let (sl, sr) = (
            loaded.metric("poincare_spread"),
            rev.metric("poincare_spread"),
        );
        out.push(
            Case::new(
                "models.flap.study.load_irregularity",
                "Poincaré spread, four 0.1 mm clearance joints, zero mean hinge moment (≥ 10× the \
                 30 N·m case)",
                "-",
                format!(
                    "finding of this model (not a published number): when the hinge load changes \
                     sign the journals leave the bearing walls, impacts start and the response \
                     is no longer periodic; threshold an order of magnitude; {recon}"
                ),
            )
            .at_least(sr, 10.0 * sl)
            .note(format!(
                "spread 30 N·m {sl:.3e} vs zero mean {sr:.3e}; oscillation RMS {:.4e} vs {:.4e} \
                 rad/s²; peak contact force {:.4e} vs {:.4e} N; contact onsets {} vs {}; {}",
                loaded.metric("flap_acceleration_oscillation_rms"),
                rev.metric("flap_acceleration_oscillation_rms"),
                loaded.metric("peak_contact_force"),
                rev.metric("peak_contact_force"),
                loaded.metric("contact_onsets"),
                rev.metric("contact_onsets"),
                summary("load")
            )),
        );
    }
    // report-only rows for the position and number studies (no published number to compare)
    for (id, study) in [
        ("models.flap.study.position", "position"),
        ("models.flap.study.number", "number"),
    ] {
        let n = cases.iter().filter(|c| c.study == study).count();
        out.push(
            Case::new(
                id,
                format!("{study} study cases completed"),
                "-",
                "study of the paper (Wan et al. 2022) on the reconstructed rigid linkage; every \
                 configuration must run (4 cases); values reported in the note",
            )
            .absolute(n as f64, 4.0, 0.0)
            .note(summary(study)),
        );
    }
    println!(
        "models.flap study: {wall:.1} s wall ({} runs in parallel, 2.25 s simulated each)",
        cases.len()
    );
}

pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    slider_crank_cases(filter, &mut out);
    flap_eigen_cases(filter, &mut out);
    flap_linkage_cases(filter, &mut out);
    manipulator_cases(filter, &mut out);
    guide_cases(filter, &mut out);
    out
}

/// Figures of docs/models: runs the studies (outputs under target/models/) and copies the
/// figures the docs embed into `dir` as `models-<system>-<name>.{svg,png}`.
pub fn figures(dir: &Path) -> Result<(), String> {
    guide_figures(dir)?;
    let mdir = manipulator_dir();
    manipulator::study(&mdir, None)?;
    copy_study_figures(
        &mdir,
        &["paths", "path_error", "base_y", "contact_force", "orbits"],
        dir,
        "models-manipulator-",
    )?;
    let fdir = flap_dir();
    clr_models::flap::study(&fdir, &flap_study_base())?;
    copy_study_figures(
        &fdir,
        &[
            "size_oscillation",
            "number_oscillation",
            "position_oscillation",
            "orbits_n4",
            "poincare_n4",
            "orbits_reversing_n4",
            "poincare_reversing_n4",
            "alpha_error_size",
        ],
        dir,
        "models-flap-",
    )
}

fn guide_dir(study: &str) -> std::path::PathBuf {
    crate::target_dir().join("models").join("guide").join(study)
}

/// Sliding guide (seed 000, paper-systems.md §3): the published trends, each with both
/// measured values in the note. Parameters are reconstructions (docs/models/guide.md).
fn guide_cases(filter: &Filter, out: &mut Vec<Case>) {
    use clr_models::guide::{self, StudyRun};
    let src = "sliding-guide paper (seed 000, abstract; paper-systems.md §3.1): finding \
               reproduced as a trend, parameters reconstructed (docs/models/guide.md)";
    let get = |runs: &[StudyRun], n: &str, m: &str| -> f64 {
        runs.iter()
            .find(|r| r.name == n)
            .map_or(f64::NAN, |r| r.metric(m))
    };
    if filter.wants("models.guide.elastic") {
        let start = std::time::Instant::now();
        match guide::elastic_vs_rigid(&guide_dir("elastic_vs_rigid")) {
            Ok(runs) => {
                let (fe, fr) = (
                    get(&runs, "elastic", "peak_contact_force"),
                    get(&runs, "rigid", "peak_contact_force"),
                );
                out.push(
                    Case::new(
                        "models.guide.elastic.peak_force",
                        "peak contact force, elastic guide ≤ rigid guide",
                        "N",
                        src,
                    )
                    .at_most(fe, fr)
                    .note(format!("elastic {fe:.4e} N, rigid {fr:.4e} N")),
                );
                let (ye, yr) = (
                    get(&runs, "elastic", "max_lateral_displacement"),
                    get(&runs, "rigid", "max_lateral_displacement"),
                );
                out.push(
                    Case::new(
                        "models.guide.elastic.lateral",
                        "max slider lateral displacement, elastic guide ≥ rigid guide",
                        "m",
                        src,
                    )
                    .at_least(ye, yr)
                    .note(format!("elastic {ye:.4e} m, rigid {yr:.4e} m")),
                );
                println!(
                    "models.guide elastic_vs_rigid: {:.1} s wall (2 runs in parallel)",
                    start.elapsed().as_secs_f64()
                );
            }
            Err(e) => out.push(
                Case::new("models.guide.elastic.study", "elastic vs rigid", "-", src)
                    .failed(0.0, e),
            ),
        }
    }
    if filter.wants("models.guide.clearance") || filter.wants("models.guide.friction") {
        guide_friction_cases(src, out);
    }
    if filter.wants("models.guide.support") {
        guide_support_cases(out);
    }
}

/// Lateral stiffness of the what-if second load path, N/m: W/k = 2.5 mm, the span of the
/// clearances studied (chosen once, not iterated; docs/models/guide.md#friction-findings).
const GUIDE_SUPPORT_STIFFNESS: f64 = 2e4;

fn guide_support_base() -> clr_models::guide::GuideParams {
    clr_models::guide::GuideParams {
        lateral_support_stiffness: GUIDE_SUPPORT_STIFFNESS,
        ..Default::default()
    }
}

fn guide_support_series() -> Vec<(clr_models::guide::Stroke, f64, Vec<f64>)> {
    use clr_models::guide::Stroke;
    vec![
        (Stroke::Deployment, 1.0, GUIDE_CLEARANCES.to_vec()),
        (Stroke::Retraction, 1.0, vec![0.25e-3, 2.0e-3]),
        (Stroke::Deployment, 0.25, GUIDE_SLOW_CLEARANCES.to_vec()),
    ]
}

/// Comma-separated values of a series.
fn list_values(x: &[f64]) -> String {
    x.iter()
        .map(|v| format!("{v:.4e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What-if of this project (not the paper): the experiment's friction trends with a second
/// lateral load path (`lateral_support_stiffness`), the hypothesis of docs/models/guide.md.
fn guide_support_cases(out: &mut Vec<Case>) {
    use clr_models::guide::{self, friction_run_name, Stroke};
    let src = "hypothesis of this project, not the paper: the sliding-guide experiment's μ_eq \
               trends (seed 000 abstract) with a second lateral load path k = 2e4 N/m \
               (docs/models/guide.md#friction-findings); thresholds: differences of relative \
               decreases ≥ 0.01 and flattening ≥ 1 % of μ_eq per 0.25 mm (3× the integration \
               sensitivity of μ_eq, 0.3 %)";
    let start = std::time::Instant::now();
    let runs = match guide::friction_study(
        &guide_dir("friction_support"),
        &guide_support_base(),
        &guide_support_series(),
        GUIDE_FRICTION_DURATION,
    ) {
        Ok(r) => r,
        Err(e) => {
            out.push(
                Case::new("models.guide.support.study", "support what-if", "-", src).failed(0.0, e),
            );
            return;
        }
    };
    let mu = |stroke: Stroke, v: f64, cs: &[f64]| -> Vec<f64> {
        cs.iter()
            .map(|&c| {
                let name = friction_run_name(stroke, v, c);
                runs.iter()
                    .find(|r| r.name == name)
                    .map_or(f64::NAN, |r| r.metric("equivalent_friction_coefficient"))
            })
            .collect()
    };
    let dep = mu(Stroke::Deployment, 1.0, &GUIDE_CLEARANCES);
    let ret = mu(Stroke::Retraction, 1.0, &[0.25e-3, 2.0e-3]);
    let slow = mu(Stroke::Deployment, 0.25, &GUIDE_SLOW_CLEARANCES);
    let fast = [dep[0], dep[2]];
    let step = dep
        .windows(2)
        .map(|w| w[0] - w[1])
        .fold(f64::INFINITY, f64::min);
    out.push(
        Case::new(
            "models.guide.support.clearance",
            "μ_eq decreases at every clearance step (deployment 1 m/s; smallest step)",
            "-",
            src,
        )
        .at_least(step, 0.0)
        .note(format!(
            "μ_eq at c = 0.25/0.5/1.0/2.0 mm: {}",
            list_values(&dep)
        )),
    );
    out.push(
        Case::new(
            "models.guide.support.direction",
            "relative decrease 0.25 → 2.0 mm at 1 m/s: deployment − retraction",
            "-",
            src,
        )
        .at_least(relative_drop(&dep) - relative_drop(&ret), 0.01)
        .note(format!(
            "deployment {:.4} ({}), retraction {:.4} ({})",
            relative_drop(&dep),
            list_values(&dep),
            relative_drop(&ret),
            list_values(&ret)
        )),
    );
    out.push(
        Case::new(
            "models.guide.support.speed",
            "relative decrease 0.25 → 1.0 mm (deployment): 0.25 m/s − 1 m/s",
            "-",
            src,
        )
        .at_least(relative_drop(&slow) - relative_drop(&fast), 0.01)
        .note(format!(
            "0.25 m/s {:.4} ({}), 1 m/s {:.4} ({})",
            relative_drop(&slow),
            list_values(&slow),
            relative_drop(&fast),
            list_values(&fast)
        )),
    );
    let (first, last) = ((dep[0] - dep[1]) / 0.25, (dep[2] - dep[3]) / 1.0);
    out.push(
        Case::new(
            "models.guide.support.flattening",
            "decrease of μ_eq per mm: first step (0.25 → 0.5 mm) − last step (1 → 2 mm)",
            "1/mm",
            src,
        )
        .at_least(first.min(first - last), 0.01 * dep[0] / 0.25)
        .note(format!(
            "{first:.4e} /mm over 0.25–0.5 mm, {last:.4e} /mm over 1–2 mm"
        )),
    );
    println!(
        "models.guide support what-if: {:.1} s wall ({} runs in parallel on the rayon pool)",
        start.elapsed().as_secs_f64(),
        runs.len()
    );
}

/// Clearances (m) of the friction study's 1 m/s series and of its 0.25 m/s series
/// (`clr_models::guide::friction_series`).
const GUIDE_CLEARANCES: [f64; 4] = [0.25e-3, 0.5e-3, 1.0e-3, 2.0e-3];
const GUIDE_SLOW_CLEARANCES: [f64; 2] = [0.25e-3, 1.0e-3];
const GUIDE_FRICTION_DURATION: f64 = clr_models::guide::FRICTION_DURATION;

fn guide_friction_series() -> Vec<(clr_models::guide::Stroke, f64, Vec<f64>)> {
    clr_models::guide::friction_series()
}

/// The clearance findings (simulation) and the equivalent-friction findings (experiment) of the
/// sliding-guide paper, from one friction study.
fn guide_friction_cases(src: &str, out: &mut Vec<Case>) {
    use clr_models::guide::{self, friction_run_name, Stroke};
    let start = std::time::Instant::now();
    let runs = match guide::friction_study(
        &guide_dir("friction"),
        &guide::GuideParams::default(),
        &guide_friction_series(),
        GUIDE_FRICTION_DURATION,
    ) {
        Ok(r) => r,
        Err(e) => {
            out.push(
                Case::new("models.guide.friction.study", "friction study", "-", src).failed(0.0, e),
            );
            return;
        }
    };
    let get = |stroke: Stroke, v: f64, c: f64, m: &str| -> f64 {
        let name = friction_run_name(stroke, v, c);
        runs.iter()
            .find(|r| r.name == name)
            .map_or(f64::NAN, |r| r.metric(m))
    };
    let series = |stroke: Stroke, v: f64, cs: &[f64], m: &str| -> Vec<f64> {
        cs.iter().map(|&c| get(stroke, v, c, m)).collect()
    };
    let list = |x: &[f64], unit: &str| -> String { list_values(x) + " " + unit };
    let cs_text = "c = 0.25/0.5/1.0/2.0 mm (deployment, 1 m/s)";
    for (id, m, unit, larger, gap) in [
        ("peak_force", "peak_contact_force", "N", true, false),
        (
            "tip_oscillation",
            "tip_oscillation_amplitude",
            "m",
            true,
            false,
        ),
        ("friction", "mean_friction_force", "N", false, true),
    ] {
        let x = series(Stroke::Deployment, 1.0, &GUIDE_CLEARANCES, m);
        // monotone over the clearances: the smallest step in the expected direction ≥ 0
        let step = x
            .windows(2)
            .map(|w| if larger { w[1] - w[0] } else { w[0] - w[1] })
            .fold(f64::INFINITY, f64::min);
        let dir = if larger { "increases" } else { "decreases" };
        let case = Case::new(
            format!("models.guide.clearance.{id}"),
            format!("{m} {dir} with clearance (smallest step, ≥ 0)"),
            unit,
            src,
        )
        .at_least(step, 0.0)
        .note(format!("{cs_text}: {}", list(&x, unit)));
        out.push(if gap {
            case.known_gap(&guide_friction_gap("clearance_friction"))
        } else {
            case
        });
    }
    // Equivalent friction coefficient (experiment of the paper): a decrease counts only when it
    // exceeds 1 % of μ_eq, three times the integration sensitivity measured on this model
    // (|Δμ_eq| = 0.27 % between rtol 1e-4 and 1e-5, docs/models/guide.md).
    let mu = "equivalent_friction_coefficient";
    let exp = "sliding-guide paper (seed 000, abstract: prototype experiment; paper-systems.md \
               §3.1); model and μ_eq definition reconstructed (docs/models/guide.md)";
    // the finding map says where, over the plausible parameters, each of these holds
    let dep = series(Stroke::Deployment, 1.0, &GUIDE_CLEARANCES, mu);
    let ret = series(Stroke::Retraction, 1.0, &GUIDE_CLEARANCES, mu);
    let slow = series(Stroke::Deployment, 0.25, &GUIDE_SLOW_CLEARANCES, mu);
    let drop = relative_drop;
    // the same threshold as the finding map (clr_models::guide_map)
    const MIN_DECREASE: f64 = clr_models::guide_map::MIN_RELATIVE_DECREASE;
    out.push(
        Case::new(
            "models.guide.friction.clearance",
            "relative decrease of μ_eq from 0.25 to 2.0 mm (deployment, 1 m/s)",
            "-",
            exp,
        )
        .at_least(drop(&dep), MIN_DECREASE)
        .note(format!(
            "μ_eq deployment 1 m/s, {cs_text}: {}",
            list(&dep, "")
        ))
        .known_gap(&guide_friction_gap("friction_clearance")),
    );
    out.push(
        Case::new(
            "models.guide.friction.direction",
            "decrease of μ_eq (0.25 → 2.0 mm, 1 m/s): deployment − retraction",
            "-",
            exp,
        )
        .at_least(drop(&dep) - drop(&ret), MIN_DECREASE)
        .note(format!(
            "relative decrease deployment {:.4}, retraction {:.4}; μ_eq retraction: {}",
            drop(&dep),
            drop(&ret),
            list(&ret, "")
        ))
        .known_gap(&guide_friction_gap("friction_direction")),
    );
    let fast = [dep[0], dep[2]];
    out.push(
        Case::new(
            "models.guide.friction.speed",
            "decrease of μ_eq (0.25 → 1.0 mm, deployment): 0.25 m/s − 1 m/s",
            "-",
            exp,
        )
        .at_least(drop(&slow) - drop(&fast), MIN_DECREASE)
        .note(format!(
            "relative decrease at 0.25 m/s {:.4} (μ_eq {}), at 1 m/s {:.4}",
            drop(&slow),
            list(&slow, ""),
            drop(&fast)
        ))
        .known_gap(&guide_friction_gap("friction_speed")),
    );
    // flattening: the decrease per mm over the last step (1 → 2 mm) is smaller than over the
    // first (0.25 → 0.5 mm), and the first is a decrease at all
    let first = (dep[0] - dep[1]) / 0.25;
    let last = (dep[2] - dep[3]) / 1.0;
    out.push(
        Case::new(
            "models.guide.friction.flattening",
            "decrease of μ_eq per mm: first step (0.25 → 0.5 mm) − last step (1 → 2 mm)",
            "1/mm",
            exp,
        )
        .at_least(first.min(first - last), MIN_DECREASE * dep[0] / 0.25)
        .note(format!(
            "deployment 1 m/s: {first:.4e} /mm over 0.25–0.5 mm, {last:.4e} /mm over 1–2 mm"
        ))
        .known_gap(&guide_friction_gap("friction_flattening")),
    );
    println!(
        "models.guide friction study: {:.1} s wall ({} runs in parallel on the rayon pool)",
        start.elapsed().as_secs_f64(),
        runs.len()
    );
}

/// Figures of docs/models/guide.md: the two guide studies, copied as
/// `models-guide-<study>-<name>.{svg,png}`.
fn guide_figures(dir: &Path) -> Result<(), String> {
    use clr_models::guide;
    guide::elastic_vs_rigid(&guide_dir("elastic_vs_rigid"))?;
    guide::friction_study(
        &guide_dir("friction"),
        &guide::GuideParams::default(),
        &guide_friction_series(),
        GUIDE_FRICTION_DURATION,
    )?;
    guide::friction_study(
        &guide_dir("friction_support"),
        &guide_support_base(),
        &guide_support_series(),
        GUIDE_FRICTION_DURATION,
    )?;
    for (study, names) in [
        ("elastic_vs_rigid", &["lateral", "tip", "contact_force"][..]),
        (
            "friction",
            &["lateral", "tip", "contact_force", "friction"][..],
        ),
        ("friction_support", &["friction"][..]),
    ] {
        copy_study_figures(
            &guide_dir(study),
            names,
            dir,
            &format!("models-guide-{study}-"),
        )?;
    }
    Ok(())
}

/// The rod-length envelope check of a run with J4 the only clearance joint: the flap angle must
/// lie between the ideal angles for rod lengths l ± (c + δ_max) (closed-form kinematics, δ_max
/// the largest penetration of J4), within 1e-9 rad.
pub(super) fn envelope_case(
    case: crate::report::CaseSpec,
    p: &clr_models::flap::FlapParams,
    o: &RunOutput,
) -> Case {
    let r = &o.results;
    let t = r.column("t").unwrap_or_default();
    let a = r.column("flap.angle").unwrap_or_default();
    let pen = r
        .column("J4.penetration")
        .unwrap_or_default()
        .into_iter()
        .fold(0.0, f64::max);
    let play = p.clearances[3] + pen;
    let mut worst = f64::NEG_INFINITY;
    let mut width = 0.0f64;
    for k in 0..t.len() {
        let x = p.actuator(t[k])[0];
        let lo = p.ideal_flap_angle(x, p.aux_rod_length - play);
        let hi = p.ideal_flap_angle(x, p.aux_rod_length + play);
        let (Some(lo), Some(hi)) = (lo, hi) else {
            worst = f64::INFINITY;
            continue;
        };
        let (lo, hi) = (lo.min(hi), lo.max(hi));
        width = width.max(hi - lo);
        worst = worst.max(lo - a[k]).max(a[k] - hi);
    }
    case.at_most(worst, 1e-9).note(format!(
        "excursion {worst:.3e} rad (negative = inside); envelope width up to {width:.3e} rad; \
         δ_max = {pen:.3e} m; flap angle error max {:.4e} rad",
        metric(o, "flap_angle_error_max")
    ))
}
