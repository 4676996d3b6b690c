//! Contact between body shapes (stops, cams, gears, blocks), with `parry2d-f64` as the
//! geometry engine.
//!
//! * [`Shape`] is plain data (SI units, body-frame coordinates) that a model file or a caller
//!   writes; [`Shape::validate`] and the constructors ([`Shape::ball`], …) refuse bad input with
//!   a [`ContactError`] that says what to change.
//! * [`ContactShape`] is a validated [`Shape`] converted once to its parry shape; build it when
//!   the model is built, not per force evaluation.
//! * [`contact_points`] gives the contact points between two posed [`ContactShape`]s, with
//!   clr-contact's conventions: penetration δ > 0 in contact, unit normal from A to B, world
//!   coordinates. The results go into a reusable [`ShapeContactWorkspace`].
//!
//! parry works with glam vectors (`glamx`), not nalgebra; the conversion happens only at this
//! module's boundary (two `f64` per point) and no parry type appears in its API.
//!
//! The query is a pure function of the poses: parry's persistent-manifold shortcut (reuse the
//! previous contact points when the relative pose barely changed) is switched off by clearing
//! the cached points before every query, so the answer does not depend on the call history
//! (rejected ODE steps, Jacobian perturbations).

use parry2d_f64::math::{Pose, Vector};
use parry2d_f64::query::{
    self, ContactManifold, ContactManifoldsWorkspace, DefaultQueryDispatcher,
    PersistentQueryDispatcher,
};
use parry2d_f64::shape::SharedShape;

use crate::body::{BodyState, Vector2};
use crate::error::ContactError;

/// Plain-data description of a body's contact shape, in the body frame (m, rad).
///
/// Build it with the validating constructors or write the variants directly and call
/// [`Shape::validate`] (done again by [`ContactShape::new`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A disc centred on the body reference point.
    Ball {
        /// Radius, m (> 0).
        radius: f64,
    },
    /// A segment along the body x axis from −`half_length` to +`half_length`, dilated by
    /// `radius` (a stadium).
    Capsule {
        /// Half length of the core segment, m (> 0).
        half_length: f64,
        /// Radius, m (> 0).
        radius: f64,
    },
    /// A rectangle centred on the body reference point, sides along the body axes.
    Cuboid {
        /// Half widths along body x and y, m (both > 0).
        half_extents: [f64; 2],
    },
    /// A convex polygon, vertices counter-clockwise in the body frame, m (≥ 3 points).
    ConvexPolygon {
        /// Vertices, counter-clockwise, without repeating the first one.
        points: Vec<[f64; 2]>,
    },
    /// An open chain of segments (a cam or guide profile), m (≥ 2 points). The solid side is
    /// not defined: contact is with the segments themselves, from either side.
    Polyline {
        /// Vertices in order; consecutive points must differ.
        points: Vec<[f64; 2]>,
    },
    /// Several convex parts rigidly attached to the body, each at a pose `[x, y, θ]`
    /// (m, m, rad) in the body frame. Parts may be balls, capsules, cuboids or convex
    /// polygons (parry does not nest composite shapes).
    Compound {
        /// `(pose [x, y, θ], part)` pairs (at least one).
        parts: Vec<([f64; 3], Shape)>,
    },
}

const LAW: &str = "contact shape";

fn finite(name: &'static str, v: f64) -> Result<(), ContactError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(ContactError::invalid(
            LAW,
            name,
            v,
            "must be finite (no NaN or infinity)",
        ))
    }
}

fn positive(name: &'static str, v: f64) -> Result<(), ContactError> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(ContactError::invalid(
            LAW,
            name,
            v,
            "must be > 0 and finite",
        ))
    }
}

/// Check that every coordinate of `points` (m) is finite; the error names point `i`. Shared
/// with [`crate::shapes3d`] (`law` names the kind of shape).
pub(crate) fn finite_points<const N: usize>(
    law: &'static str,
    name: &'static str,
    points: &[[f64; N]],
) -> Result<(), ContactError> {
    for (i, p) in points.iter().enumerate() {
        if let Some(&c) = p.iter().find(|c| !c.is_finite()) {
            return Err(ContactError::invalid(
                law,
                name,
                c,
                format!("point {i} has a non-finite coordinate; give finite coordinates in m"),
            ));
        }
    }
    Ok(())
}

fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

impl Shape {
    /// A disc of `radius` m.
    pub fn ball(radius: f64) -> Result<Self, ContactError> {
        let s = Self::Ball { radius };
        s.validate()?;
        Ok(s)
    }

    /// A capsule along the body x axis: core segment of half length `half_length` m, radius
    /// `radius` m.
    pub fn capsule(half_length: f64, radius: f64) -> Result<Self, ContactError> {
        let s = Self::Capsule {
            half_length,
            radius,
        };
        s.validate()?;
        Ok(s)
    }

    /// A rectangle of half widths `hx`, `hy` m along the body axes.
    pub fn cuboid(hx: f64, hy: f64) -> Result<Self, ContactError> {
        let s = Self::Cuboid {
            half_extents: [hx, hy],
        };
        s.validate()?;
        Ok(s)
    }

    /// A convex polygon from its vertices (m, counter-clockwise).
    pub fn convex_polygon(points: Vec<[f64; 2]>) -> Result<Self, ContactError> {
        let s = Self::ConvexPolygon { points };
        s.validate()?;
        Ok(s)
    }

