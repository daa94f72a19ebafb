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
//!
//! What none of these prunes — a fan folded through itself (not embedded, so its triangles are
//! tested pair by pair), slivers stacked within rounding of one another, two fans meeting point
//! to point — is bounded by a budget of work, linear in the triangles
//! ([`pair_budget`]): past it the search stops undecided, and the reader refuses the mesh
//! saying so ([`crate::MeshDefect::CrossingCheckOverBudget`]) unless it found crossings first.

mod apart;
mod exact;
mod fans;

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::bvh::{Bvh, NO_GROUP};
use crate::geom::{Aabb, is_zero_area};

#[cfg(test)]
use exact::coplanar_overlap;
use exact::{cross, orient};

/// At most this many crossing pairs are looked for: enough to refuse a mesh and to say how
/// badly it crosses, while a hostile file (one triangle repeated 16,384 times has 1.3·10⁸
/// pairs) stops here instead of spending time and memory quadratic in its size.
pub const MAX_CROSSING_PAIRS: usize = 100_000;

/// The work the search may do for a mesh of `triangles`: [`PAIR_BUDGET_PER_TRIANGLE`] per
/// triangle and [`PAIR_BUDGET_BASE`] more, in units of one candidate pair (a pair the tree
/// offers, looked at by its boxes); a pair decided by the exact test costs [`EXACT_TEST_COST`]
/// more (near a shared point the adaptive predicates go exact: 1–3 µs a pair).
pub(crate) fn pair_budget(triangles: usize) -> usize {
    PAIR_BUDGET_BASE.saturating_add(triangles.saturating_mul(PAIR_BUDGET_PER_TRIANGLE))
}

/// Work per triangle in the budget of the check for crossing triangles (see
/// [`Mesh::crossing_triangle_pairs`](crate::Mesh::crossing_triangle_pairs)), in units of one
/// candidate pair (an exact test costs 8 more). Valid meshes take 27–55: the shared models
/// (rocker-arm 28, fandisk 31, stanford-bunny 34 candidates a triangle, under 2 exact tests), a UV
/// sphere of 261,120 triangles 54 (40 candidates, 1.8 exact tests).
pub const PAIR_BUDGET_PER_TRIANGLE: usize = 128;

/// Work any mesh may do in that budget beside [`PAIR_BUDGET_PER_TRIANGLE`], so small crowded
/// meshes are still decided (a
/// 1,442-triangle file of the shared models takes 500,000: 128 candidates and 27 exact tests a
/// triangle).
pub const PAIR_BUDGET_BASE: usize = 1 << 21;

/// What an exact test adds to a candidate pair's cost in [`pair_budget`].
const EXACT_TEST_COST: usize = 8;

/// Triangles around a vertex of at least this valence whose fan is embedded are grouped in the
/// tree (below it a vertex's few pairs cost less than the lost spatial order of the tree).
const GROUP_VALENCE: u32 = 32;

/// The crossing pairs `(t, u)`, `t < u`, of the triangles of a mesh, in order; at most
/// [`MAX_CROSSING_PAIRS`] of them (which ones is then not fixed), and `complete` false where
/// the search stopped at its [`pair_budget`] (the pairs found so far cross; others may too).
/// Triangles of zero area (`geom::is_zero_area`, as the import drops them) have no interior to
/// cross and are left out, so a soup of degenerate triangles whose boxes all overlap costs no
/// pairwise test.
pub(crate) fn crossing_pairs(positions: &[DVec3], triangles: &[[u32; 3]]) -> Search {
    search(positions, triangles)
}

/// What [`search`] found, and how much work it took (the counts bound the work in tests).
pub(crate) struct Search {
    pub pairs: Vec<(u32, u32)>,
    /// False when the search stopped at its [`pair_budget`] before looking at every pair.
    pub complete: bool,
    /// Work done, in the units of [`pair_budget`].
    #[cfg_attr(not(test), allow(dead_code))]
    spent: usize,
    /// Pairs the tree offered (items in leaves a query entered).
    pub offered: usize,
    /// Pairs decided by the exact test [`cross`].
    #[cfg_attr(not(test), allow(dead_code))]
    tested: usize,
}

