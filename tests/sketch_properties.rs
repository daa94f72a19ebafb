//! Property tests for sketches: 2D inclusion–exclusion of areas over random rectangles,
//! circles and polygons under random rigid motions, validity of every result, and extrusions
//! (plain, twisted, tapered) and revolutions of the results staying closed with the volume the
//! area predicts. Tolerance: 1e-9 relative to the operands' size.

use std::f64::consts::TAU;

use bspcsg::{ExtrudeOptions, FillRule, Sketch};
use glam::DVec2;
use proptest::prelude::*;

/// A shape from a kind, sizes in 0..1 and a vertex count.
fn shape(kind: u8, s: [f64; 4], n: usize) -> Sketch {
    let size = |t: f64| 0.3 + 1.2 * t;
    match kind % 5 {
        0 => Sketch::rectangle(size(s[0]), size(s[1])).unwrap(),
        1 => Sketch::circle(size(s[0]) * 0.6, 1e-3 * (1.0 + s[1])).unwrap(),
        2 => Sketch::regular_polygon(3 + n as u32 % 9, size(s[0]) * 0.7).unwrap(),
        3 => Sketch::rounded_rectangle(size(s[0]), size(s[1]), 0.1 * s[2], 1e-3).unwrap(),
        // A star-shaped polygon with radii from a simple hash of the sizes.
        _ => {
            let pts: Vec<DVec2> = (0..n)
                .map(|i| {
                    let a = TAU * i as f64 / n as f64;
                    let t = ((i as f64 + 1.0) * (s[0] * 97.0 + s[1] * 13.0 + s[3] * 7.0)).sin();
                    DVec2::from_angle(a) * (0.4 + 0.6 * t.abs()) * size(s[2])
                })
                .collect();
            Sketch::polygon(&pts, FillRule::NonZero).unwrap()
        }
    }
}

prop_compose! {
    fn placed()(kind in 0u8..5, s in prop::array::uniform4(0.0f64..1.0), n in 5usize..40,
                angle in 0.0f64..360.0, offset in prop::array::uniform2(-0.8f64..0.8)) -> Sketch {
        shape(kind, s, n).rotate(angle).unwrap().translate(DVec2::from(offset)).unwrap()
    }
}

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0)
        .max(256)
}

fn valid(s: &Sketch) -> Result<(), TestCaseError> {
    let r = s.report();
    prop_assert!(r.is_valid(), "{:?}\n{:?}", r, s);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn inclusion_exclusion(a in placed(), b in placed()) {
        let (aa, ab) = (a.area(), b.area());
        let u = &a | &b;
        let i = &a & &b;
        let d = &a - &b;
        let e = &b - &a;
        for s in [&u, &i, &d, &e] {
            valid(s)?;
        }
        let tol = 1e-9 * (aa + ab);
        prop_assert!((u.area() + i.area() - aa - ab).abs() <= tol,
            "∪ {} ∩ {} A {} B {}", u.area(), i.area(), aa, ab);
        prop_assert!((d.area() - (aa - i.area())).abs() <= tol, "A−B {}", d.area());
        prop_assert!((u.area() - (d.area() + e.area() + i.area())).abs() <= tol);
        // Commutativity and idempotence.
        prop_assert!(((&b | &a).area() - u.area()).abs() <= tol);
        prop_assert!(((&a | &a).area() - aa).abs() <= tol);
        prop_assert!((&a - &a).is_empty());
    }

    /// Operands with holes and several regions spread wide, so some rings lie far from the
    /// other operand and pass through whole.
    #[test]
    fn inclusion_exclusion_of_compound_operands(
        p in prop::collection::vec(placed(), 6),
        shifts in prop::collection::vec(prop::array::uniform2(-3.0f64..3.0), 6),
    ) {
        let q: Vec<Sketch> = p
            .iter()
            .zip(&shifts)
            .map(|(s, &d)| s.translate(DVec2::from(d)).unwrap())
            .collect();
        let a = &(&q[0] - &p[1].scale(0.5).unwrap().translate(DVec2::from(shifts[0])).unwrap()) | &q[2];
        let b = &(&q[3] | &q[4]) - &p[5].scale(0.4).unwrap().translate(DVec2::from(shifts[4])).unwrap();
        valid(&a)?;
        valid(&b)?;
        let (aa, ab) = (a.area(), b.area());
        let u = &a | &b;
        let i = &a & &b;
        let d = &a - &b;
        for s in [&u, &i, &d] {
            valid(s)?;
        }
        let tol = 1e-9 * (aa + ab).max(1.0);
        prop_assert!((u.area() + i.area() - aa - ab).abs() <= tol,
            "∪ {} ∩ {} A {} B {}", u.area(), i.area(), aa, ab);
        prop_assert!((d.area() - (aa - i.area())).abs() <= tol, "A−B {}", d.area());
    }

    #[test]
    fn extrusions_close(a in placed(), b in placed(), h in 0.2f64..3.0, twist in -180.0f64..180.0,
                        top in 0.0f64..1.5) {
        let s = &a - &b;
        prop_assume!(!s.is_empty());
        let prism = s.extrude(h).unwrap();
        let report = prism.to_mesh().report();
        prop_assert!(report.is_closed_manifold(), "{}", report);
        prop_assert!((prism.volume() - s.area() * h).abs() <= 1e-9 * s.area() * h,
            "{} vs {}", prism.volume(), s.area() * h);
        // A tapered prism is a frustum: h/3 (A + s A + s² A) for a top scaled by s.
        let tapered = s.extrude_with(h, &ExtrudeOptions {
            scale_top: DVec2::splat(top), ..Default::default()
        }).unwrap();
        let report = tapered.to_mesh().report();
        prop_assert!(report.is_closed_manifold(), "{}", report);
        let want = h / 3.0 * s.area() * (1.0 + top + top * top);
        prop_assert!((tapered.volume() - want).abs() <= 1e-9 * want.max(1e-3));
        // Twisted: closed, and the volume within the slicing's second-order error.
        let twisted = s.extrude_with(h, &ExtrudeOptions {
            twist, ..Default::default()
        }).unwrap();
        let report = twisted.to_mesh().report();
        prop_assert!(report.is_closed_manifold(), "{}", report);
        prop_assert!(twisted.volume() <= s.area() * h * (1.0 + 1e-9));
        prop_assert!(twisted.volume() >= s.area() * h * 0.95, "{}", twisted.volume());
    }

    #[test]
    fn revolutions_close(a in placed(), angle in 10.0f64..360.0) {
        // The part right of the axis, by intersection with a half-plane box.
        let half = &a & &Sketch::rectangle(4.0, 4.0).unwrap().translate(DVec2::new(2.0, 0.0)).unwrap();
        prop_assume!(!half.is_empty());
        valid(&half)?;
        let solid = half.revolve(angle, 48).unwrap();
        let report = solid.to_mesh().report();
        prop_assert!(report.is_closed_manifold(), "{}", report);
        prop_assert!(solid.volume() > 0.0);
    }
}
