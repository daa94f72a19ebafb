//! Convex planar polygons, the unit booleans work on, and their splitting by a plane.

use glam::DVec3;
use smallvec::SmallVec;

use crate::geom::{Aabb, Plane, Side};

/// Vertex storage: quads and their split fragments stay inline.
pub(crate) type Vertices = SmallVec<[DVec3; 6]>;

/// A convex, planar polygon, wound counter-clockwise seen from the front of its plane, with the
/// id of the input it came from. The id survives every split, so output triangles can be traced
/// to their source (materials ride on it).
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    vertices: Vertices,
    plane: Plane,
    source: u32,
}

/// Where a polygon lies relative to a plane, and its two pieces where it spans the plane
/// ([`Polygon::split`]). It lives only until the caller matches on it; boxing the pieces would
/// add two allocations to the hottest loop.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum Split {
    /// Entirely in front (vertices within the tolerance count as on the plane).
    Front,
    /// Entirely behind.
    Back,
    /// Every vertex within the tolerance of the plane, or the polygon's own plane.
    Coplanar,
    /// Parts on both sides: the piece in front and the piece behind, each keeping the
    /// polygon's plane and source.
    Spanning {
        /// The part in front of the plane.
        front: Polygon,
        /// The part behind it.
        back: Polygon,
    },
}

impl Polygon {
    /// A polygon from its vertices, or `None` when they span no area (fewer than three, all
    /// collinear) or are not finite. The plane comes from Newell's method; convexity and
    /// planarity are the caller's promise.
    #[must_use]
    pub fn new(vertices: &[DVec3], source: u32) -> Option<Polygon> {
        Polygon::from_ring(Vertices::from_slice(vertices), source)
    }

    /// [`Polygon::new`] for a ring the crate already holds.
    pub(crate) fn from_ring(vertices: Vertices, source: u32) -> Option<Polygon> {
        if !vertices.iter().all(|v| v.is_finite()) {
            return None;
        }
        let plane = Plane::from_points(&vertices)?;
        Some(Polygon {
            vertices,
            plane,
            source,
        })
    }

    /// A polygon whose plane is already known (fragments of a split keep their parent's plane).
    pub(crate) fn with_plane(vertices: Vertices, plane: Plane, source: u32) -> Polygon {
        Polygon {
            vertices,
            plane,
            source,
        }
    }

    /// The vertices, counter-clockwise seen from the front.
    #[must_use]
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// The supporting plane; its normal points out of the solid.
    #[must_use]
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// The id of the input this polygon came from.
    #[must_use]
    pub fn source(&self) -> u32 {
        self.source
    }

    /// Sets the source id.
    pub fn set_source(&mut self, source: u32) {
        self.source = source;
    }

    /// Reverses the winding and the plane.
    pub fn flip(&mut self) {
        self.vertices.reverse();
        self.plane = self.plane.flipped();
    }

    /// The bounding box of the vertices.
    #[must_use]
    pub fn bbox(&self) -> Aabb {
        Aabb::from_points(&self.vertices)
    }

    /// The mean of the vertices: a point inside a convex polygon.
    #[must_use]
    pub fn centroid(&self) -> DVec3 {
        self.vertices.iter().copied().sum::<DVec3>() / self.vertices.len() as f64
    }

    /// The area (Newell's vector area projected on the plane's normal).
    #[must_use]
    pub fn area(&self) -> f64 {
        let c = self.vertices[0];
        let mut twice = DVec3::ZERO;
        for w in self.vertices[1..].windows(2) {
            twice += (w[0] - c).cross(w[1] - c);
        }
        0.5 * twice.dot(self.plane.normal)
    }

    /// Six times the signed volume of the cone from `apex` over this polygon.
    pub(crate) fn signed_volume6(&self, apex: DVec3) -> f64 {
        let a = self.vertices[0] - apex;
        let mut sum = 0.0;
        for w in self.vertices[1..].windows(2) {
            sum += a.dot((w[0] - apex).cross(w[1] - apex));
        }
        sum
    }

    /// True when `p`, assumed within `eps` of the plane, lies inside the polygon or within
    /// `eps` of its boundary.
    pub(crate) fn contains_coplanar_point(&self, p: DVec3, eps: f64) -> bool {
        let n = self.plane.normal;
        let v = &self.vertices;
        (0..v.len()).all(|i| {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            let edge = b - a;
            edge.cross(p - a).dot(n) >= -eps * edge.length()
        })
    }

