//! Analytic cases with known volumes and areas.

mod common;

use approx::assert_relative_eq;
use bspcsg::{Containment, Solid};
use common::{assert_clean_mesh, shells_and_genus};
use glam::DVec3;

fn cube(size: f64) -> Solid {
    Solid::cube(size).unwrap()
}

fn moved(s: &Solid, x: f64, y: f64, z: f64) -> Solid {
    s.clone().translate(DVec3::new(x, y, z)).unwrap()
}

#[test]
fn adjacent_cubes_union() {
    let a = cube(1.0);
    let b = moved(&a, 1.0, 0.0, 0.0);
    let u = &a | &b;
    assert_relative_eq!(u.volume(), 2.0, max_relative = 1e-12);
    assert_relative_eq!(u.area(), 10.0, max_relative = 1e-12);
    // The shared face vanishes and the coplanar halves merge: a 2 × 1 × 1 box, 12 triangles.
    let mesh = assert_clean_mesh(&u, "adjacent cubes");
    assert_eq!(mesh.triangle_count(), 12);
}

#[test]
fn half_overlapping_cubes() {
    let a = cube(1.0);
    let b = moved(&a, 0.5, 0.0, 0.0);
    assert_relative_eq!((&a | &b).volume(), 1.5, max_relative = 1e-12);
    assert_relative_eq!((&a - &b).volume(), 0.5, max_relative = 1e-12);
    assert_relative_eq!((&a & &b).volume(), 0.5, max_relative = 1e-12);
    assert_relative_eq!((&a | &b).area(), 8.0, max_relative = 1e-12);
    assert_relative_eq!((&a - &b).area(), 4.0, max_relative = 1e-12);
    assert_relative_eq!((&a & &b).area(), 4.0, max_relative = 1e-12);
    for (name, r) in [("∪", &a | &b), ("∩", &a & &b), ("−", &a - &b)] {
        assert_eq!(
            assert_clean_mesh(&r, name).triangle_count(),
            12,
            "{name}: a box"
        );
    }
}

#[test]
fn cube_minus_corner_cube() {
    // cube(2) spans [-1, 1]; cube(1) moved to [0, 1] shares the corner (1, 1, 1).
    let a = cube(2.0);
    let b = moved(&cube(1.0), 0.5, 0.5, 0.5);
    let d = &a - &b;
    assert_relative_eq!(d.volume(), 7.0, max_relative = 1e-12);
    assert_relative_eq!(d.area(), 24.0, max_relative = 1e-12);
    assert_eq!(
        shells_and_genus(&assert_clean_mesh(&d, "notched cube"), "notched cube"),
        (1, 0)
    );
}

#[test]
fn coaxial_cubes_come_back_as_a_handful_of_triangles() {
    // A larger cube swallowing most of a smaller one on the same axis: the union is an L of two
    // boxes, whose coplanar fragments merge back into a few polygons.
    let small = moved(&cube(1.0), 0.0, 0.0, 0.8);
    let big = cube(2.0);
    let u = &big | &small;
    assert_relative_eq!(u.volume(), 8.0 + 0.3, max_relative = 1e-12);
    let mesh = assert_clean_mesh(&u, "coaxial cubes");
    assert!(
        mesh.triangle_count() <= 30,
        "{} triangles",
        mesh.triangle_count()
    );
    let inside = &big | &cube(1.0);
    assert_eq!(
        assert_clean_mesh(&inside, "nested cubes").triangle_count(),
        12
    );
}

#[test]
fn solids_touching_along_an_edge_or_at_a_vertex_are_separate_manifold_shells() {
    let a = cube(1.0);
    let along_edge = &a | &moved(&a, 1.0, 1.0, 0.0);
    let at_vertex = &a | &moved(&a, 1.0, 1.0, 1.0);
    for (name, u) in [("edge", along_edge), ("vertex", at_vertex)] {
        assert_relative_eq!(u.volume(), 2.0, max_relative = 1e-12);
        let mesh = assert_clean_mesh(&u, name);
        assert_eq!(shells_and_genus(&mesh, name), (2, 0), "{name}");
        assert_eq!(mesh.triangle_count(), 24, "{name}");
    }
}

