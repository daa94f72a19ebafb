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
//! - a point where vertices of valence at least [`GROUP_VALENCE`] lie, several at one place or
//!   one whose fan is not embedded, is settled by a sweep about it ([`hubs`], `O(n log n)`):
//!   only pairs whose wedges overlap seen along one direction take the exact test;
//! - a triangle's box takes part in the tree in the group of its corner of highest valence
//!   (at least [`GROUP_VALENCE`]) at a settled point, and a query passes over its own group's
//!   subtrees without entering them, and over another group's where the pairs between the two
//!   are better found from that group's side ([`Fans::queries`]);
//! - a thin triangle (a sliver of such a fan) is tested against the boxes the tree offers
//!   ([`apart`]), not only its own box, so a cone's apex fan does not meet every triangle of its
//!   base's fan.
//!
//! What none of these prunes — slivers stacked within rounding of one another, a point whose
//! wedges all overlap from every direction tried, the slivers of one fan each meeting thousands
//! of another fan's boxes — is bounded by a budget of work, linear in the triangles
//! ([`pair_budget`]): past it the search stops undecided, and the reader refuses the mesh
//! saying so ([`crate::MeshDefect::CrossingCheckOverBudget`]) unless it found crossings first.

mod apart;
mod exact;
mod fans;
mod hubs;

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::bvh::{Bvh, NO_GROUP};
use crate::geom::{Aabb, is_zero_area};
use crate::mesh::repair::Links;

#[cfg(test)]
use exact::coplanar_overlap;
use exact::{cross, orient};
use hubs::{NO_POINT, Settled};

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
/// candidate pair (an exact test costs 24 more). Valid meshes take 27–90: the shared models
/// (rocker-arm 28, fandisk 31, stanford-bunny 34 candidates a triangle, under 2 exact tests), a UV
/// sphere of 261,120 triangles 85 (40 candidates, 1.8 exact tests).
pub const PAIR_BUDGET_PER_TRIANGLE: usize = 128;

/// Work any mesh may do in that budget beside [`PAIR_BUDGET_PER_TRIANGLE`], so small crowded
/// meshes are still decided (a
/// 1,442-triangle file of the shared models takes 1.2·10⁶: 128 candidates and 27 exact tests a
/// triangle).
pub const PAIR_BUDGET_BASE: usize = 1 << 21;

/// What an exact test adds to a candidate pair's cost in [`pair_budget`]. Measured by
/// instruction counts: a candidate pair costs about 230 instructions with its share of the walk
/// (stanford-bunny), an exact test as many where the filters decide it, but about 5,500 where
/// the predicates go adaptive (the folded fan's coplanar pairs), which is what crowded hostile
/// input brings; so the budget bounds time by the costly kind.
const EXACT_TEST_COST: usize = 24;

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
    /// The links of the mesh's vertices, where the triangles around every vertex a triangle
    /// uses form one closed disc ([`Links::disc`]).
    pub discs: Option<Links>,
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
    let (embedded, discs) = fans::embedded_valences(positions, triangles);
    let budget = pair_budget(triangles.len());
    let settled = hubs::settle(
        positions,
        triangles,
        &solid,
        &embedded,
        GROUP_VALENCE,
        budget,
    );
    let fans = Fans::new(positions, &settled, triangles, &solid, &boxes);
    let solid_boxes: Vec<Aabb> = solid.iter().map(|&t| boxes[t as usize]).collect();
    let thin: Vec<bool> = (0..triangles.len())
        .map(|t| apart::thin(corners(t)))
        .collect();
    let bvh = Bvh::build_grouped(&solid_boxes, &fans.of_solid);
    // Two triangles with a corner at one settled point (an embedded fan's vertex, or a point
    // a sweep settled) need no test: they do not cross, or the sweep tested them.
    // Where every settled point is one vertex, sharing it is sharing that index (three
    // compares, no loads: this runs for every pair the tree offers).
    let (point, apart_vertices) = (&settled.point, settled.apart_vertices);
    let share_settled = |t: [u32; 3], u: [u32; 3]| {
        t.iter().any(|&v| {
            let p = point[v as usize];
            p != NO_POINT
                && if apart_vertices {
                    u.iter().any(|&x| point[x as usize] == p)
                } else {
                    u.contains(&v)
                }
        })
    };
    let found_so_far = AtomicUsize::new(settled.pairs.len());
    let (offered, tested) = (AtomicUsize::new(0), AtomicUsize::new(settled.tested));
    let (spent, over) = (AtomicUsize::new(settled.spent), AtomicBool::new(false));
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
                |other| !fans.queries(own, other) || fans.beside(other, tc),
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
                        || share_settled(tri, triangles[u])
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
    pairs.extend(settled.pairs);
    pairs.sort_unstable();
    // A pair at two settled points was tested by both sweeps.
    pairs.dedup();
    pairs.truncate(MAX_CROSSING_PAIRS);
    Search {
        complete: !over.into_inner() || pairs.len() >= MAX_CROSSING_PAIRS,
        discs,
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
    /// For a group whose triangles all lie in one plane (a cap's or a cone base's fan), three
    /// points of that plane.
    plane: Vec<Option<[DVec3; 3]>>,
}

