//! `[solver]` and `[output]`: integrator settings and output times.

use serde::{Deserialize, Serialize};

use crate::field::FieldError;
use crate::linsys::LinearSolver;
use crate::newton::JacobianMode;
use crate::sim::{InitialConditionsMode, SimOptions, SolverKind};

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
    /// Absolute tolerance, in the units of q and q̇ (m, rad, m/s, rad/s). Absent: 1e-3·rtol,
    /// the one rule of built-in models, model files and `clr run --rtol` (docs/model-file.md).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub atol: Option<f64>,
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
    #[serde(skip_serializing_if = "is_default")]
    pub jacobian: JacobianMode,
    /// Highest NDF order, 1–5 (default 5).
    #[serde(skip_serializing_if = "is_five")]
    pub max_order: usize,
    /// Factorization of the augmented and Newton matrices: `auto` (default: sparse from
    /// n + m ≥ 32), `dense` or `sparse`.
    #[serde(skip_serializing_if = "is_default")]
    pub linear_solver: LinearSolver,
    /// Scale the velocities' error estimate by min(h, 1) (default false; see
    /// [`SimOptions::scale_velocity_error`]).
    #[serde(skip_serializing_if = "is_default")]
    pub scale_velocity_error: bool,
    /// Let Newton stop after one correction with an earlier contraction rate (default false;
    /// see [`SimOptions::newton_rate_reuse`]).
    #[serde(skip_serializing_if = "is_default")]
    pub newton_rate_reuse: bool,
    /// Given initial coordinates that violate the constraints: `assemble` (default: assembled
    /// and every change reported) or `exact` (refused; see [`InitialConditionsMode`]).
    #[serde(skip_serializing_if = "is_default")]
    pub initial_conditions: InitialConditionsMode,
    /// How the assembly treats clearance joints while it solves the coordinates left out:
    /// `ideal` (default: as their ideal joints, journal centred or at its
    /// `initial_eccentricity`, then released) or `as_given` (they play no part).
    #[serde(skip_serializing_if = "is_default")]
    pub initial_state: crate::initial_data::InitialState,
    /// Rigid bodies deliberately left free: coordinates of theirs that are left out and that
    /// nothing determines keep their start values (0) and are recorded, instead of refused.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub free_bodies: Vec<String>,
    /// Refuse the run when the plausibility checks find anything (default false: the
    /// findings are warnings; `clr run --strict` sets it).
    #[serde(skip_serializing_if = "is_default")]
    pub strict: bool,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            method: SolverMethod::Ndf,
            rtol: 1e-6,
            atol: None,
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
            initial_conditions: InitialConditionsMode::Assemble,
            initial_state: Default::default(),
            free_bodies: Vec::new(),
            strict: false,
        }
    }
}

// Integrator knobs at their defaults are not written (an exported file names only what it
// changes, and a Dormand–Prince file carries no NDF settings it would not use).
fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

fn is_five(v: &usize) -> bool {
    *v == 5
}

/// `[solver]` fields only NDF uses, with their defaults' test.
const NDF_ONLY: [&str; 4] = [
    "jacobian",
    "max_order",
    "scale_velocity_error",
    "newton_rate_reuse",
];

/// A Dormand–Prince run refuses the NDF settings it would ignore.
fn refuse_ndf_only(s: &SolverSettings) -> Result<(), FieldError> {
    if s.method != SolverMethod::Dopri5 {
        return Ok(());
    }
    let set = [
        s.jacobian != JacobianMode::default(),
        s.max_order != 5,
        s.scale_velocity_error,
        s.newton_rate_reuse,
    ];
    match NDF_ONLY.iter().zip(set).find(|(_, on)| *on) {
        Some((field, _)) => Err(FieldError::new(
            format!("solver.{field}"),
            format!(
                "method = \"dopri5\" does not use `{field}` (an NDF setting): remove it, or \
                 set method = \"ndf\""
            ),
        )),
        None => Ok(()),
    }
}

/// The `[solver]` fields a method does not use (`NDF_ONLY` for `dopri5`).
pub fn unused_solver_fields(method: SolverMethod) -> &'static [&'static str] {
    match method {
        SolverMethod::Dopri5 => &NDF_ONLY,
        SolverMethod::Ndf => &[],
    }
}

/// The absolute tolerance per unit of relative tolerance when `atol` is not given: atol =
/// 1e-3·rtol in the units of q and q̇ (a millimetre-scale mechanism at rtol 1e-6 is then held
/// to 1 nm and 1 nm/s where a coordinate passes through zero).
pub const ATOL_PER_RTOL: f64 = 1e-3;

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
    /// Nodes of flexible bodies and ground-fixed beams to record, by body or beam name
    /// (`[output.nodes]`, e.g. `rod = [2, 4]` or `rod = "all"`): each node adds the columns
    /// `<name>.node<k>.ux`, `.uy` (m) and `.rz` (rad), its elastic displacement and rotation in
    /// the body frame (the world frame for a ground-fixed beam), and `.x`, `.y` (m), its world
    /// position ([`crate::node_output`]). Empty by default (no columns added).
    #[serde(skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub nodes: std::collections::BTreeMap<String, NodeSelection>,
}

pub use crate::initial_data::{AllNodes, NodeSelection};

impl Default for OutputSettings {
    fn default() -> Self {
        Self {
            t_start: 0.0,
            t_end: None,
            intervals: 500,
            every_step: false,
            nodes: Default::default(),
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
    refuse_ndf_only(s)?;
    let rtol = positive("solver.rtol", s.rtol)?;
    let atol = positive("solver.atol", s.atol.unwrap_or(ATOL_PER_RTOL * rtol))?;
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
    options.initial_conditions = s.initial_conditions;
    options.strict = s.strict;
    options.initial_setup = crate::initial_data::InitialSetup {
        state: s.initial_state,
        free_bodies: s.free_bodies.clone(),
    };
    Ok(options)
}
