//! Removing needles from a closed triangle mesh by edge flips, collapses and vertex moves.
//!
//! A *needle* is a triangle whose area is below [`NEEDLE_AREA`] × d², d the diagonal of its
//! shell's bounding box (see [`crate::geom::NEEDLE_AREA`] for why that threshold). Booleans
//! make them where a vertex lies within the tolerance of a neighbour's edge (two planes meeting
//! at a tiny angle, a weld cluster), and marching cubes where the surface passes within a hair
//! of a grid vertex. Both are valid topology but useless geometry, and slicers, FEM meshers and
//! manifold3d treat them as defects.
//!
//! Local operations remove them, each moving the surface by at most [`SPECK_MOVE`] × d (d
//! capped at the scale a boolean passes; beyond it only thin needles go, see
//! [`remove_needles`]):
//!
//! * **Flip** the needle's longest edge `ab` (apex `v`, neighbour `bac`) to `vc`. The new
//!   triangles lie in the tetrahedron `abcv`, whose every point is within the apex height of
//!   `abc`: the surface moves by at most that height. Taken when `v` is far from both ends of
//!   `ab` (a *cap*), or a spike's no collapse takes. A thin spike's flip helps first only
//!   where the smaller new triangle is no needle or at least twice the smaller old one:
//!   flipping its long edge keeps its short edge, and with `c` on the spike's line the needle
//!   only moves there. Where the longest edge's flip does not help so, the spike's other
//!   edges' are tried within twice its thickness; where none applies, the longest edge's as
//!   any needle's.
//! * **Collapse** the needle's shortest edge `pq`, moving `p` onto `q` and deleting the two
//!   triangles beside it; where that would change the volume, `q` moves off its place along
//!   the fan's normal by what puts it back (a collapse keeps the volume), unless that would
//!   move it beyond the bound (at a wedge's thin end, where the fan's normals nearly cancel):
//!   then it collapses without it. The surface moves by about `|pq|`. Taken when the needle has a short edge (a *spike* or a speck). At the tip of
//!   a slit narrower than a needle, where `p` and `q` share one more neighbour `w` through a
//!   vertex `o` of valence three on the edge (`o`'s other two triangles, one on each face of
//!   the slit, would become one triangle both ways round), it deletes that pair and `o` too
//!   ([`Work::slit_tip`]): the slit's tip closes, the volume within `|pq|` of its faces.
//! * **Merge** a speck's three corners into one vertex where no single edge may collapse
//!   (`merge.rs`): between flat slivers that share its edges, or on a vertex of valence three;
//!   where that folds a neighbour too, the *cluster* of vertices joined to the speck's short
//!   edge by edges below the speck length (a patch of specks where two cone apexes nearly
//!   meet). Its condition is on the region it replaces: a disk whose boundary is one simple
//!   cycle, or an annulus bounded by two (a neck, cut: one vertex per cycle, both at the one
//!   place). Keeps the volume as a collapse does.
//! * **Stretch** a spike no flip or collapse can take (the tip of a thin wedge): one end of its
//!   short edge moves away from the other along it, about the needle's height, until the
//!   area is half again the threshold ([`Work::plan_stretch`]). Where nothing else at all
//!   applies, any edge of any needle may stretch so, within the bound.
//! * **Widen** a flat sliver that nothing else can take: its apex moves away from its long
//!   edge in its fan's plane until the area is half again the threshold
//!   ([`Work::plan_widen`]). The last resort, after every removal within the bound.
//!
//! Each needle first gets the operation that moves the surface least within twice its own
//! thickness; where none applies, within the bound (`Work::fix`). A tetrahedral shell with a
//! needle face that nothing removes is deleted whole: its volume is below `NEEDLE_AREA · d³/3`
//! (`Work::drop_tetrahedron`).
//!
//! None is taken where it would change topology (but the cut of a neck narrower than a speck,
//! which lowers the genus or splits the shell) or fold the surface: a flip needs the new edge
//! not to exist already; a collapse needs the link condition (the two ends share exactly the
//! two opposite vertices as neighbours) and a shell of more than four triangles, or, at a
//! slit's tip, that `o` has valence three and the ends share exactly the two opposite
//! vertices and `w`, and a shell of eight or more (deleting `o`'s triangles makes one
//! `(p, q, w)` of three, a disk for a disk, whose edge `pq` then meets the link condition: the
//! topology is kept); all need every new triangle to keep its orientation and have more than
//! zero area. A needle that no operation can remove stays (the report still counts it).
//!
//! Where few triangles pass the first check (a boolean's needles, along its cut), the pass runs
//! on a patch: the triangles within three rings of edges around them, numbered in the mesh's
//! order, so every choice by index is the same ([`Work::patch`]). Only the shells are found
//! over the whole mesh. Where the pass reads the triangles around a vertex the patch does not
//! hold whole (a neck cut whose shell reaches past the patch), or a shell's volume changes
//! enough to be measured, the whole mesh's pass runs instead: the result is that pass's either
//! way.

