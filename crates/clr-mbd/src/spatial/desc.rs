//! The spatial model description: plain data (serde), read from a model file with
//! `[model] space = "spatial"` (docs/model-file.md "Spatial models"). Solver and output settings,
//! time functions and contact laws are the planar description's own types.

use serde::{Deserialize, Serialize};

use crate::desc::{FrictionLawDesc, NormalLawDesc, OutputSettings, SolverSettings};
use crate::timefn::TimeFn;

pub use crate::desc::parts::Space;

/// `[model]` of a spatial model.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpatialInfo {
    /// Model name (used in reports).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// One-line description.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// `"spatial"`.
    pub space: Space,
    /// Gravitational acceleration (g_x, g_y, g_z), m/s² (default none).
    #[serde(default)]
    pub gravity: [f64; 3],
}

/// The frame a given vector is expressed in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VectorFrame {
    /// The world (inertial) frame.
    World,
    /// The body's own frame (its axes at the current orientation).
    Body,
}

/// An orientation in one of four forms; the engine stores the unit quaternion
/// ([`Orientation::quaternion`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged, deny_unknown_fields)]
pub enum Orientation {
    /// `{ quaternion = [w, x, y, z] }`: scalar first, normalized on reading (a norm off 1 by
    /// more than 1e-6 is refused as a likely typo).
    Quaternion {
        /// (w, x, y, z).
        quaternion: [f64; 4],
    },
    /// `{ matrix = [[…], […], […]] }`: the rotation matrix body → world, rows; orthonormal to
    /// 1e-6 with determinant +1.
    Matrix {
        /// Rows of A.
        matrix: [[f64; 3]; 3],
    },
    /// `{ axis = [x, y, z], angle = θ }`: θ in rad about the axis (normalized).
    AxisAngle {
        /// Rotation axis (world), any length > 0.
        axis: [f64; 3],
        /// Angle, rad.
        angle: f64,
    },
    /// `{ euler = [a, b, c], sequence = "zyx" }`: three angles in rad about the moving axes in
    /// the order named (intrinsic; "zyx" is yaw–pitch–roll, "zxz" the classical Euler angles).
    Euler {
        /// The three angles, rad.
        euler: [f64; 3],
        /// Axis sequence: three letters of x, y, z, no two neighbours equal.
        sequence: String,
    },
}

/// A spatial rigid body. Its frame is at `position` with `orientation`; the centre of mass sits
/// at `centre_of_mass` in that frame. Anchors on the body are given in this frame. Result
/// columns are those of the centre of mass.
///
/// As for planar bodies, an initial-state field that is given is fixed (kept by the assembly of
/// initial conditions unless the constraints forbid it, which is reported) and one left out is
/// solved.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpatialBody {
    /// Unique name.
    pub name: String,
    /// Mass, kg (> 0).
    pub mass: f64,
    /// Inertia tensor at the centre of mass in the body frame, kg·m², rows of a symmetric
    /// positive definite 3 × 3 matrix (products of inertia with the sign of the tensor:
    /// I_xy = −∫xy dm). Or give `principal_inertia`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<[[f64; 3]; 3]>,
    /// Principal moments of inertia at the centre of mass, kg·m² (satisfying the triangle
    /// inequalities), along `principal_axes` (default the body axes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub principal_inertia: Option<[f64; 3]>,
    /// The principal axes as rows (unit vectors in the body frame, right-handed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub principal_axes: Option<[[f64; 3]; 3]>,
    /// Centre of mass in the body frame, m (default the frame origin).
    #[serde(default)]
    pub centre_of_mass: [f64; 3],
    /// Initial position of the body frame's origin, m (world).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<[f64; 3]>,
    /// Initial orientation (default: aligned with the world).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<Orientation>,
    /// Initial velocity of the body frame's origin, m/s, in `velocity_frame`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<[f64; 3]>,
    /// Frame of `velocity` (required with it): `world` or `body`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity_frame: Option<VectorFrame>,
    /// Initial angular velocity, rad/s, in `angular_velocity_frame`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angular_velocity: Option<[f64; 3]>,
    /// Frame of `angular_velocity` (required with it): `world` or `body`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angular_velocity_frame: Option<VectorFrame>,
}

