//! The paper studies, by name: what `clr study <name>` runs. Each writes its CSV files,
//! `summary.csv` and figures into a folder; the same studies back `cargo xtask verify models`
//! (where their findings are checked) with the settings listed here.

use std::path::Path;

use crate::flap::{self, FlapParams};
use crate::map_study::MapDef;
use crate::{
    dual_guide, dual_guide_map, flap_flex_study, flap_map, guide, guide_map, lubrication_wear,
    manipulator,
};

/// One built-in study.
#[derive(Debug, Clone, Copy)]
pub struct Study {
    /// Name used on the command line (`clr study <name>`).
    pub name: &'static str,
    /// The catalog model it varies.
    pub model: &'static str,
    /// One-line description, with its size and rough wall time on 2 cores.
    pub description: &'static str,
    /// Run it, writing into the folder; returns the number of runs.
    pub run: fn(&Path) -> Result<usize, String>,
    /// A finding map (issue 19): its design can be run in part and sharded, and shards merged.
    pub map: Option<MapStudy>,
}

/// The operations of a finding-map study beyond [`Study::run`]: its [`MapDef`] (design,
/// checkpoint and resume, shards, merge).
pub type MapStudy = &'static MapDef;

/// Duration of the rigid flap studies, s (ramp 0.25 s + 4 actuator periods).
pub const FLAP_STUDY_DURATION: f64 = 2.25;
pub use crate::flap_flex::FLAP_FLEX_STUDY_DURATION;
/// Interguide spacings of the dual-guide spacing study, m.
pub const DUAL_GUIDE_SPACINGS: [f64; 3] = [0.05, 0.1, 0.2];

fn flap_rigid(dir: &Path) -> Result<usize, String> {
    let base = FlapParams {
        duration: FLAP_STUDY_DURATION,
        ..Default::default()
    };
    flap::study(dir, &base).map(|c| c.len())
}

fn flap_flexible(dir: &Path) -> Result<usize, String> {
    let base = FlapParams {
        duration: FLAP_FLEX_STUDY_DURATION,
        ..Default::default()
    };
    flap_flex_study::study(dir, &base).map(|c| c.len())
}

