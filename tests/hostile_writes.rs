//! Hostile and extreme cases for the writers: sidecar files that never clobber an input,
//! two-file writes rolled back, names near the length limit, modes, links and devices kept,
//! signals that leave nothing behind (issue 12).

mod common;

use std::fs;
use std::path::Path;
use std::time::{Duration, Instant};

use bspcsg::read_mesh;
use common::box_obj_text;
use common::hostile::{box_file, tetra_buffer, tetra_gltf};
use common::run::{Scratch, bspcsg, bspcsg_to, refused};

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
    refused(
        &["union".as_ref(), g.as_os_str(), b.as_os_str()],
        &out,
        1,
        &["cube.bin", "g.gltf"],
    );
    assert_eq!(fs::read(s.path("cube.bin")).unwrap(), before);
    assert_eq!(read_mesh(&g).unwrap().triangle_count(), 4);

    // An OBJ input's `mtllib`.
    let c = s.path("c.obj");
    let text = fs::read_to_string(&b).unwrap();
    fs::write(&c, format!("mtllib shared.mtl\n{text}")).unwrap();
    fs::write(s.path("shared.mtl"), "newmtl keep\n").unwrap();
    let out = s.path("shared.obj");
    bspcsg_to(&["union".as_ref(), c.as_os_str(), b.as_os_str()], &out)
        .code(1)
        .says(&["shared.mtl"]);
    assert_eq!(
        fs::read_to_string(s.path("shared.mtl")).unwrap(),
        "newmtl keep\n"
    );
    // Away from inputs, the same command writes both files.
    let out = s.path("fresh.gltf");
    bspcsg_to(&["union".as_ref(), g.as_os_str(), b.as_os_str()], &out).ok();
    assert!(s.path("fresh.bin").exists());
    assert!(read_mesh(&out).unwrap().triangle_count() > 0);
}

