//! The triangles a reader collects, and the mesh they make.
//!
//! Every reader drops a triangle that repeats a vertex after welding (it has no area, and only
//! a dangling edge of its own). Dropped triangles are counted, so that a file of nothing else
//! is told apart from a well-formed file with no faces at all: the first is refused, the
//! second is the empty mesh, as the writers produce for an empty result. Why the file holds
//! nothing decides how: twelve `f 1 1 2` lines repeat an index (a damaged file, exit 1), while
//! a box whose distinct corners weld into one point (a box of 10⁻⁶ at 10¹¹, where floats are
//! 1.5·10⁻⁵ apart) is geometry too small for its place, refused as a mesh that bounds nothing
//! (exit 2), as when its triangles keep their corners but lose their area.

use std::path::Path;

use glam::DVec3;

use super::parse_error;
use crate::error::{Error, MeshDefect, Result};
use crate::mesh::Mesh;
use crate::mesh::repair::split_touching;

/// Triangles of welded vertex indices, those that repeat a vertex dropped and counted.
#[derive(Default)]
pub(crate) struct Triangles {
    kept: Vec<[u32; 3]>,
    dropped: usize,
    /// Of the dropped, those whose corners the file gave as distinct vertices: their
    /// coordinates coincide.
    coincident: usize,
}

impl Triangles {
    pub fn with_capacity(n: usize) -> Self {
        Triangles {
            kept: Vec::with_capacity(n),
            dropped: 0,
            coincident: 0,
        }
    }

    /// Adds `t` unless two of its corners are one vertex. `distinct_in_file`: the file gave
    /// the corners as distinct vertices (always so where it has no indices, as STL), so a
    /// repeat is their coordinates coinciding, not an index repeated.
    #[inline]
    pub fn push(&mut self, t: [u32; 3], distinct_in_file: bool) {
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            self.kept.push(t);
        } else {
            self.dropped += 1;
            self.coincident += usize::from(distinct_in_file);
        }
    }

    /// The mesh of `positions` and the kept triangles; solids that touch along an edge or at
    /// a point, sharing vertices once welded, are given vertices of their own again (as
    /// `to_mesh` wrote them), so that a file of them reads back as closed shells.
    ///
    /// # Errors
    ///
    /// When the file had triangles but every one repeats a vertex: [`Error::InvalidMesh`]
    /// ([`MeshDefect::AllZeroArea`]) naming `path` where some had distinct corners whose
    /// coordinates coincide (the mesh is too small for its place, or bounds nothing), else
    /// [`Error::Parse`] naming `path`: the file repeats indices, so it is damaged, not empty.
    pub fn into_mesh(self, path: &Path, positions: Vec<DVec3>) -> Result<Mesh> {
        if self.kept.is_empty() && self.coincident > 0 {
            let reach = positions
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max);
            return Err(Error::InvalidMesh {
                path: Some(path.to_path_buf()),
                defect: MeshDefect::AllZeroArea {
                    triangles: self.dropped,
                    reach,
                },
            });
        }
        if self.kept.is_empty() && self.dropped > 0 {
            return Err(parse_error(
                path,
                None,
                format!(
                    "all {} triangles repeat a vertex, so none has an area; the file holds no \
                     surface",
                    self.dropped
                ),
            ));
        }
        let mesh = Mesh::new(positions, self.kept);
        Ok(split_touching(&mesh).unwrap_or(mesh))
    }
}
