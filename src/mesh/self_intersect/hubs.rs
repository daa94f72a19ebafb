//! Points where many triangles meet and no embedded fan ([`super::fans`]) settles their pairs:
//! a fan folded over, a vertex that is no disc, or several vertices at one point (two cones
//! apex to apex, which the reader keeps as two vertices). Every pair of such triangles overlaps
//! in its box, so the tree would offer them all; an angular sweep about the point offers only
//! the pairs that may cross, in `O(n log n)` for `n` triangles and the pairs it reports.
//!
//! Seen along a direction `d` from which no triangle of the point is edge-on, each triangle is
//! a wedge at the point, under half a turn wide, and the view is one-to-one on it. Two triangles
//! whose wedges meet only at the point (or along a shared ray) meet in space only where their
//! views do, at the point (or along edges on that ray): they do not cross. So only pairs whose
//! wedges overlap need the exact test. The sweep orders the wedges' ends by angle with exact
//! predicates only (the sign of `orient3d(w, p, q, c)` with `w = c + d` is the turn from `p`
//! to `q` seen along `d`), so no rounding hides an overlap.

use std::cmp::Ordering;

use glam::DVec3;
use rayon::prelude::*;

use super::exact::{cross, orient};
use super::{EXACT_TEST_COST, MAX_CROSSING_PAIRS};

/// What one sweep found: the crossing pairs, and how many pairs it tested.
type Swept = (Vec<(u32, u32)>, usize);

/// The point of a vertex whose pairs nothing settled.
pub(super) const NO_POINT: u32 = u32::MAX;

/// The points whose pairs of triangles need no test in the tree, and what settling them found.
pub(super) struct Settled {
    /// Per vertex: the point it lies at (named by one of its vertices) when every pair of
    /// triangles there is settled, else [`NO_POINT`]. Two triangles with a corner at one such
    /// point need no test.
    pub point: Vec<u32>,
    /// Whether some settled point holds more than one vertex.
    pub apart_vertices: bool,
    /// Per vertex: how many triangles meet at its settled point, else 0.
    pub weight: Vec<u32>,
    /// The crossing pairs the sweeps found.
    pub pairs: Vec<(u32, u32)>,
    /// Pairs the sweeps left to the exact test, and the work they cost in the units of
    /// [`super::pair_budget`].
    pub tested: usize,
    pub spent: usize,
}

/// Settles the points of `triangles` (those of `solid`, of non-zero area): a vertex whose fan
/// is embedded (`embedded`, from [`super::fans`]) on its own, and each point where vertices of
/// valence at least `min_valence` lie by a sweep ([`overlapping`]) and the exact test of the
/// pairs it leaves, as long as those fit in `budget`. A point that cannot be settled (seen
/// edge-on from every direction tried, or too many pairs) is left to the tree and its budget.
pub(super) fn settle(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    solid: &[u32],
    embedded: &[u32],
    min_valence: u32,
    budget: usize,
) -> Settled {
    let n = positions.len();
    let mut point = vec![NO_POINT; n];
    let mut weight = vec![0u32; n];
    for (v, &valence) in embedded.iter().enumerate() {
        if valence > 0 {
            point[v] = v as u32;
            weight[v] = valence;
        }
    }
    let mut valence = vec![0u32; n];
    for &t in solid {
        for v in triangles[t as usize] {
            valence[v as usize] += 1;
        }
    }
    let candidates: Vec<u32> = (0..n as u32)
        .filter(|&v| valence[v as usize] >= min_valence)
        .collect();
    // The points a sweep settles: several vertices at one place, or one whose fan is not
    // embedded. A lone embedded vertex is settled already.
    let hubs: Vec<Vec<u32>> = points(positions, &candidates)
        .into_iter()
        .filter(|g| g.len() > 1 || embedded[g[0] as usize] == 0)
        .collect();
    let mut hub_of = vec![NO_POINT; n];
    for (h, g) in hubs.iter().enumerate() {
        for &v in g {
            hub_of[v as usize] = h as u32;
        }
    }
    let mut fans: Vec<Vec<(u32, [DVec3; 2])>> = vec![Vec::new(); hubs.len()];
    for &t in solid {
        let tri = triangles[t as usize];
        for k in 0..3 {
            let h = hub_of[tri[k] as usize];
            if h != NO_POINT {
                let at = |j: usize| positions[tri[(k + j) % 3] as usize];
                fans[h as usize].push((t, [at(1), at(2)]));
            }
        }
    }
    // Each sweep may spend what is left of the budget once the others have spent as much.
    let limit = budget / hubs.len().max(1) / (1 + EXACT_TEST_COST);
    let swept: Vec<Option<Swept>> = hubs
        .par_iter()
        .zip(&fans)
        .map(|(g, fan)| {
            let c = positions[g[0] as usize];
            let candidates = overlapping(c, fan, limit)?;
            let crossing = candidates
                .iter()
                .copied()
                .filter(|&(t, u)| {
                    let (t, u) = (triangles[t as usize], triangles[u as usize]);
                    let at = |f: [u32; 3]| f.map(|i| positions[i as usize]);
                    cross(t, u, at(t), at(u))
                })
                .take(MAX_CROSSING_PAIRS)
                .collect();
            Some((crossing, candidates.len()))
        })
        .collect();
    let (mut pairs, mut tested, mut apart_vertices) = (Vec::new(), 0, false);
    for ((g, fan), result) in hubs.iter().zip(&fans).zip(swept) {
        let Some((crossing, count)) = result else {
            continue;
        };
        pairs.extend(crossing);
        tested += count;
        apart_vertices |= g.len() > 1;
        for &v in g {
            point[v as usize] = g[0];
            weight[v as usize] = fan.len() as u32;
        }
    }
    Settled {
        point,
        apart_vertices,
        weight,
        pairs,
        tested,
        spent: tested * (1 + EXACT_TEST_COST),
    }
}

