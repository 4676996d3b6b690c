//! Geometry and kinematics of the clearance joints: worked examples of contact-laws.md §7.7 and
//! §7.8, hand-derived closed forms, frame invariance and cross-checks between independent code
//! paths (translational corners vs multipoint on a straight guide).

use clr_contact::body::{cross, rotate, BodyState};
use clr_contact::damping::DampingFactor;
use clr_contact::elastic::{ElasticLaw, Material};
use clr_contact::friction::FrictionLaw;
use clr_contact::multipoint::{
    ContactClass, GuideSurface, MultipointDetector, PointSource, SineGuide, SliderShape,
    StraightGuide,
};
use clr_contact::normal::NormalLaw;
use clr_contact::revolute::RevoluteClearance;
use clr_contact::translational::{Configuration, GuideSide, TranslationalClearance};
use nalgebra::Vector2;

fn v(x: f64, y: f64) -> Vector2<f64> {
    Vector2::new(x, y)
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

macro_rules! assert_rel {
    ($a:expr, $b:expr, $rel:expr) => {{
        let (a, b): (f64, f64) = ($a, $b);
        assert!(
            close(a, b, $rel),
            "{} = {a:e}, expected {b:e} (rel {})",
            stringify!($a),
            $rel
        );
    }};
}

// ---------------------------------------------------------------- revolute (§7.7)

/// contact-laws.md §7.7: bearing fixed at the origin, journal centre at (c + δ)n with
/// n = (0.6, 0.8), c = 0.1 mm, δ = 10 µm, journal velocity (0.3, 0.4) m/s, ω_j = 10 rad/s.
fn worked_example() -> (RevoluteClearance, BodyState, BodyState) {
    let joint = RevoluteClearance::new(10e-3, 9.9e-3, v(0.0, 0.0), v(0.0, 0.0)).unwrap();
    let n = v(0.6, 0.8);
    let bearing = BodyState::fixed(v(0.0, 0.0), 0.0);
    let journal = BodyState::new((0.1e-3 + 10e-6) * n, 0.3, v(0.3, 0.4), 10.0);
    (joint, bearing, journal)
}

#[test]
fn revolute_worked_example_geometry() {
    // Expected values of §7.7 (exact decimals); tolerance 1e-9 relative (closed forms).
    let (joint, bearing, journal) = worked_example();
    let c = joint.contact(&bearing, &journal);
    assert_rel!(c.eccentricity, 0.11e-3, 1e-9);
    assert_rel!(c.penetration, 10e-6, 1e-9);
    assert_rel!(joint.clearance(), 0.1e-3, 1e-12);
    let (qi, qj) = joint.contact_points(&bearing, &journal);
    assert_rel!(qi.x, 6.000e-3, 1e-9);
    assert_rel!(qi.y, 8.000e-3, 1e-9);
    assert_rel!(qj.x, 6.006e-3, 1e-9);
    assert_rel!(qj.y, 8.008e-3, 1e-9);
    let vq = journal.point_velocity(qj);
    assert_rel!(vq.x, 0.2208, 1e-9);
    assert_rel!(vq.y, 0.4594, 1e-9);
    assert_rel!(
        joint.relative_normal_velocity(&bearing, &journal),
        0.5,
        1e-9
    );
    assert_rel!(
        joint.relative_tangential_velocity(&bearing, &journal),
        0.099,
        1e-9
    );
    let t = joint.tangent(&bearing, &journal);
    assert_rel!(t.x, -0.8, 1e-12);
    assert_rel!(t.y, 0.6, 1e-12);
}

#[test]
fn revolute_worked_example_forces_from_laws() {
    // §7.7: L-N (c_e = 0.5, δ̇⁻ = 0.5) and Ambrósio (μ = 0.1, v0 = 1e-4, v1 = 1e-3, so c_d = 1 at
    // v_T = 0.099). Expected values to 8 digits; tolerance 1e-8 relative.
    let (joint, bearing, journal) = worked_example();
    let steel = Material::steel();
    let elastic = ElasticLaw::hertz_internal_cylinder(&steel, 10e-3, &steel, 9.9e-3).unwrap();
    let law = NormalLaw::new(elastic, DampingFactor::LankaraniNikravesh, 0.5).unwrap();
    let friction = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap();
    let f = joint
        .contact(&bearing, &journal)
        .forces_from_laws(&law, &friction, 0.5);
    assert_rel!(f.normal_force, 7455.4750, 1e-8);
    assert_rel!(f.tangential_force, -745.5475, 1e-8);
    assert_rel!(f.journal.force.x, -3876.8470, 1e-8);
    assert_rel!(f.journal.force.y, -6411.7085, 1e-8);
    assert_rel!(f.journal.moment, -7.380920, 1e-7);
    assert_rel!(f.bearing.force.x, 3876.8470, 1e-8);
    assert_rel!(f.bearing.force.y, 6411.7085, 1e-8);
    assert_rel!(f.bearing.moment, 7.455475, 1e-7);
    // Closed form of §3.1: with the journal's reference at its centre only friction produces a
    // moment, m_j = R_j F_T.
    assert_rel!(f.journal.moment, 9.9e-3 * f.tangential_force, 1e-12);
}

#[test]
fn revolute_is_frame_invariant() {
    // Independent check: rotate the whole worked example by α about the origin and translate it
    // by d; the scalar kinematics (δ, v_N, v_T) must not change and the forces must rotate with
    // the frame. Bearing and journal centres are put
    // off the bodies' reference points so that the local-point mapping is exercised.
    let (joint0, bearing0, journal0) = worked_example();
    let c0 = joint0.contact(&bearing0, &journal0);
    let f0 = c0.generalized_forces(1000.0, -50.0);
    let alpha = 0.7_f64;
    let d = v(0.3, -0.2);
    let (si, sj) = (v(0.05, 0.01), v(-0.02, 0.04));
    let (phi_i, phi_j) = (0.4, -1.1);
    let joint = RevoluteClearance::new(10e-3, 9.9e-3, si, sj).unwrap();
    // Body positions such that the joint centres land on the rotated worked-example centres.
    let pi = rotate(alpha, bearing0.position) + d;
    let pj = rotate(alpha, journal0.position) + d;
    let bearing = BodyState::new(pi - rotate(phi_i, si), phi_i, v(0.0, 0.0), 0.0);
    // Journal body: centre velocity = rotated (0.3, 0.4), same ω; reference velocity follows.
    let r_j = pj - rotate(phi_j, sj);
    let vc = rotate(alpha, journal0.velocity);
    let omega = journal0.angular_velocity;
    let vref = vc - omega * v(-(pj - r_j).y, (pj - r_j).x);
    let journal = BodyState::new(r_j, phi_j, vref, omega);
    let c = joint.contact(&bearing, &journal);
    assert_rel!(c.penetration, c0.penetration, 1e-9);
    assert_rel!(c.normal_velocity, c0.normal_velocity, 1e-9);
    assert_rel!(c.tangential_velocity, c0.tangential_velocity, 1e-9);
    let f = c.generalized_forces(1000.0, -50.0);
    let fj = rotate(alpha, f0.journal.force);
    assert_rel!(f.journal.force.x, fj.x, 1e-9);
    assert_rel!(f.journal.force.y, fj.y, 1e-9);
    // Moments about the new reference points: (Q − r) × f computed independently.
    assert_rel!(f.journal.moment, cross(c.journal_point - r_j, fj), 1e-9);
    assert_rel!(
        f.bearing.moment,
        cross(c.bearing_point - bearing.position, -fj),
        1e-9
    );
}

#[test]
fn revolute_concentric_journal_has_no_contact_and_no_nan() {
    let joint = RevoluteClearance::new(10e-3, 9.9e-3, v(0.0, 0.0), v(0.0, 0.0)).unwrap();
    let body = BodyState::new(v(0.0, 0.0), 0.0, v(1.0, 2.0), 3.0);
    let c = joint.contact(&BodyState::default(), &body);
    assert_eq!(c.eccentricity, 0.0);
    assert_rel!(c.penetration, -0.1e-3, 1e-9);
    assert!(c
        .normal
        .iter()
        .chain(c.tangent.iter())
        .all(|x| x.is_finite()));
    assert!((c.normal.norm() - 1.0).abs() < 1e-15);
    assert!(c.normal_velocity.is_finite() && c.tangential_velocity.is_finite());
    assert_eq!(c.generalized_forces(100.0, 10.0).journal.force, v(0.0, 0.0));
}

#[test]
fn revolute_rejects_bad_geometry() {
    let o = v(0.0, 0.0);
    assert!(RevoluteClearance::new(10e-3, 10e-3, o, o).is_err());
    assert!(RevoluteClearance::new(10e-3, 11e-3, o, o).is_err());
    assert!(RevoluteClearance::new(-1.0, 0.5, o, o).is_err());
    assert!(RevoluteClearance::new(1.0, 0.0, o, o).is_err());
    assert!(RevoluteClearance::new(f64::NAN, 0.5, o, o).is_err());
    assert!(RevoluteClearance::new(1.0, 0.5, v(f64::INFINITY, 0.0), o).is_err());
    let msg = RevoluteClearance::new(10e-3, 11e-3, o, o)
        .unwrap_err()
        .to_string();
    assert!(msg.contains("journal radius"), "{msg}");
}

// ---------------------------------------------------------------- translational

/// Slider L = 0.1 m, h = 0.02 m centred on its body's reference point.
fn flat_slider() -> SliderShape {
    SliderShape::new(0.1, 0.02, v(0.0, 0.0), 0.0).unwrap()
}

/// Slider L = 0.1 m, h = 0.02 m in a guide W = 0.0202 m (clearance 0.2 mm), guide frame at the
/// ground origin along x.
fn slider_joint() -> TranslationalClearance {
    TranslationalClearance::new(flat_slider(), 0.0202, v(0.0, 0.0), 0.0).unwrap()
}

#[test]
fn translational_configurations() {
    let joint = slider_joint();
    let ground = BodyState::default();
    // Free flight: centred.
    let c = joint.contact(&ground, &BodyState::fixed(v(0.3, 0.0), 0.0));
    assert_eq!(c.configuration, Configuration::FreeFlight);
    assert_eq!(c.active().count(), 0);

    // Two adjacent corners on one surface: flat slider raised by 0.1 mm + 5 µm → the two top
    // corners penetrate the upper surface by 5 µm each.
    let c = joint.contact(&ground, &BodyState::fixed(v(0.3, 0.105e-3), 0.0));
    assert_eq!(c.configuration, Configuration::TwoCornersOneSurface);
    for k in [2, 3] {
        let cc = c.corners[k].unwrap();
        assert_eq!(cc.side, GuideSide::Upper);
        assert_rel!(cc.contact.penetration, 5e-6, 1e-6);
        assert_eq!(cc.contact.normal, v(0.0, 1.0));
    }

    // One corner: tilt θ about the centre; corner 2 at y = a sin θ + b cos θ (closed form).
    let theta = 3e-3;
    let (a, b) = (0.05, 0.01);
    let c = joint.contact(&ground, &BodyState::fixed(v(0.0, 0.0), theta));
    let y2 = a * theta.sin() + b * theta.cos();
    assert_eq!(c.configuration, Configuration::TwoCornersOppositeSurfaces);
    assert_rel!(c.corners[2].unwrap().contact.penetration, y2 - 0.0101, 1e-9);
    assert_rel!(c.corners[0].unwrap().contact.penetration, y2 - 0.0101, 1e-9);
    assert_eq!(c.corners[0].unwrap().side, GuideSide::Lower);
    let c = joint.contact(&ground, &BodyState::fixed(v(0.0, 0.05e-3), theta));
    assert_eq!(c.configuration, Configuration::OneCorner);
    assert_rel!(
        c.corners[2].unwrap().contact.penetration,
        y2 + 0.05e-3 - 0.0101,
        1e-9
    );
}

#[test]
fn translational_corner_velocities_and_forces() {
    let joint = slider_joint();
    let ground = BodyState::default();
    // Flat slider raised into the upper surface, moving with (2, 0.01) m/s and ω = 0.5 rad/s.
    let slider = BodyState::new(v(0.3, 0.105e-3), 0.0, v(2.0, 0.01), 0.5);
    let c = joint.contact(&ground, &slider);
    for k in [2, 3] {
        let cc = c.corners[k].unwrap();
        // ṙ_P = ṙ + ω k̂ × (P − r): x = 2 − ω (P − r)_y, y = 0.01 + ω (P − r)_x; n = +y, t = −x.
        let r = cc.contact.slider_point - slider.position;
        assert_rel!(cc.contact.normal_velocity, 0.01 + 0.5 * r.x, 1e-12);
        assert_rel!(cc.contact.tangential_velocity, -(2.0 - 0.5 * r.y), 1e-12);
    }
    let f = c.generalized_forces(|cc| (100.0 * cc.corner as f64, -10.0));
    // Corners 2 and 3 push the slider down with 200 N and 300 N; friction along t = −x.
    assert_rel!(f.slider.force.y, -500.0, 1e-12);
    assert_rel!(f.slider.force.x, 20.0, 1e-12);
    assert_eq!(f.slider.force, -f.guide.force);
    // Moment about the slider centre from the corner arms (±0.05, 0.01).
    let expected = cross(v(0.05, 0.01), v(10.0, -200.0)) + cross(v(-0.05, 0.01), v(10.0, -300.0));
    assert_rel!(f.slider.moment, expected, 1e-9);
}

#[test]
fn translational_rejects_bad_geometry() {
    let o = v(0.0, 0.0);
    assert!(TranslationalClearance::new(flat_slider(), 0.02, o, 0.0).is_err());
    assert!(TranslationalClearance::new(flat_slider(), -0.03, o, 0.0).is_err());
    assert!(TranslationalClearance::new(flat_slider(), 0.03, o, f64::NAN).is_err());
    let msg = TranslationalClearance::new(flat_slider(), 0.01, o, 0.0)
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("guide width") && msg.contains("slider height"),
        "{msg}"
    );
}

