//! The 2D BSP tree of a sketch's edges: each knife node is the line of an edge, its normal
//! pointing out of the region; a missing front child is an *outside* leaf, a missing back child
//! an *inside* leaf, as in the 3D kernel.
//!
//! While a cell holds many edges it is first cut by an axis-aligned line that carries no edge,
//! at a gap between edge midpoints near their median, so the tree stays `O(log n)` deep over
//! the bulk of the boundary; knife nodes take over below. Every leaf's label is right because
//! every leaf cell is bounded by the knife edge whose split made it, and cell lines never leave
//! a side without edges.
//!
//! Each node records the box of the edges below it, so a query edge far from all of them is
//! classified whole by locating one point.

use glam::DVec2;

use crate::geom::Aabb;

/// Cells holding more edges than this are cut by an axis-aligned line when a good one exists.
const CELL_EDGES: usize = 12;
/// How many edges a knife node tries as splitter.
const SPLITTER_CANDIDATES: usize = 5;

/// Inside or outside the region.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Label {
    Inside,
    Outside,
}

/// A child link: another node or a labelled leaf.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Link {
    Node(u32),
    Leaf(Label),
}

/// An oriented line: `distance(p) > 0` in front (outside the edge's region), `< 0` behind.
#[derive(Clone, Copy, Debug)]
pub(super) struct Line {
    /// A point on the line near the edge it came from, so distances stay precise there.
    pub anchor: DVec2,
    /// Unit normal, pointing to the front.
    pub normal: DVec2,
    /// For axis-aligned cell lines: the axis (0 = x, 1 = y), so cuts land exactly on them.
    pub axis: Option<usize>,
}

impl Line {
    /// The line of the directed edge `a → b`, normal to its right (out of a region on its left).
    /// `None` for a zero-length edge.
    pub fn of_edge(a: DVec2, b: DVec2) -> Option<Line> {
        let d = b - a;
        let normal = DVec2::new(d.y, -d.x).try_normalize()?;
        Some(Line {
            anchor: (a + b) * 0.5,
            normal,
            axis: None,
        })
    }

    fn axis_aligned(axis: usize, value: f64) -> Line {
        let mut anchor = DVec2::ZERO;
        anchor[axis] = value;
        let mut normal = DVec2::ZERO;
        normal[axis] = 1.0;
        Line {
            anchor,
            normal,
            axis: Some(axis),
        }
    }

    #[inline]
    pub fn distance(&self, p: DVec2) -> f64 {
        match self.axis {
            Some(k) => p[k] - self.anchor[k],
            None => self.normal.dot(p - self.anchor),
        }
    }
}

/// A piece of an input edge: its end points, their parameters along the edge, and the edge's
/// index. Cuts are computed from the whole edge, so they stay on it however often it is cut.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frag {
    pub a: DVec2,
    pub b: DVec2,
    pub ta: f64,
    pub tb: f64,
    pub edge: u32,
}

impl Frag {
    /// The part of edge `edge` (`a → b`) inside `bbox`, if any (Liang–Barsky clipping).
    pub fn clipped(edge: u32, [a, b]: [DVec2; 2], bbox: &Aabb) -> Option<Frag> {
        let d = b - a;
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for k in 0..2 {
            let (lo, hi) = (bbox.min[k], bbox.max[k]);
            if d[k] == 0.0 {
                if a[k] < lo || a[k] > hi {
                    return None;
                }
                continue;
            }
            let (mut u, mut v) = ((lo - a[k]) / d[k], (hi - a[k]) / d[k]);
            if u > v {
                std::mem::swap(&mut u, &mut v);
            }
            t0 = t0.max(u);
            t1 = t1.min(v);
        }
        if t0 > t1 {
            return None;
        }
        let at = |t: f64| {
            if t == 0.0 {
                a
            } else if t == 1.0 {
                b
            } else {
                a + d * t
            }
        };
        Some(Frag {
            a: at(t0),
            b: at(t1),
            ta: t0,
            tb: t1,
            edge,
        })
    }

    pub fn whole(edge: u32, [a, b]: [DVec2; 2]) -> Frag {
        Frag {
            a,
            b,
            ta: 0.0,
            tb: 1.0,
            edge,
        }
    }

    pub fn bbox(&self) -> Aabb {
        Aabb::new(
            self.a.min(self.b).extend(0.0),
            self.a.max(self.b).extend(0.0),
        )
    }