/// The triangles at one point `c`: each by its index and its two other corners in winding
/// order (the triangle is `c, a, b`).
pub(super) type Fan = [(u32, [DVec3; 2])];

/// Groups the vertices of `candidates` by position: one list per point (vertex indices in
/// ascending order), in order of each point's first vertex. Equal coordinates only (the reader
/// keeps vertices apart at one point only where it split a pinched point); -0 is 0.
pub(super) fn points(positions: &[DVec3], candidates: &[u32]) -> Vec<Vec<u32>> {
    let key = |v: u32| {
        positions[v as usize]
            .to_array()
            .map(|x| (x + 0.0).to_bits())
    };
    let mut sorted = candidates.to_vec();
    sorted.sort_unstable_by_key(|&v| (key(v), v));
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for (k, &v) in sorted.iter().enumerate() {
        if k > 0 && key(sorted[k - 1]) == key(v) {
            groups.last_mut().expect("a group was started").push(v);
        } else {
            groups.push(vec![v]);
        }
    }
    groups.sort_unstable_by_key(|g| g[0]);
    groups
}

/// The pairs `(t, u)`, `t < u`, of the triangles of `fan` at point `c` whose wedges overlap
/// seen along some direction, each once: a superset of the crossing pairs among them. `None`
/// when no direction tried sees every triangle off its edge, or when there are more than
/// `limit` pairs (the caller's budget).
pub(super) fn overlapping(c: DVec3, fan: &Fan, limit: usize) -> Option<Vec<(u32, u32)>> {
    // The first view that leaves at most a pair a triangle, else the one that leaves fewest.
    let mut best: Option<Vec<(u32, u32)>> = None;
    for view in View::candidates(c, fan) {
        let most = best.as_ref().map_or(limit, |b| b.len().saturating_sub(1));
        let got = seen_from(&view, fan, most);
        if let Some(pairs) = got {
            let enough = pairs.len() <= fan.len();
            best = Some(pairs);
            if enough {
                break;
            }
        }
    }
    best
}

