//! The clr model file: a TOML description of any clr-mbd model, or of a built-in model with
//! its parameters.
//!
//! Two forms (field by field in `docs/model-file.md`):
//!
//! - a **generic model**: `[model]`, `[[body]]`, `[[point]]`, `[[joint]]`, `[[driver]]`,
//!   `[[force]]`, `[[clearance]]`, `[solver]`, `[output]`; [`load`] validates it and
//!   [`ModelSpec::build`] turns it into a `clr_mbd::Model` and its `SimOptions`;
//! - a **built-in model**: `[model] builtin = "<name>"` and a `[parameters]` table merged over
//!   the catalog defaults (`clr_models::catalog`).
//!
//! Every error is a [`SpecError`] that names the file, line and field and says what to change;
//! a malformed file never panics. SI units everywhere, angles in radians.

mod build;
mod file;
pub mod locate;
mod overrides;
pub mod run;
mod timefn;

use std::path::Path;

pub use build::{Built, ModelSpec};
pub use file::ModelFile;
pub use locate::FieldPath;
pub use overrides::{
    apply_json_override, parse_assignment, parse_value as overrides_value, Assignment,
};
pub use timefn::TimeFn;

/// An error in a model file or a command-line override, with its place.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{}", self.render())]
pub struct SpecError {
    /// The file (or `--set` for command-line overrides).
    pub file: String,
    /// Line (1-based) when known.
    pub line: Option<usize>,
    /// Column (1-based) when known.
    pub column: Option<usize>,
    /// The field, e.g. `body[1].mass` (empty for the whole file).
    pub field: String,
    /// What is wrong and what to change.
    pub message: String,
}

impl SpecError {
    fn render(&self) -> String {
        let mut s = self.file.clone();
        if let Some(l) = self.line {
            s.push_str(&format!(":{l}"));
            if let Some(c) = self.column {
                s.push_str(&format!(":{c}"));
            }
        }
        if self.field.is_empty() {
            format!("{s}: {}", self.message)
        } else {
            format!("{s}: field `{}`: {}", self.field, self.message)
        }
    }

    /// An error at `path` in the text `src` of `file` (line found from the path).
    pub fn at(file: &str, src: &str, path: &FieldPath, message: impl Into<String>) -> Self {
        let (line, column) = match locate::locate(src, path) {
            Some(off) => {
                let (l, c) = locate::line_col(src, off);
                (Some(l), Some(c))
            }
            None => (None, None),
        };
        Self {
            file: file.to_string(),
            line,
            column,
            field: path.to_string(),
            message: message.into(),
        }
    }

    /// An error without a place in a file (command-line input).
    pub fn plain(file: &str, field: &str, message: impl Into<String>) -> Self {
        Self {
            file: file.to_string(),
            line: None,
            column: None,
            field: field.to_string(),
            message: message.into(),
        }
    }
}

/// A loaded and validated model file.
#[derive(Debug, Clone)]
pub enum Loaded {
    /// `[model] builtin = "<name>"`: the catalog model with its full resolved parameters.
    Builtin {
        /// Catalog name.
        name: String,
        /// Defaults with the file's `[parameters]` and the overrides applied.
        parameters: serde_json::Value,
    },
    /// A generic model, validated.
    Generic(Box<ModelSpec>),
}

/// Read, parse and validate a model file, applying `name=value` overrides (paths as in
/// `docs/model-file.md`: `body.rod.mass`, `solver.rtol`, or parameter paths of a built-in).
///
/// # Errors
/// [`SpecError`] with file, line and field.
pub fn load(path: &Path, overrides: &[Assignment]) -> Result<Loaded, SpecError> {
    let file = path.display().to_string();
    let src = std::fs::read_to_string(path)
        .map_err(|e| SpecError::plain(&file, "", format!("cannot read the model file: {e}")))?;
    load_str(&file, &src, overrides)
}

/// As [`load`] from the text `src`; `file` names it in messages.
///
/// # Errors
/// [`SpecError`] with file, line and field.
pub fn load_str(file: &str, src: &str, overrides: &[Assignment]) -> Result<Loaded, SpecError> {
    let parsed = file::parse(file, src)?;
    if let Some(name) = parsed.model.as_ref().and_then(|m| m.builtin.clone()) {
        return file::builtin(file, src, &parsed, &name, overrides);
    }
    let parsed = if overrides.is_empty() {
        parsed
    } else {
        overrides::apply_toml_overrides(file, src, overrides)?
    };
    let spec = ModelSpec::validate(file, src, parsed)?;
    Ok(Loaded::Generic(Box::new(spec)))
}
