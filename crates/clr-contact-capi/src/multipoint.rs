//! Multipoint clearance contact of a rigid rectangular slider in a guide, at the C boundary.
//!
//! The slider (length L, height h) sits on body j; the guide surface, a straight segment or a
//! bent half sine, sits on body i. Every slider candidate (the 4 corners and N points on each
//! face) that penetrates the guide is a point contact, and M guide samples find penetrations
//! between the candidates when the guide bends (clr-contact `multipoint`, `contact-laws.md` §3.2,
//! a generalization of the corner contacts of P. Flores, J. Ambrósio, J.C.P. Claro, H.M.
//! Lankarani, J. Comput. Nonlinear Dyn. 3 (2008) 011007). This is the sliding guide of a
//! telescopic mechanism: line contact at an edge, area contact when a face lies on the guide.
//!
//! [`MultipointJoint`] is the safe layer (shared with the Python package); the `clr_multipoint_*`
//! functions wrap it. Unlike the other handles, a multipoint joint is **mutable**: it keeps the
//! warm starts of the closest-point projections and the points of the last evaluation, so
//! evaluate one handle from one thread at a time (one handle per thread otherwise).

use clr_contact::body::{rotate, BodyState, Vector2};
use clr_contact::multipoint::{PointSource, SineGuide, StraightGuide};
use clr_contact::{
    ContactClass, FrictionLaw, GeneralizedForce, GuideSurface, MultipointDetector, NormalLaw,
    SliderShape,
};

use crate::error::{finite, guard, CapiError, ClrStatus};
use crate::ffi::{
    borrow, borrow_mut, free_handle, generalized, new_handle, non_null, out_ptr, write_out,
    ClrBodyState, ClrFrictionLaw, ClrGeneralizedForce, ClrNormalLaw, JointInputs, GUIDE_SLIDER,
    IMPACT_VELOCITIES,
};

/// Kind of contact found by `clr_multipoint_joint_forces`, one of the `CLR_CONTACT_CLASS_*`
/// constants (clr-contact `ContactClass`).
pub type ClrContactClass = u32;
/// No point of the slider penetrates the guide.
pub const CLR_CONTACT_CLASS_SEPARATED: ClrContactClass = 0;
/// Line contact: a corner, an edge region or a patch shorter than a slider face.
pub const CLR_CONTACT_CLASS_LINE: ClrContactClass = 1;
/// Area contact: every candidate of one slider face (both corners and its N face points)
/// penetrates, the face lies on the guide.
pub const CLR_CONTACT_CLASS_AREA: ClrContactClass = 2;

/// Where a multipoint contact point comes from, one of the `CLR_POINT_SOURCE_*` constants
/// (clr-contact `PointSource`).
pub type ClrPointSource = u32;
/// A slider corner; `index` is the corner 0..3, counter-clockwise from (−L/2, −h/2) of the slider
/// frame.
pub const CLR_POINT_SOURCE_CORNER: ClrPointSource = 0;
/// A point on a slider face; `face` is the face 0..3 (0 bottom, 1 right, 2 top, 3 left in the
/// slider frame, face f running from corner f to corner f + 1) and `index` its position 0..N−1
/// along the face, at the fraction (index + 1)/(N + 1) of the face.
pub const CLR_POINT_SOURCE_FACE: ClrPointSource = 1;
/// A guide sample of the reverse check; `index` is the sample 0..M−1. Guide samples move with the
/// slider, so the impact velocity kept for their id is only approximate.
pub const CLR_POINT_SOURCE_GUIDE_SAMPLE: ClrPointSource = 2;

/// Result of `clr_multipoint_joint_forces`. SI units, world frame.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClrMultipointForces {
    /// Kind of contact (`CLR_CONTACT_CLASS_*`).
    pub contact_class: ClrContactClass,
    /// The slider face lying on the guide (0 bottom, 1 right, 2 top, 3 left) for
    /// `CLR_CONTACT_CLASS_AREA`, −1 otherwise.
    pub area_face: i32,
    /// Arc extent of the active points along the guide, m (0 when separated or for a single
    /// point).
    pub contact_length: f64,
    /// Number of active contact points (read them with `clr_multipoint_joint_points`), –.
    pub active_points: usize,
    /// Generalized force on the guide body (i) about its reference point.
    pub guide: ClrGeneralizedForce,
    /// Generalized force on the slider body (j) about its reference point.
    pub slider: ClrGeneralizedForce,
}

/// One active contact point of the last `clr_multipoint_joint_forces`. SI units, world frame.
///
/// Conventions (contact-laws.md §3.1–3.2): the normal n is the direction in which the slider
/// penetrates the guide (minus the guide's outward normal), t = k × n, v_N = (v_slider −
/// v_guide)·n = δ̇ (> 0 approaching), v_T = (v_slider − v_guide)·t; the force on the slider is
/// −F_N n + F_T t at `slider_x`, `slider_y`, the opposite acts on the guide at `guide_x`,
/// `guide_y`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClrMultipointContact {
    /// Stable id of the point, 0..point_count−1 (corners 0..3, face points 4..4+4N−1, guide
    /// samples after): the index of its entry in the `impact_velocities` array.
    pub id: usize,
    /// Origin of the point (`CLR_POINT_SOURCE_*`).
    pub source: ClrPointSource,
    /// Slider face 0..3 of a `CLR_POINT_SOURCE_FACE` point, −1 for the other sources.
    pub face: i32,
    /// Corner 0..3, position 0..N−1 along the face, or guide sample 0..M−1 (see `source`).
    pub index: usize,
    /// Arc coordinate s of the contact on the guide, m (for the straight guide the distance from
    /// its origin; for the sine guide the x coordinate in the guide frame).
    pub arc: f64,
    /// Penetration δ > 0, m.
    pub penetration: f64,
    /// Unit normal n (direction of penetration of the slider), x component.
    pub normal_x: f64,
    /// Unit normal n, y component.
    pub normal_y: f64,
    /// Contact point on the slider, x, m.
    pub slider_x: f64,
    /// Contact point on the slider, y, m.
    pub slider_y: f64,
    /// Contact point r(s) on the guide surface, x, m.
    pub guide_x: f64,
    /// Contact point r(s) on the guide surface, y, m.
    pub guide_y: f64,
    /// Relative normal velocity v_N = δ̇, m/s (> 0 approaching).
    pub normal_velocity: f64,
    /// Relative tangential velocity v_T along t = k × n, m/s.
    pub tangential_velocity: f64,
    /// Tributary (wetted) length of the point along the guide, m: its share of the penetration
    /// profile interpolated linearly between neighbouring candidates (0 when it only just
    /// touches; contact-laws.md §3.2). The length a per-unit-length law multiplies.
    pub tributary_length: f64,
    /// Normal force F_N ≥ 0 at this point, N.
    pub normal_force: f64,
    /// Friction force F_T on the slider along t at this point, N.
    pub tangential_force: f64,
}

/// Opaque handle of a multipoint clearance joint: a rectangular slider on body j in a straight or
/// sine guide on body i, with its detector buffers and the points of the last evaluation.
pub struct ClrMultipointJoint(pub(crate) MultipointJoint);