    /// An open polyline from its vertices (m).
    pub fn polyline(points: Vec<[f64; 2]>) -> Result<Self, ContactError> {
        let s = Self::Polyline { points };
        s.validate()?;
        Ok(s)
    }

    /// Convex parts at poses `[x, y, θ]` (m, m, rad) in the body frame.
    pub fn compound(parts: Vec<([f64; 3], Shape)>) -> Result<Self, ContactError> {
        let s = Self::Compound { parts };
        s.validate()?;
        Ok(s)
    }

    /// Whether the shape is convex (a single convex part): ball, capsule, cuboid, polygon.
    pub fn is_convex(&self) -> bool {
        !matches!(self, Self::Polyline { .. } | Self::Compound { .. })
    }

    /// Check the description; the error names the offending value and what to change.
    pub fn validate(&self) -> Result<(), ContactError> {
        match self {
            Self::Ball { radius } => positive("ball radius (m)", *radius),
            Self::Capsule {
                half_length,
                radius,
            } => {
                positive("capsule half_length (m)", *half_length)?;
                positive("capsule radius (m)", *radius)
            }
            Self::Cuboid { half_extents } => {
                positive("cuboid half_extents[0] (m)", half_extents[0])?;
                positive("cuboid half_extents[1] (m)", half_extents[1])
            }
            Self::ConvexPolygon { points } => validate_convex_polygon(points),
            Self::Polyline { points } => {
                let name = "polyline points (m)";
                if points.len() < 2 {
                    return Err(ContactError::invalid(
                        LAW,
                        name,
                        points.len() as f64,
                        "a polyline needs at least 2 points; add points",
                    ));
                }
                finite_points(LAW, name, points)?;
                for (i, w) in points.windows(2).enumerate() {
                    if w[0] == w[1] {
                        return Err(ContactError::invalid(
                            LAW,
                            name,
                            i as f64,
                            format!(
                                "points {i} and {} coincide (zero-length segment); remove one",
                                i + 1
                            ),
                        ));
                    }
                }
                Ok(())
            }
            Self::Compound { parts } => {
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
                    for &c in pose {
                        finite("compound part pose [x, y, θ] (m, m, rad)", c)?;
                    }
                    if !part.is_convex() {
                        return Err(ContactError::invalid(
                            LAW,
                            name,
                            i as f64,
                            format!(
                                "part {i} is a polyline or a compound; compound parts must be \
                                 ball, capsule, cuboid or convex polygon (split a non-convex \
                                 part into convex polygons, or use a separate polyline shape)"
                            ),
                        ));
                    }
                    part.validate()?;
                }
                Ok(())
            }
        }
    }
}

fn validate_convex_polygon(points: &[[f64; 2]]) -> Result<(), ContactError> {
    let name = "convex polygon points (m)";
    let n = points.len();
    if n < 3 {
        return Err(ContactError::invalid(
            LAW,
            name,
            n as f64,
            "a convex polygon needs at least 3 points; add points",
        ));
    }
    finite_points(LAW, name, points)?;
    // Scale for the collinearity tolerance.
    let size = points
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0_f64, |m, c| m.max(c.abs()))
        .max(f64::MIN_POSITIVE);
    let tol = 1e-12 * size * size;
    let mut turning = 0.0;
    let mut strict = 0;
    for i in 0..n {
        let (o, a, b) = (points[i], points[(i + 1) % n], points[(i + 2) % n]);
        if o == a {
            return Err(ContactError::invalid(
                LAW,
                name,
                i as f64,
                format!(
                    "points {i} and {} coincide; remove one (do not repeat the first point)",
                    (i + 1) % n
                ),
            ));
        }
        let c = cross(o, a, b);
        if c < -tol {
            return Err(ContactError::invalid(
                LAW,
                name,
                ((i + 1) % n) as f64,
                format!(
                    "the polygon turns clockwise at point {}: give the vertices of a convex \
                     polygon counter-clockwise (reverse the order if they are clockwise, \
                     split a non-convex outline into convex parts of a compound)",
                    (i + 1) % n
                ),
            ));
        }
        if c > tol {
            strict += 1;
        }
        let e1 = [a[0] - o[0], a[1] - o[1]];
        let e2 = [b[0] - a[0], b[1] - a[1]];
        turning += (e1[0] * e2[1] - e1[1] * e2[0]).atan2(e1[0] * e2[0] + e1[1] * e2[1]);
    }
    if strict < 3 {
        return Err(ContactError::invalid(
            LAW,
            name,
            strict as f64,
            "the points are (nearly) collinear; the polygon needs a positive area",
        ));
    }
    if (turning - std::f64::consts::TAU).abs() > 1e-6 {
        return Err(ContactError::invalid(
            LAW,
            name,
            turning,
            "the outline winds more than once (self-intersecting); give a simple convex \
             polygon counter-clockwise",
        ));
    }
    Ok(())
}

fn to_vec(p: [f64; 2]) -> Vector {
    Vector::new(p[0], p[1])
}

