//! The step loop every model runs, planar or spatial: clr-ode one accepted step at a time,
//! the recorder, impacts, contact-memory commits, located onsets that restart the integrator,
//! progress, and the partial results of a run that stops early.
//!
//! After each accepted step, in this order (the order is part of the results):
//! 1. output times inside the step are recorded from the dense output, before the solver's
//!    order or step change invalidates the interpolant, with the memory the step used;
//! 2. impacts are located on the same dense output ([`ImpactTracker`]), still before the commit;
//! 3. the contact memory is committed (clr-contact memory rule 1);
//! 4. the model watches the step ([`Engine::watch`]: guide exits, a ball through its socket);
//! 5. the constraint violation is taken, onsets counted;
//! 6. the model's own step end ([`Engine::step_end`]: LuGre bristle resets, projection), which
//!    may ask for a restart, as a located onset does.
//!
//! What differs between the spaces (the integrand, what is recorded, what is watched) is the
//! [`Engine`] a model implements; the loop itself is written once, here.

use clr_ode::StopReason;
use clr_ode::{Control, Dopri5, Ndf, Observer, OdeError, OdeSystem, Options, Output, Stats};

use crate::error::MbdError;
use crate::impacts::{ContactProbe, ImpactTracker};
use crate::options::{SimOptions, SolverKind};
use crate::results::Results;

/// An observer that hands control back after every accepted step.
pub(crate) struct StopEachStep;

impl Observer for StopEachStep {
    fn observe(&mut self, _t: f64, _y: &[f64]) -> Control {
        Control::Stop
    }
}

/// The integrator chosen by [`SolverKind`].
pub(crate) enum AnySolver {
    Ndf(Box<Ndf>),
    Dopri5(Box<Dopri5>),
}

impl AnySolver {
    /// The integrator of `opts` with the clr-ode options every model uses (tolerances, step
    /// bounds, order, output times); `tune` adds the model's own.
    pub(crate) fn new(opts: &SimOptions, tune: impl FnOnce(Options) -> Options) -> Self {
        let ode = tune(
            Options::default()
                .rtol(opts.rtol)
                .atol(opts.atol)
                .h_max(opts.h_max)
                .max_steps(opts.max_steps)
                .max_order(opts.max_order)
                .newton_rate_reuse(opts.newton_rate_reuse)
                .output(Output::Times(opts.times.clone())),
        );
        match opts.solver {
            SolverKind::Ndf => AnySolver::Ndf(Box::new(Ndf::new(ode))),
            SolverKind::Dopri5 => AnySolver::Dopri5(Box::new(Dopri5::new(ode))),
        }
    }
}

/// Check the span, output times and order of `opts` for a state of `dim` components
/// (`expected` says what the model's state holds).
pub(crate) fn check_options(
    opts: &SimOptions,
    y0_len: usize,
    dim: usize,
    expected: impl FnOnce() -> String,
) -> Result<(), MbdError> {
    if opts.t_end <= opts.t0 || !opts.t0.is_finite() || !opts.t_end.is_finite() {
        return Err(MbdError::Options(format!(
            "t_end = {} must be finite and after t0 = {}",
            opts.t_end, opts.t0
        )));
    }
    if opts.times.windows(2).any(|w| w[1] < w[0])
        || opts.times.iter().any(|&t| t < opts.t0 || t > opts.t_end)
    {
        return Err(MbdError::Options(
            "output times must be increasing and inside [t0, t_end]".into(),
        ));
    }
    if y0_len != dim {
        return Err(MbdError::Options(format!(
            "the initial state has {y0_len} components; the model needs {}",
            expected()
        )));
    }
    if !(1..=5).contains(&opts.max_order) {
        return Err(MbdError::Options(format!(
            "max_order = {} must be 1 to 5 (the NDF orders)",
            opts.max_order
        )));
    }
    Ok(())
}

macro_rules! with_solver {
    ($s:expr, $v:ident => $body:expr) => {
        match $s {
            AnySolver::Ndf($v) => $body,
            AnySolver::Dopri5($v) => $body,
        }
    };
}

/// What a model gives the shared step loop ([`drive`]).
pub(crate) trait Engine: ContactProbe + Sized {
    /// The run's workspace besides the model (the planar Newton workspace; none in space).
    type Ws;
    /// The integrand the solver sees, borrowing the model and its workspace.
    type Sys<'a>: OdeSystem
    where
        Self: 'a;
    /// What the model watches over a run besides the shared counters.
    type Watch;

