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
//! shape contacts (they have no ideal counterpart), and the `contact` measures (an ideal joint
//! has no contact columns; a deviation of one is refused).

use serde::{Deserialize, Serialize};

use crate::desc::ModelDesc;
use crate::element::{Clearance, Compiler, Element};
use crate::error::MbdError;
use crate::results::{unit_of, Results};

/// Deviation of columns from the ideal-joint twin: column `<name>.error`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Deviation {
    /// Unique measure name.
    pub name: String,
    /// The columns compared: a column of the run or of an earlier measure (`slider.x`,
    /// `ee1.x`); one gives a signed difference, several a distance.
    pub of: Vec<String>,
}

impl Element for Deviation {
    /// Nothing to evaluate per row: the columns are written after the twin has run
    /// ([`deviation_columns`]).
    fn compile(&self, _c: &mut Compiler) -> Result<(), MbdError> {
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

impl ModelDesc {
    /// The `deviation` measures of this description.
    pub fn deviations(&self) -> Vec<&Deviation> {
        (self.measures.iter())
            .filter_map(|m| match m {
                super::Measure::Deviation(d) => Some(d),
                _ => None,
            })
            .collect()
    }

    /// The ideal-joint twin of this description (module docs), with what it left as it was, in
    /// words: every revolute and translational clearance joint at clearance 0 (film, wear and
    /// initial offset dropped), the deviation and contact measures and the metrics left out,
    /// recorded at the
    /// `[twin]` intervals.
    pub fn ideal_twin(&self) -> (ModelDesc, Vec<String>) {
        let mut twin = self.clone();
        let mut notes = Vec::new();
        for c in &mut twin.clearances {
            match c {
                Clearance::Revolute(r) => {
                    r.journal_radius = r.bearing_radius;
                    (r.lubrication, r.bearing_wear, r.initial_eccentricity) = (None, None, None);
                }
                Clearance::Translational(t) => {
                    t.slider_height = t.guide_width;
                    t.initial_offset = None;
                }
                other => notes.push(format!(
                    "the ideal twin keeps `{}` ({}): it has no ideal counterpart",
                    other.name(),
                    other.kind()
                )),
            }
        }
        // the twin's metrics are not asked for (they would name the deviation columns)
        twin.metrics.clear();
        twin.measures
            .retain(|m| !matches!(m, super::Measure::Deviation(_) | super::Measure::Contact(_)));
        let o = &mut twin.output;
        let intervals = self.twin.as_ref().and_then(|t| t.intervals);
        o.intervals = intervals.unwrap_or(if o.intervals == 0 { 1000 } else { o.intervals });
        o.every_step = false;
        (twin, notes)
    }
}

/// Refuse, before any run, a deviation of a column the run does not write or the twin cannot
/// (a contact quantity, or a column of a deviation).
pub(crate) fn check_sources(desc: &ModelDesc, columns: &[String]) -> Result<(), MbdError> {
    let contact: Vec<String> = (desc.measures.iter())
        .filter_map(|m| match m {
            super::Measure::Contact(c) => Some(format!("{}.{}", c.name, c.quantity)),
            _ => None,
        })
        .collect();
    for d in desc.deviations() {
        for c in &d.of {
            let clearance = (desc.clearances.iter()).any(|cl| {
                !cl.is_ideal()
                    && c.strip_prefix(cl.name())
                        .is_some_and(|r| r.starts_with('.'))
            });
            let why = if !columns.contains(c) {
                "the run writes no such column"
            } else if clearance || contact.contains(c) {
                "a contact quantity, which the ideal twin (no clearance) does not have; compare \
                 the motion it causes instead"
            } else {
                continue;
            };
            return Err(MbdError::Invalid {
                path: format!("{}.of", d.name),
                message: format!("`{c}`: {why}"),
            });
        }
    }
    Ok(())
}

/// Run the ideal twin of `desc` over the span of `options` (at its `[twin]` intervals) and
/// append the deviation columns to `results`, saying in their notes what the twin was. A twin
/// that fails leaves the columns NaN and says why in the notes (the run itself stands).
///
/// # Errors
/// A twin that cannot be built (an error of the description itself), or a deviation of a column
/// that neither the run nor the twin writes.
pub fn append_deviations(
    desc: &ModelDesc,
    options: &crate::SimOptions,
    results: &mut Results,
) -> Result<(), MbdError> {
    if desc.deviations().is_empty() {
        return Ok(());
    }
    let (twin_desc, notes) = desc.ideal_twin();
    let mut twin_model = twin_desc.compile()?;
    let mut o = options.clone();
    let k = twin_desc.output.intervals;
    o.times = (0..=k)
        .map(|i| o.t0 + (o.t_end - o.t0) * i as f64 / k as f64)
        .collect();
    o.every_step = false;
    results.notes.extend(notes);
    let n = results.len();
    let columns = match twin_model.simulate(&o) {
        Ok(twin) => {
            results.notes.push(format!(
                "deviation measures: the ideal twin (every revolute and translational clearance \
                 joint at clearance 0) ran over the same span, recorded at {k} equal intervals \
                 and interpolated linearly ({} steps)",
                twin.stats.accepted
            ));
            deviation_columns(desc, results, &twin)?
        }
        Err(e) => {
            results.notes.push(format!(
                "deviation measures: the ideal twin failed ({e}); their columns are NaN"
            ));
            (desc.deviations().iter())
                .map(|d| {
                    (
                        format!("{}.error", d.name),
                        unit_of(&d.of[0]),
                        vec![f64::NAN; n],
                    )
                })
                .collect()
        }
    };
    for (c, u, _) in &columns {
        results.units.push((c.clone(), u));
    }
    results.append_columns(columns.into_iter().map(|(c, _, v)| (c, v)).collect());
    Ok(())
}

/// One deviation column: its name, unit and values.
pub type DeviationColumn = (String, &'static str, Vec<f64>);

/// The `<name>.error` columns of the deviation measures of `desc` (name, unit, values at the
/// rows of `run`) from the run and its ideal twin's results (the twin interpolated linearly at
/// the run's times).
///
/// # Errors
/// [`MbdError::Invalid`] at `<name>.of` for a column that the run or the twin does not write.
pub fn deviation_columns(
    desc: &ModelDesc,
    run: &Results,
    twin: &Results,
) -> Result<Vec<DeviationColumn>, MbdError> {
    let t = run.column("t").unwrap_or_default();
    let tw = twin.column("t").unwrap_or_default();
    let mut out = Vec::new();
    for d in desc.deviations() {
        let mut sq = vec![0.0; t.len()];
        let mut signed = vec![0.0; t.len()];
        for c in &d.of {
            let missing = |who: &str| MbdError::Invalid {
                path: format!("{}.of", d.name),
                message: format!(
                    "the {who} writes no column `{c}` (a contact quantity has none in the ideal \
                     twin; compare the motion it causes instead)"
                ),
            };
            let x = run.column(c).ok_or_else(|| missing("run"))?;
            let xi = twin.column(c).ok_or_else(|| missing("ideal twin"))?;
            for (k, &tk) in t.iter().enumerate() {
                let e = x[k] - interp(&tw, &xi, tk);
                signed[k] = e;
                sq[k] += e * e;
            }
        }
        let values = if d.of.len() == 1 {
            signed
        } else {
            sq.into_iter().map(f64::sqrt).collect()
        };
        out.push((format!("{}.error", d.name), unit_of(&d.of[0]), values));
    }
    Ok(out)
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
