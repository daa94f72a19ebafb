//! The quick pass for a boolean that kept its far parts indexed: the polygons it passed through
//! whole away from the cut carry their input vertex ids, so only the cut region is welded,
//! searched for T-junctions and regrouped.

use glam::DVec3;
use rayon::prelude::*;

use super::discs::one_disc;
use super::pass::rings_of;
use super::{regions, shells, tjunction};
use crate::geom::is_zero_area;
use crate::mesh::Mesh;
use crate::mesh::needles::KnownAreas;
use crate::mesh::weld::{Wide, weld_within};
use crate::polygon::Polygon;

/// Polygons per run of the parallel gather of the rim's and the cut polygons' corners.
const GATHER_RUN: usize = 1024;

/// What a boolean knows of its output's topology: the polygons it passed through whole, with
/// one vertex id per corner (equal ids are equal positions, bit for bit).
///
/// - `polygons[..core]`: the **core**. Every vertex of a core polygon is surrounded only by
///   polygons passed through whole (so every edge is matched by the input's own neighbour),
///   and where polygons around it could merge as coplanar, they fall into three or more merge
///   classes (so no region drops it or holds it inside: see `solid::far::merge_classes`).
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
    /// How many of `ids` are the core's (the rim's follow).
    pub core_corners: usize,
    /// One more than the largest id.
    pub vertex_count: u32,
    /// Ids below this are the first operand's, the rest the second's.
    pub a_vertices: u32,
    /// Per operand, whether its polygons are discs by position (a checked mesh's: see
    /// `mesh::import::MeshPolygons::discs_if_apart`), so that the core's own vertices need no
    /// link walk (see [`discs_around_core`]).
    pub discs: [bool; 2],
    /// Per operand, whether no triangle of its core polygons' fans (from the first corner, as
    /// here) is of zero area, as checked where the solid was made (see
    /// `solid::vertex_ids::check_fans`): a fan whose corners are all own vertices of the
    /// core is then not tested again.
    pub fans: [bool; 2],
    /// Per operand, the least twice area, squared, of a triangle of its polygons' fans, as
    /// found where the solid was made (0 where not known: see
    /// `solid::vertex_ids::check_fans`), for the needle pass to skip the core's fans.
    pub least_fan: [f64; 2],
}

