//! Scenes with 2D operations, rounded rectangles, regular polygons, twisted / tapered
//! extrusions and revolutions: exact 2D distances against brute force over fine sketches,
//! distance bounds that never overestimate, both routes agreeing, and faults named by path.

use bspcsg::{BakeOptions, Containment, Scene, Sketch, TessellationOptions};
use glam::{DVec2, DVec3};

fn scene(json: &str) -> Scene {
    Scene::from_json_str(json).unwrap()
}

/// The exact signed distance to a sketch's boundary, by brute force over its edges.
fn sketch_distance(s: &Sketch, p: DVec2) -> f64 {
    let mut d = f64::INFINITY;
    for ring in s.rings() {
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            let e = b - a;
            let t = ((p - a).dot(e) / e.length_squared()).clamp(0.0, 1.0);
            d = d.min(p.distance(a + e * t));
        }
    }
    if s.contains(p) == Containment::Inside {
        -d
    } else {
        d
    }
}

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn extrude_of(shape: &str) -> Scene {
    scene(&format!(
        r#"{{"op": "extrude", "source_2d_sdf": {shape}, "extrude_depth": 100}}"#
    ))
}

#[test]
fn rounded_rectangle_and_regular_polygon_are_exact() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    // A polygonal rounded rectangle this fine is within 1e-7 of the true one.
    let rr = extrude_of(r#"{"type": "rounded_rectangle", "size": [2, 1], "radius": 0.3}"#);
    let rr_sketch = Sketch::rounded_rectangle(2.0, 1.0, 0.3, 1e-8).unwrap();
    let hex = extrude_of(r#"{"type": "regular_polygon", "sides": 7, "radius": 0.8}"#);
    let hex_sketch = Sketch::regular_polygon(7, 0.8).unwrap();
    for _ in 0..500 {
        let p = DVec2::new(rng.next() * 3.0 - 1.5, rng.next() * 2.0 - 1.0);
        let q = p.extend(0.0);
        let want = sketch_distance(&rr_sketch, p);
        assert!(
            (rr.distance(q) - want).abs() < 1e-7,
            "{p}: {} vs {want}",
            rr.distance(q)
        );
        let want = sketch_distance(&hex_sketch, p);
        assert!((hex.distance(q) - want).abs() < 1e-12, "{p}");
    }
}

#[test]
fn two_d_operations_place_and_combine() {
    let op = r#"{"op": "subtract", "pos": [0.5, 0], "rot": 30, "children": [
        {"type": "rectangle", "size": [2, 1]},
        {"op": "union", "children": [
            {"type": "circle", "radius": 0.3, "pos": [-0.5, 0]},
            {"type": "circle", "radius": 0.3, "pos": [0.5, 0]}]}]}"#;
    let s = extrude_of(op);
    let sketch = (&Sketch::rectangle(2.0, 1.0).unwrap()
        - &(&Sketch::circle(0.3, 1e-7)
            .unwrap()
            .translate(DVec2::new(-0.5, 0.0))
            .unwrap()
            | &Sketch::circle(0.3, 1e-7)
                .unwrap()
                .translate(DVec2::new(0.5, 0.0))
                .unwrap()))
        .rotate(30.0)
        .unwrap()
        .translate(DVec2::new(0.5, 0.0))
        .unwrap();
    let mut rng = Rng(7);
    for _ in 0..500 {
        let p = DVec2::new(rng.next() * 4.0 - 1.5, rng.next() * 3.0 - 1.5);
        let d = s.distance(p.extend(0.0));
        let exact = sketch_distance(&sketch, p);
        // Signs agree away from the boundary; min/max never overestimate.
        if exact.abs() > 1e-5 {
            assert_eq!(d < 0.0, exact < 0.0, "{p}: {d} vs {exact}");
        }
        assert!(d.abs() <= exact.abs() + 1e-5, "{p}: {d} vs {exact}");
    }
    // The BSP route extrudes the exact region.
    let solid = s
        .to_solid(&TessellationOptions::with_tolerance(1e-4))
        .unwrap();
    assert!((solid.volume() - sketch.area() * 100.0).abs() < 1e-3 * 100.0);
}

