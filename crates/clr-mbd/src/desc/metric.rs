//! `[[metric]]`: one number from a column over a time window (peak, extreme, mean, RMS, final
//! value, or the time of an extreme), reported with the run's metrics and usable by sweeps and
//! finding maps like the built-in models' metrics. The description is data; the built-in models'
//! crate evaluates it (`clr_models::metric::evaluate`).

use serde::{Deserialize, Serialize};

use crate::error::MbdError;
pub use crate::measure::combination::Columns;
use crate::measure::runtime::near as similar;

/// What a metric takes of its column over its window.
///
/// With several columns (`of = [...]`) the columns are taken together: `peak`, `max`, `min`,
/// `drift`, `oscillation` and the `time_of_*` give the extreme over all of them, `mean` the
/// mean of their means, `rms` the root of the mean of their squared RMS values, `onsets` and
/// `integral` the sum over them; `spread` reads them as the coordinates of one point;
/// `final` and `change` take one column only. With `metrics = [...]` instead of `of`, the
/// statistic (`max`, `min`, `peak`, `sum`, `mean` or `rms`) is taken of those earlier metrics'
/// values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Statistic {
    /// Largest |v|; for `<C>.normal_force` and `<C>.penetration` of a contact element, the
    /// extrema clr-mbd located on the dense output between the rows count too.
    Peak,
    /// Largest v (located as `peak` for those two columns).
    Max,
    /// Smallest v.
    Min,
    /// Time mean (trapezoidal rule over the rows, uneven rows allowed).
    Mean,
    /// Time RMS (trapezoidal rule on v²).
    Rms,
    /// The value at the last row of the window.
    Final,
    /// The time of the largest |v|, s.
    TimeOfPeak,
    /// The time of the largest v, s.
    TimeOfMax,
    /// The time of the smallest v, s.
    TimeOfMin,
    /// v at the last row of the window − v at its first.
    Change,
    /// Largest |v − v(first row of the window)|: how far a conserved quantity wandered.
    Drift,
    /// ∫ v dt over the window (trapezoidal rule), in the column's unit times s.
    Integral,
    /// Number of contact onsets: rows where v reaches 0.5 after a row below it (a `<C>.contact`
    /// column recorded every step counts every closing of the contact).
    Onsets,
    /// Largest |v − running mean of v over `window` s| (centred window, trapezoidal mean; rows
    /// within window/2 of the run's ends skipped): the vibration about a slowly moving value.
    Oscillation,
    /// Stroboscopic (Poincaré-section) spread of the point whose coordinates are the columns:
    /// sampled (interpolated linearly) at t_start + (k + i/N)·`period` for every whole period k
    /// in the window and N = `phases` phases i, the RMS distance of each phase's samples from
    /// their mean, averaged over the phases. 0 for a response of that period; comparable with
    /// the size of the orbit when it wanders from period to period. NaN with fewer than two
    /// whole periods.
    Spread,
    /// Sum of the values (of `metrics`).
    Sum,
}

impl Statistic {
    /// In words, for the metric's description.
    pub fn words(self) -> &'static str {
        match self {
            Statistic::Peak => "largest |value|",
            Statistic::Max => "largest value",
            Statistic::Min => "smallest value",
            Statistic::Mean => "time mean",
            Statistic::Rms => "time RMS",
            Statistic::Final => "final value",
            Statistic::TimeOfPeak => "time of the largest |value|",
            Statistic::TimeOfMax => "time of the largest value",
            Statistic::TimeOfMin => "time of the smallest value",
            Statistic::Change => "final − initial value",
            Statistic::Drift => "largest |value − initial value|",
            Statistic::Integral => "time integral",
            Statistic::Onsets => "number of onsets",
            Statistic::Oscillation => "largest |value − running mean|",
            Statistic::Spread => "stroboscopic spread",
            Statistic::Sum => "sum",
        }
    }

    /// True for the statistics that give a time (unit s) rather than a value of the column.
    pub fn is_time(self) -> bool {
        matches!(
            self,
            Statistic::TimeOfPeak | Statistic::TimeOfMax | Statistic::TimeOfMin
        )
    }
}

/// What a metric is divided by: a number (in the metric's unit over the unit it ends in) or an
/// earlier metric's name.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Divisor {
    /// A constant (a clearance, a load).
    Number(f64),
    /// An earlier metric's value.
    Metric(String),
}