/// Item 9 (two-file part): `-o x.bin --format gltf` would write its own buffer over itself.
#[test]
fn gltf_output_named_as_its_own_buffer_is_refused() {
    let s = Scratch::new("own_buffer");
    let b = box_file(&s.path("b.obj"), 0.0);
    let out = s.path("x.bin");
    refused(
        &[
            "convert".as_ref(),
            b.as_os_str(),
            "--format".as_ref(),
            "gltf".as_ref(),
        ],
        &out,
        1,
        &["would be the output itself"],
    );
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

#[test]
fn output_names_near_the_name_limit_write() {
    let dir = Scratch::new("long-name");
    let input = dir.path("in.obj");
    fs::write(&input, box_obj_text([0.0; 3], [1.0; 3])).unwrap();
    // 251 bytes + ".obj" = 255, the longest name a file system takes: the temporary beside it
    // must not be longer.
    let out = dir.path(&format!("{}.obj", "n".repeat(251)));
    bspcsg([
        "convert".as_ref(),
        input.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ])
    .ok();
    assert!(read_mesh(&out).unwrap().triangle_count() == 12);
    assert_eq!(dir.files().len(), 2, "{:?}", dir.files());
}

#[test]
fn an_existing_output_keeps_its_mode_and_a_link_stays_a_link() {
    use std::os::unix::fs::{FileTypeExt as _, PermissionsExt as _};
    let dir = Scratch::new("mode-link");
    let input = dir.path("in.obj");
    fs::write(&input, box_obj_text([0.0; 3], [1.0; 3])).unwrap();
    let convert = |out: &Path| {
        bspcsg([
            "convert".as_ref(),
            input.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
    };
    // Mode 0600 stays 0600.
    let private = dir.path("private.obj");
    fs::write(&private, "old").unwrap();
    fs::set_permissions(&private, fs::Permissions::from_mode(0o600)).unwrap();
    convert(&private).ok();
    let mode = fs::metadata(&private).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o600);
    assert_eq!(read_mesh(&private).unwrap().triangle_count(), 12);
    // A symbolic link is written through: the link stays, its target gets the content.
    let target = dir.path("target.obj");
    fs::write(&target, "old").unwrap();
    let link = dir.path("link.obj");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    convert(&link).ok();
    assert!(
        fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(read_mesh(&target).unwrap().triangle_count(), 12);
    // A character device is written to, never replaced.
    bspcsg([
        "convert".as_ref(),
        input.as_os_str(),
        "-o".as_ref(),
        "/dev/null".as_ref(),
        "--format".as_ref(),
        "obj".as_ref(),
    ])
    .ok();
    assert!(
        fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );
    // A FIFO is refused at once (opening it would block until a reader came).
    let fifo = dir.path("fifo.obj");
    assert!(
        std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let t = Instant::now();
    let run = convert(&fifo).code(1);
    assert!(run.stderr.contains("not a regular file"), "{}", run.stderr);
    assert!(t.elapsed() < Duration::from_secs(5));
    assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
}

#[test]
fn a_signal_during_export_leaves_no_temporary_file_or_directory() {
    signal_during_export("TERM", 143);
}

/// Ctrl-C: as SIGTERM, exit 128 + 2.
#[test]
fn sigint_during_export_leaves_no_temporary_file_or_directory() {
    signal_during_export("INT", 130);
}

/// A closed terminal: as SIGTERM, exit 128 + 1.
#[test]
fn sighup_during_export_leaves_no_temporary_file_or_directory() {
    signal_during_export("HUP", 129);
}

/// Sends `signal` (a `kill -s` name) to an export at several moments: each run either
/// finishes (exit 0, the output whole) or exits `code` with nothing of its own left behind.
fn signal_during_export(signal: &str, code: i32) {
    use std::process::{Command, Stdio};
    let dir = Scratch::new(&format!("signal-{signal}"));
    let scene = dir.path("sphere.json");
    fs::write(
        &scene,
        r#"{"kind":"sdf_primitive","data":{"primitive_type":"sphere","radius":1}}"#,
    )
    .unwrap();
    // A fine sphere: a few hundred thousand triangles, so the write itself takes a while.
    let mut interrupted = 0;
    for (k, delay_ms) in [50u64, 150, 300, 500, 800, 1200].into_iter().enumerate() {
        let out = dir.path(&format!("made{k}/deeper/sphere.obj"));
        let mut child = Command::new(env!("CARGO_BIN_EXE_bspcsg"))
            .args([
                "export".as_ref(),
                scene.as_os_str(),
                "--tolerance".as_ref(),
                "2e-5".as_ref(),
            ])
            .args(["-o".as_ref(), out.as_os_str(), "--quiet".as_ref()])
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        let _ = Command::new("kill")
            .args(["-s", signal, &child.id().to_string()])
            .status();
        let status = child.wait().unwrap();
        match status.code() {
            Some(0) => assert!(out.exists()),
            Some(c) if c == code => {
                interrupted += 1;
                // A signal after the rename leaves the whole output (and its directories).
                assert!(
                    !dir.path(&format!("made{k}")).exists()
                        || read_mesh(&out).is_ok_and(|m| m.triangle_count() > 0),
                    "made directories are removed unless the output was written"
                );
            }
            other => panic!("exit {other:?}"),
        }
        // No hidden temporary or backup file anywhere under the scratch directory.
        let mut stack = vec![dir.0.clone()];
        while let Some(d) = stack.pop() {
            for e in fs::read_dir(&d).unwrap() {
                let e = e.unwrap();
                let name = e.file_name().to_string_lossy().into_owned();
                assert!(!name.starts_with('.'), "{} left in {}", name, d.display());
                if e.file_type().unwrap().is_dir() {
                    stack.push(e.path());
                }
            }
        }
    }
    assert!(interrupted > 0, "no run was interrupted");
}

/// A closed result with a feature finer than float32 resolves (a box 10⁻⁹ thick at x = 1) is
/// written as asked, but STL and glTF round it away, so read back it is open: writing it to
/// those formats warns, and the warning is true; to OBJ, which keeps every coordinate, it
/// neither warns nor opens.
#[test]
fn a_result_finer_than_float32_warns_when_written_to_stl() {
    let dir = Scratch::new("float32");
    let slab = bspcsg::Solid::cuboid(glam::DVec3::new(1e-9, 1.0, 1.0))
        .unwrap()
        .translate(glam::DVec3::X)
        .unwrap()
        .to_mesh();
    assert!(slab.report().is_closed_manifold());
    let input = dir.path("slab.obj");
    bspcsg::write_mesh(&input, &slab, &[]).unwrap();
    for name in ["slab.stl", "slab.glb"] {
        let out = dir.path(name);
        bspcsg([
            "convert".as_ref(),
            input.as_os_str(),
            "-o".as_ref(),
            out.as_os_str(),
        ])
        .ok()
        .says(&["warning", "float32", "not a closed 2-manifold"]);
        let back = read_mesh(&out).unwrap().report();
        assert!(!back.is_closed_manifold(), "{name}: {back}");
    }
    let out = dir.path("copy.obj");
    let run = bspcsg([
        "convert".as_ref(),
        input.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ])
    .ok();
    assert!(!run.stderr.contains("warning"), "{}", run.stderr);
    assert!(read_mesh(&out).unwrap().report().is_closed_manifold());
}
