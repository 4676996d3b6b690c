//! The straight-guide multipoint case shared by the unit tests of `src/multipoint.rs` and by
//! `tests/c_program.rs`, and the reference evaluation both compare the C API against:
//! clr-contact's `StraightGuide`/`SineGuide` and `MultipointDetector` driven directly (not
//! through the C API). Both include this file with `#[path]`; it uses clr-contact only.

use clr_contact::body::{rotate, Vector2};
use clr_contact::multipoint::{ContactPoint, PointSource, StraightGuide};
use clr_contact::{
    BodyState, ContactClass, DampingFactor, ElasticLaw, FrictionLaw, GeneralizedForce,
    GuideSurface, MultipointDetector, NormalLaw, SliderShape,
};

/// The arguments of `clr_multipoint_joint_new_straight` for the case, N and M aside: guide
/// length 0.5 m, gap on the left (1), slider L = 0.1 m, h = 0.02 m, guide origin (0.01, 0) m and
/// angle 0 rad on body i, slider centre (0.002, 0) m and angle 0 rad on body j.
pub const STRAIGHT_JOINT: [f64; 10] = [0.5, 1.0, 0.1, 0.02, 0.01, 0.0, 0.0, 0.002, 0.0, 0.0];

/// Hertz K (N/m^1.5) and the c_e of the Lankarani–Nikravesh damping of [`hertz_ln`].
pub const HERTZ_LN: [f64; 2] = [1e10, 0.8];

/// The slider of [`STRAIGHT_JOINT`].
pub fn straight_slider() -> SliderShape {
    let j = STRAIGHT_JOINT;
    SliderShape::new(j[2], j[3], [j[7], j[8]].into(), j[9]).expect("slider")
}

/// The guide surface of [`STRAIGHT_JOINT`] on the guide body in the state `body`.
pub fn straight_guide(body: BodyState) -> StraightGuide {
    let j = STRAIGHT_JOINT;
    StraightGuide::new(body, [j[4], j[5]].into(), j[6], j[0], j[1] == 1.0).expect("guide")
}

/// Guide and slider body states of [`STRAIGHT_JOINT`]: the guide body moving and rotated, the
/// slider `along` m down the guide, tilted by `tilt` rad against it with its centre `sink` m
/// into it, sliding and spinning.
pub fn straight_case(along: f64, sink: f64, tilt: f64) -> (BodyState, BodyState) {
    let j = STRAIGHT_JOINT;
    let guide = BodyState::new([0.0, 0.001].into(), 0.01, [0.05, 0.0].into(), 0.2);
    let t = guide.rotate(Vector2::new(1.0, 0.0));
    let n = Vector2::new(-t.y, t.x);
    let centre = guide.point([j[4], j[5]].into()) + along * t + (0.5 * j[3] - sink) * n;
    let theta = guide.angle + tilt;
    let position = centre - rotate(theta, Vector2::new(j[7], j[8]));
    let slider = BodyState::new(position, theta, [0.3, -0.01].into(), 0.5);
    (guide, slider)
}

/// δ̇⁻ (m/s) of the `count` point ids: 0.05 + 0.01 id.
pub fn impact_velocities(count: usize) -> Vec<f64> {
    (0..count).map(|k| 0.05 + 0.01 * k as f64).collect()
}

/// The normal law of [`HERTZ_LN`].
pub fn hertz_ln() -> NormalLaw {
    let elastic = ElasticLaw::hertz(HERTZ_LN[0]).expect("Hertz K");
    NormalLaw::new(elastic, DampingFactor::LankaraniNikravesh, HERTZ_LN[1]).expect("normal law")
}

/// A body state as (x, y, θ, ẋ, ẏ, ω), the field order of `ClrBodyState`.
pub fn body_values(b: &BodyState) -> [f64; 6] {
    [
        b.position.x,
        b.position.y,
        b.angle,
        b.velocity.x,
        b.velocity.y,
        b.angular_velocity,
    ]
}

/// What clr-contact gives for one evaluation.
pub struct Reference {
    /// The contact class.
    pub class: ContactClass,
    /// (F_N, F_T) in N of every active point, in the order of the detector's points.
    pub forces: Vec<(f64, f64)>,
    /// Generalized force on the guide body, reduced independently from each point's force on
    /// the slider.
    pub guide: GeneralizedForce,
    /// Generalized force on the slider body.
    pub slider: GeneralizedForce,
}

/// Evaluate the contact with clr-contact's detector `det` on `surface`, for the guide and slider
/// body `states`, the normal and friction `laws` (an area law gets each point's tributary length)
/// and δ̇⁻ = `v0[id]`, as the C API does it.
pub fn evaluate(
    det: &mut MultipointDetector,
    surface: &dyn GuideSurface,
    states: (&BodyState, &BodyState),
    laws: (&NormalLaw, &FrictionLaw),
    v0: &[f64],
) -> Reference {
    let (guide, slider) = states;
    let (normal, friction) = laws;
    let class = det.detect(surface, slider);
    let mut forces = Vec::new();
    let slider = det.apply_forces(|p| {
        let c = &p.contact;
        let law = normal.with_contact_length(p.tributary_length);
        let f_n = law.force(c.penetration, c.normal_velocity, v0[p.id]);
        let f_t = friction.force(c.tangential_velocity, f_n);
        forces.push((f_n, f_t));
        (f_n, f_t)
    });
    let mut q_guide = GeneralizedForce::zero();
    for (p, &(f_n, f_t)) in det.points().iter().zip(&forces) {
        let force = -p.contact.slider_force(f_n, f_t);
        q_guide += GeneralizedForce::at(guide.position, p.contact.guide_point, force);
    }
    Reference {
        class,
        forces,
        guide: q_guide,
        slider,
    }
}

/// The values of an active point with its forces `f_n`, `f_t` (N), in the field order of
/// `ClrMultipointContact`: id, source (the `CLR_POINT_SOURCE_*` code), face (−1 unless a face
/// point), index, arc, δ, n_x, n_y, slider x, y, guide x, y, v_N, v_T, tributary length, F_N, F_T.
pub fn point_values(p: &ContactPoint, f_n: f64, f_t: f64) -> [f64; 17] {
    let (source, face, index) = match p.source {
        PointSource::Corner(k) => (0.0, -1.0, k),
        PointSource::Face { face, index } => (1.0, face as f64, index),
        PointSource::GuideSample(k) => (2.0, -1.0, k),
    };
    let c = &p.contact;
    [
        p.id as f64,
        source,
        face,
        index as f64,
        p.arc,
        c.penetration,
        c.normal.x,
        c.normal.y,
        c.slider_point.x,
        c.slider_point.y,
        c.guide_point.x,
        c.guide_point.y,
        c.normal_velocity,
        c.tangential_velocity,
        p.tributary_length,
        f_n,
        f_t,
    ]
}
