//! Building the tree: cell splits while a cell holds many polygons, face splits below.
//!
//! Polygons live in an arena with their boxes and centroids cached; the work items carry only
//! `u32` ids, so partitioning a level moves four bytes per polygon, not the polygon.

use glam::DVec3;

use super::{Kind, Label, Link, Node, Tree};
use crate::geom::{Aabb, Plane, Side};
use crate::polygon::{Polygon, Split, Vertices};

/// Cells holding more polygons than this are cut by an axis-aligned plane when a good one exists.
const CELL_POLYGONS: usize = 12;
/// How many polygons a face split tries as splitter.
const SPLITTER_CANDIDATES: usize = 5;
/// The margin by which a cell must miss every focus box to be left unbuilt, in tolerances. It
/// exceeds the clip's early-out margin (2), so a fragment of a focus polygon that reaches an
/// unbuilt cell lies clear of the cell's polygons and is labelled whole from one point.
pub(crate) const FOCUS_MARGIN: f64 = 4.0;

/// What a focused build is told: the boxes of what will be clipped against the tree, and per
/// polygon of the solid whether it is *far*: its box misses every one of them by
/// [`FOCUS_MARGIN`] tolerances, so no fragment clipped can meet it.
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
    pub far: &'a [bool],
}

/// Where a finished node is linked in.
#[derive(Clone, Copy)]
enum Slot {
    Root,
    Front(u32),
    Back(u32),
}

/// Polygons with their boxes and centroids: the solid's own, borrowed, then the split pieces,
/// appended. Borrowing spares a copy of every polygon of the operand per boolean.
struct Arena<'a> {
    base: &'a [Polygon],
    /// Per polygon of `base`, whether it is far (see [`Focus`]); empty when none is.
    far: &'a [bool],
    pieces: Vec<Polygon>,
    boxes: Vec<Aabb>,
    centroids: Vec<DVec3>,
    /// Per piece, the index in `base` of the polygon it was cut from.
    origins: Vec<u32>,
}

impl<'a> Arena<'a> {
    fn new(base: &'a [Polygon], far: &'a [bool]) -> Self {
        // Cell splits cut the long thin triangles of tessellated CAD parts into about two
        // pieces per polygon of the solid: room for that from the start spares copying the
        // growing arena (a fifth of the build's instructions).
        let room = 2 * base.len();
        let mut boxes = Vec::with_capacity(base.len() + room);
        boxes.extend(base.iter().map(Polygon::bbox));
        let mut centroids = Vec::with_capacity(base.len() + room);
        centroids.extend(base.iter().map(Polygon::centroid));
        Arena {
            base,
            far,
            pieces: Vec::with_capacity(room),
            boxes,
            centroids,
            origins: Vec::with_capacity(room),
        }
    }

    fn len(&self) -> usize {
        self.base.len() + self.pieces.len()
    }

    fn poly(&self, id: u32) -> &Polygon {
        let id = id as usize;
        match self.base.get(id) {
            Some(p) => p,
            None => &self.pieces[id - self.base.len()],
        }
    }

    /// Whether `id` is one of the solid's own polygons, not a piece this build cut: where it
    /// tracks no edge planes, its vertices were made on no plane but those of the polygons
    /// sharing them (see [`Polygon::split_as`]).
    fn given(&self, id: u32) -> bool {
        (id as usize) < self.base.len()
    }

    /// Whether `id` is a polygon far from every focus box. Far polygons are never cut, so a
    /// piece (an id past `base`) is never far: no lookup of its origin.
    fn is_far(&self, id: u32) -> bool {
        self.far.get(id as usize).copied().unwrap_or(false)
    }

    /// The index in `base` of the polygon `id` is or was cut from.
    fn origin(&self, id: u32) -> u32 {
        match (id as usize).checked_sub(self.base.len()) {
            None => id,
            Some(k) => self.origins[k],
        }
    }

    /// Stores a piece cut from polygon `from`.
    fn push(&mut self, p: Polygon, from: u32) -> u32 {
        self.origins.push(self.origin(from));
        self.boxes.push(p.bbox());
        self.centroids.push(p.centroid());
        self.pieces.push(p);
        (self.len() - 1) as u32
    }

    fn bbox_of(&self, ids: &[u32]) -> Aabb {
        ids.iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(&self.boxes[i as usize]))
    }

    /// [`Arena::bbox_of`] in a cell that far polygons may reach out of: their boxes are cut
    /// down to the cell's (grown by `eps`, as far as the pieces of cut polygons reach past a
    /// plane).
    fn bbox_in(&self, ids: &[u32], cell: &Aabb, eps: f64) -> Aabb {
        let cell = cell.expanded(eps);
        ids.iter().fold(Aabb::EMPTY, |b, &i| {
            let bbox = &self.boxes[i as usize];
            if self.is_far(i) {
                b.union(&bbox.intersection(&cell))
            } else {
                b.union(bbox)
            }
        })
    }
}

