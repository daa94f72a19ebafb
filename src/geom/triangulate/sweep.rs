//! Triangulation of a region by a sweep into monotone pieces, making no Delaunay decision.
//!
//! Why: where a region's corners lie on a grid (a Menger sponge's faces, a boolean of boxes) or
//! on circles (a face drilled with round holes), many four of them are cocircular, and a
//! Delaunay triangulation settles each such in-circle test in exact arithmetic to the last
//! stage of the adaptive predicate: most of `to_mesh` on a Menger sponge of depth 3 or a block
//! less 100 cylinders. Nothing downstream needs the Delaunay property: the repair needs a
//! triangulation of the region on its own corners with no flat triangle and no sliver, and the
//! sweep makes no triangle thinner than [`super::monotone`]'s sliver bound (a region it would
//! have to cut into one takes the Delaunay path).
//!
//! The sweep runs on the corners snapped to a fine grid; corner types, the sweep's status and
//! the pieces' ears use the exact orientation test. The input is checked to be a valid region
//! (simple loops that neither touch nor cross, one outer loop) and the output to be a
//! triangulation of it (every triangle turning left and no sliver, every boundary edge used
//! once, every other edge once each way), both on the corners as they are; anything else gives
//! `None` and the caller takes the Delaunay path.

use spade::Point2;

use super::monotone::{covers, pieces, triangulate_monotone};

/// The grid the sweep's corners are snapped to, for points scaled to at most 1: 2⁻³², far above
/// the rounding that puts a grid's corners a few units off their rows.
const SNAP: f64 = 1.0 / 4_294_967_296.0;

/// The triangles (counter-clockwise, as local vertex indices) of the region left of the
/// directed boundary edges `constraints` over `points`, when the boundary is one
/// counter-clockwise loop with clockwise holes inside it, no two loops touching. `None`
/// otherwise, or where the checks of the result fail.
pub(super) fn triangulate(
    points: &[Point2<f64>],
    constraints: &[[usize; 2]],
) -> Option<Vec<[usize; 3]>> {
    let n = points.len();
    if constraints.len() != n || n < 4 {
        return None;
    }
    let mut next = vec![usize::MAX; n];
    let mut prev = vec![usize::MAX; n];
    for &[a, b] in constraints {
        let (p, q) = (points[a], points[b]);
        if next[a] != usize::MAX || prev[b] != usize::MAX || p == q {
            return None;
        }
        next[a] = b;
        prev[b] = a;
    }
    if !edges_apart(points, constraints) {
        return None;
    }
    let (loops, outer) = loops_and_outer(points, &next, &prev)?;
    if outer != 1 {
        return None;
    }
    let expected = n + 2 * loops - 4;
    // The sweep runs on the corners snapped to a grid: where the edges run along the axes
    // (to a rounding), corners a rounding off one row are then taken in order along it, and
    // no diagonal runs a rounding away from a row's edges (a sliver). Everything else is
    // decided on the corners as they are, and checked there.
    let snapped: Vec<Point2<f64>> = points
        .iter()
        .map(|p| Point2::new(snap(p.x), snap(p.y)))
        .collect();
    let order = sweep_order(&snapped);
    let mut rank = vec![0usize; n];
    for (k, &v) in order.iter().enumerate() {
        rank[v] = k;
    }
    let diagonals = monotone_diagonals(&snapped, &next, &prev, &order, &rank)?;
    let mut tris = Vec::with_capacity(expected);
    for piece in pieces(points, &next, &diagonals)? {
        triangulate_monotone(points, &piece, &rank, &mut tris)?;
    }
    (tris.len() == expected && covers(&tris, &next)).then_some(tris)
}

/// `x` (at most 1 in magnitude) rounded to a multiple of [`SNAP`], exactly. `+ 0.0` turns a
/// negative zero into zero: the sweep order sorts by `total_cmp`, which puts −0 before +0.
fn snap(x: f64) -> f64 {
    (x / SNAP).round() * SNAP + 0.0
}

/// The exact orientation of `a b c`: positive when they turn left.
pub(super) fn orient(points: &[Point2<f64>], a: usize, b: usize, c: usize) -> f64 {
    let p = |k: usize| robust::Coord {
        x: points[k].x,
        y: points[k].y,
    };
    robust::orient2d(p(a), p(b), p(c))
}

