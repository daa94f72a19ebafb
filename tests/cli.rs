//! The `bspcsg` binary, run as a user runs it: every format in and out, `info --json` values,
//! the shared real meshes (closed ones combined, open and non-manifold ones refused), bad files,
//! unwritable outputs, usage errors and exit codes, and scene export by both routes.

mod common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};

use bspcsg::{Format, Mesh, Solid, read_mesh, read_mesh_as, write_mesh};
use common::models;
use common::run::{Run, Scratch, bspcsg};
use glam::DVec3;
use serde_json::Value;

/// `bspcsg OP INPUT… -o OUT`.
fn combine(op: &str, inputs: &[&Path], out: &Path) -> Run {
    let mut args = vec![OsStr::new(op)];
    args.extend(inputs.iter().map(|p| p.as_os_str()));
    args.extend([OsStr::new("-o"), out.as_os_str()]);
    bspcsg(args)
}

/// `bspcsg info --json PATH`, parsed.
fn info(path: &Path) -> Value {
    let run = bspcsg([OsStr::new("info"), path.as_os_str(), OsStr::new("--json")]).ok();
    serde_json::from_str(&run.stdout).unwrap_or_else(|e| panic!("{e}: {}", run.stdout))
}

fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number in {v}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Asserts the report of a closed, clean solid.
fn assert_solid(v: &Value, what: &str) {
    assert_eq!(v["watertight"], true, "{what}: {v}");
    assert_eq!(v["boundary_edges"], 0, "{what}: {v}");
    assert_eq!(v["nonmanifold_edges"], 0, "{what}: {v}");
    assert_eq!(v["degenerate_triangles"], 0, "{what}: {v}");
    assert!(v["genus"].is_u64(), "{what}: {v}");
    assert!(num(v, "volume") > 0.0, "{what}: {v}");
}

fn cube_at(x: f64) -> Solid {
    Solid::cube(1.0)
        .unwrap()
        .translate(DVec3::new(x, 0.0, 0.0))
        .unwrap()
}

fn write(path: &Path, mesh: &Mesh) -> PathBuf {
    write_mesh(path, mesh, &[]).unwrap();
    path.to_path_buf()
}

/// A unit cube with one triangle taken out: three boundary edges.
fn open_cube() -> Mesh {
    let mut m = Solid::cube(1.0).unwrap().to_mesh();
    m.triangles.pop();
    m.sources.pop();
    m
}

const FORMATS: [&str; 4] = ["obj", "stl", "gltf", "glb"];

#[test]
fn convert_every_format_to_every_other() {
    let dir = Scratch::new("convert");
    let cube = Solid::cube(1.0).unwrap().to_mesh();
    for from in FORMATS {
        let input = write(&dir.path(&format!("cube.{from}")), &cube);
        for to in FORMATS {
            let out = dir.path(&format!("{from}-to.{to}"));
            bspcsg([
                OsStr::new("convert"),
                input.as_os_str(),
                OsStr::new("-o"),
                out.as_os_str(),
            ])
            .ok();
            let v = info(&out);
            assert_solid(&v, &format!("{from} -> {to}"));
            assert_eq!(
                (v["triangles"].as_u64(), v["vertices"].as_u64()),
                (Some(12), Some(8))
            );
            assert!(
                (num(&v, "volume") - 1.0).abs() < 1e-12,
                "{from} -> {to}: {v}"
            );
            assert!((num(&v, "area") - 6.0).abs() < 1e-12, "{from} -> {to}: {v}");
        }
    }
    // --format overrides the extension.
    let out = dir.path("cube.dat");
    bspcsg([
        OsStr::new("convert"),
        dir.path("cube.obj").as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
        OsStr::new("--format"),
        OsStr::new("glb"),
    ])
    .ok();
    assert_eq!(
        read_mesh_as(&out, Format::Glb).unwrap().triangle_count(),
        12
    );
}

#[test]
fn booleans_read_and_write_every_format() {
    let dir = Scratch::new("booleans");
    let (a, b) = (cube_at(0.0).to_mesh(), cube_at(0.5).to_mesh());
    for ext in FORMATS {
        write(&dir.path(&format!("a.{ext}")), &a);
        write(&dir.path(&format!("b.{ext}")), &b);
    }
    // Every format is an input of some case and the output of another.
    let cases = [
        ("union", "obj", "stl", "gltf", 1.5),
        ("union", "gltf", "glb", "obj", 1.5),
        ("intersection", "stl", "glb", "stl", 0.5),
        ("intersection", "glb", "obj", "glb", 0.5),
        ("difference", "glb", "gltf", "obj", 0.5),
        ("difference", "stl", "obj", "stl", 0.5),
    ];
    for (op, fa, fb, fo, volume) in cases {
        let out = dir.path(&format!("{op}-{fa}-{fb}.{fo}"));
        let (a, b) = (dir.path(&format!("a.{fa}")), dir.path(&format!("b.{fb}")));
        let run = combine(op, &[&a, &b], &out).ok();
        // Not a terminal: no spinner, just the summary line.
        assert!(run.stderr.starts_with("wrote "), "{}", run.stderr);
        let v = info(&out);
        let what = format!("{op} {fa} {fb} -> {fo}");
        assert_solid(&v, &what);
        assert!((num(&v, "volume") - volume).abs() < 1e-9, "{what}: {v}");
        assert_eq!(
            (v["genus"].as_u64(), v["components"].as_u64()),
            (Some(0), Some(1))
        );
    }
}