mod collapse;
mod fix;
mod flip;
mod geometry;
mod merge;
mod stretch;
#[cfg(test)]
mod tests;
mod work;

use glam::DVec3;
use smallvec::SmallVec;

use super::Mesh;
use crate::geom::{Aabb, MAX_MOVE, NEEDLE_AREA, Tolerance};
use geometry::{area, twice_normal};
use work::{Shells, Work};

/// The farthest, as a fraction of the shell's diagonal `d`, that removing one needle may move
/// the surface. Collapsing a speck's shortest edge moves a vertex by up to that edge's length,
/// and a triangle under `NEEDLE_AREA × d²` may have a shortest edge up to
/// `√(4/√3 · NEEDLE_AREA) d ≈ 1.52·10⁻⁶ d` (an equilateral speck). [`MAX_MOVE`] alone
/// (`√NEEDLE_AREA`) left a speck about 1.2·10⁻⁶ d on a side where a turned bar's face passes a
/// hair from a box's corner, each way of removing it moving the surface 1.06·10⁻⁶ d. Twice
/// `MAX_MOVE` covers every speck's shortest edge, with room for the volume-keeping offset.
const SPECK_MOVE: f64 = 2.0 * MAX_MOVE;

/// Removes the needles it can from `mesh`, keeping it closed and oriented. Returns how many
/// needles (by the thresholds used here) remain; 0 also where the mesh is left alone: triangles
/// that use an index out of range or a non-finite position (not a mesh this pass can reason
/// about).
///
/// `scale`, where given, caps the diagonal the moves' bounds are taken from: a boolean passes
/// 16 times the size of the region where its operands met, so a part joined to a box 10³⁸
/// across keeps its well-shaped triangles (by the box's diagonal, every one of them is a
/// needle). Needles are judged by the shell's own diagonal, as the report judges them, but
/// beyond the cap only thin ones are removed, within the capped bound ([`Work::is_needle`]): a
/// sliver 1e-11 high along a cube's edge, on a shell 40 times the region (2.5 times the cap),
/// was a needle by the report only, and stayed.
///
/// `known`, where given, names triangles whose twice area, squared, is known to be at least
/// some bound (see [`KnownAreas`]): where that bound is above the first check's, it skips them.
pub(crate) fn remove_needles(
    mesh: &mut Mesh,
    scale: Option<f64>,
    known: Option<&KnownAreas>,
) -> usize {
    remove_needles_patched(mesh, scale, known, PATCH_SHARE, PATCH_RINGS)
}