#[test]
fn translational_matches_multipoint_on_straight_guides() {
    // Independent code paths: corners of the translational joint vs the multipoint detector
    // against the two straight guide surfaces y = ±W/2 (corner candidates only).
    let joint = slider_joint();
    let ground = BodyState::default();
    let slider = BodyState::new(v(0.2, 0.02e-3), 3e-3, v(0.5, -0.02), 0.3);
    let tc = joint.contact(&ground, &slider);
    let shape = SliderShape::new(0.1, 0.02, v(0.0, 0.0), 0.0).unwrap();
    let upper = StraightGuide::new(ground, v(-1.0, 0.0101), 0.0, 2.0, false).unwrap();
    let lower = StraightGuide::new(ground, v(-1.0, -0.0101), 0.0, 2.0, true).unwrap();
    let mut det = MultipointDetector::new(shape, 0, 0).unwrap();
    let mut found = 0;
    for guide in [&upper as &dyn GuideSurface, &lower] {
        det.detect(guide, &slider);
        for p in det.points() {
            let PointSource::Corner(k) = p.source else {
                panic!("only corners are candidates")
            };
            let cc = tc.corners[k].expect("corner active in both");
            assert_rel!(p.contact.penetration, cc.contact.penetration, 1e-9);
            assert_rel!(p.contact.normal_velocity, cc.contact.normal_velocity, 1e-9);
            assert_rel!(
                p.contact.tangential_velocity,
                cc.contact.tangential_velocity,
                1e-9
            );
            found += 1;
        }
    }
    assert_eq!(found, tc.active().count());
    assert!(found >= 1);
}

