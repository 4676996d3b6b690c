//! The model builder: named bodies, points, joints, drivers, forces and contact elements.
//!
//! Items refer to each other by name; [`ModelBuilder::build`] resolves and validates every
//! reference and returns a [`Model`] or a typed [`MbdError`] naming the offending item.

use std::collections::HashMap;

use clr_contact::{
    BodyState, ForceApplication, FrictionLaw, NormalLaw, RevoluteClearance, SliderShape,
    TranslationalClearance,
};
use nalgebra::Vector2;

use crate::clearance::{Clearance, ClearanceKind, FlexGuide, GuideBeam};
use crate::error::MbdError;
use crate::flexible::{FlexBeam, NodalLoadFn};
use crate::floating::FloatingBody;
use crate::system::{Con, ConKind, ForceEl, Frame, Model, Motion};

/// Name of the ground body (fixed at the origin, angle 0). It is always defined.
pub const GROUND: &str = "ground";

/// Index of the ground in resolved items (rigid bodies are numbered 0, 1, …).
pub(crate) const GROUND_ID: usize = usize::MAX;

/// A rigid body: mass, inertia about the centre of mass, initial pose and velocity.
///
/// The body reference point is its centre of mass; its coordinates are q = (x, y, θ) in m, m,
/// rad (θ counter-clockwise from the world x axis).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidBody {
    /// Mass, kg (> 0).
    pub mass: f64,
    /// Moment of inertia about the centre of mass, kg·m² (> 0).
    pub inertia: f64,
    /// Initial position of the centre of mass (x, y), m.
    pub position: [f64; 2],
    /// Initial angle, rad.
    pub angle: f64,
    /// Initial velocity of the centre of mass, m/s.
    pub velocity: [f64; 2],
    /// Initial angular velocity, rad/s.
    pub angular_velocity: f64,
}

impl RigidBody {
    /// A body of mass `mass` (kg) and centroidal inertia `inertia` (kg·m²) at rest at the origin.
    pub fn new(mass: f64, inertia: f64) -> Self {
        Self {
            mass,
            inertia,
            position: [0.0; 2],
            angle: 0.0,
            velocity: [0.0; 2],
            angular_velocity: 0.0,
        }
    }
    /// Initial pose: centre of mass at (x, y) m, angle θ rad.
    pub fn at(mut self, x: f64, y: f64, angle: f64) -> Self {
        self.position = [x, y];
        self.angle = angle;
        self
    }
    /// Initial velocity (v_x, v_y) m/s and angular velocity ω rad/s (made consistent with the
    /// constraints by [`Model::initial_state`]).
    pub fn moving(mut self, vx: f64, vy: f64, omega: f64) -> Self {
        self.velocity = [vx, vy];
        self.angular_velocity = omega;
        self
    }
}

/// Where a joint or force attaches: a named point, or a body with local coordinates (m) in the
/// body frame (origin at the centre of mass).
#[derive(Debug, Clone, PartialEq)]
pub enum Anchor {
    /// A point defined with [`ModelBuilder::point`].
    Point(String),
    /// A body name and local coordinates (m).
    Local(String, [f64; 2]),
    /// A node of a flexible beam (beam name, node index): the attachment moves with the node's
    /// displacement and rotation (small-rotation node frame); the same as a
    /// [`ModelBuilder::beam_node_point`].
    BeamNode(String, usize),
}

impl From<(&str, usize)> for Anchor {
    fn from((beam, node): (&str, usize)) -> Self {
        Anchor::BeamNode(beam.to_string(), node)
    }
}

impl From<&str> for Anchor {
    fn from(point: &str) -> Self {
        Anchor::Point(point.to_string())
    }
}

impl From<(&str, [f64; 2])> for Anchor {
    fn from((body, local): (&str, [f64; 2])) -> Self {
        Anchor::Local(body.to_string(), local)
    }
}

/// Applied force on a body: `f(t, state of the body) -> (F_x, F_y)` in N.
pub type ForceFn = Box<dyn Fn(f64, &BodyState) -> Vector2<f64>>;
/// Applied torque on a body: `f(t, state of the body) -> τ` in N·m.
pub type TorqueFn = Box<dyn Fn(f64, &BodyState) -> f64>;
/// Torque between two bodies: `f(t, state of body i, state of body j) -> τ` in N·m, acting
/// +τ on body j and −τ on body i (a motor in the joint between them).
pub type PairTorqueFn = Box<dyn Fn(f64, &BodyState, &BodyState) -> f64>;

/// A revolute clearance joint: bearing (hole) on one body, journal (pin) on another.
pub struct RevoluteClearanceSpec {
    /// Bearing radius R_i, m.
    pub bearing_radius: f64,
    /// Journal radius R_j, m (< R_i).
    pub journal_radius: f64,
    /// Normal-force law (its elastic part already contains the axial length where the law uses
    /// one, e.g. [`NormalLaw::preset`] with a `JournalBearing`).
    pub normal: NormalLaw,
    /// Friction law (use `FrictionLaw::coulomb(0.0, 1.0)` for none).
    pub friction: FrictionLaw,
}

/// A translational clearance joint: a rectangular slider (length L, height h) inside a straight
/// guide of inner width W > h (Flores, Ambrósio, Claro & Lankarani, J. Comput. Nonlinear Dyn. 3
/// (2008) 011007; corners as point contacts, clr-contact `TranslationalClearance`).
pub struct TranslationalClearanceSpec {
    /// Inner width W of the guide, m.
    pub guide_width: f64,
    /// Angle of the guide axis from the guide body's x axis, rad.
    pub guide_angle: f64,
    /// Slider length L along its axis, m.
    pub slider_length: f64,
    /// Slider height h across the guide, m (< W).
    pub slider_height: f64,
    /// Angle of the slider axis from the slider body's x axis, rad.
    pub slider_angle: f64,
    /// Normal-force law of each corner contact.
    pub normal: NormalLaw,
    /// Friction law of each corner contact.
    pub friction: FrictionLaw,
}

