//! The model builder: a convenient way to write a [`ModelDesc`] in Rust. Items refer to each
//! other by name; [`ModelBuilder::build`] compiles the description (validating every reference)
//! and returns a [`Model`] or a typed [`MbdError`] naming the offending item;
//! [`ModelBuilder::into_desc`] returns the description itself (plain data, writable to a file
//! when it holds no closure).

use std::sync::Arc;

use clr_contact::{BodyState, ForceApplication};
use nalgebra::Vector2;

use crate::desc::laws::{FrictionSpec, NormalSpec};
use crate::desc::{BeamMesh, Body, ForceApplicationDesc, ModelDesc, Point, Reduction};
use crate::element::custom::{CustomForce, CustomLoad};
use crate::element::floating_body::FlexibleBody;
use crate::element::ground_beam::GroundBeam;
use crate::element::{self as el, Anchor};
use crate::error::MbdError;
pub use crate::runtime::{RigidBody, GROUND};
use crate::system::Model;
use crate::timefn::TimeFn;

/// A revolute clearance joint: bearing (hole) on one body, journal (pin) on another.
#[derive(Debug, Clone, PartialEq)]
pub struct RevoluteClearanceSpec {
    /// Bearing radius R_i, m.
    pub bearing_radius: f64,
    /// Journal radius R_j, m (< R_i).
    pub journal_radius: f64,
    /// Normal-force law: by name ([`NormalLawDesc`], which takes the radii from here) or a
    /// prebuilt clr-contact law (its geometry is then not checked against these radii).
    pub normal: NormalSpec,
    /// Friction law (`FrictionSpec::default()` for none).
    pub friction: FrictionSpec,
}

/// A translational clearance joint: a rectangular slider (length L, height h) inside a straight
/// guide of inner width W > h (Flores, Ambrósio, Claro & Lankarani, J. Comput. Nonlinear Dyn. 3
/// (2008) 011007; corners as point contacts, clr-contact `TranslationalClearance`).
#[derive(Debug, Clone, PartialEq)]
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
    pub normal: NormalSpec,
    /// Friction law of each corner contact.
    pub friction: FrictionSpec,
}

/// A rigid rectangular slider on a face of a flexible beam, ground-fixed
/// ([`ModelBuilder::flexible_beam`]) or moving ([`ModelBuilder::floating_beam`]): clr-contact's
/// multipoint detection (corners, face points, optional reverse check with guide samples)
/// against the deformed beam surface from clr-beam; the guide reactions become work-equivalent
/// nodal loads of the beam (and, on a floating beam, forces on its frame).
#[derive(Debug, Clone, PartialEq)]
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
    pub normal: NormalSpec,
    /// Optional area law (e.g. [`NormalLaw::area`], a line term plus a term growing with the
    /// contact length) used instead of `normal` at every contact point, with the contact length
    /// set to the point's wetted length (`clr_contact::ContactPoint::tributary_length`, continuous
    /// in the configuration): an isolated edge (length → 0) gets the line law, a face lying on
    /// the guide the area law integrated over the face, with no force jump at the line → area
    /// class change. `None` keeps `normal` for every contact.
    pub area_normal: Option<NormalSpec>,
    /// Friction law of each contact point.
    pub friction: FrictionSpec,
}

/// Builds a [`Model`] by recording a [`ModelDesc`]. Methods record items and never fail;
/// [`ModelBuilder::build`] validates.
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
#[derive(Debug, Clone, Default)]
pub struct ModelBuilder {
    desc: ModelDesc,
}

impl ModelBuilder {
    /// An empty model (only the ground), no gravity.
    pub fn new() -> Self {
        Self::default()
    }

    /// Continue from a description.
    pub fn from_desc(desc: ModelDesc) -> Self {
        Self { desc }
    }

    /// The description recorded so far.
    pub fn desc(&self) -> &ModelDesc {
        &self.desc
    }

    /// The description recorded so far, mutable (e.g. to set solver or output settings).
    pub fn desc_mut(&mut self) -> &mut ModelDesc {
        &mut self.desc
    }

    /// The recorded description.
    pub fn into_desc(self) -> ModelDesc {
        self.desc
    }

    /// Gravitational acceleration (g_x, g_y) in m/s², e.g. (0, −9.81).
    pub fn gravity(&mut self, gx: f64, gy: f64) -> &mut Self {
        self.desc.model.gravity = [gx, gy];
        self
    }

