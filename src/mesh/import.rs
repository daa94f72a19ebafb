//! Meshes in: the checks an indexed triangle mesh must pass to bound a solid, and its triangles
//! merged into the convex polygons `Solid::from_mesh` is made of.

use super::Mesh;
use crate::error::{Error, MeshDefect, Result};
use crate::geom::is_zero_area;
use crate::hash::{KeyedBuild, KeyedHashMap};
use crate::mesh::repair::Links;
use crate::polygon::{Polygon, Vertices, share_face_planes};
use crate::topology::{check_closed, check_face_indices, check_finite};

/// How [`Solid::from_mesh_with`](crate::Solid::from_mesh_with) treats its input. The default is strict; see
/// [`FromMeshOptions::lenient`] for input that is known to be imperfect.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FromMeshOptions {
    /// Refuse meshes that do not bound a solid (default `true`): every edge must be used by
    /// exactly two triangles in opposite directions, no triangle may repeat a vertex index, and
    /// every shell must enclose positive volume or be a cavity of one that does.
    ///
    /// With `false`, open, non-manifold and inconsistently oriented meshes are accepted as they
    /// are and triangles that repeat an index are dropped. Booleans on such a solid still
    /// finish, but their result is only as meaningful as the input: an open surface has no
    /// well-defined inside.
    pub require_closed: bool,
    /// Merge edge-adjacent triangles of the same source that lie in one plane into convex
    /// polygons (default `true`). Fewer polygons make booleans faster on meshes with flat
    /// regions, such as CAD exports or this crate's own output read back in; and a face split
    /// into triangles has a diagonal that later cuts must be computed along, which loses all
    /// precision where the face is far larger than what cuts it (a 10³⁸ box around a small part).
    ///
    /// Two triangles merge across an edge used by exactly those two, when the new corner lies
    /// within `max(1e-12 × box diagonal, 64 ε × largest |coordinate|)` of the region's plane
    /// (coplanar up to rounding, no more) and the result stays strictly convex. Every vertex
    /// stays where it was and no vertex is dropped, so the surface and its edges are exactly
    /// those of the triangles: no T-junctions, no collinear corners.
    pub merge_coplanar: bool,
    /// Take a closed mesh whose shells cross one another (two overlapping boxes written into
    /// one file) as the union of its shells (default `false`: refused as
    /// [`SelfIntersecting`](crate::MeshDefect::SelfIntersecting)). Each shell, with the
    /// cavities inside it, is built as a solid on its own and the solids are united. Only
    /// where each shell is a solid on its own: a shell that crosses itself is still refused,
    /// as [`ShellCrossesItself`](crate::MeshDefect::ShellCrossesItself) naming the crossing.
    /// Needs [`require_closed`](Self::require_closed) (a lenient read takes the mesh as it is).
    pub union_shells: bool,
}

impl Default for FromMeshOptions {
    fn default() -> Self {
        FromMeshOptions {
            require_closed: true,
            merge_coplanar: true,
            union_shells: false,
        }
    }
}

impl FromMeshOptions {
    /// Options that accept any mesh with valid indices and finite coordinates (for callers that
    /// want to go on with open or non-manifold input, such as a command-line override).
    #[must_use]
    pub fn lenient() -> Self {
        FromMeshOptions {
            require_closed: false,
            ..FromMeshOptions::default()
        }
    }

    /// These options with [`union_shells`](Self::union_shells) set to `union`.
    ///
    /// ```
    /// use bspcsg::{FromMeshOptions, Mesh, Solid};
    /// use bspcsg::glam::DVec3;
    /// // Two unit cubes overlapping, written as one mesh.
    /// let a = Solid::cube(1.0)?.to_mesh();
    /// let b = Solid::cube(1.0)?.translate(DVec3::new(0.5, 0.25, 0.25))?.to_mesh();
    /// let mut both = a.clone();
    /// let n = both.positions.len() as u32;
    /// both.positions.extend(&b.positions);
    /// both.triangles.extend(b.triangles.iter().map(|t| t.map(|i| i + n)));
    /// both.sources.extend(&b.sources);
    /// assert!(Solid::from_mesh(&both).is_err()); // crossing shells bound no solid
    /// let union = Solid::from_mesh_with(&both, &FromMeshOptions::default().with_union_shells(true))?;
    /// assert!((union.volume() - (2.0 - 0.5 * 0.75 * 0.75)).abs() < 1e-12);
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    #[must_use]
    pub fn with_union_shells(mut self, union: bool) -> Self {
        self.union_shells = union;
        self
    }

    /// These options with [`merge_coplanar`](Self::merge_coplanar) set to `merge`.
    #[must_use]
    pub fn with_merge_coplanar(mut self, merge: bool) -> Self {
        self.merge_coplanar = merge;
        self
    }
}

