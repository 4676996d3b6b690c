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
/// section and its one-line statement of `finding` (`clr_models::findings::Summary::
/// finding_line`), or why there is none.
pub fn gap(finding_doc: &str, map: &MapDef, map_doc: &str, finding: &str) -> String {
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
            let line = s
                .finding_line(finding)
                .ok_or_else(|| format!("no finding `{finding}` in it"))?;
            Ok(if s.points < size {
                format!(
                    "{line} (preliminary: {} of the study's {size} points)",
                    s.points
                )
            } else {
                line
            })
        })
        .unwrap_or_else(|e| format!("map summary {MAPS_DIR}/{name}_summary.json unusable: {e}"));
    format!("{finding_doc}; finding map {map_doc}: {line}")
}
