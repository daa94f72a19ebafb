//! The mesh the needle pass edits: triangles with liveness, the triangles around each vertex,
//! each shell's thresholds; lookups, linking and writing the result back.

use glam::DVec3;
use smallvec::SmallVec;

use super::SPECK_MOVE;
use super::geometry::{area, plane_distance, twice_normal};
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, NEEDLE_AREA, Tolerance, is_zero_area, needle_of_kernel};
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
    /// Live triangles around each vertex.
    pub(super) around: Vec<SmallVec<[u32; 8]>>,
    /// Per vertex: its shell's index.
    pub(super) shell: Vec<u32>,
    /// Per shell: needle area, largest move, live triangle count.
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
        let n = mesh.positions.len();
        let mut sets = DisjointSets::new(n);
        for t in &mesh.triangles {
            sets.union_all(t.map(|v| v as usize));
        }
        let mut shell = vec![u32::MAX; n];
        let mut boxes: Vec<Aabb> = Vec::new();
        let mut shell_tris: Vec<usize> = Vec::new();
        for t in &mesh.triangles {
            let root = sets.find(t[0] as usize);
            if shell[root] == u32::MAX {
                shell[root] = boxes.len() as u32;
                boxes.push(Aabb::EMPTY);
                shell_tris.push(0);
            }
            let s = shell[root] as usize;
            shell_tris[s] += 1;
            for &v in t {
                boxes[s].grow(mesh.positions[v as usize]);
            }
        }
        for v in 0..n {
            shell[v] = shell[sets.find(v)];
        }
        let diag: Vec<f64> = boxes.iter().map(|b| b.diagonal().min(scale)).collect();
        let mut around: Vec<SmallVec<[u32; 8]>> = vec![SmallVec::new(); n];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for &v in tri {
                around[v as usize].push(t as u32);
            }
        }
        Work {
            first_shell: shell.clone(),
            strict: vec![false; boxes.len()],
            slab: vec![f64::INFINITY; boxes.len()],
            alive: vec![true; mesh.triangles.len()],
            positions: mesh.positions,
            tris: mesh.triangles,
            sources: mesh.sources,
            around,
            shell,
            needle_area: diag.iter().map(|d| NEEDLE_AREA * d * d).collect(),
            max_move: diag.iter().map(|d| SPECK_MOVE * d).collect(),
            tolerance: diag.iter().map(|d| Tolerance::RELATIVE * d).collect(),
            diagonal: diag,
            shell_tris,
            scale,
        }
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
            for &u in &self.around[v as usize] {
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
            count += self.around[v as usize].len();
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
            for v in 0..self.positions.len() {
                if self.shell[v] == shell && !self.around[v].is_empty() {
                    bbox.grow(self.positions[v]);
                }
            }
            let d = bbox.diagonal().min(self.scale);
            self.needle_area[shell as usize] = NEEDLE_AREA * d * d;
            self.max_move[shell as usize] = SPECK_MOVE * d;
            self.tolerance[shell as usize] = Tolerance::RELATIVE * d;
            self.diagonal[shell as usize] = d;
        }
    }

    /// The live triangle with directed edge `a`→`b`, if any.
    pub(super) fn with_edge(&self, a: u32, b: u32) -> Option<u32> {
        self.around[a as usize].iter().copied().find(|&t| {
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
            for &u in &self.around[v as usize] {
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

    pub(super) fn threshold(&self, tri: [u32; 3]) -> f64 {
        self.needle_area[self.shell[tri[0] as usize] as usize]
    }

    /// A live needle the pass removes ([`crate::geom::is_needle_to_remove`]): a needle by
    /// area that is thin, weld-sized or a speck of its shell, not its well-shaped own detail.
    /// In a shell marked `strict` (as the pass found it), only those the kernel must remove.
    pub(super) fn is_needle(&self, t: u32) -> bool {
        let tri = self.tris[t as usize];
        if !self.alive[t as usize] {
            return false;
        }
        let corners = self.corners(tri);
        let a = area(corners);
        let s = self.shell[tri[0] as usize] as usize;
        a < self.needle_area[s]
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
        let needle = area(before) < self.threshold(old);
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
        let left = (0..self.tris.len() as u32)
            .filter(|&t| self.is_needle(t))
            .count();
        let mut index = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::with_capacity(self.positions.len());
        let mut triangles = Vec::with_capacity(self.tris.len());
        let mut sources = Vec::with_capacity(self.tris.len());
        for (t, tri) in self.tris.iter().enumerate() {
            if !self.alive[t] {
                continue;
            }
            triangles.push(tri.map(|v| {
                if index[v as usize] == u32::MAX {
                    index[v as usize] = positions.len() as u32;
                    positions.push(self.positions[v as usize]);
                }
                index[v as usize]
            }));
            sources.push(self.sources[t]);
        }
        *mesh = Mesh {
            positions,
            triangles,
            sources,
        };
        left
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
