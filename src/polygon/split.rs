//! Cutting a polygon by a plane: its vertices judged against it (by [`super::side`]), and
//! where an edge is cut so that every polygon sharing the edge computes the same point.

use glam::DVec3;
use smallvec::SmallVec;

use super::planes::{Crossing, meet};
use super::side::{NEAR_PARALLEL, ON_BAND_BELOW, PARALLEL_BELOW, banded, given_noise, plane_noise};
use super::{Polygon, Split, UNKNOWN, Vertices};
use crate::geom::Plane;

impl Polygon {
    /// Classifies against `plane` and, where the polygon spans it, cuts it in two. A polygon is
    /// coplanar with its own plane whatever its vertices say (see [`Plane::is_same_or_flipped`]),
    /// and with any plane all its vertices lie on, as told below.
    ///
    /// Where the planes cross at a sine below 0.1 (`ON_BAND_BELOW`) and a vertex lies within
    /// `eps`, a vertex counts as on the plane within `eps` times the sine of the angle between
    /// them (or the plane's rounding noise), not `eps`: where they cross at a tiny angle α,
    /// `eps` would reach `eps / α` across the polygon, and the cut would run through a vertex
    /// that far from the line where the planes cross while the other operand, cut along that
    /// line, leaves a slit between (10⁻⁹° on a box: a band 0.6 wide). So too for a polygon all
    /// of whose vertices lie within `eps` of a plane crossing its own at a sine of at least
    /// 5·10⁻¹³ (`PARALLEL_BELOW`; below it the planes part by less than half the tolerance
    /// across the region it is relative to, and count as parallel): it is
    /// coplanar only if they all lie within the band.
    /// Coplanar by `eps` alone, a small face (a 0.125 cube's, on a box turned 10⁻¹⁰°) went
    /// whole to the coplanar side while the other operand's larger face, reaching beyond `eps`,
    /// was cut on the crossing line through it: the two decisions disagreed, and the part of
    /// the face between them was kept by neither (a hole: the solid 3.7·10⁻⁴ below its mesh)
    /// or by both.
    ///
    /// So too, where the planes cross clearly, for a vertex within `eps` beside an edge running
    /// along the plane at a slope below 0.1 to an end beyond `eps`: `eps` of the plane is `eps` over the slope along
    /// the edge, and such a vertex is on the plane within `eps` times the slope (or the noise).
    /// Near the poles of a 128×64 sphere less itself turned 10⁻⁴° every fan facet of either
    /// passes within 10⁻⁶ of the pole, crossing the other's at sines of 10⁻³ to 10⁻² (within
    /// the band by the angle since `ON_BAND_BELOW` is 0.1; by the slope before): corners
    /// 3·10⁻¹² off a plane counted as on it, each operand's cut along a crossing line ran
    /// 1.5·10⁻¹⁰ beside the other's, its vertices 5·10⁻⁹ apart along it (30 boundary edges).
    ///
    /// Where the planes cross at a sine below 10⁻⁷ (`NEAR_PARALLEL`), and where a vertex near
    /// the plane lies on another plane crossing it so (an edge's: the polygon's neighbour across
    /// it is nearly parallel to the cut), the vertex is judged by its distance across the line
    /// where the two cross, as both operands compute it (`crossing_at`), not by its distance
    /// from the plane, within `eps` across that line or the rounding of the line's own position
    /// (`Crossing::rounding`), whichever is wider. A vertex where three nearly parallel planes
    /// cross lies on two such lines, and polygons holding it judge it by either: within `eps`
    /// alone (3·10⁻²¹ at 1.4·10⁻⁹ rad) it read 7·10⁻¹⁹ to one side of one line and of the other
    /// by their rounding, the two operands' pictures apart (round 17's fork run: the mesh's
    /// volume 10⁻⁸ off the solid's); within the rounding (4·10⁻¹⁶ for planes anchored 0.25
    /// apart) it is on both.
    ///
    /// Vertices on the plane go to both pieces. An edge from a front to a back vertex is cut at
    /// a point every polygon sharing the edge computes the same, bit for bit: interpolated, or
    /// where the edge runs nearly along the plane (and the interpolation is off by a rounding
    /// error over that angle), the `meet` of the planes the edge lies in and `plane`, which the
    /// other operand computes the same way.
    #[must_use]
    pub fn split(&self, plane: &Plane, eps: f64) -> Split {
        self.split_as(plane, eps, None)
    }

