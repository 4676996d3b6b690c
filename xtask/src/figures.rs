//! `cargo xtask figures`: regenerate the figures embedded in `docs/`.

use std::path::Path;
use std::process::ExitCode;

/// A figure maker: writes its files into the given directory.
type Maker = fn(&Path) -> Result<(), String>;

/// Every figure of the docs, by name. Each crate's verification module contributes its own.
const MAKERS: &[(&str, Maker)] = &[
    ("ode", crate::verify::ode::figures),
    ("contact", crate::verify::contact::figures),
    ("beam", crate::verify::beam::figures),
    ("models", crate::verify::models::figures),
    (
        "models.flap flexible",
        crate::verify::models_flap_flex::figures,
    ),
    (
        "models.flap misalignment",
        crate::verify::models_flap_misalignment::figures,
    ),
    (
        "models.guide dual",
        crate::verify::models_dual_guide::figures,
    ),
    ("lubrication", crate::verify::lubrication::figures),
    ("wear.spatial", crate::verify::wear_spatial::figures),
];

/// `cargo xtask figures [NAME...]`: every maker, or those whose name starts with one of the
/// given names (`cargo xtask figures wear.spatial`).
pub fn run(args: &[String]) -> ExitCode {
    let dir = crate::workspace_root().join("docs").join("figures");
    let mut ok = true;
    let wanted = |name: &str| args.is_empty() || args.iter().any(|a| name.starts_with(a.as_str()));
    for (name, make) in MAKERS.iter().filter(|(n, _)| wanted(n)) {
        match make(&dir) {
            Ok(()) => println!("figure {name}: written"),
            Err(e) => {
                ok = false;
                eprintln!("figure {name}: {e}");
            }
        }
    }
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
