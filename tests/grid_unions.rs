//! Unions of unit boxes on an integer grid: exact volumes, vertices exactly on the grid, closed
//! 2-manifolds, and boxes that touch along an edge split into separate sheets there.

mod common;

use std::collections::HashSet;

use bspcsg::glam::DVec3;
use bspcsg::{Mesh, Solid};
use common::{assert_closed_manifold, obj_box_mesh, shells_and_genus};

/// `count` cells of an `n`³ grid drawn by a fixed linear congruential generator (repeats allowed).
fn random_cells(count: usize, n: u64, seed: u64) -> Vec<[i64; 3]> {
    let mut state = seed;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) % n) as i64
    };
    (0..count).map(|_| [next(), next(), next()]).collect()
}

/// Unit boxes filling `cells`: the crate's cuboids (one quad per face) or OBJ-style boxes of
/// 12 triangles.
fn unit_boxes(cells: &[[i64; 3]], triangulated: bool) -> Vec<Solid> {
    cells
        .iter()
        .map(|c| {
            let min = DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64);
            if triangulated {
                Solid::from_mesh(&obj_box_mesh(min, min + DVec3::ONE)).unwrap()
            } else {
                Solid::cube(1.0)
                    .unwrap()
                    .translate(min + DVec3::splat(0.5))
                    .unwrap()
            }
        })
        .collect()
}

/// The largest distance of a vertex coordinate from the nearest integer.
fn off_grid(mesh: &Mesh) -> f64 {
    mesh.positions
        .iter()
        .flat_map(|p| p.to_array())
        .map(|x| (x - x.round()).abs())
        .fold(0.0, f64::max)
}

/// The union's mesh is a closed 2-manifold of exactly the number of distinct cells, every
/// vertex on the grid; returns its shell count and genus.
fn assert_exact_union(cells: &[[i64; 3]], triangulated: bool, what: &str) -> (usize, u64) {
    let distinct: HashSet<[i64; 3]> = cells.iter().copied().collect();
    let expected = distinct.len() as f64;
    let union = Solid::union_all(unit_boxes(cells, triangulated));
    let mesh = union.to_mesh();
    let report = assert_closed_manifold(&mesh, what);
    assert_eq!(report.needles, 0, "{what}: {report}");
    assert!(
        (union.volume() - expected).abs() <= 1e-12 * expected,
        "{what}: solid volume {} for {expected}",
        union.volume()
    );
    assert!(
        (report.volume - expected).abs() <= 1e-12 * expected,
        "{what}: mesh volume {} for {expected}",
        report.volume
    );
    assert_eq!(off_grid(&mesh), 0.0, "{what}: a vertex left the grid");
    (report.shells.len(), report.genus.unwrap())
}

/// Eight boxes on the black cells of a 4×2×2 checkerboard: every pair of neighbours touches
/// along an edge only. Each edge is split into two (its vertices duplicated), so the mesh is
/// eight separate cubes.
#[test]
fn eight_boxes_touching_along_edges_come_out_as_eight_cubes() {
    let cells: Vec<[i64; 3]> = (0..4)
        .flat_map(|x| (0..2).flat_map(move |y| (0..2).map(move |z| [x, y, z])))
        .filter(|c| (c[0] + c[1] + c[2]) % 2 == 0)
        .collect();
    assert_eq!(cells.len(), 8);
    for triangulated in [false, true] {
        let (shells, genus) = assert_exact_union(&cells, triangulated, "checkerboard");
        assert_eq!((shells, genus), (8, 0));
    }
}

/// The other side of the same edges: a 4×2×2 block minus the checkerboard's eight boxes. The
/// cavities touch along edges whose ends lie in solid material, so pairing the faces across
/// the solid would leave both sheets on one pair of vertices; they are paired across the
/// cavities instead and the edge's vertices split.
#[test]
fn a_block_minus_eight_boxes_touching_along_edges_is_manifold() {
    let cells: Vec<[i64; 3]> = (0..4)
        .flat_map(|x| (0..2).flat_map(move |y| (0..2).map(move |z| [x, y, z])))
        .filter(|c| (c[0] + c[1] + c[2]) % 2 == 1)
        .collect();
    for triangulated in [false, true] {
        let block = Solid::from_mesh(&obj_box_mesh(
            DVec3::new(-1.0, -1.0, -1.0),
            DVec3::new(5.0, 3.0, 3.0),
        ))
        .unwrap();
        let holes = Solid::union_all(unit_boxes(&cells, triangulated));
        let result = block.difference(&holes);
        let mesh = result.to_mesh();
        let report = assert_closed_manifold(&mesh, "block minus checkerboard");
        assert_eq!(report.volume, 6.0 * 4.0 * 4.0 - 8.0, "{report}");
        assert_eq!(off_grid(&mesh), 0.0);
    }
}

