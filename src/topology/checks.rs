//! The checks that faces given by vertex indices must pass to bound a solid: finite positions
//! within range, faces of at least three distinct in-range indices, and closure.

use glam::DVec3;

use super::EdgeTable;
use crate::error::{Error, MeshDefect, Result};
use crate::geom::MAX_COORDINATE;

/// Refuses positions with a NaN or infinite coordinate, among those for which `used` holds.
pub(crate) fn check_finite(positions: &[DVec3], used: impl Fn(usize) -> bool) -> Result<()> {
    let bad = |i: &usize| used(*i) && !positions[*i].is_finite();
    let count = (0..positions.len()).filter(bad).count();
    if let Some(first) = (0..positions.len()).find(bad) {
        return Err(Error::mesh(MeshDefect::NonFinite {
            vertices: count,
            first,
            position: positions[first],
        }));
    }
    let far = |i: &usize| used(*i) && positions[*i].abs().max_element() > MAX_COORDINATE;
    let count = (0..positions.len()).filter(far).count();
    match (0..positions.len()).find(far) {
        Some(first) => Err(Error::mesh(MeshDefect::BeyondRange {
            vertices: count,
            first,
            position: positions[first],
            limit: MAX_COORDINATE,
        })),
        None => Ok(()),
    }
}

/// Refuses faces with fewer than three indices or an index out of range, and unless
/// `allow_repeats`, faces that repeat an index.
pub(crate) fn check_face_indices<F: AsRef<[u32]>>(
    faces: &[F],
    vertex_count: usize,
    allow_repeats: bool,
) -> Result<()> {
    if let Some((f, face)) = faces.iter().enumerate().find(|(_, f)| f.as_ref().len() < 3) {
        return Err(Error::mesh(MeshDefect::TooFewIndices {
            face: f,
            indices: face.as_ref().len(),
        }));
    }
    let out_of_range = |f: &F| f.as_ref().iter().any(|&i| i as usize >= vertex_count);
    let bad = faces.iter().filter(|f| out_of_range(f)).count();
    if let Some(first) = faces.iter().position(out_of_range) {
        let index = faces[first]
            .as_ref()
            .iter()
            .copied()
            .find(|&i| i as usize >= vertex_count)
            .unwrap_or_default();
        return Err(Error::mesh(MeshDefect::IndexOutOfRange {
            faces: bad,
            first_face: first,
            index,
            vertices: vertex_count,
        }));
    }
    if !allow_repeats {
        let bad = faces.iter().filter(|f| repeats(f.as_ref())).count();
        if let Some(first) = faces.iter().position(|f| repeats(f.as_ref())) {
            return Err(Error::mesh(MeshDefect::RepeatedIndex {
                faces: bad,
                first_face: first,
                indices: faces[first].as_ref().to_vec(),
            }));
        }
    }
    Ok(())
}

/// True when a face uses some index twice: pairwise for small faces, by sorting for large ones.
pub(crate) fn repeats(face: &[u32]) -> bool {
    if face.len() <= 16 {
        face.iter()
            .enumerate()
            .any(|(k, i)| face[k + 1..].contains(i))
    } else {
        let mut sorted = face.to_vec();
        sorted.sort_unstable();
        sorted.windows(2).any(|w| w[0] == w[1])
    }
}

/// Refuses faces that do not close up: every edge must be used by exactly two faces, in
/// opposite directions. Faces must have passed [`check_face_indices`] without repeats.
pub(crate) fn check_closed<F: AsRef<[u32]>>(faces: &[F]) -> Result<()> {
    let c = EdgeTable::new(faces, |_| true).counts();
    if c.boundary == 0 && c.non_manifold == 0 && c.inconsistent == 0 {
        Ok(())
    } else {
        Err(Error::mesh(MeshDefect::NotClosed {
            boundary_edges: c.boundary,
            non_manifold_edges: c.non_manifold,
            inconsistent_edges: c.inconsistent,
            edges: c.edges,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_faces_close() {
        let quad_pyramid: [&[u32]; 5] = [
            &[0, 3, 2, 1],
            &[0, 1, 4],
            &[1, 2, 4],
            &[2, 3, 4],
            &[3, 0, 4],
        ];
        assert!(check_closed(&quad_pyramid).is_ok());
        let open: [&[u32]; 4] = [&[0, 3, 2, 1], &[0, 1, 4], &[1, 2, 4], &[2, 3, 4]];
        let e = check_closed(&open).unwrap_err().to_string();
        assert!(e.contains("3 boundary edges"), "{e}");
    }

    #[test]
    fn repeats_small_and_large() {
        assert!(repeats(&[1, 2, 1]));
        assert!(!repeats(&[1, 2, 3]));
        let big: Vec<u32> = (0..40).collect();
        assert!(!repeats(&big));
        let mut twice = big.clone();
        twice.push(17);
        assert!(repeats(&twice));
    }
}
