//! Self-intersection of a triangle mesh: pairs of triangles whose interiors cross. A file of
//! two overlapping closed shells is closed and manifold, but bounds no solid the booleans can
//! use (its volume counts the overlap twice); this finds it.
//!
//! Candidate pairs come from a BVH over the triangles' boxes ([`crate::geom::bvh`]); each is
//! decided by exact orientation predicates (Shewchuk's adaptive `orient3d` and `orient2d`), so
//! rounding never invents or hides a crossing. Two kinds of pair count:
//! - an edge of one triangle passing strictly through the other's interior;
//! - two triangles in one plane, facing the same way, whose interiors overlap: material on the
//!   same side of both, so the shells behind them overlap (two cubes moved along one axis meet
//!   only so: their side faces lie in common planes). The same triangle twice counts.
//!
//! Contacts along edges, at vertices, and coplanar triangles facing opposite ways (two solids
//! face to face) are touching, not crossing. Triangles that share an edge cross only in a
//! common plane (their planes meet in that edge); triangles that share one vertex may also
//! cross away from it, through an edge of one.
//!
//! The work is kept near linear on valid meshes, whose box-overlapping pairs are mostly
//! neighbours, even where a vertex has thousands of triangles (a cone's apex, a cap's centre),
//! all of whose boxes overlap:
//! - a vertex whose fan is checked embedded ([`fans`], linear in its valence) settles every
//!   pair of triangles sharing it: none of them cross, and none is tested;
//! - a triangle's box takes part in the tree in the group of its corner of highest valence
//!   (over [`GROUP_VALENCE`]) whose fan is embedded, and a query passes over its own group's
//!   subtrees without entering them, and over another group's where the pairs between the two
//!   are better found from that group's side ([`Fans::queries`]);
//! - a thin triangle (a sliver of such a fan) is tested against the boxes the tree offers
//!   ([`apart`]), not only its own box, so a cone's apex fan does not meet every triangle of its
//!   base's fan.

mod apart;
mod fans;

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::bvh::{Bvh, NO_GROUP};
use crate::geom::{Aabb, is_zero_area};

/// At most this many crossing pairs are looked for: enough to refuse a mesh and to say how
/// badly it crosses, while a hostile file (one triangle repeated 16,384 times has 1.3·10⁸
/// pairs) stops here instead of spending time and memory quadratic in its size.
pub const MAX_CROSSING_PAIRS: usize = 100_000;

/// Triangles around a vertex of at least this valence whose fan is embedded are grouped in the
/// tree (below it a vertex's few pairs cost less than the lost spatial order of the tree).
const GROUP_VALENCE: u32 = 32;

