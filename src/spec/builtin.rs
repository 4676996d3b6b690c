//! The built-in form of a model file: `[model] builtin = "<name>"` and a `[parameters]` table
//! merged over the catalog defaults (`clr_models::catalog`).

use super::locate::FieldPath;
use super::overrides::{apply_json_override, Assignment};
use super::{Loaded, SpecError};

/// Sections of a generic model file (refused next to `builtin`).
const FILE_SECTIONS: [&str; 11] = [
    "body",
    "point",
    "beam",
    "flexible_body",
    "joint",
    "driver",
    "force",
    "clearance",
    "solver",
    "output",
    "model",
];

/// The built-in model a file names with `[model] builtin = "<name>"`, if any.
///
/// # Errors
/// [`SpecError`] when `builtin` is not a string.
pub(crate) fn name(file: &str, src: &str, root: &toml::Table) -> Result<Option<String>, SpecError> {
    match root.get("model").and_then(|m| m.get("builtin")) {
        None => Ok(None),
        Some(toml::Value::String(s)) => Ok(Some(s.clone())),
        Some(other) => Err(SpecError::at(
            file,
            src,
            &FieldPath::root().key("model").key("builtin"),
            format!("expected the name of a built-in model as text, got `{other}`"),
        )),
    }
}

/// The `[model] builtin = ...` form: merge `[parameters]` over the defaults, then the overrides.
pub(crate) fn builtin(
    file: &str,
    src: &str,
    root: &toml::Table,
    name: &str,
    overrides: &[Assignment],
) -> Result<Loaded, SpecError> {
    let model_path = FieldPath::root().key("model").key("builtin");
    let names: Vec<&str> = clr_models::catalog::entries()
        .iter()
        .map(|e| e.name)
        .collect();
    let mut params = clr_models::catalog::default_parameters(name).map_err(|_| {
        SpecError::at(
            file,
            src,
            &model_path,
            format!(
                "unknown built-in model `{name}`; {}",
                super::locate::suggestion(name, names.iter().copied())
            ),
        )
    })?;
    // only [model] (name, description, builtin) and [parameters] belong in this form
    for sec in root.keys() {
        if sec == "model" || sec == "parameters" {
            continue;
        }
        let hint = if FILE_SECTIONS.contains(&sec.as_str()) {
            format!("remove `{sec}` or write a generic model without `builtin`")
        } else {
            format!("unknown section `{sec}`; remove it")
        };
        return Err(SpecError::at(
            file,
            src,
            &FieldPath::root().key(sec),
            format!(
                "a built-in model file (`[model] builtin = \"{name}\"`) takes only `[model]` and \
                 `[parameters]`; {hint}"
            ),
        ));
    }
    if let Some(toml::Value::Table(m)) = root.get("model") {
        for key in m.keys() {
            if !["name", "description", "builtin"].contains(&key.as_str()) {
                let why = if key == "gravity" {
                    "a built-in model takes gravity from its `[parameters]`; remove `gravity` here"
                        .to_string()
                } else {
                    format!("`[model]` of a built-in model file takes name, description and builtin; remove `{key}`")
                };
                return Err(SpecError::at(
                    file,
                    src,
                    &FieldPath::root().key("model").key(key),
                    why,
                ));
            }
        }
    }
    match root.get("parameters") {
        Some(toml::Value::Table(p)) => {
            let base = FieldPath::root().key("parameters");
            merge_table(file, src, &base, &mut params, p)?;
        }
        Some(_) => {
            return Err(SpecError::at(
                file,
                src,
                &FieldPath::root().key("parameters"),
                "`parameters` must be a table: write `[parameters]` and the values below it",
            ))
        }
        None => {}
    }
    for a in overrides {
        apply_json_override(&mut params, a)?;
    }
    let table = root.get("parameters").and_then(toml::Value::as_table);
    refuse_unused(file, src, name, &params, table, overrides)?;
    check(file, src, name, &params)?;
    Ok(Loaded::Builtin {
        name: name.to_string(),
        parameters: params,
    })
}

