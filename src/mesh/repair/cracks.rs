//! Closing the cracks no weld could close: thin slits that lie in one plane.
//!
//! Where two faces meet at a tiny angle α, the line where they cross is only known to within
//! a rounding error over α: 10⁻¹⁷ / 10⁻¹⁰ puts it 10⁻⁷ off. Each operand's face is cut where
//! the other's plane crosses it, computed along different edges, so the two cut lines can lie
//! that far apart, in the same plane, and the surface between them belongs to neither: a slit
//! far wider than any weld. The slit bounds a piece of surface that lies flat in the plane of
//! the faces on both sides, so filling it with triangles in that plane closes the mesh and
//! moves nothing (the piece has no thickness; the volume is unchanged).
//!
//! The same loops arise around a flap: at a corner where four planes meet to rounding (a cube
//! less itself turned 1e-7° about a skew axis: one cube's corner lies on the other's face, its
//! motion being along that face), one sheet of a thin wedge holds a triangle 10⁻¹⁰ across that
//! the sheet against it lacks. Its rim is the loop; filling it would lay the reverse triangle
//! on it, a sheet of no thickness, so the flap is taken away instead — a flap of several
//! triangles too, however the fill would have drawn its diagonals.

use glam::DVec3;

use crate::geom::Plane;
use crate::geom::triangulate::{ear_clip_boundary, triangulate_boundary};
use crate::hash::FxHashMap;

/// Fills every loop of unpaired half-edges that lies within `flat` of one plane with triangles
/// running the other way, each taking the source of the triangle beside the loop's first edge;
/// a fill triangle that would lie on an existing one's reverse removes that one instead.
/// Loops that are not flat, or do not close, are left alone. Returns how many triangles were
/// removed (all from before the fill, so the fill's own start moves back by as many).
pub(super) fn close_flat_cracks(
    positions: &[DVec3],
    (triangles, sources): &mut (Vec<[u32; 3]>, Vec<u32>),
    flat: f64,
) -> usize {
    let mut cancelled: Vec<u32> = Vec::new();
    let mut uses: FxHashMap<(u32, u32), i32> = FxHashMap::default();
    let mut owner: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            *uses.entry((a, b)).or_default() += 1;
            owner.insert((a, b), t as u32);
        }
    }
    // Unpaired half-edges by their start vertex.
    let mut open: FxHashMap<u32, Vec<u32>> = FxHashMap::default();
    let mut ends: Vec<(u32, u32)> = Vec::new();
    let mut keys: Vec<(u32, u32)> = uses.keys().copied().collect();
    keys.sort_unstable();
    for (a, b) in keys {
        let surplus = uses[&(a, b)] - uses.get(&(b, a)).copied().unwrap_or(0);
        for _ in 0..surplus.max(0) {
            open.entry(a).or_default().push(ends.len() as u32);
            ends.push((a, b));
        }
    }
    let mut used = vec![false; ends.len()];
    // The triangles at each vertex (from `fan[v]` to `fan[v + 1]` in `list`), for the flaps
    // of several triangles.
    let (mut fan, mut list) = (Vec::new(), Vec::new());
    if !ends.is_empty() {
        fan = vec![0u32; positions.len() + 1];
        for tri in triangles.iter() {
            for &v in tri {
                fan[v as usize + 1] += 1;
            }
        }
        for v in 0..positions.len() {
            fan[v + 1] += fan[v];
        }
        let mut next = fan.clone();
        list = vec![0u32; 3 * triangles.len()];
        for (t, tri) in triangles.iter().enumerate() {
            for &v in tri {
                list[next[v as usize] as usize] = t as u32;
                next[v as usize] += 1;
            }
        }
    }
    for start in 0..ends.len() {
        if used[start] {
            continue;
        }
        let Some(edges) = trace(&ends, &open, &mut used, start) else {
            continue;
        };
        let ring: Vec<DVec3> = edges.iter().map(|&(a, _)| positions[a as usize]).collect();
        let Some(plane) = Plane::from_points(&ring) else {
            continue;
        };
        if ring.iter().any(|&p| plane.distance(p).abs() > flat) {
            continue;
        }
        // The fill runs against the loop, so each of its edges pairs with an open one.
        let fill: Vec<(u32, u32)> = edges.iter().rev().map(|&(a, b)| (b, a)).collect();
        let normal = -plane.normal;
        let tris = triangulate_boundary(positions, normal, &fill)
            .unwrap_or_else(|| ear_clip_boundary(positions, normal, &fill));
        if tris.len() + 2 != fill.len() {
            continue;
        }
        // A flap of several triangles whose diagonals the fill would not draw the same way:
        // taken away whole.
        if let Some(patch) = flap_patch(&uses, triangles, (&fan, &list), &edges) {
            cancelled.extend(patch);
            continue;
        }
        let source = sources[owner[&edges[0]] as usize];
        // A rim of three edges bounds one triangle: other triangles at its corners hold it.
        let corners = (tris.len() == 1).then_some(&fan[..]);
        let ears = ears_on_rim(&owner, &uses, triangles, &tris, &edges);
        for (tri, ear) in tris.into_iter().zip(ears) {
            // A fill triangle that is the reverse of one already there would make the two a
            // sheet of no thickness: the loop was a flap's rim, and the flap goes instead.
            if let Some(t) = flap(&owner, &uses, triangles, tri, corners).or(ear) {
                cancelled.push(t);
            } else {
                sources.push(source);
                triangles.push(tri);
            }
        }
    }
    if cancelled.is_empty() {
        return 0;
    }
    let mut gone = vec![false; triangles.len()];
    for &t in &cancelled {
        gone[t as usize] = true;
    }
    let mut keep = gone.iter().map(|&g| !g);
    triangles.retain(|_| keep.next().unwrap_or(true));
    let mut keep = gone.iter().map(|&g| !g);
    sources.retain(|_| keep.next().unwrap_or(true));
    gone.iter().filter(|&&g| g).count()
}

