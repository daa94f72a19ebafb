//! Meshes in: [`Solid::from_mesh`] turns an indexed triangle mesh into a solid, after checking
//! that it bounds one.

use super::Mesh;
use super::validate::{check_closed, check_face_indices, check_finite, is_zero_area};
use crate::error::{Error, Result};
use crate::polygon::Polygon;
use crate::solid::Solid;

/// How [`Solid::from_mesh_with`] treats its input. The default is strict; see
/// [`FromMeshOptions::lenient`] for input that is known to be imperfect.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FromMeshOptions {
    /// Refuse meshes that do not close up (default `true`): every edge must be used by exactly
    /// two triangles in opposite directions, and no triangle may repeat a vertex index.
    ///
    /// With `false`, open, non-manifold and inconsistently oriented meshes are accepted as they
    /// are and triangles that repeat an index are dropped. Booleans on such a solid still
    /// finish, but their result is only as meaningful as the input: an open surface has no
    /// well-defined inside.
    pub require_closed: bool,
}

impl Default for FromMeshOptions {
    fn default() -> Self {
        FromMeshOptions {
            require_closed: true,
        }
    }
}

impl FromMeshOptions {
    /// Options that accept any mesh with valid indices and finite coordinates (for callers that
    /// want to go on with open or non-manifold input, such as a command-line override).
    pub fn lenient() -> Self {
        FromMeshOptions {
            require_closed: false,
        }
    }
}

impl Solid {
    /// A solid bounded by an indexed triangle mesh, checked: see [`Solid::from_mesh_with`]
    /// with the default (strict) options.
    ///
    /// ```
    /// use bspcsg::Solid;
    /// let mesh = Solid::cube(1.0)?.to_mesh();
    /// let again = Solid::from_mesh(&mesh)?;
    /// assert!((again.volume() - 1.0).abs() < 1e-12);
    ///
    /// let mut open = mesh.clone();
    /// open.triangles.pop();
    /// open.sources.pop();
    /// let err = Solid::from_mesh(&open).unwrap_err();
    /// assert!(err.to_string().contains("not closed: 3 boundary edges"));
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    pub fn from_mesh(mesh: &Mesh) -> Result<Solid> {
        Solid::from_mesh_with(mesh, &FromMeshOptions::default())
    }

    /// A solid bounded by an indexed triangle mesh: one polygon per triangle, carrying the
    /// triangle's source id.
    ///
    /// Refused with [`Error::InvalidMesh`], whose message gives the counts, when:
    /// - `sources` and `triangles` differ in length;
    /// - a triangle uses a vertex index beyond `positions`;
    /// - a position used by a triangle has a NaN or infinite coordinate (unused ones are
    ///   ignored);
    /// - with [`require_closed`](FromMeshOptions::require_closed) (the default): a triangle
    ///   repeats an index, or the mesh is not closed (edges used by one triangle, by more than
    ///   two, or by two in the same direction).
    ///
    /// Triangles of zero area (by [`MeshReport::ZERO_AREA_RELATIVE`](crate::MeshReport::ZERO_AREA_RELATIVE)) are
    /// skipped: they bound no area, and the plane of a sliver is noise that would mislead
    /// the BSP. Their edges still count when closure is checked, so a crack closed by a sliver
    /// is accepted. The empty mesh gives the empty solid. The input is taken as exact: the
    /// solid carries no tolerance.
    pub fn from_mesh_with(mesh: &Mesh, options: &FromMeshOptions) -> Result<Solid> {
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
        }
        let polygons = mesh
            .triangles
            .iter()
            .zip(&mesh.sources)
            .filter_map(|(tri, &source)| {
                let corners = tri.map(|i| mesh.positions[i as usize]);
                if is_zero_area(corners) {
                    return None;
                }
                // Repeated indices were refused or have zero area, so this only fails where
                // Newell's method finds no plane at all.
                Polygon::new(corners.as_slice(), source)
            })
            .collect();
        Ok(Solid::from_polygons(polygons))
    }
}