/// A parameter the user gave (under `[parameters]` or by `--set`) that the model's other
/// parameters make unused (`clr_models::catalog::unused_parameters`, e.g. `axial_length` with
/// the `LN` preset) is refused at its place: every input is used or refused.
///
/// # Errors
/// [`SpecError`] at the parameter (or `--set` for an override).
pub(crate) fn refuse_unused(
    file: &str,
    src: &str,
    name: &str,
    params: &serde_json::Value,
    table: Option<&toml::Table>,
    overrides: &[Assignment],
) -> Result<(), SpecError> {
    let unused = clr_models::catalog::unused_parameters(name, params).unwrap_or_default();
    for (p, why) in unused {
        let message = format!("`{p}` is not used: {why}; remove it");
        if table.is_some_and(|t| t.contains_key(p)) {
            let path = FieldPath::root().key("parameters").key(p);
            return Err(SpecError::at(file, src, &path, message));
        }
        if overrides
            .iter()
            .any(|a| a.path.split('.').next() == Some(p))
        {
            return Err(SpecError::plain("--set", p, message));
        }
    }
    Ok(())
}

/// Check the merged parameters as a run would (the catalog builds and compiles the model), so
/// that a refused value is reported at its place in the file rather than when the run starts.
fn check(file: &str, src: &str, name: &str, params: &serde_json::Value) -> Result<(), SpecError> {
    let settings = clr_models::RunSettings::default();
    let result = clr_models::catalog::export(name, params, &settings).and_then(|d| {
        // the run settings the parameters give (atol = 1e-3·rtol, the end time), then the model
        d.sim_options()
            .map_err(|e| clr_models::ModelsError::InvalidParameters {
                model: name.to_string(),
                message: e.to_string(),
            })?;
        d.compile()
            .map(drop)
            .map_err(|e| clr_models::ModelsError::Build {
                model: name.to_string(),
                source: Box::new(e),
            })
    });
    let message = match result {
        Ok(()) => return Ok(()),
        Err(clr_models::ModelsError::InvalidParameters { message, .. }) => message,
        Err(e) => e.to_string(),
    };
    Err(SpecError::at(
        file,
        src,
        &parameter_path(&message, params),
        message,
    ))
}

/// The parameter a catalog message names in backticks (`end`, `friction.mu`), else the
/// `[parameters]` table.
fn parameter_path(message: &str, params: &serde_json::Value) -> FieldPath {
    let base = FieldPath::root().key("parameters");
    for name in message.split('`').skip(1).step_by(2) {
        let mut v = params;
        let mut p = base.clone();
        let mut found = !name.is_empty();
        for part in name.split('.') {
            match v.get(part) {
                Some(x) => {
                    v = x;
                    p = p.key(part);
                }
                None => {
                    found = false;
                    break;
                }
            }
        }
        if found {
            return p;
        }
    }
    base
}

/// Merge a TOML table into JSON defaults: every key must exist with the same kind of value.
fn merge_table(
    file: &str,
    src: &str,
    path: &FieldPath,
    target: &mut serde_json::Value,
    table: &toml::Table,
) -> Result<(), SpecError> {
    let serde_json::Value::Object(obj) = target else {
        return Err(SpecError::at(
            file,
            src,
            path,
            "this parameter is a single value, not a table",
        ));
    };
    for (k, v) in table {
        let p = path.key(k);
        let Some(slot) = obj.get_mut(k) else {
            let known: Vec<&str> = obj.keys().map(String::as_str).collect();
            return Err(SpecError::at(
                file,
                src,
                &p,
                format!(
                    "unknown parameter `{k}`; {}",
                    super::locate::suggestion(k, known.iter().copied())
                ),
            ));
        };
        if let toml::Value::Table(t) = v {
            // a table tagged by `law` or `type` that switches variant replaces the default
            // whole (e.g. friction `none` → `coulomb` with its own fields)
            let switches = ["law", "type"].iter().any(|tag| {
                t.get(*tag).and_then(|x| x.as_str()).is_some_and(|new| {
                    slot.get(*tag)
                        .and_then(|x| x.as_str())
                        .is_some_and(|old| old != new)
                })
            });
            if switches {
                *slot = super::overrides::toml_to_json(v)
                    .map_err(|m| SpecError::at(file, src, &p, m))?;
                continue;
            }
            merge_table(file, src, &p, slot, t)?;
        } else {
            let new =
                super::overrides::toml_to_json(v).map_err(|m| SpecError::at(file, src, &p, m))?;
            super::overrides::check_same_kind(slot, &new)
                .map_err(|m| SpecError::at(file, src, &p, m))?;
            *slot = new;
        }
    }
    Ok(())
}