/// The triangle already in `triangles` that runs exactly against `tri`, if any, and that other
/// triangles hold by an edge too, or, where `corners` (where each vertex's triangles start in
/// the list of them, as `fan` in [`close_flat_cracks`]) is given for a rim of one triangle,
/// at a corner: a flap on the surface. A lone face's triangles are
/// not flaps (taken away, the face would vanish, and an open result become an empty one).
///
/// A flap held by its corners alone: a cuboid ∪ a slab whose top is a grid of triangles,
/// turned 1e-9° (both of one source), left one triangle of the slab's top 0.075 long and
/// 5e-7 high on the crossing line of the two tops, a grid vertex the line passes within
/// rounding of at its apex, its other corners on the surface around it, which closed without
/// it; none of its edges was anyone else's. Filled, it and its reverse were a flat shell.
///
/// Looked for across each of `tri`'s three edges: `owner` keeps one triangle per half-edge, and
/// a flap's edge on the surface is crowded, often used the same way by a triangle of the
/// surface too, which `owner` may hold there instead. Asked across that edge alone, the flap
/// was missed and the fill laid its reverse on it: a sheet and its own reverse, a flat shell
/// (a cube less itself turned 2e-6° about (0.3, 1, 0.2): a lone sliver of the x = 1 face, 3e-8
/// wide, hanging by an edge on a wedge's own face there).
fn flap(
    owner: &FxHashMap<(u32, u32), u32>,
    uses: &FxHashMap<(u32, u32), i32>,
    triangles: &[[u32; 3]],
    tri: [u32; 3],
    corners: Option<&[u32]>,
) -> Option<u32> {
    let held = |a: u32, b: u32| {
        uses.get(&(a, b)).copied().unwrap_or(0) + uses.get(&(b, a)).copied().unwrap_or(0)
    };
    let by_edge = (0..3).any(|k| held(tri[k], tri[(k + 1) % 3]) >= 3);
    if !by_edge && corners.is_none() {
        return None;
    }
    let t = reverse_of(owner, triangles, tri)?;
    let at_corner = |fan: &[u32]| {
        tri.iter()
            .any(|&v| fan[v as usize + 1] - fan[v as usize] > 1)
    };
    (by_edge || corners.is_some_and(at_corner)).then_some(t)
}

/// The triangle already there that runs exactly against `tri` (its corners in reverse, from
/// any start), found across any of `tri`'s edges (`owner` keeps one triangle per half-edge).
fn reverse_of(
    owner: &FxHashMap<(u32, u32), u32>,
    triangles: &[[u32; 3]],
    tri: [u32; 3],
) -> Option<u32> {
    let reversed = [tri[0], tri[2], tri[1]];
    let turns = |other: [u32; 3]| {
        (0..3).any(|k| other == [reversed[k], reversed[(k + 1) % 3], reversed[(k + 2) % 3]])
    };
    (0..3)
        .filter_map(|k| owner.get(&(tri[(k + 1) % 3], tri[k])).copied())
        .find(|&t| turns(triangles[t as usize]))
}

