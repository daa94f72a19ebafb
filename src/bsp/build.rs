//! Building the tree: cell splits while a cell holds many polygons, face splits below.

use glam::DVec3;

use super::{Kind, Label, Link, Node, Tree};
use crate::geom::{Aabb, Plane, Side};
use crate::polygon::{Polygon, Split};

/// Cells holding more polygons than this are cut by an axis-aligned plane when a good one exists.
const CELL_POLYGONS: usize = 12;
/// How many polygons a face split tries as splitter.
const SPLITTER_CANDIDATES: usize = 5;

/// Where a finished node is linked in.
#[derive(Clone, Copy)]
enum Slot {
    Root,
    Front(u32),
    Back(u32),
}

impl Tree {
    /// Builds the tree of a closed solid's polygons with plane-side tolerance `eps`.
    pub fn build(polygons: Vec<Polygon>, eps: f64) -> Tree {
        let mut tree = Tree {
            nodes: Vec::with_capacity(polygons.len()),
            polygons: Vec::with_capacity(polygons.len()),
            root: Link::Leaf(Label::Outside),
            eps,
        };
        if polygons.is_empty() {
            return tree;
        }
        let mut work = vec![(polygons, Slot::Root)];
        while let Some((polys, slot)) = work.pop() {
            let index = tree.nodes.len() as u32;
            let cell = if polys.len() > CELL_POLYGONS {
                cell_plane(&polys, eps)
            } else {
                None
            };
            let (node, front, back) = match cell {
                Some(plane) => {
                    let (front, back) = split_cell(polys, &plane, eps);
                    let node = Node {
                        plane,
                        kind: Kind::Cell,
                        front: Link::Leaf(Label::Outside),
                        back: Link::Leaf(Label::Inside),
                        content: Aabb::EMPTY,
                        own: Aabb::EMPTY,
                    };
                    (node, front, back)
                }
                None => tree.face_node(polys, eps),
            };
            tree.nodes.push(node);
            tree.attach(slot, index);
            if !front.is_empty() {
                work.push((front, Slot::Front(index)));
            }
            if !back.is_empty() {
                work.push((back, Slot::Back(index)));
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
    /// inside behind.
    fn face_node(&mut self, polys: Vec<Polygon>, eps: f64) -> (Node, Vec<Polygon>, Vec<Polygon>) {
        let plane = *polys[choose_splitter(&polys, eps)].plane();
        let start = self.polygons.len() as u32;
        let mut content = Aabb::EMPTY;
        let (mut front, mut back) = (Vec::new(), Vec::new());
        for p in polys {
            match p.split(&plane, eps) {
                Split::Coplanar => {
                    content = content.union(&p.bbox());
                    self.polygons.push(p);
                }
                Split::Front => front.push(p),
                Split::Back => back.push(p),
                Split::Spanning { front: f, back: b } => {
                    front.push(f);
                    back.push(b);
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
            content,
            own: content,
        };
        (node, front, back)
    }

    /// Each node's content box grows by its children's; children come after their parents.
    fn fill_content(&mut self) {
        for i in (0..self.nodes.len()).rev() {
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

/// An axis-aligned plane through a gap between polygon centroids near their median, on the
/// longest axis that has one. The gap is wider than four tolerances, so no polygon lies in the
/// plane and both sides keep a polygon whose centroid, hence some vertex, is clearly on it.
/// `None` when no axis has such a gap or the plane would cut too many polygons.
fn cell_plane(polys: &[Polygon], eps: f64) -> Option<Plane> {
    let centroids: Vec<DVec3> = polys.iter().map(Polygon::centroid).collect();
    let size = Aabb::from_points(&centroids).size();
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&a, &b| size[b].total_cmp(&size[a]));
    let n = centroids.len();
    let mut values: Vec<f64> = Vec::with_capacity(n);
    for axis in axes {
        if size[axis] <= 4.0 * eps {
            break;
        }
        values.clear();
        values.extend(centroids.iter().map(|c| c[axis]));
        values.sort_unstable_by(f64::total_cmp);
        let Some(at) = gap_near_median(&values, 4.0 * eps) else {
            continue;
        };
        let mut normal = DVec3::ZERO;
        normal[axis] = 1.0;
        let plane = Plane { normal, offset: at };
        let spanning = polys
            .iter()
            .filter(|p| {
                let (lo, hi) = extent(p, axis);
                lo < at - eps && hi > at + eps
            })
            .count();
        if spanning * 2 <= n {
            return Some(plane);
        }
    }
    None
}

/// The midpoint of the gap wider than `min_gap` nearest the middle of sorted `values`, looking
/// no further than the middle half.
fn gap_near_median(values: &[f64], min_gap: f64) -> Option<f64> {
    let n = values.len();
    let mid = n / 2;
    for k in 0..=n / 4 {
        for i in [mid + k, mid.wrapping_sub(k)] {
            if i >= 1 && i < n && values[i] - values[i - 1] > min_gap {
                return Some(0.5 * (values[i - 1] + values[i]));
            }
        }
    }
    None
}

fn extent(p: &Polygon, axis: usize) -> (f64, f64) {
    p.vertices()
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v[axis]), hi.max(v[axis]))
        })
}

/// Splits a cell's polygons by its axis plane. No polygon is coplanar with it (see
/// [`cell_plane`]); one that is anyway, within tolerance, goes the way its normal points.
fn split_cell(polys: Vec<Polygon>, plane: &Plane, eps: f64) -> (Vec<Polygon>, Vec<Polygon>) {
    let (mut front, mut back) = (Vec::new(), Vec::new());
    for p in polys {
        match p.split(plane, eps) {
            Split::Front => front.push(p),
            Split::Back => back.push(p),
            Split::Coplanar if p.plane().normal.dot(plane.normal) > 0.0 => front.push(p),
            Split::Coplanar => back.push(p),
            Split::Spanning { front: f, back: b } => {
                front.push(f);
                back.push(b);
            }
        }
    }
    (front, back)
}

/// The splitter for a face node: of a few evenly spaced candidates, the one that cuts the fewest
/// polygons, then leaves the sides most even.
fn choose_splitter(polys: &[Polygon], eps: f64) -> usize {
    let n = polys.len();
    if n <= 2 {
        return 0;
    }
    let step = n.div_ceil(SPLITTER_CANDIDATES).max(1);
    let mut best = (usize::MAX, usize::MAX, 0);
    for c in (0..n).step_by(step) {
        let plane = polys[c].plane();
        let (mut front, mut back, mut spanning) = (0usize, 0usize, 0usize);
        for p in polys {
            match p.side(plane, eps) {
                Side::Front => front += 1,
                Side::Back => back += 1,
                Side::Spanning => spanning += 1,
                Side::Coplanar => {}
            }
        }
        let score = (spanning, front.abs_diff(back), c);
        if (score.0, score.1) < (best.0, best.1) {
            best = score;
        }
    }
    best.2
}
