//! Marching cubes over a scene's field: sparse, parallel, closed at the grid's bounds.
//!
//! The grid is walked as an octree of blocks. A block whose centre value exceeds its
//! half-diagonal in magnitude cannot hold surface (every field here is 1-Lipschitz) and is
//! skipped whole; the rest are split down to leaf blocks, which are sampled densely and
//! triangulated with the generated table of [`super::mc_table`]. Top-level blocks run in
//! parallel with rayon; vertices on block boundaries are matched afterwards by their grid edge.
//!
//! Three rules keep the output a closed 2-manifold:
//! - a value `≥ 0` is outside (exact zeros included), so tangent shapes meeting at a grid
//!   vertex are kept apart consistently;
//! - the field is intersected with the grid's box and grid points on the box are outside, so a
//!   surface running into the bounds is capped there;
//! - each vertex lies strictly inside its edge (parameter clamped to `[δ, 1 − δ]`), so no two
//!   vertices coincide even where the surface passes through a grid point.

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use super::eval::{Program, Scratch};
use super::mc_table::{TABLE, edge_corners, face_corners};
use crate::error::{Error, Result};
use crate::geom::Aabb;
use crate::hash::FxHashMap;
use crate::mesh::Mesh;

/// How to bake a scene into a mesh by marching cubes.
#[derive(Clone, Debug, PartialEq)]
pub struct BakeOptions {
    /// Edge length of the grid's cubic cells. Takes precedence over `resolution`.
    pub cell: Option<f64>,
    /// Cells along the longest side of the bounds (used when `cell` is `None`); 128 when both
    /// are `None`.
    pub resolution: Option<u32>,
    /// The region to mesh. `None`: the scene's conservative bounds plus one cell on every side.
    /// A surface cut by these bounds is closed by a cap on them.
    pub bounds: Option<Aabb>,
    /// Steps of root refinement (Illinois regula falsi) per vertex after the linear guess, at
    /// most [`MAX_REFINE_STEPS`] (it converges in a handful).
    pub refine_steps: u32,
}

impl Default for BakeOptions {
    fn default() -> Self {
        BakeOptions {
            cell: None,
            resolution: None,
            bounds: None,
            refine_steps: 3,
        }
    }
}

impl BakeOptions {
    /// Options with a cell size.
    pub fn with_cell(cell: f64) -> Self {
        BakeOptions {
            cell: Some(cell),
            ..Default::default()
        }
    }

    /// Options with a resolution (cells along the longest side).
    pub fn with_resolution(resolution: u32) -> Self {
        BakeOptions {
            resolution: Some(resolution),
            ..Default::default()
        }
    }
}

/// The most cells along one axis of a grid. Work and memory grow with the surface's area in
/// cells, not with the grid's volume, but a grid this fine around a large surface still needs
/// gigabytes.
pub const MAX_GRID_CELLS: u32 = 1 << 14;

/// The most cells a grid may have in all (1024³): a large surface in a grid this fine already
/// makes tens of millions of triangles, so finer requests are refused before memory runs out.
pub const MAX_GRID_TOTAL: u64 = 1 << 30;

/// Leaf blocks are this many cells on a side; top-level blocks `LEAF << LEVELS`.
const LEAF: usize = 8;
const LEVELS: usize = 2;
/// Vertices stay this fraction of their grid edge away from its ends. Where the surface passes
/// through a grid vertex, the roots on every edge there would meet at that vertex and the
/// triangles between them would have zero area; held apart by 10⁻⁶ of a cell, they are tiny but
/// not flat, and the surface moves by no more than that.
const DELTA: f64 = 1e-6;

/// A lattice of cubic cells.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Grid {
    pub origin: DVec3,
    pub cell: f64,
    /// Cells per axis.
    pub n: [usize; 3],
}

