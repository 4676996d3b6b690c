//! The `[[metric]]` items of a description (`clr_mbd::desc::metric`), evaluated on a run's
//! results with the same helpers the built-in models use for theirs.

use clr_mbd::desc::metric::{Divisor, MetricDesc, Statistic};
use clr_mbd::Results;

use clr_mbd::ModelDesc;

use crate::common::{self, interp, located_extreme, time_mean};
use crate::Metric;
use crate::{ModelsError, RunSettings};

/// Run a built-in's description as a run of its exported file does: compile, simulate, run the
/// ideal twin when the description asks for it (`deviation` measures, metrics of the twin),
/// then evaluate its `[[metric]]` items ([`crate::described_metrics`]). The progress callback
/// hears the end time after the twin.
///
/// # Errors
/// Build or simulation errors of the model or its twin.
pub(crate) fn run_described(
    model: &str,
    desc: &ModelDesc,
    settings: &RunSettings,
) -> Result<(Results, Vec<Metric>), ModelsError> {
    let (mut m, opts) = common::compile_run(model, desc)?;
    let mut res = common::simulate(&mut m, &opts, settings, model)?;
    let twin = clr_mbd::desc::twin::run_twin(desc, &opts, &mut res)
        .map_err(|e| common::sim_error(model, e))?;
    if let Some(cb) = &settings.progress {
        cb(opts.t_end);
    }
    let metrics = evaluate(&desc.metrics, &res, twin.as_ref());
    Ok((res, metrics))
}

/// [`run_described`] as the built-in's [`RunOutput`], with the parameters `p`.
///
/// # Errors
/// As [`run_described`].
pub(crate) fn run_output<P: serde::Serialize>(
    model: &str,
    desc: &ModelDesc,
    settings: &RunSettings,
    p: &P,
) -> Result<crate::RunOutput, ModelsError> {
    let (res, metrics) = run_described(model, desc, settings)?;
    let params = serde_json::to_value(p).unwrap_or_default();
    Ok(common::output(model, res, metrics, params))
}

/// The metrics `descs` of `res` (and of the ideal twin's results `twin`, for those with
/// `twin = true`; NaN without them), in order. A window with no row gives NaN (a failed run's
/// partial rows may end before it).
pub fn evaluate(descs: &[MetricDesc], res: &Results, twin: Option<&Results>) -> Vec<Metric> {
    let mut out: Vec<Metric> = Vec::with_capacity(descs.len());
    for d in descs {
        let source = if d.twin { twin } else { Some(res) };
        let (value, unit) = if d.metrics.is_empty() {
            match source {
                Some(r) => of_columns(d, r),
                None => (f64::NAN, unit_of_statistic(d, res)),
            }
        } else {
            of_metrics(d, &out)
        };
        let (value, unit) = divided(d, value, unit, &out);
        let unit = d.unit.clone().unwrap_or(unit);
        let window = match (d.t_start, d.t_end) {
            (None, None) => crate::output::WHOLE_RUN.to_string(),
            (Some(a), None) => format!("t ≥ {a} s"),
            (None, Some(b)) => format!("t ≤ {b} s"),
            (Some(a), Some(b)) => format!("{a} s ≤ t ≤ {b} s"),
        };
        let mut words = d.description.clone().unwrap_or_else(|| default_words(d));
        if let Some(why) = no_rows(d, source.unwrap_or(res)) {
            // said with the value, not left as a bare NaN (a window in ms, a run cut short)
            words.push_str(&format!(" [no value: {why}]"));
        }
        out.push(Metric::new(&d.name, value, &unit, &words).over(&window));
    }
    out
}

/// Why the window of a metric of columns holds no row of `res`, if it does not.
fn no_rows(d: &MetricDesc, res: &Results) -> Option<String> {
    if !d.metrics.is_empty() {
        return None;
    }
    let t = res.column("t").unwrap_or_default();
    let (first, last) = (*t.first()?, *t.last()?);
    let (from, to) = (
        d.t_start.unwrap_or(f64::NEG_INFINITY),
        d.t_end.unwrap_or(f64::INFINITY),
    );
    (!t.iter().any(|&x| x >= from && x <= to)).then(|| {
        format!("the run's rows span [{first}, {last}] s, none in the window (times in s?)")
    })
}

fn default_words(d: &MetricDesc) -> String {
    let what = if d.metrics.is_empty() {
        d.columns()
            .iter()
            .map(|c| format!("`{c}`"))
            .collect::<Vec<_>>()
            .join(", ")
    } else {
        format!("the metrics {}", d.metrics.join(", "))
    };
    let twin = if d.twin { " of the ideal twin" } else { "" };
    format!(
        "{} of {what}{twin} ([[metric]] of the model)",
        d.statistic.words()
    )
}