/// The guide surface as the constructors give it, before it is checked and placed on body i.
#[derive(Debug, Clone, Copy, PartialEq)]
enum GuideShape {
    /// Straight segment of `length` (m) with the gap on its left when `gap_on_left`.
    Straight { length: f64, gap_on_left: bool },
    /// clr-contact's half sine of `amplitude` (m) over `span` (m).
    Sine { amplitude: f64, span: f64 },
}

/// Guide surface geometry in the frame of the guide body.
#[derive(Debug, Clone, Copy, PartialEq)]
enum GuideGeometry {
    /// Straight segment from the local `origin` along the local direction `angle`.
    Straight {
        origin: Vector2<f64>,
        angle: f64,
        length: f64,
        gap_on_left: bool,
    },
    /// clr-contact's half sine r(s) = (s, A sin(πs/ℓ)) placed in the guide body frame at `origin`
    /// rotated by `angle`.
    Sine {
        sine: SineGuide,
        origin: Vector2<f64>,
        angle: f64,
    },
}

impl GuideGeometry {
    /// Check `shape` and place it on the guide body at the local point `origin` (m), rotated by
    /// `angle` (rad).
    fn new(shape: GuideShape, origin: Vector2<f64>, angle: f64) -> Result<Self, CapiError> {
        match shape {
            GuideShape::Straight {
                length,
                gap_on_left,
            } => {
                // validate once here; evaluations rebuild the guide on the current body state
                StraightGuide::new(BodyState::default(), origin, angle, length, gap_on_left)?;
                Ok(Self::Straight {
                    origin,
                    angle,
                    length,
                    gap_on_left,
                })
            }
            GuideShape::Sine { amplitude, span } => {
                let sine = SineGuide::new(amplitude, span)?;
                for (name, v) in [
                    ("sine guide origin, local x (m)", origin.x),
                    ("sine guide origin, local y (m)", origin.y),
                    ("sine guide angle (rad)", angle),
                ] {
                    if !v.is_finite() {
                        return Err(clr_contact::ContactError::invalid(
                            "sine guide",
                            name,
                            v,
                            "must be finite",
                        )
                        .into());
                    }
                }
                Ok(Self::Sine {
                    sine,
                    origin,
                    angle,
                })
            }
        }
    }
}

/// A guide surface given in a frame (at `origin`, rotated by `angle`) of a moving rigid body:
/// r(s) = R + A(θ)(o + A(α) r̄(s)), t = A(θ)A(α) t̄, n = A(θ)A(α) n̄, ṙ(s) = Ṙ + ω k × (r − R) +
/// A(θ)A(α) v̄(s) (Nikravesh 1988, ch. 4; the mounting of clr-contact's `StraightGuide`), |dr/ds|
/// unchanged by the rotation.
struct MountedGuide<'a, G> {
    local: &'a G,
    body: BodyState,
    origin: Vector2<f64>,
    angle: f64,
}

impl<G: GuideSurface> MountedGuide<'_, G> {
    fn to_world(&self, v: Vector2<f64>) -> Vector2<f64> {
        self.body.rotate(rotate(self.angle, v))
    }
}

impl<G: GuideSurface> GuideSurface for MountedGuide<'_, G> {
    fn arc_range(&self) -> (f64, f64) {
        self.local.arc_range()
    }
    fn point(&self, s: f64) -> Vector2<f64> {
        self.body
            .point(self.origin + rotate(self.angle, self.local.point(s)))
    }
    fn tangent(&self, s: f64) -> Vector2<f64> {
        self.to_world(self.local.tangent(s))
    }
    fn normal(&self, s: f64) -> Vector2<f64> {
        self.to_world(self.local.normal(s))
    }
    fn velocity(&self, s: f64) -> Vector2<f64> {
        self.body.point_velocity(self.point(s)) + self.to_world(self.local.velocity(s))
    }
    fn speed(&self, s: f64) -> f64 {
        self.local.speed(s)
    }
}

/// A multipoint clearance joint: the geometry, clr-contact's [`MultipointDetector`] and the
/// forces of the last evaluation. The safe layer under the `clr_multipoint_joint_*` functions.
#[derive(Debug, Clone)]
pub struct MultipointJoint {
    guide: GuideGeometry,
    detector: MultipointDetector,
    /// (F_N, F_T) in N of every active point of the last evaluation, in the order of
    /// `detector.points()`; capacity `point_count`, so evaluations do not allocate.
    forces: Vec<(f64, f64)>,
}

impl MultipointJoint {
    /// A slider `slider` on body j with `face_points` (N) candidates per face and
    /// `guide_samples` (M) reverse-check samples, in the straight guide of positive length
    /// `length` (m) on body i that starts at the local point `origin` (m) and runs along the
    /// local direction `angle` (rad), with the gap (where the slider is) on the left of the
    /// direction of increasing arc coordinate when `gap_on_left`, on the right otherwise.
    ///
    /// # Errors
    /// [`CapiError::Contact`] with the invalid parameter (non-positive length, non-finite data,
    /// N or M above 100 000).
    pub fn straight(
        length: f64,
        gap_on_left: bool,
        origin: Vector2<f64>,
        angle: f64,
        slider: SliderShape,
        face_points: usize,
        guide_samples: usize,
    ) -> Result<Self, CapiError> {
        let shape = GuideShape::Straight {
            length,
            gap_on_left,
        };
        let guide = GuideGeometry::new(shape, origin, angle)?;
        Self::new(guide, slider, face_points, guide_samples)
    }

    /// A slider `slider` on body j (N, M as for [`straight`](Self::straight)) on clr-contact's
    /// half-sine guide r̄(s) = (s, A sin(πs/ℓ)), s ∈ [0, ℓ], gap on the side of +y (amplitude A in
    /// m, any sign, A > 0 hogs towards the slider; span ℓ in m, > 0; the hogging guide of
    /// contact-laws.md §7.8), placed on body i with its frame at the local point `origin` (m)
    /// rotated by `angle` (rad). The sine is static in that frame: the guide moves with body i.
    ///
    /// # Errors
    /// [`CapiError::Contact`] with the invalid parameter (non-positive span, non-finite data,
    /// N or M above 100 000).
    pub fn sine(
        amplitude: f64,
        span: f64,
        origin: Vector2<f64>,
        angle: f64,
        slider: SliderShape,
        face_points: usize,
        guide_samples: usize,
    ) -> Result<Self, CapiError> {
        let shape = GuideShape::Sine { amplitude, span };
        let guide = GuideGeometry::new(shape, origin, angle)?;
        Self::new(guide, slider, face_points, guide_samples)
    }

    /// The construction shared by [`straight`](Self::straight), [`sine`](Self::sine) and the
    /// `clr_multipoint_joint_new_*` functions, once the `guide` is checked ([`GuideGeometry::new`]):
    /// the detector of `slider` with N = `face_points`, M = `guide_samples`, and its buffers.
    fn new(
        guide: GuideGeometry,
        slider: SliderShape,
        face_points: usize,
        guide_samples: usize,
    ) -> Result<Self, CapiError> {
        let detector = MultipointDetector::new(slider, face_points, guide_samples)?;
        let forces = Vec::with_capacity(detector.point_count());
        Ok(Self {
            guide,
            detector,
            forces,
        })
    }

