//! Mesh validation reports and mesh input, on built meshes and on the shared real-world models.

mod common;

use std::collections::HashMap;

use approx::assert_relative_eq;
use bspcsg::{Error, FromMeshOptions, Mesh, MeshDefect, MeshReport, Solid};
use common::models;
use glam::DVec3;

fn cube_mesh() -> Mesh {
    Solid::cube(1.0).unwrap().to_mesh()
}

fn tetra() -> Mesh {
    Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    )
}

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

fn weld(mut m: Mesh) -> Mesh {
    let mut map: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let remap: Vec<u32> = m
        .positions
        .iter()
        .map(|p| {
            let key = (*p + DVec3::ZERO).to_array().map(f64::to_bits);
            *map.entry(key).or_insert_with(|| {
                positions.push(*p);
                positions.len() as u32 - 1
            })
        })
        .collect();
    for t in &mut m.triangles {
        *t = t.map(|i| remap[i as usize]);
    }
    m.positions = positions;
    m
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

/// The tetrahedron with edge 0-1 split at m on one side only, and the crack closed by the
/// zero-area triangle [1, 0, m]: closed and oriented, but degenerate.
fn tetra_with_zero_area_triangle() -> Mesh {
    let mut m = tetra();
    m.positions.push(DVec3::new(0.5, 0.0, 0.0));
    m.triangles[0] = [0, 2, 4];
    m.triangles.push([4, 2, 1]);
    m.triangles.push([1, 0, 4]);
    m.sources.resize(m.triangles.len(), 0);
    m
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

fn invalid_message(r: bspcsg::Result<Solid>) -> String {
    match r {
        Err(Error::InvalidMesh { path: None, defect }) => defect.to_string(),
        other => panic!("expected InvalidMesh, got {other:?}"),
    }
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

fn merged(m: &Mesh) -> Solid {
    let options = FromMeshOptions::default().with_merge_coplanar(true);
    Solid::from_mesh_with(m, &options).unwrap()
}

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
