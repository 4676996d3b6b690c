//! `momentum`: linear momentum p = Σ m_k ṙ_k and angular momentum about a world point O,
//! L = Σ (I_k ω_k + m_k (r_k − r_O) × ṙ_k), of rigid bodies (r_k, ṙ_k of the centres of mass;
//! Greenwood, *Principles of Dynamics*, 1988, §4.1). Flexible bodies and beams carry momentum in
//! their elastic coordinates, which this measure does not add: a model with them must list the
//! rigid bodies it means.
//!
//! With `scales = true` it also writes the magnitudes the momenta are made of, Σ m_k |ṙ_k|
//! (`<name>.p_scale`, kg·m/s) and Σ (|I_k ω_k| + m_k |(r_k − r_O) × ṙ_k|) (`<name>.L_scale`,
//! kg·m²/s): the sizes a drift of p and L is judged against (a `[[metric]]` with `per`), since
//! p and L themselves may be zero (a free-floating system starting at rest).

use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

use super::runtime::{CompiledMeasure, MeasureEl};
use crate::element::{Compiler, Element};
use crate::error::MbdError;
use crate::runtime::GROUND_ID;

/// Momentum of rigid bodies: `<name>.px`, `<name>.py` (kg·m/s) and `<name>.L` (kg·m²/s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Momentum {
    /// Unique measure name.
    pub name: String,
    /// The rigid bodies (default: every rigid body of a model without flexible parts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bodies: Option<Vec<String>>,
    /// The world point O the angular momentum is taken about, m (default the origin).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub about: Option<[f64; 2]>,
    /// Also write `<name>.p_scale` and `<name>.L_scale` (module docs; default false).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub scales: bool,
}

impl Element for Momentum {
    fn compile(&self, c: &mut Compiler) -> Result<(), MbdError> {
        let about = self.about.unwrap_or([0.0, 0.0]);
        if !(about[0].is_finite() && about[1].is_finite()) {
            return Err(MbdError::Invalid {
                path: format!("{}.about", self.name),
                message: format!(
                    "[{}, {}] m: both coordinates must be finite",
                    about[0], about[1]
                ),
            });
        }
        let ids = match &self.bodies {
            Some(names) => names
                .iter()
                .map(|b| c.body(&self.name, "bodies", b))
                .collect::<Result<Vec<_>, _>>()?,
            None if !(c.beams.is_empty() && c.floating.is_empty()) => {
                return Err(MbdError::Invalid {
                    path: format!("{}.bodies", self.name),
                    message: "the model has flexible parts, whose elastic coordinates carry \
                              momentum this measure does not add: list the rigid bodies \
                              (`bodies = [...]`)"
                        .into(),
                })
            }
            None => (0..c.bodies.len()).collect(),
        };
        if let Some(k) = ids.iter().position(|&i| i == GROUND_ID) {
            return Err(MbdError::Invalid {
                path: format!("{}.bodies", self.name),
                message: format!("entry {k} is the ground, which has no momentum: leave it out"),
            });
        }
        let bodies = ids
            .into_iter()
            .map(|k| (k, c.bodies[k].1.mass, c.bodies[k].1.inertia))
            .collect();
        let quantities = if self.scales { 5 } else { 3 };
        c.measures.push(CompiledMeasure {
            name: self.name.clone(),
            columns: ["px", "py", "L", "p_scale", "L_scale"]
                .iter()
                .zip(["kg*m/s", "kg*m/s", "kg*m^2/s", "kg*m/s", "kg*m^2/s"])
                .take(quantities)
                .map(|(s, u)| (format!("{}.{s}", self.name), u))
                .collect(),
            el: MeasureEl::Momentum {
                bodies,
                about: Vector2::new(about[0], about[1]),
                scales: self.scales,
            },
        });
        Ok(())
    }
}
