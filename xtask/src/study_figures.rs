//! Study figures into the docs: the verification modules that make the docs' figures
//! (`cargo xtask figures`) copy a study's plots into `docs/figures` under the names the docs use.

use std::path::Path;

/// Copy the study figures `<from>/<name>.{svg,png}` into the docs folder `to` as
/// `<prefix><name>.{svg,png}` (creating `to`).
pub fn copy_study_figures(
    from: &Path,
    names: &[&str],
    to: &Path,
    prefix: &str,
) -> Result<(), String> {
    std::fs::create_dir_all(to).map_err(|e| e.to_string())?;
    for name in names {
        for ext in ["svg", "png"] {
            let src = from.join(format!("{name}.{ext}"));
            let dst = to.join(format!("{prefix}{name}.{ext}"));
            std::fs::copy(&src, &dst).map_err(|e| format!("{}: {e}", src.display()))?;
        }
    }
    Ok(())
}
