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

/// (a ∩ b) ∩ c was 1318 triangles, 33 shells, 606 boundary edges, the mesh's volume 1.1931
/// against the solid's 1.28184136 (itself 1.3e-7 below the sphere's 1.28184149, so the clip's
/// polygons did not close). It failed alike with the turns at 1e-10° … 1e-7°, closed at 1e-11°
/// (the turned planes the unturned ones to rounding) and at 1e-5°.
///
/// Traced to the clip: each pair closes, and (a ∩ b)'s mesh read back closes against c
/// ([`two_spheres_turned_a_hair_intersect_closed`]); what failed is c cutting the *fragments*
/// a ∩ b leaves, each facet split into pieces of a's plane and pieces of b's. Summed per facet
/// of c, the polygons of (a ∩ b) ∩ c missed or doubled over 1e-9 (up to 2.3e-7) on 102 of the
/// 135 facets. The three planes of a facet cross at sines near 1.5e-11, and where they meet
/// (facet 71: inside it) a's pieces are cut along the line a ∩ c from that meet, c's along
/// the same line from the same meet, each to its own fragments' corners on the line. In doubles
/// each line of two such planes lay a rounding error over the sine across the face (ε · 0.3 /
/// 1.5e-11 ≈ 5e-6), and the meet of the three, computed on the line a ∩ b, lay about 5e-6 off
/// the line a ∩ c: the two cuts from it to corners 0.08 away on the line parted by 1.1e-6,
/// a sliver of 4.6e-8 no weld closes. Where all three planes cross below `NEAR_PARALLEL`, the
/// meet is now solved from the three planes as stored, in double-double, and rounded once
/// (`meet` in `polygon/planes.rs`); the lines' own points, still in doubles, lie within the
/// rounding `Crossing::side` allows them, and the intersection closes with its volume the
/// sphere's to 1e-11.
#[test]
fn three_spheres_turned_a_hair_about_different_axes_intersect_closed() {
    let [a, b, c] = spheres();
    assert_closed_sphere(&(&(&a & &b) & &c), "(a ∩ b) ∩ c");
}

/// (a ∪ b) ∪ c was 292 triangles, 4 shells, not closed, the mesh's volume 1.27926 against the
/// solid's 1.28234 (the sphere's 1.28184149). Summed per facet of c as for the intersection
/// above, three facets were off (15: +3.0e-6, 16: +2.2e-3, 113: +9.4e-8): pieces of c kept
/// inside a, beside a's own piece. On facet 16, a ∪ b had kept, within the tolerance, a strip
/// of b's facet along its edge to facet 17, reaching 4e-13 in front of a's facet 17 and
/// 8.9e-13 behind it, under a's facet 16 (the two facet-16 planes crossing at 8.8e-12 rad).
/// Clipping c against a ∪ b, the strip, coplanar with a's facet 17 by the tolerance and sent
/// behind it by its reach, made a node of b's plane behind a's facets 16 and 17 whose front
/// leaf read the whole layer between b's plane and a's outside, c's facet lying in it. It now
/// goes where b's facet 17, nearly parallel to a's, went (`Wedge::side_of` in
/// `bsp/build/face.rs`); facets 15 and 16 sum right, and the volumes are the sphere's to
/// 2e-8 (facet 113 below).
#[test]
fn three_spheres_turned_a_hair_about_different_axes_unite_to_the_spheres_volume() {
    let [a, b, c] = spheres();
    let union = &(&a | &b) | &c;
    let expected = sphere(DVec3::Z, 0.0).volume();
    for (what, v) in [
        ("solid", union.volume()),
        ("mesh", union.to_mesh().volume()),
    ] {
        let off = (v - expected).abs() / expected;
        assert!(off < 1e-7, "{what}: volume {v} against {expected}");
    }
}

