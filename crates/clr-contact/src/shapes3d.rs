//! Contact between the shapes of bodies in space (balls, capsules, boxes, cylinders, cones,
//! convex polyhedra, triangle meshes and compounds), with `parry3d-f64` as the geometry engine:
//! the spatial counterpart of [`crate::shapes`], with the same design and conventions.
//!
//! * [`Shape3`] is plain data (SI units, body-frame coordinates) that a model file or a caller
//!   writes; [`Shape3::validate`] and the constructors ([`Shape3::ball`], …) refuse bad input
//!   with a [`ContactError`] that names the field and says what to change.
//! * [`ContactShape3`] is a validated [`Shape3`] converted once to its parry shape; build it
//!   when the model is built, not per force evaluation.
//! * [`contact_points3`] gives the contact points between two posed [`ContactShape3`]s, with
//!   clr-contact's conventions: penetration δ > 0 in contact, unit normal from A to B, world
//!   coordinates. The results go into a reusable [`ShapeContactWorkspace3`].
//! * [`BodyState3`] is the pose (position, unit quaternion) and twist of a body; only the pose
//!   enters the queries, the twist gives the relative velocity at a contact point
//!   ([`ShapeContactPoint3::relative_velocity`]).
//!
//! Axially symmetric shapes (capsule, cylinder, cone) have their axis along the body x axis,
//! as the planar capsule; a compound part's pose turns them to any other axis.
//!
//! parry works with glam vectors (`glamx`), not nalgebra. The conversion happens only at this
//! module's boundary, through the `From` impls of glamx's `nalgebra` feature (poses:
//! `Isometry3<f64>` → `DPose3`) and of nalgebra's `convert-glam033` feature that it turns on
//! (vectors both ways); no parry type appears in the API.
//!
//! The query is a pure function of the poses: parry's persistent-manifold shortcuts (reuse the
//! previous contact points when the relative pose barely changed, start GJK from the previous
//! normal) are switched off by clearing the cached points and normals before every query, so
//! the answer does not depend on the call history (rejected ODE steps, Jacobian
//! perturbations).

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{
    self, ContactManifold, ContactManifoldsWorkspace, DefaultQueryDispatcher,
    PersistentQueryDispatcher,
};
use parry3d_f64::shape::{ConvexPolyhedron, PackedFeatureId, SharedShape};

use crate::body::check_finite;
use crate::error::{positive, ContactError};
use crate::shapes::{check_prediction, finite_points};

const LAW: &str = "spatial contact shape";

/// Largest rotation angle of a compound part's rotation vector, rad: more is almost surely
/// degrees given for radians (as the spatial model file refuses angles beyond one turn).
const MAX_PART_ANGLE: f64 = std::f64::consts::TAU;

/// Largest departure of a pose quaternion's norm from 1 accepted by the queries.
const QUATERNION_NORM_TOLERANCE: f64 = 1e-6;

/// A GJK point that parry adds to a polygonal-feature manifold is reported only when it is
/// deeper than every clipped point of its manifold by more than this fraction of the smaller
/// shape's bounding radius (see [`contact_points3`]).
const GJK_POINT_MARGIN: f64 = 1e-6;

/// Pose and twist of a rigid body in space (SI units, world frame).
///
/// A point fixed on the body with body-frame coordinates s′ sits at r = r_k + R(q_k) s′ and
/// moves with ṙ = ṙ_k + ω × (r − r_k) (Haug, *Computer-Aided Kinematics and Dynamics of
/// Mechanical Systems*, 1989, §9.2), ω in the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyState3 {
    /// Position of the body-frame origin (the reference point), m.
    pub position: Vector3<f64>,
    /// Rotation body → world (unit quaternion; a norm off 1 by more than 1e-6 is refused by
    /// the queries).
    pub rotation: UnitQuaternion<f64>,
    /// Velocity of the reference point, m/s.
    pub velocity: Vector3<f64>,
    /// Angular velocity in the world frame, rad/s (the body-frame ω turned by `rotation`).
    pub angular_velocity: Vector3<f64>,
}

impl Default for BodyState3 {
    fn default() -> Self {
        Self::fixed(Vector3::zeros(), UnitQuaternion::identity())
    }
}

impl BodyState3 {
    /// A body at rest at `position` (m) with orientation `rotation` — e.g. the ground.
    pub fn fixed(position: Vector3<f64>, rotation: UnitQuaternion<f64>) -> Self {
        Self {
            position,
            rotation,
            velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
        }
    }

    /// A moving body: position (m), rotation, velocity (m/s), world angular velocity (rad/s).
    pub fn new(
        position: Vector3<f64>,
        rotation: UnitQuaternion<f64>,
        velocity: Vector3<f64>,
        angular_velocity: Vector3<f64>,
    ) -> Self {
        Self {
            position,
            rotation,
            velocity,
            angular_velocity,
        }
    }