    /// The integrand for one call into the solver.
    fn system<'a>(&'a mut self, ws: &'a mut Self::Ws) -> Self::Sys<'a>;
    /// Forget the contact memory (before the first step).
    fn reset_memory(&mut self);
    /// Commit the contact memory at an accepted state.
    fn commit_contacts(&mut self, y: &[f64]);
    /// Evaluate everything at (t, y) and append one output row.
    fn record(&mut self, t: f64, y: &[f64], out: &mut Vec<f64>);
    /// The output column names.
    fn columns(&self) -> Vec<String>;
    /// The units of the columns whose suffix does not say them ([`Results::units`]).
    fn units(&self) -> Vec<(String, &'static str)> {
        Vec::new()
    }
    /// The largest position constraint violation at (t, y), m or rad.
    fn violation(&mut self, t: f64, y: &[f64]) -> f64;
    /// Watch an accepted step right after the commit; an error stops the run.
    fn watch(&mut self, watch: &mut Self::Watch, t: f64, y: &[f64]) -> Result<(), Stop>;
    /// The model's own work at the end of a step (`onset`: the joint whose contact closed, if a
    /// located onset ended it; `violation` the position violation): changes y in place and says
    /// whether the integrator must restart.
    fn step_end(
        &mut self,
        t: f64,
        y: &mut [f64],
        onset: Option<usize>,
        violation: f64,
        opts: &SimOptions,
    ) -> Result<StepEnd, Stop>;
    /// Notes from what was watched, for the results.
    fn watch_notes(&self, watch: &Self::Watch) -> Vec<String>;
    /// Why the integrator failed at (t, y), in words (may be empty).
    fn failure_cause(&mut self, t: f64, y: &[f64]) -> String;
}

/// What [`Engine::step_end`] did.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct StepEnd {
    /// The state changed: restart the integrator from it.
    pub(crate) restart: bool,
    /// The state was projected onto the constraint manifold.
    pub(crate) projected: bool,
}

/// Why the step loop stopped early.
pub(crate) enum Stop {
    /// The integrator failed.
    Ode(OdeError),
    /// A clr-mbd step failed (projection); returned as it is.
    Mbd(MbdError),
    /// The state is not physics any more (the message says why): the run stops with
    /// [`MbdError::Stopped`] and the rows so far.
    Unphysical(String),
}

impl From<OdeError> for Stop {
    fn from(e: OdeError) -> Self {
        Stop::Ode(e)
    }
}

impl From<MbdError> for Stop {
    fn from(e: MbdError) -> Self {
        Stop::Mbd(e)
    }
}

/// What a run has computed so far: what an error keeps.
struct Run<W> {
    /// Recorded rows, row-major.
    data: Vec<f64>,
    /// Current state.
    y: Vec<f64>,
    /// Output times of the solver already recorded.
    recorded: usize,
    onsets: usize,
    projections: usize,
    max_viol: f64,
    /// Impacts of the clearance joints located so far.
    impacts: ImpactTracker,
    watch: W,
}

impl<W> Run<W> {
    fn results<E: Engine<Watch = W>>(&mut self, model: &E, stats: Stats) -> Results {
        Results {
            notes: model.watch_notes(&self.watch),
            columns: model.columns(),
            data: std::mem::take(&mut self.data),
            stats,
            onsets: self.onsets,
            projections: self.projections,
            max_position_violation: self.max_viol,
            y_final: self.y.clone(),
            impacts: std::mem::replace(&mut self.impacts, ImpactTracker::empty()).into_impacts(),
            initial_conditions: None,
            warnings: Vec::new(),
            units: model.units(),
        }
    }
}

/// Integrate `model` from y0 over [`SimOptions::t0`, `SimOptions::t_end`] with `solver`,
/// calling `progress(t)` about every 1 % of the span and at the end.
///
/// # Errors
/// [`MbdError::Failed`] with the partial results when the integrator fails,
/// [`MbdError::Stopped`] with them when the model stops the run, and the model's own
/// errors as they are.
pub(crate) fn drive<E: Engine>(
    model: &mut E,
    opts: &SimOptions,
    y0: &[f64],
    (solver, ws): (&mut AnySolver, &mut E::Ws),
    watch: E::Watch,
    progress: &dyn Fn(f64),
) -> Result<Results, MbdError> {
    let mut run = Run::new(model, opts.t0, y0, watch);
    let out = step_loop(model, opts, (solver, ws), &mut run, progress);
    match out {
        Ok(()) => {
            let stats = with_solver!(&*solver, s => s.stats());
            Ok(run.results(model, stats))
        }
        Err(stop) => Err(run.error(model, solver, stop)),
    }
}

