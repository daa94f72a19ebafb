//! Convex planar polygons, the unit booleans work on, and their splitting by a plane.

use std::sync::Arc;

use glam::DVec3;
use smallvec::SmallVec;

use crate::geom::{Aabb, Plane, Side};

mod axis;
mod planes;
mod shared;

pub(crate) use planes::{attach_edge_planes, meet};
pub(crate) use shared::share_near_parallel_vertices;

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
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    vertices: Vertices,
    plane: Plane,
    source: u32,
    /// None, or edge `i` (vertex `i` to `i + 1`) lies in `edges[i]` ([`UNKNOWN`] if not known).
    edges: EdgePlanes,
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
    /// coplanar with its own plane whatever its vertices say (see [`Plane::is_same_or_flipped`]),
    /// and with any plane all its vertices lie within `eps` of.
    ///
    /// Otherwise, where the planes cross at a sine below 10⁻³ (`ON_BAND_BELOW`), a vertex counts
    /// as on the plane within `eps` times the sine of the angle between them, not `eps`: where
    /// they cross at a tiny angle α, `eps` would reach `eps / α` across the polygon, and the cut
    /// would run through a vertex that far from the line where the planes cross while the other
    /// operand, cut along that line, leaves a slit between (10⁻⁹° on a box: a band 0.6 wide).
    /// Vertices on the plane go to both pieces. An edge from a front to a back vertex is cut at a point
    /// every polygon sharing the edge computes the same, bit for bit: interpolated, or where the
    /// edge runs nearly along the plane (and the interpolation is off by a rounding error over
    /// that angle), the `meet` of the planes the edge lies in and `plane`, which the other
    /// operand computes the same way.
    #[must_use]
    pub fn split(&self, plane: &Plane, eps: f64) -> Split {
        if self.plane.is_same_or_flipped(plane) {
            return Split::Coplanar;
        }
        let n = self.vertices.len();
        let mut dist: SmallVec<[f64; 8]> = SmallVec::with_capacity(n);
        let (mut any_front, mut any_back, mut any_on) = (false, false, false);
        for &v in &self.vertices {
            let d = plane.distance(v);
            any_front |= d > eps;
            any_back |= d < -eps;
            any_on |= d.abs() <= eps;
            dist.push(d);
        }
        if !any_front && !any_back {
            return Split::Coplanar;
        }
        let sine = if any_on {
            self.plane.normal.cross(plane.normal).length()
        } else {
            1.0
        };
        // Per vertex, how near the plane counts as on it: `eps`, or for nearly parallel planes
        // the band described above.
        let mut tight: SmallVec<[f64; 8]> = SmallVec::new();
        if sine < ON_BAND_BELOW {
            tight.extend(
                self.vertices
                    .iter()
                    .map(|&v| plane_noise(plane, v).max(eps * sine).min(eps)),
            );
            any_front = dist.iter().zip(&tight).any(|(&d, &on)| d > on);
            any_back = dist.iter().zip(&tight).any(|(&d, &on)| d < -on);
        }
        let on = |i: usize| tight.get(i).copied().unwrap_or(eps);
        match (any_front, any_back) {
            (true, false) => return Split::Front,
            (false, true) => return Split::Back,
            _ => {}
        }
        let axis = axis_of(plane);
        let track = self.edges.is_some();
        let mut front = Piece::new(track);
        let mut back = Piece::new(track);
        for i in 0..n {
            let j = (i + 1) % n;
            let (vi, di, dj) = (self.vertices[i], dist[i], dist[j]);
            let (oi, oj) = (on(i), on(j));
            if di >= -oi {
                front.push(vi, Corner::vertex(i));
            }
            if di <= oi {
                back.push(vi, Corner::vertex(i));
            }
            if (di > oi && dj < -oj) || (di < -oi && dj > oj) {
                let edge = CutEdge {
                    a: vi,
                    da: di,
                    b: self.vertices[j],
                    db: dj,
                    along: self.edge_plane(i),
                };
                let p = edge.cut(&self.plane, plane, axis, eps);
                front.push(p, Corner::cut(i));
                back.push(p, Corner::cut(i));
            }
        }
        let front = front.into_polygon(self, plane);
        let back = back.into_polygon(self, plane);
        match (front, back) {
            (Some(front), Some(back)) => Split::Spanning { front, back },
            // Cut points rounded onto a vertex: all that is left on one side is a line.
            (Some(_), None) => Split::Front,
            (None, _) => Split::Back,
        }
    }
}

