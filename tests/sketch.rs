//! 2D sketches: booleans by knives, constructors, transforms, and the solids they sweep.
//! Analytic figures from the closed forms; every result's validity report must be clean.

use std::f64::consts::{PI, TAU};

use bspcsg::{BoolOp, Containment, ExtrudeOptions, FillRule, Sketch, Solid};
use glam::DVec2;

fn valid(s: &Sketch) {
    let r = s.report();
    assert!(r.is_valid(), "{r:?}\n{s:?}");
}

fn closed(solid: &Solid) -> bspcsg::MeshReport {
    let report = solid.to_mesh().report();
    assert!(report.is_closed_manifold(), "{report}");
    report
}

/// The area of a regular n-gon inscribed in a circle of radius r.
fn ngon_area(n: u32, r: f64) -> f64 {
    0.5 * n as f64 * r * r * (TAU / n as f64).sin()
}

fn square_at(x: f64, y: f64, side: f64) -> Sketch {
    Sketch::rectangle(side, side)
        .unwrap()
        .translate(DVec2::new(x, y))
        .unwrap()
}

#[test]
fn rectangle_minus_centred_circle() {
    let rect = Sketch::rectangle(2.0, 1.0).unwrap();
    let n = bspcsg::segments_for_tolerance(0.25, 1e-4).unwrap();
    let circle = Sketch::circle(0.25, 1e-4).unwrap();
    assert!((circle.area() - ngon_area(n, 0.25)).abs() < 1e-15);
    let part = &rect - &circle;
    valid(&part);
    assert_eq!(part.regions().len(), 1);
    assert_eq!(part.regions()[0].holes().len(), 1);
    assert_eq!(part.vertex_count(), 4 + n as usize);
    assert!(
        (part.area() - (2.0 - ngon_area(n, 0.25))).abs() < 1e-14,
        "{}",
        part.area()
    );
    // And the circle is within its chordal tolerance of the true one.
    assert!((part.area() - (2.0 - PI * 0.0625)).abs() < 2.0 * PI * 0.25 * 1e-4);
    assert_eq!(part.contains(DVec2::ZERO), Containment::Outside);
    assert_eq!(part.contains(DVec2::new(0.8, 0.0)), Containment::Inside);
    assert_eq!(part.contains(DVec2::new(1.0, 0.0)), Containment::OnBoundary);
}

#[test]
fn union_of_squares_overlapping_by_half() {
    let a = square_at(0.0, 0.0, 1.0);
    let b = square_at(0.5, 0.0, 1.0);
    let u = &a | &b;
    valid(&u);
    assert_eq!(u.regions().len(), 1);
    assert_eq!(u.vertex_count(), 4, "collinear runs merged: {u:?}");
    assert!((u.area() - 1.5).abs() < 1e-15);
    assert!((u.perimeter() - 5.0).abs() < 1e-15);
    let i = &a & &b;
    valid(&i);
    assert!((i.area() - 0.5).abs() < 1e-15);
    let d = &a - &b;
    valid(&d);
    assert!((d.area() - 0.5).abs() < 1e-15);
    assert_eq!(
        u.bounds(),
        Some([DVec2::new(-0.5, -0.5), DVec2::new(1.0, 0.5)])
    );
}

#[test]
fn square_minus_four_corner_squares() {
    let big = Sketch::rectangle(4.0, 4.0).unwrap();
    let corners: Vec<Sketch> = [(-2.0, -2.0), (2.0, -2.0), (2.0, 2.0), (-2.0, 2.0)]
        .into_iter()
        .map(|(x, y)| square_at(x, y, 1.0))
        .collect();
    let cut = &big - &Sketch::union_all(corners.clone());
    valid(&cut);
    assert!((cut.area() - (16.0 - 4.0 * 0.25)).abs() < 1e-14);
    assert_eq!(cut.vertex_count(), 12, "a plus-shaped cross: {cut:?}");
    // One at a time gives the same.
    let mut step = big.clone();
    for c in &corners {
        step = &step - c;
        valid(&step);
    }
    assert!((step.area() - cut.area()).abs() < 1e-14);
}

