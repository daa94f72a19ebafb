//! Per-shell figures of the report, and telling cavities from inside-out shells.

use std::f64::consts::PI;

use glam::DVec3;

use super::ShellReport;
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, is_needle, solid_angle};
use crate::mesh::Mesh;
use crate::topology::EdgeTable;

/// Per-shell figures, shells numbered by their first triangle.
pub(super) fn shells(
    mesh: &Mesh,
    usable: &[bool],
    table: &EdgeTable,
    tri_sets: &mut DisjointSets,
    centre: DVec3,
) -> Vec<ShellReport> {
    let tris = &mesh.triangles;
    const NONE: usize = usize::MAX;
    let mut shell_of_root = vec![NONE; tris.len()];
    let mut shell_of = vec![NONE; tris.len()];
    let mut out: Vec<ShellReport> = Vec::new();
    let mut boxes: Vec<Aabb> = Vec::new();
    // Per shell, the volume about its first corner, and about `centre` (see
    // `ShellReport::volume`: an open shell keeps the latter).
    let mut origins: Vec<DVec3> = Vec::new();
    let mut centred: Vec<f64> = Vec::new();
    for t in (0..tris.len()).filter(|&t| usable[t]) {
        let root = tri_sets.find(t);
        if shell_of_root[root] == NONE {
            shell_of_root[root] = out.len();
            out.push(ShellReport {
                triangles: 0,
                vertices: 0,
                edges: 0,
                euler_characteristic: 0,
                closed: true,
                oriented: true,
                genus: None,
                volume: 0.0,
                cavity: false,
                needles: 0,
            });
            boxes.push(Aabb::EMPTY);
            origins.push(mesh.positions[tris[t][0] as usize]);
            centred.push(0.0);
        }
        let s = shell_of_root[root];
        shell_of[t] = s;
        let [a, b, c] = tris[t].map(|i| mesh.positions[i as usize]);
        out[s].triangles += 1;
        let o = origins[s];
        out[s].volume += (a - o).dot((b - o).cross(c - o));
        centred[s] += (a - centre).dot((b - centre).cross(c - centre));
        for p in [a, b, c] {
            boxes[s].grow(p);
        }
    }

    // Needles, by each shell's own size.
    for t in (0..tris.len()).filter(|&t| usable[t]) {
        let s = shell_of[t];
        let corners = tris[t].map(|i| mesh.positions[i as usize]);
        if is_needle(corners, boxes[s].diagonal()) {
            out[s].needles += 1;
        }
    }

    count_edges(table, &shell_of, &mut out);
    count_vertices(tris, usable, &shell_of, &mut out);

    for (s, centred) in out.iter_mut().zip(centred) {
        if !(s.closed && s.oriented) {
            s.volume = centred;
        }
        s.volume /= 6.0;
        s.euler_characteristic = s.vertices as i64 - s.edges as i64 + s.triangles as i64;
        let twice_genus = 2 - s.euler_characteristic;
        s.genus = (s.closed && s.oriented && twice_genus >= 0 && twice_genus % 2 == 0)
            .then_some(twice_genus as u64 / 2);
    }
    resolve_underflow(mesh, usable, &shell_of, &boxes, &mut out);
    find_cavities(mesh, usable, &shell_of, &boxes, &mut out, centre);
    out
}

/// Gives a shell whose volume underflowed to zero (a cube of side 10⁻¹¹⁰: 10⁻³³⁰ is below the
/// least positive double) the sign of its volume, as the least double of that sign, so a
/// correctly wound tiny shell is not called flat or inside out. The sign comes from the volume
/// recomputed about the shell's own centre with coordinates scaled by a power of two (exact).
fn resolve_underflow(
    mesh: &Mesh,
    usable: &[bool],
    shell_of: &[usize],
    boxes: &[Aabb],
    out: &mut [ShellReport],
) {
    let tiny: Vec<usize> = (0..out.len())
        .filter(|&s| out[s].volume == 0.0 && boxes[s].diagonal() > 0.0)
        .collect();
    if tiny.is_empty() {
        return;
    }
    // A flag per shell, not a search of `tiny`: a soup of flat triangles has a tiny shell for
    // each, and searching the list per triangle was quadratic (1M vertices: minutes).
    let mut is_tiny = vec![false; out.len()];
    for &s in &tiny {
        is_tiny[s] = true;
    }
    let mut scaled = vec![0.0; out.len()];
    for t in (0..mesh.triangles.len()).filter(|&t| usable[t]) {
        let s = shell_of[t];
        if !is_tiny[s] {
            continue;
        }
        let c = boxes[s].center();
        let k = crate::geom::unit_scale(0.5 * boxes[s].diagonal());
        let [a, b, d] = mesh.triangles[t].map(|i| (mesh.positions[i as usize] - c) * k);
        scaled[s] += a.dot(b.cross(d));
    }
    for s in tiny {
        if scaled[s] != 0.0 {
            out[s].volume = f64::from_bits(1).copysign(scaled[s]);
        }
    }
}