impl<W> Run<W> {
    fn new<E: Engine<Watch = W>>(model: &mut E, t0: f64, y0: &[f64], watch: W) -> Self {
        Run {
            data: Vec::new(),
            y: y0.to_vec(),
            recorded: 0,
            onsets: 0,
            projections: 0,
            max_viol: 0.0,
            impacts: ImpactTracker::new(model, t0, y0),
            watch,
        }
    }

    /// The error of a run that `stop` ended, keeping what was computed.
    fn error<E: Engine<Watch = W>>(
        &mut self,
        model: &mut E,
        solver: &AnySolver,
        stop: Stop,
    ) -> MbdError {
        let stats = with_solver!(solver, s => s.stats());
        match stop {
            Stop::Mbd(e) => e,
            Stop::Unphysical(reason) => MbdError::Stopped {
                reason,
                partial: Box::new(self.results(model, stats)),
            },
            Stop::Ode(e) => {
                // rows the solver interpolated but the loop has not recorded yet (none in
                // practice: a failing advance records nothing), then the counters up to the
                // failure: a failed advance hands its statistics over with the error, a failed
                // restart leaves them in the solver
                let sol = e.solution();
                for k in self.recorded..sol.len() {
                    model.record(sol.t[k], sol.state(k), &mut self.data);
                }
                let stats = if sol.stats == Stats::default() {
                    stats
                } else {
                    sol.stats
                };
                if sol.y_final.len() == self.y.len() {
                    self.y.copy_from_slice(&sol.y_final);
                }
                let cause = model.failure_cause(sol.t_final, self.y.as_slice());
                MbdError::Failed {
                    partial: Box::new(self.results(model, stats)),
                    source: e,
                    cause,
                }
            }
        }
    }
}

/// A run advanced by its caller from one communication point to the next (co-simulation):
/// the solver's end moves to each point ([`clr_ode::Solver::extend_to`]) and the history is
/// kept, so between points the integrator runs as in one run, with located onsets and
/// restarts inside a step; it restarts at a point only when asked ([`Stepping::restart_at`]).
pub(crate) struct Stepping<E: Engine> {
    solver: AnySolver,
    ws: E::Ws,
    run: Run<E::Watch>,
    y_out: Vec<f64>,
    t: f64,
    started: bool,
    restart: bool,
}

impl<E: Engine> Stepping<E> {
    /// Ready to step `model` from (t0, y0) with `solver` (output times unused).
    pub(crate) fn new(
        model: &mut E,
        (t0, y0): (f64, &[f64]),
        (solver, ws): (AnySolver, E::Ws),
        watch: E::Watch,
    ) -> Self {
        let run = Run::new(model, t0, y0, watch);
        model.reset_memory();
        model.commit_contacts(y0);
        Stepping {
            solver,
            ws,
            y_out: vec![0.0; y0.len()],
            run,
            t: t0,
            started: false,
            restart: false,
        }
    }

    /// The current time, s, and state.
    pub(crate) fn state(&self) -> (f64, &[f64]) {
        (self.t, &self.run.y)
    }

    /// Integrator statistics so far.
    pub(crate) fn stats(&self) -> Stats {
        with_solver!(&self.solver, s => s.stats())
    }

    /// Continue from (t, y) with a fresh history at the next advance (an input jumped, a saved
    /// state was restored); the contact memory restarts from y.
    pub(crate) fn restart_at(&mut self, model: &mut E, t: f64, y: &[f64]) {
        self.t = t;
        self.run.y.copy_from_slice(y);
        model.reset_memory();
        model.commit_contacts(y);
        self.run.impacts = ImpactTracker::new(model, t, y);
        self.restart = true;
    }

    /// Integrate to `tc` (s; nothing to do when tc ≤ t). The last step ends exactly at tc.
    ///
    /// # Errors
    /// As [`drive`]: the error keeps the counters (the partial results hold no rows: a
    /// stepped run records none).
    pub(crate) fn advance_to(
        &mut self,
        model: &mut E,
        opts: &SimOptions,
        tc: f64,
    ) -> Result<(), MbdError> {
        if tc <= self.t {
            return Ok(());
        }
        match self.advance_inner(model, opts, tc) {
            Ok(()) => Ok(()),
            Err(stop) => Err(self.run.error(model, &self.solver, stop)),
        }
    }

