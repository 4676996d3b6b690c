//! The simulation driver and the output recorder.
//!
//! [`Model::simulate`] integrates y = (q, q̇, E_d, W_in, z) with clr-ode, one accepted step at a
//! time: after each step the contact memory is committed (clr-contact memory rule 1), requested
//! output times inside the step are recorded from the dense output, the state is optionally
//! projected onto the constraint manifold, and contact onsets located as terminal events restart
//! the solver at the onset with δ̇⁻ equal to the penetration rate there.

use clr_ode::{Control, Dopri5, Ndf, Observer, OdeSystem, Options, Output, Stats, StopReason};

use crate::error::MbdError;
use crate::guide_exit::GuideExits;
use crate::impacts::ImpactTracker;
use crate::linsys::LinearSolver;
use crate::newton::{Integrand, JacobianMode, NewtonWs};
pub use crate::results::Results;
use crate::system::Model;

/// Which clr-ode integrator to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SolverKind {
    /// Variable-order NDF (ode15s family), the default: contact stiffness makes the problem
    /// stiff.
    #[default]
    Ndf,
    /// Dormand–Prince 5(4).
    Dopri5,
}

/// What the run does with given initial coordinates that violate the constraints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InitialConditionsMode {
    /// Assemble them (Newton projection, fixed coordinates moved only where needed) and report
    /// every change in [`Results::initial_conditions`] and [`Results::notes`] (default).
    #[default]
    Assemble,
    /// Refuse to run when a given coordinate would change by more than
    /// [`CORRECTION_TOL`](crate::CORRECTION_TOL)·max(1, |value|)
    /// ([`MbdError::InconsistentInitialConditions`]); coordinates left out are still solved.
    Exact,
}

/// Settings of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct SimOptions {
    /// Start time, s.
    pub t0: f64,
    /// End time, s.
    pub t_end: f64,
    /// Integrator (default NDF).
    pub solver: SolverKind,
    /// Relative tolerance (default 1e-6).
    pub rtol: f64,
    /// Absolute tolerance (default 1e-8, units of q and q̇).
    pub atol: f64,
    /// Largest step, s (default unbounded).
    pub h_max: f64,
    /// Step budget (default 1 000 000).
    pub max_steps: usize,
    /// Output times (increasing, inside [t0, t_end]), recorded from the dense output.
    pub times: Vec<f64>,
    /// Also record the state after every accepted step (default false).
    pub every_step: bool,
    /// Project q and q̇ onto the constraints after an accepted step whenever ‖Φ‖∞ exceeds this
    /// value (m or rad); `None` (default) never projects and relies on Baumgarte terms. Each
    /// projection restarts the integrator (its history is lost), so small thresholds cost steps.
    pub projection: Option<f64>,
    /// Locate contact onsets of clearance joints as terminal events and restart there (default
    /// true).
    pub contact_events: bool,
    /// How NDF forms its Newton matrix (default [`JacobianMode::Analytic`]).
    pub jacobian: JacobianMode,
    /// Highest NDF order, 1–5 (default 5).
    pub max_order: usize,
    /// Dense or sparse factorization of the augmented and Newton matrices (default
    /// [`LinearSolver::Auto`]).
    pub linear_solver: LinearSolver,
    /// NDF only: multiply the local error estimate of the velocities q̇ by min(h, 1) (h in s)
    /// before the error test (default false), as RADAU5 does for index-2 variables: the
    /// velocities of stiff, lightly damped structural modes (fine beam meshes) then no longer
    /// pin the step at h·ω ≲ 1 (clr-ode `Options::h_scaled_error`, docs/ode.md "Undamped and
    /// lightly damped structures"). Positions stay fully error-controlled.
    pub scale_velocity_error: bool,
    /// NDF only: let Newton stop after one correction when the contraction rate measured
    /// earlier with the same factorization predicts convergence (clr-ode
    /// `Options::newton_rate_reuse`; default false). About a third fewer right-hand sides
    /// (slider–crank at rtol 1e-7: 58 → 34 ms at the same error), but the iterate it accepts is
    /// less converged: on the flap with four clearance joints at rtol 1e-8 it moved the
    /// oscillation RMS from 0.323 to 0.428 rad/s² (that case is sensitive at 1e-8; 1e-9 and
    /// 1e-10 give 0.325 and 0.326), so it is off unless asked for.
    pub newton_rate_reuse: bool,
    /// Given initial coordinates that violate the constraints: assembled and reported
    /// (default) or refused.
    pub initial_conditions: InitialConditionsMode,
    /// How the assembly of initial conditions treats clearance joints and which bodies are
    /// deliberately left free (default: ideal counterparts, none free; see
    /// [`crate::initial`]).
    pub initial_setup: crate::initial_data::InitialSetup,
    /// Turn the findings of the plausibility checks into [`MbdError::Implausible`] (default
    /// false: they are listed in [`Results::warnings`]).
    pub strict: bool,
}

