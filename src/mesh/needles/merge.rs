//! Merging a speck's three corners, or a cluster of vertices joined by speck-short edges, into
//! one vertex, where no single edge collapse may.
//!
//! A speck can sit where no edge of it collapses: between two flat slivers whose short edges
//! are its own (each collapse of one of its edges leaves the sliver across flat), or on a
//! vertex of valence three (collapsing the edge opposite makes a doubled face). Taking the whole
//! speck at once removes it with every triangle that holds two of its corners, and the
//! condition is on the region it replaces, not on one edge: the triangles around the merged
//! vertices form a disk (Euler characteristic 1) whose boundary, the merged vertex's link, is
//! one simple cycle. Then the cone from the merged vertex over that cycle is again a closed
//! 2-manifold of the same genus.
//!
//! Where the speck is one of several triangles in a patch whose every edge is below the speck
//! length (the tiny loop where two nearly equal cone apexes cross, corners 3.5·10⁻¹⁰ apart on a
//! shell of 1.5), each collapse and each three-corner merge folds a neighbour in the patch: the
//! whole patch, its vertices joined by such edges ([`Work::cluster`]), merges at once, on the
//! same condition.
//!
//! Where the triangles around the patch form an annulus instead, bounded by two simple cycles
//! (the patch a *neck* between two cones whose apexes nearly meet, as on two spheres at one
//! centre, one turned 1e-7°, 11 and 3 segments), merging would pinch the surface into one
//! vertex of two cones. The neck is cut: each cycle gets its own apex, both at the
//! volume-keeping point. The surface stays a closed 2-manifold, of genus one less or split into
//! two shells, the two apexes at one place (as the cones' were within 10⁻⁹).

use glam::DVec3;
use smallvec::SmallVec;

use super::work::Work;
use super::{Op, Plan};

/// The most vertices a cluster merge takes at once: a patch of specks is a few points computed
/// apart where several planes nearly meet, not a region of the mesh.
const CLUSTER_VERTICES: usize = 16;

impl Work {
    /// Merging the corners of triangle `t` into one vertex (see [`Work::plan_merge_of`]).
    pub(super) fn plan_merge(&self, t: u32) -> Option<Plan> {
        self.plan_merge_of(&self.tris[t as usize], false)
    }

    /// The vertices joined to needle `t`'s shortest edge's ends by edges below the speck length
    /// (the shortest edge of a triangle of the needle area, equilateral): `None` where that edge
    /// is not that short, or the cluster is only `t`'s corners (a merge of `t`) or grows past
    /// [`CLUSTER_VERTICES`].
    pub(super) fn cluster(&self, t: u32) -> Option<SmallVec<[u32; 8]>> {
        let tri = self.tris[t as usize];
        let c = self.corners(tri);
        let speck = (4.0 / 3f64.sqrt() * self.threshold(tri)).sqrt();
        let short = |a: u32, b: u32| {
            self.positions[a as usize].distance(self.positions[b as usize]) < speck
        };
        let k = (0..3).min_by(|&i, &j| {
            let len = |k: usize| c[k].distance_squared(c[(k + 1) % 3]);
            len(i).total_cmp(&len(j))
        })?;
        let (p, q) = (tri[k], tri[(k + 1) % 3]);
        if !short(p, q) {
            return None;
        }
        let mut cluster: SmallVec<[u32; 8]> = SmallVec::new();
        cluster.push(p);
        cluster.push(q);
        let mut next = 0;
        while next < cluster.len() {
            let v = cluster[next];
            next += 1;
            for &u in self.around(v) {
                for w in self.tris[u as usize] {
                    if !cluster.contains(&w) && short(v, w) {
                        if cluster.len() == CLUSTER_VERTICES {
                            return None;
                        }
                        cluster.push(w);
                    }
                }
            }
        }
        let only_t = cluster.len() <= 3 && cluster.iter().all(|v| tri.contains(v));
        (!only_t).then_some(cluster)
    }

    /// Merging `vertices` (a triangle's corners, or a [`Work::cluster`]) into one vertex: the
    /// move and the operation, if the triangles around them form a disk whose boundary is one
    /// simple cycle through every other vertex of theirs, and every triangle that stays keeps
    /// its orientation and area. The merged vertex is put where the volume is kept, from
    /// whichever of the vertices and their centroid moves the surface least. Where they form
    /// an annulus instead and `neck` is set (a cluster: every edge in it below the speck
    /// length), the neck is cut: one vertex per boundary cycle, both at that place.
    pub(super) fn plan_merge_of(&self, vertices: &[u32], neck: bool) -> Option<Plan> {
        let star = self.star(vertices);
        // The triangles that keep one vertex, as (triangle, its vertex); the link edges are
        // theirs opposite that vertex. Those with two or more vanish.
        let mut kept: SmallVec<[(u32, u32); 24]> = SmallVec::new();
        let mut dying = 0;
        for &u in &star {
            let other = self.tris[u as usize];
            let mut corner = None;
            let mut count = 0;
            for w in other {
                if vertices.contains(&w) {
                    corner = Some(w);
                    count += 1;
                }
            }
            match (count, corner) {
                (1, Some(v)) => kept.push((u, v)),
                _ => dying += 1,
            }
        }
        if self.shell_tris[self.shell[vertices[0] as usize] as usize] <= dying + 4
            || !self.link_holds_the_rest(vertices, &star, &kept)
        {
            return None;
        }
        // A disk bounded by one cycle merges into one vertex; an annulus bounded by two (a
        // neck, where two cones' apexes cross) is cut: one vertex, at the same place, per cycle.
        let cut = match (self.euler(&star), self.link_cycles(&kept)?.1) {
            (1, 1) => false,
            (0, 2) if neck => true,
            _ => return None,
        };
        let centroid = vertices
            .iter()
            .map(|&v| self.positions[v as usize])
            .sum::<DVec3>()
            / vertices.len() as f64;
        let candidates = vertices
            .iter()
            .map(|&v| self.positions[v as usize])
            .chain([centroid]);
        let mut best: Option<(f64, f64, DVec3)> = None;
        for base in candidates {
            let Some(at) = self.keep_volume(&star, &kept, base) else {
                continue;
            };
            let Some((dev, swept)) = self.merge_move(vertices, &kept, at) else {
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
            op: Op::Merge {
                vertices: vertices.iter().copied().collect(),
                at,
                cut,
            },
        })
    }

