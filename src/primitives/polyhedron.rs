use std::collections::HashMap;

use glam::DVec3;

use crate::error::{Error, Result};
use crate::geom::{Plane, Tolerance};
use crate::mesh::triangulate::{ear_clip, project};
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
        check_indexed(vertices, faces)?;
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
            let tris = ear_clip(&project(&pts, plane.normal)).ok_or_else(|| {
                Error::InvalidMesh(format!(
                    "face {fi} is self-intersecting and cannot be triangulated"
                ))
            })?;
            for t in tris {
                // Slivers of a non-convex face may have no plane of their own: they add nothing.
                if let Some(p) = Polygon::new(t.map(|k| pts[k]).as_slice(), 0) {
                    polygons.push(p);
                }
            }
        }
        Ok(Solid::from_polygons(polygons))
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

/// Checks indexed faces for finiteness, index range, repeats and closure.
pub(crate) fn check_indexed<F: AsRef<[u32]>>(vertices: &[DVec3], faces: &[F]) -> Result<()> {
    if let Some(i) = vertices.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidMesh(format!(
            "vertex {i} has a non-finite coordinate: {}",
            vertices[i]
        )));
    }
    if faces.is_empty() {
        return Err(Error::InvalidMesh("no faces".into()));
    }
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    for (fi, f) in faces.iter().enumerate() {
        let f = f.as_ref();
        if f.len() < 3 {
            return Err(Error::InvalidMesh(format!(
                "face {fi} has {} indices; a face needs at least 3",
                f.len()
            )));
        }
        if let Some(&bad) = f.iter().find(|&&i| i as usize >= vertices.len()) {
            return Err(Error::InvalidMesh(format!(
                "face {fi} uses vertex index {bad}, but there are only {} vertices",
                vertices.len()
            )));
        }
        for (k, &i) in f.iter().enumerate() {
            if f[k + 1..].contains(&i) {
                return Err(Error::InvalidMesh(format!(
                    "face {fi} repeats vertex index {i}"
                )));
            }
        }
        for k in 0..f.len() {
            *directed.entry((f[k], f[(k + 1) % f.len()])).or_default() += 1;
        }
    }
    let (mut boundary, mut overused, mut misoriented) = (0usize, 0usize, 0usize);
    for (&(a, b), &uses) in &directed {
        let back = directed.get(&(b, a)).copied().unwrap_or(0);
        if uses > 1 {
            overused += 1;
        } else if back == 0 {
            boundary += 1;
        }
        if uses == 1 && back > 1 {
            misoriented += 1;
        }
    }
    if boundary + overused + misoriented > 0 {
        return Err(Error::InvalidMesh(format!(
            "not closed: {boundary} boundary edges, {overused} edges used more than once in one \
             direction (non-manifold or inconsistently oriented faces)"
        )));
    }
    Ok(())
}
