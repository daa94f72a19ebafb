//! A uniform grid of points for the T-junction search: which points lie near a segment.
//!
//! Why not a BVH of the points walked together with one of the edges: the dual descent hands
//! over whole leaves (four edges by four points), so most calls are pairs of a leaf's box, not
//! of an edge's; on a block less 100 cylinders 842,679 calls found 15,664 points on edges, and
//! building the two trees cost as much again. Points of a boolean's cut lie on surfaces about
//! one edge length apart, so a grid of cells two median edges wide holds a few points per cell,
//! and an edge cut into pieces no longer than a cell looks at a few cells per piece.

use glam::DVec3;

use super::buckets::{Buckets, buckets};
use crate::geom::Aabb;
use crate::geom::bvh::Bvh;
use crate::hash::KeyedHashMap;

/// Cells per axis at most (keys pack three indices of 21 bits).
const AXIS_CELLS: f64 = 1_048_576.0;

/// Pieces an edge is cut into at most; a longer edge asks a tree of the points instead (an
/// edge hundreds of cells long, next to a mesh of small ones).
const MOST_PIECES: f64 = 256.0;

/// A grid is dense (an array of every cell, not a map of the occupied ones) when its cells
/// number at most this many per point, plus [`DENSE_CELLS_ALWAYS`]: the points of a boolean's
/// cut lie on surfaces, a few per cell, so most grids qualify; a sparse spread of points (two
/// far clusters) keeps the map.
const DENSE_CELLS_PER_POINT: u64 = 16;

/// Cells a grid may always have dense, whatever its points.
const DENSE_CELLS_ALWAYS: u64 = 4096;

/// Pieces of an edge per cell it crosses.
const PIECES_PER_CELL: f64 = 1.0;

/// Points bucketed by grid cell.
pub(super) struct Grid<'p> {
    spots: &'p [DVec3],
    origin: DVec3,
    inv: f64,
    cell: f64,
    cells: Cells,
    /// The points' indices, grouped by cell.
    items: Vec<u32>,
    /// For edges cut into more than [`MOST_PIECES`] pieces: a tree of the points, built on first need.
    tree: std::sync::OnceLock<Bvh>,
}

/// Where each cell's points lie in [`Grid::items`].
enum Cells {
    /// Per occupied cell key, its range in `items`. Keyed ([`KeyedHashMap`]): the cells are
    /// of input positions, and FxHash's multiply carries a key's bits only upward, so the
    /// bucket of a key packed as [`pack`] does is set by its low `z` bits alone. Every vertex
    /// of an extrusion lies on one of two planes of constant `z`: four copies of a
    /// 10,000-point outline extruded and united put their 1.4 M points in two probe chains,
    /// and `to_mesh` ran for over ten minutes (with this map: 34 CPU-s for the whole export).
    Sparse(KeyedHashMap<u64, (u32, u32)>),
    /// Every cell, where the points' extent holds few cells beside the points
    /// ([`DENSE_CELLS_PER_POINT`]): cell `(x, y, z)`'s points are
    /// `items[starts[c]..starts[c + 1]]` for `c = (x · dims[1] + y) · dims[2] + z`. Looking a
    /// cell up is then an index, not a hash (most of the search's time was the lookups).
    Dense { starts: Vec<u32>, dims: [u64; 3] },
}

