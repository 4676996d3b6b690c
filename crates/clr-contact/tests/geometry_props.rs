//! Property tests of the joint kinematics: action–reaction (the net force of a joint on its two
//! bodies is zero), the moment balance about the world origin, no force without penetration,
//! and finite outputs for every finite state.

use clr_contact::body::{cross, BodyState};
use clr_contact::multipoint::{MultipointDetector, SliderShape, StraightGuide};
use clr_contact::revolute::RevoluteClearance;
use clr_contact::translational::TranslationalClearance;
use nalgebra::Vector2;
use proptest::prelude::*;

fn body() -> impl Strategy<Value = BodyState> {
    (
        -0.01..0.01f64,
        -0.01..0.01f64,
        -3.2..3.2f64,
        -2.0..2.0f64,
        -2.0..2.0f64,
        -50.0..50.0f64,
    )
        .prop_map(|(x, y, a, vx, vy, w)| {
            BodyState::new(Vector2::new(x, y), a, Vector2::new(vx, vy), w)
        })
}

fn local() -> impl Strategy<Value = Vector2<f64>> {
    (-0.01..0.01f64, -0.01..0.01f64).prop_map(|(x, y)| Vector2::new(x, y))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn revolute_action_reaction_and_no_force_without_penetration(
        bi in body(), bj in body(), si in local(), sj in local(),
        f_n in 0.0..1e5f64, f_t in -1e4..1e4f64,
    ) {
        let joint = RevoluteClearance::new(10e-3, 9.9e-3, si, sj).unwrap();
        let c = joint.contact(&bi, &bj);
        prop_assert!(c.penetration.is_finite() && c.normal_velocity.is_finite()
            && c.tangential_velocity.is_finite());
        let f = c.generalized_forces(f_n, f_t);
        let net = f.bearing.force + f.journal.force;
        prop_assert!(net.norm() <= 1e-12 * (f_n + f_t.abs()));
        if c.penetration <= 0.0 {
            prop_assert_eq!(f.journal.force, Vector2::zeros());
            prop_assert_eq!(f.bearing.moment, 0.0);
        } else {
            // Total moment about the world origin: the two forces act at points δ n apart, so
            // Σ (m_k + r_k × f_k) = (Q_j − Q_i) × f_j = δ F_T (closed form, §3.1).
            let total = f.bearing.moment + cross(bi.position, f.bearing.force)
                + f.journal.moment + cross(bj.position, f.journal.force);
            let scale = 0.02 * (f_n + f_t.abs());
            prop_assert!((total - c.penetration * f_t).abs() <= 1e-9 * scale,
                "{total} vs {}", c.penetration * f_t);
        }
    }

    #[test]
    fn translational_action_reaction_and_penetration_sign(
        x in -0.5..0.5f64, y in -2e-4..2e-4f64, a in -5e-3..5e-3f64,
        vx in -2.0..2.0f64, vy in -0.1..0.1f64, w in -5.0..5.0f64,
        f_n in 0.0..1e4f64, f_t in -1e3..1e3f64,
    ) {
        let joint = TranslationalClearance::new(
            SliderShape::new(0.1, 0.02, Vector2::zeros(), 0.0).unwrap(), 0.0202, Vector2::zeros(),
            0.0).unwrap();
        let slider = BodyState::new(Vector2::new(x, y), a, Vector2::new(vx, vy), w);
        let c = joint.contact(&BodyState::default(), &slider);
        for cc in c.active() {
            prop_assert!(cc.contact.penetration > 0.0);
        }
        let f = c.generalized_forces(|_| (f_n, f_t));
        prop_assert!((f.slider.force + f.guide.force).norm() <= 1e-12 * 4.0 * (f_n + f_t.abs()));
        if c.active().count() == 0 {
            prop_assert_eq!(f.slider.force, Vector2::zeros());
        }
    }

    #[test]
    fn multipoint_forces_balance_and_vanish_without_penetration(
        x in 0.1..0.9f64, y in -5e-6..5e-6f64, a in -1e-4..1e-4f64,
        vx in -2.0..2.0f64, vy in -0.1..0.1f64, w in -5.0..5.0f64,
    ) {
        let guide = StraightGuide::new(BodyState::default(), Vector2::zeros(), 0.0, 1.0, true)
            .unwrap();
        let shape = SliderShape::new(0.1, 0.02, Vector2::zeros(), 0.0).unwrap();
        let mut det = MultipointDetector::new(shape, 3, 9).unwrap();
        let slider = BodyState::new(Vector2::new(x, 0.01 + y), a, Vector2::new(vx, vy), w);
        det.detect(&guide, &slider);
        for p in det.points() {
            prop_assert!(p.contact.penetration > 0.0);
            // Closed form on the straight guide y = 0: δ = −y of the slider point (to rounding).
            prop_assert!((p.contact.penetration + p.contact.slider_point.y).abs() <= 1e-12);
        }
        let q = det.apply_forces(|p| (1e9 * p.contact.penetration, -0.1 * 1e9 * p.contact.penetration));
        let loads: Vector2<f64> = det.loads().iter().map(|l| l.force).sum();
        prop_assert!((q.force + loads).norm() <= 1e-12 * (1.0 + q.force.norm()));
        if det.points().is_empty() {
            prop_assert_eq!(q.force, Vector2::zeros());
            prop_assert_eq!(q.moment, 0.0);
        }
    }
}
