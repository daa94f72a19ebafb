//! The BSP tree of a solid: an arena of nodes with `u32` links, built and walked with explicit
//! work stacks, so no pass recurses and no input can overflow the stack.
//!
//! # Shape
//!
//! csg.js takes the first polygon as splitter, which turns a convex solid into a chain of
//! depth *n*. Here the tree has two kinds of node:
//!
//! * **Cell nodes** split space by an axis-aligned plane that carries no polygon. While a cell
//!   holds many polygons, it is cut at a gap between polygon centroids near their median, so
//!   both halves keep polygons and no polygon lies in the plane. The tree stays `O(log n)` deep
//!   over the bulk of the surface.
//! * **Face nodes** are csg.js nodes: the plane of a chosen polygon, the polygons coplanar
//!   with it, and front/back links. A missing front child is an *outside* leaf and a missing
//!   back child an *inside* leaf, exactly as in csg.js.
//!
//! Every leaf's label is right because every cell that ends in a leaf was produced by a face
//! split whose polygon bounds it; cell splits never leave a side without polygons.
//!
//! Each node also records the box of all polygons below it. A fragment whose box misses that
//! box lies in one region of the node's cell and is classified whole by locating one point.

mod build;
mod clip;
mod meter;
mod surface;

pub(crate) use build::{FOCUS_MARGIN, Focus};
pub(crate) use clip::Coplanar;
pub(crate) use meter::Meter;
pub(crate) use surface::{Surface, SurfaceIndex};

use crate::geom::{Aabb, Plane};
use crate::polygon::Polygon;

/// Inside or outside the solid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Label {
    Inside,
    Outside,
}

impl Label {
    /// The other label.
    pub(crate) fn flipped(self) -> Label {
        match self {
            Label::Inside => Label::Outside,
            Label::Outside => Label::Inside,
        }
    }
}

/// A child link: another node or a labelled leaf.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Link {
    Node(u32),
    Leaf(Label),
}

#[derive(Clone, Debug)]
pub(crate) enum Kind {
    /// An axis-aligned plane that carries no polygon.
    Cell,
    /// The plane of the polygons `tree.polygons[start..end]`, all coplanar with it.
    Face { start: u32, end: u32 },
    /// A region left unbuilt because nothing to be clipped comes near its polygons (see
    /// [`Tree::build_focused`] and `Focus`: fragments may still reach it, away from its
    /// polygons, and are labelled whole from a point); `content` still bounds its polygons
    /// within it, and `tree.stub_polygons[start..end]` lists the solid's polygons with a piece
    /// in it (far polygons, carried whole, wherever they may reach it). Plane and links are
    /// unused.
    Stub { start: u32, end: u32 },
}

#[derive(Clone, Debug)]
pub(crate) struct Node {
    pub plane: Plane,
    pub kind: Kind,
    pub front: Link,
    pub back: Link,
    /// The box of every polygon stored in this node and below it.
    pub content: Aabb,
    /// The box of the polygons stored in this node (empty for cell nodes).
    pub own: Aabb,
}

/// A BSP tree over the polygons of one solid.
#[derive(Clone, Debug)]
pub(crate) struct Tree {
    pub nodes: Vec<Node>,
    /// The polygons of the face nodes, each node's in one contiguous run.
    pub polygons: Vec<Polygon>,
    /// Per unbuilt cell, the indices (into the solid's polygons the tree was built from) of
    /// the polygons with a piece in it, each cell's in one contiguous run.
    pub stub_polygons: Vec<u32>,
    pub root: Link,
    pub eps: f64,
}

impl Tree {
    /// The label of the region holding `p`, starting at `link`, or `Err` with the node index
    /// where the walk ends in an unbuilt cell. Meant for points away from the polygons below
    /// `link`; a point on a plane that carries no polygon nearby sees the same label on both
    /// sides.
    pub fn locate(&self, mut link: Link, p: glam::DVec3) -> Result<Label, u32> {
        loop {
            match link {
                Link::Leaf(label) => return Ok(label),
                Link::Node(i) => {
                    let node = &self.nodes[i as usize];
                    if matches!(node.kind, Kind::Stub { .. }) {
                        return Err(i);
                    }
                    link = if node.plane.distance(p) >= 0.0 {
                        node.front
                    } else {
                        node.back
                    };
                }
            }
        }
    }

    /// [`Tree::locate`] from the root for a point farther than `bar` from every plane on its
    /// way: the unbuilt cell holding `p`, or `None` where the walk ends in a leaf or passes a
    /// plane within `bar` (it stops there). Any point nearer to `p` than `bar` then lies in the
    /// same cell.
    pub fn locate_clear(&self, p: glam::DVec3, bar: f64) -> Option<u32> {
        let mut link = self.root;
        loop {
            let Link::Node(i) = link else { return None };
            let node = &self.nodes[i as usize];
            if matches!(node.kind, Kind::Stub { .. }) {
                return Some(i);
            }
            let d = node.plane.distance(p);
            if d.abs() <= bar {
                return None;
            }
            link = if d >= 0.0 { node.front } else { node.back };
        }
    }

