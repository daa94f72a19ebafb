//! Dropping closed shells thinner than the weld.
//!
//! Where two faces cross at an angle so small that the sliver between them is nowhere thicker
//! than the weld (a cube less itself turned 2e-9°: slivers 1.5e-11 thick against a weld of
//! 1.4e-11), the weld pulls the sliver's two sides onto each other. What is left is a closed
//! shell that bounds nothing: two sheets back to back, a "flat shell" that is neither a solid
//! nor a cavity. Its true volume is below the weld times its area, which is within the
//! tolerance the boolean worked to, so it is read as empty and dropped, as the boolean drops a
//! polygon thinner than its tolerance.

use std::collections::HashSet;

use glam::DVec3;

use crate::disjoint_sets::DisjointSets;
use crate::hash::FxBuild;
use crate::mesh::Mesh;

/// Removes every closed shell (every edge used both ways within it) whose mean thickness,
/// twice its volume over its area, is at most `delta`; returns how many were removed. Shells
/// are told apart by shared vertices, as `split_into_shells` leaves them.
///
/// A shell holding a triangle from `filled_from` on (those the flat fill of `cracks` added) is
/// kept: the fill closes any flat open loop, a lone face too, against itself, and dropping
/// that would turn an open result into an empty one that passes every check.
pub(super) fn drop_thin_shells(mesh: &mut Mesh, delta: f64, filled_from: usize) -> usize {
    let n = mesh.positions.len();
    if mesh.triangles.is_empty() {
        return 0;
    }
    let mut sets = DisjointSets::new(n);
    for t in &mesh.triangles {
        sets.union_all(t.map(|v| v as usize));
    }
    // Per shell (by its root vertex): six times the volume about the root, twice the area.
    let mut volume = vec![0.0f64; n];
    let mut area = vec![0.0f64; n];
    // Whether the flat fill added a triangle to the shell; the roots, each once, as first met.
    // (Each triangle's root is found again only where some shell is flat: most meshes have
    // none, and a list of the roots was a tenth of this check on a sphere union.)
    let mut filled = vec![
        false;
        if filled_from < mesh.triangles.len() {
            n
        } else {
            0
        }
    ];
    let mut is_root = vec![false; n];
    let mut roots: Vec<usize> = Vec::new();
    for (i, t) in mesh.triangles.iter().enumerate() {
        let r = sets.find(t[0] as usize);
        let o = mesh.positions[r];
        let [a, b, c] = t.map(|i| mesh.positions[i as usize] - o);
        volume[r] += a.dot(b.cross(c));
        area[r] += length((b - a).cross(c - a));
        if i >= filled_from {
            filled[r] = true;
        }
        if !is_root[r] {
            is_root[r] = true;
            roots.push(r);
        }
    }
    // Mean thickness 2V / A = (6V / 3) / (2A / 2) = (2/3)·(6V) / (2A).
    let flat = |r: usize| {
        !filled.get(r).is_some_and(|&f| f) && 2.0 * volume[r].abs() / 3.0 <= delta * area[r]
    };
    // Whether every edge has its reverse is asked only of the flat shells (most meshes have
    // none, asked once per shell): a hash of every edge was as much as the shell split itself.
    // An edge's reverse shares its vertices, so it lies in the same shell.
    if !roots.iter().any(|&r| flat(r)) {
        return 0;
    }
    let root: Vec<usize> = mesh
        .triangles
        .iter()
        .map(|t| sets.find(t[0] as usize))
        .collect();
    let candidate: Vec<bool> = root.iter().map(|&r| flat(r)).collect();
    let edges: HashSet<(u32, u32), FxBuild> = mesh
        .triangles
        .iter()
        .zip(&candidate)
        .filter(|(_, c)| **c)
        .flat_map(|(t, _)| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .collect();
    let mut open = vec![false; n];
    for (t, &r) in mesh.triangles.iter().zip(&root) {
        if flat(r) {
            open[r] |= [(t[1], t[0]), (t[2], t[1]), (t[0], t[2])]
                .iter()
                .any(|e| !edges.contains(e));
        }
    }
    let thin = |r: usize| flat(r) && !open[r];
    let keep: Vec<bool> = root.iter().map(|&r| !thin(r)).collect();
    let mut counted = vec![false; n];
    let mut dropped = 0;
    for (t, &r) in root.iter().enumerate() {
        if !keep[t] && !counted[r] {
            counted[r] = true;
            dropped += 1;
        }
    }
    if dropped == 0 {
        return 0;
    }
    let mut new_index = vec![u32::MAX; n];
    let mut positions: Vec<DVec3> = Vec::with_capacity(n);
    let mut triangles = Vec::with_capacity(mesh.triangles.len());
    let mut sources = Vec::with_capacity(mesh.triangles.len());
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !keep[t] {
            continue;
        }
        triangles.push(tri.map(|i| {
            let i = i as usize;
            if new_index[i] == u32::MAX {
                new_index[i] = positions.len() as u32;
                positions.push(mesh.positions[i]);
            }
            new_index[i]
        }));
        sources.push(mesh.sources[t]);
    }
    *mesh = Mesh {
        positions,
        triangles,
        sources,
    };
    dropped
}

/// The length of `v` without squaring its components: a cross product of edges 1e99 long is
/// 1e198, whose square overflows (and an infinite area would make any shell thin).
fn length(v: DVec3) -> f64 {
    // Squared where that neither overflows nor loses digits to underflow (nearly always).
    let squared = v.length_squared();
    if squared.is_finite() && squared > LEAST_SQUARED {
        return squared.sqrt();
    }
    let m = v.abs().max_element();
    if m == 0.0 { 0.0 } else { m * (v / m).length() }
}

/// Above this (about 2⁻⁹⁰⁰, far above the subnormals) a squared length keeps every digit.
const LEAST_SQUARED: f64 = 1.2e-271;
