//! Building the hierarchy: binned SAH splits while the tree is shallow, halving by count
//! below [`SAH_DEPTH`] (or where the SAH finds no split worth making), on an explicit stack.

use glam::{DVec3, Vec3A};

use super::{BINS, MAX_LEAF, MeshBvh, Node, SAH_DEPTH};
use crate::geom::Aabb;
use crate::mesh::Mesh;

#[derive(Clone, Copy)]
struct Bin {
    lo: Vec3A,
    hi: Vec3A,
    count: u32,
}

impl Bin {
    const EMPTY: Bin = Bin {
        lo: Vec3A::splat(f32::INFINITY),
        hi: Vec3A::splat(f32::NEG_INFINITY),
        count: 0,
    };
    fn area(&self) -> f32 {
        if self.count == 0 {
            return 0.0;
        }
        let d = self.hi - self.lo;
        d.x * d.y + d.y * d.z + d.z * d.x
    }
    fn merge(&self, o: &Bin) -> Bin {
        Bin {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
            count: self.count + o.count,
        }
    }
}
impl MeshBvh {
    /// Builds the hierarchy over every triangle whose indices are in range and whose corners
    /// are finite (the others are left out and never hit).
    #[must_use]
    pub fn build(mesh: &Mesh) -> MeshBvh {
        let mut ids: Vec<u32> = Vec::with_capacity(mesh.triangles.len());
        let mut tris: Vec<[DVec3; 3]> = Vec::with_capacity(mesh.triangles.len());
        for (i, t) in mesh.triangles.iter().enumerate() {
            let c = t.map(|k| mesh.positions.get(k as usize).copied());
            if let [Some(a), Some(b), Some(c)] = c
                && a.is_finite()
                && b.is_finite()
                && c.is_finite()
            {
                ids.push(i as u32);
                tris.push([a, b, c]);
            }
        }
        let bbox = Aabb::from_points(tris.iter().flatten());
        let origin = if bbox.is_empty() {
            DVec3::ZERO
        } else {
            bbox.center()
        };
        // Outward rounding slack: a few f32 ulps of the largest relative coordinate.
        let slack = (bbox.size().max_element().max(0.0) * 4e-7) as f32;
        let boxes: Vec<(Vec3A, Vec3A)> = tris
            .iter()
            .map(|t| {
                let lo = (t[0].min(t[1]).min(t[2]) - origin).as_vec3();
                let hi = (t[0].max(t[1]).max(t[2]) - origin).as_vec3();
                (
                    Vec3A::from(lo) - Vec3A::splat(slack + lo.abs().max_element() * 2.4e-7),
                    Vec3A::from(hi) + Vec3A::splat(slack + hi.abs().max_element() * 2.4e-7),
                )
            })
            .collect();
        let centres: Vec<Vec3A> = boxes.iter().map(|(l, h)| (*l + *h) * 0.5).collect();
        let mut order: Vec<u32> = (0..tris.len() as u32).collect();
        let mut nodes: Vec<Node> = Vec::with_capacity(2 * tris.len() / 3 + 1);
        let mut depth_max = 0;
        if !tris.is_empty() {
            // (start, end, parent whose right child this is, depth)
            let mut stack: Vec<(usize, usize, Option<usize>, usize)> =
                vec![(0, tris.len(), None, 1)];
            let mut bins = [[Bin::EMPTY; BINS]; 3];
            while let Some((start, end, parent, depth)) = stack.pop() {
                depth_max = depth_max.max(depth);
                let index = nodes.len();
                if let Some(p) = parent {
                    nodes[p].start_or_right = index as u32;
                }
                let (mut lo, mut hi) = (Vec3A::splat(f32::INFINITY), Vec3A::splat(-f32::INFINITY));
                let (mut clo, mut chi) = (lo, hi);
                for &i in &order[start..end] {
                    let (l, h) = boxes[i as usize];
                    lo = lo.min(l);
                    hi = hi.max(h);
                    clo = clo.min(centres[i as usize]);
                    chi = chi.max(centres[i as usize]);
                }
                let n = end - start;
                let split = if n <= 2 {
                    None
                } else if depth >= SAH_DEPTH {
                    Some(median_split(&mut order[start..end], &centres, clo, chi) + start)
                } else {
                    sah_split(
                        &mut order[start..end],
                        &boxes,
                        &centres,
                        clo,
                        chi,
                        &mut bins,
                        lo,
                        hi,
                    )
                    .map(|m| m + start)
                };
                let split = match split {
                    None if n > MAX_LEAF => {
                        Some(median_split(&mut order[start..end], &centres, clo, chi) + start)
                    }
                    s => s,
                };
                nodes.push(Node {
                    min: lo.to_array(),
                    max: hi.to_array(),
                    start_or_right: start as u32,
                    count: if split.is_some() { 0 } else { n as u32 },
                });
                if let Some(mid) = split {
                    stack.push((mid, end, Some(index), depth + 1));
                    stack.push((start, mid, None, depth + 1));
                }
            }
        }
        let corners = order.iter().map(|&i| tris[i as usize]).collect();
        let ids = order.iter().map(|&i| ids[i as usize]).collect();
        MeshBvh {
            nodes,
            corners,
            ids,
            origin,
            depth: depth_max,
            bbox,
        }
    }
}

