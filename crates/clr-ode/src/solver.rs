//! The driver shared by both methods: input validation, output recording, event location on
//! the dense output, observers, step budget and restarts.

use crate::options::{Atol, Options, Output};
use crate::solution::{EventRecord, OdeError, Solution, Stats, StopReason};
use crate::system::{Direction, OdeSystem};

/// What an observer tells the solver after an accepted step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    /// Go on.
    Continue,
    /// Stop the run now ([`StopReason::Observer`]).
    Stop,
}

/// A callback on each accepted step: `observe(t, y)` with the state at the end of the step
/// (or at a terminal event).
pub trait Observer {
    /// Called after each accepted step.
    fn observe(&mut self, t: f64, y: &[f64]) -> Control;
}

impl<F: FnMut(f64, &[f64]) -> Control> Observer for F {
    fn observe(&mut self, t: f64, y: &[f64]) -> Control {
        self(t, y)
    }
}

/// The observer that never stops a run.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoObserver;

impl Observer for NoObserver {
    #[inline]
    fn observe(&mut self, _t: f64, _y: &[f64]) -> Control {
        Control::Continue
    }
}

/// The settings and counters a method sees during a step.
pub struct Ctx<'a> {
    /// Options of the run.
    pub opts: &'a Options,
    /// Relative tolerance (clamped to ≥ 100 ε).
    pub rtol: f64,
    /// Absolute tolerance per component.
    pub atol: &'a [f64],
    /// Counters.
    pub stats: &'a mut Stats,
}

/// Why a method could not complete a step (turned into an [`OdeError`] by the driver).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Failure {
    /// Step below the floor.
    Underflow {
        /// Time.
        t: f64,
        /// Step size.
        h: f64,
        /// Floor.
        h_min: f64,
    },
    /// Newton failed too often in one step.
    Newton {
        /// Time.
        t: f64,
        /// Step size.
        h: f64,
        /// Failures.
        failures: usize,
    },
    /// f non-finite.
    NonFiniteRhs {
        /// Time.
        t: f64,
    },
    /// Jacobian non-finite.
    NonFiniteJacobian {
        /// Time.
        t: f64,
    },
}

/// A one-step method driven by [`Solver`]: [`crate::ndf::NdfMethod`] or
/// [`crate::dopri5::Dopri5Method`]. It owns its buffers and never allocates in `step`.
pub trait Method: Default {
    /// Whether the method handles a mass matrix M ≠ I.
    const SUPPORTS_MASS: bool;
    /// Whether the method is meant for stiff problems (its failures do not suggest it again).
    const STIFF: bool;
    /// Size the buffers for dimension n (allocates only when n changes).
    fn resize(&mut self, n: usize);
    /// Total capacity of the buffers (to check that restarts do not reallocate).
    fn capacity(&self) -> usize;
    /// Begin (or restart) at (t, y) with an empty history.
    fn init<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        ctx: &mut Ctx,
        t: f64,
        y: &[f64],
        t_end: f64,
    ) -> Result<(), Failure>;
    /// Take one accepted step, not beyond `t_end`.
    fn step<S: OdeSystem>(&mut self, sys: &mut S, ctx: &mut Ctx, t_end: f64)
        -> Result<(), Failure>;
    /// Start of the last accepted step.
    fn t_old(&self) -> f64;
    /// Current time.
    fn t(&self) -> f64;
    /// Current state.
    fn y(&self) -> &[f64];
    /// Dense output on the last accepted step [t_old, t].
    fn interpolate(&self, t: f64, out: &mut [f64]);
    /// Work after output and events of a step (NDF: order and step-size change).
    fn finish_step(&mut self, ctx: &mut Ctx);
}

/// RMS norm of x_i / s_i.
#[inline]
pub(crate) fn rms_scaled(x: &[f64], s: &[f64]) -> f64 {
    let mut acc = 0.0;
    for (a, b) in x.iter().zip(s) {
        let v = a / b;
        acc += v * v;
    }
    (acc / x.len() as f64).sqrt()
}

