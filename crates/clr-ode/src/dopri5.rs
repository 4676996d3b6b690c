//! Dormand–Prince 5(4) (Dormand & Prince, J. Comput. Appl. Math. 6 (1980) 19–26) with FSAL,
//! the PI step-size controller of Hairer, Nørsett & Wanner (Solving ODEs I, 2nd ed., §IV.2,
//! eq. (2.43c), as in their code `dopri5`) and the 4th-order continuous extension of
//! Hairer, Nørsett & Wanner (§II.6, dense output coefficients of `dopri5`, `contd5`).

use crate::options::Options;
use crate::solver::{initial_step, Ctx, Failure, Method};
use crate::system::OdeSystem;

const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// error coefficients b − b̂
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// dense output (Hairer's continuous extension of order 4)
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// PI controller: β = 0.04, exponent α = 0.2 − 0.75 β, safety 0.9, step ratio in [0.2, 10]
/// (the defaults of Hairer's `dopri5`).
const BETA: f64 = 0.04;
const EXPO1: f64 = 0.2 - BETA * 0.75;
const SAFE: f64 = 0.9;
const FAC_MIN: f64 = 0.2;
const FAC_MAX: f64 = 10.0;
/// Consecutive non-finite step attempts tolerated (each divides h by 4).
const MAX_NONFINITE: usize = 30;

/// The Dormand–Prince 5(4) method state (buffers preallocated by `resize`).
#[derive(Debug, Default)]
pub struct Dopri5Method {
    n: usize,
    t: f64,
    t_old: f64,
    h: f64,
    h_last: f64,
    facold: f64,
    last_rejected: bool,
    y: Vec<f64>,
    y_new: Vec<f64>,
    ys: Vec<f64>,
    k1: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    k5: Vec<f64>,
    k6: Vec<f64>,
    k7: Vec<f64>,
    rcont: Vec<f64>,
    work: Vec<f64>,
}

impl Dopri5Method {
    /// The step size proposed for the next step (units of t).
    pub fn next_step_size(&self) -> f64 {
        self.h
    }
}

fn all_finite(x: &[f64]) -> bool {
    x.iter().all(|v| v.is_finite())
}

impl Method for Dopri5Method {
    const SUPPORTS_MASS: bool = false;
    const STIFF: bool = false;

    fn resize(&mut self, n: usize) {
        self.n = n;
        for v in [
            &mut self.y,
            &mut self.y_new,
            &mut self.ys,
            &mut self.k1,
            &mut self.k2,
            &mut self.k3,
            &mut self.k4,
            &mut self.k5,
            &mut self.k6,
            &mut self.k7,
        ] {
            v.resize(n, 0.0);
        }
        self.rcont.resize(5 * n, 0.0);
        self.work.resize(3 * n, 0.0);
    }

    fn capacity(&self) -> usize {
        [
            &self.y,
            &self.y_new,
            &self.ys,
            &self.k1,
            &self.k2,
            &self.k3,
            &self.k4,
            &self.k5,
            &self.k6,
            &self.k7,
            &self.rcont,
            &self.work,
        ]
        .iter()
        .map(|v| v.capacity())
        .sum()
    }