    /// Every vertex of `star` but the merged `vertices` is on the link (the kept triangles'
    /// edges opposite their merged vertex): none vanishes inside the patch. (Three corners of
    /// a triangle on a closed mesh leave none inside; a cluster could.)
    fn link_holds_the_rest(&self, vertices: &[u32], star: &[u32], kept: &[(u32, u32)]) -> bool {
        star.iter().all(|&u| {
            self.tris[u as usize].iter().all(|w| {
                vertices.contains(w)
                    || kept.iter().any(|&(k, v)| {
                        let (a, b) = self.opposite_edge(k, v);
                        a == *w || b == *w
                    })
            })
        })
    }

    /// The Euler characteristic V − E + F of the triangles `star` over their vertices and
    /// edges: 1 for a disk, 0 for an annulus (the star of a connected set on a closed
    /// 2-manifold, so no other surface is possible with those).
    fn euler(&self, star: &[u32]) -> i64 {
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
        vertices.len() as i64 - edges.len() as i64 + star.len() as i64
    }

    /// The link edges of the triangles that keep one vertex, split into simple cycles of at
    /// least three vertices each (each vertex starts one edge and ends one): per kept triangle
    /// its cycle's number, and how many cycles; `None` where the edges are not such cycles.
    fn link_cycles(&self, kept: &[(u32, u32)]) -> Option<(SmallVec<[usize; 24]>, usize)> {
        let link: SmallVec<[(u32, u32); 24]> = kept
            .iter()
            .map(|&(u, v)| self.opposite_edge(u, v))
            .collect();
        for (i, &(a, b)) in link.iter().enumerate() {
            if link[..i].iter().any(|&(c, d)| c == a || d == b) {
                return None;
            }
        }
        let mut label: SmallVec<[usize; 24]> = SmallVec::from_elem(usize::MAX, link.len());
        let mut cycles = 0;
        while let Some(first) = label.iter().position(|&l| l == usize::MAX) {
            let start = link[first].0;
            let (mut at, mut length) = (first, 0);
            loop {
                label[at] = cycles;
                length += 1;
                let next = link[at].1;
                if next == start {
                    break;
                }
                at = link.iter().position(|&(a, _)| a == next)?;
                if label[at] != usize::MAX {
                    return None;
                }
            }
            if length < 3 {
                return None;
            }
            cycles += 1;
        }
        Some((label, cycles))
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

    /// The surface move and swept volume of merging `vertices` at `at`, or `None` where a kept
    /// triangle would fold or go flat. Measured as an edge collapse is: the merged vertex from
    /// each kept triangle's old plane, each vertex from its triangles' new planes; a vertex
    /// left with no triangle (of valence three) by its distance to `at`.
    fn merge_move(&self, vertices: &[u32], kept: &[(u32, u32)], at: DVec3) -> Option<(f64, f64)> {
        let (mut dev, mut swept) = (0.0f64, 0.0);
        for &v in vertices {
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

    /// Merges `vertices` into their first, moved to `at`: every triangle holding two or more
    /// of them is deleted, the others are relinked to the merged vertex. With `cut` (the link
    /// two cycles, [`Work::plan_merge_of`]), those on the second cycle are relinked to the
    /// second vertex, also moved to `at`.
    pub(super) fn apply_merge(&mut self, vertices: &[u32], at: DVec3, cut: bool) -> Vec<u32> {
        let star = self.star(vertices);
        let mut kept: SmallVec<[(u32, u32); 24]> = SmallVec::new();
        for &u in &star {
            let mut inside = self.tris[u as usize]
                .into_iter()
                .filter(|w| vertices.contains(w));
            if let (Some(v), None) = (inside.next(), inside.next()) {
                kept.push((u, v));
            }
        }
        // The plan found the two cycles on this same star just before.
        let labels = cut.then(|| {
            self.link_cycles(&kept)
                .expect("a planned cut has two link cycles")
                .0
        });
        for &u in &star {
            self.unlink(u);
        }
        self.positions[vertices[0] as usize] = at;
        if cut {
            self.positions[vertices[1] as usize] = at;
        }
        let shell = self.shell[vertices[0] as usize] as usize;
        for &u in &star {
            let Some(k) = kept.iter().position(|&(w, _)| w == u) else {
                self.alive[u as usize] = false;
                self.shell_tris[shell] -= 1;
                continue;
            };
            let apex = vertices[labels.as_ref().map_or(0, |l| l[k])];
            for w in self.tris[u as usize].iter_mut() {
                if vertices.contains(w) {
                    *w = apex;
                }
            }
            self.link(u);
        }
        let mut changed = self.around(vertices[0]).to_vec();
        if cut {
            changed.extend_from_slice(self.around(vertices[1]));
            self.split_shell(vertices[0], vertices[1]);
        }
        changed
    }
}
