//! The marching-cubes case table, generated rather than typed in, so that its one rule for
//! ambiguous faces is applied identically everywhere.
//!
//! Why generated: the classic Lorensen/Bourke tables decide an ambiguous face (two diagonal
//! corners inside, the other two outside) differently in the two cubes that share it, which
//! leaves holes. Here each face's contour is derived from the face alone — its crossing edges
//! and, when it is ambiguous, one decision bit computed from the face's four values by the
//! asymptotic decider in a canonical corner order — so both cubes draw the same segments on a
//! shared face, in opposite directions. The segments on a cube's six faces chain into closed
//! loops, each loop becomes a disk of triangles, and the disks glue into a closed, consistently
//! oriented 2-manifold.
//!
//! Numbering. Corner `c` sits at `(c & 1, c >> 1 & 1, c >> 2 & 1)`. Edge `e` runs along axis
//! `e / 4` from the corner whose other two coordinates (in increasing axis order) are
//! `(e & 1, e >> 1 & 1)`. Face `f` is the side `f & 1` of axis `f / 2`; its corners are listed
//! in the canonical order `(u, v) = (0,0), (1,0), (0,1), (1,1)` of its two other axes, so a face
//! seen from either cube has the same order.
//!
//! A case is indexed by `config | decisions << 8`: bit `c` of `config` is set when corner `c`
//! is inside; bit `f` of `decisions`, meaningful only on ambiguous faces, is set when the
//! face's inside corners are connected across it.

use std::sync::LazyLock;

/// A triangle corner in a case: `0..12` an edge's vertex, `12 + l` the centre vertex of the
/// case's `l`-th centred loop.
pub(crate) type Code = u8;

/// One case: its triangles (counter-clockwise from outside) and the loops that need a centre
/// vertex (as edge lists).
#[derive(Clone, Debug, Default)]
pub(crate) struct Case {
    pub tris: Vec<[Code; 3]>,
    pub centres: Vec<Vec<u8>>,
}

pub(crate) struct Table {
    pub cases: Vec<Case>,
    /// Per config, the mask of faces that are ambiguous.
    pub ambiguous: [u8; 256],
}

pub(crate) static TABLE: LazyLock<Table> = LazyLock::new(build);

