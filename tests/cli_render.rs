//! `bspcsg render` and `bspcsg check` run as a user runs them: images of the right size from
//! every route, the scene's own camera, refusals that write nothing, checks that pass for
//! every example scene by both routes and fail with exit 3 for meshes that are wrong.

mod common;

use bspcsg::raymarch::Rgb8;
use bspcsg::{Mesh, read_mesh, write_mesh};
use common::run::{Scratch, bspcsg};
use common::scenes::{example_path as scene, example_paths};
use glam::DVec3;
use serde_json::Value;

/// Every example scene's name.
fn scenes() -> Vec<String> {
    let names: Vec<String> = example_paths()
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    assert!(names.len() >= 4, "{names:?}");
    names
}

#[test]
fn render_writes_images_of_every_route() {
    let dir = Scratch::new("render-routes");
    for name in scenes() {
        for via in ["sdf", "bsp", "mc"] {
            let out = dir.path(&format!("{name}-{via}.png"));
            let name = name.as_str();
            let run = bspcsg(args(&[
                &"render",
                &scene(name),
                &"-o",
                &out,
                &"--size",
                &"64x48",
                &"--via",
                &via,
            ]))
            .ok();
            assert!(run.stderr.contains("wrote"), "{}", run.stderr);
            let img = Rgb8::read_png(&out).unwrap();
            assert_eq!((img.width, img.height), (64, 48));
            // Something is drawn: not every pixel is the background.
            let first = img.get(0, 0);
            assert!(
                (0..48).any(|y| (0..64).any(|x| img.get(x, y) != first)),
                "{name} by {via} is blank"
            );
        }
    }
}

fn args(list: &[&dyn AsRef<std::ffi::OsStr>]) -> Vec<std::ffi::OsString> {
    list.iter().map(|a| a.as_ref().to_owned()).collect()
}

#[test]
fn render_draws_mesh_files_and_turntables() {
    let dir = Scratch::new("render-mesh");
    let obj = dir.path("part.obj");
    bspcsg(args(&[
        &"export",
        &scene("mechanical_part"),
        &"-o",
        &obj,
        &"-q",
    ]))
    .ok();
    let png = dir.path("part.png");
    bspcsg(args(&[
        &"render", &obj, &"-o", &png, &"--size", &"80x60", &"--eye", &"4,3,5", &"--flat",
    ]))
    .ok();
    assert_eq!(Rgb8::read_png(&png).unwrap().width, 80);
    let spin = dir.path("spin/turn.png");
    bspcsg(args(&[
        &"render",
        &scene("organic_blend"),
        &"-o",
        &spin,
        &"--size",
        &"32x24",
        &"--turntable",
        &"3",
    ]))
    .ok();
    let frames: Vec<Rgb8> = (0..3)
        .map(|i| Rgb8::read_png(dir.path(&format!("spin/turn-00{i}.png"))).unwrap())
        .collect();
    // The camera turns: the frames differ.
    assert!(frames[0].difference(&frames[1]).unwrap().0 > 0.5);
    // --via is for scenes only.
    let run = bspcsg(args(&[&"render", &obj, &"-o", &png, &"--via", &"bsp"])).code(1);
    assert!(run.stderr.contains("--via"), "{}", run.stderr);
}