/// True when no two edges meet but consecutive ones, at their shared corner. Edges sorted by
/// their least x are compared only with those whose boxes overlap, then by exact orientation.
fn edges_apart(points: &[Point2<f64>], constraints: &[[usize; 2]]) -> bool {
    struct Span {
        x: [f64; 2],
        y: [f64; 2],
        a: usize,
        b: usize,
    }
    let mut spans: Vec<Span> = constraints
        .iter()
        .map(|&[a, b]| {
            let (p, q) = (points[a], points[b]);
            Span {
                x: [p.x.min(q.x), p.x.max(q.x)],
                y: [p.y.min(q.y), p.y.max(q.y)],
                a,
                b,
            }
        })
        .collect();
    spans.sort_unstable_by(|s, t| s.x[0].total_cmp(&t.x[0]));
    for (i, s) in spans.iter().enumerate() {
        for t in spans[i + 1..].iter().take_while(|t| t.x[0] <= s.x[1]) {
            if t.y[0] > s.y[1] || s.y[0] > t.y[1] {
                continue;
            }
            // Consecutive edges meet only at their corner unless the second turns back along
            // the first (or the two make a loop of their own).
            let meet = if s.b == t.a && t.b != s.a {
                Some((s.a, s.b, t.b))
            } else if t.b == s.a && s.b != t.a {
                Some((t.a, t.b, s.b))
            } else if s.b == t.a || t.b == s.a {
                return false;
            } else {
                None
            };
            let apart = match meet {
                Some((u, v, w)) => orient(points, u, v, w) != 0.0 || !same_way(points, v, u, w),
                None => !segments_meet(points, s.a, s.b, t.a, t.b),
            };
            if !apart {
                return false;
            }
        }
    }
    true
}

/// For `a` and `c` on one line through `b`, whether they lie the same way from it.
pub(super) fn same_way(points: &[Point2<f64>], b: usize, a: usize, c: usize) -> bool {
    let (pa, pb, pc) = (points[a], points[b], points[c]);
    let side = |p: f64, q: f64| (p > q) as i8 - (p < q) as i8;
    side(pa.x, pb.x) * side(pc.x, pb.x) > 0 || side(pa.y, pb.y) * side(pc.y, pb.y) > 0
}

/// Whether the closed segments `ab` and `cd` (boxes known to overlap) share a point.
fn segments_meet(points: &[Point2<f64>], a: usize, b: usize, c: usize, d: usize) -> bool {
    let (o1, o2) = (orient(points, a, b, c), orient(points, a, b, d));
    let (o3, o4) = (orient(points, c, d, a), orient(points, c, d, b));
    if o1 == 0.0 && o2 == 0.0 {
        // On one line, with overlapping boxes.
        return true;
    }
    o1.signum() * o2.signum() <= 0.0 && o3.signum() * o4.signum() <= 0.0
}

/// The number of loops and of counter-clockwise ones among them. A loop's lowest (then
/// leftmost) corner is convex, so the turn there gives the loop's orientation. `None` where
/// that corner does not turn (it cannot on edges checked apart).
fn loops_and_outer(
    points: &[Point2<f64>],
    next: &[usize],
    prev: &[usize],
) -> Option<(usize, usize)> {
    let lower = |a: usize, b: usize| {
        let (p, q) = (points[a], points[b]);
        p.y < q.y || (p.y == q.y && p.x < q.x)
    };
    let mut seen = vec![false; points.len()];
    let (mut loops, mut outer) = (0, 0);
    for start in 0..points.len() {
        if seen[start] {
            continue;
        }
        loops += 1;
        let (mut at, mut low) = (start, start);
        while !seen[at] {
            seen[at] = true;
            if lower(at, low) {
                low = at;
            }
            at = next[at];
        }
        let turn = orient(points, prev[low], low, next[low]);
        if turn == 0.0 {
            return None;
        }
        outer += usize::from(turn > 0.0);
    }
    Some((loops, outer))
}

