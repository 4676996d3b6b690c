//! `distance`: the distance d = |r_b − r_a| between two points (m) and its rate
//! ḋ = (r_b − r_a)·(ṙ_b − ṙ_a)/d (m/s; 0 where the points coincide).

use serde::{Deserialize, Serialize};

use super::runtime::{CompiledMeasure, MeasureEl};
use crate::element::{Anchor, Compiler, Element};
use crate::error::MbdError;

/// Distance between two points: `<name>.distance` (m) and `<name>.distance_rate` (m/s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Distance {
    /// Unique measure name.
    pub name: String,
    /// First point.
    pub a: Anchor,
    /// Second point.
    pub b: Anchor,
}

impl Element for Distance {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let a = c.anchor(&self.name, "a", &self.a)?;
        let b = c.anchor(&self.name, "b", &self.b)?;
        c.measures.push(CompiledMeasure {
            name: self.name.clone(),
            columns: vec![
                (format!("{}.distance", self.name), "m"),
                (format!("{}.distance_rate", self.name), "m/s"),
            ],
            el: MeasureEl::Distance { a, b },
        });
        Ok(())
    }

    fn anchors(&self) -> Vec<&Anchor> {
        vec![&self.a, &self.b]
    }
}
