//! No pass recurses: the union of two 128×64 spheres, and its mesh, run with 256 KiB stacks.
//! The booleans do their heavy work through rayon, so the work runs inside a pool whose threads
//! all have the small stack: `install` runs the closure on one of them, and every nested `join`
//! and parallel iterator stays in that pool.

use bspcsg::Solid;
use glam::DVec3;

const STACK: usize = 256 * 1024;

#[test]
fn big_union_on_a_small_stack() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .stack_size(STACK)
        .build()
        .unwrap();
    let (volume, triangles, closed) = pool.install(|| {
        let a = Solid::sphere(1.0, 128, 64).unwrap();
        let b = a.clone().translate(DVec3::new(0.5, 0.0, 0.0)).unwrap();
        let u = &a | &b;
        let mesh = u.to_mesh();
        (
            u.volume(),
            mesh.triangle_count(),
            mesh.report().is_closed_manifold(),
        )
    });
    assert!(closed);
    assert!(volume > 4.18 && volume < 4.19 * 1.5, "volume {volume}");
    assert!(triangles > 10_000);
}

/// Ray marching, BVH build and traversal, and the agreement check keep explicit stacks: a
/// render of the mechanical part, a render of its mesh and a full check run on small stacks.
#[test]
fn render_and_check_on_a_small_stack() {
    use bspcsg::raymarch::{
        Camera, CheckOptions, RenderOptions, View, check_mesh, render_mesh, render_scene,
    };
    use bspcsg::{Scene, TessellationOptions};
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .stack_size(STACK)
        .build()
        .unwrap();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/mechanical_part.json"
    );
    let (lit, passed, cast) = pool.install(|| {
        let scene = Scene::from_path(path).unwrap();
        let camera = Camera::for_scene(&scene, View::Iso, (96, 72)).unwrap();
        let opts = RenderOptions::with_profile(scene.render_profile().clone());
        let image = render_scene(&scene, &camera, &opts).unwrap();
        let tol = scene.bbox().diagonal() / 500.0;
        let mesh = scene
            .to_solid(&TessellationOptions::with_tolerance(tol))
            .unwrap()
            .to_mesh();
        let cast = render_mesh(&mesh, scene.materials(), &camera, &opts).unwrap();
        let check = CheckOptions {
            tolerance: Some(2.0 * tol),
            ray_size: 96,
            ..CheckOptions::default()
        };
        let report = check_mesh(&scene, &mesh, &check).unwrap();
        let lit = |img: &bspcsg::raymarch::Image| img.pixels.iter().filter(|p| p.x > 0.2).count();
        (lit(&image), report.passed(), lit(&cast))
    });
    assert!(passed);
    assert!(lit > 500 && cast > 500, "{lit} {cast}");
}

#[test]
fn star_polygon_union_on_a_small_stack() {
    use bspcsg::{FillRule, Sketch};
    use glam::DVec2;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .stack_size(STACK)
        .build()
        .unwrap();
    let (area, valid, closed) = pool.install(|| {
        let star = |n: usize, shift: f64| {
            let pts: Vec<DVec2> = (0..n)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / n as f64;
                    DVec2::from_angle(a) * (0.75 + 0.25 * (i as f64 * 7.3).sin()) + shift
                })
                .collect();
            Sketch::polygon(&pts, FillRule::NonZero).unwrap()
        };
        let u = &star(10_000, 0.0) | &star(9_999, 0.05);
        let solid = u.extrude(1.0).unwrap();
        (
            u.area(),
            u.report().is_valid(),
            solid.to_mesh().report().is_closed_manifold(),
        )
    });
    assert!(valid && closed);
    assert!(area > 1.0 && area < 4.0, "area {area}");
}
