//! Shared test checks on meshes, through the crate's own `Mesh::report`, and the way tests
//! find the shared real meshes.

#![allow(dead_code)]

pub mod cli;
pub mod hostile;
pub mod mesh_files;
pub mod mesh_input;
pub mod run;
pub mod scenes;

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

/// Triangles whose area is below `rel × diag²` of the mesh's bounding box.
pub fn needles(mesh: &Mesh, rel: f64) -> usize {
    let d2 = mesh.bbox().diagonal().powi(2);
    (0..mesh.triangle_count())
        .filter(|&t| {
            let [a, b, c] = mesh.triangle(t);
            0.5 * (b - a).cross(c - a).length() < rel * d2
        })
        .count()
}

/// Asserts that `mesh` is a closed 2-manifold holding no needle (no triangle below 1e-12 ×
/// its bounding box's diagonal², see [`needles`]) and returns its report.
pub fn assert_closed_without_needles(mesh: &Mesh, what: &str) -> MeshReport {
    let report = assert_closed_manifold(mesh, what);
    assert_eq!(needles(mesh, 1e-12), 0, "{what}: needles; {report}");
    report
}

/// Asserts `got` within `rel` of `want` (relative), printing both.
pub fn assert_volume(got: f64, want: f64, rel: f64, what: &str) {
    let err = (got - want).abs() / want.abs();
    println!("{what}: volume {got:.15e} (want {want:.15e}, rel err {err:.2e})");
    assert!(
        err <= rel,
        "{what}: volume {got} want {want} (rel err {err:.2e})"
    );
}

/// A box as an OBJ file brings it: 8 corners and 12 triangles, read as a solid.
pub fn obj_box(min: bspcsg::glam::DVec3, max: bspcsg::glam::DVec3) -> Solid {
    Solid::from_mesh(&obj_box_mesh(min, max)).expect("a box is closed")
}

/// The 12-triangle mesh of a box (each face split along one diagonal).
pub fn obj_box_mesh(min: bspcsg::glam::DVec3, max: bspcsg::glam::DVec3) -> Mesh {
    let p = |i: usize| {
        bspcsg::glam::DVec3::new(
            if i & 1 == 0 { min.x } else { max.x },
            if i & 2 == 0 { min.y } else { max.y },
            if i & 4 == 0 { min.z } else { max.z },
        )
    };
    let quads: [[u32; 4]; 6] = [
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    Mesh::new((0..8).map(p).collect(), triangles)
}

/// OBJ text of an axis-aligned box, as a file would bring it: 8 corners written with full
/// precision and 6 outward-facing quads.
pub fn box_obj_text(min: [f64; 3], max: [f64; 3]) -> String {
    let mut s = String::new();
    for i in 0..8 {
        let c = |k: usize, bit: usize| if i & bit == 0 { min[k] } else { max[k] };
        s += &format!("v {:?} {:?} {:?}\n", c(0, 4), c(1, 2), c(2, 1));
    }
    for f in [
        [1, 2, 4, 3],
        [5, 7, 8, 6],
        [1, 5, 6, 2],
        [3, 4, 8, 7],
        [1, 3, 7, 5],
        [2, 6, 8, 4],
    ] {
        s += &format!("f {} {} {} {}\n", f[0], f[1], f[2], f[3]);
    }
    s
}
