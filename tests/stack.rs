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