/// Automatic initial step (Hairer, Nørsett & Wanner, Solving ODEs I, 2nd ed., §II.4, p. 169;
/// the same algorithm as SciPy's `select_initial_step`): h0 from ‖y0‖/‖y0'‖, then
/// h1 = (0.01 / max(‖y0'‖, ‖y''‖))^(1/(order+1)), result min(100 h0, h1, h_max, t_end − t0).
/// `slope(t, y, yp)` evaluates y'; `work` needs 3n entries.
#[allow(clippy::too_many_arguments)]
pub(crate) fn initial_step(
    mut slope: impl FnMut(f64, &[f64], &mut [f64]) -> bool,
    t0: f64,
    y0: &[f64],
    yp0: &[f64],
    order: usize,
    rtol: f64,
    atol: &[f64],
    h_max: f64,
    t_end: f64,
    work: &mut [f64],
) -> f64 {
    let n = y0.len();
    let (scale, rest) = work.split_at_mut(n);
    let (y1, yp1) = rest.split_at_mut(n);
    for i in 0..n {
        scale[i] = atol[i] + rtol * y0[i].abs();
    }
    let d0 = rms_scaled(y0, scale);
    let d1 = rms_scaled(yp0, scale);
    let span = t_end - t0;
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    }
    .min(span)
    .min(h_max);
    for i in 0..n {
        y1[i] = y0[i] + h0 * yp0[i];
    }
    if !slope(t0 + h0, y1, yp1) {
        return h0.min(1e-6 * span);
    }
    for i in 0..n {
        yp1[i] -= yp0[i];
    }
    let d2 = rms_scaled(yp1, scale) / h0;
    let h1 = if d1 <= 1e-15 && d2 <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(1.0 / (order as f64 + 1.0))
    };
    (100.0 * h0).min(h1).min(h_max).min(span)
}

/// An integrator: a [`Method`] plus the driver. Use the aliases [`crate::Ndf`] and
/// [`crate::Dopri5`].
///
/// Two ways to run it: [`Solver::solve`] (start and run to the end or the first terminal event),
/// or the stepping interface [`Solver::start`] → [`Solver::advance`] → (change the model) →
/// [`Solver::restart`] → [`Solver::advance`] …, which reuses every buffer.
pub struct Solver<M> {
    opts: Options,
    method: M,
    n: usize,
    rtol: f64,
    atol: Vec<f64>,
    t_end: f64,
    n_ev: usize,
    ev_dir: Vec<Direction>,
    ev_term: Vec<bool>,
    g_old: Vec<f64>,
    g_new: Vec<f64>,
    g_tmp: Vec<f64>,
    y_tmp: Vec<f64>,
    found: Vec<(f64, usize)>,
    next_out: usize,
    solution: Solution,
    started: bool,
    finished: bool,
}

fn nonneg_finite(x: f64) -> bool {
    x.is_finite() && x >= 0.0
}

pub(crate) fn invalid(what: impl Into<String>) -> OdeError {
    OdeError::InvalidInput {
        what: what.into(),
        solution: Box::default(),
    }
}

impl<M: Method> Solver<M> {
    /// A solver with these options (nothing is allocated until the first start).
    pub fn new(opts: Options) -> Self {
        Solver {
            opts,
            method: M::default(),
            n: 0,
            rtol: 0.0,
            atol: Vec::new(),
            t_end: 0.0,
            n_ev: 0,
            ev_dir: Vec::new(),
            ev_term: Vec::new(),
            g_old: Vec::new(),
            g_new: Vec::new(),
            g_tmp: Vec::new(),
            y_tmp: Vec::new(),
            found: Vec::new(),
            next_out: 0,
            solution: Solution::default(),
            started: false,
            finished: false,
        }
    }

    /// The options.
    pub fn options(&self) -> &Options {
        &self.opts
    }

    /// Replace the options (takes effect at the next start).
    pub fn set_options(&mut self, opts: Options) {
        self.opts = opts;
    }