/// [`overlapping`] seen along one view, from which no triangle of `fan` is edge-on.
fn seen_from(view: &View, fan: &Fan, limit: usize) -> Option<Vec<(u32, u32)>> {
    // Each wedge from its first end to its second, turning the positive way.
    let wedges: Vec<[DVec3; 2]> = fan
        .iter()
        .map(|&(_, [a, b])| {
            if view.turn(a, b) > 0.0 {
                [a, b]
            } else {
                [b, a]
            }
        })
        .collect();
    let [r, q] = wedges[0];
    let angle = Angle { view, r, q };
    // Both ends of every wedge (end `e` of wedge `e / 2`), with its half turn, ranked by
    // angle; equal angles share a rank.
    let point = |e: u32| wedges[e as usize / 2][e as usize % 2];
    let mut ends: Vec<(u8, u32)> = (0..2 * wedges.len() as u32)
        .map(|e| (angle.half(point(e)), e))
        .collect();
    let compare = |x: &(u8, u32), y: &(u8, u32)| {
        x.0.cmp(&y.0)
            .then_with(|| angle.within_half(x.0, point(x.1), point(y.1)))
    };
    ends.sort_by(compare);
    let mut rank = vec![0usize; ends.len()];
    let mut k = 0;
    for i in 0..ends.len() {
        if i > 0 && compare(&ends[i - 1], &ends[i]) != Ordering::Equal {
            k += 1;
        }
        rank[ends[i].1 as usize] = k;
    }
    let turn = k + 1;
    // Unrolled: a wedge across angle 0 ends past `turn`; a second copy of each, a turn on,
    // meets the wedges it overlaps across angle 0.
    let mut spans: Vec<(usize, usize, u32)> = Vec::with_capacity(2 * wedges.len());
    for (w, _) in wedges.iter().enumerate() {
        let (s, mut e) = (rank[2 * w], rank[2 * w + 1]);
        if e <= s {
            e += turn;
        }
        spans.push((s, e, w as u32));
        spans.push((s + turn, e + turn, w as u32));
    }
    spans.sort_unstable();
    let mut active: Vec<(usize, u32)> = Vec::new();
    let mut pairs = Vec::new();
    for &(s, e, w) in &spans {
        // Spans that started no later and end past this one's start overlap it beyond the
        // point; the others are done.
        active.retain(|&(end, _)| end > s);
        for &(_, x) in &active {
            if x != w {
                let (t, u) = (fan[w as usize].0, fan[x as usize].0);
                pairs.push((t.min(u), t.max(u)));
                if pairs.len() > 2 * limit {
                    return None;
                }
            }
        }
        active.push((e, w));
    }
    pairs.sort_unstable();
    pairs.dedup();
    (pairs.len() <= limit).then_some(pairs)
}

/// A direction to look along, from `c` towards `w`.
struct View {
    c: DVec3,
    w: DVec3,
}

impl View {
    /// The directions to try, each one from which no triangle of `fan` is seen edge-on: the
    /// sum of the triangles' unit normals (a fan's outward direction, as in [`super::fans`]),
    /// the same with each normal turned to agree with the first (two fans back to back, whose
    /// normals sum to about nothing, give their common axis), the axes and a skew direction.
    fn candidates(c: DVec3, fan: &Fan) -> Vec<View> {
        let normal = |[a, b]: [DVec3; 2]| (a - c).cross(b - c).normalize_or_zero();
        let first = fan.first().map_or(DVec3::ZERO, |&(_, e)| normal(e));
        let (mut sum, mut aligned) = (DVec3::ZERO, DVec3::ZERO);
        let mut reach = c.abs().max_element();
        for &(_, [a, b]) in fan {
            let n = normal([a, b]);
            sum += n;
            aligned += if n.dot(first) < 0.0 { -n } else { n };
            reach = reach.max((a - c).abs().max_element());
        }
        if !(reach.is_finite() && reach > 0.0) {
            return Vec::new();
        }
        // A sum that nearly cancels is a rounding residue, no direction worth a sort.
        let weak = 1e-3 * fan.len() as f64;
        [
            sum,
            aligned,
            DVec3::Z,
            DVec3::X,
            DVec3::Y,
            DVec3::new(0.6, 0.7, 0.39),
        ]
        .into_iter()
        .enumerate()
        .filter(|&(k, d)| k > 1 || d.length() > weak)
        .filter_map(|(_, d)| d.try_normalize())
        .map(|d| View {
            c,
            // Far enough from `c` to stay apart from it after rounding; any such point
            // gives a direction, and the tests on it are exact.
            w: c + d * reach,
        })
        .filter(|v| v.w.is_finite() && fan.iter().all(|&(_, [a, b])| v.turn(a, b) != 0.0))
        .collect()
    }

    /// The turn from `p` to `q` about `c` seen along the view: positive, negative or zero
    /// (the same or opposite directions), exactly.
    fn turn(&self, p: DVec3, q: DVec3) -> f64 {
        orient([self.w, p, q], self.c)
    }
}

/// Angles about the view's axis, measured from the direction of `r`; `q` is any point a
/// positive turn from `r`, which tells the direction of `r` from its opposite.
struct Angle<'a> {
    view: &'a View,
    r: DVec3,
    q: DVec3,
}

