//! Three copies of one 15 × 9 sphere, two of them turned 1e-9° about different axes, combined:
//! every face of the result is a patchwork of three planes within about 1e-11 of each other.
//! Minimised from the round-20 fork run's 1886ef4e (a cylinder intersected with three such
//! spheres) and ed3471fb (a cylinder united with one, intersected with two more).

use bspcsg::Solid;
use bspcsg::glam::{DQuat, DVec3};

/// The sphere of radius 0.6875 (15 segments, 9 rings) about (−0.375, −0.375, −0.375), turned
/// `degrees` about the unit vector `axis` first.
fn sphere(axis: DVec3, degrees: f64) -> Solid {
    let s = Solid::sphere(0.6875, 15, 9).unwrap();
    let s = if degrees == 0.0 {
        s
    } else {
        s.rotate(DQuat::from_axis_angle(axis, degrees.to_radians()))
            .unwrap()
    };
    s.translate(DVec3::splat(-0.375)).unwrap()
}

/// The three spheres of 1886ef4e: about −(1, 1, 1) and about −(0.43, 0.88, 0.19) turned 1e-9°,
/// and the third unturned.
fn spheres() -> [Solid; 3] {
    [
        sphere(DVec3::splat(-0.5773502691896257), 1e-9),
        sphere(
            DVec3::new(
                -0.4315903283733774,
                -0.8808783146297698,
                -0.19437896817705494,
            ),
            1e-9,
        ),
        sphere(DVec3::Z, 0.0),
    ]
}

/// Closed, and the mesh's volume the unturned sphere's to 1e-9 (the turns move its faces by
/// under 2e-11).
fn assert_closed_sphere(s: &Solid, what: &str) {
    let expected = sphere(DVec3::Z, 0.0).volume();
    let mesh = s.to_mesh();
    let report = mesh.report();
    assert!(report.is_closed_manifold(), "{what}: {report}");
    let off = (mesh.volume() - expected).abs() / expected;
    assert!(
        off < 1e-9,
        "{what}: mesh volume {} against {expected}",
        mesh.volume()
    );
}

/// Any two of the three intersect to a closed sphere: the case below needs all three.
#[test]
fn two_spheres_turned_a_hair_intersect_closed() {
    let [a, b, c] = spheres();
    assert_closed_sphere(&(&a & &b), "a ∩ b");
    assert_closed_sphere(&(&a & &c), "a ∩ c");
    assert_closed_sphere(&(&b & &c), "b ∩ c");
    // The first intersection's mesh read back and cut by the third: closed too.
    let ab = Solid::from_mesh(&(&a & &b).to_mesh()).unwrap();
    assert_closed_sphere(&(&ab & &c), "mesh(a ∩ b) ∩ c");
}

/// (a ∩ b) ∩ c: 1318 triangles, 33 shells, 606 boundary edges, mesh volume 1.1931 against the
/// solid's 1.28184136 (itself 1.3e-7 below the sphere's 1.28184149, so the clip's polygons
/// already do not close). Fails alike with the turns at 1e-10° … 1e-7° (at 1e-10° the solid is
/// 1.8e-3 off; (a ∪ b) ∪ c at 1e-9° is 4e-4 off), closes at 1e-11° (the turned planes are
/// the unturned ones to rounding) and at 1e-5°; with the axes rounded to four digits it fails
/// too (603 and 574 boundary edges).
///
/// Traced to the clip: each pair closes, and (a ∩ b)'s mesh read back closes against c
/// ([`two_spheres_turned_a_hair_intersect_closed`]); what fails is c cutting the *fragments*
/// a ∩ b leaves, each facet split into pieces of a's plane and pieces of b's. Summed per facet
/// of c, the polygons of a ∩ b cover each facet to 1e-12 of its area; those of (a ∩ b) ∩ c
/// miss or double over 1e-9 (up to 2.3e-7) on 102 of the 135 facets (facet 71: 11 pieces of
/// three planes, 1.6e-7 short), against the 1e-12 that gaps 1e-11 thick could explain. The
/// planes cross at sines near 1.5e-11, inside the band between `PARALLEL_BELOW` (5e-13) and
/// `NEAR_PARALLEL`, where their crossing line is known only to a rounding error over the sine
/// (1e-16 / 1.5e-11, ~1e-5 across the facet) and each fragment judges its corners against it
/// alone (the limit `PARALLEL_BELOW`'s doc in `polygon/side.rs` describes for one cut face):
/// a's pieces cut by c and c's pieces cut by a and by b end up to ~1e-5 apart along the facet,
/// leaving gaps and overlaps of ~1e-7 no weld closes. The repair then loses whole regions.
#[test]
#[ignore = "open: near-coplanar — three copies of a sphere, two turned 1e-9° about different axes, intersect to a mesh with 606 boundary edges and 7 % of the volume lost (any two close)"]
fn three_spheres_turned_a_hair_about_different_axes_intersect_closed() {
    let [a, b, c] = spheres();
    assert_closed_sphere(&(&(&a & &b) & &c), "(a ∩ b) ∩ c");
}
