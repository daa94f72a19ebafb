//! The mesh the needle pass edits: triangles with liveness, the triangles around each vertex,
//! each shell's thresholds; lookups, linking and writing the result back.

use std::cell::Cell;

use glam::DVec3;
use smallvec::SmallVec;

use super::SPECK_MOVE;
use super::geometry::{area, plane_distance, twice_normal};
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, NEEDLE_AREA, Tolerance, is_thin, is_zero_area, needle_of_kernel};
use crate::mesh::Mesh;

/// The mesh being edited: triangles with liveness, triangles per vertex and the scale of each
/// vertex's shell.
///
/// A directed edge is found among the few triangles around its start ([`Work::with_edge`]),
/// not in a map of all edges: one needle in a sphere of 10⁶ triangles made the pass hash every
/// edge (166 ms of 860 in `to_mesh`), for a handful of lookups.
pub(super) struct Work {
    pub(super) positions: Vec<DVec3>,
    pub(super) tris: Vec<[u32; 3]>,
    pub(super) sources: Vec<u32>,
    pub(super) alive: Vec<bool>,
    /// Live triangles around each vertex (read through [`Work::around`]).
    around: Vec<SmallVec<[u32; 8]>>,
    /// In a [`patch`](Work::patch), per vertex: whether every triangle around it is in the
    /// patch (empty for the whole mesh).
    complete: Vec<bool>,
    /// Whether the triangles around a vertex that is not complete were read.
    escaped: Cell<bool>,
    /// Per vertex: its shell's index.
    pub(super) shell: Vec<u32>,
    /// Per shell: needle area (by its own diagonal, as the report's), largest move (by its
    /// diagonal as capped), live triangle count.
    pub(super) needle_area: Vec<f64>,
    pub(super) max_move: Vec<f64>,
    /// The plane tolerance of booleans at the shell's scale: moves this small are always fine.
    pub(super) tolerance: Vec<f64>,
    /// Per shell: its diagonal as capped, and its slab thickness `2V/A` (see
    /// [`crate::geom::is_needle_to_remove`]; set by [`Work::make_strict`], where it is used).
    diagonal: Vec<f64>,
    slab: Vec<f64>,
    pub(super) shell_tris: Vec<usize>,
    /// Per vertex: its shell's index as the pass found it (neck cuts add shells later).
    pub(super) first_shell: Vec<u32>,
    /// Per shell as the pass found it: remove only the needles the kernel must
    /// ([`crate::geom::is_needle_to_remove`]), not the shell's own well-shaped detail
    /// ([`Work::make_strict`]).
    strict: Vec<bool>,
    /// The cap on every shell's diagonal (see [`super::remove_needles`]).
    scale: f64,
}

impl Work {
    pub(super) fn new(mesh: Mesh, scale: f64) -> Self {
        let shells = Shells::new(&mesh);
        Work::with_shells(mesh, shells, scale)
    }

