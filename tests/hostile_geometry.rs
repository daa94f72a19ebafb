//! Hostile and extreme geometry on the command line: results that are right or refused with
//! exit 2 (a tiny cube at a corner), right (a sphere less itself turned a hair) and overlapping
//! or self-crossing shells refused or united when asked (issue 12).

mod common;

use std::ffi::OsStr;
use std::fs;
use std::path::Path;

use bspcsg::read_mesh;
use common::box_obj_text;
use common::hostile::{boxes_obj, convex_difference_volume, right_or_refused};
use common::run::{Scratch, bspcsg, bspcsg_to, refused};

#[test]
fn a_tiny_cube_at_a_unit_cube_corner_never_gives_a_broken_result_with_success() {
    let dir = Scratch::new("tiny-corner");
    let unit = dir.path("unit.obj");
    fs::write(&unit, box_obj_text([0.0; 3], [1.0; 3])).unwrap();
    for s in [1e-20, 1e-60, 1e-100] {
        let tiny = dir.path(&format!("tiny{s:e}.obj"));
        fs::write(&tiny, box_obj_text([-s; 3], [0.0; 3])).unwrap();
        for op in ["union", "difference"] {
            let out = dir.path(&format!("{op}{s:e}.obj"));
            let run = bspcsg_to(&[op.as_ref(), unit.as_os_str(), tiny.as_os_str()], &out);
            // A refusal's hint fits the case: the part is far smaller than what it meets
            // (it spoke only of faces that nearly coincide).
            if run.code != 0 {
                assert!(run.stderr.contains("far smaller"), "{}", run.stderr);
            }
            right_or_refused(run, &out, &format!("{op} {s:e}"), |report| {
                assert!((report.volume - 1.0).abs() < 1e-12, "{op} {s:e}: {report}");
            });
        }
    }
}

/// Item 10: a UV sphere less itself turned 10⁻⁴° about a tilted axis. Its facets cross their
/// twins at 1.7·10⁻⁶ rad, and the difference is a film of slivers up to 3·10⁻⁷ thick between
/// them. Both operands cut each facet on the one crossing line (`MEET_BELOW` in the kernel's
/// polygon splitting), so the result is a closed 2-manifold of the slivers' volume, computed
/// here apart from the kernel by clipping the convex spheres (3.58·10⁻⁷ and 1.81·10⁻⁷; it was
/// open, with 951 and 3,678 boundary edges, and refused). At 128×64 (9.05·10⁻⁸; 30 boundary
/// edges at the pole fans before) since a vertex near a cutting plane crossing its polygon at
/// a sine below 0.1 is judged by the band by the angle (`Polygon::split`).
///
/// At 256×128 (4.53·10⁻⁸) every fan facet of either sphere passes within 10⁻⁶ of its pole, and
/// a fan edge of one is crossed by the other's fan facets from across the pole at a sine of
/// 0.0245, each of those planes within `eps` of the next there: judged by `eps` rather than by
/// the band by the angle (`ON_BAND_BELOW` at 10⁻³, not 0.1), the polygons beside such an edge
/// cut it at different points (632 boundary edges at the poles). And in the first two rings
/// neighbours across a meridian edge cross at sines of 6·10⁻⁴ and 9·10⁻⁴: such an edge, cut
/// by the twin facet, was interpolated rather than cut at the meet of the three planes
/// (`CutEdge::cut` took the meet only where the edge's own two planes cross at 10⁻³ or more),
/// 8.7·10⁻¹¹ off the crossing line, where the other operand's cut by a tree's cell plane lay
/// on it (1,666 boundary edges in three-edge slits; refused). 512×256 is past the work budget.
#[test]
fn a_sphere_less_itself_turned_a_hair_is_closed_with_the_slivers_volume() {
    let dir = Scratch::new("sphere-turned");
    for segments in [32, 64, 128, 256] {
        let sphere = bspcsg::Solid::sphere(1.0, segments, segments / 2).unwrap();
        let turned = sphere
            .clone()
            .rotate_axis_angle(bspcsg::glam::DVec3::new(0.3, 1.0, 0.2), 1e-4)
            .unwrap();
        let want = convex_difference_volume(&sphere, &turned);
        let (a, b) = (dir.path("a.obj"), dir.path("b.obj"));
        bspcsg::write_mesh(&a, &sphere.to_mesh(), &[]).unwrap();
        bspcsg::write_mesh(&b, &turned.to_mesh(), &[]).unwrap();
        let out = dir.path(&format!("out{segments}.obj"));
        bspcsg_to(&["difference".as_ref(), a.as_os_str(), b.as_os_str()], &out).ok();
        let report = read_mesh(&out).unwrap().report();
        assert!(report.is_closed_manifold(), "{segments}: {report}");
        // The film's needles are removed: a guard that sent its thin shells back to removing
        // only the kernel's own needles left 8,358 of them at 128×64 (65,190 → 80,984 triangles).
        // Open: 256×128 keeps 3 (of 262,008 triangles).
        let needles_left = if segments < 256 { 0 } else { 3 };
        assert!(report.needles <= needles_left, "{segments}: {report}");
        // Off by about the tolerance times the slivers' area (6e-11 of 3.6e-7 at 32×16).
        assert!(
            (report.volume - want).abs() < 1e-3 * want,
            "{segments}: {} vs {want:e}",
            report.volume
        );
    }
}

