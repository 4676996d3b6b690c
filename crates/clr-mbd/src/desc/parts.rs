//! The parts of a description below its element sections: `[model]`, rigid bodies and named
//! points (used by the element compiler, so they sit below [`super::ModelDesc`]).

use serde::{Deserialize, Serialize};

use super::inertia::{self, Shape};
use crate::error::MbdError;

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
    /// `"planar"` (the default; a spatial file is read by
    /// [`SpatialDesc`](crate::spatial::SpatialDesc)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub space: Option<Space>,
    /// Gravitational acceleration (g_x, g_y), m/s² (default none).
    #[serde(default)]
    pub gravity: [f64; 2],
    /// Where the force pair of every revolute clearance joint acts: `common_point` (default,
    /// collinear action and reaction) or `contact_points` (Flores et al. 2004).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clearance_force_application: Option<ForceApplicationDesc>,
}

/// Which engine a model file is for: `[model] space`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Space {
    /// Bodies move in the x–y plane (x, y, θ per body); the default.
    #[default]
    Planar,
    /// Bodies move in space (position and orientation quaternion per body).
    Spatial,
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
/// Mass and inertia are given (`mass`, `inertia`) or computed from a homogeneous `shape` and its
/// `material` or `density` ([`inertia`](super::inertia), Meriam & Kraige Table D/4); the shape's
/// centre is then the frame origin and the centre of mass. `between` places a link by its two
/// ends instead of `position` and `angle` ([`inertia::between`](super::inertia::between)).
/// [`Body::resolve`] gives the values used.
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
    /// Mass, kg (> 0); left out when `shape` computes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Moment of inertia about the centre of mass, kg·m² (> 0); left out when `shape`
    /// computes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<f64>,
    /// A homogeneous part whose mass, inertia and centre of mass (its centre, at the frame
    /// origin) the body takes (with `material` or `density`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<Shape>,
    /// A named material of [`MATERIALS`](super::inertia::MATERIALS) giving the shape's density.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// The shape's density, kg/m³ (instead of `material`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f64>,
    /// The link's two ends `[[x_a, y_a], [x_b, y_b]]` in world coordinates at the assembly
    /// position, m: the frame at their midpoint with its x axis from a to b (a at [−L/2, 0] and
    /// b at [L/2, 0] in the body frame), and the length of a bar, plate, rod or tube; instead
    /// of `position` and `angle`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub between: Option<[[f64; 2]; 2]>,
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
    /// Centre of mass in the body frame, m (default [0, 0]; with `shape` it is the shape's
    /// centre, [0, 0], and another value is refused).
    #[serde(default, skip_serializing_if = "is_zero2")]
    pub centre_of_mass: [f64; 2],
}

/// The values a [`Body`] stands for: mass, inertia and centre of mass given or computed from
/// its shape, pose given or computed from `between`.
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedBody {
    /// Mass, kg.
    pub mass: f64,
    /// Moment of inertia about the centre of mass, kg·m².
    pub inertia: f64,
    /// Centre of mass in the body frame, m.
    pub centre_of_mass: [f64; 2],
    /// Initial position of the frame origin, m (`None`: solved).
    pub position: Option<[f64; 2]>,
    /// Initial angle, rad (`None`: solved).
    pub angle: Option<f64>,
    /// The length of a bar, plate, rod or tube, m (given or from `between`); `None` without
    /// a shape or for a box or disc.
    pub length: Option<f64>,
    /// What was computed, in words (for the run's notes); `None` when everything was given.
    pub note: Option<String>,
}

impl Body {
    /// A body of given `mass` (kg) and `inertia` (kg·m², about the centre of mass), every
    /// other field left out (its pose and velocity solved by the assembly).
    pub fn new(name: impl Into<String>, mass: f64, inertia: f64) -> Self {
        Self {
            name: name.into(),
            mass: Some(mass),
            inertia: Some(inertia),
            shape: None,
            material: None,
            density: None,
            between: None,
            position: None,
            angle: None,
            velocity: None,
            angular_velocity: None,
            centre_of_mass: [0.0, 0.0],
        }
    }

    /// Which centre-of-mass coordinates (x, y, θ, v_x, v_y, ω) the description fixes: a
    /// position is fixed when it is given (or `between` gives it) and, with a centre of mass
    /// off the frame origin, the angle is given too (the centre of mass moves with the angle);
    /// likewise the velocity with the angular velocity.
    pub fn fixed_coordinates(&self) -> [bool; 6] {
        let on_origin = self.centre_of_mass == [0.0, 0.0];
        let placed = self.between.is_some();
        let (p, a) = (
            self.position.is_some() || placed,
            self.angle.is_some() || placed,
        );
        let (v, w) = (self.velocity.is_some(), self.angular_velocity.is_some());
        let pos = p && (a || on_origin);
        let vel = v && (w || on_origin);
        [pos, pos, a, vel, vel, w]
    }