/// The polygons of a checked mesh, and when they are discs by position.
pub(crate) struct MeshPolygons {
    pub polygons: Vec<Polygon>,
    /// The number of vertices the mesh's triangles use, where the polygons are **discs by
    /// position** provided their corners take that many distinct positions (no two used
    /// vertices at one position, bit for bit, as the solid's vertex ids tell positions apart);
    /// `None` where they may not be.
    ///
    /// Discs by position: around every position a polygon has as a corner, the polygons there,
    /// each fanned into triangles from any of its corners (all of them turned the other way or
    /// none), form one closed disc in the sense of `repair::Links::disc`. `to_mesh` then need not
    /// walk the links of the vertices a boolean passes through with only such polygons around
    /// them (see `repair::indexed`). Said only of a mesh checked closed and free of crossings,
    /// where:
    /// - the triangles around every vertex form one closed disc (the crossing check's links);
    /// - no triangle was skipped for its zero area (its corners would lack it);
    /// - no merged polygon has more than [`DISC_CORNERS`] corners, or two corners not next to
    ///   each other that an edge of a triangle outside it joins ([`Merger::chords_are_inside`]);
    /// - no two merged polygons share such a pair of corners (a chord of both).
    ///
    /// A merged polygon's triangles have no vertex inside it, so those at one of its corners
    /// `v` are a fan through its other corners, a stretch of `v`'s disc from the corner after
    /// `v` to the one before. Fanned again from another corner, the stretch between the same
    /// two ends runs through other corners of the polygon; these are in no other polygon's
    /// stretch, fanned either way, since no triangle outside it joins them to `v` and no other
    /// polygon has them as corners with `v`. So the link stays one cycle through distinct
    /// vertices. (Faces merged within the merge's tolerance of a plane may be two sides of a
    /// plate thinner than it, with one chord across both.)
    pub discs_if_apart: Option<usize>,
}

/// The most corners a merged polygon may have for the mesh to be discs by position
/// ([`MeshPolygons::discs_if_apart`]): each pair of its corners is looked up.
const DISC_CORNERS: usize = 8;

/// The polygons of a solid bounded by `mesh`, after the checks [`FromMeshOptions`] asks for
/// (the rules are documented on `Solid::from_mesh_with`).
pub(crate) fn polygons_from_mesh(mesh: &Mesh, options: &FromMeshOptions) -> Result<MeshPolygons> {
    if mesh.sources.len() != mesh.triangles.len() {
        return Err(Error::mesh(MeshDefect::SourceCount {
            sources: mesh.sources.len(),
            triangles: mesh.triangles.len(),
        }));
    }
    check_face_indices(
        &mesh.triangles,
        mesh.positions.len(),
        !options.require_closed,
    )?;
    let mut used = vec![false; mesh.positions.len()];
    for &i in mesh.triangles.iter().flatten() {
        used[i as usize] = true;
    }
    check_finite(&mesh.positions, |i| used[i])?;
    let mut links = None;
    if options.require_closed {
        check_closed(&mesh.triangles)?;
        let report = mesh.report();
        if report.inverted_shells > 0 {
            return Err(Error::mesh(MeshDefect::InsideOut {
                inverted_shells: report.inverted_shells,
                shells: report.shells.len(),
            }));
        }
    }
    if options.require_closed {
        // Closed and outward, but two shells (or two parts of one) may still cross: such a
        // mesh bounds no solid (its volume counts the overlap twice) and misleads the BSP.
        let crossing = super::self_intersect::crossing_pairs(&mesh.positions, &mesh.triangles);
        if let Some(&(t, u)) = crossing.pairs.first() {
            return Err(Error::mesh(MeshDefect::SelfIntersecting {
                pairs: crossing.pairs.len(),
                more: crossing.pairs.len() >= super::self_intersect::MAX_CROSSING_PAIRS
                    || !crossing.complete,
                first: [t as usize, u as usize],
            }));
        }
        if !crossing.complete {
            return Err(Error::mesh(MeshDefect::CrossingCheckOverBudget {
                triangles: mesh.triangles.len(),
                candidates: crossing.offered,
            }));
        }
        links = crossing.discs;
    }
    // One polygon per triangle of non-zero area. Repeated indices were refused or have
    // zero area, so Polygon::new only fails where Newell's method finds no plane at all.
    let triangles: Vec<Option<Polygon>> = mesh
        .triangles
        .iter()
        .zip(&mesh.sources)
        .map(|(tri, &source)| {
            let corners = tri.map(|i| mesh.positions[i as usize]);
            if is_zero_area(corners) {
                return None;
            }
            Polygon::new(corners.as_slice(), source)
        })
        .collect();
    // A mesh of triangles that all span no area bounds nothing: say so rather than return the
    // empty solid, which would pass for a right answer.
    if !triangles.is_empty() && triangles.iter().all(Option::is_none) {
        return Err(Error::mesh(MeshDefect::AllZeroArea {
            triangles: triangles.len(),
            reach: mesh.bbox().max_abs(),
        }));
    }
    if !triangles.iter().all(Option::is_some) {
        links = None;
    }
    let mut discs = links.is_some();
    let polygons = if options.merge_coplanar {
        let (mut polygons, chords_inside) = merge_coplanar(mesh, &triangles, links.as_ref());
        discs &= chords_inside;
        share_face_planes(&mut polygons, merge_tolerance(mesh));
        polygons
    } else {
        triangles.into_iter().flatten().collect()
    };
    let discs_if_apart = discs.then(|| used.iter().filter(|&&u| u).count());
    Ok(MeshPolygons {
        polygons,
        discs_if_apart,
    })
}

