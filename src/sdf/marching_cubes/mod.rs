//! Marching cubes over a scene's field: sparse, parallel, closed at the grid's bounds.
//!
//! The grid is walked as an octree of blocks. A block whose centre value exceeds its
//! half-diagonal in magnitude cannot hold surface (every field here is 1-Lipschitz) and is
//! skipped whole; the rest are split down to leaf blocks, which are sampled densely and
//! triangulated with the generated table of `table.rs`. Top-level blocks run in
//! parallel with rayon; vertices on block boundaries are matched afterwards by their grid edge.
//!
//! Three rules keep the output a closed 2-manifold:
//! - a value `≥ 0` is outside (exact zeros included), so tangent shapes meeting at a grid
//!   vertex are kept apart consistently;
//! - the field is intersected with the grid's box and grid points on the box are outside, so a
//!   surface running into the bounds is capped there;
//! - each vertex lies strictly inside its edge (parameter clamped to `[δ, 1 − δ]`), so no two
//!   vertices coincide even where the surface passes through a grid point.

mod cull;
mod grid;
mod leaf;
mod merge;
mod options;
mod refine;
mod table;

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

pub(crate) use grid::{Grid, Lattice};
pub use options::{
    BakeOptions, MAX_BAKE_TRIANGLES, MAX_GRID_CELLS, MAX_GRID_TOTAL, MAX_REFINE_STEPS,
};
pub(crate) use refine::Refine;

use super::eval::{Program, Scratch};
use crate::error::{Error, Result};
use crate::mesh::Mesh;
use cull::{Block, cannot_hold_surface, split};
use leaf::{Part, Work, leaf};
use merge::merge;

/// Leaf blocks are this many cells on a side; top-level blocks `LEAF << LEVELS`.
const LEAF: usize = 8;
const LEVELS: usize = 2;
/// Vertices stay this fraction of their grid edge away from its ends. Where the surface passes
/// through a grid vertex, the roots on every edge there would meet at that vertex and the
/// triangles between them would have zero area; held apart by 10⁻⁶ of a cell, they are tiny but
/// not flat, and the surface moves by no more than that.
const DELTA: f64 = 1e-6;

/// What marching cubes samples: anything that evaluates points in batches.
pub(crate) trait Source: Sync {
    fn eval(&self, scratch: &mut Scratch, p: DVec3) -> f64 {
        let mut out = [0.0];
        self.eval_batch(scratch, &[p], &mut out);
        out[0]
    }
    fn eval_batch(&self, scratch: &mut Scratch, points: &[DVec3], out: &mut [f64]);
}

impl Source for Program {
    fn eval(&self, _: &mut Scratch, p: DVec3) -> f64 {
        Program::eval(self, p)
    }
    fn eval_batch(&self, scratch: &mut Scratch, points: &[DVec3], out: &mut [f64]) {
        Program::eval_batch(self, scratch, points, out);
    }
}

/// The field marched: the source intersected with the grid's box.
struct Field<'a, S: Source + ?Sized> {
    source: &'a S,
    grid: Grid,
    center: DVec3,
    half: DVec3,
}

impl<S: Source + ?Sized> Field<'_, S> {
    #[inline]
    fn clip(&self, p: DVec3, d: f64) -> f64 {
        let q = (p - self.center).abs() - self.half;
        let b = q.max(DVec3::ZERO).length() + q.max_element().min(0.0);
        d.max(b)
    }

    fn eval(&self, scratch: &mut Scratch, p: DVec3) -> f64 {
        self.clip(p, self.source.eval(scratch, p))
    }

    fn eval_batch(&self, scratch: &mut Scratch, points: &[DVec3], out: &mut [f64]) {
        self.source.eval_batch(scratch, points, out);
        for (o, &p) in out.iter_mut().zip(points) {
            *o = self.clip(p, *o);
        }
    }
}

