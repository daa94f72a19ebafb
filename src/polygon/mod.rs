//! Convex planar polygons, the unit booleans work on, and their splitting by a plane.

use std::sync::Arc;

use glam::DVec3;
use smallvec::SmallVec;

use crate::geom::{Aabb, Plane};

mod axis;
mod dd;
mod faces;
mod planes;
mod shared;
mod side;
mod split;

pub(crate) use faces::share_face_planes;
#[cfg(test)]
pub(crate) use faces::share_face_planes_by_position;
pub(crate) use planes::attach_edge_planes_among;
pub(crate) use shared::share_near_parallel_vertices;
pub(crate) use side::{plane_noise, side_across_line};

/// Vertex storage: quads and their split fragments stay inline.
pub(crate) type Vertices = SmallVec<[DVec3; 6]>;

/// Per edge, the plane that made it (see [`Polygon`]). Shared, not inline: polygons are moved
/// and cloned far more often than split, and six planes inline tripled the bytes copied.
pub(crate) type EdgePlanes = Option<Arc<[Plane]>>;

/// The edge plane of an edge whose making is not known (a polygon read from a mesh with no
/// neighbour across that edge).
const UNKNOWN: Plane = Plane {
    normal: DVec3::ZERO,
    offset: 0.0,
    anchor: DVec3::ZERO,
};

/// A convex, planar polygon, wound counter-clockwise seen from the front of its plane, with the
/// id of the input it came from. The id survives every split, so output triangles can be traced
/// to their source (materials ride on it).
///
/// Each edge may also know the plane that made it besides the polygon's own: the plane of the
/// neighbour across it (see `attach_edge_planes`) or the plane that cut it. Where two faces
/// cross at a tiny angle, a point on their crossing line is only known to a rounding error over
/// the angle, and each operand computes its own; computed from its three planes the same way by
/// every polygon that holds it (`meet`), it is one point (see [`Polygon::split`]).
#[derive(Debug, PartialEq)]
pub struct Polygon {
    vertices: Vertices,
    plane: Plane,
    source: u32,
    /// None, or edge `i` (vertex `i` to `i + 1`) lies in `edges[i]` ([`UNKNOWN`] if not known).
    edges: EdgePlanes,
}

