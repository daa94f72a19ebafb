//! From a bag of directed boundary segments (region on their left) to valid regions: end points
//! within the tolerance become one vertex, opposite copies of an edge cancel, the edges chain
//! into rings turning as far right as possible at shared vertices (so rings that touch at a
//! vertex stay separate), collinear runs merge, and holes go to the smallest outer ring around
//! them.

use glam::DVec2;

use super::{Region, crossing, signed_area2};
use crate::disjoint_sets::DisjointSets;
use crate::hash::{FxHashMap, KeyedHashMap, key};

/// Vertices and the directed edges between them, after welding.
pub(super) struct Graph {
    pub points: Vec<DVec2>,
    /// Directed edges with their multiplicity (> 0), opposite copies cancelled.
    pub edges: Vec<(u32, u32, i32)>,
}

/// Welds the end points of `segments` within `eps` and sums each undirected edge's copies with
/// sign (`a → b` counts +1, `b → a` −1). Edges whose ends weld together vanish.
pub(super) fn weld(segments: &[[DVec2; 2]], eps: f64) -> Graph {
    // Exact duplicates first (most ends are shared exactly), then clusters within eps.
    // Positions come from input, so their map is keyed (see `crate::hash`).
    let mut exact: KeyedHashMap<[u64; 3], u32> = KeyedHashMap::default();
    let mut points: Vec<DVec2> = Vec::new();
    let mut ends: Vec<[u32; 2]> = Vec::with_capacity(segments.len());
    for s in segments {
        ends.push(s.map(|p| {
            *exact.entry(key(p.extend(0.0))).or_insert_with(|| {
                points.push(p);
                points.len() as u32 - 1
            })
        }));
    }
    // Clusters within eps: sweep the points in x order; with a tolerance far below the
    // spacing of distinct points, each comparison window holds one or two points.
    let mut sets = DisjointSets::new(points.len());
    let mut by_x: Vec<u32> = (0..points.len() as u32).collect();
    by_x.sort_unstable_by(|&i, &j| points[i as usize].x.total_cmp(&points[j as usize].x));
    for (k, &i) in by_x.iter().enumerate() {
        let p = points[i as usize];
        for &j in &by_x[k + 1..] {
            let q = points[j as usize];
            if q.x - p.x > eps {
                break;
            }
            if q.distance(p) <= eps {
                sets.union(i as usize, j as usize);
            }
        }
    }
    // The first point of each cluster stands for it (the set root is its first member).
    let mut count: FxHashMap<u64, i32> = FxHashMap::default();
    let mut order: Vec<(u32, u32)> = Vec::new();
    for [a, b] in ends {
        let (a, b) = (sets.find(a as usize) as u32, sets.find(b as usize) as u32);
        if a == b {
            continue;
        }
        let (key, sign) = if a < b { ((a, b), 1) } else { ((b, a), -1) };
        let c = count.entry(pair_key(key)).or_insert_with(|| {
            order.push(key);
            0
        });
        *c += sign;
    }
    let edges = order
        .into_iter()
        .filter_map(|(a, b)| {
            let c = count[&pair_key((a, b))];
            match c.signum() {
                1 => Some((a, b, c)),
                -1 => Some((b, a, -c)),
                _ => None,
            }
        })
        .collect();
    Graph { points, edges }
}

fn pair_key((a, b): (u32, u32)) -> u64 {
    ((a as u64) << 32) | b as u64
}

/// For each half-edge `from → to`, the next one round the face on its left: at `to`, the
/// outgoing half-edge met first turning clockwise from the way back. Also returns each
/// vertex's out-degree.
pub(super) fn next_around_faces(points: &[DVec2], half: &[(u32, u32)]) -> (Vec<u32>, Vec<u32>) {
    // Outgoing half-edges per vertex (compressed rows), each row sorted by angle.
    let mut degree = vec![0u32; points.len()];
    for &(a, _) in half {
        degree[a as usize] += 1;
    }
    let mut start = Vec::with_capacity(points.len() + 1);
    start.push(0usize);
    for &d in &degree {
        start.push(start[start.len() - 1] + d as usize);
    }
    let mut fill = start.clone();
    let mut rows: Vec<(f64, u32)> = vec![(0.0, 0); half.len()];
    for (h, &(a, b)) in half.iter().enumerate() {
        let d = points[b as usize] - points[a as usize];
        rows[fill[a as usize]] = (d.y.atan2(d.x), h as u32);
        fill[a as usize] += 1;
    }
    for v in 0..points.len() {
        let row = &mut rows[start[v]..start[v + 1]];
        if row.len() > 1 {
            row.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
        }
    }
    let next = half
        .iter()
        .map(|&(a, b)| {
            let row = &rows[start[b as usize]..start[b as usize + 1]];
            if row.len() == 1 {
                return row[0].1;
            }
            let back = points[a as usize] - points[b as usize];
            let back = back.y.atan2(back.x);
            // The largest angle strictly below `back`, wrapping to the largest overall.
            let k = row.partition_point(|&(ang, _)| ang < back);
            if k > 0 {
                row[k - 1].1
            } else {
                row[row.len() - 1].1
            }
        })
        .collect();
    (next, degree)
}

/// Rings from the welded graph, collinear runs merged, degenerate rings dropped, holes nested.
pub(super) fn regions(segments: &[[DVec2; 2]], eps: f64) -> Vec<Region> {
    nest(rings(segments, eps))
}

