//! Vertices on three planes, two of them nearly parallel, made one point for both operands of
//! a boolean.

use std::hash::{BuildHasher, Hash, Hasher};
use std::sync::atomic::{AtomicU32, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::Plane;
use crate::hash::{KeyedBuild, PrehashedMap};

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
    // and their hashes are found in parallel (every vertex's planes and sines: nearly all of
    // the work), listed in the same order.
    let parallel = rayon::current_num_threads() > 1;
    let build = KeyedBuild::default();
    let mut keyed: Vec<Keyed> = Vec::new();
    let mut starts = vec![0];
    for (g, group) in groups.iter().enumerate() {
        if parallel {
            let found = group.par_iter().enumerate();
            keyed.par_extend(found.flat_map_iter(|(i, p)| keys_of(&build, g, i, p)));
        } else {
            let found = group.iter().enumerate();
            keyed.extend(found.flat_map(|(i, p)| keys_of(&build, g, i, p)));
        }
        starts.push(keyed.len());
    }
    if keyed.is_empty() {
        return;
    }
    // The least point of every key. Which point that is does not depend on the order the
    // vertices come in, but of equal points (−0 and +0) the first met is kept, so each key's
    // vertices are taken in order: by one walk per shard of the keys (split by their hash),
    // shards in parallel. Each vertex keeps its key's slot, so no key is hashed twice.
    let parallel = parallel && keyed.len() >= PARALLEL_FROM;
    let shards = if parallel {
        rayon::current_num_threads().min(MAX_SHARDS)
    } else {
        1
    };
    let points: &[&mut Vec<Polygon>] = groups;
    let least: Vec<Vec<DVec3>> = if parallel {
        let of_shard = |s| least_in_shard(points, &keyed, s, shards);
        (0..shards).into_par_iter().map(of_shard).collect()
    } else {
        vec![least_in_shard(points, &keyed, 0, 1)]
    };
    // Each vertex is moved with its polygon's neighbours as they stand, the earlier ones
    // perhaps moved already: the order matters within a polygon only, so polygons go in
    // parallel, in chunks.
    let reach = SHARE_REACH * eps;
    for (g, group) in groups.iter_mut().enumerate() {
        let keyed = &keyed[starts[g]..starts[g + 1]];
        let least = &least[..];
        let moved = |(c, polygons): (usize, &mut [Polygon])| {
            move_to_least(polygons, c * CHUNK, keyed, least, shards, reach);
        };
        if parallel {
            group.par_chunks_mut(CHUNK).enumerate().for_each(moved);
        } else {
            moved((0, &mut group[..]));
        }
    }
}

/// From this many keyed vertices, the least points are found in shards and the vertices moved
/// in parallel.
const PARALLEL_FROM: usize = 512;

/// At most this many shards of keys, whatever the pool's size.
const MAX_SHARDS: usize = 8;

/// Polygons per parallel job of the second pass.
const CHUNK: usize = 256;

/// A vertex that has a key: where it is, its key and the key's hash, and the slot of its key's
/// least point in its shard (set by [`least_in_shard`], each vertex by one shard only).
struct Keyed {
    g: u32,
    i: u32,
    k: u32,
    slot: AtomicU32,
    hash: u64,
    key: Key,
}

/// The shard of `hash` among `shards` (bits the map's own buckets do not start from).
fn shard_of(hash: u64, shards: usize) -> usize {
    (hash >> 32) as usize % shards
}

/// The least point of each key of shard `s` (in order of the key's first vertex), walking the
/// vertices in order; sets each of the shard's vertices' slot.
fn least_in_shard(
    groups: &[&mut Vec<Polygon>],
    keyed: &[Keyed],
    s: usize,
    shards: usize,
) -> Vec<DVec3> {
    let mut slots: PrehashedMap<Hashed<'_>, u32> =
        PrehashedMap::with_capacity_and_hasher(keyed.len() / shards, Default::default());
    let mut least: Vec<DVec3> = Vec::new();
    for e in keyed.iter().filter(|e| shard_of(e.hash, shards) == s) {
        let v = groups[e.g as usize][e.i as usize].vertices[e.k as usize];
        let seen = Hashed {
            hash: e.hash,
            key: &e.key,
        };
        let slot = *slots.entry(seen).or_insert_with(|| {
            least.push(v);
            (least.len() - 1) as u32
        });
        let w = &mut least[slot as usize];
        if lex_less(v, *w) {
            *w = v;
        }
        e.slot.store(slot, Ordering::Relaxed);
    }
    least
}

/// Moves each keyed vertex of `polygons` (polygon `first` onwards of the group whose keyed
/// vertices are `keyed`) to its key's least point, unless that is its own place, a neighbour's
/// or further than `reach`.
fn move_to_least(
    polygons: &mut [Polygon],
    first: usize,
    keyed: &[Keyed],
    least: &[Vec<DVec3>],
    shards: usize,
    reach: f64,
) {
    let start = keyed.partition_point(|e| (e.i as usize) < first);
    for e in &keyed[start..] {
        let Some(p) = polygons.get_mut(e.i as usize - first) else {
            break;
        };
        let slot = e.slot.load(Ordering::Relaxed) as usize;
        let w = least[shard_of(e.hash, shards)][slot];
        let (n, k) = (p.vertices.len(), e.k as usize);
        let v = p.vertices[k];
        let (prev, next) = (p.vertices[(k + n - 1) % n], p.vertices[(k + 1) % n]);
        if w != v && w != prev && w != next && (w - v).length() <= reach {
            p.vertices[k] = w;
        }
    }
}

/// A key as a map holds it: hashed once, and borrowed from its first vertex.
struct Hashed<'a> {
    hash: u64,
    key: &'a Key,
}

impl Hash for Hashed<'_> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u64(self.hash);
    }
}

impl PartialEq for Hashed<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.key == other.key
    }
}

impl Eq for Hashed<'_> {}

/// The keyed vertices of polygon `i` of group `g`, their keys hashed by `build`.
fn keys_of<'a>(
    build: &'a KeyedBuild,
    g: usize,
    i: usize,
    p: &'a Polygon,
) -> impl Iterator<Item = Keyed> + 'a {
    (0..p.vertices.len()).filter_map(move |k| {
        key_of(p, k).map(|key| {
            let mut h = build.build_hasher();
            key.iter().flatten().for_each(|&w| h.write_u64(w));
            Keyed {
                g: g as u32,
                i: i as u32,
                k: k as u32,
                slot: AtomicU32::new(0),
                hash: h.finish(),
                key,
            }
        })
    })
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
