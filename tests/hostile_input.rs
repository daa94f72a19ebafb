//! Hostile and extreme input to the readers: glTF buffer URIs held to the document's folder,
//! the reader's triangle budget after instancing, byte-order marks, repeated JSON keys, empty
//! files and small messages (issue 12). Inputs that cost time or memory (crossing pairs, flat
//! soups, crafted hash collisions) are in `hostile_costs.rs`. Every input is small and
//! generated here.

mod common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use bspcsg::{Error, MAX_READ_TRIANGLES, read_mesh};
use common::box_obj_text;
use common::hostile::{tetra_buffer, tetra_gltf};
use common::run::{Scratch, bspcsg, refused};

/// Writes `sub/doc.gltf` naming `uri` and returns its path.
fn doc_with_uri(s: &Scratch, uri: &str, byte_length: u64) -> PathBuf {
    let dir = s.path("sub");
    fs::create_dir_all(&dir).unwrap();
    let p = dir.join("doc.gltf");
    fs::write(&p, tetra_gltf(uri, byte_length, r#"[{"mesh": 0}]"#, "[0]")).unwrap();
    p
}

/// Asserts that reading `doc` fails with a message naming the document and the URI.
fn read_refused(doc: &Path, uri: &str, why: &str) -> String {
    let e = read_mesh(doc).expect_err(uri);
    let msg = e.to_string();
    assert!(
        msg.contains(&doc.display().to_string()) && msg.contains(uri) && msg.contains(why),
        "{uri}: {msg}"
    );
    assert!(
        matches!(e, Error::Unsupported { .. } | Error::Parse { .. }),
        "{uri}: {e:?}"
    );
    msg
}

/// Item 7: a buffer URI is a regular file inside the glTF's own folder, its size checked
/// before reading.
#[test]
fn gltf_buffer_uri_stays_in_the_document_folder() {
    let s = Scratch::new("uri");
    fs::write(s.path("outside.bin"), tetra_buffer()).unwrap();
    let doc = doc_with_uri(&s, "inside.bin", 72);
    fs::write(s.path("sub/inside.bin"), tetra_buffer()).unwrap();
    assert_eq!(read_mesh(&doc).unwrap().triangle_count(), 4);

    // Absolute paths, `..` plain and percent-encoded, `file:`: refused before any file access.
    let abs = s.path("outside.bin").display().to_string();
    for uri in [
        abs.as_str(),
        "../outside.bin",
        "%2E%2E/outside.bin",
        "..%2Foutside.bin",
        "./../sub/../outside.bin",
        "../../../../../../etc/passwd",
        "file:///etc/passwd",
    ] {
        let doc = doc_with_uri(&s, uri, 72);
        read_refused(&doc, uri, "");
    }
    let doc = doc_with_uri(&s, "../outside.bin", 72);
    read_refused(&doc, "../outside.bin", "no `..`");

    // A symbolic link inside the folder that leads out of it: to a file, to /dev/zero.
    std::os::unix::fs::symlink(s.path("outside.bin"), s.path("sub/link.bin")).unwrap();
    let doc = doc_with_uri(&s, "link.bin", 72);
    read_refused(&doc, "link.bin", "outside the document's folder");
    std::os::unix::fs::symlink("/dev/zero", s.path("sub/zero.bin")).unwrap();
    let doc = doc_with_uri(&s, "zero.bin", 72);
    read_refused(&doc, "zero.bin", "outside the document's folder");
    // A link that stays inside is followed.
    std::os::unix::fs::symlink("inside.bin", s.path("sub/alias.bin")).unwrap();
    let doc = doc_with_uri(&s, "alias.bin", 72);
    assert_eq!(read_mesh(&doc).unwrap().triangle_count(), 4);

    // A FIFO would block forever on open; a directory is no buffer either. Both answer at once.
    let fifo = s.path("sub/fifo.bin");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let t = Instant::now();
    let doc = doc_with_uri(&s, "fifo.bin", 72);
    read_refused(&doc, "fifo.bin", "not a regular file");
    assert!(t.elapsed() < Duration::from_secs(5));
    fs::create_dir(s.path("sub/dir.bin")).unwrap();
    let doc = doc_with_uri(&s, "dir.bin", 72);
    read_refused(&doc, "dir.bin", "not a regular file");

    // Sizes: a file shorter than byteLength, a byteLength beyond the per-buffer limit.
    let doc = doc_with_uri(&s, "inside.bin", 73);
    read_refused(&doc, "inside.bin", "fewer than the buffer's byteLength 73");
    let doc = doc_with_uri(&s, "inside.bin", 1 << 40);
    read_refused(&doc, "inside.bin", "exceeds the limit");

    // Through the CLI: exit 1, the message names the document and the URI, nothing written.
    let doc = doc_with_uri(&s, "../../../../../../etc/passwd", 72);
    let out = s.path("out.obj");
    refused(
        &["convert".as_ref(), doc.as_os_str()],
        &out,
        1,
        &["etc/passwd"],
    );
}

/// A mesh of `n` triangles (a fan over four corners repeated), drawn by `instances` nodes.
fn instanced_doc(s: &Scratch, name: &str, n: usize, instances: usize) -> PathBuf {
    let mut buf = tetra_buffer();
    buf.truncate(48);
    for k in 0..n {
        let t = [[0u16, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]][k % 4];
        for i in t {
            buf.extend_from_slice(&i.to_le_bytes());
        }
    }
    fs::write(s.path(&format!("{name}.bin")), &buf).unwrap();
    let nodes: Vec<String> = (0..instances)
        .map(|k| format!(r#"{{"mesh":0,"translation":[{k},0,0]}}"#))
        .collect();
    let roots: Vec<String> = (0..instances).map(|k| k.to_string()).collect();
    let json = tetra_gltf(
        &format!("{name}.bin"),
        buf.len() as u64,
        &format!("[{}]", nodes.join(",")),
        &format!("[{}]", roots.join(",")),
    )
    .replace(r#""count": 12"#, &format!(r#""count": {}"#, 3 * n))
    .replace(
        r#""byteOffset": 48, "byteLength": 24"#,
        &format!(r#""byteOffset": 48, "byteLength": {}"#, 6 * n),
    );
    let p = s.path(&format!("{name}.gltf"));
    fs::write(&p, json).unwrap();
    p
}

/// Item 1: the reader's budget counts triangles after instancing and refuses before
/// allocating them.
#[test]
fn gltf_instancing_over_the_triangle_budget_is_refused_quickly() {
    let s = Scratch::new("budget");
    // One 1,200-triangle mesh placed 20,000 times: 24 million triangles from a small file.
    let doc = instanced_doc(&s, "many", 1200, 20_000);
    let size = fs::metadata(&doc).unwrap().len();
    assert!(size < 1_000_000, "{size} bytes");
    let t = Instant::now();
    let e = read_mesh(&doc).unwrap_err();
    let took = t.elapsed();
    assert!(matches!(e, Error::OverBudget { .. }), "{e:?}");
    let msg = e.to_string();
    assert!(
        msg.contains("24000000 triangles")
            && msg.contains("20000 mesh instances")
            && msg.contains(&MAX_READ_TRIANGLES.to_string())
            && msg.contains("many.gltf"),
        "{msg}"
    );
    assert!(took < Duration::from_secs(2), "refused in {took:?}");
    eprintln!("20,000 instances of 1,200 triangles ({size} bytes) refused in {took:?}");

    // The CLI exits 2 for it, writing nothing.
    let out = s.path("out.stl");
    refused(
        &["convert".as_ref(), doc.as_os_str()],
        &out,
        2,
        &["MAX_READ_TRIANGLES"],
    );
    bspcsg([OsStr::new("info"), doc.as_os_str()]).code(2);

    // One node drawing one mesh of 20,000 primitives on the same accessors: the same count.
    let one = instanced_doc(&s, "prims", 1200, 1);
    let primitive = r#"{"attributes": {"POSITION": 0}, "indices": 1}"#;
    let text = fs::read_to_string(&one).unwrap().replace(
        &format!("[{primitive}]"),
        &format!("[{}]", vec![primitive; 20_000].join(",")),
    );
    assert!(text.len() < 1_000_000, "{} bytes", text.len());
    fs::write(&one, text).unwrap();
    let run = bspcsg(["info".as_ref(), one.as_os_str()]).code(2);
    assert!(
        run.stderr.contains("24000000 triangles") && run.stderr.contains("prims.gltf"),
        "{}",
        run.stderr
    );

    // Below the budget the same instancing reads: 20 instances, 24,000 triangles placed.
    let doc = instanced_doc(&s, "few", 1200, 20);
    let m = read_mesh(&doc).unwrap();
    assert!(m.triangle_count() > 0 && m.triangle_count() <= 24_000);
}

#[test]
fn a_byte_order_mark_is_skipped_in_obj_and_scene_files() {
    let dir = Scratch::new("bom");
    let obj = dir.path("bom.obj");
    fs::write(
        &obj,
        format!("\u{feff}{}", box_obj_text([0.0; 3], [1.0; 3])),
    )
    .unwrap();
    let m = read_mesh(&obj).unwrap();
    let report = m.report();
    assert_eq!(m.positions.len(), 8);
    assert!(report.is_closed_manifold(), "{report}");
    assert!((report.volume - 1.0).abs() < 1e-12);
    let scene = dir.path("bom.json");
    fs::write(
        &scene,
        "\u{feff}{\"kind\":\"sdf_primitive\",\"data\":{\"primitive_type\":\"box\",\"size\":[1,2,3]}}",
    )
    .unwrap();
    let s = bspcsg::Scene::from_path(&scene).unwrap();
    assert!(s.distance(bspcsg::glam::DVec3::ZERO) < 0.0);
}

#[test]
fn a_repeated_json_key_is_refused_naming_its_path() {
    let dir = Scratch::new("dup-key");
    let scene = dir.path("dup.json");
    fs::write(
        &scene,
        r#"{"kind":"sdf_primitive","data":{"primitive_type":"sphere","radius":1,"radius":5}}"#,
    )
    .unwrap();
    let out = dir.path("dup.obj");
    refused(
        &["export".as_ref(), scene.as_os_str()],
        &out,
        1,
        &["dup.json", "$.data.radius", "duplicate key"],
    );
}

/// An empty result is written with a warning, and reads back as the empty solid with a
/// warning: `A − A` round-trips through every format and `A ∪ ∅ = A`, `A − ∅ = A`, `∅ − A = ∅`.
#[test]
fn an_empty_result_written_and_read_back_is_the_empty_solid() {
    let dir = Scratch::new("empty-results");
    let a = dir.path("a.obj");
    fs::write(&a, box_obj_text([0.0; 3], [1.0; 3])).unwrap();
    for ext in ["obj", "stl", "gltf", "glb"] {
        let empty = dir.path(&format!("a-minus-a.{ext}"));
        let run = bspcsg([
            "difference".as_ref(),
            a.as_os_str(),
            a.as_os_str(),
            "-o".as_ref(),
            empty.as_os_str(),
        ])
        .ok();
        assert!(run.stderr.contains("the result is empty"), "{}", run.stderr);
        assert!(
            run.stderr.contains("0 triangles, 0 vertices, volume 0\n"),
            "{}",
            run.stderr
        );
        let run = bspcsg(["info".as_ref(), "--json".as_ref(), empty.as_os_str()]).ok();
        assert!(
            run.stderr.contains(&format!(
                "a-minus-a.{ext} holds no triangles: read as the empty mesh"
            )),
            "{}",
            run.stderr
        );
        let json: serde_json::Value = serde_json::from_str(&run.stdout).unwrap();
        assert_eq!(json["triangles"], 0, "{json}");
        assert_eq!(json["volume"], 0.0, "{json}");
        for (op, first, second, volume) in [
            ("union", &a, &empty, 1.0),
            ("difference", &a, &empty, 1.0),
            ("difference", &empty, &a, 0.0),
            ("intersection", &a, &empty, 0.0),
        ] {
            let out = dir.path(&format!("{op}.obj"));
            let run = bspcsg([
                op.as_ref(),
                first.as_os_str(),
                second.as_os_str(),
                "-o".as_ref(),
                out.as_os_str(),
            ])
            .ok();
            assert!(
                run.stderr.contains("read as the empty mesh"),
                "{}",
                run.stderr
            );
            let mesh = read_mesh(&out).unwrap();
            assert_eq!(mesh.volume(), volume, "{op} {ext}");
            if volume > 0.0 {
                assert!(mesh.report().is_closed_manifold(), "{op} {ext}");
            }
        }
    }
}

#[test]
fn small_messages_tiny_cubes_and_unbounded_scenes() {
    let dir = Scratch::new("small-messages");
    // An empty file is called empty (not a parser's "EOF at column 0"); a missing buffer names
    // the document that needs it.
    let glb = dir.path("empty.glb");
    fs::write(&glb, "").unwrap();
    let run = bspcsg(["info".as_ref(), glb.as_os_str()]).code(1);
    assert!(
        run.stderr.contains("empty.glb: the file is empty"),
        "{}",
        run.stderr
    );
    let gltf = dir.path("lost.gltf");
    fs::write(&gltf, tetra_gltf("lost.bin", 72, r#"[{"mesh": 0}]"#, "[0]")).unwrap();
    let run = bspcsg(["info".as_ref(), gltf.as_os_str()]).code(1);
    assert!(
        run.stderr.contains("lost.gltf: buffer 0 URI `lost.bin`"),
        "{}",
        run.stderr
    );
    // A correctly wound cube of side 1e-110 (volume 1e-330, below the least double) is not
    // inside out.
    let tiny = dir.path("tiny.obj");
    fs::write(&tiny, box_obj_text([0.0; 3], [1e-110; 3])).unwrap();
    let report = read_mesh(&tiny).unwrap().report();
    assert_eq!(report.inverted_shells, 0, "{report}");
    assert!(report.shells[0].volume > 0.0, "{report}");
    // A plane-only scene by marching cubes: named, and told what to do in the scene.
    let plane = dir.path("plane.json");
    fs::write(
        &plane,
        r#"{"kind":"sdf_primitive","data":{"primitive_type":"plane","normal":[0,1,0],"offset":0}}"#,
    )
    .unwrap();
    refused(
        &[
            "export".as_ref(),
            plane.as_os_str(),
            "--via".as_ref(),
            "sdf".as_ref(),
        ],
        &dir.path("plane.obj"),
        1,
        &["plane.json", "intersect the half-space"],
    );
}

/// A fine watertight sphere 10¹² from the origin: its coordinates round to 1.2·10⁻⁴, its
/// triangles (about 0.025 across) keep their area, and `info` calls it a closed 2-manifold with
/// no degenerate triangles (it counted 8,704 of 16,128 as zero area before).
#[test]
fn a_watertight_mesh_far_from_the_origin_has_no_degenerate_triangles() {
    let dir = Scratch::new("far-sphere");
    let mut mesh = bspcsg::Solid::sphere(1.0, 256, 128).unwrap().to_mesh();
    for p in &mut mesh.positions {
        *p += bspcsg::glam::DVec3::splat(1e12);
    }
    let path = dir.path("far.obj");
    bspcsg::write_mesh(&path, &mesh, &[]).unwrap();
    let run = bspcsg(["info".as_ref(), "--json".as_ref(), path.as_os_str()]).ok();
    let json: serde_json::Value = serde_json::from_str(&run.stdout).unwrap();
    assert_eq!(json["triangles"], mesh.triangle_count(), "{json}");
    assert_eq!(json["degenerate_triangles"], 0, "{json}");
    assert_eq!(json["watertight"], true, "{json}");
    assert_eq!(json["genus"], 0, "{json}");
    let report = read_mesh(&path).unwrap().report();
    assert!(report.is_closed_manifold(), "{report}");
}
