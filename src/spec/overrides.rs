//! `name=value` overrides from the command line (`--set`, `--vary`).

use super::locate::suggestion;
use super::SpecError;

/// One `path=value` assignment. The path is dotted: `solver.rtol`, `body.rod.mass` (array items
/// by their `name` or index), or a parameter path of a built-in model (`clearance.radial`).
#[derive(Debug, Clone, PartialEq)]
pub struct Assignment {
    /// Dotted path.
    pub path: String,
    /// The value as a TOML value (`1.5`, `true`, `"ln"`, `[0, -9.81]`); bare words are strings.
    pub value: toml::Value,
}

impl Assignment {
    /// The value as written on a command line (`1.5`, `ln`).
    pub fn value_text(&self) -> String {
        match &self.value {
            toml::Value::String(s) => s.clone(),
            v => v.to_string(),
        }
    }
}

/// Parse a value written on the command line: a TOML value, or else a bare string.
pub fn parse_value(text: &str) -> toml::Value {
    let text = text.trim();
    toml::from_str::<toml::Table>(&format!("v = {text}"))
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(text.to_string()))
}

/// Parse `path=value`.
///
/// # Errors
/// [`SpecError`] when there is no `=` or the path is empty.
pub fn parse_assignment(text: &str) -> Result<Assignment, SpecError> {
    let Some((p, v)) = text.split_once('=') else {
        return Err(SpecError::plain(
            "--set",
            text,
            "expected name=value (e.g. --set solver.rtol=1e-8)",
        ));
    };
    let p = p.trim();
    if p.is_empty() || p.split('.').any(str::is_empty) {
        return Err(SpecError::plain(
            "--set",
            text,
            "the name is empty or has an empty part; write e.g. body.rod.mass=2",
        ));
    }
    Ok(Assignment {
        path: p.to_string(),
        value: parse_value(v),
    })
}

/// A TOML value as JSON (TOML dates become strings).
pub(crate) fn toml_to_json(v: &toml::Value) -> Result<serde_json::Value, String> {
    Ok(match v {
        toml::Value::String(s) => serde_json::Value::String(s.clone()),
        toml::Value::Integer(i) => serde_json::Value::from(*i),
        toml::Value::Float(f) => serde_json::Number::from_f64(*f)
            .map(serde_json::Value::Number)
            .ok_or_else(|| format!("{f} is not a finite number; give a finite value"))?,
        toml::Value::Boolean(b) => serde_json::Value::Bool(*b),
        toml::Value::Datetime(d) => serde_json::Value::String(d.to_string()),
        toml::Value::Array(a) => {
            serde_json::Value::Array(a.iter().map(toml_to_json).collect::<Result<Vec<_>, _>>()?)
        }
        toml::Value::Table(t) => serde_json::Value::Object(
            t.iter()
                .map(|(k, v)| Ok((k.clone(), toml_to_json(v)?)))
                .collect::<Result<_, String>>()?,
        ),
    })
}

fn kind(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Null => "empty",
        serde_json::Value::Bool(_) => "true/false",
        serde_json::Value::Number(_) => "number",
        serde_json::Value::String(_) => "text",
        serde_json::Value::Array(_) => "list",
        serde_json::Value::Object(_) => "table",
    }
}

/// Check that `new` has the kind of `old` (number, text, …); integers given for a float
/// parameter are converted to floats in place by the caller through [`coerce`].
pub(crate) fn check_same_kind(
    old: &serde_json::Value,
    new: &serde_json::Value,
) -> Result<(), String> {
    if old.is_null() || kind(old) == kind(new) {
        Ok(())
    } else {
        Err(format!(
            "expected a {} (the default is {old}), got {new}",
            kind(old)
        ))
    }
}

/// An integer given where the default is a float becomes a float, so a built-in receives the
/// type it expects.
fn coerce(old: &serde_json::Value, new: serde_json::Value) -> serde_json::Value {
    match (old, &new) {
        (serde_json::Value::Number(o), serde_json::Value::Number(n))
            if o.is_f64() && !n.is_f64() =>
        {
            n.as_f64()
                .and_then(serde_json::Number::from_f64)
                .map_or(new, serde_json::Value::Number)
        }
        _ => new,
    }
}

