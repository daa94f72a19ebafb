//! A bounding-volume hierarchy over boxes, for overlap queries and ray traversal.

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
    /// Builds the hierarchy; item `i` has box `boxes[i]`. Items are sorted once along a Morton
    /// (Z-order) curve of their box centres, then ranges are halved: spatially coherent leaves
    /// for `O(n log n)` with one sort.
    pub fn build(boxes: &[Aabb]) -> Bvh {
        Self::build_grouped(boxes, &[])
    }

    /// [`Bvh::build`] with item `i` in group `groups[i]` (all in [`NO_GROUP`] when `groups` is
    /// empty). Items are sorted by group first, so each group fills whole subtrees but for the
    /// `O(log n)` nodes on its range's borders, and [`Bvh::visit_skipping`] can pass over a group
    /// without entering it.
    pub fn build_grouped(boxes: &[Aabb], groups: &[u32]) -> Bvh {
        let group = |i: usize| groups.get(i).copied().unwrap_or(NO_GROUP);
        let mut nodes = Vec::with_capacity(2 * boxes.len() / LEAF_ITEMS + 1);
        if boxes.is_empty() {
            return Bvh {
                nodes,
                items: Vec::new(),
            };
        }
        let centres: Vec<DVec3> = boxes.iter().map(Aabb::center).collect();
        let frame = Aabb::from_points(&centres);
        let scale = DVec3::splat(((1u32 << 21) - 1) as f64)
            / frame.size().max(DVec3::splat(f64::MIN_POSITIVE));
        let mut keyed: Vec<(u32, u64, u32)> = centres
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let q = ((*c - frame.min) * scale).as_uvec3();
                let key = morton(q.x) | morton(q.y) << 1 | morton(q.z) << 2;
                (group(i), key, i as u32)
            })
            .collect();
        keyed.sort_unstable();
        let items: Vec<u32> = keyed.into_iter().map(|(_, _, i)| i).collect();
        // (start, end, parent whose `right` this node is)
        let mut stack: Vec<(usize, usize, Option<usize>)> = vec![(0, items.len(), None)];
        while let Some((start, end, parent)) = stack.pop() {
            let index = nodes.len();
            if let Some(p) = parent {
                nodes[p].start_or_right = index as u32;
            }
            let leaf = end - start <= LEAF_ITEMS;
            nodes.push(Node {
                bbox: Aabb::EMPTY,
                start_or_right: if leaf { start as u32 } else { 0 },
                count: if leaf { (end - start) as u32 } else { 0 },
                group: NO_GROUP,
            });
            if !leaf {
                let mid = (start + end) / 2;
                // The first child is processed next, so it lands at index + 1.
                stack.push((mid, end, Some(index)));
                stack.push((start, mid, None));
            }
        }
        // Boxes and groups bottom-up: children follow their parent in the node order.
        let same = |a: u32, b: u32| if a == b { a } else { NO_GROUP };
        for n in (0..nodes.len()).rev() {
            let node = &nodes[n];
            let (bbox, shared) = if node.count > 0 {
                let s = node.start_or_right as usize;
                let leaf = &items[s..s + node.count as usize];
                (
                    leaf.iter()
                        .fold(Aabb::EMPTY, |b, &i| b.union(&boxes[i as usize])),
                    leaf.iter()
                        .map(|&i| group(i as usize))
                        .reduce(same)
                        .unwrap_or(NO_GROUP),
                )
            } else {
                let (first, second) = (&nodes[n + 1], &nodes[node.start_or_right as usize]);
                (
                    first.bbox.union(&second.bbox),
                    same(first.group, second.group),
                )
            };
            nodes[n].bbox = bbox;
            nodes[n].group = shared;
        }
        Bvh { nodes, items }
    }

    /// The leaves: each one's box and its items.
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
        // Depth is logarithmic (median splits), so a small inline stack suffices.
        let mut stack: smallvec::SmallVec<[u32; 64]> = smallvec::smallvec![0u32];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            if (node.group != NO_GROUP && skip(node.group)) || !enter(&node.bbox) {
                continue;
            }
            if node.count > 0 {
                let s = node.start_or_right as usize;
                for &i in &self.items[s..s + node.count as usize] {
                    if item(i) {
                        return;
                    }
                }
            } else {
                stack.push(node.start_or_right);
                stack.push(n + 1);
            }
        }
    }

    /// Calls `item` for every item whose leaf box the ray `origin + t·dir` (t ≥ 0) passes
    /// through; stops when it returns true.
    pub fn ray(&self, origin: DVec3, dir: DVec3, item: impl FnMut(u32) -> bool) {
        let inv = dir.recip();
        self.visit(|b| b.ray_span(origin, inv, f64::INFINITY).is_some(), item);
    }
}

/// Spreads the low 21 bits of `v` to every third bit.
fn morton(v: u32) -> u64 {
    let mut x = (v as u64) & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
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
}