#[test]
fn info_json_keys_and_values() {
    let dir = Scratch::new("info");
    let (a, b) = (
        write(&dir.path("a.obj"), &cube_at(0.0).to_mesh()),
        write(&dir.path("b.obj"), &cube_at(0.5).to_mesh()),
    );
    let out = dir.path("u.glb");
    combine("union", &[&a, &b], &out).ok();
    let v = info(&out);
    let mut keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    keys.sort_unstable();
    let mut expected = [
        "triangles",
        "vertices",
        "volume",
        "area",
        "bbox_min",
        "bbox_max",
        "watertight",
        "boundary_edges",
        "nonmanifold_edges",
        "degenerate_triangles",
        "needles",
        "crossing_triangle_pairs",
        "components",
        "genus",
    ];
    expected.sort_unstable();
    assert_eq!(keys, expected);
    assert_eq!(v["needles"], 0, "{v}");
    assert_eq!(v["crossing_triangle_pairs"], 0, "{v}");
    assert!((num(&v, "volume") - 1.5).abs() < 1e-9, "{v}");
    assert!((num(&v, "area") - 8.0).abs() < 1e-9, "{v}");
    assert_eq!(v["bbox_min"], serde_json::json!([-0.5, -0.5, -0.5]));
    assert_eq!(v["bbox_max"], serde_json::json!([1.0, 0.5, 0.5]));
    assert_eq!(v["watertight"], true);
    assert_eq!(v["genus"], 0);
    assert_eq!(v["components"], 1);
    assert_eq!(v["boundary_edges"], 0);
    assert_eq!(v["nonmanifold_edges"], 0);
    assert_eq!(v["degenerate_triangles"], 0);
    assert!(v["triangles"].as_u64().unwrap() >= 12);

    // A cube with a hole through it has genus 1.
    let bar = Solid::cylinder(0.2, 2.0, 32).unwrap().to_mesh();
    let bar = write(&dir.path("bar.stl"), &bar);
    let ring = dir.path("ring.obj");
    combine("difference", &[&a, &bar], &ring).ok();
    let v = info(&ring);
    assert_solid(&v, "ring");
    assert_eq!(v["genus"], 1);

    // Two disjoint cubes are two components.
    let c = write(&dir.path("c.obj"), &cube_at(3.0).to_mesh());
    let two = dir.path("two.obj");
    combine("union", &[&a, &c], &two).ok();
    let v = info(&two);
    assert_eq!(
        (v["components"].as_u64(), v["genus"].as_u64()),
        (Some(2), Some(0))
    );
    assert!((num(&v, "volume") - 2.0).abs() < 1e-9);

    // Reporting on an open mesh is info's job: exit 0, with the defects.
    let open = write(&dir.path("open.stl"), &open_cube());
    let v = info(&open);
    assert_eq!(v["watertight"], false);
    assert_eq!(v["boundary_edges"], 3);
    assert_eq!(v["genus"], Value::Null);
    assert_eq!(v["triangles"], 11);

    // Text output: one `name  value` line per figure.
    let field = |text: &str, name: &str| -> String {
        text.lines()
            .find_map(|l| {
                let rest = l.strip_prefix(name)?;
                rest.starts_with("  ").then(|| rest.trim().to_owned())
            })
            .unwrap_or_else(|| panic!("no `{name}` in {text}"))
    };
    let text = bspcsg([OsStr::new("info"), out.as_os_str()]).ok().stdout;
    assert_eq!(field(&text, "watertight"), "yes");
    assert_eq!(field(&text, "genus"), "0");
    assert_eq!(field(&text, "volume"), "1.5");
    let text = bspcsg([OsStr::new("info"), open.as_os_str()]).ok().stdout;
    assert_eq!(field(&text, "watertight"), "no");
    assert_eq!(field(&text, "boundary edges"), "3");
    assert_eq!(field(&text, "genus"), "undefined");
}

