//! The file readers on arbitrary bytes: OBJ, STL (ASCII and binary) and glTF (JSON and GLB).
//! The first byte picks the format, the rest is the file.
//!
//! Checks: no panic; memory stays bounded (libFuzzer's `-rss_limit_mb` enforces it); a mesh
//! that is read has every index in range and finite positions, and turning it into a solid
//! either succeeds or fails with an error.
#![no_main]

use bspcsg::{Format, FromMeshOptions, Solid, read_mesh_from_bytes};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else {
        return;
    };
    let (name, format) = match pick % 4 {
        0 => ("fuzz.obj", Format::Obj),
        1 => ("fuzz.stl", Format::Stl),
        2 => ("fuzz.gltf", Format::Gltf),
        _ => ("fuzz.glb", Format::Glb),
    };
    // A folder with nothing in it: a glTF's external buffer URIs resolve to nothing real.
    let path = std::env::temp_dir().join("bspcsg-fuzz-empty").join(name);
    let Ok(mesh) = read_mesh_from_bytes(&path, bytes, format) else {
        return;
    };
    let n = mesh.positions.len();
    assert_eq!(mesh.sources.len(), mesh.triangles.len());
    for t in &mesh.triangles {
        for &i in t {
            assert!((i as usize) < n, "index {i} of {n}");
            assert!(mesh.positions[i as usize].is_finite());
        }
    }
    let _ = mesh.report();
    let _ = Solid::from_mesh_with(&mesh, &FromMeshOptions::default());
});
