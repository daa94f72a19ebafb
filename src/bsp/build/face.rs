//! Face splits: csg.js nodes, the splitter chosen among a few of the cell's polygons.

use glam::DVec3;

use super::arena::Arena;
use super::{Ids, Scratch};
use crate::bsp::{Kind, Label, Link, Node, Tree};
use crate::geom::{Aabb, Plane, Side};
use crate::polygon::{Split, Vertices, plane_noise};

/// How many polygons a face split tries as splitter.
const SPLITTER_CANDIDATES: usize = 5;

impl Tree {
    /// A csg.js node: the chosen splitter's plane keeps the polygons coplanar with it (a sliver
    /// across it, coplanar by the tolerance alone, also goes to the side it lies on: see
    /// [`sliver_side`]); the rest
    /// go front or back, split where they span it. Empty sides stay leaves: outside in front,
    /// inside behind. The splitter's choice already classified every polygon against its plane;
    /// only those it could not settle (see [`Class`]) are handed to [`Polygon::split`].
    pub(super) fn face_node(
        &mut self,
        ids: Ids,
        corners: &Corners,
        eps: f64,
        arena: &mut Arena,
        scratch: &mut Scratch,
    ) -> (Node, Ids, Ids, (Corners, Corners)) {
        let (mut front, mut back) = (scratch.ids_like(&ids), scratch.ids_like(&ids));
        let Ids { near: ids, far } = ids;
        let chosen = choose_splitter(&ids, arena, eps, scratch);
        let plane = *arena.poly(chosen).plane();
        // Far polygons are never cut nor chosen: each goes whole to every side it reaches.
        for &id in &far {
            let (mut ahead, mut behind) = (false, false);
            for &v in arena.poly(id).vertices() {
                let d = plane.distance(v);
                ahead |= d > eps;
                behind |= d < -eps;
            }
            if ahead || !behind {
                front.far.push(id);
            }
            if behind || !ahead {
                back.far.push(id);
            }
        }
        let splitter: Vertices = arena.poly(chosen).vertices().iter().copied().collect();
        let start = self.polygons.len() as u32;
        let mut own = Aabb::EMPTY;
        // The vertices within `eps` of the plane of nearly parallel polygons sent to one side
        // (see `Wedge`).
        let mut wedge = Wedge::default();
        // Slivers reaching both sides of the plane, settled once every polygon is noted and
        // pushed after the side's other near polygons: a near list's order only orders the
        // candidates for the splitters below (no output of the bench cases or of the 900-case
        // cross-check corpus changed, byte for byte).
        let mut two_sided: smallvec::SmallVec<[u32; 4]> = smallvec::SmallVec::new();
        for (k, &id) in ids.iter().enumerate() {
            let class = scratch.best.get(k).copied().unwrap_or(Class::Unsettled);
            let poly = arena.poly(id);
            let parallel =
                !matches!(class, Class::Front | Class::Back) && poly.nearly_parallel_to(&plane);
            let split = match class {
                Class::Front => Split::Front,
                Class::Back => Split::Back,
                // Beyond `eps` on one side only: whole to that side, even where `plane` is
                // nearly parallel and `split` would judge a near vertex by its narrower band.
                // That band depends on each polygon's angle to `plane`, so polygons settled here
                // at one vertex would judge it differently and a sliver off the corner would take
                // its plane into one subtree without its neighbour
                // (`scene_bsp_route_of_a_bracket_keeps_a_sliver_of_a_holes_ceiling`). A
                // polygon spanning `plane` still goes to `split`, which may use the band. Only
                // the tree's planes and partition matter here: its own pieces are never output.
                Class::FrontNear => Split::Front,
                Class::BackNear => Split::Back,
                // Nearly parallel planes: coplanar only within the band `split` tells.
                Class::Coplanar if poly.coplanar_within_eps(&plane) => Split::Coplanar,
                _ => poly.split_as(&plane, eps, arena.given(id).then_some(&splitter[..])),
            };
            match split {
                Split::Coplanar => {
                    own = own.union(&arena.boxes[id as usize]);
                    self.polygons.push(arena.poly(id).clone());
                    // A sliver across the plane (within `eps` of it, its own plane crossing it
                    // steeply) also bounds the side it lies on; see `sliver_side`. One reaching
                    // both sides waits for its neighbours (`Wedge::side_of`).
                    if poly.crosses(&plane) {
                        let (lo, hi) = sliver_reach(poly.vertices(), &plane);
                        if lo < 0.0 && hi > 0.0 {
                            two_sided.push(id);
                        } else {
                            match sliver_side(poly.vertices(), &plane) {
                                Some(Side::Front) => front.near.push(id),
                                Some(_) => back.near.push(id),
                                None => {}
                            }
                        }
                    }
                }
                Split::Front => {
                    if parallel {
                        wedge.note(poly.vertices(), &plane, eps, Side::Front);
                    }
                    front.near.push(id);
                }
                Split::Back => {
                    if parallel {
                        wedge.note(poly.vertices(), &plane, eps, Side::Back);
                    }
                    back.near.push(id);
                }
                Split::Spanning { front: f, back: b } => {
                    if parallel {
                        wedge.note(f.vertices(), &plane, eps, Side::Front);
                        wedge.note(b.vertices(), &plane, eps, Side::Back);
                    }
                    front.near.push(arena.push(f, id));
                    back.near.push(arena.push(b, id));
                }
            }
        }
        scratch.recycle(ids);
        scratch.recycle(far);
        for id in two_sided {
            let vs = arena.poly(id).vertices();
            let side = wedge
                .side_of(vs, &plane, eps)
                .or_else(|| sliver_side(vs, &plane));
            match side {
                Some(Side::Front) => front.near.push(id),
                Some(_) => back.near.push(id),
                None => {}
            }
        }
        // This node's own corners go down to the side a nearly parallel polygon went to, where
        // that polygon's node may need the steep faces ending at them (see `Corners`).
        let (mut front_corners, mut back_corners) = corners.split(&plane, eps);
        let own_corners = || {
            self.polygons[start as usize..]
                .iter()
                .flat_map(|p| p.vertices().iter().map(|&v| (plane.normal, v)))
        };
        if !wedge.ahead.is_empty() {
            front_corners.0.extend(own_corners());
        }
        if !wedge.behind.is_empty() {
            back_corners.0.extend(own_corners());
        }
        corners.note(&mut wedge, &plane, eps);
        // Steep polygons ending at such a vertex on the other side also bound that side.
        if !wedge.ahead.is_empty() {
            let follow = wedge.followers(&back.near, arena, &plane, eps, Side::Front);
            front.near.extend(follow);
        }
        if !wedge.behind.is_empty() {
            let follow = wedge.followers(&front.near, arena, &plane, eps, Side::Back);
            back.near.extend(follow);
        }
        let node = Node {
            plane,
            kind: Kind::Face {
                start,
                end: self.polygons.len() as u32,
            },
            front: Link::Leaf(Label::Outside),
            back: Link::Leaf(Label::Inside),
            content: own,
            own,
        };
        (node, front, back, (front_corners, back_corners))
    }
}

