//! The error type of clr-mbd.

use clr_contact::ContactError;
use clr_ode::OdeError;

use crate::results::Results;

/// Everything that can go wrong when building or running a multibody model.
///
/// Every message names the offending item and says what to change.
#[derive(Debug, thiserror::Error)]
pub enum MbdError {
    /// An item refers to a body that was never defined.
    #[error(
        "{item}: unknown {} `{body}`; {}",
        body_kind(item),
        hint(body, known, body_kind(item))
    )]
    UnknownBody {
        /// The item (joint, driver, force, point, contact) that refers to the body, with the
        /// field that names it (`pin.b.body`) when known.
        item: String,
        /// The name that was not found.
        body: String,
        /// The bodies that exist, comma-separated.
        known: String,
    },
    /// An item refers to a point that was never defined.
    #[error("{item}: unknown point `{point}`; {}", hint(point, known, "point"))]
    UnknownPoint {
        /// The item that refers to the point, with the field that names it (`pin.a`) when
        /// known.
        item: String,
        /// The name that was not found.
        point: String,
        /// The points that exist, comma-separated.
        known: String,
    },
    /// Two items share a name (all names share one namespace; `ground` is reserved).
    #[error("duplicate name `{name}` (a {first} and a {second}); give every item its own name")]
    DuplicateName {
        /// The name used twice.
        name: String,
        /// Kind of the first item with that name.
        first: &'static str,
        /// Kind of the second item with that name.
        second: &'static str,
    },
    /// A body's mass or moment of inertia is zero, negative or not finite.
    #[error("body `{body}`: {what} = {value} must be positive and finite")]
    InvalidInertia {
        /// The body.
        body: String,
        /// `"mass (kg)"` or `"moment of inertia about the centre of mass (kg·m²)"`.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A joint, driver, force or contact connects a body to itself.
    #[error("{item}: connects body `{body}` to itself; give two different bodies")]
    SameBody {
        /// The item.
        item: String,
        /// The body given twice.
        body: String,
    },
    /// Any other invalid parameter of an item (a zero axis, a negative stiffness, …).
    #[error("{item}: {what} = {value} is invalid: {requirement}")]
    InvalidParameter {
        /// The item.
        item: String,
        /// The parameter with its unit.
        what: &'static str,
        /// The value given.
        value: f64,
        /// What the value must satisfy.
        requirement: &'static str,
    },
    /// A contact law or geometry could not be built.
    #[error("{item}: {source}")]
    Contact {
        /// The contact element.
        item: String,
        /// The clr-contact error.
        source: ContactError,
    },
    /// A flexible beam could not be set up from its clr-beam model.
    #[error("{item}: {message}")]
    Beam {
        /// The beam item.
        item: String,
        /// The clr-beam error.
        message: String,
    },
    /// The constraint Jacobian is rank deficient: redundant (or conflicting) constraints.
    #[error(
        "redundant constraints: the constraint Jacobian has rank {rank} < {rows} rows; these \
         equations are linear combinations of the others: {involved}. Remove a joint or \
         replace a revolute joint by a point-on-line joint so every equation is independent"
    )]
    RedundantConstraints {
        /// Numerical rank of Φ_q.
        rank: usize,
        /// Number of constraint equations.
        rows: usize,
        /// The dependent equations and those they depend on, as `item (equation)` labels.
        involved: String,
    },
    /// Newton's iteration for consistent positions did not converge.
    #[error(
        "could not assemble the mechanism at t = {t}: position constraints still violated by \
         {residual:e} after {iterations} Newton iterations (largest: {worst}); give initial \
         poses closer to an assembled configuration or check the joint locations"
    )]
    Assembly {
        /// Time of the assembly.
        t: f64,
        /// Remaining ‖Φ‖∞ (m or rad).
        residual: f64,
        /// Iterations spent.
        iterations: usize,
        /// The most violated equation.
        worst: String,
    },
    /// Coordinates left out of the description that no joint, driver or ideal counterpart of a
    /// clearance joint determines: the assembly would have kept them at 0 in silence.
    #[error(
        "initial conditions: {coordinates} left out of the model and determined by no joint, \
         driver or ideal counterpart of a clearance joint; give them (a body at rest: velocity \
         = [0.0, 0.0], angular_velocity = 0.0), or name the bodies deliberately left free in \
         [solver] free_bodies = [{bodies}]"
    )]
    UndeterminedCoordinates {
        /// The coordinates as `body.coordinate` items (x, y, theta, vx, vy, omega).
        coordinates: String,
        /// The bodies they belong to, quoted and comma-separated (for the hint).
        bodies: String,
        /// The description field of the first one (`rod.angular_velocity`).
        field: String,
    },
    /// A contact element penetrates far beyond its clearance at t0: the initial state is
    /// wrong (an angle in degrees, a position in mm, a journal in the wrong place), and the
    /// run would start with an enormous force.
    #[error(
        "{element}: the initial state puts the {what} {penetration:.3e} m into contact at \
         t0 = {t}, {ratio:.3e} times the clearance {clearance:.3e} m; check the initial angles \
         (radians, not degrees) and positions (metres) of the bodies it joins{hint}"
    )]
    InitialPenetration {
        /// The contact element.
        element: String,
        /// What penetrates (`journal into the bearing`, `slider into the guide`).
        what: &'static str,
        /// t0, s.
        t: f64,
        /// Penetration, m.
        penetration: f64,
        /// Its clearance (radial, or total across a guide), m.
        clearance: f64,
        /// penetration / clearance.
        ratio: f64,
        /// More on where the assembly moved things (may be empty).
        hint: String,
    },
    /// `initial_conditions = "exact"` and the given initial state does not satisfy the
    /// constraints: the assembly would have changed given coordinates.
    #[error(
        "initial_conditions = \"exact\": the given initial state does not satisfy the \
         constraints; the assembly would change {corrected}. Give consistent values (the \
         assembled ones are shown), leave the coordinates to solve out of the model, or set \
         initial_conditions = \"assemble\""
    )]
    InconsistentInitialConditions {
        /// The changes as `body.coordinate given → assembled unit` items.
        corrected: String,
        /// The description field of the first change (`rod.angular_velocity`).
        field: String,
    },
    /// The joints of a floating flexible body cannot be closed at t0 without deforming it: the
    /// assembly of initial conditions keeps elastic coordinates undeformed and at rest
    /// ([`crate::init_flex`]).
    #[error(
        "flexible body `{body}`: its joints cannot be closed at t0 without deforming it \
         (closing them elastically would store {strain_energy:.3e} J at the start; the assembly \
         keeps elastic coordinates undeformed and at rest). Give the flexible body a pose, \
         velocity and beam geometry (length, joint nodes) its joints fit undeformed"
    )]
    FlexibleBodyDeformed {
        /// The flexible body.
        body: String,
        /// Strain energy ½q_fᵀK q_f (J) of the elastic closure of the joints.
        strain_energy: f64,
    },
    /// A field of the description is invalid (the path names it, e.g. `driver[0].motion.rate`
    /// or `crank_drive.motion.rate` for an element's field).
    #[error("field `{path}`: {message}")]
    Invalid {
        /// Path of the offending field.
        path: String,
        /// What is wrong and what to change.
        message: String,
    },
    /// Invalid simulation settings.
    #[error("simulation options: {0}")]
    Options(String),
    /// The integrator failed (step budget, step size underflow, Newton failures, non-finite
    /// forces). `partial` holds every row recorded up to the failure, in the columns of a
    /// successful run (see [`Results`]), with the statistics and the last state reached
    /// (`partial.y_final`); `source` is clr-ode's error with its own partial solution (the
    /// states at the output times) and says what to change.
    #[error("integration failed: {source}{}{cause}", rows_note(partial))]
    Failed {
        /// The integrator's error.
        source: OdeError,
        /// What the model shows at the last state reached that likely caused the failure (the
        /// deepest contact against its clearance, the largest contact force, the fastest body),
        /// as a sentence starting with `; ` (empty when nothing stands out).
        cause: String,
        /// The results recorded up to the failure.
        partial: Box<Results>,
    },
    /// `strict` and the plausibility checks found something ([`crate::plausible`]): refused
    /// before integrating (`partial` is `None`) or after the run (`partial` holds the whole
    /// result, whose `warnings` list the findings).
    #[error(
        "strict: {count} plausibility warning(s), refused: {warnings}. Fix the inputs, or run \
         without --strict (strict=False) to get the result with the warnings"
    )]
    Implausible {
        /// The findings, `field: message` joined by `; `.
        warnings: String,
        /// Number of findings.
        count: usize,
        /// The finished run's results (`None` when refused before integrating).
        partial: Option<Box<Results>>,
    },
    /// The run reached a state that is not physics any more (a ball driven through its socket)
    /// and stopped there; `partial` holds every row up to that step.
    #[error(
        "the run stopped at a non-physical state: {reason}. The rows up to there are kept \
         (partial results)"
    )]
    Stopped {
        /// What happened, where and what to check.
        reason: String,
        /// The results up to the stop.
        partial: Box<Results>,
    },
    /// Writing output failed.
    #[error("writing output: {0}")]
    Io(#[from] std::io::Error),
}

