//! The weld's grid pass: each distinct position, in order, joins the first earlier
//! representative within reach, or becomes one. [`serial`] walks every position;
//! [`lone_apart`] first marks, in parallel, the positions no other lies near, and walks only the
//! rest, with the same result bit for bit.

use std::hash::{BuildHasher, Hasher};
use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::{Wide, cell_of};
use crate::hash::{KeyedBuild, KeyedHashMap};

/// Representatives by grid cell. Cells are much larger than any reach: a representative within
/// reach of a point lies in the point's own cell, or in a neighbour only where the point is
/// within reach of that side.
pub(super) struct Grid {
    cells: KeyedHashMap<[i64; 3], SmallVec<[u32; 2]>>,
    reps: Vec<DVec3>,
    reach: Vec<f64>,
    cell_size: f64,
    widest: f64,
}

impl Grid {
    /// Cells of side `cell_size`, for points whose reach is at most `widest`.
    fn new(capacity: usize, cell_size: f64, widest: f64) -> Self {
        Grid {
            cells: KeyedHashMap::with_capacity_and_hasher(capacity, KeyedBuild::default()),
            reps: Vec::with_capacity(capacity),
            reach: Vec::with_capacity(capacity),
            cell_size,
            widest,
        }
    }

    /// The first representative within the larger of `reach` and its own reach of `p` (whose
    /// cell is `c`), or `p` as a new one: its index, and whether it is new. It looks only at
    /// `c` and cells one step from `c` on each axis.
    #[inline]
    fn join(&mut self, p: DVec3, c: [i64; 3], reach: f64) -> (u32, bool) {
        let (cell_size, widest) = (self.cell_size, self.widest);
        // Per axis, the neighbour offsets worth looking at.
        let offsets = |k: usize| -> SmallVec<[i64; 3]> {
            let lo = c[k] as f64 * cell_size;
            let mut o: SmallVec<[i64; 3]> = smallvec::smallvec![0];
            if p[k] - lo <= widest {
                o.push(-1);
            }
            if lo + cell_size - p[k] <= widest {
                o.push(1);
            }
            o
        };
        let (ox, oy, oz) = (offsets(0), offsets(1), offsets(2));
        for &dx in &ox {
            for &dy in &oy {
                for &dz in &oz {
                    let k = [
                        c[0].saturating_add(dx),
                        c[1].saturating_add(dy),
                        c[2].saturating_add(dz),
                    ];
                    if let Some(list) = self.cells.get(&k)
                        && let Some(&r) = list.iter().find(|&&r| {
                            self.reps[r as usize].distance(p) <= reach.max(self.reach[r as usize])
                        })
                    {
                        return (r, false);
                    }
                }
            }
        }
        self.reps.push(p);
        self.reach.push(reach);
        let r = (self.reps.len() - 1) as u32;
        self.cells.entry(c).or_default().push(r);
        (r, true)
    }
}

/// The representatives of `positions` (distinct) and each position's representative, reach
/// `wide.reach(p, delta)` at most `widest`, in cells of `64 · widest`.
pub(super) fn serial(positions: &[DVec3], delta: f64, wide: &Wide) -> (Vec<DVec3>, Vec<u32>) {
    let widest = wide.widest(delta);
    let cell_size = 64.0 * widest;
    let mut grid = Grid::new(positions.len(), cell_size, widest);
    let rep_of = positions
        .iter()
        .map(|&p| grid.join(p, cell_of(p, cell_size), wide.reach(p, delta)).0)
        .collect();
    (grid.reps, rep_of)
}

/// Blocks of `2^BLOCK_SHIFT` cells a side, for the test of lone positions.
const BLOCK_SHIFT: u32 = 4;

/// Positions per chunk of the numbering's prefix count.
const CHUNK: usize = 1 << 12;