impl Grid {
    /// The grid for a bound and options.
    pub(crate) fn new(solid_box: &Aabb, opts: &BakeOptions) -> Result<Option<Grid>> {
        if opts.refine_steps > MAX_REFINE_STEPS {
            return Err(Error::param(
                "refine_steps",
                opts.refine_steps as f64,
                "must be at most 64",
            ));
        }
        let (region, pad) = match opts.bounds {
            Some(b) => {
                if !(b.min.is_finite() && b.max.is_finite()) || b.is_empty() {
                    return Err(Error::param(
                        "bounds",
                        b.diagonal(),
                        "must be a finite, non-empty box",
                    ));
                }
                (b, false)
            }
            None => {
                if solid_box.is_empty() {
                    return Ok(None);
                }
                if !(solid_box.min.is_finite() && solid_box.max.is_finite()) {
                    return Err(Error::Scene {
                        file: None,
                        json_path: "$".into(),
                        message: "the scene is unbounded (a half-space not intersected with a \
                                  bounded shape); give BakeOptions::bounds"
                            .into(),
                    });
                }
                (*solid_box, true)
            }
        };
        let size = region.size();
        let longest = size.max_element();
        let cell = match (opts.cell, opts.resolution) {
            (Some(h), _) => {
                if !(h.is_finite() && h > 0.0) {
                    return Err(Error::param("cell", h, "must be finite and > 0"));
                }
                h
            }
            (None, r) => {
                let r = r.unwrap_or(128);
                if !(1..=MAX_GRID_CELLS).contains(&r) {
                    return Err(Error::param(
                        "resolution",
                        r as f64,
                        "must be in 1..=16384 cells",
                    ));
                }
                // The padding cells count towards the resolution.
                let inner = if pad { r.saturating_sub(2).max(1) } else { r };
                if longest > 0.0 {
                    longest / inner as f64
                } else {
                    // A degenerate (flat or point) box: any cell will do.
                    1.0
                }
            }
        };
        let mut n = [0usize; 3];
        for i in 0..3 {
            let cells = (size[i] / cell).ceil().max(1.0) + if pad { 2.0 } else { 0.0 };
            if cells.is_nan() || cells > MAX_GRID_CELLS as f64 {
                return Err(Error::param(
                    "cell",
                    cell,
                    "gives more than 16384 cells along an axis; use a larger cell",
                ));
            }
            n[i] = cells as usize;
        }
        if n.iter().map(|&c| c as u64).product::<u64>() > MAX_GRID_TOTAL {
            return Err(Error::param(
                "cell",
                cell,
                "gives more than 1024³ cells in all; use a larger cell",
            ));
        }
        let extent = DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64) * cell;
        let origin = region.center() - extent * 0.5;
        Ok(Some(Grid { origin, cell, n }))
    }

    #[inline]
    fn point(&self, i: usize, j: usize, k: usize) -> DVec3 {
        self.origin + DVec3::new(i as f64, j as f64, k as f64) * self.cell
    }

    fn bbox(&self) -> Aabb {
        Aabb::new(self.origin, self.point(self.n[0], self.n[1], self.n[2]))
    }
}

/// A block of cells `lo..hi` (per axis).
#[derive(Clone, Copy, Debug)]
struct Block {
    lo: [usize; 3],
    hi: [usize; 3],
}

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

/// One block's share of the mesh, with local vertex indices.
#[derive(Default)]
struct Part {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    /// Vertices on the block's boundary, by global edge key, to be matched with neighbours.
    shared: Vec<(u64, u32)>,
}

/// Per-thread buffers.
#[derive(Default)]
struct Work {
    scratch: Scratch,
    points: Vec<DVec3>,
    values: Vec<f64>,
    slots: Vec<u32>,
    // Root refinement state per vertex.
    a: Vec<DVec3>,
    b: Vec<DVec3>,
    /// Each vertex's grid edge (refinement narrows `a`..`b` inside it).
    edge: Vec<(DVec3, DVec3)>,
    fa: Vec<f64>,
    fb: Vec<f64>,
    side: Vec<i8>,
    probe: Vec<DVec3>,
    fprobe: Vec<f64>,
    centres: Vec<(u32, [u32; 12], u8)>,
}

/// The most root-refinement steps a bake accepts.
pub const MAX_REFINE_STEPS: u32 = 64;

