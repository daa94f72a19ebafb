//! Shared test checks on meshes, through the crate's own `Mesh::report`, and the way tests
//! find the shared real meshes.

#![allow(dead_code)]

pub mod run;

use std::path::PathBuf;

use bspcsg::{Mesh, MeshReport, Solid};

/// The shared real meshes, if `BSPCSG_MODELS` names their folder; `None`, with a note, if not.
pub fn models() -> Option<PathBuf> {
    match std::env::var_os("BSPCSG_MODELS") {
        Some(d) => Some(PathBuf::from(d)),
        None => {
            eprintln!("skipped: set BSPCSG_MODELS to the shared test-model folder");
            None
        }
    }
}

/// Asserts that `mesh` is a closed 2-manifold (closed, manifold edges and vertices, oriented,
/// no zero-area triangles, shells outward) and returns its report.
pub fn assert_closed_manifold(mesh: &Mesh, what: &str) -> MeshReport {
    let report = mesh.report();
    assert!(report.is_closed_manifold(), "{what}: {report}");
    report
}

/// Shells and total genus of a closed 2-manifold.
pub fn shells_and_genus(mesh: &Mesh, what: &str) -> (usize, u64) {
    let report = assert_closed_manifold(mesh, what);
    (
        report.shells.len(),
        report.genus.expect("closed meshes have a genus"),
    )
}

/// Asserts that the solid's mesh is a closed 2-manifold with the solid's volume.
pub fn assert_clean_mesh(solid: &Solid, what: &str) -> Mesh {
    let mesh = solid.to_mesh();
    assert_closed_manifold(&mesh, what);
    let (mv, sv) = (mesh.volume(), solid.volume());
    assert!(
        (mv - sv).abs()
            <= 1e-9 * sv.abs().max(1e-300) + 1e-12 * mesh.bbox().size().max_element().powi(3),
        "{what}: mesh volume {mv} but the solid's {sv}"
    );
    mesh
}