impl Angle<'_> {
    /// 0 at the angle of `r`, 1 within the half turn after it, 2 opposite it, 3 within the half
    /// turn after that. No corner is seen on the axis (its triangle would be edge-on).
    fn half(&self, p: DVec3) -> u8 {
        let s = self.view.turn(self.r, p);
        if s > 0.0 {
            1
        } else if s < 0.0 {
            3
        } else if self.view.turn(self.q, p) < 0.0 {
            // Seen from `q`, turning back to `p` as to `r`: `p` lies along `r`.
            0
        } else {
            2
        }
    }

    /// The order of the angles of `p` and `y`, both in half turn `half`: the turn between
    /// them says, within an open half turn; along `r` or opposite it, all are one angle.
    fn within_half(&self, half: u8, p: DVec3, y: DVec3) -> Ordering {
        if half.is_multiple_of(2) {
            return Ordering::Equal;
        }
        let s = self.view.turn(p, y);
        if s > 0.0 {
            Ordering::Less
        } else if s < 0.0 {
            Ordering::Greater
        } else {
            Ordering::Equal
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fan_of(ring: &[DVec3]) -> Vec<(u32, [DVec3; 2])> {
        (0..ring.len())
            .map(|i| (i as u32, [ring[i], ring[(i + 1) % ring.len()]]))
            .collect()
    }

    fn ring(n: usize, z: f64) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                DVec3::new(a.cos(), a.sin(), z)
            })
            .collect()
    }

    #[test]
    fn an_embedded_fan_has_no_overlapping_wedges() {
        let c = DVec3::new(0.0, 0.0, 1.0);
        let fan = fan_of(&ring(1000, 0.0));
        assert_eq!(overlapping(c, &fan, 10), Some(vec![]));
        // Wound the other way round: the same.
        let mut back = ring(1000, 0.0);
        back.reverse();
        assert_eq!(overlapping(c, &fan_of(&back), 10), Some(vec![]));
    }

    #[test]
    fn a_folded_fan_overlaps_only_near_its_fold() {
        let c = DVec3::ZERO;
        let mut r = ring(1000, 0.0);
        // Ring point 10 moved past 12: wedges 9, 10, 11 and 12 overlap one another.
        let a = std::f64::consts::TAU * 12.5 / 1000.0;
        r[10] = DVec3::new(0.9 * a.cos(), 0.9 * a.sin(), 0.0);
        let pairs = overlapping(c, &fan_of(&r), 100).unwrap();
        assert!(!pairs.is_empty() && pairs.len() < 10, "{pairs:?}");
        assert!(
            pairs
                .iter()
                .all(|&(t, u)| (9..=12).contains(&t) && (9..=12).contains(&u))
        );
        // More pairs than the limit: none.
        assert_eq!(overlapping(c, &fan_of(&r), 1), None);
    }

    #[test]
    fn two_fans_back_to_back_overlap_wedge_by_wedge() {
        // Two cones' apex fans at one point, one up and one down: their normals sum to nothing,
        // and seen along an axis each wedge of one overlaps the one or two of the other below.
        let c = DVec3::ZERO;
        let (up, down) = (ring(500, -1.0), ring(500, 1.0));
        let mut fan = fan_of(&up);
        let mut rev = down.clone();
        rev.reverse();
        fan.extend(fan_of(&rev).into_iter().map(|(t, e)| (t + 500, e)));
        let pairs = overlapping(c, &fan, 10_000).unwrap();
        assert!(pairs.len() >= 500 && pairs.len() <= 1500, "{}", pairs.len());
        assert!(pairs.iter().all(|&(t, u)| t < 500 && u >= 500));
        // Every triangle seen edge-on from every direction tried: none.
        let flat = vec![(0, [DVec3::X, DVec3::new(2.0, 0.0, 0.0)])];
        assert_eq!(overlapping(c, &flat, 10), None);
    }

    #[test]
    fn points_group_vertices_at_one_position() {
        let p = [
            DVec3::X,
            DVec3::Y,
            DVec3::X,
            DVec3::Z,
            DVec3::new(-0.0, 1.0, 0.0),
        ];
        assert_eq!(
            points(&p, &[0, 1, 2, 3, 4]),
            vec![vec![0, 2], vec![1, 4], vec![3]]
        );
    }
}
