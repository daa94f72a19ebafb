//! `bspcsg export` of scene documents, run as a user runs it: every example scene by both
//! routes, and bad scenes refused with exit 1 naming the file and the place in it.

mod common;

use std::ffi::OsStr;
use std::fs;
use std::path::PathBuf;

use common::cli::{assert_solid, info, num, rel};
use common::run::{Scratch, bspcsg};
use common::scenes::example_paths;

fn scenes() -> Vec<PathBuf> {
    let v = example_paths();
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
