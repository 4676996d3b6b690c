//! The ideal-joint twin of a description and the `deviation` columns it gives
//! ([`crate::measure::deviation`] defines the measure and the interpolation): the twin
//! description, the check of the deviation sources before a run, and the columns appended
//! after it. It lives with the description because it builds one.

use crate::element::Clearance;
use crate::error::MbdError;
use crate::measure::deviation::{interp, Deviation};
use crate::measure::Measure;
use crate::results::{unit_of, Results};

use super::ModelDesc;

impl ModelDesc {
    /// The `deviation` measures of this description.
    pub fn deviations(&self) -> Vec<&Deviation> {
        (self.measures.iter())
            .filter_map(|m| match m {
                Measure::Deviation(d) => Some(d),
                _ => None,
            })
            .collect()
    }

    /// The ideal-joint twin of this description (module docs), with what it left as it was, in
    /// words: every revolute and translational clearance joint at clearance 0 (film, wear and
    /// initial offset dropped), the deviation and contact measures, the combinations of
    /// columns it lacks (a clearance joint's) and the metrics left out, recorded at the
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
        let mut keeps = self.twin_keeps().into_iter();
        twin.measures.retain(|_| keeps.next().unwrap_or(false));
        let o = &mut twin.output;
        let intervals = self.twin.as_ref().and_then(|t| t.intervals);
        o.intervals = intervals.unwrap_or(if o.intervals == 0 { 1000 } else { o.intervals });
        o.every_step = false;
        (twin, notes)
    }
}

impl ModelDesc {
    /// Per measure, whether the ideal twin keeps it: not the deviations, not the contact
    /// measures, and not a combination that reads a column the twin does not write (of a
    /// clearance joint it makes ideal, or of a measure it leaves out before), such as the moment
    /// δ·F_T of a joint's friction pair.
    fn twin_keeps(&self) -> Vec<bool> {
        let made_ideal: Vec<&str> = (self.clearances.iter())
            .filter(|c| matches!(c, Clearance::Revolute(_) | Clearance::Translational(_)))
            .filter(|c| !c.is_ideal())
            .map(|c| c.name())
            .collect();
        let mut left_out: Vec<String> = Vec::new();
        let mut keeps = Vec::with_capacity(self.measures.len());
        for m in &self.measures {
            let keep = match m {
                Measure::Deviation(d) => {
                    left_out.push(d.column());
                    false
                }
                Measure::Contact(c) => {
                    left_out.push(format!("{}.{}", c.name, c.quantity));
                    false
                }
                Measure::Combination(c) => {
                    let missing = |col: &String| {
                        left_out.contains(col)
                            || (made_ideal.iter())
                                .any(|j| col.strip_prefix(j).is_some_and(|r| r.starts_with('.')))
                    };
                    let keep = !(c.terms.iter()).any(|t| t.of.names().iter().any(missing));
                    if !keep {
                        left_out.push(format!("{}.value", c.name));
                    }
                    keep
                }
                _ => true,
            };
            keeps.push(keep);
        }
        keeps
    }

    /// True when a run of this description needs its ideal twin: a `deviation` measure or a
    /// `[[metric]]` with `twin = true`.
    pub fn needs_twin(&self) -> bool {
        !self.deviations().is_empty() || self.metrics.iter().any(|m| m.twin)
    }
}

/// The columns of `columns` (a run's, with its deviation columns) that the ideal twin writes
/// too: all but the deviations', the contact measures' and those of the clearance elements it
/// makes ideal.
pub(crate) fn twin_columns(desc: &ModelDesc, columns: &[String]) -> Vec<String> {
    // the exact columns of the measures the twin leaves out (not every column starting with
    // their names: a deviation may be named like a body, `slider`)
    let left_out: Vec<String> = (desc.measures.iter())
        .zip(desc.twin_keeps())
        .filter(|(_, keep)| !keep)
        .filter_map(|(m, _)| match m {
            Measure::Deviation(d) => Some(d.column()),
            Measure::Contact(c) => Some(format!("{}.{}", c.name, c.quantity)),
            Measure::Combination(c) => Some(format!("{}.value", c.name)),
            _ => None,
        })
        .collect();
    let ideal: Vec<String> = (desc.clearances.iter())
        .filter(|c| matches!(c, Clearance::Revolute(_) | Clearance::Translational(_)))
        .filter(|c| !c.is_ideal())
        .map(|c| format!("{}.", c.name()))
        .collect();
    (columns.iter())
        .filter(|c| !left_out.contains(c) && !ideal.iter().any(|p| c.starts_with(p)))
        .cloned()
        .collect()
}

/// Refuse, before any run, a deviation of a column the run does not write or the twin cannot
/// (a contact quantity, or a column of a deviation).
pub(crate) fn check_sources(desc: &ModelDesc, columns: &[String]) -> Result<(), MbdError> {
    let contact: Vec<String> = (desc.measures.iter())
        .filter_map(|m| match m {
            Measure::Contact(c) => Some(format!("{}.{}", c.name, c.quantity)),
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

/// Run the ideal twin of `desc` over the span of `options` (at its `[twin]` intervals) when
/// the description needs it ([`ModelDesc::needs_twin`]), append the deviation columns to
/// `results`, saying in their notes what the twin was, and return the twin's results (for the
/// metrics with `twin = true`). A twin that fails leaves the columns NaN, says why in the notes
/// (the run itself stands) and returns `None`.
///
/// # Errors
/// A twin that cannot be built (an error of the description itself), or a deviation of a column
/// that neither the run nor the twin writes.
pub fn run_twin(
    desc: &ModelDesc,
    options: &crate::SimOptions,
    results: &mut Results,
) -> Result<Option<Results>, MbdError> {
    if !desc.needs_twin() {
        return Ok(None);
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
    let (columns, twin) = match twin_model.simulate(&o) {
        Ok(twin) => {
            results.notes.push(format!(
                "ideal twin (every revolute and translational clearance joint at clearance 0): \
                 ran over the same span, recorded at {k} equal intervals, interpolated linearly \
                 for the deviation measures ({} steps)",
                twin.stats.accepted
            ));
            (deviation_columns(desc, results, &twin)?, Some(twin))
        }
        Err(e) => {
            results.notes.push(format!(
                "ideal twin failed ({e}): the deviation columns are NaN, the twin's metrics too"
            ));
            let columns = (desc.deviations().iter())
                .map(|d| (d.column(), unit_of(&d.of[0]), vec![f64::NAN; n]))
                .collect();
            (columns, None)
        }
    };
    for (c, u, _) in &columns {
        results.units.push((c.clone(), u));
    }
    results.append_columns(columns.into_iter().map(|(c, _, v)| (c, v)).collect());
    Ok(twin)
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
        out.push((d.column(), unit_of(&d.of[0]), values));
    }
    Ok(out)
}
