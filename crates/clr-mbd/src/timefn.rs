//! Functions of time as data: drivers' motions and applied loads.
//!
//! A [`TimeFn`] is plain data (`Clone + Send + Sync`, serde), so a model that uses only these
//! can be written to and read from a model file. A Rust closure stays available as the explicit
//! opt-in [`TimeFn::custom`]; such a function cannot be written to a file (serialization fails
//! with a message naming it).

use std::fmt;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::field::FieldError;

/// A user closure returning [f(t), f′(t), f″(t)] (see [`TimeFn::custom`]).
#[derive(Clone)]
pub struct UserFn(pub Arc<dyn Fn(f64) -> [f64; 3] + Send + Sync>);

/// Closures compare by identity (the same `Arc`).
impl PartialEq for UserFn {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl fmt::Debug for UserFn {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("UserFn(<closure>)")
    }
}

/// The value of a named input at a time ([`crate::input::InputCell`] is the one kind): what a
/// bound [`TimeFn::Input`] evaluates.
pub trait InputValue: fmt::Debug + Send + Sync {
    /// [u(t), u′(t), u″(t)].
    fn value(&self, t: f64) -> [f64; 3];
}

/// A bound input inside a [`TimeFn::Input`]: compares by identity (the same cell).
#[derive(Debug, Clone)]
pub struct BoundInput(pub(crate) Arc<dyn InputValue>);

impl PartialEq for BoundInput {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// A function of time f(t) with its first two derivatives, in the unit of what it drives
/// (rad, m, N or N·m). In a model file: a table with `type` and the fields of the variant, e.g.
/// `{ type = "linear", initial = 0.0, rate = 10.0 }`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum TimeFn {
    /// f = value.
    Constant {
        /// The value.
        value: f64,
    },
    /// f = initial + rate·t.
    Linear {
        /// f(0).
        #[serde(default)]
        initial: f64,
        /// Slope per second.
        rate: f64,
    },
    /// A start-up ramp: the rate rises from 0 to `rate` over `duration` T with the cycloidal
    /// blend f′(t) = rate·(t/T − sin(2πt/T)/(2π)) (zero acceleration at both ends), then stays
    /// at `rate`: f = initial + rate·(t²/(2T) + T(cos(2πt/T) − 1)/(4π²)) for t < T and
    /// f = initial + rate·(t − T/2) after.
    Ramp {
        /// f(0).
        #[serde(default)]
        initial: f64,
        /// Final slope per second.
        rate: f64,
        /// Ramp duration T, s (> 0).
        duration: f64,
    },
    /// f = offset + amplitude·sin(ω t + phase) (a harmonic).
    Sine {
        /// Mean value.
        #[serde(default)]
        offset: f64,
        /// Amplitude.
        amplitude: f64,
        /// Angular frequency ω, rad/s.
        omega: f64,
        /// Phase, rad.
        #[serde(default)]
        phase: f64,
    },
    /// f = Σ c_k t^k.
    Polynomial {
        /// Coefficients c_0, c_1, … (units per s^k).
        coefficients: Vec<f64>,
    },
    /// A smooth step from `from` to `to` over [start, start + duration] with the cubic
    /// s²(3 − 2s), s = (t − start)/duration (zero rate at both ends); constant outside.
    SmoothStep {
        /// Value before `start`.
        #[serde(default)]
        from: f64,
        /// Value after `start + duration`.
        to: f64,
        /// Start time, s.
        #[serde(default)]
        start: f64,
        /// Duration, s (≥ 0; 0 is a jump at `start`).
        duration: f64,
    },
    /// Piecewise-linear interpolation of (times, values); held constant outside the table.
    /// f″ = 0 (the kinks are not smoothed: prefer `smooth_step` segments for drivers).
    Table {
        /// Strictly increasing times, s (at least 2).
        times: Vec<f64>,
        /// Values at those times.
        values: Vec<f64>,
    },
    /// f = Σ terms.
    Sum {
        /// The terms.
        terms: Vec<TimeFn>,
    },
    /// f = Π factors (e.g. a harmonic faded in by a smooth step).
    Product {
        /// The factors.
        factors: Vec<TimeFn>,
    },
    /// The value of the named `[[input]]` ([`crate::input`]): its default time function until
    /// a master sets it. Bound to the input when the model compiles; unbound it evaluates to NaN.
    Input {
        /// The input's name.
        name: String,
        /// The compiled model's cell (not part of the file).
        #[serde(skip)]
        cell: Option<BoundInput>,
    },
    /// A Rust closure (opt-in; cannot be written to a model file).
    #[serde(skip)]
    Custom(UserFn),
}