/// How far from `plane` rounding alone puts a point computed to lie on it: a few units in the
/// last place of its distance from the plane's anchor and of its own coordinates. Below this,
/// a vertex is on the plane whatever the angle (a neighbour's shared vertices, nearly flat
/// tessellations); it depends on the vertex and the plane alone, so every polygon holding the
/// vertex agrees.
#[inline]
fn plane_noise(plane: &Plane, v: DVec3) -> f64 {
    64.0 * f64::EPSILON * ((v - plane.anchor).abs().max_element() + v.abs().max_element())
}

/// Where a piece's vertex came from: a vertex of the split polygon, or the cut of its edge `i`
/// (packed in a `u32`: pieces are moved whole, and they stay small).
#[derive(Clone, Copy, PartialEq, Eq)]
struct Corner(u32);

impl Corner {
    #[inline]
    fn vertex(i: usize) -> Corner {
        Corner((i as u32) << 1)
    }

    #[inline]
    fn cut(i: usize) -> Corner {
        Corner(((i as u32) << 1) | 1)
    }

    /// The index, and whether it is a cut.
    #[inline]
    fn get(self) -> (usize, bool) {
        ((self.0 >> 1) as usize, self.0 & 1 == 1)
    }
}

/// A piece of a split polygon as it is collected, with where each vertex came from if the
/// parent's edge planes are tracked.
struct Piece {
    points: Vertices,
    corners: SmallVec<[Corner; 6]>,
    track: bool,
}

impl Piece {
    fn new(track: bool) -> Self {
        Piece {
            points: Vertices::new(),
            corners: SmallVec::new(),
            track,
        }
    }

    #[inline]
    fn push(&mut self, p: DVec3, corner: Corner) {
        if self.points.last() != Some(&p) {
            self.points.push(p);
            if self.track {
                self.corners.push(corner);
            }
        }
    }

    /// The piece, each edge knowing its plane: an edge along edge `i` of the parent keeps that
    /// edge's plane, any other runs along the cutting plane. `None` when fewer than three
    /// distinct points are left.
    fn into_polygon(mut self, parent: &Polygon, cut: &Plane) -> Option<Polygon> {
        while self.points.len() > 1 && self.points.first() == self.points.last() {
            self.points.pop();
            if self.track {
                self.corners.pop();
            }
        }
        let m = self.points.len();
        if m < 3 {
            return None;
        }
        if !self.track {
            // Not tracked (a tree's own polygons): no edge is cut by a meet of planes.
            return Some(Polygon::with_plane(
                self.points,
                parent.plane,
                parent.source,
            ));
        }
        let n = parent.vertices.len();
        let edges = (0..m)
            .map(|k| {
                let along = match (self.corners[k].get(), self.corners[(k + 1) % m].get()) {
                    ((i, false), (j, false)) if j == (i + 1) % n => Some(i),
                    ((i, false), (j, true)) if i == j => Some(i),
                    ((i, true), (j, false)) if j == (i + 1) % n => Some(i),
                    _ => None,
                };
                match along {
                    Some(i) => parent.edges().get(i).copied().unwrap_or(UNKNOWN),
                    None => *cut,
                }
            })
            .collect();
        Some(Polygon {
            vertices: self.points,
            plane: parent.plane,
            source: parent.source,
            edges: Some(edges),
        })
    }
}

