//! Crowded but valid meshes against folded ones: points where thousands of triangles meet.
//! The check for crossing triangles settles such a point by a sweep about it (see
//! `mesh::self_intersect::hubs`), so two cones apex to apex read as the solid they are, while a
//! folded fan of as many triangles is found crossing in bounded work. The work is counted beside
//! the search (`mesh::self_intersect::tests::crowded_points_are_settled_by_a_sweep`); here the
//! CLI answers. Every input is generated here.

mod common;

use std::ffi::OsStr;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use bspcsg::{Mesh, Solid, read_mesh};
use common::run::{Scratch, bspcsg, bspcsg_to, refused};
use common::{assert_closed_manifold, box_obj_text};

/// Writes `text` to `name` in `dir` and reads it back, asserting a closed 2-manifold: the
/// file's path and its mesh.
fn write_closed(dir: &Scratch, name: &str, text: &str) -> (PathBuf, Mesh) {
    let path = dir.path(name);
    fs::write(&path, text).unwrap();
    let mesh = read_mesh(&path).unwrap();
    assert_closed_manifold(&mesh, name);
    (path, mesh)
}

/// The unit box from (3, 3, 3) written to `box.obj` in `dir`: the other operand of the CLI
/// booleans here, apart from every crowded input.
fn unit_box(dir: &Scratch) -> PathBuf {
    let path = dir.path("box.obj");
    fs::write(&path, box_obj_text([3.0; 3], [4.0; 3])).unwrap();
    path
}

/// The volume of what `bspcsg union FLAGS a b -o out` writes (the run must succeed).
fn union_volume(flags: &[&str], a: &Path, b: &Path, out: &Path) -> f64 {
    let mut args: Vec<&OsStr> = vec!["union".as_ref()];
    args.extend(flags.iter().map(OsStr::new));
    args.extend([a.as_os_str(), b.as_os_str()]);
    bspcsg_to(&args, out).ok();
    read_mesh(out).unwrap().volume()
}

/// The volume of the pyramid over the regular `n`-gon of unit radius, height 1.
fn cone_volume(n: usize) -> f64 {
    n as f64 * (std::f64::consts::TAU / n as f64).sin() / 6.0
}

/// OBJ text of two cones of `n` sides touching apex to apex at (0, 0, 1): the second mirrored
/// through z = 1 and y = 0 (so still facing out). With `pinched` both use one apex vertex (the
/// reader splits the pinched point into two vertices again), else each its own.
fn hourglass_obj(n: usize, pinched: bool) -> String {
    let mut text = String::new();
    for (sy, base) in [(1.0, 0.0), (-1.0, 2.0)] {
        writeln!(text, "v 0 0 1\nv 0 0 {base:?}").unwrap();
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            writeln!(text, "v {:?} {:?} {base:?}", a.cos(), sy * a.sin()).unwrap();
        }
    }
    for first in [1, n + 3] {
        let apex = if pinched { 1 } else { first };
        for i in 0..n {
            let (p, q) = (first + 2 + i, first + 2 + (i + 1) % n);
            writeln!(text, "f {apex} {p} {q}\nf {} {q} {p}", first + 1).unwrap();
        }
    }
    text
}

/// OBJ text of a cone of `n` sides (apex at height 1 over the unit circle) with ring vertex 10
/// moved round past its neighbour, inside the circle: base triangles overlap in the base's
/// plane, facing the same way, sharing only the base's centre.
fn folded_cone_obj(n: usize) -> String {
    let mut text = String::from("v 0 0 1\nv 0 0 0\n");
    for i in 0..n {
        let (s, r) = if i == 10 {
            (12.5, 0.9)
        } else {
            (i as f64, 1.0)
        };
        let a = std::f64::consts::TAU * s / n as f64;
        writeln!(text, "v {:?} {:?} 0", r * a.cos(), r * a.sin()).unwrap();
    }
    for i in 0..n {
        let (p, q) = (3 + i, 3 + (i + 1) % n);
        writeln!(text, "f 1 {p} {q}\nf 2 {q} {p}").unwrap();
    }
    text
}

/// Two cones of 20,000 sides apex to apex, on two vertices or on one: every triangle of either
/// apex's fan meets every one of the other's at that point (4·10⁸ pairs whose boxes overlap),
/// which stopped the check at its budget and refused the file (exit 2). Now read as a closed
/// solid of the right volume; at 2,000 sides the CLI unites it with a box.
#[test]
fn cones_touching_apex_to_apex_read_as_a_solid() {
    let dir = Scratch::new("hourglass");
    for pinched in [false, true] {
        let name = if pinched {
            "pinched.obj"
        } else {
            "hourglass.obj"
        };
        let (_, mesh) = write_closed(&dir, name, &hourglass_obj(20_000, pinched));
        assert!(
            mesh.crossing_triangle_pairs().unwrap().is_empty(),
            "{pinched}"
        );
        let solid = Solid::from_mesh(&mesh).unwrap();
        let exact = 2.0 * cone_volume(20_000);
        assert!((solid.volume() - exact).abs() < 1e-12, "{}", solid.volume());
    }
    let path = dir.path("small.obj");
    fs::write(&path, hourglass_obj(2_000, false)).unwrap();
    let volume = union_volume(&[], &path, &unit_box(&dir), &dir.path("out.obj"));
    assert!(
        (volume - (2.0 * cone_volume(2_000) + 1.0)).abs() < 1e-9,
        "{volume}"
    );
    let info = bspcsg(["info".as_ref(), path.as_os_str()]).ok();
    assert!(
        info.stdout.contains("bounds a solid                  yes"),
        "{}",
        info.stdout
    );
}