impl Default for SimOptions {
    fn default() -> Self {
        Self {
            t0: 0.0,
            t_end: 1.0,
            solver: SolverKind::Ndf,
            rtol: 1e-6,
            atol: 1e-8,
            h_max: f64::INFINITY,
            max_steps: 1_000_000,
            times: Vec::new(),
            every_step: false,
            projection: None,
            contact_events: true,
            jacobian: JacobianMode::Analytic,
            max_order: 5,
            linear_solver: LinearSolver::Auto,
            scale_velocity_error: false,
            newton_rate_reuse: false,
            initial_conditions: InitialConditionsMode::Assemble,
            initial_setup: Default::default(),
            strict: false,
        }
    }
}

impl SimOptions {
    /// A run over [t0, t_end] with `n_out` + 1 equally spaced output times.
    pub fn span(t0: f64, t_end: f64, n_out: usize) -> Self {
        let n_out = n_out.max(1);
        let times = (0..=n_out)
            .map(|k| {
                if k == n_out {
                    t_end
                } else {
                    t0 + (t_end - t0) * k as f64 / n_out as f64
                }
            })
            .collect();
        Self {
            t0,
            t_end,
            times,
            ..Default::default()
        }
    }
    /// Set the solver.
    pub fn solver(mut self, s: SolverKind) -> Self {
        self.solver = s;
        self
    }
    /// Set rtol and atol.
    pub fn tolerances(mut self, rtol: f64, atol: f64) -> Self {
        self.rtol = rtol;
        self.atol = atol;
        self
    }
    /// Set the output times.
    pub fn times(mut self, times: Vec<f64>) -> Self {
        self.times = times;
        self
    }
}

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
pub(crate) use with_solver;

impl Model {
    /// The output column names (see [`Results`]).
    pub fn columns(&self) -> Vec<String> {
        let mut c = vec!["t".to_string()];
        for b in &self.body_names {
            for s in ["x", "y", "theta", "vx", "vy", "omega", "ax", "ay", "alpha"] {
                c.push(format!("{b}.{s}"));
            }
        }
        for b in &self.beams {
            c.extend(b.dof_names());
        }
        for f in &self.floating {
            c.extend(f.coord_names());
        }
        c.extend(self.node_output_columns());
        for j in self.joint_names() {
            for s in ["Fx", "Fy", "M"] {
                c.push(format!("{j}.{s}"));
            }
        }
        for cl in &self.clearances {
            for s in crate::results::CONTACT_COLUMNS.iter().chain(&["ex", "ey"]) {
                c.push(format!("{}.{s}", cl.name));
            }
            if cl.lugre.is_some() {
                c.push(format!("{}.lugre_z", cl.name));
            }
            if cl.film.is_some() {
                c.push(format!("{}.film_force", cl.name));
                c.push(format!("{}.film_thickness", cl.name));
            }
        }
        c.extend(crate::results::ENERGY_COLUMNS.map(String::from));
        c.extend(["violation.position", "violation.velocity"].map(String::from));
        c
    }