/// [`remove_needles`], run on a patch `rings` deep around the triangles that pass the first
/// check where they are at most one in `share` of the mesh (see [`Work::patch`]).
fn remove_needles_patched(
    mesh: &mut Mesh,
    scale: Option<f64>,
    known: Option<&KnownAreas>,
    share: usize,
    rings: usize,
) -> usize {
    let n = mesh.positions.len();
    // Positions are checked once each where all are finite (every one is used, as `to_mesh`
    // leaves them), not once per corner.
    let all_finite = mesh.positions.iter().all(|p| p.is_finite());
    if mesh
        .triangles
        .iter()
        .flatten()
        .any(|&i| i as usize >= n || !(all_finite || mesh.positions[i as usize].is_finite()))
    {
        return 0;
    }
    // Most meshes hold no needle. No shell's diagonal exceeds the whole mesh's, so one pass by
    // the mesh's threshold proves that before the shells and the edge map are built.
    let scale = scale.unwrap_or(f64::INFINITY);
    let mut bbox = Aabb::EMPTY;
    for &p in &mesh.positions {
        bbox.grow(p);
    }
    let largest_threshold = NEEDLE_AREA * bbox.diagonal().powi(2);
    // Twice the area, squared, against twice the threshold, squared: no square root per
    // triangle (this check is all the pass does on most meshes). Relaxed by a hair so rounding
    // never skips a triangle the exact test below takes.
    let bar = (2.0 * largest_threshold).powi(2) * (1.0 + 1e-9);
    let corners = |t: &[u32; 3]| t.map(|i| mesh.positions[i as usize]);
    let small = |t: &[u32; 3]| twice_area_squared(corners(t)) < bar;
    // Every `to_mesh` of the unit tests checks what it was told.
    #[cfg(test)]
    for &(start, past) in known.map_or(&[][..], |k| &k.ranges) {
        for t in &mesh.triangles[start as usize..past as usize] {
            assert!(twice_area_squared(corners(t)) >= known.unwrap().least);
        }
    }
    // The triangles that pass the first check (every needle does: no shell's threshold is above
    // the mesh's), ascending.
    let mut small_ones: Vec<u32> = Vec::new();
    let mut scan = |from: u32, past: u32| {
        for t in from..past {
            if small(&mesh.triangles[t as usize]) {
                small_ones.push(t);
            }
        }
    };
    let end = mesh.triangles.len() as u32;
    match known.filter(|k| k.least >= bar) {
        // Only the triangles between the known ranges need the check.
        Some(k) => {
            let mut from = 0;
            for &(start, past) in k.ranges.iter().chain([&(end, end)]) {
                scan(from, start);
                from = past;
            }
        }
        None => scan(0, end),
    }
    if small_ones.is_empty() {
        return 0;
    }
    let shells = Shells::new(mesh);
    let tolerance = Tolerance::RELATIVE * bbox.diagonal().min(scale);
    let swept = NEEDLE_SWEPT_TOLERANCES * tolerance;
    // Few needles in a large mesh (a boolean's cut): the pass runs on a patch around them and
    // writes it back, the whole mesh's structures never built. Where it reads beyond the patch
    // or changes a shell's volume enough to be measured, the whole mesh's pass runs instead, so
    // the result is that pass's either way.
    if small_ones.len() <= mesh.triangles.len() / share {
        let (mut work, tris_in, verts_in) = Work::patch(mesh, &shells, scale, &small_ones, rings);
        let queue: Vec<u32> = small_ones
            .iter()
            .map(|t| tris_in.binary_search(t).unwrap() as u32)
            .filter(|&t| work.is_needle(t))
            .collect();
        if queue.is_empty() {
            return 0;
        }
        let none = vec![false; shells.count()];
        let (change, seen_area) = run(&mut work, queue, &none, bbox.center());
        if !work.escaped() && !(0..=none.len()).any(|s| change[s].abs() > swept * seen_area[s]) {
            return work.finish_patch(mesh, &tris_in, &verts_in);
        }
    }
    let mut work = Work::with_shells(std::mem::take(mesh), shells, scale);
    let queue: Vec<u32> = small_ones
        .into_iter()
        .filter(|&t| work.is_needle(t))
        .collect();
    if queue.is_empty() {
        *mesh = Mesh {
            positions: work.positions,
            triangles: work.tris,
            sources: work.sources,
        };
        return 0;
    }
    let found = queue.len();
    let original = Mesh {
        positions: work.positions.clone(),
        triangles: work.tris.clone(),
        sources: work.sources.clone(),
    };
    // Each operation bounds how far it moves the surface, by the shell's diagonal, not the
    // volume it sweeps: where the triangles are far longer than the move (a sliver 10⁷ long
    // whose whole profile, a unit across, is needles by that diagonal), moves within the bound
    // swept up to a third of the solid each and folded it inside out. Where the pass changes a
    // shell's volume beyond [`NEEDLE_VOLUME_CHANGE`] (of its own volume or the mesh's, the
    // smaller), it runs again from the start removing in that shell only the needles the kernel must
    // ([`crate::geom::is_needle_to_remove`]: thin, weld-sized or specks of its thickness, not a
    // thin shell's own well-shaped faces); beyond it again, that shell keeps its needles, not
    // its shape changed. Operations never reach across shells (each changes the triangles
    // around one needle's corners), so the other shells' operations are the same again. (Until
    // round 23 one shell over the bound undid every fix of the mesh.)
    let shells = work.shells();
    let mut frozen = vec![false; shells];
    let mut strict = frozen.clone();
    // Each shell's volume and area, measured only once some shell's change needs them.
    let mut measures: Option<(Vec<f64>, Vec<f64>)> = None;
    for _ in 0..NEEDLE_RERUNS {
        let (change, seen_area) = run(&mut work, queue.clone(), &frozen, bbox.center());
        // Within what the touched triangles' area explains, a shell need not be measured.
        let near = |s: usize| change[s].abs() > swept * seen_area[s];
        if !(0..=shells).any(near) {
            return work.finish(mesh);
        }
        let (volume, area) = measures
            .get_or_insert_with(|| work::shell_measures(&original, &work.first_shell, shells));
        let mesh_volume: f64 = volume.iter().sum();
        let mesh_area: f64 = area.iter().sum();
        let beyond = |s: usize, volume: f64, area: f64| {
            near(s) && change[s].abs() > NEEDLE_VOLUME_CHANGE * volume + swept * area
        };
        // The tetrahedra deleted whole (the last entry) against the whole mesh, as they go;
        // but where they were all the mesh had (every shell deleted whole), nothing is left
        // whose volume the guard would keep: the whole result was four-triangle shells with a
        // needle face, each below `NEEDLE_AREA · d³/3` by its own diagonal (`drop_tetrahedron`;
        // an intersection of faces touching along a line, one turned 10⁻⁵°: a
        // tetrahedron 0.375 long, 7.5·10⁻⁸ × 1.6·10⁻⁸ across, of 7.3·10⁻¹⁷; its end a speck).
        let emptied = work.shell_tris.iter().all(|&n| n == 0);
        if !emptied && beyond(shells, mesh_volume.abs(), mesh_area) {
            break;
        }
        let mut over = false;
        for s in 0..shells {
            // Against the shell's own volume as well as the mesh's: a small shell beside a
            // large one keeps its shape too, and a shell whose change is a small part of itself
            // still keeps the mesh's volume (a thin hollow ball's outer shell).
            if beyond(s, volume[s].abs().min(mesh_volume.abs()), area[s]) {
                // First only the needles the kernel must remove; then none.
                if strict[s] {
                    frozen[s] = true;
                }
                strict[s] = true;
                over = true;
            }
        }
        if !over {
            return work.finish(mesh);
        }
        work = Work::new(original.clone(), scale);
        work.make_strict(&strict, volume, area);
    }
    *mesh = original;
    found
}

