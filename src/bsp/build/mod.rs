//! Building the tree: cell splits while a cell holds many polygons (`cell`), face splits below
//! (`face`), regions nothing clipped comes near left unbuilt (here).
//!
//! Polygons live in an arena (`arena`) with their boxes and centroids cached; the work items
//! carry only `u32` ids, so partitioning a level moves four bytes per polygon, not the polygon.
//! A work item's ids come in two lists, the polygons that are built and the far ones carried
//! whole (see [`Focus`]).

mod arena;
mod cell;
mod face;

use glam::DVec3;

use self::arena::Arena;
use self::cell::{axis_of, cell_plane, split_cell, wrap_plane};
use self::face::Class;
use super::meter::{CHARGE_EVERY, Meter};
use super::{Kind, Label, Link, Node, Tree};
use crate::geom::{Aabb, Plane};
use crate::polygon::Polygon;

/// Cells holding more polygons than this are cut by an axis-aligned plane when a good one exists.
const CELL_POLYGONS: usize = 12;
/// The margin by which a cell must miss every focus box to be left unbuilt, in tolerances. It
/// exceeds the clip's early-out margin (2), so a fragment of a focus polygon that reaches an
/// unbuilt cell lies clear of the cell's polygons and is labelled whole from one point.
pub(crate) const FOCUS_MARGIN: f64 = 4.0;

/// What a focused build is told: the boxes of what will be clipped against the tree, and per
/// polygon of the solid whether it is near them; one that is not is *far*: it comes within
/// [`FOCUS_MARGIN`] tolerances of none of the polygons clipped (its box misses theirs, or a
/// plane of one of the two lies between them; see `Surface::near_each_other`), so no fragment
/// clipped can meet it.
///
/// A far polygon is never cut nor chosen as a splitter. Cell planes are placed by the other
/// polygons alone ([`wrap_plane`], else their centroids); a far polygon goes whole to each
/// side of a cell plane its box reaches and of a face plane its vertices reach (both, within
/// the tolerance), and a region holding only far polygons is left unbuilt ([`Kind::Stub`]: its
/// label comes from the surface, and the far polygons listed there include every one reaching
/// into it). A built region holds no far polygon, so its leaves are labelled by the faces that
/// bound them as before. On rocker-arm 24.6 k of a tree's 40.5 k cut pieces were far
/// polygons', nearly all ending in unbuilt cells; the trees now take 196 M instructions per
/// boolean instead of 228 M. Cutting far polygons only when a cell is built, and building
/// them there, was measured slower (their cuts rose to 33 k: near polygons are dense on real
/// models, so the cells built hold many far ones).
#[derive(Clone, Copy)]
pub(crate) struct Focus<'a> {
    pub boxes: &'a [Aabb],
    /// Per polygon of the tree, whether it is near: one flag for every polygon.
    pub near: &'a [bool],
    /// Per polygon of the tree, its box (`Polygon::bbox`), which the solid's surface has made
    /// already.
    pub own_boxes: &'a [Aabb],
}

/// Where a finished node is linked in.
#[derive(Clone, Copy)]
enum Slot {
    Root,
    Front(u32),
    Back(u32),
}

/// Buffers reused by every work item of one build.
#[derive(Default)]
struct Scratch {
    /// Centroid coordinates along one axis, as [`cell::order_key`]s, for the median.
    keys: Vec<i64>,
    /// Per polygon of a face node, its [`Class`] against the candidate splitter being scored
    /// and against the best one so far.
    classes: Vec<Class>,
    best: Vec<Class>,
    /// The id lists of work items done with, emptied, for the next ones: lists made afresh
    /// for each side at every level, freed at the next and regrown, cost about 6 M of
    /// rocker-arm's 68 M instructions of trees per boolean.
    spare: Vec<Vec<u32>>,
    /// The origins of an unbuilt cell's pieces, sorted (see [`Tree::stub`]).
    origins: Vec<u32>,
}

impl Scratch {
    /// An empty list with room for `room` ids.
    fn list(&mut self, room: usize) -> Vec<u32> {
        let mut list = self.spare.pop().unwrap_or_default();
        list.reserve(room);
        list
    }

    /// Room for what either side of a cell of `ids` may take.
    fn ids_like(&mut self, ids: &Ids) -> Ids {
        Ids {
            near: self.list(ids.near.len()),
            far: self.list(ids.far.len()),
        }
    }

    /// Takes back a list no longer needed.
    fn recycle(&mut self, mut list: Vec<u32>) {
        list.clear();
        self.spare.push(list);
    }

    fn recycle_ids(&mut self, ids: Ids) {
        self.recycle(ids.near);
        self.recycle(ids.far);
    }
}

/// A cell's polygons: those that are not far (the solid's own and pieces cut from them), and
/// the far ones reaching into it, carried whole (see [`Focus`]). Kept apart, no pass over a
/// cell's polygons asks which are far. The far ones stay in increasing order (each split keeps
/// their order).
#[derive(Default)]
struct Ids {
    near: Vec<u32>,
    far: Vec<u32>,
}

