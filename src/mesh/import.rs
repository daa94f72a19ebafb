//! Meshes in: the checks an indexed triangle mesh must pass to bound a solid, and its triangles
//! merged into the convex polygons `Solid::from_mesh` is made of.

use super::Mesh;
use crate::error::{Error, Result};
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
}

impl Default for FromMeshOptions {
    fn default() -> Self {
        FromMeshOptions {
            require_closed: true,
            merge_coplanar: true,
        }
    }
}

impl FromMeshOptions {
    /// Options that accept any mesh with valid indices and finite coordinates (for callers that
    /// want to go on with open or non-manifold input, such as a command-line override).
    pub fn lenient() -> Self {
        FromMeshOptions {
            require_closed: false,
            ..FromMeshOptions::default()
        }
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
        return Err(Error::InvalidMesh(format!(
            "{} source ids for {} triangles; there must be one per triangle",
            mesh.sources.len(),
            mesh.triangles.len()
        )));
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
            return Err(Error::InvalidMesh(format!(
                "inside out: {} of {} shells enclose no positive volume and are not \
                 cavities (faces must wind counter-clockwise seen from outside)",
                report.inverted_shells,
                report.shells.len()
            )));
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
    const MANY: usize = usize::MAX;
    const UNSET: u32 = u32::MAX;
    let (tris, pos) = (&mesh.triangles, &mesh.positions);
    let bbox = mesh.bbox();
    let tol = (1e-12 * bbox.diagonal()).max(64.0 * f64::EPSILON * bbox.max_abs());

    // Directed edge -> the one triangle that runs along it, or MANY.
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
    // The triangle across directed edge u -> v, if the edge is used once each way.
    let across = |u: u32, v: u32| -> Option<usize> {
        match (owner.get(&(u, v)), owner.get(&(v, u))) {
            (Some(&a), Some(&b)) if a != MANY && b != MANY => Some(b),
            _ => None,
        }
    };

    let mut done = vec![false; tris.len()];
    let mut next = vec![UNSET; pos.len()];
    let mut prev = vec![UNSET; pos.len()];
    let mut stamp = vec![usize::MAX; pos.len()];
    let mut stack: Vec<u32> = Vec::new();
    let mut out = Vec::new();
    for (seed, polygon) in triangles.iter().enumerate() {
        let Some(polygon) = polygon else { continue };
        if done[seed] {
            continue;
        }
        done[seed] = true;
        let plane = *polygon.plane();
        let p = |i: u32| pos[i as usize];
        // Strictly convex at b: a left turn about the normal, beyond rounding.
        let convex = |a: u32, b: u32, c: u32| {
            let (e, f) = (p(b) - p(a), p(c) - p(b));
            e.cross(f).dot(plane.normal) > STRICTLY_CONVEX * e.length() * f.length()
        };
        let [a, b, c] = tris[seed];
        for (u, v) in [(a, b), (b, c), (c, a)] {
            next[u as usize] = v;
            prev[v as usize] = u;
            stamp[u as usize] = seed;
        }
        stack.clear();
        stack.extend([a, b, c]);
        let mut corners = 3;
        // Each entry is the start of a ring edge to try; a merge replaces u -> v by
        // u -> w -> v, and both new edges are tried in turn.
        while let Some(u) = stack.pop() {
            let v = next[u as usize];
            let Some(t) = across(u, v) else { continue };
            let Some(other) = &triangles[t] else { continue };
            if done[t] || other.source() != polygon.source() {
                continue;
            }
            let tri = tris[t];
            let Some(&w) = tri.iter().find(|&&i| i != u && i != v) else {
                continue;
            };
            if stamp[w as usize] == seed
                || other.plane().normal.dot(plane.normal) <= 0.0
                || plane.distance(p(w)).abs() > tol
                || !convex(prev[u as usize], u, w)
                || !convex(u, w, v)
                || !convex(w, v, next[v as usize])
            {
                continue;
            }
            next[u as usize] = w;
            prev[w as usize] = u;
            next[w as usize] = v;
            prev[v as usize] = w;
            stamp[w as usize] = seed;
            done[t] = true;
            corners += 1;
            stack.extend([u, w]);
        }
        if corners == 3 {
            out.push(polygon.clone());
            continue;
        }
        let mut ring = Vertices::with_capacity(corners);
        let mut i = a;
        for _ in 0..corners {
            ring.push(p(i));
            i = next[i as usize];
        }
        // A strictly convex ring of positive area always has a plane; keep the seed's as a
        // fallback that cannot fail.
        out.push(
            Polygon::new(ring.clone(), polygon.source())
                .unwrap_or_else(|| Polygon::with_plane(ring, plane, polygon.source())),
        );
    }
    out
}