// ---------------------------------------------------------------- multipoint (§7.8)

/// Slider of §7.8: length 0.1 m, height 0.02 m, bottom face at y = `bottom`, centred at x = 0.5.
fn hogging_setup(bottom: f64) -> (SliderShape, BodyState) {
    let shape = SliderShape::new(0.1, 0.02, v(0.0, 0.0), 0.0).unwrap();
    (shape, BodyState::fixed(v(0.5, bottom + 0.01), 0.0))
}

#[test]
fn multipoint_worked_example_penetrations() {
    // §7.8: 3 face points + corners sample x = 0.45 … 0.55; penetrations 7.534e-9, 3.767e-7,
    // 5.000e-7, 3.767e-7, 7.534e-9 m (4 digits → 1e-3 relative); the closed form
    // A sin(πx) − 39.5 µm to 1e-6 (the normal-direction correction is O(slope²) ≈ 1e-9).
    let guide = SineGuide::new(40e-6, 1.0).unwrap();
    let (shape, slider) = hogging_setup(39.5e-6);
    let mut det = MultipointDetector::new(shape, 3, 0).unwrap();
    let class = det.detect(&guide, &slider);
    let expected = [7.534e-9, 3.767e-7, 5.000e-7, 3.767e-7, 7.534e-9];
    let xs = [0.45, 0.475, 0.5, 0.525, 0.55];
    assert_eq!(det.points().len(), 5);
    for ((p, e), x) in det.points().iter().zip(expected).zip(xs) {
        assert_rel!(p.contact.penetration, e, 1e-3);
        let closed = 40e-6 * (std::f64::consts::PI * x).sin() - 39.5e-6;
        assert_rel!(p.contact.penetration, closed, 1e-6);
        assert_rel!(p.arc, x, 1e-6);
    }
    match class {
        ContactClass::Area { face, length } => {
            assert_eq!(face, 0);
            assert_rel!(length, 0.1, 1e-6);
        }
        other => panic!("expected area contact, got {other:?}"),
    }
}