/// The pass runs on a patch around the triangles that pass its first check (see
/// [`remove_needles`]) where they are at most this share of the mesh (one in so many).
const PATCH_SHARE: usize = 32;

/// How many rings of edges around the needles a patch holds complete (see [`Work::patch`]).
/// The pass reads the triangles around a needle's corners and, after an operation, around the
/// corners of the triangles it changed (one ring out); a cascade reaches further, and escapes.
const PATCH_RINGS: usize = 3;

/// How many times [`remove_needles`] runs, each stricter with the shells whose volume the last
/// changed too much, before it leaves the whole mesh as it was.
const NEEDLE_RERUNS: usize = 4;

/// The needle pass proper over `work`, from the needles in `queue` (as [`Work::is_needle`]
/// judges them), leaving those of `frozen` shells (as the pass found them, [`Work::first_shell`]) alone. Returns per such shell the
/// volume its operations changed, measured on the triangles around each needle's corners (every
/// operation on a needle changes only those) about `reference`, and the area of those
/// triangles; one entry more for the tetrahedra deleted whole.
fn run(
    work: &mut Work,
    mut queue: Vec<u32>,
    frozen: &[bool],
    reference: DVec3,
) -> (Vec<f64>, Vec<f64>) {
    let shell_of = |work: &Work, t: u32| work.first_shell[work.tris[t as usize][0] as usize];
    queue.retain(|&t| !frozen[shell_of(work, t) as usize]);
    // Per shell, and last the tetrahedra deleted whole.
    let mut change = vec![0.0; frozen.len() + 1];
    let mut seen_area = vec![0.0; frozen.len() + 1];
    let mut seen = vec![false; work.tris.len()];
    // Each operation removes a needle or makes one's smallest area larger; the budget only
    // guards against cycling between equally bad choices.
    let mut budget = 16 * queue.len() + 64;
    while let Some(t) = queue.pop() {
        if budget == 0 {
            break;
        }
        budget -= 1;
        if !work.alive[t as usize] || !work.is_needle(t) {
            continue;
        }
        let op = work.plan(t);
        let shell = if op.is_some() {
            shell_of(work, t) as usize
        } else {
            frozen.len()
        };
        // The triangles the operation changes: those around the needle's corners, and, for a
        // cluster's merge, around every vertex of the cluster.
        let mut star = work.star(&work.tris[t as usize]);
        if let Some(Op::Merge { vertices, .. }) = &op {
            for u in work.star(vertices) {
                if !star.contains(&u) {
                    star.push(u);
                }
            }
        }
        let before = work.star_volume(&star, reference);
        for &u in &star {
            if !std::mem::replace(&mut seen[u as usize], true) {
                seen_area[shell] += area(work.corners(work.tris[u as usize]));
            }
        }
        let fixed = op.map(|op| work.apply(op));
        if fixed.is_none() {
            work.drop_tetrahedron(t);
        }
        change[shell] += work.star_volume(&star, reference) - before;
        if let Some(touched) = fixed {
            // An operation changes the neighbours of every corner of the triangles it touched,
            // so the link condition of needles with a corner there: those are tried again. A
            // spike whose short edge's ends shared a third neighbour through a vertex of
            // valence three collapses once a neighbouring needle's collapse removes that vertex.
            let mut again: Vec<u32> = Vec::new();
            for u in touched {
                for v in work.tris[u as usize] {
                    for &w in work.around(v) {
                        if !again.contains(&w) && work.is_needle(w) {
                            again.push(w);
                        }
                    }
                }
            }
            queue.extend(again);
        }
    }
    (change, seen_area)
}