/// For each of a loop's fill triangles `tris`, the triangle already there that runs exactly
/// against it and is an ear of the face beside the loop, if any: two of the ear's edges or one
/// lie on the loop's `rim` and each other edge is paired (the face holds it there). Laid on
/// the ear, the fill triangle and the ear made a closed shell of no volume, kept as the
/// fill's (see [`super::thin`]); the ear is taken away instead, which leaves the same edges to
/// pair, as the loop's other fill triangles close the face's rim. None where every fill
/// triangle would so go: the loop is then a lone face's rim (see [`flap`]), not a slit beside
/// a face.
///
/// A slit where a cuboid's top and a slab's turned 1e-6° cross, cut along the slab's
/// diagonal on one side and at the computed crossing line on the other (up to 1.3e-9 apart),
/// ended at a corner of the cube's top whose triangulation held a sliver ear (area 1.6e-10)
/// on the slit's rim: the fill's triangle across that end was the ear's reverse.
fn ears_on_rim(
    owner: &FxHashMap<(u32, u32), u32>,
    uses: &FxHashMap<(u32, u32), i32>,
    triangles: &[[u32; 3]],
    tris: &[[u32; 3]],
    rim: &[(u32, u32)],
) -> Vec<Option<u32>> {
    let ear = |tri: [u32; 3]| {
        let t = reverse_of(owner, triangles, tri)?;
        let reversed = [tri[0], tri[2], tri[1]];
        let held = (0..3).all(|k| {
            let (a, b) = (reversed[k], reversed[(k + 1) % 3]);
            rim.contains(&(a, b)) || uses.get(&(b, a)).copied().unwrap_or(0) >= 1
        });
        held.then_some(t)
    };
    let ears: Vec<Option<u32>> = tris.iter().map(|&tri| ear(tri)).collect();
    if ears.iter().all(Option::is_some) {
        return vec![None; tris.len()];
    }
    ears
}

/// The triangles already there that make up a flap with `rim` (a loop of unpaired half-edges)
/// as their whole boundary, if any: two or more triangles (one is [`flap`]'s) with no corner
/// off the rim, held by the surface by an edge (one used by three triangles or more: else they
/// are a lone face, see [`flap`]). Filled, such a flap would get the fill's
/// reverse laid on it, and where the fill draws its diagonals otherwise than the flap does, no
/// fill triangle is a flap triangle's reverse: the two made a closed shell of no volume, kept
/// as the fill's (see [`super::thin`]). A flap of two slivers 10⁻⁹ wide, where a cube turned
/// 1e-6° and a box meet on their crossing line, was so left.
fn flap_patch(
    uses: &FxHashMap<(u32, u32), i32>,
    triangles: &[[u32; 3]],
    around: (&[u32], &[u32]),
    rim: &[(u32, u32)],
) -> Option<Vec<u32>> {
    let n = rim.len();
    if n < 4 {
        return None;
    }
    let (start, list) = around;
    let at = |v: u32| &list[start[v as usize] as usize..start[v as usize + 1] as usize];
    let corners: Vec<u32> = rim.iter().map(|&(a, _)| a).collect();
    let mut patch: Vec<u32> = Vec::new();
    for &v in &corners {
        for &t in at(v) {
            if !patch.contains(&t) && triangles[t as usize].iter().all(|c| corners.contains(c)) {
                patch.push(t);
            }
        }
    }
    if patch.len() != n - 2 {
        return None;
    }
    let mut boundary: Vec<(u32, u32)> = Vec::with_capacity(n);
    for &t in &patch {
        let tri = triangles[t as usize];
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if let Some(i) = boundary.iter().position(|&e| e == (b, a)) {
                boundary.swap_remove(i);
            } else {
                boundary.push((a, b));
            }
        }
    }
    boundary.sort_unstable();
    let mut loop_edges = rim.to_vec();
    loop_edges.sort_unstable();
    if boundary != loop_edges {
        return None;
    }
    let held = |a: u32, b: u32| {
        uses.get(&(a, b)).copied().unwrap_or(0) + uses.get(&(b, a)).copied().unwrap_or(0)
    };
    let crowded = patch.iter().any(|&t| {
        let tri = triangles[t as usize];
        (0..3).any(|k| held(tri[k], tri[(k + 1) % 3]) >= 3)
    });
    crowded.then_some(patch)
}