/// [`serial`], bit for bit, with most of the work in parallel. A position is *lone* when no
/// other position's cell is within one step of its own on every axis. A lone position finds no
/// representative (it looks only at such cells), and no other position ever looks at its cell
/// (a cell one step from another's is one step from it), so it is a representative and changes
/// no other position's outcome. The serial walk runs over the rest only, in order; the
/// representatives are then numbered in position order by a prefix count.
///
/// The test is on integers: each position marks a 2-bit count (none, one, more) in a table slot
/// hashed from its block of cells; a position is lone when its block's slot counts one and the
/// slots of the other blocks its neighbouring cells touch count none. A slot shared by two
/// blocks only makes a position wrongly not lone, which costs time and changes no result.
///
/// The walk over the rest is split into up to `parts` parts (see [`parts_apart`]) that run in
/// parallel, each in order.
pub(super) fn lone_apart(
    positions: &[DVec3],
    delta: f64,
    wide: &Wide,
    parts: usize,
) -> (Vec<DVec3>, Vec<u32>) {
    let widest = wide.widest(delta);
    let cell_size = 64.0 * widest;
    let n = positions.len();
    let cells: Vec<[i64; 3]> = positions
        .par_iter()
        .map(|&p| cell_of(p, cell_size))
        .collect();
    let lone = lone_cells(&cells, &KeyedBuild::default());
    let rest: Vec<u32> = (0..n as u32)
        .into_par_iter()
        .filter(|&i| !lone[i as usize])
        .collect();
    let reach: Vec<f64> = rest
        .par_iter()
        .map(|&i| wide.reach(positions[i as usize], delta))
        .collect();
    // Each position's representative, as a position index (a representative is its own). The
    // walk over the rest runs in parts that cannot reach each other, in parallel.
    let mut rep_at: Vec<u32> = (0..n as u32).into_par_iter().collect();
    let walk = |part: &[u32]| -> Vec<u32> {
        let mut grid = Grid::new(part.len(), cell_size, widest);
        let mut rep_position: Vec<u32> = Vec::with_capacity(part.len());
        let joined = part.iter().map(|&j| {
            let i = rest[j as usize];
            let (k, new) = grid.join(positions[i as usize], cells[i as usize], reach[j as usize]);
            if new {
                rep_position.push(i);
            }
            rep_position[k as usize]
        });
        joined.collect()
    };
    let parts = parts_apart(&cells, &rest, parts);
    let reps_of_parts: Vec<Vec<u32>> = parts.par_iter().map(|part| walk(part)).collect();
    for (part, reps) in parts.iter().zip(&reps_of_parts) {
        for (&j, &r) in part.iter().zip(reps) {
            rep_at[rest[j as usize] as usize] = r;
        }
    }
    // Representatives numbered in position order: per chunk, the count before it.
    let is_rep = |chunk: usize, j: usize, r: u32| r as usize == chunk * CHUNK + j;
    let counts: Vec<u32> = rep_at
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(c, rs)| {
            let reps = rs.iter().enumerate().filter(|&(j, &r)| is_rep(c, j, r));
            reps.count() as u32
        })
        .collect();
    let starts: Vec<u32> = counts
        .iter()
        .scan(0u32, |s, &c| {
            let start = *s;
            *s += c;
            Some(start)
        })
        .collect();
    let mut number = vec![0u32; n];
    number
        .par_chunks_mut(CHUNK)
        .zip(rep_at.par_chunks(CHUNK))
        .enumerate()
        .for_each(|(c, (out, rs))| {
            let mut next = starts[c];
            for (j, (o, &r)) in out.iter_mut().zip(rs).enumerate() {
                *o = next;
                next += u32::from(is_rep(c, j, r));
            }
        });
    let reps = positions
        .par_iter()
        .zip(&rep_at)
        .enumerate()
        .filter(|&(i, (_, &r))| r as usize == i)
        .map(|(_, (&p, _))| p)
        .collect();
    let rep_of = rep_at.par_iter().map(|&r| number[r as usize]).collect();
    (reps, rep_of)
}

/// From this many positions that are not lone, their walk is split into parts.
const PARTS_FROM: usize = 1 << 10;

