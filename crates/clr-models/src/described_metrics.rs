//! The `[[metric]]` items of a description (`clr_mbd::desc::metric`), evaluated on a run's
//! results with the same helpers the built-in models use for theirs.

use clr_mbd::desc::metric::{MetricDesc, Statistic};
use clr_mbd::Results;

use crate::common::{located_extreme, time_mean, time_rms};
use crate::Metric;

/// The metrics `descs` of `res`, in order. A window with no row gives NaN (a failed run's
/// partial rows may end before it).
pub fn evaluate(descs: &[MetricDesc], res: &Results) -> Vec<Metric> {
    descs.iter().map(|d| one(d, res)).collect()
}

fn one(d: &MetricDesc, res: &Results) -> Metric {
    let t = res.column("t").unwrap_or_default();
    let v = res.column(&d.of).unwrap_or_else(|| vec![f64::NAN; t.len()]);
    let (from, to) = (
        d.t_start.unwrap_or(f64::NEG_INFINITY),
        d.t_end.unwrap_or(f64::INFINITY),
    );
    let rows: Vec<usize> = (0..t.len())
        .filter(|&k| t[k] >= from && t[k] <= to)
        .collect();
    let (tw, vw): (Vec<f64>, Vec<f64>) = rows.iter().map(|&k| (t[k], v[k])).unzip();
    let value = if rows.is_empty() {
        f64::NAN
    } else {
        statistic(d, res, &tw, &vw)
    };
    let unit = if d.statistic.is_time() {
        "s"
    } else {
        res.unit(&d.of)
    };
    let window = match (d.t_start, d.t_end) {
        (None, None) => crate::output::WHOLE_RUN.to_string(),
        (Some(a), None) => format!("t ≥ {a} s"),
        (None, Some(b)) => format!("t ≤ {b} s"),
        (Some(a), Some(b)) => format!("{a} s ≤ t ≤ {b} s"),
    };
    let words = d.description.clone().unwrap_or_else(|| {
        format!(
            "{} of `{}` ([[metric]] of the model)",
            d.statistic.words(),
            d.of
        )
    });
    Metric::new(&d.name, value, unit, &words).over(&window)
}

/// The statistic of the window's rows (t, v), not empty.
fn statistic(d: &MetricDesc, res: &Results, t: &[f64], v: &[f64]) -> f64 {
    let arg = |better: &dyn Fn(f64, f64) -> bool| {
        (0..v.len()).fold(0, |b, k| if better(v[k], v[b]) { k } else { b })
    };
    let (peak, max, min) = (
        arg(&|a, b| a.abs() > b.abs()),
        arg(&|a, b| a > b),
        arg(&|a, b| a < b),
    );
    match d.statistic {
        Statistic::Peak | Statistic::Max => {
            let rows = if d.statistic == Statistic::Peak {
                v[peak].abs()
            } else {
                v[max]
            };
            located(d, res, t, rows)
        }
        Statistic::Min => v[min],
        Statistic::Mean => time_mean(t, v, t[0]),
        Statistic::Rms => time_rms(t, v, t[0]),
        Statistic::Final => v[v.len() - 1],
        Statistic::TimeOfPeak => t[peak],
        Statistic::TimeOfMax => t[max],
        Statistic::TimeOfMin => t[min],
    }
}

/// The row extreme `rows` raised to the located extrema of a contact element's impacts inside
/// the window, for `<C>.normal_force` and `<C>.penetration` (both ≥ 0, so peak and max agree).
fn located(d: &MetricDesc, res: &Results, t: &[f64], rows: f64) -> f64 {
    match d.of.rsplit_once('.') {
        Some((joint, quantity)) => {
            located_extreme(res, joint, quantity, (t[0], t[t.len() - 1]), rows)
        }
        None => rows,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn res(t: &[f64], v: &[f64]) -> Results {
        Results {
            columns: vec!["t".into(), "a.x".into()],
            data: t.iter().zip(v).flat_map(|(a, b)| [*a, *b]).collect(),
            ..Default::default()
        }
    }

    fn metric(stat: Statistic, from: Option<f64>, r: &Results) -> f64 {
        let d = MetricDesc {
            name: "m".into(),
            of: "a.x".into(),
            statistic: stat,
            t_start: from,
            t_end: None,
            description: None,
        };
        evaluate(&[d], r)[0].value
    }

    #[test]
    fn statistics_of_a_sampled_sine_equal_their_closed_forms() {
        // v = sin(2πt) on [0, 1] at 10 001 rows: mean 0, RMS 1/√2 (trapezoid rule on a whole
        // period is exact for trigonometric polynomials up to rounding), extremes ±1 at t = 1/4,
        // 3/4 (on the grid), final sin 2π = 0
        let t: Vec<f64> = (0..=10_000).map(|k| k as f64 / 10_000.0).collect();
        let v: Vec<f64> = t
            .iter()
            .map(|t| (2.0 * std::f64::consts::PI * t).sin())
            .collect();
        let r = res(&t, &v);
        assert!(metric(Statistic::Mean, None, &r).abs() < 1e-15);
        assert!((metric(Statistic::Rms, None, &r) - 0.5f64.sqrt()).abs() < 1e-15);
        assert!((metric(Statistic::Max, None, &r) - 1.0).abs() < 1e-15);
        assert!((metric(Statistic::Min, None, &r) + 1.0).abs() < 1e-15);
        assert!((metric(Statistic::TimeOfMax, None, &r) - 0.25).abs() < 1e-15);
        assert!((metric(Statistic::TimeOfMin, None, &r) - 0.75).abs() < 1e-15);
        assert!((metric(Statistic::Peak, None, &r) - 1.0).abs() < 1e-15);
        assert!(metric(Statistic::Final, None, &r).abs() < 1e-12);
        // after t = 0.5 only the negative half: mean −2/π, trapezoid error h²/12·mean|v''| =
        // 1e-8/12·(2π)²·2/π = 2.1e-8 (measured 2.1e-8)
        let m = metric(Statistic::Mean, Some(0.5), &r);
        assert!((m + 2.0 / std::f64::consts::PI).abs() < 3e-8, "{m}");
        // a window after the last row has no value
        assert!(metric(Statistic::Max, Some(2.0), &r).is_nan());
    }
}