    /// A moving body whose rotation is given as a rotation matrix A (body → world, orthonormal
    /// with determinant +1; converted by Shepperd's closed form, nalgebra
    /// `UnitQuaternion::from_rotation_matrix`).
    pub fn from_matrix(
        position: Vector3<f64>,
        rotation: &Matrix3<f64>,
        velocity: Vector3<f64>,
        angular_velocity: Vector3<f64>,
    ) -> Self {
        let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*rotation));
        Self::new(position, q, velocity, angular_velocity)
    }

    /// R s′: a body-fixed vector (body-frame coordinates) expressed in the world frame.
    pub fn rotate(&self, local: Vector3<f64>) -> Vector3<f64> {
        self.rotation * local
    }

    /// World position r_k + R s′ of the body-fixed point with body-frame coordinates `local`, m.
    pub fn point(&self, local: Vector3<f64>) -> Vector3<f64> {
        self.position + self.rotate(local)
    }

    /// Body-frame coordinates Rᵀ(r − r_k) of the world point `world`, m.
    pub fn to_local(&self, world: Vector3<f64>) -> Vector3<f64> {
        self.rotation
            .inverse_transform_vector(&(world - self.position))
    }

    /// Velocity ṙ_k + ω × (r − r_k) of the body's material point currently at `world`, m/s.
    pub fn point_velocity(&self, world: Vector3<f64>) -> Vector3<f64> {
        self.velocity + self.angular_velocity.cross(&(world - self.position))
    }

    /// The parry pose, after checking that it is finite and the quaternion is unit.
    fn pose(&self) -> Result<Pose, ContactError> {
        let p = &self.position;
        check_finite(
            LAW,
            &[
                ("body position x (m)", p.x),
                ("body position y (m)", p.y),
                ("body position z (m)", p.z),
            ],
        )?;
        let norm = self.rotation.as_ref().norm();
        if (norm - 1.0).abs() > QUATERNION_NORM_TOLERANCE || norm.is_nan() {
            return Err(ContactError::invalid(
                LAW,
                "body rotation quaternion norm",
                norm,
                "must be 1 to 1e-6 and finite; normalize the quaternion",
            ));
        }
        Ok(Isometry3::from_parts(Translation3::from(*p), self.rotation).into())
    }
}

/// Pose of a compound part in the body frame: a position (m) and a rotation vector (rad; the
/// rotation axis times the angle, at most one turn: the planar `[x, y, θ]` is
/// `position [x, y, 0]`, `rotation [0, 0, θ]`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PartPose3 {
    /// Position of the part's frame in the body frame, m.
    pub position: [f64; 3],
    /// Rotation vector of the part's frame relative to the body frame, rad.
    pub rotation: [f64; 3],
}

impl PartPose3 {
    /// The body frame itself.
    pub const IDENTITY: Self = Self {
        position: [0.0; 3],
        rotation: [0.0; 3],
    };

    /// A part at `position` (m) turned by the rotation vector `rotation` (rad).
    pub fn new(position: [f64; 3], rotation: [f64; 3]) -> Self {
        Self { position, rotation }
    }

    fn validate(&self, i: usize) -> Result<(), ContactError> {
        for c in self.position {
            check_finite(LAW, &[("compound part position (m)", c)])?;
        }
        for c in self.rotation {
            check_finite(LAW, &[("compound part rotation vector (rad)", c)])?;
        }
        let angle = Vector3::from(self.rotation).norm();
        if angle > MAX_PART_ANGLE {
            return Err(ContactError::invalid(
                LAW,
                "compound part rotation vector (rad)",
                angle,
                format!(
                    "part {i} turns by {angle} rad, more than one turn: the rotation vector is \
                     in rad (if it is in degrees, multiply it by π/180: angle {:.6} rad)",
                    angle.to_radians()
                ),
            ));
        }
        Ok(())
    }

    fn to_pose(self) -> Pose {
        Isometry3::new(Vector3::from(self.position), Vector3::from(self.rotation)).into()
    }
}

/// Plain-data description of a body's contact shape in space, in the body frame (m).
///
/// Build it with the validating constructors or write the variants directly and call
/// [`Shape3::validate`] (done again by [`ContactShape3::new`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape3 {
    /// A sphere centred on the body reference point.
    Ball {
        /// Radius, m (> 0).
        radius: f64,
    },
    /// A segment along the body x axis from −`half_length` to +`half_length`, dilated by
    /// `radius`.
    Capsule {
        /// Half length of the core segment, m (> 0).
        half_length: f64,
        /// Radius, m (> 0).
        radius: f64,
    },
    /// A box centred on the body reference point, edges along the body axes.
    Cuboid {
        /// Half widths along body x, y and z, m (all > 0).
        half_extents: [f64; 3],
    },
    /// A solid circular cylinder centred on the body reference point, axis along body x, flat
    /// ends at x = ±`half_length`.
    Cylinder {
        /// Half length along the axis, m (> 0).
        half_length: f64,
        /// Radius, m (> 0).
        radius: f64,
    },
    /// A solid circular cone, axis along body x: base disc of `radius` at x = −`half_length`,
    /// apex at x = +`half_length` (the reference point is half way, not the centroid).
    Cone {
        /// Half the height, m (> 0).
        half_length: f64,
        /// Radius of the base, m (> 0).
        radius: f64,
    },
    /// The convex hull of `points` (m), which must all be on its boundary: the vertices of a
    /// convex polyhedron, in any order (points on a face or an edge are accepted).
    ConvexPolyhedron {
        /// At least 4 points, not all in one plane.
        points: Vec<[f64; 3]>,
    },
    /// A triangle mesh (a terrain, a housing, a non-convex part's surface). The solid side is
    /// not defined: contact is with the triangles themselves, from either side.
    TriMesh {
        /// Vertices, m.
        vertices: Vec<[f64; 3]>,
        /// Triangles as three indices into `vertices`, counted from 0.
        indices: Vec<[u32; 3]>,
    },
    /// Several convex parts rigidly attached to the body, each at a [`PartPose3`] in the body
    /// frame. Parts may be balls, capsules, cuboids, cylinders, cones or convex polyhedra
    /// (parry does not nest composite shapes).
    Compound {
        /// `(pose, part)` pairs (at least one).
        parts: Vec<(PartPose3, Shape3)>,
    },
}