/// Corners of face nodes above a work item, each with its node's normal: a face node passes its
/// own polygons' corners down to the side where a nearly parallel polygon went within the
/// tolerance (noted in [`Wedge`]), and the node of that polygon's plane below notes those lying
/// within the tolerance off it as `Wedge` notes its own polygons' vertices, so that the steep
/// polygons ending at them follow to that side too.
///
/// `Wedge` alone serves where the steep polygons end at the nearly parallel polygon's own
/// vertices. Where they end at the corners of the node above, the face they bound is not in
/// the subtree: a 0.125 cube's bottom with a bar's beside it turned 10⁻¹⁰° (1.4·10⁻¹² rad,
/// its plane 5.7·10⁻¹³ above the cube's bottom there, within the tolerance), the bar's bottom
/// went behind the cube's, and the cube's side faces, whose corners lie within the tolerance in
/// front of the bar's plane, behind it by the tolerance alone (`Class::BackNear`); the bar's
/// node's front leaf read the wedge between the two planes over the cube as outside, and a slab
/// through both kept the strip of its bottom between their crossing lines over the cube beside
/// the cube's own bottom (the union open by 4.1·10⁻⁴, the solid 2.6·10⁻⁵ above its mesh).
/// With the cube's corners passed down, its side faces also bound that front subtree.
///
/// Only nodes whose planes cross at a sine below 10⁻³ note each other's corners: narrower than
/// the band in which [`Wedge`] notes a node's own polygons' vertices (`ON_BAND_BELOW`, 0.1),
/// the bound the fix was measured with; whether the two should be one is not settled. Empty
/// but where such a wedge is (no allocation otherwise).
#[derive(Default, Clone)]
pub(super) struct Corners(Vec<(DVec3, DVec3)>);