/// The names of [`TimeFn`] kinds as written in files.
pub const TIME_FN_KINDS: [&str; 10] = [
    "constant",
    "linear",
    "ramp",
    "sine",
    "polynomial",
    "smooth_step",
    "table",
    "sum",
    "product",
    "input",
];

impl TimeFn {
    /// f(t) = x0 + v·t (e.g. a crank at constant speed v rad/s from angle x0).
    pub fn linear(x0: f64, v: f64) -> Self {
        TimeFn::Linear {
            initial: x0,
            rate: v,
        }
    }
    /// f = value.
    pub fn constant(value: f64) -> Self {
        TimeFn::Constant { value }
    }
    /// f(t) = offset + amplitude·sin(ω t + phase).
    pub fn harmonic(offset: f64, amplitude: f64, omega: f64, phase: f64) -> Self {
        TimeFn::Sine {
            offset,
            amplitude,
            omega,
            phase,
        }
    }
    /// A Rust closure returning [f(t), f′(t), f″(t)] (an explicit opt-in: the model can no
    /// longer be written to a file).
    pub fn custom(f: impl Fn(f64) -> [f64; 3] + Send + Sync + 'static) -> Self {
        TimeFn::Custom(UserFn(Arc::new(f)))
    }

    /// True when this function or one of its parts is a closure.
    pub fn has_closure(&self) -> bool {
        match self {
            TimeFn::Custom(_) => true,
            TimeFn::Sum { terms: v } | TimeFn::Product { factors: v } => {
                v.iter().any(TimeFn::has_closure)
            }
            _ => false,
        }
    }

    /// True when this function or one of its parts is an `[[input]]`.
    pub fn has_input(&self) -> bool {
        match self {
            TimeFn::Input { .. } => true,
            TimeFn::Sum { terms: v } | TimeFn::Product { factors: v } => {
                v.iter().any(TimeFn::has_input)
            }
            _ => false,
        }
    }

    /// A reference to the input `name` (bound when the model compiles).
    pub fn input(name: impl Into<String>) -> Self {
        TimeFn::Input {
            name: name.into(),
            cell: None,
        }
    }

    /// [f(t), f′(t), f″(t)].
    pub fn eval(&self, t: f64) -> [f64; 3] {
        match self {
            TimeFn::Constant { value } => [*value, 0.0, 0.0],
            TimeFn::Linear { initial, rate } => [initial + rate * t, *rate, 0.0],
            TimeFn::Ramp {
                initial,
                rate,
                duration,
            } => ramp(*initial, *rate, *duration, t),
            TimeFn::Sine {
                offset,
                amplitude,
                omega,
                phase,
            } => {
                let (s, c) = (omega * t + phase).sin_cos();
                [
                    offset + amplitude * s,
                    amplitude * omega * c,
                    -amplitude * omega * omega * s,
                ]
            }
            TimeFn::Polynomial { coefficients } => polynomial(coefficients, t),
            TimeFn::SmoothStep {
                from,
                to,
                start,
                duration,
            } => smooth_step(*from, *to, *start, *duration, t),
            TimeFn::Table { times, values } => table(times, values, t),
            TimeFn::Sum { terms } => terms.iter().fold([0.0; 3], |a, f| {
                let v = f.eval(t);
                [a[0] + v[0], a[1] + v[1], a[2] + v[2]]
            }),
            TimeFn::Product { factors } => factors.iter().fold([1.0, 0.0, 0.0], |a, f| {
                // (ab)' = a'b + ab', (ab)'' = a''b + 2a'b' + ab''
                let b = f.eval(t);
                [
                    a[0] * b[0],
                    a[1] * b[0] + a[0] * b[1],
                    a[2] * b[0] + 2.0 * a[1] * b[1] + a[0] * b[2],
                ]
            }),
            TimeFn::Input { cell: Some(c), .. } => c.0.value(t),
            TimeFn::Input { cell: None, .. } => [f64::NAN; 3],
            TimeFn::Custom(f) => (f.0)(t),
        }
    }