/// The most triangles one bake may make (about 2 GB of mesh). Cells bound the grid's volume,
/// not its surface: a flat surface across a fine grid would otherwise exhaust memory.
pub const MAX_BAKE_TRIANGLES: usize = 1 << 25;

/// Bakes `program` over `grid` into a mesh (sources all 0; the caller assigns materials).
/// Refused once the surface needs more than [`MAX_BAKE_TRIANGLES`] triangles.
pub(crate) fn march<S: Source + ?Sized>(
    source: &S,
    grid: Grid,
    refine_steps: u32,
) -> crate::Result<Mesh> {
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
                    leaf(&field, &b, refine_steps, work, &mut part);
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
            "makes more than 33554432 triangles on this surface; use a larger cell",
        ));
    }
    Ok(merge(parts))
}

fn cannot_hold_surface<S: Source + ?Sized>(
    field: &Field<S>,
    scratch: &mut Scratch,
    b: &Block,
) -> bool {
    let g = &field.grid;
    let lo = g.point(b.lo[0], b.lo[1], b.lo[2]);
    let hi = g.point(b.hi[0], b.hi[1], b.hi[2]);
    let c = (lo + hi) * 0.5;
    let r = (hi - lo).length() * 0.5;
    // A margin for rounding in the field and in the corner coordinates.
    field.eval(scratch, c).abs() > r * (1.0 + 1e-9) + 1e-12 * (g.cell + c.abs().max_element())
}

fn split(b: &Block, stack: &mut Vec<Block>) {
    let mid = [0, 1, 2].map(|i| b.lo[i] + (b.hi[i] - b.lo[i]).div_ceil(2));
    for o in 0..8 {
        let mut c = *b;
        for (i, &m) in mid.iter().enumerate() {
            if o >> i & 1 == 0 {
                c.hi[i] = m;
            } else {
                c.lo[i] = m;
            }
        }
        if (0..3).all(|i| c.lo[i] < c.hi[i]) {
            stack.push(c);
        }
    }
}

