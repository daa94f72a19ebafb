//! Mesh validation reports on built meshes (genus, boundary, orientation, non-manifold and
//! degenerate cases, cavities, the display), structured defects and the mesh constructors.
//! `Solid::from_mesh` and coplanar merging are in `validate_from_mesh.rs`; the shared
//! real-world models in `validate_models.rs`.

mod common;

use approx::assert_relative_eq;
use bspcsg::{Error, FromMeshOptions, Mesh, MeshDefect, Solid};
use common::mesh_input::{cube_mesh, tetra, tetra_with_zero_area_triangle, weld};
use glam::DVec3;

/// The meshes side by side, positions welded bit for bit (so touching corners become one).
fn combine(meshes: &[Mesh]) -> Mesh {
    let mut out = Mesh::default();
    for m in meshes {
        let base = out.positions.len() as u32;
        out.positions.extend(&m.positions);
        out.triangles
            .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
        out.sources.extend(&m.sources);
    }
    weld(out)
}

fn moved(m: &Mesh, by: DVec3) -> Mesh {
    let mut m = m.clone();
    for p in &mut m.positions {
        *p += by;
    }
    m
}

#[test]
fn tetrahedron() {
    let r = tetra().report();
    assert!(r.is_closed_manifold(), "{r}");
    assert_eq!(
        (r.triangles, r.vertices, r.edges, r.shells.len()),
        (4, 4, 6, 1)
    );
    assert_eq!(r.genus, Some(0));
    assert_relative_eq!(r.volume, 1.0 / 6.0, max_relative = 1e-14);
}

#[test]
fn cube_is_genus_zero() {
    let r = cube_mesh().report();
    assert!(r.is_closed_manifold(), "{r}");
    assert_eq!((r.triangles, r.vertices, r.edges), (12, 8, 18));
    assert_eq!(r.shells[0].euler_characteristic, 2);
    assert_eq!(r.genus, Some(0));
    assert!(r.closed && r.oriented && r.outward);
    assert_relative_eq!(r.volume, 1.0, max_relative = 1e-14);
    assert_eq!(r.shells[0].volume, r.volume);
}

#[test]
fn torus_is_genus_one() {
    let torus = Solid::torus(2.0, 0.5, 24, 12).unwrap();
    let r = torus.to_mesh().report();
    assert!(r.is_closed_manifold(), "{r}");
    assert_eq!(r.shells[0].euler_characteristic, 0);
    assert_eq!(r.genus, Some(1));
    assert_relative_eq!(r.volume, torus.volume(), max_relative = 1e-12);
}

#[test]
fn sphere_and_cylinder_are_genus_zero() {
    for s in [
        Solid::sphere(1.0, 24, 12).unwrap(),
        Solid::cylinder(1.0, 2.0, 30).unwrap(),
        Solid::cone(1.0, 2.0, 7).unwrap(),
    ] {
        let r = s.to_mesh().report();
        assert!(r.is_closed_manifold(), "{r}");
        assert_eq!(r.genus, Some(0));
    }
}

#[test]
fn open_mesh_has_three_boundary_edges() {
    let mut m = cube_mesh();
    m.triangles.pop();
    m.sources.pop();
    let r = m.report();
    assert_eq!(r.boundary_edges, 3);
    assert!(!r.closed && !r.is_closed_manifold());
    assert!(!r.shells[0].closed);
    assert_eq!(r.genus, None);
    assert_eq!(
        r.non_manifold_vertices, 0,
        "a boundary vertex is one open fan"
    );
}

#[test]
fn flipped_triangle_is_an_orientation_error() {
    let mut m = cube_mesh();
    m.triangles[5].swap(1, 2);
    let r = m.report();
    assert_eq!(r.inconsistent_edges, 3);
    assert!(r.closed, "flipping changes orientation, not closure");
    assert!(!r.oriented && !r.shells[0].oriented);
    assert_eq!(r.shells.len(), 1);
    assert_eq!(r.genus, None);
    assert!(!r.is_closed_manifold());
}

