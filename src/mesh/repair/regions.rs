//! Coplanar regions: grouping, their boundaries (the straight pass-through vertices dropped by
//! [`super::straight`]), and their triangles.

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::Ring;
use super::edges::{CROWDED, ONLY_USE, UNKNOWN, run_partners, sort_by_edge, undirected};
use super::straight::simplify;
use crate::geom::triangulate::{ear_clip_boundary, triangulate_boundary};
use crate::geom::{Plane, is_zero_area};
use crate::polygon::Polygon;

/// A region's simplified boundary and its triangles (`None` where triangulation failed).
type Triangulated = (Vec<(u32, u32)>, Option<Vec<[u32; 3]>>);

/// Rings of one source in one plane, connected through shared edges.
struct Region {
    rings: SmallVec<[u32; 4]>,
    source: u32,
    normal: DVec3,
}

/// Triangles (with their source ids) covering every ring, regions merged where possible.
/// `pins` marks vertices no region may drop (ones that polygons outside `rings` use).
pub(super) fn triangulate_regions(
    positions: &[DVec3],
    rings: &[Ring],
    polygons: &[Polygon],
    delta: f64,
    pins: &[bool],
    known: Vec<u32>,
) -> (Vec<[u32; 3]>, Vec<u32>) {
    let partner = edge_partners(rings, positions.len(), known);
    let mut regions = group(positions, rings, polygons, delta, &partner);
    // Where each ring's half-edges start in `partner`.
    let mut first_half: Vec<u32> = Vec::with_capacity(rings.len());
    let mut halves = 0u32;
    for ring in rings {
        first_half.push(halves);
        halves += ring.verts.len() as u32;
    }
    let mut region_of: Vec<u32> = vec![0; rings.len()];
    // Per region kept whole from the previous round, its simplified boundary and what that
    // triangulated to: a crack-heavy pass splits a few regions per round and redoes the rest,
    // whose boundaries mostly come out the same (triangulating them again was most of the
    // quick pass at 256×128).
    let mut carried: Vec<Option<Triangulated>> = Vec::new();
    carried.resize_with(regions.len(), || None);
    loop {
        // A region that is one triangle passes through as it is: nothing to merge and nothing
        // to retriangulate (most of a real model, far from the cut). Its corners are pinned, so
        // no neighbour drops them.
        let lone: Vec<Option<[u32; 3]>> = regions
            .par_iter()
            .map(|r| lone_triangle(positions, rings, r))
            .collect();
        let mut pinned = pins.to_vec();
        for t in lone.iter().flatten() {
            for &v in t {
                pinned[v as usize] = true;
            }
        }
        for (i, r) in regions.iter().enumerate() {
            for &m in &r.rings {
                region_of[m as usize] = i as u32;
            }
        }
        let across = Across {
            partner: &partner,
            first_half: &first_half,
            region_of: &region_of,
        };
        let mut boundaries: Vec<Vec<(u32, u32)>> = regions
            .par_iter()
            .zip(&lone)
            .map(|(r, l)| match l {
                Some(_) => Vec::new(),
                None => boundary(rings, &r.rings, &across),
            })
            .collect();
        simplify(positions, &mut boundaries, &pinned, delta);
        let results: Vec<Option<Vec<[u32; 3]>>> = regions
            .par_iter()
            .zip(&boundaries)
            .zip(&lone)
            .zip(&mut carried)
            .map(|(((r, b), l), c)| match (l, c.take()) {
                (Some(_), _) => Some(Vec::new()),
                (None, Some((before, result))) if before == *b => result,
                (None, _) => triangulate_boundary(positions, r.normal, b),
            })
            .collect();
        let failed: Vec<usize> = (0..regions.len())
            .filter(|&i| results[i].is_none() && regions[i].rings.len() > 1)
            .collect();
        if failed.is_empty() {
            let count = lone.iter().flatten().count()
                + results.iter().flatten().map(Vec::len).sum::<usize>();
            let mut tris = Vec::with_capacity(count);
            let mut sources = Vec::with_capacity(count);
            for (i, result) in results.into_iter().enumerate() {
                if let Some(t) = lone[i] {
                    sources.push(regions[i].source);
                    tris.push(t);
                    continue;
                }
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
        carried.clear();
        let done = boundaries.into_iter().zip(results);
        for (i, (r, (b, result))) in regions.into_iter().zip(done).enumerate() {
            if failed.binary_search(&i).is_ok() {
                split.extend(r.rings.iter().map(|&ring| Region {
                    rings: smallvec::smallvec![ring],
                    source: r.source,
                    normal: r.normal,
                }));
                carried.resize_with(split.len(), || None);
            } else {
                split.push(r);
                carried.push(Some((b, result)));
            }
        }
        regions = split;
    }
}

/// Groups rings that share an edge used by just the two of them, with the same source, facing
/// the same way, into regions whose every vertex lies within `delta` of the region's plane (its
/// first ring's): a region is retriangulated in that plane, so no chain of small steps may
/// carry it across a gentle fold. Smaller groups join larger ones, each of their vertices
/// checked once per join, so `O(n log n)` vertex checks in all.
fn group(
    positions: &[DVec3],
    rings: &[Ring],
    polygons: &[Polygon],
    delta: f64,
    partner: &[u32],
) -> Vec<Region> {
    // Each ring's plane and source, copied side by side once (in parallel, in ring order): the
    // joins below ask them of rings in no order, and read from the polygons (a few hundred bytes
    // apart) those reads were most of this function's time on two threads, cache misses.
    let info: Vec<(Plane, u32)> = rings
        .par_iter()
        .map(|r| {
            let p = &polygons[r.polygon as usize];
            (*p.plane(), p.source())
        })
        .collect();
    let plane_of = |r: u32| &info[r as usize].0;
    let source_of = |r: u32| info[r as usize].1;
    // group[r]: the group ring r belongs to, named by its first ring, which gives the plane
    // (a group only grows by appending, so its first ring stays). Its rings are a chain:
    // next[r] the ring after r (`u32::MAX` at the end), last[g] and size[g] of group g. A list
    // per ring was an allocation per join.
    let mut group: Vec<u32> = (0..rings.len() as u32).collect();
    let mut next: Vec<u32> = vec![u32::MAX; rings.len()];
    let mut last: Vec<u32> = group.clone();
    let mut size: Vec<u32> = vec![1; rings.len()];
    let mut half = 0usize;
    for (r, ring) in rings.iter().enumerate() {
        let edges = ring.verts.len();
        for &other in &partner[half..half + edges] {
            if other >= ONLY_USE {
                continue;
            }
            let (gx, gy) = (group[r], group[other as usize]);
            if gx == gy {
                continue;
            }
            let (big, small) = if size[gx as usize] >= size[gy as usize] {
                (gx, gy)
            } else {
                (gy, gx)
            };
            let plane = plane_of(big);
            let joins = chain(&next, small).all(|m| {
                source_of(m) == source_of(big)
                    && plane_of(m).normal.dot(plane.normal) > 0.0
                    && rings[m as usize]
                        .verts
                        .iter()
                        .all(|&v| plane.distance(positions[v as usize]).abs() <= delta)
            });
            if joins {
                let mut m = small;
                while m != u32::MAX {
                    group[m as usize] = big;
                    m = next[m as usize];
                }
                next[last[big as usize] as usize] = small;
                last[big as usize] = last[small as usize];
                size[big as usize] += size[small as usize];
            }
        }
        half += edges;
    }
    (0..rings.len() as u32)
        .filter(|&g| group[g as usize] == g)
        .map(|g| {
            let (first, source) = &info[g as usize];
            Region {
                source: *source,
                normal: first.normal,
                rings: chain(&next, g).collect(),
            }
        })
        .collect()
}

/// The rings of the chain starting at `first` (see [`group`]).
fn chain(next: &[u32], first: u32) -> impl Iterator<Item = u32> + '_ {
    std::iter::successors(Some(first), move |&r| {
        let n = next[r as usize];
        (n != u32::MAX).then_some(n)
    })
}

/// For each ring edge, in ring order and edge order, the ring across it when exactly one ring
/// uses the edge each way, [`ONLY_USE`] when it is the edge's only use, [`CROWDED`] otherwise
/// (see [`run_partners`]), given those `known` already ([`UNKNOWN`] where not).
///
/// The T-junction search already sorted the half-edges by undirected edge before it inserted
/// vertices, and edges it did not search kept their partners: only the rest are sorted here
/// (on a boolean's soup about a third), with any known edge that one of them runs along too
/// (a piece of a split edge can lie along a matched one). One sort of the half-edges by
/// undirected edge, not a hash map of edge uses: a boolean's soup has 10⁵ of them.
fn edge_partners(rings: &[Ring], vertex_count: usize, known: Vec<u32>) -> Vec<u32> {
    let partner = known;
    // (undirected edge, entry << 1 | reversed), and each entry's half-edge and ring: sorting
    // puts each edge's uses together.
    let mut keyed: Vec<(u64, u32)> = Vec::with_capacity(partner.len());
    let mut entry: Vec<(u32, u32)> = Vec::with_capacity(partner.len());
    let mut add = |half: usize, r: usize, a: u32, b: u32, keyed: &mut Vec<(u64, u32)>| {
        keyed.push((
            undirected(a, b),
            (entry.len() as u32) << 1 | u32::from(a > b),
        ));
        entry.push((half as u32, r as u32));
    };
    let mut half = 0usize;
    for (r, ring) in rings.iter().enumerate() {
        for (a, b) in ring_edges(&ring.verts) {
            if partner[half] == UNKNOWN {
                add(half, r, a, b, &mut keyed);
            }
            half += 1;
        }
    }
    if keyed.is_empty() {
        return partner;
    }
    let mut sorted = sort_by_edge(&keyed, vertex_count);
    if keyed.len() == partner.len() {
        // Nothing was known (the full search).
        return assigned(&sorted.items, &entry, partner);
    }
    // Known edges along an edge sorted here join its run: their partners change too.
    let unknown = keyed.len();
    half = 0;
    for (r, ring) in rings.iter().enumerate() {
        for (a, b) in ring_edges(&ring.verts) {
            if partner[half] != UNKNOWN {
                let low = a.min(b) as usize;
                let (s, e) = (sorted.starts[low] as usize, sorted.starts[low + 1] as usize);
                let key = undirected(a, b);
                if sorted.items[s..e].iter().any(|k| k.0 == key) {
                    add(half, r, a, b, &mut keyed);
                }
            }
            half += 1;
        }
    }
    if keyed.len() > unknown {
        sorted = sort_by_edge(&keyed, vertex_count);
    }
    assigned(&sorted.items, &entry, partner)
}

/// `partner` with the partners of the sorted uses `keyed` set, entry `e`'s half-edge and ring
/// being `entry[e]` (see [`edge_partners`]).
fn assigned(keyed: &[(u64, u32)], entry: &[(u32, u32)], mut partner: Vec<u32>) -> Vec<u32> {
    let mut i = 0;
    while i < keyed.len() {
        let mut j = i + 1;
        while j < keyed.len() && keyed[j].0 == keyed[i].0 {
            j += 1;
        }
        run_partners(
            &keyed[i..j],
            |e| entry[e as usize].0 as usize,
            |e| entry[e as usize].1,
            &mut partner,
        );
        i = j;
    }
    partner
}

/// The region's triangle when it is one ring of three corners spanning area (a flat one takes
/// the general path, which drops it).
fn lone_triangle(positions: &[DVec3], rings: &[Ring], region: &Region) -> Option<[u32; 3]> {
    let [ring] = region.rings[..] else {
        return None;
    };
    let &[a, b, c] = &rings[ring as usize].verts[..] else {
        return None;
    };
    let t = [a, b, c];
    (!is_zero_area(t.map(|v| positions[v as usize]))).then_some(t)
}

fn ring_edges(v: &[u32]) -> impl Iterator<Item = (u32, u32)> + '_ {
    (0..v.len()).map(move |k| (v[k], v[(k + 1) % v.len()]))
}

