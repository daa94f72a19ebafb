//! Where a point or polygon lies against a plane: which vertices count as on it (the tolerance,
//! the band by the angle for nearly parallel planes, a vertex's distance across a crossing
//! line), and the bounds on the angle that choose among them. [`Polygon::split`] cuts by these.

use glam::DVec3;

use super::Polygon;
use super::planes::{Crossing, canonical, plane_bits};
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
    /// no edge planes, except where a vertex is near and `plane` nearly parallel, or an edge
    /// beside that vertex runs nearly along `plane`: it judges that vertex by a narrower band.
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
}

/// Which side of `cut` the point `v` of `own` lies on, judged as [`Polygon::split`] judges a
/// vertex near a nearly parallel plane (crossing it at a sine in the band from
/// [`PARALLEL_BELOW`] to [`NEAR_PARALLEL`]): by its distance across their crossing line
/// ([`Crossing::side`]); `None` for planes not in that band, or a point on the line within
/// its rounding.
pub(crate) fn side_across_line(own: &Plane, cut: &Plane, v: DVec3) -> Option<f64> {
    let sine = own.normal.cross(cut.normal).length();
    if !(PARALLEL_BELOW..NEAR_PARALLEL).contains(&sine) {
        return None;
    }
    let crossing = Crossing::new(own, cut)?;
    let s = crossing.side(v);
    (s.abs() > crossing.rounding()).then_some(s)
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

/// Whether `e`, the plane of an edge, is `plane` flipped to rounding: opposite normals whose
/// sine is below [`FLIPPED_BELOW`]. A vertex on such an edge and within `eps` of `plane` lies on
/// the face across the edge, which is `plane`'s twin (a prism's face and a cuboid's face
/// against it, each computed from its own corners): it was made on `plane` as much as on `e`.
///
/// Judged instead by the line where the polygon's own plane crosses `plane` (see
/// [`Polygon::crossing_at`]), it read beside that line: the two twins cross a third plane
/// nearly parallel to both (a cube turned 10⁻⁶°, 1.7·10⁻⁸ rad) on lines the twins' rounding
/// (3.8·10⁻¹⁶ rad between them) puts 2·10⁻⁹ apart at the cube's edge. A union of a 3-segment
/// prism, that cube on its face x = −0.4375 and a cuboid whose face x = −0.4375 is the
/// prism's twin kept the strip of the cube's face between the two lines (6.1·10⁻¹¹, the solid
/// open by that much in +x); a slab united next built its tree on the strip, whose plane read
/// outside across the prism, and kept 1.6·10⁻² of the slab's bottom inside it (round 20's fork
/// input e5d963a7: the solid 3.7·10⁻³ above its mesh).
///
/// Only flipped twins: for same-facing ones (round 18's 15d49cd9, a flat remnant of a sphere
/// less itself turned 10⁻⁹°, united with the sphere moved along a face's plane) judging the
/// vertex on the plane cut the remnant away from where the other operand's crossing lines cut
/// the sphere's faces (the volume 6.5·10⁻⁸ out of bounds), which the crossing line keeps
/// consistent.
#[inline]
fn flipped_twin(e: &Plane, plane: &Plane) -> bool {
    e.normal.dot(plane.normal) < 0.0 && e.normal.cross(plane.normal).length() < FLIPPED_BELOW
}

/// The sine below which an edge's plane facing against a cutting plane is taken as its flip
/// (see [`flipped_twin`]): 64 ulps, well above the rounding of a plane fitted to corners
/// (3.8·10⁻¹⁶ for a prism's face from cosines) and below [`PARALLEL_BELOW`] (5·10⁻¹³), under
/// which an edge's plane is never taken as a crossing line either. Between the two, an edge's
/// plane facing against `plane` is neither a twin nor a crossing: the vertex is judged by the
/// polygon's own plane and its other edge. Whether the bound could be `PARALLEL_BELOW` itself
/// was not measured (15d49cd9 shows same-facing twins must stay out).
const FLIPPED_BELOW: f64 = 64.0 * f64::EPSILON;

/// How far from `plane` the rounding of its distance alone puts a point not computed on it.
/// [`Plane::distance`] is `n · (v − anchor)`: for coordinates taken as they are, the
/// subtraction rounds each component by at most ε |vᵢ − aᵢ| and the three-term dot product adds
/// at most γ₃ Σ |nᵢ| |vᵢ − aᵢ|, about 7 ε |v − anchor|ₘₐₓ in all, which `GIVEN_NOISE_ULPS`
/// covers. [`plane_noise`]'s |v| term and its factor are for points whose own coordinates
/// were rounded onto the plane; a vertex that merely lies near it (an operand turned a hair
/// onto the other's face) must not count as on it beyond this, or the cut runs through a corner
/// 10⁻¹⁴ off the plane and the other operand, cut along the true line, leaves a slit.
#[inline]
pub(super) fn given_noise(plane: &Plane, v: DVec3) -> f64 {
    GIVEN_NOISE_ULPS * f64::EPSILON * (v - plane.anchor).abs().max_element()
}

/// Units in the last place of a vertex's distance from its anchor that rounding can put a
/// point not computed on a plane off it (see [`given_noise`]).
const GIVEN_NOISE_ULPS: f64 = 8.0;

impl Polygon {
    /// Whether vertex `i` may have been computed on `plane` (or its flip): an edge beside it
    /// lies in `plane` (or its [`flipped_twin`]), or the plane of an edge beside it is not known; where the polygon
    /// tracks no edge planes at all, any vertex, or if it is `given` (never cut) one that
    /// the polygon whose plane `plane` is holds too. Such a vertex keeps
    /// [`plane_noise`]; any other is taken as given and gets [`given_noise`]. A polygon with an
    /// edge in `plane` lies on one side of it, so it is never cut by it: where a vertex reads
    /// as made on `plane` in one polygon and as given in another, only the second can be cut
    /// there, and its cut point on the shared edge meets the first as a T-junction within
    /// rounding, which `to_mesh` resolves as any other.
    pub(super) fn made_on(&self, i: usize, plane: &Plane, given: Option<&[DVec3]>) -> bool {
        let n = self.vertices.len();
        let edges = self.edges();
        if edges.len() != n {
            return given.is_none_or(|on| on.contains(&self.vertices[i]));
        }
        [&edges[(i + n - 1) % n], &edges[i]].iter().any(|e| {
            e.normal == DVec3::ZERO || e.is_same_or_flipped(plane) || flipped_twin(e, plane)
        })
    }
}

impl Polygon {
    /// The crossing line vertex `i`, near `plane`, is judged by, and the sine of its planes:
    /// that of `plane` and whichever of the planes the vertex lies on (the polygon's own, at
    /// sine `own`, and its two edges') crosses it nearly in parallel (at a sine from
    /// [`PARALLEL_BELOW`] to [`NEAR_PARALLEL`]), the closest to parallel if more than one does
    /// (as [`meet`](super::planes::meet) takes it; the least by its bits on a tie).
    /// `None` where none does, or an edge beside the vertex lies in `plane` or its [`flipped_twin`] (the vertex was
    /// made on it).
    ///
    /// Where two faces cross at such an angle, the distance of a vertex of either from the
    /// other's plane is the distance across their crossing line times the sine plus the
    /// rounding of its coordinates off its own plane, which across the line is that over the
    /// sine (7e-9 at 1.4e-9 rad): two operands' corners 1e-10 apart, each on the other's
    /// plane to rounding, each judged against the other's face alone, were ordered along the
    /// line one way by one operand and the other way by the other. Judged by one line both
    /// operands compute the same (the [`meet`](super::planes::meet) line), in every polygon holding the vertex
    /// (those of the nearly parallel face by their own plane, its neighbours by the edge they
    /// share with it), the two pictures agree, and the edges crossing the line are cut at
    /// `meet`s on it.
    pub(super) fn crossing_at(&self, i: usize, plane: &Plane, own: f64) -> Option<(Crossing, f64)> {
        let n = self.vertices.len();
        let edges = self.edges();
        let band = |s: f64| (PARALLEL_BELOW..NEAR_PARALLEL).contains(&s);
        let mut best: Option<(&Plane, f64)> = band(own).then_some((&self.plane, own));
        for e in [&edges[(i + n - 1) % n], &edges[i]] {
            if e.normal == DVec3::ZERO {
                continue;
            }
            if e.is_same_or_flipped(plane) || flipped_twin(e, plane) {
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
/// come out closed, to the first-order volume within 10⁻⁵.
///
/// At 10⁻³ (the old bound) a 256×128 sphere less itself turned 10⁻⁴° stayed open at its poles:
/// there every fan facet of either sphere passes within 10⁻⁶ of the pole, and a fan edge of one
/// is crossed by the other's fan facets from across the pole (sine 0.0245) at points 8·10⁻¹¹
/// apart along it, each of those planes 2·10⁻¹² from the next there, within `eps`
/// (3.5·10⁻¹²). Judged by `eps`, the two polygons beside the edge took different planes as
/// through the same corner, and their cuts ended 8·10⁻¹¹ apart along it (653 boundary edges
/// in slits 8·10⁻¹¹ × 7·10⁻⁹). With the band below 0.1 those are gone (2,319 → 1,666 boundary
/// edges in all; the rest went with edge cuts at meets, see `CutEdge::cut`). Above 0.1 the
/// two bands differ by less than a factor of ten, and clear crossings keep the tolerance they
/// always had.
///
/// The bound moves more than the band by the angle: it also sets where the band by an edge's
/// slope applies in `Polygon::split` (sines from 0.1, slopes below 0.1; before, from 10⁻³ and
/// below 10⁻³, so vertices at sines 10⁻³ … 0.1 once banded at `eps` times the slope are now
/// banded at `eps` times the sine, up to 25× wider at a 128×64 sphere's poles), which
/// polygons within `eps` of a splitter are coplanar with it in the tree's build
/// (`coplanar_within_eps`: between 10⁻³ and 0.1 they now go to `split`), how far the wedge
/// notes reach (`nearly_parallel_to`), and where `crosses` steeply enough (5.7°) for
/// `sliver_side` and the followers. Raising it from 10⁻³ to 0.1 was measured through the
/// command line on 294 cases (a cube, a 64-cylinder and UV spheres 16 … 128 less, with and
/// against themselves turned 10⁻⁴° … 5.7° about (0.3, 1, 0.2) and moved; cubes turned
/// 0.001° … 12° about an edge, a corner and the diagonal; 32 and 64 spheres turned 0.001° … 3°
/// about the pole axis and the equator): all closed before and after, the outputs identical
/// but for three spheres turned 10⁻⁴° (64 less: 16,188 → 16,198 triangles, volume 4.6·10⁻⁹
/// lower relatively; 128 less: 65,194 → 65,188, 1.8·10⁻⁸ lower; 128 with: the last digit).
pub(super) const ON_BAND_BELOW: f64 = 0.1;

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
pub(super) fn banded(sine: f64) -> bool {
    (PARALLEL_BELOW..ON_BAND_BELOW).contains(&sine)
}

/// Below this sine of the angle between a polygon's plane and a cutting plane, the two cross
/// "nearly in parallel": a vertex near the plane on such a pair is judged by its distance
/// across their crossing line (see `crossing_at`). (Edges running along the plane are cut at
/// the [`meet`](super::planes::meet) of their planes below the wider `MEET_BELOW`, see
/// `CutEdge::cut`.)
///
/// The old band of `eps / sine` reaches 10⁷ tolerances across the face here, which no weld
/// closes (a box turned 10⁻⁹°: 1.7e-11 rad, a slit 0.6 wide). Above it, vertices are left to
/// the band (see [`ON_BAND_BELOW`]): where three or more nearly parallel planes meet
/// (Havocglass8's flat neighbours cross the other model's at 5e-7 to 5e-5 rad) no vertex is
/// well defined, and only the band and the weld agree (measured when this bound also set where
/// edges were cut at meets: 9 boundary edges with meets up to 1e-3, 3 up to 1e-6, none at
/// 1e-7). With edge cuts at meets up to `MEET_BELOW` (for an edge whose own two planes cross
/// below `MEET_BELOW` only where all three planes are nearly parallel, see `CutEdge::cut`),
/// Havocglass8's booleans stay closed and right.
pub(super) const NEAR_PARALLEL: f64 = 1e-7;

#[cfg(test)]
mod tests {
    use super::*;

    /// True when `plane` crosses the polygon's at a sine below [`ON_BAND_BELOW`], where
    /// [`Polygon::split`] counts vertices as on it within a band narrower than `eps`.
    fn nearly_parallel(poly: &Polygon, plane: &Plane) -> bool {
        poly.plane.normal.cross(plane.normal).length() < ON_BAND_BELOW
    }

    /// True when a vertex within `eps` of `plane` has an edge beside it running along `plane`
    /// at a slope below [`ON_BAND_BELOW`] to an end beyond `eps`, where [`Polygon::split`] also
    /// narrows the band.
    fn grazed(poly: &Polygon, plane: &Plane, eps: f64) -> bool {
        let v = poly.vertices();
        let n = v.len();
        (0..n).any(|i| {
            plane.distance(v[i]).abs() <= eps
                && [v[(i + n - 1) % n], v[(i + 1) % n]].iter().any(|&w| {
                    plane.distance(w).abs() > eps
                        && plane.normal.dot(w - v[i]).abs() < ON_BAND_BELOW * (w - v[i]).length()
                })
        })
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
        for tilt in [
            0.0, 1e-9, 1e-7, 1e-5, 5e-4, 2e-3, 0.01, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0,
        ] {
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
                            _ => {
                                !near
                                    || !(nearly_parallel(&poly, &plane)
                                        || grazed(&poly, &plane, eps))
                            }
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