/// A rigid rectangular slider on a face of a flexible beam, ground-fixed
/// ([`ModelBuilder::flexible_beam`]) or moving ([`ModelBuilder::floating_beam`]): clr-contact's
/// multipoint detection (corners, face points, optional reverse check with guide samples)
/// against the deformed beam surface from clr-beam; the guide reactions become work-equivalent
/// nodal loads of the beam (and, on a floating beam, forces on its frame).
pub struct FlexibleGuideSpec {
    /// Beam face the slider runs on (`Upper`: the +h/2 face on the left of the beam axis).
    pub face: clr_beam::Face,
    /// Slider length L, m.
    pub slider_length: f64,
    /// Slider height h, m.
    pub slider_height: f64,
    /// Angle of the slider axis from its body's x axis, rad.
    pub slider_angle: f64,
    /// Candidate points on each slider face besides the corners (e.g. 5).
    pub face_points: usize,
    /// Guide samples of the reverse check (0 disables it).
    pub guide_samples: usize,
    /// Normal-force law of each contact point (the line law, e.g. [`NormalLaw::flores_line`]).
    pub normal: NormalLaw,
    /// Optional area law (e.g. [`NormalLaw::area`], a line term plus a term growing with the
    /// contact length) used instead of `normal` at every contact point, with the contact length
    /// set to the point's wetted length (`clr_contact::ContactPoint::tributary_length`, continuous
    /// in the configuration): an isolated edge (length → 0) gets the line law, a face lying on
    /// the guide the area law integrated over the face, with no force jump at the line → area
    /// class change. `None` keeps `normal` for every contact.
    pub area_normal: Option<NormalLaw>,
    /// Friction law of each contact point.
    pub friction: FrictionLaw,
}

enum Item {
    Point {
        name: String,
        body: String,
        local: [f64; 2],
    },
    Revolute {
        name: String,
        a: Anchor,
        b: Anchor,
    },
    Fixed {
        name: String,
        a: Anchor,
        b: Anchor,
    },
    Translational {
        name: String,
        a: Anchor,
        b: Anchor,
        axis: [f64; 2],
    },
    DriveAngle {
        name: String,
        body_i: String,
        body_j: String,
        motion: Motion,
    },
    DriveDisplacement {
        name: String,
        a: Anchor,
        b: Anchor,
        axis: [f64; 2],
        motion: Motion,
    },
    Spring {
        name: String,
        a: Anchor,
        b: Anchor,
        k: f64,
        c: f64,
        l0: f64,
    },
    RotSpring {
        name: String,
        body_i: String,
        body_j: String,
        k: f64,
        c: f64,
        angle0: f64,
    },
    Force {
        name: String,
        at: Anchor,
        f: ForceFn,
    },
    Torque {
        name: String,
        body: String,
        f: TorqueFn,
    },
    PairTorque {
        name: String,
        body_i: String,
        body_j: String,
        f: PairTorqueFn,
    },
    RevClearance {
        name: String,
        bearing: Anchor,
        journal: Anchor,
        spec: RevoluteClearanceSpec,
    },
    TransClearance {
        name: String,
        guide: Anchor,
        slider: Anchor,
        spec: TranslationalClearanceSpec,
    },
    Beam {
        name: String,
        model: Box<clr_beam::BeamModel>,
    },
    BeamPoint {
        name: String,
        beam: String,
        node: usize,
    },
    SliderOnBeam {
        name: String,
        beam: String,
        slider: Anchor,
        spec: FlexibleGuideSpec,
    },
    BeamLoad {
        name: String,
        beam: String,
        node: usize,
        f: NodalLoadFn,
    },
}

impl Item {
    fn name(&self) -> &str {
        match self {
            Item::Point { name, .. }
            | Item::Revolute { name, .. }
            | Item::Fixed { name, .. }
            | Item::Translational { name, .. }
            | Item::DriveAngle { name, .. }
            | Item::DriveDisplacement { name, .. }
            | Item::Spring { name, .. }
            | Item::RotSpring { name, .. }
            | Item::Force { name, .. }
            | Item::Torque { name, .. }
            | Item::PairTorque { name, .. }
            | Item::RevClearance { name, .. }
            | Item::TransClearance { name, .. }
            | Item::Beam { name, .. }
            | Item::BeamPoint { name, .. }
            | Item::SliderOnBeam { name, .. }
            | Item::BeamLoad { name, .. } => name,
        }
    }
    fn kind(&self) -> &'static str {
        match self {
            Item::Point { .. } => "point",
            Item::Revolute { .. } => "revolute joint",
            Item::Fixed { .. } => "fixed joint",
            Item::Translational { .. } => "translational joint",
            Item::DriveAngle { .. } => "angle driver",
            Item::DriveDisplacement { .. } => "displacement driver",
            Item::Spring { .. } => "spring-damper",
            Item::RotSpring { .. } => "rotational spring-damper",
            Item::Force { .. } => "applied force",
            Item::Torque { .. } => "applied torque",
            Item::PairTorque { .. } => "torque between bodies",
            Item::RevClearance { .. } => "revolute clearance joint",
            Item::TransClearance { .. } => "translational clearance joint",
            Item::Beam { .. } => "flexible beam",
            Item::BeamPoint { .. } => "beam node point",
            Item::SliderOnBeam { .. } => "slider on a flexible guide",
            Item::BeamLoad { .. } => "beam nodal load",
        }
    }
}

