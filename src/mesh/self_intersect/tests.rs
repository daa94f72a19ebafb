//! Tests of the search for crossing triangles.

use super::*;

/// The pairs found, for the tests that look only at them.
fn crossing_pairs(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<(u32, u32)> {
    search(positions, triangles).pairs
}

/// A cone of `n` triangles around apex 0 and `n` around the centre 1 of its base (unit
/// radius, height `h`), ring vertices from 2; triangle `2i` is the apex's, `2i + 1` the
/// base's.
pub(super) fn cone(n: u32, h: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = vec![DVec3::new(0.0, 0.0, h), DVec3::ZERO];
    p.extend((0..n).map(|i| ring_point(n, f64::from(i), 1.0)));
    let ring = |i: u32| 2 + i % n;
    let t = (0..n)
        .flat_map(|i| [[0, ring(i), ring(i + 1)], [1, ring(i + 1), ring(i)]])
        .collect();
    (p, t)
}

/// The point at `i` of `n` steps round a circle of `radius` in the plane z = 0.
fn ring_point(n: u32, i: f64, radius: f64) -> DVec3 {
    let a = std::f64::consts::TAU * i / f64::from(n);
    DVec3::new(radius * a.cos(), radius * a.sin(), 0.0)
}

#[test]
fn a_cone_of_many_triangles_is_checked_in_work_linear_in_its_size() {
    // Every pair of the apex's 20,000 triangles overlaps in its box, and so does every pair
    // of the base's, and every apex triangle with every base triangle: 8·10⁸ pairs.
    let n = 20_000;
    let (p, t) = cone(n, 1.0);
    let found = search(&p, &t);
    assert!(found.pairs.is_empty() && found.complete);
    let n = n as usize;
    assert!(found.offered < 16 * n, "{}", found.offered);
    assert!(found.tested < 4 * n, "{}", found.tested);
}

/// A cone with one ring vertex folded over in its base (the base centre's fan no longer
/// embedded, so its triangles are tested pair by pair).
fn folded_cone(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mut p, t) = cone(n, 1.0);
    p[2 + 10] = ring_point(n, 12.5, 0.9);
    (p, t)
}

/// Two cones of `n` sides touching apex to apex (separate vertices at one point): every
/// triangle of either apex's fan meets every one of the other's, at that point.
fn hourglass(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mut p, mut t) = cone(n, 1.0);
    let (q, u) = cone(n, 1.0);
    let m = p.len() as u32;
    // Mirrored through z = 1 and y = 0: turned over, still facing out.
    p.extend(q.into_iter().map(|v| DVec3::new(v.x, -v.y, 2.0 - v.z)));
    t.extend(u.into_iter().map(|f| f.map(|i| i + m)));
    (p, t)
}

/// `n` thin tetrahedra along one diagonal, stacked a thousandth of their thickness apart:
/// no vertex shared, every box overlapping every other, no two crossing.
fn stacked_slivers(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let h = 1e-3 / f64::from(n);
    let mut p = Vec::new();
    let mut t = Vec::new();
    for i in 0..n {
        let z = f64::from(i) * h;
        let b = p.len() as u32;
        p.extend([
            DVec3::new(0.0, 0.0, z),
            DVec3::new(1.0, 1.0, z + 1.0),
            DVec3::new(0.5, 0.5 + 1e-3, z + 0.5),
            DVec3::new(0.5, 0.5, z + 0.5 + 0.25 * h),
        ]);
        t.extend([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]].map(|f| f.map(|k| b + k)));
    }
    (p, t)
}

/// `n` triangles at the origin, each from it to the points `(1, 0, z)` and `(0, 1, z)` for
/// its own height `z`: pages of a book, no two crossing (they meet only at the origin), every
/// wedge overlapping every other seen from any direction, so no sweep settles the point.
fn book(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut p = vec![DVec3::ZERO];
    let mut t = Vec::new();
    for i in 0..n {
        let z = f64::from(i) / f64::from(n) - 0.5;
        let b = p.len() as u32;
        p.extend([DVec3::new(1.0, 0.0, z), DVec3::new(0.0, 1.0, z)]);
        t.push([0, b, b + 1]);
    }
    (p, t)
}

/// The crowded inputs nothing prunes cost their search at most its budget (stacked slivers
/// took 8·10⁶ candidate pairs at 3,000 triangles, 10–18 s; the book would take 2·10⁸ at
/// 20,000): each stops there, undecided. Counted, not timed.
#[test]
fn crowded_triangles_stop_at_the_pair_budget() {
    let slack = 2 * (rayon::current_num_threads() + 1) * BUDGET_STEP;
    for (what, (p, t)) in [
        ("stacked slivers", stacked_slivers(5_000)),
        ("book", book(20_000)),
    ] {
        let found = search(&p, &t);
        let budget = pair_budget(t.len());
        assert!(!found.complete, "{what}");
        assert!(found.spent <= budget + slack, "{what}: {}", found.spent);
        assert!(found.spent > budget, "{what}: {}", found.spent);
        assert!(found.pairs.is_empty(), "{what}: {:?}", found.pairs);
    }
    // Small ones finish within the budget's base and are decided.
    let (p, t) = stacked_slivers(100);
    let found = search(&p, &t);
    assert!(found.complete && found.pairs.is_empty());
    let (p, t) = book(300);
    let found = search(&p, &t);
    assert!(found.complete && found.pairs.is_empty());
}