#[test]
fn overlapping_shells_are_refused_as_an_operand_and_reported_by_info() {
    let dir = Scratch::new("overlapping-shells");
    // Two unit cubes in one file, the second moved by (0.5, 0.25, 0.25): closed and manifold,
    // volume 2, but the solid they bound is 1.71875.
    let two = boxes_obj(&[
        ([0.0; 3], [1.0; 3], false),
        ([0.5, 0.25, 0.25], [1.5, 1.25, 1.25], false),
    ]);
    let shells = dir.path("shells.obj");
    fs::write(&shells, two).unwrap();
    let other = dir.path("other.obj");
    fs::write(&other, box_obj_text([0.25, 0.25, -0.5], [1.25, 1.25, 0.5])).unwrap();
    let out = dir.path("out.obj");
    refused(
        &["union".as_ref(), shells.as_os_str(), other.as_os_str()],
        &out,
        2,
        &["self-intersecting", "shells.obj"],
    );
    let info = bspcsg(["info".as_ref(), shells.as_os_str()]).ok();
    assert!(
        info.stdout.contains("bounds a solid                  no"),
        "{}",
        info.stdout
    );
    let pairs = read_mesh(&shells)
        .unwrap()
        .crossing_triangle_pairs()
        .unwrap();
    assert!(!pairs.is_empty());
    // Each cube alone, and the two touching along a face, are solids.
    assert!(
        read_mesh(&other)
            .unwrap()
            .crossing_triangle_pairs()
            .unwrap()
            .is_empty()
    );
    let err = bspcsg::read_solid(&shells, &bspcsg::FromMeshOptions::default()).unwrap_err();
    assert!(
        err.to_string().contains(&format!("{} pairs", pairs.len())),
        "{err}"
    );
}

/// Run a boolean with `--union-shells`: the volume written, or the failed run.
fn union_shells_volume(dir: &Scratch, inputs: &[&Path]) -> f64 {
    let out = dir.path("united.obj");
    let mut args: Vec<&OsStr> = vec!["union".as_ref(), "--union-shells".as_ref()];
    args.extend(inputs.iter().map(|p| p.as_os_str()));
    args.extend(["-o".as_ref(), out.as_os_str()]);
    bspcsg(&args).ok();
    let mesh = read_mesh(&out).unwrap();
    assert!(mesh.report().is_closed_manifold(), "{}", mesh.report());
    mesh.volume()
}

