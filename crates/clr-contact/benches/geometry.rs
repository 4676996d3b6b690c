//! Cost of the clearance-joint kinematics, `cargo bench -p clr-contact --bench geometry`:
//! one revolute contact evaluation with laws (ns/call), one translational corner evaluation, and
//! one multipoint detection of the §7.8 slider (corners + 3 points per face + 21 guide samples)
//! on a hogging sine guide, warm started as in a time-stepping loop.

use std::hint::black_box;

use clr_contact::body::{BodyState, Vector2};
use clr_contact::friction::FrictionLaw;
use clr_contact::multipoint::{MultipointDetector, SineGuide, SliderShape};
use clr_contact::normal::{JournalBearing, NormalLaw};
use clr_contact::revolute::RevoluteClearance;
use clr_contact::translational::TranslationalClearance;
use criterion::{criterion_group, criterion_main, Criterion};

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

criterion_group!(benches, revolute, translational, multipoint);
criterion_main!(benches);
