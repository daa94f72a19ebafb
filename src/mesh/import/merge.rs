//! The coplanar merge of a mesh's triangles: edge-adjacent triangles of one source in one plane
//! grown into strictly convex polygons, and whether those polygons keep the mesh discs by
//! position.

use crate::hash::{KeyedBuild, KeyedHashMap};
use crate::mesh::Mesh;
use crate::mesh::repair::Links;
use crate::polygon::{Polygon, Vertices};

/// The most corners a merged polygon may have for the mesh to be discs by position
/// ([`MeshPolygons::discs_if_apart`](super::MeshPolygons::discs_if_apart)): each pair of its corners is looked up.
pub(super) const DISC_CORNERS: usize = 8;

/// How far off a merged polygon's plane a corner may lie: 10⁻¹² of the mesh's diagonal, or
/// the rounding of its largest coordinates.
pub(super) fn merge_tolerance(mesh: &Mesh) -> f64 {
    let bbox = mesh.bbox();
    (1e-12 * bbox.diagonal()).max(64.0 * f64::EPSILON * bbox.max_abs())
}

/// A corner of a merged polygon turns left by more than this sine of its angle: strictly convex
/// beyond rounding.
const STRICTLY_CONVEX: f64 = 1e-12;

/// Grows convex polygons from triangles by region growing: a seed triangle's ring takes in,
/// edge by edge, the triangle across each of its edges while that keeps the ring strictly
/// convex and in the seed's plane. `triangles[t]` is triangle t's polygon, `None` if skipped.
///
/// The ring is a linked list over vertex indices (`next`, `prev`), and `stamp` marks the
/// vertices of the current ring, so each polygon costs time linear in its size.
///
/// With the mesh's `links` (a mesh checked closed, each edge used once each way, and a disc at
/// every vertex), also says whether every merged polygon has its chords inside
/// ([`Merger::chords_are_inside`]); else false.
pub(super) fn merge_coplanar(
    mesh: &Mesh,
    triangles: &[Option<Polygon>],
    links: Option<&Links>,
) -> Merged {
    let mut merger = Merger::new(mesh, triangles);
    merger.links = links;
    merger.chords_inside = links.is_some();
    let mut out = Vec::new();
    for (seed, polygon) in triangles.iter().enumerate() {
        let Some(polygon) = polygon else { continue };
        if merger.done[seed] {
            continue;
        }
        merger.done[seed] = true;
        merger.current = out.len() as u32;
        out.push(merger.grow(seed, polygon));
    }
    // Two merged polygons with the same chord would each put the other corner in a corner's
    // link when fanned across it: the link then passes through one vertex twice.
    let chords = &mut merger.chords;
    chords.sort_unstable();
    let chords_apart = chords.windows(2).all(|w| w[0] != w[1]);
    let poly_of = &merger.poly_of;
    let neighbours = merger
        .beside
        .iter()
        .map(|&(i, t)| (i, poly_of[t as usize]))
        .filter(|&(i, j)| i != j)
        .collect();
    Merged {
        polygons: out,
        chords_inside: merger.chords_inside && chords_apart,
        neighbours,
    }
}

/// What [`merge_coplanar`] makes of a mesh's triangles.
pub(super) struct Merged {
    pub polygons: Vec<Polygon>,
    /// Whether every merged polygon has its chords inside and no two share a chord.
    pub chords_inside: bool,
    /// Pairs of polygons (indices into `polygons`) of one source that meet along an edge of the
    /// mesh used once each way (each pair once from either side): every pair of polygons that
    /// `polygon::share_face_planes` may join into one face.
    pub neighbours: Vec<(u32, u32)>,
}

/// An edge used by more than one triangle in the same direction.
const MANY: usize = usize::MAX;
const UNSET: u32 = u32::MAX;

/// Directed edge -> owner. Keyed (see `crate::hash`): the file chooses which vertex indices
/// pair up, so an unkeyed hash of the pairs could be flooded.
type EdgeOwners = KeyedHashMap<(u32, u32), usize>;

