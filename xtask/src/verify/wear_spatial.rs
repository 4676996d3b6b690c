//! Verification cases of the wear along the axis of the spatial journal joint (clr-contact
//! `journal_wear`, study `journal_wear` of clr-models; docs/wear.md, "Spatial journal").
//!
//! - `wear.spatial.aligned`, `wear.spatial.global_law`, `wear.spatial.rim_wedge`: the closed
//!   forms of the unit tests (crates/clr-contact/tests/journal_wear.rs) on the flap paper's
//!   bearing (R_b = 10 mm, R_j = 9.9 mm, L = 15 mm; the configurations shared with
//!   `contact.spatial.revolute.*`), K = 1e-5, H = 2 GPa, the journal spinning at 100 rad/s over
//!   dt = 1 ms.
//! - `wear.spatial.study.*`: the aligned case of the study (the spatial Wan slider–crank, joint B
//!   a spatial revolute clearance joint) against the planar Archard wear
//!   (`clr_contact::wear::ArchardWear`) accumulated from the planar Wan slider–crank's own
//!   history of the same steady revolution, with the slip of the planar joint's contact points
//!   (`RevoluteClearance::contact`). The two are independent formulations of the same wear: the
//!   planar contact geometry and one force per step against the spatial sections, Gauss nodes
//!   and per-node slips, each on its own integrator's steps.

use clr_contact::body::{BodyState, Vector2};
use clr_contact::revolute::RevoluteClearance;
use clr_contact::wear::BearingProfile;
use clr_models::journal_wear;
use clr_models::lubrication_wear::{self, WEAR_ANGLES};
use clr_models::slider_crank::SliderCrankParams;

use super::Filter;
use crate::report::Case;

// journal_wear_forms reads the bearing of `super::journal_setup`
use super::journal_setup;
#[path = "../../../crates/clr-contact/tests/support/journal_wear_forms.rs"]
mod journal_wear_forms;

const SRC_ARCHARD: &str = "Archard, J. Appl. Phys. 24 (1953) 981: V = K ∫ p |v_t| dz dt / H";

pub fn cases(filter: &Filter) -> Vec<Case> {
    let mut out = Vec::new();
    if filter.wants("wear.spatial.aligned") {
        out.extend(aligned_cases());
    }
    if filter.wants("wear.spatial.global_law") {
        out.push(global_law_case());
    }
    if filter.wants("wear.spatial.rim_wedge") {
        out.extend(rim_wedge_cases());
    }
    if filter.wants("wear.spatial.study") {
        out.extend(study_cases());
    }
    out
}

/// A case id's failure as a failed case.
fn failed(id: &str, what: &str, unit: &str, why: String) -> Case {
    Case::new(id, what, unit, SRC_ARCHARD).failed(f64::NAN, why)
}

/// The aligned journal pressed 2 µm along +x, spinning (journal_wear_forms::aligned_uniform):
/// uniform line load F_N/L along the bore, slip ω R_j. Every station must carry the planar
/// Archard profile of F_N over ds = ω R_j dt, and the volume is K F_N ω R_j dt / H.
fn aligned_cases() -> Vec<Case> {
    let (id_p, id_v) = (
        "wear.spatial.aligned.profile",
        "wear.spatial.aligned.volume",
    );
    match journal_wear_forms::aligned_uniform() {
        Ok(r) => vec![
            Case::new(
                id_p,
                "aligned journal, uniform load: largest difference of any station's depth from \
                 the planar Archard profile of F_N, over its peak (360 angles × 12 stations)",
                "-",
                "closed form: a uniform line load F_N/L and slip ω R_j wear every section as the \
                 planar bearing (clr_contact::wear, Archard + Hertz width); tolerance 1e-12 \
                 (the Gauss shares tile the bore to rounding)",
            )
            .absolute(r.worst_station_error(), 0.0, 1e-12),
            Case::new(
                id_v,
                "aligned journal, uniform load: worn volume",
                "m^3",
                "Archard's global law V = K F_N ω R_j dt / H; tolerance 1e-12 relative \
                 (the spreading over φ and z conserves the volume)",
            )
            .relative(r.volume, r.archard, 1e-12),
        ],
        Err(e) => vec![
            failed(id_p, "aligned profile", "-", e.clone()),
            failed(id_v, "aligned volume", "m^3", e),
        ],
    }
}

