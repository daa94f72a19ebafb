//! Face splits: csg.js nodes, the splitter chosen among a few of the cell's polygons.

use super::arena::Arena;
use super::{Ids, Scratch};
use crate::bsp::{Kind, Label, Link, Node, Tree};
use crate::geom::{Aabb, Side};
use crate::polygon::{Split, Vertices};

/// How many polygons a face split tries as splitter.
const SPLITTER_CANDIDATES: usize = 5;

impl Tree {
    /// A csg.js node: the chosen splitter's plane keeps the polygons coplanar with it; the rest
    /// go front or back, split where they span it. Empty sides stay leaves: outside in front,
    /// inside behind. The splitter's choice already classified every polygon against its plane;
    /// only those it could not settle (see [`Class`]) are handed to [`Polygon::split`].
    pub(super) fn face_node(
        &mut self,
        ids: Ids,
        eps: f64,
        arena: &mut Arena,
        scratch: &mut Scratch,
    ) -> (Node, Ids, Ids) {
        let (mut front, mut back) = (Ids::with_room_for(&ids), Ids::with_room_for(&ids));
        let Ids { near: ids, far } = ids;
        let chosen = choose_splitter(&ids, arena, eps, scratch);
        let plane = *arena.poly(chosen).plane();
        // Far polygons are never cut nor chosen: each goes whole to every side it reaches.
        for id in far {
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
        for (k, id) in ids.into_iter().enumerate() {
            let class = scratch.best.get(k).copied().unwrap_or(Class::Unsettled);
            let poly = arena.poly(id);
            let split = match class {
                Class::Front => Split::Front,
                Class::Back => Split::Back,
                // Beyond `eps` on one side only: whole to that side, even where `plane` is
                // nearly parallel and `split` would judge the near vertex by the narrower band by
                // the angle. That band depends on the polygon's angle to `plane`, so polygons
                // sharing a vertex could disagree about it: two triangles of a marching-cubes
                // wall 9e-4 rad off the splitter (the wall's triangle below them) cut a sliver
                // 3e-9 across off at their corner 2.7e-12 in front of it, which their neighbour
                // round the corner, 0.2 rad off, counted as on the plane and kept behind. The
                // slivers took their planes into the front subtree without the neighbour, whose
                // leaves then labelled a wedge beyond the corner inside (9e-4 rad, 0.09 long):
                // a hole's ceiling clipped there kept a piece outside the solid, a flat shell
                // in the mesh (`tests/fuzz_findings/bsp_9.json`). By `eps` every polygon at the
                // vertex agrees. Only the tree's planes and partition matter here: its own
                // pieces are never output.
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
                }
                Split::Front => front.near.push(id),
                Split::Back => back.near.push(id),
                Split::Spanning { front: f, back: b } => {
                    front.near.push(arena.push(f, id));
                    back.near.push(arena.push(b, id));
                }
            }
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
        (node, front, back)
    }
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
