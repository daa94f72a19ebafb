//! Inserting vertices that lie on an edge into that edge.

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::Ring;
use crate::geom::Aabb;
use crate::geom::bvh::Bvh;
use crate::hash::FxHashSet;
use crate::mesh::weld::Wide;

/// Inserts into every ring edge, in order along it, each vertex within its reach (`delta`, or
/// `wide.delta` for the listed crack vertices) of the edge's interior and farther than that
/// from its ends. `O((E + k) log V)` with a BVH over the vertices.
///
/// With `skip_matched`, an edge whose reverse some other ring already has is taken as matched
/// and left alone: usually only the polygons on its two sides meet along it, and that is most
/// edges, so most queries are skipped. Where a sliver's vertex lies on such an edge after all,
/// the pass leaves a crack, and the caller retries checking every edge.
pub(super) fn insert_on_edges(
    positions: &[DVec3],
    rings: &mut [Ring],
    delta: f64,
    wide: &Wide,
    skip_matched: bool,
) {
    let mut directed: FxHashSet<(u32, u32)> =
        FxHashSet::with_capacity_and_hasher(rings.len() * 4, Default::default());
    for ring in rings.iter() {
        let n = ring.verts.len();
        directed.extend((0..n).map(|k| (ring.verts[k], ring.verts[(k + 1) % n])));
    }
    let reach: Vec<f64> = positions.iter().map(|&p| wide.reach(p, delta)).collect();
    let search = wide.widest(delta);
    let boxes: Vec<Aabb> = positions.iter().map(|&p| Aabb::new(p, p)).collect();
    let bvh = Bvh::build(&boxes);
    rings.par_iter_mut().with_min_len(64).for_each(|ring| {
        let n = ring.verts.len();
        let mut out: SmallVec<[u32; 8]> = SmallVec::with_capacity(n);
        let mut on_edge: Vec<(f64, u32)> = Vec::new();
        for k in 0..n {
            let (ia, ib) = (ring.verts[k], ring.verts[(k + 1) % n]);
            let (a, b) = (positions[ia as usize], positions[ib as usize]);
            out.push(ia);
            if skip_matched && directed.contains(&(ib, ia)) {
                continue;
            }
            let d = b - a;
            let len2 = d.length_squared();
            if len2 == 0.0 {
                continue;
            }
            let query = Aabb::new(a.min(b), a.max(b));
            on_edge.clear();
            bvh.visit(
                |bx| bx.overlaps(&query, search),
                |w| {
                    if w != ia && w != ib {
                        let p = positions[w as usize];
                        let r = reach[w as usize];
                        // Distance to the line by the cross product: `a + d·t` would carry
                        // the rounding of the edge's length (10²² on a 10³⁸-long edge).
                        let len = len2.sqrt();
                        let along = (p - a).dot(d) / len;
                        let off = (p - a).cross(d).length() / len;
                        if along > r && along < len - r && off <= r {
                            on_edge.push((along, w));
                        }
                    }
                    false
                },
            );
            // Order by comparing the points themselves: their distances from `a` can round to
            // the same value on a long edge (1 and −1 are both 10³⁸ from an end at 10³⁸).
            on_edge.sort_by(|x, y| {
                (positions[x.1 as usize] - positions[y.1 as usize])
                    .dot(d)
                    .total_cmp(&0.0)
                    .then(x.0.total_cmp(&y.0))
            });
            out.extend(on_edge.iter().map(|&(_, w)| w));
        }
        ring.verts = out;
    });
}
