//! `[[metric]]`: one number from a column over a time window (peak, extreme, mean, RMS, final
//! value, or the time of an extreme), reported with the run's metrics and usable by sweeps and
//! finding maps like the built-in models' metrics. The description is data; the built-in models'
//! crate evaluates it (`clr_models::metric::evaluate`).

use serde::{Deserialize, Serialize};

use crate::error::MbdError;

/// What a metric takes of its column over its window.
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

/// A `[[metric]]` item.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MetricDesc {
    /// Unique metric name (snake_case by convention).
    pub name: String,
    /// The column it is taken of: any column of the run, a measure's or a deviation's.
    pub of: String,
    /// What it takes of the column.
    pub statistic: Statistic,
    /// Start of the window, s (default: the run's start; e.g. the end of a transient).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_start: Option<f64>,
    /// End of the window, s (default: the run's end).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_end: Option<f64>,
    /// What the metric means, in words, reported with its value (default: the statistic and
    /// the column, e.g. "largest |value| of `B.normal_force`").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
}

/// Check the metrics of a description against the columns its runs write (`columns`, with the
/// deviation columns): names unique and not blank, columns known, windows ordered.
pub(crate) fn check(metrics: &[MetricDesc], columns: &[String]) -> Result<(), MbdError> {
    for (k, m) in metrics.iter().enumerate() {
        let at = |field: &str, message: String| MbdError::Invalid {
            path: format!("metric[{k}].{field}"),
            message,
        };
        if m.name.trim().is_empty() {
            return Err(at("name", "give the metric a name".into()));
        }
        if metrics[..k].iter().any(|o| o.name == m.name) {
            return Err(at(
                "name",
                format!("a metric `{}` is defined already", m.name),
            ));
        }
        if !columns.contains(&m.of) {
            return Err(at(
                "of",
                format!(
                    "the run writes no column `{}`{}",
                    m.of,
                    similar(columns, &m.of)
                ),
            ));
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

/// `; did you mean …` with the columns that share the name's first part.
fn similar(columns: &[String], of: &str) -> String {
    let head = of.split('.').next().unwrap_or(of);
    let tail = of.rsplit('.').next().unwrap_or(of);
    let near: Vec<&str> = (columns.iter())
        .filter(|c| c.starts_with(&format!("{head}.")) || c.ends_with(&format!(".{tail}")))
        .map(String::as_str)
        .take(8)
        .collect();
    if near.is_empty() {
        String::new()
    } else {
        format!("; similar: {}", near.join(", "))
    }
}
