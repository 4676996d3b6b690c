//! The documentation's examples are what the binary does: every TOML block of README.md and
//! docs/*.md is read by the model-file reader, and the commands of the README's "Your first
//! mechanism" path run as written.
//!
//! A block holding a `[model]` table is a whole model file: it must load and build (the same
//! reader and checks as `clr run`). Any other block is a fragment of one (a `[[shape]]` section,
//! an `[output.nodes]` table): it must deserialize as part of a model description, so a field the
//! docs name but the reader refuses (a misspelt or removed key, a wrong type) fails here.

mod common;

use std::path::{Path, PathBuf};

use clr_sim::spec::{load_str, Loaded};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A fenced block: the line of its opening fence and its text.
type Block = (usize, String);

/// The fenced blocks of `lang` in a Markdown text.
fn blocks(text: &str, lang: &str) -> Vec<Block> {
    let (mut out, mut current): (Vec<Block>, Option<Block>) = (vec![], None);
    for (i, line) in text.lines().enumerate() {
        let fence = line.trim_start().starts_with("```");
        match current.take() {
            Some(b) if fence => out.push(b),
            Some((at, mut body)) => {
                body.push_str(line);
                body.push('\n');
                current = Some((at, body));
            }
            None if fence && line.trim() == format!("```{lang}") => {
                current = Some((i + 1, String::new()))
            }
            None => {}
        }
    }
    out
}

/// Every Markdown file whose TOML blocks are checked.
fn documents() -> Vec<PathBuf> {
    let mut docs = vec![root().join("README.md")];
    let mut md: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    md.sort();
    docs.extend(md);
    docs
}

/// Checks one TOML block; the error says what the reader refused.
fn check_block(name: &str, text: &str) -> Result<(), String> {
    let whole = text.lines().any(|l| l.trim() == "[model]");
    if whole {
        return match load_str(name, text, &[]) {
            Ok(Loaded::Generic(spec)) => spec.build().map(|_| ()).map_err(|e| e.to_string()),
            Ok(Loaded::Spatial(spec)) => spec.build().map(|_| ()).map_err(|e| e.to_string()),
            Ok(Loaded::Builtin { .. }) => Ok(()),
            Err(e) => Err(e.to_string()),
        };
    }
    let bare = !text.lines().any(|l| l.trim_start().starts_with('['));
    if bare {
        return check_clearance_keys(name, text);
    }
    // A fragment: read as the sections of a model description (field names and types).
    // `[output] t_end` is the one required table: before a fragment's `[output.nodes]`, else after
    let framed = if text.contains("[output") {
        format!("[output]\nt_end = 1.0\n{text}")
    } else {
        format!("{text}\n[output]\nt_end = 1.0\n")
    };
    // the sections of a planar description, or else of a spatial one
    toml::from_str::<clr_sim::mbd::ModelDesc>(&framed)
        .map(|_| ())
        .or_else(|planar| {
            let spatial = format!("[model]\nspace = \"spatial\"\n{framed}");
            toml::from_str::<clr_sim::mbd::spatial::SpatialDesc>(&spatial)
                .map(|_| ())
                .map_err(|_| planar.to_string())
        })
}

/// A block of bare keys (`lubrication = { … }`) documents fields of a revolute clearance joint:
/// they are added to the clearance joint of tests/data/journal_bearing.toml, which must then
/// load and build.
fn check_clearance_keys(name: &str, text: &str) -> Result<(), String> {
    let base = std::fs::read_to_string(root().join("tests/data/journal_bearing.toml")).unwrap();
    let mut model: toml::Table = toml::from_str(&base).unwrap();
    let keys: toml::Table = toml::from_str(text).map_err(|e| e.to_string())?;
    let clearance = model["clearance"].as_array_mut().unwrap()[0]
        .as_table_mut()
        .unwrap();
    clearance.extend(keys);
    let merged = toml::to_string(&model).unwrap();
    check_block(name, &merged)
}

#[test]
fn every_toml_block_of_the_docs_is_read_by_the_reader() {
    let mut failures = vec![];
    let mut checked = 0;
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        let rel = doc.strip_prefix(root()).unwrap().display().to_string();
        for (line, block) in blocks(&text, "toml") {
            checked += 1;
            let name = format!("{rel}:{line}");
            if let Err(e) = check_block(&name, &block) {
                failures.push(format!("{name}: {e}"));
            }
        }
    }
    assert!(checked >= 15, "only {checked} TOML blocks found");
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The README's "Your first mechanism" commands, each `clr …` line run with the built binary
/// (output folders moved to a scratch folder).
#[test]
fn the_readme_first_mechanism_path_runs_as_written() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let start = readme
        .find("## Your first mechanism")
        .expect("README has a \"Your first mechanism\" section");
    let section = &readme[start..];
    let end = section[3..].find("\n## ").map_or(section.len(), |e| e + 3);
    let scratch = common::scratch_in("docs_examples", "first_mechanism");
    let mut ran = 0;
    for (_, block) in blocks(&section[..end], "sh") {
        for line in block.lines().map(str::trim) {
            let Some(args) = line.strip_prefix("clr ") else {
                continue;
            };
            let args: Vec<String> = args
                .split_whitespace()
                .take_while(|a| !a.starts_with('#'))
                .map(|a| match a.strip_prefix("out/") {
                    Some(rest) => scratch.join(rest).display().to_string(),
                    None if a.ends_with(".toml") => root().join(a).display().to_string(),
                    None => a.to_string(),
                })
                .collect();
            let refs: Vec<&str> = args.iter().map(String::as_str).collect();
            let o = common::clr(&refs);
            assert!(
                o.status.success(),
                "README command `{line}` failed:\n{}",
                common::stderr(&o)
            );
            ran += 1;
        }
    }
    assert!(
        ran >= 3,
        "only {ran} commands in the README's first-mechanism path"
    );
}