/// Where a joint, force or contact attaches: a body (or `"ground"`) and a point in its frame, m;
/// joints also take an `axis` (a direction in the same frame).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct End {
    /// Body name, or `"ground"` (then `at` and `axis` are world).
    pub body: String,
    /// Point in the body frame, m.
    #[serde(default)]
    pub at: [f64; 3],
    /// Axis direction in the body frame (normalized); which joints need it: [`JointKind`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<[f64; 3]>,
}

/// Kinds of spatial ideal joints (`type` in `[[joint]]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointKind {
    /// The two ends coincide; `axis` refused (3 equations).
    Spherical,
    /// The ends coincide and b turns about `a.axis` (5 equations; `b.axis` defaults to a's
    /// axis at the initial poses).
    Revolute,
    /// The ends coincide; `a.axis` on a and `b.axis` on b stay perpendicular (4 equations; the
    /// cross of a Cardan joint).
    Universal,
    /// b slides along and turns about `a.axis` through a's point (4 equations).
    Cylindrical,
    /// b slides along `a.axis` without turning (5 equations).
    Prismatic,
    /// b moves in the plane through a's point with normal `a.axis` (3 equations).
    Planar,
    /// b is welded to a at the initial poses (6 equations); `axis` refused.
    Fixed,
}

/// An ideal joint between two ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpatialJoint {
    /// Unique name.
    pub name: String,
    /// Kind.
    #[serde(rename = "type")]
    pub kind: JointKind,
    /// First end (the reference side: reactions are reported on b).
    pub a: End,
    /// Second end.
    pub b: End,
}

/// What a driver prescribes (`type` in `[[driver]]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DriverKind {
    /// The angle of a revolute or cylindrical joint, rad: b's turn about the axis relative to
    /// a, zero at the initial poses.
    RevoluteAngle,
    /// The displacement of a prismatic or cylindrical joint along its axis, m, zero at the
    /// initial poses.
    PrismaticDisplacement,
}

/// A prescribed joint motion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpatialDriver {
    /// Unique name.
    pub name: String,
    /// Kind.
    #[serde(rename = "type")]
    pub kind: DriverKind,
    /// The joint it drives.
    pub joint: String,
    /// The prescribed angle (rad) or displacement (m) as a function of time.
    pub motion: TimeFn,
}

