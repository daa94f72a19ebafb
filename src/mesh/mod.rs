//! The indexed triangle mesh: what booleans and marching cubes produce and file writers consume.

use glam::DVec3;

use crate::error::{Error, MeshDefect, Result};
use crate::geom::Aabb;
use crate::topology::check_face_indices;

/// An indexed triangle mesh with f64 positions and, per triangle, the id of the input it came
/// from (materials ride on these ids). Triangles wind counter-clockwise seen from outside.
///
/// A plain exchange type, like a file's content: the fields are public and may hold anything.
/// [`Mesh::try_new`] checks the lengths and indices where a caller wants that up front;
/// otherwise [`Mesh::report`] describes whatever the mesh holds, and readers, writers and
/// [`Solid::from_mesh`](crate::Solid::from_mesh) refuse a mesh that breaks them with its
/// [`MeshDefect`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
    /// Per-triangle source id; same length as `triangles`.
    pub sources: Vec<u32>,
}

/// A named colour for the triangles of one source id.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The name written to files (glTF material name, OBJ `usemtl`).
    pub name: String,
    /// Linear RGBA, each in 0..=1.
    pub base_color: [f64; 4],
}

impl Material {
    /// The name of the material given to triangles without one: source ids a file's
    /// materials do not cover, and scene primitives without a material.
    pub const DEFAULT_NAME: &'static str = "default";
    /// Its colour, a light grey (linear RGBA).
    pub const DEFAULT_COLOR: [f64; 4] = [0.8, 0.8, 0.8, 1.0];
}

impl Default for Material {
    /// The default material: [`Material::DEFAULT_NAME`] in [`Material::DEFAULT_COLOR`].
    fn default() -> Self {
        Material {
            name: Material::DEFAULT_NAME.to_owned(),
            base_color: Material::DEFAULT_COLOR,
        }
    }
}

