//! Where a joint or force attaches: a named point, a body with local coordinates, or a beam
//! node. In a file: `"point name"`, `{ body = "rod", at = [x, y] }` or
//! `{ beam = "guide", node = 4 }`.

use serde::{Deserialize, Serialize};

/// Where a joint or force attaches: a named point, or a body with local coordinates (m) in the
/// body frame, or a node of a flexible beam.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(from = "AnchorRepr", into = "AnchorRepr")]
pub enum Anchor {
    /// A named point (`[[point]]`).
    Point(String),
    /// A body name and local coordinates in its frame (m).
    Local(String, [f64; 2]),
    /// A node of a flexible beam (beam name, node index): the attachment moves with the node's
    /// displacement and rotation (small-rotation node frame).
    BeamNode(String, usize),
}

#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum AnchorRepr {
    Point(String),
    Local {
        body: String,
        #[serde(default)]
        at: [f64; 2],
    },
    Node {
        beam: String,
        node: usize,
    },
}

impl From<AnchorRepr> for Anchor {
    fn from(r: AnchorRepr) -> Self {
        match r {
            AnchorRepr::Point(p) => Anchor::Point(p),
            AnchorRepr::Local { body, at } => Anchor::Local(body, at),
            AnchorRepr::Node { beam, node } => Anchor::BeamNode(beam, node),
        }
    }
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