fn to_parry(shape: &Shape) -> Result<SharedShape, ContactError> {
    Ok(match shape {
        Shape::Ball { radius } => SharedShape::ball(*radius),
        Shape::Capsule {
            half_length,
            radius,
        } => SharedShape::capsule_x(*half_length, *radius),
        Shape::Cuboid { half_extents } => SharedShape::cuboid(half_extents[0], half_extents[1]),
        Shape::ConvexPolygon { points } => SharedShape::convex_polyline(
            points.iter().copied().map(to_vec).collect(),
        )
        .ok_or_else(|| {
            ContactError::invalid(
                LAW,
                "convex polygon points (m)",
                points.len() as f64,
                "parry2d refused the polygon (degenerate); give a convex polygon with a \
                         positive area",
            )
        })?,
        Shape::Polyline { points } => {
            SharedShape::polyline(points.iter().copied().map(to_vec).collect(), None)
        }
        Shape::Compound { parts } => {
            let mut out = Vec::with_capacity(parts.len());
            for (pose, part) in parts {
                out.push((
                    Pose::new(Vector::new(pose[0], pose[1]), pose[2]),
                    to_parry(part)?,
                ));
            }
            SharedShape::compound(out)
        }
    })
}

/// A validated [`Shape`] together with its parry shape, built once.
#[derive(Clone)]
pub struct ContactShape {
    desc: Shape,
    parry: SharedShape,
}

impl std::fmt::Debug for ContactShape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ContactShape")
            .field("desc", &self.desc)
            .finish_non_exhaustive()
    }
}

impl ContactShape {
    /// Validate `desc` and build its parry shape.
    pub fn new(desc: Shape) -> Result<Self, ContactError> {
        desc.validate()?;
        let parry = to_parry(&desc)?;
        Ok(Self { desc, parry })
    }

    /// The description this shape was built from.
    pub fn desc(&self) -> &Shape {
        &self.desc
    }

    /// Axis-aligned bounding box of the shape at `pose` (position and angle used), world frame,
    /// m: `[x_min, y_min, x_max, y_max]`. O(1) for every kind: parry transforms the local box
    /// of composite shapes (polylines, compounds) instead of visiting their parts, so the box
    /// of a rotated composite shape is loose.
    pub fn aabb(&self, pose: &BodyState) -> [f64; 4] {
        let p = Pose::new(Vector::new(pose.position.x, pose.position.y), pose.angle);
        let b = self.parry.compute_aabb(&p);
        [b.mins.x, b.mins.y, b.maxs.x, b.maxs.y]
    }

    /// Radius of the smallest circle about the body reference point that holds the shape, m.
    pub fn bounding_radius(&self) -> f64 {
        let b = self.parry.compute_local_aabb();
        b.mins.abs().max(b.maxs.abs()).length()
    }
}

/// Distance between two boxes `[x_min, y_min, x_max, y_max]`, m (0 when they overlap): a lower
/// bound of the distance between the shapes they hold.
pub fn boxes_gap(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    let dx = (b[0] - a[2]).max(a[0] - b[2]).max(0.0);
    let dy = (b[1] - a[3]).max(a[1] - b[3]).max(0.0);
    dx.hypot(dy)
}

/// Distance between shape A at `pose_a` and shape B at `pose_b`, m (0 when they touch or
/// overlap; parry's `distance` query, exact for convex shapes and for composite shapes part by
/// part).
///
/// # Errors
/// A non-finite pose, or a pair parry has no query for.
pub fn shape_distance(
    a: &ContactShape,
    pose_a: &BodyState,
    b: &ContactShape,
    pose_b: &BodyState,
) -> Result<f64, ContactError> {
    let (pa, pb) = (pose_of(pose_a)?, pose_of(pose_b)?);
    query::distance(&pa, &*a.parry, &pb, &*b.parry)
        .map(|d| d.distance)
        .map_err(|_| unsupported(a, b))
}

/// True when two boxes `[x_min, y_min, x_max, y_max]` (m) overlap once each is grown by
/// `margin` m (the broad phase of a shape pair: nothing within `margin` when false).
pub fn boxes_overlap(a: &[f64; 4], b: &[f64; 4], margin: f64) -> bool {
    a[0] - margin <= b[2] && b[0] - margin <= a[2] && a[1] - margin <= b[3] && b[1] - margin <= a[3]
}

/// One contact point between shapes A and B, world frame, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeContactPoint {
    /// Penetration δ, m: > 0 in contact; ≤ 0 (a gap of −δ) for a point reported only because
    /// it lies within the prediction distance.
    pub depth: f64,
    /// Unit normal from A to B (A's outward normal at the contact).
    pub normal: Vector2<f64>,
    /// Contact point on A's boundary, m.
    pub point_a: Vector2<f64>,
    /// Contact point on B's boundary, m; `point_b = point_a − depth · normal`.
    pub point_b: Vector2<f64>,
    /// Index of the part of A (compound part or polyline segment); 0 for a convex shape.
    pub part_a: u32,
    /// Index of the part of B (compound part or polyline segment); 0 for a convex shape.
    pub part_b: u32,
    /// The feature of A that carries the point (a face or a vertex of its core).
    pub feature_a: Feature,
    /// The feature of B that carries the point.
    pub feature_b: Feature,
    /// Rounding radius of A's part at the point, m: the ball or capsule radius, 0 for polygons
    /// and polylines. A's core feature lies at `point_a − radius_a · normal`.
    pub radius_a: f64,
    /// Rounding radius of B's part at the point, m; B's core feature lies at
    /// `point_b + radius_b · normal`.
    pub radius_b: f64,
}