    /// Where the force pair of every revolute clearance joint acts (default
    /// [`ForceApplication::CommonPoint`]: collinear action and reaction, so the joints conserve
    /// the system's angular momentum; [`ForceApplication::ContactPoints`] is the published Flores
    /// et al. (2004) form, whose friction pair adds a moment δ·F_T — see clr-contact's `revolute`).
    pub fn clearance_force_application(&mut self, application: ForceApplication) -> &mut Self {
        self.desc.model.clearance_force_application = Some(match application {
            ForceApplication::CommonPoint => ForceApplicationDesc::CommonPoint,
            ForceApplication::ContactPoints => ForceApplicationDesc::ContactPoints,
        });
        self
    }

    /// A rigid body named `name` (frame at its centre of mass).
    pub fn body(&mut self, name: &str, body: RigidBody) -> &mut Self {
        self.desc.bodies.push(Body {
            position: Some(body.position),
            angle: Some(body.angle),
            velocity: Some(body.velocity),
            angular_velocity: Some(body.angular_velocity),
            ..Body::new(name, body.mass, body.inertia)
        });
        self
    }

    /// A rigid body as data (with a `centre_of_mass` offset from its frame).
    pub fn body_desc(&mut self, body: Body) -> &mut Self {
        self.desc.bodies.push(body);
        self
    }

