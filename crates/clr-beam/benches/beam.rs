//! Benchmarks of clr-beam: assembly (sparse and dense) and the lowest 10 modes of a clamped
//! steel strip for 10, 100 and 1000 elements. Run with `cargo bench -p clr-beam`.

use std::hint::black_box;
use std::time::Duration;

use clr_beam::{BeamModel, Material, Section, Support};
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

fn cantilever(n: usize) -> BeamModel {
    let sec = Section::rectangular(0.02, 0.01).expect("valid section");
    let mut b =
        BeamModel::straight([0.0, 0.0], [1.0, 0.0], n, Material::steel(), sec).expect("valid beam");
    b.support(0, Support::Clamped).expect("node 0 exists");
    b
}

fn assembly(c: &mut Criterion) {
    let mut g = c.benchmark_group("beam_assembly");
    for n in [10, 100, 1000] {
        let b = cantilever(n);
        g.bench_with_input(BenchmarkId::new("sparse_K_and_M", n), &b, |bench, b| {
            bench.iter(|| {
                let k = b.stiffness_sparse().expect("assembles");
                let m = b.mass_sparse().expect("assembles");
                black_box((k, m))
            })
        });
        g.bench_with_input(BenchmarkId::new("dense_K_and_M", n), &b, |bench, b| {
            bench.iter(|| {
                let k = b.stiffness_dense().expect("assembles");
                let m = b.mass_dense().expect("assembles");
                black_box((k, m))
            })
        });
    }
    g.finish();
}

fn modes(c: &mut Criterion) {
    let mut g = c.benchmark_group("beam_lowest_10_modes");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    for n in [10, 100, 1000] {
        let b = cantilever(n);
        g.bench_with_input(BenchmarkId::from_parameter(n), &b, |bench, b| {
            bench.iter(|| black_box(b.modes(10).expect("modes")))
        });
    }
    g.finish();
}

fn queries(c: &mut Criterion) {
    let mut g = c.benchmark_group("beam_query_point");
    for n in [10, 100, 1000] {
        let b = cantilever(n);
        let path = b.path().expect("path");
        let q: Vec<f64> = (0..b.n_dof()).map(|i| 1e-4 * (i as f64).sin()).collect();
        g.bench_with_input(BenchmarkId::from_parameter(n), &q, |bench, q| {
            let mut s = 0.0;
            bench.iter(|| {
                s = (s + 0.618_034) % 1.0;
                black_box(path.point(s, q, q).expect("inside"))
            })
        });
    }
    g.finish();
}

criterion_group!(benches, assembly, modes, queries);
criterion_main!(benches);