/// An edge crossing a cutting plane: its ends, their signed distances, and the plane it lies in
/// besides its polygon's, if known.
struct CutEdge<'a> {
    a: DVec3,
    da: f64,
    b: DVec3,
    db: f64,
    along: Option<&'a Plane>,
}

/// Below this sine of the angle between a polygon's plane and a cutting plane, a vertex is on
/// the cutting plane only within `eps` of their crossing line (`eps · sine` of the plane, or
/// the plane's rounding noise), not within `eps` of the plane, which is `eps / sine` across the
/// polygon.
///
/// At 10⁻⁷ (the old bound, [`NEAR_PARALLEL`]) the unit cube less itself turned 10⁻⁴° about
/// (0.3, 1, 0.2) had 6 boundary edges and 3·10⁻⁴° a flat shell, the solid's volume 12.6 % and
/// 2.8 % high: the faces cross at 1.7·10⁻⁶ and 5·10⁻⁶ rad, each corner of one cube lies
/// 10⁻¹² … 10⁻¹¹ off the other's nearly parallel face, within `eps` (1.7·10⁻¹²), so each
/// operand cut its faces through its own corners instead of on the crossing line (10⁻⁶ away
/// along the face), and the two operands' cuts did not meet. With the band by the angle both
/// come out closed, to the first-order volume within 10⁻⁵. Above 10⁻³ the two bands differ by
/// less than a factor of a thousand, and ordinary crossings keep the tolerance they always had.
const ON_BAND_BELOW: f64 = 1e-3;

/// Below this sine of the angle between a polygon's plane and a cutting plane, the two cross
/// "nearly in parallel": edges running along the plane are cut at the [`meet`] of their planes.
///
/// The old band of `eps / sine` reaches 10⁷ tolerances across the face here, which no weld
/// closes (a box turned 10⁻⁹°: 1.7e-11 rad, a slit 0.6 wide). Above it, crossings are left to
/// the band (see [`ON_BAND_BELOW`]): where three or more nearly parallel planes meet
/// (Havocglass8's flat neighbours cross the other model's at 5e-7 to 5e-5 rad) no vertex is
/// well defined, the meet of three of them is as uncertain as an interpolation, and only the
/// band and the weld agree (measured: 9 boundary edges with the meet up to 1e-3, 3 up to 1e-6,
/// none at 1e-7).
const NEAR_PARALLEL: f64 = 1e-7;

/// Below this sine of the angle between an edge and a cutting plane, the edge's cut is the
/// [`meet`] of its planes rather than interpolated: interpolation is off along the edge by a
/// rounding error of the distances over this sine (10⁻¹⁶ / 10⁻³, far inside the weld).
const GRAZING: f64 = 1e-3;

impl CutEdge<'_> {
    /// Where the edge crosses `cut`; see [`Polygon::split`]. Everything here depends only on the
    /// edge's ends (taken in a fixed order) and the set of planes, so the polygons on both sides
    /// of the edge get the same bits.
    fn cut(&self, own: &Plane, cut: &Plane, axis: Option<usize>, eps: f64) -> DVec3 {
        let (a, da, b, db) = if lex_less(self.a, self.b) {
            (self.a, self.da, self.b, self.db)
        } else {
            (self.b, self.db, self.a, self.da)
        };
        if let Some(along) = self.along {
            let d = b - a;
            let len = d.length();
            let sine = |p: &Plane, q: &Plane| p.normal.cross(q.normal).length();
            if cut.normal.dot(d).abs() < GRAZING * len
                && sine(own, cut).min(sine(along, cut)) < NEAR_PARALLEL
                && sine(own, along) >= GRAZING
                && let Some(p) = meet(own, along, cut)
            {
                // Taken only where it lies on the edge: planes that barely cross (a neighbour
                // in the polygon's own plane) meet anywhere.
                let t = (p - a).dot(d) / (len * len);
                if (0.0..=1.0).contains(&t) && (p - a).cross(d).length() <= eps * len {
                    return p;
                }
            }
        }
        edge_cut(a, da, b, db, cut, axis)
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
