//! Polyhedra from vertices and index faces.

use glam::DVec3;

use crate::error::{Error, MeshDefect, Result};
use crate::geom::triangulate::triangulate_boundary;
use crate::geom::{Plane, Tolerance};
use crate::polygon::Polygon;
use crate::topology;

/// The polygons of a polyhedron given by vertices and index faces, after checking that the faces
/// close up: planar convex faces whole, others triangulated. Orientation is checked by the
/// caller, on the solid.
pub(crate) fn polyhedron<F: AsRef<[u32]>>(vertices: &[DVec3], faces: &[F]) -> Result<Vec<Polygon>> {
    if faces.is_empty() {
        return Err(Error::mesh(MeshDefect::NoFaces));
    }
    topology::check_finite(vertices, |_| true)?;
    topology::check_face_indices(faces, vertices.len(), false)?;
    topology::check_closed(faces)?;
    let eps = Tolerance::for_region(&crate::geom::Aabb::from_points(vertices)).eps();
    let mut polygons = Vec::with_capacity(faces.len());
    for (fi, f) in faces.iter().enumerate() {
        let pts: Vec<DVec3> = f.as_ref().iter().map(|&i| vertices[i as usize]).collect();
        let plane =
            Plane::from_points(&pts).ok_or(Error::mesh(MeshDefect::ZeroAreaFace { face: fi }))?;
        if is_planar_convex(&pts, &plane, eps) {
            polygons.push(Polygon::with_plane(pts.as_slice().into(), plane, 0));
            continue;
        }
        // The face's boundary as one loop, triangulated in O(n log n) (a star-shaped profile
        // of thousands of points is common in extrusions).
        let n = pts.len() as u32;
        let edges: Vec<(u32, u32)> = (0..n).map(|k| (k, (k + 1) % n)).collect();
        let tris = triangulate_boundary(&pts, plane.normal, &edges)
            .ok_or(Error::mesh(MeshDefect::SelfIntersectingFace { face: fi }))?;
        for t in tris {
            // Slivers of a non-convex face may have no plane of their own: they add nothing.
            if let Some(p) = Polygon::new(t.map(|k| pts[k as usize]).as_slice(), 0) {
                polygons.push(p);
            }
        }
    }
    Ok(polygons)
}

fn is_planar_convex(pts: &[DVec3], plane: &Plane, eps: f64) -> bool {
    let n = pts.len();
    pts.iter().all(|&p| plane.distance(p).abs() <= eps)
        && (0..n).all(|i| {
            let (a, b, c) = (pts[i], pts[(i + 1) % n], pts[(i + 2) % n]);
            (b - a).cross(c - b).dot(plane.normal) > 0.0
        })
}