/// Builds a [`Model`]. Methods record items and never fail; [`ModelBuilder::build`] validates.
///
/// ```
/// use clr_mbd::{ModelBuilder, RigidBody};
/// // a pendulum: 1 kg rod of length 1 m pinned at the origin, horizontal at t = 0
/// let mut b = ModelBuilder::new();
/// b.gravity(0.0, -9.81)
///     .body("rod", RigidBody::new(1.0, 1.0 / 12.0).at(0.5, 0.0, 0.0))
///     .revolute("pin", ("ground", [0.0, 0.0]), ("rod", [-0.5, 0.0]));
/// let model = b.build().unwrap();
/// assert_eq!(model.n_coordinates(), 3);
/// assert_eq!(model.n_constraints(), 2);
/// ```
#[derive(Default)]
pub struct ModelBuilder {
    bodies: Vec<(String, RigidBody)>,
    items: Vec<Item>,
    gravity: [f64; 2],
    force_application: Option<ForceApplication>,
    floating: Vec<FloatingSpec>,
}

/// A floating flexible body as given to the builder: name, beam model, reduction, pose, velocity.
type FloatingSpec = (
    String,
    Box<clr_beam::BeamModel>,
    Box<clr_beam::ReducedModel>,
    [f64; 3],
    [f64; 3],
);

impl ModelBuilder {
    /// An empty model (only the ground), no gravity.
    pub fn new() -> Self {
        Self::default()
    }

    /// Gravitational acceleration (g_x, g_y) in m/s², e.g. (0, −9.81).
    pub fn gravity(&mut self, gx: f64, gy: f64) -> &mut Self {
        self.gravity = [gx, gy];
        self
    }

    /// Where the force pair of every revolute clearance joint acts (default
    /// [`ForceApplication::CommonPoint`]: collinear action and reaction, so the joints conserve
    /// the system's angular momentum; [`ForceApplication::ContactPoints`] is the published Flores
    /// et al. (2004) form, whose friction pair adds a moment δ·F_T — see clr-contact's `revolute`).
    pub fn clearance_force_application(&mut self, application: ForceApplication) -> &mut Self {
        self.force_application = Some(application);
        self
    }

    /// A rigid body named `name`.
    pub fn body(&mut self, name: &str, body: RigidBody) -> &mut Self {
        self.bodies.push((name.to_string(), body));
        self
    }

    /// A named point fixed on `body` at local coordinates `local` (m).
    pub fn point(&mut self, name: &str, body: &str, local: [f64; 2]) -> &mut Self {
        self.items.push(Item::Point {
            name: name.into(),
            body: body.into(),
            local,
        });
        self
    }

    /// An ideal revolute joint: the anchor points `a` (on body i) and `b` (on body j) coincide
    /// (2 equations, Nikravesh 1988, eq. 5.11).
    pub fn revolute(
        &mut self,
        name: &str,
        a: impl Into<Anchor>,
        b: impl Into<Anchor>,
    ) -> &mut Self {
        self.items.push(Item::Revolute {
            name: name.into(),
            a: a.into(),
            b: b.into(),
        });
        self
    }

    /// A fixed joint: the anchors coincide and the relative angle keeps its initial value
    /// (3 equations).
    pub fn fixed(&mut self, name: &str, a: impl Into<Anchor>, b: impl Into<Anchor>) -> &mut Self {
        self.items.push(Item::Fixed {
            name: name.into(),
            a: a.into(),
            b: b.into(),
        });
        self
    }

    /// An ideal translational (prismatic) joint: the anchor on body j stays on the line through
    /// the anchor on body i along `axis` (local to body i, any length > 0), and the relative
    /// angle keeps its initial value (2 equations, Nikravesh 1988, eq. 5.15).
    pub fn translational(
        &mut self,
        name: &str,
        a: impl Into<Anchor>,
        b: impl Into<Anchor>,
        axis: [f64; 2],
    ) -> &mut Self {
        self.items.push(Item::Translational {
            name: name.into(),
            a: a.into(),
            b: b.into(),
            axis,
        });
        self
    }

    /// Driver of the absolute angle of `body`: θ = f(t) (rad).
    pub fn drive_angle(&mut self, name: &str, body: &str, motion: Motion) -> &mut Self {
        self.drive_relative_angle(name, GROUND, body, motion)
    }

    /// Driver of the relative angle θ_j − θ_i = f(t) (rad).
    pub fn drive_relative_angle(
        &mut self,
        name: &str,
        body_i: &str,
        body_j: &str,
        motion: Motion,
    ) -> &mut Self {
        self.items.push(Item::DriveAngle {
            name: name.into(),
            body_i: body_i.into(),
            body_j: body_j.into(),
            motion,
        });
        self
    }

    /// Driver of a relative displacement (an actuator): the projection of (P_j − P_i) on the unit
    /// `axis` fixed on body i equals f(t) (m).
    pub fn drive_displacement(
        &mut self,
        name: &str,
        a: impl Into<Anchor>,
        b: impl Into<Anchor>,
        axis: [f64; 2],
        motion: Motion,
    ) -> &mut Self {
        self.items.push(Item::DriveDisplacement {
            name: name.into(),
            a: a.into(),
            b: b.into(),
            axis,
            motion,
        });
        self
    }

    /// A translational spring–damper between two anchors: tension f = k(l − l0) + c·l̇ along the
    /// line between them (k in N/m, c in N·s/m, free length l0 in m).
    pub fn spring_damper(
        &mut self,
        name: &str,
        a: impl Into<Anchor>,
        b: impl Into<Anchor>,
        k: f64,
        c: f64,
        l0: f64,
    ) -> &mut Self {
        self.items.push(Item::Spring {
            name: name.into(),
            a: a.into(),
            b: b.into(),
            k,
            c,
            l0,
        });
        self
    }

