//! A bounding-volume hierarchy over a mesh's triangles for ray casting and closest-point
//! queries.
//!
//! The crate's other BVH (`geom::bvh`) sorts boxes once along a Morton curve and halves the
//! ranges: cheap to build and good enough for overlap queries between two solids. Primary rays
//! need a tree shaped by the surface area heuristic instead, so this one splits by binned SAH
//! (16 bins on each axis). Nodes keep `f32` boxes, rounded outward and stored relative to the
//! mesh centre, so that a node is 32 bytes and two fit a cache line; triangles keep `f64`
//! corners for the hit test. Build and traversal use explicit stacks.
//!
//! `build.rs` makes the tree; `triangle.rs` holds the ray–triangle and point–triangle tests
//! the queries here run at the leaves.

use glam::{DVec3, Vec3A};

use crate::geom::Aabb;

use super::camera::Ray;

mod build;
mod triangle;

use triangle::{Shear, closest_on_triangle};

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

impl MeshBvh {
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
            // A ray running in a face of the box (0 · ∞ = NaN) is bounded by nothing across it,
            // as in `Aabb::ray_span`.
            let in_face = t0.is_nan_mask() | t1.is_nan_mask();
            let near = Vec3A::select(in_face, Vec3A::NEG_INFINITY, t0.min(t1));
            let exit = Vec3A::select(in_face, Vec3A::INFINITY, t0.max(t1));
            let near = near.max_element().max(t_lo);
            // A few ulps of slack keep grazing hits (Ize's robust traversal).
            let fa = exit.min_element() * 1.000_000_5;
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

#[cfg(test)]
mod tests {
    use super::triangle::watertight;
    use super::*;
    use crate::Solid;
    use crate::mesh::Mesh;

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