#[test]
fn self_operations() {
    for a in [
        cube(1.0),
        Solid::sphere(1.0, 24, 12).unwrap(),
        Solid::torus(1.0, 0.3, 24, 12).unwrap(),
    ] {
        let v = a.volume();
        assert!((&a - &a).is_empty(), "A - A must be empty");
        assert_clean_mesh(&(&a | &a), "A ∪ A");
        assert_clean_mesh(&(&a & &a), "A ∩ A");
        assert_relative_eq!((&a | &a).volume(), v, max_relative = 1e-12);
        assert_relative_eq!((&a & &a).volume(), v, max_relative = 1e-12);
        assert_relative_eq!((&a | &a).area(), a.area(), max_relative = 1e-12);
        assert_relative_eq!((&a & &a).area(), a.area(), max_relative = 1e-12);
    }
}

#[test]
fn disjoint_unions_add() {
    let a = Solid::sphere(1.0, 32, 16).unwrap();
    let b = moved(&cube(1.0), 5.0, 0.0, 0.0);
    let u = &a | &b;
    assert_relative_eq!(u.volume(), a.volume() + 1.0, max_relative = 1e-12);
    assert_eq!(
        shells_and_genus(&assert_clean_mesh(&u, "disjoint"), "disjoint").0,
        2
    );
    assert!((&a & &b).is_empty());
    let d = &a - &b;
    assert_relative_eq!(d.volume(), a.volume(), max_relative = 1e-12);
    assert_clean_mesh(&d, "disjoint difference");
}

#[test]
fn empty_operands() {
    let a = cube(1.0);
    let e = Solid::empty();
    for (name, r) in [("A ∪ ∅", &a | &e), ("∅ ∪ A", &e | &a), ("A − ∅", &a - &e)] {
        assert_relative_eq!(r.volume(), 1.0);
        assert_eq!(assert_clean_mesh(&r, name).triangle_count(), 12, "{name}");
    }
    assert!((&e - &a).is_empty());
    assert!((&a & &e).is_empty());
}

#[test]
fn sphere_volume_converges() {
    let exact = 4.0 / 3.0 * std::f64::consts::PI;
    let mut last_err = f64::INFINITY;
    for n in [8u32, 16, 32, 64, 128, 256] {
        let err = (Solid::sphere(1.0, n, n / 2).unwrap().volume() - exact).abs() / exact;
        assert!(err < last_err, "error must shrink: {err} after {last_err}");
        last_err = err;
    }
    assert!(last_err < 1e-3, "{last_err}");
}

#[test]
fn primitive_volumes() {
    let pi = std::f64::consts::PI;
    let n = 512u32;
    let inscribed = |r: f64| 0.5 * n as f64 * r * r * (2.0 * pi / n as f64).sin();
    assert_relative_eq!(
        Solid::cylinder(1.0, 2.0, n).unwrap().volume(),
        inscribed(1.0) * 2.0,
        max_relative = 1e-12
    );
    assert_relative_eq!(
        Solid::cone(1.0, 3.0, n).unwrap().volume(),
        inscribed(1.0) * 3.0 / 3.0,
        max_relative = 1e-12
    );
    let torus = Solid::torus(2.0, 0.5, 256, 128).unwrap().volume();
    assert_relative_eq!(torus, 2.0 * pi * pi * 2.0 * 0.25, max_relative = 1e-3);
    assert_relative_eq!(
        Solid::cuboid(DVec3::new(1.0, 2.0, 3.0)).unwrap().volume(),
        6.0
    );
}

#[test]
fn containment() {
    let a = cube(2.0);
    assert_eq!(a.contains(DVec3::ZERO), Containment::Inside);
    assert_eq!(
        a.contains(DVec3::new(1.0, 0.3, 0.2)),
        Containment::OnBoundary
    );
    assert_eq!(
        a.contains(DVec3::new(1.0, 1.0, 1.0)),
        Containment::OnBoundary
    );
    assert_eq!(a.contains(DVec3::new(1.5, 0.0, 0.0)), Containment::Outside);
    let s = Solid::sphere(1.0, 64, 32).unwrap();
    assert_eq!(s.contains(DVec3::new(0.0, 0.9, 0.0)), Containment::Inside);
    assert_eq!(s.contains(DVec3::new(0.0, 1.1, 0.0)), Containment::Outside);
}