    /// Check every number (finite, durations ≥ 0, tables increasing); `path` names the field
    /// in messages (e.g. `driver[0].motion`).
    ///
    /// # Errors
    /// [`FieldError`] at the offending field.
    pub fn validate(&self, path: &str) -> Result<(), FieldError> {
        let finite = |field: &str, v: f64| -> Result<(), FieldError> {
            if v.is_finite() {
                Ok(())
            } else {
                Err(FieldError::new(
                    format!("{path}.{field}"),
                    format!("{v} must be finite"),
                ))
            }
        };
        match self {
            TimeFn::Constant { value } => finite("value", *value),
            TimeFn::Linear { initial, rate } => {
                finite("initial", *initial)?;
                finite("rate", *rate)
            }
            TimeFn::Ramp {
                initial,
                rate,
                duration,
            } => {
                finite("initial", *initial)?;
                finite("rate", *rate)?;
                positive(path, "duration", *duration)
            }
            TimeFn::Sine {
                offset,
                amplitude,
                omega,
                phase,
            } => {
                for (f, v) in [
                    ("offset", offset),
                    ("amplitude", amplitude),
                    ("omega", omega),
                    ("phase", phase),
                ] {
                    finite(f, *v)?;
                }
                Ok(())
            }
            TimeFn::Polynomial { coefficients } => {
                if coefficients.is_empty() {
                    return Err(FieldError::new(
                        format!("{path}.coefficients"),
                        "expected a non-empty list of numbers [c0, c1, ...]",
                    ));
                }
                coefficients
                    .iter()
                    .try_for_each(|c| finite("coefficients", *c))
            }
            TimeFn::SmoothStep {
                from,
                to,
                start,
                duration,
            } => {
                finite("from", *from)?;
                finite("to", *to)?;
                finite("start", *start)?;
                if duration.is_finite() && *duration >= 0.0 {
                    Ok(())
                } else {
                    Err(FieldError::new(
                        format!("{path}.duration"),
                        format!("must be finite and ≥ 0, got {duration} s"),
                    ))
                }
            }
            TimeFn::Table { times, values } => validate_table(path, times, values),
            TimeFn::Sum { terms: v } | TimeFn::Product { factors: v } => {
                let field = if matches!(self, TimeFn::Sum { .. }) {
                    "terms"
                } else {
                    "factors"
                };
                if v.is_empty() {
                    return Err(FieldError::new(
                        format!("{path}.{field}"),
                        "give at least one function",
                    ));
                }
                v.iter()
                    .enumerate()
                    .try_for_each(|(k, f)| f.validate(&format!("{path}.{field}[{k}]")))
            }
            TimeFn::Input { name, .. } if name.trim().is_empty() => Err(FieldError::new(
                format!("{path}.name"),
                "name the [[input]] this function takes its value from",
            )),
            TimeFn::Input { .. } | TimeFn::Custom(_) => Ok(()),
        }
    }
}

fn positive(path: &str, field: &str, v: f64) -> Result<(), FieldError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(FieldError::new(
            format!("{path}.{field}"),
            format!("must be positive and finite (give a value > 0), got {v}"),
        ))
    }
}

fn validate_table(path: &str, times: &[f64], values: &[f64]) -> Result<(), FieldError> {
    if times.len() < 2 || times.len() != values.len() {
        return Err(FieldError::new(
            format!("{path}.times"),
            format!(
                "a table needs at least 2 times and as many values (got {} times, {} values)",
                times.len(),
                values.len()
            ),
        ));
    }
    if !times.windows(2).all(|w| w[1] > w[0]) || !times.iter().all(|t| t.is_finite()) {
        return Err(FieldError::new(
            format!("{path}.times"),
            "times must be finite and strictly increasing",
        ));
    }
    if !values.iter().all(|v| v.is_finite()) {
        return Err(FieldError::new(
            format!("{path}.values"),
            "values must be finite",
        ));
    }
    Ok(())
}

fn ramp(initial: f64, rate: f64, tt: f64, t: f64) -> [f64; 3] {
    if t >= tt {
        [initial + rate * (t - 0.5 * tt), rate, 0.0]
    } else {
        let w = std::f64::consts::TAU / tt;
        let (s, c) = (w * t).sin_cos();
        [
            initial + rate * (t * t / (2.0 * tt) + (c - 1.0) / (w * w * tt)),
            rate * (t / tt - s / (w * tt)),
            rate / tt * (1.0 - c),
        ]
    }
}

fn polynomial(coefficients: &[f64], t: f64) -> [f64; 3] {
    // Horner for f, f′, f″ together
    let (mut f, mut d1, mut d2) = (0.0, 0.0, 0.0);
    for &c in coefficients.iter().rev() {
        d2 = d2 * t + 2.0 * d1;
        d1 = d1 * t + f;
        f = f * t + c;
    }
    [f, d1, d2]
}

fn smooth_step(from: f64, to: f64, start: f64, duration: f64, t: f64) -> [f64; 3] {
    if t < start {
        return [from, 0.0, 0.0];
    }
    if duration <= 0.0 || t >= start + duration {
        return [to, 0.0, 0.0];
    }
    let d = to - from;
    let s = (t - start) / duration;
    [
        from + d * s * s * (3.0 - 2.0 * s),
        d * 6.0 * s * (1.0 - s) / duration,
        d * (6.0 - 12.0 * s) / (duration * duration),
    ]
}