/// Samples one leaf block and appends its triangles to `part`.
fn leaf<S: Source + ?Sized>(
    field: &Field<S>,
    b: &Block,
    refine_steps: u32,
    w: &mut Work,
    part: &mut Part,
) {
    let g = &field.grid;
    let d = [0, 1, 2].map(|i| b.hi[i] - b.lo[i]);
    let (px, py, pz) = (d[0] + 1, d[1] + 1, d[2] + 1);
    let npts = px * py * pz;
    w.points.clear();
    for k in 0..pz {
        for j in 0..py {
            for i in 0..px {
                w.points
                    .push(g.point(b.lo[0] + i, b.lo[1] + j, b.lo[2] + k));
            }
        }
    }
    w.values.resize(npts, 0.0);
    field.eval_batch(&mut w.scratch, &w.points, &mut w.values);
    // Grid points on the grid's box are outside, whatever rounding says: this closes surfaces
    // that run into the bounds.
    for k in 0..pz {
        for j in 0..py {
            for i in 0..px {
                let (gi, gj, gk) = (b.lo[0] + i, b.lo[1] + j, b.lo[2] + k);
                if gi == 0 || gj == 0 || gk == 0 || gi == g.n[0] || gj == g.n[1] || gk == g.n[2] {
                    let v = &mut w.values[(k * py + j) * px + i];
                    *v = v.max(0.0);
                }
            }
        }
    }
    let idx = |i: usize, j: usize, k: usize| (k * py + j) * px + i;
    w.slots.clear();
    w.slots.resize(npts * 3, u32::MAX);
    let base = part.positions.len() as u32;
    let first_tri = part.triangles.len();
    w.a.clear();
    w.b.clear();
    w.edge.clear();
    w.fa.clear();
    w.fb.clear();
    w.centres.clear();
    let table = &*TABLE;
    let (gx, gy) = ((g.n[0] + 1) as u64, (g.n[1] + 1) as u64);
    for k in 0..d[2] {
        for j in 0..d[1] {
            for i in 0..d[0] {
                let mut vals = [0.0; 8];
                let mut config = 0usize;
                for (c, v) in vals.iter_mut().enumerate() {
                    *v = w.values[idx(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2))];
                    if *v < 0.0 {
                        config |= 1 << c;
                    }
                }
                if config == 0 || config == 255 {
                    continue;
                }
                let mut decisions = 0usize;
                let amb = table.ambiguous[config];
                if amb != 0 {
                    for f in 0..6 {
                        if amb >> f & 1 == 1
                            && super::mc_table::face_connects(face_corners(f).map(|c| vals[c]))
                        {
                            decisions |= 1 << f;
                        }
                    }
                }
                let case = &table.cases[config | decisions << 8];
                let mut edge_vertex = [u32::MAX; 12];
                let mut vertex_of = |e: usize, w: &mut Work, part: &mut Part| -> u32 {
                    if edge_vertex[e] != u32::MAX {
                        return edge_vertex[e];
                    }
                    let axis = e / 4;
                    let (c0, c1) = edge_corners(e);
                    let (li, lj, lk) = (i + (c0 & 1), j + (c0 >> 1 & 1), k + (c0 >> 2));
                    let slot = idx(li, lj, lk) * 3 + axis;
                    let mut v = w.slots[slot];
                    if v == u32::MAX {
                        v = base + w.a.len() as u32;
                        w.slots[slot] = v;
                        let (p0, p1) = (w.points[idx(li, lj, lk)], {
                            let q = super::mc_table::corner_pos(c1);
                            w.points[idx(i + q[0], j + q[1], k + q[2])]
                        });
                        let (v0, v1) = (vals[c0], vals[c1]);
                        // Keep the bracket as (inside, outside).
                        if v0 < 0.0 {
                            w.a.push(p0);
                            w.fa.push(v0);
                            w.b.push(p1);
                            w.fb.push(v1);
                            w.edge.push((p0, p1));
                        } else {
                            w.a.push(p1);
                            w.fa.push(v1);
                            w.b.push(p0);
                            w.fb.push(v0);
                            w.edge.push((p0, p1));
                        }
                        let on_boundary = (0..3).filter(|&x| x != axis).any(|x| {
                            let l = [li, lj, lk][x];
                            l == 0 || l == d[x]
                        });
                        if on_boundary {
                            let (gi, gj, gk) = (
                                (b.lo[0] + li) as u64,
                                (b.lo[1] + lj) as u64,
                                (b.lo[2] + lk) as u64,
                            );
                            let key = ((gk * gy + gj) * gx + gi) * 3 + axis as u64;
                            part.shared.push((key, v));
                        }
                    }
                    edge_vertex[e] = v;
                    v
                };
                let mut centre_ids = [u32::MAX; 4];
                for (ci, lp) in case.centres.iter().enumerate() {
                    let mut ids = [0u32; 12];
                    for (x, &e) in lp.iter().enumerate() {
                        ids[x] = vertex_of(e as usize, w, part);
                    }
                    // Centre vertices are numbered after all edge vertices of the block.
                    centre_ids[ci.min(3)] = w.centres.len() as u32 | 0x8000_0000;
                    w.centres.push((0, ids, lp.len() as u8));
                }
                for t in &case.tris {
                    let tri = t.map(|c| {
                        if c < 12 {
                            vertex_of(c as usize, w, part)
                        } else {
                            centre_ids[(c - 12).min(3) as usize]
                        }
                    });
                    part.triangles.push(tri);
                }
            }
        }
    }
    refine(field, refine_steps, w);
    for (i, &(e0, e1)) in w.edge.iter().enumerate() {
        let (a, b, fa, fb) = (w.a[i], w.b[i], w.fa[i], w.fb[i]);
        let t = fa / (fa - fb);
        let t = if t.is_finite() {
            t.clamp(0.0, 1.0)
        } else {
            0.5
        };
        let root = a + (b - a) * t;
        // Where along the grid edge (axis-aligned, so one coordinate moves), held off its ends.
        let axis = (e1 - e0).abs().max_position();
        let s = ((root[axis] - e0[axis]) / (e1[axis] - e0[axis])).clamp(DELTA, 1.0 - DELTA);
        part.positions.push(e0 + (e1 - e0) * s);
    }
    let centre_base = part.positions.len() as u32;
    for c in &w.centres {
        let n = c.2 as usize;
        let sum: DVec3 = c.1[..n].iter().map(|&v| part.positions[v as usize]).sum();
        part.positions.push(sum / n as f64);
    }
    for t in &mut part.triangles[first_tri..] {
        for v in t.iter_mut() {
            if *v & 0x8000_0000 != 0 {
                *v = centre_base + (*v & 0x7fff_ffff);
            }
        }
    }
}