/// Points where many triangles meet that no embedded fan settles — a fan folded over, two
/// cones apex to apex on two vertices or on one (a pinched point) — are settled by a sweep
/// about the point in work near linear in their triangles (these took the whole budget, 10⁹
/// pairs unbounded, before the sweep): the folded fan's crossings are found, the others are
/// decided clean.
#[test]
fn crowded_points_are_settled_by_a_sweep() {
    let (p, mut pinched) = hourglass(20_000);
    // The second cone's apex (vertex 20,002) replaced by the first's.
    let second = 20_002;
    for f in &mut pinched {
        for v in f.iter_mut() {
            if *v == second {
                *v = 0;
            }
        }
    }
    for (what, (p, t), crossing) in [
        ("folded cone", folded_cone(20_000), true),
        ("hourglass", hourglass(20_000), false),
        ("pinched hourglass", (p, pinched), false),
    ] {
        let found = search(&p, &t);
        assert!(found.complete, "{what}");
        assert_eq!(
            !found.pairs.is_empty(),
            crossing,
            "{what}: {:?}",
            found.pairs
        );
        let n = t.len();
        assert!(found.spent < 40 * n, "{what}: {}", found.spent);
        assert!(found.tested < 2 * n, "{what}: {}", found.tested);
    }
}

#[test]
fn a_cone_with_a_fan_folded_over_crosses() {
    // Ring vertex 10 moved round the base past its neighbour 11, inside the circle: base
    // triangles come to overlap in the base's plane, facing the same way, sharing only the
    // centre (whose fan is no longer embedded).
    let n = 2_000;
    let (mut p, t) = cone(n, 1.0);
    p[2 + 10] = ring_point(n, 12.5, 0.9);
    let pairs = crossing_pairs(&p, &t);
    assert!(!pairs.is_empty());
    assert!(
        pairs.iter().all(|&(a, b)| a % 2 == 1 && b % 2 == 1),
        "{pairs:?}"
    );
    // Moved out and below the base instead: the apex triangles on it pass down through
    // the base, some through base triangles they share one ring vertex with (which the
    // old test of neighbours, coplanar overlap only, took for touching).
    let (mut p, t) = cone(n, 1.0);
    p[2 + 10] = ring_point(n, 12.5, 1.2) - 0.3 * DVec3::Z;
    let pairs = crossing_pairs(&p, &t);
    let shared = |a: u32, b: u32| {
        let (a, b) = (t[a as usize], t[b as usize]);
        a.iter().filter(|v| b.contains(v)).count()
    };
    assert!(
        pairs.iter().all(|&(a, b)| a % 2 == 0 && b % 2 == 1),
        "{pairs:?}"
    );
    assert!(pairs.iter().any(|&(a, b)| shared(a, b) == 1), "{pairs:?}");
    // Unmoved, the same cone is clean.
    let (p, t) = cone(n, 1.0);
    assert!(crossing_pairs(&p, &t).is_empty());
}

#[test]
fn triangles_sharing_one_corner_cross_through_an_edge() {
    let v = DVec3::ZERO;
    let t = [v, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 2.0, 0.0)];
    // The far edge of `u` passes through `t` at (0.6, 0.6, 0).
    let u = [v, DVec3::new(1.0, 0.2, 1.0), DVec3::new(0.2, 1.0, -1.0)];
    assert!(cross([0, 1, 2], [0, 3, 4], t, u));
    assert!(cross([0, 3, 4], [0, 1, 2], u, t));
    // The same far edge lifted clear of `t`: the two meet only at the shared corner.
    let w = [v, DVec3::new(1.0, 0.2, 1.0), DVec3::new(0.2, 1.0, 0.5)];
    assert!(!cross([0, 1, 2], [0, 3, 4], t, w));
}

fn cube(at: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let m = crate::Solid::cube(1.0)
        .unwrap()
        .translate(at)
        .unwrap()
        .to_mesh();
    (m.positions, m.triangles)
}

/// Two cubes' triangles in one mesh, the second moved by `offset`; `shared` reuses the
/// first cube's vertex indices for the second when it is not moved.
fn two_cubes(offset: DVec3, shared: bool) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mut p, mut t) = cube(DVec3::ZERO);
    let (q, u) = cube(offset);
    let n = if shared { 0 } else { p.len() as u32 };
    if !shared {
        p.extend(q);
    }
    t.extend(u.into_iter().map(|f| f.map(|i| i + n)));
    (p, t)
}

