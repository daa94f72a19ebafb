//! Mesh input: `Solid::from_mesh` (round trips, sources, refusals with counts, zero-area
//! triangles, polyhedra) and merging coplanar triangles back into polygons, on built meshes.

mod common;

use approx::assert_relative_eq;
use bspcsg::{FromMeshOptions, Mesh, Solid};
use common::mesh_input::{cube_mesh, invalid_message, merged, tetra_with_zero_area_triangle};
use glam::DVec3;

// ---- Solid::from_mesh ----

#[test]
fn from_mesh_round_trip() {
    for s in [
        Solid::cube(1.0).unwrap(),
        Solid::torus(2.0, 0.5, 16, 8).unwrap(),
        Solid::sphere(1.0, 16, 8).unwrap(),
    ] {
        let back = Solid::from_mesh(&s.to_mesh()).unwrap();
        assert_relative_eq!(back.volume(), s.volume(), max_relative = 1e-12);
        assert_relative_eq!(back.area(), s.area(), max_relative = 1e-12);
        // The solid works in booleans: bite a corner off where its surface is.
        let on_surface = back.polygons()[0].vertices()[0];
        let bite = Solid::cube(0.2).unwrap().translate(on_surface).unwrap();
        let d = &back - &bite;
        assert!(d.volume() < back.volume());
    }
}

#[test]
fn from_mesh_keeps_sources() {
    let mut m = cube_mesh();
    for (t, s) in m.sources.iter_mut().enumerate() {
        *s = t as u32 / 2;
    }
    let solid =
        Solid::from_mesh_with(&m, &FromMeshOptions::default().with_merge_coplanar(false)).unwrap();
    assert_eq!(solid.polygon_count(), 12);
    let mut sources: Vec<u32> = solid.polygons().iter().map(|p| p.source()).collect();
    sources.sort();
    assert_eq!(sources, [0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5]);
    // By default each face's two triangles, of one source, merge into one quad.
    let merged = Solid::from_mesh(&m).unwrap();
    let mut sources: Vec<u32> = merged.polygons().iter().map(|p| p.source()).collect();
    sources.sort();
    assert_eq!(sources, [0, 1, 2, 3, 4, 5]);
}

#[test]
fn from_mesh_refuses_open_with_counts() {
    let mut m = cube_mesh();
    m.triangles.pop();
    m.sources.pop();
    let msg = invalid_message(Solid::from_mesh(&m));
    assert!(
        msg.contains("not closed: 3 boundary edges (of 18 edges)"),
        "{msg}"
    );
    // The lenient path goes on.
    let lenient = FromMeshOptions::lenient().with_merge_coplanar(false);
    let lenient = Solid::from_mesh_with(&m, &lenient).unwrap();
    assert_eq!(lenient.polygon_count(), 11);
}

#[test]
fn from_mesh_refuses_bad_input() {
    let mut flipped = cube_mesh();
    flipped.triangles[0].swap(0, 1);
    let msg = invalid_message(Solid::from_mesh(&flipped));
    assert!(msg.contains("3 inconsistently oriented edges"), "{msg}");

    let mut out_of_range = cube_mesh();
    out_of_range.triangles[2][1] = 8;
    let msg = invalid_message(Solid::from_mesh(&out_of_range));
    assert!(
        msg.contains("faces with a vertex index out of range: 1"),
        "{msg}"
    );
    let msg = invalid_message(Solid::from_mesh_with(
        &out_of_range,
        &FromMeshOptions::lenient(),
    ));
    assert!(
        msg.contains("out of range"),
        "lenient still needs valid indices: {msg}"
    );

    let mut nan = cube_mesh();
    nan.positions[3].y = f64::NAN;
    let msg = invalid_message(Solid::from_mesh(&nan));
    assert!(
        msg.contains("vertices with a non-finite coordinate: 1"),
        "{msg}"
    );
    // An unused non-finite position is harmless.
    let mut unused = cube_mesh();
    unused.positions.push(DVec3::INFINITY);
    assert!(Solid::from_mesh(&unused).is_ok());

    let mut repeated = cube_mesh();
    repeated.triangles.push([1, 1, 2]);
    repeated.sources.push(0);
    let msg = invalid_message(Solid::from_mesh(&repeated));
    assert!(msg.contains("faces that repeat a vertex index: 1"), "{msg}");
    let lenient = FromMeshOptions::lenient().with_merge_coplanar(false);
    let lenient = Solid::from_mesh_with(&repeated, &lenient).unwrap();
    assert_eq!(lenient.polygon_count(), 12);

    let mut sources = cube_mesh();
    sources.sources.pop();
    let msg = invalid_message(Solid::from_mesh(&sources));
    assert!(msg.contains("11 source ids for 12 triangles"), "{msg}");
}

