//! Verification cases of clr-contact (being written).

use super::Filter;
use crate::report::Case;

pub fn cases(_filter: &Filter) -> Vec<Case> {
    Vec::new()
}

/// Figures of clr-contact for `docs/figures/` (called by `cargo xtask figures`).
pub fn figures(_dir: &std::path::Path) -> Result<(), String> {
    Err("no figure yet".into())
}