/// Corners from the top of the sweep down: higher y first, then lower x (as if the plane were
/// sheared by a hair so that no two corners tie; a shear keeps lines straight, so it changes no
/// turn).
fn sweep_order(points: &[Point2<f64>]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_unstable_by(|&a, &b| {
        let (p, q) = (points[a], points[b]);
        q.y.total_cmp(&p.y).then(p.x.total_cmp(&q.x))
    });
    order
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Corner {
    Start,
    Split,
    End,
    Merge,
    /// On a chain going down: the region lies to its right.
    Down,
    /// On a chain going up: the region lies to its left.
    Up,
}

/// The diagonals that cut the region into pieces monotone along the sweep (de Berg et al.,
/// *Computational Geometry*, ch. 3). The sweep's status holds the edges with the region to
/// their east, placed by exact orientation tests.
fn monotone_diagonals(
    points: &[Point2<f64>],
    next: &[usize],
    prev: &[usize],
    order: &[usize],
    rank: &[usize],
) -> Option<Vec<(usize, usize)>> {
    let n = points.len();
    let mut kind = vec![Corner::Up; n];
    for v in 0..n {
        let (u, w) = (prev[v], next[v]);
        let (u_below, w_below) = (rank[u] > rank[v], rank[w] > rank[v]);
        kind[v] = match (u_below, w_below) {
            (true, false) => Corner::Up,
            (false, true) => Corner::Down,
            _ => {
                let turn = orient(points, u, v, w);
                if turn == 0.0 {
                    return None;
                }
                match (u_below, turn > 0.0) {
                    (true, true) => Corner::Start,
                    (true, false) => Corner::Split,
                    (false, true) => Corner::End,
                    (false, false) => Corner::Merge,
                }
            }
        };
    }
    // Status: the edges (by first corner) from west to east; the helper of each edge by its
    // first corner. Status edges never meet and all cross the sweep line, so "a corner lies
    // east of the edge" holds for a prefix of the status.
    let mut status: Vec<usize> = Vec::new();
    let mut helper = vec![usize::MAX; n];
    let mut diagonals = Vec::new();
    // A downward edge has the corners east of it on its left.
    let west_of = |e: usize, v: usize| orient(points, e, next[e], v) > 0.0;
    let insert = |status: &mut Vec<usize>, e: usize| {
        let at = status.partition_point(|&s| west_of(s, e));
        status.insert(at, e);
    };
    // The edge ending at `v`: the first one `v` does not lie strictly east of.
    let remove = |status: &mut Vec<usize>, e: usize, v: usize| -> Option<()> {
        let at = status.partition_point(|&s| west_of(s, v));
        (status.get(at) == Some(&e)).then(|| {
            status.remove(at);
        })
    };
    // The status edge directly west of `v`, checked to span its place in the order.
    let left_of = |status: &[usize], v: usize| -> Option<usize> {
        let at = status.partition_point(|&s| west_of(s, v));
        let e = *status.get(at.checked_sub(1)?)?;
        (rank[e] < rank[v] && rank[next[e]] > rank[v]).then_some(e)
    };
    for &v in order {
        match kind[v] {
            Corner::Start => {
                insert(&mut status, v);
                helper[v] = v;
            }
            Corner::End | Corner::Merge | Corner::Down => {
                let e = prev[v];
                if *kind.get(*helper.get(e)?)? == Corner::Merge {
                    diagonals.push((v, helper[e]));
                }
                remove(&mut status, e, v)?;
                if kind[v] == Corner::Down {
                    insert(&mut status, v);
                    helper[v] = v;
                } else if kind[v] == Corner::Merge {
                    let l = left_of(&status, v)?;
                    if kind[helper[l]] == Corner::Merge {
                        diagonals.push((v, helper[l]));
                    }
                    helper[l] = v;
                }
            }
            Corner::Split => {
                let l = left_of(&status, v)?;
                diagonals.push((v, helper[l]));
                helper[l] = v;
                insert(&mut status, v);
                helper[v] = v;
            }
            Corner::Up => {
                let l = left_of(&status, v)?;
                if kind[helper[l]] == Corner::Merge {
                    diagonals.push((v, helper[l]));
                }
                helper[l] = v;
            }
        }
    }
    Some(diagonals)
}

#[cfg(test)]
mod tests {
    use super::super::monotone::fat;
    use super::*;

    /// Points and directed edges of loops given as corner lists (outer counter-clockwise,
    /// holes clockwise).
    fn region(loops: &[&[(f64, f64)]]) -> (Vec<Point2<f64>>, Vec<[usize; 2]>) {
        let mut points = Vec::new();
        let mut edges = Vec::new();
        for ring in loops {
            let first = points.len();
            for (k, &(x, y)) in ring.iter().enumerate() {
                points.push(Point2::new(x, y));
                edges.push([first + k, first + (k + 1) % ring.len()]);
            }
        }
        (points, edges)
    }

    fn area(points: &[Point2<f64>], tris: &[[usize; 3]]) -> f64 {
        tris.iter()
            .map(|t| 0.5 * orient(points, t[0], t[1], t[2]))
            .sum()
    }

    /// A square with three square holes on one row, one of them a rounding below the row, and
    /// corners part-way along the outer edges: `V + 2H − 2` triangles, none a sliver, covering
    /// the square less the holes.
    #[test]
    fn grid_face_with_holes_on_a_row() {
        let low = 0.75 - 2.0 * f64::EPSILON;
        let hole = |x: f64, top: f64| [(x, top), (x + 0.1, top), (x + 0.1, 0.5), (x, 0.5)];
        let outer = [
            (0.0, 0.0),
            (0.5, 0.0),
            (1.0, 0.0),
            (1.0, 1.0),
            (0.5, 1.0),
            (0.0, 1.0),
        ];
        let (a, b, c) = (hole(0.1, 0.75), hole(0.45, low), hole(0.8, 0.75));
        // Holes run clockwise: the corner lists above are clockwise already (y up).
        let (points, edges) = region(&[&outer, &a, &b, &c]);
        let tris = triangulate(&points, &edges).expect("a valid grid region");
        assert_eq!(tris.len(), points.len() + 2 * 3 - 2);
        assert!(tris.iter().all(|t| fat(&points, t[0], t[1], t[2])));
        let holes = 0.1 * 0.25 * 2.0 + 0.1 * (low - 0.5);
        assert!((area(&points, &tris) - (1.0 - holes)).abs() < 1e-12);
    }

    /// A comb (many split and merge corners) and an L: every tooth gap and notch triangulated.
    #[test]
    fn comb_and_l_shapes() {
        // Teeth up (their tops start, the gaps' floors merge), and the same comb upside down
        // (the gaps' roofs split).
        let mut comb = vec![(0.0, 0.0), (9.0, 0.0), (9.0, 3.0)];
        for x in (1..9).rev() {
            let x = f64::from(x);
            comb.extend(if x as i32 % 2 == 0 {
                [(x, 3.0), (x, 1.0)]
            } else {
                [(x, 1.0), (x, 3.0)]
            });
        }
        comb.push((0.0, 3.0));
        let flipped: Vec<(f64, f64)> = comb.iter().rev().map(|&(x, y)| (x, 3.0 - y)).collect();
        let l = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ];
        for ring in [&comb[..], &flipped[..], &l[..]] {
            let (points, edges) = region(&[ring]);
            let Some(tris) = triangulate(&points, &edges) else {
                panic!("no triangulation of {ring:?}");
            };
            assert_eq!(tris.len(), points.len() - 2);
            let expected: f64 = (0..ring.len())
                .map(|k| {
                    let (p, q) = (ring[k], ring[(k + 1) % ring.len()]);
                    0.5 * (p.0 * q.1 - q.0 * p.1)
                })
                .sum();
            assert!((area(&points, &tris) - expected).abs() < 1e-12);
        }
    }

    /// What the sweep refuses, for the Delaunay path to decide: a hole touching the outer loop,
    /// crossing loops, two outer loops, a hole outside, a loop crossing itself.
    #[test]
    fn refusals() {
        let square = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)];
        let bowtie = [(0.0, 0.0), (4.0, 4.0), (4.0, 0.0), (0.0, 4.0)];
        let touching = [(0.0, 1.0), (0.0, 2.0), (1.0, 2.0), (1.0, 1.0)];
        let crossing = [(3.0, 1.0), (3.0, 2.0), (5.0, 2.0), (5.0, 1.0)];
        let outside = [(6.0, 1.0), (6.0, 2.0), (7.0, 2.0), (7.0, 1.0)];
        let second = [(6.0, 0.0), (7.0, 0.0), (7.0, 1.0), (6.0, 1.0)];
        for loops in [
            &[&bowtie[..]][..],
            &[&square, &touching],
            &[&square, &crossing],
            &[&square, &outside],
            &[&square, &second],
        ] {
            let (points, edges) = region(loops);
            assert!(triangulate(&points, &edges).is_none(), "{loops:?}");
        }
    }
}