/// Eight random grid boxes (repeats and edge contacts included), in both box forms.
#[test]
fn unions_of_eight_random_grid_boxes_are_exact() {
    for seed in 1..=20 {
        let cells = random_cells(8, 3, seed);
        for triangulated in [false, true] {
            assert_exact_union(&cells, triangulated, &format!("seed {seed}"));
        }
    }
}

/// A thousand boxes in a 12³ grid (748 distinct cells): exact volume, every vertex on the
/// grid. Before the BSP's cell planes had to leave a polygon whole on each side, a cascade of
/// planes at 2 + 2⁻ᵏ cut slivers thinner than the weld: boundary edges, inside-out shells,
/// vertices 1.6e-10 off the grid.
#[test]
fn a_thousand_grid_boxes_union_exactly() {
    let cells = random_cells(1000, 12, 1);
    for triangulated in [false, true] {
        let (shells, genus) = assert_exact_union(&cells, triangulated, "1000 boxes");
        assert_eq!((shells, genus), (55, 23));
    }
    let dense = random_cells(1000, 10, 3);
    let (_, _) = assert_exact_union(&dense, false, "1000 boxes in 10³");
}

/// Two bars of two boxes, (0..2, 0, 0) and (0..2, 1, 1), touching along the edge y = z = 1
/// from x = 0 to 2, between two 2×2 walls at x = −1 and x = 2. The library's union (one
/// source) and the command line's (a source per input) must pair the contact alike. With one
/// source the contact is one edge 0 → 2 (its middle vertex dropped with the merged faces);
/// pairing across the solid leaves both sheets on its two end vertices, which the walls close
/// into one fan each, so the pairing flips to across the empty wedges (genus 0). With a source
/// per box the vertex at x = 1 stays and pinches nothing, and the contact stayed split (genus 1)
/// until a straight run of edges closed at both ends was flipped like one edge. In
/// `random_cells(1000, 12, 1)` the same contact (x = 7..9 along y = 7, z = 1) gave the command
/// line's union genus 24 against the library's 23.
#[test]
fn a_contact_between_walls_pairs_alike_with_or_without_sources() {
    let wall = |x: i64| [[x, 0, 0], [x, 1, 0], [x, 0, 1], [x, 1, 1]];
    let mut cells: Vec<[i64; 3]> = [wall(-1), wall(2)].concat();
    cells.extend([[0, 0, 0], [1, 0, 0], [0, 1, 1], [1, 1, 1]]);
    for (cells, what) in [
        (cells, "walls and bars"),
        (random_cells(1000, 12, 1), "1000 boxes"),
    ] {
        let one = Solid::union_all(unit_boxes(&cells, false)).to_mesh();
        let per_box = Solid::union_all(
            unit_boxes(&cells, false)
                .into_iter()
                .enumerate()
                .map(|(i, s)| s.with_source(i as u32)),
        )
        .to_mesh();
        assert_eq!(
            shells_and_genus(&one, what),
            shells_and_genus(&per_box, what),
            "{what}: one source against a source per box"
        );
    }
}