#[test]
fn touching_squares_share_an_edge_or_a_corner() {
    let a = square_at(0.0, 0.0, 1.0);
    let side = &a | &square_at(1.0, 0.0, 1.0);
    valid(&side);
    assert_eq!((side.regions().len(), side.vertex_count()), (1, 4));
    assert!((side.area() - 2.0).abs() < 1e-15);
    let corner = &a | &square_at(1.0, 1.0, 1.0);
    valid(&corner);
    assert_eq!(corner.regions().len(), 2);
    assert!((&a & &square_at(1.0, 0.0, 1.0)).is_empty());
    assert!((&a - &a).is_empty());
    let aa = &a | &a;
    valid(&aa);
    assert!((aa.area() - 1.0).abs() < 1e-15);
}

#[test]
fn hole_and_island() {
    let ring = &Sketch::rectangle(4.0, 4.0).unwrap() - &Sketch::rectangle(2.0, 2.0).unwrap();
    let island = Sketch::rectangle(1.0, 1.0).unwrap();
    let both = &ring | &island;
    valid(&both);
    assert_eq!(both.regions().len(), 2);
    assert!((both.area() - 13.0).abs() < 1e-14);
    assert_eq!(both.contains(DVec2::new(0.75, 0.0)), Containment::Outside);
}

#[test]
fn constructors() {
    let rr = Sketch::rounded_rectangle(2.0, 1.0, 0.25, 1e-3).unwrap();
    valid(&rr);
    let quarter = bspcsg::segments_for_tolerance(0.25, 1e-3)
        .unwrap()
        .div_ceil(4);
    let exact = 2.0 - 0.25 * 0.25 * 4.0 + ngon_area(4 * quarter, 0.25);
    assert!(
        (rr.area() - exact).abs() < 1e-14,
        "{} vs {exact}",
        rr.area()
    );
    let hex = Sketch::regular_polygon(6, 1.0).unwrap();
    valid(&hex);
    assert!((hex.area() - ngon_area(6, 1.0)).abs() < 1e-15);
    let round = Sketch::rounded_rectangle(1.0, 1.0, 0.5, 1e-3).unwrap();
    valid(&round);
    assert!(Sketch::rectangle(0.0, 1.0).is_err());
    assert!(Sketch::circle(1.0, 0.0).is_err());
    assert!(Sketch::rounded_rectangle(1.0, 1.0, 0.6, 1e-3).is_err());
    assert!(Sketch::polygon(&[DVec2::ZERO, DVec2::X, DVec2::NAN], FillRule::NonZero).is_err());
}

