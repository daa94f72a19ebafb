//! Marching-cubes baking: closed 2-manifolds with the right volume and genus.

mod common;

use bspcsg::{BakeOptions, Scene};
use common::{assert_closed_manifold, shells_and_genus};

fn scene(json: &str) -> Scene {
    Scene::from_json_str(json).unwrap()
}

#[test]
fn sphere_at_cell_005_is_watertight_genus_0_and_within_0_3_percent() {
    let s =
        scene(r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#);
    let mesh = s.bake(&BakeOptions::with_cell(0.05)).unwrap();
    assert_eq!(shells_and_genus(&mesh, "sphere"), (1, 0));
    let exact = 4.0 / 3.0 * std::f64::consts::PI;
    let rel = (mesh.volume() - exact).abs() / exact;
    println!(
        "sphere volume {} (exact {exact}), rel err {rel:.2e}, {} triangles",
        mesh.volume(),
        mesh.triangle_count()
    );
    assert!(rel < 0.003, "{rel}");
}

#[test]
fn torus_at_cell_005_is_genus_1_within_1_percent() {
    let s = scene(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "torus", "radius": 1, "tube_radius": 0.25}}"#,
    );
    let mesh = s.bake(&BakeOptions::with_cell(0.05)).unwrap();
    assert_eq!(shells_and_genus(&mesh, "torus"), (1, 1));
    let exact = 2.0 * std::f64::consts::PI.powi(2) * 1.0 * 0.25f64.powi(2);
    let rel = (mesh.volume() - exact).abs() / exact;
    println!(
        "torus volume {} (exact {exact}), rel err {rel:.2e}",
        mesh.volume()
    );
    assert!(rel < 0.01, "{rel}");
}

#[test]
fn spheres_tangent_at_a_grid_vertex_stay_manifold() {
    // Cell 1/8 and bounds at ±1.25: the tangent point (0, 0, 0) is grid vertex (10, 6, 6),
    // where the field is exactly zero.
    let s = scene(
        r#"{"op": "union", "children": [
            {"kind": "sdf_primitive", "pos": [-0.5, 0, 0], "data": {"primitive_type": "sphere", "radius": 0.5}},
            {"kind": "sdf_primitive", "pos": [0.5, 0, 0], "data": {"primitive_type": "sphere", "radius": 0.5}}
        ]}"#,
    );
    assert_eq!(s.distance(glam::DVec3::ZERO), 0.0);
    let opts = BakeOptions {
        cell: Some(0.125),
        region: Some(bspcsg::Aabb::new(
            glam::DVec3::new(-1.25, -0.75, -0.75),
            glam::DVec3::new(1.25, 0.75, 0.75),
        )),
        ..Default::default()
    };
    let mesh = s.bake(&opts).unwrap();
    let (shells, genus) = shells_and_genus(&mesh, "tangent spheres");
    // Zero counts as outside, so the spheres stay apart: two spheres, genus 0.
    assert_eq!((shells, genus), (2, 0));
    // No two vertices share a position either.
    let mut seen = std::collections::HashSet::new();
    assert!(
        mesh.positions
            .iter()
            .all(|p| seen.insert(p.to_array().map(f64::to_bits)))
    );
}

#[test]
fn surfaces_touching_or_crossing_the_bounds_are_closed() {
    let unit = bspcsg::Aabb::new(glam::DVec3::splat(-1.0), glam::DVec3::splat(1.0));
    // A box whose faces lie exactly on the bounds.
    let b =
        scene(r#"{"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [2, 2, 2]}}"#);
    let opts = BakeOptions {
        cell: Some(0.1),
        region: Some(unit),
        ..Default::default()
    };
    let mesh = b.bake(&opts).unwrap();
    assert_closed_manifold(&mesh, "box on the bounds");
    // Marching cubes chamfers each sharp edge by at most half a cell square per length.
    let chamfer = 12.0 * 2.0 * 0.1 * 0.1 / 2.0;
    let v = mesh.volume();
    assert!(v <= 8.0 + 1e-9 && v >= 8.0 - chamfer - 1e-3, "{v}");
    // A sphere cut by bounds inside it: the bounds close it into a cube.
    let s =
        scene(r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1.2}}"#);
    let mesh = s.bake(&opts).unwrap();
    assert_eq!(shells_and_genus(&mesh, "sphere cut by the bounds").1, 0);
    // The ball of radius 1.2 less six caps of height 0.2 beyond the cube [-1, 1]³.
    let pi = std::f64::consts::PI;
    let exact = 4.0 / 3.0 * pi * 1.2f64.powi(3) - 6.0 * pi * 0.04 * (3.0 * 1.2 - 0.2) / 3.0;
    let v = mesh.volume();
    assert!((v - exact).abs() / exact < 0.01, "{v} vs {exact}");
}

