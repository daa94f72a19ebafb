//! Vertices on three planes, two of them nearly parallel, made one point for both operands of
//! a boolean.

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::Plane;
use crate::hash::{KeyedBuild, KeyedHashMap};

use super::Polygon;
use super::planes::{canonical, plane_bits};
use super::split::lex_less;

/// Below this sine of the angle between two of a vertex's three planes, the vertex is shared.
pub(crate) const SHARE_BELOW: f64 = 1e-3;

/// How far, in tolerances, a vertex may move to the shared point. The two operands' points
/// differ by a rounding error over the angle (3e-9 on a unit sphere turned 1e-4°, about 10³
/// tolerances); a point further off is not the same vertex computed twice.
const SHARE_REACH: f64 = 1e4;

type Key = [[u64; 6]; 3];

/// Where a facet of one operand crosses a nearly parallel facet of the other, each operand
/// cuts its own edges by the other's plane, and the crossing is only known to a rounding error
/// over the angle between them: the two operands' cut points lie 4e-11 … 3e-9 apart on a
/// sphere turned 1e-4° against a weld of 3e-11, and never weld.
///
/// A vertex of a clipped polygon whose two edges' planes are known lies on three planes, its
/// polygon's and those two; every vertex on the same three planes is the same point. Where two
/// of the planes are nearly parallel, each vertex is moved to one representative of all the
/// points computed for it: the least, lexicographically — a point one operand did compute (so
/// it stays where that operand's side tests put it), chosen the same whichever order the
/// polygons come in.
pub(crate) fn share_near_parallel_vertices(groups: &mut [&mut Vec<Polygon>], eps: f64) {
    // The vertices that have a key, in order, so the second pass computes none again (the
    // planes' sines were half of this pass on real models). With more than one thread the keys
    // are found in parallel (every vertex's planes and sines: nearly all of the work), listed
    // in the same order.
    let parallel = rayon::current_num_threads() > 1;
    let mut keyed: Vec<(u32, u32, u32, Key)> = Vec::new();
    for (g, group) in groups.iter().enumerate() {
        if parallel {
            let found = group.par_iter().enumerate();
            keyed.par_extend(found.flat_map_iter(|(i, p)| keys_of(g, i, p)));
        } else {
            keyed.extend(group.iter().enumerate().flat_map(|(i, p)| keys_of(g, i, p)));
        }
    }
    let mut least: KeyedHashMap<Key, DVec3> =
        KeyedHashMap::with_capacity_and_hasher(keyed.len(), KeyedBuild::default());
    for &(g, i, k, key) in &keyed {
        let v = groups[g as usize][i as usize].vertices[k as usize];
        least
            .entry(key)
            .and_modify(|w| {
                if lex_less(v, *w) {
                    *w = v;
                }
            })
            .or_insert(v);
    }
    if least.is_empty() {
        return;
    }
    let reach = SHARE_REACH * eps;
    for (g, i, k, key) in keyed {
        let p = &mut groups[g as usize][i as usize];
        let (n, k) = (p.vertices.len(), k as usize);
        // The first pass put every key in `keyed` into `least`.
        let w = least[&key];
        let v = p.vertices[k];
        let (prev, next) = (p.vertices[(k + n - 1) % n], p.vertices[(k + 1) % n]);
        if w != v && w != prev && w != next && (w - v).length() <= reach {
            p.vertices[k] = w;
        }
    }
}

/// The keyed vertices of polygon `i` of group `g`: (group, polygon, vertex, key).
fn keys_of(g: usize, i: usize, p: &Polygon) -> impl Iterator<Item = (u32, u32, u32, Key)> + '_ {
    (0..p.vertices.len())
        .filter_map(move |k| key_of(p, k).map(|key| (g as u32, i as u32, k as u32, key)))
}

/// The sorted planes vertex `k` of `p` lies on, if both its edges' planes are known, the three
/// are distinct and two of them are nearly parallel.
fn key_of(p: &Polygon, k: usize) -> Option<Key> {
    let n = p.vertices.len();
    let before = p.edge_plane((k + n - 1) % n)?;
    let after = p.edge_plane(k)?;
    let planes = [p.plane, *before, *after];
    let sine = |a: &Plane, b: &Plane| a.normal.cross(b.normal).length();
    let s = [
        sine(&planes[0], &planes[1]),
        sine(&planes[0], &planes[2]),
        sine(&planes[1], &planes[2]),
    ];
    if s.contains(&0.0) || s.iter().all(|&x| x >= SHARE_BELOW) {
        return None;
    }
    let mut key = planes.map(|q| plane_bits(&canonical(&q)));
    key.sort_unstable();
    Some(key)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane(point: [f64; 3], normal: [f64; 3]) -> Plane {
        Plane::from_point_normal(DVec3::from(point), DVec3::from(normal)).unwrap()
    }

    /// A triangle in `own` with its edge planes.
    fn triangle(v: [DVec3; 3], own: Plane, edges: [Plane; 3]) -> Polygon {
        let mut p = Polygon::with_plane(v.into_iter().collect(), own, 0);
        p.edges = Some(edges.into_iter().collect());
        p
    }

    /// Two polygons (one of each operand) holding the vertex on the same three planes, z = 0,
    /// a plane 1e-7 rad off it and x = 0.5, computed 1e-9 apart: both get the lesser point. A
    /// vertex on three planes at large angles is left alone.
    #[test]
    fn a_vertex_on_three_planes_two_nearly_parallel_is_one_point() {
        let own = plane([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        let twin = plane([0.0, 0.3, 0.0], [0.0, -1e-7, 1.0]);
        let side = plane([0.5, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let other = plane([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let p = DVec3::new(0.5, 0.3, 0.0);
        let q = p + DVec3::new(0.0, 1e-9, 0.0);
        let (a0, a1) = (DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.5, 0.0, 0.0));
        // Vertex 2 (p) lies between edge 1 (along `side`) and edge 2 (along `twin`).
        let a = triangle([a0, a1, p], own, [other, side, twin]);
        // The same vertex from the other operand: own plane `twin`, edges `own` and `side`.
        let b = triangle([a1, q, a0], twin, [side, own, other]);
        let (mut first, mut second) = (vec![a], vec![b]);
        share_near_parallel_vertices(&mut [&mut first, &mut second], 1e-12);
        assert_eq!(first[0].vertices[2], p);
        assert_eq!(second[0].vertices[1], p);
        // Corners on `other`, `side` and `own` (all at right angles) are not moved.
        assert_eq!(first[0].vertices[1], a1);
    }
}
