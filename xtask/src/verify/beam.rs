//! Verification cases of clr-beam (being written).

use super::Filter;
use crate::report::Case;

pub fn cases(_filter: &Filter) -> Vec<Case> {
    Vec::new()
}

/// Figures of clr-beam for `docs/figures/` (called by `cargo xtask figures`).
pub fn figures(_dir: &std::path::Path) -> Result<(), String> {
    Err("no figure yet".into())
}
