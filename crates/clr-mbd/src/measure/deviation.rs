//! `deviation`: how far a quantity of the run is from the same quantity of the **ideal-joint
//! twin**, the same model with every revolute and translational clearance joint made ideal
//! (clearance 0: the journal on the bearing centre, the slider on the guide's centre line), run
//! alongside over the same time span (Flores et al., *Kinematics and Dynamics of Multibody
//! Systems with Imperfect Joints*, Springer 2008, compare every clearance run with this
//! reference; so do the built-in models).
//!
//! The twin records at `[twin] intervals` equal intervals (default: the run's `intervals`, 1000
//! when the run records every step only) and is interpolated linearly at the run's times. One
//! source column gives the signed difference `<name>.error` = x − x_ideal; several give the
//! distance √Σ(x_k − x_k,ideal)² (an end-effector's path error from its `.x` and `.y`). The
//! error has the unit of the sources, which must agree.
//!
//! What the twin leaves as it is, and says so in the run's notes: sliders on flexible guides and
//! shape contacts (they have no ideal counterpart). It leaves out the `contact` measures (an
//! ideal joint has no contact columns; a deviation of one is refused) and the `combination`
//! measures that read a column it does not write (a clearance joint's, or a left-out measure's).

use serde::{Deserialize, Serialize};

use crate::element::{Compiler, Element};
use crate::error::MbdError;
use crate::results::unit_of;

/// Deviation of columns from the ideal-joint twin: column `<name>.error` (or `<name>.<suffix>`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Deviation {
    /// Unique measure name.
    pub name: String,
    /// The columns compared: a column of the run or of an earlier measure (`slider.x`,
    /// `ee1.x`); one gives a signed difference, several a distance.
    pub of: Vec<String>,
    /// The column's suffix (default `error`): `<name>.<suffix>`, so that one name can carry the
    /// deviations of several quantities (`flap.error`, `flap.alpha_error`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub suffix: Option<String>,
}

impl Deviation {
    /// The column it writes, `<name>.<suffix>`.
    pub fn column(&self) -> String {
        format!(
            "{}.{}",
            self.name,
            self.suffix.as_deref().unwrap_or("error")
        )
    }
}

impl Element for Deviation {
    /// Nothing to evaluate per row: the columns are written after the twin has run
    /// ([`deviation_columns`]).
    fn compile(&self, _c: &mut Compiler) -> Result<(), MbdError> {
        if let Some(s) = &self.suffix {
            if s.is_empty() || s.contains(|c: char| c == '.' || c.is_whitespace()) {
                return Err(MbdError::Invalid {
                    path: format!("{}.suffix", self.name),
                    message: format!(
                        "`{s}`: the suffix ends the column name `<name>.<suffix>`; give one \
                         word without dots or spaces"
                    ),
                });
            }
        }
        if self.of.is_empty() {
            return Err(MbdError::Invalid {
                path: format!("{}.of", self.name),
                message: "name at least one column to compare with the ideal twin".into(),
            });
        }
        let units: Vec<&str> = self.of.iter().map(|c| unit_of(c)).collect();
        if units.iter().any(|u| *u != units[0]) {
            return Err(MbdError::Invalid {
                path: format!("{}.of", self.name),
                message: format!(
                    "the columns {} have the units {}: a distance needs one unit",
                    self.of.join(", "),
                    units.join(", ")
                ),
            });
        }
        Ok(())
    }
}

/// `[twin]`: how the ideal-joint twin of the deviation measures records.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwinSettings {
    /// Equal output intervals of the twin over the run's time span (default: the run's
    /// `intervals`, or 1000 when it records every step only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intervals: Option<usize>,
}

/// Linear interpolation of the samples (t, v) at `at`, held constant outside them (NaN without
/// samples).
pub fn interp(t: &[f64], v: &[f64], at: f64) -> f64 {
    if t.is_empty() {
        return f64::NAN;
    }
    if at <= t[0] {
        return v[0];
    }
    if at >= t[t.len() - 1] {
        return v[v.len() - 1];
    }
    let k = t.partition_point(|&x| x <= at);
    let (t0, t1) = (t[k - 1], t[k]);
    if t1 == t0 {
        return v[k];
    }
    v[k - 1] + (v[k] - v[k - 1]) * (at - t0) / (t1 - t0)
}
