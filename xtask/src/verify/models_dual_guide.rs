//! Verification cases of clr-models: the dual-stage dual guide (seed 000, issue 6 §1): the
//! published trends against the single guide and over the interguide spacing (each with both
//! measured values in the note), and an independent Newton's-law check of the new model.
//! Parameters are reconstructions (docs/models/dual_guide.md).

use std::path::Path;

use super::Filter;
use crate::report::Case;

fn dir(study: &str) -> std::path::PathBuf {
    crate::target_dir()
        .join("models")
        .join("guide")
        .join("dual")
        .join(study)
}

/// Interguide spacings of the spacing study, m.
const SPACINGS: [f64; 3] = clr_models::studies::DUAL_GUIDE_SPACINGS;

pub fn cases(filter: &Filter) -> Vec<Case> {
    use clr_models::dual_guide::{self, StudyRun};
    let mut out = Vec::new();
    let src = "sliding-guide paper (seed 000, abstract; paper-systems.md §3.1): dual-stage dual \
               guide finding as a trend, parameters reconstructed (docs/models/dual_guide.md)";
    let get = |runs: &[StudyRun], n: &str, m: &str| -> f64 {
        runs.iter()
            .find(|r| r.name == n)
            .map_or(f64::NAN, |r| r.metric(m))
    };
    if filter.wants("models.guide.dual.newton") {
        out.push(newton_case());
    }
    if filter.wants("models.guide.dual.impacts") || filter.wants("models.guide.dual.lateral") {
        let start = std::time::Instant::now();
        match dual_guide::single_vs_dual(&dir("single_vs_dual")) {
            Ok(runs) => {
                let wall = start.elapsed().as_secs_f64();
                for (id, metric, unit, what) in [
                    ("impacts", "impacts", "-", "contact onsets"),
                    (
                        "lateral",
                        "max_lateral_displacement",
                        "m",
                        "max lateral displacement of the loaded carriage",
                    ),
                ] {
                    let (d, s) = (get(&runs, "dual", metric), get(&runs, "single", metric));
                    let per_pad = (
                        get(&runs, "dual", "impacts_per_pad"),
                        get(&runs, "single", "impacts_per_pad"),
                    );
                    out.push(
                        Case::new(
                            format!("models.guide.dual.{id}"),
                            format!("{what}, dual-stage dual guide ≥ single guide"),
                            unit,
                            src,
                        )
                        .at_least(d, s)
                        .note(format!(
                            "dual {d:.4e}, single {s:.4e} {unit} (impacts per pad: dual {:.1}, \
                             single {:.1}); study {wall:.1} s wall (2 runs in parallel)",
                            per_pad.0, per_pad.1
                        )),
                    );
                }
                println!("models.guide.dual single_vs_dual: {wall:.1} s wall (2 runs in parallel)");
            }
            Err(e) => out.push(
                Case::new(
                    "models.guide.dual.single_vs_dual",
                    "single vs dual",
                    "-",
                    src,
                )
                .failed(0.0, e),
            ),
        }
    }
    if filter.wants("models.guide.dual.spacing") {
        let start = std::time::Instant::now();
        match dual_guide::spacing_study(&dir("spacing"), &SPACINGS) {
            Ok(runs) => {
                let wall = start.elapsed().as_secs_f64();
                let j: Vec<f64> = runs.iter().map(|r| r.metric("jamming_indicator")).collect();
                let m: Vec<f64> = runs
                    .iter()
                    .map(|r| r.metric("peak_jamming_ratio"))
                    .collect();
                out.push(
                    Case::new(
                        "models.guide.dual.spacing_jamming",
                        "jamming indicator (mean Σ|actuator force| / μF), smallest spacing ≤ \
                         largest spacing",
                        "-",
                        src,
                    )
                    .at_most(j[0], j[2])
                    .note(format!(
                        "d = 50/100/200 mm: jamming indicator {:.3}, {:.3}, {:.3}; peak ratio \
                         {:.3}, {:.3}, {:.3}; study {wall:.1} s wall (3 runs in parallel)",
                        j[0], j[1], j[2], m[0], m[1], m[2]
                    ))
                    .known_gap(&super::maps::gap(
                        "docs/models/dual_guide.md#results",
                        &clr_models::dual_guide_map::MAP,
                        "docs/models/dual_guide.md#finding-map",
                        &["spacing_jamming"],
                    )),
                );
                println!("models.guide.dual spacing study: {wall:.1} s wall (3 runs in parallel)");
            }
            Err(e) => out.push(
                Case::new("models.guide.dual.spacing", "spacing study", "-", src).failed(0.0, e),
            ),
        }
    }
    out
}

/// Newton's second law on the unloaded dual guide under constant actuator accelerations
/// (a₁ = 2, a₂ = 3 m/s², no contact): the stage-2 actuator force equals m₂ (a₁ + a₂).
fn newton_case() -> Case {
    use clr_models::dual_guide::DualGuideParams;
    use clr_models::RunSettings;
    let p = DualGuideParams::newton_check();
    let expected = p.newton_stage1_force();
    let c = Case::new(
        "models.guide.dual.newton",
        "stage-1 actuator force of the unloaded, accelerated dual guide at t = 0.02 s",
        "N",
        "closed form F₁ = (m₁ + 2 m_g2) a₁ + m₂ (a₁ + a₂) (Newton's second law, no contact)",
    );
    match clr_models::dual_guide::run("dual_guide", &p, &RunSettings::default()) {
        Ok(o) => {
            let f = o.results.column("act1.Fx").unwrap_or_default();
            let last = f.last().copied().unwrap_or(f64::NAN);
            let onsets = o
                .metrics
                .iter()
                .find(|m| m.name == "impacts")
                .map_or(f64::NAN, |m| m.value);
            c.relative(last, expected, 1e-6)
                .note(format!("{onsets} contact onsets (expected 0)"))
        }
        Err(e) => c.failed(expected, e.to_string()),
    }
}

/// Figures of docs/models/dual_guide.md: both studies, copied as
/// `models-guide-dual-<study>-<name>.{svg,png}`.
pub fn figures(out: &Path) -> Result<(), String> {
    use clr_models::dual_guide;
    dual_guide::single_vs_dual(&dir("single_vs_dual"))?;
    dual_guide::spacing_study(&dir("spacing"), &SPACINGS)?;
    for study in ["single_vs_dual", "spacing"] {
        crate::study_figures::copy_study_figures(
            &dir(study),
            &["lateral", "actuator"],
            out,
            &format!("models-guide-dual-{study}-"),
        )?;
    }
    Ok(())
}
