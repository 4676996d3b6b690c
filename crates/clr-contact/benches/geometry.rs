//! Cost of the clearance-joint kinematics, `cargo bench -p clr-contact --bench geometry`:
//! one revolute contact evaluation with laws (ns/call), one translational corner evaluation, and
//! one multipoint detection of the §7.8 slider (corners + 3 points per face + 21 guide samples)
//! on a hogging sine guide, warm started as in a time-stepping loop; and one spatial shape
//! contact query (`shapes3d`) per pair kind: ball on a box (exact path), box on a box (four
//! corners), cylinder end on a box (polygonal features and GJK), ball on a 2-triangle mesh.

use std::hint::black_box;

use clr_contact::body::{BodyState, Vector2};
use clr_contact::friction::FrictionLaw;
use clr_contact::multipoint::{MultipointDetector, SineGuide, SliderShape};
use clr_contact::normal::{JournalBearing, NormalLaw};
use clr_contact::revolute::RevoluteClearance;
use clr_contact::shapes3d::{
    contact_points3, BodyState3, ContactShape3, Shape3, ShapeContactWorkspace3,
};
use clr_contact::translational::TranslationalClearance;
use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{UnitQuaternion, Vector3};

fn revolute(c: &mut Criterion) {
    let jb = JournalBearing::flap_paper_test();
    let law = NormalLaw::preset("LN", &jb, 0.5).unwrap();
    let friction = FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap();
    let joint = RevoluteClearance::new(10e-3, 9.9e-3, Vector2::zeros(), Vector2::zeros()).unwrap();
    let bearing = BodyState::default();
    let journal = BodyState::new(
        0.11e-3 * Vector2::new(0.6, 0.8),
        0.3,
        Vector2::new(0.3, 0.4),
        10.0,
    );
    c.bench_function("revolute contact + L-N + Ambrosio", |b| {
        b.iter(|| {
            black_box(&joint)
                .contact(black_box(&bearing), black_box(&journal))
                .forces_from_laws(&law, &friction, 0.5)
        })
    });
}

fn translational(c: &mut Criterion) {
    let shape = SliderShape::new(0.1, 0.02, Vector2::zeros(), 0.0).unwrap();
    let joint = TranslationalClearance::new(shape, 0.0202, Vector2::zeros(), 0.0).unwrap();
    let guide = BodyState::default();
    let slider = BodyState::new(
        Vector2::new(0.2, 0.02e-3),
        3e-3,
        Vector2::new(0.5, -0.02),
        0.3,
    );
    c.bench_function("translational corners + forces", |b| {
        b.iter(|| {
            black_box(&joint)
                .contact(black_box(&guide), black_box(&slider))
                .generalized_forces(|p| (1e9 * p.contact.penetration, 0.0))
        })
    });
}

fn multipoint(c: &mut Criterion) {
    let guide = SineGuide::new(40e-6, 1.0).unwrap();
    let shape = SliderShape::new(0.1, 0.02, Vector2::zeros(), 0.0).unwrap();
    let mut det = MultipointDetector::new(shape, 3, 21).unwrap();
    let mut k = 0u64;
    c.bench_function(
        "multipoint detect + forces (16 candidates, 21 samples)",
        |b| {
            b.iter(|| {
                // Small motion between calls, as between time steps (warm start).
                k += 1;
                let x = 0.5 + 1e-6 * (k % 100) as f64;
                let slider = BodyState::fixed(Vector2::new(x, 39.5e-6 + 0.01), 0.0);
                det.detect(&guide, black_box(&slider));
                black_box(det.apply_forces(|p| (1e9 * p.contact.penetration, 0.0)))
            })
        },
    );
}

fn shapes3d(c: &mut Criterion) {
    let floor = ContactShape3::new(Shape3::cuboid(1.0, 1.0, 0.1).unwrap()).unwrap();
    let mesh = Shape3::trimesh(
        vec![
            [-1.0, -1.0, 0.1],
            [1.0, -1.0, 0.1],
            [1.0, 1.0, 0.1],
            [-1.0, 1.0, 0.1],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let mesh = ContactShape3::new(mesh.unwrap()).unwrap();
    let ground = BodyState3::default();
    // B resting 0.1 mm deep on the top face z = 0.1, slightly turned.
    let rest = |half_height: f64, rv: Vector3<f64>| {
        BodyState3::fixed(
            Vector3::new(0.1, -0.05, 0.1 + half_height - 1e-4),
            UnitQuaternion::from_scaled_axis(rv),
        )
    };
    let upright = Vector3::new(0.0, -std::f64::consts::FRAC_PI_2, 0.0);
    let cases = [
        (
            "ball on box",
            &floor,
            Shape3::ball(0.02),
            rest(0.02, Vector3::zeros()),
        ),
        (
            "box on box",
            &floor,
            Shape3::cuboid(0.04, 0.03, 0.02),
            rest(0.02, Vector3::new(0.0, 0.0, 0.3)),
        ),
        (
            "cylinder end on box",
            &floor,
            Shape3::cylinder(0.02, 0.03),
            rest(0.02, upright),
        ),
        (
            "ball on trimesh",
            &mesh,
            Shape3::ball(0.02),
            rest(0.02, Vector3::zeros()),
        ),
    ];
    for (name, a, b, pose) in cases {
        let b = ContactShape3::new(b.unwrap()).unwrap();
        let mut ws = ShapeContactWorkspace3::new();
        c.bench_function(&format!("shapes3d {name}"), |bch| {
            bch.iter(|| {
                contact_points3(a, &ground, black_box(&b), black_box(&pose), 1e-3, &mut ws)
                    .unwrap()
                    .len()
            })
        });
    }
}

criterion_group!(benches, revolute, translational, multipoint, shapes3d);
criterion_main!(benches);