    /// Number of point ids 4 + 4N + M (–): the length of the impact-velocity array and the
    /// largest possible number of active points.
    pub fn point_count(&self) -> usize {
        self.detector.point_count()
    }

    /// The clr-contact detector (its points are those of the last evaluation, also after
    /// [`reset`](Self::reset)).
    pub fn detector(&self) -> &MultipointDetector {
        &self.detector
    }

    /// Forget the warm starts of the projections and the points of the last evaluation (the next
    /// evaluation starts from a coarse scan of the guide, as the first one does).
    pub fn reset(&mut self) {
        self.detector.reset();
        // the detector keeps its last points; `points` pairs them with the (now empty) forces
        self.forces.clear();
    }

    /// Check the number of impact velocities against [`point_count`](Self::point_count).
    ///
    /// # Errors
    /// [`CapiError::ArrayLength`] when they differ.
    pub fn check_impact_count(&self, got: usize) -> Result<(), CapiError> {
        let expected = self.point_count();
        if got == expected {
            return Ok(());
        }
        Err(CapiError::ArrayLength {
            name: IMPACT_VELOCITIES,
            what: "one impact velocity (m/s) per point id, clr_multipoint_joint_point_count",
            expected,
            got,
        })
    }

    /// Evaluate the contact at the guide body state `guide` and slider body state `slider`:
    /// detect the active points (contact-laws.md §3.2), then at each point F_N from `normal` with
    /// δ̇ = v_N and δ̇⁻ = `impact_velocities[id]` (an area law gets the point's tributary length as
    /// its contact length, other laws ignore it) and F_T from `friction` (None: frictionless);
    /// −F_N n + F_T t on the slider at its contact point, the opposite on the guide at r(s), both
    /// reduced to the body's reference point. Allocates nothing.
    ///
    /// # Errors
    /// [`CapiError::ArrayLength`] unless `impact_velocities` has [`point_count`](Self::point_count)
    /// entries, [`CapiError::NonFinite`] for a non-finite entry; nothing changes on error.
    pub fn forces(
        &mut self,
        normal: &NormalLaw,
        friction: Option<&FrictionLaw>,
        guide: &BodyState,
        slider: &BodyState,
        impact_velocities: &[f64],
    ) -> Result<ClrMultipointForces, CapiError> {
        self.check_impact_count(impact_velocities.len())?;
        for &v in impact_velocities {
            finite("impact_velocities[k] (m/s)", v)?;
        }
        let class = match self.guide {
            GuideGeometry::Straight {
                origin,
                angle,
                length,
                gap_on_left,
            } => {
                let g = StraightGuide::new(*guide, origin, angle, length, gap_on_left)?;
                self.detector.detect(&g, slider)
            }
            GuideGeometry::Sine {
                ref sine,
                origin,
                angle,
            } => {
                let g = MountedGuide {
                    local: sine,
                    body: *guide,
                    origin,
                    angle,
                };
                self.detector.detect(&g, slider)
            }
        };
        let forces = &mut self.forces;
        forces.clear();
        let q_slider = self.detector.apply_forces(|p| {
            let c = &p.contact;
            let law = normal.with_contact_length(p.tributary_length);
            let f_n = law.force(c.penetration, c.normal_velocity, impact_velocities[p.id]);
            let f_t = friction.map_or(0.0, |f| f.force(c.tangential_velocity, f_n));
            forces.push((f_n, f_t));
            (f_n, f_t)
        });
        let mut q_guide = GeneralizedForce::zero();
        for load in self.detector.loads() {
            q_guide += GeneralizedForce::at(guide.position, load.point, load.force);
        }
        let (contact_class, area_face, contact_length) = match class {
            ContactClass::Separated => (CLR_CONTACT_CLASS_SEPARATED, -1, 0.0),
            ContactClass::Line { length } => (CLR_CONTACT_CLASS_LINE, -1, length),
            ContactClass::Area { face, length } => (CLR_CONTACT_CLASS_AREA, face as i32, length),
        };
        Ok(ClrMultipointForces {
            contact_class,
            area_face,
            contact_length,
            active_points: self.forces.len(),
            guide: generalized(q_guide),
            slider: generalized(q_slider),
        })
    }

    /// The active points of the last [`forces`](Self::forces), sorted by arc coordinate (none
    /// before the first evaluation or after [`reset`](Self::reset)).
    pub fn points(&self) -> impl ExactSizeIterator<Item = ClrMultipointContact> + '_ {
        self.detector
            .points()
            .iter()
            .zip(&self.forces)
            .map(|(p, &(f_n, f_t))| {
                let (source, face, index) = match p.source {
                    PointSource::Corner(k) => (CLR_POINT_SOURCE_CORNER, -1, k),
                    PointSource::Face { face, index } => {
                        (CLR_POINT_SOURCE_FACE, face as i32, index)
                    }
                    PointSource::GuideSample(k) => (CLR_POINT_SOURCE_GUIDE_SAMPLE, -1, k),
                };
                let c = &p.contact;
                ClrMultipointContact {
                    id: p.id,
                    source,
                    face,
                    index,
                    arc: p.arc,
                    penetration: c.penetration,
                    normal_x: c.normal.x,
                    normal_y: c.normal.y,
                    slider_x: c.slider_point.x,
                    slider_y: c.slider_point.y,
                    guide_x: c.guide_point.x,
                    guide_y: c.guide_point.y,
                    normal_velocity: c.normal_velocity,
                    tangential_velocity: c.tangential_velocity,
                    tributary_length: p.tributary_length,
                    normal_force: f_n,
                    tangential_force: f_t,
                }
            })
    }
}

/// Map a C 0/1 flag.
fn flag(name: &'static str, meaning: &'static str, value: i32) -> Result<bool, CapiError> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        v => Err(CapiError::Flag {
            name,
            meaning,
            value: v.into(),
        }),
    }
}

