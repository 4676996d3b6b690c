//! Solver options shared by [`crate::Ndf`] and [`crate::Dopri5`].

/// Absolute tolerance: one value for all components or one per component.
#[derive(Debug, Clone, PartialEq)]
pub enum Atol {
    /// The same absolute tolerance for every component (units of y).
    Scalar(f64),
    /// One absolute tolerance per component (length n, units of each y_i).
    Vector(Vec<f64>),
}

/// Which states the solution records.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Output {
    /// The initial state and the state after every accepted step (the default).
    #[default]
    Steps,
    /// The states at these times (increasing, within [t0, t_end]), from the dense output.
    /// Times after a terminal event are not reached.
    Times(Vec<f64>),
    /// Only the state where each `advance` stops (end of the run, terminal event or observer
    /// stop); a restart loop records one state per stop.
    End,
}

/// The formula family of the [`crate::Ndf`] solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Formula {
    /// Numerical differentiation formulas (Klopfenstein–Shampine, κ of Shampine & Reichelt 1997,
    /// Table 1): the default, as in ode15s.
    #[default]
    Ndf,
    /// Plain backward differentiation formulas (κ = 0).
    Bdf,
}

/// Options of a run. Build with [`Options::default`] and the setter methods.
///
/// Error control: a step is accepted when the RMS norm of (error_i / (atol_i + rtol·|y_i|)) is
/// at most 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Relative tolerance (default 1e-6). Values below 100·ε are raised to 100·ε.
    pub rtol: f64,
    /// Absolute tolerance (default 1e-8, units of y).
    pub atol: Atol,
    /// Initial step size (units of t); `None` selects it automatically (Hairer, Nørsett &
    /// Wanner, Solving ODEs I, §II.4, algorithm of `hinit`).
    pub h0: Option<f64>,
    /// Largest step size (units of t; default unbounded).
    pub h_max: f64,
    /// Step-size floor (units of t, default 0): a step that would go below
    /// max(h_min, 10 ulp(t)) is a [`crate::OdeError::StepSizeUnderflow`].
    pub h_min: f64,
    /// Budget of accepted steps from `start` (restarts do not reset it; default 1 000 000).
    pub max_steps: usize,
    /// What the solution records.
    pub output: Output,
    /// NDF/BDF only: highest order, 1–5 (default 5).
    pub max_order: usize,
    /// NDF/BDF only: NDF (default) or plain BDF coefficients.
    pub formula: Formula,
    /// NDF/BDF only: Newton failures allowed within one step (each halves the step) before
    /// [`crate::OdeError::NewtonFailure`] (default 20). The limit is per step, not per run.
    pub max_newton_failures: usize,
    /// Fixed step size: take steps of exactly `h0` with no error control (used to measure the
    /// order of a method). NDF/BDF raise the order by one per step up to `max_order` unless
    /// started with a history ([`crate::Ndf::start_with_history`]).
    pub fixed_step: bool,
    /// NDF/BDF only: components whose local error estimate is multiplied by min(h, 1) (h the
    /// step in units of t) before the error norm; `None` (default) for none. Use it for the
    /// velocities of a second-order system y = (x, ẋ) with undamped or lightly damped stiff
    /// modes: where h·ω ≫ 1 the velocity of such a mode behaves like an index-2 variable (its
    /// error is the position error divided by h), so an unscaled test pins h at h·ω ≲ 1. The
    /// same scaling as RADAU5's index-2 variables (Hairer & Wanner, Solving ODEs II, 2nd ed.,
    /// §VII.4, and the NIND2 option of their code). See docs/ode.md, "Undamped structures".
    pub h_scaled_error: Option<std::ops::Range<usize>>,
    /// NDF/BDF only, ODEs (M = I) only: let Newton stop after its first correction when the
    /// contraction rate θ measured earlier with the same factorization predicts convergence
    /// (θ/(1 − θ)·‖Δ‖ below the tolerance), as RADAU5 and CVODE do (default false). It pays
    /// where f is expensive (clr-mbd turns it on: an augmented solve per f); on the Test Set
    /// problems it is not a clear win (docs/ode.md, "Newton rate carried across steps").
    pub newton_rate_reuse: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            rtol: 1e-6,
            atol: Atol::Scalar(1e-8),
            h0: None,
            h_max: f64::INFINITY,
            h_min: 0.0,
            max_steps: 1_000_000,
            output: Output::Steps,
            max_order: 5,
            formula: Formula::Ndf,
            max_newton_failures: 20,
            fixed_step: false,
            h_scaled_error: None,
            newton_rate_reuse: false,
        }
    }
}

impl Options {
    /// Set the relative tolerance.
    pub fn rtol(mut self, rtol: f64) -> Self {
        self.rtol = rtol;
        self
    }
    /// Set a scalar absolute tolerance.
    pub fn atol(mut self, atol: f64) -> Self {
        self.atol = Atol::Scalar(atol);
        self
    }
    /// Set per-component absolute tolerances.
    pub fn atol_vec(mut self, atol: Vec<f64>) -> Self {
        self.atol = Atol::Vector(atol);
        self
    }
    /// Set the initial step size.
    pub fn h0(mut self, h0: f64) -> Self {
        self.h0 = Some(h0);
        self
    }
    /// Set the largest step size.
    pub fn h_max(mut self, h_max: f64) -> Self {
        self.h_max = h_max;
        self
    }
    /// Set the step-size floor.
    pub fn h_min(mut self, h_min: f64) -> Self {
        self.h_min = h_min;
        self
    }
    /// Set the step budget.
    pub fn max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }
    /// Set what the solution records.
    pub fn output(mut self, output: Output) -> Self {
        self.output = output;
        self
    }
    /// Set the highest NDF/BDF order (1–5).
    pub fn max_order(mut self, max_order: usize) -> Self {
        self.max_order = max_order;
        self
    }
    /// Use plain BDF coefficients instead of NDF.
    pub fn bdf(mut self) -> Self {
        self.formula = Formula::Bdf;
        self
    }
    /// Set the per-step limit of Newton failures.
    pub fn max_newton_failures(mut self, n: usize) -> Self {
        self.max_newton_failures = n;
        self
    }
    /// Multiply the local error estimate of `components` (e.g. the velocities n..2n of
    /// y = (x, ẋ)) by min(h, 1) before the error norm (see [`Options::h_scaled_error`]).
    pub fn h_scaled_error(mut self, components: std::ops::Range<usize>) -> Self {
        self.h_scaled_error = Some(components);
        self
    }
    /// Reuse the Newton contraction rate across steps (see [`Options::newton_rate_reuse`]).
    pub fn newton_rate_reuse(mut self, on: bool) -> Self {
        self.newton_rate_reuse = on;
        self
    }
    /// Fixed steps of size `h` with no error control.
    pub fn fixed_step(mut self, h: f64) -> Self {
        self.h0 = Some(h);
        self.fixed_step = true;
        self
    }
}