/// Overlapping shells are resolved as their union when asked (`--union-shells`,
/// `FromMeshOptions::union_shells`), a cavity staying with the shell around it; a shell that
/// crosses itself is refused either way, naming the crossing.
#[test]
fn overlapping_shells_are_united_when_asked_and_a_shell_through_itself_is_refused() {
    let dir = Scratch::new("union-shells");
    let a = ([0.0; 3], [1.0; 3], false);
    let b = ([0.5, 0.25, 0.25], [1.5, 1.25, 1.25], false);
    let shells = dir.path("shells.obj");
    fs::write(&shells, boxes_obj(&[a, b])).unwrap();
    let other = dir.path("other.obj");
    fs::write(&other, box_obj_text([0.25, 0.25, -0.5], [1.25, 1.25, 0.5])).unwrap();
    // A ∪ B = 2 − 0.5 · 0.75 · 0.75 = 1.71875; with the third box, by inclusion–exclusion
    // 1.71875 + 1 − (0.28125 + 0.1875 − 0.09375) = 2.34375.
    let alone = dir.path("alone.obj");
    fs::write(&alone, box_obj_text([5.0; 3], [6.0; 3])).unwrap();
    assert!((union_shells_volume(&dir, &[&shells, &alone]) - 2.71875).abs() < 1e-12);
    assert!((union_shells_volume(&dir, &[&shells, &other]) - 2.34375).abs() < 1e-12);
    let options = bspcsg::FromMeshOptions::default().with_union_shells(true);
    let solid = bspcsg::read_solid(&shells, &options).unwrap();
    assert!((solid.volume() - 1.71875).abs() < 1e-12);
    // A box with a cavity [0.1, 0.9]³ (0.488 of solid), crossed by B: (A − C) ∪ B =
    // 0.488 + 1 − (0.28125 − 0.4 · 0.65 · 0.65) = 1.37575.
    let hollow = dir.path("hollow.obj");
    let cavity = ([0.1; 3], [0.9; 3], true);
    fs::write(&hollow, boxes_obj(&[a, cavity, b])).unwrap();
    let solid = bspcsg::read_solid(&hollow, &options).unwrap();
    assert!(
        (solid.volume() - 1.37575).abs() < 1e-12,
        "{}",
        solid.volume()
    );
    assert!((union_shells_volume(&dir, &[&hollow, &alone]) - 2.37575).abs() < 1e-12);
    // One shell through itself: a cube whose corner (1, 1, 1) is pulled down to
    // (0.8, 0.8, −0.5), through its own bottom face. Closed and manifold, not a solid.
    let folded = dir.path("folded.obj");
    let text = box_obj_text([0.0; 3], [1.0; 3]).replacen("v 1.0 1.0 1.0", "v 0.8 0.8 -0.5", 1);
    assert!(text.contains("v 0.8 0.8 -0.5"));
    fs::write(&folded, &text).unwrap();
    let mesh = read_mesh(&folded).unwrap();
    assert!(mesh.report().closed, "{}", mesh.report());
    let pairs = mesh.crossing_triangle_pairs().unwrap();
    assert!(!pairs.is_empty());
    let err = bspcsg::read_solid(&folded, &options).unwrap_err();
    assert!(
        matches!(
            err.mesh_defect(),
            Some(bspcsg::MeshDefect::ShellCrossesItself { .. })
        ),
        "{err}"
    );
    let first = format!("first: triangles {} and {}", pairs[0][0], pairs[0][1]);
    for flags in [&["--union-shells"][..], &[]] {
        let out = dir.path("out.obj");
        let mut args: Vec<&OsStr> = vec!["union".as_ref()];
        args.extend(flags.iter().map(OsStr::new));
        args.extend([folded.as_os_str(), alone.as_os_str()]);
        refused(&args, &out, 2, &["folded.obj", &first]);
    }
    // Without the flag, overlapping shells are refused with a hint at it.
    let out = dir.path("out.obj");
    bspcsg_to(
        &["union".as_ref(), shells.as_os_str(), alone.as_os_str()],
        &out,
    )
    .code(2)
    .says(&["--union-shells"]);
}

/// The count `info` prints on its line `crossing triangle pairs`.
fn info_crossing_pairs(mesh: &Path) -> usize {
    let info = bspcsg(["info".as_ref(), mesh.as_os_str()]).ok();
    info.stdout
        .lines()
        .find_map(|l| l.strip_prefix("crossing triangle pairs"))
        .unwrap_or_else(|| panic!("{}", info.stdout))
        .trim()
        .parse()
        .unwrap()
}