impl Corners {
    /// The corners reaching each side of `plane` (within `eps`: both).
    pub(super) fn split(&self, plane: &Plane, eps: f64) -> (Corners, Corners) {
        let (mut front, mut back) = (Corners::default(), Corners::default());
        for &(n, v) in &self.0 {
            let d = plane.distance(v);
            if d >= -eps {
                front.0.push((n, v));
            }
            if d <= eps {
                back.0.push((n, v));
            }
        }
        (front, back)
    }

    /// Notes in `wedge` the corners of nodes nearly parallel to `plane` within `eps` off it.
    fn note(&self, wedge: &mut Wedge, plane: &Plane, eps: f64) {
        for &(n, v) in &self.0 {
            // Crossing at a sine of 10⁻³ or more: not the wedge's planes.
            let cos = n.dot(plane.normal);
            if cos * cos <= 1.0 - 1e-6 {
                continue;
            }
            match off_within(plane, v, eps) {
                Some(Side::Front) => wedge.ahead.push(v),
                Some(_) => wedge.behind.push(v),
                None => {}
            }
        }
    }
}

/// The vertices within the tolerance of a face node's plane, but off it, of polygons in planes
/// nearly parallel to it (crossing it at a sine below `ON_BAND_BELOW`, 0.1) that [`Polygon::split`] sent to
/// one side by its narrow band: `ahead` those in front, `behind` those behind.
///
/// Such a polygon, within the tolerance of the plane but judged by the band, bounds a wedge
/// between its plane and the node's on that side, thinner than the tolerance where it lies but
/// unbounded along the line where the two planes cross. Its steep neighbours, ending at the
/// same vertices within the tolerance, are settled by the tolerance alone (`Class::FrontNear`,
/// `Class::BackNear`) and go to the other side only: the subtree holding the wedge then lacks
/// the planes that end it, and read a region far beyond its polygons as inside. A 0.125 cube's
/// top beside a slab's turned 1e-10° (5e-13 above the slab's top plane, the cube's side faces
/// reaching it within 1.6e-12) left the region above the slab's top and below the cube's
/// unbounded along y: a bar's top in the cube's plane, 0.06 beyond the cube, was dropped there
/// as inside (the union's solid 8.1e-4 below its mesh). Such a steep polygon, sharing one of
/// these vertices (bit for bit, as polygons sharing a corner do), also goes to that side
/// (`followers`), where its plane ends the wedge.
#[derive(Default)]
struct Wedge {
    ahead: smallvec::SmallVec<[DVec3; 8]>,
    behind: smallvec::SmallVec<[DVec3; 8]>,
}

impl Wedge {
    /// Notes the vertices of a polygon (or piece) sent to `side` that lie on that side within
    /// `eps`.
    fn note(&mut self, vertices: &[DVec3], plane: &Plane, eps: f64, side: Side) {
        for &v in vertices {
            match off_within(plane, v, eps) {
                Some(s) if s == side => match side {
                    Side::Front => self.ahead.push(v),
                    _ => self.behind.push(v),
                },
                _ => {}
            }
        }
    }

    /// The side of `plane` a sliver reaching both sides of it beyond its rounding lies on, by its
    /// neighbours: the side where a nearly parallel polygon noted there has a vertex at one of
    /// the sliver's corners on that side (to the plane's rounding: the two polygons' cut points
    /// on the edge they share differ in the last bits); `None` where neither side or both do.
    ///
    /// The sliver is then the end of a thin wedge whose long face, nearly parallel to `plane`,
    /// the band sent to that side; its reach to the other side is the tolerance's. A union of
    /// three 15 × 9 spheres, two turned 1e-9° about different axes ((a ∪ b) ∪ c): a ∪ b kept a
    /// strip of b's facet 16 along its edge to facet 17, reaching 4e-13 in front of a's facet 17
    /// (where b stands out of a: the strip's own part, beside b's facet 17 in front) and, cut
    /// within the tolerance, 8.9e-13 behind it, under a's facet 16. Clipping c against a ∪ b,
    /// the strip, sent behind a's facet 17 by its reach, made a node of b's plane behind a's
    /// facets 16 and 17 whose front leaf read the layer between b's plane and a's (8.9e-13
    /// apart, crossing at 8.8e-12 rad) outside across the facet, and c's facet, lying in that
    /// layer inside a, was kept: 2.2e-3 of area doubled, 4 shells. Sent where b's facet 17
    /// went, its plane bounds the strip alone.
    fn side_of(&self, vertices: &[DVec3], plane: &Plane, eps: f64) -> Option<Side> {
        let at = |noted: &[DVec3], side: Side| {
            vertices.iter().any(|&v| {
                off_within(plane, v, eps) == Some(side)
                    && noted
                        .iter()
                        .any(|&w| (v - w).abs().max_element() <= plane_noise(plane, v))
            })
        };
        match (at(&self.ahead, Side::Front), at(&self.behind, Side::Back)) {
            (true, false) => Some(Side::Front),
            (false, true) => Some(Side::Back),
            _ => None,
        }
    }

