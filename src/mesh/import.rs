//! Meshes in: the checks an indexed triangle mesh must pass to bound a solid, and its triangles
//! merged into the convex polygons `Solid::from_mesh` is made of.

use super::Mesh;
use crate::error::{Error, MeshDefect, Result};
use crate::geom::is_zero_area;
use crate::hash::{FxBuild, FxHashMap};
use crate::polygon::{Polygon, Vertices};
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

/// The polygons of a solid bounded by `mesh`, after the checks [`FromMeshOptions`] asks for
/// (the rules are documented on `Solid::from_mesh_with`).
pub(crate) fn polygons_from_mesh(mesh: &Mesh, options: &FromMeshOptions) -> Result<Vec<Polygon>> {
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
    let polygons = if options.merge_coplanar {
        merge_coplanar(mesh, &triangles)
    } else {
        triangles.into_iter().flatten().collect()
    };
    Ok(polygons)
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
fn merge_coplanar(mesh: &Mesh, triangles: &[Option<Polygon>]) -> Vec<Polygon> {
    let mut merger = Merger::new(mesh, triangles);
    let mut out = Vec::new();
    for (seed, polygon) in triangles.iter().enumerate() {
        let Some(polygon) = polygon else { continue };
        if merger.done[seed] {
            continue;
        }
        merger.done[seed] = true;
        out.push(merger.grow(seed, polygon));
    }
    out
}

/// An edge used by more than one triangle in the same direction.
const MANY: usize = usize::MAX;
const UNSET: u32 = u32::MAX;

/// The state of [`merge_coplanar`]: edge ownership, which triangles are taken, and the ring
/// being grown as a linked list over vertex indices.
struct Merger<'a> {
    tris: &'a [[u32; 3]],
    pos: &'a [glam::DVec3],
    triangles: &'a [Option<Polygon>],
    /// How far off the seed's plane a new corner may lie.
    tol: f64,
    /// Directed edge -> the one triangle that runs along it, or [`MANY`].
    owner: FxHashMap<(u32, u32), usize>,
    done: Vec<bool>,
    next: Vec<u32>,
    prev: Vec<u32>,
    /// The seed whose ring a vertex is on.
    stamp: Vec<usize>,
    stack: Vec<u32>,
}

impl<'a> Merger<'a> {
    fn new(mesh: &'a Mesh, triangles: &'a [Option<Polygon>]) -> Self {
        let (tris, pos) = (&mesh.triangles, &mesh.positions);
        let bbox = mesh.bbox();
        let tol = (1e-12 * bbox.diagonal()).max(64.0 * f64::EPSILON * bbox.max_abs());
        let mut owner: FxHashMap<(u32, u32), usize> =
            FxHashMap::with_capacity_and_hasher(3 * tris.len(), FxBuild::default());
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
                corners += 1;
                self.stack.extend([u, w]);
            }
        }
        if corners == 3 {
            return polygon.clone();
        }
        let mut ring = Vertices::with_capacity(corners);
        let mut i = a;
        for _ in 0..corners {
            ring.push(self.p(i));
            i = self.next[i as usize];
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
