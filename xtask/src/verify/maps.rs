//! The finding maps of issue 19 in the known-gap notes: each note of a published finding that a
//! built-in reconstruction does not reproduce states where, over the plausible space of the
//! reconstruction, the finding holds and which parameters decide it. The numbers are read from
//! the map summaries committed under `docs/models/maps/` (written by `clr study
//! <model>_findings_map`, copied there with the run's wall time in the model's page), so that a
//! note always quotes the map the docs show.

use clr_models::findings::Summary;
use clr_models::map_study::MapDef;

/// Folder of the committed map summaries.
pub const MAPS_DIR: &str = "docs/models/maps";

/// The known-gap link of a finding: the model page's section on the finding, then the map's
/// section and the one-line statement of each of `findings` (`clr_models::findings::Summary::
/// finding_line`, joined by "; ", each led by its id when there are several), or why there is
/// none. A finding measured two ways (the flap's irregularity: Poincaré spread and divergence
/// rate) quotes both.
pub fn gap(finding_doc: &str, map: &MapDef, map_doc: &str, findings: &[&str]) -> String {
    let (name, size) = (map.name, map.default_points);
    let path = crate::workspace_root()
        .join(MAPS_DIR)
        .join(format!("{name}_summary.json"));
    if !path.exists() {
        return format!(
            "{finding_doc}; finding map {map_doc}: not run yet (`clr study {name}`, its \
             summary copied to {MAPS_DIR}/)"
        );
    }
    let line = std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str::<Summary>(&t).map_err(|e| e.to_string()))
        .and_then(|s| {
            let lines = findings
                .iter()
                .map(|f| {
                    let line = s
                        .finding_line(f)
                        .ok_or_else(|| format!("no finding `{f}` in it"))?;
                    // with several, each line says which finding it is about
                    Ok::<_, String>(if findings.len() > 1 {
                        format!("`{f}` {line}")
                    } else {
                        line
                    })
                })
                .collect::<Result<Vec<_>, _>>()?
                .join("; ");
            Ok(if s.points < size {
                format!(
                    "{lines} (preliminary: {} of the study's {size} points)",
                    s.points
                )
            } else {
                lines
            })
        })
        .unwrap_or_else(|e| format!("map summary {MAPS_DIR}/{name}_summary.json unusable: {e}"));
    format!("{finding_doc}; finding map {map_doc}: {line}")
}

#[cfg(test)]
mod tests {
    use super::*;

    // Every finding id that verify's known-gap notes quote is a finding of its map, so a note
    // never reads "no finding" once the map's summary is committed.
    #[test]
    fn quoted_findings_belong_to_their_maps() {
        let ids = |m: &MapDef| (m.findings)().into_iter().map(|f| f.id).collect::<Vec<_>>();
        let guide = ids(&clr_models::guide_map::MAP);
        for f in [
            "clearance_friction",
            "friction_clearance",
            "friction_direction",
            "friction_speed",
            "friction_flattening",
        ] {
            assert!(guide.iter().any(|g| g == f), "{f}");
        }
        let flap = ids(&clr_models::flap_map::MAP);
        for f in ["suspension", "suspension_weakens"]
            .iter()
            .chain(&super::super::models_flap_flex::IRREGULAR)
        {
            assert!(flap.iter().any(|g| g == f), "{f}");
        }
        assert!(ids(&clr_models::dual_guide_map::MAP).contains(&"spacing_jamming".to_string()));
    }

    // The committed dual-guide summary (256 points) is quoted without "preliminary"; an unknown
    // finding is named in the note instead of being dropped.
    #[test]
    fn a_note_quotes_the_committed_summary_or_names_the_problem() {
        let m = &clr_models::dual_guide_map::MAP;
        let ok = gap("doc", m, "map", &["spacing_jamming", "more_impacts"]);
        assert!(ok.contains("of 256") && !ok.contains("preliminary"), "{ok}");
        assert_eq!(ok.matches("holds at").count(), 2, "{ok}");
        assert!(ok.contains("`more_impacts` holds at"), "{ok}");
        let bad = gap("doc", m, "map", &["no_such_finding"]);
        assert!(bad.contains("no finding `no_such_finding`"), "{bad}");
    }
}
