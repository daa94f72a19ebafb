//! Hostile and extreme input to the readers and writers: glTF buffer URIs held to the
//! document's folder, the reader's triangle budget after instancing, and sidecar files that
//! never clobber an input. Every input is small and generated here.

mod common;

use std::ffi::OsStr;
use std::fs;
use std::path::Path;
use std::time::{Duration, Instant};

use bspcsg::{Error, MAX_READ_TRIANGLES, read_mesh};
use common::run::{Scratch, bspcsg};

/// A unit tetrahedron as a glTF buffer: 4 float32 positions, then 12 u16 indices.
fn tetra_buffer() -> Vec<u8> {
    let mut b = Vec::new();
    for p in [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ] {
        for x in p {
            b.extend_from_slice(&x.to_le_bytes());
        }
    }
    for i in [0u16, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3] {
        b.extend_from_slice(&i.to_le_bytes());
    }
    b
}

/// glTF JSON: one tetrahedron mesh drawn by every node of `nodes`, its buffer at `uri`.
fn tetra_gltf(uri: &str, byte_length: u64, nodes: &str, scene_nodes: &str) -> String {
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": {scene_nodes}}}],
  "nodes": {nodes},
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [0, 0, 0], "max": [1, 1, 1]}},
    {{"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}}
  ],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 24}}
  ],
  "buffers": [{{"byteLength": {byte_length}, "uri": "{uri}"}}]
}}"#
    )
}

/// Writes `sub/doc.gltf` naming `uri` and returns its path.
fn doc_with_uri(s: &Scratch, uri: &str, byte_length: u64) -> std::path::PathBuf {
    let dir = s.path("sub");
    fs::create_dir_all(&dir).unwrap();
    let p = dir.join("doc.gltf");
    fs::write(&p, tetra_gltf(uri, byte_length, r#"[{"mesh": 0}]"#, "[0]")).unwrap();
    p
}

/// Asserts that reading `doc` fails with a message naming the document and the URI.
fn refused(doc: &Path, uri: &str, why: &str) -> String {
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
        refused(&doc, uri, "");
    }
    let doc = doc_with_uri(&s, "../outside.bin", 72);
    refused(&doc, "../outside.bin", "no `..`");

    // A symbolic link inside the folder that leads out of it: to a file, to /dev/zero.
    std::os::unix::fs::symlink(s.path("outside.bin"), s.path("sub/link.bin")).unwrap();
    let doc = doc_with_uri(&s, "link.bin", 72);
    refused(&doc, "link.bin", "outside the document's folder");
    std::os::unix::fs::symlink("/dev/zero", s.path("sub/zero.bin")).unwrap();
    let doc = doc_with_uri(&s, "zero.bin", 72);
    refused(&doc, "zero.bin", "outside the document's folder");
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
    refused(&doc, "fifo.bin", "not a regular file");
    assert!(t.elapsed() < Duration::from_secs(5));
    fs::create_dir(s.path("sub/dir.bin")).unwrap();
    let doc = doc_with_uri(&s, "dir.bin", 72);
    refused(&doc, "dir.bin", "not a regular file");

    // Sizes: a file shorter than byteLength, a byteLength beyond the per-buffer limit.
    let doc = doc_with_uri(&s, "inside.bin", 73);
    refused(&doc, "inside.bin", "fewer than the buffer's byteLength 73");
    let doc = doc_with_uri(&s, "inside.bin", 1 << 40);
    refused(&doc, "inside.bin", "exceeds the limit");

    // Through the CLI: exit 1, the message names the document and the URI, nothing written.
    let doc = doc_with_uri(&s, "../../../../../../etc/passwd", 72);
    let out = s.path("out.obj");
    let run = bspcsg([
        OsStr::new("convert"),
        doc.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .code(1);
    assert!(run.stderr.contains("etc/passwd"), "{}", run.stderr);
    assert!(!out.exists());
}

/// A mesh of `n` triangles (a fan over four corners repeated), drawn by `instances` nodes.
fn instanced_doc(s: &Scratch, name: &str, n: usize, instances: usize) -> std::path::PathBuf {
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
    let run = bspcsg([
        OsStr::new("convert"),
        doc.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .code(2);
    assert!(run.stderr.contains("MAX_READ_TRIANGLES"), "{}", run.stderr);
    assert!(!out.exists());
    bspcsg([OsStr::new("info"), doc.as_os_str()]).code(2);

    // Below the budget the same instancing reads: 20 instances, 24,000 triangles placed.
    let doc = instanced_doc(&s, "few", 1200, 20);
    let m = read_mesh(&doc).unwrap();
    assert!(m.triangle_count() > 0 && m.triangle_count() <= 24_000);
}
