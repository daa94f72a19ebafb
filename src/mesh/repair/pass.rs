//! One repair pass: weld the corners, insert T-junction vertices, merge and triangulate the
//! coplanar regions, fill flat cracks if asked, split into shells and drop the thin ones. Which
//! passes run, and which one is kept, is the parent module's choice.

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use super::{Ring, cracks, regions, shells, thin, tjunction};
use crate::mesh::Mesh;
use crate::mesh::weld::{Wide, weld_within};
use crate::polygon::{Polygon, dedup_ring};

/// One repair pass with weld tolerance `delta` (wider near the `wide` points); `quick` skips the
/// T-junction search on edges already matched (see [`tjunction::insert_on_edges`]); with
/// `dragged`, edges whose ends a wide weld moved take vertices that much farther (see
/// [`wide_drag`]); with `fill_flat`, crack loops within that distance of one plane are filled
/// before the shells are split. Returns the mesh and the end points of its cracks.
pub(super) fn repair(
    polygons: &[Polygon],
    delta: f64,
    wide: &Wide,
    quick: bool,
    dragged: bool,
    fill_flat: Option<f64>,
) -> (Mesh, Vec<DVec3>) {
    let (mesh, cracks, _) = pass(
        polygons,
        delta,
        wide,
        quick,
        dragged,
        fill_flat,
        Mode::Plain,
    );
    (mesh, cracks)
}

/// A pass at the first weld `delta` (`quick` as for [`repair`]) with tied angles about crowded
/// edges ordered to alternate (see [`shells::split_into_shells`]): for the mesh no other pass
/// closes.
pub(super) fn tie_repair(polygons: &[Polygon], delta: f64, quick: bool) -> (Mesh, Vec<DVec3>) {
    let wide = Wide::default();
    let (mesh, cracks, _) = pass(polygons, delta, &wide, quick, false, None, Mode::Ties);
    (mesh, cracks)
}

/// What a pass does besides the repair.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Plain,
    /// Also measures the volume its weld sweeps beyond `delta`.
    Measured,
    /// Orders tied angles about crowded edges to alternate.
    Ties,
}

/// [`repair`] without filling, and the volume its weld sweeps beyond `delta` (see
/// [`swept_beyond`]).
pub(super) fn measured_repair(
    polygons: &[Polygon],
    delta: f64,
    wide: &Wide,
    quick: bool,
    dragged: bool,
) -> (Mesh, Vec<DVec3>, f64) {
    pass(polygons, delta, wide, quick, dragged, None, Mode::Measured)
}

/// [`repair`]; in [`Mode::Measured`], also the volume its weld sweeps beyond `delta` (else 0).
fn pass(
    polygons: &[Polygon],
    delta: f64,
    wide: &Wide,
    quick: bool,
    dragged: bool,
    fill_flat: Option<f64>,
    mode: Mode,
) -> (Mesh, Vec<DVec3>, f64) {
    // Sized first: collecting a flat map grows the list by copying (10⁶ corners).
    let mut corners: Vec<DVec3> =
        Vec::with_capacity(polygons.iter().map(|p| p.vertices().len()).sum());
    for p in polygons {
        corners.extend_from_slice(p.vertices());
    }
    let (positions, map) = weld_within(&corners, delta, wide);
    let swept = if mode == Mode::Measured {
        swept_beyond(polygons, &corners, &positions, &map, delta)
    } else {
        0.0
    };
    let drag = if dragged {
        wide_drag(&corners, &positions, &map, delta, wide)
    } else {
        Vec::new()
    };
    let mut rings = rings_of(polygons, &map, &positions, delta, 0);
    let known = tjunction::insert_on_edges(&positions, &drag, &mut rings, delta, wide, quick, &[]);
    let pinned = vec![false; positions.len()];
    let mut triangles =
        regions::triangulate_regions(&positions, &rings, polygons, delta, &pinned, known);
    let mut filled_from = triangles.0.len();
    if let Some(flat) = fill_flat {
        filled_from -= cracks::close_flat_cracks(&positions, &mut triangles, flat);
    }
    let (mut mesh, cracks) = shells::split_into_shells(
        positions,
        triangles,
        &mut filled_from,
        delta,
        mode == Mode::Ties,
    );
    thin::drop_thin_shells(&mut mesh, delta, filled_from);
    (mesh, cracks, swept)
}