/// The state of [`merge_coplanar`]: edge ownership, which triangles are taken, and the ring
/// being grown as a linked list over vertex indices.
struct Merger<'a> {
    tris: &'a [[u32; 3]],
    pos: &'a [glam::DVec3],
    triangles: &'a [Option<Polygon>],
    /// How far off the seed's plane a new corner may lie.
    tol: f64,
    /// Directed edge -> the one triangle that runs along it, or [`MANY`].
    owner: EdgeOwners,
    done: Vec<bool>,
    next: Vec<u32>,
    prev: Vec<u32>,
    /// The seed whose ring a vertex is on.
    stamp: Vec<usize>,
    stack: Vec<u32>,
    /// The mesh's links, where the chords of merged polygons are checked.
    links: Option<&'a Links>,
    /// Whether every merged polygon so far has its chords inside (see
    /// [`Merger::chords_are_inside`]).
    chords_inside: bool,
    /// The current ring's edges that merges replaced (the diagonals of its triangles), while
    /// it has at most [`DISC_CORNERS`] corners.
    diagonals: [(u32, u32); DISC_CORNERS - 3],
    /// The chords of the merged polygons so far (pairs of corners not next to each other that
    /// no edge joins), lower vertex first, while every one has its chords inside.
    chords: Vec<(u32, u32)>,
    /// The index of the polygon being grown.
    current: u32,
    /// Triangle -> the index of the polygon it was merged into.
    poly_of: Vec<u32>,
    /// (polygon, triangle of the same source across one of its ring edges): the ring edges a
    /// merge refused, each of which stays an edge of the polygon.
    beside: Vec<(u32, u32)>,
}

impl<'a> Merger<'a> {
    fn new(mesh: &'a Mesh, triangles: &'a [Option<Polygon>]) -> Self {
        let (tris, pos) = (&mesh.triangles, &mesh.positions);
        let tol = merge_tolerance(mesh);
        let mut owner = EdgeOwners::with_capacity_and_hasher(3 * tris.len(), KeyedBuild::default());
        for (t, tri) in tris
            .iter()
            .enumerate()
            .filter(|(t, _)| triangles[*t].is_some())
        {
            for k in 0..3 {
                owner
                    .entry((tri[k], tri[(k + 1) % 3]))
                    .and_modify(|o| *o = MANY)
                    .or_insert(t);
            }
        }
        Merger {
            tris,
            pos,
            triangles,
            tol,
            owner,
            done: vec![false; tris.len()],
            next: vec![UNSET; pos.len()],
            prev: vec![UNSET; pos.len()],
            stamp: vec![usize::MAX; pos.len()],
            stack: Vec::new(),
            links: None,
            chords_inside: false,
            diagonals: [(UNSET, UNSET); DISC_CORNERS - 3],
            chords: Vec::new(),
            current: 0,
            poly_of: vec![UNSET; tris.len()],
            beside: Vec::new(),
        }
    }

    /// The triangle across directed edge u -> v, if the edge is used once each way.
    fn across(&self, u: u32, v: u32) -> Option<usize> {
        match (self.owner.get(&(u, v)), self.owner.get(&(v, u))) {
            (Some(&a), Some(&b)) if a != MANY && b != MANY => Some(b),
            _ => None,
        }
    }

    fn p(&self, i: u32) -> glam::DVec3 {
        self.pos[i as usize]
    }

    /// Whether no two corners of the merged polygon `ring` (at most [`DISC_CORNERS`] of them)
    /// not next to each other are joined by an edge of a triangle outside it; the pairs no
    /// edge joins (its chords) are kept in `chords`, for [`merge_coplanar`] to check that no
    /// other polygon has them.
    ///
    /// The polygon's own triangles join such corners only along the ring edges its merges
    /// replaced (`diagonals`); the mesh being closed, each of those is used by the two
    /// triangles beside it and no third. Any other pair must be no edge at all: the second is
    /// not in the first's link.
    fn chords_are_inside(&mut self, links: &Links, ring: &[u32]) -> bool {
        let n = ring.len();
        for i in 0..n {
            for j in i + 2..n - usize::from(i == 0) {
                let (u, w) = (ring[i], ring[j]);
                let diagonals = &self.diagonals[..n - 3];
                if diagonals.contains(&(u, w)) || diagonals.contains(&(w, u)) {
                    continue;
                }
                if links.of(u as usize).iter().any(|e| e.0 == w) {
                    return false;
                }
                self.chords.push((u.min(w), u.max(w)));
            }
        }
        true
    }

    /// Strictly convex at b: a left turn about `normal`, beyond rounding.
    fn convex(&self, normal: glam::DVec3, a: u32, b: u32, c: u32) -> bool {
        let (e, f) = (self.p(b) - self.p(a), self.p(c) - self.p(b));
        e.cross(f).dot(normal) > STRICTLY_CONVEX * e.length() * f.length()
    }

