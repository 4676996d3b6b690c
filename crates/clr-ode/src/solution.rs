//! What a run returns: the solution, its statistics, why it stopped, and typed errors.

/// Counters of one run (accumulated over restarts).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected step attempts (error test or Newton failure).
    pub rejected: usize,
    /// Evaluations of f (including those of finite-difference Jacobians).
    pub f_evals: usize,
    /// Jacobian evaluations (analytic or finite-difference).
    pub jac_evals: usize,
    /// LU factorizations of the Newton matrix M − hγJ.
    pub lu_factorizations: usize,
    /// Newton iterations.
    pub newton_iters: usize,
    /// Events located (terminal and non-terminal).
    pub events: usize,
}

/// Why a run (or one `advance`) stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StopReason {
    /// Not finished yet (a run in progress, or a failed run).
    #[default]
    Running,
    /// t_end was reached.
    EndReached,
    /// A terminal event with this index stopped the run.
    TerminalEvent(usize),
    /// The observer asked to stop.
    Observer,
}

/// One located event.
#[derive(Debug, Clone, PartialEq)]
pub struct EventRecord {
    /// Time of the zero crossing (units of t).
    pub t: f64,
    /// State at the crossing (from the dense output).
    pub y: Vec<f64>,
    /// Index of the event function.
    pub index: usize,
}

/// The recorded solution of a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Solution {
    /// State dimension n.
    pub dim: usize,
    /// Output times.
    pub t: Vec<f64>,
    /// Output states, flat: state k is `y[k * dim..(k + 1) * dim]` (see [`Solution::state`]).
    pub y: Vec<f64>,
    /// Located events in time order.
    pub events: Vec<EventRecord>,
    /// Why the run stopped.
    pub stop: StopReason,
    /// Counters.
    pub stats: Stats,
    /// Time of the last state reached (end, event or failure).
    pub t_final: f64,
    /// Last state reached (at `t_final`).
    pub y_final: Vec<f64>,
}

impl Solution {
    /// Number of recorded output points.
    pub fn len(&self) -> usize {
        self.t.len()
    }
    /// True when nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
    /// Recorded state number `k`.
    pub fn state(&self, k: usize) -> &[f64] {
        &self.y[k * self.dim..(k + 1) * self.dim]
    }
    /// Iterator over (t, state) pairs.
    pub fn iter(&self) -> impl Iterator<Item = (f64, &[f64])> {
        self.t
            .iter()
            .copied()
            .zip(self.y.chunks_exact(self.dim.max(1)))
    }
    pub(crate) fn push(&mut self, t: f64, y: &[f64]) {
        self.t.push(t);
        self.y.extend_from_slice(y);
    }
    pub(crate) fn reset(&mut self, dim: usize) {
        self.dim = dim;
        self.t.clear();
        self.y.clear();
        self.events.clear();
        self.stop = StopReason::Running;
        self.stats = Stats::default();
        self.t_final = f64::NAN;
        self.y_final.clear();
    }
}

/// The last clause of a step failure's advice: the stiff solver under an explicit method; under
/// the stiff one, the model (a stiff solver that still needs tiny steps meets a discontinuity or
/// a force far larger than the model's scale, which no method change fixes).
fn stiff_advice(stiff: bool) -> &'static str {
    if stiff {
        " (the stiff solver is already in use: look for a force far out of scale or a \
         discontinuity in the model)"
    } else {
        ", or use the stiff solver (Ndf) if the problem is stiff"
    }
}

/// A failed run. Every variant carries the solution computed up to the failure.
#[derive(Debug, thiserror::Error)]
pub enum OdeError {
    /// The step size fell below its floor.
    #[error(
        "step size {h:e} at t = {t} fell below its floor {h_min:e}: the solution may be \
         singular there; loosen rtol/atol, lower Options::h_min, or check the model{}",
        stiff_advice(*stiff)
    )]
    StepSizeUnderflow {
        /// The method was the stiff one (NDF): its advice does not suggest it again.
        stiff: bool,
        /// Time reached.
        t: f64,
        /// Step size that was too small.
        h: f64,
        /// The floor max(h_min, 10 ulp(t)).
        h_min: f64,
        /// Solution up to `t`.
        solution: Box<Solution>,
    },
    /// The step budget was spent.
    #[error(
        "step budget of {max_steps} accepted steps spent at t = {t}: raise Options::max_steps, \
         loosen the tolerances{}",
        stiff_advice(*stiff)
    )]
    StepBudget {
        /// The method was the stiff one (NDF): its advice does not suggest it again.
        stiff: bool,
        /// Time reached.
        t: f64,
        /// The budget.
        max_steps: usize,
        /// Solution up to `t`.
        solution: Box<Solution>,
    },
    /// Newton's iteration failed too often within one step.
    #[error(
        "Newton iteration failed {failures} times in one step at t = {t} (last h = {h:e}): \
         check the analytic Jacobian, make the DAE initial state consistent, or raise \
         Options::max_newton_failures"
    )]
    NewtonFailure {
        /// Time reached.
        t: f64,
        /// Last step size tried.
        h: f64,
        /// Failures in that step.
        failures: usize,
        /// Solution up to `t`.
        solution: Box<Solution>,
    },
    /// f returned NaN or infinity and smaller steps did not help.
    #[error(
        "the right-hand side f returned a non-finite value near t = {t} even with reduced \
         steps: check the model for divisions by zero or overflow"
    )]
    NonFiniteRhs {
        /// Time reached.
        t: f64,
        /// Solution up to `t`.
        solution: Box<Solution>,
    },
    /// The Jacobian (analytic or finite-difference) has non-finite entries.
    #[error(
        "the Jacobian has a non-finite entry at t = {t}: check the analytic Jacobian or the \
         model near this state"
    )]
    NonFiniteJacobian {
        /// Time reached.
        t: f64,
        /// Solution up to `t`.
        solution: Box<Solution>,
    },
    /// The input is invalid (nothing was integrated).
    #[error("invalid input: {what}")]
    InvalidInput {
        /// What is wrong and what to change.
        what: String,
        /// An empty solution.
        solution: Box<Solution>,
    },
}

impl OdeError {
    /// The solution computed up to the failure.
    pub fn solution(&self) -> &Solution {
        match self {
            OdeError::StepSizeUnderflow { solution, .. }
            | OdeError::StepBudget { solution, .. }
            | OdeError::NewtonFailure { solution, .. }
            | OdeError::NonFiniteRhs { solution, .. }
            | OdeError::NonFiniteJacobian { solution, .. }
            | OdeError::InvalidInput { solution, .. } => solution,
        }
    }

    /// Take the solution computed up to the failure.
    pub fn into_solution(self) -> Solution {
        match self {
            OdeError::StepSizeUnderflow { solution, .. }
            | OdeError::StepBudget { solution, .. }
            | OdeError::NewtonFailure { solution, .. }
            | OdeError::NonFiniteRhs { solution, .. }
            | OdeError::NonFiniteJacobian { solution, .. }
            | OdeError::InvalidInput { solution, .. } => *solution,
        }
    }
}