#[test]
fn multipoint_reverse_check_finds_the_mid_face_penetration() {
    // §7.8: corner-only detection sees 7.5 nm; the reverse check from 5 guide samples over the
    // slider span finds the true 0.5 µm at mid-face.
    let guide = SineGuide::new(40e-6, 1.0).unwrap();
    let (shape, slider) = hogging_setup(39.5e-6);
    let max = |det: &MultipointDetector| {
        det.points()
            .iter()
            .map(|p| p.contact.penetration)
            .fold(0.0, f64::max)
    };
    let mut corners_only = MultipointDetector::new(shape, 0, 0).unwrap();
    corners_only.detect(&guide, &slider);
    assert_rel!(max(&corners_only), 7.534e-9, 1e-3);
    let mut with_reverse = MultipointDetector::new(shape, 0, 5).unwrap();
    with_reverse.detect(&guide, &slider);
    assert_rel!(max(&with_reverse), 5.000e-7, 1e-6);
    // Corners (2) + guide samples at 0.475, 0.5, 0.525 (the end samples duplicate the corners).
    assert_eq!(with_reverse.points().len(), 5);
    let samples = with_reverse
        .points()
        .iter()
        .filter(|p| matches!(p.source, PointSource::GuideSample(_)))
        .count();
    assert_eq!(samples, 3);
}

