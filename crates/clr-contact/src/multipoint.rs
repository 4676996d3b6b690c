//! Multipoint contact of a rigid rectangular slider against a deformable guide surface.
//!
//! Method of `contact-laws.md` §3.2 (a generalization of the corner contacts of Flores, Ambrósio,
//! Claro, Lankarani, J. Comput. Nonlinear Dyn. 3 (2008) 011007 to a flexible guide):
//!
//! 1. **Candidate points on the slider**: the 4 corners plus N equally spaced points on each face.
//! 2. **Closest-point projection** of each candidate P onto the guide curve r(s): the root of
//!    g(s) = (P − r(s))·r′(s) by Gauss–Newton steps Δs = (P − r)·**t**/|r′| (curvature term
//!    dropped, which only slows convergence when the gap times the curvature is not small), warm
//!    started from the previous evaluation and clamped to the arc range.
//! 3. **Signed gap** (P − r(s*))·**n**_g with **n**_g the guide normal into the gap; the
//!    penetration is δ = −gap when positive. A point whose projection is clamped at an end of the
//!    guide and lies beyond it is not in contact itself: the slider outline from its neighbour
//!    over the guide to it is clipped at the end, and the candidate stands for the clipped point
//!    over the end (arc s_e, its depth there, `ContactPoint::over_guide` the fraction of the
//!    segment still over the guide). The contact of a slider passing the end of its guide thus
//!    shrinks continuously: the wetted length of the clipped segment goes to 0 as the
//!    neighbour reaches the end, instead of a corner's share dropping out when it crosses.
//! 4. **Reverse check**: M guide sample points spread over the arc interval under the slider are
//!    tested against the slider rectangle. A guide point inside the slider is a contact whose
//!    depth is measured along **n**_g to the slider face facing the guide. This finds penetrations
//!    *between* slider candidate points when the guide bends (§7.8: a hogging guide touching the
//!    middle of the slider face while the corners barely touch). A sample adds a contact only
//!    when it is deeper (by more than 0.1 %) than the gap linearly interpolated between the two
//!    candidates of that face whose projections bracket it: where the guide is straight under
//!    the face the candidates already describe the contact, and a sample on a candidate is a
//!    duplicate.
//! 5. **Classification**: area contact when every candidate of one slider face (both corners and
//!    the N face points) is active — the face lies on the guide; line contact otherwise (a corner,
//!    an edge region or a patch shorter than a face). The contact length is the arc extent of the
//!    active points.
//! 6. **Forces**: a caller-supplied rule gives (F_N, F_T) per active point; they are summed into
//!    the slider's generalized force and returned as point loads at arc coordinates for the guide
//!    (a beam maps them with its shape functions, Q += S(s)ᵀ f).
//!
//! Conventions as in [`crate::revolute`] and [`crate::translational`]: the contact normal **n**
//! points in the direction the slider penetrates (**n** = −**n**_g), **t** = k̂ × **n**, δ̇ = v_N =
//! (ṙ_slider − ṙ_guide)·**n** (> 0 approaching), v_T = (ṙ_slider − ṙ_guide)·**t**, force on the
//! slider −F_N **n** + F_T **t**, on the guide the opposite.
//!
//! [`MultipointDetector`] owns every buffer; after construction no evaluation allocates.
//!
//! The two shape queries (is a guide point inside the slider rectangle; how deep, measured along
//! the guide normal to the slider face that faces the guide) are written here in `f64` rather
//! than taken from parry: `parry2d` computes in `f32` (about 3e-8 m resolution at 0.5 m, coarser
//! than the 7.5 nm penetrations of contact-laws.md §7.8), and `parry2d-f64`'s cuboid point
//! projection and ray cast would answer them but need conversions to its own vector types around
//! a query that is a dozen lines in the slider frame. The crate therefore does not depend on parry.

use nalgebra::Vector2;

use crate::body::{
    check_finite, check_positive, perp, rotate, BodyState, GeneralizedForce, PointContact,
};
use crate::error::ContactError;

/// A guide surface parametrized by an arc coordinate s (m), e.g. the top face of a deformed beam.
///
/// s need not be the exact arc length of the deformed curve (a beam's undeformed axial coordinate
/// is fine): [`GuideSurface::speed`] gives |dr/ds|, 1 by default.
pub trait GuideSurface {
    /// The admissible interval (s_min, s_max) of the arc coordinate, m, s_min < s_max.
    fn arc_range(&self) -> (f64, f64);
    /// Surface point r(s) in the world frame, m.
    fn point(&self, s: f64) -> Vector2<f64>;
    /// Unit tangent dr/ds / |dr/ds| at s.
    fn tangent(&self, s: f64) -> Vector2<f64>;
    /// Unit normal at s pointing out of the guide material, into the gap where the slider is.
    fn normal(&self, s: f64) -> Vector2<f64>;
    /// Velocity of the guide's material point at s, m/s.
    fn velocity(&self, s: f64) -> Vector2<f64>;
    /// |dr/ds| (dimensionless); 1 when s is the arc length.
    fn speed(&self, _s: f64) -> f64 {
        1.0
    }
}

