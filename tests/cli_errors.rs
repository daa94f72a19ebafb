//! The `bspcsg` binary refusing what it cannot do: bad files, invalid geometry, unwritable or
//! missing outputs, unknown extensions and usage errors, each with its documented exit code and
//! a message naming the file, leaving no output; `--quiet`.

mod common;

use std::ffi::OsStr;
use std::fs;
use std::path::PathBuf;

use bspcsg::Solid;
use common::cli::{FORMATS, combine, info, open_cube, write};
use common::run::{Scratch, bspcsg};

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