/// Force elements (`type` in `[[force]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum SpatialForce {
    /// Point-to-point spring–damper: tension k(ℓ − ℓ₀) + c ℓ̇ along the line between a and b.
    SpringDamper {
        /// Unique name.
        name: String,
        /// First end (`axis` refused).
        a: End,
        /// Second end.
        b: End,
        /// k, N/m.
        #[serde(default)]
        stiffness: f64,
        /// c, N·s/m.
        #[serde(default)]
        damping: f64,
        /// ℓ₀, m.
        #[serde(default)]
        free_length: f64,
    },
    /// Point-to-point actuator: force f(t) (N, positive pushing a and b apart).
    Actuator {
        /// Unique name.
        name: String,
        /// First end.
        a: End,
        /// Second end.
        b: End,
        /// Force, N.
        force: TimeFn,
    },
    /// Rotational spring–damper about the axis of a revolute or cylindrical joint: torque
    /// −k(θ − θ₀) − c θ̇ on b (and the opposite on a), θ the joint angle (zero at the initial
    /// poses, in (−π, π]).
    RotationalSpringDamper {
        /// Unique name.
        name: String,
        /// The joint.
        joint: String,
        /// k, N·m/rad.
        #[serde(default)]
        stiffness: f64,
        /// c, N·m·s/rad.
        #[serde(default)]
        damping: f64,
        /// θ₀, rad.
        #[serde(default)]
        free_angle: f64,
    },
    /// Six-axis bushing between a's frame (a's body axes at its point) and b's point: force
    /// −K_t Δx − C_t Δẋ and moment −K_r Δφ − C_r Δω, Δx the offset of b's point from a's and Δφ
    /// the rotation vector of b relative to a since the initial poses, both in a's axes.
    Bushing {
        /// Unique name.
        name: String,
        /// First end.
        a: End,
        /// Second end.
        b: End,
        /// (k_x, k_y, k_z), N/m.
        #[serde(default)]
        stiffness: [f64; 3],
        /// (c_x, c_y, c_z), N·s/m.
        #[serde(default)]
        damping: [f64; 3],
        /// Rotational stiffness about a's x, y, z, N·m/rad.
        #[serde(default)]
        rotational_stiffness: [f64; 3],
        /// Rotational damping, N·m·s/rad.
        #[serde(default)]
        rotational_damping: [f64; 3],
    },
    /// Applied force at a point, components f(t) in N in `frame`.
    Force {
        /// Unique name.
        name: String,
        /// Point of application.
        at: End,
        /// Frame of the components: `world` or `body`.
        frame: VectorFrame,
        /// x component, N.
        #[serde(default = "zero")]
        fx: TimeFn,
        /// y component, N.
        #[serde(default = "zero")]
        fy: TimeFn,
        /// z component, N.
        #[serde(default = "zero")]
        fz: TimeFn,
    },
    /// Applied torque on a body, components f(t) in N·m in `frame`.
    Torque {
        /// Unique name.
        name: String,
        /// Body.
        body: String,
        /// Frame of the components: `world` or `body`.
        frame: VectorFrame,
        /// x component, N·m.
        #[serde(default = "zero")]
        mx: TimeFn,
        /// y component, N·m.
        #[serde(default = "zero")]
        my: TimeFn,
        /// z component, N·m.
        #[serde(default = "zero")]
        mz: TimeFn,
    },
}

fn zero() -> TimeFn {
    TimeFn::Constant { value: 0.0 }
}

impl SpatialForce {
    /// The element's name.
    pub fn name(&self) -> &str {
        match self {
            Self::SpringDamper { name, .. }
            | Self::Actuator { name, .. }
            | Self::RotationalSpringDamper { name, .. }
            | Self::Bushing { name, .. }
            | Self::Force { name, .. }
            | Self::Torque { name, .. } => name,
        }
    }
}

/// A spherical clearance joint (ball in socket, `type = "spherical"` in `[[clearance]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphericalClearance {
    /// Unique name.
    pub name: String,
    /// `"spherical"`.
    #[serde(rename = "type")]
    pub kind: ClearanceKind,
    /// Centre of the socket (on its body).
    pub socket: End,
    /// Centre of the ball (on its body).
    pub ball: End,
    /// Socket radius R_s, m.
    pub socket_radius: f64,
    /// Ball radius R_b, m (R_b < R_s; R_b = R_s is the ideal spherical joint).
    pub ball_radius: f64,
    /// Normal-force law: `hertz`, `power`, `linear` with their stiffness, or
    /// `hertz-internal-sphere` from `bearing_material` (socket) and `journal_material` (ball),
    /// K = (4/3)E*√(R_sR_b/(R_s − R_b)); any damping factor.
    pub normal: NormalLawDesc,
    /// Friction law (default none): every law of the planar joints, the slip velocity being
    /// the vector in the tangent plane; LuGre with a vector bristle state.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<FrictionLawDesc>,
}

/// Kinds of spatial clearance joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClearanceKind {
    /// Ball in socket ([`SphericalClearance`]).
    Spherical,
    /// Journal in bearing with thrust faces ([`JournalClearanceDesc`]).
    Revolute,
    /// Journal in bearing without thrust faces ([`JournalClearanceDesc`]).
    Cylindrical,
    /// Two `[[shape]]`s in contact ([`ShapeContactDesc3`]).
    Contact,
}