fn table(times: &[f64], values: &[f64], t: f64) -> [f64; 3] {
    let n = times.len();
    if n == 0 {
        return [0.0; 3];
    }
    if t <= times[0] {
        return [values[0], 0.0, 0.0];
    }
    if t >= times[n - 1] {
        return [values[n - 1], 0.0, 0.0];
    }
    // first index with times[k] > t (k ≥ 1 here)
    let k = times.partition_point(|&x| x <= t);
    let (t0, t1, v0, v1) = (times[k - 1], times[k], values[k - 1], values[k]);
    let slope = (v1 - v0) / (t1 - t0);
    [v0 + slope * (t - t0), slope, 0.0]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Derivatives checked against central differences of f (independent of the closed forms);
    /// tolerance 1e-6 relative on f′ and 1e-5 on f″ (h = 1e-5, error O(h²·f‴)).
    #[test]
    fn derivatives_match_finite_differences() {
        let fns = [
            TimeFn::Ramp {
                initial: 0.3,
                rate: 10.0,
                duration: 0.2,
            },
            TimeFn::harmonic(1.0, 0.5, 7.0, 0.3),
            TimeFn::Polynomial {
                coefficients: vec![1.0, -2.0, 0.5, 0.25],
            },
            TimeFn::SmoothStep {
                from: 1.0,
                to: 3.0,
                start: 0.05,
                duration: 0.2,
            },
            TimeFn::Product {
                factors: vec![
                    TimeFn::SmoothStep {
                        from: 0.0,
                        to: 1.0,
                        start: 0.0,
                        duration: 0.3,
                    },
                    TimeFn::harmonic(0.0, 0.02, 12.0, 0.0),
                ],
            },
            TimeFn::Sum {
                terms: vec![TimeFn::constant(0.4), TimeFn::linear(0.1, 2.0)],
            },
        ];
        let h = 1e-5;
        for f in &fns {
            for &t in &[0.03, 0.11, 0.19, 0.35] {
                let [_, d1, d2] = f.eval(t);
                let fd1 = (f.eval(t + h)[0] - f.eval(t - h)[0]) / (2.0 * h);
                let fd2 = (f.eval(t + h)[1] - f.eval(t - h)[1]) / (2.0 * h);
                assert!((d1 - fd1).abs() < 1e-6 * (1.0 + d1.abs()), "{f:?} t={t}");
                assert!((d2 - fd2).abs() < 1e-5 * (1.0 + d2.abs()), "{f:?} t={t}");
            }
        }
        // the ramp is continuous at t = T: initial + rate·T/2
        let r = TimeFn::Ramp {
            initial: 0.0,
            rate: 10.0,
            duration: 0.2,
        };
        assert!((r.eval(0.2 - 1e-12)[0] - 1.0).abs() < 1e-9);
        assert!((r.eval(0.2)[0] - 1.0).abs() < 1e-12);
    }

    /// Piecewise-linear table: exact values at the knots and midpoints (closed form).
    #[test]
    fn table_interpolates_and_holds_its_ends() {
        let f = TimeFn::Table {
            times: vec![0.0, 1.0, 3.0],
            values: vec![0.0, 2.0, 1.0],
        };
        assert_eq!(f.eval(-1.0), [0.0, 0.0, 0.0]);
        assert_eq!(f.eval(0.5), [1.0, 2.0, 0.0]);
        assert_eq!(f.eval(2.0), [1.5, -0.5, 0.0]);
        assert_eq!(f.eval(4.0), [1.0, 0.0, 0.0]);
        assert!(f.validate("f").is_ok());
        let bad = TimeFn::Table {
            times: vec![0.0, 0.0],
            values: vec![1.0, 2.0],
        };
        assert!(bad.validate("f").unwrap_err().path == "f.times");
    }

    /// A closure cannot be written to a file; data round-trips through TOML exactly.
    #[test]
    fn data_round_trips_and_closures_refuse_to_serialize() {
        #[derive(Serialize, Deserialize)]
        struct W {
            f: TimeFn,
        }
        let f = TimeFn::Sum {
            terms: vec![
                TimeFn::harmonic(0.1, 0.2, 3.0, 0.1),
                TimeFn::linear(0.3, 1.7),
            ],
        };
        let s = toml::to_string(&W { f: f.clone() }).unwrap();
        let back: W = toml::from_str(&s).unwrap();
        assert_eq!(back.f, f);
        assert!(toml::to_string(&W {
            f: TimeFn::custom(|t| [t, 1.0, 0.0])
        })
        .is_err());
    }
}