    /// A rotational spring–damper: torque on body j τ = −k(θ_j − θ_i − θ0) − c(ω_j − ω_i), −τ on
    /// body i (k in N·m/rad, c in N·m·s/rad, θ0 in rad).
    pub fn rotational_spring_damper(
        &mut self,
        name: &str,
        body_i: &str,
        body_j: &str,
        k: f64,
        c: f64,
        angle0: f64,
    ) -> &mut Self {
        self.items.push(Item::RotSpring {
            name: name.into(),
            body_i: body_i.into(),
            body_j: body_j.into(),
            k,
            c,
            angle0,
        });
        self
    }

    /// An applied force (N, world frame) at an anchor, a function of time and the body state.
    pub fn applied_force(
        &mut self,
        name: &str,
        at: impl Into<Anchor>,
        f: impl Fn(f64, &BodyState) -> Vector2<f64> + 'static,
    ) -> &mut Self {
        self.items.push(Item::Force {
            name: name.into(),
            at: at.into(),
            f: Box::new(f),
        });
        self
    }

    /// An applied torque (N·m) on a body, a function of time and the body state.
    pub fn applied_torque(
        &mut self,
        name: &str,
        body: &str,
        f: impl Fn(f64, &BodyState) -> f64 + 'static,
    ) -> &mut Self {
        self.items.push(Item::Torque {
            name: name.into(),
            body: body.into(),
            f: Box::new(f),
        });
        self
    }

    /// A torque between two bodies (a joint drive): +τ on body j, −τ on body i.
    pub fn torque_between(
        &mut self,
        name: &str,
        body_i: &str,
        body_j: &str,
        f: impl Fn(f64, &BodyState, &BodyState) -> f64 + 'static,
    ) -> &mut Self {
        self.items.push(Item::PairTorque {
            name: name.into(),
            body_i: body_i.into(),
            body_j: body_j.into(),
            f: Box::new(f),
        });
        self
    }

    /// A revolute clearance joint: bearing centre at anchor `bearing`, journal centre at anchor
    /// `journal`; a force element (no constraint equation).
    pub fn revolute_clearance(
        &mut self,
        name: &str,
        bearing: impl Into<Anchor>,
        journal: impl Into<Anchor>,
        spec: RevoluteClearanceSpec,
    ) -> &mut Self {
        self.items.push(Item::RevClearance {
            name: name.into(),
            bearing: bearing.into(),
            journal: journal.into(),
            spec,
        });
        self
    }

    /// A translational clearance joint: the guide frame's origin is anchor `guide` (the guide
    /// centre line passes through it along `spec.guide_angle`), the slider centre is anchor
    /// `slider`; a force element (no constraint equation).
    pub fn translational_clearance(
        &mut self,
        name: &str,
        guide: impl Into<Anchor>,
        slider: impl Into<Anchor>,
        spec: TranslationalClearanceSpec,
    ) -> &mut Self {
        self.items.push(Item::TransClearance {
            name: name.into(),
            guide: guide.into(),
            slider: slider.into(),
            spec,
        });
        self
    }

    /// A ground-fixed flexible beam: a clr-beam model (nodes, elements, supports, Rayleigh
    /// damping, mass kind) whose free nodal DOF become coordinates of the model (see the
    /// `flexible` module docs). Joints to beam nodes are not available yet.
    pub fn flexible_beam(&mut self, name: &str, model: clr_beam::BeamModel) -> &mut Self {
        self.items.push(Item::Beam {
            name: name.into(),
            model: Box::new(model),
        });
        self
    }

    /// A moving flexible body in a floating frame of reference (Shabana 2020 ch. 5; formulation
    /// and reference conditions in [`crate::floating`]): the beam `model`
    /// (coordinates in the body frame, m; its supports are the reference conditions, e.g. a clamp
    /// at node 0) and its reduction `reduced` (from `model.modal_truncation(n)` or
    /// `model.craig_bampton(..)`), the initial frame pose `pose` = (R_x m, R_y m, θ rad) and
    /// velocity (Ṙ_x, Ṙ_y m/s, θ̇ rad/s); elastic coordinates start at rest and undeformed.
    /// Attach joints with `(name, node)` anchors (a deforming node gets a node-frame tie, see
    /// [`crate::floating`]) or body-local `(name, [x, y])` anchors (rigid with the frame).
    /// Its coordinates `name.x`, `name.y`, `name.theta`, `name.q<k>`
    /// come after the rigid bodies' in q.
    pub fn floating_beam(
        &mut self,
        name: &str,
        model: clr_beam::BeamModel,
        reduced: clr_beam::ReducedModel,
        pose: [f64; 3],
        velocity: [f64; 3],
    ) -> &mut Self {
        self.floating.push((
            name.into(),
            Box::new(model),
            Box::new(reduced),
            pose,
            velocity,
        ));
        self
    }

    /// A named point at node `node` of flexible beam `beam`: joints, springs, forces and contact
    /// elements anchored at it (`Anchor::Point(name)`, or just `"name"`) move with the node's
    /// displacement and rotation (small-rotation node frame).
    pub fn beam_node_point(&mut self, name: &str, beam: &str, node: usize) -> &mut Self {
        self.items.push(Item::BeamPoint {
            name: name.into(),
            beam: beam.into(),
            node,
        });
        self
    }

    /// A slider on a flexible guide: the slider centre is anchor `slider` (a rigid body), the
    /// guide is a face of flexible beam `beam` (see [`FlexibleGuideSpec`]): a ground-fixed
    /// [`ModelBuilder::flexible_beam`] or a moving [`ModelBuilder::floating_beam`] (then the face
    /// is r = R + A(θ)(ū₀ + Φ q_f) with the beam's cubic interpolation and offset ±h/2, and the
    /// guide reactions act on (R, θ, q_f) by virtual work; see `docs/mbd.md`). Onsets are not
    /// located as events for this element.
    pub fn slider_on_beam(
        &mut self,
        name: &str,
        beam: &str,
        slider: impl Into<Anchor>,
        spec: FlexibleGuideSpec,
    ) -> &mut Self {
        self.items.push(Item::SliderOnBeam {
            name: name.into(),
            beam: beam.into(),
            slider: slider.into(),
            spec,
        });
        self
    }

