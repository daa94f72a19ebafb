//! No pass recurses: the union of two 128×64 spheres runs on a thread with a 256 KiB stack.

use bspcsg::Solid;
use glam::DVec3;

#[test]
fn big_union_on_a_small_stack() {
    let handle = std::thread::Builder::new()
        .stack_size(256 * 1024)
        .spawn(|| {
            let a = Solid::sphere(1.0, 128, 64).unwrap();
            let b = a.clone().translate(DVec3::new(0.5, 0.0, 0.0)).unwrap();
            let u = &a | &b;
            let mesh = u.to_mesh();
            assert!(mesh.report().is_closed_manifold());
            (u.volume(), mesh.triangle_count())
        })
        .unwrap();
    let (volume, triangles) = handle
        .join()
        .expect("the union must not overflow the stack");
    assert!(volume > 4.18 && volume < 4.19 * 1.5, "volume {volume}");
    assert!(triangles > 10_000);
}