/// Create a multipoint clearance joint in a straight guide (clr-contact `StraightGuide`,
/// `MultipointDetector`; contact-laws.md §3.2, after the corner contacts of P. Flores, J.
/// Ambrósio, J.C.P. Claro, H.M. Lankarani, J. Comput. Nonlinear Dyn. 3 (2008) 011007): a
/// rectangular slider of length L and height h (m, > 0) on body j, centred at
/// (`slider_centre_x`, `slider_centre_y`) (m, local to body j) and rotated by `slider_angle`
/// (rad), against the guide surface of length `guide_length` (m, > 0) on body i that starts at
/// (`guide_origin_x`, `guide_origin_y`) (m, local to body i) and runs along the local direction
/// `guide_angle` (rad); the slider is on the left of that direction when `gap_on_left` = 1, on
/// the right when 0 (other values: `CLR_STATUS_INVALID_ARGUMENT`). Candidates are the 4 corners
/// and `face_points` (N) equally spaced points on each face; `guide_samples` (M) guide points
/// under the slider are checked against the rectangle (0 disables this reverse check, which only
/// matters for a bent guide). N, M ≤ 100 000. A guide with two faces (a channel) is two joints.
/// On success `*out` receives a new handle to free with `clr_multipoint_joint_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn clr_multipoint_joint_new_straight(
    guide_length: f64,
    gap_on_left: i32,
    slider_length: f64,
    slider_height: f64,
    guide_origin_x: f64,
    guide_origin_y: f64,
    guide_angle: f64,
    slider_centre_x: f64,
    slider_centre_y: f64,
    slider_angle: f64,
    face_points: usize,
    guide_samples: usize,
    out: *mut *mut ClrMultipointJoint,
) -> ClrStatus {
    let gap = flag(
        "gap_on_left",
        "1: slider on the left of the guide direction, 0: on the right",
        gap_on_left,
    );
    new_joint(
        out,
        gap.map(|gap_on_left| GuideShape::Straight {
            length: guide_length,
            gap_on_left,
        }),
        [guide_origin_x, guide_origin_y, guide_angle],
        [slider_length, slider_height],
        [slider_centre_x, slider_centre_y, slider_angle],
        [face_points, guide_samples],
    )
}

/// Create a multipoint clearance joint in a bent guide: clr-contact's `SineGuide`
/// r̄(s) = (s, A sin(πs/ℓ)), s ∈ [0, ℓ], the shape of a simply supported beam in its first mode
/// (the hogging guide of contact-laws.md §7.8), with the slider on its +y side; amplitude A =
/// `amplitude` (m, any sign: > 0 bulges towards the slider), span ℓ = `span` (m, > 0). The sine
/// is fixed in a frame of body i at (`guide_origin_x`, `guide_origin_y`) (m, local to body i)
/// rotated by `guide_angle` (rad): r(s) = R_i + A(θ_i)(o + A(α) r̄(s)), moving with body i
/// (a guide state at rest at the origin gives clr-contact's static `SineGuide`). Slider and
/// candidates as in `clr_multipoint_joint_new_straight`; use M > 0 guide samples so that
/// penetrations between the candidates are found. On success `*out` receives a new handle to
/// free with `clr_multipoint_joint_free`.
///
/// # Safety
/// `out` is NULL or writable.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn clr_multipoint_joint_new_sine(
    amplitude: f64,
    span: f64,
    slider_length: f64,
    slider_height: f64,
    guide_origin_x: f64,
    guide_origin_y: f64,
    guide_angle: f64,
    slider_centre_x: f64,
    slider_centre_y: f64,
    slider_angle: f64,
    face_points: usize,
    guide_samples: usize,
    out: *mut *mut ClrMultipointJoint,
) -> ClrStatus {
    new_joint(
        out,
        Ok(GuideShape::Sine { amplitude, span }),
        [guide_origin_x, guide_origin_y, guide_angle],
        [slider_length, slider_height],
        [slider_centre_x, slider_centre_y, slider_angle],
        [face_points, guide_samples],
    )
}

/// The one construction path of the `clr_multipoint_joint_new_*` functions: after `out`, the
/// guide `shape` (an error of its C arguments comes first), then the slider of `slider_size`
/// (L, h) placed on body j at `slider_frame` (centre x, y, angle), the guide placed on body i at
/// `guide_frame` (origin x, y, angle) and the detector with `counts` (N, M).
///
/// # Safety
/// `out` is NULL or writable.
unsafe fn new_joint(
    out: *mut *mut ClrMultipointJoint,
    shape: Result<GuideShape, CapiError>,
    guide_frame: [f64; 3],
    slider_size: [f64; 2],
    slider_frame: [f64; 3],
    counts: [usize; 2],
) -> ClrStatus {
    new_handle(out, || {
        let shape = shape?;
        let ([length, height], [centre_x, centre_y, angle]) = (slider_size, slider_frame);
        let slider = SliderShape::new(length, height, [centre_x, centre_y].into(), angle)?;
        let [origin_x, origin_y, angle] = guide_frame;
        let guide = GuideGeometry::new(shape, [origin_x, origin_y].into(), angle)?;
        let [n, m] = counts;
        Ok(ClrMultipointJoint(MultipointJoint::new(
            guide, slider, n, m,
        )?))
    })
}

/// Number of point ids of the joint, 4 + 4N + M (–): the length of the `impact_velocities` array
/// of `clr_multipoint_joint_forces` and the largest number of active points, so a points buffer
/// of this capacity is always large enough.
///
/// # Safety
/// `joint` is NULL or a live handle; `out` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_multipoint_joint_point_count(
    joint: *const ClrMultipointJoint,
    out: *mut usize,
) -> ClrStatus {
    write_out(out, || Ok(borrow("joint", joint)?.0.point_count()))
}

/// Evaluate the multipoint contact at the states of the guide body (i) and the slider body (j)
/// and write the result to `*out`. Detection (contact-laws.md §3.2): every candidate is projected
/// on the guide (Gauss–Newton, warm started from the previous evaluation of this handle); one
/// with penetration δ > 0 over the guide is an active point, and guide samples inside the slider
/// add points where the guide bulges between candidates. At each active point F_N comes from
/// `normal` with δ̇ = v_N and δ̇⁻ = `impact_velocities[id]` (m/s), F_T from `friction` (NULL:
/// frictionless); the force on the slider is −F_N n + F_T t at its contact point, the opposite
/// acts on the guide at r(s), reduced to each body's reference point (Flores et al. 2008). An
/// area-type normal law would get each point's tributary length as its contact length; the laws
/// of `clr_normal_law_new` are point laws and use none. `impact_velocities` holds
/// `n_impact_velocities` = `clr_multipoint_joint_point_count` doubles indexed by point id (the
/// caller keeps them per point: the point's v_N at its first evaluation with δ > 0, until it
/// separates; entries of inactive points are not used but must be finite). The points are then
/// read with `clr_multipoint_joint_points`. Zero forces when separated. Allocates nothing; the
/// handle is updated (warm starts, points), so do not evaluate it from two threads at once.
///
/// # Safety
/// `joint` is NULL or a live handle not used by another thread during the call; `normal` is NULL
/// or a live handle; `friction` is NULL or a live handle; `guide`, `slider` are NULL or point to
/// `ClrBodyState`; `impact_velocities` is NULL or points to `n_impact_velocities` doubles; `out`
/// is NULL or writable.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn clr_multipoint_joint_forces(
    joint: *mut ClrMultipointJoint,
    normal: *const ClrNormalLaw,
    friction: *const ClrFrictionLaw,
    guide: *const ClrBodyState,
    slider: *const ClrBodyState,
    impact_velocities: *const f64,
    n_impact_velocities: usize,
    out: *mut ClrMultipointForces,
) -> ClrStatus {
    write_out(out, || {
        let joint = &mut borrow_mut("joint", joint)?.0;
        let a = JointInputs::read(normal, friction, [guide, slider], GUIDE_SLIDER)?;
        let v0 = non_null(IMPACT_VELOCITIES, impact_velocities)?;
        // the length is checked before the slice is formed: a wrong count must not make a
        // slice over memory the caller did not give
        joint.check_impact_count(n_impact_velocities)?;
        let v0 = std::slice::from_raw_parts(v0, n_impact_velocities);
        joint.forces(a.normal, a.friction, &a.i, &a.j, v0)
    })
}

