//! Validation and mesh input on the shared real-world models (see their README.md): genus,
//! shells, open and non-manifold models, every model's report, and coplanar merging on them.

mod common;

use approx::assert_relative_eq;
use bspcsg::{FromMeshOptions, Mesh, MeshReport, Solid};
use common::mesh_input::{invalid_message, merged, weld};
use common::models;
use glam::DVec3;

// ---- The shared real-world models (see their README.md) ----

/// A test-only OBJ reader: `v x y z` positions and `f a/b/c …` faces (1-based or negative
/// indices, texture and normal indices ignored), fan-triangulated, positions welded bit for bit.
fn load_obj(name: &str) -> Option<Mesh> {
    let path = models()?.join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words.take(3).map(|w| w.parse().unwrap()).collect();
                assert_eq!(c.len(), 3, "line {}", n + 1);
                positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let idx: Vec<u32> = words
                    .map(|w| {
                        let i: i64 = w.split('/').next().unwrap().parse().unwrap();
                        let i = if i < 0 {
                            positions.len() as i64 + i
                        } else {
                            i - 1
                        };
                        u32::try_from(i).unwrap()
                    })
                    .collect();
                for k in 1..idx.len() - 1 {
                    triangles.push([idx[0], idx[k], idx[k + 1]]);
                }
            }
            _ => {}
        }
    }
    Some(weld(Mesh::new(positions, triangles)))
}

#[test]
fn model_spot_is_genus_zero() {
    let Some(m) = load_obj("spot.obj") else {
        return;
    };
    let r = m.report();
    assert_eq!(r.triangles, 5856);
    assert!(r.is_closed_manifold(), "{r}");
    assert_eq!((r.shells.len(), r.genus), (1, Some(0)));
    assert_relative_eq!(r.volume, 0.718258788, max_relative = 1e-8);
    let s = Solid::from_mesh(&m).unwrap();
    assert_relative_eq!(s.volume(), r.volume, max_relative = 1e-12);
}

#[test]
fn model_rocker_arm_is_genus_one() {
    let Some(m) = load_obj("rocker-arm.obj") else {
        return;
    };
    let r = m.report();
    assert_eq!(r.triangles, 20088);
    assert!(r.is_closed_manifold(), "{r}");
    assert_eq!((r.shells.len(), r.genus), (1, Some(1)));
    assert_relative_eq!(r.volume, 0.0425136236, max_relative = 1e-8);
}

#[test]
fn model_fandisk_is_genus_zero() {
    let Some(m) = load_obj("fandisk.obj") else {
        return;
    };
    let r = m.report();
    assert_eq!(r.triangles, 12946);
    assert!(r.is_closed_manifold(), "{r}");
    assert_eq!(r.genus, Some(0));
    assert_relative_eq!(r.volume, 20.2433749, max_relative = 1e-8);
}

#[test]
fn model_cray_left_has_two_shells() {
    let Some(m) = load_obj("Cray_left.obj") else {
        return;
    };
    let r = m.report();
    assert_eq!(r.triangles, 576);
    assert!(r.closed && r.oriented && r.outward, "{r}");
    assert_eq!(r.shells.len(), 2);
    assert_relative_eq!(r.volume, 1.95686465e12, max_relative = 1e-8);
}

#[test]
fn model_havocglass_far_from_origin() {
    for (name, volume) in [
        ("Havocglass8_left.obj", 2779422.24),
        ("Havocglass8_right.obj", 348996.763),
    ] {
        let Some(m) = load_obj(name) else { return };
        let r = m.report();
        assert!(r.closed && r.oriented && r.outward, "{name}: {r}");
        assert_relative_eq!(r.volume, volume, max_relative = 1e-8);
    }
}

#[test]
fn model_bunny_is_open() {
    let Some(m) = load_obj("stanford-bunny.obj") else {
        return;
    };
    let r = m.report();
    assert_eq!(r.triangles, 69451);
    assert_eq!(r.boundary_edges, 223);
    assert!(!r.closed && !r.is_closed_manifold());
    assert_eq!(r.genus, None);
    let msg = invalid_message(Solid::from_mesh(&m));
    assert!(msg.contains("not closed: 223 boundary edges"), "{msg}");
    assert!(Solid::from_mesh_with(&m, &FromMeshOptions::lenient()).is_ok());
}

#[test]
fn model_box_not_manifold() {
    let Some(m) = load_obj("boxNotManifold.obj") else {
        return;
    };
    let r = m.report();
    assert_eq!(r.triangles, 12);
    assert_eq!(r.boundary_edges, 4);
    assert!(!r.is_closed_manifold());
    let msg = invalid_message(Solid::from_mesh(&m));
    assert!(msg.contains("4 boundary edges"), "{msg}");
}

#[test]
fn model_openscad_nonmanifold() {
    let Some(m) = load_obj("openscad-nonmanifold-crash.obj") else {
        return;
    };
    let r = m.report();
    assert_eq!(r.triangles, 1442);
    assert_eq!(r.non_manifold_edges, 18);
    assert_eq!(r.boundary_edges, 0);
    assert_eq!((r.degenerate_triangles, r.repeated_index_triangles), (1, 0));
    assert!(!r.is_closed_manifold());
    assert_relative_eq!(r.volume, 451.960155, max_relative = 1e-8);
    let msg = invalid_message(Solid::from_mesh(&m));
    assert!(msg.contains("18 non-manifold edges"), "{msg}");
}

/// Prints the report of every model (run with `--nocapture` to read them).
#[test]
fn model_reports_print() {
    let Some(dir) = models() else { return };
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".obj"))
        .collect();
    names.sort();
    for name in names {
        let r: MeshReport = load_obj(&name).unwrap().report();
        println!("{name}: {r}");
    }
}

// ---- Merging coplanar triangles ----

#[test]
fn merge_on_models() {
    for name in [
        "fandisk.obj",
        "rocker-arm.obj",
        "Havocglass8_left.obj",
        "Cray_left.obj",
    ] {
        let Some(m) = load_obj(name) else { return };
        let plain = Solid::from_mesh(&m).unwrap();
        let back = merged(&m);
        println!(
            "{name}: {} triangles -> {} polygons",
            m.triangles.len(),
            back.polygon_count()
        );
        assert!(back.polygon_count() <= plain.polygon_count());
        assert_relative_eq!(back.volume(), plain.volume(), max_relative = 1e-12);
        assert_relative_eq!(back.area(), plain.area(), max_relative = 1e-12);
        assert!(back.to_mesh().report().closed);
    }
}

#[test]
fn merge_on_bad_models_is_lenient_too() {
    for name in [
        "openscad-nonmanifold-crash.obj",
        "boxNotManifold.obj",
        "stanford-bunny.obj",
    ] {
        let Some(m) = load_obj(name) else { return };
        let lenient = FromMeshOptions::lenient();
        let plain = Solid::from_mesh_with(&m, &lenient).unwrap();
        let back = Solid::from_mesh_with(&m, &lenient.with_merge_coplanar(true)).unwrap();
        assert!(back.polygon_count() <= plain.polygon_count());
        assert_relative_eq!(back.volume(), plain.volume(), max_relative = 1e-12);
    }
}
