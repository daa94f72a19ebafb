//! Fins: sheets with no inside, two faces a weld apart that the weld laid onto each other,
//! dropped before the shells are split (see `shells::split_into_shells`).

use glam::DVec3;

/// [`cancel_reversed_pairs`] for a flat fin whose two sides cover one quad along different
/// diagonals: triangles `a b c` and `a c d` dropped with `a d b` and `d c b`, where `d` lies
/// within the weld (`shortest` over [`FIN_SHORTEST_WELDS`]) of the plane of `a b c`. The two
/// sides of one welded sheet are triangulated region by region, and a region that grew on one
/// side took the other diagonal: a union of a box turned 1e-9° with an unturned box on its face
/// left a slot 6.6e-12 wide, laid flat by the weld; the next union triangulated its sides apart,
/// and the repair split the slot's ends into two shells with 6 boundary edges. `keyed` is the
/// triangles looked at (rotated to their least vertex, sorted), `dropped` those already taken.
fn cancel_reversed_quads(
    (positions, shortest): (&[DVec3], f64),
    triangles: &[[u32; 3]],
    keyed: &[([u32; 3], u32)],
    dropped: &mut [bool],
) -> bool {
    let find = |t: [u32; 3], dropped: &[bool]| {
        let k = (0..3).min_by_key(|&k| t[k]).expect("three corners");
        let key = [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
        let at = keyed.partition_point(|&(k, _)| k < key);
        (at..keyed.len())
            .take_while(|&m| keyed[m].0 == key)
            .map(|m| keyed[m].1)
            .find(|&i| !dropped[i as usize])
    };
    let flat = shortest / FIN_SHORTEST_WELDS;
    // The triangles looked at by each directed edge.
    let mut by_edge: std::collections::HashMap<(u32, u32), Vec<u32>> = Default::default();
    for &(_, i) in keyed {
        let t = triangles[i as usize];
        for k in 0..3 {
            by_edge.entry((t[k], t[(k + 1) % 3])).or_default().push(i);
        }
    }
    let mut any = false;
    for &(_, i) in keyed {
        if dropped[i as usize] {
            continue;
        }
        let t = triangles[i as usize];
        'corners: for k in 0..3 {
            // `t` is `a b c` with `c → a` its edge k + 2; the quad's other half is `a c d`.
            // Every triangle across that edge is tried: on a crowded edge the fold's other
            // half need not be the first.
            let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let across = by_edge.get(&(a, c)).map_or(&[][..], Vec::as_slice);
            for &j in across {
                let u = triangles[j as usize];
                if j == i || dropped[j as usize] || u.contains(&b) {
                    continue;
                }
                let m = (0..3).find(|&m| u[m] == a).expect("a corner of the pair");
                let d = u[(m + 2) % 3];
                let [pa, pb, pc, pd] = [a, b, c, d].map(|v| positions[v as usize]);
                let n = (pb - pa).cross(pc - pa);
                if n.length() == 0.0 || ((pd - pa).dot(n) / n.length()).abs() > flat {
                    continue;
                }
                let Some(x) = find([a, d, b], dropped) else {
                    continue;
                };
                dropped[x as usize] = true;
                let Some(y) = find([d, c, b], dropped) else {
                    dropped[x as usize] = false;
                    continue;
                };
                for z in [i, j, x, y] {
                    dropped[z as usize] = true;
                }
                any = true;
                break 'corners;
            }
        }
    }
    any
}

/// How many welds long a fin's every edge must be for [`cancel_reversed_pairs`] to drop it:
/// the reach of the first wider weld the repair retries with.
///
/// A fin is a sliver laid flat along a crossing (its edges 10⁻⁷ … 0.6 long in the cases it
/// closes). A triangle and its reverse with an edge shorter than that are rather one point
/// computed several ways a little beyond the weld (where three spheres' poles meet, turned
/// 1e-9° and 1e-3° apart: four points within 2·10⁻¹¹ against a weld of 10⁻¹¹). Dropped, the
/// pass closed with the copies of the point apart, and the needles between them took 1.6·10⁻⁹
/// of the volume in vertex moves; kept, the pass leaves cracks there and the wider weld makes
/// them one point, closed with the volume right.
pub(super) const FIN_SHORTEST_WELDS: f64 = 10.0;