    /// The work over the whole `mesh`, whose shells are `shells`.
    pub(super) fn with_shells(mesh: Mesh, shells: Shells, scale: f64) -> Self {
        let n = mesh.positions.len();
        let mut around: Vec<SmallVec<[u32; 8]>> = vec![SmallVec::new(); n];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for &v in tri {
                around[v as usize].push(t as u32);
            }
        }
        let shell = shells.of_vertex.clone();
        Work::with(mesh, around, Vec::new(), shell, shells, scale)
    }

    /// The work over the patch of `mesh` around the triangles `centres` (ascending): every
    /// triangle with a corner within `rings` edges of a corner of one of them, the
    /// vertices and triangles numbered in their order in `mesh`, so that every choice the pass
    /// makes by index is made alike. The vertices within the rings are *complete* (every
    /// triangle around them is in the patch); reading the triangles around any other marks the
    /// work [`escaped`](Work::escaped): its result is then not the whole mesh's pass's. Also
    /// returns the patch's triangles and vertices by their indices in `mesh`.
    pub(super) fn patch(
        mesh: &Mesh,
        shells: &Shells,
        scale: f64,
        centres: &[u32],
        rings: usize,
    ) -> (Self, Vec<u32>, Vec<u32>) {
        let n = mesh.positions.len();
        // Per vertex: 0 outside, 1 on the patch's rim (used by it, not complete), 2 complete.
        let mut mark = vec![0u8; n];
        for &t in centres {
            for v in mesh.triangles[t as usize] {
                mark[v as usize] = 2;
            }
        }
        // Each ring: the corners of the triangles at a complete vertex become complete.
        for _ in 0..rings {
            let mut grown: Vec<u32> = Vec::new();
            for tri in &mesh.triangles {
                if tri.iter().any(|&v| mark[v as usize] == 2) {
                    grown.extend(tri.iter().copied().filter(|&v| mark[v as usize] == 0));
                }
            }
            for v in grown {
                mark[v as usize] = 2;
            }
        }
        let mut tris_in: Vec<u32> = Vec::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            if tri.iter().any(|&v| mark[v as usize] == 2) {
                tris_in.push(t as u32);
                for &v in tri {
                    if mark[v as usize] == 0 {
                        mark[v as usize] = 1;
                    }
                }
            }
        }
        let mut local = vec![u32::MAX; n];
        let mut verts_in: Vec<u32> = Vec::new();
        let mut complete: Vec<bool> = Vec::new();
        for (v, &m) in mark.iter().enumerate() {
            if m > 0 {
                local[v] = verts_in.len() as u32;
                verts_in.push(v as u32);
                complete.push(m == 2);
            }
        }
        let triangles: Vec<[u32; 3]> = tris_in
            .iter()
            .map(|&t| mesh.triangles[t as usize].map(|v| local[v as usize]))
            .collect();
        let mut around: Vec<SmallVec<[u32; 8]>> = vec![SmallVec::new(); verts_in.len()];
        for (t, tri) in triangles.iter().enumerate() {
            for &v in tri {
                around[v as usize].push(t as u32);
            }
        }
        let part = Mesh {
            positions: verts_in
                .iter()
                .map(|&v| mesh.positions[v as usize])
                .collect(),
            triangles,
            sources: tris_in.iter().map(|&t| mesh.sources[t as usize]).collect(),
        };
        let shell = verts_in
            .iter()
            .map(|&v| shells.of_vertex[v as usize])
            .collect();
        let work = Work::with(part, around, complete, shell, shells.clone(), scale);
        (work, tris_in, verts_in)
    }

    fn with(
        mesh: Mesh,
        around: Vec<SmallVec<[u32; 8]>>,
        complete: Vec<bool>,
        shell: Vec<u32>,
        shells: Shells,
        scale: f64,
    ) -> Self {
        let own = shells.diagonal;
        let diag: Vec<f64> = own.iter().map(|d| d.min(scale)).collect();
        Work {
            first_shell: shell.clone(),
            strict: vec![false; diag.len()],
            slab: vec![f64::INFINITY; diag.len()],
            alive: vec![true; mesh.triangles.len()],
            positions: mesh.positions,
            tris: mesh.triangles,
            sources: mesh.sources,
            around,
            complete,
            escaped: Cell::new(false),
            shell,
            needle_area: own.iter().map(|d| NEEDLE_AREA * d * d).collect(),
            max_move: diag.iter().map(|d| SPECK_MOVE * d).collect(),
            tolerance: diag.iter().map(|d| Tolerance::RELATIVE * d).collect(),
            diagonal: diag,
            shell_tris: shells.tris,
            scale,
        }
    }

    /// The live triangles around vertex `v`. In a [`patch`](Work::patch), reading those of a
    /// vertex that is not complete marks the work escaped.
    pub(super) fn around(&self, v: u32) -> &[u32] {
        if self.complete.get(v as usize) == Some(&false) {
            self.escaped.set(true);
        }
        &self.around[v as usize]
    }

    /// Whether the pass read the triangles around a vertex its patch does not hold whole (see
    /// [`Work::patch`]).
    pub(super) fn escaped(&self) -> bool {
        self.escaped.get()
    }

    /// How many shells the pass found.
    pub(super) fn shells(&self) -> usize {
        self.strict.len()
    }

    /// Marks the shells (as the pass found them) of `strict`, whose volume `volume` and area
    /// `area` are [`shell_measures`]' of the mesh this work was made from: in those, only the
    /// needles of [`crate::geom::is_needle_to_remove`] are removed. Made before any operation.
    pub(super) fn make_strict(&mut self, strict: &[bool], volume: &[f64], area: &[f64]) {
        self.strict.clone_from_slice(strict);
        for s in 0..strict.len() {
            self.slab[s] = 2.0 * volume[s].abs() / area[s];
        }
    }

    /// After a neck cut between apexes `a` and `b`: where no edge joins their sides any more,
    /// `b`'s side becomes a shell of its own, and each side's count and thresholds are its own.
    /// Kept whole, a side split off small kept the old shell's count and diagonal: a cone of
    /// four triangles 2·10⁻⁵ across cut off a shell 3 across had faces that were needles by the
    /// old diagonal only, and passed the "more than four triangles" guard of a collapse, which
    /// folded it into two triangles back to back.
    pub(super) fn split_shell(&mut self, a: u32, b: u32) {
        let old = self.shell[a as usize];
        let mut side = vec![b];
        let mut reached = vec![false; self.positions.len()];
        reached[b as usize] = true;
        let mut next = 0;
        while next < side.len() {
            let v = side[next];
            next += 1;
            for &u in self.around(v) {
                for w in self.tris[u as usize] {
                    if w == a {
                        return;
                    }
                    if !std::mem::replace(&mut reached[w as usize], true) {
                        side.push(w);
                    }
                }
            }
        }
        let new = self.shell_tris.len() as u32;
        let mut count = 0;
        for &v in &side {
            self.shell[v as usize] = new;
            count += self.around(v).len();
        }
        // Each triangle is counted at its three corners.
        let count = count / 3;
        self.shell_tris[old as usize] -= count;
        self.shell_tris.push(count);
        self.needle_area.push(0.0);
        self.max_move.push(0.0);
        self.tolerance.push(0.0);
        self.diagonal.push(0.0);
        // The side keeps the shell's slab thickness (a bound: `s` is at most the diagonal).
        self.slab.push(self.slab[old as usize]);
        for shell in [old, new] {
            let mut bbox = Aabb::EMPTY;
            // Read through `around` on purpose: on a patch, a shell reaching its rim cannot be
            // measured here, and reading a rim vertex marks the work escaped (the whole mesh's
            // pass then runs instead).
            for v in 0..self.positions.len() {
                if self.shell[v] == shell && !self.around(v as u32).is_empty() {
                    bbox.grow(self.positions[v]);
                }
            }
            let own = bbox.diagonal();
            let d = own.min(self.scale);
            self.needle_area[shell as usize] = NEEDLE_AREA * own * own;
            self.max_move[shell as usize] = SPECK_MOVE * d;
            self.tolerance[shell as usize] = Tolerance::RELATIVE * d;
            self.diagonal[shell as usize] = d;
        }
    }

    /// The live triangle with directed edge `a`→`b`, if any.
    pub(super) fn with_edge(&self, a: u32, b: u32) -> Option<u32> {
        self.around(a).iter().copied().find(|&t| {
            let tri = self.tris[t as usize];
            (0..3).any(|k| tri[k] == a && tri[(k + 1) % 3] == b)
        })
    }

    pub(super) fn corners(&self, tri: [u32; 3]) -> [DVec3; 3] {
        tri.map(|i| self.positions[i as usize])
    }

    /// The corners of `tri` with its vertex `v` (if it has it) moved to `at`.
    pub(super) fn corners_moved(&self, tri: [u32; 3], v: u32, at: DVec3) -> [DVec3; 3] {
        tri.map(|w| {
            if w == v {
                at
            } else {
                self.positions[w as usize]
            }
        })
    }

    /// The live triangles with a corner among `vertices` (a triangle's corners, a cluster),
    /// each once.
    pub(super) fn star(&self, vertices: &[u32]) -> SmallVec<[u32; 24]> {
        let mut star = SmallVec::new();
        for &v in vertices {
            for &u in self.around(v) {
                if !star.contains(&u) {
                    star.push(u);
                }
            }
        }
        star
    }

    /// The signed volume the live triangles of `star` span with `reference`.
    pub(super) fn star_volume(&self, star: &[u32], reference: DVec3) -> f64 {
        let spans = star.iter().filter(|&&u| self.alive[u as usize]).map(|&u| {
            let [a, b, c] = self.corners(self.tris[u as usize]).map(|p| p - reference);
            a.dot(b.cross(c))
        });
        spans.sum::<f64>() / 6.0
    }

    /// The needle area of `tri`'s shell, by its own diagonal, as the report judges it.
    pub(super) fn threshold(&self, tri: [u32; 3]) -> f64 {
        self.needle_area[self.shell[tri[0] as usize] as usize]
    }

    /// The needle area at the shell's capped diagonal, the scale moves are bounded at: a
    /// triangle below it has a plane that is noise at that scale, and a move is not measured
    /// against it. Above it, a needle by [`Work::threshold`] (a shell larger than
    /// `NEEDLE_REGION_REACH` regions) is still a plane the move must keep to: a part joined to
    /// a box 10³⁸ across, every triangle of it a needle by the shell's diagonal, keeps its
    /// shape.
    pub(super) fn noise_area(&self, tri: [u32; 3]) -> f64 {
        let d = self.diagonal[self.shell[tri[0] as usize] as usize];
        NEEDLE_AREA * d * d
    }

    /// A live needle the pass removes: a needle by area, by the shell's own diagonal as the
    /// report judges it; where the shell is larger than the scale the pass's moves are bounded
    /// at and the triangle is a needle only by the shell's diagonal, a thin one
    /// ([`crate::geom::NEEDLE_THIN`]: a vertex a hair from an edge), not the shape's
    /// well-shaped detail there (an I-beam's bars 0.12 thick on shells 10⁶ across, `bsp_4`:
    /// moves within the bound took 9 of its 40 and 3·10⁻⁸ of its volume). In a shell marked
    /// `strict` (as the pass found it), only those the kernel must remove
    /// ([`crate::geom::is_needle_to_remove`]).
    pub(super) fn is_needle(&self, t: u32) -> bool {
        let tri = self.tris[t as usize];
        if !self.alive[t as usize] {
            return false;
        }
        let corners = self.corners(tri);
        let a = area(corners);
        let s = self.shell[tri[0] as usize] as usize;
        a < self.needle_area[s]
            && (a < self.noise_area(tri) || is_thin(corners, a))
            && (!self.strict[self.first_shell[tri[0] as usize] as usize]
                || needle_of_kernel(corners, a, self.diagonal[s], self.slab[s]))
    }

    /// A triangle that may replace another facing `normal`: not flat, not folded over.
    pub(super) fn acceptable(&self, tri: [u32; 3], normal: DVec3) -> bool {
        let c = self.corners(tri);
        !is_zero_area(c) && twice_normal(c).dot(normal) > 0.0
    }

    /// Triangle `old` with its corner at `end` moved to `at`, its corners becoming `after`:
    /// `None` where it goes flat or folds over, else how far that moves the surface (the moved
    /// corner from the old plane, the old corner from the new; nothing for a needle, whose own
    /// plane is noise, so only flatness and orientation are checked against the new normal)
    /// and the volume swept. Collapses and merges measure each triangle of the star this way.
    pub(super) fn moved_corner(
        &self,
        old: [u32; 3],
        after: [DVec3; 3],
        end: DVec3,
        at: DVec3,
    ) -> Option<(f64, f64)> {
        let before = self.corners(old);
        let needle = area(before) < self.noise_area(old);
        let reference = if needle {
            twice_normal(after)
        } else {
            twice_normal(before)
        };
        if is_zero_area(after) || twice_normal(after).dot(reference) <= 0.0 {
            return None;
        }
        let swept = (twice_normal(before).dot(at - end) / 6.0).abs();
        let dev = if needle {
            0.0
        } else {
            plane_distance(before, at).max(plane_distance(after, end))
        };
        Some((dev, swept))
    }

    /// Deletes the shell of needle `t` where it is a tetrahedron (four triangles) and nothing
    /// else removed the needle. A tetrahedron with a face under the needle area `A·d²` holds
    /// at most `A·d²·D/3`, `D` the shell's own diagonal (its height is under `D`): a spike
    /// 2·10⁻⁸ across and 0.06 long, where a prism and a bar turned alike about close axes
    /// meet, holds 3.5·10⁻¹⁸.
    /// No flip, collapse or merge applies to a tetrahedron, and widening its base to the
    /// threshold would move a corner past the bound.
    pub(super) fn drop_tetrahedron(&mut self, t: u32) {
        let shell = self.shell[self.tris[t as usize][0] as usize] as usize;
        if self.shell_tris[shell] != 4 {
            return;
        }
        let star = self.star(&self.tris[t as usize]);
        // Only a closed tetrahedron: repair may pass a mesh that still has cracks, where a
        // four-triangle shell can be an open patch whose deletion would widen a hole.
        let closed = star.len() == 4
            && star.iter().all(|&u| {
                let [a, b, c] = self.tris[u as usize];
                [(a, b), (b, c), (c, a)]
                    .iter()
                    .all(|&(p, q)| self.with_edge(q, p).is_some())
            });
        if !closed {
            return;
        }
        for u in star {
            self.unlink(u);
            self.alive[u as usize] = false;
            self.shell_tris[shell] -= 1;
        }
    }

    pub(super) fn unlink(&mut self, t: u32) {
        let tri = self.tris[t as usize];
        for v in tri {
            self.around[v as usize].retain(|u| *u != t);
        }
    }

    pub(super) fn link(&mut self, t: u32) {
        let tri = self.tris[t as usize];
        for v in tri {
            self.around[v as usize].push(t);
        }
    }

    /// Writes the live triangles and the positions they use back; returns the needles left.
    pub(super) fn finish(self, mesh: &mut Mesh) -> usize {
        let left = self.needles_left();
        *mesh = compact(&self.positions, &self.tris, &self.sources, &self.alive);
        left
    }

    /// [`Work::finish`] for a [`patch`](Work::patch) of `mesh` (its triangles and vertices
    /// `tris_in` and `verts_in` there): the patch written into `mesh`, then the live triangles
    /// and the positions they use kept. The triangles outside it were no needles and are as
    /// they were (the shells' thresholds are too, but for a shell a neck cut split wholly
    /// inside the patch), so the needles left are the patch's.
    pub(super) fn finish_patch(self, mesh: &mut Mesh, tris_in: &[u32], verts_in: &[u32]) -> usize {
        let left = self.needles_left();
        for (&v, &p) in verts_in.iter().zip(&self.positions) {
            mesh.positions[v as usize] = p;
        }
        let mut alive = vec![true; mesh.triangles.len()];
        for (k, &t) in tris_in.iter().enumerate() {
            mesh.triangles[t as usize] = self.tris[k].map(|v| verts_in[v as usize]);
            mesh.sources[t as usize] = self.sources[k];
            alive[t as usize] = self.alive[k];
        }
        *mesh = compact(&mesh.positions, &mesh.triangles, &mesh.sources, &alive);
        left
    }

    fn needles_left(&self) -> usize {
        (0..self.tris.len() as u32)
            .filter(|&t| self.is_needle(t))
            .count()
    }
}