/// Illinois regula falsi on every bracket at once: each step evaluates one probe per vertex.
fn refine<S: Source + ?Sized>(field: &Field<S>, steps: u32, w: &mut Work) {
    let n = w.a.len();
    w.side.clear();
    w.side.resize(n, 0);
    for _ in 0..steps {
        w.probe.clear();
        for i in 0..n {
            let t = w.fa[i] / (w.fa[i] - w.fb[i]);
            let t = if t.is_finite() {
                t.clamp(0.0, 1.0)
            } else {
                0.5
            };
            w.probe.push(w.a[i] + (w.b[i] - w.a[i]) * t);
        }
        w.fprobe.resize(n, 0.0);
        field.eval_batch(&mut w.scratch, &w.probe, &mut w.fprobe);
        for i in 0..n {
            let (p, f) = (w.probe[i], w.fprobe[i]);
            if f < 0.0 {
                w.a[i] = p;
                w.fa[i] = f;
                // The outside end stayed twice: halve its weight (Illinois).
                if w.side[i] == -1 {
                    w.fb[i] *= 0.5;
                }
                w.side[i] = -1;
            } else {
                w.b[i] = p;
                w.fb[i] = f;
                if w.side[i] == 1 {
                    w.fa[i] *= 0.5;
                }
                w.side[i] = 1;
            }
        }
    }
}

/// Joins the blocks' parts, matching boundary vertices by grid edge.
fn merge(parts: Vec<Part>) -> Mesh {
    let nv: usize = parts.iter().map(|p| p.positions.len()).sum();
    let nt: usize = parts.iter().map(|p| p.triangles.len()).sum();
    let ns: usize = parts.iter().map(|p| p.shared.len()).sum();
    let mut seen: FxHashMap<u64, u32> =
        FxHashMap::with_capacity_and_hasher(ns / 2 + 1, Default::default());
    let mut positions = Vec::with_capacity(nv);
    let mut triangles = Vec::with_capacity(nt);
    let mut remap: Vec<u32> = Vec::new();
    for part in parts {
        remap.clear();
        remap.resize(part.positions.len(), u32::MAX);
        // Boundary vertices first: the first block to reach a grid edge owns its vertex, also
        // among the leaf blocks of one part.
        for &(key, local) in &part.shared {
            let g = *seen.entry(key).or_insert_with(|| {
                positions.push(part.positions[local as usize]);
                (positions.len() - 1) as u32
            });
            remap[local as usize] = g;
        }
        for (i, &p) in part.positions.iter().enumerate() {
            if remap[i] == u32::MAX {
                remap[i] = positions.len() as u32;
                positions.push(p);
            }
        }
        triangles.extend(part.triangles.iter().map(|t| t.map(|v| remap[v as usize])));
    }
    Mesh::new(positions, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::HashMap;

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
            let grid = Grid { origin: DVec3::ZERO, cell: 1.0, n };
            let mesh = march(&lattice, grid, 2).unwrap();
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
            let mesh = march(
                &lattice,
                Grid {
                    origin: DVec3::ZERO,
                    cell: 1.0,
                    n: [3, 3, 3],
                },
                1,
            )
            .unwrap();
            assert!(
                check_closed(&mesh).is_ok(),
                "{config}: {:?}",
                check_closed(&mesh)
            );
        }
    }
}