/// The unit of the statistic of `d`'s first column (before `per` and `unit`).
fn unit_of_statistic(d: &MetricDesc, res: &Results) -> String {
    let column = d.columns().first().map_or("-", |c| res.unit(c));
    match d.statistic {
        s if s.is_time() => "s".into(),
        Statistic::Onsets | Statistic::Spread => "-".into(),
        Statistic::Integral => integrated(column),
        _ => column.into(),
    }
}

/// The unit of ∫ v dt for v in `unit`.
fn integrated(unit: &str) -> String {
    match unit {
        "-" => "s",
        "N" => "N*s",
        "N*m" => "N*m*s",
        "W" => "J",
        "m/s" => "m",
        "m/s^2" => "m/s",
        "rad/s" => "rad",
        "rad/s^2" => "rad/s",
        other => return format!("{other}*s"),
    }
    .into()
}

/// The value and unit after `per` (0/0 gives 0).
fn divided(d: &MetricDesc, value: f64, unit: String, done: &[Metric]) -> (f64, String) {
    let (by, by_unit) = match &d.per {
        None => return (value, unit),
        Some(Divisor::Number(x)) => (*x, "-".to_string()),
        Some(Divisor::Metric(m)) => done
            .iter()
            .find(|o| &o.name == m)
            .map_or((f64::NAN, "-".into()), |o| (o.value, o.unit.clone())),
    };
    let v = if value == 0.0 && by == 0.0 {
        0.0
    } else {
        value / by
    };
    let u = if by_unit == unit {
        "-".to_string()
    } else if by_unit == "-" {
        unit
    } else {
        format!("{unit}/({by_unit})")
    };
    (v, u)
}

/// The statistic of the earlier metrics' values.
fn of_metrics(d: &MetricDesc, done: &[Metric]) -> (f64, String) {
    let found: Vec<&Metric> = (d.metrics.iter())
        .filter_map(|n| done.iter().find(|m| &m.name == n))
        .collect();
    let v: Vec<f64> = found.iter().map(|m| m.value).collect();
    let unit = found.first().map_or("-".to_string(), |m| m.unit.clone());
    if v.is_empty() {
        return (f64::NAN, unit);
    }
    let n = v.len() as f64;
    let value = match d.statistic {
        Statistic::Max => v.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        Statistic::Min => v.iter().cloned().fold(f64::INFINITY, f64::min),
        Statistic::Peak => v.iter().fold(0.0, |a: f64, x| a.max(x.abs())),
        Statistic::Sum => v.iter().sum(),
        Statistic::Mean => v.iter().sum::<f64>() / n,
        Statistic::Rms => (v.iter().map(|x| x * x).sum::<f64>() / n).sqrt(),
        // refused when the description is checked
        _ => f64::NAN,
    };
    (value, unit)
}

/// The statistic of `d`'s columns of `res` over its window.
fn of_columns(d: &MetricDesc, res: &Results) -> (f64, String) {
    let unit = unit_of_statistic(d, res);
    let t = res.column("t").unwrap_or_default();
    let (from, to) = (
        d.t_start.unwrap_or(f64::NEG_INFINITY),
        d.t_end.unwrap_or(f64::INFINITY),
    );
    let rows: Vec<usize> = (0..t.len())
        .filter(|&k| t[k] >= from && t[k] <= to)
        .collect();
    if rows.is_empty() {
        return (f64::NAN, unit);
    }
    let tw: Vec<f64> = rows.iter().map(|&k| t[k]).collect();
    let columns: Vec<Vec<f64>> = (d.columns().iter())
        .map(|c| {
            let v = res.column(c).unwrap_or_else(|| vec![f64::NAN; t.len()]);
            rows.iter().map(|&k| v[k]).collect()
        })
        .collect();
    let value = match d.statistic {
        Statistic::Spread => spread(d, &t, res, &tw),
        _ => pooled(d, res, &tw, &columns),
    };
    (value, unit)
}