#[test]
fn fill_rules() {
    // A pentagram: the centre pentagon winds twice.
    let star: Vec<DVec2> = (0..5)
        .map(|k| {
            let a = TAU * (2 * k) as f64 / 5.0 + PI / 2.0;
            DVec2::new(a.cos(), a.sin())
        })
        .collect();
    let nz = Sketch::polygon(&star, FillRule::NonZero).unwrap();
    let eo = Sketch::polygon(&star, FillRule::EvenOdd).unwrap();
    valid(&nz);
    valid(&eo);
    assert_eq!(nz.regions().len(), 1);
    assert_eq!(nz.vertex_count(), 10);
    assert_eq!(eo.regions().len(), 5);
    // The inner pentagon's circumradius for a unit pentagram.
    let inner_r = (0.3 * PI).cos() / (0.2 * PI).cos() * (0.1 * PI).cos() / (0.3 * PI).cos()
        * (0.1 * PI).sin()
        / (0.1 * PI).cos()
        * (0.2 * PI).cos()
        / (0.3 * PI).sin()
        * (0.3 * PI).sin();
    let _ = inner_r;
    let inner = ngon_area(5, (0.1 * PI).sin() / (0.3 * PI).sin());
    assert!(
        (nz.area() - eo.area() - inner).abs() < 1e-12,
        "{} {} {inner}",
        nz.area(),
        eo.area()
    );
    // Clockwise input is re-wound; a figure eight has two lobes of opposite winding.
    let cw: Vec<DVec2> = [(0.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, 0.0)]
        .map(|(x, y)| DVec2::new(x, y))
        .to_vec();
    let s = Sketch::polygon(&cw, FillRule::NonZero).unwrap();
    valid(&s);
    assert!((s.area() - 1.0).abs() < 1e-15);
    let eight: Vec<DVec2> = [(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)]
        .map(|(x, y)| DVec2::new(x, y))
        .to_vec();
    let e = Sketch::polygon(&eight, FillRule::NonZero).unwrap();
    valid(&e);
    assert_eq!(e.regions().len(), 2);
    assert!((e.area() - 0.5).abs() < 1e-15);
    // Two overlapping squares given as rings: non-zero unites, even-odd leaves the overlap out.
    let rings: Vec<Vec<DVec2>> = [square_at(0.0, 0.0, 1.0), square_at(0.5, 0.0, 1.0)]
        .iter()
        .map(|s| s.regions()[0].outer().to_vec())
        .collect();
    let u = Sketch::from_rings(&rings, FillRule::NonZero).unwrap();
    let x = Sketch::from_rings(&rings, FillRule::EvenOdd).unwrap();
    valid(&u);
    valid(&x);
    assert!((u.area() - 1.5).abs() < 1e-15);
    assert!((x.area() - 1.0).abs() < 1e-15);
}

#[test]
fn transforms() {
    let s = &square_at(0.0, 0.0, 1.0) - &Sketch::circle(0.3, 1e-3).unwrap();
    let area = s.area();
    let moved = s
        .rotate(37.0)
        .unwrap()
        .translate(DVec2::new(3.0, -2.0))
        .unwrap();
    valid(&moved);
    assert!((moved.area() - area).abs() < 1e-13);
    let mirrored = s.scale_xy(DVec2::new(-2.0, 1.0)).unwrap();
    valid(&mirrored);
    assert!((mirrored.area() - 2.0 * area).abs() < 1e-13);
    let m = s.mirror(DVec2::new(1.0, 1.0)).unwrap();
    valid(&m);
    assert!((m.area() - area).abs() < 1e-13);
    assert!(s.scale(0.0).is_err());
    assert!(s.rotate(f64::NAN).is_err());
}

#[test]
fn boolean_matches_operators() {
    let a = Sketch::circle(1.0, 1e-3).unwrap();
    let b = square_at(0.7, 0.3, 1.2);
    for (op, r) in [
        (BoolOp::Union, &a | &b),
        (BoolOp::Intersection, &a & &b),
        (BoolOp::Difference, &a - &b),
    ] {
        assert_eq!(a.boolean(&b, op), r);
        valid(&r);
    }
    let inc_exc = (&a | &b).area() + (&a & &b).area() - a.area() - b.area();
    assert!(inc_exc.abs() < 1e-12, "{inc_exc}");
}

// ---- solids ----

#[test]
fn revolve_tube_full_turn() {
    let profile = Sketch::rectangle(1.0, 2.0)
        .unwrap()
        .translate(DVec2::new(1.5, 0.0))
        .unwrap();
    let tol = 1e-4;
    let n = bspcsg::segments_for_tolerance(2.0, tol).unwrap();
    let tube = profile.revolve(360.0, n).unwrap();
    let report = closed(&tube);
    assert_eq!(report.genus, Some(1));
    let exact = 6.0 * PI;
    // Inscribed polygons: the volume of the revolved n-gon annulus, and 6π within the
    // chordal tolerance times the outer wall's area.
    let polygonal = (ngon_area(n, 2.0) - ngon_area(n, 1.0)) * 2.0;
    assert!(
        (tube.volume() - polygonal).abs() < 1e-11,
        "{}",
        tube.volume()
    );
    assert!(
        (tube.volume() - exact).abs() < tol * 2.0 * TAU * 2.0,
        "{}",
        tube.volume()
    );
}