/// Shells that overlap only in shared planes (no edge through a face) are found by their
/// coplanar faces facing the same way; shells face to face (facing opposite ways) touch.
#[test]
fn shells_overlapping_in_shared_planes_are_refused_and_face_to_face_ones_accepted() {
    let dir = Scratch::new("shell-planes");
    let unit = ([0.0; 3], [1.0; 3], false);
    let moved = dir.path("moved.obj");
    fs::write(
        &moved,
        boxes_obj(&[unit, ([0.5, 0.0, 0.0], [1.5, 1.0, 1.0], false)]),
    )
    .unwrap();
    let alone = dir.path("alone.obj");
    fs::write(&alone, box_obj_text([5.0; 3], [6.0; 3])).unwrap();
    assert!(info_crossing_pairs(&moved) > 0);
    let out = dir.path("out.obj");
    refused(
        &["union".as_ref(), moved.as_os_str(), alone.as_os_str()],
        &out,
        2,
        &["self-intersecting", "moved.obj"],
    );
    // As their union: 1.5, and 2.5 with the far box.
    let options = bspcsg::FromMeshOptions::default().with_union_shells(true);
    assert_eq!(bspcsg::read_solid(&moved, &options).unwrap().volume(), 1.5);
    assert_eq!(union_shells_volume(&dir, &[&moved, &alone]), 2.5);
    // Stacked face to face (moved off the corners, which welding would join into edges of
    // four faces): coplanar faces that overlap facing opposite ways touch. Volume 2.
    let stacked = dir.path("stacked.obj");
    let top = ([0.25, 0.25, 1.0], [1.25, 1.25, 2.0], false);
    fs::write(&stacked, boxes_obj(&[unit, top])).unwrap();
    assert_eq!(info_crossing_pairs(&stacked), 0);
    let solid = bspcsg::read_solid(&stacked, &bspcsg::FromMeshOptions::default()).unwrap();
    assert!((solid.volume() - 2.0).abs() < 1e-12, "{}", solid.volume());
    // The same cube twice: each triangle crosses its copy; refused.
    let twice = dir.path("twice.obj");
    fs::write(&twice, boxes_obj(&[unit, unit])).unwrap();
    assert!(info_crossing_pairs(&twice) >= 12);
    refused(
        &["union".as_ref(), twice.as_os_str(), alone.as_os_str()],
        &out,
        2,
        &["twice.obj"],
    );
}