/// The statistic over several columns taken together (`Statistic` docs).
fn pooled(d: &MetricDesc, res: &Results, t: &[f64], columns: &[Vec<f64>]) -> f64 {
    let each = |f: &dyn Fn(&str, &[f64]) -> f64| -> Vec<f64> {
        (d.columns().iter().zip(columns))
            .map(|(c, v)| f(c, v))
            .collect()
    };
    let max = |v: Vec<f64>| v.into_iter().fold(f64::NEG_INFINITY, f64::max);
    let n = columns.len() as f64;
    match d.statistic {
        Statistic::Peak => max(each(&|c, v| located(c, res, t, row_peak(v)))),
        Statistic::Max => max(each(&|c, v| {
            let m = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            located(c, res, t, m)
        })),
        Statistic::Min => (each(&|_, v| v.iter().cloned().fold(f64::INFINITY, f64::min)))
            .into_iter()
            .fold(f64::INFINITY, f64::min),
        Statistic::Mean => each(&|_, v| time_mean(t, v, t[0])).iter().sum::<f64>() / n,
        Statistic::Rms => {
            let sq = each(&|_, v| {
                let s: Vec<f64> = v.iter().map(|x| x * x).collect();
                time_mean(t, &s, t[0])
            });
            (sq.iter().sum::<f64>() / n).sqrt()
        }
        Statistic::Final => columns[0][t.len() - 1],
        Statistic::Change => columns[0][t.len() - 1] - columns[0][0],
        Statistic::Drift => max(each(&|_, v| {
            v.iter().fold(0.0, |a: f64, x| a.max((x - v[0]).abs()))
        })),
        Statistic::Integral => each(&|_, v| integral(t, v)).iter().sum(),
        Statistic::Onsets => each(&|_, v| onsets(v) as f64).iter().sum(),
        Statistic::Oscillation => {
            let w = d.window.unwrap_or(f64::NAN);
            max(each(&|_, v| oscillation(t, v, w)))
        }
        Statistic::TimeOfPeak | Statistic::TimeOfMax | Statistic::TimeOfMin => {
            time_of_extreme(d.statistic, t, columns)
        }
        // refused when the description is checked
        Statistic::Sum | Statistic::Spread => f64::NAN,
    }
}

/// Largest |v|.
fn row_peak(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |a: f64, x| a.max(x.abs()))
}

/// The time of the extreme over all columns (the first row that reaches it).
fn time_of_extreme(s: Statistic, t: &[f64], columns: &[Vec<f64>]) -> f64 {
    let key = |x: f64| match s {
        Statistic::TimeOfPeak => x.abs(),
        Statistic::TimeOfMax => x,
        _ => -x,
    };
    let mut best = (f64::NEG_INFINITY, f64::NAN);
    for v in columns {
        for (k, &x) in v.iter().enumerate() {
            if key(x) > best.0 {
                best = (key(x), t[k]);
            }
        }
    }
    best.1
}

/// ∫ v dt by the trapezoidal rule over the rows.
fn integral(t: &[f64], v: &[f64]) -> f64 {
    (1..t.len())
        .map(|k| 0.5 * (v[k] + v[k - 1]) * (t[k] - t[k - 1]))
        .sum()
}

/// Rows where v reaches 0.5 after a row below it.
fn onsets(v: &[f64]) -> usize {
    v.windows(2).filter(|w| w[0] < 0.5 && w[1] >= 0.5).count()
}

/// Largest |v − the running mean of v over `window` s| ([`Statistic::Oscillation`]).
pub fn oscillation(t: &[f64], v: &[f64], window: f64) -> f64 {
    let n = t.len();
    let mut out = 0.0f64;
    let (mut lo, mut hi) = (0usize, 0usize);
    for k in 0..n {
        let (a, b) = (t[k] - 0.5 * window, t[k] + 0.5 * window);
        if a < t[0] || b > t[n - 1] {
            continue;
        }
        while t[lo] < a {
            lo += 1;
        }
        while hi + 1 < n && t[hi + 1] <= b {
            hi += 1;
        }
        let mean = time_mean(&t[lo..=hi], &v[lo..=hi], f64::NEG_INFINITY);
        out = out.max((v[k] - mean).abs());
    }
    out
}

