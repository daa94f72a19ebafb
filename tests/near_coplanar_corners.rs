//! Faces crossing at a hair (10⁻¹¹ rad) whose crossing line ends, within the rounding of its
//! own position, at a corner where two other faces meet: both operands must end their cuts at
//! one point there, or the solid's polygons leave a flat unmatched sliver and its volume
//! (summed about the box centre) is off by the sliver's area times its lever.

use bspcsg::Solid;
use bspcsg::glam::{DQuat, DVec3};

// The fuzz programs' own OBJ box (two triangles a face): the crate's cuboid, with its quads,
// does not show what is below.
#[path = "../fuzz/fuzz_targets/program.rs"]
#[allow(dead_code)]
mod program;

/// A box of `size` centred at the origin, read as a mesh as the fuzz programs' OBJ box is.
fn obj_box(size: DVec3) -> Solid {
    Solid::from_mesh(&program::obj_box(size)).unwrap()
}

/// The cuboid both cases subtract: its top and +x face cut the box.
fn cuboid() -> Solid {
    Solid::cuboid(DVec3::new(0.375, 1.125, 1.375))
        .unwrap()
        .translate(DVec3::new(0.0, 0.0, -0.5))
        .unwrap()
}

/// Round 20's fork input 25a6e85f, step 0, minimised: a 0.5 × 0.125 × 1.125 OBJ box turned
/// 1e-9° about a skew axis, less a 0.375 × 1.125 × 1.375 cuboid whose top and +x face cut it.
/// The result is the box's part beyond x = 0.1875 (0.0263671875) and a wedge 10⁻¹² thick where
/// the turned top rises above the cuboid's.
///
/// The two tops cross at sine 1.53·10⁻¹¹ on a line that passes the corner P = (0.1875, 0.5,
/// 0.1875) (the box's +y face, the cuboid's +x face) 1.56·10⁻⁵ aside, 1.7·10⁻¹⁶ of height,
/// inside the line's rounding band (`Crossing::rounding`, 7.8·10⁻¹⁶). The cuboid's top, cut
/// by the box's while whole, ends at the meets on the line: (0.1875, 0.5000156) on its edge
/// x = 0.1875, then (0.18748, 0.5) where the box's +y face cuts it. The box's top, judging P on
/// the line, ended its wedge at P: the cuboid's piece kept a flat sliver of 9.8·10⁻⁷ the box's
/// did not cover, and the solid came out 0.0263670044, 1.83·10⁻⁷ below its mesh (the sliver's
/// area times its lever from the box centre, 0.5625, over 3). P is now judged beside the line,
/// its edges meeting it more than a weld away, and both cut at the same meets.
#[test]
fn a_crossing_line_ending_at_a_corner_within_its_rounding_leaves_no_sliver() {
    let axis = DVec3::new(
        -0.6213364776626645,
        -0.6214918530536684,
        -0.4771675367349194,
    );
    let turned = obj_box(DVec3::new(0.5, 0.125, 1.125))
        .rotate(DQuat::from_axis_angle(axis, 1e-9f64.to_radians()))
        .unwrap()
        .translate(DVec3::new(0.125, 0.4375, -0.375))
        .unwrap();
    let result = &turned - &cuboid();
    let mesh = result.to_mesh();
    let report = mesh.report();
    assert!(report.is_closed_manifold(), "{report}");
    let want = 0.1875 * 0.125 * 1.125;
    assert!(
        (mesh.volume() - want).abs() < 1e-12,
        "mesh {}",
        mesh.volume()
    );
    assert!(
        (result.volume() - want).abs() < 1e-12,
        "the solid's {} against {want}",
        result.volume()
    );
}

/// The same with the turn left out: the crossing line is the cuboid's top itself, no corner
/// is judged across it, and the solid is exact.
#[test]
fn the_same_difference_unturned_is_exact() {
    let box_ = obj_box(DVec3::new(0.5, 0.125, 1.125))
        .translate(DVec3::new(0.125, 0.4375, -0.375))
        .unwrap();
    let result = &box_ - &cuboid();
    let want = 0.1875 * 0.125 * 1.125;
    assert!(
        (result.volume() - want).abs() < 1e-15,
        "{}",
        result.volume()
    );
    assert!((result.to_mesh().volume() - want).abs() < 1e-15);
}