    /// [`Polygon::split`], where `given`, for a polygon tracking no edge planes, holds the
    /// vertices of the polygon whose plane `plane` is (none for a plane of no polygon) and
    /// says that this one was never cut: only its vertices shared with that polygon may then
    /// have been made on `plane` (see `made_on`), as a clip would tell from the edge planes. A
    /// tree's own polygons track none, and the pieces its build cuts hold vertices made on its
    /// planes; the build tells which are which.
    pub(crate) fn split_as(&self, plane: &Plane, eps: f64, given: Option<&[DVec3]>) -> Split {
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
        let sine = if any_on {
            self.plane.normal.cross(plane.normal).length()
        } else {
            1.0
        };
        if !any_front && !any_back && !banded(sine) {
            return Split::Coplanar;
        }
        // Per vertex, how near the plane counts as on it: `eps`, or for nearly parallel planes
        // the band described above.
        let mut tight: SmallVec<[f64; 8]> = SmallVec::new();
        if sine < ON_BAND_BELOW {
            tight.extend(self.vertices.iter().enumerate().map(|(i, &v)| {
                let noise = if self.made_on(i, plane, given) {
                    plane_noise(plane, v)
                } else {
                    given_noise(plane, v)
                };
                noise.max(eps * sine).min(eps)
            }));
        }
        // A vertex near a plane crossing the polygon's own clearly, beside an edge running
        // nearly along it: `eps` of the plane is `eps` over the edge's slope along the edge, so
        // such a vertex is on the plane only within the band by that slope.
        let mut grazed = false;
        if any_on && tight.is_empty() {
            for i in 0..n {
                if dist[i].abs() > eps {
                    continue;
                }
                let v = self.vertices[i];
                let slope = [(i + n - 1) % n, (i + 1) % n]
                    .into_iter()
                    .filter(|&j| dist[j].abs() > eps)
                    .map(|j| {
                        plane.normal.dot(self.vertices[j] - v).abs()
                            / (self.vertices[j] - v).length()
                    })
                    .fold(f64::INFINITY, f64::min);
                if slope < ON_BAND_BELOW {
                    if tight.is_empty() {
                        tight.resize(n, eps);
                    }
                    tight[i] = plane_noise(plane, v).max(eps * slope).min(eps);
                    grazed = true;
                }
            }
        }
        // A vertex near the plane, on a plane crossing it nearly in parallel (the polygon's own
        // or an edge's), is judged by its distance across their crossing line instead.
        let mut judged = false;
        if any_on && self.edges().len() == n {
            for i in 0..n {
                if dist[i].abs() <= eps
                    && let Some((crossing, at)) = self.crossing_at(i, plane, sine)
                {
                    if tight.is_empty() {
                        tight.resize(n, eps);
                    }
                    dist[i] = crossing.side(self.vertices[i]);
                    tight[i] = if at == sine && self.beside_the_line(i, plane, eps) {
                        eps * at
                    } else {
                        (eps * at).max(crossing.rounding())
                    };
                    judged = true;
                }
            }
        }
        if sine < ON_BAND_BELOW || judged || grazed {
            any_front = dist.iter().zip(&tight).any(|(&d, &on)| d > on);
            any_back = dist.iter().zip(&tight).any(|(&d, &on)| d < -on);
        }
        let on = |i: usize| tight.get(i).copied().unwrap_or(eps);
        match (any_front, any_back) {
            (false, false) => return Split::Coplanar,
            (true, false) => return Split::Front,
            (false, true) => return Split::Back,
            _ => {}
        }
        // Cut where its edges cross the line on which the polygon's own plane crosses `plane`
        // nearly in parallel: each end by its distance across that line (the other vertices
        // were judged so above where they could be). By their distances from `plane`, each off
        // by a rounding error, an edge in the polygon's own plane on both sides (no `meet` for
        // it: see `CutEdge::cut`) was cut a rounding error over the sine off the line, 6e-9 at
        // 1.7e-9 rad, where the other operand, cut by this polygon's plane, ends on the line.
        // `sine` is this where a vertex was near the plane (else a placeholder).
        let own = if any_on {
            sine
        } else {
            self.plane.normal.cross(plane.normal).length()
        };
        if (PARALLEL_BELOW..NEAR_PARALLEL).contains(&own)
            && let Some(crossing) = Crossing::new(&self.plane, plane)
        {
            for i in 0..n {
                if dist[i].abs() > eps {
                    dist[i] = crossing.side(self.vertices[i]);
                }
            }
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
        let front = front.take_polygon(self, plane);
        let back = back.take_polygon(self, plane);
        match (front, back) {
            (Some(front), Some(back)) => Split::Spanning { front, back },
            // Cut points rounded onto a vertex: all that is left on one side is a line.
            (Some(_), None) => Split::Front,
            (None, _) => Split::Back,
        }
    }
}

impl Polygon {
    /// Whether vertex `i`, near the line where the polygon's own plane crosses `plane` nearly in
    /// parallel, lies beside that line by its edges: an edge beside it, in a known plane that
    /// crosses `plane` clearly, meets the line more than the weld (8 `eps`) from it. Such a
    /// vertex is the meet of other planes that the line passes only within its rounding, and
    /// the other operand, cutting its faces along the line, cuts that edge's plane at the meet,
    /// not at the vertex; judged on the line, the polygon's cut ended at the vertex and left a
    /// flat sliver between (an OBJ box turned 10⁻⁹° less a cuboid: its corner 1.56·10⁻⁵
    /// beside the line, 1.7·10⁻¹⁶ of height against the rounding's 7.8·10⁻¹⁶; the solid
    /// 1.83·10⁻⁷ below its mesh). A vertex made on the line is that meet to the bit.
    fn beside_the_line(&self, i: usize, plane: &Plane, eps: f64) -> bool {
        let n = self.vertices.len();
        let v = self.vertices[i];
        let edges = self.edges();
        [&edges[(i + n - 1) % n], &edges[i]].into_iter().any(|e| {
            e.normal != DVec3::ZERO
                && !e.is_same_or_flipped(plane)
                && e.normal.cross(plane.normal).length() >= NEAR_PARALLEL
                && meet(&self.plane, plane, e).is_some_and(|m| (m - v).length() > 8.0 * eps)
        })
    }
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