    /// The two pieces of a fragment whose ends lie on opposite sides of `line` (distances `da`,
    /// `db`), in front first. `edges` holds the end points of the whole edges.
    pub fn cut(&self, line: &Line, da: f64, db: f64, edges: &[[DVec2; 2]]) -> (Frag, Frag) {
        let [e0, e1] = edges[self.edge as usize];
        let (d0, d1) = (line.distance(e0), line.distance(e1));
        let t = if d0 != d1 {
            (d0 / (d0 - d1)).clamp(self.ta.min(self.tb), self.ta.max(self.tb))
        } else {
            0.5 * (self.ta + self.tb)
        };
        let mut p = e0 + (e1 - e0) * t;
        if let Some(k) = line.axis {
            p[k] = line.anchor[k];
        }
        let first = Frag {
            a: self.a,
            b: p,
            ta: self.ta,
            tb: t,
            edge: self.edge,
        };
        let second = Frag {
            a: p,
            b: self.b,
            ta: t,
            tb: self.tb,
            edge: self.edge,
        };
        if da > 0.0 || db < 0.0 {
            (first, second)
        } else {
            (second, first)
        }
    }
}

/// Where a fragment lies relative to a line.
pub(super) enum Side {
    Front,
    Back,
    On,
    Spanning(f64, f64),
}

pub(super) fn side(line: &Line, f: &Frag, eps: f64) -> Side {
    let (da, db) = (line.distance(f.a), line.distance(f.b));
    let front = da > eps || db > eps;
    let back = da < -eps || db < -eps;
    match (front, back) {
        (false, false) => Side::On,
        (true, false) => Side::Front,
        (false, true) => Side::Back,
        (true, true) => Side::Spanning(da, db),
    }
}

#[derive(Clone, Debug)]
pub(super) struct Node {
    pub line: Line,
    /// True for a knife (the line of edges stored here), false for an axis-aligned cell line.
    pub knife: bool,
    pub front: Link,
    pub back: Link,
    /// The box of every edge stored at or below this node.
    pub content: Aabb,
}

/// The BSP tree of one sketch's edges.
#[derive(Clone, Debug)]
pub(super) struct KnifeTree {
    pub nodes: Vec<Node>,
    pub root: Link,
}

#[derive(Clone, Copy)]
enum Slot {
    Root,
    Front(u32),
    Back(u32),
}

impl KnifeTree {
    /// Builds the tree of the pieces `frags` of a valid region's directed `edges`. Where the
    /// pieces are the edges clipped to a box, the tree labels every point of that box right:
    /// a leaf cell's part inside the box holds no boundary and borders the knife piece that
    /// made it. With no pieces at all the whole box has one label, `empty`.
    pub fn build_from(
        edges: &[[DVec2; 2]],
        mut frags: Vec<Frag>,
        eps: f64,
        empty: Label,
    ) -> KnifeTree {
        let mut tree = KnifeTree {
            nodes: Vec::new(),
            root: Link::Leaf(empty),
        };
        let mut own: Vec<Aabb> = Vec::new();
        let mut work: Vec<(Vec<u32>, Slot)> = vec![((0..frags.len() as u32).collect(), Slot::Root)];
        if frags.is_empty() {
            return tree;
        }
        while let Some((ids, slot)) = work.pop() {
            let index = tree.nodes.len() as u32;
            let cell = if ids.len() > CELL_EDGES {
                cell_line(&ids, &frags, eps)
            } else {
                None
            };
            let (line, knife) = match cell {
                Some(line) => (line, false),
                None => (choose_knife(&ids, &frags, edges, eps), true),
            };
            let mut stored = Aabb::EMPTY;
            let (mut front, mut back) = (Vec::new(), Vec::new());
            for id in ids {
                let f = frags[id as usize];
                match side(&line, &f, eps) {
                    Side::Front => front.push(id),
                    Side::Back => back.push(id),
                    // Only a knife's own edges lie on its line (cell lines pass between
                    // midpoints); they bound the cells on both sides and go no further.
                    Side::On if knife => stored = stored.union(&f.bbox()),
                    Side::On => front.push(id),
                    Side::Spanning(da, db) => {
                        let (pf, pb) = f.cut(&line, da, db, edges);
                        frags.push(pf);
                        front.push(frags.len() as u32 - 1);
                        frags.push(pb);
                        back.push(frags.len() as u32 - 1);
                    }
                }
            }
            tree.nodes.push(Node {
                line,
                knife,
                front: Link::Leaf(Label::Outside),
                back: Link::Leaf(Label::Inside),
                content: Aabb::EMPTY,
            });
            own.push(stored);
            match slot {
                Slot::Root => tree.root = Link::Node(index),
                Slot::Front(p) => tree.nodes[p as usize].front = Link::Node(index),
                Slot::Back(p) => tree.nodes[p as usize].back = Link::Node(index),
            }
            if !front.is_empty() {
                work.push((front, Slot::Front(index)));
            }
            if !back.is_empty() {
                work.push((back, Slot::Back(index)));
            }
        }
        // Content boxes: children come after their parents, so a reverse sweep sees them first.
        for i in (0..tree.nodes.len()).rev() {
            let mut b = own[i];
            for link in [tree.nodes[i].front, tree.nodes[i].back] {
                if let Link::Node(c) = link {
                    b = b.union(&tree.nodes[c as usize].content);
                }
            }
            tree.nodes[i].content = b;
        }
        tree
    }