/// Bakes `program` over `grid` into a mesh (sources all 0; the caller assigns materials).
/// Refused once the surface needs more than [`MAX_BAKE_TRIANGLES`] triangles.
pub(crate) fn march<S: Source + ?Sized>(source: &S, grid: Grid, refine: Refine) -> Result<Mesh> {
    let bbox = grid.bbox();
    let field = Field {
        source,
        grid,
        center: bbox.center(),
        half: bbox.size() * 0.5,
    };
    // Coarse levels are culled here, sequentially (a few hundred evaluations at most), so a
    // huge grid around a small shape never lists its empty blocks; the surviving top-level
    // blocks then run in parallel.
    let top = LEAF << LEVELS;
    let mut tops = Vec::new();
    let mut frontier = vec![Block {
        lo: [0; 3],
        hi: grid.n,
    }];
    let mut scratch = Scratch::default();
    while let Some(b) = frontier.pop() {
        if cannot_hold_surface(&field, &mut scratch, &b) {
            continue;
        }
        if (0..3).all(|i| b.hi[i] - b.lo[i] <= top) {
            tops.push(b);
        } else {
            split(&b, &mut frontier);
        }
    }
    // Deterministic output order whatever the traversal.
    tops.sort_unstable_by_key(|b| (b.lo[2], b.lo[1], b.lo[0]));
    let made = AtomicUsize::new(0);
    let parts: Vec<Part> = tops
        .par_iter()
        .map_init(Work::default, |work, &b| {
            let mut part = Part::default();
            let mut stack = vec![b];
            while let Some(b) = stack.pop() {
                if made.load(Ordering::Relaxed) > MAX_BAKE_TRIANGLES {
                    break;
                }
                if cannot_hold_surface(&field, &mut work.scratch, &b) {
                    continue;
                }
                let size = (0..3).map(|i| b.hi[i] - b.lo[i]).max().unwrap_or(0);
                if size > LEAF {
                    split(&b, &mut stack);
                } else {
                    let before = part.triangles.len();
                    leaf(&field, &b, refine, work, &mut part);
                    made.fetch_add(part.triangles.len() - before, Ordering::Relaxed);
                }
            }
            part
        })
        .collect();
    if made.load(Ordering::Relaxed) > MAX_BAKE_TRIANGLES {
        return Err(Error::param(
            "cell",
            grid.cell,
            format!(
                "makes more than {MAX_BAKE_TRIANGLES} triangles on this surface; use a larger cell"
            ),
        ));
    }
    Ok(merge(parts))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::HashMap;

    /// The grid of unit cells from the origin, `n` cells along each axis.
    fn unit_grid(n: [usize; 3]) -> Grid {
        let extent = DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64);
        Grid {
            anchor: DVec3::ZERO,
            first: [0; 3],
            cell: 1.0,
            n,
            hair: crate::geom::MAX_MOVE * extent.length(),
        }
    }

    /// Trilinear interpolation of values at the lattice points of a unit-cell grid.
    struct Lattice {
        n: [usize; 3],
        values: Vec<f64>,
    }

    impl Lattice {
        fn at(&self, i: usize, j: usize, k: usize) -> f64 {
            self.values[(k * (self.n[1] + 1) + j) * (self.n[0] + 1) + i]
        }
    }

    impl Source for Lattice {
        fn eval_batch(&self, _: &mut Scratch, points: &[DVec3], out: &mut [f64]) {
            for (o, p) in out.iter_mut().zip(points) {
                let c = [p.x, p.y, p.z];
                let mut i = [0usize; 3];
                let mut t = [0.0; 3];
                for a in 0..3 {
                    let x = c[a].clamp(0.0, self.n[a] as f64);
                    i[a] = (x.floor() as usize).min(self.n[a].saturating_sub(1));
                    t[a] = x - i[a] as f64;
                }
                let mut v = 0.0;
                for corner in 0..8 {
                    let (dx, dy, dz) = (corner & 1, corner >> 1 & 1, corner >> 2 & 1);
                    let w = (if dx == 1 { t[0] } else { 1.0 - t[0] })
                        * (if dy == 1 { t[1] } else { 1.0 - t[1] })
                        * (if dz == 1 { t[2] } else { 1.0 - t[2] });
                    if w != 0.0 {
                        v += w * self.at(i[0] + dx, i[1] + dy, i[2] + dz);
                    }
                }
                *o = v;
            }
        }
    }

    /// A closed 2-manifold by the crate's report (which also counts zero-area triangles), with
    /// distinct vertices at distinct positions (vertices stay inside their edges).
    fn check_closed(mesh: &Mesh) -> std::result::Result<(), String> {
        let report = mesh.report();
        if !report.is_closed_manifold() {
            return Err(report.to_string());
        }
        let mut pos: HashMap<[u64; 3], u32> = HashMap::new();
        for (i, p) in mesh.positions.iter().enumerate() {
            if let Some(j) = pos.insert(p.to_array().map(f64::to_bits), i as u32) {
                return Err(format!("vertices {i} and {j} coincide"));
            }
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn random_lattices_give_closed_oriented_manifolds(
            nx in 1usize..20, ny in 1usize..12, nz in 1usize..12,
            seed in any::<u64>(), zeros in 0u32..4,
        ) {
            let n = [nx, ny, nz];
            let count = (nx + 1) * (ny + 1) * (nz + 1);
            let mut state = seed | 1;
            let values = (0..count)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    let r = (state >> 11) as f64 / (1u64 << 53) as f64;
                    // Exact zeros sometimes, to exercise the sign convention.
                    if (state & 7) < zeros as u64 { 0.0 } else { 0.2 * r - 0.1 }
                })
                .collect();
            let lattice = Lattice { n, values };
            let grid = unit_grid(n);
            let mesh = march(&lattice, grid, Refine::Steps(2)).unwrap();
            prop_assert!(check_closed(&mesh).is_ok(), "{:?}", check_closed(&mesh));
            // Positive volume: outward orientation.
            if !mesh.is_empty() {
                prop_assert!(mesh.volume() > 0.0);
            }
        }
    }

    #[test]
    fn saddle_faces_and_exact_zeros() {
        // Every config of one cube, corner values ±1 or 0: closed in each case.
        for config in 0..6561u32 {
            let mut c = config;
            let values: Vec<f64> = (0..8)
                .map(|_| {
                    let v = [-0.1, 0.0, 0.1][(c % 3) as usize];
                    c /= 3;
                    v
                })
                .collect();
            let lattice = Lattice {
                n: [1, 1, 1],
                values,
            };
            // Pad by embedding in a 3³ grid whose border is outside.
            let mut big = vec![0.1; 64];
            for k in 0..2 {
                for j in 0..2 {
                    for i in 0..2 {
                        big[((k + 1) * 4 + j + 1) * 4 + i + 1] = lattice.at(i, j, k);
                    }
                }
            }
            let lattice = Lattice {
                n: [3, 3, 3],
                values: big,
            };
            let mesh = march(&lattice, unit_grid([3, 3, 3]), Refine::Steps(1)).unwrap();
            assert!(
                check_closed(&mesh).is_ok(),
                "{config}: {:?}",
                check_closed(&mesh)
            );
        }
    }
}
