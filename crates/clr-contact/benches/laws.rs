//! Cost of one normal-force and one friction evaluation (ns/call), `cargo bench -p clr-contact`.
//!
//! Each iteration evaluates the law at 64 states spread over compression and restitution, so the
//! figure per call is the reported time / 64. Inputs go through `black_box` so nothing is folded.

use std::hint::black_box;

use clr_contact::damping::DampingFactor;
use clr_contact::elastic::ElasticLaw;
use clr_contact::friction::{FrictionLaw, LuGre};
use clr_contact::normal::{JournalBearing, NormalLaw};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};

const N: usize = 64;

fn states() -> Vec<(f64, f64)> {
    (0..N)
        .map(|i| {
            let s = i as f64 / N as f64;
            (
                20e-6 * (std::f64::consts::PI * s).sin(),
                0.5 * (std::f64::consts::PI * s).cos(),
            )
        })
        .collect()
}

fn normal_laws(c: &mut Criterion) {
    let jb = JournalBearing::flap_paper_test();
    let e_star = jb.bearing.composite_modulus(&jb.journal);
    let dr = jb.clearance();
    let laws = [
        ("hertz-ln", NormalLaw::preset("LN", &jb, 0.5).unwrap()),
        (
            "liu-gonthier",
            NormalLaw::preset("Modified", &jb, 0.5).unwrap(),
        ),
        ("bai-zhao-zq", NormalLaw::preset("Bai", &jb, 0.5).unwrap()),
        (
            "pereira-ln",
            NormalLaw::new(
                ElasticLaw::pereira_internal(e_star, dr, jb.length).unwrap(),
                DampingFactor::LankaraniNikravesh,
                0.5,
            )
            .unwrap(),
        ),
        (
            "johnson-exact",
            NormalLaw::new(
                ElasticLaw::johnson(e_star, dr, jb.length).unwrap(),
                DampingFactor::Exact,
                0.5,
            )
            .unwrap(),
        ),
    ];
    let xs = states();
    let mut g = c.benchmark_group("normal_force");
    g.throughput(Throughput::Elements(N as u64));
    for (name, law) in laws {
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &(d, v) in &xs {
                    acc += black_box(&law).force(black_box(d), black_box(v), 0.5);
                }
                acc
            })
        });
    }
    g.finish();
}

fn friction_laws(c: &mut Criterion) {
    let laws = [
        ("coulomb", FrictionLaw::coulomb(0.1, 1e-4).unwrap()),
        ("ambrosio", FrictionLaw::ambrosio(0.1, 1e-4, 1e-3).unwrap()),
        ("threlfall", FrictionLaw::threlfall(0.1, 1e-2).unwrap()),
        (
            "stribeck",
            FrictionLaw::stribeck(0.2, 0.1, 0.01, 0.1).unwrap(),
        ),
    ];
    let vs: Vec<f64> = (0..N).map(|i| (i as f64 - 32.0) * 4e-3).collect();
    let mut g = c.benchmark_group("friction_force");
    g.throughput(Throughput::Elements(N as u64));
    for (name, law) in laws {
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &v in &vs {
                    acc += black_box(&law).force(black_box(v), 1000.0);
                }
                acc
            })
        });
    }
    let lugre = LuGre::new(1e5, 300.0, 0.0, 0.2, 0.1, 0.01).unwrap();
    g.bench_function("lugre", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &v in &vs {
                let z = black_box(1e-6);
                let zd = lugre.z_dot(black_box(v), z);
                acc += lugre.force(v, z, zd, 1000.0);
            }
            acc
        })
    });
    g.finish();
}

criterion_group!(benches, normal_laws, friction_laws);
criterion_main!(benches);
