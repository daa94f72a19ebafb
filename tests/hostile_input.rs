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

/// A closed box mesh written to `path` in the format its extension names.
fn box_file(path: &Path, min: f64) -> std::path::PathBuf {
    let m = common::obj_box_mesh(
        bspcsg::glam::DVec3::splat(min),
        bspcsg::glam::DVec3::splat(min + 1.0),
    );
    bspcsg::write_mesh(path, &m, &[]).unwrap();
    path.to_path_buf()
}

/// Item 5: a sidecar (`X.bin` for `-o X.gltf`, `X.mtl` for `-o X.obj`) never replaces an
/// input or a file an input needs; the command exits 1 before any work, the input intact.
#[test]
fn sidecar_never_replaces_an_input_or_its_buffer() {
    let s = Scratch::new("sidecar");
    fs::write(s.path("cube.bin"), tetra_buffer()).unwrap();
    let g = s.path("g.gltf");
    fs::write(&g, tetra_gltf("cube.bin", 72, r#"[{"mesh": 0}]"#, "[0]")).unwrap();
    let b = box_file(&s.path("b.obj"), 0.25);
    let before = fs::read(s.path("cube.bin")).unwrap();

    let out = s.path("cube.gltf");
    let run = bspcsg([
        OsStr::new("union"),
        g.as_os_str(),
        b.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .code(1);
    assert!(
        run.stderr.contains("cube.bin") && run.stderr.contains("g.gltf"),
        "{}",
        run.stderr
    );
    assert!(!out.exists());
    assert_eq!(fs::read(s.path("cube.bin")).unwrap(), before);
    assert_eq!(read_mesh(&g).unwrap().triangle_count(), 4);

    // An OBJ input's `mtllib`.
    let c = s.path("c.obj");
    let text = fs::read_to_string(&b).unwrap();
    fs::write(&c, format!("mtllib shared.mtl\n{text}")).unwrap();
    fs::write(s.path("shared.mtl"), "newmtl keep\n").unwrap();
    let out = s.path("shared.obj");
    let run = bspcsg([
        OsStr::new("union"),
        c.as_os_str(),
        b.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .code(1);
    assert!(run.stderr.contains("shared.mtl"), "{}", run.stderr);
    assert_eq!(
        fs::read_to_string(s.path("shared.mtl")).unwrap(),
        "newmtl keep\n"
    );
    // Away from inputs, the same command writes both files.
    let out = s.path("fresh.gltf");
    bspcsg([
        OsStr::new("union"),
        g.as_os_str(),
        b.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .ok();
    assert!(s.path("fresh.bin").exists());
    assert!(read_mesh(&out).unwrap().triangle_count() > 0);
}

/// Item 9 (two-file part): `-o x.bin --format gltf` would write its own buffer over itself.
#[test]
fn gltf_output_named_as_its_own_buffer_is_refused() {
    let s = Scratch::new("own_buffer");
    let b = box_file(&s.path("b.obj"), 0.0);
    let out = s.path("x.bin");
    let run = bspcsg([
        OsStr::new("convert"),
        b.as_os_str(),
        OsStr::new("--format"),
        OsStr::new("gltf"),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .code(1);
    assert!(
        run.stderr.contains("would be the output itself"),
        "{}",
        run.stderr
    );
    assert!(!out.exists());
    // The library refuses it too.
    let m = read_mesh(&b).unwrap();
    let e = bspcsg::write_mesh_as(&out, &m, &[], bspcsg::Format::Gltf).unwrap_err();
    assert!(e.to_string().contains("output itself"), "{e}");
    assert_eq!(s.files(), ["b.obj"]);
}

/// Item 9 (two-file part): when the main file cannot be renamed into place, the companion
/// replaced before it is put back, so the old main file never points at a new companion.
#[test]
fn failed_main_rename_restores_the_old_companion() {
    let s = Scratch::new("rollback");
    let m = read_mesh(box_file(&s.path("b.obj"), 0.0)).unwrap();
    fs::write(s.path("out.bin"), b"old buffer").unwrap();
    // A non-empty directory where the main file goes: its rename fails after the companion's.
    fs::create_dir(s.path("out.gltf")).unwrap();
    fs::write(s.path("out.gltf/keep"), b"x").unwrap();
    let e = bspcsg::write_mesh_as(s.path("out.gltf"), &m, &[], bspcsg::Format::Gltf);
    assert!(e.is_err());
    assert_eq!(fs::read(s.path("out.bin")).unwrap(), b"old buffer");
    // No temporary or backup file left behind.
    assert_eq!(s.files(), ["b.obj", "out.bin", "out.gltf"]);

    // Without an old companion, the new one is removed again.
    fs::remove_file(s.path("out.bin")).unwrap();
    assert!(bspcsg::write_mesh_as(s.path("out.gltf"), &m, &[], bspcsg::Format::Gltf).is_err());
    assert_eq!(s.files(), ["b.obj", "out.gltf"]);
}

/// The crate's former unkeyed position hash (FxHash's multiply-rotate over the bytes of
/// `[u64; 3]`, length first), to craft positions that all land in one bucket under it.
fn unkeyed_hash_state(state: u64, bytes: &[u8]) -> u64 {
    bytes.iter().fold(state, |h, &b| {
        (h.rotate_left(5) ^ u64::from(b)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
    })
}

/// OBJ text of `points` as vertices, each three a triangle.
fn points_obj(points: &[[f64; 3]]) -> String {
    let mut s = String::with_capacity(points.len() * 60);
    for p in points {
        s += &format!("v {:?} {:?} {:?}\n", p[0], p[1], p[2]);
    }
    for k in (0..points.len() - 2).step_by(3) {
        s += &format!("f {} {} {}\n", k + 1, k + 2, k + 3);
    }
    s
}

#[test]
fn welder_hash_flooding_costs_no_more_than_random_positions() {
    // 16384 positions whose unkeyed hashes agree in the low 13 bits (the bucket of a table
    // sized for them), against as many random ones: the welder's keyed hash spreads both.
    const N: usize = 16384;
    const MASK: u64 = (1 << 13) - 1;
    let prefix = unkeyed_hash_state(
        0,
        &[
            &3usize.to_ne_bytes()[..],
            &1.0f64.to_bits().to_le_bytes(),
            &2.0f64.to_bits().to_le_bytes(),
        ]
        .concat(),
    );
    let mut crafted = Vec::with_capacity(N);
    let mut k = 0u64;
    while crafted.len() < N {
        let z = f64::from_bits(3.0f64.to_bits() + k);
        k += 1;
        if unkeyed_hash_state(prefix, &z.to_bits().to_le_bytes()) & MASK == 0 {
            crafted.push([1.0, 2.0, z]);
        }
    }
    // Random positions of the same form (same text length per line).
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let random: Vec<[f64; 3]> = (0..N)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            [1.0, 2.0, f64::from_bits(3.0f64.to_bits() + (state >> 24))]
        })
        .collect();
    let dir = Scratch::new("flood");
    let (c, r) = (dir.path("crafted.obj"), dir.path("random.obj"));
    fs::write(&c, points_obj(&crafted)).unwrap();
    fs::write(&r, points_obj(&random)).unwrap();
    let best = |p: &Path| {
        (0..5)
            .map(|_| {
                let t = Instant::now();
                let m = read_mesh(p).unwrap();
                assert_eq!(m.positions.len(), N / 3 * 3);
                t.elapsed()
            })
            .min()
            .unwrap()
    };
    let (tc, tr) = (best(&c), best(&r));
    assert!(tc <= 3 * tr, "crafted {tc:?} vs random {tr:?}");
}

#[test]
fn a_tiny_cube_at_a_unit_cube_corner_never_gives_a_broken_result_with_success() {
    let dir = Scratch::new("tiny-corner");
    let unit = dir.path("unit.obj");
    fs::write(&unit, box_obj([0.0; 3], [1.0; 3])).unwrap();
    for s in [1e-20, 1e-60, 1e-100] {
        let tiny = dir.path(&format!("tiny{s:e}.obj"));
        fs::write(&tiny, box_obj([-s; 3], [0.0; 3])).unwrap();
        for op in ["union", "difference"] {
            let out = dir.path(&format!("{op}{s:e}.obj"));
            let run = bspcsg([
                op.as_ref(),
                unit.as_os_str(),
                tiny.as_os_str(),
                "-o".as_ref(),
                out.as_os_str(),
            ]);
            // Either right (closed, the unit cube's volume) or refused with exit 2 and nothing
            // written: never exit 0 with an open mesh.
            if run.code == 0 {
                let report = read_mesh(&out).unwrap().report();
                assert!(report.is_closed_manifold(), "{op} {s:e}: {report}");
                assert!((report.volume - 1.0).abs() < 1e-12, "{op} {s:e}: {report}");
            } else {
                let run = run.code(2);
                assert!(
                    run.stderr.contains("not a closed 2-manifold"),
                    "{}",
                    run.stderr
                );
                assert!(!out.exists(), "{op} {s:e}: nothing is written");
            }
        }
    }
}

/// OBJ text of an axis-aligned box, outward-facing quads.
fn box_obj(min: [f64; 3], max: [f64; 3]) -> String {
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