#[test]
fn the_scene_camera_is_the_one_used() {
    let dir = Scratch::new("render-camera");
    let text = std::fs::read_to_string(scene("mechanical_part")).unwrap();
    let with_camera = text.replacen(
        "\"render_profile\"",
        "\"camera\": {\"eye\": [0.5, 6, 4], \"target\": [0, 0.3, 0]},\n  \
         \"lights\": [{\"type\": \"point\", \"position\": [3, 5, 2], \"color\": \"#ffeedd\"}],\n  \
         \"render_profile\"",
        1,
    );
    let lit = dir.path("lit.json");
    std::fs::write(&lit, &with_camera).unwrap();
    let a = dir.path("a.png");
    bspcsg(args(&[&"render", &lit, &"-o", &a, &"--size", &"64x48"])).ok();
    // The same camera given on the command line: the same image.
    let b = dir.path("b.png");
    bspcsg(args(&[
        &"render",
        &lit,
        &"-o",
        &b,
        &"--size",
        &"64x48",
        &"--eye",
        &"0.5,6,4",
        &"--target",
        &"0,0.3,0",
    ]))
    .ok();
    let (a, b) = (Rgb8::read_png(&a).unwrap(), Rgb8::read_png(&b).unwrap());
    assert_eq!(a.difference(&b), Some((0.0, 0)));
    // The default view differs.
    let c = dir.path("c.png");
    bspcsg(args(&[
        &"render", &lit, &"-o", &c, &"--size", &"64x48", &"--view", &"iso",
    ]))
    .ok();
    assert!(a.difference(&Rgb8::read_png(&c).unwrap()).unwrap().0 > 1.0);
}

#[test]
fn bad_render_input_is_refused_and_nothing_written() {
    let dir = Scratch::new("render-bad");
    let plane = dir.path("plane.json");
    std::fs::write(
        &plane,
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "plane", "normal": [0, 1, 0]}}"#,
    )
    .unwrap();
    let out = dir.path("out/x.png");
    let part = scene("mechanical_part");
    let cases: Vec<(Vec<std::ffi::OsString>, &str)> = vec![
        (args(&[&"render", &plane, &"-o", &out]), "unbounded"),
        (
            args(&[&"render", &part, &"-o", &out, &"--size", &"0x100"]),
            "at least 1x1",
        ),
        (
            args(&[&"render", &part, &"-o", &out, &"--size", &"100000x100000"]),
            "too large",
        ),
        (
            args(&[&"render", &part, &"-o", &out, &"--eye", &"NaN,1,2"]),
            "finite",
        ),
        (
            args(&[
                &"render",
                &part,
                &"-o",
                &out,
                &"--eye",
                &"0,5,0",
                &"--target",
                &"0,0,0",
            ]),
            "up",
        ),
        (args(&[&"render", &part, &"-o", &dir.path("x.jpg")]), "PNG"),
    ];
    for (a, why) in cases {
        let run = bspcsg(&a).code(1);
        assert!(run.stderr.contains(why), "{a:?}: {}", run.stderr);
    }
    // Nothing written, not even the output's directory.
    assert_eq!(dir.files(), vec!["plane.json"]);
}

#[test]
fn check_passes_for_every_example_scene_by_both_routes() {
    for name in scenes() {
        for via in ["bsp", "sdf"] {
            let run = bspcsg(args(&[&"check", &scene(&name), &"--via", &via, &"--json"])).ok();
            let v: Value = serde_json::from_str(&run.stdout).unwrap();
            assert_eq!(v["passed"], true, "{name} {via}: {}", run.stdout);
            let pct = v["rays"]["agreement_pct"].as_f64().unwrap();
            assert!(pct >= 99.5 && v["rays"]["rays"] == 3 * 512 * 512, "{pct}");
            assert!(v["surface"]["samples"].as_u64().unwrap() >= 100_000);
            assert_eq!(
                v["sign"]["agreement_pct"].as_f64(),
                Some(100.0),
                "{name} {via}"
            );
        }
    }
}

/// The mechanical part by the BSP route, as a mesh.
fn part_mesh(dir: &Scratch) -> Mesh {
    let obj = dir.path("part.obj");
    bspcsg(args(&[
        &"export",
        &scene("mechanical_part"),
        &"-o",
        &obj,
        &"-q",
    ]))
    .ok();
    read_mesh(&obj).unwrap()
}