/// `beam` when the field names a beam (`tip_load.beam`), else `body`.
fn body_kind(item: &str) -> &'static str {
    if item.ends_with(".beam") {
        "beam"
    } else {
        "body"
    }
}

/// "did you mean `x`?" or the list of valid names, and how to define a new one.
fn hint(name: &str, known: &str, what: &str) -> String {
    let ground = (what == "body").then_some(crate::runtime::GROUND);
    let all: Vec<&str> = ground
        .into_iter()
        .chain(known.split(", ").filter(|s| !s.is_empty()))
        .collect();
    let define = match what {
        "body" => "a [[body]] (ModelBuilder::body)",
        "beam" => "a [[beam]] or [[flexible_body]] (ModelBuilder::flexible_beam)",
        _ => "a [[point]] (ModelBuilder::point)",
    };
    match crate::field::closest(name, all.iter().copied()) {
        Some(c) => format!("did you mean `{c}`? (or define {define})"),
        None if all.is_empty() => format!("none is defined; define {define}"),
        None => format!("valid: {}; or define {define}", all.join(", ")),
    }
}

/// ` (N rows recorded up to t = T s)`, or nothing without rows.
fn rows_note(r: &Results) -> String {
    if r.is_empty() {
        String::new()
    } else {
        format!(
            " ({} rows recorded up to t = {} s)",
            r.len(),
            r.row(r.len() - 1)[0]
        )
    }
}

