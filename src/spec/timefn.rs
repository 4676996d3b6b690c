//! Functions of time as data: drivers' motions and applied loads.

use serde::Serialize;

/// A function of time f(t) with its first two derivatives, in the unit of what it drives
/// (rad, m, N or N·m).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum TimeFn {
    /// f = value.
    Constant {
        /// The value.
        value: f64,
    },
    /// f = initial + rate·t.
    Linear {
        /// f(0).
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
        initial: f64,
        /// Final slope per second.
        rate: f64,
        /// Ramp duration T, s (> 0).
        duration: f64,
    },
    /// f = offset + amplitude·sin(ω t + phase).
    Sine {
        /// Mean value.
        offset: f64,
        /// Amplitude.
        amplitude: f64,
        /// Angular frequency ω, rad/s.
        omega: f64,
        /// Phase, rad.
        phase: f64,
    },
    /// f = Σ c_k t^k.
    Polynomial {
        /// Coefficients c_0, c_1, … (units per s^k).
        coefficients: Vec<f64>,
    },
}

/// The names of [`TimeFn`] kinds as written in files.
pub const TIME_FN_KINDS: [&str; 5] = ["constant", "linear", "ramp", "sine", "polynomial"];

impl TimeFn {
    /// [f(t), f′(t), f″(t)].
    pub fn eval(&self, t: f64) -> [f64; 3] {
        match self {
            TimeFn::Constant { value } => [*value, 0.0, 0.0],
            TimeFn::Linear { initial, rate } => [initial + rate * t, *rate, 0.0],
            TimeFn::Ramp {
                initial,
                rate,
                duration,
            } => {
                let tt = *duration;
                if t >= tt {
                    [initial + rate * (t - 0.5 * tt), *rate, 0.0]
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
            TimeFn::Polynomial { coefficients } => {
                // Horner for f, f′, f″ together
                let (mut f, mut d1, mut d2) = (0.0, 0.0, 0.0);
                for &c in coefficients.iter().rev() {
                    d2 = d2 * t + 2.0 * d1;
                    d1 = d1 * t + f;
                    f = f * t + c;
                }
                [f, d1, d2]
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Derivatives checked against central differences of f (independent of the closed forms).
    #[test]
    fn derivatives_match_finite_differences() {
        let fns = [
            TimeFn::Ramp {
                initial: 0.3,
                rate: 10.0,
                duration: 0.2,
            },
            TimeFn::Sine {
                offset: 1.0,
                amplitude: 0.5,
                omega: 7.0,
                phase: 0.3,
            },
            TimeFn::Polynomial {
                coefficients: vec![1.0, -2.0, 0.5, 0.25],
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
}