#[test]
fn each_input_keeps_its_source_id() {
    let dir = Scratch::new("sources");
    let inputs: Vec<PathBuf> = [("left", 0.0), ("middle", 0.5), ("right", 1.0)]
        .iter()
        .map(|&(name, x)| write(&dir.path(&format!("{name}.stl")), &cube_at(x).to_mesh()))
        .collect();
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let run = |op: &str, out: &Path| {
        combine(op, &inputs, out).ok();
    };
    let gltf = dir.path("u.gltf");
    run("union", &gltf);
    let doc: Value = serde_json::from_slice(&fs::read(&gltf).unwrap()).unwrap();
    let names: Vec<&str> = doc["materials"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["left", "middle", "right"]);
    // One primitive per input that has triangles in the result.
    assert_eq!(doc["meshes"][0]["primitives"].as_array().unwrap().len(), 3);
    assert!((num(&info(&gltf), "volume") - 2.0).abs() < 1e-9);

    let obj = dir.path("u.obj");
    run("union", &obj);
    let text = fs::read_to_string(&obj).unwrap();
    assert_eq!(text.matches("\nusemtl ").count(), 3, "{text}");
    assert!(
        fs::read_to_string(dir.path("u.mtl"))
            .unwrap()
            .contains("newmtl middle")
    );

    // left − middle − right: [-0.5, 0.5] less [0, 2] leaves [-0.5, 0]; right does not touch
    // what is left, so only two sources remain.
    let diff = dir.path("d.gltf");
    run("difference", &diff);
    let v = info(&diff);
    assert_solid(&v, "difference");
    assert!((num(&v, "volume") - 0.5).abs() < 1e-9, "{v}");
    let doc: Value = serde_json::from_slice(&fs::read(&diff).unwrap()).unwrap();
    assert_eq!(doc["meshes"][0]["primitives"].as_array().unwrap().len(), 2);
    // The three share only the plane x = 0.5: the intersection is empty, written as a valid
    // file with a warning.
    let inter = dir.path("i.glb");
    let mut args = vec![OsStr::new("intersection")];
    args.extend(inputs.iter().map(|p| p.as_os_str()));
    args.extend([OsStr::new("-o"), inter.as_os_str()]);
    let r = bspcsg(args).ok();
    assert!(r.stderr.contains("the result is empty"), "{}", r.stderr);
    assert!(inter.exists());
}

/// A copy of a mesh file moved by `offset`, written to `to`.
fn moved(from: &Path, offset: DVec3, to: &Path) -> PathBuf {
    let mut m = read_mesh(from).unwrap();
    for p in &mut m.positions {
        *p += offset;
    }
    write(to, &m)
}

#[test]
fn real_meshes_combine_closed() {
    let Some(models) = models() else { return };
    let dir = Scratch::new("models");
    let spot = models.join("spot.obj");
    let spot2 = moved(&spot, DVec3::new(0.3, 0.1, 0.2), &dir.path("spot2.stl"));
    let fandisk = models.join("fandisk.obj");
    let fandisk2 = moved(
        &fandisk,
        DVec3::new(0.8, 0.6, -0.5),
        &dir.path("fandisk2.glb"),
    );
    let rocker = models.join("rocker-arm.obj");
    // The lower half of the rocker arm's box (0.3 × 0.5 × 1.0, centred), larger on every
    // other side.
    let half = Solid::cuboid(DVec3::new(0.4, 0.6, 0.6))
        .unwrap()
        .translate(DVec3::new(0.0, 0.0, -0.3))
        .unwrap();
    let half = write(&dir.path("half.gltf"), &half.to_mesh());
    let cases = [
        ("union", &spot, &spot2, "spot-union.glb", 0.718258788),
        (
            "difference",
            &fandisk,
            &fandisk2,
            "fandisk-diff.obj",
            20.2433749,
        ),
        (
            "intersection",
            &rocker,
            &half,
            "rocker-half.stl",
            0.0425136236,
        ),
    ];
    for (op, a, b, out, volume_a) in cases {
        let out = dir.path(out);
        combine(op, &[a, b], &out).ok();
        let v = info(&out);
        assert_solid(&v, op);
        let vol = num(&v, "volume");
        println!("{op}: volume {vol} (first input {volume_a})");
        match op {
            "union" => assert!(vol > volume_a * 1.05 && vol < 2.0 * volume_a, "{vol}"),
            _ => assert!(vol < volume_a * 0.95 && vol > 0.05 * volume_a, "{vol}"),
        }
    }
}

