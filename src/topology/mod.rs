//! Face-set topology shared by the mesh report, mesh import and polyhedra: one edge table (the
//! half-edges of all faces sorted by undirected edge, so that each edge's uses sit next to each
//! other: `O(n log n)` and no hashing), and the checks that faces given by vertex indices must
//! pass to bound a solid. Knows nothing of meshes or solids, only index lists.

mod checks;
mod edges;

pub(crate) use checks::{check_closed, check_face_indices, check_finite};
pub(crate) use edges::EdgeTable;