#[test]
fn multipoint_line_contact_in_the_middle_of_the_face() {
    // Bottom at 39.9 µm: only |x − 0.5| < acos(39.9/40)/π = 0.02251 m touches (closed form); a
    // 41-sample reverse check (spacing 2.5 mm) must see a line contact of that extent to within
    // one spacing, and the corners are free.
    let guide = SineGuide::new(40e-6, 1.0).unwrap();
    let (shape, slider) = hogging_setup(39.9e-6);
    let mut det = MultipointDetector::new(shape, 3, 41).unwrap();
    let half = (39.9_f64 / 40.0).acos() / std::f64::consts::PI;
    match det.detect(&guide, &slider) {
        ContactClass::Line { length } => {
            assert!(
                (length - 2.0 * half).abs() <= 2.0 * 2.5e-3,
                "{length} vs {}",
                2.0 * half
            )
        }
        other => panic!("expected line contact, got {other:?}"),
    }
    assert!(det
        .points()
        .iter()
        .all(|p| !matches!(p.source, PointSource::Corner(_))));
    // Tributary lengths of a contiguous region add up to its extent.
    let total: f64 = det.points().iter().map(|p| p.tributary_length).sum();
    let first = det.points().first().unwrap().arc;
    let last = det.points().last().unwrap().arc;
    assert_rel!(total, last - first, 1e-12);
}

#[test]
fn multipoint_flat_face_tributary_lengths_and_forces() {
    // Flat slider 5 µm into a straight horizontal guide: 5 bottom points, spacing 25 mm; the
    // corners carry 12.5 mm and the interior points 25 mm (sum = L = 0.1 m).
    let ground = BodyState::default();
    let guide = StraightGuide::new(ground, v(0.0, 0.0), 0.0, 1.0, true).unwrap();
    let shape = SliderShape::new(0.1, 0.02, v(0.0, 0.0), 0.0).unwrap();
    let slider = BodyState::new(v(0.4, 0.01 - 5e-6), 0.0, v(1.5, -0.02), 0.2);
    let mut det = MultipointDetector::new(shape, 3, 0).unwrap();
    assert!(matches!(
        det.detect(&guide, &slider),
        ContactClass::Area { face: 0, .. }
    ));
    let lengths: Vec<f64> = det.points().iter().map(|p| p.tributary_length).collect();
    for (l, e) in lengths.iter().zip([0.0125, 0.025, 0.025, 0.025, 0.0125]) {
        assert_rel!(*l, e, 1e-9);
    }
    for p in det.points() {
        assert_rel!(p.contact.penetration, 5e-6, 1e-6);
        // n = (0, −1): v_N = −(ṙ_P)_y = 0.02 − ω (P − r)_x; t = (1, 0): v_T = 1.5 − ω (P − r)_y.
        let r = p.contact.slider_point - slider.position;
        assert_rel!(p.contact.normal_velocity, 0.02 - 0.2 * r.x, 1e-9);
        assert_rel!(p.contact.tangential_velocity, 1.5 - 0.2 * r.y, 1e-9);
    }
    // A distributed law p(δ) = k δ per unit length times the tributary length: total k δ L;
    // friction −0.1 F_N along t = (1, 0).
    let k = 1e12;
    let q = det.apply_forces(|p| {
        let f_n = k * p.contact.penetration * p.tributary_length;
        (f_n, -0.1 * f_n)
    });
    assert_rel!(q.force.y, k * 5e-6 * 0.1, 1e-6);
    assert_rel!(q.force.x, -0.1 * k * 5e-6 * 0.1, 1e-6);
    let loads: Vector2<f64> = det.loads().iter().map(|l| l.force).sum();
    assert_rel!(loads.y, -q.force.y, 1e-12);
    // Moment about the slider reference, summed independently from the slider contact points
    // and the guide loads (each the opposite of the force on the slider).
    let m: f64 = det
        .points()
        .iter()
        .zip(det.loads())
        .map(|(p, l)| cross(p.contact.slider_point - slider.position, -l.force))
        .sum();
    assert!(
        (q.moment - m).abs() <= 1e-12 * q.force.norm(),
        "{} vs {m}",
        q.moment
    );
    // Closed form: arms (x_i, −h/2) with Σ x_i f_y = 0 (uniform load centred under the
    // reference point), so m = (h/2)·Σ f_x; exact up to the δ-sized change of the arms.
    assert_rel!(q.moment, 0.01 * q.force.x, 1e-3);
}

