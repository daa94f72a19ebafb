//! A bounding-volume hierarchy over a mesh's triangles for ray casting and closest-point
//! queries.
//!
//! The crate's other BVH (`geom::bvh`) sorts boxes once along a Morton curve and halves the
//! ranges: cheap to build and good enough for overlap queries between two solids. Primary rays
//! need a tree shaped by the surface area heuristic instead, so this one splits by binned SAH
//! (16 bins on each axis). Nodes keep `f32` boxes, rounded outward and stored relative to the
//! mesh centre, so that a node is 32 bytes and two fit a cache line; triangles keep `f64`
//! corners for the hit test. Build and traversal use explicit stacks.

use glam::{DVec3, Vec3A};

use crate::geom::Aabb;
use crate::mesh::Mesh;

use super::camera::Ray;

const BINS: usize = 16;
/// At most this many triangles per leaf.
const MAX_LEAF: usize = 8;
/// Below this depth splits follow the SAH; deeper, ranges are halved by count so the depth
/// stays below `SAH_DEPTH + 32` for any input.
const SAH_DEPTH: usize = 64;
/// Traversal stack size: enough for the deepest tree the build can make.
const STACK: usize = SAH_DEPTH + 40;

#[derive(Clone, Copy, Debug)]
struct Node {
    min: [f32; 3],
    /// Leaf: first triangle; inner: index of the second child (the first follows the node).
    start_or_right: u32,
    max: [f32; 3],
    /// Triangles in a leaf; 0 for an inner node.
    count: u32,
}

/// A ray hit on a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshHit {
    /// Ray parameter.
    pub t: f64,
    /// Index of the triangle in the mesh.
    pub triangle: u32,
    /// Barycentric weights of the triangle's second and third corners.
    pub uv: (f64, f64),
}

