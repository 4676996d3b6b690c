//! The parts of a description below its element sections: `[model]`, rigid bodies and named
//! points (used by the element compiler, so they sit below [`super::ModelDesc`]).

use serde::{Deserialize, Serialize};

/// `[model]`: name, description and model-wide settings.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelInfo {
    /// Model name (used in reports).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// One-line description.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Gravitational acceleration (g_x, g_y), m/s² (default none).
    #[serde(default)]
    pub gravity: [f64; 2],
    /// Where the force pair of every revolute clearance joint acts: `common_point` (default,
    /// collinear action and reaction) or `contact_points` (Flores et al. 2004).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearance_force_application: Option<ForceApplicationDesc>,
}

/// Where a revolute clearance joint's force pair acts (clr-contact `ForceApplication`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ForceApplicationDesc {
    /// Both forces at the midpoint of the two contact points (r_i^Q + r_j^Q)/2: collinear
    /// action and reaction, so the joint conserves angular momentum exactly (the default).
    CommonPoint,
    /// At the contact points of each body (the published Flores et al. 2004 form).
    ContactPoints,
}

impl From<ForceApplicationDesc> for clr_contact::ForceApplication {
    fn from(a: ForceApplicationDesc) -> Self {
        match a {
            ForceApplicationDesc::CommonPoint => clr_contact::ForceApplication::CommonPoint,
            ForceApplicationDesc::ContactPoints => clr_contact::ForceApplication::ContactPoints,
        }
    }
}

/// A rigid body. Its frame is at `position` with angle `angle`; the centre of mass sits at
/// `centre_of_mass` in that frame (default the frame origin). Anchors and points on the body are
/// given in this frame. The model's coordinates (and result columns) are those of the centre
/// of mass.
///
/// The four initial-state fields are optional. A field that is given is *fixed*: the assembly
/// of consistent initial conditions ([`Model::initial_state`](crate::Model::initial_state))
/// keeps it unless the constraints cannot be met otherwise (every such change is reported). A
/// field left out is *solved*: it starts from 0 and the assembly chooses it (as Adams'
/// initial-conditions analysis does for coordinates that are not fixed).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Unique name.
    pub name: String,
    /// Mass, kg (> 0).
    pub mass: f64,
    /// Moment of inertia about the centre of mass, kg·m² (> 0).
    pub inertia: f64,
    /// Initial position of the body frame's origin, m (left out: solved from [0, 0]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<[f64; 2]>,
    /// Initial angle, rad (left out: solved from 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle: Option<f64>,
    /// Initial velocity of the body frame's origin, m/s (left out: solved from [0, 0]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<[f64; 2]>,
    /// Initial angular velocity, rad/s (left out: solved from 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angular_velocity: Option<f64>,
    /// Centre of mass in the body frame, m (default [0, 0]).
    #[serde(default, skip_serializing_if = "is_zero2")]
    pub centre_of_mass: [f64; 2],
}

impl Body {
    /// Which centre-of-mass coordinates (x, y, θ, v_x, v_y, ω) the description fixes: a
    /// position is fixed when it is given and, with a centre of mass off the frame origin, the
    /// angle is given too (the centre of mass moves with the angle); likewise the velocity with
    /// the angular velocity.
    pub fn fixed_coordinates(&self) -> [bool; 6] {
        let on_origin = self.centre_of_mass == [0.0, 0.0];
        let (p, a) = (self.position.is_some(), self.angle.is_some());
        let (v, w) = (self.velocity.is_some(), self.angular_velocity.is_some());
        let pos = p && (a || on_origin);
        let vel = v && (w || on_origin);
        [pos, pos, a, vel, vel, w]
    }
}

fn is_zero2(v: &[f64; 2]) -> bool {
    v[0] == 0.0 && v[1] == 0.0
}

/// A named point: on a body (`body`, `at`) or at a beam node (`beam`, `node`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// Unique name.
    pub name: String,
    /// Body (or `ground`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// Local coordinates in the body frame, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<[f64; 2]>,
    /// Beam (ground-fixed or floating) whose node this point is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beam: Option<String>,
    /// Node index on `beam`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub node: Option<usize>,
}