    /// A nodal load on beam `beam` at node `node`: `f(t) -> [F_x, F_y, M]` (N, N, N·m, global
    /// axes); components on constrained DOF are taken by the supports.
    pub fn beam_nodal_load(
        &mut self,
        name: &str,
        beam: &str,
        node: usize,
        f: impl Fn(f64) -> [f64; 3] + 'static,
    ) -> &mut Self {
        self.items.push(Item::BeamLoad {
            name: name.into(),
            beam: beam.into(),
            node,
            f: Box::new(f),
        });
        self
    }

    /// Validate every item and build the model.
    ///
    /// # Errors
    /// [`MbdError::DuplicateName`], [`MbdError::UnknownBody`], [`MbdError::UnknownPoint`],
    /// [`MbdError::InvalidInertia`], [`MbdError::SameBody`], [`MbdError::InvalidParameter`],
    /// [`MbdError::Contact`].
    pub fn build(self) -> Result<Model, MbdError> {
        let mut names: HashMap<String, &'static str> = HashMap::new();
        names.insert(GROUND.to_string(), "ground");
        let mut claim = |name: &str, kind: &'static str| -> Result<(), MbdError> {
            if let Some(first) = names.get(name) {
                return Err(MbdError::DuplicateName {
                    name: name.to_string(),
                    first,
                    second: kind,
                });
            }
            names.insert(name.to_string(), kind);
            Ok(())
        };
        let mut body_ids = HashMap::new();
        for (k, (name, b)) in self.bodies.iter().enumerate() {
            claim(name, "body")?;
            for (what, v) in [
                ("mass (kg)", b.mass),
                (
                    "moment of inertia about the centre of mass (kg·m²)",
                    b.inertia,
                ),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(MbdError::InvalidInertia {
                        body: name.clone(),
                        what,
                        value: v,
                    });
                }
            }
            let finite = b
                .position
                .iter()
                .chain(b.velocity.iter())
                .all(|v| v.is_finite())
                && b.angle.is_finite()
                && b.angular_velocity.is_finite();
            if !finite {
                return Err(MbdError::InvalidParameter {
                    item: name.clone(),
                    what: "initial pose or velocity",
                    value: f64::NAN,
                    requirement: "every component must be finite",
                });
            }
            body_ids.insert(name.clone(), k);
        }
        // floating bodies: frame index after the rigid bodies, coordinates before the beams
        let mut floating: Vec<FloatingBody> = Vec::with_capacity(self.floating.len());
        let mut offset = 3 * self.bodies.len();
        for (name, model, red, pose, vel) in &self.floating {
            claim(name, "floating flexible body")?;
            let mut fb = FloatingBody::new(name, model, red, *pose, *vel)?;
            fb.offset = offset;
            offset += fb.n_coords();
            body_ids.insert(name.clone(), self.bodies.len() + floating.len());
            floating.push(fb);
        }
        for item in &self.items {
            claim(item.name(), item.kind())?;
        }
        let known = self
            .bodies
            .iter()
            .map(|(n, _)| n.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        let body = |item: &str, name: &str| -> Result<usize, MbdError> {
            if name == GROUND {
                return Ok(GROUND_ID);
            }
            body_ids
                .get(name)
                .copied()
                .ok_or_else(|| MbdError::UnknownBody {
                    item: item.to_string(),
                    body: name.to_string(),
                    known: known.clone(),
                })
        };
        // points first: anchors may refer to them
        let mut points: HashMap<String, (usize, Vector2<f64>)> = HashMap::new();
        let mut point_list = Vec::new();
        for item in &self.items {
            if let Item::Point {
                name,
                body: b,
                local,
            } = item
            {
                let id = body(name, b)?;
                check_finite_vec(name, "local point (m)", *local)?;
                points.insert(name.clone(), (id, Vector2::new(local[0], local[1])));
                point_list.push((name.clone(), id, Vector2::new(local[0], local[1])));
            }
        }
        let anchor = |item: &str, a: &Anchor| -> Result<(usize, Vector2<f64>), MbdError> {
            match a {
                Anchor::Point(p) => points
                    .get(p)
                    .copied()
                    .ok_or_else(|| MbdError::UnknownPoint {
                        item: item.to_string(),
                        point: p.clone(),
                    }),
                Anchor::Local(b, l) => {
                    check_finite_vec(item, "local anchor coordinates (m)", *l)?;
                    Ok((body(item, b)?, Vector2::new(l[0], l[1])))
                }
                // resolved by the beam-aware wrapper below; reaching here means no such beam
                Anchor::BeamNode(b, _) => Err(MbdError::UnknownBody {
                    item: item.to_string(),
                    body: b.clone(),
                    known: known.clone(),
                }),
            }
        };
        let body_name = |id: usize| -> String {
            match self.bodies.get(id) {
                Some(b) => b.0.clone(),
                None if id == GROUND_ID => GROUND.to_string(),
                None => "a beam node".to_string(),
            }
        };
        let distinct = |item: &str, i: usize, j: usize| -> Result<(), MbdError> {
            if i == j {
                Err(MbdError::SameBody {
                    item: item.to_string(),
                    body: body_name(i),
                })
            } else {
                Ok(())
            }
        };
        let nb = self.bodies.len();
        let angle0 = |id: usize| -> f64 {
            match self.bodies.get(id) {
                Some(b) => b.1.angle,
                None => floating.get(id.wrapping_sub(nb)).map_or(0.0, |f| f.pose[2]),
            }
        };
        let mut cons: Vec<Con> = Vec::new();
        let mut forces: Vec<ForceEl> = Vec::new();
        let mut clearances: Vec<Clearance> = Vec::new();
        let mut motions: Vec<Motion> = Vec::new();
        let mut beams: Vec<FlexBeam> = Vec::new();
        let mut items = Vec::with_capacity(self.items.len());
        for item in self.items {
            if let Item::Beam { name, model } = item {
                let mut fb = FlexBeam::new(&name, &model)?;
                fb.offset = offset;
                offset += fb.n_free();
                beams.push(fb);
            } else {
                items.push(item);
            }
        }
        // attachment frames: rigid bodies, then the beam nodes named by beam_node_point
        let mut frames: Vec<Frame> = (0..self.bodies.len()).map(Frame::rigid).collect();
        frames.extend(floating.iter().map(|f| Frame {
            cols: [Some(f.offset), Some(f.offset + 1), Some(f.offset + 2)],
            base: Vector2::zeros(),
        }));
        let mut float_nodes: HashMap<(String, usize), (usize, Vector2<f64>)> = HashMap::new();
        let mut float_points: HashMap<String, (usize, Vector2<f64>)> = HashMap::new();
        let mut ties: Vec<(usize, usize, usize)> = Vec::new();
        let mut node_points: HashMap<String, usize> = HashMap::new();
        let mut node_frames: HashMap<(String, usize), usize> = HashMap::new();
        let mut wanted: Vec<(String, String, usize, Option<String>)> = Vec::new();
        for item in &items {
            if let Item::BeamPoint { name, beam, node } = item {
                wanted.push((name.clone(), beam.clone(), *node, Some(name.clone())));
            }
            for a in item_anchors(item) {
                if let Anchor::BeamNode(beam, node) = a {
                    wanted.push((item.name().to_string(), beam.clone(), *node, None));
                }
            }
        }
        for (name, beam, node, point) in &wanted {
            if let Some(f) = floating.iter().position(|f| &f.name == beam) {
                if *node >= floating[f].nodes.len() {
                    return Err(MbdError::InvalidParameter {
                        item: name.clone(),
                        what: "floating-body node index",
                        value: *node as f64,
                        requirement: "must be a node of the floating body's beam model",
                    });
                }
                let a = if let Some(&a) = float_nodes.get(&(beam.clone(), *node)) {
                    a
                } else if floating[f].is_reference_node(*node) {
                    let p = floating[f].nodes[*node];
                    (nb + f, Vector2::new(p[0], p[1]))
                } else {
                    // a deforming node: its own frame coordinates tied to the body (3 rows)
                    frames.push(Frame {
                        cols: [Some(offset), Some(offset + 1), Some(offset + 2)],
                        base: Vector2::zeros(),
                    });
                    let j = frames.len() - 1;
                    cons.push(Con {
                        name: format!("{beam}.node{node}"),
                        kind: ConKind::FloatNode {
                            f,
                            node: *node,
                            col: offset,
                            i: nb + f,
                            j,
                        },
                        row: 0,
                    });
                    ties.push((f, *node, offset));
                    offset += 3;
                    (j, Vector2::zeros())
                };
                float_nodes.insert((beam.clone(), *node), a);
                if let Some(p) = point {
                    float_points.insert(p.clone(), a);
                }
                continue;
            }
            {
                let key = (beam.clone(), *node);
                if let Some(&k) = node_frames.get(&key) {
                    if let Some(p) = point {
                        node_points.insert(p.clone(), k);
                    }
                    continue;
                }
                let Some(fb) = beams.iter().find(|b| &b.name == beam) else {
                    return Err(MbdError::UnknownBody {
                        item: name.clone(),
                        body: beam.clone(),
                        known: "(beams) ".to_string() + &known,
                    });
                };
                if *node >= fb.nodes.len() {
                    return Err(MbdError::InvalidParameter {
                        item: name.clone(),
                        what: "beam node index",
                        value: *node as f64,
                        requirement: "must be a node of the beam model",
                    });
                }
                let cols = [0, 1, 2].map(|c| {
                    fb.free
                        .iter()
                        .position(|&d| d == 3 * node + c)
                        .map(|k| fb.offset + k)
                });
                let p = fb.nodes[*node];
                frames.push(Frame {
                    cols,
                    base: Vector2::new(p[0], p[1]),
                });
                node_frames.insert(key, frames.len() - 1);
                if let Some(p) = point {
                    node_points.insert(p.clone(), frames.len() - 1);
                }
            }
        }
        let anchor = |item: &str, a: &Anchor| -> Result<(usize, Vector2<f64>), MbdError> {
            match a {
                Anchor::Point(p) if node_points.contains_key(p) => {
                    Ok((node_points[p], Vector2::zeros()))
                }
                Anchor::Point(p) if float_points.contains_key(p) => Ok(float_points[p]),
                Anchor::BeamNode(b, k) if float_nodes.contains_key(&(b.clone(), *k)) => {
                    Ok(float_nodes[&(b.clone(), *k)])
                }
                Anchor::BeamNode(b, k) => node_frames
                    .get(&(b.clone(), *k))
                    .map(|&f| (f, Vector2::zeros()))
                    .ok_or_else(|| MbdError::UnknownBody {
                        item: item.to_string(),
                        body: b.clone(),
                        known: known.clone(),
                    }),
                _ => anchor(item, a),
            }
        };
        for item in items {
            let name = item.name().to_string();
            match item {
                Item::Point { .. } | Item::Beam { .. } | Item::BeamPoint { .. } => {}
                Item::SliderOnBeam {
                    beam, slider, spec, ..
                } => {
                    let (j, sj) = anchor(&name, &slider)?;
                    if j == GROUND_ID || j >= self.bodies.len() {
                        return Err(MbdError::InvalidParameter {
                            item: name,
                            what: "slider body",
                            value: f64::NAN,
                            requirement:
                                "the slider must be a rigid body (not the ground or a beam node)",
                        });
                    }
                    // a ground-fixed beam, or a floating-frame body (its face moves with it)
                    let found = match beams.iter().position(|fb| fb.name == beam) {
                        Some(b) => Some((
                            GuideBeam::Fixed(b),
                            GROUND_ID,
                            beams[b].path.clone(),
                            beams[b].n_dof_full,
                        )),
                        None => floating.iter().position(|f| f.name == beam).map(|f| {
                            (
                                GuideBeam::Floating(f),
                                nb + f,
                                floating[f].path.clone(),
                                3 * floating[f].nodes.len(),
                            )
                        }),
                    };
                    let Some((guide_beam, guide_frame, path, nfull)) = found else {
                        return Err(MbdError::UnknownBody {
                            item: name,
                            body: beam,
                            known: "(beams) ".to_string() + &known,
                        });
                    };
                    let Some(path) = path else {
                        return Err(MbdError::InvalidParameter {
                            item: name,
                            what: "beam path",
                            value: f64::NAN,
                            requirement: "the beam's elements must form one chain (as BeamModel::straight makes)",
                        });
                    };
                    let contact = |source| MbdError::Contact {
                        item: name.clone(),
                        source,
                    };
                    let shape = slider_shape(
                        &name,
                        [spec.slider_length, spec.slider_height],
                        sj,
                        spec.slider_angle,
                    )?;
                    let detector = clr_contact::MultipointDetector::new(
                        shape,
                        spec.face_points,
                        spec.guide_samples,
                    )
                    .map_err(contact)?;
                    clearances.push(Clearance {
                        name,
                        i: guide_frame,
                        j,
                        kind: ClearanceKind::FlexGuide(Box::new(FlexGuide {
                            beam: guide_beam,
                            path,
                            face: spec.face,
                            area_normal: spec.area_normal,
                            detector,
                            qfull: vec![0.0; nfull],
                            qdfull: vec![0.0; nfull],
                        })),
                        normal: spec.normal,
                        friction: spec.friction,
                        mem: 0,
                    });
                }
                Item::BeamLoad { beam, node, f, .. } => {
                    let Some(fb) = beams.iter_mut().find(|b| b.name == beam) else {
                        return Err(MbdError::UnknownBody {
                            item: name,
                            body: beam,
                            known: "(beams) ".to_string() + &known,
                        });
                    };
                    if 3 * node + 2 >= fb.n_dof_full {
                        return Err(MbdError::InvalidParameter {
                            item: name,
                            what: "node index",
                            value: node as f64,
                            requirement: "must be a node of the beam model",
                        });
                    }
                    let idx = [0, 1, 2].map(|c| fb.free.iter().position(|&d| d == 3 * node + c));
                    fb.loads.push((idx, f));
                }
                Item::Revolute { a, b, .. } => {
                    let (i, si) = anchor(&name, &a)?;
                    let (j, sj) = anchor(&name, &b)?;
                    distinct(&name, i, j)?;
                    cons.push(Con::coincide(&name, i, si, j, sj));
                }
                Item::Fixed { a, b, .. } => {
                    let (i, si) = anchor(&name, &a)?;
                    let (j, sj) = anchor(&name, &b)?;
                    distinct(&name, i, j)?;
                    cons.push(Con::coincide(&name, i, si, j, sj));
                    cons.push(Con::angle(&name, i, j, angle0(j) - angle0(i), None));
                }
                Item::Translational { a, b, axis, .. } => {
                    let (i, si) = anchor(&name, &a)?;
                    let (j, sj) = anchor(&name, &b)?;
                    distinct(&name, i, j)?;
                    let u = unit_axis(&name, axis)?;
                    let w = Vector2::new(-u.y, u.x);
                    cons.push(Con::project(&name, i, si, j, sj, w, None));
                    cons.push(Con::angle(&name, i, j, angle0(j) - angle0(i), None));
                }
                Item::DriveAngle {
                    body_i,
                    body_j,
                    motion,
                    ..
                } => {
                    let i = body(&name, &body_i)?;
                    let j = body(&name, &body_j)?;
                    distinct(&name, i, j)?;
                    motions.push(motion);
                    cons.push(Con::angle(&name, i, j, 0.0, Some(motions.len() - 1)));
                }
                Item::DriveDisplacement {
                    a, b, axis, motion, ..
                } => {
                    let (i, si) = anchor(&name, &a)?;
                    let (j, sj) = anchor(&name, &b)?;
                    distinct(&name, i, j)?;
                    let u = unit_axis(&name, axis)?;
                    motions.push(motion);
                    cons.push(Con::project(
                        &name,
                        i,
                        si,
                        j,
                        sj,
                        u,
                        Some(motions.len() - 1),
                    ));
                }
                Item::Spring { a, b, k, c, l0, .. } => {
                    let (i, si) = anchor(&name, &a)?;
                    let (j, sj) = anchor(&name, &b)?;
                    distinct(&name, i, j)?;
                    non_negative(&name, "stiffness k (N/m)", k)?;
                    non_negative(&name, "damping c (N·s/m)", c)?;
                    non_negative(&name, "free length l0 (m)", l0)?;
                    forces.push(ForceEl::Spring {
                        name,
                        i,
                        si,
                        j,
                        sj,
                        k,
                        c,
                        l0,
                    });
                }
                Item::RotSpring {
                    body_i,
                    body_j,
                    k,
                    c,
                    angle0: a0,
                    ..
                } => {
                    let i = body(&name, &body_i)?;
                    let j = body(&name, &body_j)?;
                    distinct(&name, i, j)?;
                    non_negative(&name, "stiffness k (N·m/rad)", k)?;
                    non_negative(&name, "damping c (N·m·s/rad)", c)?;
                    if !a0.is_finite() {
                        return Err(MbdError::InvalidParameter {
                            item: name,
                            what: "free angle θ0 (rad)",
                            value: a0,
                            requirement: "must be finite",
                        });
                    }
                    forces.push(ForceEl::RotSpring {
                        name,
                        i,
                        j,
                        k,
                        c,
                        angle0: a0,
                    });
                }
                Item::Force { at, f, .. } => {
                    let (i, si) = anchor(&name, &at)?;
                    if i == GROUND_ID {
                        return Err(ground_load(name));
                    }
                    forces.push(ForceEl::Force { name, i, si, f });
                }
                Item::Torque { body: b, f, .. } => {
                    let i = body(&name, &b)?;
                    if i == GROUND_ID {
                        return Err(ground_load(name));
                    }
                    forces.push(ForceEl::Torque { name, i, f });
                }
                Item::PairTorque {
                    body_i, body_j, f, ..
                } => {
                    let i = body(&name, &body_i)?;
                    let j = body(&name, &body_j)?;
                    distinct(&name, i, j)?;
                    forces.push(ForceEl::PairTorque { name, i, j, f });
                }
                Item::RevClearance {
                    bearing,
                    journal,
                    spec,
                    ..
                } => {
                    let (i, si) = anchor(&name, &bearing)?;
                    let (j, sj) = anchor(&name, &journal)?;
                    distinct(&name, i, j)?;
                    let geometry =
                        RevoluteClearance::new(spec.bearing_radius, spec.journal_radius, si, sj)
                            .map_err(|source| MbdError::Contact {
                                item: name.clone(),
                                source,
                            })?;
                    clearances.push(Clearance {
                        name,
                        i,
                        j,
                        kind: ClearanceKind::Revolute(
                            geometry,
                            self.force_application
                                .unwrap_or(ForceApplication::CommonPoint),
                        ),
                        normal: spec.normal,
                        friction: spec.friction,
                        mem: 0,
                    });
                }
                Item::TransClearance {
                    guide,
                    slider,
                    spec,
                    ..
                } => {
                    let (i, gi) = anchor(&name, &guide)?;
                    let (j, sj) = anchor(&name, &slider)?;
                    distinct(&name, i, j)?;
                    let contact = |source| MbdError::Contact {
                        item: name.clone(),
                        source,
                    };
                    let shape = slider_shape(
                        &name,
                        [spec.slider_length, spec.slider_height],
                        sj,
                        spec.slider_angle,
                    )?;
                    let geometry =
                        TranslationalClearance::new(shape, spec.guide_width, gi, spec.guide_angle)
                            .map_err(contact)?;
                    clearances.push(Clearance {
                        name,
                        i,
                        j,
                        kind: ClearanceKind::Translational {
                            geometry,
                            origin: gi,
                            angle: spec.guide_angle,
                            width: spec.guide_width,
                        },
                        normal: spec.normal,
                        friction: spec.friction,
                        mem: 0,
                    });
                }
            }
        }
        if !(self.gravity[0].is_finite() && self.gravity[1].is_finite()) {
            return Err(MbdError::InvalidParameter {
                item: "gravity".into(),
                what: "gravitational acceleration (m/s²)",
                value: f64::NAN,
                requirement: "both components must be finite",
            });
        }
        for (f, node, col) in ties {
            floating[f].ties.push((node, col));
        }
        Model::assemble(
            self.bodies,
            beams,
            floating,
            frames,
            point_list,
            cons,
            motions,
            forces,
            clearances,
            Vector2::new(self.gravity[0], self.gravity[1]),
        )
    }
}