/// Copy the active points of the last `clr_multipoint_joint_forces` (sorted by arc coordinate)
/// into `points`, which has room for `capacity` entries, and write their number to `*count`.
/// When `capacity` is smaller than the number of points nothing is copied, `*count` receives the
/// number needed and the status is `CLR_STATUS_BUFFER_TOO_SMALL`; a capacity of
/// `clr_multipoint_joint_point_count` is always enough. `points` may be NULL when `capacity` is 0
/// (a query of the count). Before the first evaluation and after `clr_multipoint_joint_reset`
/// there are no points. Allocates nothing.
///
/// # Safety
/// `joint` is NULL or a live handle; `points` is NULL or points to `capacity` writable
/// `ClrMultipointContact`; `count` is NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn clr_multipoint_joint_points(
    joint: *const ClrMultipointJoint,
    points: *mut ClrMultipointContact,
    capacity: usize,
    count: *mut usize,
) -> ClrStatus {
    guard(|| {
        let count = out_ptr("count", count)?;
        let joint = borrow("joint", joint)?;
        if capacity > 0 {
            non_null("points", points)?;
        }
        let active = joint.0.points();
        let needed = active.len();
        if needed > capacity {
            count.write(needed);
            return Err(CapiError::BufferTooSmall {
                name: "points",
                needed,
                capacity,
            });
        }
        for (k, p) in active.enumerate() {
            points.add(k).write(p);
        }
        count.write(needed);
        Ok(())
    })
}

/// Forget the warm starts of the projections and the points of the last evaluation: the next
/// `clr_multipoint_joint_forces` starts from a coarse scan of the guide (65 samples), as the first
/// one does. Call it after a jump of the slider (a restart, a reinitialization) so that the
/// result does not depend on the evaluations before the jump.
///
/// # Safety
/// `joint` is NULL or a live handle not used by another thread during the call.
#[no_mangle]
pub unsafe extern "C" fn clr_multipoint_joint_reset(joint: *mut ClrMultipointJoint) -> ClrStatus {
    guard(|| {
        borrow_mut("joint", joint)?.0.reset();
        Ok(())
    })
}