/// A spatial revolute or cylindrical clearance joint (`type = "revolute"` or `"cylindrical"` in
/// `[[clearance]]`): a journal of finite length in a bore of finite length, which can tilt, touch
/// at the bore's rims and (revolute) slide axially against its thrust faces (clr-contact
/// `journal`, docs/contact.md "Spatial journal in bearing"). A misaligned bearing is a bearing
/// axis tilted in its body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JournalClearanceDesc {
    /// Unique name.
    pub name: String,
    /// `"revolute"` or `"cylindrical"`.
    #[serde(rename = "type")]
    pub kind: ClearanceKind,
    /// Centre of the bore (mid-length) and its axis, on the bearing body.
    pub bearing: End,
    /// Centre of the journal (mid-length) and its axis, on the journal body.
    pub journal: End,
    /// Bore radius R_b, m.
    pub bearing_radius: f64,
    /// Bore length L_b, m.
    pub bearing_length: f64,
    /// Journal radius R_j < R_b, m.
    pub journal_radius: f64,
    /// Journal length L_j, m.
    pub journal_length: f64,
    /// Total axial end play c_a between the collars and the bearing's end faces, m (revolute
    /// only, required there).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial_clearance: Option<f64>,
    /// Outer radius R_t of the thrust collars, m (revolute only; default R_j).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thrust_radius: Option<f64>,
    /// Gauss–Legendre order per wetted region (1..=32; default 10).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quadrature_order: Option<usize>,
    /// Radial normal-force law: the total force F_N(δ) of a journal of contact length
    /// L_c = min(L_b, L_j), integrated along the wetted length as F_N/L_c per unit length. Every
    /// law of the planar revolute clearance joint; the line laws that take a `length` (liu,
    /// johnson, pereira, presets with length) get L_c (do not give `length`).
    pub normal: NormalLawDesc,
    /// Point law of the thrust faces (revolute only; default: the radial law object).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thrust_normal: Option<NormalLawDesc>,
    /// Friction law (default none): stateless laws only (LuGre is refused), applied at every
    /// Gauss point and thrust point.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<FrictionLawDesc>,
    /// An oil film in the joint (default none): clr-contact `JournalFilm`, docs/lubrication.md
    /// §13; its length is the overlap of journal and bore.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lubrication: Option<JournalLubricationDesc>,
}

/// `lubrication = { model, viscosity, film_threshold, dry_threshold }` of a spatial journal
/// joint: the planar joint's fields without `length` (the film length is the overlap of journal
/// and bore, from the geometry; a `length` is refused with that reason).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JournalLubricationDesc {
    /// `short_bearing` (Ocvirk) or `long_bearing` (Sommerfeld, half film).
    pub model: crate::element::revolute_clearance::LubricationModel,
    /// Dynamic viscosity μ of the lubricant, Pa·s.
    pub viscosity: f64,
    /// Film threshold h_t, m (> 0): the film force is frozen below this minimum film thickness.
    pub film_threshold: f64,
    /// Dry threshold h_d, m (0 ≤ h_d < h_t, default 0).
    #[serde(default)]
    pub dry_threshold: f64,
    /// Refused when given (read only to say why): the film length comes from the geometry, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
}

/// One `[[clearance]]` of a spatial model: a ball in a socket, or a journal in a bearing.
// plain data read once per model file: the variants' sizes do not matter
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum SpatialClearance {
    /// `type = "spherical"`.
    Spherical(SphericalClearance),
    /// `type = "revolute"` or `"cylindrical"`.
    Journal(JournalClearanceDesc),
    /// `type = "contact"`: two shapes.
    Contact(ShapeContactDesc3),
}

impl SpatialClearance {
    /// The joint's name.
    pub fn name(&self) -> &str {
        match self {
            Self::Spherical(s) => &s.name,
            Self::Journal(j) => &j.name,
            Self::Contact(c) => &c.name,
        }
    }
    /// Radial clearance, m (socket − ball radius, or bore − journal radius; NaN for a shape
    /// contact, which has none: see [`SpatialClearance::clearance`]).
    pub fn radial_clearance(&self) -> f64 {
        self.clearance().unwrap_or(f64::NAN)
    }
    /// Radial clearance of a joint, m; `None` for a shape contact.
    pub fn clearance(&self) -> Option<f64> {
        match self {
            Self::Spherical(s) => Some(s.socket_radius - s.ball_radius),
            Self::Journal(j) => Some(j.bearing_radius - j.journal_radius),
            Self::Contact(_) => None,
        }
    }
}