/// The feature of a shape's core that carries a contact point. A force element uses it to move
/// the normal with the right body: a vertex pressed into a face keeps the face's normal (the
/// normal turns with the body of the face), two rounded vertices (balls) keep the line of their
/// centres.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// A straight side (polygon edge, polyline segment, capsule core segment).
    Face,
    /// A corner, or the centre of a ball (a vertex of zero or positive `radius`).
    Vertex,
    /// parry did not identify it.
    Unknown,
}

impl Feature {
    fn from_parry(f: parry2d_f64::shape::PackedFeatureId) -> Self {
        if f.is_face() {
            Self::Face
        } else if f.is_vertex() {
            Self::Vertex
        } else {
            Self::Unknown
        }
    }
}

/// Reusable buffers of [`contact_points`] (parry's contact manifolds and workspace, and the
/// output points). Keep one per shape pair: it is also parry's per-pair bookkeeping.
#[derive(Default)]
pub struct ShapeContactWorkspace {
    manifolds: Vec<ContactManifold<(), ()>>,
    parry: Option<ContactManifoldsWorkspace>,
    points: Vec<ShapeContactPoint>,
}

impl std::fmt::Debug for ShapeContactWorkspace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ShapeContactWorkspace")
            .field("points", &self.points)
            .finish_non_exhaustive()
    }
}

impl ShapeContactWorkspace {
    /// Empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// The points of the last [`contact_points`] call.
    pub fn points(&self) -> &[ShapeContactPoint] {
        &self.points
    }
}

fn pose_of(body: &BodyState) -> Result<Pose, ContactError> {
    finite("body position x (m)", body.position.x)?;
    finite("body position y (m)", body.position.y)?;
    finite("body angle (rad)", body.angle)?;
    Ok(Pose::new(
        Vector::new(body.position.x, body.position.y),
        body.angle,
    ))
}

fn nv(v: Vector) -> Vector2<f64> {
    Vector2::new(v.x, v.y)
}

/// Contact points between shape A at `pose_a` and shape B at `pose_b` (only their position and
/// angle are used), including separated points within `prediction` m (≥ 0; 0 for touching or
/// penetrating points only).
///
/// * A ball against a convex shape uses parry's `contact` (one exact point).
/// * Every other pair (polygons, capsules, polylines, compounds) uses parry's contact
///   manifolds: up to two points per pair of convex parts (a flat face resting on a segment
///   gives its two end points), one manifold per pair of parts that overlap.
///
/// A smooth body pressed against a fine polyline touches several segments; each gives its own
/// point (see [`ShapeContactPoint::part_a`]), so a force element must decide how to combine
/// them (e.g. keep the deepest point per cluster).
///
/// No allocation after warm-up for convex–convex pairs; parry's composite-shape query
/// (polyline, compound) rebuilds its list of manifolds each call.
pub fn contact_points<'w>(
    a: &ContactShape,
    pose_a: &BodyState,
    b: &ContactShape,
    pose_b: &BodyState,
    prediction: f64,
    workspace: &'w mut ShapeContactWorkspace,
) -> Result<&'w [ShapeContactPoint], ContactError> {
    check_prediction(LAW, prediction)?;
    let pa = pose_of(pose_a)?;
    let pb = pose_of(pose_b)?;
    let side_a = Posed {
        shape: &*a.parry,
        desc: Some(&a.desc),
        pose: pa,
    };
    let side_b = Posed {
        shape: &*b.parry,
        desc: Some(&b.desc),
        pose: pb,
    };
    query_points(side_a, side_b, prediction, workspace).map_err(|()| unsupported(a, b))?;
    Ok(&workspace.points)
}

/// Contact points between the segment `p0`–`p1` (world frame, m; A, e.g. a piece of a deformed
/// beam face) and shape B at `pose_b`, with the conventions of [`contact_points`] (the
/// segment's part index is 0, its features faces or vertices, radius 0). The segment is built
/// on the stack: nothing is allocated for it.
///
/// # Errors
/// A non-finite point, pose or prediction, or a shape B parry has no query for.
pub fn segment_contact_points<'w>(
    [p0, p1]: [Vector2<f64>; 2],
    b: &ContactShape,
    pose_b: &BodyState,
    prediction: f64,
    workspace: &'w mut ShapeContactWorkspace,
) -> Result<&'w [ShapeContactPoint], ContactError> {
    check_prediction(LAW, prediction)?;
    for c in [p0.x, p0.y, p1.x, p1.y] {
        finite("segment end point (m)", c)?;
    }
    let segment =
        parry2d_f64::shape::Segment::new(Vector::new(p0.x, p0.y), Vector::new(p1.x, p1.y));
    let side_a = Posed {
        shape: &segment,
        desc: None,
        pose: Pose::IDENTITY,
    };
    let side_b = Posed {
        shape: &*b.parry,
        desc: Some(&b.desc),
        pose: pose_of(pose_b)?,
    };
    query_points(side_a, side_b, prediction, workspace).map_err(|()| {
        ContactError::invalid(
            LAW,
            "shape pair",
            f64::NAN,
            format!(
                "parry2d has no contact query for a segment against {:?}",
                kind(&b.desc)
            ),
        )
    })?;
    Ok(&workspace.points)
}