/// Cloned field by field, the vertices copied as one block: the derived clone went through the
/// vertex storage's element-by-element `extend` (`SmallVec`'s `Clone`), the larger part of
/// what a boolean's kept far polygons cost to hand on.
impl Clone for Polygon {
    fn clone(&self) -> Self {
        Polygon {
            vertices: Vertices::from_slice(&self.vertices),
            plane: self.plane,
            source: self.source,
            edges: self.edges.clone(),
        }
    }
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
            edges: None,
        })
    }

    /// A polygon whose plane is already known (fragments of a split keep their parent's plane).
    pub(crate) fn with_plane(vertices: Vertices, plane: Plane, source: u32) -> Polygon {
        Polygon {
            vertices,
            plane,
            source,
            edges: None,
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
        // Edge i ran from vertex i to i + 1; reversed, edge k runs from old n-1-k to old n-2-k.
        if let Some(edges) = &self.edges {
            let n = edges.len();
            self.edges = Some((0..n).map(|k| edges[(2 * n - 2 - k) % n]).collect());
        }
    }

    /// The edge planes, one per edge, or none where none is known.
    fn edges(&self) -> &[Plane] {
        self.edges.as_deref().unwrap_or(&[])
    }

    /// The plane edge `i` lies in besides the polygon's own, if known.
    fn edge_plane(&self, i: usize) -> Option<&Plane> {
        self.edges().get(i).filter(|e| e.normal != DVec3::ZERO)
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
}

/// The bounding box of `polygons`' vertices.
pub(crate) fn bbox_of(polygons: &[Polygon]) -> Aabb {
    let mut b = Aabb::EMPTY;
    for p in polygons {
        for &v in p.vertices() {
            b.grow(v);
        }
    }
    b
}

/// The signed volume `polygons` bound, by the divergence theorem in f64, summed relative to
/// their box's centre (what [`crate::Solid::volume`] gives, for polygons not yet a solid).
pub(crate) fn volume_of(polygons: &[Polygon]) -> f64 {
    let apex = bbox_of(polygons).center();
    polygons.iter().map(|p| p.signed_volume6(apex)).sum::<f64>() / 6.0
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
    use super::planes::{attach_edge_planes, meet};
    use super::split::edge_cut;
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

    fn plane(point: [f64; 3], normal: [f64; 3]) -> Plane {
        Plane::from_point_normal(DVec3::from(point), DVec3::from(normal)).unwrap()
    }

    #[test]
    fn meet_is_the_same_bits_in_any_order_and_facing() {
        let p = plane([0.1, 0.2, 2.0], [0.0, 0.0, 1.0]);
        let q = plane([0.3, -0.1, 2.0], [1e-9, 2e-9, 1.0]);
        let r = plane([0.7, 0.0, 0.0], [1.0, 0.1, 0.0]);
        let x = meet(&p, &q, &r).unwrap();
        for (a, b, c) in [(&q, &r, &p), (&r, &p, &q), (&q, &p, &r)] {
            assert_eq!(meet(a, b, c), Some(x));
        }
        assert_eq!(meet(&p.flipped(), &q, &r.flipped()), Some(x));
        for pl in [&p, &q, &r] {
            assert!(pl.distance(x).abs() < 1e-15, "{}", pl.distance(x));
        }
        assert_eq!(meet(&p, &p.flipped(), &r), None);
    }

    /// A square in z = 0 cut by a plane crossing it at 1e-11 rad: every vertex lies within
    /// 1e-11 of the plane, so with the tolerance band of 1e-10 the square would be "coplanar"
    /// or cut through a vertex far from where the planes cross; it is cut on the crossing line.
    #[test]
    fn nearly_parallel_cut_runs_along_the_crossing_line() {
        let mut square = square();
        attach_edge_planes(std::slice::from_mut(&mut square));
        let tilt = 1e-11;
        let cut = plane([0.3, 0.0, 0.0], [-tilt, 0.0, 1.0]);
        let Split::Spanning { front, back } = square.split(&cut, 2e-12) else {
            panic!("expected a split");
        };
        for piece in [&front, &back] {
            let on: Vec<DVec3> = piece
                .vertices()
                .iter()
                .copied()
                .filter(|v| cut.distance(*v).abs() < 1e-20)
                .collect();
            assert_eq!(on.len(), 2, "{piece:?}");
            assert!(on.iter().all(|v| (v.x - 0.3).abs() < 1e-4), "{on:?}");
        }
        assert!((front.area() + back.area() - 1.0).abs() < 1e-14);
        // The cut edge knows the plane that made it.
        assert!(front.edges().contains(&cut));
    }

    #[test]
    fn edge_planes_follow_a_flip() {
        let mut p = square();
        p.edges = Some(
            (0..4)
                .map(|k| plane([k as f64, 0.0, 0.0], [1.0, 0.0, 0.0]))
                .collect(),
        );
        let before: Vec<(DVec3, DVec3, Plane)> = (0..4)
            .map(|k| (p.vertices[k], p.vertices[(k + 1) % 4], p.edges()[k]))
            .collect();
        p.flip();
        for (a, b, e) in before {
            let k = p.vertices.iter().position(|&v| v == b).unwrap();
            assert_eq!(p.vertices[(k + 1) % 4], a);
            assert_eq!(p.edges()[k], e);
        }
    }

    #[test]
    fn edge_planes_are_the_neighbours_planes() {
        let cube = crate::Solid::cube(1.0).unwrap();
        let mut polygons = cube.into_polygons();
        attach_edge_planes(&mut polygons);
        for p in &polygons {
            assert_eq!(p.edges().len(), p.vertices.len());
            for (k, e) in p.edges().iter().enumerate() {
                assert!(e.normal.dot(p.plane.normal).abs() < 1e-15, "{e:?}");
                for v in [p.vertices[k], p.vertices[(k + 1) % p.vertices.len()]] {
                    assert!(e.distance(v).abs() < 1e-15);
                }
            }
        }
    }
}