    fn init<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        ctx: &mut Ctx,
        t: f64,
        y: &[f64],
        t_end: f64,
    ) -> Result<(), Failure> {
        self.t = t;
        self.t_old = t;
        self.y.copy_from_slice(y);
        sys.rhs(t, y, &mut self.k1);
        ctx.stats.f_evals += 1;
        if !all_finite(&self.k1) {
            return Err(Failure::NonFiniteRhs { t });
        }
        self.facold = 1e-4;
        self.last_rejected = false;
        self.h_last = 0.0;
        let opts: &Options = ctx.opts;
        self.h = match opts.h0 {
            Some(h) => h.min(opts.h_max),
            None => {
                let stats = &mut *ctx.stats;
                initial_step(
                    |t, y, yp| {
                        sys.rhs(t, y, yp);
                        stats.f_evals += 1;
                        all_finite(yp)
                    },
                    t,
                    y,
                    &self.k1,
                    4,
                    ctx.rtol,
                    ctx.atol,
                    opts.h_max,
                    t_end,
                    &mut self.work,
                )
            }
        };
        // the dense output of a zero-length step is the constant y
        self.rcont.fill(0.0);
        self.rcont[..self.n].copy_from_slice(y);
        Ok(())
    }

    fn step<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        ctx: &mut Ctx,
        t_end: f64,
    ) -> Result<(), Failure> {
        let n = self.n;
        let opts = ctx.opts;
        let t = self.t;
        let mut nonfinite = 0usize;
        if t >= t_end {
            // nothing left to integrate; the driver never asks for this
            return Err(Failure::Underflow {
                t,
                h: 0.0,
                h_min: 0.0,
            });
        }
        let h_max = opts
            .h_max
            .min(sys.max_step(t, &self.y).max(opts.h_min.max(10.0 * ulp(t))));
        loop {
            let floor = opts.h_min.max(10.0 * ulp(t));
            let mut h = self.h.min(h_max);
            if h < floor && !opts.fixed_step {
                return Err(Failure::Underflow { t, h, h_min: floor });
            }
            // do not leave a sliver before t_end
            if t + h >= t_end || t_end - (t + h) <= 1e-8 * h {
                h = t_end - t;
            }
            let (y, ys) = (&self.y, &mut self.ys);
            let (k1, k2, k3, k4, k5, k6, k7) = (
                &self.k1,
                &mut self.k2,
                &mut self.k3,
                &mut self.k4,
                &mut self.k5,
                &mut self.k6,
                &mut self.k7,
            );
            for i in 0..n {
                ys[i] = y[i] + h * A21 * k1[i];
            }
            sys.rhs(t + C2 * h, ys, k2);
            for i in 0..n {
                ys[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
            }
            sys.rhs(t + C3 * h, ys, k3);
            for i in 0..n {
                ys[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
            }
            sys.rhs(t + C4 * h, ys, k4);
            for i in 0..n {
                ys[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
            }
            sys.rhs(t + C5 * h, ys, k5);
            for i in 0..n {
                ys[i] = y[i]
                    + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
            }
            let t_new = if h == t_end - t { t_end } else { t + h };
            sys.rhs(t_new, ys, k6);
            let y_new = &mut self.y_new;
            for i in 0..n {
                y_new[i] = y[i]
                    + h * (A71 * k1[i] + A73 * k3[i] + A74 * k4[i] + A75 * k5[i] + A76 * k6[i]);
            }
            sys.rhs(t_new, y_new, k7);
            ctx.stats.f_evals += 6;
            let mut acc = 0.0;
            for i in 0..n {
                let e = h
                    * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
                let sk = ctx.atol[i] + ctx.rtol * y[i].abs().max(y_new[i].abs());
                acc += (e / sk) * (e / sk);
            }
            let err = (acc / n as f64).sqrt();
            if !err.is_finite() || !all_finite(y_new) || !all_finite(k7) {
                nonfinite += 1;
                ctx.stats.rejected += 1;
                if opts.fixed_step || nonfinite > MAX_NONFINITE {
                    return Err(Failure::NonFiniteRhs { t });
                }
                self.h = 0.25 * h;
                self.last_rejected = true;
                continue;
            }
            if opts.fixed_step {
                self.accept(t, t_new, h);
                return Ok(());
            }
            let fac11 = err.powf(EXPO1);
            let fac = (fac11 / self.facold.powf(BETA) / SAFE).clamp(1.0 / FAC_MAX, 1.0 / FAC_MIN);
            if err <= 1.0 {
                self.facold = err.max(1e-4);
                let mut h_new = h / fac;
                if self.last_rejected {
                    h_new = h_new.min(h);
                }
                self.last_rejected = false;
                self.accept(t, t_new, h);
                self.h = h_new;
                return Ok(());
            }
            ctx.stats.rejected += 1;
            self.last_rejected = true;
            self.h = h / (fac11 / SAFE).min(1.0 / FAC_MIN);
        }
    }

    fn t_old(&self) -> f64 {
        self.t_old
    }

    fn t(&self) -> f64 {
        self.t
    }

    fn y(&self) -> &[f64] {
        &self.y
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) {
        let n = self.n;
        let h = self.h_last;
        let theta = if h > 0.0 { (t - self.t_old) / h } else { 0.0 };
        let theta1 = 1.0 - theta;
        let r = &self.rcont;
        for i in 0..n {
            out[i] = r[i]
                + theta
                    * (r[n + i]
                        + theta1 * (r[2 * n + i] + theta * (r[3 * n + i] + theta1 * r[4 * n + i])));
        }
    }

    fn finish_step(&mut self, _ctx: &mut Ctx) {}
}

impl Dopri5Method {
    /// Accept the step of size h from t: dense-output coefficients, then FSAL swap.
    fn accept(&mut self, t: f64, t_new: f64, h: f64) {
        let n = self.n;
        let r = &mut self.rcont;
        for i in 0..n {
            let y0 = self.y[i];
            let y1 = self.y_new[i];
            let ydiff = y1 - y0;
            let bspl = h * self.k1[i] - ydiff;
            r[i] = y0;
            r[n + i] = ydiff;
            r[2 * n + i] = bspl;
            r[3 * n + i] = ydiff - h * self.k7[i] - bspl;
            r[4 * n + i] = h
                * (D1 * self.k1[i]
                    + D3 * self.k3[i]
                    + D4 * self.k4[i]
                    + D5 * self.k5[i]
                    + D6 * self.k6[i]
                    + D7 * self.k7[i]);
        }
        self.t_old = t;
        self.t = t_new;
        self.h_last = h;
        std::mem::swap(&mut self.y, &mut self.y_new);
        std::mem::swap(&mut self.k1, &mut self.k7);
    }
}

/// Distance from x to the next larger float (units of x).
pub(crate) fn ulp(x: f64) -> f64 {
    let a = x.abs();
    if a == 0.0 {
        f64::MIN_POSITIVE
    } else {
        f64::from_bits(a.to_bits() + 1) - a
    }
}