/// Largest coordinate magnitude of `points`, m (the scale of the relative tolerances).
fn extent(points: &[[f64; 3]]) -> f64 {
    points
        .iter()
        .flatten()
        .fold(0.0_f64, |m, c| m.max(c.abs()))
        .max(f64::MIN_POSITIVE)
}

fn to_vec(p: [f64; 3]) -> Vector {
    Vector::from(Vector3::from(p))
}

fn nv(v: Vector) -> Vector3<f64> {
    Vector3::from(v)
}

impl Shape3 {
    /// A sphere of `radius` m.
    pub fn ball(radius: f64) -> Result<Self, ContactError> {
        Self::Ball { radius }.validated()
    }

    /// A capsule along the body x axis: core segment of half length `half_length` m, radius
    /// `radius` m.
    pub fn capsule(half_length: f64, radius: f64) -> Result<Self, ContactError> {
        Self::Capsule {
            half_length,
            radius,
        }
        .validated()
    }

    /// A box of half widths `hx`, `hy`, `hz` m along the body axes.
    pub fn cuboid(hx: f64, hy: f64, hz: f64) -> Result<Self, ContactError> {
        Self::Cuboid {
            half_extents: [hx, hy, hz],
        }
        .validated()
    }

    /// A cylinder along the body x axis of half length `half_length` m and radius `radius` m.
    pub fn cylinder(half_length: f64, radius: f64) -> Result<Self, ContactError> {
        Self::Cylinder {
            half_length,
            radius,
        }
        .validated()
    }

    /// A cone along the body x axis (apex at +`half_length`, base of `radius` at
    /// −`half_length`), m.
    pub fn cone(half_length: f64, radius: f64) -> Result<Self, ContactError> {
        Self::Cone {
            half_length,
            radius,
        }
        .validated()
    }

    /// A convex polyhedron from its vertices (m).
    pub fn convex_polyhedron(points: Vec<[f64; 3]>) -> Result<Self, ContactError> {
        Self::ConvexPolyhedron { points }.validated()
    }

    /// A triangle mesh from its vertices (m) and triangles (indices from 0).
    pub fn trimesh(vertices: Vec<[f64; 3]>, indices: Vec<[u32; 3]>) -> Result<Self, ContactError> {
        Self::TriMesh { vertices, indices }.validated()
    }

    /// Convex parts at poses in the body frame.
    pub fn compound(parts: Vec<(PartPose3, Shape3)>) -> Result<Self, ContactError> {
        Self::Compound { parts }.validated()
    }

    fn validated(self) -> Result<Self, ContactError> {
        self.validate()?;
        Ok(self)
    }

    /// Whether the shape is convex (a single convex part): all but trimesh and compound.
    pub fn is_convex(&self) -> bool {
        !matches!(self, Self::TriMesh { .. } | Self::Compound { .. })
    }

    /// Check the description; the error names the offending value and what to change.
    pub fn validate(&self) -> Result<(), ContactError> {
        match self {
            Self::Ball { radius } => positive(LAW, "ball radius (m)", *radius).map(drop),
            Self::Capsule {
                half_length,
                radius,
            } => {
                positive(LAW, "capsule half_length (m)", *half_length)?;
                positive(LAW, "capsule radius (m)", *radius).map(drop)
            }
            Self::Cuboid { half_extents } => {
                positive(LAW, "cuboid half_extents[0] (m)", half_extents[0])?;
                positive(LAW, "cuboid half_extents[1] (m)", half_extents[1])?;
                positive(LAW, "cuboid half_extents[2] (m)", half_extents[2]).map(drop)
            }
            Self::Cylinder {
                half_length,
                radius,
            } => {
                positive(LAW, "cylinder half_length (m)", *half_length)?;
                positive(LAW, "cylinder radius (m)", *radius).map(drop)
            }
            Self::Cone {
                half_length,
                radius,
            } => {
                positive(LAW, "cone half_length (m)", *half_length)?;
                positive(LAW, "cone radius (m)", *radius).map(drop)
            }
            Self::ConvexPolyhedron { points } => convex_hull(points).map(drop),
            Self::TriMesh { vertices, indices } => validate_trimesh(vertices, indices),
            Self::Compound { parts } => validate_compound(parts),
        }
    }
}