fn other_axes(a: usize) -> (usize, usize) {
    match a {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

pub(crate) fn corner_pos(c: usize) -> [usize; 3] {
    [c & 1, (c >> 1) & 1, (c >> 2) & 1]
}

fn corner_at(p: [usize; 3]) -> usize {
    p[0] | (p[1] << 1) | (p[2] << 2)
}

/// The two corners of edge `e`, the one at the axis' 0 first.
pub(crate) fn edge_corners(e: usize) -> (usize, usize) {
    let a = e / 4;
    let (u, v) = other_axes(a);
    let mut p = [0; 3];
    p[u] = e & 1;
    p[v] = (e >> 1) & 1;
    let c0 = corner_at(p);
    p[a] = 1;
    (c0, corner_at(p))
}

/// The corners of face `f` in canonical `(u, v)` order.
pub(crate) fn face_corners(f: usize) -> [usize; 4] {
    let (a, s) = (f / 2, f & 1);
    let (u, v) = other_axes(a);
    let mut out = [0; 4];
    for (i, o) in out.iter_mut().enumerate() {
        let mut p = [0; 3];
        p[a] = s;
        p[u] = i & 1;
        p[v] = i >> 1;
        *o = corner_at(p);
    }
    out
}

fn on_face(c: usize, f: usize) -> bool {
    corner_pos(c)[f / 2] == f & 1
}

fn edge_on_face(e: usize, f: usize) -> bool {
    let (c0, c1) = edge_corners(e);
    on_face(c0, f) && on_face(c1, f)
}

fn edges_share_face(a: usize, b: usize) -> bool {
    (0..6).any(|f| edge_on_face(a, f) && edge_on_face(b, f))
}

/// Whether a face with these canonical corner values is ambiguous, and if so whether its
/// inside corners connect: the bilinear interpolant's saddle value is inside (`< 0`). Both
/// cubes sharing the face pass the same values in the same order, so they agree bit for bit.
#[inline]
pub(crate) fn face_connects(v: [f64; 4]) -> bool {
    let num = v[0] * v[3] - v[1] * v[2];
    let den = v[0] + v[3] - v[1] - v[2];
    // saddle = num / den; zero counts as outside, like the grid values.
    num != 0.0 && ((num < 0.0) != (den < 0.0))
}

fn midpoint(e: usize) -> [f64; 3] {
    let (c0, c1) = edge_corners(e);
    let (p, q) = (corner_pos(c0), corner_pos(c1));
    [0, 1, 2].map(|i| 0.5 * (p[i] + q[i]) as f64)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Orients segment `(e1, e2)` on face `f` so that, seen from outside the cube, the inside
/// corners lie to its right. `reference` is a corner on a known side: the corner the segment
/// cuts off, or any inside corner for a segment across the face.
fn orient(e1: usize, e2: usize, f: usize, reference: usize, inside: bool) -> (usize, usize) {
    let (a, b) = (midpoint(e1), midpoint(e2));
    let c = corner_pos(reference).map(|x| x as f64);
    let n = cross(sub(b, a), sub(c, a));
    let m = n[f / 2] * if f & 1 == 1 { 1.0 } else { -1.0 };
    if (m < 0.0) == inside {
        (e1, e2)
    } else {
        (e2, e1)
    }
}

fn shared_corner(e1: usize, e2: usize) -> Option<usize> {
    let (a0, a1) = edge_corners(e1);
    let (b0, b1) = edge_corners(e2);
    [a0, a1].into_iter().find(|&c| c == b0 || c == b1)
}

fn build_case(config: usize, decisions: usize) -> Case {
    let inside = |c: usize| config >> c & 1 == 1;
    let crossing = |e: usize| {
        let (c0, c1) = edge_corners(e);
        inside(c0) != inside(c1)
    };
    let mut next = [usize::MAX; 12];
    for f in 0..6 {
        let edges: Vec<usize> = (0..12)
            .filter(|&e| edge_on_face(e, f) && crossing(e))
            .collect();
        let mut segments = Vec::new();
        match edges.len() {
            2 => {
                let (e1, e2) = (edges[0], edges[1]);
                match shared_corner(e1, e2) {
                    Some(c) => segments.push(orient(e1, e2, f, c, inside(c))),
                    None => {
                        let c = face_corners(f)
                            .into_iter()
                            .find(|&c| inside(c))
                            .unwrap_or(0);
                        segments.push(orient(e1, e2, f, c, true));
                    }
                }
            }
            4 => {
                let connect = decisions >> f & 1 == 1;
                // Cut off the corners of the side that is not connected.
                for c in face_corners(f) {
                    if inside(c) == connect {
                        continue;
                    }
                    let pair: Vec<usize> = edges
                        .iter()
                        .copied()
                        .filter(|&e| {
                            let (c0, c1) = edge_corners(e);
                            c0 == c || c1 == c
                        })
                        .collect();
                    segments.push(orient(pair[0], pair[1], f, c, inside(c)));
                }
            }
            _ => {}
        }
        for (a, b) in segments {
            next[a] = b;
        }
    }
    let mut case = Case::default();
    let mut seen = [false; 12];
    for start in 0..12 {
        if next[start] == usize::MAX || seen[start] {
            continue;
        }
        let mut lp = vec![start];
        seen[start] = true;
        let mut e = next[start];
        while e != start {
            lp.push(e);
            seen[e] = true;
            e = next[e];
        }
        triangulate(&lp, &mut case);
    }
    case
}

/// A disk over one loop. A fan whose diagonals join edges with no common face keeps every
/// interior edge private to the cube; where no such apex exists, a centre vertex does.
fn triangulate(lp: &[usize], case: &mut Case) {
    let n = lp.len();
    if n == 3 {
        case.tris.push([lp[0] as u8, lp[1] as u8, lp[2] as u8]);
        return;
    }
    let apex = (0..n).find(|&a| (2..n - 1).all(|i| !edges_share_face(lp[a], lp[(a + i) % n])));
    match apex {
        Some(a) => {
            for i in 1..n - 1 {
                case.tris.push([
                    lp[a] as u8,
                    lp[(a + i) % n] as u8,
                    lp[(a + i + 1) % n] as u8,
                ]);
            }
        }
        None => {
            let c = 12 + case.centres.len() as u8;
            for i in 0..n {
                case.tris.push([c, lp[i] as u8, lp[(i + 1) % n] as u8]);
            }
            case.centres.push(lp.iter().map(|&e| e as u8).collect());
        }
    }
}

fn build() -> Table {
    let mut ambiguous = [0u8; 256];
    for (config, mask) in ambiguous.iter_mut().enumerate() {
        for f in 0..6 {
            let v = face_corners(f).map(|c| config >> c & 1 == 1);
            if v[0] == v[3] && v[1] == v[2] && v[0] != v[1] {
                *mask |= 1 << f;
            }
        }
    }
    let mut cases = vec![Case::default(); 256 * 64];
    for config in 0..256 {
        let mask = ambiguous[config] as usize;
        // Only decision bits on ambiguous faces matter; other indices stay unused.
        let mut d = 0usize;
        loop {
            cases[config | d << 8] = build_case(config, d);
            if d == mask {
                break;
            }
            d = (d.wrapping_sub(mask)) & mask;
        }
    }
    Table { cases, ambiguous }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_case_closes_into_loops() {
        let t = &*TABLE;
        for config in 0..256usize {
            let mask = t.ambiguous[config] as usize;
            let mut d = 0usize;
            loop {
                let case = &t.cases[config | d << 8];
                // Every crossing edge appears, and each triangle edge between two cube edges is
                // either a face segment or private.
                let crossing = (0..12)
                    .filter(|&e| {
                        let (a, b) = edge_corners(e);
                        (config >> a & 1) != (config >> b & 1)
                    })
                    .count();
                let used: std::collections::BTreeSet<u8> = case
                    .tris
                    .iter()
                    .flatten()
                    .copied()
                    .filter(|&c| c < 12)
                    .collect();
                assert_eq!(used.len(), crossing, "config {config:08b} d {d:06b}");
                if d == mask {
                    break;
                }
                d = (d.wrapping_sub(mask)) & mask;
            }
        }
        assert!(t.cases[1].tris.len() == 1);
    }
}