/// A 32×16 and a 64×32 sphere minus the same sphere turned by 1e-4° about a skew axis: every
/// pair of matching facets crosses at 1.7e-6 rad, leaving slivers up to 1.7e-7 thick. The
/// result must be closed with the volume of the slivers (`first_order_sliver_volume`: 3.5801e-7
/// at 32×16, 1.8074e-7 at 64×32), in bounded time. Open: 32×16 gives 5,613 triangles, 32
/// shells, 970 boundary edges, mesh 2.83e-7 against the solid's 3.57e-7; 64×32 4,374 boundary
/// edges, 50 shells; 128×64 17,439 boundary edges (the repair gives up after two passes where
/// thousands of crack points are left, 1912 at 32×16).
///
/// Traced at 32×16 (the first crack): A's facet f and B's twin f' cross along a line L. A's
/// polygon on f has an edge along L from P = f ∩ g ∩ f' (its edge with neighbour g cut by f',
/// interpolated) to a vertex 0.06 away; B's polygon on f' has a corner Z on L (its edge cut by
/// f) 1.3e-3 from P, which must lie on A's edge as a T-junction. Both points lie within 1e-16
/// of f and f', yet Z is 2.2e-10 off A's edge: points within rounding of two planes crossing at
/// 1.7e-6 rad fill a band 1e-10 wide about their line, and a point and a segment computed apart
/// in it miss each other by up to its width, 8 welds. Moving every vertex on three planes, two
/// nearly parallel, to their `meet` (one computed line for every point on L) closes 32×16 with
/// the first-order volume (3.58040e-7), but leaves cracks at 64×32 where four planes nearly
/// meet in a point, and shifts the polygons of cubes turned 1e-5° and less by 0.6 % … 26 %
/// (`robustness.rs`, `turned_cubes.rs`): not landed. Closed since 57fae4e and 99b9509: edge
/// cuts along a nearly parallel cutting plane are taken at the shared three-plane meet below
/// `MEET_BELOW` (1e-5), so both operands compute the same points on L.
#[test]
fn sphere_minus_itself_turned_a_ten_thousandth_of_a_degree() {
    for (segments, rings) in [(32, 16), (64, 32)] {
        let a = Solid::sphere(1.0, segments, rings).unwrap();
        let b = a
            .clone()
            .rotate_axis_angle(DVec3::new(0.3, 1.0, 0.2), 1e-4)
            .unwrap();
        let start = std::time::Instant::now();
        let result = a.difference(&b);
        let mesh = result.to_mesh();
        let elapsed = start.elapsed();
        let what = format!("{segments}×{rings}");
        let report = assert_closed_manifold(&mesh, &what);
        assert!(
            result.volume() >= 0.0 && report.volume >= 0.0,
            "{what}: {report}"
        );
        // Within 1e-3 of the first order and what the first weld (8 tolerances) explains over
        // both sides of the slivers (twice the sphere's area).
        let want = first_order_sliver_volume(&a, &b);
        let weld = 8.0 * result.tolerance().eps() * 2.0 * 4.0 * std::f64::consts::PI;
        assert!(
            (report.volume - want).abs() <= 1e-3 * want + weld,
            "{what}: mesh {:e} want {want:e}",
            report.volume
        );
        // A guard against a runaway (512×256 once took 154 s), not a speed measure: both sizes
        // take 0.6 s together here, and over 2 s on the shared machine under load.
        assert!(elapsed.as_secs_f64() < 30.0, "{what}: {elapsed:?}");
    }
}

/// The volume of `a` less `b`, `b` being `a` turned by a hair with its polygons in the same
/// order, to first order: over each facet of `a`, the positive part of the distance to the
/// twin facet's plane (linear across the facet), by midpoint quadrature on 64² sub-triangles of
/// each fan triangle. The second order is the angle times smaller.
fn first_order_sliver_volume(a: &Solid, b: &Solid) -> f64 {
    let n = 64;
    let mut total = 0.0;
    for (p, q) in a.polygons().iter().zip(b.polygons()) {
        let plane = q.plane();
        for [x, y, z] in p.fan() {
            let d = [x, y, z].map(|v| plane.distance(v));
            let area = 0.5 * (y - x).cross(z - x).length();
            let mut sum = 0.0;
            for i in 0..n {
                for j in 0..n - i {
                    // The upward sub-triangle at (i, j) and, where there is one, the downward.
                    for (s, t) in [(1.0, 1.0), (2.0, 2.0)] {
                        if s == 2.0 && i + j + 1 >= n {
                            continue;
                        }
                        let (u, w) = (
                            (i as f64 + s / 3.0) / n as f64,
                            (j as f64 + t / 3.0) / n as f64,
                        );
                        sum += (d[0] * (1.0 - u - w) + d[1] * u + d[2] * w).max(0.0);
                    }
                }
            }
            total += area * sum / (n * n) as f64;
        }
    }
    total
}