/// [`Statistic::Spread`] of the point whose coordinates are `d`'s columns, interpolated in
/// the whole rows (`t`, all of them) from the window's start to its last row `tw`.
fn spread(d: &MetricDesc, t: &[f64], res: &Results, tw: &[f64]) -> f64 {
    let (period, phases) = (d.period.unwrap_or(f64::NAN), d.phases.unwrap_or(8));
    let coords: Vec<Vec<f64>> = (d.columns().iter())
        .map(|c| res.column(c).unwrap_or_default())
        .collect();
    // sampled from the window's start itself (not its first row), so that the phases are those
    // of the forcing whatever the rows
    let t0 = d.t_start.map_or(tw[0], |s| s.max(t[0]));
    let t_end = tw[tw.len() - 1];
    let periods = ((t_end - t0) / period + 1e-9).floor() as usize;
    if periods < 2 {
        return f64::NAN;
    }
    let mut total = 0.0;
    for i in 0..phases {
        let points: Vec<Vec<f64>> = (0..periods)
            .map(|k| {
                let at = t0 + (k as f64 + i as f64 / phases as f64) * period;
                coords.iter().map(|x| interp(t, x, at)).collect()
            })
            .collect();
        let n = points.len() as f64;
        let mean: Vec<f64> = (0..coords.len())
            .map(|j| points.iter().map(|p| p[j]).sum::<f64>() / n)
            .collect();
        let var = (points.iter())
            .map(|p| {
                (p.iter().zip(&mean))
                    .map(|(x, m)| (x - m).powi(2))
                    .sum::<f64>()
            })
            .sum::<f64>()
            / n;
        total += var.sqrt();
    }
    total / phases as f64
}