    /// Of the polygons `ids` sent to the side opposite `side`, the steep ones reaching into
    /// `side` within `eps` at a vertex noted on it.
    fn followers(
        &self,
        ids: &[u32],
        arena: &Arena,
        plane: &Plane,
        eps: f64,
        side: Side,
    ) -> Vec<u32> {
        let noted = match side {
            Side::Front => &self.ahead,
            _ => &self.behind,
        };
        ids.iter()
            .copied()
            .filter(|&id| {
                let poly = arena.poly(id);
                poly.crosses(plane)
                    && poly
                        .vertices()
                        .iter()
                        .any(|&v| off_within(plane, v, eps) == Some(side) && noted.contains(&v))
            })
            .collect()
    }
}

/// The side of `plane` a point within `eps` of it lies on beyond the rounding of its distance
/// ([`plane_noise`]): `None` for a point farther, or on the plane within that rounding.
fn off_within(plane: &Plane, v: DVec3, eps: f64) -> Option<Side> {
    let d = plane.distance(v);
    if d.abs() > eps || d.abs() <= plane_noise(plane, v) {
        None
    } else if d > 0.0 {
        Some(Side::Front)
    } else {
        Some(Side::Back)
    }
}

/// The side of `plane` a polygon lying within the tolerance of it, in a plane crossing it
/// steeply, reaches further to; `None` on a tie: every vertex on the plane, or a sliver
/// reaching exactly as far to both sides, which then stays at the node alone.
///
/// Such a polygon is coplanar with `plane` by the tolerance alone: the end of a sliver thinner
/// than the tolerance, such as the wedge between two faces crossing at 1.4e-10 rad (a cube's
/// face beside a slab's turned 1e-8°, 1.5e-13 apart where the cube ends). Kept at the node
/// alone, as csg.js keeps coplanar polygons, its plane bounded neither side, and the subtree on
/// the sliver's side, which holds the sliver's long faces, took the region beyond its end for
/// the sliver's inside: a face of the other operand lying there, outside by 1e-13 (and within
/// the tolerance of the sliver's face, which that operand's tree had judged inside it), was
/// dropped with it, a hole of 1.1e-6 in a union of that cube and slab with a bar (the solid
/// 4.6e-8 below its larger operand). Passed also to the side it lies on (never to both: on
/// the other side its plane bounds nothing, and a leaf behind it would read inside), its plane
/// bounds the sliver there.
///
/// A vertex off the plane within its rounding ([`plane_noise`]) reaches neither side. A 0.125
/// cube's face z = −0.5625 stood out of a box's face turned 1e-5° by 1.3e-15 (the noise there
/// 8.9e-15) as a sliver across the cube's face x = −0.4375, where the box's face, coplanar with
/// that node, stays. Passed to the back, its plane alone bounded the region behind and read
/// outside below z = −0.5625, across the box's inside: the intersection of that union with the
/// cube dropped a strip of the cube's face lying in that plane (a flat shell).
///
/// A sliver reaching both sides beyond the rounding goes where its nearly parallel neighbour
/// went, when one shares its corner (see `Wedge::side_of`); its reach decides only otherwise.
fn sliver_side(vertices: &[DVec3], plane: &Plane) -> Option<Side> {
    let (lo, hi) = sliver_reach(vertices, plane);
    if hi > -lo {
        Some(Side::Front)
    } else if -lo > hi {
        Some(Side::Back)
    } else {
        None
    }
}

/// How far a polygon's vertices reach behind (`lo`, at most 0) and in front of (`hi`, at least
/// 0) `plane`, a vertex within the plane's rounding ([`plane_noise`]) reaching neither side.
fn sliver_reach(vertices: &[DVec3], plane: &Plane) -> (f64, f64) {
    vertices.iter().fold((0.0f64, 0.0f64), |(lo, hi), &v| {
        let d = plane.distance(v);
        // Within the plane's rounding a vertex is on it: it reaches neither side.
        let d = if d.abs() <= plane_noise(plane, v) {
            0.0
        } else {
            d
        };
        (lo.min(d), hi.max(d))
    })
}