/// The anchors an item refers to.
fn item_anchors(item: &Item) -> Vec<&Anchor> {
    match item {
        Item::Revolute { a, b, .. }
        | Item::Fixed { a, b, .. }
        | Item::Translational { a, b, .. }
        | Item::DriveDisplacement { a, b, .. }
        | Item::Spring { a, b, .. } => vec![a, b],
        Item::Force { at, .. } => vec![at],
        Item::RevClearance {
            bearing, journal, ..
        } => vec![bearing, journal],
        Item::TransClearance { guide, slider, .. } => vec![guide, slider],
        Item::SliderOnBeam { slider, .. } => vec![slider],
        _ => Vec::new(),
    }
}

/// A clr-contact slider rectangle (length, height in m) centred at `centre` on its body.
fn slider_shape(
    item: &str,
    size: [f64; 2],
    centre: Vector2<f64>,
    angle: f64,
) -> Result<SliderShape, MbdError> {
    SliderShape::new(size[0], size[1], centre, angle).map_err(|source| MbdError::Contact {
        item: item.to_string(),
        source,
    })
}

fn ground_load(item: String) -> MbdError {
    MbdError::InvalidParameter {
        item,
        what: "body index",
        value: f64::NAN,
        requirement: "a load on the ground does nothing; attach it to a moving body",
    }
}

fn check_finite_vec(item: &str, what: &'static str, v: [f64; 2]) -> Result<(), MbdError> {
    if v[0].is_finite() && v[1].is_finite() {
        Ok(())
    } else {
        Err(MbdError::InvalidParameter {
            item: item.to_string(),
            what,
            value: if v[0].is_finite() { v[1] } else { v[0] },
            requirement: "must be finite",
        })
    }
}

fn non_negative(item: &str, what: &'static str, v: f64) -> Result<(), MbdError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(MbdError::InvalidParameter {
            item: item.to_string(),
            what,
            value: v,
            requirement: "must be finite and not negative",
        })
    }
}

fn unit_axis(item: &str, axis: [f64; 2]) -> Result<Vector2<f64>, MbdError> {
    let v = Vector2::new(axis[0], axis[1]);
    let n = v.norm();
    if n.is_finite() && n > 0.0 {
        Ok(v / n)
    } else {
        Err(MbdError::InvalidParameter {
            item: item.to_string(),
            what: "axis length (local coordinates)",
            value: n,
            requirement: "the axis must be a finite non-zero vector",
        })
    }
}