    fn advance_inner(&mut self, model: &mut E, opts: &SimOptions, tc: f64) -> Result<(), Stop> {
        let (solver, ws) = (&mut self.solver, &mut self.ws);
        if !self.started {
            with_solver!(&mut *solver, s => s.start(&mut model.system(ws), self.t, &self.run.y, tc))?;
            self.started = true;
        } else {
            with_solver!(&mut *solver, s => s.extend_to(tc))?;
            if self.restart {
                with_solver!(&mut *solver, s => s.restart(&mut model.system(ws), self.t, &self.run.y))?;
            }
        }
        self.restart = false;
        loop {
            let reason = with_solver!(&mut *solver, s => s.advance_observed(
                &mut model.system(ws), &mut StopEachStep))?;
            let (t, restart) =
                after_step(model, opts, solver, &mut self.run, &mut self.y_out, reason)?;
            self.t = t;
            if t >= tc {
                // the restart a step end asks for happens at the next advance, from the state
                // the caller may still change
                self.restart = restart;
                return Ok(());
            }
            if restart {
                with_solver!(&mut *solver, s => s.restart(&mut model.system(ws), t, &self.run.y))?;
            }
        }
    }
}

/// The step loop of [`drive`]: records into `run`, which keeps what was computed when an error
/// stops it.
fn step_loop<E: Engine>(
    model: &mut E,
    opts: &SimOptions,
    (solver, ws): (&mut AnySolver, &mut E::Ws),
    run: &mut Run<E::Watch>,
    progress: &dyn Fn(f64),
) -> Result<(), Stop> {
    let mut y_out = vec![0.0; run.y.len()];
    let report_every = 0.01 * (opts.t_end - opts.t0);
    let mut last_report = opts.t0;
    model.reset_memory();
    model.commit_contacts(&run.y);
    with_solver!(&mut *solver, s => s.start(&mut model.system(ws), opts.t0, &run.y, opts.t_end))?;
    // outputs at t0 were recorded by the solver's start
    run.recorded = with_solver!(&*solver, s => s.solution().t.len());
    for _ in 0..run.recorded {
        model.record(opts.t0, &run.y, &mut run.data);
    }
    if opts.every_step && run.recorded == 0 {
        model.record(opts.t0, &run.y, &mut run.data);
    }
    loop {
        let reason = with_solver!(&mut *solver, s => s.advance_observed(
            &mut model.system(ws), &mut StopEachStep))?;
        let (t, restart) = after_step(model, opts, solver, run, &mut y_out, reason)?;
        let done = reason == StopReason::EndReached || t >= opts.t_end;
        if (done && t > last_report) || t - last_report >= report_every {
            progress(t);
            last_report = t;
        }
        if done {
            return Ok(());
        }
        if restart {
            with_solver!(&mut *solver, s => s.restart(&mut model.system(ws), t, &run.y))?;
        }
    }
}

/// The work after one accepted step of the solver (the module's list, 1 to 6), on `run`:
/// returns the step's end time and whether the integrator must restart from `run.y` (a located
/// onset, or the model's own step end changed the state). `y_out` is scratch of the state's
/// length.
fn after_step<E: Engine>(
    model: &mut E,
    opts: &SimOptions,
    solver: &AnySolver,
    run: &mut Run<E::Watch>,
    y_out: &mut [f64],
    reason: StopReason,
) -> Result<(f64, bool), Stop> {
    let t = with_solver!(solver, s => s.solution().t_final);
    run.y
        .copy_from_slice(with_solver!(solver, s => &s.solution().y_final));
    let n_out = with_solver!(solver, s => s.solution().t.len());
    while run.recorded < n_out {
        let to = with_solver!(solver, s => s.solution().t[run.recorded]);
        y_out.copy_from_slice(with_solver!(solver, s => s.solution().state(run.recorded)));
        model.record(to, y_out, &mut run.data);
        run.recorded += 1;
    }
    let interp = |tp: f64, out: &mut [f64]| with_solver!(solver, s => s.interpolate(tp, out));
    run.impacts.step(model, (t, &run.y), &interp, y_out);
    model.commit_contacts(&run.y);
    model.watch(&mut run.watch, t, &run.y)?;
    let pv = model.violation(t, &run.y);
    run.max_viol = run.max_viol.max(pv);
    let onset = match reason {
        StopReason::TerminalEvent(e) => Some(e),
        _ => None,
    };
    if onset.is_some() {
        run.onsets += 1;
    }
    let end = model.step_end(t, &mut run.y, onset, pv, opts)?;
    run.projections += usize::from(end.projected);
    if opts.every_step {
        model.record(t, &run.y, &mut run.data);
    }
    Ok((t, onset.is_some() || end.restart))
}