#[test]
fn coordinates_beyond_the_range_are_refused() {
    assert!(Solid::cube(1e200).is_err());
    assert!(Solid::sphere(1e101, 8, 4).is_err());
    assert!(cube(1.0).translate(DVec3::new(1e150, 0.0, 0.0)).is_err());
    // A corner at (1e100, 5e99) turned 45° about Z reaches y ≈ 1.06e100.
    let edge = cube(1e100).translate(DVec3::new(5e99, 0.0, 0.0)).unwrap();
    assert!(edge.rotate_euler(DVec3::new(0.0, 0.0, 45.0)).is_err());
    let far = bspcsg::Mesh::new(
        vec![DVec3::ZERO, DVec3::X * 1e150, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    );
    let err = Solid::from_mesh(&far).unwrap_err().to_string();
    assert!(err.contains("supported range"), "{err}");
    // Within the range, a huge box still keeps a small part's detail: the unit cavity is its
    // own shell (its volume, 1 in 1e297, is below what f64 can show).
    let huge = Solid::cube(1e99).unwrap();
    let hole = &huge - &cube(1.0);
    assert_eq!(hole.contains(DVec3::ZERO), Containment::Outside);
    assert_eq!(hole.contains(DVec3::splat(0.6)), Containment::Inside);
    let (shells, _) = shells_and_genus(&assert_clean_mesh(&hole, "cavity"), "cavity");
    assert_eq!(shells, 2);
}

#[test]
fn disjoint_union_keeps_the_tolerance_its_parts_carry() {
    // Two overlapping spheres far out (their union carries a tolerance of their scale), then a
    // tiny cube far from them: the tiny cube must not lower that tolerance below what the
    // spheres' fragments were made with.
    let s = Solid::sphere(1.0, 24, 12).unwrap();
    let pair = &moved(&s, 1000.0, 0.0, 0.0) | &moved(&s, 1000.5, 0.0, 0.0);
    let u = &pair | &cube(1e-3);
    let (shells, genus) = shells_and_genus(&assert_clean_mesh(&u, "far pair and tiny cube"), "u");
    assert_eq!((shells, genus), (2, 0));
}

#[test]
fn tangent_cylinders_with_coincident_faces_open_the_cavity() {
    // B lies inside A and its two side faces next to x = 0.5 lie inside A's faces there (same
    // plane, same outward direction). A − B has no surface where they coincide: the cavity
    // opens through A's skin, and the area is A's and B's less twice the shared faces.
    let (n, r, h) = (24u32, 0.375, 0.75);
    let a = Solid::cylinder(0.5, 1.0, n).unwrap();
    let b = moved(&Solid::cylinder(r, h, n).unwrap(), 0.125, 0.0, 0.0);
    let d = &a - &b;
    let shared_face = 2.0 * r * (std::f64::consts::PI / n as f64).sin() * h;
    assert_relative_eq!(
        d.area(),
        a.area() + b.area() - 4.0 * shared_face,
        max_relative = 1e-12
    );
    assert_relative_eq!(d.volume(), a.volume() - b.volume(), max_relative = 1e-12);
    let (shells, genus) = shells_and_genus(&assert_clean_mesh(&d, "open cavity"), "open cavity");
    assert_eq!((shells, genus), (1, 0));
}

#[test]
fn inside_out_meshes_are_refused() {
    let mut m = cube(1.0).to_mesh();
    for t in &mut m.triangles {
        t.swap(1, 2);
    }
    let err = Solid::from_mesh(&m).unwrap_err().to_string();
    assert!(err.contains("inside out"), "{err}");
    let faces: Vec<[u32; 3]> = m.triangles.clone();
    assert!(Solid::polyhedron(&m.positions, &faces).is_err());
}

#[test]
fn a_star_prism_of_thousands_of_points_triangulates_quickly() {
    // Non-convex caps take the O(n log n) triangulation, not O(n³) ear clipping.
    let n = 2000usize;
    let ring: Vec<DVec3> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            let rad = if k % 2 == 0 { 1.0 } else { 0.6 };
            DVec3::new(rad * t.cos(), rad * t.sin(), 0.0)
        })
        .collect();
    let mut v = ring.clone();
    v.extend(ring.iter().map(|p| *p + DVec3::Z));
    let n32 = n as u32;
    let mut faces: Vec<Vec<u32>> = vec![(0..n32).rev().collect(), (n32..2 * n32).collect()];
    for k in 0..n32 {
        let k1 = (k + 1) % n32;
        faces.push(vec![k, k1, n32 + k1, n32 + k]);
    }
    let t0 = std::time::Instant::now();
    let prism = Solid::polyhedron(&v, &faces).unwrap();
    assert!(t0.elapsed().as_secs_f64() < 10.0, "took {:?}", t0.elapsed());
    let cap: f64 = (0..n)
        .map(|k| ring[k].truncate().perp_dot(ring[(k + 1) % n].truncate()) * 0.5)
        .sum();
    assert_relative_eq!(prism.volume(), cap, max_relative = 1e-12);
    assert_clean_mesh(&prism, "star prism");
}