/// How far off a merged polygon's plane a corner may lie: 10⁻¹² of the mesh's diagonal, or
/// the rounding of its largest coordinates.
fn merge_tolerance(mesh: &Mesh) -> f64 {
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
fn merge_coplanar(
    mesh: &Mesh,
    triangles: &[Option<Polygon>],
    links: Option<&Links>,
) -> (Vec<Polygon>, bool) {
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
        out.push(merger.grow(seed, polygon));
    }
    // Two merged polygons with the same chord would each put the other corner in a corner's
    // link when fanned across it: the link then passes through one vertex twice.
    let chords = &mut merger.chords;
    chords.sort_unstable();
    let chords_apart = chords.windows(2).all(|w| w[0] != w[1]);
    (out, merger.chords_inside && chords_apart)
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
    /// keeps the ring of `seed` strictly convex, in its plane and of one source.
    fn mergeable(&self, seed: usize, polygon: &Polygon, u: u32) -> Option<(usize, u32)> {
        let plane = polygon.plane();
        let v = self.next[u as usize];
        let t = self.across(u, v)?;
        let other = self.triangles[t].as_ref()?;
        if self.done[t] || other.source() != polygon.source() {
            return None;
        }
        let w = *self.tris[t].iter().find(|&&i| i != u && i != v)?;
        let refused = self.stamp[w as usize] == seed
            || other.plane().normal.dot(plane.normal) <= 0.0
            || plane.distance(self.p(w)).abs() > self.tol
            || !self.convex(plane.normal, self.prev[u as usize], u, w)
            || !self.convex(plane.normal, u, w, v)
            || !self.convex(plane.normal, w, v, self.next[v as usize]);
        (!refused).then_some((t, w))
    }
}

#[cfg(test)]
mod tests {
    use crate::{BoolOp, Mesh, Solid, boolean};
    use glam::DVec3;

    /// Triangle `t` of `positions` turned to face away from `centre`.
    fn outward(positions: &[DVec3], t: [u32; 3], centre: DVec3) -> [u32; 3] {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let facing = (b - a).cross(c - a).dot((a + b + c) / 3.0 - centre);
        if facing > 0.0 { t } else { [t[0], t[2], t[1]] }
    }

    /// A plate 2e-10 thick whose top and bottom are each two triangles of one source, merged
    /// into quads within the tolerance a far box sets, both with the chord from (-1,0,0) to
    /// (1,0,0). Fanned across that chord, both quads put the same corner twice in each pole's
    /// link: the edge between the poles in four triangles. The mesh is not discs by position,
    /// and a boolean that keeps the plate whole must still give a closed 2-manifold.
    #[test]
    fn two_polygons_with_one_chord_are_not_discs_by_position() {
        let h = 1e-10;
        let mut positions = vec![
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, h),
            DVec3::new(0.0, -1.0, h),
            DVec3::new(0.0, 1.0, -h),
            DVec3::new(0.0, -1.0, -h),
        ];
        let plate: [([u32; 3], u32); 8] = [
            ([0, 3, 2], 0),
            ([1, 2, 3], 0),
            ([0, 4, 5], 1),
            ([1, 5, 4], 1),
            ([0, 2, 4], 2),
            ([1, 4, 2], 3),
            ([0, 5, 3], 4),
            ([1, 3, 5], 5),
        ];
        let mut triangles: Vec<[u32; 3]> = plate
            .iter()
            .map(|(t, _)| outward(&positions, *t, DVec3::ZERO))
            .collect();
        let mut sources: Vec<u32> = plate.iter().map(|(_, s)| *s).collect();
        // A unit box far away widens the merge's tolerance past the plate's thickness.
        let far = Solid::cube(1.0)
            .unwrap()
            .translate(DVec3::splat(500.5))
            .unwrap()
            .to_mesh();
        let base = positions.len() as u32;
        positions.extend(&far.positions);
        triangles.extend(far.triangles.iter().map(|t| t.map(|i| i + base)));
        sources.extend(far.sources.iter().map(|s| s + 10));
        let mesh = Mesh {
            positions,
            triangles,
            sources,
        };
        let plate = Solid::from_mesh(&mesh).unwrap();
        assert!(!plate.clone().into_parts().1.unwrap().discs());
        let kept = boolean(&plate, &Solid::cube(4.0).unwrap(), BoolOp::Intersection).to_mesh();
        let report = kept.report();
        assert!(report.is_closed_manifold(), "{report}");
        assert_eq!(kept.triangles.len(), 8);
    }

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
}