fn validate_compound(parts: &[(PartPose3, Shape3)]) -> Result<(), ContactError> {
    let name = "compound parts";
    if parts.is_empty() {
        return Err(ContactError::invalid(
            LAW,
            name,
            0.0,
            "a compound needs at least one part",
        ));
    }
    for (i, (pose, part)) in parts.iter().enumerate() {
        pose.validate(i)?;
        if !part.is_convex() {
            return Err(ContactError::invalid(
                LAW,
                name,
                i as f64,
                format!(
                    "part {i} is a triangle mesh or a compound; compound parts must be ball, \
                     capsule, cuboid, cylinder, cone or convex polyhedron (split a non-convex \
                     part into convex polyhedra, or use a separate trimesh shape)"
                ),
            ));
        }
        part.validate()?;
    }
    Ok(())
}

/// The convex hull of `points`, refused when it has no volume or leaves a point inside.
fn convex_hull(points: &[[f64; 3]]) -> Result<ConvexPolyhedron, ContactError> {
    let name = "convex polyhedron points (m)";
    if points.len() < 4 {
        return Err(ContactError::invalid(
            LAW,
            name,
            points.len() as f64,
            "a convex polyhedron needs at least 4 points; add points",
        ));
    }
    finite_points(LAW, name, points)?;
    let size = extent(points);
    let flat = || {
        ContactError::invalid(
            LAW,
            name,
            points.len() as f64,
            "the points are (nearly) in one plane: the polyhedron needs a positive volume",
        )
    };
    let pts: Vec<Vector> = points.iter().copied().map(to_vec).collect();
    let hull = ConvexPolyhedron::from_convex_hull(&pts).ok_or_else(flat)?;
    if hull_volume(&hull) <= 1e-9 * size * size * size {
        return Err(flat());
    }
    // Every given point must lie on a face plane (within a relative 1e-9): a point inside the
    // hull would be dropped silently by the hull.
    let tol = 1e-9 * size;
    for (i, p) in pts.iter().enumerate() {
        let outside = hull
            .faces()
            .iter()
            .map(|f| f.normal.dot(*p) - support(&hull, f.normal))
            .fold(f64::NEG_INFINITY, f64::max);
        if outside < -tol {
            return Err(ContactError::invalid(
                LAW,
                name,
                i as f64,
                format!(
                    "point {i} lies inside the hull of the others, {:.3e} m from its surface: \
                     give only the vertices of the convex polyhedron (remove the point)",
                    -outside
                ),
            ));
        }
    }
    Ok(hull)
}

