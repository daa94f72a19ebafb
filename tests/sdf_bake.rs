//! Marching-cubes baking: closed 2-manifolds with the right volume and genus.

mod common;

use bspcsg::{BakeOptions, Scene};
use common::{Topology, vertices_are_manifold};

fn scene(json: &str) -> Scene {
    Scene::from_json_str(json).unwrap()
}

#[test]
fn sphere_at_cell_005_is_watertight_genus_0_and_within_0_3_percent() {
    let s =
        scene(r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#);
    let mesh = s.bake(&BakeOptions::with_cell(0.05)).unwrap();
    let t = Topology::of(&mesh);
    t.assert_closed_manifold("sphere");
    assert!(vertices_are_manifold(&mesh));
    assert_eq!(t.components, 1);
    assert_eq!(t.genus(), 0);
    let exact = 4.0 / 3.0 * std::f64::consts::PI;
    let rel = (mesh.volume() - exact).abs() / exact;
    println!(
        "sphere volume {} (exact {exact}), rel err {rel:.2e}, {} triangles",
        mesh.volume(),
        mesh.triangle_count()
    );
    assert!(rel < 0.003, "{rel}");
}