/// Every built-in study.
pub fn studies() -> Vec<Study> {
    vec![
        Study {
            name: "manipulator_cases",
            model: "manipulator",
            description:
                "ideal case and cases 1-5 of Kuang, Bai, Wei (2026), 2 s each (6 runs, ~2 s)",
            run: |dir| manipulator::study(dir, None).map(|c| c.len()),
            map: None,
        },
        Study {
            name: "flap_clearance",
            model: "flap",
            description: "rigid flap linkage: clearance size, joint position, number of joints, \
                          reversing load (14 runs of 2.25 s, ~1 min)",
            run: flap_rigid,
            map: None,
        },
        Study {
            name: "flap_misalignment",
            model: "flap",
            description: "rigid flap linkage in space, spatial revolute clearance joints of the \
                          paper's 15 mm bearing length, bore axes misaligned 0/0.05/0.1/0.2° \
                          about and across the link: clearance size and position (49 runs of \
                          1.25 s + 8 planar, ~9 min; docs/models/flap.md#misalignment)",
            run: |dir| crate::flap_spatial::study(dir).map(|c| c.len()),
            map: None,
        },
        Study {
            name: "flap_flexible",
            model: "flap",
            description:
                "flexible lever arm / aux rod / aux lever arm: number of flexible bodies, \
                          number of joints, 4 joints + 3 flexible, reversing load (24 runs of 1.25 s, ~1.5 min)",
            run: flap_flexible,
            map: None,
        },
        Study {
            name: "guide_elastic_vs_rigid",
            model: "guide",
            description: "single sliding guide, elastic against rigid guide (2 runs, ~10 s)",
            run: |dir| guide::elastic_vs_rigid(dir).map(|r| r.len()),
            map: None,
        },
        Study {
            name: "guide_friction",
            model: "guide",
            description: "single sliding guide: clearance x stroke direction x speed, equivalent \
                          friction coefficient (10 runs of 0.2 s, ~1 min)",
            run: |dir| {
                guide::friction_study(
                    dir,
                    &guide::GuideParams::default(),
                    &guide::friction_series(),
                    guide::FRICTION_DURATION,
                )
                .map(|r| r.len())
            },
            map: None,
        },
        Study {
            name: "flap_findings_map",
            model: "flap",
            description: "finding map of the flexible flap's four findings (issue 19): 256 Sobol \
                          points over hinge moment and stiffness, modal damping, clearance and \
                          joint order, 5 runs of 1.25 s at rtol 1e-8 each with its ideal \
                          reference, 3 with a twin (3328 simulations, about 4 h on 2 cores; \
                          docs/models/flap.md#finding-map)",
            run: |dir| flap_map::MAP.study(dir),
            map: Some(&flap_map::MAP),
        },
        Study {
            name: "guide_findings_map",
            model: "guide",
            description: "finding map of the guide's five friction findings (issue 19): 256 \
                          Sobol points over 8 reconstructed parameters, 8 runs of 0.2 s each \
                          (2048 runs, hours on 2 cores; docs/models/guide.md#finding-map)",
            run: |dir| guide_map::MAP.study(dir),
            map: Some(&guide_map::MAP),
        },
        Study {
            name: "dual_guide_vs_single",
            model: "dual_guide",
            description: "dual-stage dual guide against the single guide (2 runs, ~5 s)",
            run: |dir| dual_guide::single_vs_dual(dir).map(|r| r.len()),
            map: None,
        },
        Study {
            name: "dual_guide_spacing",
            model: "dual_guide",
            description:
                "dual-stage dual guide at interguide spacings 50/100/200 mm (3 runs, ~10 s)",
            run: |dir| dual_guide::spacing_study(dir, &DUAL_GUIDE_SPACINGS).map(|r| r.len()),
            map: None,
        },
        Study {
            name: "dual_guide_findings_map",
            model: "dual_guide",
            description: "finding map of the dual guide's three findings (issue 19): 256 Sobol \
                          points over spacing, load offset, carriage twist (reduced model, 0 on \
                          a quarter), clearance and load, 3 runs of 0.1 s each (768 runs, about \
                          half an hour on 2 cores; docs/models/dual_guide.md#finding-map)",
            run: |dir| dual_guide_map::MAP.study(dir),
            map: Some(&dual_guide_map::MAP),
        },
        Study {
            name: "flap_lubricated",
            model: "flap",
            description: "rigid flap linkage, 0.1 mm in all four joints: dry against lubricated \
                          (short bearing, 0.04 Pa·s), steady and reversing hinge load: 4 cases + 2 \
                          ideal references (6 runs of 2.25 s, ~15 s)",
            run: |dir| lubrication_wear::flap_lubricated(dir).map(|c| c.len()),
            map: None,
        },
        Study {
            name: "wan_slider_crank_wear",
            model: "wan_slider_crank",
            description: "Wan slider-crank joint worn by Archard's law (K = 1e-5, H = 2 GPa, \
                          N = 360): one steady-state cycle per update extrapolated by <= 1 um \
                          per update up to 1e6 cycles (15 runs of 0.2 s, ~5 s)",
            run: |dir| lubrication_wear::wan_slider_crank_wear(dir).map(|u| u.len()),
            map: None,
        },
        Study {
            name: "journal_wear",
            model: "wan_slider_crank",
            description: "Wan slider-crank in space, joint B a spatial revolute clearance joint \
                          of 15 mm with the bore misaligned 0/0.1/0.2°: Archard wear map \
                          h_w(φ, z) of one steady revolution, extrapolated to 1e6 cycles, edge \
                          concentration (3 runs of 0.2 s, ~4 s; docs/wear.md, study `journal_wear`)",
            run: |dir| crate::journal_wear::study(dir).map(|c| c.len()),
            map: None,
        },
    ]
}

/// A study by name.
///
/// # Errors
/// The valid names when `name` is unknown.
pub fn find(name: &str) -> Result<Study, String> {
    studies()
        .into_iter()
        .find(|s| s.name == name)
        .ok_or_else(|| {
            format!(
                "unknown study `{name}`; valid: {}",
                studies()
                    .iter()
                    .map(|s| s.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn study_names_are_unique_and_name_catalog_models() {
        let all = studies();
        let models: Vec<&str> = crate::catalog::entries().iter().map(|e| e.name).collect();
        for (k, s) in all.iter().enumerate() {
            assert!(models.contains(&s.model), "{} names {}", s.name, s.model);
            assert!(all[k + 1..].iter().all(|o| o.name != s.name), "{}", s.name);
        }
        let e = find("nope").unwrap_err();
        assert!(e.contains("guide_friction"), "{e}");
    }
}