#[test]
fn revolve_quarter_turn() {
    let profile = Sketch::rectangle(1.0, 2.0)
        .unwrap()
        .translate(DVec2::new(1.5, 0.0))
        .unwrap();
    let full = profile.revolve(360.0, 256).unwrap();
    let quarter = profile.revolve(90.0, 256).unwrap();
    let report = closed(&quarter);
    assert_eq!(report.genus, Some(0));
    assert!((quarter.volume() - full.volume() / 4.0).abs() < 1e-12);
    // Partial turns of any angle stay closed.
    for angle in [1.0, 45.0, 179.0, 180.0, 270.0, 359.0] {
        let s = profile.revolve(angle, 64).unwrap();
        closed(&s);
        assert!(s.volume() > 0.0);
    }
}

#[test]
fn revolve_profile_touching_the_axis() {
    // A half disc against the axis makes a sphere; a rectangle against it a cylinder.
    let disc = Sketch::circle(1.0, 1e-3).unwrap();
    let half = &disc & &square_at(1.0, 0.0, 2.0);
    valid(&half);
    let ball = half.revolve(360.0, 256).unwrap();
    let r = closed(&ball);
    assert_eq!(r.genus, Some(0));
    assert!((ball.volume() - 4.0 / 3.0 * PI).abs() < 0.01);
    let cyl = square_at(0.5, 0.0, 1.0).revolve(360.0, 64).unwrap();
    closed(&cyl);
    assert!((cyl.volume() - ngon_area(64, 1.0)).abs() < 1e-12);
    let wedge = square_at(0.5, 0.0, 1.0).revolve(90.0, 64).unwrap();
    closed(&wedge);
    assert!(square_at(0.0, 0.0, 1.0).revolve(360.0, 64).is_err());
}

#[test]
fn extrude_plain_and_with_holes() {
    let part = &Sketch::rectangle(2.0, 1.0).unwrap() - &Sketch::circle(0.25, 1e-3).unwrap();
    let prism = part.extrude(3.0).unwrap();
    let r = closed(&prism);
    assert_eq!(r.genus, Some(1));
    assert!((prism.volume() - part.area() * 3.0).abs() < 1e-12);
    let centred = part
        .extrude_with(
            3.0,
            &ExtrudeOptions {
                center: true,
                ..Default::default()
            },
        )
        .unwrap();
    let b = centred.bbox();
    assert!((b.min.z + 1.5).abs() < 1e-15 && (b.max.z - 1.5).abs() < 1e-15);
}

#[test]
fn extrude_to_a_point() {
    let square = Sketch::rectangle(1.0, 1.0).unwrap();
    for h in [0.5, 1.0, 3.0] {
        let pyramid = square
            .extrude_with(
                h,
                &ExtrudeOptions {
                    scale_top: DVec2::ZERO,
                    ..Default::default()
                },
            )
            .unwrap();
        closed(&pyramid);
        assert!(
            (pyramid.volume() - h / 3.0).abs() < 1e-14,
            "{}",
            pyramid.volume()
        );
    }
    // A frustum: h/3 (A + √(A·A') + A') with A' = s²A.
    let s = 0.5;
    let frustum = square
        .extrude_with(
            2.0,
            &ExtrudeOptions {
                scale_top: DVec2::splat(s),
                ..Default::default()
            },
        )
        .unwrap();
    closed(&frustum);
    assert!((frustum.volume() - 2.0 / 3.0 * (1.0 + s + s * s)).abs() < 1e-14);
    let wedge = ExtrudeOptions {
        scale_top: DVec2::new(0.0, 1.0),
        ..Default::default()
    };
    assert!(square.extrude_with(1.0, &wedge).is_err());
    // Per-axis scale: walls are not planar, the solid still closes.
    let stretched = ExtrudeOptions {
        scale_top: DVec2::new(2.0, 0.5),
        ..Default::default()
    };
    closed(&square.extrude_with(1.0, &stretched).unwrap());
}