/// The `alive` triangles of a mesh and the positions they use, numbered in order of first use.
fn compact(positions: &[DVec3], tris: &[[u32; 3]], sources: &[u32], alive: &[bool]) -> Mesh {
    let mut index = vec![u32::MAX; positions.len()];
    let mut kept = Vec::with_capacity(positions.len());
    let live = alive.iter().filter(|&&a| a).count();
    let mut triangles = Vec::with_capacity(live);
    let mut kept_sources = Vec::with_capacity(live);
    for ((tri, &source), _) in tris.iter().zip(sources).zip(alive).filter(|(_, a)| **a) {
        let mut out = [0u32; 3];
        for (o, &v) in out.iter_mut().zip(tri) {
            let i = &mut index[v as usize];
            if *i == u32::MAX {
                *i = kept.len() as u32;
                kept.push(positions[v as usize]);
            }
            *o = *i;
        }
        triangles.push(out);
        kept_sources.push(source);
    }
    Mesh {
        positions: kept,
        triangles,
        sources: kept_sources,
    }
}

/// A mesh's shells as the needle pass numbers them (in the order of their first triangles):
/// per vertex its shell, per shell its triangle count and its own diagonal (not capped: the
/// needle area is the report's; `Work` caps it for the moves' bounds).
#[derive(Clone)]
pub(super) struct Shells {
    pub(super) of_vertex: Vec<u32>,
    tris: Vec<usize>,
    diagonal: Vec<f64>,
}