impl Ids {
    fn is_empty(&self) -> bool {
        self.near.is_empty() && self.far.is_empty()
    }

    fn len(&self) -> usize {
        self.near.len() + self.far.len()
    }
}

struct Work {
    ids: Ids,
    slot: Slot,
    /// Indices of the focus boxes that may reach this cell (`None`: build everything).
    focus: Option<Vec<u32>>,
    /// The cell's bounds from the axis-aligned planes above it (infinite where none bounds it).
    cell: Aabb,
    /// Corners of face nodes above, passed down to the side a nearly parallel polygon went
    /// to within the tolerance (see `face::Corners`).
    corners: face::Corners,
}

impl Tree {
    /// Builds the whole tree of a closed solid's polygons with plane-side tolerance `eps`.
    pub fn build(polygons: Vec<Polygon>, eps: f64) -> Tree {
        Tree::build_focused(&polygons, eps, None, None)
    }

    /// The whole cell, before any plane bounds it.
    const EVERYWHERE: Aabb = Aabb {
        min: DVec3::splat(f64::NEG_INFINITY),
        max: DVec3::splat(f64::INFINITY),
    };

    /// Builds the tree, but where `focus` is given, only the cells whose polygons come within
    /// [`FOCUS_MARGIN`] tolerances of a focus box; the rest stay [`Kind::Stub`]s. Booleans pass
    /// the boxes of the other operand's polygons that come near this surface: only those are
    /// clipped. Their fragments do reach unbuilt cells: point location ends in one wherever a
    /// fragment is classified whole (its box misses a node's content, or spans a cell plane
    /// with no surface near), and a fragment can be routed into one. None comes within the
    /// margin of the cell's polygons (a fragment lies in its polygon's box), so the cell's
    /// surface does not cross it and `Tree::clip` labels it from one point, by counting
    /// crossings (see [`Kind::Stub`]). On rocker-arm ∪ moved about 4,800 fragments per
    /// boolean are labelled so.
    ///
    /// The corners of the pieces its splits cut are charged to `meter`, as a clip's are: past
    /// its limit the build stops, leaving the cells not yet built as leaves, and the tree is
    /// for no use (a clip by it returns nothing once the meter is past its limit).
    pub fn build_focused(
        polygons: &[Polygon],
        eps: f64,
        focus: Option<Focus>,
        meter: Option<&Meter>,
    ) -> Tree {
        // Room for about what the trees of real models end with (half a node and half a stored
        // polygon per polygon of the solid): regrowing from empty was 5 % of the build.
        let mut tree = Tree {
            nodes: Vec::with_capacity(polygons.len() / 2),
            polygons: Vec::with_capacity(polygons.len() / 2),
            stub_polygons: Vec::new(),
            root: Link::Leaf(Label::Outside),
            eps,
        };
        if polygons.is_empty() {
            return tree;
        }
        let margin = FOCUS_MARGIN * eps;
        let mut arena = Arena::new(polygons, focus.as_ref());
        let mut scratch = Scratch::default();
        let all = 0..arena.len() as u32;
        let ids = match focus {
            None => Ids {
                near: all.collect(),
                far: Vec::new(),
            },
            Some(f) => {
                debug_assert_eq!(f.near.len(), arena.len(), "a near flag per polygon");
                let (near, far) = all.partition(|&i| f.near[i as usize]);
                Ids { near, far }
            }
        };
        let focus = focus.map(|f| f.boxes);
        let mut work = vec![Work {
            ids,
            slot: Slot::Root,
            focus: focus.map(|f| (0..f.len() as u32).collect()),
            cell: Self::EVERYWHERE,
            corners: face::Corners::default(),
        }];
        while let Some(Work {
            ids,
            slot,
            focus: near,
            cell,
            corners,
        }) = work.pop()
        {
            let index = tree.nodes.len() as u32;
            // The box of the cell's polygons that are not far, for the focus and `wrap_plane`
            // (without a focus no polygon is far, and `wrap_plane` needs none).
            let content =
                (focus.is_some() && !ids.near.is_empty()).then(|| arena.bbox_of(&ids.near));
            let near = match (focus, near) {
                (Some(boxes), Some(near)) => {
                    // Keep only the focus boxes that reach the cell's polygons that are not
                    // far (a far one comes near none of them): none where every polygon is far.
                    let mut near = near;
                    match &content {
                        None => near.clear(),
                        Some(content) => {
                            near.retain(|&i| boxes[i as usize].overlaps(content, margin));
                        }
                    }
                    if near.is_empty() {
                        scratch.recycle(near);
                        tree.stub(ids, &cell, &arena, &mut scratch);
                        tree.attach(slot, index);
                        continue;
                    }
                    Some(near)
                }
                _ => None,
            };
            // The plane is placed by the polygons that are not far alone: first around them,
            // where many far polygons lie beyond their box.
            let plane = wrap_plane(&ids, content.as_ref(), &arena, eps).or_else(|| {
                (ids.near.len() > CELL_POLYGONS)
                    .then(|| cell_plane(&ids.near, &arena, eps, &mut scratch.keys))
                    .flatten()
            });
            let (node, front, back, (front_corners, back_corners)) = match plane {
                Some(plane) => {
                    let (front, back) = split_cell(ids, &plane, eps, &mut arena, &mut scratch);
                    let sides = corners.split(&plane, eps);
                    (Node::cell(plane), front, back, sides)
                }
                None => tree.face_node(ids, &corners, eps, &mut arena, &mut scratch),
            };
            // The children's cells: a face plane bounds no axis.
            let (mut front_cell, mut back_cell) = (cell, cell);
            if let (Kind::Cell, Some(axis)) = (&node.kind, axis_of(&node.plane)) {
                let at = node.plane.anchor[axis];
                front_cell.min[axis] = front_cell.min[axis].max(at);
                back_cell.max[axis] = back_cell.max[axis].min(at);
            }
            tree.nodes.push(node);
            tree.attach(slot, index);
            if let Some(meter) = meter
                && arena.cut >= CHARGE_EVERY
                && !meter.charge(std::mem::take(&mut arena.cut))
            {
                break;
            }
            if front.is_empty() {
                scratch.recycle_ids(front);
            } else {
                let focus = near.as_ref().map(|near| {
                    let mut copy = scratch.list(near.len());
                    copy.extend_from_slice(near);
                    copy
                });
                work.push(Work {
                    ids: front,
                    slot: Slot::Front(index),
                    focus,
                    cell: front_cell,
                    corners: front_corners,
                });
            }
            if back.is_empty() {
                scratch.recycle_ids(back);
                if let Some(near) = near {
                    scratch.recycle(near);
                }
            } else {
                work.push(Work {
                    ids: back,
                    slot: Slot::Back(index),
                    focus: near,
                    cell: back_cell,
                    corners: back_corners,
                });
            }
        }
        if let Some(meter) = meter {
            meter.charge(arena.cut);
        }
        tree.fill_content();
        tree
    }

