//! Boolean benchmarks. Medians on a shared 2-core machine are noisy: compare ratios measured
//! in one session (e.g. against `../shared/bench/manifold_reference.py`).

use bspcsg::Solid;
use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;

#[path = "common/cases.rs"]
mod cases;

fn sphere_union(c: &mut Criterion) {
    let mut group = c.benchmark_group("sphere_union");
    group.sample_size(20);
    for segments in [32u32, 64, 128, 256] {
        let (a, b) = cases::sphere_pair(segments);
        group.bench_function(format!("{segments}x{}", segments / 2), |bench| {
            bench.iter(|| &a | &b)
        });
    }
    // The same with the closed 2-manifold mesh made from the result.
    let (a, b) = cases::sphere_pair(128);
    group.bench_function("128x64_to_mesh", |bench| bench.iter(|| (&a | &b).to_mesh()));
    group.finish();
}

fn mixed(c: &mut Criterion) {
    let mut group = c.benchmark_group("mixed");
    group.sample_size(20);
    let cube = Solid::cube(1.6).unwrap();
    let sphere = Solid::sphere(1.0, 64, 32).unwrap();
    group.bench_function("cube_minus_sphere_64x32", |b| b.iter(|| &cube - &sphere));
    let (a, b) = cases::sphere_pair(64);
    let b = b.rotate_euler(DVec3::new(0.0, 0.0, 30.0)).unwrap();
    group.bench_function("sphere_intersect_sphere_64x32", |bench| {
        bench.iter(|| &a & &b)
    });
    let (block, holes) = cases::block_and_holes(32);
    group.bench_function("block_minus_10x10_cylinders", |b| {
        b.iter(|| &block - &holes)
    });
    group.bench_function("block_minus_10x10_cylinders_with_union", |b| {
        b.iter(|| {
            let (block, holes) = cases::block_and_holes(32);
            block - holes
        })
    });
    group.sample_size(10);
    group.bench_function("menger_sponge_depth_3", |b| {
        b.iter(|| cases::menger_sponge(3))
    });
    group.finish();
}

criterion_group!(benches, sphere_union, mixed);
criterion_main!(benches);
