//! Solids to and from indexed triangle meshes.

use super::Solid;
use crate::error::Result;
use crate::mesh::weld::Welder;
use crate::mesh::{FromMeshOptions, Mesh, repair};

impl Solid {
    /// The solid as an indexed triangle mesh that is a closed 2-manifold whenever the solid is
    /// closed: vertices welded, T-junctions removed, coplanar fragments of one source merged and
    /// triangulated without zero-area triangles, and solids that touch along an edge or at a
    /// vertex returned as separate manifold shells. Each triangle carries its polygon's source
    /// id. See [`Solid::to_mesh_unrepaired`] for the plain fan triangulation.
    #[must_use]
    pub fn to_mesh(&self) -> Mesh {
        repair::polygons_to_mesh(self.polygons(), self.tolerance().eps(), self.index())
    }

    /// Each polygon fanned into triangles, positions welded bit for bit and nothing else:
    /// after a boolean this has T-junctions. For inspecting what a boolean produced.
    #[must_use]
    pub fn to_mesh_unrepaired(&self) -> Mesh {
        let mut welder = Welder::with_capacity(self.corner_count() / 2);
        let mut triangles = Vec::with_capacity(self.corner_count());
        let mut sources = Vec::with_capacity(self.corner_count());
        for p in self.polygons() {
            let idx: Vec<u32> = p.vertices().iter().map(|&v| welder.index(v)).collect();
            for k in 1..idx.len() - 1 {
                let t = [idx[0], idx[k], idx[k + 1]];
                if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                    triangles.push(t);
                    sources.push(p.source());
                }
            }
        }
        Mesh {
            positions: welder.positions,
            triangles,
            sources,
        }
    }

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
    ///
    /// # Errors
    ///
    /// As [`Solid::from_mesh_with`].
    pub fn from_mesh(mesh: &Mesh) -> Result<Solid> {
        Solid::from_mesh_with(mesh, &FromMeshOptions::default())
    }

    /// A solid bounded by an indexed triangle mesh: one polygon per triangle, carrying the
    /// triangle's source id.
    ///
    /// Refused with [`Error::InvalidMesh`](crate::Error::InvalidMesh), whose message gives the counts, when:
    /// - `sources` and `triangles` differ in length;
    /// - a triangle uses a vertex index beyond `positions`;
    /// - a position used by a triangle has a NaN or infinite coordinate (unused ones are
    ///   ignored);
    /// - with [`require_closed`](FromMeshOptions::require_closed) (the default): a triangle
    ///   repeats an index, the mesh is not closed (edges used by one triangle, by more than
    ///   two, or by two in the same direction), or it is inside out (a shell winds clockwise
    ///   seen from outside and is no cavity).
    ///
    /// Triangles of zero area (by [`MeshReport::ZERO_AREA_ULPS`](crate::MeshReport::ZERO_AREA_ULPS)) are
    /// skipped: they bound no area, and the plane of a sliver is noise that would mislead
    /// the BSP. Their edges still count when closure is checked, so a crack closed by a sliver
    /// is accepted. The empty mesh gives the empty solid. The input is taken as exact: the
    /// solid carries no tolerance.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidMesh`](crate::Error::InvalidMesh) with the [`MeshDefect`](crate::MeshDefect) in the cases listed
    /// above.
    pub fn from_mesh_with(mesh: &Mesh, options: &FromMeshOptions) -> Result<Solid> {
        super::overlapping::solid_from_mesh(mesh, options)
    }
}

impl From<&Solid> for Mesh {
    fn from(solid: &Solid) -> Mesh {
        solid.to_mesh()
    }
}

impl TryFrom<&Mesh> for Solid {
    type Error = crate::error::Error;

    /// [`Solid::from_mesh`]: the mesh checked with the default (strict) options.
    fn try_from(mesh: &Mesh) -> Result<Solid> {
        Solid::from_mesh(mesh)
    }
}
