//! Building the hierarchy: items sorted once along a Morton curve of their box centres (by
//! group first), then ranges halved.

use glam::DVec3;

use super::{Bvh, LEAF_ITEMS, NO_GROUP, Node};
use crate::geom::Aabb;

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
        sort_keyed(&mut keyed);
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
}

/// Sorts `keyed` (group, Morton key, item; listed in item order) as `sort_unstable` would (no two
/// entries are equal): by stable counting passes over 11-bit digits of the key, then of the
/// group, lowest first, skipping a pass whose entries all share the digit. Building a BVH was
/// mostly this sort (a comparison sort of 10⁴–10⁵ entries, ~300 instructions per item).
fn sort_keyed(keyed: &mut Vec<(u32, u64, u32)>) {
    const BITS: u32 = 11;
    if keyed.len() < 256 {
        keyed.sort_unstable();
        return;
    }
    // Passes 0..6 cover the key's 63 bits, 6..9 the group's 32.
    let digit = |e: &(u32, u64, u32), pass: u32| -> usize {
        let bits = if pass < 6 {
            e.1 >> (pass * BITS)
        } else {
            u64::from(e.0) >> ((pass - 6) * BITS)
        };
        (bits & ((1 << BITS) - 1)) as usize
    };
    let mut other = vec![(0u32, 0u64, 0u32); keyed.len()];
    for pass in 0..9 {
        let mut start = [0u32; 1 << BITS];
        for e in keyed.iter() {
            start[digit(e, pass)] += 1;
        }
        if start.iter().any(|&c| c as usize == keyed.len()) {
            continue;
        }
        let mut at = 0u32;
        for c in start.iter_mut() {
            (*c, at) = (at, at + *c);
        }
        for e in keyed.iter() {
            let d = &mut start[digit(e, pass)];
            other[*d as usize] = *e;
            *d += 1;
        }
        std::mem::swap(keyed, &mut other);
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

    /// The counting passes give the comparison sort's order, with groups and repeated keys.
    #[test]
    fn keyed_sort_matches_the_comparison_sort() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for (n, groups) in [(100, 1), (1000, 1), (5000, 3), (5000, 1000)] {
            let keyed: Vec<(u32, u64, u32)> = (0..n)
                .map(|i| {
                    // Few distinct keys, so ties fall to the item.
                    let key = (next() % 64) << (next() % 57);
                    let group = if groups == 1 {
                        NO_GROUP
                    } else {
                        (next() % groups) as u32
                    };
                    (group, key & ((1 << 63) - 1), i as u32)
                })
                .collect();
            let mut want = keyed.clone();
            want.sort_unstable();
            let mut got = keyed;
            sort_keyed(&mut got);
            assert_eq!(got, want, "{n} {groups}");
        }
    }
}