/// Require a prediction distance ≥ 0 and finite, m (shared with [`crate::shapes3d`]).
pub(crate) fn check_prediction(law: &'static str, prediction: f64) -> Result<(), ContactError> {
    if prediction >= 0.0 && prediction.is_finite() {
        Ok(())
    } else {
        Err(ContactError::invalid(
            law,
            "prediction (m)",
            prediction,
            "must be ≥ 0 and finite",
        ))
    }
}

/// A parry shape at a pose with its description (`None`: a bare segment).
struct Posed<'s> {
    shape: &'s dyn parry2d_f64::shape::Shape,
    desc: Option<&'s Shape>,
    pose: Pose,
}

impl Posed<'_> {
    fn is_ball(&self) -> bool {
        matches!(self.desc, Some(Shape::Ball { .. }))
    }
    fn is_convex(&self) -> bool {
        self.desc.is_none_or(Shape::is_convex)
    }
    /// The feature and radius parry's `contact` leaves unnamed: a ball is a rounded vertex at
    /// its centre; the other shape is whatever carries the closest point (a face unless it is a
    /// ball too).
    fn unnamed_feature(&self) -> (Feature, f64) {
        match self.desc {
            Some(Shape::Ball { radius }) => (Feature::Vertex, *radius),
            Some(Shape::Capsule { radius, .. }) => (Feature::Unknown, *radius),
            _ => (Feature::Unknown, 0.0),
        }
    }
    fn part_radius(&self, k: u32) -> f64 {
        self.desc.map_or(0.0, |d| part_radius(d, k))
    }
}

