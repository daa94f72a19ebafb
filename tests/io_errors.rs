//! Mesh files that cannot be read or written: unsupported glTF, cycles and bad indices,
//! truncated and garbage bytes, OBJ errors naming file and line, empty files, coinciding
//! corners, missing files, unknown extensions, and writes that fail leaving nothing behind.

mod common;

use std::fs;
use std::path::Path;

use bspcsg::{
    Error, Format, FromMeshOptions, Material, Mesh, MeshDefect, Solid, read_mesh, read_mesh_as,
    read_solid, write_mesh, write_mesh_as,
};
use common::hostile::{tetra_buffer, tetra_gltf};
use common::mesh_files::{files_in, materials, scratch, sphere};

#[test]
fn gltf_lines_are_unsupported() {
    let dir = scratch("gltf_lines");
    fs::write(dir.join("t.bin"), tetra_buffer()).unwrap();
    let p = dir.join("lines.gltf");
    let text = tetra_gltf("t.bin", 72, r#"[{"mesh": 0}]"#, "[0]")
        .replace(r#""indices": 1}"#, r#""indices": 1, "mode": 1}"#);
    fs::write(&p, text).unwrap();
    assert!(matches!(read_mesh(&p), Err(Error::Unsupported { .. })));
}

#[test]
fn gltf_cycle_and_bad_indices_are_errors() {
    let dir = scratch("gltf_bad");
    fs::write(dir.join("t.bin"), tetra_buffer()).unwrap();
    let p = dir.join("cycle.gltf");
    let nodes = r#"[{"mesh": 0, "children": [1]}, {"children": [0]}]"#;
    fs::write(&p, tetra_gltf("t.bin", 72, nodes, "[0]")).unwrap();
    assert!(matches!(read_mesh(&p), Err(Error::Parse { .. })));

    // Index 9 of 4 vertices.
    let mut buf = tetra_buffer();
    buf[48..50].copy_from_slice(&9u16.to_le_bytes());
    fs::write(dir.join("t.bin"), &buf).unwrap();
    let p = dir.join("index.gltf");
    fs::write(&p, tetra_gltf("t.bin", 72, r#"[{"mesh": 0}]"#, "[0]")).unwrap();
    let e = read_mesh(&p).unwrap_err().to_string();
    assert!(e.contains("vertex 9"), "{e}");

    // A buffer shorter than its byteLength.
    fs::write(dir.join("t.bin"), &buf[..40]).unwrap();
    assert!(matches!(read_mesh(&p), Err(Error::Parse { .. })));

    // A missing .bin names the .gltf that needs it, and the .bin.
    fs::remove_file(dir.join("t.bin")).unwrap();
    match read_mesh(&p) {
        Err(e @ Error::Io { .. }) => {
            let Error::Io { path, source } = &e else {
                unreachable!()
            };
            assert!(path.ends_with(p.file_name().unwrap()), "{e}");
            assert!(source.to_string().contains("t.bin"), "{e}");
            assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn truncated_binary_stl() {
    let dir = scratch("stl_truncated");
    let p = dir.join("s.stl");
    write_mesh(&p, &sphere(), &[]).unwrap();
    let bytes = fs::read(&p).unwrap();
    for len in [0, 10, 80, 83, 84, 100, bytes.len() - 1, bytes.len() - 50] {
        fs::write(&p, &bytes[..len]).unwrap();
        let e = read_mesh(&p);
        assert!(matches!(e, Err(Error::Parse { .. })), "{len}: {e:?}");
    }
    // Cut at a record boundary and with the count left alone: still refused.
    fs::write(&p, &bytes[..84 + 50 * 10]).unwrap();
    let e = read_mesh(&p).unwrap_err().to_string();
    assert!(e.contains("s.stl") && e.contains("triangles"), "{e}");
}

#[test]
fn garbage_bytes_are_errors_in_every_format() {
    let dir = scratch("garbage");
    // A simple deterministic byte soup (xorshift), including NULs and newlines.
    let mut x = 0x9E37_79B9_7F4A_7C15u64;
    let mut bytes = Vec::new();
    for _ in 0..5000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        bytes.push((x >> 24) as u8);
    }
    for prefix in [&b""[..], b"solid ", b"glTF\x02\0\0\0", b"v 1 2 3\nf "] {
        for format in Format::ALL {
            let p = dir.join(format!("g.{format}"));
            let mut data = prefix.to_vec();
            data.extend_from_slice(&bytes);
            fs::write(&p, &data).unwrap();
            let r = read_mesh_as(&p, format);
            assert!(r.is_err(), "{format} with prefix {prefix:?}");
        }
    }
}

#[test]
fn obj_errors_name_file_and_line() {
    let dir = scratch("obj_errors");
    let p = dir.join("bad.obj");
    let cases = [
        ("v 0 0 0\nv 1 0 0\nv 0 NaN 0\nf 1 2 3\n", 3),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n# x\nf 1 2 4\n", 5),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", 4),
        ("v 0 0 0\nv 1 0 zero\n", 2),
    ];
    for (text, line) in cases {
        fs::write(&p, text).unwrap();
        let e = read_mesh(&p).unwrap_err();
        let shown = e.to_string();
        assert!(shown.contains(&format!("bad.obj:{line}:")), "{shown}");
        assert!(matches!(e, Error::Parse { line: Some(l), .. } if l == line));
    }
}

/// A zero-byte file is an error (a write that never happened); a well-formed file with no
/// faces is the empty mesh, so an empty result written and read back is empty again.
#[test]
fn empty_files_are_errors_and_files_of_no_faces_are_the_empty_mesh() {
    let dir = scratch("empty");
    for name in ["e.obj", "e.stl", "e.gltf", "e.glb"] {
        let p = dir.join(name);
        fs::write(&p, "").unwrap();
        let e = read_mesh(&p).unwrap_err();
        assert!(matches!(e, Error::Parse { .. }), "{name}");
        assert!(e.to_string().contains("the file is empty"), "{e}");
        fs::write(&p, " \n\t\n").unwrap();
        assert!(
            read_mesh(&p)
                .unwrap_err()
                .to_string()
                .contains("the file is empty")
        );
    }
    // Well-formed files with no faces.
    for (name, text) in [
        ("comments.obj", "# nothing here\ng empty\nmtllib e.mtl\n"),
        ("solid.stl", "solid empty\nendsolid empty\n"),
        ("none.gltf", r#"{"asset": {"version": "2.0"}}"#),
    ] {
        let p = dir.join(name);
        fs::write(&p, text).unwrap();
        assert!(read_mesh(&p).unwrap().is_empty(), "{name}");
    }
    // Not empty but not a surface: vertices without faces, faces that all repeat a vertex,
    // and text that is not OBJ at all.
    for (name, text, message) in [
        (
            "verts.obj",
            "v 0 0 0\nv 1 0 0\n",
            "holds 2 vertices but no faces",
        ),
        (
            "degenerate.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\nf 2 3 3\n",
            "all 2 triangles repeat a vertex",
        ),
        (
            "prose.obj",
            "# a note\nhello world\n",
            "prose.obj:2: the file holds no faces, and `hello`",
        ),
    ] {
        let p = dir.join(name);
        fs::write(&p, text).unwrap();
        let e = read_mesh(&p).unwrap_err();
        assert!(matches!(e, Error::Parse { .. }), "{name}: {e:?}");
        assert!(e.to_string().contains(message), "{name}: {e}");
    }
    // The writers' output for an empty mesh reads back as the empty mesh, and as the empty
    // solid: A ∪ ∅ = A, A − ∅ = A, A ∩ ∅ = ∅.
    let empty = Mesh::default();
    let a = Solid::cube(1.0).unwrap();
    for format in Format::ALL {
        let p = dir.join(format!("out.{format}"));
        write_mesh(&p, &empty, &[]).unwrap();
        assert!(read_mesh(&p).unwrap().is_empty(), "{format}");
        let nothing = read_solid(&p, &FromMeshOptions::default()).unwrap();
        assert!(nothing.is_empty(), "{format}");
        assert_eq!((&a | &nothing).volume(), 1.0, "{format}");
        assert_eq!((&a - &nothing).volume(), 1.0, "{format}");
        assert!((&a & &nothing).is_empty(), "{format}");
    }
}

/// Distinct corners whose coordinates coincide are geometry, not a damaged file: a mesh that
/// bounds nothing (exit 2 on the command line), as when triangles keep their corners but lose
/// their area. A box of 3·10⁻⁶ at 10¹¹, where floats are 1.5·10⁻⁵ apart, is written as eight
/// equal vertices; it was refused as a file that "repeats a vertex" (exit 1).
#[test]
fn a_mesh_whose_distinct_corners_coincide_is_refused_as_geometry() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("coincident-corners");
    fs::create_dir_all(&dir).unwrap();
    let far = format!(
        "{}f 1 2 4\nf 1 4 3\nf 5 7 8\nf 5 8 6\nf 1 5 6\nf 1 6 2\nf 3 4 8\nf 3 8 7\nf 1 3 7\nf 1 7 5\nf 2 6 8\nf 2 8 4\n",
        "v 1e11 1e11 1e11\n".repeat(8)
    );
    for (name, text) in [
        ("far.obj", far.as_str()),
        (
            "coincident.stl",
            "solid d\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid d\n",
        ),
        (
            "coincident.obj",
            "v 0 0 0\nv 0 0 0\nv 1 0 0\nv 1 0 0\nf 1 2 3\nf 3 4 1\n",
        ),
        ("origin.obj", "v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 3\n"),
    ] {
        let p = dir.join(name);
        fs::write(&p, text).unwrap();
        let e = read_mesh(&p).unwrap_err();
        assert!(
            matches!(
                e,
                Error::InvalidMesh {
                    defect: MeshDefect::AllZeroArea { .. },
                    ..
                }
            ),
            "{name}: {e:?}"
        );
        assert!(e.to_string().contains(name), "{name}: {e}");
        // Only a mesh away from the origin is told to move nearer it.
        let at_origin = name == "origin.obj";
        assert_eq!(
            e.to_string().contains("move it nearer the origin"),
            !at_origin,
            "{name}: {e}"
        );
    }
}

#[test]
fn missing_file_names_the_path() {
    let p = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no/such/mesh.obj");
    match read_mesh(&p) {
        Err(e @ Error::Io { .. }) => {
            assert!(e.to_string().contains("no/such/mesh.obj"), "{e}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn unknown_extension() {
    let e = read_mesh(Path::new("mesh.ply")).unwrap_err();
    assert!(matches!(e, Error::Unsupported { .. }));
    assert!(e.to_string().contains(".ply"));
    let e = write_mesh(Path::new("mesh"), &sphere(), &[]).unwrap_err();
    assert!(matches!(e, Error::Unsupported { .. }));
    // An explicit format overrides the extension.
    let dir = scratch("override");
    let p = dir.join("mesh.dat");
    write_mesh_as(&p, &sphere(), &[], "glb".parse().unwrap()).unwrap();
    assert_eq!(
        read_mesh_as(&p, Format::Glb).unwrap().triangle_count(),
        sphere().triangle_count()
    );
}

#[test]
fn failed_writes_leave_nothing_behind() {
    let dir = scratch("unwritable");
    let mesh = sphere();
    for format in Format::ALL {
        let p = dir.join("missing-dir").join(format!("x.{format}"));
        let e = write_mesh(&p, &mesh, &materials()).unwrap_err();
        match e {
            Error::Io { path, .. } => assert!(path.starts_with(dir.join("missing-dir"))),
            other => panic!("{other:?}"),
        }
    }
    assert!(files_in(&dir).is_empty());

    // A refused mesh leaves an existing file untouched and no temporary files.
    let p = dir.join("keep.glb");
    fs::write(&p, b"old").unwrap();
    let mut bad = mesh.clone();
    bad.positions[0].x = 1e300; // beyond float32
    assert!(matches!(
        write_mesh(&p, &bad, &[]),
        Err(Error::InvalidMesh {
            defect: MeshDefect::TooLargeForFormat { .. },
            ..
        })
    ));
    bad.triangles[0][0] = u32::MAX;
    assert!(matches!(
        write_mesh(&p, &bad, &[]),
        Err(Error::InvalidMesh {
            defect: MeshDefect::IndexOutOfRange {
                index: u32::MAX,
                ..
            },
            ..
        })
    ));
    let bad_colour = [Material {
        name: "x".into(),
        base_color: [1.5, 0.0, 0.0, 1.0],
    }];
    assert!(matches!(
        write_mesh(&p, &mesh, &bad_colour),
        Err(Error::InvalidParameter { .. })
    ));
    assert_eq!(fs::read(&p).unwrap(), b"old");
    // A directory in the way of the output: the rename fails, the temporary is removed.
    fs::create_dir(dir.join("taken.obj")).unwrap();
    assert!(write_mesh(dir.join("taken.obj"), &mesh, &[]).is_err());
    assert_eq!(files_in(&dir), ["keep.glb", "taken.obj"]);
    // A successful write replaces the old content.
    write_mesh(&p, &mesh, &[]).unwrap();
    assert_eq!(
        read_mesh(&p).unwrap().triangle_count(),
        mesh.triangle_count()
    );
    assert_eq!(files_in(&dir), ["keep.glb", "taken.obj"]);
}