impl From<ShapeContactDesc3> for SpatialClearance {
    fn from(c: ShapeContactDesc3) -> Self {
        Self::Contact(c)
    }
}

impl From<SphericalClearance> for SpatialClearance {
    fn from(s: SphericalClearance) -> Self {
        Self::Spherical(s)
    }
}

impl From<JournalClearanceDesc> for SpatialClearance {
    fn from(j: JournalClearanceDesc) -> Self {
        Self::Journal(j)
    }
}

impl Serialize for SpatialClearance {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Spherical(c) => c.serialize(s),
            Self::Journal(c) => c.serialize(s),
            Self::Contact(c) => c.serialize(s),
        }
    }
}

/// `[[shape]]` of a spatial model: a contact shape on a body or the ground. Its frame sits at
/// `at` (a point in the body frame) turned by `orientation` from the body axes; the geometry is
/// written in that frame (m). Shapes do nothing on their own; a `[[clearance]]` of
/// `type = "contact"` ([`ShapeContactDesc3`]) puts two of them in contact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpatialShape {
    /// Unique name (contact elements refer to it).
    pub name: String,
    /// Origin of the shape frame: `{ body, at = [x, y, z] }` (the ground is `"ground"`); no
    /// `axis`.
    pub at: End,
    /// Orientation of the shape frame relative to the body frame (default: the body axes), in
    /// any form of [`Orientation`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<Orientation>,
    /// The geometry in the shape frame.
    pub geometry: Geometry3,
}

/// The geometry of a spatial shape, tagged by `type` (m; clr-contact [`clr_contact::Shape3`]).
/// Axially symmetric shapes (capsule, cylinder, cone) have their axis along the shape x axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum Geometry3 {
    /// A sphere centred on the shape origin.
    Ball {
        /// Radius, m.
        radius: f64,
    },
    /// A segment along x from −`half_length` to `half_length`, dilated by `radius`.
    Capsule {
        /// Half length of the core segment, m.
        half_length: f64,
        /// Radius, m.
        radius: f64,
    },
    /// A box centred on the shape origin.
    Cuboid {
        /// Half widths along x, y, z, m.
        half_extents: [f64; 3],
    },
    /// A solid cylinder centred on the origin, axis along x, flat ends at x = ±`half_length`.
    Cylinder {
        /// Half length, m.
        half_length: f64,
        /// Radius, m.
        radius: f64,
    },
    /// A solid cone along x: base of `radius` at x = −`half_length`, apex at +`half_length`.
    Cone {
        /// Half the height, m.
        half_length: f64,
        /// Base radius, m.
        radius: f64,
    },
    /// The convex hull of its vertices (every point must be a vertex or on the boundary), m.
    ConvexPolyhedron {
        /// At least 4 points, not in one plane.
        points: Vec<[f64; 3]>,
    },
    /// A triangle mesh (contact with the triangles from either side), m.
    Trimesh {
        /// Vertices, m.
        vertices: Vec<[f64; 3]>,
        /// Triangles as three vertex indices counted from 0.
        indices: Vec<[u32; 3]>,
    },
    /// Convex parts (ball, capsule, cuboid, cylinder, cone, convex polyhedron) at poses in the
    /// shape frame.
    Compound {
        /// The parts.
        parts: Vec<Part3>,
    },
}

/// One convex part of a compound spatial shape.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Part3 {
    /// Origin of the part in the shape frame, m.
    #[serde(default)]
    pub at: [f64; 3],
    /// Orientation of the part in the shape frame (default the shape axes; at most one turn).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<Orientation>,
    /// The part's geometry (convex).
    pub geometry: Geometry3,
}

