//! Both routes for every example scene: the baked mesh is a closed 2-manifold, the BSP route's
//! volume agrees with it within the tessellation tolerance, and the SDF's sign agrees with the
//! BSP solid's point containment everywhere farther than two cells from the surface.

mod common;

use bspcsg::{BakeOptions, Containment, Scene, TessellationOptions};
use common::assert_closed_manifold;
use glam::DVec3;

const TOLERANCE: f64 = 0.01;
const CELL: f64 = 0.05;

fn check(name: &str) {
    let path = format!("{}/examples/scenes/{name}.json", env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::from_path(&path).unwrap();

    let mesh = scene.bake(&BakeOptions::with_cell(CELL)).unwrap();
    assert_closed_manifold(&mesh, name);
    assert!(
        mesh.sources
            .iter()
            .all(|&s| (s as usize) < scene.materials().len())
    );

    let solid = scene
        .to_solid(&TessellationOptions {
            tolerance: Some(TOLERANCE),
            cell: Some(CELL),
            max_angle: None,
        })
        .unwrap();
    let (v_sdf, v_bsp) = (mesh.volume(), solid.volume());
    // Every surface point of either route lies within the tolerance of the true surface (the
    // marching-cubes cell is small enough that its chamfers stay below it), so the volumes
    // differ by at most area × tolerance.
    let bound = mesh.area() * TOLERANCE;
    println!(
        "{name}: sdf {v_sdf:.5}, bsp {v_bsp:.5}, |diff| {:.2e} ≤ {bound:.2e}",
        (v_sdf - v_bsp).abs()
    );
    assert!((v_sdf - v_bsp).abs() <= bound, "{name}: {v_sdf} vs {v_bsp}");
    // Both routes carry the scene's materials on their source ids.
    let mut bsp_sources: Vec<u32> = solid.polygons().iter().map(|p| p.source()).collect();
    bsp_sources.sort_unstable();
    bsp_sources.dedup();
    let mut sdf_sources = mesh.sources.clone();
    sdf_sources.sort_unstable();
    sdf_sources.dedup();
    assert_eq!(bsp_sources, sdf_sources, "{name}: materials");

    let classifier = solid.classifier();
    let bb = scene.bbox().expanded(0.3);
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut tested, mut agree) = (0, 0);
    for _ in 0..3000 {
        let p = bb.min + (bb.max - bb.min) * DVec3::new(rnd(), rnd(), rnd());
        let d = scene.distance(p);
        // |d| never overestimates the distance, so |d| > 2h means at least two cells away.
        if d.abs() <= 2.0 * CELL {
            continue;
        }
        tested += 1;
        let inside = classifier.classify(p) == Containment::Inside;
        if inside == (d < 0.0) {
            agree += 1;
        } else {
            println!("{name}: disagree at {p}: d = {d}");
        }
    }
    println!("{name}: {agree}/{tested} points agree");
    assert!(tested > 1000);
    assert_eq!(agree, tested, "{name}");
}

#[test]
fn mechanical_part() {
    check("mechanical_part");
}

#[test]
fn organic_blend() {
    check("organic_blend");
}

#[test]
fn extruded_profile() {
    check("extruded_profile");
}

#[test]
fn turned_and_twisted() {
    check("turned_and_twisted");
}