/// Support function h(n) = max over the hull's vertices of n·v, m.
fn support(hull: &ConvexPolyhedron, n: Vector) -> f64 {
    hull.points()
        .iter()
        .map(|v| n.dot(*v))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Volume of a convex polyhedron, m³: Σ over faces of the fan tetrahedra from the origin,
/// (1/6) p₀·(p₁ × p₂) (divergence theorem).
fn hull_volume(hull: &ConvexPolyhedron) -> f64 {
    let pts = hull.points();
    let adj = hull.vertices_adj_to_face();
    let mut v6 = 0.0_f64;
    for f in hull.faces() {
        let first = f.first_vertex_or_edge as usize;
        let ids = &adj[first..first + f.num_vertices_or_edges as usize];
        for w in ids[1..].windows(2) {
            let (p0, p1, p2) = (pts[ids[0] as usize], pts[w[0] as usize], pts[w[1] as usize]);
            v6 += p0.dot(p1.cross(p2));
        }
    }
    v6.abs() / 6.0
}

fn validate_trimesh(vertices: &[[f64; 3]], indices: &[[u32; 3]]) -> Result<(), ContactError> {
    let name = "trimesh indices";
    if indices.is_empty() {
        return Err(ContactError::invalid(
            LAW,
            name,
            0.0,
            "a triangle mesh needs at least one triangle; add indices",
        ));
    }
    finite_points(LAW, "trimesh vertices (m)", vertices)?;
    let n = vertices.len();
    let one_based = indices.iter().flatten().all(|&k| k > 0);
    let size = extent(vertices);
    for (t, tri) in indices.iter().enumerate() {
        if let Some(&k) = tri.iter().find(|&&k| k as usize >= n) {
            let hint = if one_based && k as usize == n {
                " (indices count from 0: subtract 1 from every index)"
            } else {
                ""
            };
            return Err(ContactError::invalid(
                LAW,
                name,
                k as f64,
                format!("triangle {t} refers to vertex {k}, but there are {n} vertices{hint}"),
            ));
        }
        let [a, b, c] = tri.map(|k| Vector3::from(vertices[k as usize]));
        let area2 = (b - a).cross(&(c - a)).norm();
        if area2 <= 1e-12 * size * size {
            return Err(ContactError::invalid(
                LAW,
                name,
                t as f64,
                format!(
                    "triangle {t} {tri:?} has (nearly) zero area (repeated or collinear \
                     vertices); remove it"
                ),
            ));
        }
    }
    Ok(())
}

/// The body-frame pose of a parry cylinder or cone (axis along y) with its axis along body x:
/// a quarter turn about z, y ↦ x.
fn x_axis_frame() -> Pose {
    Isometry3::rotation(Vector3::new(0.0, 0.0, -std::f64::consts::FRAC_PI_2)).into()
}

/// The parry shape of a validated description and its pose in the body frame.
fn to_parry(shape: &Shape3) -> Result<(SharedShape, Pose), ContactError> {
    let identity = Pose::IDENTITY;
    Ok(match shape {
        Shape3::Ball { radius } => (SharedShape::ball(*radius), identity),
        Shape3::Capsule {
            half_length,
            radius,
        } => (SharedShape::capsule_x(*half_length, *radius), identity),
        Shape3::Cuboid { half_extents: h } => (SharedShape::cuboid(h[0], h[1], h[2]), identity),
        Shape3::Cylinder {
            half_length,
            radius,
        } => (SharedShape::cylinder(*half_length, *radius), x_axis_frame()),
        Shape3::Cone {
            half_length,
            radius,
        } => (SharedShape::cone(*half_length, *radius), x_axis_frame()),
        Shape3::ConvexPolyhedron { points } => (SharedShape::new(convex_hull(points)?), identity),
        Shape3::TriMesh { vertices, indices } => {
            let v = vertices.iter().copied().map(to_vec).collect();
            let mesh = SharedShape::trimesh(v, indices.clone()).map_err(|e| {
                ContactError::invalid(
                    LAW,
                    "trimesh indices",
                    indices.len() as f64,
                    format!("parry3d refused the mesh ({e}); check the indices"),
                )
            })?;
            (mesh, identity)
        }
        Shape3::Compound { parts } => {
            let mut out = Vec::with_capacity(parts.len());
            for (pose, part) in parts {
                let (shape, frame) = to_parry(part)?;
                out.push((pose.to_pose() * frame, shape));
            }
            (SharedShape::compound(out), identity)
        }
    })
}

/// A validated [`Shape3`] together with its parry shape, built once.
#[derive(Clone)]
pub struct ContactShape3 {
    desc: Shape3,
    parry: SharedShape,
    /// Pose of the parry shape in the body frame (a quarter turn for cylinders and cones).
    frame: Pose,
    bounding_radius: f64,
}

impl std::fmt::Debug for ContactShape3 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ContactShape3")
            .field("desc", &self.desc)
            .finish_non_exhaustive()
    }
}

impl ContactShape3 {
    /// Validate `desc` and build its parry shape.
    pub fn new(desc: Shape3) -> Result<Self, ContactError> {
        desc.validate()?;
        let (parry, frame) = to_parry(&desc)?;
        let b = parry.compute_aabb(&frame);
        let bounding_radius = b.mins.abs().max(b.maxs.abs()).length();
        Ok(Self {
            desc,
            parry,
            frame,
            bounding_radius,
        })
    }

    /// The description this shape was built from.
    pub fn desc(&self) -> &Shape3 {
        &self.desc
    }

    /// Axis-aligned bounding box of the shape at `pose` (position and rotation used), world
    /// frame, m: `[x_min, y_min, z_min, x_max, y_max, z_max]`. O(1) for every kind: parry
    /// transforms the local box of composite shapes (trimeshes, compounds) instead of visiting
    /// their parts, so the box of a rotated composite shape is loose.
    ///
    /// # Errors
    /// A non-finite position or a rotation quaternion whose norm is not 1.
    pub fn aabb3(&self, pose: &BodyState3) -> Result<[f64; 6], ContactError> {
        let b = self.parry.compute_aabb(&(pose.pose()? * self.frame));
        Ok([b.mins.x, b.mins.y, b.mins.z, b.maxs.x, b.maxs.y, b.maxs.z])
    }

    /// Radius of a sphere about the body reference point that holds the shape, m (the
    /// farthest corner of the body-frame bounding box: an upper bound, as the planar
    /// [`crate::ContactShape::bounding_radius`]).
    pub fn bounding_radius(&self) -> f64 {
        self.bounding_radius
    }

    /// A triangulation of the shape's surface in the body frame, for drawing (report pages,
    /// animations): vertices (m) and triangles (indices into the vertices, counter-clockwise
    /// seen from outside for the solid kinds). Balls, capsules, cylinders and cones are
    /// tessellated with `segments` (at least 3) around their axis; cuboids and convex polyhedra
    /// are exact, triangle meshes are returned as given, compounds part by part.
    pub fn surface(&self, segments: u32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
        append_surface(
            &*self.parry,
            &self.frame,
            segments.max(3),
            &mut vertices,
            &mut triangles,
        );
        (vertices, triangles)
    }