/// Writes `mesh`, checks it against the mechanical part, expects exit 3 naming `measure`.
fn check_fails(dir: &Scratch, name: &str, mesh: &Mesh, measure: &str) -> String {
    let path = dir.path(&format!("{name}.obj"));
    write_mesh(&path, mesh, &[]).unwrap();
    let run = bspcsg(args(&[&"check", &scene("mechanical_part"), &path])).code(3);
    assert!(run.stdout.contains("FAIL"), "{}", run.stdout);
    assert!(run.stderr.contains(measure), "{name}: {}", run.stderr);
    assert!(
        run.stderr.contains(" at ("),
        "the worst place is named: {}",
        run.stderr
    );
    run.stderr
}

#[test]
fn check_fails_with_exit_3_for_wrong_meshes() {
    let dir = Scratch::new("check-wrong");
    let mesh = part_mesh(&dir);
    // The scene's own mesh passes as a file too.
    let own = dir.path("own.obj");
    write_mesh(&own, &mesh, &[]).unwrap();
    bspcsg(args(&[&"check", &scene("mechanical_part"), &own])).ok();

    // Moved by 2 % of its size.
    let size = mesh.bbox().size().max_element();
    let mut moved = mesh.clone();
    for p in &mut moved.positions {
        *p += DVec3::new(0.02 * size, 0.0, 0.0);
    }
    check_fails(&dir, "moved", &moved, "surface distance");

    // Scaled by 1.02 about the origin (the part's centre line).
    let mut scaled = mesh.clone();
    for p in &mut scaled.positions {
        *p *= 1.02;
    }
    check_fails(&dir, "scaled", &scaled, "surface distance");

    // One mounting hole's wall deleted: a small part missing, caught by coverage only.
    let axis = DVec3::new(1.5, 0.0, 1.0);
    let keep: Vec<usize> = (0..mesh.triangle_count())
        .filter(|&t| mesh.triangle(t).iter().any(|c| c.distance(axis) > 0.33))
        .collect();
    let cut = Mesh {
        positions: mesh.positions.clone(),
        triangles: keep.iter().map(|&t| mesh.triangles[t]).collect(),
        sources: keep.iter().map(|&t| mesh.sources[t]).collect(),
    };
    let why = check_fails(&dir, "cut", &cut, "coverage");
    assert!(!why.contains("surface distance"), "{why}");

    // The same part made without one hole's cutter.
    let text = std::fs::read_to_string(scene("mechanical_part")).unwrap();
    let no_hole = dir.path("no_hole.json");
    std::fs::write(
        &no_hole,
        text.replacen("\"pos\": [-1.5, 0, -1.0]", "\"pos\": [-1.5, 20, -1.0]", 1),
    )
    .unwrap();
    let solid = dir.path("solid.obj");
    bspcsg(args(&[&"export", &no_hole, &"-o", &solid, &"-q"])).ok();
    check_fails(&dir, "no_hole", &read_mesh(&solid).unwrap(), "coverage");

    // A difference image on request: a PNG three views wide.
    let diff = dir.path("diff/d.png");
    bspcsg(args(&[
        &"check",
        &scene("mechanical_part"),
        &dir.path("moved.obj"),
        &"--rays",
        &"64",
        &"--image",
        &diff,
    ]))
    .code(3);
    let img = Rgb8::read_png(&diff).unwrap();
    assert_eq!((img.width, img.height), (192, 64));
}

#[test]
fn check_refuses_bad_input_with_exit_1() {
    let dir = Scratch::new("check-bad");
    let plane = dir.path("plane.json");
    std::fs::write(
        &plane,
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "plane", "normal": [0, 1, 0]}}"#,
    )
    .unwrap();
    let run = bspcsg(args(&[&"check", &plane])).code(1);
    assert!(run.stderr.contains("unbounded"), "{}", run.stderr);
    let run = bspcsg(args(&[
        &"check",
        &scene("mechanical_part"),
        &dir.path("none.obj"),
    ]))
    .code(1);
    assert!(run.stderr.contains("none.obj"), "{}", run.stderr);
    let run = bspcsg(args(&[
        &"check",
        &scene("mechanical_part"),
        &"--tolerance",
        &"-1",
    ]))
    .code(1);
    assert!(run.stderr.contains("above zero"), "{}", run.stderr);
}
