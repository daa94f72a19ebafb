//! Cutting a polygon by a plane: which vertices count as on it, and where an edge is cut so
//! that every polygon sharing the edge computes the same point.

use glam::DVec3;
use smallvec::SmallVec;

use super::planes::{Crossing, canonical, meet, plane_bits};
use super::{Polygon, Split, UNKNOWN, Vertices};
use crate::geom::{Plane, Side, Tolerance};

impl Polygon {
    /// Where the polygon lies relative to `plane`, vertices within `eps` counting as on it, and
    /// whether some vertex does.
    ///
    /// A tree build that classified polygons by this to choose a splitter takes `Front` and
    /// `Back` as final, with a vertex near or not and for nearly parallel planes too, so that
    /// every polygon it settles at a vertex judges the vertex alike (see `Tree::face_node`);
    /// and `Coplanar` where `plane` is the polygon's own or coplanar by `eps` alone (see
    /// `coplanar_within_eps`). [`Polygon::split`] gives the same answers for a polygon tracking
    /// no edge planes, except where a vertex is near and `plane` nearly parallel: it judges
    /// that vertex by a narrower band.
    pub(crate) fn side_near(&self, plane: &Plane, eps: f64) -> (Side, bool) {
        if self.plane.is_same_or_flipped(plane) {
            return (Side::Coplanar, true);
        }
        let (mut front, mut back, mut near) = (false, false, false);
        for &v in &self.vertices {
            let d = plane.distance(v);
            front |= d > eps;
            back |= d < -eps;
            near |= d.abs() <= eps;
        }
        let side = match (front, back) {
            (false, false) => Side::Coplanar,
            (true, false) => Side::Front,
            (false, true) => Side::Back,
            (true, true) => Side::Spanning,
        };
        (side, near)
    }

    /// True when a polygon all of whose vertices lie within `eps` of `plane` is coplanar with
    /// it for that alone: `plane` is its own, or crosses it at a sine of at least
    /// [`ON_BAND_BELOW`] or below [`PARALLEL_BELOW`] (see [`Polygon::split`]).
    pub(crate) fn coplanar_within_eps(&self, plane: &Plane) -> bool {
        self.plane.is_same_or_flipped(plane)
            || !banded(self.plane.normal.cross(plane.normal).length())
    }

    /// True when `plane` crosses the polygon's own at a sine below [`ON_BAND_BELOW`] (or is its
    /// own): the negation of [`Polygon::crosses`] but for rounding at that bound, from the
    /// cosine alone (no square root), for a build's every polygon near a splitter.
    pub(crate) fn nearly_parallel_to(&self, plane: &Plane) -> bool {
        let cos = self.plane.normal.dot(plane.normal);
        cos * cos > 1.0 - ON_BAND_BELOW * ON_BAND_BELOW
    }

    /// True when the polygon's plane and a plane of unit normal `normal` count as parallel:
    /// they cross at a sine below [`PARALLEL_BELOW`], so a polygon within `eps` of the other
    /// is coplanar with it by `eps` alone.
    pub(crate) fn parallel_to(&self, normal: DVec3) -> bool {
        self.plane.normal.cross(normal).length() < PARALLEL_BELOW
    }

    /// True when `plane` crosses the polygon's own at a sine of at least [`ON_BAND_BELOW`] (not
    /// nearly parallel), so that a polygon within `eps` of it is a sliver thinner than the
    /// tolerance across it rather than a face lying in it.
    pub(crate) fn crosses(&self, plane: &Plane) -> bool {
        !self.plane.is_same_or_flipped(plane)
            && self.plane.normal.cross(plane.normal).length() >= ON_BAND_BELOW
    }

