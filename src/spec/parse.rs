//! From a model file's text to a `clr_mbd::ModelDesc`: TOML syntax, the upgrade of files
//! written for older versions of the format (each change reported), and the description's
//! schema with the offending field's path, line and a suggestion. There is no second data
//! layer: the file is read straight into the description.

use clr_mbd::desc::FieldError;
use clr_mbd::element::{Clearance, Driver, Force, Joint};
use clr_mbd::ModelDesc;

use super::locate::{closest, FieldPath, Seg};
use super::SpecError;

/// Parse the text as a TOML table; a syntax error is placed at its line and column.
///
/// # Errors
/// [`SpecError`] with the place of the syntax error.
pub(crate) fn table(file: &str, src: &str) -> Result<toml::Table, SpecError> {
    toml::from_str(src).map_err(|e: toml::de::Error| {
        let offset = e.span().map(|s| s.start);
        SpecError::at_offset(file, src, offset, e.message().trim())
    })
}

/// Bring a file written for an older version of the format up to date, in place; returns one
/// note per change (what was assumed and how to write it now).
///
/// Older files could leave out a clearance joint's `type` (then a revolute clearance joint)
/// and spell kinds with other case or hyphens (`Spring-Damper`).
pub(crate) fn upgrade(root: &mut toml::Table) -> Vec<String> {
    let mut notes = Vec::new();
    let sections: [(&str, &[&str]); 4] = [
        ("joint", Joint::KINDS),
        ("driver", Driver::KINDS),
        ("force", Force::KINDS),
        ("clearance", Clearance::KINDS),
    ];
    for (section, kinds) in sections {
        let Some(toml::Value::Array(items)) = root.get_mut(section) else {
            continue;
        };
        for (k, item) in items.iter_mut().enumerate() {
            let Some(t) = item.as_table_mut() else {
                continue;
            };
            let kind = t
                .get("type")
                .and_then(toml::Value::as_str)
                .map(str::to_string);
            match kind.as_deref() {
                None if section == "clearance" && !t.contains_key("type") => {
                    t.insert("type".into(), "revolute".into());
                    notes.push(format!(
                        "{section}[{k}]: no `type` given; read as `type = \"revolute\"` (older \
                         files could leave it out; write it to silence this note)"
                    ));
                }
                Some(kind) if !kinds.contains(&kind) => {
                    let norm = kind.trim().to_ascii_lowercase().replace('-', "_");
                    if let Some(&known) = kinds.iter().find(|k| **k == norm) {
                        t.insert("type".into(), known.into());
                        notes.push(format!(
                            "{section}[{k}].type: `{kind}` read as `{known}` (write `{known}`)"
                        ));
                    }
                }
                _ => {}
            }
        }
    }
    notes
}

/// The model description in the (upgraded) table; an error names the field, its line and a
/// likely fix.
///
/// # Errors
/// [`SpecError`] at the offending field.
pub(crate) fn desc(file: &str, src: &str, table: toml::Table) -> Result<ModelDesc, SpecError> {
    refuse_unused_solver_fields(file, src, &table)?;
    ModelDesc::from_toml_table(table).map_err(|e| schema_error(file, src, &e))
}

/// A `[solver]` field the chosen method does not use is refused even at its default value
/// (`max_order = 5` under `method = "dopri5"`): every input is used or refused.
fn refuse_unused_solver_fields(
    file: &str,
    src: &str,
    table: &toml::Table,
) -> Result<(), SpecError> {
    let Some(solver) = table.get("solver").and_then(toml::Value::as_table) else {
        return Ok(());
    };
    let method = match solver.get("method").and_then(toml::Value::as_str) {
        Some("dopri5") => clr_mbd::desc::SolverMethod::Dopri5,
        _ => return Ok(()),
    };
    let unused = clr_mbd::desc::unused_solver_fields(method);
    match unused.iter().find(|k| solver.contains_key(**k)) {
        Some(k) => Err(SpecError::at(
            file,
            src,
            &FieldPath::root().key("solver").key(k),
            format!(
                "method = \"dopri5\" does not use `{k}` (an NDF setting): remove it, or set \
                 method = \"ndf\""
            ),
        )),
        None => Ok(()),
    }
}

/// A schema error of the description as a [`SpecError`]: the path gets the field a message
/// names (`missing field `mass``), the message a suggestion.
pub(super) fn schema_error(file: &str, src: &str, e: &FieldError) -> SpecError {
    let mut path = parse_path(&e.path);
    let message = e.message.trim();
    let named = |prefix: &str| {
        message
            .strip_prefix(prefix)
            .and_then(|r| r.split('`').next())
            .map(str::to_string)
    };
    let text = if let Some(name) = named("unknown field `") {
        path = with_last(path, &name);
        match closest(&name, expected(message).iter().map(String::as_str)) {
            Some(c) => format!("unknown field `{name}`; did you mean `{c}`?"),
            None => format!(
                "unknown field `{name}`; valid fields here: {}",
                expected(message).join(", ")
            ),
        }
    } else if let Some(name) = named("missing field `") {
        path = with_last(path, &name);
        format!("missing value: give `{name}` (see docs/model-file.md)")
    } else if let Some(name) = named("unknown variant `") {
        let valid = expected(message);
        match closest(&name, valid.iter().map(String::as_str)) {
            Some(c) => format!("unknown type `{name}`; did you mean `{c}`?"),
            None => format!("unknown type `{name}`; valid: {}", valid.join(", ")),
        }
    } else {
        message.to_string()
    };
    SpecError::at(file, src, &path, text)
}

/// The names serde lists after "expected" in its message.
fn expected(message: &str) -> Vec<String> {
    let Some(rest) = message.split("expected").nth(1) else {
        return Vec::new();
    };
    rest.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// `path` ending in the key `name` (appended unless it is already the last key).
fn with_last(path: FieldPath, name: &str) -> FieldPath {
    match path.0.last() {
        Some(Seg::Key(k)) if k == name => path,
        _ => path.key(name),
    }
}

/// A dotted path with indices (`clearance[0].normal.restitution`) as a [`FieldPath`].
pub(crate) fn parse_path(text: &str) -> FieldPath {
    let mut p = FieldPath::root();
    for part in text.split('.').filter(|s| !s.is_empty()) {
        let mut pieces = part.split('[');
        if let Some(key) = pieces.next().filter(|k| !k.is_empty()) {
            p = p.key(key);
        }
        for idx in pieces {
            if let Ok(i) = idx.trim_end_matches(']').parse() {
                p = p.index(i);
            }
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Upgrades are reported, and a current file needs none.
    #[test]
    fn old_forms_are_upgraded_with_a_note() {
        let mut t: toml::Table = toml::from_str(
            "[[clearance]]\nname = \"B\"\n[[force]]\ntype = \"Spring-Damper\"\nname = \"s\"\n",
        )
        .unwrap();
        let notes = upgrade(&mut t);
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert_eq!(t["clearance"][0]["type"].as_str(), Some("revolute"));
        assert_eq!(t["force"][0]["type"].as_str(), Some("spring_damper"));
        assert!(upgrade(&mut t).is_empty());
    }

    #[test]
    fn paths_parse_with_indices() {
        let p = parse_path("clearance[0].normal.restitution");
        assert_eq!(p.to_string(), "clearance[0].normal.restitution");
        assert_eq!(parse_path("").to_string(), "");
    }
}
