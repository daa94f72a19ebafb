//! Inserting vertices that lie on an edge into that edge.

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::Ring;
use super::edges::{UNKNOWN, run_partners, sort_by_edge, undirected};
use super::grid::Grid;
use crate::geom::Aabb;
use crate::mesh::weld::Wide;

/// Inserts into every ring edge, in order along it, each vertex within its reach (`delta`, or
/// `wide.delta` for the listed crack vertices) of the edge's interior and farther than that
/// from its ends. An edge whose ends a wide weld moved (`drag`, per vertex, empty when none
/// did) lies up to that move off where it was computed, so it takes vertices that much
/// farther too.
///
/// The candidate vertices go into a uniform grid and each searched edge asks it for the cells
/// along it ([`Grid`]): a BVH of the vertices queried per edge re-entered its top levels every
/// time, and a BVH of the edges descended together with it paired whole leaves.
///
/// With `skip_matched`, an edge whose reverse some other ring already has is taken as matched
/// and left alone: usually only the polygons on its two sides meet along it, and that is most
/// edges, so most queries are skipped. Where a sliver's vertex lies on such an edge after all,
/// the pass leaves a crack, and the caller retries checking every edge. `outside` lists directed
/// edges of polygons not among `rings` (the core of an indexed boolean) that match ring edges
/// all the same.
///
/// Returns, per ring edge after the insertion, its partner where the matched-edge check found
/// it (see [`reversed_edges`]), else [`UNKNOWN`]: the regions sort only the rest again.
pub(super) fn insert_on_edges(
    positions: &[DVec3],
    drag: &[f64],
    rings: &mut [Ring],
    delta: f64,
    wide: &Wide,
    skip_matched: bool,
    outside: &[(u32, u32)],
) -> Vec<u32> {
    let mut first_edge: Vec<usize> = Vec::with_capacity(rings.len() + 1);
    let mut total = 0usize;
    for ring in rings.iter() {
        first_edge.push(total);
        total += ring.verts.len();
    }
    let known = if skip_matched {
        reversed_edges(rings, outside, total, positions.len())
    } else {
        vec![UNKNOWN; total]
    };
    let matched = |h: usize| known[h] != UNKNOWN;
    let search = wide.widest(delta);
    // The candidates: every vertex, or, where matched edges are skipped, the ends of unmatched
    // edges. A vertex in the middle of a neighbour's edge splits the edge on its own side, so
    // those pieces have no reverse either: the ends of unmatched edges are the vertices that can
    // lie on one. Most of a boolean's result is matched, so the search tree is small.
    let mut candidate = vec![!skip_matched; positions.len()];
    if skip_matched {
        for (ring, &first) in rings.iter().zip(&first_edge) {
            let n = ring.verts.len();
            for k in 0..n {
                if !matched(first + k) {
                    candidate[ring.verts[k] as usize] = true;
                    candidate[ring.verts[(k + 1) % n] as usize] = true;
                }
            }
        }
    }
    let points: Vec<u32> = (0..positions.len() as u32)
        .filter(|&v| candidate[v as usize])
        .collect();
    let reach: Vec<f64> = points
        .iter()
        .map(|&v| wide.reach(positions[v as usize], delta))
        .collect();
    let spots: Vec<DVec3> = points.iter().map(|&v| positions[v as usize]).collect();
    // The edges to search, as (ring edge, first end, second end, drag), each with its box grown
    // by the reach and drag: a point within reach of the edge lies in it.
    let dragged = |v: u32| drag.get(v as usize).copied().unwrap_or(0.0);
    // Sized first: grown by doubling, these three were copied a dozen times each.
    let searched = known.iter().filter(|&&p| p == UNKNOWN).count();
    let mut edges: Vec<(u32, u32, u32, f64)> = Vec::with_capacity(searched);
    let mut edge_boxes: Vec<Aabb> = Vec::with_capacity(searched);
    let mut lengths: Vec<f64> = Vec::with_capacity(searched);
    for (ring, &first) in rings.iter().zip(&first_edge) {
        let n = ring.verts.len();
        for k in 0..n {
            let (ia, ib) = (ring.verts[k], ring.verts[(k + 1) % n]);
            let (a, b) = (positions[ia as usize], positions[ib as usize]);
            if matched(first + k) || (b - a).length_squared() == 0.0 {
                continue;
            }
            let slack = dragged(ia).max(dragged(ib));
            let grow = search + slack;
            edges.push(((first + k) as u32, ia, ib, slack));
            edge_boxes.push(Aabb::new(a.min(b) - grow, a.max(b) + grow));
            lengths.push(a.distance(b));
        }
    }
    if edges.is_empty() || points.is_empty() {
        return known;
    }
    // Cells two median edges wide (see [`Grid`]).
    let median = *lengths
        .select_nth_unstable_by(edges.len() / 2, f64::total_cmp)
        .1;
    let grid = Grid::new(&spots, 2.0 * median);
    // Each edge asks the grid for the points near it, in parallel over runs of edges; only the
    // points on an edge are kept, each once.
    let mut hits: Vec<Hit> = edges
        .par_iter()
        .zip(edge_boxes.par_iter())
        .with_min_len(256)
        .flat_map_iter(|(&(at, ia, ib, slack), edge_box)| {
            let mut found: SmallVec<[Hit; 2]> = SmallVec::new();
            let a = positions[ia as usize];
            let d = positions[ib as usize] - a;
            let grow = search + slack;
            grid.near_segment(a, positions[ib as usize], grow, |item| {
                let p = spots[item as usize];
                if !edge_box.contains_point(p, 0.0) {
                    return;
                }
                let w = points[item as usize];
                if w == ia || w == ib || found.iter().any(|h| h.vertex == w) {
                    return;
                }
                let r = reach[item as usize];
                // Distance to the line by the cross product: `a + d·t` would carry the rounding
                // of the edge's length (10²² on a 10³⁸-long edge).
                let len = d.length_squared().sqrt();
                let along = (p - a).dot(d) / len;
                let off = (p - a).cross(d).length() / len;
                if along > r && along < len - r && off <= r + slack {
                    found.push(Hit {
                        key: u64::from(at) << 32 | u64::from(w),
                        along,
                        vertex: w,
                    });
                }
            });
            found
        })
        .collect();
    if hits.is_empty() {
        return known;
    }
    // The edges were searched in ring order and their hits collected in that order, so the hits
    // come grouped by edge, edges ascending: only each edge's few hits need ordering by vertex
    // (a sort of the whole list was 3.5 M instructions of a block less 100 cylinders).
    // Should an edge's hits ever come apart, the whole list is sorted instead (checked in
    // release builds too: a hit out of place would be a vertex missed).
    let mut i = 0;
    while i < hits.len() {
        let edge = hits[i].key >> 32;
        let mut j = i + 1;
        while j < hits.len() && hits[j].key >> 32 == edge {
            j += 1;
        }
        if j < hits.len() && hits[j].key >> 32 < edge {
            hits.sort_unstable_by_key(|h| h.key);
            break;
        }
        if j - i > 1 {
            hits[i..j].sort_unstable_by_key(|h| h.key);
        }
        i = j;
    }
    // The hits of ring edge `k`: `hits[start[k]..start[k + 1]]`.
    let mut start = vec![0u32; total + 1];
    for h in &hits {
        start[(h.key >> 32) as usize + 1] += 1;
    }
    for k in 0..total {
        start[k + 1] += start[k];
    }
    let each = rings.par_iter_mut().enumerate().with_min_len(64);
    each.for_each(|(r, ring)| {
        let first = first_edge[r];
        let n = ring.verts.len();
        if start[first] == start[first + n] {
            return;
        }
        let mut out: SmallVec<[u32; 8]> = SmallVec::with_capacity(n);
        for k in 0..n {
            let (ia, ib) = (ring.verts[k], ring.verts[(k + 1) % n]);
            out.push(ia);
            let found = &hits[start[first + k] as usize..start[first + k + 1] as usize];
            if found.is_empty() {
                continue;
            }
            let mut on_edge: SmallVec<[&Hit; 4]> = found.iter().collect();
            let d = positions[ib as usize] - positions[ia as usize];
            // Order by comparing the points themselves: their distances from `a` can round to
            // the same value on a long edge (1 and −1 are both 10³⁸ from an end at 10³⁸).
            on_edge.sort_by(|x, y| {
                (positions[x.vertex as usize] - positions[y.vertex as usize])
                    .dot(d)
                    .total_cmp(&0.0)
                    .then(x.along.total_cmp(&y.along))
            });
            out.extend(on_edge.iter().map(|h| h.vertex));
        }
        ring.verts = out;
    });
    // Old edge `h` is now edge `h + start[h]` (the vertices inserted before it push it on), and
    // only edges that were not matched took vertices.
    let mut renumbered = vec![UNKNOWN; total + hits.len()];
    for (h, &p) in known.iter().enumerate() {
        if p != UNKNOWN {
            renumbered[h + start[h] as usize] = p;
        }
    }
    renumbered
}