/// A BVH over a mesh's triangles (see the module docs).
#[derive(Clone, Debug, Default)]
pub struct MeshBvh {
    nodes: Vec<Node>,
    /// Triangle corners in leaf order.
    corners: Vec<[DVec3; 3]>,
    /// The mesh triangle of each entry in `corners`.
    ids: Vec<u32>,
    /// Node boxes are relative to this point.
    origin: DVec3,
    depth: usize,
    /// The box of every triangle (empty when there are none).
    bbox: Aabb,
}

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

    /// Number of triangles held.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.corners.len()
    }

    /// Depth of the tree (1 for a single leaf, 0 when empty).
    #[must_use]
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// The box of every triangle (empty when there are none).
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.bbox
    }

    /// The nearest hit with `t` in `(t_min, t_max)`.
    #[must_use]
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<MeshHit> {
        let mut best: Option<MeshHit> = None;
        let shear = Shear::new(ray);
        self.traverse(ray, t_min, t_max, |bvh, k, tf| {
            if let Some((t, u, v)) = shear.hit(&bvh.corners[k], t_min, *tf) {
                *tf = t;
                best = Some(MeshHit {
                    t,
                    triangle: bvh.ids[k],
                    uv: (u, v),
                });
            }
            false
        });
        best
    }

    /// True when some triangle is hit with `t` in `(t_min, t_max)` (shadow rays).
    #[must_use]
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let mut hit = false;
        let shear = Shear::new(ray);
        self.traverse(ray, t_min, t_max, |bvh, k, tf| {
            hit = shear.hit(&bvh.corners[k], t_min, *tf).is_some();
            hit
        });
        hit
    }

    /// How many triangles the ray crosses with `t > 0`, for inside tests by parity. The
    /// watertight test hits at least one triangle at a shared edge or vertex and may hit both,
    /// so a ray through an edge can count twice: callers vote across directions.
    #[must_use]
    pub fn crossings(&self, ray: &Ray) -> usize {
        let mut n = 0;
        let shear = Shear::new(ray);
        self.traverse(ray, 0.0, f64::INFINITY, |bvh, k, tf| {
            if shear.hit(&bvh.corners[k], 0.0, *tf).is_some() {
                n += 1;
            }
            false
        });
        n
    }

    /// Visits the triangles of leaves the ray enters before `t_far`, nearer child first;
    /// `leaf(bvh, k, t_far)` may shrink `t_far` and returns true to stop.
    #[inline]
    fn traverse(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        mut leaf: impl FnMut(&MeshBvh, usize, &mut f64) -> bool,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let o = Vec3A::from((ray.origin - self.origin).as_vec3());
        let inv = Vec3A::from(ray.dir.recip().as_vec3());
        let t_lo = t_min as f32;
        let mut t_far = t_max;
        // Each node's box is tested once, when its parent is opened; the stack keeps the entry
        // distance so that nodes beyond a hit found meanwhile are dropped unopened.
        let mut stack = [(0u32, 0.0f32); STACK];
        let mut top = 0usize;
        let slab = |n: &Node, far: f32| -> Option<f32> {
            let t0 = (Vec3A::from(n.min) - o) * inv;
            let t1 = (Vec3A::from(n.max) - o) * inv;
            let near = t0.min(t1).max_element().max(t_lo);
            // A few ulps of slack keep grazing hits (Ize's robust traversal).
            let fa = t0.max(t1).min_element() * 1.000_000_5;
            (near <= fa.min(far)).then_some(near)
        };
        let slack = |t: f64| (t as f32) * 1.000_000_5;
        if let Some(near) = slab(&self.nodes[0], slack(t_far)) {
            stack[0] = (0, near);
            top = 1;
        }
        while top > 0 {
            top -= 1;
            let (n, near) = stack[top];
            let far = slack(t_far);
            if near > far {
                continue;
            }
            let n = n as usize;
            let node = &self.nodes[n];
            if node.count > 0 {
                let s = node.start_or_right as usize;
                for k in s..s + node.count as usize {
                    if leaf(self, k, &mut t_far) {
                        return;
                    }
                }
            } else {
                let (a, b) = (n + 1, node.start_or_right as usize);
                let ta = slab(&self.nodes[a], far);
                let tb = slab(&self.nodes[b], far);
                // Push the farther first so the nearer pops next.
                match (ta, tb) {
                    (Some(x), Some(y)) => {
                        let (first, second) = if x <= y {
                            ((a, x), (b, y))
                        } else {
                            ((b, y), (a, x))
                        };
                        stack[top] = (second.0 as u32, second.1);
                        stack[top + 1] = (first.0 as u32, first.1);
                        top += 2;
                    }
                    (Some(x), None) => {
                        stack[top] = (a as u32, x);
                        top += 1;
                    }
                    (None, Some(y)) => {
                        stack[top] = (b as u32, y);
                        top += 1;
                    }
                    (None, None) => {}
                }
            }
        }
    }

    /// The point of the mesh nearest to `p`, its distance and triangle; `None` for an empty
    /// mesh. Only triangles nearer than `max_distance` are considered.
    #[must_use]
    pub fn closest_point(&self, p: DVec3, max_distance: f64) -> Option<(DVec3, f64, u32)> {
        if self.nodes.is_empty() {
            return None;
        }
        let q = p - self.origin;
        let mut best_d2 = max_distance * max_distance;
        let mut best: Option<(DVec3, u32)> = None;
        let box_d2 = |n: &Node| -> f64 {
            let lo = Vec3A::from(n.min).as_dvec3();
            let hi = Vec3A::from(n.max).as_dvec3();
            (lo - q).max(q - hi).max(DVec3::ZERO).length_squared()
        };
        let mut stack = [(0u32, 0.0f64); STACK];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let (n, d2) = stack[top];
            if d2 > best_d2 {
                continue;
            }
            let node = &self.nodes[n as usize];
            if node.count > 0 {
                let s = node.start_or_right as usize;
                for k in s..s + node.count as usize {
                    let c = closest_on_triangle(p, &self.corners[k]);
                    let d2 = (c - p).length_squared();
                    if d2 <= best_d2 {
                        best_d2 = d2;
                        best = Some((c, self.ids[k]));
                    }
                }
            } else {
                let (a, b) = (n + 1, self.nodes[n as usize].start_or_right);
                let (da, db) = (
                    box_d2(&self.nodes[a as usize]),
                    box_d2(&self.nodes[b as usize]),
                );
                let (first, second) = if da <= db {
                    ((a, da), (b, db))
                } else {
                    ((b, db), (a, da))
                };
                stack[top] = second;
                stack[top + 1] = first;
                top += 2;
            }
        }
        best.map(|(c, t)| (c, best_d2.sqrt(), t))
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

/// The per-ray part of the watertight test: the axis permutation and shear that map the ray
/// to +z, computed once per ray rather than per triangle.
#[derive(Clone, Copy)]
pub(crate) struct Shear {
    origin: DVec3,
    k: [usize; 3],
    s: [f64; 3],
}

impl Shear {
    #[inline]
    pub(crate) fn new(ray: &Ray) -> Shear {
        let d = ray.dir;
        let kz = d.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let sz = 1.0 / d[kz];
        Shear {
            origin: ray.origin,
            k: [kx, ky, kz],
            s: [d[kx] * sz, d[ky] * sz, sz],
        }
    }

    /// The watertight ray–triangle test of Woop, Benthin and Wald (JCGT 2013): edge functions
    /// in a ray-aligned shear frame, so a ray through a shared edge or vertex hits at least one
    /// of the triangles there (never slips between them). Both sides count. Returns
    /// `(t, u, v)`.
    #[inline]
    pub(crate) fn hit(&self, tri: &[DVec3; 3], t_min: f64, t_max: f64) -> Option<(f64, f64, f64)> {
        let [kx, ky, kz] = self.k;
        let [sx, sy, sz] = self.s;
        let a = tri[0] - self.origin;
        let b = tri[1] - self.origin;
        let c = tri[2] - self.origin;
        let ax = a[kx] - sx * a[kz];
        let ay = a[ky] - sy * a[kz];
        let bx = b[kx] - sx * b[kz];
        let by = b[ky] - sy * b[kz];
        let cx = c[kx] - sx * c[kz];
        let cy = c[ky] - sy * c[kz];
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let t = (u * a[kz] + v * b[kz] + w * c[kz]) * sz / det;
        if !(t > t_min && t < t_max) {
            return None;
        }
        Some((t, v / det, w / det))
    }
}