impl Shells {
    pub(super) fn count(&self) -> usize {
        self.tris.len()
    }

    pub(super) fn new(mesh: &Mesh) -> Self {
        let n = mesh.positions.len();
        let mut sets = DisjointSets::new(n);
        for t in &mesh.triangles {
            sets.union_all(t.map(|v| v as usize));
        }
        // Shells numbered by their first triangles, by root vertex.
        let mut shell = vec![u32::MAX; n];
        let mut shell_tris: Vec<usize> = Vec::new();
        for t in &mesh.triangles {
            let root = sets.find(t[0] as usize);
            if shell[root] == u32::MAX {
                shell[root] = shell_tris.len() as u32;
                shell_tris.push(0);
            }
            shell_tris[shell[root] as usize] += 1;
        }
        // Each box grown by the shell's vertices once each (not once per corner: the same box).
        // A vertex no triangle uses is in no shell.
        let mut boxes = vec![Aabb::EMPTY; shell_tris.len()];
        for v in 0..n {
            let s = shell[sets.find(v)];
            shell[v] = s;
            if let Some(b) = boxes.get_mut(s as usize) {
                b.grow(mesh.positions[v]);
            }
        }
        Shells {
            of_vertex: shell,
            tris: shell_tris,
            diagonal: boxes.iter().map(|b| b.diagonal()).collect(),
        }
    }
}

/// Each shell's volume and area in `mesh`, by `shell` (per vertex, [`Work::first_shell`] of a
/// work made from `mesh`; `shells` of them). Each volume is taken about its shell's first
/// corner, for precision. Measured only where the pass's change to a shell needs them (one
/// cross product per triangle): on most meshes with needles no shell comes near the bound.
pub(super) fn shell_measures(mesh: &Mesh, shell: &[u32], shells: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut volume, mut area) = (vec![0.0; shells], vec![0.0; shells]);
    let mut origin = vec![None; shells];
    for t in &mesh.triangles {
        let s = shell[t[0] as usize] as usize;
        let o = *origin[s].get_or_insert(mesh.positions[t[0] as usize]);
        let [a, b, c] = t.map(|v| mesh.positions[v as usize] - o);
        let n = (b - a).cross(c - a);
        volume[s] += a.dot(n) / 6.0;
        area[s] += 0.5 * n.length();
    }
    (volume, area)
}
