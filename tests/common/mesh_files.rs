//! Helpers of the mesh-file test files (`io.rs`, `io_errors.rs`): scratch directories and the
//! meshes and materials they write.

use std::fs;
use std::path::{Path, PathBuf};

use bspcsg::{Material, Mesh, Solid};

/// A fresh, empty directory for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("io").join(name);
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

pub fn sphere() -> Mesh {
    Solid::sphere(1.5, 48, 24).unwrap().to_mesh()
}

pub fn materials() -> Vec<Material> {
    vec![
        Material {
            name: "steel grey".into(),
            base_color: [0.6, 0.6, 0.65, 1.0],
        },
        Material {
            name: "glass".into(),
            base_color: [0.2, 0.5, 0.9, 0.4],
        },
    ]
}

pub fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}