/// A fan of 20,000 triangles around a cone's base centre, folded over at one ring vertex: the
/// fan is not embedded, so its pairs were tested one by one until the budget stopped them
/// (exit 2, "gave up"). The sweep about the centre leaves only the pairs near the fold, which
/// cross: the file is refused as self-intersecting, naming the file (exit 2).
#[test]
fn a_folded_fan_of_many_triangles_is_found_crossing() {
    let dir = Scratch::new("folded");
    let (path, mesh) = write_closed(&dir, "folded.obj", &folded_cone_obj(20_000));
    let pairs = mesh.crossing_triangle_pairs().unwrap();
    assert!(!pairs.is_empty() && pairs.len() < 10, "{pairs:?}");
    let other = unit_box(&dir);
    let out = dir.path("out.obj");
    let args: [&OsStr; 3] = ["union".as_ref(), path.as_os_str(), other.as_os_str()];
    refused(&args, &out, 2, &["folded.obj", "self-intersecting"]);
}

/// OBJ text of a low cone (apex at (0.9, 0, 0.2)) over a five-lobed base of `n` sides (radius
/// `1 + 0.6 cos 5θ`), the base a fan about the origin; and the base's area.
fn lobed_cone_obj(n: usize) -> (String, f64) {
    let ring: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let r = 1.0 + 0.6 * (5.0 * a).cos();
            [r * a.cos(), r * a.sin()]
        })
        .collect();
    let mut text = String::from("v 0.9 0 0.2\nv 0 0 0\n");
    let mut area = 0.0;
    for (i, [x, y]) in ring.iter().enumerate() {
        writeln!(text, "v {x:?} {y:?} 0").unwrap();
        let [u, v] = ring[(i + 1) % n];
        area += 0.5 * (x * v - u * y);
    }
    for i in 0..n {
        let (p, q) = (3 + i, 3 + (i + 1) % n);
        writeln!(text, "f 1 {p} {q}\nf 2 {q} {p}").unwrap();
    }
    (text, area)
}

/// A low cone over a five-lobed base of 20,000 sides, its apex over a lobe: the apex's fan is
/// not embedded seen along its normals (the sweep settles it), and each of its slivers meets the
/// boxes of thousands of the base's triangles (a tangent plane of the lobed base cuts across
/// them), which stopped the check at its budget. The base's fan is flat and every apex triangle
/// lies on one side of its plane, so no such pair needs a test: a solid of volume area × height / 3.
#[test]
fn a_cone_over_a_lobed_base_reads_as_a_solid() {
    let dir = Scratch::new("lobed");
    let (text, area) = lobed_cone_obj(20_000);
    let (_, mesh) = write_closed(&dir, "lobed.obj", &text);
    assert!(mesh.crossing_triangle_pairs().unwrap().is_empty());
    let volume = Solid::from_mesh(&mesh).unwrap().volume();
    assert!((volume - area * 0.2 / 3.0).abs() < 1e-12, "{volume}");
}

/// OBJ text of `n` thin tetrahedra along one diagonal, stacked a thousandth of their thickness
/// apart: no vertex shared, every box overlapping every other, no two crossing.
fn stacked_slivers_obj(n: usize) -> String {
    let h = 1e-3 / n as f64;
    let mut text = String::new();
    for i in 0..n {
        let z = i as f64 * h;
        writeln!(text, "v 0 0 {z:?}\nv 1 1 {:?}", z + 1.0).unwrap();
        writeln!(
            text,
            "v 0.5 {:?} {:?}\nv 0.5 0.5 {:?}",
            0.5 + 1e-3,
            z + 0.5,
            z + 0.5 + 0.25 * h
        )
        .unwrap();
    }
    for i in 0..n {
        let b = 4 * i + 1;
        for [p, q, r] in [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]] {
            writeln!(text, "f {} {} {}", b + p, b + q, b + r).unwrap();
        }
    }
    text
}

/// What the check still gives up on: 5,000 slivers stacked within a thousandth of their
/// thickness (a valid mesh; 2·10⁸ pairs of overlapping boxes, no point shared). The check stops
/// at its budget: a boolean refuses the file saying so and what to do (exit 2), `info` says the
/// check gave up, and `--allow-open` takes the mesh unchecked.
#[test]
fn stacked_slivers_stop_the_crossing_check_at_its_budget() {
    let dir = Scratch::new("slivers");
    let (path, mesh) = write_closed(&dir, "slivers.obj", &stacked_slivers_obj(5_000));
    let err = mesh.crossing_triangle_pairs().unwrap_err();
    assert!(
        matches!(
            err.mesh_defect(),
            Some(bspcsg::MeshDefect::CrossingCheckOverBudget { triangles, .. })
                if *triangles == 20_000
        ),
        "{err}"
    );
    let out = dir.path("out.obj");
    let other = unit_box(&dir);
    let args: [&OsStr; 3] = ["union".as_ref(), path.as_os_str(), other.as_os_str()];
    let needles = [
        "slivers.obj",
        "gave up after",
        "candidate pairs",
        "--allow-open",
    ];
    refused(&args, &out, 2, &needles);
    let info = bspcsg(["info".as_ref(), path.as_os_str()]).ok();
    assert!(
        info.stdout.contains("gave up at its budget"),
        "{}",
        info.stdout
    );
    assert!(
        info.stdout
            .contains("bounds a solid                  not known"),
        "{}",
        info.stdout
    );
    let volume = union_volume(&["--allow-open"], &path, &other, &out);
    let slivers = mesh.volume();
    assert!(slivers > 0.0);
    assert!((volume - (slivers + 1.0)).abs() < 1e-9, "{volume}");
}