/// The positions `rest` (indices into `cells`, in order) in up to `parts` parts that cannot
/// reach each other, as indices into `rest`, each part in order: split at cell coordinates of
/// one axis that no position of `rest` occupies, nearest equal counts. A position looks only at
/// cells one step from its own, so positions on either side of an empty cell coordinate never
/// meet, and each part's walk on its own gives what the walk over all of `rest` gives. One part
/// below [`PARTS_FROM`] positions, or where no axis has such a coordinate.
fn parts_apart(cells: &[[i64; 3]], rest: &[u32], parts: usize) -> Vec<Vec<u32>> {
    let all = || vec![(0..rest.len() as u32).collect()];
    if parts < 2 || rest.len() < PARTS_FROM {
        return all();
    }
    for axis in [0, 1, 2] {
        let mut xs: Vec<i64> = rest.iter().map(|&i| cells[i as usize][axis]).collect();
        xs.sort_unstable();
        // Coordinates no position has: one more than a coordinate followed by a gap, the one
        // nearest each quantile.
        let gap_after = |j: usize| i128::from(xs[j + 1]) - i128::from(xs[j]) >= 2;
        let mut cuts: Vec<i64> = (1..parts)
            .filter_map(|q| {
                let m = xs.len() * q / parts;
                let up = (m..xs.len() - 1).find(|&j| gap_after(j));
                let down = (0..m.min(xs.len() - 1)).rev().find(|&j| gap_after(j));
                let nearest = match (down, up) {
                    (Some(d), Some(u)) => Some(if m - d <= u - m { d } else { u }),
                    (d, u) => d.or(u),
                };
                nearest.map(|j| xs[j] + 1)
            })
            .collect();
        cuts.sort_unstable();
        cuts.dedup();
        if cuts.is_empty() {
            continue;
        }
        let mut out: Vec<Vec<u32>> = vec![Vec::new(); cuts.len() + 1];
        for (j, &i) in rest.iter().enumerate() {
            let x = cells[i as usize][axis];
            out[cuts.partition_point(|&c| c < x)].push(j as u32);
        }
        return out;
    }
    all()
}

/// Per cell of `cells` (one per distinct position, repeats allowed): whether it is the only one
/// within one step of it on every axis, tested through blocks hashed by `hasher` (see
/// [`lone_apart`]: keyed per process, since the cells come from input; the tests pass a fixed
/// hasher, so which cells share a slot is the same in every run).
fn lone_cells(cells: &[[i64; 3]], hasher: &(impl BuildHasher + Sync)) -> Vec<bool> {
    // Two bits per slot, at least 32 slots per cell: few slots are shared.
    let bits = (cells.len().max(1) * 32)
        .next_power_of_two()
        .trailing_zeros();
    let table: Vec<AtomicU64> = (0..(1usize << bits) / 32)
        .into_par_iter()
        .map(|_| AtomicU64::new(0))
        .collect();
    let slot = |b: [i64; 3]| -> (usize, u32) {
        let mut h = hasher.build_hasher();
        b.iter().for_each(|&x| h.write_u64(x as u64));
        let s = (h.finish() >> (64 - bits)) as usize;
        (s / 32, 2 * (s % 32) as u32)
    };
    let block = |c: [i64; 3]| c.map(|x| x >> BLOCK_SHIFT);
    cells.par_iter().for_each(|&c| {
        let (w, shift) = slot(block(c));
        let once = 1u64 << shift;
        let seen = table[w].fetch_or(once, Ordering::Relaxed);
        if seen & once != 0 {
            table[w].fetch_or(once << 1, Ordering::Relaxed);
        }
    });
    let count = |b: [i64; 3]| {
        let (w, shift) = slot(b);
        (table[w].load(Ordering::Relaxed) >> shift) & 3
    };
    cells
        .par_iter()
        .map(|&c| {
            let own = block(c);
            // Per axis, the blocks of the cells one step either side (one or two blocks).
            let lo = c.map(|x| x.saturating_sub(1) >> BLOCK_SHIFT);
            let hi = c.map(|x| x.saturating_add(1) >> BLOCK_SHIFT);
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        let b = [x, y, z];
                        if count(b) != u64::from(b == own) {
                            return false;
                        }
                    }
                }
            }
            true
        })
        .collect()
}

#[cfg(test)]
mod tests;