    // Always inlined: four calls in the split's loop, each a few instructions past the call.
    #[inline(always)]
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
    /// distinct points are left. The points are moved out of the piece, taken by reference:
    /// taken by value, the whole piece (~200 bytes) was copied into the call.
    fn take_polygon(&mut self, parent: &Polygon, cut: &Plane) -> Option<Polygon> {
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
                std::mem::take(&mut self.points),
                parent.plane,
                parent.source,
            ));
        }
        let n = parent.vertices.len();
        let own = parent.edges();
        // Each corner with the next, the last with the first: an exact-size iterator, so the
        // shared slice is allocated once at its size.
        let corners = &self.corners[..m];
        let next = corners[1..].iter().chain(&corners[..1]);
        let edges = corners
            .iter()
            .zip(next)
            .map(|(a, b)| {
                let ((i, a_cut), (j, b_cut)) = (a.get(), b.get());
                // Along edge `i` of the parent: from its vertex `i` (or its cut) to its vertex
                // `i + 1`, or from its vertex `i` to its cut.
                let along = if b_cut {
                    !a_cut && i == j
                } else {
                    j == if i + 1 == n { 0 } else { i + 1 }
                };
                if along {
                    own.get(i).copied().unwrap_or(UNKNOWN)
                } else {
                    *cut
                }
            })
            .collect();
        Some(Polygon {
            vertices: std::mem::take(&mut self.points),
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

/// Below this sine of the angle between a cutting plane and the polygon's plane or the plane
/// of the edge it cuts, an edge running nearly along the cutting plane is cut at the [`meet`]
/// of the three planes rather than interpolated. The meet takes the line of the two closest to
/// parallel, computed the same by both operands, so every point either puts on the crossing
/// line of two nearly coincident faces lies on one line to rounding.
///
/// Interpolated, a cut lies on the crossing line only to a rounding error of the ends'
/// distances over the sine, across the face: at 1.7·10⁻⁶ rad (a 32×16 sphere less itself
/// turned 10⁻⁴°), 10⁻¹¹ to 10⁻¹⁰, up to four welds. Each operand cut its facet on its own
/// estimate of the line, from its own edges, and the two met at neither end: slits a facet
/// long and 10⁻¹¹ to 10⁻¹⁰ wide (291 loops, 971 boundary edges; 64×32: 4,349), the mesh's
/// volume 21 % below the solid's. Cut at meets up to 10⁻⁵ (3·10⁻⁶ is enough there), the 32×16
/// and 64×32 spheres less themselves turned 10⁻⁵° to 10⁻²° come out closed, their volume
/// within 2·10⁻⁴ of the true one (10⁻⁵° to 3·10⁻⁴° were open before). Above 10⁻⁵ an
/// interpolation is off by under 10⁻¹¹ (10⁻¹⁶ over the sine), within the weld.
///
/// So too where the edge's own two planes cross at this bound or more, the cutting plane
/// crossing one of them below it: the meet then takes the crossing line of the cut and that
/// plane, on which the other operand's points lie. Taken only where they crossed at
/// [`GRAZING`] or more, the meridian edges of a 256×128 sphere's first two rings (neighbours
/// crossing at 6·10⁻⁴ and 9·10⁻⁴), cut by the facets of the sphere turned 10⁻⁴°, were
/// interpolated 8.7·10⁻¹¹ off the crossing line, where the other operand's cut of the twin
/// facet by a cell plane of its tree lay on it: three-edge slits, 1,666 boundary edges.
///
/// An edge whose own two planes cross below this bound is cut at the meet only where all three
/// planes do: three collinear edges of one crossing line cut by a third face (fork input
/// 8114e14d), interpolated, scattered one point over 1.2e-7 and left a flat shell; the meet of
/// the same three planes is the same point for each.
///
/// Vertices are still judged against the crossing line only below [`NEAR_PARALLEL`](super::side::NEAR_PARALLEL) (see
/// `crossing_at`): the meet here only places the cut.
const MEET_BELOW: f64 = 1e-5;

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
            if cut.normal.dot(d).abs() < GRAZING * len {
                let (own_cut, along_cut) = (sine(own, cut), sine(along, cut));
                let own_along = sine(own, along);
                // Either the edge's own two planes cross wider than the cut crosses one of
                // them (the meet's line is the cut's with that plane), or all three planes are
                // nearly parallel (the same three planes, so the same bits in any order).
                let meets = own_cut.min(along_cut) < MEET_BELOW
                    && (own_along >= MEET_BELOW
                        || (own_along >= PARALLEL_BELOW && own_cut.max(along_cut) < MEET_BELOW));
                if meets && let Some(p) = meet(own, along, cut) {
                    // Taken only where it lies on the edge: planes that barely cross (a
                    // neighbour in the polygon's own plane) meet anywhere.
                    let t = (p - a).dot(d) / (len * len);
                    let reach = eps / own_along.min(1.0);
                    if (0.0..=1.0).contains(&t) && (p - a).cross(d).length() <= reach * len {
                        return p;
                    }
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
pub(super) fn edge_cut(
    a: DVec3,
    da: f64,
    b: DVec3,
    db: f64,
    plane: &Plane,
    axis: Option<usize>,
) -> DVec3 {
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

/// Lexicographic order of points, for choosing one of several candidates the same way
/// whatever order they come in.
#[inline]
pub(super) fn lex_less(a: DVec3, b: DVec3) -> bool {
    (a.x, a.y, a.z) < (b.x, b.y, b.z)
}