    fn posed(&self, pose: &BodyState3) -> Result<Posed<'_>, ContactError> {
        Ok(Posed {
            shape: self,
            pose: pose.pose()? * self.frame,
        })
    }
}

/// Append the surface of a parry shape placed at `frame` ([`ContactShape3::surface`]).
fn append_surface(
    shape: &dyn parry3d_f64::shape::Shape,
    frame: &Pose,
    n: u32,
    vertices: &mut Vec<[f64; 3]>,
    triangles: &mut Vec<[u32; 3]>,
) {
    if let Some(c) = shape.as_compound() {
        for (pose, part) in c.shapes() {
            append_surface(&**part, &(*frame * *pose), n, vertices, triangles);
        }
        return;
    }
    let (points, idx) = if let Some(b) = shape.as_ball() {
        b.to_trimesh(n, n.div_ceil(2).max(2))
    } else if let Some(b) = shape.as_cuboid() {
        b.to_trimesh()
    } else if let Some(c) = shape.as_capsule() {
        c.to_trimesh(n, n.div_ceil(2).max(2))
    } else if let Some(c) = shape.as_cylinder() {
        c.to_trimesh(n)
    } else if let Some(c) = shape.as_cone() {
        c.to_trimesh(n)
    } else if let Some(c) = shape.as_convex_polyhedron() {
        c.to_trimesh()
    } else if let Some(m) = shape.as_trimesh() {
        (m.vertices().to_vec(), m.indices().to_vec())
    } else {
        return; // every kind `to_parry` builds is handled above
    };
    let base = vertices.len() as u32;
    vertices.extend(
        points
            .into_iter()
            .map(|p| -> [f64; 3] { nv(*frame * p).into() }),
    );
    triangles.extend(idx.into_iter().map(|t| t.map(|k| base + k)));
}

/// Distance between two boxes `[x_min, y_min, z_min, x_max, y_max, z_max]`, m (0 when they
/// overlap): a lower bound of the distance between the shapes they hold.
pub fn boxes_gap3(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    let gap = |k: usize| (b[k] - a[k + 3]).max(a[k] - b[k + 3]).max(0.0);
    Vector3::new(gap(0), gap(1), gap(2)).norm()
}

/// True when two boxes `[x_min, y_min, z_min, x_max, y_max, z_max]` (m) overlap once each is
/// grown by `margin` m (the broad phase of a shape pair: nothing within `margin` when false).
pub fn boxes_overlap3(a: &[f64; 6], b: &[f64; 6], margin: f64) -> bool {
    (0..3).all(|k| a[k] - margin <= b[k + 3] && b[k] - margin <= a[k + 3])
}

/// Distance between shape A at `pose_a` and shape B at `pose_b`, m (0 when they touch or
/// overlap; parry's `distance` query, exact for convex shapes and for composite shapes part by
/// part): the gap of the conservative step bound.
///
/// # Errors
/// A non-finite pose or non-unit quaternion, or a pair parry has no query for.
pub fn shape_distance3(
    a: &ContactShape3,
    pose_a: &BodyState3,
    b: &ContactShape3,
    pose_b: &BodyState3,
) -> Result<f64, ContactError> {
    let (sa, sb) = (a.posed(pose_a)?, b.posed(pose_b)?);
    query::distance(&sa.pose, &*a.parry, &sb.pose, &*b.parry)
        .map(|d| d.distance)
        .map_err(|_| unsupported(a, b))
}

/// One contact point between shapes A and B, world frame, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeContactPoint3 {
    /// Penetration δ, m: > 0 in contact; ≤ 0 (a gap of −δ) for a point reported only because
    /// it lies within the prediction distance.
    pub depth: f64,
    /// Unit normal from A to B (A's outward normal at the contact).
    pub normal: Vector3<f64>,
    /// Contact point on A's boundary, m.
    pub point_a: Vector3<f64>,
    /// Contact point on B's boundary, m; `point_b = point_a − depth · normal`.
    pub point_b: Vector3<f64>,
    /// Index of the part of A (compound part or mesh triangle); 0 for a convex shape.
    pub part_a: u32,
    /// Index of the part of B (compound part or mesh triangle); 0 for a convex shape.
    pub part_b: u32,
    /// The feature of A that carries the point (a face, an edge or a vertex of its core).
    pub feature_a: Feature3,
    /// The feature of B that carries the point.
    pub feature_b: Feature3,
    /// Rounding radius of A's part at the point, m: the ball or capsule radius, 0 for the
    /// other shapes. A's core feature lies at `point_a − radius_a · normal`.
    pub radius_a: f64,
    /// Rounding radius of B's part at the point, m; B's core feature lies at
    /// `point_b + radius_b · normal`.
    pub radius_b: f64,
}

impl ShapeContactPoint3 {
    /// Relative velocity v = ṙ_B(p_B) − ṙ_A(p_A) of the two contact points as material points
    /// of their bodies, m/s. δ̇ = −v·n is the rate of the penetration (> 0 approaching) and
    /// v − (v·n) n the slip in the tangent plane (the planar element's convention, see
    /// docs/contact.md, shape contact).
    pub fn relative_velocity(&self, a: &BodyState3, b: &BodyState3) -> Vector3<f64> {
        b.point_velocity(self.point_b) - a.point_velocity(self.point_a)
    }
}