/// `[[clearance]] type = "contact"` of a spatial model: two `[[shape]]`s in contact, the normal
/// pointing from `shapes[0]` (A) to `shapes[1]` (B). The fields are those of the planar shape
/// contact (docs/model-file.md "Shapes and shape contact").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeContactDesc3 {
    /// Unique name.
    pub name: String,
    /// `"contact"`.
    #[serde(rename = "type")]
    pub kind: ClearanceKind,
    /// The two shapes (names of `[[shape]]` items) on different bodies.
    pub shapes: [String; 2],
    /// Normal-force law of each contact point (`hertz`, `power` or `linear` with `stiffness`).
    pub normal: NormalLawDesc,
    /// Friction law of each contact point in its tangent plane (default none; stateless laws,
    /// LuGre refused).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<FrictionLawDesc>,
    /// Gap within which points are tracked before they touch, m (default a tenth of the smaller
    /// shape's bounding radius).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prediction: Option<f64>,
    /// Points of one contact patch closer than this merge into the deepest, m (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub merge_distance: Option<f64>,
    /// Most contact points at once (default 4, 1–64; each has its own impact memory).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_points: Option<usize>,
}

/// Marks an error message of a `[[clearance]]` table whose path continues inside the table
/// (joined back by [`SpatialDesc::from_toml_table`]).
const INNER_PATH: &str = "\u{1}at ";

impl<'de> Deserialize<'de> for SpatialClearance {
    /// By its `type`: the table is read as the matching struct, and an error keeps the path of
    /// the field inside it.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let v = toml::Value::deserialize(d)?;
        // the kind as serde reads it (its message lists the kinds, which the Python builder's
        // probes parse)
        let kind = match v.get("type") {
            Some(t) => ClearanceKind::deserialize(t.clone())
                .map_err(|e| D::Error::custom(format!("{INNER_PATH}type\u{1}{}", e.message())))?,
            None => return Err(D::Error::missing_field("type")),
        };
        let inner = |e: serde_path_to_error::Error<toml::de::Error>| {
            D::Error::custom(format!(
                "{INNER_PATH}{}\u{1}{}",
                e.path(),
                e.inner().message()
            ))
        };
        match kind {
            ClearanceKind::Revolute | ClearanceKind::Cylindrical => {
                serde_path_to_error::deserialize(v)
                    .map(Self::Journal)
                    .map_err(inner)
            }
            ClearanceKind::Spherical => serde_path_to_error::deserialize(v)
                .map(Self::Spherical)
                .map_err(inner),
            ClearanceKind::Contact => serde_path_to_error::deserialize(v)
                .map(Self::Contact)
                .map_err(inner),
        }
    }
}

/// A whole spatial model as data (`[model] space = "spatial"`). Sections: `[model]`,
/// `[[body]]`, `[[joint]]`, `[[driver]]`, `[[force]]`, `[[shape]]`, `[[clearance]]`, `[solver]`,
/// `[output]`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpatialDesc {
    /// Name, description, space, gravity.
    pub model: SpatialInfo,
    /// Rigid bodies.
    #[serde(default, rename = "body", skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<SpatialBody>,
    /// Ideal joints.
    #[serde(default, rename = "joint", skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<SpatialJoint>,
    /// Drivers.
    #[serde(default, rename = "driver", skip_serializing_if = "Vec::is_empty")]
    pub drivers: Vec<SpatialDriver>,
    /// Force elements.
    #[serde(default, rename = "force", skip_serializing_if = "Vec::is_empty")]
    pub forces: Vec<SpatialForce>,
    /// Contact shapes on bodies or the ground (used by `type = "contact"` clearances).
    #[serde(default, rename = "shape", skip_serializing_if = "Vec::is_empty")]
    pub shapes: Vec<SpatialShape>,
    /// Clearance joints and shape contacts.
    #[serde(default, rename = "clearance", skip_serializing_if = "Vec::is_empty")]
    pub clearances: Vec<SpatialClearance>,
    /// Integrator settings (as planar models).
    #[serde(default)]
    pub solver: SolverSettings,
    /// Time span and output times (as planar models).
    #[serde(default)]
    pub output: OutputSettings,
    /// Named outputs: points' positions, velocities and accelerations, distances
    /// ([`SpatialMeasure`]).
    #[serde(default, rename = "measure", skip_serializing_if = "Vec::is_empty")]
    pub measures: Vec<SpatialMeasure>,
    /// Numbers taken of columns over time windows, as in planar files
    /// ([`MetricDesc`](crate::desc::metric::MetricDesc); `twin` is refused).
    #[serde(default, rename = "metric", skip_serializing_if = "Vec::is_empty")]
    pub metrics: Vec<crate::desc::metric::MetricDesc>,
}

