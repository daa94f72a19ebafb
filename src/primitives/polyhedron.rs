use glam::DVec3;

use crate::error::{Error, Result};
use crate::geom::{Plane, Tolerance};
use crate::mesh::triangulate::triangulate_boundary;
use crate::mesh::validate;
use crate::polygon::Polygon;
use crate::solid::Solid;

impl Solid {
    /// A solid from vertices and faces (each a list of vertex indices, counter-clockwise seen
    /// from outside). Faces that are planar and convex become one polygon each; others are
    /// triangulated.
    ///
    /// The input is checked and refused with [`Error::InvalidMesh`] (with counts) unless every
    /// coordinate is finite, every face has at least three distinct in-range indices and spans
    /// an area, and the faces close up: every edge is used once in each direction.
    ///
    /// ```
    /// use glam::DVec3;
    /// let v = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    /// let tetra = bspcsg::Solid::polyhedron(&v, &[[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]).unwrap();
    /// assert!((tetra.volume() - 1.0 / 6.0).abs() < 1e-12);
    /// ```
    pub fn polyhedron<F: AsRef<[u32]>>(vertices: &[DVec3], faces: &[F]) -> Result<Solid> {
        if faces.is_empty() {
            return Err(Error::InvalidMesh("no faces".into()));
        }
        validate::check_finite(vertices, |_| true)?;
        validate::check_face_indices(faces, vertices.len(), false)?;
        validate::check_closed(faces)?;
        let eps = Tolerance::for_region(&crate::geom::Aabb::from_points(vertices)).eps();
        let mut polygons = Vec::with_capacity(faces.len());
        for (fi, f) in faces.iter().enumerate() {
            let pts: Vec<DVec3> = f.as_ref().iter().map(|&i| vertices[i as usize]).collect();
            let plane = Plane::from_points(&pts)
                .ok_or_else(|| Error::InvalidMesh(format!("face {fi} has no area")))?;
            if is_planar_convex(&pts, &plane, eps) {
                polygons.push(Polygon::with_plane(pts.as_slice().into(), plane, 0));
                continue;
            }
            // The face's boundary as one loop, triangulated in O(n log n) (a star-shaped profile
            // of thousands of points is common in extrusions).
            let n = pts.len() as u32;
            let edges: Vec<(u32, u32)> = (0..n).map(|k| (k, (k + 1) % n)).collect();
            let tris = triangulate_boundary(&pts, plane.normal, &edges).ok_or_else(|| {
                Error::InvalidMesh(format!(
                    "face {fi} is self-intersecting and cannot be triangulated"
                ))
            })?;
            for t in tris {
                // Slivers of a non-convex face may have no plane of their own: they add nothing.
                if let Some(p) = Polygon::new(t.map(|k| pts[k as usize]).as_slice(), 0) {
                    polygons.push(p);
                }
            }
        }
        let solid = Solid::from_polygons(polygons);
        if solid.volume() <= 0.0 {
            return Err(Error::InvalidMesh(
                "inside out: the faces enclose no positive volume (they must wind \
                 counter-clockwise seen from outside)"
                    .into(),
            ));
        }
        Ok(solid)
    }
}

fn is_planar_convex(pts: &[DVec3], plane: &Plane, eps: f64) -> bool {
    let n = pts.len();
    pts.iter().all(|&p| plane.distance(p).abs() <= eps)
        && (0..n).all(|i| {
            let (a, b, c) = (pts[i], pts[(i + 1) % n], pts[(i + 2) % n]);
            (b - a).cross(c - b).dot(plane.normal) > 0.0
        })
}