/// The row extreme `rows` raised to the located extrema of a contact element's impacts inside
/// the window, for `<C>.normal_force` and `<C>.penetration` (both ≥ 0, so peak and max agree).
fn located(column: &str, res: &Results, t: &[f64], rows: f64) -> f64 {
    match column.rsplit_once('.') {
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
            t_start: from,
            ..MetricDesc::new("m", "a.x", stat)
        };
        evaluate(&[d], r, None)[0].value
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
        // a window after the last row has no value, and says why
        assert!(metric(Statistic::Max, Some(2.0), &r).is_nan());
        let d = MetricDesc::new("m", "a.x", Statistic::Max).after(2.0);
        let words = &evaluate(&[d], &r, None)[0].description;
        assert!(
            words.contains("no value") && words.contains("[0, 1] s"),
            "{words}"
        );
    }

    /// Results with columns `t` and `c<k>` from the closures.
    fn table(t: &[f64], cols: &[&dyn Fn(f64) -> f64]) -> Results {
        let mut columns = vec!["t".to_string()];
        columns.extend((0..cols.len()).map(|k| format!("c{k}.x")));
        let data = (t.iter())
            .flat_map(|&x| std::iter::once(x).chain(cols.iter().map(move |f| f(x))))
            .collect();
        Results {
            columns,
            data,
            ..Default::default()
        }
    }

    fn value(d: MetricDesc, r: &Results) -> f64 {
        evaluate(&[d], r, None)[0].value
    }

    #[test]
    fn drift_change_integral_and_onsets_equal_their_closed_forms() {
        use std::f64::consts::PI;
        let t: Vec<f64> = (0..=10_000).map(|k| k as f64 / 10_000.0).collect();
        // v = 1 + t²: change v(1) − v(0) = 1, drift max |v − v(0)| = 1, ∫₀¹ v dt = 4/3 with
        // the trapezoid error h²/12·(v'(1) − v'(0)) = 1e-8/6
        let r = table(&t, &[&|x| 1.0 + x * x, &|x| (2.0 * PI * 5.0 * x).sin()]);
        let of = |s| MetricDesc::new("m", "c0.x", s);
        assert!((value(of(Statistic::Change), &r) - 1.0).abs() < 1e-15);
        assert!((value(of(Statistic::Drift), &r) - 1.0).abs() < 1e-15);
        let i = value(of(Statistic::Integral), &r);
        assert!((i - 4.0 / 3.0 - 1e-8 / 6.0).abs() < 1e-14, "{i}");
        assert_eq!(
            evaluate(&[of(Statistic::Integral)], &r, None)[0].unit,
            "m*s"
        );
        // onsets of a square wave from sign(sin 10πt): it rises to 1 at t = 0.2 k (k = 1..4)
        // and at t = 0+ (the first row is 0, the second positive): 5 onsets; two columns of it
        // count 10
        let square = |x: f64| f64::from((2.0 * PI * 5.0 * x).sin() > 1e-9);
        let r2 = table(&t, &[&square, &square]);
        let on = |c: &[&str]| value(MetricDesc::of_columns("m", c, Statistic::Onsets), &r2);
        assert_eq!(on(&["c0.x"]), 5.0);
        assert_eq!(on(&["c0.x", "c1.x"]), 10.0);
    }

    #[test]
    fn columns_taken_together_and_metrics_of_metrics() {
        use std::f64::consts::PI;
        let t: Vec<f64> = (0..=10_000).map(|k| k as f64 / 10_000.0).collect();
        // a sin 2πt and b cos 2πt (a = 2, b = −3): peak 3 at t = 0 (|b|), RMS over both
        // √((a²/2 + b²/2)/2) = √(13/4) (trapezoid exact on a whole period)
        let r = table(
            &t,
            &[&|x| 2.0 * (2.0 * PI * x).sin(), &|x| {
                -3.0 * (2.0 * PI * x).cos()
            }],
        );
        let both = |s| MetricDesc::of_columns("m", &["c0.x", "c1.x"], s);
        assert!((value(both(Statistic::Peak), &r) - 3.0).abs() < 1e-15);
        assert!((value(both(Statistic::Rms), &r) - 3.25f64.sqrt()).abs() < 1e-12);
        assert_eq!(value(both(Statistic::TimeOfPeak), &r), 0.0);
        // largest value: −3 cos 2πt = 3 at t = 0.5
        assert_eq!(value(both(Statistic::TimeOfMax), &r), 0.5);
        // metrics of metrics, and `per`: 2/3 of the larger peak; 0/0 gives 0
        let descs = [
            MetricDesc::new("a", "c0.x", Statistic::Peak),
            MetricDesc::new("b", "c1.x", Statistic::Peak),
            MetricDesc::of_metrics("largest", &["a", "b"], Statistic::Max),
            MetricDesc::of_metrics("total", &["a", "b"], Statistic::Sum),
            MetricDesc::new("ratio", "c0.x", Statistic::Peak)
                .per(Divisor::Metric("largest".into())),
            MetricDesc::new("zero", "c0.x", Statistic::Final).per(Divisor::Number(0.0)),
        ];
        let m = evaluate(&descs, &r, None);
        let v = |k: usize| m[k].value;
        // the extremes fall on rows (t = 1/4 and 1/2): 2, 3, 5 and 2/3 to rounding (1e-15)
        assert!(
            (v(2) - 3.0).abs() < 1e-15 && (v(3) - 5.0).abs() < 1e-15,
            "{m:?}"
        );
        assert!(
            (v(4) - 2.0 / 3.0).abs() < 1e-15 && m[4].unit == "-",
            "{m:?}"
        );
        // sin 2π·1 is 2.4e-16, not 0: x/0 is then infinite, not hidden
        assert!(v(5).is_infinite() || v(5) == 0.0, "{m:?}");
    }

    #[test]
    fn stroboscopic_spread_is_zero_for_a_periodic_orbit_and_the_half_distance_for_period_two() {
        use std::f64::consts::PI;
        let t: Vec<f64> = (0..=40_000).map(|k| k as f64 * 1e-4).collect();
        // a circle of period T = 0.5 s sampled every T: every phase sees one point, spread 0
        let spread = |r: &Results| {
            value(
                MetricDesc {
                    period: Some(0.5),
                    phases: Some(10),
                    ..MetricDesc::of_columns("s", &["c0.x", "c1.x"], Statistic::Spread).after(1.0)
                },
                r,
            )
        };
        let r = table(&t, &[&|x| (4.0 * PI * x).cos(), &|x| (4.0 * PI * x).sin()]);
        // the samples fall on rows (phases 0.05 s apart, rows 1e-4 s): rounding only, 1e-12
        assert!(spread(&r) < 1e-12, "{}", spread(&r));
        // a period-2 orbit: x jumps between +d and −d on alternate periods (x = d·cos(2πt/T')
        // with T' = 2T sampled at T-multiples alternates ±d·cos φ); with the RMS distance of
        // the two points from their mean |d cos φ|, the mean over phases φ_i = π i/10 of
        // |cos φ_i| (6 whole periods: 3 samples each side, equal weights)
        let d = 0.3;
        let r2 = table(&t, &[&move |x| d * (2.0 * PI * x).cos(), &|_| 0.0]);
        let want = (0..10)
            .map(|i| (d * (PI * i as f64 / 10.0).cos()).abs())
            .sum::<f64>()
            / 10.0;
        assert!(
            (spread(&r2) - want).abs() < 1e-12,
            "{} vs {want}",
            spread(&r2)
        );
    }

    #[test]
    fn oscillation_amplitude_of_a_sine_on_a_ramp() {
        // closed form: v = a t + A sin(2π t/T); the running mean over one period T of the sine
        // is 0 and of the ramp is the ramp itself, so the amplitude is A (to sampling error)
        let (a, amp, period) = (3.0, 0.25, 0.1);
        let t: Vec<f64> = (0..=20_000).map(|k| k as f64 * 1e-4).collect();
        let v: Vec<f64> = t
            .iter()
            .map(|&x| a * x + amp * (2.0 * std::f64::consts::PI * x / period).sin())
            .collect();
        let got = oscillation(&t, &v, period);
        assert!((got - amp).abs() < 1e-3 * amp, "{got}");
    }
}