#[test]
fn multipoint_ignores_points_beyond_the_guide_end() {
    // Slider centred on the end x = 1 of a straight guide on [0, 1]: the corners and face points
    // past x = 1 are not over the guide; those over it are.
    let ground = BodyState::default();
    let guide = StraightGuide::new(ground, v(0.0, 0.0), 0.0, 1.0, true).unwrap();
    let shape = SliderShape::new(0.1, 0.02, v(0.0, 0.0), 0.0).unwrap();
    let slider = BodyState::fixed(v(1.0, 0.01 - 1e-6), 0.0);
    let mut det = MultipointDetector::new(shape, 3, 0).unwrap();
    det.detect(&guide, &slider);
    assert!(det
        .points()
        .iter()
        .all(|p| p.contact.slider_point.x <= 1.0 + 1e-12));
    // Corner 0 (x = 0.95), face points at 0.975 and 1.0 are over the guide.
    assert_eq!(det.points().len(), 3);
}

/// A flat slider 5 µm into a straight guide on [0, 1] slides off its end (clr issue 29). Closed
/// forms, with the bottom face over [x_l, x_r] = [x_c − L/2, x_c + L/2] and its 5 candidates at
/// x_k = x_l + k L/4:
///
/// - a distributed law p = k δ per unit length has the total force k δ o, o = the overlap
///   length clamp(1 − x_l, 0, L) of the face with the guide: Σ l_i δ_i = δ o (the clipped
///   profile is flat, so the lumping is exact; tolerance 1e-9 relative to δ L);
/// - a point law weighted by `over_guide` gives candidate k the fraction of its share
///   [x_k − L/8, x_k + L/8] ∩ [x_l, x_r] of the face that lies at x ≤ 1 (tolerance 1e-9);
/// - both are continuous: across each crossing of a candidate (x_k = 1 ± 1e-9 m) the totals
///   move by less than 1e-6 of their scale, where before the clipping a corner's share (L/8 of
///   the area force, one whole point of the point law) dropped out.
#[test]
fn multipoint_force_leaves_continuously_past_the_guide_end() {
    let ground = BodyState::default();
    let guide = StraightGuide::new(ground, v(0.0, 0.0), 0.0, 1.0, true).unwrap();
    let (l, h, depth) = (0.1, 0.02, 5e-6);
    let shape = SliderShape::new(l, h, v(0.0, 0.0), 0.0).unwrap();
    let mut det = MultipointDetector::new(shape, 3, 0).unwrap();
    // bottom-face candidates in order along x: corner 0, face points 4, 5, 6, corner 1
    let ids = [0usize, 4, 5, 6, 1];
    let totals = |det: &mut MultipointDetector, xc: f64| {
        det.detect(&guide, &BodyState::fixed(v(xc, 0.5 * h - depth), 0.0));
        let wetted: f64 = det
            .points()
            .iter()
            .map(|p| p.tributary_length * p.contact.penetration)
            .sum();
        let weights: f64 = det.points().iter().map(|p| p.over_guide).sum();
        (wetted, weights)
    };
    let sp = 0.25 * l;
    let mut xc = 0.9;
    while xc < 1.0 + 0.5 * l + 0.01 {
        let xl = xc - 0.5 * l;
        let (wetted, _) = totals(&mut det, xc);
        let overlap = (1.0 - xl).clamp(0.0, l);
        assert!(
            (wetted - depth * overlap).abs() <= 1e-9 * depth * l,
            "x_c = {xc}: Σ l δ = {wetted:e}, closed form {:e}",
            depth * overlap
        );
        for (k, &id) in ids.iter().enumerate() {
            let xk = xl + k as f64 * sp;
            let (lo, hi) = ((xk - 0.5 * sp).max(xl), (xk + 0.5 * sp).min(xl + l));
            let expected = ((hi.min(1.0) - lo) / (hi - lo)).clamp(0.0, 1.0);
            let got = det
                .points()
                .iter()
                .find(|p| p.id == id)
                .map_or(0.0, |p| p.over_guide);
            assert!(
                (got - expected).abs() <= 1e-9,
                "x_c = {xc}, candidate {id} at x = {xk}: weight {got}, closed form {expected}"
            );
        }
        assert!(det
            .points()
            .iter()
            .all(|p| p.contact.slider_point.x <= 1.0 + 1e-12 && p.arc <= 1.0));
        xc += 0.00137;
    }
    // continuity across each candidate's crossing of the end
    for k in 0..5 {
        let crossing = 1.0 + 0.5 * l - k as f64 * sp;
        let (a, wa) = totals(&mut det, crossing - 1e-9);
        let (b, wb) = totals(&mut det, crossing + 1e-9);
        assert!(
            (a - b).abs() <= 1e-6 * depth * l,
            "Σ l δ {a:e} → {b:e} at {k}"
        );
        assert!((wa - wb).abs() <= 1e-6, "Σ weights {wa} → {wb} at {k}");
    }
}

