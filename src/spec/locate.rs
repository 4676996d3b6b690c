//! Paths into a model file (`body[1].mass`) and their line numbers.

use std::fmt;

use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// One step of a [`FieldPath`]: a table key or an array index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Seg {
    /// A key of a table.
    Key(String),
    /// An element of an array (array of tables `[[body]]` included), from 0.
    Index(usize),
}

/// Where a value sits in a model file, e.g. `clearance[0].normal.restitution`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct FieldPath(pub Vec<Seg>);

impl FieldPath {
    /// The empty path (the whole file).
    pub fn root() -> Self {
        Self(Vec::new())
    }
    /// This path extended by a key.
    pub fn key(&self, k: &str) -> Self {
        let mut v = self.0.clone();
        v.push(Seg::Key(k.to_string()));
        Self(v)
    }
    /// This path extended by an array index.
    pub fn index(&self, i: usize) -> Self {
        let mut v = self.0.clone();
        v.push(Seg::Index(i));
        Self(v)
    }
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut first = true;
        for s in &self.0 {
            match s {
                Seg::Key(k) => {
                    if !first {
                        write!(f, ".")?;
                    }
                    write!(f, "{k}")?;
                }
                Seg::Index(i) => write!(f, "[{i}]")?,
            }
            first = false;
        }
        Ok(())
    }
}

/// Line (1-based) and column (1-based) of a byte offset in `src`.
pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(src.len());
    let before = &src.as_bytes()[..offset];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let col = offset
        - before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |p| p + 1)
        + 1;
    (line, col)
}

/// Byte offset of the deepest part of `path` present in the TOML text `src` (the key for table
/// entries, the element for array items). `None` when the text does not parse or nothing of the
/// path is present.
pub fn locate(src: &str, path: &FieldPath) -> Option<usize> {
    let root = DeTable::parse(src).ok()?;
    let mut best = None;
    let mut table: Option<&DeTable> = Some(root.get_ref());
    let mut value: Option<&Spanned<DeValue>> = None;
    for seg in &path.0 {
        match seg {
            Seg::Key(k) => {
                let t = match (table, value) {
                    (Some(t), _) => t,
                    (None, Some(v)) => match v.get_ref() {
                        DeValue::Table(t) => t,
                        _ => break,
                    },
                    _ => break,
                };
                let Some((key, v)) = t.iter().find(|(key, _)| key.get_ref() == k) else {
                    break;
                };
                best = Some(key.span().start);
                table = None;
                value = Some(v);
            }
            Seg::Index(i) => {
                let Some(v) = value else { break };
                let DeValue::Array(a) = v.get_ref() else {
                    break;
                };
                let Some(e) = a.get(*i) else { break };
                best = Some(e.span().start);
                table = None;
                value = Some(e);
            }
        }
    }
    best
}

pub use clr_mbd::desc::{closest, edit_distance, suggestion};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_matches_hand_counts() {
        // kitten → sitting: 3 edits (the textbook example, Levenshtein 1966)
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("mass", "mass"), 0);
        assert_eq!(closest("mas", ["mass", "inertia"]), Some("mass"));
        assert_eq!(closest("zzzzzz", ["mass", "inertia"]), None);
    }

    #[test]
    fn locate_finds_keys_in_arrays_of_tables() {
        let src = "[model]\nname = \"x\"\n\n[[body]]\nname = \"a\"\n\n[[body]]\nname = \"b\"\nmass = 2.0\n";
        let p = FieldPath::root().key("body").index(1).key("mass");
        assert_eq!(p.to_string(), "body[1].mass");
        let off = locate(src, &p).unwrap();
        assert_eq!(line_col(src, off).0, 9);
        // a missing key falls back to its table
        let p = FieldPath::root().key("body").index(0).key("mass");
        let off = locate(src, &p).unwrap();
        assert_eq!(line_col(src, off).0, 4);
    }
}
