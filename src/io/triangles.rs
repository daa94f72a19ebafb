//! The triangles a reader collects, and the mesh they make.
//!
//! Every reader drops a triangle that repeats a vertex after welding (it has no area, and only
//! a dangling edge of its own). Dropped triangles are counted, so that a file of nothing else
//! (twelve `f 1 1 2` lines) is told apart from a well-formed file with no faces at all: the
//! first is refused, the second is the empty mesh, as the writers produce for an empty result.

use std::path::Path;

use glam::DVec3;

use super::parse_error;
use crate::error::Result;
use crate::mesh::Mesh;
use crate::mesh::repair::split_touching;

/// Triangles of welded vertex indices, those that repeat a vertex dropped and counted.
#[derive(Default)]
pub(crate) struct Triangles {
    kept: Vec<[u32; 3]>,
    dropped: usize,
}

impl Triangles {
    pub fn with_capacity(n: usize) -> Self {
        Triangles {
            kept: Vec::with_capacity(n),
            dropped: 0,
        }
    }

    /// Adds `t` unless two of its corners are one vertex.
    #[inline]
    pub fn push(&mut self, t: [u32; 3]) {
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            self.kept.push(t);
        } else {
            self.dropped += 1;
        }
    }

    /// The mesh of `positions` and the kept triangles; solids that touch along an edge or at
    /// a point, sharing vertices once welded, are given vertices of their own again (as
    /// `to_mesh` wrote them), so that a file of them reads back as closed shells.
    ///
    /// # Errors
    ///
    /// [`Error::Parse`](crate::Error::Parse) naming `path` when the file had triangles but
    /// every one repeats a vertex: such a file is damaged, not empty.
    pub fn into_mesh(self, path: &Path, positions: Vec<DVec3>) -> Result<Mesh> {
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
