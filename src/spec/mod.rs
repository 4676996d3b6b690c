//! The clr model file: a TOML description of any clr-mbd model, or of a built-in model with
//! its parameters.
//!
//! Two forms (field by field in `docs/model-file.md`):
//!
//! - a **generic model**: `[model]`, `[[body]]`, `[[point]]`, `[[beam]]`, `[[flexible_body]]`,
//!   `[[joint]]`, `[[driver]]`, `[[force]]`, `[[clearance]]`, `[solver]`, `[output]`; a file
//!   that reads as a `clr_mbd::ModelDesc` (what `clr export <name>` writes) is compiled as is,
//!   any other is checked by the validator; [`load`] does either and [`ModelSpec::build`] turns
//!   the result into a `clr_mbd::Model` and its `SimOptions`;
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
    // a model description (`clr_mbd::ModelDesc`, e.g. written by `clr export`) is used as is;
    // anything else goes through the validator of model files. A description that does not
    // compile gets the validator's message (placed at the field, written for files) when the
    // validator reads the file and rejects it too, else its own (placed at the item or field)
    if let Some(desc) = read_desc(src, overrides) {
        return match ModelSpec::from_desc(file, src, desc?) {
            Ok(spec) => Ok(Loaded::Generic(Box::new(spec))),
            Err(e) if file::parse(file, src).is_ok() => {
                Err(load_generic(file, src, overrides).err().unwrap_or(e))
            }
            Err(e) => Err(e),
        };
    }
    load_generic(file, src, overrides)
}

/// The text as a model description with the overrides applied, when it is one: it parses as
/// `clr_mbd::ModelDesc` and has at least one body, beam or flexible body (a file without any
/// is left to the validator, which says what is missing). An override that does not apply, or
/// leaves something that is no description, is an error.
fn read_desc(src: &str, overrides: &[Assignment]) -> Option<Result<clr_mbd::ModelDesc, SpecError>> {
    let desc: clr_mbd::ModelDesc = toml::from_str(src).ok()?;
    if desc.bodies.is_empty() && desc.beams.is_empty() && desc.flexible_bodies.is_empty() {
        return None;
    }
    if overrides.is_empty() {
        return Some(Ok(desc));
    }
    Some(overrides::apply_to_table(src, overrides).and_then(|v| {
        v.try_into().map_err(|e: toml::de::Error| {
            SpecError::plain("--set", "", format!("after the overrides: {}", e.message()))
        })
    }))
}

/// [`load_str`] through the model-file validator.
fn load_generic(file: &str, src: &str, overrides: &[Assignment]) -> Result<Loaded, SpecError> {
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