/// A `[[metric]]` item.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MetricDesc {
    /// Unique metric name (snake_case by convention).
    pub name: String,
    /// The column it is taken of (any column of the run, a measure's or a deviation's), or
    /// several taken together ([`Statistic`]); absent when `metrics` is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub of: Option<Columns>,
    /// Earlier metrics combined instead of columns (with `max`, `min`, `peak`, `sum`, `mean`
    /// or `rms`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub metrics: Vec<String>,
    /// What it takes of the column.
    pub statistic: Statistic,
    /// Start of the window, s (default: the run's start; e.g. the end of a transient).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_start: Option<f64>,
    /// End of the window, s (default: the run's end).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_end: Option<f64>,
    /// The running-mean window of `oscillation`, s (a period of the slowest vibration kept).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window: Option<f64>,
    /// The sampling period of `spread`, s (the period of the forcing).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
    /// The phases per period of `spread` (default 8).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phases: Option<usize>,
    /// Divide the value by a number or an earlier metric (0/0 gives 0: nothing happened).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub per: Option<Divisor>,
    /// Take the column of the ideal-joint twin's run (recorded at its `[twin]` intervals)
    /// instead of the model's (default false): the ideal mechanism's amplitude, say.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub twin: bool,
    /// The metric's unit (one of [`crate::results::UNITS`]; default: the column's, `s` for the
    /// `time_of_*`, `-` for `onsets` and `spread`, the column's times s for `integral`, `-` for
    /// a metric `per` another of the same unit).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit: Option<String>,
    /// What the metric means, in words, reported with its value (default: the statistic and
    /// the column, e.g. "largest |value| of `B.normal_force`").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
}

impl MetricDesc {
    /// `statistic` of column `of` over the whole run, every option at its default.
    pub fn new(name: &str, of: &str, statistic: Statistic) -> Self {
        Self::of_columns(name, &[of], statistic)
    }

    /// `statistic` of the columns `of` taken together ([`Statistic`]).
    pub fn of_columns(name: &str, of: &[&str], statistic: Statistic) -> Self {
        let of = match of {
            [one] => Columns::One(one.to_string()),
            many => Columns::Many(many.iter().map(|c| c.to_string()).collect()),
        };
        MetricDesc {
            name: name.into(),
            of: Some(of),
            metrics: Vec::new(),
            statistic,
            t_start: None,
            t_end: None,
            window: None,
            period: None,
            phases: None,
            per: None,
            twin: false,
            unit: None,
            description: None,
        }
    }

    /// `statistic` of the earlier metrics `metrics`.
    pub fn of_metrics(name: &str, metrics: &[&str], statistic: Statistic) -> Self {
        MetricDesc {
            of: None,
            metrics: metrics.iter().map(|m| m.to_string()).collect(),
            ..Self::new(name, "", statistic)
        }
    }

    /// The same over t ≥ `t_start` s.
    pub fn after(self, t_start: f64) -> Self {
        MetricDesc {
            t_start: Some(t_start),
            ..self
        }
    }

    /// The same with its description.
    pub fn described(self, words: &str) -> Self {
        MetricDesc {
            description: Some(words.into()),
            ..self
        }
    }

    /// The same divided by `per`.
    pub fn per(self, per: Divisor) -> Self {
        MetricDesc {
            per: Some(per),
            ..self
        }
    }

    /// The same in `unit`.
    pub fn in_unit(self, unit: &str) -> Self {
        MetricDesc {
            unit: Some(unit.into()),
            ..self
        }
    }

    /// The columns it is taken of (none for a metric of metrics).
    pub fn columns(&self) -> &[String] {
        self.of.as_ref().map_or(&[], Columns::names)
    }
}