#[test]
fn multipoint_buffers_are_reused() {
    // No allocation after construction: the output buffers keep their address and capacity.
    let guide = SineGuide::new(40e-6, 1.0).unwrap();
    let (shape, slider) = hogging_setup(39.5e-6);
    let mut det = MultipointDetector::new(shape, 3, 11).unwrap();
    det.detect(&guide, &slider);
    det.apply_forces(|_| (1.0, 0.0));
    let (p0, l0) = (det.points().as_ptr(), det.loads().as_ptr());
    for k in 0..20 {
        let s = BodyState::fixed(v(0.5 + 1e-3 * k as f64, 39.5e-6 + 0.01), 1e-6 * k as f64);
        det.detect(&guide, &s);
        det.apply_forces(|_| (1.0, 0.0));
        assert_eq!(det.points().as_ptr(), p0);
        assert_eq!(det.loads().as_ptr(), l0);
    }
}

#[test]
fn multipoint_rejects_bad_slider() {
    let o = v(0.0, 0.0);
    assert!(SliderShape::new(0.0, 0.02, o, 0.0).is_err());
    assert!(SliderShape::new(0.1, -0.02, o, 0.0).is_err());
    assert!(SliderShape::new(0.1, 0.02, o, f64::NAN).is_err());
    assert!(StraightGuide::new(BodyState::default(), o, 0.0, 0.0, true).is_err());
}

#[test]
fn multipoint_uses_the_guide_velocity() {
    // Guide and slider carried by the same rigid motion (translation + rotation about the
    // guide body's reference point): v_N = 0 and v_T = ω δ (closed form); the reverse-check
    // samples add nothing on a straight guide under a flat face.
    let (vel, omega) = (v(0.7, -0.3), 2.0);
    let guide_body = BodyState::new(v(0.1, 0.2), 0.3, vel, omega);
    let guide = StraightGuide::new(guide_body, v(0.0, 0.0), 0.0, 1.0, true).unwrap();
    let shape = SliderShape::new(0.1, 0.02, v(0.0, 0.0), 0.0).unwrap();
    // Slider centre 0.4 m along the guide, 5 µm into it, same orientation.
    let centre = guide_body.point(v(0.4, 0.01 - 5e-6));
    let slider = BodyState::new(centre, 0.3, guide_body.point_velocity(centre), omega);
    let mut det = MultipointDetector::new(shape, 3, 7).unwrap();
    det.detect(&guide, &slider);
    assert_eq!(det.points().len(), 5);
    for p in det.points() {
        assert_rel!(p.contact.penetration, 5e-6, 1e-6);
        assert!(p.contact.normal_velocity.abs() < 1e-12);
        // The contact points differ by δ n, so the common rotation leaves v_T = ω δ.
        assert_rel!(p.contact.tangential_velocity, omega * 5e-6, 1e-6);
    }
}