/// What the regions know of the ring edges: which ring lies across each ([`edge_partners`]),
/// and each ring's region.
struct Across<'a> {
    partner: &'a [u32],
    /// Ring `r`'s edges are `partner[first_half[r]..]`, in ring order.
    first_half: &'a [u32],
    region_of: &'a [u32],
}

impl Across<'_> {
    /// [`boundary`] from the partners, where every edge of the region has its own reverse in
    /// one ring or no other use: an edge is inner when the ring across is in the region too.
    /// `None` where some edge is used otherwise (three rings along it, a ring with it twice),
    /// for the count.
    fn boundary(&self, rings: &[Ring], members: &[u32]) -> Option<Vec<(u32, u32)>> {
        let region = self.region_of[*members.first()? as usize];
        let total = members.iter().map(|&m| rings[m as usize].verts.len()).sum();
        let mut out = Vec::with_capacity(total);
        for &m in members {
            let verts = &rings[m as usize].verts;
            let first = self.first_half[m as usize] as usize;
            for (k, edge) in ring_edges(verts).enumerate() {
                match self.partner[first + k] {
                    CROWDED => return None,
                    ONLY_USE => out.push(edge),
                    other if self.region_of[other as usize] != region => out.push(edge),
                    _ => {}
                }
            }
        }
        Some(out)
    }
}