/// The crossing pairs `(t, u)`, `t < u`, of the triangles of a mesh, in order; at most
/// [`MAX_CROSSING_PAIRS`] of them (which ones is then not fixed). Triangles of zero area
/// (`geom::is_zero_area`, as the import drops them) have no interior to cross and are left out,
/// so a soup of degenerate triangles whose boxes all overlap costs no pairwise test.
pub(crate) fn crossing_pairs(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<(u32, u32)> {
    search(positions, triangles).pairs
}

/// What [`search`] found, and how much work it took (the counts bound the work in tests).
struct Search {
    pairs: Vec<(u32, u32)>,
    /// Pairs the tree offered (items in leaves a query entered).
    #[cfg_attr(not(test), allow(dead_code))]
    offered: usize,
    /// Pairs decided by the exact test [`cross`].
    #[cfg_attr(not(test), allow(dead_code))]
    tested: usize,
}

fn search(positions: &[DVec3], triangles: &[[u32; 3]]) -> Search {
    let corners = |t: usize| triangles[t].map(|i| positions[i as usize]);
    let boxes: Vec<Aabb> = (0..triangles.len())
        .map(|t| Aabb::from_points(&corners(t)))
        .collect();
    let solid: Vec<u32> = (0..triangles.len() as u32)
        .filter(|&t| !is_zero_area(corners(t as usize)))
        .collect();
    let embedded = fans::embedded_valences(positions, triangles);
    let fans = Fans::new(positions, &embedded, triangles, &solid, &boxes);
    let solid_boxes: Vec<Aabb> = solid.iter().map(|&t| boxes[t as usize]).collect();
    let thin: Vec<bool> = (0..triangles.len())
        .map(|t| apart::thin(corners(t)))
        .collect();
    let bvh = Bvh::build_grouped(&solid_boxes, &fans.of_solid);
    // Two triangles around one vertex with an embedded fan do not cross.
    let share_embedded = |t: [u32; 3], u: [u32; 3]| {
        t.iter()
            .any(|&v| embedded[v as usize] > 0 && u.contains(&v))
    };
    let found_so_far = AtomicUsize::new(0);
    let (offered, tested) = (AtomicUsize::new(0), AtomicUsize::new(0));
    let mut pairs: Vec<(u32, u32)> = solid
        .par_iter()
        .zip(&fans.of_solid)
        .with_min_len(1024)
        .flat_map_iter(|(&t, &own)| {
            let t = t as usize;
            let mut found = Vec::new();
            if found_so_far.load(Ordering::Relaxed) >= MAX_CROSSING_PAIRS {
                return found;
            }
            let (tri, b, tc, thin_t) = (triangles[t], boxes[t], corners(t), thin[t]);
            let (mut offers, mut tests) = (0, 0);
            bvh.visit_skipping(
                |other| !fans.queries(own, other),
                |node| node.overlaps(&b, 0.0) && !(thin_t && apart::apart(tc, node)),
                |k| {
                    offers += 1;
                    let (u, other) = (solid[k as usize] as usize, fans.of_solid[k as usize]);
                    let mine = if own == NO_GROUP || other == NO_GROUP || own == other {
                        u > t
                    } else {
                        fans.queries(own, other)
                    };
                    if !mine
                        || !boxes[u].overlaps(&b, 0.0)
                        || share_embedded(tri, triangles[u])
                        || thin_t && apart::apart(tc, &boxes[u])
                        || thin[u] && apart::apart(corners(u), &b)
                    {
                        return false;
                    }
                    tests += 1;
                    if cross(tri, triangles[u], tc, corners(u)) {
                        found.push((t.min(u) as u32, t.max(u) as u32));
                        // Stop this triangle's walk, and the others', once enough are found.
                        return found_so_far.fetch_add(1, Ordering::Relaxed) + 1
                            >= MAX_CROSSING_PAIRS;
                    }
                    false
                },
            );
            offered.fetch_add(offers, Ordering::Relaxed);
            tested.fetch_add(tests, Ordering::Relaxed);
            found
        })
        .collect();
    pairs.sort_unstable();
    pairs.truncate(MAX_CROSSING_PAIRS);
    Search {
        pairs,
        offered: offered.into_inner(),
        tested: tested.into_inner(),
    }
}

/// The groups of the tree: one per vertex of valence at least [`GROUP_VALENCE`] whose fan is
/// embedded, holding the triangles for which it is the corner of highest such valence.
struct Fans {
    /// The group of each triangle of `solid` (numbered from 0), or [`NO_GROUP`].
    of_solid: Vec<u32>,
    /// Each group's vertex.
    centre: Vec<DVec3>,
    /// The box of each group's triangles.
    reach: Vec<Aabb>,
}

impl Fans {
    fn new(
        positions: &[DVec3],
        embedded: &[u32],
        triangles: &[[u32; 3]],
        solid: &[u32],
        boxes: &[Aabb],
    ) -> Fans {
        let mut number = vec![NO_GROUP; positions.len()];
        let mut centre = Vec::new();
        for (v, &valence) in embedded.iter().enumerate() {
            if valence >= GROUP_VALENCE {
                number[v] = centre.len() as u32;
                centre.push(positions[v]);
            }
        }
        let mut reach = vec![Aabb::EMPTY; centre.len()];
        let of_solid = solid
            .iter()
            .map(|&t| {
                let best = triangles[t as usize]
                    .into_iter()
                    .filter(|&v| number[v as usize] != NO_GROUP)
                    .max_by_key(|&v| (embedded[v as usize], std::cmp::Reverse(v)));
                let Some(v) = best else {
                    return NO_GROUP;
                };
                let g = number[v as usize];
                reach[g as usize] = reach[g as usize].union(&boxes[t as usize]);
                g
            })
            .collect();
        Fans {
            of_solid,
            centre,
            reach,
        }
    }

    /// Whether a triangle of group `own` looks for its pairs with the triangles of group
    /// `other`, or leaves them to the other's queries. Each pair of different groups is looked
    /// for from one side only, and from the side that can prune: a fan's triangles all reach
    /// its vertex, so they cannot be told apart from a box around it. A cone's base triangles
    /// all meet the box of its apex's (which holds the base's centre), while the apex's
    /// triangles meet only the few boxes of the base's below them.
    fn queries(&self, own: u32, other: u32) -> bool {
        if own == NO_GROUP || other == NO_GROUP {
            return true;
        }
        if own == other {
            return false;
        }
        let inside =
            |g: u32, h: u32| self.reach[h as usize].contains_point(self.centre[g as usize], 0.0);
        match (inside(own, other), inside(other, own)) {
            (false, true) => true,
            (true, false) => false,
            _ => own < other,
        }
    }
}

/// The sign of the exact orientation of `d` against the plane through `a`, `b`, `c`.
fn orient([a, b, c]: [DVec3; 3], d: DVec3) -> f64 {
    let p = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// True when segment `pq`, whose ends lie on the sides `sp`, `sq` of triangle `abc`'s plane
/// (signs of [`orient`]), passes strictly through the triangle's interior.
fn pierces([p, q]: [DVec3; 2], [sp, sq]: [f64; 2], [a, b, c]: [DVec3; 3]) -> bool {
    if !(sp > 0.0 && sq < 0.0 || sp < 0.0 && sq > 0.0) {
        return false;
    }
    let (s1, s2, s3) = (
        orient([p, q, a], b),
        orient([p, q, b], c),
        orient([p, q, c], a),
    );
    s1 > 0.0 && s2 > 0.0 && s3 > 0.0 || s1 < 0.0 && s2 < 0.0 && s3 < 0.0
}

/// True when triangles `t` and `u` (vertex indices `ti`, `ui`; corners `tc`, `uc`) cross: an
/// edge of either passes strictly through the other, or they lie in one plane, face the same
/// way and their interiors overlap. Triangles sharing one corner `v` meet on the line where
/// their planes cross, from `v`; if both run along it into their interiors, the one that stops
/// first stops on its far edge inside the other: that edge passes through it.
fn cross(ti: [u32; 3], ui: [u32; 3], tc: [DVec3; 3], uc: [DVec3; 3]) -> bool {
    if ui.iter().filter(|i| ti.contains(i)).count() >= 2 {
        // Neighbours across an edge: their planes meet in that edge unless they are one plane.
        // Shared corners lie on both planes by construction, so only the other corners decide
        // whether the two are coplanar (rarely: then the 2D test). Triangles sharing one
        // corner take the general test below, where that corner's signs are exactly zero.
        let off_plane = |own: [u32; 3], c: [DVec3; 3], other: [u32; 3], plane: [DVec3; 3]| {
            (0..3).any(|k| !other.contains(&own[k]) && orient(plane, c[k]) != 0.0)
        };
        return !off_plane(ui, uc, ti, tc)
            && !off_plane(ti, tc, ui, uc)
            && coplanar_overlap(tc, uc);
    }
    let st = tc.map(|p| orient(uc, p));
    let su = uc.map(|p| orient(tc, p));
    if st.iter().chain(&su).all(|&s| s == 0.0) {
        return coplanar_overlap(tc, uc);
    }
    let edges = |v: [DVec3; 3], s: [f64; 3]| {
        [(0, 1), (1, 2), (2, 0)].map(|(i, j)| ([v[i], v[j]], [s[i], s[j]]))
    };
    edges(tc, st).into_iter().any(|(e, s)| pierces(e, s, uc))
        || edges(uc, su).into_iter().any(|(e, s)| pierces(e, s, tc))
}

/// For two triangles in one plane: true when they face the same way and their interiors
/// overlap. Exact: both are projected by dropping the coordinate along which the plane's
/// normal is largest (which only forgets a coordinate, and keeps the plane one-to-one with its
/// image), then decided by `orient2d`. Two convex polygons' interiors are disjoint exactly
/// when the line through some edge of one has the other wholly on its closed outer side; this
/// also settles the cases a test of crossing edges and strictly inner corners misses (one
/// triangle inside the other with every corner on its boundary, or the same triangle twice).
fn coplanar_overlap(t: [DVec3; 3], u: [DVec3; 3]) -> bool {
    let normal = |v: [DVec3; 3]| (v[1] - v[0]).cross(v[2] - v[0]).abs();
    let n = normal(t) + normal(u);
    let (i, j) = if n.x >= n.y && n.x >= n.z {
        (1, 2)
    } else if n.y >= n.z {
        (2, 0)
    } else {
        (0, 1)
    };
    let flat = |v: [DVec3; 3]| v.map(|p| robust::Coord { x: p[i], y: p[j] });
    let (t, u) = (flat(t), flat(u));
    let turn = |v: [robust::Coord<f64>; 3]| robust::orient2d(v[0], v[1], v[2]);
    let (ot, ou) = (turn(t), turn(u));
    // A triangle of no area has no interior; opposite turns are opposite facings (touching).
    if ot == 0.0 || ou == 0.0 || (ot > 0.0) != (ou > 0.0) {
        return false;
    }
    // Both turn the same way, so one sign says which side of an edge is inside, for either.
    let inner = |o: f64| if ot > 0.0 { o > 0.0 } else { o < 0.0 };
    let separates = |v: [robust::Coord<f64>; 3], w: [robust::Coord<f64>; 3]| {
        (0..3).any(|k| {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            !w.iter().any(|&p| inner(robust::orient2d(a, b, p)))
        })
    };
    !separates(t, u) && !separates(u, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cone of `n` triangles around apex 0 and `n` around the centre 1 of its base (unit
    /// radius, height `h`), ring vertices from 2; triangle `2i` is the apex's, `2i + 1` the
    /// base's.
    pub(super) fn cone(n: u32, h: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut p = vec![DVec3::new(0.0, 0.0, h), DVec3::ZERO];
        p.extend((0..n).map(|i| ring_point(n, f64::from(i), 1.0)));
        let ring = |i: u32| 2 + i % n;
        let t = (0..n)
            .flat_map(|i| [[0, ring(i), ring(i + 1)], [1, ring(i + 1), ring(i)]])
            .collect();
        (p, t)
    }

    /// The point at `i` of `n` steps round a circle of `radius` in the plane z = 0.
    fn ring_point(n: u32, i: f64, radius: f64) -> DVec3 {
        let a = std::f64::consts::TAU * i / f64::from(n);
        DVec3::new(radius * a.cos(), radius * a.sin(), 0.0)
    }

    #[test]
    fn a_cone_of_many_triangles_is_checked_in_work_linear_in_its_size() {
        // Every pair of the apex's 20,000 triangles overlaps in its box, and so does every pair
        // of the base's, and every apex triangle with every base triangle: 8·10⁸ pairs.
        let n = 20_000;
        let (p, t) = cone(n, 1.0);
        let found = search(&p, &t);
        assert!(found.pairs.is_empty());
        let n = n as usize;
        assert!(found.offered < 16 * n, "{}", found.offered);
        assert!(found.tested < 4 * n, "{}", found.tested);
    }

    #[test]
    fn a_cone_with_a_fan_folded_over_crosses() {
        // Ring vertex 10 moved round the base past its neighbour 11, inside the circle: base
        // triangles come to overlap in the base's plane, facing the same way, sharing only the
        // centre (whose fan is no longer embedded).
        let n = 2_000;
        let (mut p, t) = cone(n, 1.0);
        p[2 + 10] = ring_point(n, 12.5, 0.9);
        let pairs = crossing_pairs(&p, &t);
        assert!(!pairs.is_empty());
        assert!(
            pairs.iter().all(|&(a, b)| a % 2 == 1 && b % 2 == 1),
            "{pairs:?}"
        );
        // Moved out and below the base instead: the apex triangles on it pass down through
        // the base, some through base triangles they share one ring vertex with (which the
        // old test of neighbours, coplanar overlap only, took for touching).
        let (mut p, t) = cone(n, 1.0);
        p[2 + 10] = ring_point(n, 12.5, 1.2) - 0.3 * DVec3::Z;
        let pairs = crossing_pairs(&p, &t);
        let shared = |a: u32, b: u32| {
            let (a, b) = (t[a as usize], t[b as usize]);
            a.iter().filter(|v| b.contains(v)).count()
        };
        assert!(
            pairs.iter().all(|&(a, b)| a % 2 == 0 && b % 2 == 1),
            "{pairs:?}"
        );
        assert!(pairs.iter().any(|&(a, b)| shared(a, b) == 1), "{pairs:?}");
        // Unmoved, the same cone is clean.
        let (p, t) = cone(n, 1.0);
        assert!(crossing_pairs(&p, &t).is_empty());
    }

    #[test]
    fn triangles_sharing_one_corner_cross_through_an_edge() {
        let v = DVec3::ZERO;
        let t = [v, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 2.0, 0.0)];
        // The far edge of `u` passes through `t` at (0.6, 0.6, 0).
        let u = [v, DVec3::new(1.0, 0.2, 1.0), DVec3::new(0.2, 1.0, -1.0)];
        assert!(cross([0, 1, 2], [0, 3, 4], t, u));
        assert!(cross([0, 3, 4], [0, 1, 2], u, t));
        // The same far edge lifted clear of `t`: the two meet only at the shared corner.
        let w = [v, DVec3::new(1.0, 0.2, 1.0), DVec3::new(0.2, 1.0, 0.5)];
        assert!(!cross([0, 1, 2], [0, 3, 4], t, w));
    }

    fn cube(at: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let m = crate::Solid::cube(1.0)
            .unwrap()
            .translate(at)
            .unwrap()
            .to_mesh();
        (m.positions, m.triangles)
    }

    /// Two cubes' triangles in one mesh, the second moved by `offset`; `shared` reuses the
    /// first cube's vertex indices for the second when it is not moved.
    fn two_cubes(offset: DVec3, shared: bool) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let (mut p, mut t) = cube(DVec3::ZERO);
        let (q, u) = cube(offset);
        let n = if shared { 0 } else { p.len() as u32 };
        if !shared {
            p.extend(q);
        }
        t.extend(u.into_iter().map(|f| f.map(|i| i + n)));
        (p, t)
    }

    #[test]
    fn shells_overlapping_only_in_shared_planes_cross() {
        // B = A moved 0.5 along x: no edge passes through a face, but the faces y = 0, y = 1,
        // z = 0 and z = 1 of both overlap facing the same way.
        let (p, t) = two_cubes(DVec3::new(0.5, 0.0, 0.0), false);
        let pairs = crossing_pairs(&p, &t);
        assert!(!pairs.is_empty());
        for &(a, b) in &pairs {
            let normal = |k: u32| {
                let [x, y, z] = t[k as usize].map(|i| p[i as usize]);
                (y - x).cross(z - x).normalize()
            };
            assert!((a as usize) < 12 && (b as usize) >= 12, "{a} {b}");
            assert_eq!(normal(a), normal(b));
            assert_eq!(normal(a).x, 0.0, "only the side faces overlap");
        }
        // Stacked face to face, or side by side: touching, facing opposite ways.
        for offset in [DVec3::Z, DVec3::X, DVec3::new(1.0, 0.5, 0.0)] {
            let (p, t) = two_cubes(offset, false);
            assert!(crossing_pairs(&p, &t).is_empty(), "{offset}");
        }
        // The same cube twice, on copied vertices or on the same ones: each triangle crosses
        // its copy.
        for shared in [false, true] {
            let (p, t) = two_cubes(DVec3::ZERO, shared);
            let pairs = crossing_pairs(&p, &t);
            assert!(pairs.len() >= 12, "{shared}: {pairs:?}");
            assert!((0..12).all(|k| pairs.contains(&(k, k + 12))), "{shared}");
        }
    }

    #[test]
    fn coplanar_triangles_overlap_only_with_interiors_meeting_and_facing_the_same_way() {
        let v = |x: f64, y: f64| DVec3::new(x, y, 3.0);
        let big = [v(0.0, 0.0), v(2.0, 0.0), v(0.0, 2.0)];
        // Inside `big` with every corner on its boundary: no edges cross, no corner is inside.
        let inside = [v(0.0, 0.0), v(2.0, 0.0), v(1.0, 1.0)];
        assert!(coplanar_overlap(big, inside));
        assert!(coplanar_overlap(big, big));
        assert!(coplanar_overlap(big, [big[1], big[2], big[0]]));
        // Facing the other way: two solids face to face.
        assert!(!coplanar_overlap(big, [inside[0], inside[2], inside[1]]));
        // Neighbours across an edge, and triangles meeting at a corner only.
        assert!(!coplanar_overlap(
            big,
            [v(2.0, 0.0), v(2.0, 2.0), v(0.0, 2.0)]
        ));
        assert!(!coplanar_overlap(
            big,
            [v(2.0, 0.0), v(4.0, 0.0), v(2.0, 1.0)]
        ));
        // Crossing edges only, and one corner strictly inside.
        assert!(coplanar_overlap(
            big,
            [v(1.0, -1.0), v(1.0, 3.0), v(-1.0, 1.0)]
        ));
        assert!(coplanar_overlap(
            big,
            [v(0.5, 0.5), v(5.0, 4.0), v(4.0, 5.0)]
        ));
        // No area, no interior.
        assert!(!coplanar_overlap(
            big,
            [v(0.0, 0.0), v(1.0, 1.0), v(2.0, 2.0)]
        ));
        // A tilted plane: the projection drops the largest normal coordinate, exactly.
        let tilt = |x: f64, y: f64| DVec3::new(x, y, 0.5 * x + 0.25 * y);
        let a = [tilt(0.0, 0.0), tilt(2.0, 0.0), tilt(0.0, 2.0)];
        let b = [tilt(0.0, 0.0), tilt(2.0, 0.0), tilt(1.0, 1.0)];
        assert!(cross([0, 1, 2], [0, 1, 3], a, b));
        assert!(!cross(
            [0, 1, 2],
            [1, 0, 3],
            a,
            [b[1], b[0], tilt(1.0, -1.0)]
        ));
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
