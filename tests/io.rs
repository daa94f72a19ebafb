//! Mesh file reading and writing that works: round trips through every format, hand-written
//! files, glTF's transforms and buffers, real meshes, the Khronos validator. Bad input and
//! failed writes are in `io_errors.rs`.

mod common;

use std::collections::HashMap;
use std::fmt::Write as _;
use std::fs;
use std::path::Path;

use base64::Engine as _;
use bspcsg::{Error, Format, Mesh, Solid, read_mesh, write_mesh, write_mesh_as};
use common::hostile::{tetra_buffer, tetra_gltf};
use common::mesh_files::{files_in, materials, scratch, sphere};
use common::models;
use glam::DVec3;

/// A cube and a sphere with different source ids, so writers emit two materials.
fn two_part() -> Mesh {
    let cube = Solid::cube(2.0).unwrap();
    let ball = Solid::sphere(0.8, 32, 16)
        .unwrap()
        .translate(DVec3::new(1.0, 1.0, 1.0))
        .unwrap()
        .with_source(1);
    (&cube | &ball).to_mesh()
}

/// Undirected edges used by exactly one triangle: zero for a closed mesh.
fn boundary_edges(m: &Mesh) -> usize {
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    uses.values().filter(|&&n| n == 1).count()
}

/// The number of distinct float32 positions among the used vertices.
fn f32_positions(m: &Mesh) -> usize {
    let set: std::collections::HashSet<[u32; 3]> = m
        .triangles
        .iter()
        .flatten()
        .map(|&i| {
            m.positions[i as usize]
                .as_vec3()
                .to_array()
                .map(f32::to_bits)
        })
        .collect();
    set.len()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn obj_glb_obj_round_trip_keeps_topology_and_volume() {
    let dir = scratch("round_trip");
    let original = sphere();
    let a = dir.join("a.obj");
    write_mesh(&a, &original, &[]).unwrap();
    let m1 = read_mesh(&a).unwrap();
    // OBJ prints f64 losslessly: the same mesh comes back, bit for bit.
    assert_eq!(m1.positions, original.positions);
    assert_eq!(m1.triangles, original.triangles);

    let b = dir.join("b.glb");
    write_mesh(&b, &m1, &[]).unwrap();
    let m2 = read_mesh(&b).unwrap();
    let c = dir.join("c.obj");
    write_mesh(&c, &m2, &[]).unwrap();
    let m3 = read_mesh(&c).unwrap();

    for m in [&m2, &m3] {
        assert_eq!(m.triangle_count(), original.triangle_count());
        assert_eq!(m.vertex_count(), original.vertex_count());
        assert_eq!(boundary_edges(m), 0);
        // glTF stores float32 positions.
        assert!(rel(m.volume(), original.volume()) < 1e-6);
    }
    assert_eq!(m3, m2);
    assert_eq!(files_in(&dir), ["a.obj", "b.glb", "c.obj"]);
}

#[test]
fn gltf_with_materials_round_trip() {
    let dir = scratch("gltf_materials");
    let original = two_part();
    let p = dir.join("part.gltf");
    write_mesh(&p, &original, &materials()).unwrap();
    assert_eq!(files_in(&dir), ["part.bin", "part.gltf"]);
    let json = fs::read_to_string(&p).unwrap();
    assert!(json.contains(&format!(
        "\"generator\": \"bspcsg {}\"",
        env!("CARGO_PKG_VERSION")
    )));
    assert!(json.contains("\"uri\": \"part.bin\""));
    assert!(json.contains("steel grey"));
    assert!(json.contains("glass"));
    let back = read_mesh(&p).unwrap();
    // The boolean leaves vertices that differ only beyond float32 precision; glTF stores
    // float32, so they weld on reading. STL stores the same float32 values.
    let stl = dir.join("part.stl");
    write_mesh(&stl, &original, &[]).unwrap();
    let via_stl = read_mesh(&stl).unwrap();
    println!(
        "{} -> {} vertices, {} -> {} triangles, {} boundary edges",
        original.vertex_count(),
        back.vertex_count(),
        original.triangle_count(),
        back.triangle_count(),
        boundary_edges(&back)
    );
    assert_eq!(back.vertex_count(), f32_positions(&original));
    assert_eq!(back.vertex_count(), via_stl.vertex_count());
    assert_eq!(back.triangle_count(), via_stl.triangle_count());
    assert!(rel(back.volume(), original.volume()) < 1e-6);
    // Read meshes carry source id 0 throughout.
    assert!(back.sources.iter().all(|&s| s == 0));
}

#[test]
fn obj_with_materials_writes_mtl() {
    let dir = scratch("obj_materials");
    let original = two_part();
    let p = dir.join("part.obj");
    // Only the cube's source has a material; the sphere's gets the default.
    write_mesh(&p, &original, &materials()[..1]).unwrap();
    assert_eq!(files_in(&dir), ["part.mtl", "part.obj"]);
    let obj = fs::read_to_string(&p).unwrap();
    assert!(obj.contains("mtllib part.mtl\n"));
    assert!(obj.contains("usemtl steel_grey\n"));
    assert!(obj.contains("usemtl default\n"));
    let mtl = fs::read_to_string(dir.join("part.mtl")).unwrap();
    assert!(mtl.contains("newmtl steel_grey\nKd 0.6 0.6 0.65\nd 1\n"));
    let back = read_mesh(&p).unwrap();
    assert_eq!(back.triangle_count(), original.triangle_count());
    assert_eq!(back.positions, original.positions);
    assert!(rel(back.volume(), original.volume()) < 1e-12);
}

#[test]
fn binary_stl_round_trip() {
    let dir = scratch("stl_binary");
    let original = sphere();
    let p = dir.join("s.stl");
    write_mesh(&p, &original, &materials()).unwrap();
    let bytes = fs::read(&p).unwrap();
    assert_eq!(bytes.len(), 84 + 50 * original.triangle_count());
    assert!(!bytes.starts_with(b"solid"));
    let back = read_mesh(&p).unwrap();
    assert_eq!(back.triangle_count(), original.triangle_count());
    assert_eq!(back.vertex_count(), original.vertex_count());
    assert_eq!(boundary_edges(&back), 0);
    assert!(rel(back.volume(), original.volume()) < 1e-6);
}

/// ASCII STL text for a mesh, with float32 coordinates as most writers print them.
fn ascii_stl(m: &Mesh) -> String {
    let mut s = String::from("solid test\n");
    for t in 0..m.triangle_count() {
        let [a, b, c] = m.triangle(t);
        let n = (b - a).cross(c - a).normalize_or_zero();
        let _ = writeln!(
            s,
            "  facet normal {} {} {}",
            n.x as f32, n.y as f32, n.z as f32
        );
        s.push_str("    outer loop\n");
        for p in [a, b, c] {
            let _ = writeln!(
                s,
                "      vertex {:e} {:e} {:e}",
                p.x as f32, p.y as f32, p.z as f32
            );
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid test\n");
    s
}

#[test]
fn ascii_stl_reads_like_binary() {
    let dir = scratch("stl_ascii");
    let original = sphere();
    let ascii = dir.join("a.stl");
    fs::write(&ascii, ascii_stl(&original)).unwrap();
    let binary = dir.join("b.stl");
    write_mesh(&binary, &original, &[]).unwrap();
    let a = read_mesh(&ascii).unwrap();
    let b = read_mesh(&binary).unwrap();
    // `{:e}` of an f32 parses back to the same f32, so ASCII and binary agree exactly.
    assert!(a == b, "ASCII and binary STL differ");
    assert_eq!(boundary_edges(&a), 0);
}

#[test]
fn hand_written_ascii_stl() {
    let dir = scratch("stl_hand");
    let p = dir.join("tetra.stl");
    // A unit tetrahedron, outward winding, with the odd spacing and case real files have.
    fs::write(
        &p,
        "solid tetra\r\n\
         facet normal 0 0 -1\n outer loop\n  vertex 0 0 0\n  vertex 0 1 0\n  vertex 1 0 0\n endloop\nendfacet\n\
         FACET NORMAL 0 -1 0\n OUTER LOOP\n  VERTEX 0 0 0\n  VERTEX 1 0 0\n  VERTEX 0 0 1\n ENDLOOP\nENDFACET\n\
         \tfacet normal -1 0 0\n\touter loop\n\t\tvertex 0 0 0\n\t\tvertex 0 0 1\n\t\tvertex 0 1 0\n\tendloop\n\tendfacet\n\
         facet normal 0.57735 0.57735 0.57735\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n\
         endsolid tetra\n",
    )
    .unwrap();
    let m = read_mesh(&p).unwrap();
    assert_eq!(m.triangle_count(), 4);
    assert_eq!(m.vertex_count(), 4);
    assert_eq!(boundary_edges(&m), 0);
    assert!((m.volume() - 1.0 / 6.0).abs() < 1e-15);
}

#[test]
fn gltf_node_transforms_and_mirroring() {
    let dir = scratch("gltf_transform");
    fs::write(dir.join("tetra data.bin"), tetra_buffer()).unwrap();
    let uri = "tetra%20data.bin";

    let plain = dir.join("plain.gltf");
    fs::write(&plain, tetra_gltf(uri, 72, r#"[{"mesh": 0}]"#, "[0]")).unwrap();
    let m = read_mesh(&plain).unwrap();
    assert_eq!(m.triangle_count(), 4);
    assert!((m.volume() - 1.0 / 6.0).abs() < 1e-15);

    // A parent that translates and scales by 2, a child that mirrors x (TRS), and a sibling
    // with the same mirror as a matrix; both children use the mesh.
    let nodes = r#"[
        {"translation": [10, 0, 0], "scale": [2, 2, 2], "children": [1, 2]},
        {"mesh": 0, "scale": [-1, 1, 1]},
        {"mesh": 0, "matrix": [-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1]}
    ]"#;
    let mirrored = dir.join("mirrored.gltf");
    fs::write(&mirrored, tetra_gltf(uri, 72, nodes, "[0]")).unwrap();
    let m = read_mesh(&mirrored).unwrap();
    assert_eq!(m.triangle_count(), 8);
    assert_eq!(m.vertex_count(), 8);
    assert_eq!(boundary_edges(&m), 0);
    // Two tetrahedra scaled by 2, winding reversed by the mirror so volume stays positive.
    assert!(
        (m.volume() - 2.0 * 8.0 / 6.0).abs() < 1e-12,
        "{}",
        m.volume()
    );
    let b = m.bbox();
    assert_eq!(b.min, DVec3::new(8.0, 0.0, 0.0));
    assert_eq!(b.max, DVec3::new(10.0, 2.0, 12.0));
}

#[test]
fn gltf_embedded_buffer_and_glb_without_indices() {
    let dir = scratch("gltf_embedded");
    let data = base64::engine::general_purpose::STANDARD.encode(tetra_buffer());
    let p = dir.join("embedded.gltf");
    let uri = format!("data:application/octet-stream;base64,{data}");
    fs::write(&p, tetra_gltf(&uri, 72, r#"[{"mesh": 0}]"#, "[0]")).unwrap();
    let m = read_mesh(&p).unwrap();
    assert_eq!(m.triangle_count(), 4);

    // The same tetrahedron as a non-indexed primitive in a .glb written by hand.
    let mut bin = Vec::new();
    let corners = [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    for t in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
        for i in t {
            for x in corners[i] {
                bin.extend_from_slice(&x.to_le_bytes());
            }
        }
    }
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":12,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}}],
        "bufferViews":[{{"buffer":0,"byteLength":{n}}}],"buffers":[{{"byteLength":{n}}}]}}"#,
        n = bin.len()
    );
    let mut json = json.into_bytes();
    json.resize(json.len().next_multiple_of(4), b' ');
    let mut glb = Vec::new();
    let total = 12 + 8 + json.len() + 8 + bin.len();
    glb.extend_from_slice(b"glTF");
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&(total as u32).to_le_bytes());
    glb.extend_from_slice(&(json.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&json);
    glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&bin);
    let p = dir.join("flat.glb");
    fs::write(&p, &glb).unwrap();
    let m = read_mesh(&p).unwrap();
    assert_eq!(m.triangle_count(), 4);
    assert_eq!(m.vertex_count(), 4);
    assert!((m.volume() - 1.0 / 6.0).abs() < 1e-15);

    // Every truncation of the GLB is an error, never a panic.
    for len in 0..glb.len() {
        fs::write(&p, &glb[..len]).unwrap();
        assert!(read_mesh(&p).is_err(), "truncated to {len} bytes");
    }
}

#[test]
fn real_meshes_read_watertight_with_known_volumes() {
    let Some(dir) = models() else { return };
    let cases = [
        ("spot.obj", Some(5856), 0.718258788),
        ("fandisk.obj", Some(12946), 20.2433749),
        ("rocker-arm.obj", Some(20088), 0.0425136236),
    ];
    for (name, triangles, volume) in cases {
        let m = read_mesh(dir.join(name)).unwrap();
        if let Some(t) = triangles {
            assert_eq!(m.triangle_count(), t, "{name}");
        }
        assert_eq!(boundary_edges(&m), 0, "{name}");
        assert!(rel(m.volume(), volume) < 1e-8, "{name}: {}", m.volume());
    }
}

#[test]
fn real_meshes_survive_every_format() {
    let Some(models) = models() else { return };
    let dir = scratch("real_formats");
    let m = read_mesh(models.join("rocker-arm.obj")).unwrap();
    for format in Format::ALL {
        let p = dir.join(format!("r.{format}"));
        write_mesh(&p, &m, &[]).unwrap();
        let back = read_mesh(&p).unwrap();
        assert_eq!(back.triangle_count(), m.triangle_count(), "{format}");
        assert_eq!(back.vertex_count(), m.vertex_count(), "{format}");
        assert_eq!(boundary_edges(&back), 0, "{format}");
        assert!(rel(back.volume(), m.volume()) < 1e-6, "{format}");
    }
    // The open scan reads (it is the solid constructors' job to refuse it).
    let bunny = read_mesh(models.join("stanford-bunny.obj")).unwrap();
    assert_eq!(boundary_edges(&bunny), 223);
}

#[test]
fn khronos_validator_accepts_written_gltf() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    if !root.join("node_modules/gltf-validator").is_dir() {
        eprintln!("skipped: run `npm install` for node_modules/gltf-validator");
        return;
    }
    let dir = scratch("validator");
    let mut files = Vec::new();
    for (name, mesh, mats) in [
        ("sphere", sphere(), vec![]),
        ("parts", two_part(), materials()),
        ("empty", Mesh::default(), vec![]),
    ] {
        for ext in ["gltf", "glb"] {
            let p = dir.join(format!("{name} file.{ext}"));
            write_mesh(&p, &mesh, &mats).unwrap();
            files.push(p);
        }
    }
    let out = match std::process::Command::new("node")
        .arg(root.join("tests/gltf/validate.mjs"))
        .args(&files)
        .output()
    {
        Ok(o) => o,
        Err(e) => {
            eprintln!("skipped: cannot run node: {e}");
            return;
        }
    };
    let stdout = String::from_utf8_lossy(&out.stdout);
    println!("{stdout}{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "validator reported errors:\n{stdout}");
    assert_eq!(stdout.matches(": 0 errors").count(), files.len());
}

/// An L-shaped prism as Blender writes it: two concave hexagonal caps and six quads. Each cap
/// starts at a corner that does not see the whole face, so fanning it (what tobj did) folds a
/// triangle outside the L: area 15 instead of 14.
const L_PRISM_OBJ: &str = "\
# L-shaped prism: [0,2]x[0,1] ∪ [0,1]x[0,2], z in [0,1]
v 0 0 0
v 2 0 0
v 2 1 0
v 1 1 0
v 1 2 0
v 0 2 0
v 0 0 1
v 2 0 1
v 2 1 1
v 1 1 1
v 1 2 1
v 0 2 1
f 8 9 10 11 12 7
f 2 1 6 5 4 3
f 1 2 8 7
f 2 3 9 8
f 3 4 10 9
f 4 5 11 10
f 5 6 12 11
f 6 1 7 12
";

#[test]
fn obj_concave_ngon_caps_keep_their_area() {
    let dir = scratch("l_prism");
    let path = dir.join("l_prism.obj");
    fs::write(&path, L_PRISM_OBJ).unwrap();
    let mesh = read_mesh(&path).unwrap();
    assert!((mesh.area() - 14.0).abs() < 1e-12, "area {}", mesh.area());
    assert!(
        (mesh.volume() - 3.0).abs() < 1e-12,
        "volume {}",
        mesh.volume()
    );
    let report = mesh.report();
    assert!(report.is_closed_manifold(), "{report}");
    assert_eq!(report.genus, Some(0));

    // Booleans with it are exact: filling the notch gives the 2×2×1 box, cutting a unit
    // corner away leaves two unit cubes' worth.
    let l = Solid::from_mesh(&mesh).unwrap();
    let notch = Solid::cube(1.0)
        .unwrap()
        .translate(DVec3::new(1.5, 1.5, 0.5))
        .unwrap();
    let corner = Solid::cube(1.0)
        .unwrap()
        .translate(DVec3::splat(0.5))
        .unwrap();
    let filled = (&l | &notch).to_mesh();
    assert!(filled.report().is_closed_manifold());
    assert!((filled.volume() - 4.0).abs() < 1e-12, "{}", filled.volume());
    assert!((filled.area() - 16.0).abs() < 1e-12, "{}", filled.area());
    let cut = (&l - &corner).to_mesh();
    assert!(cut.report().is_closed_manifold());
    assert!((cut.volume() - 2.0).abs() < 1e-12, "{}", cut.volume());
    assert!((cut.area() - 12.0).abs() < 1e-12, "{}", cut.area());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn encode_mesh_gives_the_bytes_write_mesh_writes() {
    let dir = scratch("encode");
    let mesh = two_part();
    let mats = materials();
    for format in Format::ALL {
        for materials in [&mats[..], &[]] {
            let path = dir.join(format!("part.{format}"));
            let encoded = bspcsg::encode_mesh(&path, &mesh, materials, format).unwrap();
            assert_eq!(encoded[0].path, path, "{format}: the main file comes first");
            let expected_files = match format {
                Format::Gltf => 2,
                Format::Obj if !materials.is_empty() => 2,
                _ => 1,
            };
            assert_eq!(encoded.len(), expected_files, "{format}");
            write_mesh_as(&path, &mesh, materials, format).unwrap();
            for file in &encoded {
                assert_eq!(file.path.parent(), Some(dir.as_path()));
                let written = fs::read(&file.path).unwrap();
                assert_eq!(written, file.bytes, "{}", file.path.display());
            }
            // What was encoded reads back as the mesh.
            let back = read_mesh(&path).unwrap();
            assert_eq!(back.triangle_count(), mesh.triangle_count(), "{format}");
            assert!(rel(back.volume(), mesh.volume()) < 1e-5, "{format}");
            for file in &encoded {
                fs::remove_file(&file.path).unwrap();
            }
        }
    }
    // Nothing is written by encoding, and a companion that would be the file itself is refused.
    let clash = bspcsg::encode_mesh(dir.join("part.bin"), &mesh, &[], Format::Gltf);
    assert!(matches!(clash, Err(Error::Io { .. })), "{clash:?}");
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
}
