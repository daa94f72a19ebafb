//! Dropping the vertices that pass straight through every region boundary that uses them, from
//! all of those boundaries at once.

use glam::DVec3;
use smallvec::SmallVec;

use super::buckets::{Buckets, buckets};

/// Removes every vertex that lies within `delta` of the segment between its only two
/// neighbours and passes straight through on every boundary that uses it, from all of those
/// boundaries at once, so that adjacent regions keep matching edges. `pinned` vertices stay.
pub(super) fn simplify(
    positions: &[DVec3],
    boundaries: &mut [Vec<(u32, u32)>],
    pinned: &[bool],
    delta: f64,
) {
    struct Edge {
        a: u32,
        b: u32,
        region: u32,
        alive: bool,
    }
    let total: usize = boundaries.iter().map(Vec::len).sum();
    let mut edges: Vec<Edge> = Vec::with_capacity(total);
    for (r, b) in boundaries.iter().enumerate() {
        edges.extend(b.iter().map(|&(a, b)| Edge {
            a,
            b,
            region: r as u32,
            alive: true,
        }));
    }
    // Per vertex, its outgoing and its incoming edges, in edge order: one list each, cut by
    // vertex (a counting sort), not a small vector per vertex, which spilled to the heap at
    // every vertex of more than four boundary edges. A vertex's lists only shrink: it is
    // emptied when dropped, and an incoming edge is replaced by the one rerouted into it.
    let mut outgoing = Lists::new(positions.len(), edges.iter().map(|e| e.a));
    let mut incoming = Lists::new(positions.len(), edges.iter().map(|e| e.b));
    let mut work: Vec<u32> = (0..positions.len() as u32)
        .filter(|&v| !outgoing.of(v).is_empty() && !pinned[v as usize])
        .collect();
    while let Some(v) = work.pop() {
        let (outs, ins) = (outgoing.of(v), incoming.of(v));
        if outs.is_empty() || outs.len() != ins.len() {
            continue;
        }
        // Exactly two neighbours, v strictly between them on a line.
        let ends = outs.iter().map(|&e| edges[e as usize].b);
        let Some(nbrs) = two_distinct(ends.chain(ins.iter().map(|&e| edges[e as usize].a))) else {
            continue;
        };
        if !between(positions, nbrs[0], v, nbrs[1], delta) {
            continue;
        }
        // Pair each incoming x→v with an outgoing v→y of the same region, y ≠ x.
        let mut pairs: SmallVec<[(u32, u32); 4]> = SmallVec::new();
        let mut used: SmallVec<[u32; 4]> = SmallVec::new();
        let ok = ins.iter().all(|&ei| {
            let e_in = &edges[ei as usize];
            let partner = outs.iter().copied().find(|&eo| {
                let e_out = &edges[eo as usize];
                e_out.region == e_in.region && e_out.b != e_in.a && !used.contains(&eo)
            });
            match partner {
                Some(eo) => {
                    used.push(eo);
                    pairs.push((ei, eo));
                    true
                }
                None => false,
            }
        });
        if !ok {
            continue;
        }
        for (ei, eo) in pairs {
            let y = edges[eo as usize].b;
            edges[eo as usize].alive = false;
            edges[ei as usize].b = y;
            incoming.replace(y, eo, ei);
        }
        outgoing.clear(v);
        incoming.clear(v);
        work.extend(nbrs.into_iter().filter(|&n| !pinned[n as usize]));
    }
    for b in boundaries.iter_mut() {
        b.clear();
    }
    for e in edges.into_iter().filter(|e| e.alive) {
        boundaries[e.region as usize].push((e.a, e.b));
    }
}

/// Per vertex, a list of edge indices in one array: `items[start[v]..start[v] + len[v]]`.
struct Lists {
    start: Vec<u32>,
    len: Vec<u32>,
    items: Vec<u32>,
}

impl Lists {
    /// The lists of edges `0..` by the vertex `ends` gives each, in edge order.
    fn new(vertex_count: usize, ends: impl Iterator<Item = u32> + Clone) -> Self {
        let Buckets { starts, items } = buckets(
            vertex_count,
            ends.enumerate().map(|(e, v)| (v as usize, e as u32)),
        );
        let len = starts.windows(2).map(|w| w[1] - w[0]).collect();
        Lists {
            start: starts,
            len,
            items,
        }
    }

    fn of(&self, v: u32) -> &[u32] {
        let s = self.start[v as usize] as usize;
        &self.items[s..s + self.len[v as usize] as usize]
    }

    fn clear(&mut self, v: u32) {
        self.len[v as usize] = 0;
    }

    /// Takes `old` out of `v`'s list and puts `new` at its end.
    fn replace(&mut self, v: u32, old: u32, new: u32) {
        let s = self.start[v as usize] as usize;
        let list = &mut self.items[s..s + self.len[v as usize] as usize];
        let k = list
            .iter()
            .position(|&e| e == old)
            .expect("an alive edge is in its end's incoming list");
        // A short list: shifted by hand (a rotation costs more to set up than to do).
        for j in k + 1..list.len() {
            list[j - 1] = list[j];
        }
        *list.last_mut().expect("holds old") = new;
    }
}

/// The two values `items` holds, in order of first appearance, when it holds exactly two
/// (looking no further than a third).
fn two_distinct(items: impl Iterator<Item = u32>) -> Option<[u32; 2]> {
    let mut found = [u32::MAX; 2];
    let mut count = 0;
    for x in items {
        if found[..count].contains(&x) {
            continue;
        }
        if count == 2 {
            return None;
        }
        found[count] = x;
        count += 1;
    }
    (count == 2).then_some(found)
}

/// True when `v` lies within `delta` of the segment `a`–`b` and strictly inside it.
fn between(positions: &[DVec3], a: u32, v: u32, b: u32, delta: f64) -> bool {
    let (a, v, b) = (
        positions[a as usize],
        positions[v as usize],
        positions[b as usize],
    );
    let d = b - a;
    let len2 = d.length_squared();
    if len2 == 0.0 {
        return false;
    }
    let t = (v - a).dot(d) / len2;
    // The cross product: `a + d·t` would carry the rounding of a long edge's length.
    t > 0.0 && t < 1.0 && (v - a).cross(d).length() <= delta * len2.sqrt()
}