#[test]
fn real_open_and_non_manifold_meshes_are_refused() {
    let Some(models) = models() else { return };
    let dir = Scratch::new("refused");
    let cases = [
        (
            "stanford-bunny.obj",
            "223 boundary edges",
            DVec3::new(-0.02, 0.1, 0.0),
        ),
        ("boxNotManifold.obj", "4 boundary edges", DVec3::ZERO),
        (
            "openscad-nonmanifold-crash.obj",
            "18 non-manifold edges",
            DVec3::new(-17.0, 0.0, -210.0),
        ),
    ];
    for (name, counts, centre) in cases {
        let bad = models.join(name);
        let probe = Solid::cube(0.05).unwrap().translate(centre).unwrap();
        let probe = write(&dir.path("probe.obj"), &probe.to_mesh());
        let out = dir.path("out.glb");
        for op in ["union", "difference"] {
            let r = combine(op, &[&bad, &probe], &out).code(2);
            assert!(
                r.stderr.contains(name) && r.stderr.contains(counts),
                "{}",
                r.stderr
            );
            assert!(r.stderr.contains("--allow-open"), "{}", r.stderr);
            assert!(!out.exists());
        }
        // As the second input too.
        let r = combine("intersection", &[&probe, &bad], &out).code(2);
        assert!(r.stderr.contains(name) && r.stderr.contains(counts));
        assert_eq!(dir.files(), ["probe.obj"]);

        // Asked to go on, it does.
        let r = bspcsg([
            OsStr::new("union"),
            bad.as_os_str(),
            probe.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
            OsStr::new("--allow-open"),
        ])
        .ok();
        println!("{name} --allow-open: {}", r.stderr.trim());
        assert!(info(&out)["triangles"].as_u64().unwrap() > 0);
        fs::remove_file(&out).unwrap();

        // info reports on it (exit 0) with the same counts.
        let v = info(&bad);
        assert_eq!(v["watertight"], false);
        assert_eq!(v["genus"], Value::Null);
    }
    let v = info(&models.join("stanford-bunny.obj"));
    assert_eq!(v["boundary_edges"], 223);
    let v = info(&models.join("openscad-nonmanifold-crash.obj"));
    assert_eq!(
        (
            v["nonmanifold_edges"].as_u64(),
            v["degenerate_triangles"].as_u64()
        ),
        (Some(18), Some(1))
    );
}

/// Bad files: each is refused with exit 1 and a message naming the file, by every command that
/// reads it, and no output appears (an existing one stays as it was).
#[test]
fn bad_files_exit_1_naming_the_file() {
    let dir = Scratch::new("bad");
    let cube = Solid::cube(1.0).unwrap().to_mesh();
    let good = write(&dir.path("good.obj"), &cube);
    let mut full = Vec::new();
    for ext in FORMATS {
        full.push((
            ext,
            fs::read(write(&dir.path(&format!("full.{ext}")), &cube)).unwrap(),
        ));
    }
    // A deterministic byte soup (xorshift), NULs and newlines included.
    let mut x = 0x9E37_79B9_7F4A_7C15u64;
    let garbage: Vec<u8> = (0..3000)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect();
    let mut cases: Vec<(String, Vec<u8>, &str)> = vec![
        ("nan.obj".into(), b"v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n".to_vec(), "nan.obj:3:"),
        ("inf.obj".into(), b"v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n".to_vec(), "inf.obj:2:"),
        (
            "index.obj".into(),
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n".to_vec(),
            "index.obj:4:",
        ),
        (
            "relative.obj".into(),
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -7\n".to_vec(),
            "relative.obj:4:",
        ),
        (
            "nan.stl".into(),
            b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 nan\nvertex 0 1 0\n\
              endloop\nendfacet\nendsolid t\n"
                .to_vec(),
            "nan.stl",
        ),
        ("verts.obj".into(), b"v 0 0 0\nv 1 0 0\n".to_vec(), "verts.obj"),
    ];
    for (ext, bytes) in &full {
        cases.push((format!("empty.{ext}"), Vec::new(), "empty."));
        cases.push((format!("garbage.{ext}"), garbage.clone(), "garbage."));
        // Cut short: OBJ in the middle of its third vertex line (a cut between lines would
        // leave a valid, smaller file), binary STL mid-record, glTF mid-JSON, GLB mid-chunk.
        let cut = match *ext {
            "obj" => {
                let text = std::str::from_utf8(bytes).unwrap();
                text.match_indices("\nv ").nth(2).unwrap().0 + 5
            }
            _ => bytes.len() * 2 / 3,
        };
        cases.push((
            format!("truncated.{ext}"),
            bytes[..cut].to_vec(),
            "truncated.",
        ));
    }
    // A .gltf whose .bin is missing.
    let gltf = write(&dir.path("nobin.gltf"), &cube);
    fs::remove_file(dir.path("nobin.bin")).unwrap();
    let kept = fs::read(&gltf).unwrap();

    let out = dir.path("out.glb");
    fs::write(&out, b"old").unwrap();
    let mut all: Vec<(PathBuf, String)> = vec![
        (gltf, "nobin.bin".into()),
        (dir.path("missing.obj"), "missing.obj".into()),
    ];
    for (name, bytes, needle) in &cases {
        let p = dir.path(name);
        fs::write(&p, bytes).unwrap();
        all.push((p, needle.to_string()));
    }
    let before = dir.files();
    for (path, needle) in &all {
        let shown = path.display();
        let r = bspcsg([OsStr::new("info"), path.as_os_str()]).code(1);
        assert!(r.stderr.contains(needle.as_str()), "{shown}: {}", r.stderr);
        assert!(r.stdout.is_empty());
        for args in [
            vec![OsStr::new("union"), good.as_os_str(), path.as_os_str()],
            vec![OsStr::new("difference"), path.as_os_str(), good.as_os_str()],
            vec![OsStr::new("convert"), path.as_os_str()],
        ] {
            let mut args = args;
            args.extend([OsStr::new("-o"), out.as_os_str()]);
            let r = bspcsg(&args).code(1);
            assert!(r.stderr.contains(needle.as_str()), "{shown}: {}", r.stderr);
            assert!(r.stderr.starts_with("bspcsg: error: "), "{}", r.stderr);
        }
    }
    assert_eq!(fs::read(&out).unwrap(), b"old");
    assert_eq!(dir.files(), before);
    assert_eq!(fs::read(dir.path("nobin.gltf")).unwrap(), kept);
}

