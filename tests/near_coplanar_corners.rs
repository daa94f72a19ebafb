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

/// The tilt of [`tilted_box`]'s top: sine 1.46·10⁻¹¹, as the turned box's above.
const TILT: f64 = 1.0 / (1u64 << 36) as f64;

/// The fuzz programs' OBJ box 2 × 2 × 1.5 over [-0.5, 1.5]², its bottom at z = -1 and its top
/// raised from z = 0.5 by `TILT` × `rise(x, y)` at each corner: a plane, `rise` being linear,
/// crossing z = 0.5 where `rise` is 0. Every coordinate is a short dyadic, so the corners are
/// exact.
fn tilted_box(rise: fn(f64, f64) -> f64) -> Solid {
    let mut mesh = program::obj_box(DVec3::new(2.0, 2.0, 1.5));
    for p in &mut mesh.positions {
        *p += DVec3::new(0.5, 0.5, -0.25);
        if p.z > 0.0 {
            p.z += TILT * rise(p.x, p.y);
        }
    }
    Solid::from_mesh(&mesh).unwrap()
}

/// The OBJ box [0, 1]² × [-0.75, 0.5], its top split along its diagonal from (0, 0) to (1, 1).
fn unit_box() -> Solid {
    obj_box(DVec3::new(1.0, 1.0, 1.25))
        .translate(DVec3::new(0.5, 0.5, -0.125))
        .unwrap()
}

/// A box's top and another's tilted by 2⁻³⁶ cross on a line that passes corners of the first
/// top given there to the bit, not made on it by a split (the case `beside_the_line` in
/// `polygon/split.rs` leaves to the rounding band: no edge of such a corner meets the line
/// away from it, except along the line itself). Three lines: along the top's own diagonal
/// (x = y, through (0, 0) and (1, 1)), across it (x + y = 1, through (1, 0) and (0, 1)), and
/// through the corner (0, 0) and the middle of the edge y = 1 (y = 2x). The wedge where the
/// unit box's top rises above the tilted one, `TILT` × `wedge` in volume (10⁻¹² or less, below
/// the weld), is the difference; the union, intersection and the other difference must each
/// be closed, manifold and within 10⁻¹¹ of their volume, mesh and solid alike.
#[test]
fn tops_crossing_at_a_hair_through_given_corners_close_with_their_volume() {
    type Rise = fn(f64, f64) -> f64;
    // The rise, the tilted box's volume and the wedge's (each over TILT).
    let lines: [(Rise, f64, f64); 3] = [
        (|x, y| x - y, 0.0, 1.0 / 6.0),
        (|x, y| x + y - 1.0, 0.0, 1.0 / 6.0),
        (|x, y| 2.0 * x - y, 2.0, 1.0 / 12.0),
    ];
    for (k, (rise, extra, wedge)) in lines.into_iter().enumerate() {
        let (a, b) = (unit_box(), tilted_box(rise));
        let (a_volume, b_volume, wedge) = (1.25, 6.0 + TILT * extra, TILT * wedge);
        let cases = [
            ("union", &a | &b, b_volume + wedge),
            ("intersection", &a & &b, a_volume - wedge),
            ("tilted less unit", &b - &a, b_volume - a_volume + wedge),
            ("unit less tilted", &a - &b, wedge),
        ];
        for (name, result, want) in cases {
            let mesh = result.to_mesh();
            let report = mesh.report();
            assert!(report.is_closed_manifold(), "line {k}, {name}: {report}");
            // The wedge alone may go: it is thinner than the weld.
            let slack = 1e-11 + wedge;
            assert!(
                (mesh.volume() - want).abs() < slack,
                "line {k}, {name}: mesh {} against {want}",
                mesh.volume()
            );
            assert!(
                (result.volume() - want).abs() < slack,
                "line {k}, {name}: the solid's {} against {want}",
                result.volume()
            );
        }
    }
}