/// A straight guide surface fixed on a (possibly moving) rigid body: the segment of the body-frame
/// line through `origin` along the direction at `angle`, s ∈ [0, length], normal to the left of
/// the tangent (`gap_on_left = true`) or to the right.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StraightGuide {
    body: BodyState,
    origin: Vector2<f64>,
    tangent: Vector2<f64>,
    normal: Vector2<f64>,
    length: f64,
}

impl StraightGuide {
    /// The guide on `body` from local point `origin` (m), local direction `angle` (rad), of length
    /// `length` (m, > 0), with the gap on the left of the direction of increasing s when
    /// `gap_on_left`.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for a non-positive length or non-finite data.
    pub fn new(
        body: BodyState,
        origin: Vector2<f64>,
        angle: f64,
        length: f64,
        gap_on_left: bool,
    ) -> Result<Self, ContactError> {
        check_positive("straight guide", &[("length (m)", length)])?;
        check_finite(
            "straight guide",
            &[
                ("origin, local x (m)", origin.x),
                ("origin, local y (m)", origin.y),
                ("angle (rad)", angle),
            ],
        )?;
        let tangent = body.rotate(rotate(angle, Vector2::new(1.0, 0.0)));
        let left = perp(tangent);
        Ok(Self {
            body,
            origin: body.point(origin),
            tangent,
            normal: if gap_on_left { left } else { -left },
            length,
        })
    }
}

impl GuideSurface for StraightGuide {
    fn arc_range(&self) -> (f64, f64) {
        (0.0, self.length)
    }
    fn point(&self, s: f64) -> Vector2<f64> {
        self.origin + s * self.tangent
    }
    fn tangent(&self, _s: f64) -> Vector2<f64> {
        self.tangent
    }
    fn normal(&self, _s: f64) -> Vector2<f64> {
        self.normal
    }
    fn velocity(&self, s: f64) -> Vector2<f64> {
        self.body.point_velocity(self.point(s))
    }
}

/// A static guide bent in a half sine, r(s) = (s, A sin(πs/ℓ)) for s ∈ [0, ℓ], gap above it
/// (normal to the left of the tangent): the shape of a simply supported beam in its first mode,
/// and the hogging guide of `contact-laws.md` §7.8 (A = 40 µm, ℓ = 1 m). s is the x coordinate,
/// so [`GuideSurface::speed`] is √(1 + y′²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SineGuide {
    amplitude: f64,
    span: f64,
}

impl SineGuide {
    /// The guide of amplitude A (m, any sign: positive hogs upward) and span ℓ (m, > 0).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for a non-positive span or non-finite amplitude.
    pub fn new(amplitude: f64, span: f64) -> Result<Self, ContactError> {
        check_positive("sine guide", &[("span (m)", span)])?;
        check_finite("sine guide", &[("amplitude (m)", amplitude)])?;
        Ok(Self { amplitude, span })
    }

    /// y′(s) = (Aπ/ℓ) cos(πs/ℓ).
    fn slope(&self, s: f64) -> f64 {
        let k = std::f64::consts::PI / self.span;
        self.amplitude * k * (k * s).cos()
    }
}

impl GuideSurface for SineGuide {
    fn arc_range(&self) -> (f64, f64) {
        (0.0, self.span)
    }
    fn point(&self, s: f64) -> Vector2<f64> {
        let k = std::f64::consts::PI / self.span;
        Vector2::new(s, self.amplitude * (k * s).sin())
    }
    fn tangent(&self, s: f64) -> Vector2<f64> {
        let dy = self.slope(s);
        Vector2::new(1.0, dy) / (1.0 + dy * dy).sqrt()
    }
    fn normal(&self, s: f64) -> Vector2<f64> {
        perp(self.tangent(s))
    }
    fn velocity(&self, _s: f64) -> Vector2<f64> {
        Vector2::zeros()
    }
    fn speed(&self, s: f64) -> f64 {
        self.slope(s).hypot(1.0)
    }
}

/// The rigid rectangular slider: length L along its local x axis, height h along y, centred at
/// `centre` (local coordinates on its body) and rotated by `angle` from the body's x axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliderShape {
    length: f64,
    height: f64,
    centre: Vector2<f64>,
    angle: f64,
}

impl SliderShape {
    /// A slider of length L and height h (m, both > 0) at local `centre` (m), rotated by `angle`
    /// (rad) on its body.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] for a non-positive dimension or non-finite data.
    pub fn new(
        length: f64,
        height: f64,
        centre: Vector2<f64>,
        angle: f64,
    ) -> Result<Self, ContactError> {
        check_positive(
            "slider",
            &[
                ("slider length L (m)", length),
                ("slider height h (m)", height),
            ],
        )?;
        check_finite(
            "slider",
            &[
                ("centre, local x (m)", centre.x),
                ("centre, local y (m)", centre.y),
                ("angle (rad)", angle),
            ],
        )?;
        Ok(Self {
            length,
            height,
            centre,
            angle,
        })
    }

    /// Slider length L, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Slider height h, m.
    pub fn height(&self) -> f64 {
        self.height
    }

    /// Centre of the slider in the frame of its body, m.
    pub fn centre(&self) -> Vector2<f64> {
        self.centre
    }

    /// Angle of the slider's x axis from its body's x axis, rad.
    pub fn angle(&self) -> f64 {
        self.angle
    }

