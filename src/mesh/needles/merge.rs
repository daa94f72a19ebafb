//! Merging a speck's three corners into one vertex, where no single edge collapse may.
//!
//! A speck can sit where no edge of it collapses: between two flat slivers whose short edges
//! are its own (each collapse of one of its edges leaves the sliver across flat), or on a
//! vertex of valence three (collapsing the edge opposite makes a doubled face). Taking the whole
//! speck at once removes it with every triangle that holds two of its corners, and the
//! condition is on the region it replaces, not on one edge: the triangles around the three
//! corners form a disk (Euler characteristic 1) whose boundary, the merged vertex's link, is
//! one simple cycle. Then the cone from the merged vertex over that cycle is again a closed
//! 2-manifold of the same genus.

use glam::DVec3;
use smallvec::SmallVec;

use super::work::Work;
use super::{Op, Plan};

impl Work {
    /// Merging the corners of triangle `t` into one vertex: the move and the operation, if the
    /// triangles around them form a disk, and every triangle that stays keeps its orientation
    /// and area. The merged vertex is put where the volume is kept, from whichever of the
    /// corners and the centroid moves the surface least.
    pub(super) fn plan_merge(&self, t: u32) -> Option<Plan> {
        let tri = self.tris[t as usize];
        let star = self.star(tri);
        // The triangles that keep one corner, as (triangle, its corner); the link edges are
        // theirs opposite that corner. Those with two or three corners vanish.
        let mut kept: SmallVec<[(u32, u32); 24]> = SmallVec::new();
        let mut dying = 0;
        for &u in &star {
            let other = self.tris[u as usize];
            let mut corner = None;
            let mut count = 0;
            for w in other {
                if tri.contains(&w) {
                    corner = Some(w);
                    count += 1;
                }
            }
            match (count, corner) {
                (1, Some(v)) => kept.push((u, v)),
                _ => dying += 1,
            }
        }
        if self.shell_tris[self.shell[tri[0] as usize] as usize] <= dying + 4
            || !self.is_disk(&star)
            || !self.link_is_cycle(&kept)
        {
            return None;
        }
        let c = self.corners(tri);
        let candidates = [c[0], c[1], c[2], (c[0] + c[1] + c[2]) / 3.0];
        let mut best: Option<(f64, f64, DVec3)> = None;
        for base in candidates {
            let Some(at) = self.keep_volume(&star, &kept, base) else {
                continue;
            };
            let Some((dev, swept)) = self.merge_move(tri, &kept, at) else {
                continue;
            };
            if best.is_none_or(|(d, _, _)| dev < d) {
                best = Some((dev, swept, at));
            }
        }
        let (dev, swept, at) = best?;
        Some(Plan {
            dev,
            swept,
            op: Op::Merge { t, at },
        })
    }