/// Free a multipoint joint. NULL is ignored. Freeing a handle twice is undefined behaviour.
///
/// # Safety
/// `joint` is NULL or a handle from `clr_multipoint_joint_new_straight` or
/// `clr_multipoint_joint_new_sine` not freed yet.
#[no_mangle]
pub unsafe extern "C" fn clr_multipoint_joint_free(joint: *mut ClrMultipointJoint) {
    free_handle(joint)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multipoint_case::{
        body_values, evaluate, hertz_ln, impact_velocities, point_values, straight_case,
        straight_guide, straight_slider, STRAIGHT_JOINT,
    };
    use clr_contact::normal::GuideFace;
    use clr_contact::Material;
    use std::ffi::CStr;
    use std::ptr::{null, null_mut};

    fn message() -> String {
        unsafe { CStr::from_ptr(crate::error::last_error_ptr()) }
            .to_string_lossy()
            .into_owned()
    }

    fn state(b: &BodyState) -> ClrBodyState {
        let [x, y, theta, vx, vy, omega] = body_values(b);
        ClrBodyState {
            x,
            y,
            theta,
            vx,
            vy,
            omega,
        }
    }

    fn bits(g: &ClrGeneralizedForce) -> [u64; 3] {
        [g.fx.to_bits(), g.fy.to_bits(), g.moment.to_bits()]
    }

    /// Status and message of the constructor call `new` (given the output pointer), which must
    /// give a handle exactly on success; the handle too, unless freed here with `keep` false.
    fn try_new(
        keep: bool,
        new: impl FnOnce(*mut *mut ClrMultipointJoint) -> ClrStatus,
    ) -> (ClrStatus, String, *mut ClrMultipointJoint) {
        let mut h = null_mut();
        let s = new(&mut h);
        assert_eq!(h.is_null(), s != ClrStatus::Ok, "{s:?}");
        if !keep {
            unsafe { clr_multipoint_joint_free(h) };
            h = null_mut();
        }
        (s, message(), h)
    }

    /// The handle of the constructor call `new`, which must succeed.
    fn created(
        new: impl FnOnce(*mut *mut ClrMultipointJoint) -> ClrStatus,
    ) -> *mut ClrMultipointJoint {
        let (s, msg, h) = try_new(true, new);
        assert_eq!(s, ClrStatus::Ok, "{msg}");
        h
    }

    /// The handle of the shared straight case with N = `n`, M = `m`.
    fn new_straight(n: usize, m: usize) -> *mut ClrMultipointJoint {
        let [len, gap, l, h, ox, oy, angle, cx, cy, sa] = STRAIGHT_JOINT;
        let gap = gap as i32;
        created(|out| unsafe {
            clr_multipoint_joint_new_straight(len, gap, l, h, ox, oy, angle, cx, cy, sa, n, m, out)
        })
    }

    /// The handle of the §7.8 sine guide (A = 40 um, span 1 m) with its frame at `origin`
    /// rotated by `angle` on body i, and the slider 0.1 m x 0.02 m centred on body j.
    fn new_sine(origin: Vector2<f64>, angle: f64, n: usize, m: usize) -> *mut ClrMultipointJoint {
        let (a, span, ox, oy) = (40e-6, 1.0, origin.x, origin.y);
        created(|out| unsafe {
            clr_multipoint_joint_new_sine(
                a, span, 0.1, 0.02, ox, oy, angle, 0.0, 0.0, 0.0, n, m, out,
            )
        })
    }

    /// The safe layer of the shared straight case with N = `n`, M = `m`.
    fn safe_straight(n: usize, m: usize) -> MultipointJoint {
        let j = STRAIGHT_JOINT;
        let (origin, gap_on_left) = ([j[4], j[5]].into(), j[1] == 1.0);
        MultipointJoint::straight(j[0], gap_on_left, origin, j[6], straight_slider(), n, m).unwrap()
    }

    fn read_points(h: *const ClrMultipointJoint) -> Vec<ClrMultipointContact> {
        let mut count = 0usize;
        let mut buf = vec![ClrMultipointContact::default(); 64];
        let s = unsafe { clr_multipoint_joint_points(h, buf.as_mut_ptr(), buf.len(), &mut count) };
        assert_eq!(s, ClrStatus::Ok, "{}", message());
        buf.truncate(count);
        buf
    }

    /// `clr_multipoint_joint_forces` of `h` at the body `states` (guide, slider) with the `laws`
    /// (normal, friction) and δ̇⁻ = `v0`, which must succeed.
    fn joint_forces(
        h: *mut ClrMultipointJoint,
        states: (&BodyState, &BodyState),
        laws: (&NormalLaw, &FrictionLaw),
        v0: &[f64],
    ) -> ClrMultipointForces {
        let (gs, ss) = (state(states.0), state(states.1));
        let (cn, cf) = (ClrNormalLaw(*laws.0), ClrFrictionLaw(*laws.1));
        let mut out = ClrMultipointForces::default();
        let (v, n) = (v0.as_ptr(), v0.len());
        let s = unsafe { clr_multipoint_joint_forces(h, &cn, &cf, &gs, &ss, v, n, &mut out) };
        assert_eq!(s, ClrStatus::Ok, "{}", message());
        out
    }

    /// Every output of the handle against clr-contact's detector driven directly with the same
    /// guide, slider, force rule and sequence of states (the warm starts included): bit for bit.
    fn compare(
        h: *mut ClrMultipointJoint,
        reference: (&mut MultipointDetector, &dyn GuideSurface),
        states: (&BodyState, &BodyState),
        laws: (&NormalLaw, &FrictionLaw),
        v0: &[f64],
    ) -> ClrMultipointForces {
        let out = joint_forces(h, states, laws, v0);
        let (det, guide) = reference;
        let r = evaluate(det, guide, states, laws, v0);
        assert_eq!(bits(&out.slider), bits(&generalized(r.slider)));
        assert_eq!(bits(&out.guide), bits(&generalized(r.guide)));
        assert_eq!(out.active_points, det.points().len());
        match r.class {
            ContactClass::Separated => {
                assert_eq!((out.contact_class, out.area_face), (0, -1));
                assert_eq!(out.contact_length, 0.0);
            }
            ContactClass::Line { length } => {
                assert_eq!((out.contact_class, out.area_face), (1, -1));
                assert_eq!(out.contact_length.to_bits(), length.to_bits());
            }
            ContactClass::Area { face, length } => {
                assert_eq!(out.contact_class, CLR_CONTACT_CLASS_AREA);
                assert_eq!(out.area_face, face as i32);
                assert_eq!(out.contact_length.to_bits(), length.to_bits());
            }
        }
        let points = read_points(h);
        assert_eq!(points.len(), det.points().len());
        for ((o, p), &(f_n, f_t)) in points.iter().zip(det.points()).zip(&r.forces) {
            let got = [
                o.id as f64,
                o.source as f64,
                o.face as f64,
                o.index as f64,
                o.arc,
                o.penetration,
                o.normal_x,
                o.normal_y,
                o.slider_x,
                o.slider_y,
                o.guide_x,
                o.guide_y,
                o.normal_velocity,
                o.tangential_velocity,
                o.tributary_length,
                o.normal_force,
                o.tangential_force,
            ];
            let want = point_values(p, f_n, f_t);
            assert_eq!(
                got.map(f64::to_bits),
                want.map(f64::to_bits),
                "point {}",
                o.id
            );
        }
        out
    }

    #[test]
    fn straight_guide_matches_clr_contact_bit_for_bit() {
        let (n, m) = (3, 5);
        let h = new_straight(n, m);
        let mut count = 0usize;
        assert_eq!(
            unsafe { clr_multipoint_joint_point_count(h, &mut count) },
            ClrStatus::Ok
        );
        assert_eq!(count, 4 + 4 * n + m);
        let v0 = impact_velocities(count);
        let mut det = MultipointDetector::new(straight_slider(), n, m).unwrap();
        let normal = hertz_ln();
        let friction = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap();
        // A sequence (warm starts carried over): tilted line contact on the rear edge, the face
        // flat on the guide (area), separated, and the tilted edge again further on.
        let mut classes = Vec::new();
        for (along, sink, tilt) in [
            (0.2, 15e-6, 4e-4),
            (0.201, 10e-6, 0.0),
            (0.202, -1e-6, 0.0),
            (0.25, 20e-6, -5e-4),
        ] {
            let (bi, bj) = straight_case(along, sink, tilt);
            let guide = straight_guide(bi);
            let out = compare(h, (&mut det, &guide), (&bi, &bj), (&normal, &friction), &v0);
            classes.push((out.contact_class, out.active_points));
            // action and reaction: equal and opposite forces on the two bodies
            assert_eq!(out.guide.fx, -out.slider.fx);
            assert_eq!(out.guide.fy, -out.slider.fy);
        }
        assert_eq!(
            classes,
            [
                (CLR_CONTACT_CLASS_LINE, 4),
                (CLR_CONTACT_CLASS_AREA, 5),
                (CLR_CONTACT_CLASS_SEPARATED, 0),
                (CLR_CONTACT_CLASS_LINE, 4),
            ]
        );
        unsafe { clr_multipoint_joint_free(h) };
    }

    #[test]
    fn area_law_gets_the_tributary_length() {
        // The sliding-guide area law (clr-contact NormalLaw::area, not constructible through
        // clr_normal_law_new) through the safe layer: each point's own wetted length.
        let face = GuideFace {
            slider: Material::new(70e9, 0.33).unwrap(),
            guide: Material::new(207e9, 0.3).unwrap(),
            edge_radius: 1e-3,
            width: 0.02,
            layer_depth: 5e-3,
        };
        let area = NormalLaw::area(&face, 0.8, 0.0).unwrap();
        let friction = FrictionLaw::coulomb(0.1, 1e-3).unwrap();
        let mut joint = safe_straight(3, 0);
        let h: *mut ClrMultipointJoint = Box::into_raw(Box::new(ClrMultipointJoint(joint.clone())));
        let v0 = vec![0.1; joint.point_count()];
        let mut det = MultipointDetector::new(straight_slider(), 3, 0).unwrap();
        let (bi, bj) = straight_case(0.2, 15e-6, 4e-4);
        let guide = straight_guide(bi);
        let out = compare(h, (&mut det, &guide), (&bi, &bj), (&area, &friction), &v0);
        // the safe layer gives the same numbers
        let safe = joint.forces(&area, Some(&friction), &bi, &bj, &v0).unwrap();
        assert_eq!(bits(&safe.slider), bits(&out.slider));
        // and the lengths matter: with l = 0 everywhere the force is the edge law's alone
        let lengths: f64 = joint.points().map(|p| p.tributary_length).sum();
        assert!(lengths > 0.0);
        let edge: f64 = joint
            .points()
            .map(|p| area.force(p.penetration, p.normal_velocity, 0.1))
            .sum();
        let total: f64 = joint.points().map(|p| p.normal_force).sum();
        assert!(total > 1.5 * edge, "{total} vs {edge}");
        unsafe { clr_multipoint_joint_free(h) };
    }

    #[test]
    fn sine_guide_matches_clr_contact_and_moves_with_its_body() {
        // contact-laws.md §7.8: A = 40 um, span 1 m, slider 0.1 m x 0.02 m with its bottom face
        // at 39.5 um over x = 0.45 .. 0.55; N = 3 gives the penetrations 7.534e-9, 3.767e-7,
        // 5.000e-7, 3.767e-7, 7.534e-9 m (4 digits).
        let (n, m) = (3, 5);
        let h = new_sine(Vector2::zeros(), 0.0, n, m);
        let shape = SliderShape::new(0.1, 0.02, Vector2::zeros(), 0.0).unwrap();
        let mut det = MultipointDetector::new(shape, n, m).unwrap();
        let sine = SineGuide::new(40e-6, 1.0).unwrap();
        let normal = hertz_ln();
        let friction = FrictionLaw::threlfall(0.1, 0.01).unwrap();
        let v0: Vec<f64> = (0..4 + 4 * n + m).map(|k| 0.2 + 0.001 * k as f64).collect();
        let ground = BodyState::default();
        let mut first = None;
        for (x, bottom, vx) in [
            (0.5, 39.5e-6, 0.4),
            (0.5004, 39.6e-6, 0.4),
            (0.52, 39.0e-6, 0.1),
        ] {
            let bj = BodyState::new([x, bottom + 0.01].into(), 0.0, [vx, -1e-3].into(), 0.01);
            let out = compare(
                h,
                (&mut det, &sine),
                (&ground, &bj),
                (&normal, &friction),
                &v0,
            );
            first.get_or_insert((out, read_points(h)));
        }
        let (out, points) = first.unwrap();
        assert_eq!(out.contact_class, CLR_CONTACT_CLASS_AREA);
        assert_eq!(out.area_face, 0);
        let expected = [7.534e-9, 3.767e-7, 5.000e-7, 3.767e-7, 7.534e-9];
        let penetration_is = |p: &ClrMultipointContact, e: f64| {
            let d = p.penetration;
            assert!((d - e).abs() <= 1e-3 * e, "{d} vs {e}");
        };
        assert_eq!(points.len(), 5);
        for (p, e) in points.iter().zip(expected) {
            penetration_is(p, e);
        }
        unsafe { clr_multipoint_joint_free(h) };

        // The same guide on a moving body (frame at (0.3, -0.2) rotated by 0.7 rad on a body at
        // (1, 2) turned by -0.4 rad) with the slider carried rigidly along: the same contact in
        // the guide frame, and no relative velocity.
        let (o, alpha) = (Vector2::new(0.3, -0.2), 0.7);
        let bi = BodyState::new([1.0, 2.0].into(), -0.4, [0.5, -0.3].into(), 2.0);
        let carry = |local: Vector2<f64>, angle: f64| {
            let p = bi.point(o + rotate(alpha, local));
            BodyState::new(p, bi.angle + alpha + angle, bi.point_velocity(p), 2.0)
        };
        let bj = carry(Vector2::new(0.5, 39.5e-6 + 0.01), 0.0);
        let h = new_sine(o, alpha, n, m);
        joint_forces(h, (&bi, &bj), (&normal, &friction), &v0);
        let moved_points = read_points(h);
        assert_eq!(moved_points.len(), 5);
        let to_world = |x: f64, y: f64| bi.rotate(rotate(alpha, Vector2::new(x, y)));
        for (p, e) in moved_points.iter().zip(expected) {
            penetration_is(p, e);
            // world normal = the static case's normal (0, -1) turned with the guide frame
            let nw = to_world(0.0, -1.0);
            assert!((p.normal_x - nw.x).abs() < 1e-3 && (p.normal_y - nw.y).abs() < 1e-3);
            // rigid motion together: the slider point P and the guide point r(s) = P + δ n
            // differ by the penetration, so v_rel = ω k × (P − r) = ω δ along ∓t, v_N = 0
            assert!(p.normal_velocity.abs() < 1e-12, "{}", p.normal_velocity);
            let slip = 2.0 * p.penetration;
            assert!((p.tangential_velocity.abs() - slip).abs() < 1e-12 * (1.0 + slip));
        }
        unsafe { clr_multipoint_joint_free(h) };
    }

    #[test]
    fn bad_input_gives_status_codes_and_touches_nothing() {
        let h = new_straight(3, 5);
        let (bi, bj) = straight_case(0.2, 15e-6, 4e-4);
        let (gs, ss) = (state(&bi), state(&bj));
        let cn = ClrNormalLaw(hertz_ln());
        let v0 = vec![0.1; 21];
        let mut out = ClrMultipointForces::default();
        let forces = |joint: *mut ClrMultipointJoint,
                      normal: *const ClrNormalLaw,
                      guide: *const ClrBodyState,
                      slider: *const ClrBodyState,
                      v: *const f64,
                      n: usize,
                      out: *mut ClrMultipointForces| unsafe {
            clr_multipoint_joint_forces(joint, normal, null(), guide, slider, v, n, out)
        };
        let ok = forces(h, &cn, &gs, &ss, v0.as_ptr(), 21, &mut out);
        assert_eq!(ok, ClrStatus::Ok);
        let before = read_points(h);
        assert_eq!(before.len(), 4);
        let good = out;

        // NULL pointers, each named in the message
        let sentinel = ClrMultipointForces {
            active_points: 777,
            ..Default::default()
        };
        let mut out = sentinel;
        let expect = |got: ClrStatus, want: ClrStatus, needle: &str| {
            assert_eq!(got, want, "{needle}");
            assert!(message().contains(needle), "{}", message());
        };
        let expect_null = |got, name| expect(got, ClrStatus::NullPointer, &format!("`{name}`"));
        let p = v0.as_ptr();
        expect_null(forces(null_mut(), &cn, &gs, &ss, p, 21, &mut out), "joint");
        expect_null(forces(h, null(), &gs, &ss, p, 21, &mut out), "normal");
        expect_null(forces(h, &cn, null(), &ss, p, 21, &mut out), "guide");
        expect_null(forces(h, &cn, &gs, null(), p, 21, &mut out), "slider");
        expect_null(
            forces(h, &cn, &gs, &ss, null(), 21, &mut out),
            "impact_velocities",
        );
        expect_null(forces(h, &cn, &gs, &ss, p, 21, null_mut()), "out");
        // non-finite state and impact velocity
        let nan = ClrBodyState { vy: f64::NAN, ..ss };
        let inf = ClrBodyState {
            theta: f64::INFINITY,
            ..gs
        };
        let non_finite = ClrStatus::NonFinite;
        expect(
            forces(h, &cn, &gs, &nan, p, 21, &mut out),
            non_finite,
            "slider state",
        );
        expect(
            forces(h, &cn, &inf, &ss, p, 21, &mut out),
            non_finite,
            "guide state",
        );
        let mut bad_v0 = v0.clone();
        bad_v0[20] = f64::NAN; // an inactive point's entry: still rejected
        let bad = forces(h, &cn, &gs, &ss, bad_v0.as_ptr(), 21, &mut out);
        expect(bad, non_finite, "impact_velocities");
        // wrong array length
        let short = forces(h, &cn, &gs, &ss, p, 4, &mut out);
        expect(short, ClrStatus::InvalidArgument, "has 4 entries; pass 21");
        // nothing written, and the handle still holds the last good evaluation
        assert_eq!(out, sentinel);
        assert_eq!(read_points(h), before);

        // output buffer too small: the count needed, nothing copied
        let mut count = 0usize;
        let mut small = [ClrMultipointContact {
            id: 999,
            ..Default::default()
        }; 2];
        let s = unsafe { clr_multipoint_joint_points(h, small.as_mut_ptr(), 2, &mut count) };
        assert_eq!(s, ClrStatus::BufferTooSmall);
        assert_eq!(count, good.active_points);
        assert!(small.iter().all(|p| p.id == 999));
        assert!(
            message().contains("room for 2 entries but 4"),
            "{}",
            message()
        );
        // a capacity-0 query with NULL, exact capacity, NULL with a capacity, NULL count/joint
        count = 0;
        let s = unsafe { clr_multipoint_joint_points(h, null_mut(), 0, &mut count) };
        assert_eq!((s, count), (ClrStatus::BufferTooSmall, 4));
        let mut exact = [ClrMultipointContact::default(); 4];
        let s = unsafe { clr_multipoint_joint_points(h, exact.as_mut_ptr(), 4, &mut count) };
        assert_eq!((s, count), (ClrStatus::Ok, 4));
        assert_eq!(exact.to_vec(), before);
        let s = unsafe { clr_multipoint_joint_points(h, null_mut(), 8, &mut count) };
        assert_eq!(s, ClrStatus::NullPointer);
        let s = unsafe { clr_multipoint_joint_points(h, exact.as_mut_ptr(), 4, null_mut()) };
        assert_eq!(s, ClrStatus::NullPointer);
        let s = unsafe { clr_multipoint_joint_points(null(), exact.as_mut_ptr(), 4, &mut count) };
        assert_eq!(s, ClrStatus::NullPointer);
        let s = unsafe { clr_multipoint_joint_point_count(h, null_mut()) };
        assert_eq!(s, ClrStatus::NullPointer);
        let s = unsafe { clr_multipoint_joint_point_count(null(), &mut count) };
        assert_eq!(s, ClrStatus::NullPointer);

        // reset: no points until the next evaluation, which gives the same result as the first
        assert_eq!(unsafe { clr_multipoint_joint_reset(h) }, ClrStatus::Ok);
        let s = unsafe { clr_multipoint_joint_points(h, null_mut(), 0, &mut count) };
        assert_eq!((s, count), (ClrStatus::Ok, 0));
        let mut again = ClrMultipointForces::default();
        let s = forces(h, &cn, &gs, &ss, v0.as_ptr(), 21, &mut again);
        assert_eq!(s, ClrStatus::Ok);
        assert_eq!(bits(&again.slider), bits(&good.slider));
        assert_eq!(
            unsafe { clr_multipoint_joint_reset(null_mut()) },
            ClrStatus::NullPointer
        );
        unsafe { clr_multipoint_joint_free(h) };
        unsafe { clr_multipoint_joint_free(null_mut()) };
    }

    #[test]
    fn invalid_parameters_give_no_handle() {
        type Args = (f64, i32, f64, f64, f64, usize, usize);
        let straight = |(len, gap, l, h, angle, n, m): Args| {
            let (s, msg, _) = try_new(false, |out| unsafe {
                clr_multipoint_joint_new_straight(
                    len, gap, l, h, 0.0, 0.0, angle, 0.0, 0.0, 0.0, n, m, out,
                )
            });
            (s, msg)
        };
        let cases: [(Args, ClrStatus, &str); 9] = [
            (
                (0.0, 1, 0.1, 0.02, 0.0, 3, 5),
                ClrStatus::InvalidParameter,
                "length (m)",
            ),
            (
                (f64::NAN, 1, 0.1, 0.02, 0.0, 3, 5),
                ClrStatus::InvalidParameter,
                "length (m)",
            ),
            (
                (0.5, 2, 0.1, 0.02, 0.0, 3, 5),
                ClrStatus::InvalidArgument,
                "`gap_on_left` = 2",
            ),
            (
                (0.5, -1, 0.1, 0.02, 0.0, 3, 5),
                ClrStatus::InvalidArgument,
                "must be 0 or 1",
            ),
            (
                (0.5, 1, -0.1, 0.02, 0.0, 3, 5),
                ClrStatus::InvalidParameter,
                "slider length L",
            ),
            (
                (0.5, 1, 0.1, 0.0, 0.0, 3, 5),
                ClrStatus::InvalidParameter,
                "slider height h",
            ),
            (
                (0.5, 1, 0.1, 0.02, f64::INFINITY, 3, 5),
                ClrStatus::InvalidParameter,
                "angle",
            ),
            (
                (0.5, 1, 0.1, 0.02, 0.0, 100_001, 5),
                ClrStatus::InvalidParameter,
                "per face N",
            ),
            (
                (0.5, 1, 0.1, 0.02, 0.0, 3, 200_000),
                ClrStatus::InvalidParameter,
                "samples M",
            ),
        ];
        for (args, status, needle) in cases {
            let (s, msg) = straight(args);
            assert_eq!(s, status, "{args:?}: {msg}");
            assert!(msg.contains(needle), "{args:?}: {msg}");
        }
        assert_eq!(straight((0.5, 0, 0.1, 0.02, 0.0, 0, 0)).0, ClrStatus::Ok);
        let s = unsafe {
            clr_multipoint_joint_new_straight(
                0.5,
                1,
                0.1,
                0.02,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                0.0,
                3,
                5,
                null_mut(),
            )
        };
        assert_eq!(s, ClrStatus::NullPointer);

        let sine = |a: f64, span: f64, ox: f64| {
            let (s, msg, _) = try_new(false, |out| unsafe {
                clr_multipoint_joint_new_sine(
                    a, span, 0.1, 0.02, ox, 0.0, 0.0, 0.0, 0.0, 0.0, 3, 5, out,
                )
            });
            (s, msg)
        };
        assert_eq!(sine(-40e-6, 1.0, 0.0).0, ClrStatus::Ok);
        let (s, msg) = sine(40e-6, 0.0, 0.0);
        assert_eq!(s, ClrStatus::InvalidParameter);
        assert!(msg.contains("span"), "{msg}");
        let (s, msg) = sine(f64::NAN, 1.0, 0.0);
        assert_eq!(s, ClrStatus::InvalidParameter);
        assert!(msg.contains("amplitude"), "{msg}");
        let (s, msg) = sine(40e-6, 1.0, f64::NEG_INFINITY);
        assert_eq!(s, ClrStatus::InvalidParameter);
        assert!(msg.contains("origin"), "{msg}");
    }

    #[test]
    fn evaluations_do_not_allocate() {
        // The point buffers keep their address and capacity over evaluations of every class.
        let mut joint = safe_straight(3, 5);
        let normal = hertz_ln();
        let v0 = vec![0.1; joint.point_count()];
        let (bi, bj) = straight_case(0.2, 15e-6, 4e-4);
        joint.forces(&normal, None, &bi, &bj, &v0).unwrap();
        let (p0, f0, cap) = (
            joint.detector().points().as_ptr(),
            joint.forces.as_ptr(),
            joint.forces.capacity(),
        );
        for k in 0..30 {
            let (bi, bj) = straight_case(0.1 + 0.01 * k as f64, 20e-6 - 1e-6 * k as f64, 1e-4);
            joint.forces(&normal, None, &bi, &bj, &v0).unwrap();
            assert_eq!(joint.detector().points().as_ptr(), p0);
            assert_eq!(joint.forces.as_ptr(), f0);
            assert_eq!(joint.forces.capacity(), cap);
        }
    }
}