/// Geometry that does not bound a solid exits 2; nothing is written.
#[test]
fn invalid_geometry_exits_2() {
    let dir = Scratch::new("geometry");
    let good = write(&dir.path("good.obj"), &Solid::cube(1.0).unwrap().to_mesh());
    let open = write(&dir.path("open.obj"), &open_cube());
    let mut inverted = Solid::cube(1.0).unwrap().to_mesh();
    for t in &mut inverted.triangles {
        t.swap(1, 2);
    }
    let inverted = write(&dir.path("inverted.stl"), &inverted);
    let out = dir.path("out.obj");
    fs::write(&out, b"old").unwrap();
    for (bad, needle) in [
        (&open, "open.obj is not closed: 3 boundary edges"),
        (&inverted, "inverted.stl is inside out"),
    ] {
        let r = combine("union", &[&good, bad], &out).code(2);
        assert!(r.stderr.contains(needle), "{}", r.stderr);
    }
    // Coordinates beyond float32 cannot be written to STL or glTF.
    let huge = Solid::cube(1e50).unwrap().to_mesh();
    assert_eq!(huge.triangle_count(), 12);
    let huge = write(&dir.path("huge.obj"), &huge);
    for ext in ["stl", "glb"] {
        let target = dir.path(&format!("huge.{ext}"));
        let r = bspcsg([
            OsStr::new("convert"),
            huge.as_os_str(),
            OsStr::new("-o"),
            target.as_os_str(),
        ])
        .code(2);
        assert!(r.stderr.contains("float32"), "{}", r.stderr);
    }
    assert_eq!(fs::read(&out).unwrap(), b"old");
    assert_eq!(
        dir.files(),
        [
            "good.obj",
            "huge.obj",
            "inverted.stl",
            "open.obj",
            "out.obj"
        ]
    );
    // Asked to go on, the open one is combined.
    bspcsg([
        OsStr::new("union"),
        good.as_os_str(),
        open.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
        OsStr::new("--allow-open"),
    ])
    .ok();
    assert!(fs::read(&out).unwrap().starts_with(b"# bspcsg"));
}

#[test]
fn unwritable_outputs_exit_1_leaving_nothing() {
    let dir = Scratch::new("unwritable");
    let good = write(&dir.path("good.obj"), &Solid::cube(1.0).unwrap().to_mesh());
    fs::create_dir(dir.path("taken.glb")).unwrap();
    fs::write(dir.path("file"), b"").unwrap();
    let mut targets = vec![
        (dir.path("taken.glb"), "is a directory"),
        (dir.path("file/out.stl"), "file is not a directory"),
        (dir.path("file/deeper/out.obj"), "file is not a directory"),
    ];
    if cfg!(target_os = "linux") {
        // A directory where no file can be created, even by root: the write itself fails.
        targets.push((
            PathBuf::from("/proc/bspcsg-test-out.gltf"),
            "bspcsg-test-out",
        ));
    }
    let before = dir.files();
    for (out, needle) in &targets {
        for args in [
            vec![OsStr::new("union"), good.as_os_str(), good.as_os_str()],
            vec![OsStr::new("convert"), good.as_os_str()],
        ] {
            let mut args = args;
            args.extend([OsStr::new("-o"), out.as_os_str()]);
            let r = bspcsg(&args).code(1);
            assert!(r.stderr.contains(needle), "{}: {}", out.display(), r.stderr);
        }
    }
    assert_eq!(dir.files(), before);
    assert!(dir.path("taken.glb").is_dir());
}