/// The SDF never overestimates the distance to the BSP route's surface by more than its
/// tolerance; points are sampled around the solid.
fn never_overestimates(s: &Scene, tol: f64) {
    let solid = s
        .to_solid(&TessellationOptions::with_tolerance(tol))
        .unwrap();
    let mesh = solid.to_mesh();
    assert!(mesh.report().is_closed_manifold());
    let b = s.bbox().expanded(0.5);
    let mut rng = Rng(99);
    let tris: Vec<[DVec3; 3]> = (0..mesh.triangle_count())
        .map(|t| mesh.triangle(t))
        .collect();
    for _ in 0..300 {
        let p = b.min + (b.max - b.min) * DVec3::new(rng.next(), rng.next(), rng.next());
        let surface = tris
            .iter()
            .map(|t| point_triangle(p, t[0], t[1], t[2]))
            .fold(f64::INFINITY, f64::min);
        let d = s.distance(p);
        assert!(d.abs() <= surface + 2.0 * tol, "{p}: |{d}| > {surface}");
    }
}

fn point_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    // Closest point on a triangle (Ericson), distance only.
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (p - (a + ab * (d1 / (d1 - d3)))).length();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (p - (a + ac * (d2 / (d2 - d6)))).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + (c - b) * w)).length();
    }
    let denom = 1.0 / (va + vb + vc);
    (p - (a + ab * (vb * denom) + ac * (vc * denom))).length()
}

#[test]
fn twisted_and_tapered_extrusions_are_bounds() {
    for extra in [
        r#""twist": 120"#,
        r#""scale_top": 0"#,
        r#""scale_top": [1.5, 0.5]"#,
        r#""twist": -90, "scale_top": 0.4"#,
    ] {
        let s = scene(&format!(
            r#"{{"op": "extrude", "extrude_depth": 2, {extra},
                "source_2d_sdf": {{"type": "rounded_rectangle", "size": [1.2, 0.6], "radius": 0.1}}}}"#
        ));
        never_overestimates(&s, 2e-3);
    }
}

#[test]
fn revolutions_full_and_partial() {
    // A full turn of a rectangle against the axis is a cylinder: exact outside; inside, the
    // profile's edge on the axis counts as boundary, so the distance is a bound there.
    let s = scene(
        r#"{"op": "revolve", "source_2d_sdf": {"type": "rectangle", "size": [1, 2], "pos": [0.5, 0]}}"#,
    );
    let cyl = Scene::from_json_str(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "cylinder", "radius": 1, "height": 2}}"#,
    )
    .unwrap();
    let mut rng = Rng(5);
    for _ in 0..200 {
        let p = DVec3::new(rng.next(), rng.next(), rng.next()) * 4.0 - 2.0;
        let (d, want) = (s.distance(p), cyl.distance(p));
        if want >= 0.0 {
            assert!((d - want).abs() < 1e-12, "{p}: {d} vs {want}");
        } else {
            assert!(d < 0.0 && d >= want - 1e-12, "{p}: {d} vs {want}");
        }
    }
    // Profiles reaching x < 0 are clipped at the axis on both routes.
    let torus = scene(
        r#"{"op": "revolve", "angle": 90,
            "source_2d_sdf": {"op": "union", "children": [
                {"type": "circle", "radius": 0.3, "pos": [1, 0]},
                {"type": "rectangle", "size": [1, 0.2], "pos": [0, 0.5]}]}}"#,
    );
    never_overestimates(&torus, 2e-3);
    let mesh = torus.bake(&BakeOptions::with_cell(0.03)).unwrap();
    let solid = torus
        .to_solid(&TessellationOptions::with_tolerance(1e-3))
        .unwrap();
    assert!(
        (mesh.volume() - solid.volume()).abs() < 0.03 * solid.volume(),
        "{} vs {}",
        mesh.volume(),
        solid.volume()
    );
}