    /// The triangles `star` form a disk: V − E + F = 1 over their vertices and edges (the star
    /// of a connected set on a closed 2-manifold, so no other surface is possible with it).
    fn is_disk(&self, star: &[u32]) -> bool {
        let mut vertices: SmallVec<[u32; 32]> = SmallVec::new();
        let mut edges: SmallVec<[(u32, u32); 48]> = SmallVec::new();
        for &u in star {
            let tri = self.tris[u as usize];
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if !vertices.contains(&a) {
                    vertices.push(a);
                }
                let e = (a.min(b), a.max(b));
                if !edges.contains(&e) {
                    edges.push(e);
                }
            }
        }
        vertices.len() as i64 - edges.len() as i64 + star.len() as i64 == 1
    }

    /// The link edges of the triangles that keep one corner form one simple cycle of at least
    /// three vertices: each vertex starts one edge and ends one, and the walk covers them all.
    fn link_is_cycle(&self, kept: &[(u32, u32)]) -> bool {
        if kept.len() < 3 {
            return false;
        }
        let link: SmallVec<[(u32, u32); 24]> = kept
            .iter()
            .map(|&(u, v)| self.opposite_edge(u, v))
            .collect();
        for (i, &(a, b)) in link.iter().enumerate() {
            if link[..i].iter().any(|&(c, d)| c == a || d == b) {
                return false;
            }
        }
        let start = link[0].0;
        let mut at = start;
        for steps in 1..=link.len() {
            let Some(&(_, next)) = link.iter().find(|&&(a, _)| a == at) else {
                return false;
            };
            at = next;
            if at == start {
                return steps == link.len();
            }
        }
        false
    }

    /// Triangle `u`'s edge opposite its corner `v`, in its winding.
    fn opposite_edge(&self, u: u32, v: u32) -> (u32, u32) {
        let tri = self.tris[u as usize];
        let k = (0..3).find(|&k| tri[k] == v).unwrap_or(0);
        (tri[(k + 1) % 3], tri[(k + 2) % 3])
    }

    /// The point off `base` along the new fan's normal where the cone over the link encloses
    /// what `star` did. Volumes are taken about `base`: the old star and the new fan share their
    /// boundary, so the difference does not depend on the origin.
    fn keep_volume(&self, star: &[u32], kept: &[(u32, u32)], base: DVec3) -> Option<DVec3> {
        let mut old = 0.0;
        for &u in star {
            let [a, b, c] = self.corners(self.tris[u as usize]);
            old += (a - base).dot((b - base).cross(c - base)) / 6.0;
        }
        let mut gradient = DVec3::ZERO;
        for &(u, v) in kept {
            let (w1, w2) = self.opposite_edge(u, v);
            let (p, q) = (self.positions[w1 as usize], self.positions[w2 as usize]);
            gradient += (p - base).cross(q - base) / 6.0;
        }
        let at = base + (old / gradient.length_squared()) * gradient;
        if old == 0.0 {
            Some(base)
        } else {
            at.is_finite().then_some(at)
        }
    }

    /// The surface move and swept volume of merging `tri`'s corners at `at`, or `None` where a
    /// kept triangle would fold or go flat. Measured as an edge collapse is: the merged vertex
    /// from each kept triangle's old plane, each corner from its triangles' new planes; a
    /// corner left with no triangle (of valence three) by its distance to `at`.
    fn merge_move(&self, tri: [u32; 3], kept: &[(u32, u32)], at: DVec3) -> Option<(f64, f64)> {
        let (mut dev, mut swept) = (0.0f64, 0.0);
        for v in tri {
            if !kept.iter().any(|&(_, w)| w == v) {
                dev = dev.max(self.positions[v as usize].distance(at));
            }
        }
        for &(u, v) in kept {
            let old = self.tris[u as usize];
            let after = self.corners_moved(old, v, at);
            let (d, s) = self.moved_corner(old, after, self.positions[v as usize], at)?;
            dev = dev.max(d);
            swept += s;
        }
        Some((dev, swept))
    }

    /// Merges the corners of `t` into its first, moved to `at`: every triangle holding two or
    /// three of them is deleted, the others are relinked to the merged vertex.
    pub(super) fn apply_merge(&mut self, t: u32, at: DVec3) -> Vec<u32> {
        let tri = self.tris[t as usize];
        let keep = tri[0];
        let star = self.star(tri);
        for &u in &star {
            self.unlink(u);
        }
        self.positions[keep as usize] = at;
        let shell = self.shell[keep as usize] as usize;
        for &u in &star {
            let corners = self.tris[u as usize]
                .iter()
                .filter(|w| tri.contains(w))
                .count();
            if corners >= 2 {
                self.alive[u as usize] = false;
                self.shell_tris[shell] -= 1;
                continue;
            }
            for w in self.tris[u as usize].iter_mut() {
                if tri.contains(w) {
                    *w = keep;
                }
            }
            self.link(u);
        }
        self.around[keep as usize].to_vec()
    }
}
