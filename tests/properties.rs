//! Property tests: volume identities of booleans over random primitives under random rigid
//! motions. Tolerance: 1e-9 relative to the larger operand.

use bspcsg::Solid;
use glam::{DQuat, DVec3};
use proptest::prelude::*;

/// A primitive from a kind and three size parameters in 0..1.
fn primitive(kind: u8, s: [f64; 3], segments: u32) -> Solid {
    let size = |t: f64| 0.3 + 1.2 * t;
    match kind % 4 {
        0 => Solid::cuboid(DVec3::new(size(s[0]), size(s[1]), size(s[2]))),
        1 => Solid::sphere(size(s[0]) * 0.7, segments, segments / 2 + 2),
        2 => Solid::cylinder(size(s[0]) * 0.6, size(s[1]), segments),
        _ => Solid::frustum(
            size(s[0]) * 0.6,
            size(s[2]) * 0.3 * s[1],
            size(s[1]),
            segments,
        ),
    }
    .unwrap()
}

fn rigid(solid: Solid, axis: [f64; 3], angle: f64, offset: [f64; 3]) -> Solid {
    let axis = DVec3::from(axis).try_normalize().unwrap_or(DVec3::Y);
    solid
        .rotate(DQuat::from_axis_angle(axis, angle))
        .unwrap()
        .translate(DVec3::from(offset))
        .unwrap()
}

prop_compose! {
    fn placed()(kind in 0u8..4, s in prop::array::uniform3(0.0f64..1.0), segments in 5u32..20,
                axis in prop::array::uniform3(-1.0f64..1.0), angle in 0.0f64..6.3,
                offset in prop::array::uniform3(-0.8f64..0.8)) -> Solid {
        rigid(primitive(kind, s, segments), axis, angle, offset)
    }
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * scale
}

/// 256 cases, or more where `PROPTEST_CASES` asks for them (a deeper run by hand).
fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0)
        .max(256)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn inclusion_exclusion(a in placed(), b in placed()) {
        let (va, vb) = (a.volume(), b.volume());
        let scale = va.max(vb);
        let (u, i, d) = (&a | &b, &a & &b, &a - &b);
        for (name, solid) in [("union", &u), ("intersection", &i), ("difference", &d)] {
            let report = solid.to_mesh().report();
            prop_assert!(report.is_closed_manifold(), "{name}: {report}");
        }
        let (union, inter, diff) = (u.volume(), i.volume(), d.volume());
        prop_assert!(close(union + inter, va + vb, scale),
            "V(A∪B) + V(A∩B) = {} but V(A) + V(B) = {}", union + inter, va + vb);
        prop_assert!(close(diff, va - inter, scale),
            "V(A−B) = {diff} but V(A) − V(A∩B) = {}", va - inter);
        prop_assert!(inter >= -1e-9 * scale && inter <= va.min(vb) * (1.0 + 1e-9));
    }

    #[test]
    fn volume_invariant_under_rigid_motion(a in placed(), b in placed(),
            axis in prop::array::uniform3(-1.0f64..1.0), angle in 0.0f64..6.3,
            offset in prop::array::uniform3(-5.0f64..5.0)) {
        let before = (&a - &b).volume();
        let move_ = |s: &Solid| rigid(s.clone(), axis, angle, offset);
        let moved = &move_(&a) - &move_(&b);
        let after = moved.volume();
        prop_assert!(close(before, after, a.volume().max(b.volume())),
            "before {before}, after {after}");
        let report = moved.to_mesh().report();
        prop_assert!(report.is_closed_manifold(), "{report}");
    }

    #[test]
    fn self_operations_are_identities(a in placed()) {
        let v = a.volume();
        for solid in [&a | &a, &a & &a] {
            let report = solid.to_mesh().report();
            prop_assert!(report.is_closed_manifold(), "{report}");
        }
        prop_assert!((&a - &a).volume().abs() <= 1e-9 * v);
        prop_assert!(close((&a | &a).volume(), v, v));
        prop_assert!(close((&a & &a).volume(), v, v));
    }
}

/// The same configuration at scale 1e-6, 1 and 1e6 gives the same volumes, scaled.
#[test]
fn same_answer_at_every_scale() {
    let build = |k: f64| {
        let a = Solid::sphere(k, 32, 16).unwrap();
        let b = Solid::cuboid(DVec3::splat(1.2 * k))
            .unwrap()
            .rotate_euler(DVec3::new(10.0, 20.0, 30.0))
            .unwrap()
            .translate(DVec3::new(0.5 * k, 0.25 * k, 0.0))
            .unwrap();
        [(&a | &b), (&a & &b), (&a - &b)].map(|s| {
            let report = s.to_mesh().report();
            assert!(report.is_closed_manifold(), "scale {k}: {report}");
            (s.volume() / (k * k * k), s.area() / (k * k))
        })
    };
    let unit = build(1.0);
    for k in [1e-6, 1e6] {
        let scaled = build(k);
        for (u, s) in unit.iter().zip(&scaled) {
            assert!(
                (u.0 - s.0).abs() <= 1e-12 * u.0,
                "scale {k}: {} vs {}",
                s.0,
                u.0
            );
            assert!(
                (u.1 - s.1).abs() <= 1e-12 * u.1,
                "scale {k}: area {} vs {}",
                s.1,
                u.1
            );
        }
    }
}

/// Scale, mirror and shear keep the solid outward-facing with the right volume.
#[test]
fn affine_maps_scale_volume_by_determinant() {
    let a = Solid::sphere(1.0, 24, 12).unwrap();
    let v = a.volume();
    let mirrored = a.clone().scale_xyz(DVec3::new(-1.0, 2.0, 0.5)).unwrap();
    assert!((mirrored.volume() - v).abs() < 1e-12 * v);
    let m = glam::DAffine3::from_cols_array(&[
        1.0, 0.0, 0.0, 0.7, 1.0, 0.0, 0.0, 0.0, 3.0, 1.0, 2.0, 3.0,
    ]);
    let sheared = a.clone().transform(m).unwrap();
    assert!((sheared.volume() - 3.0 * v).abs() < 1e-12 * v);
    assert!(a.clone().scale(0.0).is_err());
    assert!(a.translate(DVec3::new(f64::NAN, 0.0, 0.0)).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases() / 4))]

    /// A program of booleans, each on the previous result and a new placed primitive, as
    /// manifold's fuzzer runs programs of cube transforms: results fed back in carry their
    /// tolerance and their T-junctions. Every step keeps inclusion–exclusion and a clean mesh.
    #[test]
    fn chained_booleans_stay_closed(first in placed(),
                                    steps in prop::collection::vec((0u8..3, placed()), 1..8)) {
        let mut acc = first;
        for (k, (op, p)) in steps.into_iter().enumerate() {
            let (va, vp) = (acc.volume(), p.volume());
            let inter = (&acc & &p).volume();
            let next = match op {
                0 => &acc | &p,
                1 => &acc & &p,
                _ => &acc - &p,
            };
            let expect = match op {
                0 => va + vp - inter,
                1 => inter,
                _ => va - inter,
            };
            prop_assert!(close(next.volume(), expect, va.max(vp)),
                "step {k}: volume {} but expected {expect}", next.volume());
            let report = next.to_mesh().report();
            prop_assert!(report.is_closed_manifold(), "step {k}: {report}");
            acc = next;
        }
    }
}
