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

/// The example scene `name` (`examples/scenes/<name>.json`).
pub fn example(name: &str) -> Scene {
    Scene::from_path(scenes_dir().join(format!("{name}.json"))).unwrap()
}