    /// The automatic choices of a run with `opts`, in words ([`Results::notes`]).
    pub(crate) fn run_notes(&self, opts: &SimOptions) -> Vec<String> {
        let mut notes = self.notes.clone();
        if opts.solver == SolverKind::Ndf
            && opts.jacobian == JacobianMode::Analytic
            && self.n_bristle_states() > 0
        {
            notes.push(format!(
                "NDF differenced the whole right-hand side for its Newton matrix (jacobian = \
                 \"finite_difference\"): the {} LuGre bristle states have no analytic Jacobian \
                 rows yet",
                self.n_bristle_states()
            ));
        }
        notes
    }

    /// The assembled initial state at `opts.t0` (with `opts.initial_setup`) as a one-row
    /// [`Results`] (the columns of a run, `initial_conditions` set), without integrating: what
    /// `clr view` draws.
    ///
    /// # Errors
    /// As [`Model::assemble_initial_state_with`].
    pub fn initial_results(&mut self, opts: &SimOptions) -> Result<Results, MbdError> {
        let t0 = opts.t0;
        let (y, ic) = self.assemble_initial_state_with(t0, &opts.initial_setup)?;
        let mut data = Vec::new();
        self.record(t0, &y, &mut data);
        Ok(Results {
            columns: self.columns(),
            data,
            initial_conditions: Some(ic),
            ..Default::default()
        })
    }

    /// Evaluate everything at (t, y) and append one output row.
    pub(crate) fn record(&mut self, t: f64, y: &[f64], out: &mut Vec<f64>) {
        let n = self.n;
        self.load_bristles(y);
        let (q, qd) = y.split_at(n);
        self.solve_accelerations(t, q, qd);
        out.push(t);
        for k in 0..self.bodies.len() {
            out.extend_from_slice(&q[3 * k..3 * k + 3]);
            out.extend_from_slice(&qd[3 * k..3 * k + 3]);
            out.extend_from_slice(&self.accelerations()[3 * k..3 * k + 3]);
        }
        for b in &self.beams {
            out.extend_from_slice(&q[b.offset..b.offset + b.n_free()]);
        }
        for f in &self.floating {
            out.extend_from_slice(&q[f.offset..f.offset + f.n_coords()]);
        }
        self.record_node_outputs(q, out);
        for s in self.joint_starts() {
            out.extend_from_slice(&self.reaction(s));
        }
        for (k, c) in self.contacts.iter().enumerate() {
            out.extend_from_slice(&[
                c.penetration,
                c.penetration_rate,
                c.normal_force,
                c.friction_force,
                c.active_points as f64,
                c.eccentricity[0],
                c.eccentricity[1],
            ]);
            if let Some(z) = self.bristle_output(k) {
                out.push(z);
            }
            if self.clearances[k].film.is_some() {
                out.extend_from_slice(&[c.film_force, c.film_thickness]);
            }
        }
        let e = self.energies(q, qd);
        let pv = self.phi.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let vv = self.phid.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let o = self.energy_offset();
        let (dissipated, work_in) = (y[o], y[o + 1]);
        out.extend_from_slice(&[
            e.kinetic,
            e.potential,
            e.elastic,
            e.total(),
            dissipated,
            work_in,
            // constant up to the integration error: what went in is stored or dissipated
            e.total() + dissipated - work_in,
            pv,
            vv,
        ]);
    }

    /// World position (m) of a body-fixed point `local` on body k at coordinates q.
    pub fn point_position(&self, k: usize, local: [f64; 2], q: &[f64]) -> [f64; 2] {
        let b = clr_contact::BodyState::fixed(
            nalgebra::Vector2::new(q[3 * k], q[3 * k + 1]),
            q[3 * k + 2],
        );
        let p = b.point(nalgebra::Vector2::new(local[0], local[1]));
        [p.x, p.y]
    }

