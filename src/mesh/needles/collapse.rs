//! Collapsing a needle's edge: one end onto the other, keeping the volume.

use glam::DVec3;
use smallvec::SmallVec;

use super::geometry::twice_normal;
use super::work::Work;
use super::{Op, Plan};

impl Work {
    /// Collapsing edge `from`–`to` of triangle `t` by moving `from` onto `to`: the move and the
    /// operation, if the topology allows it and every triangle around both ends stays
    /// acceptable.
    ///
    /// The merged vertex keeps the volume: where moving `from` onto `to` would add or cut
    /// some (the fan around `from` is not flat), it goes to the point off `to` along the merged
    /// fan's area-weighted normal that puts it back. Specks fanned over a face where a sphere
    /// grazes a box's corner cut volume at each collapse, all of one sign, whichever end was
    /// kept (6.8·10⁻⁹ over eleven collapses); the offsets are at most 6·10⁻⁸ there. Where the
    /// fan around `from` is flat, nothing moves off it.
    ///
    /// The move is measured both ways: how far the merged vertex lies from the plane of each
    /// triangle around either end as it was, and each old end from each triangle as it
    /// becomes. Sliding a vertex along a flat region or a straight crease moves nothing,
    /// however long the edge.
    pub(super) fn plan_collapse(&self, t: u32, from: u32, to: u32) -> Option<Plan> {
        if self.shell_tris[self.shell[from as usize] as usize] <= 4 {
            return None;
        }
        let t2 = self
            .with_edge(to, from)
            .or_else(|| self.with_edge(from, to).filter(|&u| u != t))?;
        let t1 = self
            .with_edge(from, to)
            .or_else(|| self.with_edge(to, from))?;
        let (t1, t2) = if t1 == t2 { (t, t2) } else { (t1, t2) };
        if t1 == t2 {
            return None;
        }
        let opposite = |u: u32| {
            self.tris[u as usize]
                .iter()
                .copied()
                .find(|&w| w != from && w != to)
        };
        let (o1, o2) = (opposite(t1)?, opposite(t2)?);
        if o1 == o2 {
            return None;
        }
        let cap = match self.link_condition(from, to, o1, o2) {
            true => None,
            false => Some(self.slit_tip(from, to, [(t1, o1), (t2, o2)])?),
        };
        if cap.is_some() && self.shell_tris[self.shell[from as usize] as usize] < 8 {
            return None;
        }
        let (source, target) = (self.positions[from as usize], self.positions[to as usize]);
        // The volume is linear in a vertex's position: moving `from` by `m` changes it by
        // (area-weighted normal of its fan) · m / 6, `t1` and `t2` flattening to nothing (and
        // a slit tip's pair turning into one triangle both ways round, which spans nothing).
        let gone = cap.unwrap_or([t1; 2]);
        let fan = |v: u32| {
            self.around(v)
                .iter()
                .copied()
                .filter(move |&u| u != t1 && u != t2 && !gone.contains(&u))
        };
        let moved = |old: [u32; 3]| old.map(|w| if w == from { to } else { w });
        let mut change = 0.0;
        for &u in self.around(from) {
            change += twice_normal(self.corners(self.tris[u as usize])).dot(target - source) / 6.0;
        }
        let mut gradient = DVec3::ZERO;
        for u in fan(from).chain(fan(to)) {
            gradient += twice_normal(self.corners(moved(self.tris[u as usize])));
        }
        let at = match (6.0 * change / gradient.length_squared()) * gradient {
            fix if fix.is_finite() && change != 0.0 => target - fix,
            _ => target,
        };
        // Where the fan's normals nearly cancel (a wedge's two faces back to back at its thin
        // end), that offset, along their tiny sum, runs far along the crease they share: round
        // 20's 0afdfd64 moved `to` 1.96·10⁻³ (the bound 1.25·10⁻⁶) to keep the volume of
        // collapsing an edge 2·10⁻¹¹ long. Beyond the bound, the collapse goes without it: the
        // volume then changes by `change` above (linear in the vertex: at most the edge's
        // length times a third of the fan's area, about 10⁻¹³ there against a guard of
        // 6.8·10⁻¹²), which the pass's guard weighs as it weighs every move.
        let at = if at.distance(target) > self.max_move[self.shell[to as usize] as usize] {
            target
        } else {
            at
        };
        let corners = |tri: [u32; 3]| {
            tri.map(|w| {
                if w == to {
                    at
                } else {
                    self.positions[w as usize]
                }
            })
        };
        // Closing a slit's tip fills the tetrahedron `from`, `to` and the pair's two other
        // corners, every point of which lies within |from − to| of the pair's face at `to`;
        // and `to` itself moves by the volume-keeping offset, |at − to|. Without the pair, its
        // fan can be the slit's two faces nearly back to back (a fin): their normals cancel,
        // so the offset, along their tiny sum, runs along the crease they share, in every plane
        // of the fan, which the planes below do not see (a cube's corner slid 0.34 up its
        // vertical edge, out of the solid, for a tip 3.2·10⁻¹¹ long).
        let mut dev: f64 = match cap {
            Some(_) => source.distance(target).max(at.distance(target)),
            None => 0.0,
        };
        let mut swept = 0.0;
        for (u, end) in fan(from)
            .map(|u| (u, source))
            .chain(fan(to).map(|u| (u, target)))
        {
            let old = self.tris[u as usize];
            let (d, s) = self.moved_corner(old, corners(moved(old)), end, at)?;
            dev = dev.max(d);
            swept += s;
        }
        Some(Plan {
            dev,
            swept,
            op: Op::Collapse {
                from,
                to,
                at,
                t1,
                t2,
                cap,
            },
        })
    }