/// One repair pass over the rim and the cut polygons at weld tolerance `delta`, with the core's
/// fans added before the shells are split. `None` where a core fan degenerates (a seam vertex
/// welded onto another corner of it, or a fan triangle of zero area): the full pass decides.
/// Also returns the fans of core polygons whose every corner is an own vertex, by their places
/// in the mesh, with the least twice area, squared, their operands' fans were found to have
/// (see [`Indexed::least_fan`]): the shells are split without moving a triangle.
pub(super) fn repair(
    polygons: &[Polygon],
    index: &Indexed,
    delta: f64,
) -> Option<(Mesh, Vec<DVec3>, KnownAreas)> {
    let rest = &polygons[index.core..];
    // Where each polygon's corners start in `corners` (counted from the core's end), and the
    // corners, copied in runs in parallel, each run into its own part of the list: the polygons
    // lie a few hundred bytes apart, and reading them one after the other (twice: once to size
    // the list) was a tenth of this pass's time on the calling thread (rocker-arm, two threads).
    let mut first_corner: Vec<u32> = rest
        .par_iter()
        .with_min_len(GATHER_RUN)
        .map(|p| p.vertices().len() as u32)
        .collect();
    let mut total = 0u32;
    for f in &mut first_corner {
        (*f, total) = (total, total + *f);
    }
    let mut corners = vec![DVec3::ZERO; total as usize];
    let mut parts: Vec<&mut [DVec3]> = Vec::with_capacity(rest.len().div_ceil(GATHER_RUN));
    let mut tail = &mut corners[..];
    for k in (0..rest.len()).step_by(GATHER_RUN) {
        let end = first_corner.get(k + GATHER_RUN).copied().unwrap_or(total);
        let (part, after) = tail.split_at_mut((end - first_corner[k]) as usize);
        parts.push(part);
        tail = after;
    }
    rest.par_chunks(GATHER_RUN)
        .zip(parts)
        .for_each(|(run, part)| {
            let mut at = 0;
            for p in run {
                let vs = p.vertices();
                part[at..at + vs.len()].copy_from_slice(vs);
                at += vs.len();
            }
        });
    let wide = Wide::default();
    let (positions, map) = weld_within(&corners, delta, &wide);
    let core_corners = index.core_corners;
    // The welded vertex of each id the rim uses; the core's own vertices come after them.
    let mut vertex_of = vec![u32::MAX; index.vertex_count as usize];
    // Whether discs by position may stand for the core's own vertices: not where the weld made
    // two ids one vertex (see [`discs_around_core`]). Per welded vertex, the id a rim corner
    // gave it.
    let mut by_position = index.discs[0] || index.discs[1];
    let mut id_at = vec![u32::MAX; if by_position { positions.len() } else { 0 }];
    let mut rim_ids = index.ids[core_corners..].iter();
    for &r in &index.rim {
        let at = first_corner[r as usize - index.core] as usize;
        let n = polygons[r as usize].vertices().len();
        for (&id, &v) in rim_ids.by_ref().take(n).zip(&map[at..at + n]) {
            vertex_of[id as usize] = v;
            if let Some(taken) = id_at.get_mut(v as usize) {
                by_position &= *taken == u32::MAX || *taken == id;
                *taken = id;
            }
        }
    }
    drop(id_at);
    let disc_of = |id: u32| by_position && index.discs[usize::from(id >= index.a_vertices)];
    let mut pinned = vec![false; positions.len()];
    let mut own = 0usize;
    // Whether each of the core's own vertices is a disc by position, in the order numbered.
    let mut own_discs: Vec<bool> = Vec::new();
    for &id in &index.ids[..core_corners] {
        let v = &mut vertex_of[id as usize];
        if *v == u32::MAX {
            *v = (positions.len() + own) as u32;
            own += 1;
            if by_position {
                own_discs.push(disc_of(id));
            }
        } else if (*v as usize) < pinned.len() {
            // A seam vertex: no region of the rim may drop it.
            pinned[*v as usize] = true;
        }
    }
    let mut rings = rings_of(rest, &map, &positions, delta, index.core);
    // The rim's and the cut polygons' repair, and beside it the core's fans (which read only
    // the welded positions and write the core's own vertices): the two ran one after the other
    // on one thread, the fans about a twentieth of this pass (5 M instructions of 90 M on
    // rocker-arm). Joined in that order, whatever the threads. The seam is found on the first
    // side, beside the fans, rather than before the join on the calling thread, and the rings
    // are dropped there once the regions are made.
    //
    // The fans' side also lays out the output's positions, the welded ones and the core's own
    // after them (the own ones' list, appended afterwards, was copied on the calling thread).
    let welded = positions.len();
    let ((mut triangles, mut sources), core) = rayon::join(
        || {
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
            let known =
                tjunction::insert_on_edges(&positions, &[], &mut rings, delta, &wide, true, &seam);
            let made =
                regions::triangulate_regions(&positions, &rings, polygons, delta, &pinned, known);
            drop(rings);
            made
        },
        || {
            core_fans(
                polygons,
                index,
                &vertex_of,
                &positions,
                own,
                &own_discs,
                by_position,
            )
        },
    );
    let core = core?;
    let positions = core.positions;
    // The triangles whose links are walked (where some own vertex may be a disc by position):
    // all but the fans of core polygons whose corners are all such vertices.
    let mut walked: Vec<[u32; 3]> = Vec::new();
    if by_position {
        walked.reserve(triangles.len() + core.walked.len());
        walked.extend_from_slice(&triangles);
        walked.extend_from_slice(&core.walked);
    }
    let at = triangles.len() as u32;
    let known = KnownAreas {
        ranges: core
            .known
            .ranges
            .iter()
            .map(|&(s, e)| (s + at, e + at))
            .collect(),
        least: core.known.least,
    };
    triangles.extend_from_slice(&core.triangles);
    sources.extend_from_slice(&core.sources);
    let disc = if by_position {
        discs_around_core(&walked, positions.len(), welded, &own_discs)
    } else {
        one_disc(&triangles, positions.len())
    };
    // No fin (a triangle and its reverse) is dropped here, as the full pass does: one whose
    // sides pair with each other splits its vertices and leaves cracks, and the full pass
    // follows. One folded into the solid's own pairs (a slit of no width) would be kept.
    // Every indexed boolean of the unit tests checks the skip against the walk of every link.
    #[cfg(test)]
    assert_eq!(disc, one_disc(&triangles, positions.len()));
    let (mesh, cracks) = shells::split_around_discs(positions, (triangles, sources), &disc, 0.0);
    Some((mesh, cracks, known))
}

/// The core's fans, numbered as they follow the rim's and the cut polygons' triangles (from 0
/// here), with the output's positions (the welded ones, then the `own` core's own vertices,
/// numbered from the welded ones' count), the fans whose links are walked and the ranges of
/// those checked where the solid was made (see [`repair`]). `None` where a fan degenerates.
struct CoreFans {
    triangles: Vec<[u32; 3]>,
    sources: Vec<u32>,
    positions: Vec<DVec3>,
    walked: Vec<[u32; 3]>,
    known: KnownAreas,
}

