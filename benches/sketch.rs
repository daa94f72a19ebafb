//! 2D boolean benchmarks: two 10,000-vertex random star polygons, 1,000 circles united, and a
//! plate drilled with 400 holes one at a time.

use bspcsg::Sketch;
use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec2;

#[path = "common/sketch_cases.rs"]
mod cases;

fn stars(c: &mut Criterion) {
    let mut group = c.benchmark_group("sketch");
    group.sample_size(10);
    let a = cases::random_star(10_000, 1, DVec2::ZERO);
    let b = cases::random_star(10_000, 2, DVec2::new(0.3, 0.1));
    group.bench_function("star_union_10k", |bench| bench.iter(|| &a | &b));
    group.bench_function("star_intersection_10k", |bench| bench.iter(|| &a & &b));
    group.bench_function("star_polygon_from_points_10k", |bench| {
        bench.iter(|| cases::random_star(10_000, 1, DVec2::ZERO))
    });
    let circles = cases::random_circles(1000, 3);
    group.bench_function("union_1000_circles", |bench| {
        bench.iter(|| Sketch::union_all(circles.clone()))
    });
    // A plate drilled hole by hole: each boolean's tree of the plate covers only the hole's box.
    let plate = Sketch::rectangle(20.0, 20.0).unwrap();
    let holes = cases::hole_grid(20);
    group.bench_function("plate_minus_400_holes_one_by_one", |bench| {
        bench.iter(|| holes.iter().fold(plate.clone(), |p, h| &p - h))
    });
    group.finish();
}

criterion_group!(benches, stars);
criterion_main!(benches);
