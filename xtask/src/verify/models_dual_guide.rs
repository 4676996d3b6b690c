//! Verification cases of clr-models: dual_guide (in progress; the cases are added with the model).

use std::path::Path;

use super::Filter;
use crate::report::Case;

pub fn cases(_filter: &Filter) -> Vec<Case> {
    Vec::new()
}

pub fn figures(_dir: &Path) -> Result<(), String> {
    Ok(())
}