    /// Integrate from (t0, y0) to t_end, or to the first terminal event or observer stop.
    pub fn solve<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        t0: f64,
        y0: &[f64],
        t_end: f64,
    ) -> Result<Solution, OdeError> {
        self.solve_observed(sys, t0, y0, t_end, &mut NoObserver)
    }

    /// As [`Solver::solve`], calling `observer` after each accepted step.
    pub fn solve_observed<S: OdeSystem, O: Observer>(
        &mut self,
        sys: &mut S,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        observer: &mut O,
    ) -> Result<Solution, OdeError> {
        self.start(sys, t0, y0, t_end)?;
        self.advance_observed(sys, observer)?;
        Ok(self.take_solution())
    }

    fn validate<S: OdeSystem>(
        &self,
        sys: &S,
        t0: f64,
        y0: &[f64],
        t_end: f64,
    ) -> Result<(), OdeError> {
        let n = sys.dim();
        let o = &self.opts;
        if n == 0 {
            return Err(invalid(
                "the state is empty (dim() = 0): give at least one component",
            ));
        }
        if y0.len() != n {
            return Err(invalid(format!(
                "the initial state has {} components but the system has dim() = {n}",
                y0.len()
            )));
        }
        if !t0.is_finite() || !t_end.is_finite() {
            return Err(invalid("t0 and t_end must be finite"));
        }
        if t_end <= t0 {
            return Err(invalid(format!(
                "t_end = {t_end} is not after t0 = {t0}: integrate forward with t_end > t0"
            )));
        }
        if let Some(i) = y0.iter().position(|v| !v.is_finite()) {
            return Err(invalid(format!(
                "initial state component {i} is not finite"
            )));
        }
        if !nonneg_finite(o.rtol) {
            return Err(invalid(format!(
                "rtol = {} must be finite and non-negative",
                o.rtol
            )));
        }
        match &o.atol {
            Atol::Scalar(a) if !nonneg_finite(*a) => {
                return Err(invalid(format!(
                    "atol = {a} must be finite and non-negative"
                )))
            }
            Atol::Vector(v) if v.len() != n => {
                return Err(invalid(format!(
                    "atol has {} components but the system has dim() = {n}",
                    v.len()
                )))
            }
            Atol::Vector(v) => {
                if let Some(i) = v.iter().position(|a| !nonneg_finite(*a)) {
                    return Err(invalid(format!(
                        "atol[{i}] = {} must be finite and non-negative",
                        v[i]
                    )));
                }
            }
            _ => {}
        }
        if let Some(h0) = o.h0 {
            if !(h0.is_finite() && h0 > 0.0) {
                return Err(invalid(format!("h0 = {h0} must be positive and finite")));
            }
        }
        if o.fixed_step && o.h0.is_none() {
            return Err(invalid("fixed_step needs the step size h0"));
        }
        if o.h_max.is_nan() || o.h_max <= 0.0 {
            return Err(invalid(format!("h_max = {} must be positive", o.h_max)));
        }
        if !nonneg_finite(o.h_min) || o.h_min >= o.h_max {
            return Err(invalid(format!(
                "h_min = {} must be non-negative and below h_max = {}",
                o.h_min, o.h_max
            )));
        }
        if !(1..=5).contains(&o.max_order) {
            return Err(invalid(format!(
                "max_order = {} must be between 1 and 5",
                o.max_order
            )));
        }
        if let Some(r) = &o.h_scaled_error {
            if r.start >= r.end || r.end > n {
                return Err(invalid(format!(
                    "h_scaled_error = {}..{} must be a non-empty range within 0..{n}",
                    r.start, r.end
                )));
            }
        }
        if o.max_steps == 0 {
            return Err(invalid("max_steps must be at least 1"));
        }
        if let Output::Times(ts) = &o.output {
            if ts.windows(2).any(|w| w[1].is_nan() || w[1] < w[0]) {
                return Err(invalid("output times must be increasing"));
            }
            if ts.iter().any(|&t| !(t0..=t_end).contains(&t)) {
                return Err(invalid(format!(
                    "output times must lie within [t0, t_end] = [{t0}, {t_end}]"
                )));
            }
        }
        if !M::SUPPORTS_MASS && sys.mass_kind() != crate::system::MassKind::Identity {
            return Err(invalid(
                "this solver integrates explicit ODEs y' = f only; use Ndf for a mass matrix or a DAE",
            ));
        }
        sys.validate().map_err(invalid)
    }

    /// Begin a run at (t0, y0) towards t_end: validates the input, sizes the buffers (allocating
    /// only if the dimension grew) and clears the recorded solution.
    pub fn start<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        t0: f64,
        y0: &[f64],
        t_end: f64,
    ) -> Result<(), OdeError> {
        self.started = false;
        self.validate(sys, t0, y0, t_end)?;
        let n = sys.dim();
        self.n = n;
        self.t_end = t_end;
        self.rtol = self.opts.rtol.max(100.0 * f64::EPSILON);
        self.atol.clear();
        match &self.opts.atol {
            Atol::Scalar(a) => self.atol.resize(n, *a),
            Atol::Vector(v) => self.atol.extend_from_slice(v),
        }
        self.n_ev = sys.n_events();
        self.ev_dir.clear();
        self.ev_term.clear();
        for i in 0..self.n_ev {
            self.ev_dir.push(sys.event_direction(i));
            self.ev_term.push(sys.event_terminal(i));
        }
        self.g_old.resize(self.n_ev, 0.0);
        self.g_new.resize(self.n_ev, 0.0);
        self.g_tmp.resize(self.n_ev, 0.0);
        self.found.clear();
        self.found.reserve(self.n_ev);
        self.y_tmp.resize(n, 0.0);
        self.method.resize(n);
        self.solution.reset(n);
        self.next_out = 0;
        self.started = true;
        self.restart(sys, t0, y0)
    }

    /// Continue from (t, y) with the history reset (after a discontinuity, e.g. a contact
    /// switch at a terminal event): same t_end, options, output and statistics; no buffer is
    /// reallocated. With `Output::Steps`, (t, y) is recorded, so a jump shows as two states at
    /// the same time.
    pub fn restart<S: OdeSystem>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
    ) -> Result<(), OdeError> {
        if !self.started {
            return Err(invalid("restart before start: call start (or solve) first"));
        }
        if y.len() != self.n {
            return Err(invalid(format!(
                "the restart state has {} components but the system has dim() = {}",
                y.len(),
                self.n
            )));
        }
        if !t.is_finite() || t > self.t_end {
            return Err(invalid(format!(
                "restart time {t} must be finite and not after t_end = {}",
                self.t_end
            )));
        }
        if let Some(i) = y.iter().position(|v| !v.is_finite()) {
            return Err(invalid(format!(
                "restart state component {i} is not finite"
            )));
        }
        self.finished = t >= self.t_end;
        self.solution.stop = StopReason::Running;
        if !self.finished {
            let mut ctx = Ctx {
                opts: &self.opts,
                rtol: self.rtol,
                atol: &self.atol,
                stats: &mut self.solution.stats,
            };
            if let Err(f) = self.method.init(sys, &mut ctx, t, y, self.t_end) {
                return Err(self.fail(f));
            }
        }
        if self.n_ev > 0 {
            sys.events(t, y, &mut self.g_old);
        }
        match &self.opts.output {
            Output::Steps => self.solution.push(t, y),
            Output::Times(ts) => {
                while self.next_out < ts.len() && ts[self.next_out] <= t {
                    if ts[self.next_out] == t {
                        self.solution.push(t, y);
                    }
                    self.next_out += 1;
                }
            }
            Output::End => {}
        }
        self.set_final(t, y);
        if self.finished {
            self.solution.stop = StopReason::EndReached;
        }
        Ok(())
    }

    fn set_final(&mut self, t: f64, y: &[f64]) {
        self.solution.t_final = t;
        self.solution.y_final.clear();
        self.solution.y_final.extend_from_slice(y);
    }

    fn take_partial(&mut self) -> Box<Solution> {
        let (t, y) = (self.method.t(), self.method.y());
        self.solution.t_final = t;
        self.solution.y_final.clear();
        self.solution.y_final.extend_from_slice(y);
        self.solution.stop = StopReason::Running;
        self.finished = true;
        Box::new(std::mem::take(&mut self.solution))
    }

    fn fail(&mut self, f: Failure) -> OdeError {
        let solution = self.take_partial();
        match f {
            Failure::Underflow { t, h, h_min } => OdeError::StepSizeUnderflow {
                stiff: M::STIFF,
                t,
                h,
                h_min,
                solution,
            },
            Failure::Newton { t, h, failures } => OdeError::NewtonFailure {
                t,
                h,
                failures,
                solution,
            },
            Failure::NonFiniteRhs { t } => OdeError::NonFiniteRhs { t, solution },
            Failure::NonFiniteJacobian { t } => OdeError::NonFiniteJacobian { t, solution },
        }
    }

    /// Integrate until t_end or a terminal event.
    pub fn advance<S: OdeSystem>(&mut self, sys: &mut S) -> Result<StopReason, OdeError> {
        self.advance_observed(sys, &mut NoObserver)
    }

    /// Integrate until t_end, a terminal event, or the observer's stop. After a terminal event
    /// the method stands at the end of the step that crossed it: call [`Solver::restart`] with
    /// the (possibly changed) event state, or `advance` again to go on as if nothing happened.
    pub fn advance_observed<S: OdeSystem, O: Observer>(
        &mut self,
        sys: &mut S,
        observer: &mut O,
    ) -> Result<StopReason, OdeError> {
        if !self.started {
            return Err(invalid("advance before start: call start (or solve) first"));
        }
        if self.finished {
            // t_end was reached (possibly in a step that also stopped for an event or the
            // observer): nothing is left to integrate
            self.solution.stop = StopReason::EndReached;
            return Ok(StopReason::EndReached);
        }
        let n = self.n;
        loop {
            if self.solution.stats.accepted >= self.opts.max_steps {
                let t = self.method.t();
                return Err(OdeError::StepBudget {
                    stiff: M::STIFF,
                    t,
                    max_steps: self.opts.max_steps,
                    solution: self.take_partial(),
                });
            }
            {
                let mut ctx = Ctx {
                    opts: &self.opts,
                    rtol: self.rtol,
                    atol: &self.atol,
                    stats: &mut self.solution.stats,
                };
                if let Err(f) = self.method.step(sys, &mut ctx, self.t_end) {
                    return Err(self.fail(f));
                }
                ctx.stats.accepted += 1;
            }
            let t_old = self.method.t_old();
            let t_new = self.method.t();
            // events
            let mut terminal: Option<(f64, usize)> = None;
            if self.n_ev > 0 {
                sys.events(t_new, self.method.y(), &mut self.g_new);
                self.found.clear();
                for i in 0..self.n_ev {
                    if self.ev_dir[i].triggered(self.g_old[i], self.g_new[i]) {
                        let te = locate_root(
                            sys,
                            &self.method,
                            i,
                            (t_old, self.g_old[i]),
                            (t_new, self.g_new[i]),
                            &mut self.y_tmp,
                            &mut self.g_tmp,
                        );
                        self.found.push((te, i));
                    }
                }
                self.found
                    .sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                for k in 0..self.found.len() {
                    let (te, i) = self.found[k];
                    let mut ye = vec![0.0; n];
                    if te == t_new {
                        ye.copy_from_slice(self.method.y());
                    } else {
                        self.method.interpolate(te, &mut ye);
                    }
                    self.solution.events.push(EventRecord {
                        t: te,
                        y: ye,
                        index: i,
                    });
                    self.solution.stats.events += 1;
                    if self.ev_term[i] {
                        terminal = Some((te, i));
                        break;
                    }
                }
            }
            let t_stop = terminal.map_or(t_new, |(te, _)| te);
            if let (Some(_), Some(ev)) = (terminal, self.solution.events.last()) {
                self.y_tmp.copy_from_slice(&ev.y);
            } else {
                self.y_tmp.copy_from_slice(self.method.y());
            }
            // output
            match &self.opts.output {
                Output::Steps => self.solution.push(t_stop, &self.y_tmp),
                Output::Times(ts) => {
                    while self.next_out < ts.len() && ts[self.next_out] <= t_stop {
                        let to = ts[self.next_out];
                        if to == t_stop {
                            self.solution.t.push(to);
                            self.solution.y.extend_from_slice(&self.y_tmp);
                        } else {
                            let k = self.solution.y.len();
                            self.solution.y.resize(k + n, 0.0);
                            self.method.interpolate(to, &mut self.solution.y[k..]);
                            self.solution.t.push(to);
                        }
                        self.next_out += 1;
                    }
                }
                Output::End => {}
            }
            let ctl = observer.observe(t_stop, &self.y_tmp);
            {
                let mut ctx = Ctx {
                    opts: &self.opts,
                    rtol: self.rtol,
                    atol: &self.atol,
                    stats: &mut self.solution.stats,
                };
                self.method.finish_step(&mut ctx);
            }
            std::mem::swap(&mut self.g_old, &mut self.g_new);
            if t_new >= self.t_end {
                self.finished = true;
            }
            let stop = if let Some((_, i)) = terminal {
                Some(StopReason::TerminalEvent(i))
            } else if ctl == Control::Stop {
                Some(StopReason::Observer)
            } else if self.finished {
                Some(StopReason::EndReached)
            } else {
                None
            };
            if let Some(reason) = stop {
                self.solution.t_final = t_stop;
                self.solution.y_final.clear();
                self.solution.y_final.extend_from_slice(&self.y_tmp);
                if self.opts.output == Output::End {
                    self.solution.t.push(t_stop);
                    self.solution.y.extend_from_slice(&self.y_tmp);
                }
                self.solution.stop = reason;
                return Ok(reason);
            }
        }
    }

    /// Current time of the method (end of the last accepted step).
    pub fn t(&self) -> f64 {
        self.method.t()
    }

    /// Current state of the method.
    pub fn y(&self) -> &[f64] {
        self.method.y()
    }

    /// The end time of the run.
    pub fn t_end(&self) -> f64 {
        self.t_end
    }

    /// Move the end of the run to `t_end` (not before the current time) and keep the history:
    /// the next [`Solver::advance`] goes on from where the last step ended, with the method's
    /// step size and order, and its steps do not pass the new end. This is how a co-simulation
    /// step advances to the next communication point without a restart.
    ///
    /// # Errors
    /// [`OdeError::InvalidInput`] before [`Solver::start`], or for a `t_end` that is not finite
    /// or lies before the current time.
    pub fn extend_to(&mut self, t_end: f64) -> Result<(), OdeError> {
        if !self.started {
            return Err(invalid(
                "extend_to before start: call start (or solve) first",
            ));
        }
        let t = self.method.t();
        if !t_end.is_finite() || t_end < t {
            return Err(invalid(format!(
                "the new end {t_end} must be finite and not before the current time {t}"
            )));
        }
        self.t_end = t_end;
        self.finished = t >= t_end;
        Ok(())
    }

    /// The solution recorded so far.
    pub fn solution(&self) -> &Solution {
        &self.solution
    }

    /// Move the recorded solution out (the solver keeps an empty one).
    pub fn take_solution(&mut self) -> Solution {
        std::mem::take(&mut self.solution)
    }

    /// Statistics so far.
    pub fn stats(&self) -> Stats {
        self.solution.stats
    }

    /// Dense output on the last accepted step (valid for t in [t_old, t]).
    pub fn interpolate(&self, t: f64, out: &mut [f64]) {
        self.method.interpolate(t, out)
    }

    /// Total capacity of the work buffers (method and driver, not the recorded solution):
    /// unchanged by [`Solver::restart`], which reuses them.
    pub fn work_capacity(&self) -> usize {
        self.method.capacity()
            + self.atol.capacity()
            + self.g_old.capacity()
            + self.g_new.capacity()
            + self.g_tmp.capacity()
            + self.y_tmp.capacity()
            + self.found.capacity()
    }

    /// The method (for method-specific queries, e.g. the current NDF order).
    pub fn method(&self) -> &M {
        &self.method
    }

    pub(crate) fn method_mut(&mut self) -> &mut M {
        &mut self.method
    }
}

