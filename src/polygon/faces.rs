//! One plane for all the polygons of one flat face of a mesh.

use crate::geom::Plane;
#[cfg(test)]
use crate::hash::key;

use super::Polygon;
#[cfg(test)]
use super::planes::edge_owners;

/// Gives the polygons of each flat face one plane, bit for bit: that of the first polygon of
/// the face (in the order given). A face is grown across `neighbours` (pairs of indices into
/// `polygons` that meet along an edge, either way round) from that polygon to neighbours of
/// the same source facing the same way, whose planes cross its plane at a sine below
/// [`PARALLEL_BELOW`](super::side::PARALLEL_BELOW) and all of whose vertices lie within `tol`
/// of it: the triangles of a tessellated flat face, which merge into several polygons where
/// a larger one would not be strictly convex (a grid's cells), each with its own Newell
/// plane, the same plane up to rounding. Mesh import's coplanar merge gives the pairs: it tries every edge of every
/// polygon it makes, so those it refused are the polygon's edges (no hashing of positions).
///
/// A boolean cuts such a face on one line only if its polygons share one plane. Where another
/// operand's face crosses it at a tiny angle α, the crossing line of each polygon's plane moves
/// by the rounding of that plane's position over α: a 2 × 2 slab whose top is a 16 × 16 grid,
/// turned 1e-9° against a cuboid's top (1.7e-11 rad), had each grid cell's piece cut on its own
/// line, up to 4e-7 from the cuboid's cut on the plane its tree kept for the whole top (108
/// boundary edges); so too where the slab's sides met the crossing lines at 1e-8°, the cut
/// points on three planes keyed by different planes of one face (see
/// `share_near_parallel_vertices`).
pub(crate) fn share_face_planes(polygons: &mut [Polygon], neighbours: &[(u32, u32)], tol: f64) {
    // Each polygon's neighbours, both ways round, as one array sliced by `start`.
    let mut start = vec![0u32; polygons.len() + 1];
    for &(i, j) in neighbours {
        start[i as usize + 1] += 1;
        start[j as usize + 1] += 1;
    }
    for i in 0..polygons.len() {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut beside = vec![0u32; 2 * neighbours.len()];
    for &(i, j) in neighbours {
        for (a, b) in [(i, j), (j, i)] {
            beside[fill[a as usize] as usize] = b;
            fill[a as usize] += 1;
        }
    }
    let mut face = vec![u32::MAX; polygons.len()];
    let mut stack = Vec::new();
    for first in 0..polygons.len() {
        if face[first] != u32::MAX {
            continue;
        }
        face[first] = first as u32;
        let (plane, source) = (polygons[first].plane, polygons[first].source);
        stack.push(first);
        while let Some(i) = stack.pop() {
            for &j in &beside[start[i] as usize..start[i + 1] as usize] {
                let j = j as usize;
                if face[j] == u32::MAX && same_face(&polygons[j], &plane, source, tol) {
                    face[j] = first as u32;
                    stack.push(j);
                }
            }
        }
    }
    for i in 0..polygons.len() {
        let first = face[i] as usize;
        if first != i {
            polygons[i].plane = polygons[first].plane;
        }
    }
}

/// [`share_face_planes`] with its neighbours found by position (the polygons holding an edge
/// the other way round, ends bit for bit, as [`edge_owners`] keys them): kept for the tests
/// that the merge's neighbours give the same planes.
#[cfg(test)]
pub(crate) fn share_face_planes_by_position(polygons: &mut [Polygon], tol: f64) {
    let owner = edge_owners(polygons);
    let mut neighbours = Vec::new();
    for (i, p) in polygons.iter().enumerate() {
        let v = &p.vertices;
        for k in 0..v.len() {
            if let Some(&j) = owner.get(&(key(v[(k + 1) % v.len()]), key(v[k]))) {
                neighbours.push((i as u32, j));
            }
        }
    }
    share_face_planes(polygons, &neighbours, tol);
}

/// Whether `p` lies in `plane` of a face of `source`, up to rounding (see
/// [`share_face_planes`]).
fn same_face(p: &Polygon, plane: &Plane, source: u32, tol: f64) -> bool {
    p.source == source
        && p.plane.normal.dot(plane.normal) > 0.0
        && p.parallel_to(plane.normal)
        && p.vertices.iter().all(|&v| plane.distance(v).abs() <= tol)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn quad(corners: [[f64; 3]; 4], source: u32) -> Polygon {
        let v: Vec<DVec3> = corners.into_iter().map(DVec3::from).collect();
        Polygon::new(&v, source).unwrap()
    }

    /// Two quads of one flat face share the first one's plane (their anchors differ before);
    /// a neighbour of another source, one turned 1e-9 rad, and one across no shared edge keep
    /// their own: given the neighbours, and found by position.
    #[test]
    fn the_polygons_of_one_flat_face_share_a_plane() {
        let a = quad([[0., 0., 1.], [1., 0., 1.], [1., 1., 1.], [0., 1., 1.]], 0);
        let b = quad([[1., 0., 1.], [2., 0., 1.], [2., 1., 1.], [1., 1., 1.]], 0);
        let other = quad([[0., 1., 1.], [1., 1., 1.], [1., 2., 1.], [0., 2., 1.]], 1);
        let tilt = 1e-9;
        let turned = quad(
            [
                [1., -1., 1. - tilt],
                [2., -1., 1. - tilt],
                [2., 0., 1.],
                [1., 0., 1.],
            ],
            0,
        );
        let apart = quad([[5., 5., 1.], [6., 5., 1.], [6., 6., 1.], [5., 6., 1.]], 0);
        assert_ne!(a.plane, b.plane);
        let given = vec![a.clone(), b, other.clone(), turned.clone(), apart.clone()];
        let mut polygons = given.clone();
        // a meets b and other, b meets turned; apart meets none.
        share_face_planes(&mut polygons, &[(0, 1), (2, 0), (1, 3)], 1e-12);
        let mut by_position = given;
        share_face_planes_by_position(&mut by_position, 1e-12);
        for polygons in [polygons, by_position] {
            assert_eq!(polygons[1].plane, a.plane);
            assert_eq!(polygons[0].plane, a.plane);
            assert_eq!(polygons[2].plane, other.plane);
            assert_eq!(polygons[3].plane, turned.plane);
            assert_eq!(polygons[4].plane, apart.plane);
        }
    }
}
