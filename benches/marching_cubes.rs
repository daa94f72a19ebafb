//! Marching-cubes baking: the issue's targets are a sphere at 256³ cells and the mechanical
//! example at 128³, each under 100 ms on the 2-core machine.

use std::hint::black_box;

use bspcsg::{BakeOptions, Scene};
use criterion::{Criterion, criterion_group, criterion_main};

fn bench(c: &mut Criterion) {
    let sphere = Scene::from_json_str(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#,
    )
    .expect("sphere scene");
    let part = Scene::from_path(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/mechanical_part.json"
    ))
    .expect("mechanical example");
    let organic = Scene::from_path(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/organic_blend.json"
    ))
    .expect("organic example");
    let mut g = c.benchmark_group("bake");
    g.sample_size(20);
    g.bench_function("sphere_256", |b| {
        b.iter(|| black_box(&sphere).bake(&BakeOptions::with_resolution(256)))
    });
    g.bench_function("mechanical_128", |b| {
        b.iter(|| black_box(&part).bake(&BakeOptions::with_resolution(128)))
    });
    g.bench_function("organic_128", |b| {
        b.iter(|| black_box(&organic).bake(&BakeOptions::with_resolution(128)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
