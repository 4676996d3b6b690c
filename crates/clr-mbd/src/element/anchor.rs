//! Where a joint or force attaches: a named point, a body with local coordinates, or a beam
//! node. In a file: `"point name"`, `{ body = "rod", at = [x, y] }` or
//! `{ beam = "guide", node = 4 }`.

use serde::{Deserialize, Serialize};

/// Where a joint or force attaches: a named point, or a body with local coordinates (m) in the
/// body frame, or a node of a flexible beam.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(into = "AnchorRepr")]
pub enum Anchor {
    /// A named point (`[[point]]`).
    Point(String),
    /// A body name and local coordinates in its frame (m).
    Local(String, [f64; 2]),
    /// A node of a flexible beam (beam name, node index): the attachment moves with the node's
    /// displacement and rotation (small-rotation node frame).
    BeamNode(String, usize),
}

/// The written form (serialization only; reading goes through [`AnchorVisitor`], which refuses
/// unknown keys: an untagged enum would drop a misspelt `att` silently).
#[derive(Serialize)]
#[serde(untagged)]
enum AnchorRepr {
    Point(String),
    Local { body: String, at: [f64; 2] },
    Node { beam: String, node: usize },
}

impl From<Anchor> for AnchorRepr {
    fn from(a: Anchor) -> Self {
        match a {
            Anchor::Point(p) => AnchorRepr::Point(p),
            Anchor::Local(body, at) => AnchorRepr::Local { body, at },
            Anchor::BeamNode(beam, node) => AnchorRepr::Node { beam, node },
        }
    }
}

impl<'de> Deserialize<'de> for Anchor {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(AnchorVisitor)
    }
}

const ANCHOR_KEYS: &[&str] = &["body", "at", "beam", "node"];

/// Reads `"point"`, `{ body, at }` or `{ beam, node }`, refusing other keys and mixtures.
struct AnchorVisitor;

impl<'de> serde::de::Visitor<'de> for AnchorVisitor {
    type Value = Anchor;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a point name, `{ body = \"…\", at = [x, y] }` or `{ beam = \"…\", node = k }`")
    }

    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Anchor, E> {
        Ok(Anchor::Point(v.to_string()))
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Anchor, A::Error> {
        use serde::de::Error;
        let (mut body, mut at, mut beam, mut node) = (None, None, None, None);
        while let Some(key) = map.next_key::<String>()? {
            match key.as_str() {
                "body" => body = Some(map.next_value::<String>()?),
                "at" => at = Some(map.next_value::<[f64; 2]>()?),
                "beam" => beam = Some(map.next_value::<String>()?),
                "node" => node = Some(map.next_value::<usize>()?),
                other => return Err(A::Error::unknown_field(other, ANCHOR_KEYS)),
            }
        }
        match (body, at, beam, node) {
            (Some(b), at, None, None) => Ok(Anchor::Local(b, at.unwrap_or([0.0, 0.0]))),
            (None, None, Some(b), Some(n)) => Ok(Anchor::BeamNode(b, n)),
            (None, None, Some(_), None) => Err(A::Error::missing_field("node")),
            (None, Some(_), None, None) => Err(A::Error::missing_field("body")),
            (None, None, None, _) => Err(A::Error::missing_field("body")),
            _ => Err(A::Error::custom(
                "an anchor is on a body (`body`, `at`) or a beam node (`beam`, `node`), not both",
            )),
        }
    }
}

impl From<(&str, usize)> for Anchor {
    fn from((beam, node): (&str, usize)) -> Self {
        Anchor::BeamNode(beam.to_string(), node)
    }
}

impl From<&str> for Anchor {
    fn from(point: &str) -> Self {
        Anchor::Point(point.to_string())
    }
}

impl From<(&str, [f64; 2])> for Anchor {
    fn from((body, local): (&str, [f64; 2])) -> Self {
        Anchor::Local(body.to_string(), local)
    }
}