#[test]
fn missing_output_directories_are_made_only_on_success() {
    let dir = Scratch::new("mkdir");
    let good = write(&dir.path("good.obj"), &Solid::cube(1.0).unwrap().to_mesh());
    let huge = write(&dir.path("huge.obj"), &Solid::cube(1e50).unwrap().to_mesh());
    let open = write(&dir.path("open.obj"), &open_cube());
    let before = dir.files();
    // Failures before the write (a refused input) and in it (float32 overflow): no directory.
    bspcsg([
        OsStr::new("union"),
        good.as_os_str(),
        open.as_os_str(),
        OsStr::new("-o"),
        dir.path("new/a.glb").as_os_str(),
    ])
    .code(2);
    bspcsg([
        OsStr::new("convert"),
        huge.as_os_str(),
        OsStr::new("-o"),
        dir.path("new/deeper/huge.stl").as_os_str(),
    ])
    .code(2);
    assert_eq!(dir.files(), before);
    // Success makes them (the README's set-up command writes into a fresh `out/`).
    let out = dir.path("new/deeper/cube.gltf");
    bspcsg([
        OsStr::new("convert"),
        good.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .ok();
    assert_eq!(info(&out)["volume"], 1.0);
    assert!(dir.path("new/deeper/cube.bin").exists());
}

#[test]
fn unknown_extensions_exit_1() {
    let dir = Scratch::new("extensions");
    let cube = Solid::cube(1.0).unwrap().to_mesh();
    let good = write(&dir.path("good.obj"), &cube);
    let ply = dir.path("mesh.ply");
    fs::copy(&good, &ply).unwrap();
    let r = bspcsg([OsStr::new("info"), ply.as_os_str()]).code(1);
    assert!(
        r.stderr.contains("mesh.ply") && r.stderr.contains(".ply"),
        "{}",
        r.stderr
    );
    let out = dir.path("out.xyz");
    let r = bspcsg([
        OsStr::new("convert"),
        good.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .code(1);
    assert!(
        r.stderr.contains("out.xyz") && r.stderr.contains(".xyz"),
        "{}",
        r.stderr
    );
    assert!(!out.exists());
    let noext = dir.path("noext");
    combine("union", &[&good, &good], &noext).code(1);
    assert!(!noext.exists());
}

#[test]
fn usage_errors_exit_1_and_help_exits_0() {
    let dir = Scratch::new("usage");
    let good = write(&dir.path("good.obj"), &Solid::cube(1.0).unwrap().to_mesh());
    let good = good.to_str().unwrap();
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/scenes/mechanical_part.json"
    );
    let out = dir.path("out.obj");
    let out = out.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec![],
        vec!["frobnicate"],
        vec!["--quiet"],
        vec!["union", good, "-o", out],
        vec!["union", good, good],
        vec!["difference", "-o", out],
        vec!["info"],
        vec!["info", good, "--bogus"],
        vec!["convert", good],
        vec!["convert", good, "-o", out, "--format", "ply"],
        vec!["export", scene, "-o", out, "--via", "raytrace"],
        vec!["export", scene, "-o", out, "--tolerance", "0"],
        vec!["export", scene, "-o", out, "--tolerance", "-1"],
        vec!["export", scene, "-o", out, "--cell", "nan"],
        vec!["export", scene, "-o", out, "--cell", "1e999"],
        vec![
            "export",
            scene,
            "-o",
            out,
            "--via",
            "sdf",
            "--tolerance",
            "0.1",
        ],
    ];
    for args in cases {
        let r = bspcsg(&args).code(1);
        // clap's own message: the usage line or a pointer to --help.
        assert!(
            r.stderr.contains("Usage:") || r.stderr.contains("try '--help'"),
            "{args:?}: {}",
            r.stderr
        );
    }
    assert_eq!(dir.files(), ["good.obj"]);

    let r = bspcsg(["--help"]).ok();
    for needle in [
        "Exit codes:",
        "Examples:",
        "invalid geometry",
        "union",
        "export",
    ] {
        assert!(r.stdout.contains(needle), "{}", r.stdout);
    }
    for sub in [
        "union",
        "intersection",
        "difference",
        "info",
        "convert",
        "export",
    ] {
        let r = bspcsg([sub, "--help"]).ok();
        assert!(r.stdout.contains("Example"), "{sub}: {}", r.stdout);
        assert!(r.stdout.contains(&format!("bspcsg {sub}")), "{sub}");
        assert!(r.stdout.contains("Exit codes:"), "{sub}");
        bspcsg(["help", sub]).ok();
    }
    let r = bspcsg(["--version"]).ok();
    assert!(r.stdout.starts_with("bspcsg "));
}

#[test]
fn quiet_prints_nothing_but_errors() {
    let dir = Scratch::new("quiet");
    let good = write(&dir.path("good.obj"), &Solid::cube(1.0).unwrap().to_mesh());
    let out = dir.path("out.glb");
    let args = [
        OsStr::new("convert"),
        good.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ];
    let r = bspcsg(args).ok();
    // Stderr is a pipe here, so the spinner stays hidden: no carriage returns, no escapes.
    assert!(
        !r.stderr.contains('\r') && !r.stderr.contains('\x1b'),
        "{:?}",
        r.stderr
    );
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    let mut quiet = vec![OsStr::new("--quiet")];
    quiet.extend(args);
    let r = bspcsg(&quiet).ok();
    assert_eq!((r.stdout.as_str(), r.stderr.as_str()), ("", ""));
    // Global: also after the subcommand.
    let r = bspcsg([args[0], args[1], args[2], args[3], OsStr::new("-q")]).ok();
    assert_eq!(r.stderr, "");
    let missing = dir.path("missing.obj");
    let r = bspcsg([
        OsStr::new("-q"),
        OsStr::new("convert"),
        missing.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .code(1);
    assert!(r.stderr.contains("missing.obj"));
}

fn scenes() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    let mut v: Vec<PathBuf> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension() == Some(OsStr::new("json")))
        .collect();
    v.sort();
    assert!(!v.is_empty());
    v
}

#[test]
fn export_every_example_scene_by_both_routes() {
    let dir = Scratch::new("export");
    for scene in scenes() {
        let name = scene.file_stem().unwrap().to_string_lossy().into_owned();
        let mut volumes = Vec::new();
        for via in ["bsp", "sdf"] {
            for ext in ["obj", "glb"] {
                let out = dir.path(&format!("{name}-{via}.{ext}"));
                bspcsg([
                    OsStr::new("export"),
                    scene.as_os_str(),
                    OsStr::new("-o"),
                    out.as_os_str(),
                    OsStr::new("--via"),
                    OsStr::new(via),
                ])
                .ok();
                let v = info(&out);
                assert_solid(&v, &format!("{name} {via} {ext}"));
                volumes.push((via, ext, num(&v, "volume")));
            }
            // The scene's materials: OBJ usemtl groups with a .mtl beside them.
            let obj = fs::read_to_string(dir.path(&format!("{name}-{via}.obj"))).unwrap();
            assert!(obj.contains("\nusemtl "), "{name} {via}");
            assert!(dir.path(&format!("{name}-{via}.mtl")).exists());
        }
        println!("{name}: {volumes:?}");
        // The same route in two formats: float32 (glb) against f64 (obj).
        assert!(rel(volumes[0].2, volumes[1].2) < 1e-5, "{volumes:?}");
        assert!(rel(volumes[2].2, volumes[3].2) < 1e-5, "{volumes:?}");
        // The two routes agree within a few percent at their default resolutions.
        assert!(
            rel(volumes[0].2, volumes[2].2) < 0.03,
            "{name}: {volumes:?}"
        );
    }
    // Options reach the library: a finer tolerance, a coarser cell.
    let scene = &scenes()[0];
    for (via, option, value) in [("bsp", "--tolerance", "0.05"), ("sdf", "--cell", "0.1")] {
        let out = dir.path(&format!("options-{via}.stl"));
        bspcsg([
            OsStr::new("export"),
            scene.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
            OsStr::new("--via"),
            OsStr::new(via),
            OsStr::new(option),
            OsStr::new(value),
        ])
        .ok();
        assert_solid(&info(&out), via);
    }
}

#[test]
fn bad_scenes_exit_1_naming_file_and_place() {
    let dir = Scratch::new("bad_scenes");
    let out = dir.path("out.glb");
    let cases = [
        (
            "syntax.json",
            "{\"kind\": ",
            "syntax.json: $: not valid JSON",
        ),
        (
            "radius.json",
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": -1}}"#,
            "radius.json: $.data.radius",
        ),
        ("empty.json", "", "empty.json"),
    ];
    for (name, text, needle) in cases {
        let p = dir.path(name);
        fs::write(&p, text).unwrap();
        for via in ["bsp", "sdf"] {
            let r = bspcsg([
                OsStr::new("export"),
                p.as_os_str(),
                OsStr::new("-o"),
                out.as_os_str(),
                OsStr::new("--via"),
                OsStr::new(via),
            ])
            .code(1);
            assert!(r.stderr.contains(needle), "{}", r.stderr);
        }
    }
    let missing = dir.path("missing.json");
    let r = bspcsg([
        OsStr::new("export"),
        missing.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ])
    .code(1);
    assert!(r.stderr.contains("missing.json"), "{}", r.stderr);
    // A cell so fine the grid would be too large: refused before any work, naming the option.
    let scene = &scenes()[0];
    let r = bspcsg([
        OsStr::new("export"),
        scene.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
        OsStr::new("--via"),
        OsStr::new("sdf"),
        OsStr::new("--cell"),
        OsStr::new("1e-7"),
    ])
    .code(1);
    assert!(r.stderr.contains("cell"), "{}", r.stderr);
    assert_eq!(dir.files(), ["empty.json", "radius.json", "syntax.json"]);
}

/// Regression: booleans with a float32-rounded operand came out open. A box from OBJ ∪ a
/// sphere exported to .glb had 5 boundary edges (the same sphere through OBJ was closed);
/// `spot.obj − a float32 sphere` had a non-manifold edge and a flat inside-out shell. Fixed by
/// the 1e-12 tolerance with anchored planes.
#[test]
fn union_with_float32_sphere_is_closed() {
    let dir = Scratch::new("known_bug");
    let scene = |name: &str, json: &str| {
        let p = dir.path(name);
        fs::write(&p, json).unwrap();
        p
    };
    let box_scene = scene(
        "box.json",
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [2, 1, 1.5]}}"#,
    );
    let ball_scene = scene(
        "ball.json",
        r#"{"kind": "sdf_primitive", "pos": [0.9, 0.3, 0.2],
            "data": {"primitive_type": "sphere", "radius": 0.8}}"#,
    );
    let (cube, ball) = (dir.path("box.obj"), dir.path("ball.glb"));
    for (s, out) in [(&box_scene, &cube), (&ball_scene, &ball)] {
        bspcsg([
            OsStr::new("export"),
            s.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
        ])
        .ok();
        assert_solid(&info(out), "input");
    }
    let out = dir.path("union.obj");
    combine("union", &[&cube, &ball], &out).ok();
    assert_solid(&info(&out), "box ∪ float32 sphere");

    if let Some(models) = models() {
        let cutter = scene(
            "cutter.json",
            r#"{"kind": "sdf_primitive", "pos": [0.3, 0.3, 0.5],
                "data": {"primitive_type": "sphere", "radius": 0.4}}"#,
        );
        let glb = dir.path("cutter.glb");
        bspcsg([
            OsStr::new("export"),
            cutter.as_os_str(),
            OsStr::new("-o"),
            glb.as_os_str(),
        ])
        .ok();
        let out = dir.path("spot-cut.obj");
        combine("difference", &[&models.join("spot.obj"), &glb], &out).ok();
        assert_solid(&info(&out), "spot − float32 sphere");
    }
}