fn core_fans(
    polygons: &[Polygon],
    index: &Indexed,
    vertex_of: &[u32],
    welded_positions: &[DVec3],
    own: usize,
    own_discs: &[bool],
    by_position: bool,
) -> Option<CoreFans> {
    let welded = welded_positions.len();
    let mut positions = Vec::with_capacity(welded + own);
    positions.extend_from_slice(welded_positions);
    positions.resize(welded + own, DVec3::ZERO);
    let (welded_positions, own_positions) = positions.split_at_mut(welded);
    let welded_positions = &*welded_positions;
    let at_of = |i: u32, own_positions: &[DVec3]| {
        let i = i as usize;
        if i < welded {
            welded_positions[i]
        } else {
            own_positions[i - welded]
        }
    };
    // Room for every fan (fewer triangles than corners; the rim's corners are few).
    let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(index.ids.len());
    let mut sources: Vec<u32> = Vec::with_capacity(index.ids.len());
    let mut walked: Vec<[u32; 3]> = Vec::new();
    let mut known = KnownAreas {
        ranges: Vec::new(),
        least: f64::INFINITY,
    };
    let mut at = 0usize;
    for p in &polygons[..index.core] {
        let vs = p.vertices();
        let ids = &index.ids[at..at + vs.len()];
        at += vs.len();
        let v = |k: usize| vertex_of[ids[k] as usize];
        let mut walk = false;
        let mut own = true;
        for (k, &x) in vs.iter().enumerate() {
            let i = v(k) as usize;
            if i >= welded {
                own_positions[i - welded] = x;
                walk |= by_position && !own_discs[i - welded];
            } else {
                walk = true;
                own = false;
            }
        }
        // Every corner an own vertex: its position is this polygon's corner, bit for bit (equal
        // ids are equal positions, but for the sign of a zero, which no magnitude the test
        // computes depends on), so the fan is the one checked when the solid was made.
        let operand = usize::from(ids[0] >= index.a_vertices);
        let checked = own && index.fans[operand];
        if own && index.least_fan[operand] > 0.0 {
            let at = triangles.len() as u32;
            let past = at + vs.len() as u32 - 2;
            match known.ranges.last_mut() {
                Some(last) if last.1 == at => last.1 = past,
                _ => known.ranges.push((at, past)),
            }
            known.least = known.least.min(index.least_fan[operand]);
        }
        for k in 1..vs.len() - 1 {
            let t = [v(0), v(k), v(k + 1)];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                return None;
            }
            #[cfg(test)]
            assert!(!checked || !is_zero_area(t.map(|i| at_of(i, own_positions))));
            if !checked && is_zero_area(t.map(|i| at_of(i, own_positions))) {
                return None;
            }
            triangles.push(t);
            sources.push(p.source());
            if walk && by_position {
                walked.push(t);
            }
        }
    }
    Some(CoreFans {
        triangles,
        sources,
        positions,
        walked,
        known,
    })
}

/// Which vertices are discs ([`one_disc`]) in the mesh of the rim's and the cut polygons'
/// triangles and the core's fans, from the links of `walked` alone: all of those triangles
/// but the fans of core polygons whose every corner is an own vertex (numbered from `welded`)
/// that `own_discs` says is a disc by position.
///
/// An own vertex is used by the fans of core polygons alone: every polygon around its position
/// was passed through whole, all of them core (a rim polygon's corners are welded, see
/// [`Indexed`]). So its triangles are the fans of all of its operand's polygons at that
/// position, and its link's vertices are the output vertices of the ids around it: own
/// vertices, one per id, and welded ones, one per id unless the weld made two ids one vertex
/// (the caller then walks every link). Where its operand is discs by position, it is a disc,
/// and needs no walk: the core far from the cut costs nothing here. Every other vertex has all
/// its triangles in `walked`: a welded one those of the rim and the cut polygons and the fans
/// of every core polygon holding it (each has a welded corner), an own one not a disc by
/// position the fans of every polygon around it (each has it as a corner). A wrong skip would
/// keep one vertex where two fans meet and leave its half-edges without their twins found: an
/// open or pinched mesh passed as closed.
fn discs_around_core(
    walked: &[[u32; 3]],
    vertex_count: usize,
    welded: usize,
    own_discs: &[bool],
) -> Vec<bool> {
    let mut disc = one_disc(walked, vertex_count);
    for (d, &known) in disc[welded..].iter_mut().zip(own_discs) {
        *d |= known;
    }
    disc
}