#[test]
fn multipoint_wetted_length_of_a_tilted_face_is_the_exact_wedge_integral() {
    // Closed form: a flat face tilted by φ on a straight guide, its lowest corner δ_c deep, has
    // the linear penetration profile δ(s) = δ_c − s·tan φ (s from the corner along the guide),
    // so ∫ max(δ, 0) ds = δ_c²/(2 tan φ) while the wedge is shorter than the face, and
    // L·(δ_c − L tan φ / 2) once the whole face touches. The lumped Σ l_i δ_i must equal it
    // (tolerance 1e-5 relative: the interpolant is exact for a linear profile; the end face's
    // own wedge at the corner adds ½ φ δ_c², i.e. φ² = 4e-6 of the total at φ = 2e-3), and it must be
    // continuous as the face turns flat (no jump at the line → area class change).
    let ground = BodyState::default();
    let guide = StraightGuide::new(ground, v(0.0, 0.0), 0.0, 1.0, true).unwrap();
    let (l, h) = (0.06, 0.01);
    let shape = SliderShape::new(l, h, v(0.0, 0.0), 0.0).unwrap();
    let mut det = MultipointDetector::new(shape, 3, 0).unwrap();
    let dc = 1e-5;
    let integral = |det: &MultipointDetector| -> f64 {
        det.points()
            .iter()
            .map(|p| p.tributary_length * p.contact.penetration)
            .sum()
    };
    let mut previous: Option<f64> = None;
    for phi in [2e-3, 1e-3, 5e-4, 3.4e-4, 3.3e-4, 2e-4, 1e-4, 1e-6, 0.0] {
        // bottom-left corner (−L/2, −h/2) at depth δ_c, face rising to the right by φ
        let (sn, cs) = (f64::sin(phi), f64::cos(phi));
        let corner = v(-0.5 * l * cs + 0.5 * h * sn, -0.5 * l * sn - 0.5 * h * cs);
        let centre = v(0.4, -dc) - corner;
        let slider = BodyState::new(centre, phi, v(0.0, 0.0), 0.0);
        det.detect(&guide, &slider);
        let t = phi.tan();
        // arc length of the face projected on the guide: L cos φ
        let span = l * cs;
        let expected = if t > 0.0 && dc / t < span {
            dc * dc / (2.0 * t)
        } else {
            span * (dc - 0.5 * span * t)
        };
        let got = integral(&det);
        assert_rel!(got, expected, 1e-5);
        if let Some(p) = previous {
            // the profile changes little between neighbouring tilts: no jump
            assert!(
                (got - p).abs() <= 0.6 * got.max(p),
                "{p} → {got} at φ = {phi}"
            );
        }
        previous = Some(got);
    }
}

/// `tributary_partials` chains to the derivative of every active point's wetted length: on a
/// face tilted by 0.2 mrad with its lowest corner 10 µm into a straight guide (a partial wedge:
/// active and separated candidates on one face), the central difference of each length under
/// a move of the slider (x, y, θ) equals Σ ∂l/∂s*·Δs* + ∂l/∂gap·Δgap over the candidates'
/// projections moved the same way (tolerance 1e-6 of the largest length change: the lengths are
/// rational in the gaps, step 1e-9 m or rad, truncation ~(1e-9/1e-6)² relative).
#[test]
fn multipoint_tributary_partials_match_central_differences() {
    let ground = BodyState::default();
    let guide = StraightGuide::new(ground, v(0.0, 0.0), 0.0, 1.0, true).unwrap();
    let (l, h, phi, dc) = (0.06, 0.01, 2e-4, 1e-5);
    let shape = SliderShape::new(l, h, v(0.0, 0.0), 0.0).unwrap();
    let mut det = MultipointDetector::new(shape, 3, 0).unwrap();
    let (sn, cs) = (f64::sin(phi), f64::cos(phi));
    let corner = v(-0.5 * l * cs + 0.5 * h * sn, -0.5 * l * sn - 0.5 * h * cs);
    let x0 = [0.4 - corner.x, -dc - corner.y, phi];
    let at = |det: &mut MultipointDetector, x: [f64; 3]| {
        det.detect(&guide, &BodyState::fixed(v(x[0], x[1]), x[2]));
        let n = det.candidate_count();
        let proj: Vec<(f64, f64)> = (0..n)
            .map(|c| det.projection(c).map(|p| (p.0, p.1)).unwrap())
            .collect();
        let lengths: Vec<(usize, f64)> = det
            .points()
            .iter()
            .map(|p| (p.id, p.tributary_length))
            .collect();
        (proj, lengths)
    };
    let (_, base) = at(&mut det, x0);
    let active = base.len();
    assert!(
        active >= 2 && active < det.candidate_count(),
        "a partial wedge: {base:?}"
    );
    let hstep = 1e-9;
    for dir in 0..3 {
        let (mut xp, mut xm) = (x0, x0);
        xp[dir] += hstep;
        xm[dir] -= hstep;
        let (pp, lp) = at(&mut det, xp);
        let (pm, lm) = at(&mut det, xm);
        at(&mut det, x0);
        let scale = lp
            .iter()
            .zip(&lm)
            .map(|(a, b)| (a.1 - b.1).abs())
            .fold(1e-30, f64::max);
        for (k, &(id, _)) in base.iter().enumerate() {
            assert_eq!((lp[k].0, lm[k].0), (id, id), "same active set");
            let fd = lp[k].1 - lm[k].1;
            let mut chained = 0.0;
            assert!(det.tributary_partials(id, |c, dl_ds, dl_dg| {
                chained += dl_ds * (pp[c].0 - pm[c].0) + dl_dg * (pp[c].1 - pm[c].1);
            }));
            assert!(
                (chained - fd).abs() <= 1e-6 * scale,
                "dir {dir} id {id}: {chained} vs {fd}"
            );
        }
    }
}