    /// Where the link condition refuses collapsing `from` onto `to` only because the two ends
    /// share one more neighbour `w` through a vertex `o` of valence three, the apex of one of
    /// the triangles on the edge (`sides`: each with its apex), whose two other triangles
    /// `(from, o, w)` and `(to, w, o)` the collapse would turn into one triangle both ways
    /// round: those two, to delete with `o`.
    ///
    /// That is the tip of a slit narrower than a needle, between two faces nearly touching
    /// along `o`–`w` (a box's face and another's turned 10⁻⁴ rad, 3.2·10⁻¹⁰ apart at the
    /// tip, which ends in a needle 9.4·10⁻⁶ long). It is the same as removing `o` (its three
    /// triangles become `(from, to, w)`, a disk for a disk) and then collapsing an edge that
    /// meets the link condition: the topology is kept. Stretching the needle instead moved
    /// `from` 1.2·10⁻⁶ across the slit, widening it over the turned face by 4.8·10⁻⁹ of volume.
    pub(super) fn slit_tip(&self, from: u32, to: u32, sides: [(u32, u32); 2]) -> Option<[u32; 2]> {
        let (side, o) = sides
            .into_iter()
            .find(|&(_, o)| self.around(o).len() == 3)?;
        let mut pair = self.around(o).iter().copied().filter(|&u| u != side);
        let (u, v) = (pair.next()?, pair.next()?);
        let has = |u: u32, w: u32| self.tris[u as usize].contains(&w);
        let (at_from, at_to) = if has(u, from) { (u, v) } else { (v, u) };
        if !has(at_from, from) || has(at_from, to) || !has(at_to, to) || has(at_to, from) {
            return None;
        }
        let w = self.tris[at_from as usize]
            .into_iter()
            .find(|&x| x != from && x != o)?;
        // Relabelled, the pair is one triangle both ways round.
        let relabelled = self.tris[at_from as usize].map(|x| if x == from { to } else { x });
        let reversed = {
            let [a, b, c] = self.tris[at_to as usize];
            [c, b, a]
        };
        if !(0..3).any(|k| relabelled == [0, 1, 2].map(|j| reversed[(j + k) % 3])) {
            return None;
        }
        let [o1, o2] = sides.map(|(_, o)| o);
        (w != o1 && w != o2 && self.link_condition_with(from, to, [o1, o2, w]))
            .then_some([at_from, at_to])
    }

    /// The ends of edge `pq` share exactly the neighbours `o1` and `o2`.
    pub(super) fn link_condition(&self, p: u32, q: u32, o1: u32, o2: u32) -> bool {
        self.link_condition_with(p, q, [o1, o2])
    }

    /// The ends of edge `pq` share exactly the neighbours `expected`.
    fn link_condition_with(&self, p: u32, q: u32, expected: impl AsRef<[u32]>) -> bool {
        let (np, nq) = (self.neighbours(p), self.neighbours(q));
        let shared = np.iter().filter(|w| nq.contains(w)).count();
        let expected = expected.as_ref();
        shared == expected.len() && expected.iter().all(|w| np.contains(w) && nq.contains(w))
    }

    /// The vertices joined to `v` by an edge, each once.
    fn neighbours(&self, v: u32) -> SmallVec<[u32; 16]> {
        let mut out: SmallVec<[u32; 16]> = SmallVec::new();
        for &t in self.around(v) {
            for &w in &self.tris[t as usize] {
                if w != v && !out.contains(&w) {
                    out.push(w);
                }
            }
        }
        out
    }

    /// Moves vertex `from` onto `to`, and that to `at`, deleting `t1` and `t2` (the triangles
    /// on edge from–to) and, at a slit's tip, the `cap` pair ([`Work::slit_tip`]).
    pub(super) fn apply_collapse(
        &mut self,
        from: u32,
        to: u32,
        at: DVec3,
        [t1, t2]: [u32; 2],
        cap: Option<[u32; 2]>,
    ) -> Vec<u32> {
        self.positions[to as usize] = at;
        let gone = cap.unwrap_or([t1; 2]);
        let fan: SmallVec<[u32; 8]> = self
            .around(from)
            .iter()
            .copied()
            .filter(|&u| u != t1 && u != t2 && !gone.contains(&u))
            .collect();
        for u in [t1, t2].into_iter().chain(cap.into_iter().flatten()) {
            self.unlink(u);
            self.alive[u as usize] = false;
            self.shell_tris[self.shell[from as usize] as usize] -= 1;
        }
        for &u in &fan {
            self.unlink(u);
        }
        for &u in &fan {
            for w in self.tris[u as usize].iter_mut() {
                if *w == from {
                    *w = to;
                }
            }
            self.link(u);
        }
        let mut changed: Vec<u32> = self.around(to).to_vec();
        changed.extend(fan);
        changed
    }
}
