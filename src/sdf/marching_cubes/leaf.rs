//! One leaf block: sampled densely, each cell triangulated by the table, vertices placed on
//! their grid edges after root refinement.

use glam::DVec3;

use super::cull::Block;
use super::refine::{self, Refine};
use super::table::{TABLE, corner_pos, edge_corners, face_connects, face_corners};
use super::{DELTA, Field, Grid, Source};
use crate::sdf::eval::Scratch;

/// One block's share of the mesh, with local vertex indices.
#[derive(Default)]
pub(super) struct Part {
    pub(super) positions: Vec<DVec3>,
    pub(super) triangles: Vec<[u32; 3]>,
    /// Vertices on the block's boundary, by global edge key, to be matched with neighbours.
    pub(super) shared: Vec<(u64, u32)>,
}

/// Per-thread buffers.
#[derive(Default)]
pub(super) struct Work {
    pub(super) scratch: Scratch,
    pub(super) points: Vec<DVec3>,
    pub(super) values: Vec<f64>,
    pub(super) slots: Vec<u32>,
    // Root refinement state per vertex.
    pub(super) a: Vec<DVec3>,
    pub(super) b: Vec<DVec3>,
    /// Each vertex's grid edge (refinement narrows `a`..`b` inside it).
    pub(super) edge: Vec<(DVec3, DVec3)>,
    pub(super) fa: Vec<f64>,
    pub(super) fb: Vec<f64>,
    pub(super) side: Vec<i8>,
    pub(super) probe: Vec<DVec3>,
    /// The vertices still refined.
    pub(super) active: Vec<u32>,
    pub(super) fprobe: Vec<f64>,
    pub(super) centres: Vec<(u32, [u32; 12], u8)>,
}

/// Samples one leaf block and appends its triangles to `part`.
pub(super) fn leaf<S: Source + ?Sized>(
    field: &Field<S>,
    b: &Block,
    refine: Refine,
    w: &mut Work,
    part: &mut Part,
) {
    let frame = LeafFrame::new(&field.grid, b, part.positions.len() as u32);
    sample(field, &frame, w);
    let first_tri = part.triangles.len();
    w.slots.clear();
    w.slots.resize(frame.npts() * 3, u32::MAX);
    w.a.clear();
    w.b.clear();
    w.edge.clear();
    w.fa.clear();
    w.fb.clear();
    w.centres.clear();
    for k in 0..frame.d[2] {
        for j in 0..frame.d[1] {
            for i in 0..frame.d[0] {
                triangulate_cell(&frame, [i, j, k], w, part);
            }
        }
    }
    refine::refine(field, refine, w);
    place_edge_vertices(w, part);
    place_centre_vertices(w, part, first_tri);
}

/// Where a leaf block sits in the grid, and how its sample points are numbered.
struct LeafFrame {
    /// The block's first cell in the grid.
    lo: [usize; 3],
    /// Cells per axis.
    d: [usize; 3],
    /// The grid's cells per axis.
    n: [usize; 3],
    /// The index the block's first new vertex will have in its part.
    base: u32,
    /// Sample points along x and y (`d + 1`), kept for [`LeafFrame::idx`] in the hot loops.
    px: usize,
    py: usize,
}

impl LeafFrame {
    fn new(g: &Grid, b: &Block, base: u32) -> Self {
        let d = [0, 1, 2].map(|i| b.hi[i] - b.lo[i]);
        LeafFrame {
            lo: b.lo,
            d,
            n: g.n,
            base,
            px: d[0] + 1,
            py: d[1] + 1,
        }
    }

    /// Sample points per axis.
    fn points(&self) -> [usize; 3] {
        self.d.map(|d| d + 1)
    }

    fn npts(&self) -> usize {
        self.points().iter().product()
    }

    /// The index of local sample point `(i, j, k)`.
    #[inline]
    fn idx(&self, i: usize, j: usize, k: usize) -> usize {
        (k * self.py + j) * self.px + i
    }

    /// True for a local point on the grid's box.
    fn on_grid_box(&self, i: usize, j: usize, k: usize) -> bool {
        let (gi, gj, gk) = (self.lo[0] + i, self.lo[1] + j, self.lo[2] + k);
        gi == 0 || gj == 0 || gk == 0 || gi == self.n[0] || gj == self.n[1] || gk == self.n[2]
    }

    /// The grid-wide key of the edge along `axis` from local point `l`, by which neighbouring
    /// blocks match their boundary vertices.
    fn edge_key(&self, l: [usize; 3], axis: usize) -> u64 {
        let (gx, gy) = ((self.n[0] + 1) as u64, (self.n[1] + 1) as u64);
        let [gi, gj, gk] = [0, 1, 2].map(|x| (self.lo[x] + l[x]) as u64);
        ((gk * gy + gj) * gx + gi) * 3 + axis as u64
    }
}