/// Solids touching along an edge or at a point: `to_mesh` gives each its own vertices there
/// (two closed shells), a file keeps them (OBJ and glTF by index, manifold3d reads them so),
/// and a reader that joins equal positions pairs the faces around the shared edge by angle
/// again, so the file reads back as the same closed solid — also from STL, which has no
/// indices. Issue 12 item 3 (a cube less itself turned 10⁻³° wrote such slivers) and item 10
/// (grid unions of boxes written to a file).
#[test]
fn shells_touching_along_an_edge_or_at_a_point_read_back_as_closed_solids() {
    let dir = Scratch::new("edge-touch");
    let (a, b) = (dir.path("a.obj"), dir.path("b.obj"));
    fs::write(&a, box_obj_text([0.0; 3], [1.0; 3])).unwrap();
    for (touch, other) in [
        ("edge", [1.0, 1.0, 0.0]),
        ("vertex", [1.0, 1.0, 1.0]),
        ("overlap", [0.5, 0.5, 0.5]),
    ] {
        let max = other.map(|x| x + 1.0);
        fs::write(&b, box_obj_text(other, max)).unwrap();
        let volume = if touch == "overlap" { 1.875 } else { 2.0 };
        for ext in ["obj", "stl", "glb"] {
            let out = dir.path(&format!("{touch}.{ext}"));
            let run = bspcsg([
                "union".as_ref(),
                a.as_os_str(),
                b.as_os_str(),
                "-o".as_ref(),
                out.as_os_str(),
            ])
            .ok();
            assert!(
                !run.stderr.contains("warning"),
                "{touch}.{ext}: {}",
                run.stderr
            );
            let report = read_mesh(&out).unwrap().report();
            assert!(report.is_closed_manifold(), "{touch}.{ext}: {report}");
            assert_eq!(report.shells.len(), if touch == "overlap" { 1 } else { 2 });
            assert!((report.volume - volume).abs() < 1e-12, "{report}");
            let info = bspcsg(["info".as_ref(), out.as_os_str()]).ok();
            assert!(
                info.stdout
                    .lines()
                    .any(|l| l.contains("closed 2-manifold") && l.contains("yes")),
                "{}",
                info.stdout
            );
            // And it is an operand like any closed solid.
            let again = dir.path("again.obj");
            bspcsg([
                "difference".as_ref(),
                out.as_os_str(),
                a.as_os_str(),
                "-o".as_ref(),
                again.as_os_str(),
            ])
            .ok();
            let rest = read_mesh(&again).unwrap().report();
            assert!(rest.is_closed_manifold(), "{rest}");
            assert!((rest.volume - (volume - 1.0)).abs() < 1e-12, "{rest}");
        }
    }
    // A file of boxes in a 2×2×2 checkerboard, every box its own vertices with equal
    // positions: every inner edge has four faces, every box is a closed shell.
    let cells = [
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let boxes: Vec<_> = cells
        .iter()
        .map(|&c| (c, c.map(|x| x + 1.0), false))
        .collect();
    let checker = dir.path("checker.obj");
    fs::write(&checker, boxes_obj(&boxes)).unwrap();
    let report = read_mesh(&checker).unwrap().report();
    assert!(report.is_closed_manifold(), "{report}");
    assert_eq!(report.shells.len(), 4);
    assert!((report.volume - 4.0).abs() < 1e-12, "{report}");
    // Faces around an edge that do not alternate in direction do not bound a solid there (a
    // box turned inside out touching another): not paired, still a non-manifold edge.
    let boxes = [
        ([0.0; 3], [1.0; 3], false),
        ([1.0, 1.0, 0.0], [2.0, 2.0, 1.0], true),
    ];
    fs::write(&checker, boxes_obj(&boxes)).unwrap();
    let report = read_mesh(&checker).unwrap().report();
    assert_eq!(report.non_manifold_edges, 1, "{report}");
    assert!(!report.is_closed_manifold());
}

/// The library's round trip of touching results: a cube less itself turned 10⁻³° (slivers
/// touching along edges) and a 3×3×3 checkerboard union of unit cubes (touching along every
/// inner edge and at corners), written and read back: closed, the same volume.
#[test]
fn touching_results_round_trip_as_closed_solids() {
    use bspcsg::glam::{DQuat, DVec3};
    use bspcsg::{Solid, write_mesh};
    let dir = Scratch::new("touch-round-trip");
    let cube = Solid::cuboid(DVec3::ONE).unwrap();
    // The box [0, 1]³ turned about the origin, as the CLI would turn a file of it.
    let corner = cube.clone().translate(DVec3::splat(0.5)).unwrap();
    let axis = DVec3::new(0.3, 1.0, 0.2).normalize();
    let turned = corner
        .clone()
        .rotate(DQuat::from_axis_angle(axis, 1e-3_f64.to_radians()))
        .unwrap();
    let slivers = corner.difference(&turned);
    let mut grid = Vec::new();
    for i in 0..27 {
        let (x, y, z) = (i % 3, i / 3 % 3, i / 9);
        if (x + y + z) % 2 == 0 {
            let at = DVec3::new(f64::from(x), f64::from(y), f64::from(z));
            grid.push(cube.clone().translate(at).unwrap());
        }
    }
    let checker = Solid::union_all(grid);
    // STL and glTF store f32: rounding a sliver 10⁻⁵ thick to it folds a triangle flat, a loss
    // of the format, not of the touching; the checkerboard's integers round to themselves.
    let all = ["obj", "stl", "glb", "gltf"];
    for (name, solid, formats) in [
        ("slivers", &slivers, &all[..1]),
        ("checker", &checker, &all[..]),
    ] {
        let mesh = solid.to_mesh();
        let report = mesh.report();
        assert!(report.is_closed_manifold(), "{name}: {report}");
        let back = mesh
            .as_read_back()
            .expect("touching shells share positions");
        assert!(
            back.report().is_closed_manifold(),
            "{name}: {}",
            back.report()
        );
        for ext in formats {
            let path = dir.path(&format!("{name}.{ext}"));
            write_mesh(&path, &mesh, &[]).unwrap();
            let read = read_mesh(&path).unwrap().report();
            assert!(read.is_closed_manifold(), "{name}.{ext}: {read}");
            assert_eq!(read.shells.len(), report.shells.len(), "{name}.{ext}");
            let allowed = 1e-12 * report.volume.abs().max(1.0);
            assert!(
                (read.volume - report.volume).abs() <= allowed,
                "{name}.{ext}: {} vs {}",
                read.volume,
                report.volume
            );
        }
    }
    assert!((checker.volume() - 14.0).abs() < 1e-12);
}
