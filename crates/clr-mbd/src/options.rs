//! The options of a run, planar or spatial: time span, integrator, tolerances, output times,
//! Newton matrix and initial conditions ([`SimOptions`]).

use crate::linsys::LinearSolver;
use crate::newton::JacobianMode;

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