/// The directed edges of a region's rings that no other ring of it (nor the ring itself, where
/// a T-junction made a spike `a → b → a`) uses the other way.
///
/// Two ways: the edge partners the grouping found say which edges are inner
/// ([`Across::boundary`]); where some edge has more uses than a pair, the uses are counted in a
/// sorted list (not a hash map: most regions are a ring or two, so a region costs no allocation
/// beyond its edges).
fn boundary(rings: &[Ring], members: &[u32], across: &Across) -> Vec<(u32, u32)> {
    if let Some(edges) = across.boundary(rings, members) {
        return edges;
    }
    let total = members.iter().map(|&m| rings[m as usize].verts.len()).sum();
    let mut edges: Vec<(u32, u32)> = Vec::with_capacity(total);
    for &m in members {
        edges.extend(ring_edges(&rings[m as usize].verts));
    }
    // (edge, uses a→b minus uses b→a, a < b).
    let mut count: Vec<(u64, i32)> = edges
        .iter()
        .map(|&(a, b)| (undirected(a, b), if a < b { 1 } else { -1 }))
        .collect();
    count.sort_unstable_by_key(|c| c.0);
    count.dedup_by(|later, kept| {
        let same = later.0 == kept.0;
        if same {
            kept.1 += later.1;
        }
        same
    });
    if count.len() == edges.len() {
        // No edge used twice: every edge is boundary.
        return edges;
    }
    let mut out = Vec::with_capacity(edges.len());
    for (a, b) in edges {
        let k = count
            .binary_search_by_key(&undirected(a, b), |c| c.0)
            .expect("counted above");
        let c = &mut count[k].1;
        // Emit each surplus use once, in its own direction.
        if a < b && *c > 0 {
            *c -= 1;
            out.push((a, b));
        } else if a > b && *c < 0 {
            *c += 1;
            out.push((a, b));
        }
    }
    out
}