#[test]
fn cubes_touching_at_a_vertex() {
    let m = combine(&[cube_mesh(), moved(&cube_mesh(), DVec3::ONE)]);
    let r = m.report();
    assert_eq!(r.vertices, 15);
    assert_eq!(r.shells.len(), 2);
    assert_eq!(r.non_manifold_vertices, 1);
    assert_eq!((r.boundary_edges, r.non_manifold_edges), (0, 0));
    assert!(r.closed && r.oriented && r.outward);
    assert_eq!(r.genus, Some(0));
    assert!(
        r.shells
            .iter()
            .all(|s| s.genus == Some(0) && s.vertices == 8)
    );
    assert!(!r.is_closed_manifold(), "a pinched vertex is not manifold");
    assert_relative_eq!(r.volume, 2.0, max_relative = 1e-14);
}

#[test]
fn cubes_sharing_an_edge() {
    let m = combine(&[cube_mesh(), moved(&cube_mesh(), DVec3::new(1.0, 1.0, 0.0))]);
    let r = m.report();
    assert_eq!(
        r.shells.len(),
        2,
        "an edge of four triangles does not join shells"
    );
    assert_eq!(r.non_manifold_edges, 1);
    assert_eq!(r.non_manifold_vertices, 2);
    assert!(!r.closed);
    assert!(r.shells.iter().all(|s| s.closed && s.genus == Some(0)));
    assert_eq!(r.genus, Some(0));
}

#[test]
fn three_triangles_on_one_edge() {
    let mut m = tetra();
    m.positions.push(DVec3::new(0.5, -1.0, 0.0));
    m.triangles.push([1, 0, 4]);
    m.sources.push(0);
    let r = m.report();
    assert_eq!(r.non_manifold_edges, 1);
    assert_eq!(r.boundary_edges, 2);
    assert!(!r.closed && !r.is_closed_manifold());
    assert_eq!(r.genus, None);
}

#[test]
fn zero_area_triangle_is_degenerate() {
    let m = tetra_with_zero_area_triangle();
    let r = m.report();
    assert_eq!((r.degenerate_triangles, r.repeated_index_triangles), (1, 0));
    assert!(r.closed && r.oriented);
    assert_eq!(r.genus, Some(0));
    assert!(!r.is_closed_manifold());
    assert!(
        r.to_string()
            .contains("degenerate triangles (zero area): 1"),
        "{r}"
    );
}

#[test]
fn repeated_index_is_degenerate() {
    let mut m = cube_mesh();
    m.triangles.push([3, 3, 5]);
    m.sources.push(0);
    let r = m.report();
    assert_eq!((r.degenerate_triangles, r.repeated_index_triangles), (1, 1));
    assert_eq!(r.edges, 18, "a collapsed triangle adds no edges");
    assert!(!r.is_closed_manifold());
}

#[test]
fn inside_out_cube() {
    let m = Solid::cube(1.0).unwrap().flipped().to_mesh();
    let r = m.report();
    assert!(r.closed && r.oriented);
    assert!(!r.outward);
    assert_eq!(r.inverted_shells, 1);
    assert!(!r.shells[0].cavity);
    assert_relative_eq!(r.volume, -1.0, max_relative = 1e-14);
    assert!(!r.is_closed_manifold());
    assert!(r.to_string().contains("inside out"), "{r}");
}

#[test]
fn cavity_faces_outward() {
    // A cube with a cube-shaped hole: the inner shell has negative volume and is correct.
    let inner = Solid::cube(1.0).unwrap().flipped().to_mesh();
    let m = combine(&[Solid::cube(2.0).unwrap().to_mesh(), inner]);
    let r = m.report();
    assert_eq!(r.shells.len(), 2);
    assert!(r.shells[1].cavity && r.shells[1].volume < 0.0);
    assert!(r.outward && r.is_closed_manifold(), "{r}");
    assert_relative_eq!(r.volume, 7.0, max_relative = 1e-14);
    assert!(r.to_string().contains("1 cavity"), "{r}");

    // The same hole beside the cube instead of inside it is an inside-out solid.
    let beside = Solid::cube(1.0).unwrap().flipped().to_mesh();
    let m = combine(&[cube_mesh(), moved(&beside, DVec3::X * 3.0)]);
    let r = m.report();
    assert!(!r.outward && !r.shells[1].cavity);
    assert_eq!(r.inverted_shells, 1);

    // Nested twice: a ball in the cavity of a ball is outward again.
    let m = combine(&[
        Solid::cube(4.0).unwrap().to_mesh(),
        Solid::cube(3.0).unwrap().flipped().to_mesh(),
        Solid::cube(2.0).unwrap().to_mesh(),
        Solid::cube(1.0).unwrap().flipped().to_mesh(),
    ]);
    let r = m.report();
    assert!(r.is_closed_manifold(), "{r}");
    assert_eq!(r.shells.iter().filter(|s| s.cavity).count(), 2);
}

