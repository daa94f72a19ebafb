//! Self-intersection of a triangle mesh: pairs of triangles whose interiors cross. A file of
//! two overlapping closed shells is closed and manifold, but bounds no solid the booleans can
//! use (its volume counts the overlap twice); this finds it.
//!
//! Candidate pairs come from a BVH over the triangles' boxes ([`crate::geom::bvh`]); each is
//! decided by exact orientation predicates (Shewchuk's adaptive `orient3d`), so rounding
//! never invents or hides a crossing. Only proper crossings count: an edge of one triangle
//! passing strictly through the other's interior. Triangles that share a vertex, and contacts
//! along edges, at vertices or in a common plane, are touching, not crossing.

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::Aabb;
use crate::geom::bvh::Bvh;

/// The crossing pairs `(t, u)`, `t < u`, of the triangles of a mesh, in order.
pub(crate) fn crossing_pairs(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let corners = |t: usize| triangles[t].map(|i| positions[i as usize]);
    let boxes: Vec<Aabb> = (0..triangles.len())
        .map(|t| Aabb::from_points(&corners(t)))
        .collect();
    let bvh = Bvh::build(&boxes);
    let mut pairs: Vec<(u32, u32)> = (0..triangles.len())
        .into_par_iter()
        .with_min_len(1024)
        .flat_map_iter(|t| {
            let mut found = Vec::new();
            let (tri, b) = (triangles[t], boxes[t]);
            bvh.visit(
                |node| node.overlaps(&b, 0.0),
                |u| {
                    let u = u as usize;
                    if u > t
                        && boxes[u].overlaps(&b, 0.0)
                        && !triangles[u].iter().any(|i| tri.contains(i))
                        && cross(corners(t), corners(u))
                    {
                        found.push((t as u32, u as u32));
                    }
                    false
                },
            );
            found
        })
        .collect();
    pairs.sort_unstable();
    pairs
}

/// The sign of the exact orientation of `d` against the plane through `a`, `b`, `c`.
fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let p = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// True when segment `pq` passes strictly through the interior of triangle `abc`.
fn pierces([p, q]: [DVec3; 2], [a, b, c]: [DVec3; 3]) -> bool {
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if !(sp > 0.0 && sq < 0.0 || sp < 0.0 && sq > 0.0) {
        return false;
    }
    let (s1, s2, s3) = (orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a));
    s1 > 0.0 && s2 > 0.0 && s3 > 0.0 || s1 < 0.0 && s2 < 0.0 && s3 < 0.0
}

/// True when an edge of either triangle passes strictly through the other.
fn cross(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
    let edges = |v: [DVec3; 3]| [[v[0], v[1]], [v[1], v[2]], [v[2], v[0]]];
    edges(t).into_iter().any(|e| pierces(e, u)) || edges(u).into_iter().any(|e| pierces(e, t))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(at: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let m = crate::Solid::cube(1.0)
            .unwrap()
            .translate(at)
            .unwrap()
            .to_mesh();
        (m.positions, m.triangles)
    }

    #[test]
    fn overlapping_shells_cross_and_touching_ones_do_not() {
        for (offset, crossing) in [(0.5, true), (1.0, false), (2.0, false)] {
            let (mut p, mut t) = cube(DVec3::ZERO);
            let (q, u) = cube(DVec3::new(offset, 0.25, 0.25));
            let n = p.len() as u32;
            p.extend(q);
            t.extend(u.into_iter().map(|f| f.map(|i| i + n)));
            assert_eq!(!crossing_pairs(&p, &t).is_empty(), crossing, "{offset}");
        }
        let (p, t) = cube(DVec3::ZERO);
        assert!(crossing_pairs(&p, &t).is_empty());
    }
}