/// Round 20's fork input e5d963a7, minimised: a 3-segment prism (a cylinder of radius 0.25)
/// whose face x = −0.4375 is fitted from cosines (3.8·10⁻¹⁶ rad off the axis), ∪ a 0.125 cube
/// turned 1e-6° on that face, ∪ a 0.125 × 0.25 × 0.125 cuboid whose face x = −0.4375 is the
/// prism's twin, ∪ a 1.125 × 0.75 × 0.125 slab through all three.
///
/// The cube's face crosses both twins at 1.7·10⁻⁸ rad, on lines 2·10⁻⁹ apart at its edge. Cut
/// on the prism's face by the first union, its corners there were judged across the line of
/// the cuboid's face by the second: beside it, so the strip between (6.1·10⁻¹¹) stayed, the
/// second union open in +x. The slab's union built its tree on the strip, whose plane read
/// outside across the prism, and kept 1.6·10⁻² of the slab's bottom inside the prism: the
/// solid 3.6·10⁻⁴ above its mesh, which was right. A corner on an edge in the cutting plane's
/// flipped twin is now judged on it (`flipped_twin` in `polygon/side.rs`).
#[test]
fn a_corner_cut_on_a_face_is_on_its_flipped_twin() {
    let at = |solid: Solid| solid.translate(DVec3::splat(-0.5)).unwrap();
    let prism = Solid::cylinder(0.25, 0.5, 3)
        .unwrap()
        .translate(DVec3::new(-0.3125, -0.5, -0.5))
        .unwrap();
    let axis = DVec3::new(
        -0.7028307572563588,
        -0.10980825701606559,
        -0.7028307572563588,
    );
    let turn = DQuat::from_axis_angle(axis, 1e-6f64.to_radians());
    let cube = at(Solid::cube(0.125).unwrap().rotate(turn).unwrap());
    let cuboid = at(Solid::cuboid(DVec3::new(0.125, 0.25, 0.125)).unwrap());
    let slab = at(Solid::cuboid(DVec3::new(1.125, 0.75, 0.125)).unwrap());
    let twins = &(&prism | &cube) | &cuboid;
    let open: DVec3 = twins
        .polygons()
        .iter()
        .map(|p| p.plane().normal() * p.area())
        .sum();
    assert!(open.length() < 1e-15, "the union is open by {open}");
    let result = &twins | &slab;
    let mesh = result.to_mesh();
    let report = mesh.report();
    assert!(report.is_closed_manifold(), "{report}");
    // The same unions with the cube unturned (it lies in the cuboid, which lies in the slab).
    let want = 0.12600910253592848;
    assert!(
        (mesh.volume() - want).abs() < 1e-10,
        "mesh {}",
        mesh.volume()
    );
    assert!(
        (result.volume() - mesh.volume()).abs() < 1e-10,
        "solid {} mesh {}",
        result.volume(),
        mesh.volume()
    );
}

/// Round 20's fork input e11e6f68, minimised: a 0.125 cube ∪ a 0.75 × 0.125 × 0.125 bar beside
/// it turned 10⁻¹⁰° (its bottom 1.4·10⁻¹² rad from the cube's, 5.7·10⁻¹³ above it over the
/// cube, within `eps`), ∪ a 1.125 × 0.125 × 0.125 slab through both turned 10⁻⁸°.
///
/// In the first union's tree the bar's bottom (sine 1.4·10⁻¹² to the cube's plane, above
/// `PARALLEL_BELOW`, so banded, not coplanar) lay behind the cube's bottom; the cube's side
/// faces, whose corners lie within `eps` in front of the bar's plane, went behind it by the
/// tolerance alone (`Class::BackNear`), so its front leaf read the wedge between the two planes
/// as outside, across the cube too. The slab's bottom crosses the two planes on lines 3.7·10⁻³
/// apart (the band `eps / sine` is 8·10⁻³ wide there); the strip of it between them over the
/// cube passed the cube's plane behind and the bar's in front, and was kept beside the cube's
/// own bottom, which the slab's tree cut at the first line (the same on the top): the solid
/// 2.6·10⁻⁵ above its mesh, open by 4.1·10⁻⁴. The cube's bottom now passes its corners down to
/// the side the bar's went to, and the bar's node sends the cube's side faces ending at them to
/// its front too (`Corners` in `bsp/build/face.rs`).
#[test]
fn a_wedge_under_a_face_turned_a_hair_stays_inside_the_face_beside_it() {
    let at = |solid: Solid| solid.translate(DVec3::splat(-0.5)).unwrap();
    let cube = at(Solid::cube(0.125).unwrap());
    let bar = Solid::cuboid(DVec3::new(0.75, 0.125, 0.125))
        .unwrap()
        .rotate(DQuat::from_axis_angle(
            -DVec3::ONE.normalize(),
            1e-10f64.to_radians(),
        ))
        .unwrap()
        .translate(DVec3::new(0.0625, -0.5, -0.5))
        .unwrap();
    let axis = DVec3::new(
        -0.986043261930034,
        -0.14758676060535142,
        0.07705085136711223,
    );
    let slab = at(Solid::cuboid(DVec3::new(1.125, 0.125, 0.125))
        .unwrap()
        .rotate(DQuat::from_axis_angle(axis, 1e-8f64.to_radians()))
        .unwrap());
    let result = &(&cube | &bar) | &slab;
    let open: DVec3 = result
        .polygons()
        .iter()
        .map(|p| p.plane().normal() * p.area())
        .sum();
    let mesh = result.to_mesh();
    let report = mesh.report();
    assert!(report.is_closed_manifold(), "{report}");
    // The slab and the part of the bar beyond it (0.375 long): the turns move it by < 1e-10.
    let want = 1.125 * 0.125 * 0.125 + 0.375 * 0.125 * 0.125;
    assert!(open.length() < 1e-14, "the union is open by {open}");
    assert!(
        (mesh.volume() - want).abs() < 1e-10,
        "mesh {}",
        mesh.volume()
    );
    assert!(
        (result.volume() - want).abs() < 1e-10,
        "solid {} mesh {}",
        result.volume(),
        mesh.volume()
    );
}

