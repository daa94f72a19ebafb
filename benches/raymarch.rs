//! Rendering and checking. The targets on the 2-core machine: the mechanical part ray
//! marched at 800×600 with shadows and AO under 1 s; a 1M-triangle mesh's BVH built under 1 s
//! and cast at ≥ 5 M primary rays/s; `check` of the mechanical part under 2 s.

use std::hint::black_box;

use bspcsg::raymarch::{
    Camera, CheckOptions, MeshBvh, RenderOptions, View, check_mesh, render_scene,
};
use bspcsg::{Mesh, Scene, TessellationOptions};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use rayon::prelude::*;

/// A closed bumpy sphere of `2 n (n − 1)` triangles: a UV grid with a ripple so the BVH sees
/// varied triangle sizes and orientations.
fn bumpy_sphere(n: usize) -> Mesh {
    let (rings, segs) = (n, n);
    let mut positions = vec![DVec3::Y, DVec3::NEG_Y];
    for i in 1..rings {
        let theta = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..segs {
            let phi = std::f64::consts::TAU * j as f64 / segs as f64;
            let r = 1.0 + 0.05 * (9.0 * theta).sin() * (7.0 * phi).sin();
            positions.push(
                DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    -theta.sin() * phi.sin(),
                ) * r,
            );
        }
    }
    let at = |i: usize, j: usize| (2 + (i - 1) * segs + j % segs) as u32;
    let mut triangles = Vec::with_capacity(2 * rings * segs);
    for j in 0..segs {
        triangles.push([0, at(1, j), at(1, j + 1)]);
        triangles.push([1, at(rings - 1, j + 1), at(rings - 1, j)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segs {
            triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    Mesh::new(positions, triangles)
}

fn bench(c: &mut Criterion) {
    let part = Scene::from_path(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/mechanical_part.json"
    ))
    .expect("mechanical example");

    let mut g = c.benchmark_group("raymarch");
    g.sample_size(10);
    let camera = Camera::for_scene(&part, View::Iso, (800, 600)).expect("camera");
    let opts = RenderOptions::for_scene(&part);
    assert!(opts.profile.shadow_steps > 0 && opts.profile.ao_steps > 0);
    g.bench_function("mechanical_800x600_shadows_ao", |b| {
        b.iter(|| render_scene(black_box(&part), &camera, &opts).expect("render"))
    });

    let tol = part.bbox().diagonal() / 500.0;
    let part_mesh = part
        .to_solid(&TessellationOptions::with_tolerance(tol))
        .expect("bsp route")
        .to_mesh();
    let check = CheckOptions {
        tolerance: Some(2.0 * tol),
        ..CheckOptions::default()
    };
    g.bench_function("check_mechanical_bsp", |b| {
        b.iter(|| {
            let r = check_mesh(black_box(&part), &part_mesh, &check).expect("check");
            assert!(r.passed());
        })
    });
    g.finish();

    let mesh = bumpy_sphere(708);
    assert!(mesh.triangle_count() >= 1_000_000);
    let mut g = c.benchmark_group("bvh_1m");
    g.sample_size(10);
    g.bench_function("build", |b| b.iter(|| MeshBvh::build(black_box(&mesh))));
    let bvh = MeshBvh::build(&mesh);
    let cam = Camera::framing(&mesh.bbox(), View::Iso, (1000, 1000)).expect("camera");
    let rays: Vec<_> = (0..1000u32)
        .flat_map(|y| (0..1000u32).map(move |x| (x, y)))
        .map(|(x, y)| cam.ray(x as f64, y as f64).expect("ray"))
        .collect();
    g.throughput(Throughput::Elements(rays.len() as u64));
    g.bench_function("primary_rays", |b| {
        b.iter(|| {
            rays.par_chunks(4096)
                .map(|chunk| {
                    chunk
                        .iter()
                        .filter(|r| bvh.intersect(r, 0.0, f64::INFINITY).is_some())
                        .count()
                })
                .sum::<usize>()
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