    /// Corner k (0..4, counter-clockwise from (−L/2, −h/2)) in the frame of the slider's body
    /// (centre + A(angle)·corner), m.
    pub fn body_corner(&self, k: usize) -> Vector2<f64> {
        self.body_point(self.corner(k))
    }

    /// Slider-frame point → point in the frame of the slider's body, m.
    fn body_point(&self, p: Vector2<f64>) -> Vector2<f64> {
        self.centre + rotate(self.angle, p)
    }

    /// Corner k (0..4, counter-clockwise from (−L/2, −h/2)) in the slider frame, m.
    pub(crate) fn corner(&self, k: usize) -> Vector2<f64> {
        let (a, b) = (0.5 * self.length, 0.5 * self.height);
        match k % 4 {
            0 => Vector2::new(-a, -b),
            1 => Vector2::new(a, -b),
            2 => Vector2::new(a, b),
            _ => Vector2::new(-a, b),
        }
    }

    /// Slider-frame point → world point on `body`.
    pub(crate) fn world_point(&self, body: &BodyState, p: Vector2<f64>) -> Vector2<f64> {
        body.point(self.body_point(p))
    }

    /// World point → slider-frame point on `body`.
    fn slider_point(&self, body: &BodyState, w: Vector2<f64>) -> Vector2<f64> {
        rotate(-self.angle, body.to_local(w) - self.centre)
    }
}

/// Where a contact point comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointSource {
    /// Slider corner 0..4 (counter-clockwise from (−L/2, −h/2)).
    Corner(usize),
    /// Point `index` (0..N) on slider face `face` (face f runs from corner f to corner f+1).
    Face {
        /// Face 0..4 (0 bottom, 1 right, 2 top, 3 left in the slider frame).
        face: usize,
        /// Position along the face, 0..N.
        index: usize,
    },
    /// Guide sample `0..M` of the reverse check.
    GuideSample(usize),
}

/// One active contact point (SI units, world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// Stable index of the candidate (corners 0..4, face points 4..4+4N, guide samples after);
    /// use it to index a [`crate::memory::ContactMemory`] of [`MultipointDetector::point_count`]
    /// entries. Guide samples move with the slider, so their memory is approximate.
    pub id: usize,
    /// Origin of the point.
    pub source: PointSource,
    /// Arc coordinate of the contact on the guide, m.
    pub arc: f64,
    /// Penetration, normal **n** = −**n**_g, tangent, contact points (r(s) on the guide) and
    /// relative velocities.
    pub contact: PointContact,
    /// Wetted (tributary) length of the point, m: its lumped share of the penetration profile
    /// interpolated linearly between neighbouring candidates (0 when the point only just
    /// touches, the half spacings to both neighbours when they penetrate too); the length a
    /// distributed (per unit length) law should multiply. Continuous in the configuration.
    pub tributary_length: f64,
    /// Fraction [0, 1] of the point's share of the slider outline (the half segments to its two
    /// neighbouring candidates, measured along the guide's tangent at the end) that lies over
    /// the guide: 1 unless the share reaches past an end of the guide (then the point may be a
    /// candidate past the end whose contact is clipped to the end, step 3 of the module docs).
    /// A point law (one without a wetted length) multiplies its force by it, so the part of the
    /// slider that passes the end leaves the contact continuously.
    pub over_guide: f64,
}

/// A point load on the guide at an arc coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointLoad {
    /// Arc coordinate s, m.
    pub arc: f64,
    /// Application point r(s), m.
    pub point: Vector2<f64>,
    /// Force on the guide, N.
    pub force: Vector2<f64>,
}

/// Kind of contact found by [`MultipointDetector::detect`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactClass {
    /// No point penetrates.
    Separated,
    /// Localized contact: a corner, an edge region or a patch shorter than a face.
    Line {
        /// Arc extent of the active points, m (0 for a single point).
        length: f64,
    },
    /// A whole slider face lies on the guide (all its candidates active).
    Area {
        /// The face 0..4 (0 bottom, 1 right, 2 top, 3 left).
        face: usize,
        /// Arc extent of the active points, m.
        length: f64,
    },
}

/// Reusable multipoint contact detector for one slider against one guide surface.
#[derive(Debug, Clone)]
pub struct MultipointDetector {
    shape: SliderShape,
    face_points: usize,
    guide_samples: usize,
    max_iterations: usize,
    /// Warm starts of the projections of the slider candidates (NaN: none yet).
    warm: Vec<f64>,
    /// Projection of every slider candidate at the last evaluation: (s*, signed gap, active);
    /// for a candidate past an end, that of its clipped point.
    projected: Vec<(f64, f64, bool)>,
    /// Per slider candidate at the last evaluation: its projection is clamped at an end of the
    /// guide and it lies past that end.
    past_end: Vec<bool>,
    /// Per slider candidate past an end: the neighbour over the guide its contact is clipped
    /// towards and the fraction λ ∈ (0, 1) of the segment from that neighbour at which the end
    /// lies (`None`: not clipped).
    clip: Vec<Option<(usize, f64)>>,
    /// Coordinate of every slider candidate along the outward tangent of a guide end, m
    /// (scratch of [`Self::clip_at_ends`]).
    along: Vec<f64>,
    points: Vec<ContactPoint>,
    loads: Vec<PointLoad>,
    class: ContactClass,
    slider_reference: Vector2<f64>,
}