/// A vertex found on a ring edge: `key` is the ring edge's index and the vertex's, `along` its
/// distance along the edge.
struct Hit {
    key: u64,
    along: f64,
    vertex: u32,
}

/// For each ring edge (rings in order, edges in ring order), its partner as
/// [`run_partners`](super::edges::run_partners) gives it where some ring, or an `outside`
/// edge, uses it the other way (the edge is matched), else [`UNKNOWN`]: one sort of the
/// half-edges by undirected edge rather than a hash set of them. A matched edge is not
/// searched, so it and its partner stand after the insertion, and the regions sort again only
/// the edges that were not matched.
fn reversed_edges(
    rings: &[Ring],
    outside: &[(u32, u32)],
    total: usize,
    vertex_count: usize,
) -> Vec<u32> {
    // (undirected edge, half-edge index << 1 | runs from the larger index to the smaller).
    let mut keyed: Vec<(u64, u32)> = Vec::with_capacity(total + outside.len());
    let mut owner: Vec<u32> = Vec::with_capacity(total);
    for (r, ring) in rings.iter().enumerate() {
        let n = ring.verts.len();
        for k in 0..n {
            let (a, b) = (ring.verts[k], ring.verts[(k + 1) % n]);
            keyed.push((
                undirected(a, b),
                (keyed.len() as u32) << 1 | u32::from(a > b),
            ));
            owner.push(r as u32);
        }
    }
    for &(a, b) in outside {
        keyed.push((
            undirected(a, b),
            (keyed.len() as u32) << 1 | u32::from(a > b),
        ));
    }
    let keyed = sort_by_edge(&keyed, vertex_count).items;
    let mut known = vec![UNKNOWN; total];
    let mut i = 0;
    while i < keyed.len() {
        let mut j = i + 1;
        while j < keyed.len() && keyed[j].0 == keyed[i].0 {
            j += 1;
        }
        let run = &keyed[i..j];
        if run.iter().any(|&(_, h)| (h ^ run[0].1) & 1 == 1) {
            // Outside edges are numbered past the rings' and come last: the regions see only
            // the rings' own uses.
            let rings_own = run
                .iter()
                .take_while(|&&(_, h)| ((h >> 1) as usize) < total);
            let own = rings_own.count();
            run_partners(
                &run[..own],
                |h| h as usize,
                |h| owner[h as usize],
                &mut known,
            );
        }
        i = j;
    }
    known
}