/// The feature of a shape's core that carries a contact point (see [`crate::Feature`] for the
/// planar one and how a force element uses it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature3 {
    /// A flat face (polyhedron or box face, triangle, the flat end of a cylinder or cone, or
    /// the segment parry puts on a cylinder's or a cone's curved side).
    Face,
    /// An edge (of a polyhedron, a box or a triangle; a capsule's core segment; a rim).
    Edge,
    /// A corner, or the centre of a ball (a vertex of zero or positive rounding radius).
    Vertex,
    /// parry did not identify it.
    Unknown,
}

impl Feature3 {
    fn from_parry(f: PackedFeatureId) -> Self {
        if f.is_face() {
            Self::Face
        } else if f.is_edge() {
            Self::Edge
        } else if f.is_vertex() {
            Self::Vertex
        } else {
            Self::Unknown
        }
    }
}

/// Reusable buffers of [`contact_points3`] (parry's contact manifolds and workspace, and the
/// output points). Keep one per shape pair: it is also parry's per-pair bookkeeping.
#[derive(Default)]
pub struct ShapeContactWorkspace3 {
    manifolds: Vec<ContactManifold<(), ()>>,
    parry: Option<ContactManifoldsWorkspace>,
    points: Vec<ShapeContactPoint3>,
}

impl std::fmt::Debug for ShapeContactWorkspace3 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShapeContactWorkspace3")
            .field("points", &self.points)
            .finish_non_exhaustive()
    }
}

impl ShapeContactWorkspace3 {
    /// Empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// The points of the last [`contact_points3`] call.
    pub fn points(&self) -> &[ShapeContactPoint3] {
        &self.points
    }
}

/// Contact points between shape A at `pose_a` and shape B at `pose_b` (only their position
/// and rotation are used), including separated points within `prediction` m (≥ 0; 0 for
/// touching or penetrating points only).
///
/// * A ball against a convex shape uses parry's `contact` (one exact point: the projection of
///   the centre on the other shape).
/// * Every other pair uses parry's contact manifolds, one per pair of convex parts (compound
///   parts, mesh triangles) that overlap: the clipped contact polygon of the two features that
///   touch, so a box flat on a box gives the corners of their overlap (up to 8 points), a
///   cylinder's flat end the four corners of parry's inscribed square, a capsule lying on a
///   face its two core ends.
/// * parry (3-D) adds GJK's deepest point, features unknown, to every polygonal-feature
///   manifold. It duplicates a clipped point whenever the clipping found the deepest one, and
///   would be counted twice by a force element; it is reported only when it is deeper than
///   every clipped point of its manifold by more than 1e-6 × the smaller shape's bounding
///   radius, or when the clipping found nothing.
///
/// A smooth body pressed against a fine mesh touches several triangles; each gives its own
/// point (see [`ShapeContactPoint3::part_a`]), so a force element must decide how to combine
/// them, as with the planar polylines.
///
/// No allocation after warm-up for a ball against a convex shape, box–box, a capsule in
/// contact, and any convex pair within `prediction`; a penetrating cylinder, cone or
/// polyhedron goes through parry's EPA, which allocates its polytope at each call, and parry's
/// composite-shape queries (trimesh, compound) rebuild their list of manifolds on every call.
///
/// # Errors
/// A non-finite pose, a non-unit quaternion, a negative or non-finite prediction, or a pair
/// parry has no query for.
pub fn contact_points3<'w>(
    a: &ContactShape3,
    pose_a: &BodyState3,
    b: &ContactShape3,
    pose_b: &BodyState3,
    prediction: f64,
    workspace: &'w mut ShapeContactWorkspace3,
) -> Result<&'w [ShapeContactPoint3], ContactError> {
    check_prediction(LAW, prediction)?;
    let (sa, sb) = (a.posed(pose_a)?, b.posed(pose_b)?);
    query_points(&sa, &sb, prediction, workspace).map_err(|()| unsupported(a, b))?;
    Ok(&workspace.points)
}

/// A shape at its world pose (the body pose times the shape's frame).
struct Posed<'s> {
    shape: &'s ContactShape3,
    pose: Pose,
}

impl Posed<'_> {
    fn is_ball(&self) -> bool {
        matches!(self.shape.desc, Shape3::Ball { .. })
    }
    fn is_convex(&self) -> bool {
        self.shape.desc.is_convex()
    }
    fn parry(&self) -> &dyn parry3d_f64::shape::Shape {
        &*self.shape.parry
    }
    /// The feature and radius parry's `contact` leaves unnamed: a ball is a rounded vertex at
    /// its centre; the other shape is whatever carries the closest point.
    fn unnamed_feature(&self) -> (Feature3, f64) {
        match self.shape.desc {
            Shape3::Ball { radius } => (Feature3::Vertex, radius),
            Shape3::Capsule { radius, .. } => (Feature3::Unknown, radius),
            _ => (Feature3::Unknown, 0.0),
        }
    }
}