/// How much work a query counts before it adds it to the shared count and looks at the budget.
const BUDGET_STEP: usize = 4096;

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
    let budget = pair_budget(triangles.len());
    let (spent, over) = (AtomicUsize::new(0), AtomicBool::new(false));
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
            if spent.load(Ordering::Relaxed) > budget {
                over.store(true, Ordering::Relaxed);
                return found;
            }
            let (tri, b, tc, thin_t) = (triangles[t], boxes[t], corners(t), thin[t]);
            let (mut offers, mut tests, mut work) = (0, 0, 0);
            bvh.visit_skipping(
                |other| !fans.queries(own, other),
                |node| node.overlaps(&b, 0.0) && !(thin_t && apart::apart(tc, node)),
                |k| {
                    offers += 1;
                    work += 1;
                    // Every step, this query's work joins the shared count, which stops all
                    // queries once it passes the budget.
                    if work >= BUDGET_STEP {
                        let total = spent.fetch_add(work, Ordering::Relaxed) + work;
                        work = 0;
                        if total > budget {
                            over.store(true, Ordering::Relaxed);
                            return true;
                        }
                    }
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
                    work += EXACT_TEST_COST;
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
            spent.fetch_add(work, Ordering::Relaxed);
            tested.fetch_add(tests, Ordering::Relaxed);
            found
        })
        .collect();
    pairs.sort_unstable();
    pairs.truncate(MAX_CROSSING_PAIRS);
    Search {
        complete: !over.into_inner() || pairs.len() >= MAX_CROSSING_PAIRS,
        spent: spent.into_inner(),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The pairs found, for the tests that look only at them.
    fn crossing_pairs(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<(u32, u32)> {
        search(positions, triangles).pairs
    }

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
        assert!(found.pairs.is_empty() && found.complete);
        let n = n as usize;
        assert!(found.offered < 16 * n, "{}", found.offered);
        assert!(found.tested < 4 * n, "{}", found.tested);
    }

    /// A cone with one ring vertex folded over in its base (the base centre's fan no longer
    /// embedded, so its triangles are tested pair by pair).
    fn folded_cone(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let (mut p, t) = cone(n, 1.0);
        p[2 + 10] = ring_point(n, 12.5, 0.9);
        (p, t)
    }

    /// Two cones of `n` sides touching apex to apex (separate vertices at one point): every
    /// triangle of either apex's fan meets every one of the other's, at that point.
    fn hourglass(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let (mut p, mut t) = cone(n, 1.0);
        let (q, u) = cone(n, 1.0);
        let m = p.len() as u32;
        // Mirrored through z = 1 and y = 0: turned over, still facing out.
        p.extend(q.into_iter().map(|v| DVec3::new(v.x, -v.y, 2.0 - v.z)));
        t.extend(u.into_iter().map(|f| f.map(|i| i + m)));
        (p, t)
    }

    /// `n` thin tetrahedra along one diagonal, stacked a thousandth of their thickness apart:
    /// no vertex shared, every box overlapping every other, no two crossing.
    fn stacked_slivers(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let h = 1e-3 / f64::from(n);
        let mut p = Vec::new();
        let mut t = Vec::new();
        for i in 0..n {
            let z = f64::from(i) * h;
            let b = p.len() as u32;
            p.extend([
                DVec3::new(0.0, 0.0, z),
                DVec3::new(1.0, 1.0, z + 1.0),
                DVec3::new(0.5, 0.5 + 1e-3, z + 0.5),
                DVec3::new(0.5, 0.5, z + 0.5 + 0.25 * h),
            ]);
            t.extend([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]].map(|f| f.map(|k| b + k)));
        }
        (p, t)
    }

    /// The crowded inputs nothing prunes cost their search at most its budget (they took
    /// 27·10⁶, 9·10⁶ and 8·10⁶ candidate pairs at 6,000, 12,000 and 3,000 triangles, 10–18 s;
    /// at 20,000 sides the folded cone would take 10⁹): each stops there, undecided unless it
    /// found a crossing first. Counted, not timed.
    #[test]
    fn crowded_triangles_stop_at_the_pair_budget() {
        let slack = 2 * (rayon::current_num_threads() + 1) * BUDGET_STEP;
        for (what, (p, t)) in [
            ("folded cone", folded_cone(20_000)),
            ("hourglass", hourglass(20_000)),
            ("stacked slivers", stacked_slivers(5_000)),
        ] {
            let found = search(&p, &t);
            let budget = pair_budget(t.len());
            assert!(!found.complete, "{what}");
            assert!(found.spent <= budget + slack, "{what}: {}", found.spent);
            assert!(found.spent > budget, "{what}: {}", found.spent);
            if what != "folded cone" {
                assert!(found.pairs.is_empty(), "{what}: {:?}", found.pairs);
            }
        }
        // Small ones finish within the budget's base and are decided.
        let (p, t) = hourglass(300);
        let found = search(&p, &t);
        assert!(found.complete && found.pairs.is_empty());
        let (p, t) = folded_cone(300);
        assert!(search(&p, &t).complete);
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