/// Rings from the welded graph, collinear runs merged, degenerate rings dropped.
pub(super) fn rings(segments: &[[DVec2; 2]], eps: f64) -> Vec<Vec<DVec2>> {
    chain(&weld(segments, eps), eps)
}

fn chain(graph: &Graph, eps: f64) -> Vec<Vec<DVec2>> {
    let mut half: Vec<(u32, u32)> = Vec::new();
    for &(a, b, c) in &graph.edges {
        for _ in 0..c {
            half.push((a, b));
        }
    }
    let (next, out_degree) = next_around_faces(&graph.points, &half);
    let mut used = vec![false; half.len()];
    let mut rings = Vec::new();
    for start in 0..half.len() {
        if used[start] {
            continue;
        }
        let mut ids: Vec<u32> = Vec::new();
        let mut h = start;
        while !used[h] {
            used[h] = true;
            ids.push(half[h].0);
            h = next[h] as usize;
        }
        // A walk that returns elsewhere than its start means rounding broke a vertex's order;
        // the ring still closes on itself, and validity is checked below.
        let ring = merge_collinear(&ids, &graph.points, &out_degree, eps);
        if ring.len() >= 3 {
            let perimeter: f64 = (0..ring.len())
                .map(|i| ring[i].distance(ring[(i + 1) % ring.len()]))
                .sum();
            // Slivers thinner than the tolerance are not regions.
            if signed_area2(&ring).abs() > eps * perimeter {
                rings.push(ring);
            }
        }
    }
    rings
}

/// Drops vertices of degree two lying within `eps` of the line through their neighbours
/// (straight runs and zero-width spikes), repeating until none is left.
fn merge_collinear(ids: &[u32], points: &[DVec2], out_degree: &[u32], eps: f64) -> Vec<DVec2> {
    let removable = |p: u32, v: u32, n: u32| {
        if out_degree[v as usize] != 1 {
            return false;
        }
        let (p, v, n) = (points[p as usize], points[v as usize], points[n as usize]);
        let base = n - p;
        let len = base.length();
        if len == 0.0 {
            return true;
        }
        (base.perp_dot(v - p) / len).abs() <= eps
    };
    let mut kept: Vec<u32> = Vec::with_capacity(ids.len());
    for &v in ids {
        kept.push(v);
        while kept.len() >= 3 {
            let k = kept.len();
            if removable(kept[k - 3], kept[k - 2], kept[k - 1]) {
                kept.remove(k - 2);
            } else {
                break;
            }
        }
    }
    // Across the seam where the ring closes.
    loop {
        let k = kept.len();
        if k < 3 {
            break;
        }
        if removable(kept[k - 2], kept[k - 1], kept[0]) {
            kept.pop();
        } else if removable(kept[k - 1], kept[0], kept[1]) {
            kept.remove(0);
        } else {
            break;
        }
    }
    kept.into_iter().map(|i| points[i as usize]).collect()
}

/// Outer rings (counter-clockwise) become regions; each hole (clockwise) joins the smallest
/// outer ring around it.
pub(super) fn nest(rings: Vec<Vec<DVec2>>) -> Vec<Region> {
    let mut outers: Vec<(f64, [DVec2; 2], Vec<DVec2>)> = Vec::new();
    let mut holes: Vec<Vec<DVec2>> = Vec::new();
    for r in rings {
        let a = signed_area2(&r);
        if a > 0.0 {
            let (lo, hi) = r
                .iter()
                .fold((r[0], r[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
            outers.push((a, [lo, hi], r));
        } else {
            holes.push(r);
        }
    }
    outers.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut regions: Vec<Region> = outers
        .iter()
        .map(|(_, _, r)| Region {
            outer: r.clone(),
            holes: Vec::new(),
        })
        .collect();
    for hole in holes {
        let p = probe(&hole);
        let candidates: Vec<usize> = (0..outers.len())
            .filter(|&k| {
                let [lo, hi] = outers[k].1;
                p.cmpge(lo).all() && p.cmple(hi).all()
            })
            .collect();
        // A valid boundary puts every hole inside some outer ring: the smallest one around it,
        // so the largest candidate needs no test when the smaller ones fail. A hole outside
        // every box cannot come from a valid boundary; it is dropped.
        let home = candidates.split_last().map(|(&last, rest)| {
            rest.iter()
                .copied()
                .find(|&k| winding(&outers[k].2, p) != 0)
                .unwrap_or(last)
        });
        if let Some(k) = home {
            regions[k].holes.push(hole);
        }
    }
    regions
}

/// A point on a ring away from its vertices: the middle of its longest edge.
fn probe(ring: &[DVec2]) -> DVec2 {
    let n = ring.len();
    let k = (0..n)
        .max_by(|&i, &j| {
            let li = ring[i].distance_squared(ring[(i + 1) % n]);
            let lj = ring[j].distance_squared(ring[(j + 1) % n]);
            li.total_cmp(&lj)
        })
        .unwrap_or(0);
    0.5 * (ring[k] + ring[(k + 1) % n])
}

fn winding(ring: &[DVec2], p: DVec2) -> i64 {
    (0..ring.len())
        .map(|i| crossing(p, ring[i], ring[(i + 1) % ring.len()]))
        .sum()
}
