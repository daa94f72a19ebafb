//! Helpers of the command line's test files (`cli.rs`, `cli_errors.rs`, `cli_scenes.rs`):
//! running a boolean, reading `info --json`, and the small meshes they feed the binary.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};

use bspcsg::{Mesh, Solid, write_mesh};
use glam::DVec3;
use serde_json::Value;

use super::run::{Run, bspcsg};

/// `bspcsg OP INPUT… -o OUT`.
pub fn combine(op: &str, inputs: &[&Path], out: &Path) -> Run {
    let mut args = vec![OsStr::new(op)];
    args.extend(inputs.iter().map(|p| p.as_os_str()));
    args.extend([OsStr::new("-o"), out.as_os_str()]);
    bspcsg(args)
}

/// `bspcsg info --json PATH`, parsed.
pub fn info(path: &Path) -> Value {
    let run = bspcsg([OsStr::new("info"), path.as_os_str(), OsStr::new("--json")]).ok();
    serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("{e}: {}", run.stdout))
}

pub fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number in {v}"))
}

pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Asserts the report of a closed, clean solid.
pub fn assert_solid(v: &Value, what: &str) {
    assert_eq!(v["watertight"], true, "{what}: {v}");
    assert_eq!(v["boundary_edges"], 0, "{what}: {v}");
    assert_eq!(v["nonmanifold_edges"], 0, "{what}: {v}");
    assert_eq!(v["degenerate_triangles"], 0, "{what}: {v}");
    assert!(v["genus"].is_u64(), "{what}: {v}");
    assert!(num(v, "volume") > 0.0, "{what}: {v}");
}

pub fn cube_at(x: f64) -> Solid {
    Solid::cube(1.0)
        .unwrap()
        .translate(DVec3::new(x, 0.0, 0.0))
        .unwrap()
}

pub fn write(path: &Path, mesh: &Mesh) -> PathBuf {
    write_mesh(path, mesh, &[]).unwrap();
    path.to_path_buf()
}

/// A unit cube with one triangle taken out: three boundary edges.
pub fn open_cube() -> Mesh {
    let mut m = Solid::cube(1.0).unwrap().to_mesh();
    m.triangles.pop();
    m.sources.pop();
    m
}

pub const FORMATS: [&str; 4] = ["obj", "stl", "gltf", "glb"];