impl Mesh {
    /// A mesh from positions, triangles and one source id per triangle, checked: refused with
    /// [`MeshDefect::SourceCount`] when the lengths differ and
    /// [`MeshDefect::IndexOutOfRange`] when a triangle refers to a missing vertex.
    ///
    /// ```
    /// use bspcsg::{Mesh, glam::DVec3};
    /// let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    /// assert!(Mesh::try_new(p.clone(), vec![[0, 1, 2]], vec![7]).is_ok());
    /// assert!(Mesh::try_new(p.clone(), vec![[0, 1, 3]], vec![7]).is_err());
    /// assert!(Mesh::try_new(p, vec![[0, 1, 2]], vec![]).is_err());
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::InvalidMesh`] with the defect, as above.
    pub fn try_new(
        positions: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
        sources: Vec<u32>,
    ) -> Result<Self> {
        if sources.len() != triangles.len() {
            return Err(Error::mesh(MeshDefect::SourceCount {
                sources: sources.len(),
                triangles: triangles.len(),
            }));
        }
        check_face_indices(&triangles, positions.len(), true)?;
        Ok(Mesh {
            positions,
            triangles,
            sources,
        })
    }

    /// The corner positions of every triangle whose indices are all in range, in order.
    pub fn triangle_corners(&self) -> impl Iterator<Item = [DVec3; 3]> + '_ {
        self.valid_triangles()
    }

    /// A mesh whose triangles all have source id 0. Indices are not checked (see
    /// [`Mesh::try_new`]).
    #[must_use]
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Self {
        let sources = vec![0; triangles.len()];
        Mesh {
            positions,
            triangles,
            sources,
        }
    }

    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// True when the mesh has no triangles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The corner positions of triangle `t`.
    ///
    /// # Panics
    ///
    /// When `t` or one of its vertex indices is out of range, like slice indexing. The
    /// measurements below skip such triangles instead; [`Mesh::report`] counts them.
    #[must_use]
    pub fn triangle(&self, t: usize) -> [DVec3; 3] {
        self.triangles[t].map(|i| self.positions[i as usize])
    }

    /// The corners of every triangle whose indices are all in range.
    fn valid_triangles(&self) -> impl Iterator<Item = [DVec3; 3]> + '_ {
        self.triangles.iter().filter_map(|t| {
            let [a, b, c] = t.map(|i| self.positions.get(i as usize).copied());
            Some([a?, b?, c?])
        })
    }

    /// The pairs of triangles whose interiors cross (indices, smaller first, sorted): empty for
    /// the surface of a solid; overlapping shells, or a shell through itself, give some. Exact
    /// (orientation predicates on the coordinates as stored). An edge of one through the
    /// other's interior counts, and so do two triangles in one plane facing the same way whose
    /// interiors overlap (shells meeting only in shared planes; a triangle and its copy);
    /// triangles that only touch (along an edge, at a point, face to face facing opposite
    /// ways) do not. Triangles of zero area have no interior and cross nothing. At most
    /// [`MAX_CROSSING_PAIRS`] pairs are found (which ones is then not fixed), and at most
    /// [`PAIR_BUDGET_PER_TRIANGLE`] candidate pairs per triangle (and [`PAIR_BUDGET_BASE`])
    /// are looked at, so a hostile file costs bounded time and memory.
    /// [`crate::Solid::from_mesh`] refuses a closed mesh that has any.
    ///
    /// # Errors
    /// [`MeshDefect::CrossingCheckOverBudget`](crate::MeshDefect::CrossingCheckOverBudget)
    /// where the budget ran out before a crossing was found (pairs found before it are
    /// returned: the mesh crosses, whatever the rest).
    pub fn crossing_triangle_pairs(&self) -> crate::Result<Vec<[u32; 2]>> {
        let found = self_intersect::crossing_pairs(&self.positions, &self.triangles);
        if found.pairs.is_empty() && !found.complete {
            return Err(crate::Error::mesh(
                crate::MeshDefect::CrossingCheckOverBudget {
                    triangles: self.triangles.len(),
                    candidates: found.offered,
                },
            ));
        }
        Ok(found.pairs.into_iter().map(|(t, u)| [t, u]).collect())
    }

    /// The bounding box of the vertices used by triangles.
    #[must_use]
    pub fn bbox(&self) -> Aabb {
        let mut b = Aabb::EMPTY;
        for t in self.valid_triangles() {
            for p in t {
                b.grow(p);
            }
        }
        b
    }

    /// Signed volume by the divergence theorem, summed relative to the box centre so that
    /// meshes far from the origin lose no precision. Positive for outward-facing closed meshes.
    #[must_use]
    pub fn volume(&self) -> f64 {
        let c = self.bbox().center();
        let sum: f64 = self
            .valid_triangles()
            .map(|t| {
                let [a, b, d] = t.map(|p| p - c);
                a.dot(b.cross(d))
            })
            .sum();
        sum / 6.0
    }

    /// Total surface area.
    #[must_use]
    pub fn area(&self) -> f64 {
        self.valid_triangles()
            .map(|[a, b, c]| 0.5 * (b - a).cross(c - a).length())
            .sum()
    }

    /// This mesh as a reader gives it back from a file of its positions: bit-identical
    /// positions (`-0.0` and `0.0` too) are one vertex, and solids that then share vertices
    /// where they touch along an edge or at a point get vertices of their own again. `None`
    /// when no two vertices share a position (the mesh reads back as it is).
    ///
    /// Solids [`to_mesh`](crate::Solid::to_mesh) gives touching along an edge read back as the
    /// same closed shells:
    ///
    /// ```
    /// use bspcsg::{Solid, glam::DVec3};
    /// let a = Solid::cube(1.0).unwrap();
    /// let b = a.clone().translate(DVec3::new(1.0, 1.0, 0.0)).unwrap();
    /// let mesh = a.union(&b).to_mesh();
    /// assert!(mesh.report().is_closed_manifold());
    /// let back = mesh.as_read_back().expect("the edge's ends share positions");
    /// assert!(back.report().is_closed_manifold());
    /// assert_eq!(back.vertex_count(), mesh.vertex_count());
    /// ```
    #[must_use]
    pub fn as_read_back(&self) -> Option<Mesh> {
        let mut welder = weld::Welder::with_capacity(self.positions.len());
        let map: Vec<u32> = self.positions.iter().map(|&p| welder.index(p)).collect();
        if welder.positions.len() == self.positions.len() {
            return None;
        }
        // As a reader: out-of-range corners are kept for the report to see, triangles that now
        // repeat a vertex are dropped.
        let mut welded = Mesh {
            positions: welder.positions,
            ..Mesh::default()
        };
        let mut readable = self.sources.len() == self.triangles.len();
        for (t, tri) in self.triangles.iter().enumerate() {
            let tri = tri.map(|i| map.get(i as usize).copied().unwrap_or(u32::MAX));
            readable &= !tri.contains(&u32::MAX);
            if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                welded.triangles.push(tri);
                welded
                    .sources
                    .push(self.sources.get(t).copied().unwrap_or_default());
            }
        }
        if !readable {
            return Some(welded);
        }
        Some(repair::split_touching(&welded).unwrap_or(welded))
    }
}

pub(crate) mod import;
pub(crate) mod needles;
pub(crate) mod repair;
pub(crate) mod report;
pub(crate) mod self_intersect;
pub(crate) mod weld;

pub use import::FromMeshOptions;
pub use report::{MeshReport, ShellReport};
pub use self_intersect::{MAX_CROSSING_PAIRS, PAIR_BUDGET_BASE, PAIR_BUDGET_PER_TRIANGLE};
