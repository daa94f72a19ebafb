//! Vertices whose triangles form one closed disc around them: there the shell split has nothing
//! to pair by angle and nothing to split.

use rayon::prelude::*;

/// For each of the `vertex_count` vertices, whether its triangles form exactly one closed fan
/// in which every edge at the vertex is used once each way ([`Links::disc`]).
pub(super) fn one_disc(triangles: &[[u32; 3]], vertex_count: usize) -> Vec<bool> {
    Links::new(triangles, vertex_count).disc
}

/// Above this many edges a link is sorted by start and walked by binary search; below, the
/// linear search per step is cheaper than the sort.
const SORTED_ABOVE: usize = 32;

/// The link of every vertex of a triangle mesh; around a disc vertex, in cycle order.
pub(crate) struct Links {
    /// Vertex `v`'s link edges are `edges[start[v]..start[v + 1]]`.
    start: Vec<u32>,
    edges: Vec<(u32, u32)>,
    /// Whether each vertex's triangles form exactly one closed fan in which every edge at the
    /// vertex is used once each way.
    ///
    /// The link of a vertex `v` is, per triangle at `v`, the edge from the corner after `v` to
    /// the corner before it. When those edges start at distinct vertices and, followed end to
    /// start, close into one cycle through all of them, every edge `v→x` is used once and `x→v`
    /// once (no other triangle holds both), and each corner's previous edge is twinned with the
    /// next corner's: one fan. A vertex where two solids touch (two cycles), an open one (a
    /// chain) or one on an edge of more than two triangles (a repeated start) is not a disc. A
    /// vertex no triangle uses is not one either.
    ///
    /// Costs one counting pass over the corners and a walk around each vertex's link: far less
    /// than pairing every half-edge through a sort by edge and a union–find of the corners.
    pub disc: Vec<bool>,
}

impl Links {
    /// The links of the `vertex_count` vertices of `triangles`.
    pub fn new(triangles: &[[u32; 3]], vertex_count: usize) -> Links {
        // A counting sort of the corners by vertex: `end[v]` counts up to the end of v's run,
        // and filling backwards leaves it at the run's start.
        let mut end = vec![0u32; vertex_count + 1];
        for &v in triangles.iter().flatten() {
            end[v as usize] += 1;
        }
        let mut sum = 0;
        for e in &mut end[..vertex_count] {
            sum += *e;
            *e = sum;
        }
        end[vertex_count] = sum;
        let mut edges = vec![(0u32, 0u32); triangles.len() * 3];
        let mut repeats = false;
        for &[a, b, c] in triangles {
            repeats |= a == b || b == c || a == c;
            for (v, next, prev) in [(a, b, c), (b, c, a), (c, a, b)] {
                let at = &mut end[v as usize];
                *at -= 1;
                edges[*at as usize] = (next, prev);
            }
        }
        let start = end;
        let mut disc = cycles(&start, &mut edges);
        if repeats {
            // A triangle through a vertex twice is no part of a disc (its link would pass
            // through the vertex itself).
            for t in triangles {
                if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                    for &v in t {
                        disc[v as usize] = false;
                    }
                }
            }
        }
        Links { start, edges, disc }
    }

    /// The link edges of vertex `v`: one `(a, b)` per triangle `(v, a, b)` at `v`, and around a
    /// [`disc`](Links::disc) vertex in cycle order (each edge's `b` is the next one's `a`).
    pub fn of(&self, v: usize) -> &[(u32, u32)] {
        &self.edges[self.start[v] as usize..self.start[v + 1] as usize]
    }
}

/// Vertices per block of [`cycles`]: a block's links are walked on one thread.
const CYCLE_BLOCK: usize = 4096;

/// [`one_cycle`] of every vertex's link, vertex `v`'s being `edges[start[v]..start[v + 1]]`.
///
/// Each link is walked on its own edges alone, so blocks of vertices (and the runs of edges
/// they own) are walked in parallel, each result in its vertex's place: the same for any
/// number of threads. The walks are about half of [`Links::new`], which runs on one thread in
/// `to_mesh` otherwise.
fn cycles(start: &[u32], edges: &mut [(u32, u32)]) -> Vec<bool> {
    let vertex_count = start.len() - 1;
    let mut disc = vec![false; vertex_count];
    let mut blocks = Vec::with_capacity(vertex_count.div_ceil(CYCLE_BLOCK));
    let mut rest = edges;
    for (k, flags) in disc.chunks_mut(CYCLE_BLOCK).enumerate() {
        let first = k * CYCLE_BLOCK;
        let len = (start[first + flags.len()] - start[first]) as usize;
        let (own, tail) = std::mem::take(&mut rest).split_at_mut(len);
        rest = tail;
        blocks.push((first, flags, own));
    }
    blocks.into_par_iter().for_each(|(first, flags, own)| {
        let base = start[first] as usize;
        for (k, flag) in flags.iter_mut().enumerate() {
            let (s, e) = (start[first + k] as usize, start[first + k + 1] as usize);
            *flag = one_cycle(&mut own[s - base..e - base]);
        }
    });
    disc
}

