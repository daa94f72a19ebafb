//! Distance functions against analytic values and against brute force over their polyhedra.

use bspcsg::{Containment, Scene, TessellationOptions};
use glam::DVec3;

fn prim(data: &str) -> Scene {
    Scene::from_json_str(&format!(r#"{{"kind": "sdf_primitive", "data": {data}}}"#)).unwrap()
}

fn node(json: &str) -> Scene {
    Scene::from_json_str(json).unwrap()
}

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

fn close(s: &Scene, p: DVec3, want: f64) {
    let d = s.distance(p);
    assert!((d - want).abs() < 1e-9, "at {p}: {d}, want {want}");
}

#[test]
fn sphere_box_cylinder() {
    let s = prim(r#"{"primitive_type": "sphere", "radius": 1}"#);
    close(&s, v(2.0, 0.0, 0.0), 1.0);
    close(&s, DVec3::ZERO, -1.0);
    let b = prim(r#"{"primitive_type": "box", "size": [2, 4, 6]}"#);
    close(&b, v(2.0, 0.0, 0.0), 1.0);
    close(&b, DVec3::ZERO, -1.0);
    close(&b, v(2.0, 3.0, 4.0), 3f64.sqrt());
    close(&b, v(0.5, 0.0, 0.0), -0.5);
    let c = prim(r#"{"primitive_type": "cylinder", "radius": 1, "height": 2}"#);
    close(&c, v(2.0, 0.0, 0.0), 1.0);
    close(&c, v(0.0, 2.0, 0.0), 1.0);
    close(&c, v(2.0, 2.0, 0.0), 2f64.sqrt());
    close(&c, DVec3::ZERO, -1.0);
    close(&c, v(0.5, 0.9, 0.0), -0.1);
}

#[test]
fn cone_pyramid_plane_torus() {
    let c = prim(r#"{"primitive_type": "cone", "radius": 1, "height": 2}"#);
    close(&c, v(0.0, 2.0, 0.0), 1.0); // above the apex
    close(&c, v(0.0, -2.0, 0.0), 1.0); // below the base
    close(&c, DVec3::ZERO, -1.0 / 5f64.sqrt()); // to the slant 2r + y = 1
    close(&c, v(2.0, -1.0, 0.0), 1.0); // beside the base rim
    let f = prim(r#"{"primitive_type": "cone", "radius": 1, "radius_top": 1, "height": 2}"#);
    let cyl = prim(r#"{"primitive_type": "cylinder", "radius": 1, "height": 2}"#);
    for p in [
        v(0.3, 0.2, 0.1),
        v(2.0, 0.5, 0.0),
        v(0.0, 3.0, 0.2),
        v(1.5, 1.5, 0.0),
    ] {
        close(&f, p, cyl.distance(p));
    }
    let p = prim(r#"{"primitive_type": "pyramid", "base": 2, "height": 2}"#);
    close(&p, v(0.0, 2.0, 0.0), 1.0); // above the apex at y = 1
    close(&p, v(0.0, -2.0, 0.0), 1.0); // below the base at y = -1
    close(&p, v(0.0, -0.5, 0.0), -0.5); // nearest the base
    let pl = prim(r#"{"primitive_type": "plane", "normal": [0, 2, 0], "offset": -1}"#);
    close(&pl, v(5.0, 3.0, -2.0), 2.0);
    close(&pl, v(0.0, 0.0, 0.0), -1.0);
    let t = prim(r#"{"primitive_type": "torus", "radius": 1, "tube_radius": 0.25}"#);
    close(&t, v(1.0, 0.0, 0.0), -0.25);
    close(&t, DVec3::ZERO, 0.75);
    close(&t, v(0.0, 0.0, 2.0), 0.75);
    close(&t, v(1.0, 1.0, 0.0), 0.75);
}

#[test]
fn extrusions_of_rectangle_circle_polygon() {
    let r = node(
        r#"{"op": "extrude", "source_2d_sdf": {"type": "rectangle", "size": [2, 1]}, "extrude_depth": 2}"#,
    );
    close(&r, v(0.0, 0.0, 2.0), 1.0);
    close(&r, v(2.0, 0.0, 0.0), 1.0);
    close(&r, DVec3::ZERO, -0.5);
    close(&r, v(2.0, 1.5, 2.0), 3f64.sqrt());
    let c = node(
        r#"{"op": "extrude", "source_2d_sdf": {"type": "circle", "radius": 1}, "extrude_depth": 2}"#,
    );
    close(&c, DVec3::ZERO, -1.0);
    close(&c, v(2.0, 0.0, 0.0), 1.0);
    close(&c, v(2.0, 0.0, 2.0), 2f64.sqrt());
    // A clockwise square polygon equals the rectangle.
    let p = node(
        r#"{"op": "extrude", "source_2d_sdf": {"type": "polygon", "points": [[-1, -0.5], [-1, 0.5], [1, 0.5], [1, -0.5]]}, "extrude_depth": 2}"#,
    );
    for q in [
        v(0.0, 0.0, 2.0),
        v(2.0, 0.0, 0.0),
        DVec3::ZERO,
        v(0.3, -0.2, 0.9),
        v(-3.0, 2.0, 1.5),
    ] {
        close(&p, q, r.distance(q));
    }
}

#[test]
fn transforms_rotation_order_and_scale() {
    let t = node(
        r#"{"kind": "sdf_primitive", "pos": [1, 2, 3], "data": {"primitive_type": "sphere", "radius": 1}}"#,
    );
    close(&t, v(1.0, 2.0, 5.0), 1.0);
    // Box 1×2×3, rotated 90° about X then 90° about Y (fixed axes): extents become
    // x: 1 (from z), y: 1.5 (from z via X), z: 0.5 (from x).
    let r = node(
        r#"{"kind": "sdf_primitive", "rot": [90, 90, 0], "data": {"primitive_type": "box", "size": [1, 2, 3]}}"#,
    );
    close(&r, v(1.5, 0.0, 0.0), 0.5);
    close(&r, v(0.0, 2.0, 0.0), 0.5);
    close(&r, v(0.0, 0.0, 1.0), 0.5);
    // The same order as Solid::rotate_euler.
    let solid = bspcsg::Solid::cuboid(v(1.0, 2.0, 3.0))
        .unwrap()
        .rotate_euler(v(90.0, 90.0, 0.0))
        .unwrap();
    let bb = solid.bbox();
    assert!((bb.max - v(1.0, 1.5, 0.5)).length() < 1e-9, "{bb:?}");
    // Uniform scale scales the distance exactly.
    let s = node(
        r#"{"kind": "sdf_primitive", "scale": 2, "data": {"primitive_type": "sphere", "radius": 1}}"#,
    );
    close(&s, v(3.0, 0.0, 0.0), 1.0);
    close(&s, DVec3::ZERO, -2.0);
    // Non-uniform scale: an ellipsoid with semi-axes (2, 1, 0.5); the value is a bound that
    // never exceeds the true distance and has the right sign.
    let e = node(
        r#"{"kind": "sdf_primitive", "scale": [2, 1, 0.5], "data": {"primitive_type": "sphere", "radius": 1}}"#,
    );
    let surface: Vec<DVec3> = (0..200)
        .flat_map(|i| {
            let th = std::f64::consts::PI * (i as f64 + 0.5) / 200.0;
            (0..400).map(move |j| {
                let ph = std::f64::consts::TAU * j as f64 / 400.0;
                v(
                    2.0 * th.sin() * ph.cos(),
                    th.cos(),
                    0.5 * th.sin() * ph.sin(),
                )
            })
        })
        .collect();
    for q in [
        v(3.0, 0.0, 0.0),
        v(0.0, 0.0, 1.0),
        v(1.0, 1.0, 1.0),
        v(0.5, 0.2, 0.1),
        v(-2.5, 0.5, 0.3),
    ] {
        let d = e.distance(q);
        let inside = (q.x / 2.0).powi(2) + q.y.powi(2) + (q.z / 0.5).powi(2) < 1.0;
        assert_eq!(d < 0.0, inside, "{q}");
        let truth = surface
            .iter()
            .map(|s| (*s - q).length())
            .fold(f64::INFINITY, f64::min);
        assert!(d.abs() <= truth + 1e-2, "{q}: {d} vs {truth}");
    }
    // Nested transforms compose: parent scale 2 and child offset 1 puts the sphere at x = 2.
    let n = node(
        r#"{"op": "union", "scale": 2, "children": [
            {"kind": "sdf_primitive", "pos": [1, 0, 0], "data": {"primitive_type": "sphere", "radius": 0.5}}]}"#,
    );
    close(&n, v(2.0, 0.0, 0.0), -1.0);
    close(&n, v(4.0, 0.0, 0.0), 1.0);
}

#[test]
fn boolean_and_smooth_ops() {
    let two = |op: &str, extra: &str| {
        node(&format!(
            r#"{{"op": "{op}" {extra}, "children": [
                {{"kind": "sdf_primitive", "pos": [-0.5, 0, 0], "data": {{"primitive_type": "sphere", "radius": 1}}}},
                {{"kind": "sdf_primitive", "pos": [0.5, 0, 0], "data": {{"primitive_type": "sphere", "radius": 1}}}}
            ]}}"#
        ))
    };
    let p = v(0.1, 0.7, 0.2);
    let a = (p - v(-0.5, 0.0, 0.0)).length() - 1.0;
    let b = (p - v(0.5, 0.0, 0.0)).length() - 1.0;
    close(&two("union", ""), p, a.min(b));
    close(&two("intersect", ""), p, a.max(b));
    close(&two("subtract", ""), p, a.max(-b));
    let k: f64 = 4.0;
    let su = -((-k * a).exp() + (-k * b).exp()).ln() / k;
    close(&two("smooth_union", r#", "smooth_k": 4"#), p, su);
    let si = ((k * a).exp() + (k * b).exp()).ln() / k;
    close(&two("smooth_intersect", r#", "smooth_k": 4"#), p, si);
    let ss = ((k * a).exp() + (-k * b).exp()).ln() / k;
    close(&two("smooth_subtract", r#", "smooth_k": 4"#), p, ss);
    let kp: f64 = 0.5;
    let h = (0.5 + (b - a) / (2.0 * kp)).clamp(0.0, 1.0);
    let poly = b + (a - b) * h - kp * h * (1.0 - h);
    close(
        &two(
            "smooth_union",
            r#", "smooth_k": 0.5, "smooth": "polynomial""#,
        ),
        p,
        poly,
    );
    // Subtract folds: the first minus each of the rest.
    let s = node(
        r#"{"op": "subtract", "children": [
            {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [4, 1, 1]}},
            {"kind": "sdf_primitive", "pos": [-1, 0, 0], "data": {"primitive_type": "sphere", "radius": 0.3}},
            {"kind": "sdf_primitive", "pos": [1, 0, 0], "data": {"primitive_type": "sphere", "radius": 0.3}}
        ]}"#,
    );
    assert!(s.distance(v(-1.0, 0.0, 0.0)) > 0.0);
    assert!(s.distance(v(1.0, 0.0, 0.0)) > 0.0);
    assert!(s.distance(DVec3::ZERO) < 0.0);
}

#[test]
fn material_is_the_deciding_primitive() {
    let s = node(
        r##"{"materials": {"red": [1, 0, 0], "blue": "#0000ff"},
            "tree": {"op": "subtract", "children": [
                {"op": "union", "children": [
                    {"kind": "sdf_primitive", "pos": [-1, 0, 0], "data": {"primitive_type": "box", "size": [2, 2, 2], "material": "red"}},
                    {"kind": "sdf_primitive", "pos": [1.5, 0, 0], "data": {"primitive_type": "sphere", "radius": 1, "material": "blue"}}
                ]},
                {"kind": "sdf_primitive", "pos": [-1, 1, 0], "data": {"primitive_type": "sphere", "radius": 0.5, "material": "blue"}}
            ]}}"##,
    );
    let names: Vec<&str> = s.materials().iter().map(|m| m.name.as_str()).collect();
    let id = |n: &str| names.iter().position(|&m| m == n).unwrap() as u32;
    assert_eq!(s.material_at(v(-1.9, 0.0, 0.0)), id("red"));
    assert_eq!(s.material_at(v(2.4, 0.0, 0.0)), id("blue"));
    // On the cut surface the subtracted primitive decides.
    assert_eq!(s.material_at(v(-1.0, 0.5, 0.0)), id("blue"));
    assert_eq!(
        s.materials()[id("blue") as usize].base_color,
        [0.0, 0.0, 1.0, 1.0]
    );
}

/// Unsigned distance from `p` to triangle `abc` (Ericson's closest point).
fn point_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
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

/// Every primitive against brute force over its tessellation: exact for the polyhedral ones,
/// within the chordal tolerance for the round ones.
#[test]
fn every_primitive_against_brute_force() {
    let cases: [(&str, f64); 9] = [
        (
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [1, 2, 0.5]}}"#,
            1e-9,
        ),
        (
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "pyramid", "base": 1.5, "height": 1}}"#,
            1e-9,
        ),
        (
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "pyramid", "base": 0.5, "height": 2}}"#,
            1e-9,
        ),
        (
            r#"{"op": "extrude", "source_2d_sdf": {"type": "polygon", "points": [[0, 0], [1, 0], [1, 1], [0.5, 0.3], [0, 1]]}, "extrude_depth": 0.7}"#,
            1e-9,
        ),
        (
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 0.8}}"#,
            2e-3,
        ),
        (
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "cylinder", "radius": 0.5, "height": 1.5}}"#,
            2e-3,
        ),
        (
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "cone", "radius": 0.7, "height": 1.2}}"#,
            2e-3,
        ),
        (
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "cone", "radius": 0.3, "radius_top": 0.8, "height": 1}}"#,
            2e-3,
        ),
        (
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "torus", "radius": 0.7, "tube_radius": 0.2}}"#,
            2e-3,
        ),
    ];
    for (json, tol) in cases {
        let s = node(json);
        let solid = s
            .to_solid(&TessellationOptions::with_tolerance(5e-4))
            .unwrap();
        let tris: Vec<[DVec3; 3]> = solid.polygons().iter().flat_map(|p| p.fan()).collect();
        let classifier = solid.classifier();
        let bb = s.bbox().expanded(0.5);
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..300 {
            let p = bb.min + (bb.max - bb.min) * v(rnd(), rnd(), rnd());
            let d = s.distance(p);
            let truth = tris
                .iter()
                .map(|t| point_triangle(p, t[0], t[1], t[2]))
                .fold(f64::INFINITY, f64::min);
            assert!(
                (d.abs() - truth).abs() <= tol,
                "{json} at {p}: {d} vs {truth}"
            );
            if truth > tol {
                let inside = classifier.classify(p) == Containment::Inside;
                assert_eq!(d < 0.0, inside, "{json} at {p}: sign");
            }
        }
    }
}