impl MultipointDetector {
    /// A detector for `shape` with `face_points` (N) candidates on each face besides the corners
    /// and `guide_samples` (M) guide points for the reverse check (0 disables it).
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] when N or M exceeds 100 000 (the buffers are
    /// preallocated; such counts are almost surely a mistake).
    pub fn new(
        shape: SliderShape,
        face_points: usize,
        guide_samples: usize,
    ) -> Result<Self, ContactError> {
        const MAX: usize = 100_000;
        for (name, v) in [
            ("points per face N", face_points),
            ("guide samples M", guide_samples),
        ] {
            if v > MAX {
                return Err(ContactError::invalid(
                    "multipoint detector",
                    name,
                    v as f64,
                    format!("must be at most {MAX}"),
                ));
            }
        }
        let candidates = 4 + 4 * face_points;
        let total = candidates + guide_samples;
        Ok(Self {
            shape,
            face_points,
            guide_samples,
            max_iterations: 50,
            warm: vec![f64::NAN; candidates],
            projected: vec![(f64::NAN, f64::NAN, false); candidates],
            past_end: vec![false; candidates],
            clip: vec![None; candidates],
            along: vec![0.0; candidates],
            points: Vec::with_capacity(total),
            loads: Vec::with_capacity(total),
            class: ContactClass::Separated,
            slider_reference: Vector2::zeros(),
        })
    }

    /// The slider shape.
    pub fn shape(&self) -> &SliderShape {
        &self.shape
    }

    /// Number of distinct point ids (4 + 4N + M), the size of a matching contact memory.
    pub fn point_count(&self) -> usize {
        self.warm.len() + self.guide_samples
    }

    /// Active contact points of the last [`detect`](Self::detect), sorted by arc coordinate.
    pub fn points(&self) -> &[ContactPoint] {
        &self.points
    }

    /// Guide point loads of the last [`apply_forces`](Self::apply_forces) (emptied by
    /// [`detect`](Self::detect)).
    pub fn loads(&self) -> &[PointLoad] {
        &self.loads
    }

    /// Classification of the last [`detect`](Self::detect).
    pub fn class(&self) -> ContactClass {
        self.class
    }

    /// Number of slider candidates 4 + 4N (ids 0..4 + 4N; guide samples follow).
    pub fn candidate_count(&self) -> usize {
        self.warm.len()
    }

    /// Position of slider candidate `id` (< [`candidate_count`](Self::candidate_count)) in the
    /// frame of the slider's body, m; `None` for other ids.
    pub fn candidate_body_point(&self, id: usize) -> Option<Vector2<f64>> {
        (id < self.warm.len()).then(|| self.shape.body_point(self.candidate(id).0))
    }

    /// Where the contact of slider candidate `id` (< [`candidate_count`](Self::candidate_count))
    /// was evaluated at the last [`detect`](Self::detect), in the frame of the slider's body,
    /// m: the candidate itself, or for a candidate past an end of the guide the point of the
    /// slider outline over that end it was clipped to; `None` for other ids.
    pub fn contact_body_point(&self, id: usize) -> Option<Vector2<f64>> {
        if id >= self.warm.len() {
            return None;
        }
        let local = self.candidate(id).0;
        Some(match self.clip[id] {
            Some((nb, lambda)) => {
                let other = self.candidate(nb).0;
                self.shape.body_point(other + lambda * (local - other))
            }
            None => self.shape.body_point(local),
        })
    }

    /// Whether slider candidate `id` lay past an end of the guide at the last
    /// [`detect`](Self::detect) (its projection clamped at the end and the point beyond it);
    /// `false` for other ids. Corners are ids 0..4, counter-clockwise from (−L/2, −h/2).
    pub fn past_end(&self, id: usize) -> bool {
        self.past_end.get(id).copied().unwrap_or(false)
    }

    /// Projection of slider candidate `id` at the last [`detect`](Self::detect): (arc
    /// coordinate s* (m), signed gap (m, < 0 penetrating), active); `None` for other ids.
    pub fn projection(&self, id: usize) -> Option<(f64, f64, bool)> {
        self.projected.get(id).copied()
    }

    /// Partial derivatives of the tributary length of the active candidate `id` (see
    /// [`ContactPoint::tributary_length`]) with respect to the projections of the candidates it
    /// depends on, for Jacobians: calls `f(candidate, ∂l/∂s*, ∂l/∂gap)` once per term (a
    /// candidate may appear several times; sum them), with s* and the signed gap of
    /// [`projection`](Self::projection). Nothing is called for an inactive id. Returns false
    /// (and calls nothing) when guide samples are active: the lengths then come from the
    /// neighbour rule on the points' arcs, not from the candidates' projections.
    ///
    /// Per segment of the face chain between `id` (δ = −gap > 0) and a neighbour (clamped
    /// penetration o): l += ½|Δs| when o > 0, else ½|Δs|·δ/(δ − o) (the wedge rule of
    /// [`detect`](Self::detect)); o = min(−gap, 0) for an inactive neighbour, whose derivative is
    /// 0 where the clamp holds.
    pub fn tributary_partials(&self, id: usize, mut f: impl FnMut(usize, f64, f64)) -> bool {
        if self
            .points
            .iter()
            .any(|p| matches!(p.source, PointSource::GuideSample(_)))
        {
            return false;
        }
        if !self.projected.get(id).is_some_and(|p| p.2) {
            return true;
        }
        let n = self.face_points;
        for face in 0..4 {
            let mut previous: Option<usize> = None;
            for b in self.face_chain(face, n) {
                if let Some(a) = previous {
                    if a == id {
                        self.share_partials(a, b, &mut f);
                    }
                    if b == id {
                        self.share_partials(b, a, &mut f);
                    }
                }
                previous = Some(b);
            }
        }
        true
    }

    /// Candidates of slider face `face` in order: corner, N face points, next corner.
    fn face_chain(&self, face: usize, n: usize) -> impl Iterator<Item = usize> {
        core::iter::once(face)
            .chain((0..n).map(move |i| 4 + face * n + i))
            .chain(core::iter::once((face + 1) % 4))
    }

    /// Partials of the share of active candidate `me` from its segment to `other`.
    fn share_partials(&self, me: usize, other: usize, f: &mut impl FnMut(usize, f64, f64)) {
        let (sm, gm, _) = self.projected[me];
        let (so, go, act_o) = self.projected[other];
        let d = (so - sm).abs();
        if !d.is_finite() {
            return;
        }
        // d|s_o − s_me|/ds_o (0 where the two projections coincide)
        let sgn = if so > sm {
            1.0
        } else if so < sm {
            -1.0
        } else {
            0.0
        };
        let delta = -gm;
        // an active neighbour's penetration, or an inactive one's clamped at 0 (its derivative
        // is 0 where the clamp holds: a candidate past the end of the guide)
        let (o, do_dgo) = if act_o || -go < 0.0 {
            (-go, -1.0)
        } else {
            (0.0, 0.0)
        };
        if o > 0.0 {
            f(other, 0.5 * sgn, 0.0);
            f(me, -0.5 * sgn, 0.0);
            return;
        }
        let w = delta / (delta - o);
        let den = (delta - o) * (delta - o);
        f(other, 0.5 * w * sgn, 0.5 * d * delta / den * do_dgo);
        // ∂w/∂δ = −o/(δ − o)², ∂δ/∂gap = −1
        f(me, -0.5 * w * sgn, 0.5 * d * o / den);
    }

    /// Forget the warm starts (e.g. after a jump of the slider).
    pub fn reset(&mut self) {
        self.warm.iter_mut().for_each(|s| *s = f64::NAN);
    }

    /// Slider-frame position of candidate `id` (< 4 + 4N).
    fn candidate(&self, id: usize) -> (Vector2<f64>, PointSource) {
        if id < 4 {
            return (self.shape.corner(id), PointSource::Corner(id));
        }
        let n = self.face_points;
        let (face, index) = ((id - 4) / n, (id - 4) % n);
        let a = self.shape.corner(face);
        let b = self.shape.corner(face + 1);
        let f = (index + 1) as f64 / (n + 1) as f64;
        (a + f * (b - a), PointSource::Face { face, index })
    }

    /// Find every penetrating point of the slider (body state `slider`) against `guide`, classify
    /// the contact and return the classification. Results are in [`points`](Self::points).
    pub fn detect<G: GuideSurface + ?Sized>(
        &mut self,
        guide: &G,
        slider: &BodyState,
    ) -> ContactClass {
        self.points.clear();
        self.loads.clear();
        self.slider_reference = slider.position;
        let (s_min, s_max) = guide.arc_range();
        let candidates = self.warm.len();
        let mut corner_span = (f64::INFINITY, f64::NEG_INFINITY);
        for id in 0..candidates {
            let (local, source) = self.candidate(id);
            let p = self.shape.world_point(slider, local);
            let start = if self.warm[id].is_finite() {
                self.warm[id]
            } else {
                coarse_start(guide, p)
            };
            let (s, beyond) = project(guide, p, start, self.max_iterations);
            self.warm[id] = s;
            if id < 4 {
                corner_span = (corner_span.0.min(s), corner_span.1.max(s));
            }
            let ng = guide.normal(s);
            let r = guide.point(s);
            let delta = -(p - r).dot(&ng);
            let active = delta > 0.0 && !beyond;
            self.projected[id] = (s, -delta, active);
            self.past_end[id] = beyond;
            self.clip[id] = None;
            if active {
                self.push_point(guide, slider, id, source, s, delta, p, r, ng);
            }
        }
        if self.past_end.iter().any(|&b| b) {
            self.clip_at_ends(guide, slider);
        }
        // Reverse check from guide samples spread over the arc interval under the slider corners.
        let m = self.guide_samples;
        if m > 0 {
            let (lo, hi) = (corner_span.0.max(s_min), corner_span.1.min(s_max));
            let spacing = if m > 1 {
                (hi - lo) / (m - 1) as f64
            } else {
                hi - lo
            };
            for k in 0..m {
                let s = if m > 1 {
                    lo + k as f64 * spacing
                } else {
                    0.5 * (lo + hi)
                };
                let g = guide.point(s);
                let ng = guide.normal(s);
                let Some((delta, face)) = self.depth_inside(slider, g, ng) else {
                    continue;
                };
                // Already seen by the slider candidates: the depth their gaps interpolate to.
                let seen = self
                    .interpolated_gap(face, s)
                    .is_some_and(|gap| delta + gap <= 1e-3 * delta + 1e-15);
                if !seen {
                    let p = g - delta * ng;
                    let id = candidates + k;
                    self.push_point(
                        guide,
                        slider,
                        id,
                        PointSource::GuideSample(k),
                        s,
                        delta,
                        p,
                        g,
                        ng,
                    );
                }
            }
        }
        self.points
            .sort_unstable_by(|a, b| a.arc.total_cmp(&b.arc).then(a.id.cmp(&b.id)));
        self.assign_tributary_lengths(m);
        self.class = self.classify();
        self.class
    }

    /// Depth (along **n**_g) of guide point `g` inside the slider, measured to the slider face
    /// that faces the guide, with that face; `None` when `g` is outside the rectangle.
    fn depth_inside(
        &self,
        slider: &BodyState,
        g: Vector2<f64>,
        ng: Vector2<f64>,
    ) -> Option<(f64, usize)> {
        let q = self.shape.slider_point(slider, g);
        let (a, b) = (0.5 * self.shape.length, 0.5 * self.shape.height);
        if !(q.x.abs() < a && q.y.abs() < b) {
            return None;
        }
        // Guide normal in the slider frame.
        let nl = rotate(-(slider.angle + self.shape.angle), ng);
        // (m·n_g, distance of q inside the face) for the outward normals m of the four faces.
        let faces = [
            (-nl.y, q.y + b),
            (nl.x, a - q.x),
            (nl.y, b - q.y),
            (-nl.x, q.x + a),
        ];
        let (face, (dot, dist)) = faces
            .into_iter()
            .enumerate()
            .min_by(|x, y| x.1 .0.total_cmp(&y.1 .0))
            .unwrap_or((0, (-1.0, 0.0)));
        (dot < 0.0).then(|| (dist / -dot, face))
    }

    /// Signed gap at arc coordinate `s` linearly interpolated between the two consecutive
    /// candidates of slider face `face` (corner, face points, corner) whose projections bracket
    /// `s`; `None` when no pair brackets it.
    fn interpolated_gap(&self, face: usize, s: f64) -> Option<f64> {
        let n = self.face_points;
        let ids = core::iter::once(face)
            .chain((0..n).map(|i| 4 + face * n + i))
            .chain(core::iter::once((face + 1) % 4));
        let mut previous: Option<(f64, f64)> = None;
        for id in ids {
            let (sk, gk, _) = self.projected[id];
            if let Some((sp, gp)) = previous {
                let (lo, hi) = if sp <= sk { (sp, sk) } else { (sk, sp) };
                if lo <= s && s <= hi {
                    let w = if hi > lo { (s - sp) / (sk - sp) } else { 0.0 };
                    return Some(gp + w * (gk - gp));
                }
            }
            previous = Some((sk, gk));
        }
        None
    }

    #[allow(clippy::too_many_arguments)]
    fn push_point<G: GuideSurface + ?Sized>(
        &mut self,
        guide: &G,
        slider: &BodyState,
        id: usize,
        source: PointSource,
        arc: f64,
        penetration: f64,
        slider_point: Vector2<f64>,
        guide_point: Vector2<f64>,
        guide_normal: Vector2<f64>,
    ) {
        let v = slider.point_velocity(slider_point) - guide.velocity(arc);
        self.points.push(ContactPoint {
            id,
            source,
            arc,
            contact: PointContact::new(penetration, -guide_normal, slider_point, guide_point, v),
            tributary_length: 0.0,
            over_guide: 1.0,
        });
    }

    /// The two neighbours of slider candidate `id` along the slider outline (the previous and
    /// the next candidate of its face chains).
    fn outline_neighbours(&self, id: usize) -> [usize; 2] {
        let n = self.face_points;
        let last_of = |face: usize| if n > 0 { 4 + face * n + n - 1 } else { face };
        let first_of = |face: usize| if n > 0 { 4 + face * n } else { (face + 1) % 4 };
        if id < 4 {
            return [last_of((id + 3) % 4), first_of(id)];
        }
        let (face, index) = ((id - 4) / n, (id - 4) % n);
        let previous = if index == 0 { face } else { id - 1 };
        let next = if index + 1 == n {
            (face + 1) % 4
        } else {
            id + 1
        };
        [previous, next]
    }

    /// Clip the contact of the slider at an end of the guide, for each end some candidate lies
    /// past. With a(P) = (P − r_e)·t_e the coordinate along the outward tangent t_e from the
    /// end r_e (a > 0 past the end):
    ///
    /// - a candidate P_me past the end is not in contact itself; the slider outline from a
    ///   neighbour P_nb over the guide (a_nb < 0) to it crosses the end's normal line at
    ///   P = P_nb + λ (P_me − P_nb), λ = a_nb / (a_nb − a_me), and the candidate stands for P:
    ///   arc s_e, penetration −(P − r_e)·n_e (the deeper of two such neighbours). Its segment
    ///   to the neighbour is thereby clipped at the end: its wetted share shrinks to 0 as the
    ///   neighbour reaches the end, and at the crossing (a_me → 0⁺) P is P_me;
    /// - every active candidate gets `over_guide`, the fraction of its share of the outline
    ///   (the half segments to its two neighbours, measured along t_e) with a ≤ 0, which a
    ///   point law multiplies its force by: 1 for a share wholly over the guide, falling
    ///   linearly to 0 as the share passes the end (also for the last corner to leave).
    ///
    /// Both make the contact force continuous in the configuration as the slider passes the
    /// end (a jump there stalls an adaptive integrator).
    fn clip_at_ends<G: GuideSurface + ?Sized>(&mut self, guide: &G, slider: &BodyState) {
        let (s_min, s_max) = guide.arc_range();
        for (s_e, sign) in [(s_min, -1.0), (s_max, 1.0)] {
            let at_end = |&(k, past): &(usize, &bool)| *past && self.projected[k].0 == s_e;
            if !self.past_end.iter().enumerate().any(|p| at_end(&p)) {
                continue;
            }
            let (r_e, n_e) = (guide.point(s_e), guide.normal(s_e));
            let t_e = guide.tangent(s_e) * sign;
            for id in 0..self.along.len() {
                let p = self.shape.world_point(slider, self.candidate(id).0);
                self.along[id] = (p - r_e).dot(&t_e);
            }
            for me in 0..self.past_end.len() {
                if self.past_end[me] && self.projected[me].0 == s_e {
                    self.clip_candidate(guide, slider, me, (s_e, r_e, n_e));
                }
            }
            let candidates = self.along.len();
            for k in 0..self.points.len() {
                let id = self.points[k].id;
                if id < candidates {
                    self.points[k].over_guide = self.share_over_guide(id);
                }
            }
        }
    }

    /// Clip candidate `me` (past the end at arc `s_e`, point `r_e`, normal `n_e`) to the
    /// deepest point of the outline over the end ([`Self::clip_at_ends`]).
    fn clip_candidate<G: GuideSurface + ?Sized>(
        &mut self,
        guide: &G,
        slider: &BodyState,
        me: usize,
        (s_e, r_e, n_e): (f64, Vector2<f64>, Vector2<f64>),
    ) {
        let a_me = self.along[me];
        let p_me = self.shape.world_point(slider, self.candidate(me).0);
        let mut best: Option<(usize, f64, Vector2<f64>, f64)> = None;
        for nb in self.outline_neighbours(me) {
            let a_nb = self.along[nb];
            if self.past_end[nb] || !(a_nb < 0.0 && a_me > 0.0) {
                continue;
            }
            let p_nb = self.shape.world_point(slider, self.candidate(nb).0);
            let lambda = a_nb / (a_nb - a_me);
            let p = p_nb + lambda * (p_me - p_nb);
            let delta = -(p - r_e).dot(&n_e);
            if best.is_none_or(|b| delta > b.3) {
                best = Some((nb, lambda, p, delta));
            }
        }
        let Some((nb, lambda, p, delta)) = best else {
            return;
        };
        self.clip[me] = Some((nb, lambda));
        self.projected[me] = (s_e, -delta, delta > 0.0);
        if delta > 0.0 {
            let source = self.candidate(me).1;
            self.push_point(guide, slider, me, source, s_e, delta, p, r_e, n_e);
        }
    }

    /// Fraction of candidate `id`'s share of the slider outline (the half segments to its two
    /// neighbours, extents measured along the end's outward tangent: `along`) that lies over
    /// the guide (a ≤ 0); for a share of no extent along the tangent, 1 over the guide, else 0.
    fn share_over_guide(&self, id: usize) -> f64 {
        let a = self.along[id];
        let (mut over, mut extent) = (0.0, 0.0);
        for nb in self.outline_neighbours(id) {
            let mid = 0.5 * (a + self.along[nb]);
            let (lo, hi) = if a <= mid { (a, mid) } else { (mid, a) };
            extent += hi - lo;
            over += (hi.min(0.0) - lo).max(0.0);
        }
        if extent > 0.0 {
            over / extent
        } else if a <= 0.0 {
            1.0
        } else {
            0.0
        }
    }

    /// Tributary (wetted) length of every active point, m: the integral of the penetration
    /// profile linearly interpolated between consecutive candidates of each slider face, lumped
    /// on the candidates. A segment of arc length Δ between two active candidates gives Δ/2 to
    /// each; a segment with one active end a (δ_a > 0) and one separated end b (δ_b ≤ 0) is
    /// wetted over Δ·δ_a/(δ_a − δ_b) and gives a the half of that (the wedge's centroid rule,
    /// so that Σ l_i δ_i is the exact integral ∫δ ds of the interpolant). The lengths are
    /// therefore continuous in the configuration: they grow from 0 as an edge starts to
    /// penetrate and reach the face's tributary lengths when the whole face touches, so a
    /// per-unit-length law switches smoothly between line and area contact. When guide samples
    /// of the reverse check are active, every point gets the neighbour rule instead
    /// ([`Self::neighbour_lengths`]).
    fn assign_tributary_lengths(&mut self, guide_samples: usize) {
        if self
            .points
            .iter()
            .any(|p| matches!(p.source, PointSource::GuideSample(_)))
        {
            self.neighbour_lengths(guide_samples);
            return;
        }
        let n = self.face_points;
        let index_of = |points: &[ContactPoint], id: usize| points.iter().position(|p| p.id == id);
        for face in 0..4 {
            let chain = core::iter::once(face)
                .chain((0..n).map(|i| 4 + face * n + i))
                .chain(core::iter::once((face + 1) % 4));
            let mut previous: Option<usize> = None;
            for id in chain {
                if let Some(a) = previous {
                    let (sa, ga, act_a) = self.projected[a];
                    let (sb, gb, act_b) = self.projected[id];
                    let d = (sb - sa).abs();
                    // an inactive candidate beyond the guide end counts as separated
                    let (da, db) = (
                        if act_a { -ga } else { (-ga).min(0.0) },
                        if act_b { -gb } else { (-gb).min(0.0) },
                    );
                    for (me, mine, other) in [(a, (act_a, da), db), (id, (act_b, db), da)] {
                        let (active, delta) = mine;
                        if !active || !d.is_finite() {
                            continue;
                        }
                        let share = if other > 0.0 {
                            0.5 * d
                        } else {
                            0.5 * d * delta / (delta - other)
                        };
                        if let Some(k) = index_of(&self.points, me) {
                            self.points[k].tributary_length += share;
                        }
                    }
                }
                previous = Some(id);
            }
        }
    }

    /// Old neighbour rule, used when guide samples of the reverse check are active (a guide
    /// bulging between the candidates, where the candidates' interpolation does not describe
    /// the profile): half the arc distance to each neighbouring active point within one
    /// candidate spacing.
    fn neighbour_lengths(&mut self, guide_samples: usize) {
        let n = self.face_points;
        let mut spacing = self.shape.length.max(self.shape.height) / (n as f64 + 1.0);
        if guide_samples > 1 {
            let (lo, hi) = self.projected[..4]
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p.0), hi.max(p.0))
                });
            spacing = spacing.max((hi - lo) / (guide_samples - 1) as f64);
        }
        let limit = 1.05 * spacing;
        for i in 1..self.points.len() {
            let d = self.points[i].arc - self.points[i - 1].arc;
            if d <= limit {
                self.points[i - 1].tributary_length += 0.5 * d;
                self.points[i].tributary_length += 0.5 * d;
            }
        }
    }

    fn classify(&self) -> ContactClass {
        let (Some(first), Some(last)) = (self.points.first(), self.points.last()) else {
            return ContactClass::Separated;
        };
        let length = last.arc - first.arc;
        let n = self.face_points;
        for face in 0..4 {
            let corners = self.projected[face].2 && self.projected[(face + 1) % 4].2;
            let interior = (0..n).all(|i| self.projected[4 + face * n + i].2);
            if corners && interior {
                return ContactClass::Area { face, length };
            }
        }
        ContactClass::Line { length }
    }

    /// Apply a force rule `force(point) -> (F_N, F_T)` (N) at every active point of the last
    /// [`detect`](Self::detect): −F_N **n** + F_T **t** on the slider at its contact point, the
    /// opposite on the guide as a [`PointLoad`] (see [`loads`](Self::loads)). Returns the
    /// generalized force on the slider body about its reference point.
    pub fn apply_forces(
        &mut self,
        mut force: impl FnMut(&ContactPoint) -> (f64, f64),
    ) -> GeneralizedForce {
        self.loads.clear();
        let mut total = GeneralizedForce::zero();
        for p in &self.points {
            let (f_n, f_t) = force(p);
            let f = p.contact.slider_force(f_n, f_t);
            total += GeneralizedForce::at(self.slider_reference, p.contact.slider_point, f);
            self.loads.push(PointLoad {
                arc: p.arc,
                point: p.contact.guide_point,
                force: -f,
            });
        }
        total
    }
}

