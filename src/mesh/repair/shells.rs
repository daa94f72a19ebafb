//! Pairing half-edges and splitting vertices so that every edge and vertex is manifold.

use glam::DVec3;
use rayon::prelude::*;

use super::discs::one_disc;
use super::edges::{sort_by_edge, undirected};
use super::fins::{FIN_SHORTEST_WELDS, cancel_reversed_pairs};
use super::runs::{closed_runs, runs_of};
use crate::disjoint_sets::DisjointSets;
use crate::mesh::Mesh;

/// Triangles per run of [`split_around_discs`]' parallel search for the half-edges to pair.
const KEYED_RUN: usize = 4096;

/// Builds the mesh with each vertex split into one copy per fan of triangles around it.
///
/// Half-edges `a→b` and `b→a` pair up as twins. Around an edge used by more than two triangles
/// (solids touching along it), the triangles are sorted by angle and each `a→b` triangle pairs
/// with a neighbour: by default the clockwise one, across the solid's interior wedge. A vertex's
/// corners linked through twins form fans; each fan gets its own vertex, so solids touching at
/// an edge or a vertex become separate manifold shells.
///
/// Pairing across the solid keeps two cubes that share an edge apart, but where the edge is
/// where two *cavities* touch (a solid meeting itself along an edge whose ends lie in solid
/// material) the fans at the edge's ends then close into one: both pairs of the edge would keep
/// the same two vertices. For each connected chain of such edges the other pairing (across the
/// empty wedges, as if the solid's pieces overlapped by a hair) is tried, and kept when it
/// leaves fewer edges whose pairs share their vertices: the chain's vertices then split, every
/// edge of the output is used by exactly two triangles. A straight run of such edges whose
/// far ends both close (the contact's inner vertices kept, as between polygons of different
/// sources, so no edge of it pinches) is flipped alike, kept when it leaves fewer such runs:
/// the route (one source or one per input) does not change how a contact pairs.
///
/// A vertex whose triangles already form one closed disc (nearly all of them: see [`one_disc`])
/// keeps its one vertex, and the half-edges between two such vertices need no twin found: only
/// the rest are sorted by edge and paired.
///
/// Also returns the end points of half-edges left without a twin: the cracks. `delta` is the
/// weld the positions were welded with (see [`FIN_SHORTEST_WELDS`]); with `alternate_ties`,
/// triangles whose angles about a crowded edge tie within that weld's noise are ordered to
/// alternate (see [`around_edge`]).
pub(super) fn split_into_shells(
    positions: Vec<DVec3>,
    (mut triangles, mut sources): (Vec<[u32; 3]>, Vec<u32>),
    filled_from: &mut usize,
    delta: f64,
    alternate_ties: bool,
) -> (Mesh, Vec<DVec3>) {
    let mut disc = one_disc(&triangles, positions.len());
    let fins = (&positions[..], FIN_SHORTEST_WELDS * delta);
    if cancel_reversed_pairs(fins, &mut triangles, &mut sources, &disc, filled_from) {
        disc = one_disc(&triangles, positions.len());
    }
    let ties = if alternate_ties { delta } else { 0.0 };
    split_around_discs(positions, (triangles, sources), &disc, ties)
}