/// Locate the zero of g_i on the last step by the Illinois variant of regula falsi (Dowell &
/// Jarratt, BIT 11 (1971) 168–174) on the dense output. Returns the time on the far side of
/// the sign change, with the bracket reduced to a few ulp.
fn locate_root<S: OdeSystem, M: Method>(
    sys: &mut S,
    method: &M,
    i: usize,
    lo: (f64, f64),
    hi: (f64, f64),
    y: &mut [f64],
    g: &mut [f64],
) -> f64 {
    let (mut t_lo, mut g_lo) = lo;
    let (mut t_hi, mut g_hi) = hi;
    let mut side = 0i32;
    for _ in 0..200 {
        let tol = 4.0 * f64::EPSILON * t_lo.abs().max(t_hi.abs()) + f64::MIN_POSITIVE;
        if t_hi - t_lo <= tol {
            break;
        }
        let mut tm = if g_hi != g_lo {
            (t_lo * g_hi - t_hi * g_lo) / (g_hi - g_lo)
        } else {
            0.5 * (t_lo + t_hi)
        };
        let w = t_hi - t_lo;
        if !(tm > t_lo + 0.001 * tol && tm < t_hi - 0.001 * tol && tm.is_finite()) {
            tm = t_lo + 0.5 * w;
        }
        method.interpolate(tm, y);
        sys.events(tm, y, g);
        let gm = g[i];
        // g_lo is never zero (a step starting on g = 0 does not trigger, see Direction)
        if gm == 0.0 || (gm > 0.0) != (g_lo > 0.0) {
            // the sign change lies in [t_lo, tm]: move the far end
            t_hi = tm;
            g_hi = gm;
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        } else {
            t_lo = tm;
            g_lo = gm;
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        }
    }
    t_hi
}