    /// The label of the region holding `p`, walking down from `link`. Meant for points away
    /// from every edge below `link`.
    pub fn locate(&self, mut link: Link, p: DVec2) -> Label {
        loop {
            match link {
                Link::Leaf(label) => return label,
                Link::Node(i) => {
                    let node = &self.nodes[i as usize];
                    link = if node.line.distance(p) >= 0.0 {
                        node.front
                    } else {
                        node.back
                    };
                }
            }
        }
    }
}

/// An axis-aligned line across the cell's longest side, at a gap between edge midpoints near
/// their median, wider than the tolerance, so no edge lies on it and both sides keep edges.
fn cell_line(ids: &[u32], frags: &[Frag], eps: f64) -> Option<Line> {
    let mut b = Aabb::EMPTY;
    for &id in ids {
        b = b.union(&frags[id as usize].bbox());
    }
    let axis = if b.size().x >= b.size().y { 0 } else { 1 };
    let mut values: Vec<f64> = ids
        .iter()
        .map(|&id| {
            let f = &frags[id as usize];
            0.5 * (f.a[axis] + f.b[axis])
        })
        .collect();
    let n = values.len();
    let mid = n / 2;
    // Usually the median itself has a gap below it: a selection, not a sort, finds it.
    values.select_nth_unstable_by(mid, f64::total_cmp);
    let below = values[..mid]
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    if values[mid] - below > 4.0 * eps {
        return Some(Line::axis_aligned(axis, 0.5 * (below + values[mid])));
    }
    let above = values[mid + 1..]
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    if above - values[mid] > 4.0 * eps {
        return Some(Line::axis_aligned(axis, 0.5 * (values[mid] + above)));
    }
    values.sort_unstable_by(f64::total_cmp);
    // Look outward from the median over the middle half.
    for step in 0..n / 2 {
        for k in [mid + step, mid.wrapping_sub(step + 1)] {
            if k < n / 4 || k + 1 >= n - n / 4 || k + 1 >= n {
                continue;
            }
            if values[k + 1] - values[k] > 4.0 * eps {
                return Some(Line::axis_aligned(axis, 0.5 * (values[k] + values[k + 1])));
            }
        }
    }
    None
}

/// The knife among a few candidates that cuts the fewest edges and balances the sides best.
fn choose_knife(ids: &[u32], frags: &[Frag], edges: &[[DVec2; 2]], eps: f64) -> Line {
    let step = (ids.len() / SPLITTER_CANDIDATES).max(1);
    let mut best: Option<(usize, Line)> = None;
    for &cand in ids.iter().step_by(step).take(SPLITTER_CANDIDATES) {
        let f = frags[cand as usize];
        let [e0, e1] = edges[f.edge as usize];
        let Some(line) = Line::of_edge(e0, e1) else {
            continue;
        };
        let (mut front, mut back, mut spans) = (0usize, 0usize, 0usize);
        for &id in ids {
            match side(&line, &frags[id as usize], eps) {
                Side::Front => front += 1,
                Side::Back => back += 1,
                Side::On => {}
                Side::Spanning(..) => spans += 1,
            }
        }
        let score = 4 * spans + front.abs_diff(back);
        if best.as_ref().is_none_or(|(s, _)| score < *s) {
            best = Some((score, line));
        }
    }
    // Input edges have length (zero-length ones are dropped before), so a candidate exists.
    best.map(|(_, l)| l).unwrap_or(Line {
        anchor: DVec2::ZERO,
        normal: DVec2::X,
        axis: None,
    })
}