/// Partitions by SAH over 16 bins on each axis; `None` when a leaf is cheaper or no bin
/// boundary separates the centroids. Returns the split offset within `order`.
#[allow(clippy::too_many_arguments)]
fn sah_split(
    order: &mut [u32],
    boxes: &[(Vec3A, Vec3A)],
    centres: &[Vec3A],
    clo: Vec3A,
    chi: Vec3A,
    bins: &mut [[Bin; BINS]; 3],
    lo: Vec3A,
    hi: Vec3A,
) -> Option<usize> {
    let extent = chi - clo;
    let scale = Vec3A::select(
        extent.cmpgt(Vec3A::ZERO),
        Vec3A::splat(BINS as f32 * 0.999_99) / extent,
        Vec3A::ZERO,
    );
    for axis_bins in bins.iter_mut() {
        *axis_bins = [Bin::EMPTY; BINS];
    }
    for &i in order.iter() {
        let (l, h) = boxes[i as usize];
        let b = ((centres[i as usize] - clo) * scale).as_uvec3();
        for axis in 0..3 {
            let bin = &mut bins[axis][(b[axis] as usize).min(BINS - 1)];
            bin.lo = bin.lo.min(l);
            bin.hi = bin.hi.max(h);
            bin.count += 1;
        }
    }
    let n = order.len();
    let parent = Bin {
        lo,
        hi,
        count: n as u32,
    };
    // Leaf cost: n intersections; a split costs one traversal step plus the children weighted
    // by area.
    let mut best = (n as f32 * parent.area(), usize::MAX, 0usize);
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let mut right = [Bin::EMPTY; BINS];
        let mut acc = Bin::EMPTY;
        for k in (1..BINS).rev() {
            acc = acc.merge(&bins[axis][k]);
            right[k] = acc;
        }
        let mut left = Bin::EMPTY;
        for k in 1..BINS {
            left = left.merge(&bins[axis][k - 1]);
            if left.count == 0 || right[k].count == 0 {
                continue;
            }
            let cost = 0.5 * parent.area()
                + left.area() * left.count as f32
                + right[k].area() * right[k].count as f32;
            if cost < best.0 {
                best = (cost, axis, k);
            }
        }
    }
    let (_, axis, k) = best;
    if axis == usize::MAX {
        return (n > MAX_LEAF).then(|| median_split(order, centres, clo, chi));
    }
    let (c0, s) = (clo[axis], scale[axis]);
    let mid = partition(order, |i| {
        ((((centres[i as usize][axis] - c0) * s) as usize).min(BINS - 1)) < k
    });
    Some(mid)
}

/// Halves by count along the longest centroid axis.
fn median_split(order: &mut [u32], centres: &[Vec3A], clo: Vec3A, chi: Vec3A) -> usize {
    let e = chi - clo;
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = order.len() / 2;
    order.select_nth_unstable_by(mid, |&a, &b| {
        centres[a as usize][axis].total_cmp(&centres[b as usize][axis])
    });
    mid
}

fn partition(v: &mut [u32], pred: impl Fn(u32) -> bool) -> usize {
    let mut i = 0;
    for j in 0..v.len() {
        if pred(v[j]) {
            v.swap(i, j);
            i += 1;
        }
    }
    i
}
