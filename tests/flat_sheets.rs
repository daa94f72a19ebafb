//! A boolean whose result is a flat closed sheet, thinner than the weld: both its sides lie on
//! any face of a later operand that passes through it, within the tolerance. It bounds nothing
//! (its mesh is empty), and a later boolean must not make something of it.

use bspcsg::Solid;
use bspcsg::glam::{DQuat, DVec3};

/// A cuboid of `size` centred at the origin, turned by `radians` about `axis`, then moved to
/// `offset` (as the fuzz target's programs build their operands).
fn turned_box(size: [f64; 3], axis: [f64; 3], radians: f64, offset: [f64; 3]) -> Solid {
    Solid::cuboid(DVec3::from(size))
        .unwrap()
        .rotate(DQuat::from_axis_angle(DVec3::from(axis), radians))
        .unwrap()
        .translate(DVec3::from(offset))
        .unwrap()
}

/// The round-17 fork run's 33894a02: a unit cube turned 1e-7° less a 0.625 × 0.625 × 1.25 box
/// turned 1e-9° (a notch along its edge), ∩ a 0.625 × 0.625 × 0.875 box turned 1e-9° about
/// another axis at the same centre, which nearly fills the notch: what is left between the
/// notch's walls and the box's (their faces 0.3125 from the centre, crossing at 1e-11 rad
/// through one line) is two flat wedges up to ~1.2e-11 thick (the weld is 9.5e-12), volume
/// 1.5e-12, whose mesh is empty. Intersected with a 0.625 × 0.625 × 0.125 slab turned 1e-9°
/// whose face y = −0.0625 passes through a wedge, the coplanar rule kept the wedge's side
/// facing as the slab's face does and dropped the other: an open result of "volume" 7.9e-6,
/// larger than the operand. The sheet is now the empty solid (`solid/flat.rs`).
#[test]
fn intersection_with_a_flat_sheet_left_by_boxes_turned_1e_9_degrees_is_empty() {
    let cube = turned_box(
        [1.0; 3],
        [
            -1.7438920176758813e-5,
            -1.7438920176758813e-5,
            0.999999999695884,
        ],
        1.7453292519943295e-9,
        [0.0, -0.25, 0.1875],
    );
    let hole = turned_box(
        [0.625, 0.625, 1.25],
        [
            -0.8952170655766105,
            0.31271176479378965,
            0.31748662595447424,
        ],
        1.7453292519943298e-11,
        [0.25; 3],
    );
    let fill = turned_box(
        [0.625, 0.625, 0.875],
        [0.605815661485127, 0.2605273557528672, 0.7517399026284006],
        1.7453292519943298e-11,
        [0.25; 3],
    );
    let slab = turned_box(
        [0.625, 0.625, 0.125],
        [
            -0.8986656249709273,
            0.31365192400946096,
            0.30663099168345004,
        ],
        1.7453292519943298e-11,
        [0.25; 3],
    );
    let holed = &cube - &hole;
    assert!(
        (holed.volume() - 0.82421875).abs() < 1e-9,
        "{}",
        holed.volume()
    );
    let sheet = &holed & &fill;
    let mesh = sheet.to_mesh();
    assert!(mesh.is_empty(), "{}", mesh.report());
    assert!(sheet.volume().abs() < 1e-11, "{}", sheet.volume());
    let cut = &sheet & &slab;
    let v = cut.volume();
    assert!(
        v.abs() <= sheet.volume().abs() + 1e-12,
        "the intersection's volume {v} is larger than the sheet's {}",
        sheet.volume()
    );
    let report = cut.to_mesh().report();
    assert!(report.is_closed_manifold(), "{report}");
}