    /// The convex polygon grown from triangle `seed` (whose polygon is `polygon`).
    fn grow(&mut self, seed: usize, polygon: &Polygon) -> Polygon {
        self.poly_of[seed] = self.current;
        let [a, b, c] = self.tris[seed];
        for (u, v) in [(a, b), (b, c), (c, a)] {
            self.next[u as usize] = v;
            self.prev[v as usize] = u;
            self.stamp[u as usize] = seed;
        }
        self.stack.clear();
        self.stack.extend([a, b, c]);
        let mut corners = 3;
        // Each entry is the start of a ring edge to try; a merge replaces u -> v by
        // u -> w -> v, and both new edges are tried in turn.
        while let Some(u) = self.stack.pop() {
            if let Some((t, w)) = self.mergeable(seed, polygon, u) {
                let v = self.next[u as usize];
                self.next[u as usize] = w;
                self.prev[w as usize] = u;
                self.next[w as usize] = v;
                self.prev[v as usize] = w;
                self.stamp[w as usize] = seed;
                self.done[t] = true;
                self.poly_of[t] = self.current;
                if let Some(d) = self.diagonals.get_mut(corners - 3) {
                    *d = (u, v);
                }
                corners += 1;
                self.stack.extend([u, w]);
            }
        }
        if corners == 3 {
            return polygon.clone();
        }
        let mut ring = Vertices::with_capacity(corners);
        let mut at = [0u32; DISC_CORNERS];
        let mut i = a;
        for k in 0..corners {
            ring.push(self.p(i));
            if let Some(slot) = at.get_mut(k) {
                *slot = i;
            }
            i = self.next[i as usize];
        }
        if let Some(links) = self.links.filter(|_| self.chords_inside) {
            self.chords_inside =
                corners <= DISC_CORNERS && self.chords_are_inside(links, &at[..corners]);
        }
        // A strictly convex ring of positive area always has a plane; keep the seed's as a
        // fallback that cannot fail.
        Polygon::from_ring(ring.clone(), polygon.source())
            .unwrap_or_else(|| Polygon::with_plane(ring, *polygon.plane(), polygon.source()))
    }

    /// The triangle across ring edge `u -> next[u]` and its third vertex, when taking it in
    /// keeps the ring of `seed` strictly convex, in its plane and of one source. A triangle of
    /// the source refused is kept in `beside`: the edge stays one of the polygon's.
    fn mergeable(&mut self, seed: usize, polygon: &Polygon, u: u32) -> Option<(usize, u32)> {
        let plane = polygon.plane();
        let v = self.next[u as usize];
        let t = self.across(u, v)?;
        let other = self.triangles[t].as_ref()?;
        if other.source() != polygon.source() {
            return None;
        }
        if self.done[t] {
            self.beside.push((self.current, t as u32));
            return None;
        }
        let w = *self.tris[t].iter().find(|&&i| i != u && i != v)?;
        let refused = self.stamp[w as usize] == seed
            || other.plane().normal.dot(plane.normal) <= 0.0
            || plane.distance(self.p(w)).abs() > self.tol
            || !self.convex(plane.normal, self.prev[u as usize], u, w)
            || !self.convex(plane.normal, u, w, v)
            || !self.convex(plane.normal, w, v, self.next[v as usize]);
        if refused {
            self.beside.push((self.current, t as u32));
        }
        (!refused).then_some((t, w))
    }
}

#[cfg(test)]
mod tests {
    use super::{Mesh, Polygon};

