//! The quick pass for a boolean that kept its far parts indexed: the polygons it passed through
//! whole away from the cut carry their input vertex ids, so only the cut region is welded,
//! searched for T-junctions and regrouped.

use glam::DVec3;

use super::{regions, rings_of, shells, tjunction};
use crate::geom::is_zero_area;
use crate::mesh::Mesh;
use crate::mesh::weld::{Wide, weld_within};
use crate::polygon::Polygon;

/// What a boolean knows of its output's topology: the polygons it passed through whole, with
/// one vertex id per corner (equal ids are equal positions, bit for bit).
///
/// - `polygons[..core]`: the **core**. Every vertex of a core polygon is surrounded only by
///   polygons passed through whole (so every edge is matched by the input's own neighbour),
///   none of them coplanar with a neighbour of its source (so no region would merge them).
///   Each is emitted as its fan, without welding, T-junction search or regrouping.
/// - `polygons[i]` for `i` in `rim`: the **rim**, passed through whole but touching the cut
///   region or a flat area; repaired with the cut polygons. Their ids tie the core's vertices
///   to the welded ones.
#[derive(Clone, Debug, Default)]
pub(crate) struct Indexed {
    pub core: usize,
    /// The rim polygons' indices, ascending (all at or past `core`).
    pub rim: Vec<u32>,
    /// The corners' vertex ids of the core polygons, then of the rim polygons, in order.
    pub ids: Vec<u32>,
    /// One more than the largest id.
    pub vertex_count: u32,
}

/// One repair pass over the rim and the cut polygons at weld tolerance `delta`, with the core's
/// fans added before the shells are split. `None` where a core fan degenerates (a seam vertex
/// welded onto another corner of it, or a fan triangle of zero area): the full pass decides.
pub(super) fn repair(
    polygons: &[Polygon],
    index: &Indexed,
    delta: f64,
) -> Option<(Mesh, Vec<DVec3>)> {
    let rest = &polygons[index.core..];
    let mut corners: Vec<DVec3> = Vec::with_capacity(rest.iter().map(|p| p.vertices().len()).sum());
    // Where each polygon's corners start in `corners`, counted from the core's end.
    let mut first_corner: Vec<u32> = Vec::with_capacity(rest.len());
    for p in rest {
        first_corner.push(corners.len() as u32);
        corners.extend_from_slice(p.vertices());
    }
    let wide = Wide::default();
    let (mut positions, map) = weld_within(&corners, delta, &wide);
    let core_corners: usize = polygons[..index.core]
        .iter()
        .map(|p| p.vertices().len())
        .sum();
    // The welded vertex of each id the rim uses; the core's own vertices come after them.
    let mut vertex_of = vec![u32::MAX; index.vertex_count as usize];
    let mut rim_ids = index.ids[core_corners..].iter();
    for &r in &index.rim {
        let at = first_corner[r as usize - index.core] as usize;
        let n = polygons[r as usize].vertices().len();
        for (&id, &v) in rim_ids.by_ref().take(n).zip(&map[at..at + n]) {
            vertex_of[id as usize] = v;
        }
    }
    let mut pinned = vec![false; positions.len()];
    let mut own = 0usize;
    for &id in &index.ids[..core_corners] {
        let v = &mut vertex_of[id as usize];
        if *v == u32::MAX {
            *v = (positions.len() + own) as u32;
            own += 1;
        } else if (*v as usize) < pinned.len() {
            // A seam vertex: no region of the rim may drop it.
            pinned[*v as usize] = true;
        }
    }
    let mut rings = rings_of(rest, &map, &positions, delta, index.core);
    // The core's edges between two welded vertices: the rim's edges across them are matched.
    let mut seam: Vec<(u32, u32)> = Vec::new();
    let mut at = 0usize;
    for p in &polygons[..index.core] {
        let ids = &index.ids[at..at + p.vertices().len()];
        at += ids.len();
        for k in 0..ids.len() {
            let a = vertex_of[ids[k] as usize];
            let b = vertex_of[ids[(k + 1) % ids.len()] as usize];
            if (a as usize) < pinned.len() && (b as usize) < pinned.len() {
                seam.push((a, b));
            }
        }
    }
    let known = tjunction::insert_on_edges(&positions, &[], &mut rings, delta, &wide, true, &seam);
    let (mut triangles, mut sources) =
        regions::triangulate_regions(&positions, &rings, polygons, delta, &pinned, known);
    // The core's own vertices, in the order they were numbered above.
    let welded = positions.len();
    positions.resize(welded + own, DVec3::ZERO);
    let mut at = 0usize;
    triangles.reserve(core_corners);
    sources.reserve(core_corners);
    for p in &polygons[..index.core] {
        let vs = p.vertices();
        let ids = &index.ids[at..at + vs.len()];
        at += vs.len();
        let v = |k: usize| vertex_of[ids[k] as usize];
        for (k, &x) in vs.iter().enumerate() {
            if v(k) as usize >= welded {
                positions[v(k) as usize] = x;
            }
        }
        for k in 1..vs.len() - 1 {
            let t = [v(0), v(k), v(k + 1)];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                return None;
            }
            if is_zero_area(t.map(|i| positions[i as usize])) {
                return None;
            }
            triangles.push(t);
            sources.push(p.source());
        }
    }
    // No fill here: every triangle may be looked at for a reversed twin.
    let mut filled_from = triangles.len();
    Some(shells::split_into_shells(
        positions,
        (triangles, sources),
        &mut filled_from,
    ))
}