    /// The fan triangles `(0, i, i+1)` of the polygon.
    pub fn fan(&self) -> impl Iterator<Item = [DVec3; 3]> + '_ {
        let v = &self.vertices;
        (1..v.len() - 1).map(move |i| [v[0], v[i], v[i + 1]])
    }

    /// Where the polygon lies relative to `plane`, vertices within `eps` counting as on it.
    pub(crate) fn side(&self, plane: &Plane, eps: f64) -> Side {
        if self.plane.is_same_or_flipped(plane) {
            return Side::Coplanar;
        }
        let (mut front, mut back) = (false, false);
        for &v in &self.vertices {
            match plane.side_of(v, eps) {
                Side::Front => front = true,
                Side::Back => back = true,
                _ => {}
            }
        }
        match (front, back) {
            (false, false) => Side::Coplanar,
            (true, false) => Side::Front,
            (false, true) => Side::Back,
            (true, true) => Side::Spanning,
        }
    }

    /// Classifies against `plane` and, where the polygon spans it, cuts it in two. A polygon is
    /// coplanar with its own plane whatever its vertices say (see [`Plane::is_same_or_flipped`]).
    /// Vertices
    /// within `eps` of the plane go to both pieces; an edge from a front to a back vertex is cut
    /// at a point computed the same way, bit for bit, by both polygons that share the edge.
    #[must_use]
    pub fn split(&self, plane: &Plane, eps: f64) -> Split {
        if self.plane.is_same_or_flipped(plane) {
            return Split::Coplanar;
        }
        let n = self.vertices.len();
        let mut dist: SmallVec<[f64; 8]> = SmallVec::with_capacity(n);
        let (mut any_front, mut any_back) = (false, false);
        for &v in &self.vertices {
            let d = plane.distance(v);
            any_front |= d > eps;
            any_back |= d < -eps;
            dist.push(d);
        }
        match (any_front, any_back) {
            (false, false) => return Split::Coplanar,
            (true, false) => return Split::Front,
            (false, true) => return Split::Back,
            (true, true) => {}
        }
        let axis = axis_of(plane);
        let mut front = Vertices::new();
        let mut back = Vertices::new();
        for i in 0..n {
            let j = (i + 1) % n;
            let (vi, di, dj) = (self.vertices[i], dist[i], dist[j]);
            if di >= -eps {
                front.push(vi);
            }
            if di <= eps {
                back.push(vi);
            }
            if (di > eps && dj < -eps) || (di < -eps && dj > eps) {
                let p = edge_cut(vi, di, self.vertices[j], dj, plane, axis);
                front.push(p);
                back.push(p);
            }
        }
        dedup_ring(&mut front);
        dedup_ring(&mut back);
        Split::Spanning {
            front: Polygon::with_plane(front, self.plane, self.source),
            back: Polygon::with_plane(back, self.plane, self.source),
        }
    }
}

/// The axis a plane's normal lies along, if it is exactly axis-aligned.
#[inline]
fn axis_of(plane: &Plane) -> Option<usize> {
    let n = plane.normal;
    if n.y == 0.0 && n.z == 0.0 {
        Some(0)
    } else if n.x == 0.0 && n.z == 0.0 {
        Some(1)
    } else if n.x == 0.0 && n.y == 0.0 {
        Some(2)
    } else {
        None
    }
}

/// The point where the edge `a`–`b` crosses `plane`, given the endpoints' signed distances.
///
/// The endpoints are put in a fixed order first, so the two polygons sharing an edge get the
/// same bits; interpolation starts from the nearer endpoint; coordinates the endpoints share
/// stay exact; on an axis-aligned plane the cut coordinate is the plane's own.
#[inline]
fn edge_cut(a: DVec3, da: f64, b: DVec3, db: f64, plane: &Plane, axis: Option<usize>) -> DVec3 {
    let (a, da, b, db) = if lex_less(a, b) {
        (a, da, b, db)
    } else {
        (b, db, a, da)
    };
    let t = da / (da - db);
    let mut p = if t <= 0.5 {
        a + (b - a) * t
    } else {
        b + (a - b) * (db / (db - da))
    };
    if let Some(k) = axis {
        p[k] = plane.offset * plane.normal[k];
    }
    p
}

#[inline]
fn lex_less(a: DVec3, b: DVec3) -> bool {
    (a.x, a.y, a.z) < (b.x, b.y, b.z)
}

/// Drops entries equal to their predecessor (cyclically).
pub(crate) fn dedup_ring<A: smallvec::Array>(v: &mut SmallVec<A>)
where
    A::Item: PartialEq,
{
    v.dedup();
    while v.len() > 1 && v.first() == v.last() {
        v.pop();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Polygon {
        Polygon::new(
            [
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
            ]
            .as_slice(),
            7,
        )
        .unwrap()
    }

    #[test]
    fn newell_plane_of_square() {
        let p = square();
        assert_eq!(p.plane().normal, DVec3::Z);
        assert_eq!(p.plane().offset, 0.0);
        assert!((p.area() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn collinear_points_give_no_polygon() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert!(Polygon::new(line.as_slice(), 0).is_none());
    }

    #[test]
    fn split_keeps_area_and_source() {
        let p = square();
        let cut = Plane::from_point_normal(DVec3::new(0.25, 0.0, 0.0), DVec3::new(1.0, 0.3, 0.0))
            .unwrap();
        match p.split(&cut, 1e-12) {
            Split::Spanning { front, back } => {
                assert!((front.area() + back.area() - 1.0).abs() < 1e-14);
                assert_eq!(front.source(), 7);
                assert_eq!(back.plane(), p.plane());
            }
            other => panic!("expected a split, got {other:?}"),
        }
    }

    #[test]
    fn shared_edge_is_cut_at_the_same_point() {
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = DVec3::new(1.7, -0.4, 2.9);
        let plane =
            Plane::from_point_normal(DVec3::new(0.5, 0.0, 0.0), DVec3::new(1.0, 0.2, 0.1)).unwrap();
        let p = edge_cut(a, plane.distance(a), b, plane.distance(b), &plane, None);
        let q = edge_cut(b, plane.distance(b), a, plane.distance(a), &plane, None);
        assert_eq!(p, q);
        assert!(plane.distance(p).abs() < 1e-15);
    }

    #[test]
    fn axis_plane_cut_is_exact() {
        let a = DVec3::new(0.0, -3.4e38, -3.4e38);
        let b = DVec3::new(0.0, 3.4e38, -3.4e38);
        let plane = Plane::from_point_normal(DVec3::new(0.0, 12.5, 0.0), DVec3::Y).unwrap();
        let p = edge_cut(a, plane.distance(a), b, plane.distance(b), &plane, Some(1));
        assert_eq!(p, DVec3::new(0.0, 12.5, -3.4e38));
    }
}