/// Initial arc coordinate for a point without warm start: the closest of 65 uniform samples.
fn coarse_start<G: GuideSurface + ?Sized>(guide: &G, p: Vector2<f64>) -> f64 {
    let (lo, hi) = guide.arc_range();
    let n = 64;
    (0..=n)
        .map(|k| lo + (hi - lo) * k as f64 / n as f64)
        .map(|s| (s, (guide.point(s) - p).norm_squared()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(lo, |(s, _)| s)
}

/// Closest-point projection of `p` on the guide by Gauss–Newton from `start`, clamped to the arc
/// range. Returns (s*, beyond) where `beyond` flags a projection clamped at an end with the point
/// lying past that end (not over the guide).
fn project<G: GuideSurface + ?Sized>(
    guide: &G,
    p: Vector2<f64>,
    start: f64,
    max_iterations: usize,
) -> (f64, bool) {
    let (lo, hi) = guide.arc_range();
    let tol = 1e-13 * (hi - lo).abs().max(f64::MIN_POSITIVE);
    let mut s = start.clamp(lo, hi);
    let mut along = 0.0;
    for _ in 0..max_iterations {
        along = (p - guide.point(s)).dot(&guide.tangent(s));
        let speed = guide.speed(s);
        let step = if speed > 0.0 { along / speed } else { 0.0 };
        let next = (s + step).clamp(lo, hi);
        let moved = (next - s).abs();
        s = next;
        if moved <= tol {
            break;
        }
    }
    let clamped = s <= lo || s >= hi;
    // Past an end the tangential offset stays finite; accept rounding-level offsets only.
    let beyond = clamped && along.abs() > 1e-9 * (hi - lo).abs().max(1.0);
    (s, beyond)
}
