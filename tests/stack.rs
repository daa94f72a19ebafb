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