/// Evaluates the field at every sample point of the block. Grid points on the grid's box are
/// outside, whatever rounding says: this closes surfaces that run into the bounds.
fn sample<S: Source + ?Sized>(field: &Field<S>, frame: &LeafFrame, w: &mut Work) {
    let g = &field.grid;
    let [px, py, pz] = frame.points();
    w.points.clear();
    for k in 0..pz {
        for j in 0..py {
            for i in 0..px {
                w.points
                    .push(g.point(frame.lo[0] + i, frame.lo[1] + j, frame.lo[2] + k));
            }
        }
    }
    w.values.resize(frame.npts(), 0.0);
    field.eval_batch(&mut w.scratch, &w.points, &mut w.values);
    // A point inside by less than a hair (a needle's size, half what the needle pass may move)
    // counts as outside: where the surface grazes a row of grid points, their values a hair
    // below zero made a shell of its own, a rod 10⁻⁶ of the grid across whose end caps were
    // needles no collapse could remove without changing the rod's topology. It becomes a hair
    // outside, not zero: at zero every crossing from that point starts on the point itself, and
    // refinement left those vertices about 1e-8 apart, which f32 files (STL, glTF) merge into
    // zero-area triangles.
    let hair = g.hair;
    for v in w.values.iter_mut() {
        if *v < 0.0 && *v > -hair {
            *v = hair;
        }
    }
    for k in 0..pz {
        for j in 0..py {
            for i in 0..px {
                if frame.on_grid_box(i, j, k) {
                    let v = &mut w.values[frame.idx(i, j, k)];
                    *v = v.max(0.0);
                }
            }
        }
    }
}

/// One cell of a leaf block being triangulated: its corner values and the vertex already made
/// on each of its twelve edges.
struct Cell<'f> {
    frame: &'f LeafFrame,
    /// The cell's first corner, in the block's local sample points.
    at: [usize; 3],
    vals: [f64; 8],
    edge_vertex: [u32; 12],
}

impl Cell<'_> {
    /// The vertex on cell edge `e`: the one this cell or a neighbour in the block already made
    /// on that grid edge, or a new one whose bracket (inside end, outside end) is queued for
    /// refinement. Vertices on the block's boundary are listed in `part.shared`.
    fn vertex(&mut self, e: usize, w: &mut Work, part: &mut Part) -> u32 {
        if self.edge_vertex[e] != u32::MAX {
            return self.edge_vertex[e];
        }
        let f = self.frame;
        let [i, j, k] = self.at;
        let axis = e / 4;
        let (c0, c1) = edge_corners(e);
        let l = [i + (c0 & 1), j + (c0 >> 1 & 1), k + (c0 >> 2)];
        let slot = f.idx(l[0], l[1], l[2]) * 3 + axis;
        let mut v = w.slots[slot];
        if v == u32::MAX {
            v = f.base + w.a.len() as u32;
            w.slots[slot] = v;
            let q = corner_pos(c1);
            let (p0, p1) = (
                w.points[f.idx(l[0], l[1], l[2])],
                w.points[f.idx(i + q[0], j + q[1], k + q[2])],
            );
            let (v0, v1) = (self.vals[c0], self.vals[c1]);
            // Keep the bracket as (inside, outside).
            if v0 < 0.0 {
                w.a.push(p0);
                w.fa.push(v0);
                w.b.push(p1);
                w.fb.push(v1);
            } else {
                w.a.push(p1);
                w.fa.push(v1);
                w.b.push(p0);
                w.fb.push(v0);
            }
            w.edge.push((p0, p1));
            let on_boundary = (0..3)
                .filter(|&x| x != axis)
                .any(|x| l[x] == 0 || l[x] == f.d[x]);
            if on_boundary {
                part.shared.push((f.edge_key(l, axis), v));
            }
        }
        self.edge_vertex[e] = v;
        v
    }
}

/// Triangulates the cell whose first corner is local point `at`, by its configuration and, on
/// ambiguous faces, the face's saddle decision.
fn triangulate_cell(frame: &LeafFrame, at: [usize; 3], w: &mut Work, part: &mut Part) {
    let [i, j, k] = at;
    let mut vals = [0.0; 8];
    let mut config = 0usize;
    for (c, v) in vals.iter_mut().enumerate() {
        *v = w.values[frame.idx(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2))];
        if *v < 0.0 {
            config |= 1 << c;
        }
    }
    if config == 0 || config == 255 {
        return;
    }
    let table = &*TABLE;
    let mut decisions = 0usize;
    let amb = table.ambiguous[config];
    if amb != 0 {
        for f in 0..6 {
            if amb >> f & 1 == 1 && face_connects(face_corners(f).map(|c| vals[c])) {
                decisions |= 1 << f;
            }
        }
    }
    let case = &table.cases[config | decisions << 8];
    let mut cell = Cell {
        frame,
        at,
        vals,
        edge_vertex: [u32::MAX; 12],
    };
    let mut centre_ids = [u32::MAX; 4];
    for (ci, lp) in case.centres.iter().enumerate() {
        let mut ids = [0u32; 12];
        for (x, &e) in lp.iter().enumerate() {
            ids[x] = cell.vertex(e as usize, w, part);
        }
        // Centre vertices are numbered after all edge vertices of the block.
        centre_ids[ci.min(3)] = w.centres.len() as u32 | 0x8000_0000;
        w.centres.push((0, ids, lp.len() as u8));
    }
    for t in &case.tris {
        let tri = t.map(|c| {
            if c < 12 {
                cell.vertex(c as usize, w, part)
            } else {
                centre_ids[(c - 12).min(3) as usize]
            }
        });
        part.triangles.push(tri);
    }
}

/// Places each edge vertex at its refined root, held off the ends of its grid edge.
fn place_edge_vertices(w: &Work, part: &mut Part) {
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
}

/// Places the centre vertices (of cases with an interior vertex) at the mean of their loop,
/// and renumbers the block's triangles that use them.
fn place_centre_vertices(w: &Work, part: &mut Part, first_tri: usize) {
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