#[test]
fn from_mesh_skips_zero_area() {
    let m = tetra_with_zero_area_triangle();
    let s = Solid::from_mesh(&m).unwrap();
    assert_eq!(s.polygon_count(), 5);
    assert_relative_eq!(s.volume(), 1.0 / 6.0, max_relative = 1e-14);
}

#[test]
fn from_empty_mesh_is_empty() {
    assert!(Solid::from_mesh(&Mesh::default()).unwrap().is_empty());
}

#[test]
fn polyhedron_shares_the_checks() {
    let v = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let open = Solid::polyhedron(&v, &[[0, 2, 1], [0, 1, 3], [1, 2, 3]]);
    let msg = invalid_message(open);
    assert!(msg.contains("not closed: 3 boundary edges"), "{msg}");
    let bad = Solid::polyhedron(&v, &[[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 9]]);
    assert!(invalid_message(bad).contains("out of range"));
}

// ---- Merging coplanar triangles ----

#[test]
fn merge_restores_the_polygons_of_primitives() {
    for s in [
        Solid::cube(1.0).unwrap(),
        Solid::cylinder(1.0, 2.0, 30).unwrap(),
        Solid::cone(1.0, 2.0, 7).unwrap(),
        Solid::sphere(1.0, 16, 8).unwrap(),
        Solid::torus(2.0, 0.5, 16, 8).unwrap(),
    ] {
        let mesh = s.to_mesh();
        let back = merged(&mesh);
        assert_eq!(back.polygon_count(), s.polygon_count());
        assert_relative_eq!(back.volume(), s.volume(), max_relative = 1e-12);
        assert_relative_eq!(back.area(), s.area(), max_relative = 1e-12);
        // The same vertices and edges: meshing it again gives a closed manifold.
        let again = back.to_mesh();
        assert_eq!(again.positions.len(), mesh.positions.len());
        assert!(again.report().is_closed_manifold());
    }
}

#[test]
fn merge_respects_sources() {
    let mut m = cube_mesh();
    for (t, s) in m.sources.iter_mut().enumerate() {
        *s = t as u32;
    }
    assert_eq!(merged(&m).polygon_count(), 12);
}

#[test]
fn merge_keeps_convexity() {
    // An L-shaped prism: its L faces need at least two convex pieces each.
    let mut v = Vec::new();
    for z in [0.0, 1.0] {
        for (x, y) in [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)] {
            v.push(DVec3::new(x, y, z));
        }
    }
    let bottom: Vec<u32> = (0..6).rev().collect();
    let top: Vec<u32> = (6..12).collect();
    let mut faces = vec![bottom, top];
    for i in 0..6 {
        let j = (i + 1) % 6;
        faces.push(vec![i, j, j + 6, i + 6]);
    }
    let l = Solid::polyhedron(&v, &faces).unwrap();
    let back = merged(&l.to_mesh());
    assert_eq!(back.polygon_count(), 6 + 2 * 2);
    for p in back.polygons() {
        let vs = p.vertices();
        for k in 0..vs.len() {
            let (a, b, c) = (vs[k], vs[(k + 1) % vs.len()], vs[(k + 2) % vs.len()]);
            assert!(
                (b - a).cross(c - b).dot(p.plane().normal()) > 0.0,
                "not convex: {vs:?}"
            );
        }
    }
    assert_relative_eq!(back.volume(), 3.0, max_relative = 1e-12);
    let cut = &back - &Solid::cube(1.0).unwrap();
    assert_relative_eq!(cut.volume(), 3.0 - 0.125, max_relative = 1e-12);
}