/// Follows unpaired half-edges from `start` until they come back to its first vertex; `None`
/// (and the edges left free) when the walk ends elsewhere.
fn trace(
    ends: &[(u32, u32)],
    open: &FxHashMap<u32, Vec<u32>>,
    used: &mut [bool],
    start: usize,
) -> Option<Vec<(u32, u32)>> {
    let first = ends[start].0;
    let mut path = vec![start as u32];
    used[start] = true;
    let mut at = ends[start].1;
    while at != first {
        let next = open
            .get(&at)
            .and_then(|list| list.iter().copied().find(|&e| !used[e as usize]));
        let Some(e) = next.filter(|_| path.len() < ends.len()) else {
            for &e in &path {
                used[e as usize] = false;
            }
            used[start] = true;
            return None;
        };
        used[e as usize] = true;
        path.push(e);
        at = ends[e as usize].1;
    }
    Some(path.iter().map(|&e| ends[e as usize]).collect())
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::close_flat_cracks;
    use crate::topology::check_closed;

    /// Whether every edge of `triangles` is used once each way.
    fn closed(triangles: &[[u32; 3]]) -> bool {
        check_closed(triangles).is_ok()
    }

    /// A slit in the flat top of a pyramid whose rim runs along two edges of a sliver ear
    /// `0 1 2` (10⁻⁶ high on an edge of 1) folded over the face beside it: the ear faces
    /// against the top, as rounding leaves a sliver where two tops cross at a hair, and
    /// hangs on the top's edge 0–2. The slit `0 → 1 → 2 → 3` turns back at 0 (its corner 3
    /// lies 10⁻⁷ below the line 0–2, left of 0), so its only fill is `0 3 2` and `2 1 0`, the
    /// ear's exact reverse, none of whose edges has three uses: no flap. Laid on the ear, the
    /// two made a closed flat shell and the top's edge 0–2 two uses each way; the ear is taken
    /// away instead and the top closes as one sheet.
    #[test]
    fn a_fill_triangle_that_reverses_an_ear_on_the_rim_takes_the_ear_away() {
        let positions = vec![
            DVec3::ZERO,
            DVec3::new(0.5, 1e-6, 0.0),
            DVec3::X,
            DVec3::new(-0.1, -1e-7, 0.0),
            DVec3::new(0.5, 1.0, 0.0),
            DVec3::new(0.5, -1.0, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.5, 0.0, -1.0),
        ];
        let ear = [0, 1, 2];
        let top = [
            [0, 2, 4],
            ear,
            [2, 7, 4],
            [6, 0, 4],
            [3, 0, 6],
            [6, 5, 3],
            [2, 3, 5],
            [5, 7, 2],
        ];
        let sides = [[5, 6, 8], [7, 5, 8], [4, 7, 8], [6, 4, 8]];
        let triangles: Vec<[u32; 3]> = top.iter().chain(&sides).copied().collect();
        let count = triangles.len();
        assert!(!closed(&triangles));
        let mut mesh = (triangles, vec![0; count]);
        assert_eq!(close_flat_cracks(&positions, &mut mesh, 1e-12), 1);
        assert!(!mesh.0.contains(&ear), "{:?}", mesh.0);
        assert!(closed(&mesh.0), "{:?}", mesh.0);
        // One fill triangle in for the ear: `0 3 2`.
        assert_eq!(mesh.0.len(), count);
        assert_eq!(mesh.1.len(), count);
    }

    /// A flap of two slivers hung on a tetrahedron's edge 0–1, whose rim the fill would close by
    /// the other diagonal (4–5, the short one): no fill triangle is the reverse of a flap's, and
    /// the fill laid on the flap made a closed shell of no volume. The flap is taken away whole
    /// instead, the tetrahedron left as it was.
    #[test]
    fn a_flap_of_two_triangles_is_taken_away() {
        let positions = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(0.5, 1e-3, 0.0),
            DVec3::new(0.5, -1e-3, 0.0),
        ];
        let tetrahedron = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        let flap = [[0, 4, 1], [1, 5, 0]];
        let triangles: Vec<[u32; 3]> = tetrahedron.iter().chain(&flap).copied().collect();
        let mut mesh = (triangles, vec![0; 6]);
        assert_eq!(close_flat_cracks(&positions, &mut mesh, 1e-12), 2);
        assert_eq!(mesh.0, tetrahedron.to_vec());
    }

    /// A lone triangle on a tetrahedron's face, sharing two of its corners (0 and 1) but none
    /// of its edges (its apex 4 is its own): held at its corners, it is taken away, not
    /// filled into a flat shell with its reverse. Alone, a triangle is a face and is filled.
    #[test]
    fn a_triangle_held_at_its_corners_alone_is_taken_away() {
        let positions = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(0.5, 1e-3, 0.0),
        ];
        let tetrahedron = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        let triangles: Vec<[u32; 3]> = tetrahedron.iter().chain(&[[0, 4, 1]]).copied().collect();
        let mut mesh = (triangles, vec![0; 5]);
        assert_eq!(close_flat_cracks(&positions, &mut mesh, 1e-12), 1);
        assert_eq!(mesh.0, tetrahedron.to_vec());
        let mut alone = (vec![[0, 4, 1]], vec![0]);
        assert_eq!(close_flat_cracks(&positions, &mut alone, 1e-12), 0);
        assert_eq!(alone.0.len(), 2);
    }
}
