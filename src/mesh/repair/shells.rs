//! Pairing half-edges and splitting vertices so that every edge and vertex is manifold.

use glam::DVec3;

use crate::disjoint_sets::DisjointSets;
use crate::mesh::Mesh;

/// Builds the mesh with each vertex split into one copy per fan of triangles around it.
///
/// Half-edges `a→b` and `b→a` pair up as twins. Around an edge used by more than two triangles
/// (solids touching along it), the triangles are sorted by angle and each `a→b` triangle pairs
/// with its clockwise neighbour — the one across the solid's interior wedge. A vertex's corners
/// linked through twins form fans; each fan gets its own vertex, so solids touching at an edge
/// or a vertex become separate manifold shells.
///
/// Also returns the end points of half-edges left without a twin: the cracks.
pub(super) fn split_into_shells(
    positions: Vec<DVec3>,
    (triangles, sources): (Vec<[u32; 3]>, Vec<u32>),
) -> (Mesh, Vec<DVec3>) {
    let n = triangles.len() * 3;
    let from = |h: usize| triangles[h / 3][h % 3];
    let to = |h: usize| triangles[h / 3][(h % 3 + 1) % 3];
    // Half-edges sorted by their undirected edge, as (min << 32 | max, half-edge).
    let mut keyed: Vec<(u64, u32)> = (0..n)
        .map(|h| {
            let (a, b) = (from(h), to(h));
            (((a.min(b) as u64) << 32) | a.max(b) as u64, h as u32)
        })
        .collect();
    keyed.sort_unstable();
    let order: Vec<u32> = keyed.iter().map(|&(_, h)| h).collect();
    let mut twin: Vec<u32> = vec![u32::MAX; n];
    let mut i = 0;
    while i < n {
        let mut j = i + 1;
        while j < n && keyed[j].0 == keyed[i].0 {
            j += 1;
        }
        let group = &order[i..j];
        if let [h1, h2] = *group {
            if from(h1 as usize) == to(h2 as usize) {
                twin[h1 as usize] = h2;
                twin[h2 as usize] = h1;
            }
        } else if group.len() > 2 {
            pair_by_angle(&positions, &triangles, group, &mut twin);
        }
        i = j;
    }
    // Corner h sits at vertex from(h). Around that vertex, the corner of the previous
    // half-edge's twin continues the fan.
    let mut fans = DisjointSets::new(n);
    for h in 0..n {
        let prev = h / 3 * 3 + (h % 3 + 2) % 3;
        let t = twin[prev];
        if t != u32::MAX {
            fans.union(h, t as usize);
        }
    }
    let mut vertex_of_fan: Vec<u32> = vec![u32::MAX; n];
    let mut out_positions = Vec::with_capacity(positions.len());
    let mut out_triangles = vec![[0u32; 3]; triangles.len()];
    for h in 0..n {
        let root = fans.find(h);
        if vertex_of_fan[root] == u32::MAX {
            vertex_of_fan[root] = out_positions.len() as u32;
            out_positions.push(positions[from(h) as usize]);
        }
        out_triangles[h / 3][h % 3] = vertex_of_fan[root];
    }
    let cracks = (0..n)
        .filter(|&h| twin[h] == u32::MAX)
        .flat_map(|h| [positions[from(h) as usize], positions[to(h) as usize]])
        .collect();
    let mesh = Mesh {
        positions: out_positions,
        triangles: out_triangles,
        sources,
    };
    (mesh, cracks)
}

/// Pairs the half-edges of a non-manifold edge by the angle of their triangles about it.
fn pair_by_angle(positions: &[DVec3], triangles: &[[u32; 3]], group: &[u32], twin: &mut [u32]) {
    let h0 = group[0] as usize;
    let (a, b) = (
        triangles[h0 / 3][h0 % 3],
        triangles[h0 / 3][(h0 % 3 + 1) % 3],
    );
    let (pa, pb) = (positions[a as usize], positions[b as usize]);
    let axis = (pb - pa).normalize_or_zero();
    let u = axis.any_orthonormal_vector();
    let w = axis.cross(u);
    // (angle, half-edge, runs a→b)
    let mut around: Vec<(f64, u32, bool)> = group
        .iter()
        .map(|&h| {
            let t = triangles[h as usize / 3];
            let apex = t[(h as usize % 3 + 2) % 3];
            let e = positions[apex as usize] - pa;
            (e.dot(w).atan2(e.dot(u)), h, t[h as usize % 3] == a)
        })
        .collect();
    around.sort_by(|x, y| x.0.total_cmp(&y.0));
    let m = around.len();
    for k in 0..m {
        let (_, h, forward) = around[k];
        if !forward {
            continue;
        }
        // The interior of an a→b triangle lies clockwise (decreasing angle) of it.
        let (_, partner, partner_forward) = around[(k + m - 1) % m];
        if !partner_forward && twin[partner as usize] == u32::MAX {
            twin[h as usize] = partner;
            twin[partner as usize] = h;
        }
    }
}