    /// The polygons with a piece in an unbuilt cell (see [`Kind::Stub`]).
    pub fn stub_polygons(&self, node: u32) -> &[u32] {
        match self.nodes[node as usize].kind {
            Kind::Stub { start, end } => &self.stub_polygons[start as usize..end as usize],
            Kind::Cell | Kind::Face { .. } => &[],
        }
    }

    /// True when a polygon stored at or below `link` has a box within `margin` of `bbox`.
    pub fn near_surface(&self, link: Link, bbox: &Aabb, margin: f64) -> bool {
        let mut stack: smallvec::SmallVec<[Link; 32]> = smallvec::smallvec![link];
        while let Some(link) = stack.pop() {
            let Link::Node(i) = link else { continue };
            let node = &self.nodes[i as usize];
            if !bbox.overlaps(&node.content, margin) {
                continue;
            }
            if matches!(node.kind, Kind::Stub { .. }) {
                return true;
            }
            if bbox.overlaps(&node.own, margin)
                && self
                    .face_polygons(node)
                    .iter()
                    .any(|p| bbox.overlaps(&p.bbox(), margin))
            {
                return true;
            }
            stack.push(node.front);
            stack.push(node.back);
        }
        false
    }

    /// The polygons stored at a face node (none for other nodes).
    pub fn face_polygons(&self, node: &Node) -> &[Polygon] {
        match node.kind {
            Kind::Face { start, end } => &self.polygons[start as usize..end as usize],
            Kind::Cell | Kind::Stub { .. } => &[],
        }
    }

    /// Depth of the deepest leaf.
    #[cfg(test)]
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = vec![(self.root, 0usize)];
        while let Some((link, d)) = stack.pop() {
            deepest = deepest.max(d);
            if let Link::Node(i) = link {
                let n = &self.nodes[i as usize];
                if matches!(n.kind, Kind::Stub { .. }) {
                    continue;
                }
                stack.push((n.front, d + 1));
                stack.push((n.back, d + 1));
            }
        }
        deepest
    }
}