    /// The mass, inertia, centre of mass and pose the body stands for, every input used or
    /// refused: `shape` with exactly one of `material` and `density` and without `mass`,
    /// `inertia` or `centre_of_mass`; otherwise `mass` and `inertia`; `between` without
    /// `position` or `angle`.
    ///
    /// # Errors
    /// [`MbdError::Invalid`] at the field (`crank.shape.bar.width`, `crank.mass`) saying what
    /// to change.
    pub fn resolve(&self) -> Result<ResolvedBody, MbdError> {
        let at = |field: &str, message: String| MbdError::Invalid {
            path: format!("{}.{field}", self.name),
            message,
        };
        let placement = match self.between {
            Some([a, b]) => {
                self.refuse_given(
                    &[
                        ("position", self.position.is_some()),
                        ("angle", self.angle.is_some()),
                    ],
                    |field| {
                        format!(
                            "`{field}` and `between` are both given: `between` sets the \
                             position (the midpoint) and the angle; remove one of them"
                        )
                    },
                )?;
                Some(inertia::between(a, b).map_err(|e| at(e.field, e.message))?)
            }
            None => None,
        };
        let span = placement.map(|p| p.length);
        let length = match &self.shape {
            Some(shape) => shape.length(span).ok().flatten(),
            None => None,
        };
        let (mass, inertia, com, computed) = match &self.shape {
            Some(shape) => self.mass_from_shape(shape, span)?,
            None => {
                self.refuse_given(
                    &[
                        ("material", self.material.is_some()),
                        ("density", self.density.is_some()),
                    ],
                    |field| {
                        format!(
                            "`{field}` is used only with `shape`: give the part's `shape` \
                             (bar, plate, box, rod, tube, disc), or remove `{field}`"
                        )
                    },
                )?;
                let need = |field: &str, v: Option<f64>| {
                    v.ok_or_else(|| {
                        at(
                            field,
                            format!(
                                "missing value: give `{field}`; a body has `mass` (kg) and `inertia` (kg·m²), or \
                                 a `shape` with its `material` or `density` to compute them"
                            ),
                        )
                    })
                };
                let (m, i) = (need("mass", self.mass)?, need("inertia", self.inertia)?);
                (m, i, self.centre_of_mass, None)
            }
        };
        let mut words: Vec<String> = computed.into_iter().collect();
        if let (Some(l), Some(d)) = (length, span) {
            if (l - d).abs() > inertia::LENGTH_TOLERANCE * d {
                words.push(format!(
                    "the given length {l} m is used, while the `between` points are {d:e} m \
                     apart ({:.2e} relative): the assembly of the initial conditions corrects \
                     the pose to the joints",
                    (l - d).abs() / d
                ));
            }
        }
        if let Some(p) = placement {
            words.push(format!(
                "position = [{:e}, {:e}] m (midpoint of `between`), angle = {:e} rad, \
                 ends at [∓{:e}, 0] m in the body frame",
                p.position[0],
                p.position[1],
                p.angle,
                0.5 * length.unwrap_or(p.length)
            ));
        }
        Ok(ResolvedBody {
            mass,
            inertia,
            centre_of_mass: com,
            position: placement.map(|p| p.position).or(self.position),
            angle: placement.map(|p| p.angle).or(self.angle),
            length,
            note: (!words.is_empty())
                .then(|| format!("body `{}`: {}", self.name, words.join("; "))),
        })
    }

    /// Refuse the first field of `fields` (name, given) that is given, at `<body>.<field>`,
    /// with the message `why(field)`.
    fn refuse_given(
        &self,
        fields: &[(&str, bool)],
        why: impl Fn(&str) -> String,
    ) -> Result<(), MbdError> {
        match fields.iter().find(|(_, given)| *given) {
            Some((field, _)) => Err(MbdError::Invalid {
                path: format!("{}.{field}", self.name),
                message: why(field),
            }),
            None => Ok(()),
        }
    }

    /// Mass, inertia, centre of mass and the note of a body given by its shape; `span` is the
    /// distance of the `between` points, m.
    fn mass_from_shape(
        &self,
        shape: &Shape,
        span: Option<f64>,
    ) -> Result<(f64, f64, [f64; 2], Option<String>), MbdError> {
        let at = |field: &str, message: String| MbdError::Invalid {
            path: format!("{}.{field}", self.name),
            message,
        };
        self.refuse_given(
            &[
                ("mass", self.mass.is_some()),
                ("inertia", self.inertia.is_some()),
                ("centre_of_mass", !is_zero2(&self.centre_of_mass)),
            ],
            |field| {
                format!(
                    "`{field}` and `shape` are both given: the shape computes the mass, the \
                     inertia and the centre of mass (its centre, at the frame origin); remove \
                     `{field}`, or remove `shape` and give `mass` and `inertia`"
                )
            },
        )?;
        let (density, from) = match (&self.material, self.density) {
            (Some(_), Some(_)) => {
                return Err(at(
                    "density",
                    "`material` and `density` are both given: keep one".into(),
                ))
            }
            (Some(name), None) => {
                let m = inertia::material(name).map_err(|e| at(e.field, e.message))?;
                (m.density, format!("{} ({})", m.name, m.source))
            }
            (None, Some(rho)) => (rho, "`density`".to_string()),
            (None, None) => {
                return Err(at(
                    "material",
                    format!(
                        "a `shape` needs `material` (one of {}) or `density` (kg/m³)",
                        inertia::MATERIALS.map(|m| m.name).join(", ")
                    ),
                ))
            }
        };
        let p = shape.mass_properties(density, span).map_err(|e| {
            let field = if matches!(e.field, "density" | "material") {
                e.field.to_string()
            } else {
                format!("shape.{}.{}", shape.kind(), e.field)
            };
            at(&field, e.message)
        })?;
        let length = match shape.length(span) {
            Ok(Some(l)) => format!(", length {l:e} m"),
            _ => String::new(),
        };
        let note = format!(
            "{}{length} of density {density} kg/m³ from {from}: mass = {:e} kg, inertia = \
             {:e} kg·m² about the centre of mass, centre of mass = [0, 0] m (the frame origin)",
            shape.kind(),
            p.mass,
            p.inertia
        );
        Ok((p.mass, p.inertia, p.centre_of_mass, Some(note)))
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