/// The model file that documents each section's fields in the tests: a complete file holding an
/// item of that section (and type).
fn base_for(section: &str, kind: Option<&str>) -> Option<&'static str> {
    Some(match (section, kind) {
        ("body" | "point" | "output", _) => "tests/data/pendulum.toml",
        ("beam", _) => "tests/data/cantilever.toml",
        ("flexible_body", _) => "tests/data/flexible_slider_crank.toml",
        ("clearance", Some("revolute")) => "tests/data/journal_bearing.toml",
        ("clearance", Some("translational")) => "tests/data/slider_in_guide.toml",
        ("clearance", Some("slider_on_beam")) => "models/guide.toml",
        ("metric", _) => "models/examples/four_bar_measures.toml",
        ("input", _) => "models/examples/slider_crank_fmu.toml",
        _ => return None,
    })
}

/// The `required` rows of docs/model-file.md's field tables: (section, type, field, doc line).
fn required_rows(doc: &str) -> Vec<(String, Option<String>, String, usize)> {
    let (mut section, mut kind) = (None::<String>, None::<String>);
    let mut rows = vec![];
    for (i, line) in doc.lines().enumerate() {
        if let Some(h) = line.strip_prefix("### `[") {
            section = Some(
                h.trim_start_matches('[')
                    .split(']')
                    .next()
                    .unwrap()
                    .to_string(),
            );
            kind = None;
        } else if line.starts_with("### ") || line.starts_with("## ") {
            section = None;
        } else if let Some(rest) = line
            .strip_prefix("**")
            .filter(|r| r.contains("(`type = \""))
        {
            kind = rest
                .split("type = \"")
                .nth(1)
                .map(|k| k.split('"').next().unwrap().into());
        }
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let Some(section) = section.as_ref() else {
            continue;
        };
        if cells.len() < 5 || !cells[3].starts_with("required") {
            continue;
        }
        for field in cells[1].split(',').map(|f| f.trim().trim_matches('`')) {
            rows.push((section.clone(), kind.clone(), field.to_string(), i + 1));
        }
    }
    rows
}

/// Every field docs/model-file.md calls required is refused when left out, with an error that
/// names it (the reader and the docs say the same).
#[test]
fn every_field_the_docs_call_required_is_refused_when_left_out() {
    let doc = std::fs::read_to_string(root().join("docs/model-file.md")).unwrap();
    let rows = required_rows(&doc);
    assert!(rows.len() >= 30, "only {} required rows found", rows.len());
    let mut failures = vec![];
    for (section, kind, field, line) in rows {
        let Some(base) = base_for(&section, kind.as_deref()) else {
            failures.push(format!(
                "model-file.md:{line}: no test file for [{section}] {kind:?}"
            ));
            continue;
        };
        let text = std::fs::read_to_string(root().join(base)).unwrap();
        let mut model: toml::Table = toml::from_str(&text).unwrap();
        let item = match model.get_mut(&section) {
            Some(toml::Value::Array(items)) => items.iter_mut().find(|t| {
                kind.as_deref()
                    .is_none_or(|k| t.get("type").and_then(|v| v.as_str()) == Some(k))
            }),
            Some(v @ toml::Value::Table(_)) => Some(v),
            _ => None,
        };
        let Some(toml::Value::Table(item)) = item else {
            failures.push(format!(
                "model-file.md:{line}: {base} has no [{section}] {kind:?}"
            ));
            continue;
        };
        if item.remove(&field).is_none() {
            failures.push(format!(
                "model-file.md:{line}: {base} [{section}] has no `{field}`"
            ));
            continue;
        }
        let name = format!("{base} without {section}.{field}");
        match check_block(&name, &toml::to_string(&model).unwrap()) {
            Ok(()) => failures.push(format!(
                "model-file.md:{line}: `{field}` of [{section}] {kind:?} is called required, \
                 but {base} without it is accepted"
            )),
            Err(e) if !e.contains(&field) => failures.push(format!(
                "model-file.md:{line}: leaving out `{field}` gives an error not naming it: {e}"
            )),
            Err(_) => {}
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