    /// A named point fixed on `body` at local coordinates `local` (m).
    pub fn point(&mut self, name: &str, body: &str, local: [f64; 2]) -> &mut Self {
        self.desc.points.push(Point {
            name: name.into(),
            body: Some(body.into()),
            at: Some(local),
            beam: None,
            node: None,
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
        self.desc.joints.push(
            el::revolute::Revolute {
                name: name.into(),
                a: a.into(),
                b: b.into(),
            }
            .into(),
        );
        self
    }

    /// A fixed joint: the anchors coincide and the relative angle keeps its initial value
    /// (3 equations).
    pub fn fixed(&mut self, name: &str, a: impl Into<Anchor>, b: impl Into<Anchor>) -> &mut Self {
        self.desc.joints.push(
            el::fixed::Fixed {
                name: name.into(),
                a: a.into(),
                b: b.into(),
            }
            .into(),
        );
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
        self.desc.joints.push(
            el::translational::Translational {
                name: name.into(),
                a: a.into(),
                b: b.into(),
                axis,
            }
            .into(),
        );
        self
    }

    /// Driver of the absolute angle of `body`: θ = f(t) (rad).
    pub fn drive_angle(&mut self, name: &str, body: &str, motion: TimeFn) -> &mut Self {
        self.desc.drivers.push(
            el::drive_angle::DriveAngle {
                name: name.into(),
                body: body.into(),
                motion,
            }
            .into(),
        );
        self
    }

    /// Driver of the relative angle θ_j − θ_i = f(t) (rad).
    pub fn drive_relative_angle(
        &mut self,
        name: &str,
        body_i: &str,
        body_j: &str,
        motion: TimeFn,
    ) -> &mut Self {
        self.desc.drivers.push(
            el::drive_angle::DriveRelativeAngle {
                name: name.into(),
                body_i: body_i.into(),
                body_j: body_j.into(),
                motion,
            }
            .into(),
        );
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
        motion: TimeFn,
    ) -> &mut Self {
        self.desc.drivers.push(
            el::drive_displacement::DriveDisplacement {
                name: name.into(),
                a: a.into(),
                b: b.into(),
                axis,
                motion,
            }
            .into(),
        );
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
        self.desc.forces.push(
            el::spring_damper::SpringDamper {
                name: name.into(),
                a: a.into(),
                b: b.into(),
                stiffness: k,
                damping: c,
                free_length: l0,
            }
            .into(),
        );
        self
    }

    /// A linear bushing from the ground point `a` to the body point `b`: F = −K(r_b − r_a) − C ṙ_b
    /// with K = diag(k_x, k_y) in N/m and C = diag(c_x, c_y) in N·s/m along the world axes.
    pub fn bushing(
        &mut self,
        name: &str,
        a: impl Into<Anchor>,
        b: impl Into<Anchor>,
        stiffness: [f64; 2],
        damping: [f64; 2],
    ) -> &mut Self {
        self.desc.forces.push(
            el::bushing::Bushing {
                name: name.into(),
                a: a.into(),
                b: b.into(),
                stiffness,
                damping,
            }
            .into(),
        );
        self
    }

    /// A point-to-point actuator between anchors `a` and `b`: axial force F(t) in N along the
    /// line between them (positive pushes them apart, extending the actuator) and viscous
    /// damping c·l̇ in N·s/m of the extension rate.
    pub fn actuator(
        &mut self,
        name: &str,
        a: impl Into<Anchor>,
        b: impl Into<Anchor>,
        force: TimeFn,
        damping: f64,
    ) -> &mut Self {
        self.desc.forces.push(
            el::actuator::Actuator {
                name: name.into(),
                a: a.into(),
                b: b.into(),
                force,
                damping,
            }
            .into(),
        );
        self
    }

    /// A rotational spring–damper: torque on body j τ = −k(θ_j − θ_i − θ0) − c(ω_j − ω_i), −τ on
    /// body i (k in N·m/rad, c in N·m·s/rad, θ0 in rad); body i may be the ground.
    pub fn rotational_spring_damper(
        &mut self,
        name: &str,
        body_i: &str,
        body_j: &str,
        k: f64,
        c: f64,
        angle0: f64,
    ) -> &mut Self {
        self.desc.forces.push(
            el::rotational_spring_damper::RotationalSpringDamper {
                name: name.into(),
                body_i: body_i.into(),
                body_j: body_j.into(),
                stiffness: k,
                damping: c,
                free_angle: angle0,
            }
            .into(),
        );
        self
    }

    /// An applied force (N, world frame) at an anchor with components as functions of time.
    pub fn force(
        &mut self,
        name: &str,
        at: impl Into<Anchor>,
        fx: TimeFn,
        fy: TimeFn,
    ) -> &mut Self {
        self.desc.forces.push(
            el::applied_force::AppliedForce {
                name: name.into(),
                at: at.into(),
                fx,
                fy,
            }
            .into(),
        );
        self
    }

    /// An applied torque τ(t) (N·m) on a body.
    pub fn torque(&mut self, name: &str, body: &str, torque: TimeFn) -> &mut Self {
        self.desc.forces.push(
            el::applied_torque::AppliedTorque {
                name: name.into(),
                body: body.into(),
                torque,
            }
            .into(),
        );
        self
    }

    /// A torque τ(t) between two bodies (a joint motor): +τ on body j, −τ on body i.
    pub fn motor_torque(
        &mut self,
        name: &str,
        body_i: &str,
        body_j: &str,
        torque: TimeFn,
    ) -> &mut Self {
        self.desc.forces.push(
            el::torque_between::TorqueBetween {
                name: name.into(),
                body_i: body_i.into(),
                body_j: body_j.into(),
                torque,
            }
            .into(),
        );
        self
    }

    fn custom(&mut self, name: &str, load: CustomLoad) -> &mut Self {
        self.desc.forces.push(el::Force::Custom(CustomForce {
            name: name.into(),
            load,
        }));
        self
    }

    /// An applied force (N, world frame) at an anchor, a Rust closure of time and the body state
    /// (opt-in: the model can no longer be written to a file; see [`ModelBuilder::force`]).
    pub fn applied_force(
        &mut self,
        name: &str,
        at: impl Into<Anchor>,
        f: impl Fn(f64, &BodyState) -> Vector2<f64> + Send + Sync + 'static,
    ) -> &mut Self {
        self.custom(name, CustomLoad::Force(at.into(), Arc::new(f)))
    }

    /// An applied torque (N·m) on a body, a Rust closure of time and the body state (opt-in).
    pub fn applied_torque(
        &mut self,
        name: &str,
        body: &str,
        f: impl Fn(f64, &BodyState) -> f64 + Send + Sync + 'static,
    ) -> &mut Self {
        self.custom(name, CustomLoad::Torque(body.into(), Arc::new(f)))
    }

    /// A torque between two bodies, a Rust closure (opt-in): +τ on body j, −τ on body i.
    pub fn torque_between(
        &mut self,
        name: &str,
        body_i: &str,
        body_j: &str,
        f: impl Fn(f64, &BodyState, &BodyState) -> f64 + Send + Sync + 'static,
    ) -> &mut Self {
        self.custom(
            name,
            CustomLoad::PairTorque(body_i.into(), body_j.into(), Arc::new(f)),
        )
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
        self.desc.clearances.push(
            el::revolute_clearance::RevoluteClearance {
                name: name.into(),
                bearing: bearing.into(),
                journal: journal.into(),
                bearing_radius: spec.bearing_radius,
                journal_radius: spec.journal_radius,
                normal: spec.normal,
                friction: spec.friction,
                // the model-wide setting ([`ModelBuilder::clearance_force_application`])
                force_application: None,
                bearing_wear: None,
                lubrication: None,
                initial_eccentricity: None,
            }
            .into(),
        );
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
        self.desc.clearances.push(
            el::translational_clearance::TranslationalClearance {
                name: name.into(),
                guide: guide.into(),
                slider: slider.into(),
                guide_width: spec.guide_width,
                guide_angle: spec.guide_angle,
                slider_length: spec.slider_length,
                slider_height: spec.slider_height,
                slider_angle: spec.slider_angle,
                normal: spec.normal,
                friction: spec.friction,
                initial_offset: None,
            }
            .into(),
        );
        self
    }

    /// A ground-fixed flexible beam: a straight clr-beam mesh (supports, Rayleigh damping, mass
    /// kind) whose free nodal DOF become coordinates of the model (see the `flexible` module
    /// docs). Attach with `(name, node)` anchors or [`ModelBuilder::beam_node_point`].
    pub fn flexible_beam(&mut self, name: &str, mesh: BeamMesh) -> &mut Self {
        self.desc.beams.push(GroundBeam::new(name, mesh));
        self
    }

    /// A moving flexible body in a floating frame of reference (Shabana 2020 ch. 5; formulation
    /// and reference conditions in [`crate::floating`]): the beam `mesh` (coordinates in the
    /// body frame, m; its supports are the reference conditions, e.g. a clamp at node 0), its
    /// `reduction` (modal or Craig–Bampton), the initial frame pose `pose` = (R_x m, R_y m,
    /// θ rad) and velocity (Ṙ_x, Ṙ_y m/s, θ̇ rad/s); elastic coordinates start at rest and
    /// undeformed. Attach joints with `(name, node)` anchors (a deforming node gets a node-frame
    /// tie, see [`crate::floating`]) or body-local `(name, [x, y])` anchors (rigid with the
    /// frame). Its coordinates `name.x`, `name.y`, `name.theta`, `name.q<k>` come after the
    /// rigid bodies' in q.
    pub fn floating_beam(
        &mut self,
        name: &str,
        mesh: BeamMesh,
        reduction: Reduction,
        pose: [f64; 3],
        velocity: [f64; 3],
    ) -> &mut Self {
        self.desc.flexible_bodies.push(FlexibleBody {
            name: name.into(),
            beam: mesh,
            reduction,
            pose: Some(pose),
            velocity: Some(velocity),
        });
        self
    }

    /// A named point at node `node` of flexible beam `beam`: joints, springs, forces and contact
    /// elements anchored at it (`Anchor::Point(name)`, or just `"name"`) move with the node's
    /// displacement and rotation (small-rotation node frame).
    pub fn beam_node_point(&mut self, name: &str, beam: &str, node: usize) -> &mut Self {
        self.desc.points.push(Point {
            name: name.into(),
            body: None,
            at: None,
            beam: Some(beam.into()),
            node: Some(node),
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
        self.desc.clearances.push(
            el::slider_on_beam::SliderOnBeam {
                name: name.into(),
                beam: beam.into(),
                slider: slider.into(),
                face: spec.face.into(),
                slider_length: spec.slider_length,
                slider_height: spec.slider_height,
                slider_angle: spec.slider_angle,
                face_points: spec.face_points,
                guide_samples: spec.guide_samples,
                normal: spec.normal,
                area_normal: spec.area_normal,
                friction: spec.friction,
            }
            .into(),
        );
        self
    }

    /// A nodal load on beam `beam` at node `node` with components F_x(t), F_y(t) (N) and M(t)
    /// (N·m), global axes; components on constrained DOF are taken by the supports.
    pub fn nodal_load(
        &mut self,
        name: &str,
        beam: &str,
        node: usize,
        [fx, fy, moment]: [TimeFn; 3],
    ) -> &mut Self {
        self.desc.forces.push(
            el::nodal_load::NodalLoad {
                name: name.into(),
                beam: beam.into(),
                node,
                fx,
                fy,
                moment,
            }
            .into(),
        );
        self
    }

    /// A nodal load on beam `beam` at node `node` as a Rust closure `f(t) -> [F_x, F_y, M]`
    /// (opt-in; see [`ModelBuilder::nodal_load`]).
    pub fn beam_nodal_load(
        &mut self,
        name: &str,
        beam: &str,
        node: usize,
        f: impl Fn(f64) -> [f64; 3] + Send + Sync + 'static,
    ) -> &mut Self {
        self.custom(name, CustomLoad::Nodal(beam.into(), node, Arc::new(f)))
    }

    /// Validate every item and build the model.
    ///
    /// # Errors
    /// [`MbdError::DuplicateName`], [`MbdError::UnknownBody`], [`MbdError::UnknownPoint`],
    /// [`MbdError::InvalidInertia`], [`MbdError::SameBody`], [`MbdError::InvalidParameter`],
    /// [`MbdError::Contact`], [`MbdError::Invalid`].
    pub fn build(&self) -> Result<Model, MbdError> {
        self.desc.compile()
    }
}
