//! The clr model file: a TOML description of any clr-mbd model, or of a built-in model with
//! its parameters.
//!
//! Two forms (field by field in `docs/model-file.md`):
//!
//! - a **generic model**: the file *is* a `clr_mbd::ModelDesc` (`[model]`, `[[body]]`,
//!   `[[point]]`, `[[beam]]`, `[[flexible_body]]`, `[[joint]]`, `[[driver]]`, `[[force]]`,
//!   `[[clearance]]`, `[solver]`, `[output]`; what `clr export` writes). [`load`] reads it
//!   straight into the description (files of older versions of the format are upgraded, each
//!   change reported), compiles it once to check it, and [`ModelSpec::build`] hands over the
//!   `clr_mbd::Model` with its `SimOptions`;
//! - a **built-in model**: `[model] builtin = "<name>"` and a `[parameters]` table merged over
//!   the catalog defaults (`clr_models::catalog`).
//!
//! Every error is a [`SpecError`] that names the file, line and field and says what to change;
//! a malformed file never panics. SI units everywhere, angles in radians.

mod builtin;
pub mod locate;
mod model;
pub(crate) mod overrides;
mod parse;
pub mod run;
mod spatial;
pub mod sweep;

use std::path::Path;

pub use clr_mbd::timefn::TimeFn;
pub use locate::FieldPath;
pub use model::{Built, ModelSpec};
pub use overrides::{
    apply_json_override, parse_assignment, parse_value as overrides_value, Assignment,
};
pub use spatial::SpatialSpec;

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
        Self {
            field: path.to_string(),
            ..Self::at_offset(file, src, locate::locate(src, path), message)
        }
    }

    /// An error at the byte `offset` of `src` (line and column from it), without a field.
    pub(crate) fn at_offset(
        file: &str,
        src: &str,
        offset: Option<usize>,
        message: impl Into<String>,
    ) -> Self {
        let (line, column) = offset.map_or((None, None), |off| {
            let (l, c) = locate::line_col(src, off);
            (Some(l), Some(c))
        });
        Self {
            file: file.to_string(),
            line,
            column,
            field: String::new(),
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
    /// A spatial model (`[model] space = "spatial"`), validated.
    Spatial(Box<SpatialSpec>),
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
    let mut root = parse::table(file, src)?;
    if let Some(name) = builtin::name(file, src, &root)? {
        return builtin::builtin(file, src, &root, &name, overrides);
    }
    if is_spatial(&root) {
        for a in overrides {
            overrides::set_toml(&mut root, a)?;
        }
        return SpatialSpec::from_table(file, src, root, Vec::new())
            .map(|s| Loaded::Spatial(Box::new(s)));
    }
    let notes = parse::upgrade(&mut root);
    let spec = generic_with(file, src, &root, notes.clone(), overrides);
    match spec {
        Err(e) if !overrides.is_empty() => {
            Err(blame_override(file, src, &root, notes, overrides, e))
        }
        other => other.map(|s| Loaded::Generic(Box::new(s))),
    }
}

/// Whether the file says `[model] space = "spatial"`.
fn is_spatial(root: &toml::Table) -> bool {
    root.get("model")
        .and_then(|m| m.get("space"))
        .and_then(|s| s.as_str())
        == Some("spatial")
}

/// The generic model of the (upgraded) table `root` of the file with `overrides` applied.
fn generic_with(
    file: &str,
    src: &str,
    root: &toml::Table,
    mut notes: Vec<String>,
    overrides: &[Assignment],
) -> Result<ModelSpec, SpecError> {
    let mut root = root.clone();
    for a in overrides {
        overrides::set_toml(&mut root, a)?;
    }
    if !overrides.is_empty() {
        // an override may bring an old form back (a clearance `type` removed by --set)
        notes.extend(parse::upgrade(&mut root));
    }
    let desc = parse::desc(file, src, root)?;
    if desc.bodies.is_empty() && desc.beams.is_empty() && desc.flexible_bodies.is_empty() {
        // placed at the missing section (an empty or comment-only file has no other place)
        return Err(SpecError::at(
            file,
            src,
            &FieldPath::root().key("body"),
            "the file defines nothing that moves: give at least one [[body]], [[beam]] or \
             [[flexible_body]], or `[model] builtin = \"<name>\"` for a built-in model \
             (`clr list` names them)",
        ));
    }
    ModelSpec::from_desc(file, src, desc, notes)
}

/// The error `e` of the file with `overrides` placed on the `--set` that causes it rather than
/// on the file's line of the value it replaced: the first override whose addition gives the
/// same error (the file alone reading without it). An error the file has without its
/// overrides stays at its line.
fn blame_override(
    file: &str,
    src: &str,
    root: &toml::Table,
    notes: Vec<String>,
    overrides: &[Assignment],
    e: SpecError,
) -> SpecError {
    let same = |r: Result<ModelSpec, SpecError>| {
        r.err()
            .is_some_and(|x| x.field == e.field && x.message == e.message)
    };
    if same(generic_with(file, src, root, notes.clone(), &[])) {
        return e;
    }
    let culprit = (1..=overrides.len())
        .find(|&k| {
            same(generic_with(
                file,
                src,
                root,
                notes.clone(),
                &overrides[..k],
            ))
        })
        .map(|k| &overrides[k - 1]);
    let place = match culprit {
        Some(a) => format!("--set '{}={}'", a.path, a.value_text()),
        None => "--set (these overrides together)".to_string(),
    };
    SpecError {
        file: place,
        line: None,
        column: None,
        ..e
    }
}