#[test]
fn twisted_square_converges() {
    let square = Sketch::rectangle(1.0, 1.0).unwrap();
    let twisted = |slices: Option<u32>| {
        let s = square
            .extrude_with(
                2.0,
                &ExtrudeOptions {
                    twist: 90.0,
                    slices,
                    ..Default::default()
                },
            )
            .unwrap();
        closed(&s);
        s.volume()
    };
    let default = twisted(None);
    assert!((default - 2.0).abs() < 1e-3, "{default}");
    let mut last = f64::INFINITY;
    for n in [1, 2, 4, 8, 16, 32, 64, 128] {
        let err = (twisted(Some(n)) - 2.0).abs();
        assert!(err < last, "{n} slices: error {err} after {last}");
        last = err;
    }
    assert!(last < 1e-4, "{last}");
}

#[path = "../benches/common/sketch_cases.rs"]
mod cases;

#[test]
fn big_star_polygons() {
    let a = cases::random_star(10_000, 1, DVec2::ZERO);
    let b = cases::random_star(10_000, 2, DVec2::new(0.3, 0.1));
    valid(&a);
    let t = std::time::Instant::now();
    let u = &a | &b;
    eprintln!("star union {:?}", t.elapsed());
    let i = &a & &b;
    valid(&u);
    valid(&i);
    let tol = 1e-9 * (a.area() + b.area());
    assert!((u.area() + i.area() - a.area() - b.area()).abs() < tol);
}

#[test]
fn many_circles() {
    let circles = cases::random_circles(1000, 3);
    let total: f64 = circles.iter().map(Sketch::area).sum();
    let t = std::time::Instant::now();
    let u = Sketch::union_all(circles.clone());
    eprintln!(
        "1000 circles {:?}: {} regions, {} vertices",
        t.elapsed(),
        u.regions().len(),
        u.vertex_count()
    );
    valid(&u);
    assert!(u.area() < total && u.area() > 0.3 * total);
    // Every circle centre is inside the union.
    for c in &circles {
        let [lo, hi] = c.bounds().unwrap();
        assert_eq!(u.contains(0.5 * (lo + hi)), bspcsg::Containment::Inside);
    }
    let extruded = u.extrude(1.0).unwrap();
    assert!((extruded.volume() - u.area()).abs() < 1e-9 * u.area());
}

#[test]
fn cone_of_a_sketch_with_a_hole() {
    // Holes and separate regions all narrow to the same apex: the surface is pinched there, and
    // the mesh must still come out closed, manifold and oriented.
    let ring = &Sketch::rectangle(2.0, 2.0).unwrap() - &Sketch::circle(0.5, 1e-3).unwrap();
    let two = &ring | &square_at(3.0, 0.0, 1.0);
    for s in [ring, two] {
        let cone = s
            .extrude_with(
                3.0,
                &ExtrudeOptions {
                    scale_top: DVec2::ZERO,
                    ..Default::default()
                },
            )
            .unwrap();
        closed(&cone);
        assert!(
            (cone.volume() - s.area()).abs() < 1e-12,
            "{} vs {}",
            cone.volume(),
            s.area()
        );
    }
}

#[test]
fn plate_drilled_hole_by_hole() {
    let plate = Sketch::rectangle(20.0, 20.0).unwrap();
    let holes = cases::hole_grid(20);
    let t = std::time::Instant::now();
    let drilled = holes.iter().fold(plate, |p, h| &p - h);
    eprintln!("400 holes one by one: {:?}", t.elapsed());
    valid(&drilled);
    assert_eq!(drilled.regions().len(), 1);
    assert_eq!(drilled.regions()[0].holes().len(), 400);
    let expected = 400.0 - holes.iter().map(Sketch::area).sum::<f64>();
    assert!(
        (drilled.area() - expected).abs() < 1e-9,
        "{}",
        drilled.area()
    );
}