/// [`split_into_shells`] with `disc` from [`one_disc`]: around a disc vertex every edge is used
/// once each way and its corners are one fan, so a half-edge between two of them needs no twin
/// found (most of a boolean's output). `ties` is the weld within which tied angles about a
/// crowded edge are ordered to alternate, 0 for none (see [`around_edge`]).
pub(super) fn split_around_discs(
    positions: Vec<DVec3>,
    (triangles, sources): (Vec<[u32; 3]>, Vec<u32>),
    disc: &[bool],
    ties: f64,
) -> (Mesh, Vec<DVec3>) {
    let n = triangles.len() * 3;
    let from = |h: usize| triangles[h / 3][h % 3];
    let to = |h: usize| triangles[h / 3][(h % 3 + 1) % 3];
    // The half-edges not between two discs, sorted by their undirected edge, as
    // (min << 32 | max, half-edge).
    // Found in runs of triangles in parallel, collected in order: the test reads every
    // triangle, a boolean's core fans included, and few pass it.
    let keyed: Vec<(u64, u32)> = triangles
        .par_chunks(KEYED_RUN)
        .enumerate()
        .flat_map_iter(|(run, tris)| {
            let first = run * KEYED_RUN;
            tris.iter().enumerate().flat_map(move |(t, tri)| {
                (0..3).filter_map(move |k| {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    let h = (3 * (first + t) + k) as u32;
                    (!(disc[a as usize] && disc[b as usize])).then(|| (undirected(a, b), h))
                })
            })
        })
        .collect();
    let keyed = sort_by_edge(&keyed, positions.len()).items;
    let order: Vec<u32> = keyed.iter().map(|&(_, h)| h).collect();
    let mut twin: Vec<u32> = vec![u32::MAX; n];
    // Edges used by more than two triangles, each as its half-edges sorted by angle.
    let mut crowded: Vec<Vec<(u32, bool)>> = Vec::new();
    let mut i = 0;
    while i < keyed.len() {
        let mut j = i + 1;
        while j < keyed.len() && keyed[j].0 == keyed[i].0 {
            j += 1;
        }
        let group = &order[i..j];
        if let [h1, h2] = *group {
            if from(h1 as usize) == to(h2 as usize) {
                twin[h1 as usize] = h2;
                twin[h2 as usize] = h1;
            }
        } else if group.len() > 2 {
            crowded.push(around_edge(&positions, &triangles, group, ties));
        }
        i = j;
    }
    let mut across_solid = vec![true; crowded.len()];
    for (g, around) in crowded.iter().enumerate() {
        pair_around(around, across_solid[g], &mut twin);
    }
    let mut corner_vertex = fan_vertices(&triangles, &twin, disc, &order);
    if !crowded.is_empty() {
        let pinched = pinched_edges(&crowded, &corner_vertex);
        let runs = runs_of(&crowded, &triangles, &positions);
        let closed = closed_runs(&crowded, &triangles, &runs, &corner_vertex);
        if pinched.iter().chain(&closed).any(|&p| p > 0) {
            let chains = chains_of(&crowded, &triangles);
            let bad_chain: Vec<bool> = {
                let mut bad = vec![false; crowded.len()];
                for (g, (&p, &c)) in pinched.iter().zip(&closed).enumerate() {
                    if p > 0 || c > 0 {
                        bad[chains[g]] = true;
                    }
                }
                bad
            };
            let mut flipped_twin = twin.clone();
            for (g, around) in crowded.iter().enumerate() {
                if bad_chain[chains[g]] {
                    across_solid[g] = false;
                    for &(h, _) in around {
                        flipped_twin[h as usize] = u32::MAX;
                    }
                }
            }
            for (g, around) in crowded.iter().enumerate() {
                if !across_solid[g] {
                    pair_around(around, false, &mut flipped_twin);
                }
            }
            let flipped_vertex = fan_vertices(&triangles, &flipped_twin, disc, &order);
            let flipped_pinched = pinched_edges(&crowded, &flipped_vertex);
            let flipped_closed = closed_runs(&crowded, &triangles, &runs, &flipped_vertex);
            // Per chain: how many pinched edges each pairing leaves, then how many straight
            // runs closed at both ends. A run of several edges (its straight-through vertices
            // kept, as between polygons of different sources) pinches no edge where the one
            // edge of the merged polygons pinches, but closes the same ends: pair them alike.
            let mut score = vec![((0usize, 0usize), (0usize, 0usize)); crowded.len()];
            for g in 0..crowded.len() {
                let c = chains[g];
                score[c].0 = (score[c].0.0 + pinched[g], score[c].0.1 + closed[g]);
                score[c].1 = (
                    score[c].1.0 + flipped_pinched[g],
                    score[c].1.1 + flipped_closed[g],
                );
            }
            let keep_flip: Vec<bool> = (0..crowded.len())
                .map(|c| bad_chain[c] && score[c].1 < score[c].0)
                .collect();
            if keep_flip.iter().any(|&k| k) {
                for (g, around) in crowded.iter().enumerate() {
                    if !keep_flip[chains[g]] {
                        for &(h, _) in around {
                            flipped_twin[h as usize] = twin[h as usize];
                        }
                    }
                }
                twin = flipped_twin;
                corner_vertex = fan_vertices(&triangles, &twin, disc, &order);
            }
        }
    }
    // One output vertex per fan, numbered in order of first use: a disc vertex's corners are
    // one fan (numbered by vertex), the others' by their fan's first corner.
    let mut by_vertex: Vec<u32> = vec![u32::MAX; positions.len()];
    let mut renumber: Vec<u32> = if corner_vertex.is_empty() {
        Vec::new()
    } else {
        vec![u32::MAX; n]
    };
    let mut out_positions = Vec::with_capacity(positions.len());
    let mut out_triangles = vec![[0u32; 3]; triangles.len()];
    for (t, (tri, out)) in triangles.iter().zip(&mut out_triangles).enumerate() {
        for k in 0..3 {
            let v = tri[k] as usize;
            let slot = if disc[v] {
                &mut by_vertex[v]
            } else {
                &mut renumber[corner_vertex[3 * t + k] as usize]
            };
            if *slot == u32::MAX {
                *slot = out_positions.len() as u32;
                out_positions.push(positions[v]);
            }
            out[k] = *slot;
        }
    }
    // Only half-edges with a twin to find can lack one; listed in half-edge order.
    let mut open: Vec<u32> = order
        .iter()
        .copied()
        .filter(|&h| twin[h as usize] == u32::MAX)
        .collect();
    open.sort_unstable();
    let cracks = open
        .iter()
        .flat_map(|&h| {
            [
                positions[from(h as usize) as usize],
                positions[to(h as usize) as usize],
            ]
        })
        .collect();
    let mesh = Mesh {
        positions: out_positions,
        triangles: out_triangles,
        sources,
    };
    (mesh, cracks)
}