/// Apply an assignment to the JSON parameters of a built-in model. The path must exist.
///
/// # Errors
/// [`SpecError`] naming the unknown part with the closest valid name, or a value of the wrong
/// kind.
pub fn apply_json_override(
    params: &mut serde_json::Value,
    a: &Assignment,
) -> Result<(), SpecError> {
    let err = |m: String| SpecError::plain("--set", &a.path, m);
    let mut cur = params;
    for part in a.path.split('.') {
        cur = match cur {
            serde_json::Value::Object(o) => {
                if !o.contains_key(part) {
                    let known: Vec<String> = o.keys().cloned().collect();
                    return Err(err(format!(
                        "unknown parameter `{part}`; {}",
                        suggestion(part, known.iter().map(String::as_str))
                    )));
                }
                o.get_mut(part).expect("checked above")
            }
            serde_json::Value::Array(v) => {
                let n = v.len();
                match part.parse::<usize>().ok().filter(|&i| i < n) {
                    Some(i) => &mut v[i],
                    None => {
                        return Err(err(format!(
                            "`{part}` is not an index of this list (0 to {})",
                            n.saturating_sub(1)
                        )))
                    }
                }
            }
            _ => {
                return Err(err(format!(
                    "`{part}` goes below a single value; shorten the name"
                )))
            }
        };
    }
    let new = toml_to_json(&a.value).map_err(err)?;
    check_same_kind(cur, &new).map_err(err)?;
    let new = coerce(cur, new);
    *cur = new;
    Ok(())
}

/// Set one assignment in a model file's table (array items by `name` or index; missing keys
/// are added, and the description then refuses the ones it does not know).
///
/// # Errors
/// [`SpecError`] naming the part of the path that does not exist.
pub(crate) fn set_toml(root: &mut toml::Table, a: &Assignment) -> Result<(), SpecError> {
    let (table, last) = walk_mut(root, &a.path)?;
    table.insert(last.to_string(), a.value.clone());
    Ok(())
}

/// The value a `--set` path names in a model file's table (not defaults: the field must be
/// written in the file).
///
/// # Errors
/// A message naming the missing part.
pub(crate) fn get_toml(root: &toml::Table, path: &str) -> Result<toml::Value, String> {
    // the same walk as `--set`, on a copy (the walk creates missing tables; the copy keeps the
    // file's table as it is)
    let mut copy = root.clone();
    let (table, last) = walk_mut(&mut copy, path).map_err(|e| e.to_string())?;
    table.get(last).cloned().ok_or_else(|| {
        format!(
            "`{path}` is not written in the model file; write its value there to make it a \
             parameter"
        )
    })
}

/// The table holding the last part of `path` (tables on the way are created; array items are
/// chosen by `name` or index) and that last part.
fn walk_mut<'a, 'p>(
    root: &'a mut toml::Table,
    path: &'p str,
) -> Result<(&'a mut toml::Table, &'p str), SpecError> {
    let err = |m: String| SpecError::plain("--set", path, m);
    let parts: Vec<&str> = path.split('.').collect();
    let (last, init) = parts.split_last().expect("paths are non-empty");
    let mut table = root;
    let mut k = 0;
    while k < init.len() {
        let part = init[k];
        let next = table
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        table = match next {
            toml::Value::Table(t) => t,
            toml::Value::Array(items) => {
                // an array of tables: the next part names an item (by `name` or index)
                k += 1;
                let Some(sel) = init.get(k) else {
                    return Err(err(format!(
                        "`{part}` is a list; name an item, e.g. {part}.<name>.{last}"
                    )));
                };
                let names: Vec<String> = items
                    .iter()
                    .filter_map(|i| i.get("name").and_then(|n| n.as_str()).map(str::to_string))
                    .collect();
                let pos = items
                    .iter()
                    .position(|i| i.get("name").and_then(|n| n.as_str()) == Some(*sel))
                    .or_else(|| sel.parse::<usize>().ok().filter(|&i| i < items.len()));
                let Some(pos) = pos else {
                    return Err(err(format!(
                        "no {part} named `{sel}`; {}",
                        suggestion(sel, names.iter().map(String::as_str))
                    )));
                };
                match &mut items[pos] {
                    toml::Value::Table(t) => t,
                    _ => return Err(err(format!("{part} item `{sel}` is not a table"))),
                }
            }
            _ => return Err(err(format!("`{part}` is a single value; shorten the name"))),
        };
        k += 1;
    }
    Ok((table, last))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn assignments_parse_values_and_override_json() {
        let a = parse_assignment("solver.rtol=1e-8").unwrap();
        assert_eq!(a.value, toml::Value::Float(1e-8));
        let a = parse_assignment("normal.damping=ln").unwrap();
        assert_eq!(a.value, toml::Value::String("ln".into()));
        assert!(parse_assignment("noequals").is_err());
        let mut p = serde_json::json!({"clearance": {"radial": 0.5e-3, "law": "LN"}});
        apply_json_override(&mut p, &parse_assignment("clearance.radial=1").unwrap()).unwrap();
        assert_eq!(p["clearance"]["radial"].as_f64(), Some(1.0));
        assert!(p["clearance"]["radial"].is_f64());
        let e = apply_json_override(&mut p, &parse_assignment("clearance.radail=1").unwrap())
            .unwrap_err();
        assert!(e.message.contains("did you mean `radial`"), "{e}");
        let e =
            apply_json_override(&mut p, &parse_assignment("clearance.law=2").unwrap()).unwrap_err();
        assert!(e.message.contains("expected a text"), "{e}");
    }
}