/// Both rims wetted on opposite sides, Hertz, spin and axial sliding
/// (journal_wear_forms::global_law): the worn volume against an independent composite Simpson
/// integral of K p |v_t| dt / H over the joint's public sections.
fn global_law_case() -> Case {
    let id = "wear.spatial.global_law";
    match journal_wear_forms::global_law() {
        Ok(r) => Case::new(
            id,
            "crossed journal (both rims, opposite sides), Hertz, spin + axial sliding: worn \
             volume against Simpson's rule of K ∫ p |v_t| dz dt / H on the sections",
            "m^3",
            "Archard's global law; independent composite Simpson (4000 intervals per region); \
             tolerance 1e-6 (Simpson's own error on the (z − z₀)^{3/2} root ~1e-7, the order-10 \
             Gauss rule < 1e-8: docs/contact.md)",
        )
        .relative(r.volume, r.simpson, 1e-6),
        Err(e) => failed(id, "global law", "m^3", e),
    }
}

/// The journal tilted onto one rim, linear law F = kδ (journal_wear_forms::rim_wedge): the
/// line load is the wedge p(z) = k tan γ (z − z₀)/L and the slip ω R_j, so station m's worn
/// area is K ω R_j dt ∫_cell p dz / (H Δz) in closed form.
fn rim_wedge_cases() -> Vec<Case> {
    let (id_v, id_s) = (
        "wear.spatial.rim_wedge.volume",
        "wear.spatial.rim_wedge.stations",
    );
    match journal_wear_forms::rim_wedge() {
        Ok(r) => vec![
            Case::new(
                id_v,
                "journal tilted onto one rim, linear law: worn volume of the wedge",
                "m^3",
                "closed form K ω R_j dt k tan γ (L/2 − z₀)²/(2 L H); tolerance 1e-9 (Gauss is \
                 exact for the linear load after the u² substitution; z₀ solved to 1e-11 L)",
            )
            .relative(r.volume, r.total, 1e-9),
            Case::new(
                id_s,
                "journal tilted onto one rim: largest error of a station's worn area (10 \
                 stations) over the rim station's",
                "-",
                "closed form ∫_cell p dz per station; tolerance 3e-3 (a node's share straddling \
                 a cell boundary misplaces up to p′w²/8 of its load, w the share's length, at \
                 Gauss order 32)",
            )
            .at_most(r.worst_station_error(), 3e-3),
        ],
        Err(e) => vec![
            failed(id_v, "rim wedge volume", "m^3", e.clone()),
            failed(id_s, "rim wedge stations", "-", e),
        ],
    }
}

/// The planar wear of the steady revolution of the planar Wan slider–crank (the planar wear
/// study's first update, circular bearing), with the slip of the contact points; and the same
/// with the planar study's slip |Δω| R_j. Returns (profile, volume, volume with |Δω| R_j).
fn planar_wear(p: &SliderCrankParams) -> Result<(BearingProfile, f64, f64), String> {
    let res = lubrication_wear::wear_cycle_run(p, &[0.0; WEAR_ANGLES])?;
    let t_from = p.transient_revolutions * 60.0 / p.crank_speed_rpm;
    let joint = RevoluteClearance::new(
        p.bearing_radius,
        p.journal_radius,
        Vector2::zeros(),
        Vector2::new(p.rod_length / 2.0, 0.0),
    )
    .map_err(|e| e.to_string())?;
    let column = |name: &str| res.column(name).ok_or(format!("no column {name}"));
    let body = |b: &str| -> Result<Vec<BodyState>, String> {
        let c = ["x", "y", "theta", "vx", "vy", "omega"].map(|n| column(&format!("{b}.{n}")));
        let [x, y, th, vx, vy, w] = c;
        let (x, y, th, vx, vy, w) = (x?, y?, th?, vx?, vy?, w?);
        Ok((0..x.len())
            .map(|k| {
                BodyState::new(
                    Vector2::new(x[k], y[k]),
                    th[k],
                    Vector2::new(vx[k], vy[k]),
                    w[k],
                )
            })
            .collect())
    };
    let (slider, rod) = (body("slider")?, body("rod")?);
    let [t, phi, f_n, dw] = lubrication_wear::contact_history(&res, t_from, p.journal_radius);
    let skip = slider.len() - t.len();
    let slip: Vec<f64> = (0..t.len())
        .map(|k| {
            joint
                .contact(&slider[skip + k], &rod[skip + k])
                .tangential_velocity
        })
        .collect();
    let law = lubrication_wear::wan_archard(p)?;
    let mut approx = BearingProfile::zero(WEAR_ANGLES).map_err(|e| e.to_string())?;
    let v_dw = law
        .accumulate_history(&mut approx, &t, &phi, &f_n, &dw)
        .map_err(|e| e.to_string())?;
    let mut profile = BearingProfile::zero(WEAR_ANGLES).map_err(|e| e.to_string())?;
    let v = law
        .accumulate_history(&mut profile, &t, &phi, &f_n, &slip)
        .map_err(|e| e.to_string())?;
    Ok((profile, v, v_dw))
}