    /// Classifies against `plane` and, where the polygon spans it, cuts it in two. A polygon is
    /// coplanar with its own plane whatever its vertices say (see [`Plane::is_same_or_flipped`]),
    /// and with any plane all its vertices lie on, as told below.
    ///
    /// Where the planes cross at a sine below 10⁻³ (`ON_BAND_BELOW`) and a vertex lies within
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
                    tight[i] = (eps * at).max(crossing.rounding());
                    judged = true;
                }
            }
        }
        if sine < ON_BAND_BELOW || judged {
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
        let own = self.plane.normal.cross(plane.normal).length();
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
pub(crate) fn plane_noise(plane: &Plane, v: DVec3) -> f64 {
    64.0 * f64::EPSILON * ((v - plane.anchor).abs().max_element() + v.abs().max_element())
}

/// How far from `plane` the rounding of its distance alone puts a point not computed on it.
/// [`Plane::distance`] is `n · (v − anchor)`: for coordinates taken as they are, the
/// subtraction rounds each component by at most ε |vᵢ − aᵢ| and the three-term dot product adds
/// at most γ₃ Σ |nᵢ| |vᵢ − aᵢ|, about 7 ε |v − anchor|ₘₐₓ in all, which `GIVEN_NOISE_ULPS`
/// covers. [`plane_noise`]'s |v| term and its factor are for points whose own coordinates
/// were rounded onto the plane; a vertex that merely lies near it (an operand turned a hair
/// onto the other's face) must not count as on it beyond this, or the cut runs through a corner
/// 10⁻¹⁴ off the plane and the other operand, cut along the true line, leaves a slit.
#[inline]
fn given_noise(plane: &Plane, v: DVec3) -> f64 {
    GIVEN_NOISE_ULPS * f64::EPSILON * (v - plane.anchor).abs().max_element()
}

/// Units in the last place of a vertex's distance from its anchor that rounding can put a
/// point not computed on a plane off it (see [`given_noise`]).
const GIVEN_NOISE_ULPS: f64 = 8.0;

impl Polygon {
    /// Whether vertex `i` may have been computed on `plane` (or its flip): an edge beside it
    /// lies in `plane`, or the plane of an edge beside it is not known; where the polygon
    /// tracks no edge planes at all, any vertex, or if it is `given` (never cut) one that
    /// the polygon whose plane `plane` is holds too. Such a vertex keeps
    /// [`plane_noise`]; any other is taken as given and gets [`given_noise`]. A polygon with an
    /// edge in `plane` lies on one side of it, so it is never cut by it: where a vertex reads
    /// as made on `plane` in one polygon and as given in another, only the second can be cut
    /// there, and its cut point on the shared edge meets the first as a T-junction within
    /// rounding, which `to_mesh` resolves as any other.
    fn made_on(&self, i: usize, plane: &Plane, given: Option<&[DVec3]>) -> bool {
        let n = self.vertices.len();
        let edges = self.edges();
        if edges.len() != n {
            return given.is_none_or(|on| on.contains(&self.vertices[i]));
        }
        [&edges[(i + n - 1) % n], &edges[i]]
            .iter()
            .any(|e| e.normal == DVec3::ZERO || e.is_same_or_flipped(plane))
    }
}

impl Polygon {
    /// The crossing line vertex `i`, near `plane`, is judged by, and the sine of its planes:
    /// that of `plane` and whichever of the planes the vertex lies on (the polygon's own, at
    /// sine `own`, and its two edges') crosses it nearly in parallel (at a sine from
    /// [`PARALLEL_BELOW`] to [`NEAR_PARALLEL`]), the closest to parallel if more than one does
    /// (as [`meet`] takes it; the least by its bits on a tie).
    /// `None` where none does, or an edge beside the vertex lies in `plane` (the vertex was
    /// made on it).
    ///
    /// Where two faces cross at such an angle, the distance of a vertex of either from the
    /// other's plane is the distance across their crossing line times the sine plus the
    /// rounding of its coordinates off its own plane, which across the line is that over the
    /// sine (7e-9 at 1.4e-9 rad): two operands' corners 1e-10 apart, each on the other's
    /// plane to rounding, each judged against the other's face alone, were ordered along the
    /// line one way by one operand and the other way by the other. Judged by one line both
    /// operands compute the same (the [`meet`] line), in every polygon holding the vertex
    /// (those of the nearly parallel face by their own plane, its neighbours by the edge they
    /// share with it), the two pictures agree, and the edges crossing the line are cut at
    /// `meet`s on it.
    fn crossing_at(&self, i: usize, plane: &Plane, own: f64) -> Option<(Crossing, f64)> {
        let n = self.vertices.len();
        let edges = self.edges();
        let band = |s: f64| (PARALLEL_BELOW..NEAR_PARALLEL).contains(&s);
        let mut best: Option<(&Plane, f64)> = band(own).then_some((&self.plane, own));
        for e in [&edges[(i + n - 1) % n], &edges[i]] {
            if e.normal == DVec3::ZERO {
                continue;
            }
            if e.is_same_or_flipped(plane) {
                return None;
            }
            let s = e.normal.cross(plane.normal).length();
            // The pair closest to parallel, as `meet` takes it (bits break a tie).
            let closer = |(b, t): (&Plane, f64)| {
                s < t || (s == t && plane_bits(&canonical(e)) < plane_bits(&canonical(b)))
            };
            if band(s) && best.is_none_or(closer) {
                best = Some((e, s));
            }
        }
        let (on, s) = best?;
        Some((Crossing::new(on, plane)?, s))
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

/// Below this sine of the angle between a polygon's plane and a cutting plane, the two count
/// as parallel, and a polygon within `eps` of the plane is coplanar with it as for two exactly
/// parallel planes, the same for every polygon on either (faces a tolerance apart, flush at a
/// tolerance the caller asked for; translated copies). Between this and [`ON_BAND_BELOW`] it
/// is coplanar only within the band by the angle.
///
/// Half the relative tolerance (`Tolerance::RELATIVE`, 10⁻¹²): below it the planes part by
/// less than half of `eps` across the region `eps` is relative to (where the operands' boxes
/// meet), the band `eps / sine` is over twice that region wide, and where two such faces touch
/// within half of `eps` anywhere there, every vertex of either there lies within `eps` of the
/// other's plane, so the two operands cannot judge the crossing differently.
///
/// Within the band they could: the crossing line of planes 10⁻¹³ apart is known only to a
/// rounding error over the angle, 10⁻¹⁷ / 1.7·10⁻¹³ = 6·10⁻⁵ across the face, and each
/// fragment of a face cut before judged its corners against it alone. A box turned 10⁻¹¹°
/// (1.7·10⁻¹³ rad) united with a bar under its bottom face was cut on that line into a slot
/// thinner than the weld (open, 4 boundary edges), and, the box's bottom already cut by a
/// third solid, its fragments kept 5.6·10⁻⁵ more area in the slot than the bar's top: the
/// solid's volume 7·10⁻⁶ above the sum of the operands. At 10⁻¹⁴ (the old bound, a hundredth
/// of the tolerance) turns of 10⁻¹¹° were banded; turns of 10⁻¹⁰° (1.7·10⁻¹²) still are.
pub(super) const PARALLEL_BELOW: f64 = Tolerance::RELATIVE / 2.0;

/// Whether a polygon within `eps` of a plane crossing its own at `sine` is coplanar with it
/// only within the band by the angle (see [`Polygon::split`]).
#[inline]
fn banded(sine: f64) -> bool {
    (PARALLEL_BELOW..ON_BAND_BELOW).contains(&sine)
}

/// Below this sine of the angle between a polygon's plane and a cutting plane, the two cross
/// "nearly in parallel": a vertex near the plane on such a pair is judged by its distance
/// across their crossing line (see `crossing_at`). (Edges running along the plane are cut at
/// the [`meet`] of their planes below the wider [`MEET_BELOW`].)
///
/// The old band of `eps / sine` reaches 10⁷ tolerances across the face here, which no weld
/// closes (a box turned 10⁻⁹°: 1.7e-11 rad, a slit 0.6 wide). Above it, vertices are left to
/// the band (see [`ON_BAND_BELOW`]): where three or more nearly parallel planes meet
/// (Havocglass8's flat neighbours cross the other model's at 5e-7 to 5e-5 rad) no vertex is
/// well defined, and only the band and the weld agree (measured when this bound also set where
/// edges were cut at meets: 9 boundary edges with meets up to 1e-3, 3 up to 1e-6, none at
/// 1e-7). With edge cuts at meets up to [`MEET_BELOW`] (for an edge whose own two planes cross
/// below [`GRAZING`] only where all three planes are nearly parallel, see `CutEdge::cut`),
/// Havocglass8's booleans stay closed and right.
const NEAR_PARALLEL: f64 = 1e-7;

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
/// An edge whose own two planes cross below [`GRAZING`] is cut at the meet too where all three
/// planes cross below this bound: three collinear edges of one crossing line cut by a third
/// face (fork input 8114e14d), interpolated, scattered one point over 1.2e-7 and left a flat
/// shell; the meet of the same three planes is the same point for each.
///
/// Vertices are still judged against the crossing line only below [`NEAR_PARALLEL`] (see
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
                // Either the edge's own two planes cross clearly, or all three planes are
                // nearly parallel (the same three planes, so the same bits in any order).
                let meets = own_cut.min(along_cut) < MEET_BELOW
                    && (own_along >= GRAZING
                        || (own_along >= PARALLEL_BELOW
                            && own_cut.max(along_cut).max(own_along) < MEET_BELOW));
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

#[cfg(test)]
mod tests {
    use super::*;

    /// True when `plane` crosses the polygon's at a sine below [`ON_BAND_BELOW`], where
    /// [`Polygon::split`] counts vertices as on it within a band narrower than `eps`.
    fn nearly_parallel(poly: &Polygon, plane: &Plane) -> bool {
        poly.plane.normal.cross(plane.normal).length() < ON_BAND_BELOW
    }

    /// Where `side_near` settles a polygon, `split` says the same: planes through a vertex
    /// (a vertex near), tilted from the polygon's own by angles from 10⁻⁹ to 1 rad (inside and
    /// outside the nearly parallel band), at offsets within and beyond the tolerance.
    #[test]
    fn side_near_settles_as_split_does() {
        let ring = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.3, 0.1, 0.7),
            DVec3::new(0.4, 1.6, 1.2),
        ];
        let poly = Polygon::new(&ring, 3).unwrap();
        let n = poly.plane().normal;
        let across = n.any_orthonormal_vector();
        let eps = 1e-9;
        let (mut settled, mut near_settled, mut in_band) = (0, 0, 0);
        for tilt in [0.0, 1e-9, 1e-7, 1e-5, 5e-4, 2e-3, 0.1, 1.0] {
            let normal = (n + across * tilt).normalize();
            for &v in &ring {
                for offset in [-3.0 * eps, -0.5 * eps, 0.0, 0.7 * eps, 2.0 * eps, 0.3] {
                    for normal in [normal, -normal] {
                        let plane = Plane::through(v + normal * offset, normal);
                        let (side, near) = poly.side_near(&plane, eps);
                        let split = poly.split(&plane, eps);
                        let want = match side {
                            Side::Coplanar => "Coplanar",
                            Side::Front => "Front",
                            Side::Back => "Back",
                            Side::Spanning => continue,
                        };
                        let sure = match side {
                            Side::Coplanar => poly.coplanar_within_eps(&plane),
                            _ => !near || !nearly_parallel(&poly, &plane),
                        };
                        if !sure {
                            in_band += 1;
                            continue;
                        }
                        settled += 1;
                        near_settled += usize::from(near && side != Side::Coplanar);
                        let got = format!("{split:?}");
                        assert!(got.starts_with(want), "{want} vs {got}: {plane:?}");
                    }
                }
            }
        }
        assert!(
            settled > 100 && near_settled > 20 && in_band > 5,
            "{settled} settled, {near_settled} with a vertex near, {in_band} in the band"
        );
    }
}