/// Regression with identical operands (every face coplanar with one of the other's):
/// `fandisk ∪ fandisk` and `fandisk ∩ fandisk` kept 3 boundary edges and `fandisk − fandisk`
/// a one-triangle sliver; `Havocglass8_left ∪ itself` (far from the origin) had a boundary
/// edge, two non-manifold edges and lost 19 of its 2,779,422 units of volume.
#[test]
fn real_mesh_op_itself_is_exact() {
    let Some(models) = models() else { return };
    let dir = Scratch::new("known_bug_self");
    let out = dir.path("out.obj");
    for name in [
        "fandisk.obj",
        "Havocglass8_left.obj",
        "spot.obj",
        "rocker-arm.obj",
    ] {
        let a = models.join(name);
        let volume = num(&info(&a), "volume");
        for op in ["union", "intersection", "difference"] {
            combine(op, &[&a, &a], &out).ok();
            let text = fs::read_to_string(&out).unwrap();
            if op == "difference" {
                assert!(!text.contains("\nf "), "{name} − itself is not empty");
            } else {
                let v = info(&out);
                assert_solid(&v, &format!("{name} {op} itself"));
                assert!(rel(num(&v, "volume"), volume) < 1e-9, "{name} {op}: {v}");
            }
        }
    }
}

#[test]
fn info_counts_needles() {
    // A tetrahedron whose fourth corner lies 1e-12 off the middle of a base edge: the face
    // through that edge and that corner is a needle (area 5e-13, below 1e-12 × diagonal²).
    let dir = Scratch::new("needles");
    let mesh = Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.5, 0.0, 1e-12)],
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    );
    let path = write(&dir.path("needles.obj"), &mesh);
    let v = info(&path);
    assert_eq!(v["needles"], 1, "{v}");
    let run = bspcsg([OsStr::new("info"), path.as_os_str()]).ok();
    assert!(run.stdout.contains("needles"), "{}", run.stdout);
}