/// A polygon against a candidate splitter's plane, from [`Polygon::side_near`]: what
/// [`Polygon::split`] would say without cutting, where that is settled (`*Near`: a vertex
/// within `eps`, the rest beyond it on one side, which the build takes as it is even where
/// `split` would judge that vertex by the band of nearly parallel planes; see
/// [`Tree::face_node`]); `Unsettled` is left to `split`.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Class {
    Front,
    Back,
    FrontNear,
    BackNear,
    Coplanar,
    Unsettled,
}

/// The splitter for a face node: of a few evenly spaced candidates, the one that cuts the fewest
/// polygons, then leaves the sides most even. A candidate that cuts nothing and leaves nothing
/// in front is taken at once: on a convex patch every candidate is like that; one that cuts more
/// polygons than the best so far is dropped as soon as it does. Leaves the
/// polygons' classes against the chosen plane in `scratch.best` (empty when there was no
/// choice to make).
fn choose_splitter(ids: &[u32], arena: &Arena, eps: f64, scratch: &mut Scratch) -> u32 {
    let n = ids.len();
    scratch.best.clear();
    if n <= 2 {
        return ids[0];
    }
    let step = n.div_ceil(SPLITTER_CANDIDATES).max(1);
    let mut best = (usize::MAX, usize::MAX, ids[0]);
    for c in (0..n).step_by(step) {
        let plane = arena.poly(ids[c]).plane();
        let (mut front, mut back, mut spanning) = (0usize, 0usize, 0usize);
        scratch.classes.clear();
        for &id in ids {
            let (side, near) = arena.poly(id).side_near(plane, eps);
            scratch.classes.push(match (side, near) {
                (Side::Front, false) => Class::Front,
                (Side::Back, false) => Class::Back,
                (Side::Front, true) => Class::FrontNear,
                (Side::Back, true) => Class::BackNear,
                (Side::Coplanar, _) => Class::Coplanar,
                (Side::Spanning, _) => Class::Unsettled,
            });
            match side {
                Side::Front => front += 1,
                Side::Back => back += 1,
                Side::Spanning => spanning += 1,
                Side::Coplanar => {}
            }
            // Cutting more polygons than the best so far, this candidate cannot win.
            if spanning > best.0 {
                break;
            }
        }
        if spanning > best.0 {
            continue;
        }
        if spanning == 0 && front == 0 {
            std::mem::swap(&mut scratch.best, &mut scratch.classes);
            return ids[c];
        }
        let score = (spanning, front.abs_diff(back), ids[c]);
        if (score.0, score.1) < (best.0, best.1) {
            best = score;
            std::mem::swap(&mut scratch.best, &mut scratch.classes);
        }
    }
    best.2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sliver reaching further one way goes that way; one on the plane, or reaching exactly
    /// as far to both sides (1e-13 each), has no side and stays at the node alone.
    #[test]
    fn a_sliver_reaching_as_far_both_ways_has_no_side() {
        let plane = Plane::from_point_normal(DVec3::ZERO, DVec3::Z).unwrap();
        let sliver = |up: f64, down: f64| {
            let vs = [
                DVec3::new(0.0, 0.0, up),
                DVec3::new(1.0, 0.0, -down),
                DVec3::new(0.0, 1.0, 0.0),
            ];
            sliver_side(&vs, &plane)
        };
        assert_eq!(sliver(2e-13, 1e-13), Some(Side::Front));
        assert_eq!(sliver(1e-13, 2e-13), Some(Side::Back));
        assert_eq!(sliver(1e-13, 1e-13), None);
        assert_eq!(sliver(0.0, 0.0), None);
    }

    /// A vertex off the plane within its rounding ([`plane_noise`], 1.4e-14 half a unit from
    /// the anchor) reaches neither side: a sliver whose one vertex stands 1e-15 off has no side,
    /// one 1e-13 off has.
    #[test]
    fn a_sliver_reaching_within_the_planes_rounding_has_no_side() {
        let plane = Plane::from_point_normal(DVec3::ZERO, DVec3::Z).unwrap();
        let sliver = |up: f64| {
            let vs = [
                DVec3::new(0.5, 0.0, up),
                DVec3::new(0.5, 1.0, 0.0),
                DVec3::new(-0.5, 0.0, 0.0),
            ];
            sliver_side(&vs, &plane)
        };
        assert_eq!(sliver(1e-15), None);
        assert_eq!(sliver(-1e-15), None);
        assert_eq!(sliver(1e-13), Some(Side::Front));
        assert_eq!(sliver(-1e-13), Some(Side::Back));
    }
}
