//! Coplanar regions: grouping, their boundaries, and dropping straight pass-through vertices.

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::Ring;
use crate::mesh::triangulate::{ear_clip_boundary, triangulate_boundary};
use crate::mesh::weld::FxHashMap;
use crate::polygon::Polygon;

/// Rings of one source in one plane, connected through shared edges.
struct Region {
    rings: Vec<u32>,
    source: u32,
    normal: DVec3,
}

/// Triangles (with their source ids) covering every ring, regions merged where possible.
pub(super) fn triangulate_regions(
    positions: &[DVec3],
    rings: &[Ring],
    polygons: &[Polygon],
    delta: f64,
) -> (Vec<[u32; 3]>, Vec<u32>) {
    let mut regions = group(positions, rings, polygons, delta);
    loop {
        let mut boundaries: Vec<Vec<(u32, u32)>> = regions
            .par_iter()
            .map(|r| boundary(rings, &r.rings))
            .collect();
        simplify(positions, &mut boundaries, delta);
        let results: Vec<Option<Vec<[u32; 3]>>> = regions
            .par_iter()
            .zip(&boundaries)
            .map(|(r, b)| triangulate_boundary(positions, r.normal, b))
            .collect();
        let failed: Vec<usize> = (0..regions.len())
            .filter(|&i| results[i].is_none() && regions[i].rings.len() > 1)
            .collect();
        if failed.is_empty() {
            let mut tris = Vec::new();
            let mut sources = Vec::new();
            for (i, result) in results.into_iter().enumerate() {
                let t = result.unwrap_or_else(|| {
                    ear_clip_boundary(positions, regions[i].normal, &boundaries[i])
                });
                sources.extend(std::iter::repeat_n(regions[i].source, t.len()));
                tris.extend(t);
            }
            return (tris, sources);
        }
        // A merged region whose boundary crosses itself: keep its polygons separate and redo
        // the pass, since neighbours may have dropped vertices these polygons still use.
        let mut split = Vec::with_capacity(regions.len());
        for (i, r) in regions.into_iter().enumerate() {
            if failed.binary_search(&i).is_ok() {
                split.extend(r.rings.iter().map(|&ring| Region {
                    rings: vec![ring],
                    source: r.source,
                    normal: r.normal,
                }));
            } else {
                split.push(r);
            }
        }
        regions = split;
    }
}

/// Unions rings that share an edge used by just the two of them, with the same source, facing
/// the same way, each ring's vertices within `delta` of the other's plane: a merged region is
/// retriangulated in one plane, so nearly flat curved patches must not merge.
fn group(positions: &[DVec3], rings: &[Ring], polygons: &[Polygon], delta: f64) -> Vec<Region> {
    let mut uses: FxHashMap<(u32, u32), SmallVec<[u32; 2]>> =
        FxHashMap::with_capacity_and_hasher(rings.len() * 4, Default::default());
    for (r, ring) in rings.iter().enumerate() {
        for (a, b) in ring_edges(&ring.verts) {
            uses.entry((a, b)).or_default().push(r as u32);
        }
    }
    let mut parent: Vec<u32> = (0..rings.len() as u32).collect();
    let find = |parent: &mut Vec<u32>, mut x: u32| {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    };
    for (r, ring) in rings.iter().enumerate() {
        let p = &polygons[ring.polygon as usize];
        for (a, b) in ring_edges(&ring.verts) {
            let (Some(fwd), Some(back)) = (uses.get(&(a, b)), uses.get(&(b, a))) else {
                continue;
            };
            if fwd.len() != 1 || back.len() != 1 {
                continue;
            }
            let other = &rings[back[0] as usize];
            let q = &polygons[other.polygon as usize];
            let within = |ring: &Ring, plane: &crate::geom::Plane| {
                ring.verts
                    .iter()
                    .all(|&v| plane.distance(positions[v as usize]).abs() <= delta)
            };
            if p.source() == q.source()
                && p.plane().normal.dot(q.plane().normal) > 0.0
                && within(other, p.plane())
                && within(ring, q.plane())
            {
                let (x, y) = (find(&mut parent, r as u32), find(&mut parent, back[0]));
                parent[x.max(y) as usize] = x.min(y);
            }
        }
    }
    let mut index: FxHashMap<u32, usize> = FxHashMap::default();
    let mut regions: Vec<Region> = Vec::new();
    for r in 0..rings.len() as u32 {
        let root = find(&mut parent, r);
        let k = *index.entry(root).or_insert_with(|| {
            let p = &polygons[rings[root as usize].polygon as usize];
            regions.push(Region {
                rings: Vec::new(),
                source: p.source(),
                normal: p.plane().normal,
            });
            regions.len() - 1
        });
        regions[k].rings.push(r);
    }
    regions
}