/// Drops each triangle together with one that holds the same three vertices the other way
/// round: a sheet with no inside, two faces a weld apart that the weld laid onto each other
/// (a sliver 10⁻¹² thick between faces crossing at 10⁻¹¹ rad, left by the boolean as a fin on
/// the solid's edge). Every edge of the pair is used once each way by it, so what is left
/// pairs as before; the pair bounds no volume. Kept, the fin's sides pair by the order of
/// their half-edges, their angles being equal: in the case traced they paired with each other,
/// and the vertices where the fin meets the solid split into two shells with boundary edges.
/// Only triangles before `filled_from` (where the flat fill's, which close a crack loop by the
/// reverse of what it bounds, start; moved down by those dropped) and at a vertex that is not a
/// disc (a pair's own corners never are, where it meets anything else) are looked at, and only
/// those whose every edge is longer than `shortest` (see [`FIN_SHORTEST_WELDS`]). True if any
/// was dropped.
pub(super) fn cancel_reversed_pairs(
    (positions, shortest): (&[DVec3], f64),
    triangles: &mut Vec<[u32; 3]>,
    sources: &mut Vec<u32>,
    disc: &[bool],
    filled_from: &mut usize,
) -> bool {
    // Each triangle rotated to start at its least vertex: a triangle and its reverse differ
    // only in the order of the last two.
    let rotated = |t: [u32; 3]| {
        let k = (0..3).min_by_key(|&k| t[k]).expect("three corners");
        [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
    };
    let mut keyed: Vec<([u32; 3], u32)> = triangles
        .iter()
        .enumerate()
        .take(*filled_from)
        .filter(|(_, t)| {
            t.iter().any(|&v| !disc[v as usize]) && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
        })
        .filter(|(_, t)| {
            let [a, b, c] = t.map(|v| positions[v as usize]);
            a.distance(b).min(b.distance(c)).min(c.distance(a)) > shortest
        })
        .map(|(i, &t)| (rotated(t), i as u32))
        .collect();
    if keyed.len() < 2 {
        return false;
    }
    keyed.sort_unstable();
    let mut dropped = vec![false; triangles.len()];
    let mut any = false;
    for j in 0..keyed.len() {
        let (key, i) = keyed[j];
        if dropped[i as usize] || key[1] > key[2] {
            continue;
        }
        let reverse = [key[0], key[2], key[1]];
        let at = keyed.partition_point(|&(k, _)| k < reverse);
        if let Some(m) = (at..keyed.len())
            .take_while(|&m| keyed[m].0 == reverse)
            .find(|&m| !dropped[keyed[m].1 as usize])
        {
            dropped[i as usize] = true;
            dropped[keyed[m].1 as usize] = true;
            any = true;
        }
    }
    any |= cancel_reversed_quads((positions, shortest), triangles, &keyed, &mut dropped);
    if !any {
        return false;
    }
    *filled_from -= dropped.iter().filter(|&&d| d).count();
    let mut k = 0;
    triangles.retain(|_| {
        k += 1;
        !dropped[k - 1]
    });
    let mut k = 0;
    sources.retain(|_| {
        k += 1;
        !dropped[k - 1]
    });
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat unit quad `0 1 2 3` split along 0–2 on one side and along 1–3 the other way
    /// round on the other, with triangle `0 1 4` off the sheet; the fourth corner lifted by
    /// `lift` along z. Returns the triangles kept and `filled_from` after the drop.
    fn fin_after_drop(lift: f64) -> (Vec<[u32; 3]>, usize) {
        let weld = 1e-6;
        let positions = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, lift),
            DVec3::new(0.5, -0.5, 1.0),
        ];
        let mut triangles = vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [3, 2, 1], [0, 1, 4]];
        let mut sources = vec![0, 0, 1, 1, 2];
        let mut filled_from = triangles.len();
        let disc = [false; 5];
        let fins = (&positions[..], FIN_SHORTEST_WELDS * weld);
        cancel_reversed_pairs(fins, &mut triangles, &mut sources, &disc, &mut filled_from);
        assert_eq!(sources.len(), triangles.len());
        (triangles, filled_from)
    }

    #[test]
    fn a_flat_quad_and_its_reverse_along_the_other_diagonal_are_dropped() {
        let (triangles, filled_from) = fin_after_drop(0.0);
        assert_eq!(triangles, vec![[0, 1, 4]]);
        assert_eq!(filled_from, 1);
        // Within the weld of the plane it is still one sheet.
        assert_eq!(fin_after_drop(0.5e-6).0, vec![[0, 1, 4]]);
    }

    #[test]
    fn a_quad_folded_two_welds_off_its_plane_is_kept() {
        let (triangles, filled_from) = fin_after_drop(2e-6);
        assert_eq!(triangles.len(), 5);
        assert_eq!(filled_from, 5);
    }

    /// The triangles [`cancel_reversed_pairs`] keeps of `triangles` at a weld of 1e-6, every
    /// vertex but `discs` taken as no disc.
    fn kept(positions: &[DVec3], triangles: &[[u32; 3]], discs: &[u32]) -> Vec<[u32; 3]> {
        let mut triangles = triangles.to_vec();
        let mut sources = vec![0; triangles.len()];
        let mut filled_from = triangles.len();
        let disc: Vec<bool> = (0..positions.len() as u32)
            .map(|v| discs.contains(&v))
            .collect();
        let fins = (positions, FIN_SHORTEST_WELDS * 1e-6);
        cancel_reversed_pairs(fins, &mut triangles, &mut sources, &disc, &mut filled_from);
        assert_eq!(
            (sources.len(), filled_from),
            (triangles.len(), triangles.len())
        );
        triangles
    }

    /// The same four triangles as a fold: `0 3 1` (area 0.5) laid over `0 1 2`, `0 2 3` and
    /// `3 2 1`, whose shared corner 2 lies inside it 10⁻⁷ from its edge 0–3, so that `0 2 3`
    /// is a sliver (5·10⁻⁸; a fork input's was 1.7·10⁻¹³ under triangles of 10⁻²). A closed
    /// flat tetrahedron too, dropped whole (corner 2, where only the three meet, is a disc:
    /// the others are not). Two welds above the sheet, the fold is kept.
    #[test]
    fn a_triangle_folded_over_a_sliver_is_dropped_with_it() {
        let fold = |lift: f64| {
            let positions = [
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(1e-7, 0.5, lift),
                DVec3::Y,
                DVec3::new(0.5, -0.5, 1.0),
            ];
            let triangles = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [3, 2, 1], [0, 1, 4]];
            kept(&positions, &triangles, &[2])
        };
        assert_eq!(fold(0.0), vec![[0, 1, 4]]);
        assert_eq!(fold(0.5e-6), vec![[0, 1, 4]]);
        assert_eq!(fold(2e-6).len(), 5);
    }

    /// The flat quad `2 3 4 5` split along 2–4 on one side and along 3–5 the other way round,
    /// on a crowded sheet: every edge its triangles are looked across (each of the 12 directed
    /// edges between its corners) also carries a triangle to a corner one unit off the sheet
    /// (0 above for edges running up in number, 1 below for the others, so no two of them are
    /// a reversed pair), and those come first across the edge (their least corner is lower).
    /// The fin goes however many triangles share its edges; the twelve stay.
    #[test]
    fn a_fin_is_dropped_when_its_other_half_is_not_first_across_the_edge() {
        let positions = [
            DVec3::new(0.5, 0.5, 1.0),
            DVec3::new(0.5, 0.5, -1.0),
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::Y,
        ];
        let fin = [[2, 3, 4], [2, 4, 5], [2, 5, 3], [5, 4, 3]];
        let mut crowd = Vec::new();
        for a in 2..6u32 {
            for c in 2..6u32 {
                if a != c {
                    crowd.push([a, c, if a < c { 0 } else { 1 }]);
                }
            }
        }
        let triangles: Vec<[u32; 3]> = fin.iter().chain(&crowd).copied().collect();
        assert_eq!(kept(&positions, &triangles, &[]), crowd);
    }

    /// Two thin pyramids base to base, 2·10⁻⁶ high each (two welds): the lower one's top
    /// split along 0–2, the upper one's bottom along 1–3. The four base triangles are a flat
    /// tetrahedron and go, as a union joins the two; the eight sides, themselves a thin closed
    /// solid, are no fin and all stay, closed, with both pyramids' volume.
    #[test]
    fn two_thin_parts_face_to_face_keep_everything_but_the_face() {
        let height = 2e-6;
        let positions = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::Y,
            DVec3::new(0.5, 0.5, -height),
            DVec3::new(0.5, 0.5, height),
        ];
        let face = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [3, 2, 1]];
        let below = [[1, 0, 4], [2, 1, 4], [3, 2, 4], [0, 3, 4]];
        let above = [[0, 1, 5], [1, 2, 5], [2, 3, 5], [3, 0, 5]];
        let triangles: Vec<[u32; 3]> = face.iter().chain(&below).chain(&above).copied().collect();
        let sides: Vec<[u32; 3]> = below.iter().chain(&above).copied().collect();
        let left = kept(&positions, &triangles, &[4, 5]);
        assert_eq!(left, sides);
        let mesh = crate::mesh::Mesh::new(positions.to_vec(), left);
        let report = mesh.report();
        assert!(report.is_closed_manifold(), "{report}");
        let want = 2.0 * height / 3.0;
        assert!(
            (mesh.volume() - want).abs() < 1e-9 * want,
            "{}",
            mesh.volume()
        );
    }
}
