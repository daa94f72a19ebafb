//! A bounding-volume hierarchy over boxes, for overlap queries and ray traversal: the tree and
//! its queries here, its building in [`build`].

mod build;

use glam::DVec3;

use super::Aabb;

const LEAF_ITEMS: usize = 4;

#[derive(Clone, Debug)]
struct Node {
    bbox: Aabb,
    /// Leaf: first item in `items`; inner: index of the second child (the first is next).
    start_or_right: u32,
    /// Items in a leaf; 0 for an inner node.
    count: u32,
    /// The group all items below share ([`Bvh::build_grouped`]), or [`NO_GROUP`].
    group: u32,
}

/// The group of an item in no group, and of a node whose items are in more than one.
pub(crate) const NO_GROUP: u32 = u32::MAX;

/// A BVH over item boxes (see [`Bvh::build`]).
/// Nodes are stored depth-first, so an inner node's first child follows it.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    items: Vec<u32>,
}

impl Bvh {
    /// The leaves: each one's box and its items.
    #[cfg(test)]
    pub fn leaves(&self) -> impl Iterator<Item = (&Aabb, &[u32])> + '_ {
        self.nodes.iter().filter(|n| n.count > 0).map(|n| {
            let s = n.start_or_right as usize;
            (&n.bbox, &self.items[s..s + n.count as usize])
        })
    }

    /// Calls `item` for each item in leaves whose boxes pass `enter`; stops when it returns true.
    pub fn visit(&self, enter: impl FnMut(&Aabb) -> bool, item: impl FnMut(u32) -> bool) {
        self.visit_skipping(|_| false, enter, item);
    }

    /// [`Bvh::visit`] passing over every subtree whose items are all in one group for which
    /// `skip` is true; items of such groups in mixed leaves are still given to `item`.
    pub fn visit_skipping(
        &self,
        skip: impl Fn(u32) -> bool,
        mut enter: impl FnMut(&Aabb) -> bool,
        mut item: impl FnMut(u32) -> bool,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        // Median splits halve every range, so the tree is under 32 levels deep for any `u32`
        // count of items, and the descent keeps at most one second child per level: a plain
        // array holds the stack (a `SmallVec`'s push and pop, with their check for a spilled
        // buffer, were a third of the walk of the check for crossing triangles).
        let mut stack = [0u32; 64];
        let mut depth = 0;
        let mut n = 0u32;
        loop {
            let node = &self.nodes[n as usize];
            if (node.group == NO_GROUP || !skip(node.group)) && enter(&node.bbox) {
                if node.count == 0 {
                    // The first child next, without the stack: the order of pushing both.
                    stack[depth] = node.start_or_right;
                    depth += 1;
                    n += 1;
                    continue;
                }
                let s = node.start_or_right as usize;
                for &i in &self.items[s..s + node.count as usize] {
                    if item(i) {
                        return;
                    }
                }
            }
            if depth == 0 {
                return;
            }
            depth -= 1;
            n = stack[depth];
        }
    }

    /// Inner nodes whose subtrees together hold every item once, split level by level until there
    /// are at least `count` of them or only leaves are left: independent pieces of work for
    /// [`Bvh::visit_pairs`] in parallel.
    pub fn cut(&self, count: usize) -> Vec<u32> {
        if self.nodes.is_empty() {
            return Vec::new();
        }
        let mut cut = vec![0u32];
        while cut.len() < count && cut.iter().any(|&n| self.nodes[n as usize].count == 0) {
            cut = cut
                .iter()
                .flat_map(|&n| {
                    let node = &self.nodes[n as usize];
                    if node.count > 0 {
                        [n, u32::MAX]
                    } else {
                        [n + 1, node.start_or_right]
                    }
                })
                .filter(|&n| n != u32::MAX)
                .collect();
        }
        cut
    }

    /// Calls `pair(i, j)` for every item `i` below node `from` of this tree (0 for all, or one
    /// of [`Bvh::cut`]) and item `j` of `other` whose boxes overlap (`boxes`: this tree's items'
    /// boxes, then `other`'s). One descent of both trees together: querying `other` once per
    /// item of this one enters the top of `other` again for every query (on the T-junction
    /// search, ~130 nodes per query for ~11 items found). Used by the tests; callers take a
    /// margin.
    #[cfg(test)]
    pub fn visit_pairs(
        &self,
        from: u32,
        other: &Bvh,
        boxes: (&[Aabb], &[Aabb]),
        pair: impl FnMut(u32, u32),
    ) {
        self.visit_pairs_within(from, other, 0.0, boxes, pair);
    }

    /// Calls `pair(i, j)` for every item `i` below node `from` of this tree (0 for all, or one
    /// of [`Bvh::cut`]) and item `j` of `other` whose own boxes come within `margin` of each
    /// other (`boxes`: this tree's items' boxes, then `other`'s, as built), in one descent of
    /// both trees together. Where two leaves meet, each one's items are first kept to those
    /// within `margin` of the other leaf's box (an item's box lies in its leaf's, so no pair is
    /// lost): most of the up to 16 pairs are then not asked at all.
    pub fn visit_pairs_within(
        &self,
        from: u32,
        other: &Bvh,
        margin: f64,
        (mine, theirs): (&[Aabb], &[Aabb]),
        mut pair: impl FnMut(u32, u32),
    ) {
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return;
        }
        fn leaf<'t>(tree: &'t Bvh, n: &Node) -> &'t [u32] {
            let s = n.start_or_right as usize;
            &tree.items[s..s + n.count as usize]
        }
        let children = |tree: &Bvh, n: u32| [n + 1, tree.nodes[n as usize].start_or_right];
        // Pairs go on the stack only once their boxes are known to overlap.
        if !self.nodes[from as usize]
            .bbox
            .overlaps(&other.nodes[0].bbox, margin)
        {
            return;
        }
        // The first pair of children found overlapping is taken next without the stack.
        let mut stack: smallvec::SmallVec<[(u32, u32); 128]> = smallvec::SmallVec::new();
        let mut next = Some((from, 0));
        while let Some((a, b)) = next.take().or_else(|| stack.pop()) {
            let (na, nb) = (&self.nodes[a as usize], &other.nodes[b as usize]);
            // Descend the inner node with the larger box, or the only inner one.
            let down_a = match (na.count > 0, nb.count > 0) {
                (true, true) => {
                    let mut near_a = [0u32; LEAF_ITEMS];
                    let mut count = 0;
                    for &j in leaf(other, nb) {
                        if theirs[j as usize].overlaps(&na.bbox, margin) {
                            near_a[count] = j;
                            count += 1;
                        }
                    }
                    if count == 0 {
                        continue;
                    }
                    for &i in leaf(self, na) {
                        let own = &mine[i as usize];
                        if !own.overlaps(&nb.bbox, margin) {
                            continue;
                        }
                        for &j in &near_a[..count] {
                            if own.overlaps(&theirs[j as usize], margin) {
                                pair(i, j);
                            }
                        }
                    }
                    continue;
                }
                (true, false) => false,
                (false, true) => true,
                (false, false) => {
                    na.bbox.size().length_squared() >= nb.bbox.size().length_squared()
                }
            };
            let mut go = |pair: (u32, u32)| match next {
                None => next = Some(pair),
                Some(_) => stack.push(pair),
            };
            if down_a {
                for c in children(self, a) {
                    if self.nodes[c as usize].bbox.overlaps(&nb.bbox, margin) {
                        go((c, b));
                    }
                }
            } else {
                for c in children(other, b) {
                    if other.nodes[c as usize].bbox.overlaps(&na.bbox, margin) {
                        go((a, c));
                    }
                }
            }
        }
    }

    /// The items in the order [`Bvh::visit`] meets them (where it enters every leaf).
    #[cfg(test)]
    pub fn order(&self) -> &[u32] {
        &self.items
    }

    /// Calls `item` for every item whose leaf box the ray `origin + t·dir` (t ≥ 0) passes
    /// through; stops when it returns true.
    pub fn ray(&self, origin: DVec3, dir: DVec3, item: impl FnMut(u32) -> bool) {
        let inv = dir.recip();
        self.visit(|b| b.ray_span(origin, inv, f64::INFINITY).is_some(), item);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlap_and_ray_find_the_right_boxes() {
        let boxes: Vec<Aabb> = (0..100)
            .map(|i| {
                let p = DVec3::new(i as f64, (i % 7) as f64, 0.0);
                Aabb::new(p, p + DVec3::splat(0.5))
            })
            .collect();
        let bvh = Bvh::build(&boxes);
        let q = Aabb::new(DVec3::new(10.2, 3.2, 0.1), DVec3::new(10.3, 3.3, 0.2));
        let overlapping = |query: &Aabb| {
            let mut found = Vec::new();
            bvh.visit(
                |b| b.overlaps(query, 0.0),
                |i| {
                    if boxes[i as usize].overlaps(query, 0.0) {
                        found.push(i);
                    }
                    false
                },
            );
            found
        };
        assert_eq!(overlapping(&q), vec![10]);
        let far = Aabb::new(DVec3::splat(-5.0), DVec3::splat(-4.0));
        assert!(overlapping(&far).is_empty());
        // The leaves hold every item once, each inside its leaf's box.
        let mut items: Vec<u32> = bvh
            .leaves()
            .flat_map(|(leaf, items)| {
                assert!(
                    items
                        .iter()
                        .all(|&i| leaf.union(&boxes[i as usize]) == *leaf)
                );
                items.iter().copied()
            })
            .collect();
        items.sort();
        assert_eq!(items, (0..100).collect::<Vec<_>>());
        let mut hit = Vec::new();
        bvh.ray(DVec3::new(-1.0, 0.25, 0.25), DVec3::X, |i| {
            if boxes[i as usize].min.y == 0.0 {
                hit.push(i);
            }
            false
        });
        hit.sort();
        assert_eq!(hit, (0..100).filter(|i| i % 7 == 0).collect::<Vec<_>>());
    }

    /// The walk meets items in the order of a recursive descent, first child first, passing
    /// over skipped groups' subtrees and boxes `enter` refuses, and stops where `item` asks.
    #[test]
    fn visit_skipping_walks_depth_first_in_order() {
        let at = |t: f64| DVec3::new(t.cos(), t.sin(), 0.1 * t);
        let boxes: Vec<Aabb> = (0..700)
            .map(|i| Aabb::new(at(i as f64 * 0.03), at(i as f64 * 0.03) + 0.05))
            .collect();
        let groups: Vec<u32> = (0..700)
            .map(|i| if i % 3 == 0 { NO_GROUP } else { i / 90 })
            .collect();
        let bvh = Bvh::build_grouped(&boxes, &groups);
        let (skip, q) = (
            |g: u32| g % 2 == 1,
            Aabb::new(DVec3::new(-0.5, -1.0, 0.0), DVec3::new(1.0, 1.0, 1.2)),
        );
        fn walk(t: &Bvh, n: usize, go: &dyn Fn(&Node) -> bool, out: &mut Vec<u32>) {
            let node = &t.nodes[n];
            if go(node) && node.count > 0 {
                let s = node.start_or_right as usize;
                out.extend(&t.items[s..s + node.count as usize]);
            } else if go(node) {
                walk(t, n + 1, go, out);
                walk(t, node.start_or_right as usize, go, out);
            }
        }
        let mut want = Vec::new();
        walk(
            &bvh,
            0,
            &|n| (n.group == NO_GROUP || !skip(n.group)) && n.bbox.overlaps(&q, 0.0),
            &mut want,
        );
        assert!(want.len() > 50 && want.len() < 600, "{}", want.len());
        for stop in [want.len(), 17] {
            let mut got = Vec::new();
            bvh.visit_skipping(
                skip,
                |b| b.overlaps(&q, 0.0),
                |i| {
                    got.push(i);
                    got.len() == stop
                },
            );
            assert_eq!(got, want[..stop]);
        }
    }

    /// Every pair of overlapping boxes, one from each tree, is met exactly once, whether the
    /// first tree is descended whole or piece by piece from a cut.
    #[test]
    fn pairs_meet_every_overlap_once() {
        // Short segments along a helix and points scattered near it: the shape of the
        // T-junction search (cut edges and their ends along the operands' crossing curve).
        let at = |t: f64| DVec3::new(t.cos(), t.sin(), 0.1 * t);
        let edges: Vec<Aabb> = (0..300)
            .map(|i| {
                let (a, b) = (at(i as f64 * 0.05), at((i + 1) as f64 * 0.05));
                Aabb::new(a.min(b), a.max(b))
            })
            .collect();
        let points: Vec<Aabb> = (0..500)
            .map(|i| {
                let p = at(i as f64 * 0.031) + DVec3::splat(0.002 * ((i % 5) as f64 - 2.0));
                Aabb::new(p, p)
            })
            .collect();
        let (eb, pb) = (Bvh::build(&edges), Bvh::build(&points));
        let mut want: Vec<(u32, u32)> = Vec::new();
        for (i, e) in edges.iter().enumerate() {
            for (j, p) in points.iter().enumerate() {
                if e.overlaps(p, 0.0) {
                    want.push((i as u32, j as u32));
                }
            }
        }
        assert!(want.len() > 150, "{}", want.len());
        for count in [1, 7, 64, 10_000] {
            let cut = eb.cut(count);
            assert!(
                cut.len() >= count.min(300 / LEAF_ITEMS),
                "{count}: {}",
                cut.len()
            );
            let mut met = Vec::new();
            for &piece in &cut {
                eb.visit_pairs(piece, &pb, (&edges, &points), |i, j| met.push((i, j)));
            }
            // Only overlapping pairs are given, each once: sorted, not deduplicated, a pair
            // met twice or one not overlapping would show.
            met.sort();
            assert_eq!(met, want, "{count}");
        }
        // Within a margin: every pair of boxes that close, once.
        let margin = 0.004;
        let mut near: Vec<(u32, u32)> = Vec::new();
        for (i, e) in edges.iter().enumerate() {
            for (j, p) in points.iter().enumerate() {
                if e.overlaps(p, margin) {
                    near.push((i as u32, j as u32));
                }
            }
        }
        assert!(near.len() > want.len(), "{} {}", near.len(), want.len());
        let mut met = Vec::new();
        for &piece in &eb.cut(64) {
            eb.visit_pairs_within(piece, &pb, margin, (&edges, &points), |i, j| {
                met.push((i, j))
            });
        }
        met.sort();
        assert_eq!(met, near);
        // The order the items are visited in is a permutation of them.
        let mut order = pb.order().to_vec();
        order.sort();
        assert_eq!(order, (0..500).collect::<Vec<_>>());
    }
}