impl Fans {
    fn new(
        positions: &[DVec3],
        settled: &Settled,
        triangles: &[[u32; 3]],
        solid: &[u32],
        boxes: &[Aabb],
    ) -> Fans {
        let (point, weight) = (&settled.point, &settled.weight);
        let mut number = vec![NO_GROUP; positions.len()];
        let mut centre = Vec::new();
        for (v, &w) in weight.iter().enumerate() {
            if w >= GROUP_VALENCE && point[v] == v as u32 {
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
                    .filter(|&v| point[v as usize] != NO_POINT)
                    .map(|v| point[v as usize])
                    .filter(|&p| number[p as usize] != NO_GROUP)
                    .max_by_key(|&p| (weight[p as usize], std::cmp::Reverse(p)));
                let Some(p) = best else {
                    return NO_GROUP;
                };
                let g = number[p as usize];
                reach[g as usize] = reach[g as usize].union(&boxes[t as usize]);
                g
            })
            .collect();
        // A group is flat when every one of its triangles lies exactly in its first one's plane.
        let mut plane: Vec<Option<[DVec3; 3]>> = vec![None; centre.len()];
        let mut flat = vec![true; centre.len()];
        for (&t, &g) in solid.iter().zip(&of_solid) {
            if g == NO_GROUP || !flat[g as usize] {
                continue;
            }
            let c = triangles[t as usize].map(|i| positions[i as usize]);
            match plane[g as usize] {
                None => plane[g as usize] = Some(c),
                Some(p) => flat[g as usize] = c.iter().all(|&q| orient(p, q) == 0.0),
            }
        }
        for (p, flat) in plane.iter_mut().zip(flat) {
            if !flat {
                *p = None;
            }
        }
        Fans {
            of_solid,
            centre,
            reach,
            plane,
        }
    }

    /// Whether triangle `t` cannot cross any triangle of group `g` because the group is flat and
    /// `t` lies on one closed side of its plane, not in it: `t`'s interior is then strictly off
    /// the plane and its edges at most touch it, so no edge of either passes through the other
    /// and they are not coplanar. (A cone's apex fan over its flat base fan, whose slivers meet
    /// the boxes of many of the base's triangles, needs no pair tested.)
    // Kept out of line: inlined, it grew the tree walk's closures enough to slow the walk of
    // every mesh by 3 % (callgrind, stanford-bunny), groups or not.
    #[inline(never)]
    fn beside(&self, g: u32, t: [DVec3; 3]) -> bool {
        let Some(Some(p)) = self.plane.get(g as usize) else {
            return false;
        };
        let s = t.map(|q| orient(*p, q));
        (s.iter().all(|&x| x >= 0.0) || s.iter().all(|&x| x <= 0.0)) && s.iter().any(|&x| x != 0.0)
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
mod tests;