/// [`Shear::hit`] for one ray and one triangle.
#[cfg(test)]
fn watertight(ray: &Ray, tri: &[DVec3; 3], t_min: f64, t_max: f64) -> Option<(f64, f64, f64)> {
    Shear::new(ray).hit(tri, t_min, t_max)
}

/// The point of triangle `t` nearest to `p` (Ericson, Real-Time Collision Detection 5.1.5).
pub(crate) fn closest_on_triangle(p: DVec3, t: &[DVec3; 3]) -> DVec3 {
    let [a, b, c] = *t;
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom == 0.0 || !denom.is_finite() {
        // Degenerate triangle: the nearest of its edges' endpoints will do.
        return [a, b, c]
            .into_iter()
            .min_by(|x, y| {
                (*x - p)
                    .length_squared()
                    .total_cmp(&(*y - p).length_squared())
            })
            .unwrap_or(a);
    }
    let v = vb / denom;
    let w = vc / denom;
    a + ab * v + ac * w
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Solid;

    fn sphere_mesh() -> Mesh {
        Solid::sphere(1.0, 48, 24).unwrap().to_mesh()
    }

    #[test]
    fn rays_hit_where_brute_force_does() {
        let mesh = sphere_mesh();
        let bvh = MeshBvh::build(&mesh);
        assert_eq!(bvh.triangle_count(), mesh.triangle_count());
        let mut rng = 0x1234_5678u64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..500 {
            let origin = DVec3::new(next(), next(), next()) * 3.0;
            let dir = (DVec3::new(next(), next(), next()) - origin * 0.3).normalize();
            let ray = Ray { origin, dir };
            let brute = (0..mesh.triangle_count())
                .filter_map(|t| watertight(&ray, &mesh.triangle(t), 0.0, f64::INFINITY))
                .map(|h| h.0)
                .min_by(f64::total_cmp);
            let fast = bvh.intersect(&ray, 0.0, f64::INFINITY).map(|h| h.t);
            assert_eq!(brute, fast);
            let n = bvh.crossings(&ray);
            assert_eq!(fast.is_some(), n > 0);
            // The mesh is closed: from outside a ray crosses an even number of times.
            if origin.length() > 1.01 {
                assert_eq!(n % 2, 0, "{ray:?}");
            }
        }
    }

    #[test]
    fn closest_point_matches_brute_force() {
        let mesh = sphere_mesh();
        let bvh = MeshBvh::build(&mesh);
        for p in [
            DVec3::new(0.3, 2.0, -0.4),
            DVec3::ZERO,
            DVec3::new(0.9, 0.1, 0.2),
        ] {
            let brute = (0..mesh.triangle_count())
                .map(|t| (closest_on_triangle(p, &mesh.triangle(t)) - p).length())
                .min_by(f64::total_cmp)
                .unwrap();
            let (_, d, _) = bvh.closest_point(p, f64::INFINITY).unwrap();
            assert!((d - brute).abs() < 1e-12, "{p}: {d} vs {brute}");
        }
    }

    #[test]
    fn a_ray_through_a_shared_vertex_is_not_lost() {
        // The octahedron's vertices sit on the axes; a ray straight at one hits.
        let mesh = Solid::sphere(1.0, 4, 2).unwrap().to_mesh();
        let bvh = MeshBvh::build(&mesh);
        for dir in [DVec3::NEG_Y, DVec3::Y, DVec3::NEG_X] {
            let ray = Ray {
                origin: -dir * 3.0,
                dir,
            };
            assert!(bvh.intersect(&ray, 0.0, f64::INFINITY).is_some(), "{dir}");
        }
    }

    #[test]
    fn degenerate_input_stays_shallow() {
        // Many nested triangles whose boxes share one centre: SAH finds no split, so every
        // range is halved by count, and the depth is that of a balanced tree of leaves.
        const N: u32 = 5000;
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for i in 0..N {
            let s = 1.0 + i as f64 * 1e-3;
            positions.extend([
                DVec3::new(-s, -s, 0.0),
                DVec3::new(s, -s, 0.0),
                DVec3::new(0.0, s, 0.0),
            ]);
            triangles.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        let bvh = MeshBvh::build(&Mesh::new(positions, triangles));
        let balanced = 1 + (f64::from(N) / MAX_LEAF as f64).log2().ceil() as usize;
        assert_eq!(bvh.triangle_count(), N as usize);
        assert!(
            bvh.depth() <= balanced,
            "depth {} > {balanced}",
            bvh.depth()
        );
    }
}
