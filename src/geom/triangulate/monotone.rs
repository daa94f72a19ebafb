//! The second half of the sweep triangulation (see `sweep`): the monotone pieces its
//! diagonals cut a region into, their triangles, and the checks of the result.

use smallvec::SmallVec;
use spade::Point2;

use super::sweep::{orient, same_way};

/// A triangle is a sliver when twice its area is at most this times its longest edge squared.
/// A corner a rounding off a straight edge makes one (10⁻¹⁶ of a grid's); the thinnest triangle
/// on a grid of `k` cells across is about `1/k²`. The sweep makes none: a region it would cut
/// into one takes the Delaunay path, which makes none where it can be helped.
const SLIVER: f64 = 1e-6;

/// The faces the boundary and the diagonals cut the region into, each counter-clockwise: after
/// each edge comes the first edge leaving its end clockwise from the way back.
pub(super) fn pieces(
    points: &[Point2<f64>],
    next: &[usize],
    diagonals: &[(usize, usize)],
) -> Option<Vec<Vec<usize>>> {
    let n = points.len();
    let mut out: Vec<SmallVec<[usize; 3]>> = next.iter().map(|&w| smallvec::smallvec![w]).collect();
    for &(a, b) in diagonals {
        out[a].push(b);
        out[b].push(a);
    }
    let mut used: Vec<SmallVec<[bool; 3]>> = out
        .iter()
        .map(|o| smallvec::smallvec![false; o.len()])
        .collect();
    let half_edges = n + 2 * diagonals.len();
    let mut faces = Vec::with_capacity(diagonals.len() + 1);
    for v in 0..n {
        for k in 0..out[v].len() {
            if used[v][k] {
                continue;
            }
            let mut face = Vec::new();
            let (mut a, mut j) = (v, k);
            while !used[a][j] {
                used[a][j] = true;
                face.push(a);
                if face.len() > half_edges {
                    return None;
                }
                let b = out[a][j];
                j = first_clockwise(points, b, a, &out[b])?;
                a = b;
            }
            if (a, j) != (v, k) {
                return None;
            }
            faces.push(face);
        }
    }
    Some(faces)
}

/// The index in `around` of the neighbour of `b` met first turning clockwise from the way to
/// `a` (`a` itself left out). `None` where two neighbours lie the same way.
fn first_clockwise(points: &[Point2<f64>], b: usize, a: usize, around: &[usize]) -> Option<usize> {
    // 0: less than a half turn clockwise, 1: exactly a half turn, 2: more.
    let sector = |c: usize| -> Option<u8> {
        let turn = orient(points, b, a, c);
        if turn < 0.0 {
            Some(0)
        } else if turn > 0.0 {
            Some(2)
        } else {
            (!same_way(points, b, a, c)).then_some(1)
        }
    };
    let mut best: Option<(u8, usize)> = None;
    for (k, &c) in around.iter().enumerate() {
        if c == a {
            continue;
        }
        let s = sector(c)?;
        let better = match best {
            None => true,
            Some((t, _)) if s != t => s < t,
            Some((_, j)) => {
                let turn = orient(points, b, c, around[j]);
                if turn == 0.0 {
                    return None;
                }
                turn < 0.0
            }
        };
        if better {
            best = Some((s, k));
        }
    }
    best.map(|(_, k)| k)
}

