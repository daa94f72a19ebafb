//! The agreement check between a scene and a mesh (`check_mesh`): it passes for the scene's own
//! mesh, fails for meshes that are moved, scaled, missing a hole or a small part, and refuses
//! what it cannot measure.

mod common;

use bspcsg::raymarch::{Camera, CheckOptions, CheckReport, View, check_mesh};
use bspcsg::{Mesh, Scene, Solid, TessellationOptions};
use common::scenes::{SPHERE, example, scenes_dir};
use glam::DVec3;

/// A cheaper check for the many cases below.
fn quick(tol: f64) -> CheckOptions {
    CheckOptions {
        tolerance: Some(tol),
        surface_samples: 20_000,
        coverage_samples: 10_000,
        ray_size: 160,
        sign_samples: 5_000,
        ..CheckOptions::default()
    }
}

fn mechanical() -> (Scene, Mesh, f64) {
    let scene = example("mechanical_part");
    let tol = scene.bbox().diagonal() / 500.0;
    let mesh = scene
        .to_solid(&TessellationOptions::with_tolerance(tol))
        .unwrap()
        .to_mesh();
    (scene, mesh, 2.0 * tol)
}

#[test]
fn check_passes_for_the_scene_own_mesh() {
    let (scene, mesh, tol) = mechanical();
    let r = check_mesh(&scene, &mesh, &quick(tol)).unwrap();
    assert!(r.passed(), "{:?}", r.failures);
    assert!(r.rays.agreement_pct > 99.9, "{:?}", r.rays);
    assert!(r.sign.agreement_pct == 100.0 && r.sign.samples == 5_000);
    assert!(r.surface.max <= tol && r.coverage.max <= tol);
    assert!(r.surface.samples >= 20_000 + mesh.triangle_count());
}

/// Checks, expects a failure of `measure`, and returns all failures with the report.
fn fails_with(scene: &Scene, mesh: &Mesh, tol: f64, measure: &str) -> (String, CheckReport) {
    let r = check_mesh(scene, mesh, &quick(tol)).unwrap();
    assert!(!r.passed(), "expected a {measure} failure");
    let all = r.failures.join("\n");
    assert!(all.contains(measure), "{all}");
    (all, r)
}

#[test]
fn check_fails_for_a_moved_mesh() {
    let (scene, mut mesh, tol) = mechanical();
    let shift = 0.02 * scene.bbox().size().max_element();
    for p in &mut mesh.positions {
        p.x += shift;
    }
    let (why, _) = fails_with(&scene, &mesh, tol, "surface distance");
    assert!(why.contains("rays") || why.contains("coverage"), "{why}");
}

#[test]
fn check_fails_for_a_scaled_mesh() {
    let (scene, mut mesh, tol) = mechanical();
    for p in &mut mesh.positions {
        *p *= 1.02;
    }
    fails_with(&scene, &mesh, tol, "surface distance");
}

#[test]
fn check_fails_for_a_missing_hole() {
    let (scene, _, tol) = mechanical();
    let text = std::fs::read_to_string(scenes_dir().join("mechanical_part.json")).unwrap();
    // Move one mounting hole's cutter far away: the plate is solid there.
    let edited = text.replacen("\"pos\": [-1.5, 0, -1.0]", "\"pos\": [-1.5, 20, -1.0]", 1);
    let solid_plate = Scene::from_json_str(&edited).unwrap();
    let mesh = solid_plate
        .to_solid(&TessellationOptions::with_tolerance(tol / 2.0))
        .unwrap()
        .to_mesh();
    let (_, r) = fails_with(&scene, &mesh, tol, "coverage");
    // The worst place named is on the hole's wall, 0.2 from its axis at (-1.5, y, -1.0).
    let w = r.coverage.worst;
    let off_axis = ((w.x + 1.5).powi(2) + (w.z + 1.0).powi(2)).sqrt();
    assert!((off_axis - 0.2).abs() < 0.02, "{w}");
}

#[test]
fn check_fails_for_a_small_deleted_part() {
    let (scene, mesh, tol) = mechanical();
    // Delete one mounting hole's wall: the triangles with every corner near its axis.
    let axis = DVec3::new(1.5, 0.0, 1.0);
    let keep: Vec<usize> = (0..mesh.triangle_count())
        .filter(|&t| mesh.triangle(t).iter().any(|c| c.distance(axis) > 0.33))
        .collect();
    assert!(keep.len() < mesh.triangle_count());
    let cut = Mesh {
        positions: mesh.positions.clone(),
        triangles: keep.iter().map(|&t| mesh.triangles[t]).collect(),
        sources: keep.iter().map(|&t| mesh.sources[t]).collect(),
    };
    // Every remaining triangle lies on the surface: only coverage can tell.
    let r = check_mesh(&scene, &cut, &quick(tol)).unwrap();
    assert!(r.surface.max <= tol);
    let (why, r) = fails_with(&scene, &cut, tol, "coverage");
    assert!(why.contains("missing"), "{why}");
    let w = r.coverage.worst;
    assert!(
        ((w.x - 1.5).powi(2) + (w.z - 1.0).powi(2)).sqrt() < 0.25,
        "{w}"
    );
}

#[test]
fn check_refuses_what_it_cannot_measure() {
    let scene = Scene::from_json_str(SPHERE).unwrap();
    assert!(check_mesh(&scene, &Mesh::default(), &CheckOptions::default()).is_err());
    let plane = Scene::from_json_str(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "plane", "normal": [0, 1, 0], "offset": 0}}"#,
    )
    .unwrap();
    let mesh = Solid::sphere(1.0, 16, 8).unwrap().to_mesh();
    assert!(check_mesh(&plane, &mesh, &CheckOptions::default()).is_err());
    // An unbounded scene has no default framing either.
    assert!(Camera::framing(&plane.bbox(), View::Iso, (8, 8)).is_err());
    let mesh = Solid::sphere(1.0, 16, 8).unwrap().to_mesh();
    let bad = CheckOptions {
        tolerance: Some(f64::NAN),
        ..CheckOptions::default()
    };
    assert!(check_mesh(&scene, &mesh, &bad).is_err());
}