/// The points of [`contact_points3`] into `workspace.points`; `Err` when parry has no query.
fn query_points(
    a: &Posed,
    b: &Posed,
    prediction: f64,
    workspace: &mut ShapeContactWorkspace3,
) -> Result<(), ()> {
    workspace.points.clear();
    if (a.is_ball() && b.is_convex()) || (b.is_ball() && a.is_convex()) {
        let c =
            query::contact(&a.pose, a.parry(), &b.pose, b.parry(), prediction).map_err(|_| ())?;
        if let Some(c) = c {
            let ((feature_a, radius_a), (feature_b, radius_b)) =
                (a.unnamed_feature(), b.unnamed_feature());
            workspace.points.push(ShapeContactPoint3 {
                depth: -c.dist,
                normal: nv(c.normal1),
                point_a: nv(c.point1),
                point_b: nv(c.point2),
                part_a: 0,
                part_b: 0,
                feature_a,
                feature_b,
                radius_a,
                radius_b,
            });
        }
        return Ok(());
    }
    // Recompute every point from scratch: no reuse of the previous call's points, and GJK
    // starts from its default direction, not the previous normal.
    for m in &mut workspace.manifolds {
        m.clear();
        m.local_n1 = Vector::ZERO;
        m.local_n2 = Vector::ZERO;
    }
    let pos12 = a.pose.inv_mul(&b.pose);
    DefaultQueryDispatcher
        .contact_manifolds(
            &pos12,
            a.parry(),
            b.parry(),
            prediction,
            &mut workspace.manifolds,
            &mut workspace.parry,
        )
        .map_err(|_| ())?;
    let margin = GJK_POINT_MARGIN * a.shape.bounding_radius.min(b.shape.bounding_radius);
    for m in &workspace.manifolds {
        push_manifold(a, b, m, prediction, margin, &mut workspace.points);
    }
    Ok(())
}

/// The points of one manifold within `prediction`, without parry's duplicate GJK point.
fn push_manifold(
    a: &Posed,
    b: &Posed,
    m: &ContactManifold<(), ()>,
    prediction: f64,
    margin: f64,
    out: &mut Vec<ShapeContactPoint3>,
) {
    let is_gjk = |p: &query::TrackedContact<()>| p.fid1.is_unknown() && p.fid2.is_unknown();
    let clipped_deepest = m
        .points
        .iter()
        .filter(|p| !is_gjk(p))
        .map(|p| p.dist)
        .fold(f64::INFINITY, f64::min);
    // Frames of the two parts (compound part: parry's subshape pose).
    let (sub1, sub2) = match &m.subshape_poses {
        Some(s) => (s.pos1, s.pos2),
        None => (None, None),
    };
    let fa = sub1.map_or(a.pose, |s| a.pose * s);
    let fb = sub2.map_or(b.pose, |s| b.pose * s);
    let normal = nv(fa.rotation * m.local_n1);
    let radius_a = part_radius(&a.shape.desc, m.subshape1);
    let radius_b = part_radius(&b.shape.desc, m.subshape2);
    for p in &m.points {
        // parry's polygon clipping keeps face points beyond the prediction distance; report
        // only those within it.
        if p.dist > prediction || (is_gjk(p) && p.dist >= clipped_deepest - margin) {
            continue;
        }
        out.push(ShapeContactPoint3 {
            depth: -p.dist,
            normal,
            point_a: nv(fa * p.local_p1),
            point_b: nv(fb * p.local_p2),
            part_a: m.subshape1,
            part_b: m.subshape2,
            feature_a: Feature3::from_parry(p.fid1),
            feature_b: Feature3::from_parry(p.fid2),
            radius_a,
            radius_b,
        });
    }
}

/// The rounding radius of part `k` of a shape (m): ball and capsule radii, else 0.
fn part_radius(s: &Shape3, k: u32) -> f64 {
    match s {
        Shape3::Ball { radius } | Shape3::Capsule { radius, .. } => *radius,
        Shape3::Compound { parts } => parts
            .get(k as usize)
            .map_or(0.0, |(_, p)| part_radius(p, 0)),
        _ => 0.0,
    }
}

fn unsupported(a: &ContactShape3, b: &ContactShape3) -> ContactError {
    ContactError::invalid(
        LAW,
        "shape pair",
        f64::NAN,
        format!(
            "parry3d has no contact query for {} against {}",
            kind(&a.desc),
            kind(&b.desc)
        ),
    )
}

fn kind(s: &Shape3) -> &'static str {
    match s {
        Shape3::Ball { .. } => "ball",
        Shape3::Capsule { .. } => "capsule",
        Shape3::Cuboid { .. } => "cuboid",
        Shape3::Cylinder { .. } => "cylinder",
        Shape3::Cone { .. } => "cone",
        Shape3::ConvexPolyhedron { .. } => "convex polyhedron",
        Shape3::TriMesh { .. } => "trimesh",
        Shape3::Compound { .. } => "compound",
    }
}