/// Buffers reused by every work item of one build.
#[derive(Default)]
struct Scratch {
    /// Centroid coordinates along one axis, as [`order_key`]s, for the median.
    keys: Vec<i64>,
    /// The ids of a cell that are not far, whose centroids place its plane.
    near_ids: Vec<u32>,
    /// Per polygon of a face node, its [`Class`] against the candidate splitter being scored
    /// and against the best one so far.
    classes: Vec<Class>,
    best: Vec<Class>,
}

struct Work {
    ids: Vec<u32>,
    slot: Slot,
    /// Indices of the focus boxes that may reach this cell (`None`: build everything).
    focus: Option<Vec<u32>>,
    /// The cell's bounds from the axis-aligned planes above it (infinite where none bounds it).
    cell: Aabb,
}

impl Tree {
    /// Builds the whole tree of a closed solid's polygons with plane-side tolerance `eps`.
    pub fn build(polygons: Vec<Polygon>, eps: f64) -> Tree {
        Tree::build_focused(&polygons, eps, None)
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
    pub fn build_focused(polygons: &[Polygon], eps: f64, focus: Option<Focus>) -> Tree {
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
        let far: &[bool] = focus.map_or(&[], |f| f.far);
        let focus = focus.map(|f| f.boxes);
        let mut arena = Arena::new(polygons, far);
        let mut scratch = Scratch::default();
        let mut work = vec![Work {
            ids: (0..arena.len() as u32).collect(),
            slot: Slot::Root,
            focus: focus.map(|f| (0..f.len() as u32).collect()),
            cell: Self::EVERYWHERE,
        }];
        // Far polygons are carried whole (see [`Focus`]).
        let uncut = !far.is_empty();
        while let Some(Work {
            ids,
            slot,
            focus: near,
            cell,
        }) = work.pop()
        {
            let index = tree.nodes.len() as u32;
            let near = match (focus, near) {
                (Some(boxes), Some(near)) => {
                    // Keep only the focus boxes that reach the cell's polygons that are not
                    // far (a far one's box misses them all): none where every polygon is far.
                    let near: Vec<u32> = if uncut {
                        let mut content = Aabb::EMPTY;
                        for &i in &ids {
                            if !arena.is_far(i) {
                                content = content.union(&arena.boxes[i as usize]);
                            }
                        }
                        if content.is_empty() {
                            Vec::new()
                        } else {
                            near.into_iter()
                                .filter(|&i| boxes[i as usize].overlaps(&content, margin))
                                .collect()
                        }
                    } else {
                        let content = arena.bbox_of(&ids);
                        near.into_iter()
                            .filter(|&i| boxes[i as usize].overlaps(&content, margin))
                            .collect()
                    };
                    if near.is_empty() {
                        let content = if uncut {
                            arena.bbox_in(&ids, &cell, eps)
                        } else {
                            arena.bbox_of(&ids)
                        };
                        // The polygons the cell's pieces were cut from, each once.
                        let mut origins = ids;
                        for id in &mut origins {
                            *id = arena.origin(*id);
                        }
                        origins.sort_unstable();
                        origins.dedup();
                        let start = tree.stub_polygons.len();
                        tree.stub_polygons.extend_from_slice(&origins);
                        let end = tree.stub_polygons.len();
                        tree.nodes
                            .push(Node::stub(content, start as u32, end as u32));
                        tree.attach(slot, index);
                        continue;
                    }
                    Some(near)
                }
                _ => None,
            };
            // Where far polygons are carried uncut, the plane is placed by the others alone:
            // first around them, where many far polygons lie beyond their box.
            let plane = if uncut {
                let mut placing = std::mem::take(&mut scratch.near_ids);
                placing.clear();
                placing.extend(ids.iter().copied().filter(|&i| !arena.is_far(i)));
                let plane = wrap_plane(&ids, &placing, &arena, eps).or_else(|| {
                    (placing.len() > CELL_POLYGONS)
                        .then(|| cell_plane(&placing, &arena, eps, &mut scratch.keys))
                        .flatten()
                });
                scratch.near_ids = placing;
                plane
            } else if ids.len() > CELL_POLYGONS {
                cell_plane(&ids, &arena, eps, &mut scratch.keys)
            } else {
                None
            };
            let (node, front, back) = match plane {
                Some(plane) => {
                    let (front, back) = split_cell(ids, &plane, eps, &mut arena, uncut);
                    (Node::cell(plane), front, back)
                }
                None => tree.face_node(ids, eps, &mut arena, &mut scratch, uncut),
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
            if !front.is_empty() {
                work.push(Work {
                    ids: front,
                    slot: Slot::Front(index),
                    focus: near.clone(),
                    cell: front_cell,
                });
            }
            if !back.is_empty() {
                work.push(Work {
                    ids: back,
                    slot: Slot::Back(index),
                    focus: near,
                    cell: back_cell,
                });
            }
        }
        tree.fill_content();
        tree
    }

    fn attach(&mut self, slot: Slot, index: u32) {
        match slot {
            Slot::Root => self.root = Link::Node(index),
            Slot::Front(p) => self.nodes[p as usize].front = Link::Node(index),
            Slot::Back(p) => self.nodes[p as usize].back = Link::Node(index),
        }
    }

    /// A csg.js node: the chosen splitter's plane keeps the polygons coplanar with it; the rest
    /// go front or back, split where they span it. Empty sides stay leaves: outside in front,
    /// inside behind. The splitter's choice already classified every polygon against its plane;
    /// only those it could not settle (see [`Class`]) are handed to [`Polygon::split`].
    fn face_node(
        &mut self,
        ids: Vec<u32>,
        eps: f64,
        arena: &mut Arena,
        scratch: &mut Scratch,
        uncut: bool,
    ) -> (Node, Vec<u32>, Vec<u32>) {
        let (mut front, mut back) = (Vec::with_capacity(ids.len()), Vec::with_capacity(ids.len()));
        let mut far = Vec::new();
        let ids = if uncut && ids.iter().any(|&i| arena.is_far(i)) {
            let (near, f): (Vec<u32>, Vec<u32>) = ids.into_iter().partition(|&i| !arena.is_far(i));
            far = f;
            near
        } else {
            ids
        };
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
                front.push(id);
            }
            if behind || !ahead {
                back.push(id);
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
                Split::Front => front.push(id),
                Split::Back => back.push(id),
                Split::Spanning { front: f, back: b } => {
                    front.push(arena.push(f, id));
                    back.push(arena.push(b, id));
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

/// An axis-aligned plane through a gap between polygon centroids near their median, on the
/// longest axis that has one. The gap is wider than four tolerances, so no polygon lies in the
/// plane and both sides keep a polygon whose centroid, hence some vertex, is clearly on it.
/// `None` when no axis has such a gap, the plane would cut too many polygons, or one side would
/// get no polygon whole.
fn cell_plane(ids: &[u32], arena: &Arena, eps: f64, keys: &mut Vec<i64>) -> Option<Plane> {
    let size = Aabb::from_points(ids.iter().map(|&i| &arena.centroids[i as usize])).size();
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&a, &b| size[b].total_cmp(&size[a]));
    let n = ids.len();
    for axis in axes {
        if size[axis] <= 4.0 * eps {
            break;
        }
        keys.clear();
        keys.extend(
            ids.iter()
                .map(|&i| order_key(arena.centroids[i as usize][axis])),
        );
        let Some(at) = gap_near_median(keys, 4.0 * eps) else {
            continue;
        };
        let (mut spanning, mut whole_front, mut whole_back) = (0usize, 0usize, 0usize);
        for &i in ids {
            let b = &arena.boxes[i as usize];
            if b.min[axis] > at + eps {
                whole_front += 1;
            } else if b.max[axis] < at - eps {
                whole_back += 1;
            } else if b.min[axis] < at - eps && b.max[axis] > at + eps {
                spanning += 1;
            }
        }
        // Each side must lose a polygon: a plane that only cuts pieces off the polygons it
        // spans would be followed by another half as far away, and so on (polygons in z = 2
        // beside walls rising from it drew planes at 2 + 2⁻¹, 2 + 2⁻², … 2 + 2⁻³⁶, slivers
        // thinner than the weld that moved vertices off their grid).
        if spanning * 2 <= n && whole_front > 0 && whole_back > 0 {
            let mut normal = DVec3::ZERO;
            normal[axis] = 1.0;
            return Some(Plane::through(normal * at, normal));
        }
    }
    None
}

/// A cell plane midway across the gap between the box of a cell's polygons that are not far
/// (`near`) and the far polygons wholly beyond it, on the side where those are most, if they
/// are at least half the cell's: that side then holds far polygons only and is left unbuilt
/// at once. Two tolerances outside the box, it cut clipped fragments into slivers (grid boxes'
/// vertices left the grid by 4.5e-12, a union of 1,000 of them came out open). Planes placed by the
/// near polygons' centroids alone always keep near polygons on both sides, so without this
/// the far polygons of a sphere (31 k of 32 k quads) rode down every level (its boolean took
/// 558 M instructions instead of 367 M). At a quarter of the cell's, fandisk's difference
/// came out cut so that `to_mesh` needed its wider welds (93 → 672 M).
fn wrap_plane(ids: &[u32], near: &[u32], arena: &Arena, eps: f64) -> Option<Plane> {
    // The plane needs at least half the cell's polygons far and beyond the near box.
    if near.is_empty() || 2 * (ids.len() - near.len()) < ids.len() {
        return None;
    }
    let bbox = arena.bbox_of(near);
    // Far polygons wholly beyond the near ones' box by more than four tolerances, counted per
    // side, with the nearest such coordinate.
    let (low, high) = (bbox.min - 4.0 * eps, bbox.max + 4.0 * eps);
    let (mut below, mut above) = ([0usize; 3], [0usize; 3]);
    let (mut below_at, mut above_at) = (bbox.min - 4.0 * eps, bbox.max + 4.0 * eps);
    let (mut below_edge, mut above_edge) = ([f64::NEG_INFINITY; 3], [f64::INFINITY; 3]);
    for &i in ids {
        if !arena.is_far(i) {
            continue;
        }
        let b = &arena.boxes[i as usize];
        for axis in 0..3 {
            if b.max[axis] < low[axis] {
                below[axis] += 1;
                below_edge[axis] = below_edge[axis].max(b.max[axis]);
            }
            if b.min[axis] > high[axis] {
                above[axis] += 1;
                above_edge[axis] = above_edge[axis].min(b.min[axis]);
            }
        }
    }
    // The plane lies midway across the gap, as a cell plane does: more than two tolerances
    // from the near polygons and from the far ones it leaves wholly to one side.
    for axis in 0..3 {
        below_at[axis] = 0.5 * (bbox.min[axis] + below_edge[axis]);
        above_at[axis] = 0.5 * (bbox.max[axis] + above_edge[axis]);
    }
    let mut best = (0usize, 0usize, 0.0f64);
    for axis in 0..3 {
        if below[axis] > best.0 {
            best = (below[axis], axis, below_at[axis]);
        }
        if above[axis] > best.0 {
            best = (above[axis], axis, above_at[axis]);
        }
    }
    let (count, axis, at) = best;
    (count > 0 && 2 * count >= ids.len()).then(|| {
        let mut normal = DVec3::ZERO;
        normal[axis] = 1.0;
        Plane::through(normal * at, normal)
    })
}

/// An integer that orders as [`f64::total_cmp`] orders `x`: selecting on these is a plain
/// integer comparison where `total_cmp` is several instructions (the median's selection was a
/// third of the cell plane's cost).
#[inline]
fn order_key(x: f64) -> i64 {
    let bits = x.to_bits() as i64;
    bits ^ (((bits >> 63) as u64) >> 1) as i64
}

/// The value whose [`order_key`] is `key` (the map is its own inverse).
#[inline]
fn from_key(key: i64) -> f64 {
    f64::from_bits((key ^ (((key >> 63) as u64) >> 1) as i64) as u64)
}

/// The midpoint of a gap wider than `min_gap` next to the median of the values whose
/// [`order_key`]s are `keys` (reordered), in linear time; where the median value repeats, the
/// gap nearest the middle of the sorted values within the middle half.
fn gap_near_median(keys: &mut [i64], min_gap: f64) -> Option<f64> {
    let n = keys.len();
    let mid = n / 2;
    let (below, &mut median, above) = keys.select_nth_unstable(mid);
    let median = from_key(median);
    let lower = below
        .iter()
        .max()
        .map_or(f64::NEG_INFINITY, |&k| from_key(k));
    if median - lower > min_gap && lower.is_finite() {
        return Some(0.5 * (lower + median));
    }
    let upper = above.iter().min().map_or(f64::INFINITY, |&k| from_key(k));
    if upper - median > min_gap && upper.is_finite() {
        return Some(0.5 * (median + upper));
    }
    keys.sort_unstable();
    for k in 0..=n / 4 {
        for i in [mid + k, mid.wrapping_sub(k)] {
            if i >= 1 && i < n && from_key(keys[i]) - from_key(keys[i - 1]) > min_gap {
                let (a, b) = (from_key(keys[i - 1]), from_key(keys[i]));
                return Some(0.5 * (a + b));
            }
        }
    }
    None
}

/// Splits a cell's polygons by its axis plane. No polygon is coplanar with it (see
/// [`cell_plane`]); one that is anyway, within tolerance, goes the way its normal points.
///
/// Where far polygons are carried `uncut` (see [`Focus`]), one goes whole to each side its box
/// reaches beyond the tolerance (both, where it lies within it).
fn split_cell(
    ids: Vec<u32>,
    plane: &Plane,
    eps: f64,
    arena: &mut Arena,
    uncut: bool,
) -> (Vec<u32>, Vec<u32>) {
    let axis = plane.normal.abs().max_position();
    let at = plane.offset;
    // Either side may take every polygon (and pieces of the spanning ones): no regrowing.
    let (mut front, mut back) = (Vec::with_capacity(ids.len()), Vec::with_capacity(ids.len()));
    for id in ids {
        let b = &arena.boxes[id as usize];
        if uncut && arena.is_far(id) {
            if b.max[axis] > at + eps || b.min[axis] >= at - eps {
                front.push(id);
            }
            if b.min[axis] < at - eps || b.max[axis] <= at + eps {
                back.push(id);
            }
            continue;
        }
        let given = arena.given(id);
        match axis_split(arena.poly(id), b, given, plane, axis, eps) {
            Split::Front => front.push(id),
            Split::Back => back.push(id),
            Split::Coplanar if arena.poly(id).plane().normal.dot(plane.normal) > 0.0 => {
                front.push(id)
            }
            Split::Coplanar => back.push(id),
            Split::Spanning { front: f, back: b } => {
                front.push(arena.push(f, id));
                back.push(arena.push(b, id));
            }
        }
    }
    (front, back)
}

/// [`Polygon::split_as`] by an axis-aligned plane (normal `+axis`), settled from the box where
/// it lies to one side; `given` as [`Arena::given`] says.
fn axis_split(
    poly: &Polygon,
    b: &Aabb,
    given: bool,
    plane: &Plane,
    axis: usize,
    eps: f64,
) -> Split {
    let at = plane.offset;
    // The box settles most polygons without looking at their vertices.
    if b.min[axis] >= at - eps && b.max[axis] > at + eps {
        return Split::Front;
    }
    if b.max[axis] <= at + eps && b.min[axis] < at - eps {
        return Split::Back;
    }
    // A strict span with no vertex near the plane takes the quick axis cut.
    let quick = (b.min[axis] < at - eps && b.max[axis] > at + eps)
        .then(|| poly.split_axis(plane, axis, eps))
        .flatten();
    quick.unwrap_or_else(|| poly.split_as(plane, eps, given.then_some(&[][..])))
}

/// The axis of an axis-aligned plane with normal `+axis` (a cell's), or `None`.
fn axis_of(plane: &Plane) -> Option<usize> {
    let axis = plane.normal.abs().max_position();
    (plane.normal[axis] == 1.0).then_some(axis)
}

/// A polygon against a candidate splitter's plane, from [`Polygon::side_near`]: what
/// [`Polygon::split`] would say without cutting, where that is settled (`*Near`: a vertex
/// within `eps`, the rest beyond it on one side, which the build takes as it is even where
/// `split` would judge that vertex by the band of nearly parallel planes; see
/// [`Tree::face_node`]); `Unsettled` is left to `split`.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Class {
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

    #[test]
    fn gap_next_to_the_median() {
        let keys = |v: &[f64]| v.iter().map(|&x| order_key(x)).collect::<Vec<_>>();
        let mut v = keys(&[5.0, 1.0, 3.0, 3.0, 3.0, 2.0, 4.0]);
        assert_eq!(gap_near_median(&mut v, 0.5), Some(2.5));
        let mut same = keys(&[1.0; 8]);
        assert_eq!(gap_near_median(&mut same, 0.5), None);
        let mut negative = keys(&[-4.0, -0.0, 0.0, -1.0, 3.0, -2.0]);
        assert_eq!(gap_near_median(&mut negative, 0.5), Some(-0.5));
    }

    /// Keys order as `total_cmp` does and map back to the same bits.
    #[test]
    fn order_keys_follow_total_cmp() {
        let v = [
            f64::NEG_INFINITY,
            -1e300,
            -1.5,
            -f64::MIN_POSITIVE / 4.0,
            -0.0,
            0.0,
            f64::MIN_POSITIVE / 4.0,
            2.0,
            1e300,
            f64::INFINITY,
        ];
        for a in v {
            assert_eq!(from_key(order_key(a)).to_bits(), a.to_bits());
            for b in v {
                assert_eq!(order_key(a).cmp(&order_key(b)), a.total_cmp(&b), "{a} {b}");
            }
        }
    }
}