/// Triangulates a piece monotone along the sweep (counter-clockwise corners) by the stack walk
/// down its two chains, appending counter-clockwise triangles; `None` where the piece is not
/// monotone or a triangle would not turn left.
pub(super) fn triangulate_monotone(
    points: &[Point2<f64>],
    piece: &[usize],
    rank: &[usize],
    tris: &mut Vec<[usize; 3]>,
) -> Option<()> {
    let m = piece.len();
    if m < 3 {
        return None;
    }
    let top = (0..m).min_by_key(|&k| rank[piece[k]])?;
    let bottom = (0..m).max_by_key(|&k| rank[piece[k]])?;
    // Counter-clockwise from the top runs down the left chain to the bottom, then up the right.
    let left: Vec<usize> = (1..m)
        .map(|s| (top + s) % m)
        .take_while(|&k| k != bottom)
        .map(|k| piece[k])
        .collect();
    let mut right: Vec<usize> = (1..m)
        .map(|s| (bottom + s) % m)
        .take_while(|&k| k != top)
        .map(|k| piece[k])
        .collect();
    right.reverse();
    let descending = |c: &[usize]| c.windows(2).all(|w| rank[w[0]] < rank[w[1]]);
    if !descending(&left) || !descending(&right) {
        return None;
    }
    // The corners from the top down, each with its chain (true: left).
    let mut walk: Vec<(usize, bool)> = Vec::with_capacity(m);
    walk.push((piece[top], true));
    let (mut i, mut j) = (0, 0);
    while i < left.len() || j < right.len() {
        if j == right.len() || (i < left.len() && rank[left[i]] < rank[right[j]]) {
            walk.push((left[i], true));
            i += 1;
        } else {
            walk.push((right[j], false));
            j += 1;
        }
    }
    walk.push((piece[bottom], true));
    let mut emit = |a: usize, b: usize, c: usize| -> Option<()> {
        fat(points, a, b, c).then(|| tris.push([a, b, c]))
    };
    let mut stack: Vec<(usize, bool)> = vec![walk[0], walk[1]];
    for k in 2..m {
        let (v, side) = walk[k];
        if k == m - 1 || stack.last().is_some_and(|s| s.1 != side) {
            // A fan from `v` to every corner on the stack (one chain, but for its first).
            let on_left = stack.last().is_some_and(|s| s.1);
            for w in stack.windows(2) {
                if on_left {
                    emit(w[0].0, w[1].0, v)?;
                } else {
                    emit(w[1].0, w[0].0, v)?;
                }
            }
            stack.clear();
            stack.push(walk[k - 1]);
            stack.push(walk[k]);
        } else {
            let mut last = stack.pop()?;
            while let Some(&q) = stack.last() {
                let (a, b, c) = if side {
                    (q.0, last.0, v)
                } else {
                    (v, last.0, q.0)
                };
                // A corner convex by a hair stays on the stack: cutting its ear would leave a
                // sliver (a corner a rounding off a straight edge), and a fan reaches it later.
                if !fat(points, a, b, c) {
                    break;
                }
                emit(a, b, c)?;
                last = stack.pop()?;
            }
            stack.push(last);
            stack.push(walk[k]);
        }
    }
    Some(())
}

/// True when `a b c` turns left and is no sliver: twice its area above [`SLIVER`] times its
/// longest edge squared.
pub(super) fn fat(points: &[Point2<f64>], a: usize, b: usize, c: usize) -> bool {
    let (pa, pb, pc) = (points[a], points[b], points[c]);
    let d2 = |p: Point2<f64>, q: Point2<f64>| (p.x - q.x).powi(2) + (p.y - q.y).powi(2);
    let longest = d2(pa, pb).max(d2(pb, pc)).max(d2(pc, pa));
    let turn = orient(points, a, b, c);
    turn > 0.0 && turn > SLIVER * longest
}

/// True when the triangles use each boundary edge once, in its direction, and every other edge
/// once each way: triangles that all turn left and so meet a boundary with one outer loop
/// cover its region exactly once.
pub(super) fn covers(tris: &[[usize; 3]], next: &[usize]) -> bool {
    let key = |a: usize, b: usize| ((a as u64) << 32) | b as u64;
    let mut edges: Vec<u64> = tris
        .iter()
        .flat_map(|t| [key(t[0], t[1]), key(t[1], t[2]), key(t[2], t[0])])
        .collect();
    edges.sort_unstable();
    if edges.windows(2).any(|w| w[0] == w[1]) {
        return false;
    }
    let mut boundary = 0;
    for &e in &edges {
        let (a, b) = ((e >> 32) as usize, (e & 0xffff_ffff) as usize);
        if next[a] == b {
            boundary += 1;
        } else if next[b] == a || edges.binary_search(&key(b, a)).is_err() {
            return false;
        }
    }
    boundary == next.len()
}