/// The volume a weld sweeps by moving corners farther than `delta`, bounded from above: per
/// polygon, its area times the largest such move across its plane.
///
/// A wider weld is for one point computed two ways: where faces cross at a tiny angle, the two
/// computations differ along the line where they cross, which lies in every face at the point,
/// so the move sweeps next to nothing. Pulling the two sides of a wedge thinner than the reach
/// onto each other moves its corners across its faces: it sweeps the wedge.
fn swept_beyond(
    polygons: &[Polygon],
    corners: &[DVec3],
    positions: &[DVec3],
    map: &[u32],
    delta: f64,
) -> f64 {
    let mut swept = 0.0;
    let mut at = 0;
    for p in polygons {
        let n = p.vertices().len();
        let normal = p.plane().normal;
        let mut most: f64 = 0.0;
        for k in at..at + n {
            let moved = positions[map[k] as usize] - corners[k];
            if moved.length() > delta {
                most = most.max(moved.dot(normal).abs());
            }
        }
        at += n;
        if most > 0.0 {
            swept += most * p.area().abs();
        }
    }
    swept
}

/// Per welded vertex, how far a wider weld than `delta` moved a corner onto it (0 where none
/// did); empty when nothing is widened.
///
/// A wide weld drags every edge at that corner with it: a vertex that lay within `delta` of
/// the edge's middle as computed can then be up to the drag farther from it (bsp_6: welding
/// two computations of one point 2.4·10⁻¹⁰ apart left a vertex 0.07 along the edge 1.15·10⁻¹⁰
/// off it, 3.6 weld distances, and a new slit). The T-junction search allows each edge its
/// ends' drag on top of the reach ([`tjunction::insert_on_edges`]). Ordinary welds move
/// corners by at most `delta` and add nothing, so the first pass is unchanged.
fn wide_drag(
    corners: &[DVec3],
    positions: &[DVec3],
    map: &[u32],
    delta: f64,
    wide: &Wide,
) -> Vec<f64> {
    if wide.widest(delta) <= delta {
        return Vec::new();
    }
    let mut drag = vec![0.0f64; positions.len()];
    for (&c, &v) in corners.iter().zip(map) {
        let moved = c.distance(positions[v as usize]);
        if moved > delta {
            drag[v as usize] = drag[v as usize].max(moved);
        }
    }
    drag
}

/// Polygons per chunk of [`rings_of`]'s parallel path.
const RINGS_CHUNK: usize = 1 << 10;

/// The rings of `polygons` through the weld `map` of their corners in order, numbered from
/// `first`; rings that welding emptied or flattened (see [`spans_area`]) are left out. Each ring
/// is its own: with more than one thread and from two chunks of polygons on, the chunks run in
/// parallel from their first corners (a prefix count) and are listed in order, the same list.
pub(super) fn rings_of(
    polygons: &[Polygon],
    map: &[u32],
    positions: &[DVec3],
    delta: f64,
    first: usize,
) -> Vec<Ring> {
    if polygons.len() < 2 * RINGS_CHUNK || rayon::current_num_threads() == 1 {
        return rings_in(polygons, map, positions, delta, first);
    }
    let corners: Vec<usize> = polygons
        .par_chunks(RINGS_CHUNK)
        .map(|c| c.iter().map(|p| p.vertices().len()).sum())
        .collect();
    let starts: Vec<usize> = corners
        .iter()
        .scan(0, |at, &n| {
            let start = *at;
            *at += n;
            Some(start)
        })
        .collect();
    polygons
        .par_chunks(RINGS_CHUNK)
        .zip(starts)
        .enumerate()
        .flat_map_iter(|(k, (chunk, at))| {
            rings_in(chunk, &map[at..], positions, delta, first + k * RINGS_CHUNK)
        })
        .collect()
}

/// [`rings_of`] on one thread, `map` starting at `polygons`' first corner.
fn rings_in(
    polygons: &[Polygon],
    map: &[u32],
    positions: &[DVec3],
    delta: f64,
    first: usize,
) -> Vec<Ring> {
    let mut rings = Vec::with_capacity(polygons.len());
    let mut at = 0usize;
    for (i, p) in polygons.iter().enumerate() {
        let n = p.vertices().len();
        let mut verts: SmallVec<[u32; 8]> = map[at..at + n].iter().copied().collect();
        at += n;
        dedup_ring(&mut verts);
        if verts.len() >= 3 && spans_area(positions, &verts, p, delta) {
            rings.push(Ring {
                verts,
                polygon: (first + i) as u32,
            });
        }
    }
    rings
}

/// False when welding collapsed the ring onto a line (width below `delta` everywhere).
fn spans_area(positions: &[DVec3], verts: &[u32], polygon: &Polygon, delta: f64) -> bool {
    let n = polygon.plane().normal;
    let at = |k: usize| positions[verts[k] as usize];
    let first = at(0);
    // Twice the area over the longest edge bounds the ring's width from below.
    let mut twice_area = 0.0;
    let mut longest: f64 = 0.0;
    for i in 0..verts.len() {
        let (a, b) = (at(i), at((i + 1) % verts.len()));
        twice_area += (a - first).cross(b - first).dot(n);
        longest = longest.max(a.distance(b));
    }
    longest > 0.0 && twice_area / longest > delta * 1e-3
}
