//! `[solver]` and `[output]`: integrator settings and output times.

use serde::{Deserialize, Serialize};

use crate::field::FieldError;
use crate::linsys::LinearSolver;
use crate::newton::JacobianMode;
use crate::sim::{SimOptions, SolverKind};

/// Integrator of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SolverMethod {
    /// Variable-order NDF (default).
    #[default]
    Ndf,
    /// Dormand–Prince 5(4).
    Dopri5,
}

/// `[solver]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSettings {
    /// Integrator (default `ndf`).
    pub method: SolverMethod,
    /// Relative tolerance (default 1e-6).
    pub rtol: f64,
    /// Absolute tolerance (default 1e-8, units of q and q̇).
    pub atol: f64,
    /// Largest step, s (default unbounded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub h_max: Option<f64>,
    /// Step budget (default 1 000 000).
    pub max_steps: usize,
    /// Baumgarte α, 1/s (default 5).
    pub baumgarte_alpha: f64,
    /// Baumgarte β, 1/s (default 5).
    pub baumgarte_beta: f64,
    /// Projection threshold on ‖Φ‖∞ (m or rad); absent: no projection.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub projection: Option<f64>,
    /// Locate contact onsets as events (default true).
    pub contact_events: bool,
    /// NDF's Newton matrix: `analytic` (default; the elements' Jacobians in the reduced
    /// second-order system) or `finite_difference` (the whole right-hand side differenced).
    pub jacobian: JacobianMode,
    /// Highest NDF order, 1–5 (default 5).
    pub max_order: usize,
    /// Factorization of the augmented and Newton matrices: `auto` (default: sparse from
    /// n + m ≥ 32), `dense` or `sparse`.
    pub linear_solver: LinearSolver,
    /// Scale the velocities' error estimate by min(h, 1) (default false; see
    /// [`SimOptions::scale_velocity_error`]).
    pub scale_velocity_error: bool,
    /// Let Newton stop after one correction with an earlier contraction rate (default false;
    /// see [`SimOptions::newton_rate_reuse`]).
    pub newton_rate_reuse: bool,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            method: SolverMethod::Ndf,
            rtol: 1e-6,
            atol: 1e-8,
            h_max: None,
            max_steps: 1_000_000,
            baumgarte_alpha: crate::system::DEFAULT_BAUMGARTE_ALPHA,
            baumgarte_beta: crate::system::DEFAULT_BAUMGARTE_BETA,
            projection: None,
            contact_events: true,
            jacobian: JacobianMode::Analytic,
            max_order: 5,
            linear_solver: LinearSolver::Auto,
            scale_velocity_error: false,
            newton_rate_reuse: false,
        }
    }
}

/// `[output]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSettings {
    /// Start time, s (default 0).
    pub t_start: f64,
    /// End time, s (required to run).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t_end: Option<f64>,
    /// Number of equal output intervals (default 500; 0 only with `every_step`).
    pub intervals: usize,
    /// Also record after every accepted step (default false).
    pub every_step: bool,
}

impl Default for OutputSettings {
    fn default() -> Self {
        Self {
            t_start: 0.0,
            t_end: None,
            intervals: 500,
            every_step: false,
        }
    }
}

fn positive(path: &str, v: f64) -> Result<f64, FieldError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(FieldError::new(
            path,
            format!("must be positive and finite (give a value > 0), got {v}"),
        ))
    }
}

fn non_negative(path: &str, v: f64) -> Result<f64, FieldError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(FieldError::new(
            path,
            format!("must be finite and ≥ 0, got {v} 1/s"),
        ))
    }
}

/// Check the settings and build the clr-mbd options.
pub(crate) fn sim_options(
    s: &SolverSettings,
    o: &OutputSettings,
) -> Result<SimOptions, FieldError> {
    let rtol = positive("solver.rtol", s.rtol)?;
    let atol = positive("solver.atol", s.atol)?;
    let h_max = match s.h_max {
        Some(h) => positive("solver.h_max", h)?,
        None => f64::INFINITY,
    };
    non_negative("solver.baumgarte_alpha", s.baumgarte_alpha)?;
    non_negative("solver.baumgarte_beta", s.baumgarte_beta)?;
    if let Some(p) = s.projection {
        positive("solver.projection", p)?;
    }
    if !(1..=5).contains(&s.max_order) {
        return Err(FieldError::new(
            "solver.max_order",
            format!("give an NDF order from 1 to 5, got {}", s.max_order),
        ));
    }
    if s.max_steps == 0 {
        return Err(FieldError::new(
            "solver.max_steps",
            "give a step budget ≥ 1",
        ));
    }
    let t0 = o.t_start;
    if !t0.is_finite() {
        return Err(FieldError::new(
            "output.t_start",
            format!("{t0} must be finite"),
        ));
    }
    let t_end = o.t_end.ok_or_else(|| {
        FieldError::new(
            "output.t_end",
            "missing value: give the end time t_end in s (or `--t-end` on the command line)",
        )
    })?;
    if !(t_end.is_finite() && t_end > t0) {
        return Err(FieldError::new(
            "output.t_end",
            format!("t_end = {t_end} s must be finite and after t_start = {t0} s"),
        ));
    }
    if (o.intervals == 0 && !o.every_step) || o.intervals > 10_000_000 {
        return Err(FieldError::new(
            "output.intervals",
            "give between 1 and 10 000 000 output intervals (0 only with every_step = true)",
        ));
    }
    let mut options = if o.intervals == 0 {
        SimOptions {
            t0,
            t_end,
            ..SimOptions::default()
        }
    } else {
        SimOptions::span(t0, t_end, o.intervals)
    }
    .solver(match s.method {
        SolverMethod::Ndf => SolverKind::Ndf,
        SolverMethod::Dopri5 => SolverKind::Dopri5,
    })
    .tolerances(rtol, atol);
    options.h_max = h_max;
    options.max_steps = s.max_steps;
    options.every_step = o.every_step;
    options.projection = s.projection;
    options.contact_events = s.contact_events;
    options.jacobian = s.jacobian;
    options.max_order = s.max_order;
    options.linear_solver = s.linear_solver;
    options.scale_velocity_error = s.scale_velocity_error;
    options.newton_rate_reuse = s.newton_rate_reuse;
    Ok(options)
}