/// Round 20's fork input 0a15665e, minimised (its cuboid far above left out): a 0.125 × 0.125
/// × 0.5 OBJ bar turned 1e-2° ∪ a 0.125 × 0.25 × 0.125 OBJ box turned 1e-3° ∪ a 0.125 cube,
/// all about (−0.5, −0.5, −0.5), less a 1 × 1 × 0.125 slab whose top and bottom are the cube's.
/// What is left is the bar's two ends (0.125² × 0.375, 1.5e-8 more by the turns) and the
/// wedges where the box's top and bottom, turned at a sine of 1.4e-5 to the slab's faces, stand
/// out of them.
///
/// Open (6 boundary edges: a lone triangle of 2.9e-17 at the corner (−0.5625, −0.5625,
/// −0.5625) and its twin at (−0.4375, −0.4375, −0.4375)); with the bar or the box made by the
/// crate's cuboid (quads), or without the bar or the cube, it closes. Traced at the bottom
/// corner (the top is the same turned over), the tolerance 3.1e-13:
///
/// - The union keeps a triangle of the box's bottom of 7.3e-17 between the box's −x face, the
///   bar's −y face and the line where the box's bottom crosses the cube's (6.7e-9 … 1.2e-8 on
///   a side): there the box stands out below the cube by up to 1.2e-13, within the tolerance.
///   The box's −x face is cut at the cube's bottom by the tolerance (its part below, 1.2e-13
///   tall, is not kept), so the union's pieces there are the box's triangle beside a piece of
///   the cube's bottom lying exactly in z = −0.5625, sharing an edge 1.2e-13 apart (welded).
/// - The difference keeps that triangle: judged against the slab's bottom by the band of
///   nearly parallel planes (the plane's rounding, 1.6e-14), its corner 1.2e-13 below is
///   outside the slab.
/// - The slab's bottom is clipped by the union's tree. In the cell x < −0.56249997,
///   y < −0.56249999 the node of the box's bottom has behind it a node of the cube's bottom
///   (its only polygon that piece of 2.4e-17 beside the box's −x face), whose front leaf, the
///   layer below z = −0.5625 and above the box's bottom, reads outside: no plane of the box's
///   −x face bounds it. The slab's piece over the box's triangle (the part below y =
///   −0.5624999933, a cell plane) is dropped there; above that cell plane it is kept out to
///   x = −0.5625 instead of the box's −x face. The box's triangle has no cap, and the mesh
///   keeps a lone triangle there.
///
/// The class of [`a_wedge_under_a_face_turned_a_hair_stays_inside_the_face_beside_it`]: the
/// layer between two nearly parallel planes, behind one and in front of a node of the other
/// with a small polygon, reads outside where the solid is inside. The union's mesh read back
/// and cut by the slab is open too (4 boundary edges).
#[test]
#[ignore = "open: two lone triangles of 2.9e-17 at the cube's corners (6 boundary edges): the union's tree reads the layer below the cube's bottom and above the box's bottom, turned 1e-3°, as outside, and drops the slab's face over the box's piece standing 1.2e-13 out"]
fn a_slab_through_a_box_turned_a_hair_caps_the_wedge_under_the_cube() {
    let at = |solid: Solid| solid.translate(DVec3::splat(-0.5)).unwrap();
    let turned = |solid: Solid, axis: DVec3, degrees: f64| {
        at(solid
            .rotate(DQuat::from_axis_angle(axis, degrees.to_radians()))
            .unwrap())
    };
    let bar = turned(
        obj_box(DVec3::new(0.125, 0.125, 0.5)),
        DVec3::new(
            -0.5766095342544187,
            -0.5777202805021225,
            -0.5777202805021225,
        ),
        1e-2,
    );
    let box_ = turned(
        obj_box(DVec3::new(0.125, 0.25, 0.125)),
        DVec3::new(
            -0.5779434611618907,
            -0.5779434611618907,
            -0.5761620530722484,
        ),
        1e-3,
    );
    let cube = at(Solid::cube(0.125).unwrap());
    let slab = at(Solid::cuboid(DVec3::new(1.0, 1.0, 0.125)).unwrap());
    let result = &(&(&bar | &box_) | &cube) - &slab;
    let mesh = result.to_mesh();
    let report = mesh.report();
    assert!(report.is_closed_manifold(), "{report}");
    let want = 0.125 * 0.125 * 0.375;
    assert!(
        (mesh.volume() - result.volume()).abs() < 1e-12,
        "mesh {} solid {}",
        mesh.volume(),
        result.volume()
    );
    assert!((result.volume() - want).abs() < 1e-7, "{}", result.volume());
}