/// (a ∪ b) ∪ c: 267 triangles, 2 shells, not closed, the solid's and the mesh's volumes
/// 1.2818415137 (2.1e-8 above the sphere's). What is left is facet 113: a piece of c of
/// 9.4e-8 at a's corner with facets 114 and 128 (all three a's planes meet there), kept inside
/// a. a ∪ b had kept a triangle of b's facet 113 there of area 2.5e-24, its corners within a
/// few tolerances of each other, reaching 3.5e-13 behind a's facet 128 (within the tolerance,
/// that side only): sent behind it as a sliver, it made a node of b's plane behind a's facets 113,
/// 114 and 128 whose front leaf reads the layer between b's plane and a's (1e-12 apart) outside,
/// and c's piece lies in that layer. Keeping such a point-like polygon at the node alone
/// (corners within 4 tolerances of one) closes this union, but round 20's fork input c095e8fc
/// then loses 1.6e-4 of its solid's volume (its point-like sliver within one tolerance is
/// needed on its side), so that is not the rule.
#[test]
#[ignore = "open: near-coplanar — three copies of a sphere, two turned 1e-9° about different axes, unite to 2 shells, not closed, the volume 2.1e-8 high (a point-like piece of b at a's corner, facet 113; the intersection closes)"]
fn three_spheres_turned_a_hair_about_different_axes_unite_closed() {
    let [a, b, c] = spheres();
    assert_closed_sphere(&(&(&a | &b) | &c), "(a ∪ b) ∪ c");
}

/// Round 20's fork input ed3471fb, as it runs: a cylinder (radius 0.6875, 1.375 long, 15
/// segments, about (−0.5, −0.5, −0.3125)) ∪ the sphere turned 1e-9° about −(1, 1, 1), ∩ the
/// sphere turned 1e-9° about (−0.88, −0.19, −0.43), ∩ the sphere turned 1e-9° about (0.33,
/// −0.67, −0.67). The mesh closes with the sphere's volume, but the solid's is 1.28089380,
/// 9.5e-4 short: on one facet (normal (0.756, −0.634, 0.161)) its polygons sum to 0.046742
/// against the facet's 0.051032, a hole of 4.3e-3 the repair's fill closes. The three spheres
/// without the cylinder, the same four in another order (the third sphere before the second,
/// or the last two intersected first), and the first two steps' mesh read back ∩ the third
/// sphere all come out right.
///
/// Traced: (cylinder ∪ a) ∩ b keeps on that facet six pieces of b's and one triangle of a's,
/// 8.5e-8, at the facet's corner near (0.151, −0.742, −0.141), where a stands inside b and the
/// cylinder does not reach. Clipping c by that solid's tree, behind the node of b's facet is a
/// node of a's plane whose only polygon is that triangle; its front leaf, the layer behind b's
/// plane and in front of a's (the planes crossing at about 1e-11 rad, the layer under 1e-12
/// thick across the facet), reads outside. c's facet, behind b's plane there (inside) but in
/// front of a's, is dropped in that layer across the facet, far from the triangle, while b's
/// pieces in front of c's plane are dropped by c's tree: neither covers it. The class of the
/// union's facet 113 above and of `near_coplanar_corners.rs`'s wedges: a node of a small
/// polygon in a plane nearly parallel to its parent's reads the whole layer between them.
#[test]
#[ignore = "open: near-coplanar — the solid's polygons 9.5e-4 short of the sphere (a hole of 4.3e-3 on one facet): a node of a's plane holding a triangle of 8.5e-8 reads the layer behind b's plane outside"]
fn a_cylinder_united_with_a_sphere_then_cut_by_two_turned_copies_keeps_every_facet() {
    let cylinder = Solid::cylinder(0.6875, 1.375, 15)
        .unwrap()
        .translate(DVec3::new(-0.5, -0.5, -0.3125))
        .unwrap();
    let a = sphere(DVec3::splat(-0.5773502691896257), 1e-9);
    let b = sphere(
        DVec3::new(
            -0.8808783146297698,
            -0.19437896817705494,
            -0.43159032837337735,
        ),
        1e-9,
    );
    let c = sphere(
        DVec3::new(0.3266061076740213, -0.6683294286615044, -0.6683294286615044),
        1e-9,
    );
    let result = &(&(&cylinder | &a) & &b) & &c;
    assert_closed_sphere(&result, "((cylinder ∪ a) ∩ b) ∩ c");
    let expected = sphere(DVec3::Z, 0.0).volume();
    let off = (result.volume() - expected).abs() / expected;
    assert!(off < 1e-9, "the solid's volume {}", result.volume());
}