impl Tree {
    /// Classifies a point: `Some(label)`, or `None` when it lies on the surface within the
    /// tolerance. Where the point lies within the tolerance of a plane both sides are explored,
    /// and a disagreement between them also means "on the surface".
    pub fn classify_point(&self, p: glam::DVec3) -> Option<Label> {
        let eps = self.eps;
        let (mut inside, mut outside) = (false, false);
        let mut stack = vec![self.root];
        while let Some(link) = stack.pop() {
            let i = match link {
                Link::Leaf(Label::Inside) => {
                    inside = true;
                    continue;
                }
                Link::Leaf(Label::Outside) => {
                    outside = true;
                    continue;
                }
                Link::Node(i) => i,
            };
            let node = &self.nodes[i as usize];
            let d = node.plane.distance(p);
            if d > eps {
                stack.push(node.front);
            } else if d < -eps {
                stack.push(node.back);
            } else {
                if self
                    .face_polygons(node)
                    .iter()
                    .any(|poly| poly.contains_coplanar_point(p, eps))
                {
                    return None;
                }
                stack.push(node.front);
                stack.push(node.back);
            }
        }
        match (inside, outside) {
            (true, false) => Some(Label::Inside),
            (false, true) => Some(Label::Outside),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::Split;
    use crate::solid::Solid;
    use glam::DVec3;

    /// csg.js's first-polygon splitter makes a convex solid a chain as deep as its polygon
    /// count; cell splits keep it logarithmic with a short face chain at the bottom.
    #[test]
    fn trees_of_convex_solids_stay_shallow() {
        let sphere = Solid::sphere(1.0, 128, 64).unwrap();
        let n = sphere.polygon_count();
        let tree = Tree::build(sphere.into_polygons(), 1e-12);
        assert!(tree.depth() < 64, "depth {} for {n} polygons", tree.depth());
    }

    /// A polygon thinner than the tolerance across a face node's plane, which crosses its own
    /// steeply (a wedge's end between two faces 1.4e-10 rad apart, 1.5e-13 wide), is stored at
    /// that node as coplanar and also passed to the side it lies on, so the subtree there is
    /// bounded by its plane. Stored at the node alone, the region beyond the sliver's end
    /// read as the sliver's inside, and a face of the other operand there was dropped.
    #[test]
    fn a_sliver_across_a_splitter_bounds_the_side_it_lies_on() {
        let eps = 1e-12;
        let floor = Polygon::new(
            &[
                DVec3::new(-1.0, -1.0, 0.0),
                DVec3::new(1.0, -1.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(-1.0, 1.0, 0.0),
            ],
            0,
        )
        .unwrap();
        // In the plane x = 0, at most 2e-13 above the floor.
        let sliver = Polygon::new(
            &[
                DVec3::new(0.0, -0.5, 0.0),
                DVec3::new(0.0, 0.5, 0.0),
                DVec3::new(0.0, 0.0, 2e-13),
            ],
            0,
        )
        .unwrap();
        assert!(matches!(sliver.split(floor.plane(), eps), Split::Coplanar));
        let tree = Tree::build(vec![floor.clone(), sliver.clone()], eps);
        let Link::Node(root) = tree.root else {
            panic!("no node")
        };
        let root = &tree.nodes[root as usize];
        assert!(root.plane.is_same_or_flipped(floor.plane()));
        let Link::Node(front) = root.front else {
            panic!("nothing in front of the floor")
        };
        assert!(
            tree.nodes[front as usize]
                .plane
                .is_same_or_flipped(sliver.plane())
        );
        assert!(matches!(root.back, Link::Leaf(Label::Inside)));
    }

    /// A face nearly parallel to a splitter (crossing it at 1e-12 rad), within the tolerance
    /// of it but in front by the narrow band of nearly parallel planes, goes to the front: the
    /// wedge between the two planes is there. Its steep neighbour, sharing its corners 5e-13
    /// and 1e-12 in front but reaching far behind, goes behind by the tolerance; it also goes
    /// to the front, where its plane ends the wedge. Without it the region in front of the
    /// splitter and behind the face read inside wherever it reached, beyond the neighbour too.
    #[test]
    fn a_steep_face_ending_a_wedge_in_front_of_a_splitter_bounds_it_there() {
        let eps = 1e-12;
        let square = |z: f64| {
            Polygon::new(
                &[
                    DVec3::new(-1.0, -1.0, z),
                    DVec3::new(1.0, -1.0, z),
                    DVec3::new(1.0, 1.0, z),
                    DVec3::new(-1.0, 1.0, z),
                ],
                0,
            )
            .unwrap()
        };
        let floor = square(0.0);
        // 5e-13 … 1e-12 above the floor, rising along x.
        let lift = |x: f64| 5e-13 + 1e-12 * x;
        let (a, b) = (
            DVec3::new(0.0, 0.0, lift(0.0)),
            DVec3::new(0.5, 0.0, lift(0.5)),
        );
        let top = Polygon::new(
            &[
                a,
                b,
                DVec3::new(0.5, 0.5, lift(0.5)),
                DVec3::new(0.0, 0.5, lift(0.0)),
            ],
            0,
        )
        .unwrap();
        assert!(matches!(top.split(floor.plane(), eps), Split::Front));
        // Facing −y, from the top's edge down to z = −1.
        let side = Polygon::new(
            &[DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.5, 0.0, -1.0), b, a],
            0,
        )
        .unwrap();
        assert!(side.plane().normal.y < -0.99);
        let tree = Tree::build(vec![floor.clone(), top, side], eps);
        let Link::Node(root) = tree.root else {
            panic!("no node")
        };
        assert!(
            tree.nodes[root as usize]
                .plane
                .is_same_or_flipped(floor.plane())
        );
        // In the wedge, and beside it beyond the side face (outside).
        let wedge = DVec3::new(0.25, 0.25, 4e-13);
        let beside = DVec3::new(0.25, -0.5, 4e-13);
        assert_eq!(tree.locate(tree.root, wedge), Ok(Label::Inside));
        assert_eq!(tree.locate(tree.root, beside), Ok(Label::Outside));
    }

    /// Issue 12 item 6: a tree's build charges the corners of the pieces its splits cut to the
    /// boolean's meter, as clipping does, and stops past the meter's limit, so a boolean whose
    /// trees alone cut past its budget is refused before clipping with them (four copies of a
    /// 10,000-point wavy extrusion stopped at 1.0 GB, not 3.1 GB). With room, the tree is the
    /// one an unmetered build makes.
    #[test]
    fn a_tree_build_charges_its_cut_pieces_and_stops_past_its_meter() {
        let polygons = Solid::sphere(1.0, 128, 64).unwrap().into_polygons();
        let whole = Tree::build_focused(&polygons, 1e-12, None, None);
        let roomy = Meter::new(u64::MAX);
        let metered = Tree::build_focused(&polygons, 1e-12, None, Some(&roomy));
        assert_eq!(metered.nodes.len(), whole.nodes.len());
        assert_eq!(metered.polygons.len(), whole.polygons.len());
        // Cell splits cut about two pieces per polygon here, each of three or four corners.
        let per_polygon = roomy.used() as f64 / polygons.len() as f64;
        assert!(
            per_polygon > 1.0 && per_polygon < 32.0,
            "{} corners for {} polygons",
            roomy.used(),
            polygons.len()
        );
        let limit = roomy.used() / 4;
        let tight = Meter::new(limit);
        let stopped = Tree::build_focused(&polygons, 1e-12, None, Some(&tight));
        assert!(tight.exceeded());
        assert!(
            tight.used() < limit + 2 * meter::CHARGE_EVERY,
            "{}",
            tight.used()
        );
        assert!(stopped.nodes.len() < whole.nodes.len() / 2);
    }
}