impl From<crate::field::FieldError> for MbdError {
    fn from(e: crate::field::FieldError) -> Self {
        MbdError::Invalid {
            path: e.path,
            message: e.message,
        }
    }
}

impl MbdError {
    /// The same error with `f` applied to the partial results of a failed or stopped run
    /// ([`MbdError::Failed`], [`MbdError::Stopped`]; other errors unchanged).
    pub(crate) fn map_partial(self, f: impl FnOnce(crate::Results) -> crate::Results) -> Self {
        match self {
            MbdError::Failed {
                partial,
                source,
                cause,
            } => MbdError::Failed {
                partial: Box::new(f(*partial)),
                source,
                cause,
            },
            MbdError::Stopped { reason, partial } => MbdError::Stopped {
                reason,
                partial: Box::new(f(*partial)),
            },
            e => e,
        }
    }

    /// The results recorded up to an integrator failure ([`MbdError::Failed`]) or a stop
    /// ([`MbdError::Stopped`]), or of a strict run refused after it finished; `None` for every
    /// other error (nothing was integrated).
    pub fn partial(&self) -> Option<&Results> {
        match self {
            MbdError::Failed { partial, .. } | MbdError::Stopped { partial, .. } => Some(partial),
            MbdError::Implausible {
                partial: Some(p), ..
            } => Some(p),
            _ => None,
        }
    }

    /// Take the results recorded up to an integrator failure (see [`MbdError::partial`]).
    pub fn into_partial(self) -> Option<Results> {
        match self {
            MbdError::Failed { partial, .. } | MbdError::Stopped { partial, .. } => Some(*partial),
            MbdError::Implausible {
                partial: Some(p), ..
            } => Some(*p),
            _ => None,
        }
    }
}
