//! The example scenes and a one-sphere scene, for the tests that render or check scenes.

use std::path::{Path, PathBuf};

use bspcsg::Scene;

/// A scene of one unit sphere.
pub const SPHERE: &str =
    r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#;

/// The folder of the example scenes.
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes")
}

/// The path of the example scene `name` (`examples/scenes/<name>.json`).
pub fn example_path(name: &str) -> PathBuf {
    scenes_dir().join(format!("{name}.json"))
}

/// The example scene `name`, read.
pub fn example(name: &str) -> Scene {
    Scene::from_path(example_path(name)).unwrap()
}

/// The paths of every example scene, sorted.
pub fn example_paths() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    paths
}
