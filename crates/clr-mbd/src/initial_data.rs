//! Plain data of the assembly of initial conditions and of the plausibility checks: the
//! settings ([`InitialState`], [`InitialSetup`]), what the assembly reports
//! ([`IdealCounterpart`], [`SolvedCoordinate`]) and the findings of the checks ([`Warning`]).
//! It imports nothing from the crate, so the description, the runtime, the assembly and the
//! results can all name these types without importing each other.

use serde::{Deserialize, Serialize};

/// The names of a rigid body's six initial coordinates in
/// [`BodyInitialState::coordinates`](crate::BodyInitialState) (centre of mass): x, y (m),
/// θ (rad), v_x, v_y (m/s), ω (rad/s).
pub const COORDINATE_NAMES: [&str; 6] = ["x", "y", "theta", "vx", "vy", "omega"];
/// Units of [`COORDINATE_NAMES`].
pub const COORDINATE_UNITS: [&str; 6] = ["m", "m", "rad", "m/s", "m/s", "rad/s"];

/// How the assembly of initial conditions treats contact elements (`[solver] initial_state`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InitialState {
    /// Revolute and translational clearance joints act as their ideal joints while the
    /// coordinates left out are solved (journal centred, or at the joint's
    /// `initial_eccentricity`; slider centred and aligned), then are released (default).
    #[default]
    Ideal,
    /// Contact elements play no part in the assembly: coordinates determined only through a
    /// clearance joint are undetermined (and refused).
    AsGiven,
}

/// Settings of the assembly of initial conditions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct InitialSetup {
    /// Ideal counterparts or not.
    pub state: InitialState,
    /// Bodies deliberately left free: their undetermined coordinates keep their start values
    /// (0 when left out) and are recorded instead of refused.
    pub free_bodies: Vec<String>,
}

/// An ideal counterpart the assembly used.
#[derive(Debug, Clone, PartialEq)]
pub struct IdealCounterpart {
    /// The contact element.
    pub element: String,
    /// Its rows took part in the position assembly.
    pub positions: bool,
    /// Its rows took part in the velocity assembly.
    pub velocities: bool,
    /// The initial offset it imposed: revolute, the journal centre from the bearing centre in
    /// the bearing body's frame; translational, (0, offset across the guide); m.
    pub offset: [f64; 2],
    /// Rows left out because they repeat others (`J4 (ideal counterpart) (normal offset)`).
    pub dropped: Vec<String>,
}

/// A coordinate the assembly solved, with the constraint items that determined it.
#[derive(Debug, Clone, PartialEq)]
pub struct SolvedCoordinate {
    /// Body name.
    pub body: String,
    /// Coordinate name ([`COORDINATE_NAMES`]).
    pub coordinate: &'static str,
    /// The assembled value, in [`COORDINATE_UNITS`].
    pub value: f64,
    /// Joints, drivers and ideal counterparts whose rows involve it (empty when undetermined).
    pub from: Vec<String>,
    /// No constraint determines it: it kept its start value (the body is in `free_bodies`).
    pub undetermined: bool,
}

/// The unit of a coordinate name ([`COORDINATE_UNITS`]).
pub fn unit_of(name: &str) -> &'static str {
    COORDINATE_NAMES
        .iter()
        .position(|n| *n == name)
        .map_or("", |k| COORDINATE_UNITS[k])
}

/// A finding of the plausibility checks ([`crate::plausible`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// The field or item it concerns (`J1.bearing_radius`, `crank.omega`, `energy`).
    pub field: String,
    /// What was found and what to check.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.field, self.message)
    }
}

/// Which nodes of one body `[output.nodes]` records.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a list of node indices (e.g. [2, 4], 0 at the beam's start) or \"all\""
)]
pub enum NodeSelection {
    /// Node indices (0 at the beam's `start`).
    Nodes(Vec<usize>),
    /// `"all"`: every node of the mesh.
    All(AllNodes),
}

/// The keyword `"all"` of [`NodeSelection`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AllNodes {
    /// Every node.
    All,
}

/// Where a recorded node lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum NodeOwner {
    /// A ground-fixed beam (index into the model's beams).
    Beam(usize),
    /// A floating flexible body (index into the model's floating bodies).
    Floating(usize),
}

/// One recorded node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct NodeOutput {
    pub(crate) owner: NodeOwner,
    pub(crate) node: usize,
}