/// Whether the directed edges `link` start at distinct vertices and form one cycle; if so, they
/// are left in the cycle's order.
///
/// Walks from the first edge, each step to the first edge (after the first) starting where the
/// last one ended, and fails where that edge was walked already (a start met twice), where none
/// starts there, or where the walk is back at the first edge's start early. Where it comes back
/// after exactly `link.len()` steps, every edge was met once, each from a start of its own.
/// A long link (a cone's apex, a cylinder cap's centre) is sorted by start first, so the walk
/// costs `O(n log n)` instead of `O(n²)`.
fn one_cycle(link: &mut [(u32, u32)]) -> bool {
    let Some(&first) = link.first() else {
        return false;
    };
    if link.len() > SORTED_ABOVE {
        return sorted_cycle(link);
    }
    // In place: step `i` finds the edge starting where the last one ended and swaps it to `i`.
    // The first such edge lying before `i` (already walked) means a start met twice.
    let mut at = first.1;
    for i in 1..link.len() {
        if at == first.0 {
            return false;
        }
        match (1..link.len()).find(|&j| link[j].0 == at) {
            Some(j) if j >= i => {
                link.swap(i, j);
                at = link[i].1;
            }
            _ => return false,
        }
    }
    at == first.0
}

/// [`one_cycle`] for a long link: sorted by start, a repeated start is seen side by side, and
/// each step finds its successor by binary search.
fn sorted_cycle(link: &mut [(u32, u32)]) -> bool {
    link.sort_unstable();
    if link.windows(2).any(|w| w[0].0 == w[1].0) {
        return false;
    }
    // Starts are distinct, so each edge has at most one successor; the walk from edge 0 is one
    // cycle through every edge exactly when it first comes back to edge 0 after `len` steps.
    let mut order = Vec::with_capacity(link.len());
    let mut at = 0;
    for step in 1..=link.len() {
        order.push(link[at]);
        match link.binary_search_by_key(&link[at].1, |e| e.0) {
            Ok(next) if (next == 0) == (step == link.len()) => at = next,
            _ => return false,
        }
    }
    link.copy_from_slice(&order);
    true
}

#[cfg(test)]
mod tests {
    use super::{Links, one_disc};

    /// An octahedron: every vertex one disc of four triangles.
    fn octahedron() -> Vec<[u32; 3]> {
        // 0 +x, 1 −x, 2 +y, 3 −y, 4 +z, 5 −z
        vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ]
    }

    #[test]
    fn a_closed_surface_is_discs_everywhere() {
        assert!(one_disc(&octahedron(), 6).iter().all(|&d| d));
    }

    #[test]
    fn an_open_fan_is_not_a_disc() {
        let mut t = octahedron();
        t.pop();
        let disc = one_disc(&t, 6);
        // The removed triangle's corners 0, 3, 5 are open; 1, 2, 4 stay closed.
        assert_eq!(disc, [false, true, true, false, true, false]);
    }

    #[test]
    fn two_solids_touching_at_a_vertex_are_not_a_disc_there() {
        // Two octahedra sharing vertex 0 (the second's −x corner is the first's +x).
        let mut t = octahedron();
        let map = [6, 0, 7, 8, 9, 10];
        t.extend(octahedron().iter().map(|tri| tri.map(|v| map[v as usize])));
        let disc = one_disc(&t, 11);
        assert!(!disc[0]);
        assert!(disc[1..].iter().all(|&d| d));
    }

    #[test]
    fn an_edge_of_four_triangles_is_not_a_disc_at_its_ends() {
        // Two octahedra sharing the edge 0–2.
        let mut t = octahedron();
        let map = [0, 6, 2, 7, 8, 9];
        t.extend(octahedron().iter().map(|tri| tri.map(|v| map[v as usize])));
        let disc = one_disc(&t, 10);
        assert!(!disc[0] && !disc[2]);
        assert!(disc[3] && disc[6]);
    }

    #[test]
    fn a_triangle_repeating_a_vertex_is_no_disc() {
        let mut t = octahedron();
        t.push([0, 0, 2]);
        let disc = one_disc(&t, 6);
        assert!(!disc[0] && !disc[2]);
    }

    #[test]
    fn a_long_link_is_walked_in_order_and_its_defects_found() {
        // A double cone (bipyramid) over a ring of `n` vertices: apexes 0 and 1 of valence n.
        let n = 100u32;
        let ring = |i: u32| 2 + i % n;
        let mut t: Vec<[u32; 3]> = (0..n)
            .flat_map(|i| [[0, ring(i), ring(i + 1)], [1, ring(i + 1), ring(i)]])
            .collect();
        let links = Links::new(&t, n as usize + 2);
        assert!(links.disc.iter().all(|&d| d));
        let apex = links.of(0);
        assert_eq!(apex.len(), n as usize);
        assert!((0..apex.len()).all(|k| apex[k].1 == apex[(k + 1) % apex.len()].0));
        // Two triangles swapped for two that skip a ring vertex and come back: the walk from
        // apex 0 meets a start twice.
        t[0] = [0, ring(0), ring(2)];
        t[2] = [0, ring(2), ring(1)];
        assert!(!one_disc(&t, n as usize + 2)[0]);
        // The ring split into two cycles around apex 0.
        let mut t: Vec<[u32; 3]> = (0..n).map(|i| [0, ring(i), ring(i + 1)]).collect();
        t[n as usize / 2 - 1][2] = ring(0);
        t[n as usize - 1][2] = ring(n / 2);
        assert!(!one_disc(&t, n as usize + 2)[0]);
        // An open fan (a chain): one triangle gone.
        t = (1..n).map(|i| [0, ring(i), ring(i + 1)]).collect();
        assert!(!one_disc(&t, n as usize + 2)[0]);
    }

    #[test]
    fn an_unused_vertex_is_not_a_disc() {
        assert!(!one_disc(&octahedron(), 7)[6]);
    }
}