    /// Integrate from a consistent initial state ([`Model::initial_state`]) over
    /// [`SimOptions::t0`, `SimOptions::t_end`] and record the outputs.
    ///
    /// # Errors
    /// Invalid options, assembly failures, or [`MbdError::Failed`] when the integrator fails:
    /// it carries every row recorded up to the failure ([`MbdError::partial`]).
    pub fn simulate(&mut self, opts: &SimOptions) -> Result<Results, MbdError> {
        self.simulate_with(opts, &|_| {})
    }

    /// As [`Model::simulate`], calling `progress` with the simulated time t (s) as the run
    /// advances: after the first accepted step that reaches 1 % of the span beyond the previous
    /// call (at most about 100 calls per run, however many steps), and once more with the final
    /// time (t_end when the run completes). The times passed are strictly increasing. The
    /// driver itself allocates nothing per call.
    ///
    /// # Errors
    /// As [`Model::simulate`].
    pub fn simulate_with(
        &mut self,
        opts: &SimOptions,
        progress: &dyn Fn(f64),
    ) -> Result<Results, MbdError> {
        let (y0, ic) = self.assemble_initial_state_with(opts.t0, &opts.initial_setup)?;
        let corrected = ic.corrected();
        if opts.initial_conditions == InitialConditionsMode::Exact && !corrected.is_empty() {
            return Err(inconsistent(&ic, &corrected));
        }
        let start = self.check_start(opts.t0, &y0, &ic)?;
        if opts.strict && !start.is_empty() {
            return Err(implausible(&start, None));
        }
        let scales = self.scales(&y0[..self.n]);
        let with_report = |model: &Model, mut r: Results| {
            let mut notes = ic.notes();
            notes.append(&mut r.notes);
            r.notes = notes;
            r.initial_conditions = Some(ic.clone());
            r.warnings = start.clone();
            r.warnings.extend(model.check_end(&r, &scales));
            r
        };
        match self.simulate_from_with(opts, &y0, progress) {
            Ok(r) => {
                let r = with_report(self, r);
                if opts.strict && !r.warnings.is_empty() {
                    let w = r.warnings.clone();
                    return Err(implausible(&w, Some(r)));
                }
                Ok(r)
            }
            Err(e) => Err(e.map_partial(|r| with_report(self, r))),
        }
    }

    /// As [`Model::simulate`] from a given state y0 = (q, q̇, E_d, W_in, z) of length
    /// [`OdeSystem::dim`] = 2n + 2 + [`Model::n_bristle_states`] (not modified; project it first
    /// with [`Model::project`] if it may violate the constraints). The recorded
    /// `energy.dissipated` and `energy.work_in` continue from the E_d and W_in given in y0 (J).
    ///
    /// # Errors
    /// As [`Model::simulate`].
    pub fn simulate_from(&mut self, opts: &SimOptions, y0: &[f64]) -> Result<Results, MbdError> {
        self.simulate_from_with(opts, y0, &|_| {})
    }