/// The most the needle pass may change a shell's volume: [`NEEDLE_VOLUME_CHANGE`] of its own
/// volume or the mesh's (the smaller), plus [`NEEDLE_SWEPT_TOLERANCES`] plane tolerances (at the
/// pass's scale) times the shell's area. Flips change it too: a thin needle's flip sweeps the
/// tetrahedron on its long edge, up to its area times the reach of the neighbour across that
/// edge (a tenth of a percent of an I-beam scene's volume, `bsp_15`).
/// Collapses and merges keep the volume, but stretching the tip of a wedge changes it: by
/// 1.9·10⁻⁴ of a sliver of boxes (7.9·10⁻¹⁰), 2.7·10⁻³ of sphere − itself turned 10⁻⁶° (a
/// crescent of 1.8·10⁻⁹), 0.15 of cube − itself turned 3·10⁻⁹° (wedges of 4.1·10⁻¹¹, a change
/// of 1.2 tolerances times the area). The beams' folding moves changed it by 1.6 times.
const NEEDLE_VOLUME_CHANGE: f64 = 1e-2;

/// See [`NEEDLE_VOLUME_CHANGE`]: a wider weld may sweep as much (`repair::SWEPT_WELDS` times
/// the first weld's reach of 8 tolerances).
const NEEDLE_SWEPT_TOLERANCES: f64 = 32.0;

/// Triangles of a mesh whose twice area, squared ([`twice_area_squared`]), is at least `least`:
/// those in the ranges `start..past` of triangle indices, ascending and apart. (`to_mesh`'s core
/// fans, whose corners are where they were when the solid was made and checked.)
#[derive(Debug, Default)]
pub(crate) struct KnownAreas {
    pub ranges: Vec<(u32, u32)>,
    pub least: f64,
}

/// A triangle's twice area, squared, as [`remove_needles`] first checks it: the cross product
/// of the edges from its first corner.
pub(crate) fn twice_area_squared(c: [DVec3; 3]) -> f64 {
    twice_normal(c).length_squared()
}

/// A planned change: how far it moves the surface, the volume it sweeps, what it does.
struct Plan {
    dev: f64,
    swept: f64,
    op: Op,
}

/// A change to the mesh.
enum Op {
    Flip {
        t: u32,
        u: u32,
        new_t: [u32; 3],
        new_u: [u32; 3],
    },
    /// `from` onto `to`, which moves to `at`; at a slit's tip, deleting the `cap` pair too
    /// ([`Work::slit_tip`]).
    Collapse {
        from: u32,
        to: u32,
        at: DVec3,
        t1: u32,
        t2: u32,
        cap: Option<[u32; 2]>,
    },
    /// `vertices` (a triangle's corners, a cluster) into one vertex at `at`; with `cut`, into
    /// two there, one per cycle of the link.
    Merge {
        vertices: SmallVec<[u32; 8]>,
        at: DVec3,
        cut: bool,
    },
    /// Vertex `v` to `at`.
    Move { v: u32, at: DVec3 },
}