fn ring_edges(v: &[u32]) -> impl Iterator<Item = (u32, u32)> + '_ {
    (0..v.len()).map(move |k| (v[k], v[(k + 1) % v.len()]))
}

/// The directed edges of a region's rings that no other ring of it (nor the ring itself, where
/// a T-junction made a spike `a → b → a`) uses the other way.
fn boundary(rings: &[Ring], members: &[u32]) -> Vec<(u32, u32)> {
    let mut count: FxHashMap<(u32, u32), i32> = FxHashMap::default();
    for &m in members {
        for (a, b) in ring_edges(&rings[m as usize].verts) {
            *count.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
        }
    }
    let mut out = Vec::new();
    for &m in members {
        for (a, b) in ring_edges(&rings[m as usize].verts) {
            let c = count.get_mut(&(a.min(b), a.max(b))).expect("counted above");
            // Emit each surplus use once, in its own direction.
            if a < b && *c > 0 {
                *c -= 1;
                out.push((a, b));
            } else if a > b && *c < 0 {
                *c += 1;
                out.push((a, b));
            }
        }
    }
    out
}

/// Removes every vertex that lies within `delta` of the segment between its only two
/// neighbours and passes straight through on every boundary that uses it, from all of those
/// boundaries at once, so that adjacent regions keep matching edges.
fn simplify(positions: &[DVec3], boundaries: &mut [Vec<(u32, u32)>], delta: f64) {
    struct Edge {
        a: u32,
        b: u32,
        region: u32,
        alive: bool,
    }
    let mut edges: Vec<Edge> = Vec::new();
    for (r, b) in boundaries.iter().enumerate() {
        edges.extend(b.iter().map(|&(a, b)| Edge {
            a,
            b,
            region: r as u32,
            alive: true,
        }));
    }
    let mut outgoing: FxHashMap<u32, SmallVec<[u32; 4]>> = FxHashMap::default();
    let mut incoming: FxHashMap<u32, SmallVec<[u32; 4]>> = FxHashMap::default();
    for (i, e) in edges.iter().enumerate() {
        outgoing.entry(e.a).or_default().push(i as u32);
        incoming.entry(e.b).or_default().push(i as u32);
    }
    let mut work: Vec<u32> = outgoing.keys().copied().collect();
    work.sort_unstable();
    while let Some(v) = work.pop() {
        let (Some(outs), Some(ins)) = (outgoing.get(&v), incoming.get(&v)) else {
            continue;
        };
        if outs.is_empty() || outs.len() != ins.len() {
            continue;
        }
        // Exactly two neighbours, v strictly between them on a line.
        let mut nbrs: SmallVec<[u32; 2]> = SmallVec::new();
        for &e in outs.iter() {
            push_unique(&mut nbrs, edges[e as usize].b);
        }
        for &e in ins.iter() {
            push_unique(&mut nbrs, edges[e as usize].a);
        }
        if nbrs.len() != 2 || !between(positions, nbrs[0], v, nbrs[1], delta) {
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
            let into_y = incoming.get_mut(&y).expect("y has an incoming edge");
            into_y.retain(|e| *e != eo);
            into_y.push(ei);
        }
        outgoing.remove(&v);
        incoming.remove(&v);
        work.extend(nbrs);
    }
    for b in boundaries.iter_mut() {
        b.clear();
    }
    for e in edges.into_iter().filter(|e| e.alive) {
        boundaries[e.region as usize].push((e.a, e.b));
    }
}

fn push_unique(v: &mut SmallVec<[u32; 2]>, x: u32) {
    if !v.contains(&x) {
        v.push(x);
    }
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
    t > 0.0 && t < 1.0 && (a + d * t).distance(v) <= delta
}