    /// As [`Model::simulate_from`] with a progress hook (see [`Model::simulate_with`]).
    ///
    /// # Errors
    /// As [`Model::simulate`].
    pub fn simulate_from_with(
        &mut self,
        opts: &SimOptions,
        y0: &[f64],
        progress: &dyn Fn(f64),
    ) -> Result<Results, MbdError> {
        check_options(opts, y0.len(), self.dim(), || {
            format!(
                "2n + 2 + m = {} (q, q̇, dissipated energy, input work, {} LuGre bristle states)",
                self.dim(),
                self.n_bristle_states()
            )
        })?;
        self.events_on = opts.contact_events;
        self.set_linear_solver(opts.linear_solver);
        let mut solver = AnySolver::new(opts, |mut ode| {
            if opts.scale_velocity_error {
                ode = ode.h_scaled_error(self.n..2 * self.n);
            }
            if let Some(atol) = self.bristle_atol(opts.atol, opts.rtol) {
                ode = ode.atol_vec(atol);
            }
            ode
        });
        let mut run = Run {
            data: Vec::new(),
            y: y0.to_vec(),
            recorded: 0,
            onsets: 0,
            projections: 0,
            max_viol: 0.0,
            impacts: ImpactTracker::new(self, opts.t0, y0),
            exits: GuideExits::new(self),
        };
        let mut newton = NewtonWs::new(self, opts.jacobian, opts.linear_solver);
        match self.integrate(opts, (&mut solver, &mut newton), &mut run, progress) {
            Ok(()) => {
                let stats = with_solver!(&solver, s => s.stats());
                let mut res = run.results(self.columns(), stats, self);
                let mut notes = self.run_notes(opts);
                notes.append(&mut res.notes);
                res.notes = notes;
                Ok(res)
            }
            Err(Stop::Mbd(e)) => Err(e),
            Err(Stop::Ode(e)) => {
                // rows the solver interpolated but the driver has not recorded yet (none in
                // practice: a failing advance records nothing), then the counters up to the
                // failure: a failed advance hands its statistics over with the error, a failed
                // restart leaves them in the solver
                let sol = e.solution();
                for k in run.recorded..sol.len() {
                    self.record(sol.t[k], sol.state(k), &mut run.data);
                }
                let stats = if sol.stats == Stats::default() {
                    with_solver!(&solver, s => s.stats())
                } else {
                    sol.stats
                };
                if sol.y_final.len() == run.y.len() {
                    run.y.copy_from_slice(&sol.y_final);
                }
                let cause = self.failure_cause(sol.t_final, run.y.as_slice());
                Err(MbdError::Failed {
                    partial: Box::new(run.results(self.columns(), stats, self)),
                    source: e,
                    cause,
                })
            }
        }
    }

    /// The step loop of [`Model::simulate_from_with`]: records into `run`, which keeps what was
    /// computed when an error stops it.
    fn integrate(
        &mut self,
        opts: &SimOptions,
        (solver, newton): (&mut AnySolver, &mut NewtonWs),
        run: &mut Run,
        progress: &dyn Fn(f64),
    ) -> Result<(), Stop> {
        let mut y_out = vec![0.0; self.dim()];
        let report_every = 0.01 * (opts.t_end - opts.t0);
        let mut last_report = opts.t0;
        self.memory.reset();
        self.commit_contacts(&run.y);
        let ig = &mut Integrand {
            model: self,
            ws: newton,
        };
        with_solver!(&mut *solver, s => s.start(ig, opts.t0, &run.y, opts.t_end))?;
        // outputs at t0 were recorded by the solver's start
        run.recorded = with_solver!(&*solver, s => s.solution().t.len());
        for _ in 0..run.recorded {
            self.record(opts.t0, &run.y, &mut run.data);
        }
        if opts.every_step && run.recorded == 0 {
            self.record(opts.t0, &run.y, &mut run.data);
        }
        loop {
            let reason = with_solver!(&mut *solver, s => s.advance_observed(&mut Integrand {
                    model: self,
                    ws: newton,
                }, &mut StopEachStep))?;
            let t = with_solver!(&*solver, s => s.solution().t_final);
            run.y
                .copy_from_slice(with_solver!(&*solver, s => &s.solution().y_final));
            // outputs inside the step, recorded by the solver from its dense output (before its
            // order/step change invalidates the interpolant), evaluated before the memory commit
            let n_out = with_solver!(&*solver, s => s.solution().t.len());
            while run.recorded < n_out {
                let to = with_solver!(&*solver, s => s.solution().t[run.recorded]);
                y_out
                    .copy_from_slice(with_solver!(&*solver, s => s.solution().state(run.recorded)));
                self.record(to, &y_out, &mut run.data);
                run.recorded += 1;
            }
            // impacts from the same dense output, with the memory the step used (before commit)
            let interp =
                |tp: f64, out: &mut [f64]| with_solver!(&*solver, s => s.interpolate(tp, out));
            run.impacts.step(self, (t, &run.y), &interp, &mut y_out);
            self.commit_contacts(&run.y);
            run.exits.observe(self, t);
            let (pv, _) = self.violation(t, &run.y);
            run.max_viol = run.max_viol.max(pv);
            let mut restart = false;
            if let StopReason::TerminalEvent(_) = reason {
                run.onsets += 1;
                restart = true;
            }
            // LuGre bristles: undeflected at open points and at a new contact (crate::lugre)
            let onset = match reason {
                StopReason::TerminalEvent(e) => Some(e),
                _ => None,
            };
            if self.reset_bristles(&mut run.y, onset) {
                restart = true;
            }
            if let Some(tol) = opts.projection {
                // also at t_end: the last recorded state satisfies the threshold like the others
                if pv > tol {
                    self.project(t, &mut run.y, tol * 1e-3)?;
                    run.projections += 1;
                    restart = true;
                }
            }
            if opts.every_step {
                self.record(t, &run.y, &mut run.data);
            }
            let done = reason == StopReason::EndReached || t >= opts.t_end;
            if (done && t > last_report) || t - last_report >= report_every {
                progress(t);
                last_report = t;
            }
            if done {
                return Ok(());
            }
            if restart {
                with_solver!(&mut *solver, s => s.restart(&mut Integrand {
                    model: self,
                    ws: newton,
                }, t, &run.y))?;
            }
        }
    }
}