/// A mesh file's solids that touch along an edge or at a point, given vertices of their own.
///
/// A file keeps no two vertices at one position apart once a reader welds them, so the shells
/// [`split_into_shells`] made for such solids share their touching vertices again when read
/// back: an edge of four faces, a vertex of two fans. Pairing the faces around such an edge by
/// angle, as the split did, and splitting each vertex per fan gives the same closed shells
/// back. `None` when there is nothing to split, and when the split leaves a half-edge without
/// a twin: the faces around a crowded edge do not alternate in direction (shells overlapping or
/// turned inside out there, not touching) or the mesh is open, a defect to report as it is.
///
/// Triangles must be in range and repeat no vertex (as readers leave them).
pub(crate) fn split_touching(mesh: &Mesh) -> Option<Mesh> {
    // Nearly every file: each vertex one disc, so nothing to split and no copy to make.
    let disc = one_disc(&mesh.triangles, mesh.positions.len());
    if mesh.triangles.iter().flatten().all(|&v| disc[v as usize]) {
        return None;
    }
    let mut used = vec![false; mesh.positions.len()];
    for t in &mesh.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let used = used.iter().filter(|&&u| u).count();
    let (split, cracks) = split_around_discs(
        mesh.positions.clone(),
        (mesh.triangles.clone(), mesh.sources.clone()),
        &disc,
        0.0,
    );
    (split.positions.len() > used && cracks.is_empty()).then_some(split)
}

/// For each corner (half-edge `h` sits at vertex `from(h)`) not at a `disc` vertex, the fan it
/// belongs to, named by its first corner (`u32::MAX` at disc vertices, whose corners are all one
/// fan: see [`one_disc`]; an empty list where every vertex is a disc). Around a vertex, the
/// corner of the previous half-edge's twin continues the fan.
///
/// `keyed` lists the half-edges not between two discs: every corner at a vertex that is not a
/// disc starts one of them (so none listed: every vertex is a disc), and only those are joined.
/// The sets keep their least member as root, so the names do not depend on the order joined.
fn fan_vertices(triangles: &[[u32; 3]], twin: &[u32], disc: &[bool], keyed: &[u32]) -> Vec<u32> {
    let n = triangles.len() * 3;
    if keyed.is_empty() {
        return Vec::new();
    }
    let mut fans = DisjointSets::new(n);
    for &h in keyed {
        let h = h as usize;
        if disc[triangles[h / 3][h % 3] as usize] {
            continue;
        }
        let prev = h / 3 * 3 + (h % 3 + 2) % 3;
        let t = twin[prev];
        if t != u32::MAX {
            fans.union(h, t as usize);
        }
    }
    let corners = triangles.iter().flatten().enumerate();
    corners
        .map(|(h, &v)| {
            if disc[v as usize] {
                u32::MAX
            } else {
                fans.find(h) as u32
            }
        })
        .collect()
}