/// The points of [`contact_points`] into `workspace.points`; `Err` when parry has no query.
fn query_points(
    a: Posed,
    b: Posed,
    prediction: f64,
    workspace: &mut ShapeContactWorkspace,
) -> Result<(), ()> {
    workspace.points.clear();
    if (a.is_ball() && b.is_convex()) || (b.is_ball() && a.is_convex()) {
        let c = query::contact(&a.pose, a.shape, &b.pose, b.shape, prediction).map_err(|_| ())?;
        if let Some(c) = c {
            let ((feature_a, radius_a), (feature_b, radius_b)) =
                (a.unnamed_feature(), b.unnamed_feature());
            workspace.points.push(ShapeContactPoint {
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
    // Recompute every point from scratch: no reuse of the previous call's points.
    for m in &mut workspace.manifolds {
        m.clear();
    }
    let pos12 = a.pose.inv_mul(&b.pose);
    DefaultQueryDispatcher
        .contact_manifolds(
            &pos12,
            a.shape,
            b.shape,
            prediction,
            &mut workspace.manifolds,
            &mut workspace.parry,
        )
        .map_err(|_| ())?;
    for m in &workspace.manifolds {
        if m.points.is_empty() {
            continue;
        }
        // Frames of the two parts (compound part or polyline segment: parry's subshape pose).
        let (sub1, sub2) = match &m.subshape_poses {
            Some(s) => (s.pos1, s.pos2),
            None => (None, None),
        };
        let fa = sub1.map_or(a.pose, |s| a.pose * s);
        let fb = sub2.map_or(b.pose, |s| b.pose * s);
        let normal = nv(fa.rotation * m.local_n1);
        let radius_a = a.part_radius(m.subshape1);
        let radius_b = b.part_radius(m.subshape2);
        for p in &m.points {
            // parry's polygon clipping keeps both face points even when one lies beyond the
            // prediction distance; report only those within it.
            if p.dist > prediction {
                continue;
            }
            workspace.points.push(ShapeContactPoint {
                depth: -p.dist,
                normal,
                point_a: nv(fa * p.local_p1),
                point_b: nv(fb * p.local_p2),
                part_a: m.subshape1,
                part_b: m.subshape2,
                feature_a: Feature::from_parry(p.fid1),
                feature_b: Feature::from_parry(p.fid2),
                radius_a,
                radius_b,
            });
        }
    }
    Ok(())
}

/// The rounding radius of part `k` of a shape (m): ball and capsule radii, else 0.
fn part_radius(s: &Shape, k: u32) -> f64 {
    match s {
        Shape::Ball { radius } | Shape::Capsule { radius, .. } => *radius,
        Shape::Compound { parts } => parts
            .get(k as usize)
            .map_or(0.0, |(_, p)| part_radius(p, 0)),
        _ => 0.0,
    }
}

fn unsupported(a: &ContactShape, b: &ContactShape) -> ContactError {
    ContactError::invalid(
        LAW,
        "shape pair",
        f64::NAN,
        format!(
            "parry2d has no contact query for {:?} against {:?}",
            kind(&a.desc),
            kind(&b.desc)
        ),
    )
}

fn kind(s: &Shape) -> &'static str {
    match s {
        Shape::Ball { .. } => "ball",
        Shape::Capsule { .. } => "capsule",
        Shape::Cuboid { .. } => "cuboid",
        Shape::ConvexPolygon { .. } => "convex polygon",
        Shape::Polyline { .. } => "polyline",
        Shape::Compound { .. } => "compound",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::PI;

    fn at(x: f64, y: f64, angle: f64) -> BodyState {
        BodyState::fixed(Vector2::new(x, y), angle)
    }

    fn shape(s: Result<Shape, ContactError>) -> ContactShape {
        ContactShape::new(s.unwrap()).unwrap()
    }

    #[test]
    fn ball_ball_closed_form() {
        let (r1, r2) = (0.03, 0.02);
        let a = shape(Shape::ball(r1));
        let b = shape(Shape::ball(r2));
        let ca = Vector2::new(0.1, -0.2);
        let dir = Vector2::new(0.6, 0.8);
        let delta = 1e-4;
        let cb = ca + dir * (r1 + r2 - delta);
        let mut ws = ShapeContactWorkspace::new();
        let pts = contact_points(
            &a,
            &at(ca.x, ca.y, 0.3),
            &b,
            &at(cb.x, cb.y, -1.0),
            0.0,
            &mut ws,
        )
        .unwrap();
        assert_eq!(pts.len(), 1);
        let p = pts[0];
        assert_relative_eq!(p.depth, delta, max_relative = 1e-9);
        assert_relative_eq!(p.normal, dir, epsilon = 1e-12);
        assert_relative_eq!(p.point_a, ca + dir * r1, epsilon = 1e-12);
        assert_relative_eq!(p.point_b, cb - dir * r2, epsilon = 1e-12);
        // Separated by 1 mm: nothing without prediction, a negative depth with it.
        let cb = ca + dir * (r1 + r2 + 1e-3);
        let sep = at(cb.x, cb.y, 0.0);
        assert!(
            contact_points(&a, &at(ca.x, ca.y, 0.0), &b, &sep, 0.0, &mut ws)
                .unwrap()
                .is_empty()
        );
        let pts = contact_points(&a, &at(ca.x, ca.y, 0.0), &b, &sep, 2e-3, &mut ws).unwrap();
        assert_relative_eq!(pts[0].depth, -1e-3, max_relative = 1e-9);
    }

    #[test]
    fn ball_cuboid_closed_form_both_orders() {
        let (hx, hy, r) = (0.05, 0.02, 0.01);
        let cub = shape(Shape::cuboid(hx, hy));
        let ball = shape(Shape::ball(r));
        let theta: f64 = 0.4;
        let (c, s) = (theta.cos(), theta.sin());
        let rot = |v: Vector2<f64>| Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y);
        let o = Vector2::new(1.0, 2.0);
        let delta = 2e-4;
        // Ball above the top face, 0.02 m right of centre, body frame of the cuboid.
        let local = Vector2::new(0.02, hy + r - delta);
        let cb = o + rot(local);
        let n = rot(Vector2::new(0.0, 1.0));
        let mut ws = ShapeContactWorkspace::new();
        let pts = contact_points(
            &cub,
            &at(o.x, o.y, theta),
            &ball,
            &at(cb.x, cb.y, 0.0),
            0.0,
            &mut ws,
        )
        .unwrap();
        assert_eq!(pts.len(), 1);
        assert_relative_eq!(pts[0].depth, delta, max_relative = 1e-9);
        assert_relative_eq!(pts[0].normal, n, epsilon = 1e-12);
        assert_relative_eq!(
            pts[0].point_a,
            o + rot(Vector2::new(0.02, hy)),
            epsilon = 1e-12
        );
        assert_relative_eq!(pts[0].point_b, cb - n * r, epsilon = 1e-12);
        // Swapped: the normal points from the ball to the cuboid.
        let pts = contact_points(
            &ball,
            &at(cb.x, cb.y, 0.0),
            &cub,
            &at(o.x, o.y, theta),
            0.0,
            &mut ws,
        )
        .unwrap();
        assert_eq!(pts.len(), 1);
        assert_relative_eq!(pts[0].depth, delta, max_relative = 1e-9);
        assert_relative_eq!(pts[0].normal, -n, epsilon = 1e-12);
    }

    /// Ground segment (polyline A) and a block (cuboid B) resting on it.
    #[test]
    fn cuboid_on_segment_flat_two_equal_corners() {
        let ground = shape(Shape::polyline(vec![[-1.0, 0.0], [1.0, 0.0]]));
        let (hx, hy) = (0.1, 0.05);
        let block = shape(Shape::cuboid(hx, hy));
        let delta = 1e-4;
        let mut ws = ShapeContactWorkspace::new();
        let g = at(0.0, 0.0, 0.0);
        let x0 = 0.3;
        let pts = contact_points(&ground, &g, &block, &at(x0, hy - delta, 0.0), 0.0, &mut ws)
            .unwrap()
            .to_vec();
        assert_eq!(pts.len(), 2, "{pts:?}");
        let mut xs: Vec<f64> = pts.iter().map(|p| p.point_b.x).collect();
        xs.sort_by(f64::total_cmp);
        assert_relative_eq!(xs[0], x0 - hx, epsilon = 1e-12);
        assert_relative_eq!(xs[1], x0 + hx, epsilon = 1e-12);
        for p in &pts {
            assert_relative_eq!(p.depth, delta, max_relative = 1e-9);
            assert_relative_eq!(p.normal, Vector2::new(0.0, 1.0), epsilon = 1e-12);
            assert_relative_eq!(p.point_b.y, -delta, epsilon = 1e-12);
            assert_relative_eq!(p.point_a.y, 0.0, epsilon = 1e-12);
            assert_relative_eq!(p.point_a.x, p.point_b.x, epsilon = 1e-12);
        }
        // Swapped order (block A, ground B): same depths, normal from the block to the ground.
        let pts =
            contact_points(&block, &at(x0, hy - delta, 0.0), &ground, &g, 0.0, &mut ws).unwrap();
        assert_eq!(pts.len(), 2, "{pts:?}");
        for p in pts {
            assert_relative_eq!(p.depth, delta, max_relative = 1e-9);
            assert_relative_eq!(p.normal, Vector2::new(0.0, -1.0), epsilon = 1e-12);
            assert_relative_eq!(p.point_a.y, -delta, epsilon = 1e-12);
        }
    }

    /// Corner heights of a block at centre (x0, yc), angle θ: y = yc ± hx sin θ − hy cos θ.
    #[test]
    fn cuboid_on_segment_tilted_corner_depths() {
        let ground = shape(Shape::polyline(vec![[-1.0, 0.0], [0.0, 0.0], [1.0, 0.0]]));
        let (hx, hy) = (0.1, 0.05);
        let block = shape(Shape::cuboid(hx, hy));
        let g = at(0.0, 0.0, 0.0);
        let mut ws = ShapeContactWorkspace::new();
        let theta: f64 = 0.02;
        let (s, c) = theta.sin_cos();
        let x0 = 0.4;
        // One corner down by δ1, the other lifted by 2 hx sin θ − δ1 > 0.
        let d1 = 1e-4;
        let yc = hx * s + hy * c - d1;
        let pts = contact_points(&ground, &g, &block, &at(x0, yc, theta), 0.0, &mut ws)
            .unwrap()
            .to_vec();
        assert_eq!(pts.len(), 1, "{pts:?}");
        assert_relative_eq!(pts[0].depth, d1, max_relative = 1e-9);
        assert_relative_eq!(pts[0].point_b.x, x0 - hx * c + hy * s, epsilon = 1e-12);
        assert_relative_eq!(pts[0].normal, Vector2::new(0.0, 1.0), epsilon = 1e-12);
        // Both corners down: depths −(yc ∓ hx sin θ − hy cos θ).
        let yc = hy * c - 5e-3;
        let mut pts = contact_points(&ground, &g, &block, &at(x0, yc, theta), 0.0, &mut ws)
            .unwrap()
            .to_vec();
        assert_eq!(pts.len(), 2, "{pts:?}");
        pts.sort_by(|p, q| p.point_b.x.total_cmp(&q.point_b.x));
        assert_relative_eq!(pts[0].depth, -(yc - hx * s - hy * c), max_relative = 1e-9);
        assert_relative_eq!(pts[1].depth, -(yc + hx * s - hy * c), max_relative = 1e-9);
        // The lifted corner is reported (negative depth) only within the prediction distance.
        let yc = hx * s + hy * c - d1;
        let gap = 2.0 * hx * s - d1;
        let pts =
            contact_points(&ground, &g, &block, &at(x0, yc, theta), 1.1 * gap, &mut ws).unwrap();
        let mut depths: Vec<f64> = pts.iter().map(|p| p.depth).collect();
        depths.sort_by(f64::total_cmp);
        assert_eq!(depths.len(), 2, "{pts:?}");
        assert_relative_eq!(depths[0], -gap, max_relative = 1e-9);
        assert_relative_eq!(depths[1], d1, max_relative = 1e-9);
    }

    /// A ball outside a cam approximated by an N-segment inscribed polyline: the depth lies
    /// between the exact circle's depth minus the sagitta R(1 − cos(π/N)) and the exact depth.
    #[test]
    fn ball_on_polyline_cam_within_sagitta() {
        let (big_r, r, n) = (0.05, 0.01, 720);
        let pts_cam: Vec<[f64; 2]> = (0..=n)
            .map(|k| {
                let phi = 2.0 * PI * k as f64 / n as f64;
                [big_r * phi.cos(), big_r * phi.sin()]
            })
            .collect();
        // Closed loop: the last point repeats the first.
        let cam = shape(Shape::polyline(pts_cam));
        let ball = shape(Shape::ball(r));
        let sagitta = big_r * (1.0 - (PI / n as f64).cos());
        let center = at(0.01, -0.02, 0.7);
        let mut ws = ShapeContactWorkspace::new();
        for (i, psi) in [0.0, 0.1234, 1.0, 2.5, -2.0, PI / n as f64]
            .iter()
            .enumerate()
        {
            let delta_exact = 2e-4 * (1.0 + i as f64);
            let d = big_r + r - delta_exact;
            let dir = Vector2::new((psi + 0.7).cos(), (psi + 0.7).sin());
            let cb = center.position + dir * d;
            let pts =
                contact_points(&cam, &center, &ball, &at(cb.x, cb.y, 0.0), 0.0, &mut ws).unwrap();
            assert!(!pts.is_empty());
            let deepest = pts
                .iter()
                .max_by(|p, q| p.depth.total_cmp(&q.depth))
                .unwrap();
            assert!(
                deepest.depth <= delta_exact + 1e-12
                    && deepest.depth >= delta_exact - sagitta - 1e-12,
                "psi {psi}: depth {} exact {delta_exact} sagitta {sagitta}",
                deepest.depth
            );
            // The normal is close to the radial direction (within one segment angle).
            assert!(deepest.normal.dot(&dir) > (2.0 * PI / n as f64).cos() - 1e-12);
            assert_relative_eq!(deepest.normal.norm(), 1.0, epsilon = 1e-12);
        }
    }

    #[test]
    fn polygon_square_matches_cuboid_and_compound() {
        let h = 0.02;
        let square = shape(Shape::convex_polygon(vec![
            [-h, -h],
            [h, -h],
            [h, h],
            [-h, h],
        ]));
        let cub = shape(Shape::cuboid(h, h));
        let comp = shape(Shape::compound(vec![
            ([0.0, 0.0, 0.0], Shape::cuboid(h, h).unwrap()),
            ([1.0, -0.05, 0.0], Shape::ball(0.01).unwrap()),
        ]));
        let ground = shape(Shape::cuboid(1.0, 0.1));
        let g = at(0.0, -0.1, 0.0);
        let delta = 3e-5;
        let pose = at(0.2, h - delta, 0.0);
        let mut ws = ShapeContactWorkspace::new();
        for s in [&square, &cub, &comp] {
            let pts = contact_points(&ground, &g, s, &pose, 0.0, &mut ws).unwrap();
            assert_eq!(pts.len(), 2, "{s:?}: {pts:?}");
            for p in pts {
                assert_relative_eq!(p.depth, delta, max_relative = 1e-9);
                assert_relative_eq!(p.normal, Vector2::new(0.0, 1.0), epsilon = 1e-12);
            }
        }
        // A compound part away from the body origin: its pose is applied.
        let pose = at(-0.5, 0.06 - delta, 0.0);
        let pts = contact_points(&ground, &g, &comp, &pose, 0.0, &mut ws).unwrap();
        assert_eq!(pts.len(), 1, "{pts:?}");
        assert_relative_eq!(pts[0].depth, delta, max_relative = 1e-9);
        assert_relative_eq!(pts[0].point_b, Vector2::new(0.5, -delta), epsilon = 1e-12);
        assert_eq!(pts[0].part_b, 1);
    }

    #[test]
    fn repeated_queries_are_history_free() {
        let ground = shape(Shape::polyline(vec![[-1.0, 0.0], [1.0, 0.0]]));
        let block = shape(Shape::cuboid(0.1, 0.05));
        let g = at(0.0, 0.0, 0.0);
        let p1 = at(0.0, 0.05 - 1e-4, 0.0);
        let p2 = at(1e-5, 0.05 - 2e-4, 1e-4);
        let mut ws = ShapeContactWorkspace::new();
        let fresh = contact_points(&ground, &g, &block, &p2, 0.0, &mut ws)
            .unwrap()
            .to_vec();
        let mut ws = ShapeContactWorkspace::new();
        contact_points(&ground, &g, &block, &p1, 0.0, &mut ws).unwrap();
        let after = contact_points(&ground, &g, &block, &p2, 0.0, &mut ws)
            .unwrap()
            .to_vec();
        assert_eq!(fresh, after);
    }

    #[test]
    fn invalid_shapes_refused() {
        let bad: Vec<Result<Shape, ContactError>> = vec![
            Shape::ball(0.0),
            Shape::ball(-1.0),
            Shape::ball(f64::NAN),
            Shape::capsule(0.1, 0.0),
            Shape::capsule(f64::INFINITY, 0.1),
            Shape::cuboid(0.1, -0.1),
            Shape::convex_polygon(vec![[0.0, 0.0], [1.0, 0.0]]),
            // Clockwise.
            Shape::convex_polygon(vec![[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]),
            // Non-convex (arrow head).
            Shape::convex_polygon(vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.2], [1.0, 1.0]]),
            // Collinear.
            Shape::convex_polygon(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]]),
            // Pentagram: every turn counter-clockwise, but it winds twice.
            Shape::convex_polygon(
                (0..5)
                    .map(|k| {
                        let a = 4.0 * PI * k as f64 / 5.0;
                        [a.cos(), a.sin()]
                    })
                    .collect(),
            ),
            Shape::convex_polygon(vec![[0.0, 0.0], [1.0, f64::NAN], [0.0, 1.0]]),
            Shape::polyline(vec![[0.0, 0.0]]),
            Shape::polyline(vec![[0.0, 0.0], [0.0, 0.0], [1.0, 0.0]]),
            Shape::polyline(vec![[0.0, 0.0], [f64::NAN, 0.0]]),
            Shape::compound(vec![]),
            Shape::compound(vec![(
                [0.0, 0.0, 0.0],
                Shape::Polyline {
                    points: vec![[0.0, 0.0], [1.0, 0.0]],
                },
            )]),
            Shape::compound(vec![([f64::NAN, 0.0, 0.0], Shape::Ball { radius: 1.0 })]),
            Shape::compound(vec![([0.0, 0.0, 0.0], Shape::Ball { radius: -1.0 })]),
        ];
        for (i, r) in bad.into_iter().enumerate() {
            let e = r.expect_err(&format!("case {i} accepted"));
            assert!(matches!(e, ContactError::InvalidParameter { .. }), "{e}");
        }
        // Hand-written variants are checked again when built.
        assert!(ContactShape::new(Shape::Ball { radius: -1.0 }).is_err());
        // Bad poses and prediction are refused.
        let b = shape(Shape::ball(1.0));
        let mut ws = ShapeContactWorkspace::new();
        let ok = at(0.0, 0.0, 0.0);
        assert!(contact_points(&b, &at(f64::NAN, 0.0, 0.0), &b, &ok, 0.0, &mut ws).is_err());
        assert!(contact_points(&b, &ok, &b, &ok, -1.0, &mut ws).is_err());
        // A valid convex polygon with a collinear midpoint is accepted.
        Shape::convex_polygon(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 1.0]]).unwrap();
    }
}
