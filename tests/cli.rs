//! The `bspcsg` binary, run as a user runs it, on good inputs: every format in and out,
//! `info --json` values, and the shared real meshes (closed ones combined, open and
//! non-manifold ones refused). Exit codes for bad files, outputs and usage are in
//! `cli_errors.rs`; scene export in `cli_scenes.rs`; `render` and `check` in `cli_render.rs`.

mod common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};

use bspcsg::{Format, Mesh, Solid, read_mesh, read_mesh_as};
use common::cli::{FORMATS, assert_solid, combine, cube_at, info, num, open_cube, rel, write};
use common::models;
use common::run::{Scratch, bspcsg};
use glam::DVec3;
use serde_json::Value;

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