    /// Issue 12 item 8 (edge ownership in merging an operand's coplanar triangles): a file
    /// chooses which vertex indices pair up as edges, so pairs crafted to share one bucket
    /// under the unkeyed hash spread under the map's own hasher like random pairs.
    #[test]
    fn crafted_edges_spread_in_the_edge_owner_map_like_random_ones() {
        use std::hash::BuildHasher;

        use crate::hash::test_support::{bucket_collisions, lcg};
        const N: usize = 1024;
        let buckets = (3 * N * 8 / 7).next_power_of_two();
        let mask = (buckets - 1) as u64;
        let fx = crate::hash::FxBuild::default();
        let crafted: Vec<(u32, u32)> = (0u32..)
            .map(|b| (1, b))
            .filter(|e| fx.hash_one(e) & mask == 0)
            .take(N)
            .collect();
        let mut next = lcg(0x9e37_79b9_7f4a_7c15);
        let random: Vec<(u32, u32)> = (0..N).map(|_| (1, (next() >> 40) as u32)).collect();
        let collisions = |edges: &[(u32, u32)], hash: &dyn Fn(&(u32, u32)) -> u64| {
            bucket_collisions(edges.iter().map(hash), buckets)
        };
        let owners =
            super::EdgeOwners::with_capacity_and_hasher(3 * N, crate::hash::KeyedBuild::default());
        let keyed = |e: &(u32, u32)| owners.hasher().hash_one(e);
        assert_eq!(
            collisions(&crafted, &|e| fx.hash_one(e)),
            (N * (N - 1) / 2) as u64
        );
        let (c, r) = (collisions(&crafted, &keyed), collisions(&random, &keyed));
        let spread = (N * N / (2 * buckets)) as u64;
        assert!(
            c <= 3 * r.max(spread),
            "crafted {c} vs random {r} collisions"
        );
        assert!(
            c <= 2 * spread.max(8),
            "crafted {c}, expected about {spread}"
        );
    }
    /// Round 23 found each flat face's neighbours by hashing every directed edge by its ends'
    /// positions (38 M instructions of 41 M on rocker-arm); the merge's refused edges give the
    /// same planes, bit for bit: on a 32 × 32 grid slab turned so that its cells' Newell planes
    /// differ (its faces must share planes, or the test could not fail), and on every closed
    /// model under `BSPCSG_MODELS` (openscad-nonmanifold-crash, read leniently only, differs in
    /// 4 of 1,116 polygons: edges of more than two triangles).
    #[test]
    fn the_merges_neighbours_share_the_planes_positions_do() {
        use crate::polygon::{share_face_planes, share_face_planes_by_position};
        let mut meshes = vec![("turned grid slab".to_string(), turned_grid_slab(32))];
        if let Some(dir) = std::env::var_os("BSPCSG_MODELS") {
            let mut paths: Vec<_> = std::fs::read_dir(dir)
                .unwrap()
                .map(|e| e.unwrap().path())
                .filter(|p| p.extension().is_some_and(|e| e == "obj"))
                .collect();
            paths.sort();
            for path in paths {
                let name = path.file_name().unwrap().to_string_lossy().into_owned();
                meshes.push((name, crate::io::read_mesh(&path).unwrap()));
            }
        }
        let bits = |p: &Polygon| {
            let plane = p.plane();
            let bits3 = |v: glam::DVec3| v.to_array().map(f64::to_bits);
            (
                bits3(plane.normal),
                plane.offset.to_bits(),
                bits3(plane.anchor),
            )
        };
        for (name, mesh) in &meshes {
            let merged = super::merge_coplanar(mesh, &super::super::triangle_polygons(mesh), None);
            let tol = super::merge_tolerance(mesh);
            let mut given = merged.polygons.clone();
            share_face_planes(&mut given, &merged.neighbours, tol);
            let mut by_position = merged.polygons.clone();
            share_face_planes_by_position(&mut by_position, tol);
            let moved = (0..given.len())
                .filter(|&i| bits(&given[i]) != bits(&merged.polygons[i]))
                .count();
            let differ = (0..given.len())
                .filter(|&i| bits(&given[i]) != bits(&by_position[i]))
                .count();
            println!(
                "{name}: {} polygons, {} neighbour pairs, {moved} planes shared, {differ} differ",
                given.len(),
                merged.neighbours.len()
            );
            // Where an edge is used by more than two triangles (a lenient read), the map kept
            // whichever polygon came last and the merge has no neighbour across it.
            if crate::topology::check_closed(&mesh.triangles).is_ok() {
                assert_eq!(differ, 0, "{name}");
            }
            if name.starts_with("turned") {
                assert!(moved > 1000, "{name}: {moved} planes shared");
            }
        }
    }

    /// A 2 × 2 × 0.5 slab whose top and bottom are `n` × `n` grids of triangles (two a cell) and
    /// whose sides are strips, turned 0.7 rad about (0.3, 1, 0.2).
    fn turned_grid_slab(n: u32) -> Mesh {
        let side = n + 1;
        let at = |i: u32, j: u32, top: bool| (if top { 0 } else { side * side }) + i * side + j;
        let turn = glam::DQuat::from_axis_angle(glam::DVec3::new(0.3, 1.0, 0.2).normalize(), 0.7);
        let mut positions = Vec::new();
        for z in [0.25, -0.25] {
            for i in 0..=n {
                for j in 0..=n {
                    let (x, y) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
                    positions.push(turn * glam::DVec3::new(2.0 * x - 1.0, 2.0 * y - 1.0, z));
                }
            }
        }
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let [a, b, c, d] = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
                let top = |(i, j)| at(i, j, true);
                let bottom = |(i, j)| at(i, j, false);
                triangles.push([top(a), top(b), top(c)]);
                triangles.push([top(a), top(c), top(d)]);
                triangles.push([bottom(a), bottom(c), bottom(b)]);
                triangles.push([bottom(a), bottom(d), bottom(c)]);
            }
        }
        let mut ring = Vec::new();
        ring.extend((0..n).map(|i| (i, 0)));
        ring.extend((0..n).map(|j| (n, j)));
        ring.extend((1..=n).rev().map(|i| (i, n)));
        ring.extend((1..=n).rev().map(|j| (0, j)));
        for (k, &p) in ring.iter().enumerate() {
            let q = ring[(k + 1) % ring.len()];
            let (tp, tq) = (at(p.0, p.1, true), at(q.0, q.1, true));
            let (bp, bq) = (at(p.0, p.1, false), at(q.0, q.1, false));
            triangles.push([tq, tp, bp]);
            triangles.push([tq, bp, bq]);
        }
        Mesh::new(positions, triangles)
    }
}
