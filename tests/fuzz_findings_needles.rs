//! Inputs the `booleans` fuzz target in `fuzz/` found failing whose output was closed but held
//! needles, or where removing them moved the surface: minimised bytes replayed as named tests,
//! each beside the same operands built by hand and the invariant the needle pass broke. The
//! other inline findings are in `fuzz_findings.rs`; the fork runs' batches in `fuzz_forks.rs`.

#[path = "common/fuzz_replay.rs"]
mod fuzz_replay;

use bspcsg::Solid;
use bspcsg::glam::{DQuat, DVec3};
use fuzz_replay::{program, replay};

/// A fuzz input's unit value (two bytes, little-endian) less a half, as `program.rs` reads an
/// axis or an offset.
fn unit(lo: u8, hi: u8) -> f64 {
    u16::from_le_bytes([lo, hi]) as f64 / 65535.0 - 0.5
}

/// The round-20 fork run's 3645ffb4 cut after its step 1 (closed, 1 needle): a 0.5 OBJ cube
/// less a 0.5 cube turned 1e-8° whose top lies 0.0625 below the cube's, ∪ a 1.125 × 1.125 ×
/// 0.125 slab through the cube's lower part. At the cube's vertical edge x = y = −0.75 the
/// turned cut leaves a slit tip; its needle's collapse moved the cube's corner (−0.75, −0.75,
/// −0.25) onto its neighbour 3.2e-11 away, whose fan was then a fin (two triangles nearly back
/// to back, their normals cancelling). The volume-keeping offset along that fan's normal, the
/// two triangles' tiny sum, was 0.34, along the edge both lie in: no plane of the fan saw it
/// (0 against each), so the plan counted 3.2e-11. The corner went to z = +0.094, a fin 0.34
/// out of the solid, and the shell's box grew by it: a triangle of 4.0e-12 (a needle by the
/// grown box, 4.16e-12, not by the true one, 3.70e-12) was left. The offset now counts as a
/// move of its own at a slit's tip.
#[test]
fn union_with_a_slab_through_a_cube_less_a_cube_turned_1e_8_degrees_keeps_its_corner() {
    let input = [
        0x11, 0x03, 0x03, 0x03, 0x00, 0x08, 0x08, 0x00, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
        0x00, 0xa7, 0x40, 0x03, 0x03, 0x03, 0x00, 0x03, 0x03, 0x28, 0x00, 0x00, 0x00, 0x13, 0x00,
        0x00, 0x00, 0x03, 0x03, 0x00, 0x08, 0x08, 0x00, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
        0x00, 0xa7, 0x01, 0x00, 0x00, 0x00, 0x00, 0x40,
    ];
    replay(&input);
    // The same operands built here: no point of the mesh may lie outside the operands' boxes
    // by more than the needle pass's bound (2·10⁻⁶ of the diagonal, ~4·10⁻⁶).
    let cube = Solid::from_mesh(&program::obj_box(DVec3::splat(0.5)))
        .unwrap()
        .translate(DVec3::splat(-0.5))
        .unwrap();
    let axis = DVec3::new(unit(0x03, 0x03), unit(0x28, 0x00), unit(0x00, 0x00)).normalize();
    let cut = Solid::cuboid(DVec3::splat(0.5))
        .unwrap()
        .rotate(DQuat::from_axis_angle(axis, 1e-8f64.to_radians()))
        .unwrap()
        .translate(DVec3::new(-0.5, -0.5, -0.3125))
        .unwrap();
    let slab = Solid::cuboid(DVec3::new(1.125, 1.125, 0.125))
        .unwrap()
        .translate(2.0 * DVec3::new(unit(0x01, 0x00), unit(0x00, 0x00), unit(0x00, 0x40)))
        .unwrap();
    let solid = &(&cube - &cut) | &slab;
    let mesh = solid.to_mesh();
    let report = mesh.report();
    assert!(
        report.is_closed_manifold() && report.needles == 0,
        "{report}"
    );
    let (lo, hi) = (DVec3::new(-1.5625, -1.5625, -0.75), DVec3::splat(-0.25));
    let bbox = mesh.bbox();
    assert!(
        bbox.min.cmpge(lo - 1e-5).all() && bbox.max.cmple(hi + 1e-5).all(),
        "{bbox:?}"
    );
    assert!((mesh.volume() - solid.volume()).abs() < 1e-9);
}

/// The round-18 fork run's b447eea7, minimised (80 bytes, most zeroed): a 1.125 × 1.125 × 1.5
/// box turned 1e-6° ∪ a 0.125 cube (twice), − a cylinder (radius 0.75, 8 sides) turned 1e-3°,
/// − an OBJ 1.125 × 1.5 × 1.5 box where the first box was: step 3 is four sliver shells where
/// the turned box pokes out (8.2e-9 in all). On the one of 32 triangles, a spike of 1.26e-13
/// (threshold 2.46e-12: edges 2.7e-5, 2.7e-5 and 2.4e-8, height 9.2e-9) whose short edge no
/// collapse may take (link condition): flipping its longest edge kept the short edge, with the
/// neighbour's apex, on the spike's line too, in its place: a needle of the same area (1.2578e-13
/// → 1.2578e-13, counted as helping, the smaller area a hair larger). The next took a stretch
/// off the box's face by 2.6e-7, changing the shell's volume by 2e-9, beyond 1 % of it: redone
/// strict, then left whole with two needles. A thin spike's flip now helps first only where
/// the smaller new area leaves the needles or at least doubles, and where the longest edge's
/// does not, the other edges' are tried within twice its thickness (the longest edge's as any
/// needle's only where none applies): the other long edge's (its apex 9.2e-9 off the neighbour's plane) puts
/// the short edge beside an apex off the line, and the neighbouring needle goes the same way
/// (the shell's volume unchanged). Fails without that: 2 needles.
#[test]
fn sliver_shells_of_a_box_turned_1e_6_degrees_flip_their_caps_off_their_line() {
    replay(&[
        0x00, 0x08, 0x5c, 0xd7, 0x00, 0x00, 0xd7, 0x00, 0xdc, 0x00, 0x00, 0xfd, 0x00, 0x00, 0x00,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xff,
        0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
        0x00, 0x00, 0x00, 0xd7, 0x00, 0x00, 0xd7, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xd7, 0xd7,
        0xd7, 0xd7, 0x00, 0xd7, 0x00, 0xd7, 0x00, 0x00, 0x00, 0x00, 0x40, 0x00, 0x28, 0x23, 0x00,
        0x08, 0x00, 0x08, 0x2f, 0xd7,
    ]);
}