/// The study's aligned case against the planar wear of the same mechanism.
fn study_cases() -> Vec<Case> {
    let (id_v, id_p, id_e) = (
        "wear.spatial.study.planar_volume",
        "wear.spatial.study.planar_profile",
        "wear.spatial.study.uniform_along_axis",
    );
    let run = || -> Result<_, String> {
        let p = SliderCrankParams::wan();
        let (case, _) = journal_wear::run_case(&p, 0.0)?;
        let (planar, v_planar, v_dw) = planar_wear(&p)?;
        // the spatial map averaged over z: Δz Σ_m h_km / L
        let m = case.cycle.station_count() as f64;
        let mean: Vec<f64> = (0..planar.len())
            .map(|k| {
                case.cycle
                    .stations()
                    .iter()
                    .map(|s| s.depths()[k])
                    .sum::<f64>()
                    / m
            })
            .collect();
        let worst = mean
            .iter()
            .zip(planar.depths())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        Ok((case, v_planar, v_dw, worst / planar.max_depth(), planar))
    };
    match run() {
        Ok((case, v_planar, v_dw, worst, planar)) => vec![
            Case::new(
                id_v,
                "spatial Wan slider–crank, aligned joint B: worn volume of one steady revolution \
                 against the planar wear of the planar run",
                "m^3",
                "independent formulation: planar Archard (clr_contact::wear) on the planar Wan \
                 slider–crank's history with the contact points' slip; tolerance 1e-3 (measured \
                 1.2e-4: the runs differ only by their integrators' step sequences, over which \
                 the trapezoidal rule sums, and the spatial Gauss rule against one planar \
                 force; 8× margin)",
            )
            .relative(case.volume_per_cycle, v_planar, 1e-3)
            .note(format!(
                "planar with the planar study's slip |Δω| R_j: {v_dw:.6e} m³ ({:+.2} % against \
                 the spatial): that slip leaves out the centres' relative tangential velocity",
                100.0 * (v_dw / case.volume_per_cycle - 1.0)
            )),
            Case::new(
                id_p,
                "aligned joint B: largest difference of the spatial map averaged over z from \
                 the planar profile (360 angles), over the planar peak",
                "-",
                "independent formulation (as planar_volume); tolerance 1e-2 of the peak \
                 (measured 4.7e-3: the Hertz-width bins of the largest loads sit where each \
                 run's steps sample the impacts; 2× margin)",
            )
            .at_most(worst, 1e-2)
            .note(format!(
                "spatial peak {:.6e} m, planar peak {:.6e} m",
                case.depth_per_cycle,
                planar.max_depth()
            )),
            Case::new(
                id_e,
                "aligned joint B: edge concentration of the wear map",
                "-",
                "closed form: nothing tilts the journal (planar reduction), so every station \
                 wears alike and the ratio is 1; tolerance 1e-9",
            )
            .absolute(case.edge_concentration, 1.0, 1e-9),
        ],
        Err(e) => vec![
            failed(id_v, "study volume", "m^3", e.clone()),
            failed(id_p, "study profile", "-", e.clone()),
            failed(id_e, "study edge concentration", "-", e),
        ],
    }
}

/// Figures of docs/wear.md ("Spatial journal: the study"): the study's `axial_profile` and
/// `rim_profile` (the study is run into target/models/wear/journal, ~4 s) copied to
/// `wear_journal_<name>.{svg,png}`.
pub fn figures(dir: &std::path::Path) -> Result<(), String> {
    let sdir = crate::target_dir()
        .join("models")
        .join("wear")
        .join("journal");
    journal_wear::study(&sdir)?;
    crate::study_figures::copy_study_figures(
        &sdir,
        &["axial_profile", "rim_profile"],
        dir,
        "wear_journal_",
    )
}