/// Check the metrics of a description against the columns its runs write (`columns`, with the
/// deviation columns) and those of its ideal twin (`twin`): names unique and not blank, columns
/// known, windows ordered, each statistic's options given and used, units known, metrics
/// referred to defined before.
pub(crate) fn check(
    metrics: &[MetricDesc],
    columns: &[String],
    twin: &[String],
) -> Result<(), MbdError> {
    for (k, m) in metrics.iter().enumerate() {
        let at = |field: &str, message: String| MbdError::Invalid {
            path: format!("metric[{k}].{field}"),
            message,
        };
        if m.name.trim().is_empty() {
            return Err(at("name", "give the metric a name".into()));
        }
        let earlier = |name: &str| metrics[..k].iter().any(|o| o.name == name);
        if earlier(&m.name) {
            return Err(at(
                "name",
                format!("a metric `{}` is defined already", m.name),
            ));
        }
        check_sources(m, columns, twin, &earlier).map_err(|(f, msg)| at(f, msg))?;
        check_options(m).map_err(|(f, msg)| at(f, msg))?;
        if let Some(Divisor::Metric(d)) = &m.per {
            if !earlier(d) {
                return Err(at(
                    "per",
                    format!("no metric `{d}` is defined before this one: list it first"),
                ));
            }
        }
        if let Some(u) = &m.unit {
            if crate::results::known_unit(u).is_none() {
                return Err(at(
                    "unit",
                    format!(
                        "`{u}` is not a unit clr knows; one of {}",
                        crate::results::UNITS.join(", ")
                    ),
                ));
            }
        }
        let (from, to) = (
            m.t_start.unwrap_or(f64::NEG_INFINITY),
            m.t_end.unwrap_or(f64::INFINITY),
        );
        if from.is_nan() || to.is_nan() || from >= to {
            return Err(at(
                "t_start",
                format!("the window [{from}, {to}] s is empty: `t_start` must be before `t_end`"),
            ));
        }
    }
    Ok(())
}

type Refusal = (&'static str, String);

/// `of` or `metrics`, one of them, naming what exists.
fn check_sources(
    m: &MetricDesc,
    columns: &[String],
    twin: &[String],
    earlier: &dyn Fn(&str) -> bool,
) -> Result<(), Refusal> {
    let combining = matches!(
        m.statistic,
        Statistic::Max
            | Statistic::Min
            | Statistic::Peak
            | Statistic::Sum
            | Statistic::Mean
            | Statistic::Rms
    );
    match (&m.of, m.metrics.is_empty()) {
        (Some(_), false) | (None, true) => Err((
            "of",
            "give either `of` (columns) or `metrics` (earlier metrics), not both or neither".into(),
        )),
        (None, false) => {
            if !combining || m.twin {
                return Err((
                    "statistic",
                    format!(
                        "`{:?}` cannot combine metrics: use max, min, peak, sum, mean or rms{}",
                        m.statistic,
                        if m.twin { ", without `twin`" } else { "" }
                    ),
                ));
            }
            match m.metrics.iter().find(|n| !earlier(n)) {
                Some(n) => Err((
                    "metrics",
                    format!("no metric `{n}` is defined before this one: list it first"),
                )),
                None => Ok(()),
            }
        }
        (Some(of), true) => {
            let names = of.names();
            if names.is_empty() {
                return Err(("of", "name at least one column".into()));
            }
            if m.statistic == Statistic::Sum {
                return Err((
                    "statistic",
                    "`sum` combines metrics: for a sum of columns use `integral`, `onsets` or a                      `combination` measure"
                        .into(),
                ));
            }
            let known = if m.twin { twin } else { columns };
            if let Some(c) = names.iter().find(|c| !known.contains(c)) {
                let whose = if m.twin {
                    "the ideal twin writes"
                } else {
                    "the run writes"
                };
                return Err((
                    "of",
                    format!("{whose} no column `{c}`{}", similar(known, c)),
                ));
            }
            let single = matches!(m.statistic, Statistic::Final | Statistic::Change);
            if single && names.len() > 1 {
                return Err(("of", format!("`{:?}` takes one column", m.statistic)));
            }
            Ok(())
        }
    }
}

/// The statistic's own options: given where it needs them, refused where unused.
fn check_options(m: &MetricDesc) -> Result<(), Refusal> {
    let positive = |x: Option<f64>| x.is_some_and(|x| x.is_finite() && x > 0.0);
    match (m.statistic, m.window) {
        (Statistic::Oscillation, w) if !positive(w) => {
            return Err((
                "window",
                "`oscillation` needs `window`, the running-mean window in s (> 0)".into(),
            ))
        }
        (s, Some(_)) if s != Statistic::Oscillation => {
            return Err(("window", "only `oscillation` uses `window`".into()))
        }
        _ => {}
    }
    if m.statistic == Statistic::Spread {
        if !positive(m.period) {
            return Err((
                "period",
                "`spread` needs `period`, the sampling period in s (> 0)".into(),
            ));
        }
        if m.phases == Some(0) {
            return Err(("phases", "give at least one phase per period".into()));
        }
    } else if m.period.is_some() || m.phases.is_some() {
        return Err(("period", "only `spread` uses `period` and `phases`".into()));
    }
    if let Some(Divisor::Number(x)) = m.per {
        if !x.is_finite() {
            return Err(("per", format!("{x}: divide by a finite number")));
        }
    }
    Ok(())
}