/// A drilled hole 1/50 of the scene across: by the default chordal tolerance alone (1/500 of
/// the diagonal) a few segments, with the default angle bound at least 36, so the hole's
/// volume is right within 1.5 %; a chosen tolerance without an angle is taken as given.
#[test]
fn default_tessellation_is_bounded_by_angle() {
    let scene = Scene::from_json_str(
        r#"{"op": "subtract", "children": [
            {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [10, 1, 10]}},
            {"kind": "sdf_primitive", "pos": [1, 0, 1],
             "data": {"primitive_type": "cylinder", "radius": 0.1, "height": 2}}
        ]}"#,
    )
    .unwrap();
    let hole = |opts: &TessellationOptions| 100.0 - scene.to_solid(opts).unwrap().volume();
    let exact = std::f64::consts::PI * 0.01;
    let by_default = hole(&TessellationOptions::default());
    assert!(
        (by_default - exact).abs() < 0.015 * exact,
        "hole volume {by_default} against {exact}"
    );
    // 36 segments: the inscribed 36-gon's area.
    let n36 = 0.5 * 36.0 * 0.01 * (std::f64::consts::TAU / 36.0).sin();
    assert!(
        (by_default - n36).abs() < 1e-9,
        "{by_default} against {n36}"
    );
    // The default tolerance, 1/500 of the box's diagonal, given explicitly: 5 segments.
    let tolerance = 201.0f64.sqrt() / 500.0;
    let chordal_only = hole(&TessellationOptions::with_tolerance(tolerance));
    assert!(chordal_only < 0.9 * exact, "{chordal_only}");
    let with_angle = hole(&TessellationOptions {
        max_angle: Some(5.0),
        ..TessellationOptions::with_tolerance(tolerance)
    });
    let n72 = 0.5 * 72.0 * 0.01 * (std::f64::consts::TAU / 72.0).sin();
    assert!(
        (with_angle - n72).abs() < 1e-9,
        "{with_angle} against {n72}"
    );
    for bad in [0.0, -1.0, 121.0, f64::NAN] {
        let opts = TessellationOptions {
            max_angle: Some(bad),
            ..TessellationOptions::default()
        };
        assert!(scene.to_solid(&opts).is_err(), "max_angle {bad}");
    }
}

/// Every example scene baked as `bspcsg export --via sdf` bakes it (default options) keeps its
/// triangles whole in float32, as STL and glTF store them: no two corners of a triangle round
/// to the same point. Marching cubes once put vertices about 1e-8 apart where the surface
/// grazed grid points, and the organic blend's STL came back with six zero-area triangles.
#[test]
fn default_bakes_survive_float32() {
    for name in [
        "mechanical_part",
        "organic_blend",
        "extruded_profile",
        "turned_and_twisted",
    ] {
        let path = format!("{}/examples/scenes/{name}.json", env!("CARGO_MANIFEST_DIR"));
        let mesh = Scene::from_path(&path)
            .unwrap()
            .bake(&BakeOptions::default())
            .unwrap();
        let collapsed = mesh
            .triangles
            .iter()
            .filter(|t| {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_vec3());
                a == b || b == c || c == a
            })
            .count();
        println!(
            "{name}: {} triangles, {collapsed} collapse in f32",
            mesh.triangles.len()
        );
        assert_eq!(collapsed, 0, "{name}");
    }
}

/// The BSP route bakes every smooth subtree on the lattice of the scene's grid, each over the
/// part around it. A sphere of radius 10⁻³ beside a box 1000 across, at a cell of 10⁻⁴: its
/// bake is a small grid of a lattice 10⁷ cells across, and the values a hair inside count as
/// outside with the hair of at most the largest grid a bake may have (0.028 of a cell). With
/// the whole lattice's (1.7·10⁻³, more than the radius) the sphere was gone.
#[test]
fn a_small_smooth_part_of_a_large_scene_keeps_its_bake() {
    let scene = Scene::from_json_str(
        r#"{"op": "union", "children": [
            {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [1000, 1000, 1000]}},
            {"op": "smooth_union", "smooth": "polynomial", "smooth_k": 0.0002, "children": [
                {"kind": "sdf_primitive", "pos": [600, 0, 0],
                 "data": {"primitive_type": "sphere", "radius": 0.001}}]}
        ]}"#,
    )
    .unwrap();
    let options = TessellationOptions {
        tolerance: None,
        cell: Some(1e-4),
        max_angle: None,
    };
    let mesh = scene.to_solid(&options).unwrap().to_mesh();
    let report = mesh.report();
    assert!(
        report.is_closed_manifold() && report.shells.len() == 2,
        "{report}"
    );
    let sphere = report
        .shells
        .iter()
        .map(|s| s.volume)
        .fold(f64::INFINITY, f64::min);
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 1e-9;
    assert!(
        (sphere - exact).abs() < 0.05 * exact,
        "sphere {sphere}, exact {exact}"
    );
}
