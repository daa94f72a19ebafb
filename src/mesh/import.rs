//! Meshes in: the checks an indexed triangle mesh must pass to bound a solid, and its triangles
//! merged into the convex polygons `Solid::from_mesh` is made of.

mod merge;

use super::Mesh;
use crate::error::{Error, MeshDefect, Result};
use crate::geom::is_zero_area;
use crate::polygon::{Polygon, share_face_planes};
use crate::topology::{check_closed, check_face_indices, check_finite};
use merge::{merge_coplanar, merge_tolerance};

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
    /// - no merged polygon has more than [`DISC_CORNERS`](merge::DISC_CORNERS) corners, or two corners not next to
    ///   each other that an edge of a triangle outside it joins (`Merger::chords_are_inside` in [`merge`]);
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
    let triangles = triangle_polygons(mesh);
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
        let mut merged = merge_coplanar(mesh, &triangles, links.as_ref());
        discs &= merged.chords_inside;
        share_face_planes(
            &mut merged.polygons,
            &merged.neighbours,
            merge_tolerance(mesh),
        );
        merged.polygons
    } else {
        triangles.into_iter().flatten().collect()
    };
    let discs_if_apart = discs.then(|| used.iter().filter(|&&u| u).count());
    Ok(MeshPolygons {
        polygons,
        discs_if_apart,
    })
}

/// One polygon per triangle of non-zero area, `None` for the others. Repeated indices were
/// refused or have zero area, so `Polygon::new` only fails where Newell's method finds no
/// plane at all.
fn triangle_polygons(mesh: &Mesh) -> Vec<Option<Polygon>> {
    mesh.triangles
        .iter()
        .zip(&mesh.sources)
        .map(|(tri, &source)| {
            let corners = tri.map(|i| mesh.positions[i as usize]);
            if is_zero_area(corners) {
                return None;
            }
            Polygon::new(corners.as_slice(), source)
        })
        .collect()
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
}