impl<'p> Grid<'p> {
    /// The grid of `spots` with cells `cell` wide (widened where the points' extent would need
    /// more than [`AXIS_CELLS`] per axis).
    pub(super) fn new(spots: &'p [DVec3], cell: f64) -> Self {
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for &p in spots {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        let extent = if spots.is_empty() {
            0.0
        } else {
            (hi - lo).max_element()
        };
        let mut cell = cell.max(extent / (AXIS_CELLS - 2.0));
        if !(cell.is_finite() && cell > 0.0) {
            cell = 1.0;
        }
        let mut grid = Grid {
            spots,
            origin: if spots.is_empty() { DVec3::ZERO } else { lo },
            inv: 1.0 / cell,
            cell,
            cells: Cells::Sparse(KeyedHashMap::default()),
            items: Vec::with_capacity(spots.len()),
            tree: std::sync::OnceLock::new(),
        };
        if !spots.is_empty() {
            let top = grid.index(hi);
            let dims = top.map(|t| t + 1);
            let total = dims[0].saturating_mul(dims[1]).saturating_mul(dims[2]);
            if total <= DENSE_CELLS_PER_POINT * spots.len() as u64 + DENSE_CELLS_ALWAYS {
                let linear: Vec<u32> = spots
                    .iter()
                    .map(|&p| linear(dims, grid.index(p)) as u32)
                    .collect();
                let Buckets { starts, items } = buckets(
                    total as usize,
                    linear
                        .iter()
                        .enumerate()
                        .map(|(i, &c)| (c as usize, i as u32)),
                );
                grid.items = items;
                grid.cells = Cells::Dense { starts, dims };
                return grid;
            }
        }
        // Grouped by a count per occupied cell, then placed in point order: two lookups per
        // point (a sort of the keyed points was 2.9 M instructions of rocker-arm's to_mesh).
        let keys: Vec<u64> = spots
            .iter()
            .map(|&p| {
                let [x, y, z] = grid.index(p);
                pack(x, y, z)
            })
            .collect();
        let mut cells: KeyedHashMap<u64, (u32, u32)> = KeyedHashMap::default();
        cells.reserve(keys.len());
        for &k in &keys {
            cells.entry(k).or_insert((0, 0)).1 += 1;
        }
        let mut at = 0u32;
        for range in cells.values_mut() {
            let count = range.1;
            *range = (at, at);
            at += count;
        }
        grid.items.resize(keys.len(), 0);
        for (i, &k) in keys.iter().enumerate() {
            let range = cells.get_mut(&k).expect("counted above");
            grid.items[range.1 as usize] = i as u32;
            range.1 += 1;
        }
        grid.cells = Cells::Sparse(cells);
        grid
    }

    /// The points in cell `[x, y, z]`.
    fn in_cell(&self, c: [u64; 3]) -> &[u32] {
        match &self.cells {
            Cells::Sparse(cells) => match cells.get(&pack(c[0], c[1], c[2])) {
                Some(&(s, e)) => &self.items[s as usize..e as usize],
                None => &[],
            },
            Cells::Dense { starts, dims } => {
                let at = linear(*dims, c) as usize;
                &self.items[starts[at] as usize..starts[at + 1] as usize]
            }
        }
    }

    /// The cell indices of `p`, clamped to the grid.
    fn index(&self, p: DVec3) -> [u64; 3] {
        let q = (p - self.origin) * self.inv;
        let top = AXIS_CELLS - 1.0;
        // Truncation is the floor once clamped to non-negative (and cheaper than `floor`).
        [q.x, q.y, q.z].map(|c| c.clamp(0.0, top) as u64)
    }

    /// Calls `near` for every point that may lie within `grow` of the segment `a`–`b`: every
    /// point within that distance is passed, at least once, and others may be (a point can
    /// come more than once).
    pub(super) fn near_segment(&self, a: DVec3, b: DVec3, grow: f64, mut near: impl FnMut(u32)) {
        let d = b - a;
        let len = d.length();
        // Pieces a cell long (shorter ones cost more in cells than they save in points); a cell
        // met again by the next piece is skipped.
        let pieces = (PIECES_PER_CELL * len / self.cell).ceil().max(1.0);
        // The pieces' ends are computed, so each piece's box is padded by their rounding.
        let pad = grow + 1e-12 * (len + a.abs().max_element() + b.abs().max_element());
        // A reach wider than half a cell (a wide weld's, among small edges) would make each
        // piece ask many cells: the tree instead.
        if pieces > MOST_PIECES || !pieces.is_finite() || !pad.is_finite() || 2.0 * pad > self.cell
        {
            let tree = self.tree.get_or_init(|| {
                let boxes: Vec<Aabb> = self.spots.iter().map(|&p| Aabb::new(p, p)).collect();
                Bvh::build(&boxes)
            });
            let bounds = Aabb::new(a.min(b) - grow, a.max(b) + grow);
            tree.visit(
                |b| b.overlaps(&bounds, 0.0),
                |i| {
                    near(i);
                    false
                },
            );
            return;
        }
        let n = pieces as usize;
        let mut from = a;
        let mut seen: smallvec::SmallVec<[u64; 16]> = smallvec::SmallVec::new();
        // A dense grid's cells end at `dims`; a sparse one's at the clamp.
        let last = match &self.cells {
            Cells::Sparse(_) => [u64::MAX; 3],
            Cells::Dense { dims, .. } => dims.map(|d| d - 1),
        };
        for k in 0..n {
            let to = if k + 1 == n {
                b
            } else {
                a + d * ((k + 1) as f64 / pieces)
            };
            let [x0, y0, z0] = self.index(from.min(to) - pad);
            let [x1, y1, z1] = self.index(from.max(to) + pad);
            let [x1, y1, z1] = [x1.min(last[0]), y1.min(last[1]), z1.min(last[2])];
            for x in x0..=x1 {
                for y in y0..=y1 {
                    for z in z0..=z1 {
                        // One piece meets each cell once; only a run of pieces meets one again.
                        if n > 1 {
                            let key = pack(x, y, z);
                            if seen.iter().rev().take(27).any(|&k| k == key) {
                                continue;
                            }
                            seen.push(key);
                        }
                        for &i in self.in_cell([x, y, z]) {
                            near(i);
                        }
                    }
                }
            }
            from = to;
        }
    }
}

/// The dense grid's index of cell `[x, y, z]` (each below `dims`).
fn linear(dims: [u64; 3], [x, y, z]: [u64; 3]) -> u64 {
    (x * dims[1] + y) * dims[2] + z
}

/// A sparse grid's key of cell `(x, y, z)` (each below [`AXIS_CELLS`]).
fn pack(x: u64, y: u64, z: u64) -> u64 {
    x << 42 | y << 21 | z
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use glam::DVec3;

    use super::{Cells, Grid};
    use crate::hash::test_support::lcg;

    /// The least time of a few builds of the grid of `spots` (cells `cell` wide).
    fn build_time(spots: &[DVec3], cell: f64) -> Duration {
        (0..3)
            .map(|_| {
                let start = Instant::now();
                let grid = Grid::new(spots, cell);
                assert!(matches!(grid.cells, Cells::Sparse(_)));
                start.elapsed()
            })
            .min()
            .unwrap()
    }

    /// Numbers in [0, 1) from a linear congruential generator seeded with `seed`.
    fn unit_numbers(seed: u64) -> impl FnMut() -> f64 {
        let mut next = lcg(seed);
        move || (next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Points on one plane of constant `z` (an extrusion's caps) build a sparse grid as fast
    /// as points spread in `z`: with an unkeyed multiply hash their cell keys shared one
    /// bucket, and building the grid of 60,000 took 1.6 s against 1.1 ms.
    #[test]
    fn a_sparse_grid_of_points_on_one_plane_builds_as_fast_as_a_spread_one() {
        let mut next = unit_numbers(99);
        let n = 60_000;
        let flat: Vec<DVec3> = (0..n)
            .map(|_| DVec3::new(next(), next(), 0.0) * 100.0)
            .collect();
        let spread: Vec<DVec3> = (0..n)
            .map(|_| DVec3::new(next(), next(), next()) * 100.0)
            .collect();
        let (flat, spread) = (build_time(&flat, 0.01), build_time(&spread, 0.01));
        assert!(
            flat < 3 * spread + Duration::from_millis(20),
            "one plane {flat:?}, spread {spread:?}"
        );
    }

    /// Every point within reach of a segment is handed over, by the cells (short segments, a
    /// small reach; of a sparse grid and of a dense one) and by the tree (long segments, or a
    /// reach wider than half a cell).
    #[test]
    fn hands_over_every_point_near_a_segment() {
        let mut spots = Vec::new();
        let mut next = unit_numbers(12345);
        for _ in 0..2000 {
            spots.push(DVec3::new(next(), next(), next()) * 10.0);
        }
        // Cells 0.01 wide: a sparse grid (10⁹ cells); 0.5 wide: a dense one (8,000 cells).
        for (cell, wide, dense) in [(0.01, 0.5, false), (0.5, 0.2, true)] {
            let grid = Grid::new(&spots, cell);
            assert_eq!(matches!(grid.cells, Cells::Dense { .. }), dense);
            for _ in 0..200 {
                // Segments from inside the points' box to up to 5 beyond it.
                let a = DVec3::new(next(), next(), next()) * 10.0;
                let b = a + (DVec3::new(next(), next(), next()) - 0.5) * 10.0 * next();
                let grow = if next() < 0.5 { 0.004 } else { wide };
                let mut got = vec![false; spots.len()];
                grid.near_segment(a, b, grow, |i| got[i as usize] = true);
                for (i, &p) in spots.iter().enumerate() {
                    let d = b - a;
                    let t = ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
                    if p.distance(a + d * t) <= grow {
                        assert!(got[i], "point {i} near {a} {b} missed (cells {cell})");
                    }
                }
            }
        }
    }
}