    /// Leaves a cell unbuilt: a [`Kind::Stub`] listing the polygons its pieces were cut from,
    /// each once, in increasing order.
    fn stub(&mut self, ids: Ids, cell: &Aabb, arena: &Arena, scratch: &mut Scratch) {
        let content = arena.bbox_in(&ids, cell, self.eps);
        let origins = &mut scratch.origins;
        origins.clear();
        origins.extend(ids.near.iter().map(|&id| arena.origin(id)));
        origins.sort_unstable();
        origins.dedup();
        // Far polygons are never cut: each is its own origin, listed once and in order already,
        // so only the near ones' origins need sorting; the two lists are merged.
        debug_assert!(ids.far.is_sorted_by(|a, b| a < b), "far ids in order, once");
        let start = self.stub_polygons.len();
        merge_into(&mut self.stub_polygons, origins, &ids.far);
        let end = self.stub_polygons.len();
        self.nodes
            .push(Node::stub(content, start as u32, end as u32));
        scratch.recycle_ids(ids);
    }

    fn attach(&mut self, slot: Slot, index: u32) {
        match slot {
            Slot::Root => self.root = Link::Node(index),
            Slot::Front(p) => self.nodes[p as usize].front = Link::Node(index),
            Slot::Back(p) => self.nodes[p as usize].back = Link::Node(index),
        }
    }

    /// Each node's content box grows by its children's; children come after their parents.
    fn fill_content(&mut self) {
        for i in (0..self.nodes.len()).rev() {
            if matches!(self.nodes[i].kind, Kind::Stub { .. }) {
                continue;
            }
            let (front, back) = (self.nodes[i].front, self.nodes[i].back);
            let mut content = self.nodes[i].content;
            for link in [front, back] {
                if let Link::Node(c) = link {
                    content = content.union(&self.nodes[c as usize].content);
                }
            }
            self.nodes[i].content = content;
        }
    }
}

/// Appends to `out` the ids of two increasing lists, in increasing order, an id in both once.
fn merge_into(out: &mut Vec<u32>, a: &[u32], b: &[u32]) {
    out.reserve(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        let (x, y) = (a[i], b[j]);
        out.push(x.min(y));
        i += usize::from(x <= y);
        j += usize::from(y <= x);
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
}

impl Node {
    fn cell(plane: Plane) -> Node {
        Node {
            plane,
            kind: Kind::Cell,
            front: Link::Leaf(Label::Outside),
            back: Link::Leaf(Label::Inside),
            content: Aabb::EMPTY,
            own: Aabb::EMPTY,
        }
    }

    fn stub(content: Aabb, start: u32, end: u32) -> Node {
        Node {
            plane: Plane::through(DVec3::ZERO, DVec3::X),
            kind: Kind::Stub { start, end },
            front: Link::Leaf(Label::Outside),
            back: Link::Leaf(Label::Outside),
            content,
            own: Aabb::EMPTY,
        }
    }
}