#[test]
fn empty_and_unbounded_scenes() {
    let empty = scene(
        r#"{"op": "intersect", "children": [
            {"kind": "sdf_primitive", "pos": [-5, 0, 0], "data": {"primitive_type": "sphere", "radius": 1}},
            {"kind": "sdf_primitive", "pos": [5, 0, 0], "data": {"primitive_type": "sphere", "radius": 1}}
        ]}"#,
    );
    assert!(empty.bake(&BakeOptions::default()).unwrap().is_empty());
    let half = scene(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "plane", "normal": [0, 1, 0]}}"#,
    );
    assert!(half.bake(&BakeOptions::default()).is_err());
    let bounded = BakeOptions {
        resolution: Some(16),
        region: Some(bspcsg::Aabb::new(
            glam::DVec3::splat(-1.0),
            glam::DVec3::splat(1.0),
        )),
        ..Default::default()
    };
    let mesh = half.bake(&bounded).unwrap();
    assert_closed_manifold(&mesh, "half-space in bounds");
    // The half cube, less the chamfers of its 20 units of sharp edges (cell 1/8).
    let v = mesh.volume();
    assert!(
        v <= 4.0 && v > 4.0 - 20.0 * 0.125 * 0.125 / 2.0 - 1e-3,
        "{v}"
    );
    assert!(half.bake(&BakeOptions::with_cell(-1.0)).is_err());
}

mod random {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        #[test]
        fn random_sphere_sums_are_closed_manifolds(
            spheres in proptest::collection::vec(
                ((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 0.05f64..0.7), 1..6),
            smooth in proptest::option::of(1.0f64..30.0),
            cell in 0.04f64..0.2,
        ) {
            let children: Vec<String> = spheres
                .iter()
                .map(|((x, y, z), r)| format!(
                    r#"{{"kind": "sdf_primitive", "pos": [{x}, {y}, {z}], "data": {{"primitive_type": "sphere", "radius": {r}}}}}"#
                ))
                .collect();
            let op = match smooth {
                Some(k) => format!(r#""op": "smooth_union", "smooth_k": {k}"#),
                None => r#""op": "union""#.to_string(),
            };
            let s = Scene::from_json_str(&format!(r#"{{{op}, "children": [{}]}}"#, children.join(","))).unwrap();
            let mesh = s.bake(&BakeOptions::with_cell(cell)).unwrap();
            let report = mesh.report();
            prop_assert!(report.is_closed_manifold(), "{report}");
            // Spheres smaller than a cell may fall between grid points: then nothing is baked.
            prop_assert!(mesh.is_empty() || mesh.volume() > 0.0);
        }
    }
}

#[test]
fn a_huge_sparse_grid_is_cheap() {
    // 16384 cells along x, but the sphere is tiny: only blocks near it are visited.
    let s = scene(
        r#"{"op": "union", "children": [
            {"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 0.5}},
            {"kind": "sdf_primitive", "pos": [800, 0, 0], "data": {"primitive_type": "box", "size": [0.01, 0.01, 0.01]}}
        ]}"#,
    );
    let mesh = s.bake(&BakeOptions::with_cell(0.05)).unwrap();
    assert_closed_manifold(&mesh, "sparse");
    assert!(s.bake(&BakeOptions::with_cell(0.001)).is_err());
}