#[test]
fn empty_mesh() {
    let r = Mesh::default().report();
    assert_eq!(
        (r.triangles, r.vertices, r.edges, r.shells.len()),
        (0, 0, 0, 0)
    );
    assert_eq!(r.genus, Some(0));
    assert_eq!(r.volume, 0.0);
    assert!(r.is_closed_manifold());
    assert!(!r.to_string().is_empty());
}

#[test]
fn display_is_compact() {
    let s = cube_mesh().report().to_string();
    assert_eq!(
        s,
        "12 triangles, 8 vertices, 18 edges, 1 shell: closed 2-manifold, genus 0, volume 1"
    );
    let mut m = cube_mesh();
    m.triangles.pop();
    let s = m.report().to_string();
    assert!(s.contains("NOT a closed 2-manifold"), "{s}");
    assert!(s.contains("boundary edges: 3"), "{s}");
    assert_eq!(s.lines().count(), 2, "{s}");
}

/// Callers match on the kind of defect, not on message text; the file, where there is one,
/// rides beside it.
#[test]
fn mesh_defects_are_structured() {
    let mut open = cube_mesh();
    open.triangles.pop();
    open.sources.pop();
    let e = Solid::from_mesh(&open).unwrap_err();
    assert_eq!(
        e.mesh_defect(),
        Some(&MeshDefect::NotClosed {
            boundary_edges: 3,
            non_manifold_edges: 0,
            inconsistent_edges: 0,
            edges: 18,
        })
    );
    let inverted = Mesh::new(
        cube_mesh().positions,
        cube_mesh()
            .triangles
            .iter()
            .map(|&[a, b, c]| [a, c, b])
            .collect(),
    );
    assert_eq!(
        Solid::from_mesh(&inverted).unwrap_err().mesh_defect(),
        Some(&MeshDefect::InsideOut {
            inverted_shells: 1,
            shells: 1
        })
    );
    let v = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let far = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z * 1e200];
    let tetra_faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
    assert!(matches!(
        Solid::polyhedron(&far, &tetra_faces).unwrap_err().mesh_defect(),
        Some(MeshDefect::BeyondRange { vertices: 1, first: 3, limit, .. })
            if *limit == bspcsg::MAX_COORDINATE
    ));
    assert_eq!(
        Solid::polyhedron(&v, &[[0u32; 0]; 0])
            .unwrap_err()
            .mesh_defect(),
        Some(&MeshDefect::NoFaces)
    );

    // read_solid names the file beside the same defect.
    let dir = std::env::temp_dir().join(format!("bspcsg-defects-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("open.stl");
    bspcsg::write_mesh(&path, &open, &[]).unwrap();
    let e = bspcsg::read_solid(&path, &FromMeshOptions::default()).unwrap_err();
    match &e {
        Error::InvalidMesh {
            path: Some(p),
            defect: MeshDefect::NotClosed { boundary_edges, .. },
        } => {
            assert_eq!(p, &path);
            assert!(*boundary_edges > 0);
        }
        other => panic!("expected a NotClosed defect with the path, got {other:?}"),
    }
    assert!(e.to_string().contains("open.stl is not closed: "), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn mesh_constructors_and_iterator() {
    let cube = cube_mesh();
    let area: f64 = cube
        .triangle_corners()
        .map(|[a, b, c]| 0.5 * (b - a).cross(c - a).length())
        .sum();
    assert_relative_eq!(area, cube.area(), max_relative = 1e-15);
    assert_eq!(cube.triangle_corners().count(), 12);
    let checked = Mesh::try_new(
        cube.positions.clone(),
        cube.triangles.clone(),
        cube.sources.clone(),
    )
    .unwrap();
    assert_eq!(checked, cube);
    let short = Mesh::try_new(cube.positions.clone(), cube.triangles.clone(), vec![0; 11]);
    assert!(matches!(
        short.unwrap_err().mesh_defect(),
        Some(MeshDefect::SourceCount {
            sources: 11,
            triangles: 12
        })
    ));
    let solid = Solid::try_from(&cube).unwrap();
    assert_relative_eq!(solid.volume(), 1.0, max_relative = 1e-14);
}