#[test]
fn shells_overlapping_only_in_shared_planes_cross() {
    // B = A moved 0.5 along x: no edge passes through a face, but the faces y = 0, y = 1,
    // z = 0 and z = 1 of both overlap facing the same way.
    let (p, t) = two_cubes(DVec3::new(0.5, 0.0, 0.0), false);
    let pairs = crossing_pairs(&p, &t);
    assert!(!pairs.is_empty());
    for &(a, b) in &pairs {
        let normal = |k: u32| {
            let [x, y, z] = t[k as usize].map(|i| p[i as usize]);
            (y - x).cross(z - x).normalize()
        };
        assert!((a as usize) < 12 && (b as usize) >= 12, "{a} {b}");
        assert_eq!(normal(a), normal(b));
        assert_eq!(normal(a).x, 0.0, "only the side faces overlap");
    }
    // Stacked face to face, or side by side: touching, facing opposite ways.
    for offset in [DVec3::Z, DVec3::X, DVec3::new(1.0, 0.5, 0.0)] {
        let (p, t) = two_cubes(offset, false);
        assert!(crossing_pairs(&p, &t).is_empty(), "{offset}");
    }
    // The same cube twice, on copied vertices or on the same ones: each triangle crosses
    // its copy.
    for shared in [false, true] {
        let (p, t) = two_cubes(DVec3::ZERO, shared);
        let pairs = crossing_pairs(&p, &t);
        assert!(pairs.len() >= 12, "{shared}: {pairs:?}");
        assert!((0..12).all(|k| pairs.contains(&(k, k + 12))), "{shared}");
    }
}

#[test]
fn coplanar_triangles_overlap_only_with_interiors_meeting_and_facing_the_same_way() {
    let v = |x: f64, y: f64| DVec3::new(x, y, 3.0);
    let big = [v(0.0, 0.0), v(2.0, 0.0), v(0.0, 2.0)];
    // Inside `big` with every corner on its boundary: no edges cross, no corner is inside.
    let inside = [v(0.0, 0.0), v(2.0, 0.0), v(1.0, 1.0)];
    assert!(coplanar_overlap(big, inside));
    assert!(coplanar_overlap(big, big));
    assert!(coplanar_overlap(big, [big[1], big[2], big[0]]));
    // Facing the other way: two solids face to face.
    assert!(!coplanar_overlap(big, [inside[0], inside[2], inside[1]]));
    // Neighbours across an edge, and triangles meeting at a corner only.
    assert!(!coplanar_overlap(
        big,
        [v(2.0, 0.0), v(2.0, 2.0), v(0.0, 2.0)]
    ));
    assert!(!coplanar_overlap(
        big,
        [v(2.0, 0.0), v(4.0, 0.0), v(2.0, 1.0)]
    ));
    // Crossing edges only, and one corner strictly inside.
    assert!(coplanar_overlap(
        big,
        [v(1.0, -1.0), v(1.0, 3.0), v(-1.0, 1.0)]
    ));
    assert!(coplanar_overlap(
        big,
        [v(0.5, 0.5), v(5.0, 4.0), v(4.0, 5.0)]
    ));
    // No area, no interior.
    assert!(!coplanar_overlap(
        big,
        [v(0.0, 0.0), v(1.0, 1.0), v(2.0, 2.0)]
    ));
    // A tilted plane: the projection drops the largest normal coordinate, exactly.
    let tilt = |x: f64, y: f64| DVec3::new(x, y, 0.5 * x + 0.25 * y);
    let a = [tilt(0.0, 0.0), tilt(2.0, 0.0), tilt(0.0, 2.0)];
    let b = [tilt(0.0, 0.0), tilt(2.0, 0.0), tilt(1.0, 1.0)];
    assert!(cross([0, 1, 2], [0, 1, 3], a, b));
    assert!(!cross(
        [0, 1, 2],
        [1, 0, 3],
        a,
        [b[1], b[0], tilt(1.0, -1.0)]
    ));
}

#[test]
fn overlapping_shells_cross_and_touching_ones_do_not() {
    for (offset, crossing) in [(0.5, true), (1.0, false), (2.0, false)] {
        let (mut p, mut t) = cube(DVec3::ZERO);
        let (q, u) = cube(DVec3::new(offset, 0.25, 0.25));
        let n = p.len() as u32;
        p.extend(q);
        t.extend(u.into_iter().map(|f| f.map(|i| i + n)));
        assert_eq!(!crossing_pairs(&p, &t).is_empty(), crossing, "{offset}");
    }
    let (p, t) = cube(DVec3::ZERO);
    assert!(crossing_pairs(&p, &t).is_empty());
}
