//! Boolean benchmarks. Medians on a shared 2-core machine are noisy: compare ratios measured
//! in one session (`tools/speed_table.sh` runs manifold3d on the same inputs, interleaved).
//! The `closed_mesh` group times what a user gets, the boolean and its closed 2-manifold mesh,
//! on the cases of `docs/performance.md` (the real models with `BSPCSG_MODELS` set).

use bspcsg::{BoolOp, Solid, boolean, read_mesh};
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

/// Boolean + `to_mesh`, the time `docs/performance.md` compares with manifold3d.
fn closed_mesh(c: &mut Criterion) {
    let mut group = c.benchmark_group("closed_mesh");
    group.sample_size(10);
    let (a, b) = cases::sphere_pair(256);
    group.bench_function("sphere_256x128_union", |bench| {
        bench.iter(|| (&a | &b).to_mesh())
    });
    let cube = Solid::cube(2.0).unwrap();
    let sphere = Solid::sphere(1.0, 128, 64).unwrap();
    group.bench_function("cube_minus_sphere_128x64", |bench| {
        bench.iter(|| (&cube - &sphere).to_mesh())
    });
    match std::env::var_os("BSPCSG_MODELS") {
        Some(dir) => {
            for (name, offset, op) in [
                ("fandisk", DVec3::new(0.5, 0.5, 0.25), BoolOp::Difference),
                ("rocker-arm", DVec3::new(0.05, 0.02, 0.01), BoolOp::Union),
                ("spot", DVec3::new(0.3, 0.1, 0.2), BoolOp::Union),
            ] {
                let path = std::path::Path::new(&dir).join(format!("{name}.obj"));
                let a = Solid::from_mesh(&read_mesh(&path).unwrap()).unwrap();
                let b = a.clone().translate(offset).unwrap();
                group.bench_function(format!("{name}_{op}_moved"), |bench| {
                    bench.iter(|| boolean(&a, &b, op).to_mesh())
                });
            }
        }
        None => eprintln!("BSPCSG_MODELS is not set: the real-model cases are skipped"),
    }
    group.finish();
}

criterion_group!(benches, sphere_union, mixed, closed_mesh);
criterion_main!(benches);