/// Edges per shell. An edge of several shells counts in each; each shell must use it exactly
/// twice, in opposite directions, to be closed and oriented.
fn count_edges(table: &EdgeTable, shell_of: &[usize], out: &mut [ShellReport]) {
    let mut uses: Vec<(usize, usize)> = Vec::new();
    for run in table.runs() {
        uses.clear();
        uses.extend(run.iter().map(|&(_, tag)| (shell_of[tag >> 1], tag & 1)));
        uses.sort_unstable();
        for group in uses.chunk_by(|x, y| x.0 == y.0) {
            let shell = &mut out[group[0].0];
            shell.edges += 1;
            match group {
                [(_, x), (_, y)] => shell.oriented &= x != y,
                _ => shell.closed = false,
            }
        }
    }
}

/// Distinct vertices per shell.
fn count_vertices(tris: &[[u32; 3]], usable: &[bool], shell_of: &[usize], out: &mut [ShellReport]) {
    let mut pairs: Vec<(usize, u32)> = (0..tris.len())
        .filter(|&t| usable[t])
        .flat_map(|t| tris[t].map(|v| (shell_of[t], v)))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    for &(s, _) in &pairs {
        out[s].vertices += 1;
    }
}

/// Marks the closed, oriented shells of negative volume around which the other closed,
/// oriented shells wind exactly once: holes in a solid, not inside-out solids.
///
/// In a valid solid the winding number is 1 in material and 0 outside, and a shell's own
/// winding number is ±1 inside it, so a shell facing inward must have the others winding once
/// around it. Only shells whose boxes hold the test point can wind around it.
fn find_cavities(
    mesh: &Mesh,
    usable: &[bool],
    shell_of: &[usize],
    boxes: &[Aabb],
    shells: &mut [ShellReport],
    centre: DVec3,
) {
    let sound = |s: &ShellReport| s.closed && s.oriented;
    let negative: Vec<usize> = (0..shells.len())
        .filter(|&s| sound(&shells[s]) && shells[s].volume < 0.0)
        .collect();
    // Only a shell of positive volume can make the others wind once around anything.
    if negative.is_empty() || !shells.iter().any(|s| sound(s) && s.volume > 0.0) {
        return;
    }
    // Triangles grouped by shell (counting sort), and each shell's largest triangle, whose
    // centroid is the point least likely to lie on another shell.
    let tris = &mesh.triangles;
    let mut start = vec![0usize; shells.len() + 1];
    let mut largest: Vec<Option<(f64, usize)>> = vec![None; shells.len()];
    for t in (0..tris.len()).filter(|&t| usable[t]) {
        let s = shell_of[t];
        start[s + 1] += 1;
        let [a, b, c] = tris[t].map(|i| mesh.positions[i as usize] - centre);
        let area = (b - a).cross(c - a).length_squared();
        if largest[s].is_none_or(|(best, _)| area > best) {
            largest[s] = Some((area, t));
        }
    }
    for s in 0..shells.len() {
        start[s + 1] += start[s];
    }
    let mut fill = start.clone();
    let mut by_shell = vec![0usize; start[shells.len()]];
    for t in (0..tris.len()).filter(|&t| usable[t]) {
        by_shell[fill[shell_of[t]]] = t;
        fill[shell_of[t]] += 1;
    }
    for s in negative {
        let Some((_, t)) = largest[s] else { continue };
        let [a, b, c] = tris[t].map(|i| mesh.positions[i as usize] - centre);
        let p = (a + b + c) / 3.0;
        let mut winding = 0.0;
        for other in 0..shells.len() {
            if other == s || !sound(&shells[other]) || !boxes[other].contains_point(p + centre, 0.0)
            {
                continue;
            }
            for &t in &by_shell[start[other]..start[other + 1]] {
                let [a, b, c] = tris[t].map(|i| mesh.positions[i as usize] - centre);
                winding += solid_angle(a - p, b - p, c - p);
            }
        }
        shells[s].cavity = (winding / (4.0 * PI)).round() == 1.0;
    }
}
