//! Field-level errors of a description and name suggestions ("did you mean"): the leaf every
//! layer of clr-mbd reports through.

/// A field-level error of a description: the path of the field (`joint[2].axis`) and what to
/// change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("field `{path}`: {message}")]
pub struct FieldError {
    /// Path of the offending field, e.g. `clearance[0].normal.restitution`.
    pub path: String,
    /// What is wrong and what to change.
    pub message: String,
}

impl FieldError {
    /// An error at `path`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
        }
    }
}

/// Levenshtein edit distance between two strings (characters, not bytes).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

/// The candidate closest to `name` by edit distance, when it is close enough to be a likely
/// typo (distance ≤ max(2, len/3)) or one contains the other.
pub fn closest<'a, I: IntoIterator<Item = &'a str>>(name: &str, candidates: I) -> Option<&'a str> {
    let lower = name.to_ascii_lowercase();
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        let d = edit_distance(&lower, &c.to_ascii_lowercase());
        if best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    let (d, c) = best?;
    let limit = (name.chars().count() / 3).max(2);
    let contains = !lower.is_empty()
        && (c.to_ascii_lowercase().contains(&lower) || lower.contains(&c.to_ascii_lowercase()));
    (d <= limit || contains).then_some(c)
}

/// `"; did you mean `x`?"` when a close candidate exists, else the list of valid names.
pub fn suggestion<'a, I>(name: &str, candidates: I) -> String
where
    I: IntoIterator<Item = &'a str> + Clone,
{
    match closest(name, candidates.clone()) {
        Some(c) => format!("did you mean `{c}`?"),
        None => {
            let all: Vec<&str> = candidates.into_iter().collect();
            if all.is_empty() {
                "none is defined".to_string()
            } else {
                format!("valid: {}", all.join(", "))
            }
        }
    }
}