/// For each crowded edge, how many of its half-edges share both output vertices with another
/// of its half-edges that is not their twin: the pairs that splitting the fans did not part.
fn pinched_edges(crowded: &[Vec<(u32, bool)>], corner_vertex: &[u32]) -> Vec<usize> {
    let ends = |h: usize| {
        let next = h / 3 * 3 + (h % 3 + 1) % 3;
        let (a, b) = (corner_vertex[h], corner_vertex[next]);
        (a.min(b), a.max(b))
    };
    crowded
        .iter()
        .map(|around| {
            let mut keys: Vec<(u32, u32)> = around.iter().map(|&(h, _)| ends(h as usize)).collect();
            keys.sort_unstable();
            let mut pinched = 0;
            let mut k = 0;
            while k < keys.len() {
                let mut m = k + 1;
                while m < keys.len() && keys[m] == keys[k] {
                    m += 1;
                }
                if m - k > 2 {
                    pinched += m - k;
                }
                k = m;
            }
            pinched
        })
        .collect()
}

/// For each crowded edge, the chain it belongs to (named by its first edge): crowded edges
/// sharing an end vertex are one chain, as the pairing of one decides the fans at that vertex.
fn chains_of(crowded: &[Vec<(u32, bool)>], triangles: &[[u32; 3]]) -> Vec<usize> {
    let mut sets = DisjointSets::new(crowded.len());
    let mut first_at: crate::hash::FxHashMap<u32, usize> = Default::default();
    for (g, around) in crowded.iter().enumerate() {
        let h = around[0].0 as usize;
        let t = triangles[h / 3];
        for v in [t[h % 3], t[(h % 3 + 1) % 3]] {
            let first = *first_at.entry(v).or_insert(g);
            sets.union(g, first);
        }
    }
    (0..crowded.len()).map(|g| sets.find(g)).collect()
}

/// The half-edges of a crowded edge sorted by the angle of their triangles about it, each with
/// whether it runs the same way as the first.
///
/// Around an edge where solids touch, the triangles alternate in direction. Each angle is that
/// of the triangle's far corner, good only to the weld over that corner's distance from the
/// edge: where two sheets touch across a gap thinner than the weld, their corners welded onto
/// each other, a triangle of one reaching beyond where the faces cross can read below the other
/// sheet though it lies above it along the edge (a box turned 1e-9° on a cut cylinder's top:
/// the gap 4e-12 … 8.4e-12 at the edge, the far corner 1.5e-11 below; two half-edges of one
/// direction side by side, which [`pair_around`] leaves without twins). With `ties` (the weld;
/// 0 for none), two neighbours of opposite direction within that noise of each other are
/// swapped where that makes their neighbours alternate. Slivers of two operands crossing on the
/// edge tie there too, and for them the angles' order is the one later passes close from (a
/// 32×16 sphere less itself turned 1e-6°), so the repair asks for this only where no ordinary
/// pass closes the mesh.
fn around_edge(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    group: &[u32],
    ties: f64,
) -> Vec<(u32, bool)> {
    let h0 = group[0] as usize;
    let (a, b) = (
        triangles[h0 / 3][h0 % 3],
        triangles[h0 / 3][(h0 % 3 + 1) % 3],
    );
    let (pa, pb) = (positions[a as usize], positions[b as usize]);
    let axis = (pb - pa).normalize_or_zero();
    let u = axis.any_orthonormal_vector();
    let w = axis.cross(u);
    // (angle, half-edge, forward, how far the weld may put the angle off)
    let mut around: Vec<(f64, u32, bool, f64)> = group
        .iter()
        .map(|&h| {
            let t = triangles[h as usize / 3];
            let apex = t[(h as usize % 3 + 2) % 3];
            let e = positions[apex as usize] - pa;
            let (x, y) = (e.dot(u), e.dot(w));
            let noise = if ties > 0.0 { ties / x.hypot(y) } else { 0.0 };
            (y.atan2(x), h, t[h as usize % 3] == a, noise)
        })
        .collect();
    around.sort_by(|x, y| x.0.total_cmp(&y.0));
    let m = around.len();
    if ties > 0.0 {
        for k in 0..m {
            let (prev, next, after) = ((k + m - 1) % m, (k + 1) % m, (k + 2) % m);
            let (p, q) = (around[k], around[next]);
            let apart = (q.0 - p.0).rem_euclid(std::f64::consts::TAU);
            if p.2 != q.2 && apart <= p.3 + q.3 && around[prev].2 == p.2 && around[after].2 == q.2 {
                around.swap(k, next);
            }
        }
    }
    around.into_iter().map(|(_, h, f, _)| (h, f)).collect()
}

