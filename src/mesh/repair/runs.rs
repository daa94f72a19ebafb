//! Straight runs of crowded edges (used by more than two triangles, where solids touch), and
//! which runs the fans at both far ends close into one: what decides, as for a single pinched
//! edge, whether [`super::shells`] pairs the run across the empty wedges instead.

use glam::DVec3;

use crate::disjoint_sets::DisjointSets;

/// For each crowded edge, its straight run (named by an edge of it): crowded edges meeting at
/// a vertex that no other crowded edge reaches, and running on in one line through it.
pub(super) fn runs_of(
    crowded: &[Vec<(u32, bool)>],
    triangles: &[[u32; 3]],
    positions: &[DVec3],
) -> Vec<usize> {
    let ends = |g: usize| {
        let h = crowded[g][0].0 as usize;
        let t = triangles[h / 3];
        [t[h % 3], t[(h % 3 + 1) % 3]]
    };
    let mut at: crate::hash::FxHashMap<u32, Vec<usize>> = Default::default();
    for g in 0..crowded.len() {
        for v in ends(g) {
            at.entry(v).or_default().push(g);
        }
    }
    let mut sets = DisjointSets::new(crowded.len());
    for (&v, edges) in &at {
        if let [g1, g2] = edges[..] {
            let far = |g: usize| ends(g).into_iter().find(|&w| w != v).unwrap_or(v);
            let p = positions[v as usize];
            let (d1, d2) = (
                positions[far(g1) as usize] - p,
                positions[far(g2) as usize] - p,
            );
            if d1.cross(d2).length_squared() <= 1e-24 * d1.length_squared() * d2.length_squared()
                && d1.dot(d2) < 0.0
            {
                sets.union(g1, g2);
            }
        }
    }
    (0..crowded.len()).map(|g| sets.find(g)).collect()
}

/// For each straight run of two or more crowded edges whose both far ends keep every sheet of
/// the run in one fan, 1 at the run's name (else 0): the fans closed into one there, as where
/// two cavities touching along the run end in solid material. A run of one such edge is
/// pinched (see `shells::pinched_edges`) instead.
pub(super) fn closed_runs(
    crowded: &[Vec<(u32, bool)>],
    triangles: &[[u32; 3]],
    runs: &[usize],
    corner_vertex: &[u32],
) -> Vec<usize> {
    let corner = |h: usize, k: usize| {
        let at = h / 3 * 3 + (h % 3 + k) % 3;
        (triangles[at / 3][at % 3], corner_vertex[at])
    };
    // Per run: its edge count, and per end vertex how many of its edges reach it and whether
    // every sheet there is one fan.
    let mut edges = vec![0usize; crowded.len()];
    let mut ends: crate::hash::FxHashMap<(usize, u32), (usize, bool)> = Default::default();
    for (g, around) in crowded.iter().enumerate() {
        edges[runs[g]] += 1;
        let h0 = around[0].0 as usize;
        for k in 0..2 {
            let (v, fan) = corner(h0, k);
            let closed = around.iter().all(|&(h, _)| {
                let h = h as usize;
                [corner(h, 0), corner(h, 1)].contains(&(v, fan))
            });
            let e = ends.entry((runs[g], v)).or_insert((0, true));
            e.0 += 1;
            e.1 &= closed;
        }
    }
    let mut open = vec![false; crowded.len()];
    for (&(run, _), &(reach, closed)) in &ends {
        if reach == 1 && !closed {
            open[run] = true;
        }
    }
    (0..crowded.len())
        .map(|g| usize::from(runs[g] == g && edges[g] >= 2 && !open[g]))
        .collect()
}