/// The error of `strict` runs with plausibility findings.
fn implausible(w: &[crate::initial_data::Warning], partial: Option<Results>) -> MbdError {
    MbdError::Implausible {
        warnings: w
            .iter()
            .map(|w| w.to_string())
            .collect::<Vec<_>>()
            .join("; "),
        count: w.len(),
        partial: partial.map(Box::new),
    }
}

/// The error of `exact` initial conditions for the given changes (body, coordinate, given,
/// assembled).
fn inconsistent(
    ic: &crate::InitialConditions,
    corrected: &[(&str, &'static str, f64, f64)],
) -> MbdError {
    let list: Vec<String> = corrected
        .iter()
        .map(|(b, c, g, a)| format!("{b}.{c} from {g:.9e} to {a:.9e}"))
        .collect();
    MbdError::InconsistentInitialConditions {
        corrected: list.join(", "),
        field: corrected
            .first()
            .map_or(String::new(), |(b, c, _, _)| ic.field_of(b, c)),
    }
}

/// What [`Model::simulate_from_with`] has computed so far.
struct Run {
    /// Recorded rows, row-major.
    data: Vec<f64>,
    /// Current state (q, q̇, E_d, W_in, z).
    y: Vec<f64>,
    /// Output times of the solver already recorded.
    recorded: usize,
    onsets: usize,
    projections: usize,
    max_viol: f64,
    /// Impacts of the clearance joints located so far.
    impacts: ImpactTracker,
    /// Sliders that passed an end of their guide so far (reported in the notes).
    exits: GuideExits,
}

impl Run {
    fn results(self, columns: Vec<String>, stats: Stats, model: &Model) -> Results {
        Results {
            notes: self.exits.notes(model),
            columns,
            data: self.data,
            stats,
            onsets: self.onsets,
            projections: self.projections,
            max_position_violation: self.max_viol,
            y_final: self.y,
            impacts: self.impacts.into_impacts(),
            initial_conditions: None,
            warnings: Vec::new(),
        }
    }
}

/// Why the step loop stopped early: the integrator failed, or a clr-mbd step (projection) did.
enum Stop {
    Ode(clr_ode::OdeError),
    Mbd(MbdError),
}

impl From<clr_ode::OdeError> for Stop {
    fn from(e: clr_ode::OdeError) -> Self {
        Stop::Ode(e)
    }
}

impl From<MbdError> for Stop {
    fn from(e: MbdError) -> Self {
        Stop::Mbd(e)
    }
}