#[test]
fn faults_name_their_path() {
    for (json, path) in [
        (
            r#"{"op": "extrude", "extrude_depth": 1, "source_2d_sdf": {"op": "xor", "children": []}}"#,
            "$.source_2d_sdf.op",
        ),
        (
            r#"{"op": "extrude", "extrude_depth": 1, "source_2d_sdf": {"op": "union", "children": [{"type": "circle", "radius": -1}]}}"#,
            "$.source_2d_sdf.children[0].radius",
        ),
        (
            r#"{"op": "extrude", "extrude_depth": 1, "scale_top": [0, 1], "source_2d_sdf": {"type": "circle", "radius": 1}}"#,
            "$.scale_top",
        ),
        (
            r#"{"op": "revolve", "angle": 400, "source_2d_sdf": {"type": "circle", "radius": 1}}"#,
            "$.angle",
        ),
        (
            r#"{"op": "revolve", "source_2d_sdf": {"type": "circle", "radius": 1, "pos": [-3, 0]}}"#,
            "$.source_2d_sdf",
        ),
        (
            r#"{"op": "extrude", "extrude_depth": 1, "source_2d_sdf": {"op": "union", "children": ["nope"]}}"#,
            "$.source_2d_sdf.children[0]",
        ),
        (
            r#"{"op": "extrude", "extrude_depth": 1, "source_2d_sdf": {"type": "rounded_rectangle", "size": [1, 1], "radius": 0.6}}"#,
            "$.source_2d_sdf.radius",
        ),
        (
            r#"{"op": "extrude", "extrude_depth": 1, "source_2d_sdf": {"type": "regular_polygon", "sides": 2, "radius": 1}}"#,
            "$.source_2d_sdf.sides",
        ),
    ] {
        let err = Scene::from_json_str(json).unwrap_err().to_string();
        assert!(err.starts_with(&format!("{path}:")), "{err} (want {path})");
    }
}

#[test]
fn twisted_extrusion_distance_is_negative_inside_and_zero_only_on_the_surface() {
    // Inside the solid the bound must stay negative (not clipped by the box term), and on the
    // box around the column it must stay positive (a box or cylinder distance alone would be
    // zero there, where sphere tracing would report a false surface).
    let s = scene(
        r#"{"op": "extrude", "extrude_depth": 2, "twist": 90, "scale_top": 0.6,
            "source_2d_sdf": {"op": "subtract", "children": [
                {"type": "regular_polygon", "sides": 6, "radius": 0.8},
                {"type": "circle", "radius": 0.2}]}}"#,
    );
    let solid = s
        .to_solid(&TessellationOptions::with_tolerance(1e-3))
        .unwrap();
    let classifier = solid.classifier();
    let b = s.bbox();
    let mut rng = Rng(11);
    let (mut inside, mut outside) = (0, 0);
    for _ in 0..2000 {
        let p = b.min + (b.max - b.min) * DVec3::new(rng.next(), rng.next(), rng.next());
        let d = s.distance(p);
        // Within the tessellation tolerance of the surface the two may differ.
        match classifier.classify(p) {
            Containment::Inside => {
                assert!(d < 1e-3, "{p}: {d} inside");
                inside += (d < 0.0) as usize;
            }
            Containment::Outside => {
                assert!(d > -1e-3, "{p}: {d} outside");
                outside += 1;
            }
            Containment::OnBoundary => {}
        }
    }
    assert!(inside > 100 && outside > 100, "{inside} {outside}");
    // On the faces of the bounding box, away from the column, the distance is positive.
    for p in [
        DVec3::new(b.max.x, b.max.y, 0.0),
        DVec3::new(b.min.x, 0.0, 0.9),
        DVec3::new(b.max.x, b.min.y, -0.9),
    ] {
        assert!(s.distance(p) > 0.05, "{p}: {}", s.distance(p));
    }
}