/// Pairs the half-edges of a crowded edge: each forward one with its clockwise neighbour (across
/// the solid's interior wedge) when `across_solid`, else with its counter-clockwise one.
fn pair_around(around: &[(u32, bool)], across_solid: bool, twin: &mut [u32]) {
    let m = around.len();
    for k in 0..m {
        let (h, forward) = around[k];
        if !forward {
            continue;
        }
        // The interior of an a→b triangle lies clockwise (decreasing angle) of it.
        let other = if across_solid {
            (k + m - 1) % m
        } else {
            (k + 1) % m
        };
        let (partner, partner_forward) = around[other];
        if !partner_forward && twin[partner as usize] == u32::MAX {
            twin[h as usize] = partner;
            twin[partner as usize] = h;
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::split_into_shells;

    /// A tetrahedron with a fin on one edge: a triangle and its reverse, as the weld leaves a
    /// sliver thinner than itself. The fin is dropped, the tetrahedron left whole and closed;
    /// the fill's triangles (from `filled_from`) are not looked at.
    #[test]
    fn a_flat_fin_on_an_edge_is_dropped() {
        let positions = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(0.5, -1.0, -1.0),
        ];
        let tetrahedron = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        let fin = [[0, 1, 4], [4, 1, 0]];
        let triangles: Vec<[u32; 3]> = tetrahedron.iter().chain(&fin).copied().collect();
        let sources = vec![0; triangles.len()];
        let mut filled_from = triangles.len();
        let (mesh, cracks) = split_into_shells(
            positions.clone(),
            (triangles.clone(), sources.clone()),
            &mut filled_from,
            1e-12,
            false,
        );
        assert!(cracks.is_empty(), "{cracks:?}");
        assert_eq!(mesh.triangles.len(), 4);
        assert_eq!(filled_from, 4);
        assert!(mesh.report().is_closed_manifold(), "{}", mesh.report());
        assert!((mesh.volume() - 1.0 / 6.0).abs() < 1e-15);
        // The fin as the fill's: kept.
        let mut filled_from = 4;
        let (mesh, _) = split_into_shells(
            positions,
            (triangles, sources),
            &mut filled_from,
            1e-12,
            false,
        );
        assert_eq!((mesh.triangles.len(), filled_from), (6, 4));
    }

    /// A triangle and its reverse whose corners lie within a few welds of each other (one point
    /// computed three ways, a little beyond the weld) are kept for the wider weld to join, not
    /// dropped as a fin; the same pair at a tenth of the weld is longer than ten welds each way
    /// and is dropped.
    #[test]
    fn a_pair_within_ten_welds_is_not_a_fin() {
        let d = 1e-11;
        let positions = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(-2.0 * d, -3.0 * d, 0.0),
            DVec3::new(-3.0 * d, 0.0, -2.0 * d),
        ];
        let tetrahedron = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        let speck = [[0, 4, 5], [5, 4, 0]];
        let triangles: Vec<[u32; 3]> = tetrahedron.iter().chain(&speck).copied().collect();
        let sources = vec![0; triangles.len()];
        for (delta, kept) in [(d, 6), (0.1 * d, 4)] {
            let mut filled_from = triangles.len();
            let (mesh, _) = split_into_shells(
                positions.clone(),
                (triangles.clone(), sources.clone()),
                &mut filled_from,
                delta,
                false,
            );
            assert_eq!((mesh.triangles.len(), filled_from), (kept, kept), "{delta}");
        }
    }
}