impl SpatialDesc {
    /// Read a description from a parsed model file, with the path of the offending field on
    /// error.
    ///
    /// # Errors
    /// [`crate::FieldError`] at the offending field.
    pub fn from_toml_table(table: toml::Table) -> Result<Self, crate::FieldError> {
        serde_path_to_error::deserialize::<_, Self>(toml::Value::Table(table)).map_err(|e| {
            let (path, msg) = (e.path().to_string(), e.inner().message().to_string());
            // a [[clearance]] table's own error: the path continues inside it
            match msg
                .strip_prefix(INNER_PATH)
                .and_then(|m| m.split_once('\u{1}'))
            {
                Some((inner, m)) => crate::FieldError::new(format!("{path}.{inner}"), m),
                None => crate::FieldError::new(path, msg),
            }
        })
    }

    /// The simulation options of `solver` and `output`.
    ///
    /// # Errors
    /// [`crate::FieldError`] for invalid settings.
    pub fn sim_options(&self) -> Result<crate::SimOptions, crate::FieldError> {
        crate::desc::sim_options_of(&self.solver, &self.output)
    }

    /// The description as TOML text.
    ///
    /// # Errors
    /// The serializer's message.
    pub fn to_toml(&self) -> Result<String, String> {
        toml::to_string(self).map_err(|e| e.to_string())
    }
}

const _: () = {
    const fn assert_plain_data<T: Clone + Send + Sync + 'static>() {}
    assert_plain_data::<SpatialDesc>();
};

/// `[[measure]]` of a spatial file (`type` is the kind; computed by `super::measure`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum SpatialMeasure {
    /// Position of a point, m: `<name>.x .y .z`.
    Position(PointMeasure),
    /// Velocity of a point, m/s: `<name>.vx .vy .vz`.
    Velocity(PointMeasure),
    /// Acceleration of a point, m/s²: `<name>.ax .ay .az`.
    Acceleration(PointMeasure),
    /// Distance between two points, m, and its rate, m/s: `<name>.distance .distance_rate`.
    Distance(DistanceMeasure),
}

/// A point of a body, in the world frame or in the frame of `frame`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointMeasure {
    /// Name: the columns' prefix.
    pub name: String,
    /// The body and the point in its frame, m (`axis` is refused).
    pub at: End,
    /// A body whose frame the coordinates are taken in (default: the world).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame: Option<String>,
}

/// Two points of bodies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DistanceMeasure {
    /// Name: the columns' prefix.
    pub name: String,
    /// First point (body and point in its frame, m).
    pub a: End,
    /// Second point.
    pub b: End,
}

impl SpatialMeasure {
    /// Its name.
    pub fn name(&self) -> &str {
        match self {
            SpatialMeasure::Position(p)
            | SpatialMeasure::Velocity(p)
            | SpatialMeasure::Acceleration(p) => &p.name,
            SpatialMeasure::Distance(d) => &d.name,
        }
    }

    /// The columns it writes.
    pub fn columns(&self) -> Vec<String> {
        let suffixes: &[&str] = match self {
            SpatialMeasure::Position(_) => &["x", "y", "z"],
            SpatialMeasure::Velocity(_) => &["vx", "vy", "vz"],
            SpatialMeasure::Acceleration(_) => &["ax", "ay", "az"],
            SpatialMeasure::Distance(_) => &["distance", "distance_rate"],
        };
        let n = self.name();
        suffixes.iter().map(|s| format!("{n}.{s}")).collect()
    }

    pub(crate) fn ends(&self) -> Vec<(&'static str, &End)> {
        match self {
            SpatialMeasure::Position(p)
            | SpatialMeasure::Velocity(p)
            | SpatialMeasure::Acceleration(p) => vec![("at", &p.at)],
            SpatialMeasure::Distance(d) => vec![("a", &d.a), ("b", &d.b)],
        }
    }
}
