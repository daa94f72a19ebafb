//! The polygons a boolean keeps whole, away from the other operand, numbered by vertex so that
//! `to_mesh` repairs only around the cut (see [`Indexed`]).

use rayon::prelude::*;
use smallvec::SmallVec;

use crate::bsp::{Label, Surface};
use crate::disjoint_sets::DisjointSets;
use crate::mesh::repair::Indexed;
use crate::polygon::Polygon;

use super::vertex_ids::{VertexIds, reach};

/// One operand's kept far polygons, by their indices in the operand's `polys` (cloned once,
/// straight into the output, by [`assemble`]): `kept[..core]` the core, `kept[core..core + rim]`
/// the rim, both with their corners' vertex ids in `ids`; the rest (an operand not indexed)
/// without.
#[derive(Default)]
pub(super) struct Far<'a> {
    polys: &'a [Polygon],
    kept: Vec<u32>,
    ids: Vec<u32>,
    core: usize,
    rim: usize,
    /// How many of `ids` are the core's corners (the rim's follow).
    core_corners: usize,
    /// Whether each polygon's ids are reversed (see [`keep_far`]).
    turned: bool,
    vertex_count: u32,
    /// Whether the operand's polygons are discs by position (see [`VertexIds::discs`]).
    discs: bool,
    /// Whether the operand's polygons' fans span area (see [`VertexIds::fans`]).
    fans: bool,
    /// The least twice area, squared, of a fan triangle (see [`VertexIds::least_fan`]).
    least_fan: f64,
}

/// The polygons away from the other surface whose region is labelled `keep`. Polygons sharing a
/// vertex (by `ids`, the vertex ids of `polys`), both away from the other surface, lie in
/// the same region, so each connected group needs one ray.
///
/// With `flat` (the weld distance of `to_mesh`, for an operand whose polygons share their
/// vertices bit for bit), they are also sorted into core and rim: a kept polygon is core when
/// none of its vertices is used by a polygon near the other surface (then every polygon around
/// them is far, in the same group, and kept) and none is a vertex `to_mesh` could drop from a
/// coplanar region: around each, the polygons that `to_mesh` could merge as coplanar (one
/// source, each's corners within `flat` of the other's plane) fall into at least three such
/// classes (see [`merge_classes`]), or no two of them could merge at all.
///
/// With `turned` (B of a difference, whose polygons the boolean flips), each polygon's ids are
/// laid out reversed, as its corners will be.
pub(super) fn keep_far<'a>(
    polys: &'a [Polygon],
    ids: &VertexIds,
    near: &[bool],
    other: &Surface,
    keep: Label,
    flat: Option<f64>,
    turned: bool,
) -> Far<'a> {
    debug_assert!(ids.fits(polys));
    let mut groups = DisjointSets::new(polys.len());
    // Per vertex id, the first far polygon using it, and its id among the far vertices
    // (numbered as they first appear).
    let mut first = vec![u32::MAX; ids.vertex_count()];
    let mut renumber = vec![u32::MAX; ids.vertex_count()];
    let mut far_count = 0u32;
    for (i, _) in near.iter().enumerate().filter(|(_, n)| !**n) {
        // No earlier polygon's loop joins `i` (each joins polygons up to itself): it is its
        // set's root here, and the root is followed as its corners join it to others.
        let mut root = i;
        for &id in ids.corners(i) {
            let f = &mut first[id as usize];
            if *f == u32::MAX {
                *f = i as u32;
                renumber[id as usize] = far_count;
                far_count += 1;
            } else {
                root = groups.join(root, *f as usize);
            }
        }
    }
    let mut label: Vec<Option<Label>> = vec![None; polys.len()];
    let mut kept: Vec<u32> = Vec::new();
    for (i, p) in polys.iter().enumerate() {
        if near[i] {
            continue;
        }
        let root = groups.find(i);
        let l = *label[root].get_or_insert_with(|| other.label(p.centroid()));
        if l == keep {
            kept.push(i as u32);
        }
    }
    let Some(flat) = flat else {
        return Far {
            polys,
            kept,
            ..Far::default()
        };
    };
    // Vertices that cannot be core: used by a near polygon, or, found when first asked, where
    // polygons around it may merge and fall into fewer than three merge classes (see
    // [`merge_classes`]; all polygons around a vertex of a kept one are kept, or one of them is
    // near).
    let mut open = vec![Open::Unknown; ids.vertex_count()];
    for (i, _) in near.iter().enumerate().filter(|(_, n)| **n) {
        for &id in ids.corners(i) {
            open[id as usize] = Open::Yes;
        }
    }
    let mut is_open = |id: u32| match open[id as usize] {
        Open::Yes => true,
        Open::No => false,
        // Known from the solid where no two polygons around come within `flat`.
        Open::Unknown if ids.apart_beyond(id, flat) => {
            // Debug builds and the unit tests (run in release too) check the floor against the
            // full test: bounded, a floor being known only around at most `STAR_CAP` polygons.
            if cfg!(any(test, debug_assertions)) {
                assert!(
                    merge_classes(polys, ids.around(id), flat) == usize::MAX,
                    "vertex {id}: the floor missed a merge"
                );
            }
            open[id as usize] = Open::No;
            false
        }
        Open::Unknown => {
            let is = merge_classes(polys, ids.around(id), flat) < 3;
            open[id as usize] = if is { Open::Yes } else { Open::No };
            is
        }
    };
    let (mut core, mut rim): (Vec<u32>, Vec<u32>) = kept
        .into_iter()
        .partition(|&i| ids.corners(i as usize).iter().all(|&id| !is_open(id)));
    let (n_core, n_rim) = (core.len(), rim.len());
    core.append(&mut rim);
    let mut out_ids = Vec::with_capacity(core.iter().map(|&i| ids.corners(i as usize).len()).sum());
    let push_ring = |out: &mut Vec<u32>, i: u32| {
        let ring = ids
            .corners(i as usize)
            .iter()
            .map(|&id| renumber[id as usize]);
        if turned {
            out.extend(ring.rev());
        } else {
            out.extend(ring);
        }
    };
    for &i in &core[..n_core] {
        push_ring(&mut out_ids, i);
    }
    let core_corners = out_ids.len();
    for &i in &core[n_core..] {
        push_ring(&mut out_ids, i);
    }
    Far {
        polys,
        kept: core,
        ids: out_ids,
        core: n_core,
        rim: n_rim,
        core_corners,
        turned,
        vertex_count: far_count,
        discs: ids.discs(),
        fans: ids.fans(),
        least_fan: ids.least_fan(),
    }
}

/// How many classes the polygons `star` (those around one vertex) fall into when every two that
/// `to_mesh` could merge as coplanar ([`mergeable`]) are put in one; `usize::MAX` where no two
/// could merge. Exact from three up: the count only falls as classes join, so the scan stops
/// once it is below three, the one question asked of it.
///
/// Around a vertex among three classes or more, the regions `to_mesh` forms meet along at
/// least three boundary edges to three distinct neighbours, and a boundary vertex is dropped
/// only where it has exactly two (see `mesh::repair::regions`): it stays a corner of every
/// region it is on. Where every corner of the polygons is such a vertex (or one no two
/// polygons around could merge at), no vertex lies inside a region nor is dropped from its
/// boundary, so the regions triangulate to as many triangles as the polygons' fans (`n − 2`
/// for `n` corners). With one class the vertex lies inside a region; with two it may lie
/// straight along the crease between two, and be dropped: such a vertex stays out of the core.
/// (The Menger sponge's bars, read from a mesh: each wall is several convex polygons, and
/// every corner of a wall away from the cut is a corner of three walls.)
///
/// The argument holds where faces are exactly coplanar or clearly apart. On folds within
/// `flat` (faces nearly but not exactly coplanar) the regions compare each ring with their
/// group's first ring's plane and may join two polygons of the star that [`mergeable`] keeps
/// apart; the result is still closed, but may keep a vertex the repair of the soup drops.
fn merge_classes(polys: &[Polygon], star: &[u32], flat: f64) -> usize {
    let n = star.len();
    // Each polygon's class, named by its first member; joined by relabelling (stars are small).
    let mut class: SmallVec<[u32; 16]> = (0..n as u32).collect();
    let mut classes = n;
    for x in 0..n {
        for y in x + 1..n {
            if class[x] == class[y]
                || !mergeable(&polys[star[x] as usize], &polys[star[y] as usize], flat)
            {
                continue;
            }
            let (keep, gone) = (class[x].min(class[y]), class[x].max(class[y]));
            for c in &mut class {
                if *c == gone {
                    *c = keep;
                }
            }
            classes -= 1;
            if classes < 3 {
                return classes;
            }
        }
    }
    if classes == n { usize::MAX } else { classes }
}

/// Whether a vertex may not be core, where known.
#[derive(Clone, Copy)]
enum Open {
    Unknown,
    Yes,
    No,
}

/// Whether `to_mesh` could put the two polygons in one coplanar region: one source, facing the
/// same way, the corners of one within `flat` of the other's plane.
/// The distances are [`reach`]'s, as the merge floors' are.
fn mergeable(p: &Polygon, q: &Polygon, flat: f64) -> bool {
    p.source() == q.source()
        && p.plane().normal.dot(q.plane().normal) > 0.0
        && (reach(p, q) <= flat || reach(q, p) <= flat)
}

/// The boolean's output: both operands' cores, then A's rim and the rest of A (far polygons of
/// an operand not indexed, and the clipped ones), then B's likewise (the order the polygons had
/// before the cores were taken out), B's polygons flipped with `flip_b`; with the index of the
/// cores and rims, if any. Each operand comes as its [`Far`] and its clipped polygons.
///
/// The far polygons are cloned from the operands straight into the output (once: not first
/// into a list of their own and then moved again), the clipped ones moved, and B's flipped, in
/// parallel: rayon's `par_extend` of an indexed iterator writes each polygon to its own slot,
/// so the order is the one above on any number of threads. The ids, a few words per polygon,
/// are laid out on the calling thread.
pub(super) fn assemble(
    (a, a_rest): (Far, Vec<Polygon>),
    (b, b_rest): (Far, Vec<Polygon>),
    flip_b: bool,
) -> (Vec<Polygon>, Option<Indexed>) {
    let total = a.kept.len() + a_rest.len() + b.kept.len() + b_rest.len();
    let core = a.core + b.core;
    let vertex_count = a.vertex_count + b.vertex_count;
    let offset = a.vertex_count;
    let (a_core, a_rim, b_core, b_rim) = (a.core, a.rim, b.core, b.rim);
    // The ids: A's core, B's core (past A's), A's rim, B's rim. B's came reversed from
    // `keep_far` where B is flipped.
    debug_assert!(!a.turned && (b.ids.is_empty() || b.turned == flip_b));
    let (a_split, b_split) = (a.core_corners, b.core_corners);
    let mut ids = Vec::with_capacity(a.ids.len() + b.ids.len());
    ids.extend_from_slice(&a.ids[..a_split]);
    ids.extend(b.ids[..b_split].iter().map(|&i| i + offset));
    ids.extend_from_slice(&a.ids[a_split..]);
    ids.extend(b.ids[b_split..].iter().map(|&i| i + offset));
    // Where the rims land: after both cores, and after all of A.
    let a_at = a_core + b_core;
    let b_at = a.kept.len() + a_rest.len() + b_core;
    let mut rim = Vec::with_capacity(a_rim + b_rim);
    rim.extend(a_at as u32..(a_at + a_rim) as u32);
    rim.extend(b_at as u32..(b_at + b_rim) as u32);
    let turn = |mut p: Polygon| {
        if flip_b {
            p.flip();
        }
        p
    };
    let a_far = |i: &u32| a.polys[*i as usize].clone();
    let b_far = |i: &u32| turn(b.polys[*i as usize].clone());
    let mut polygons = Vec::with_capacity(total);
    polygons.par_extend(
        a.kept[..a_core]
            .par_iter()
            .map(a_far)
            .chain(b.kept[..b_core].par_iter().map(b_far))
            .chain(a.kept[a_core..].par_iter().map(a_far))
            .chain(a_rest.into_par_iter())
            .chain(b.kept[b_core..].par_iter().map(b_far))
            .chain(b_rest.into_par_iter().map(turn)),
    );
    let index = (core > 0).then_some(Indexed {
        core,
        rim,
        ids,
        core_corners: a_split + b_split,
        vertex_count,
        a_vertices: offset,
        discs: [a.discs, b.discs],
        // Flipped, B's polygons start their fans at another corner: not the ones checked.
        fans: [a.fans, b.fans && !flip_b],
        least_fan: [a.least_fan, if flip_b { 0.0 } else { b.least_fan }],
    });
    (polygons, index)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::mesh::repair::indexed_pass_closes;
    use crate::solid::{BoolOp, Solid, boolean};

    /// The indexed result against the same polygons repaired as a soup: both closed 2-manifolds
    /// of the same volume and triangle count, and the indexed one really passed a core through.
    fn same_as_soup(a: &Solid, b: &Solid, op: BoolOp) {
        let indexed = boolean(a, b, op);
        let index = indexed.index().expect("indexed");
        assert!(index.core > 0, "{op}: no core passed through");
        let eps = indexed.carried_eps();
        assert!(
            indexed_pass_closes(indexed.polygons(), eps, index),
            "{op}: fell back"
        );
        let soup = Solid::with_eps(indexed.polygons().to_vec(), indexed.carried_eps(), None);
        let (fast, full) = (indexed.to_mesh(), soup.to_mesh());
        assert!(
            fast.report().is_closed_manifold(),
            "{op}: {:?}",
            fast.report()
        );
        assert!(full.report().is_closed_manifold());
        assert_eq!(fast.triangle_count(), full.triangle_count(), "{op}");
        assert!((fast.volume() - full.volume()).abs() < 1e-9 * full.volume().abs().max(1.0));
        // Each triangle keeps its source.
        assert_eq!(fast.sources.len(), fast.triangle_count());
    }

    #[test]
    fn primitives_pass_their_far_part_through() {
        let sphere = Solid::sphere(1.0, 32, 16).unwrap();
        let moved = sphere
            .clone()
            .translate(DVec3::new(0.5, 0.1, 0.05))
            .unwrap();
        for op in BoolOp::ALL {
            same_as_soup(&sphere, &moved, op);
        }
        let cube = Solid::cube(2.0).unwrap().with_source(1);
        same_as_soup(&cube, &sphere.clone().with_source(2), BoolOp::Difference);
    }

    #[test]
    fn meshes_pass_their_far_part_through() {
        let a = Solid::from_mesh(&Solid::sphere(1.0, 48, 24).unwrap().to_mesh()).unwrap();
        let b = a.clone().translate(DVec3::new(0.3, 0.4, 0.0)).unwrap();
        for op in BoolOp::ALL {
            same_as_soup(&a, &b, op);
        }
    }

    /// A cube less the bars of a depth-3 Menger sponge read from a mesh: each wall of a bar
    /// pierced by others is several coplanar convex polygons of one source, so before the walls'
    /// corners were counted by class (three or more planes around each) none was core.
    #[test]
    fn coplanar_walls_pass_through_where_every_corner_is_one_of_three() {
        let mut bars = Vec::new();
        for cells in [1u32, 3, 9] {
            let cell = 1.0 / f64::from(cells);
            let hole = cell / 3.0;
            for axis in 0..3 {
                for i in 0..cells {
                    for j in 0..cells {
                        let u = -0.5 + cell * (f64::from(i) + 0.5);
                        let v = -0.5 + cell * (f64::from(j) + 0.5);
                        let mut size = DVec3::splat(hole);
                        size[axis] = 1.5;
                        let mut centre = DVec3::ZERO;
                        centre[(axis + 1) % 3] = u;
                        centre[(axis + 2) % 3] = v;
                        bars.push(Solid::cuboid(size).unwrap().translate(centre).unwrap());
                    }
                }
            }
        }
        let bars = Solid::from_mesh(&Solid::union_all(bars).to_mesh()).unwrap();
        let cube = Solid::from_mesh(&Solid::cube(1.0).unwrap().to_mesh())
            .unwrap()
            .with_source(1);
        same_as_soup(&cube, &bars.with_source(2), BoolOp::Difference);
    }

    #[test]
    fn a_mesh_solids_vertex_ids_give_what_ones_made_per_boolean_give() {
        let mut mesh = Solid::sphere(1.0, 40, 20).unwrap().to_mesh();
        let a = Solid::from_mesh(&mesh).unwrap();
        for p in &mut mesh.positions {
            *p += DVec3::new(0.4, 0.3, 0.1);
        }
        let b = Solid::from_mesh(&mesh).unwrap().with_source(2);
        // Moved, a solid drops its vertex ids; a new source keeps them.
        assert!(a.vertex_ids.is_some() && b.vertex_ids.is_some());
        assert!(a.clone().translate(DVec3::X).unwrap().vertex_ids.is_none());
        let bare = |s: &Solid| Solid::from_polygons(s.polygons().to_vec());
        for op in BoolOp::ALL {
            let (own, made) = (boolean(&a, &b, op), boolean(&bare(&a), &bare(&b), op));
            assert_eq!(own.polygons(), made.polygons(), "{op}");
            let (x, y) = (own.index().unwrap(), made.index().unwrap());
            assert!(x.core > 0, "{op}");
            assert_eq!(
                (x.core, &x.rim, &x.ids, x.vertex_count),
                (y.core, &y.rim, &y.ids, y.vertex_count),
                "{op}"
            );
        }
    }

    /// A vertex among more polygons than `merge_floors` compares has no floor: `keep_far` runs
    /// its full test there and sorts core from rim as with vertex ids made per boolean (no
    /// floors at all). A spindle: two cones of `n` sides, apexes down at z = −1 and up at
    /// z = 1.1, joined by a band from z = 0 to 0.1; a cube cuts the top apex only, so the
    /// bottom apex is asked about, and its triangles are core.
    #[test]
    fn a_vertex_above_the_star_cap_gets_the_full_test() {
        let n = 4 * super::super::vertex_ids::STAR_CAP as u32;
        let mut positions = vec![DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.0, 0.0, 1.1)];
        for z in [0.0, 0.1] {
            for i in 0..n {
                let a = f64::from(i) / f64::from(n) * std::f64::consts::TAU;
                positions.push(DVec3::new(a.cos(), a.sin(), z));
            }
        }
        let mut triangles = Vec::new();
        for i in 0..n {
            let (p, q) = (2 + i, 2 + (i + 1) % n);
            triangles.push([0, q, p]);
            triangles.push([p, q, q + n]);
            triangles.push([p, q + n, p + n]);
            triangles.push([1, p + n, q + n]);
        }
        let spindle = Solid::from_mesh(&crate::Mesh::new(positions, triangles)).unwrap();
        assert!(spindle.to_mesh().report().is_closed_manifold());
        let cube = Solid::cube(0.2)
            .unwrap()
            .translate(DVec3::new(0.0, 0.0, 1.1))
            .unwrap()
            .with_source(2);
        let bare = |s: &Solid| Solid::from_polygons(s.polygons().to_vec());
        for op in BoolOp::ALL {
            let (own, made) = (
                boolean(&spindle, &cube, op),
                boolean(&bare(&spindle), &cube, op),
            );
            assert_eq!(own.polygons(), made.polygons(), "{op}");
            let (x, y) = (own.index(), made.index());
            assert_eq!(x.is_some(), y.is_some(), "{op}");
            if let (Some(x), Some(y)) = (x, y) {
                assert_eq!(
                    (x.core, &x.rim, &x.ids, x.vertex_count),
                    (y.core, &y.rim, &y.ids, y.vertex_count),
                    "{op}"
                );
            }
        }
        // The union keeps the bottom cone, around the apex asked about, as core.
        let union = boolean(&spindle, &cube, BoolOp::Union);
        let core = union.index().map_or(0, |x| x.core);
        assert!(core >= n as usize, "{core}");
    }

    #[test]
    fn a_boolean_of_booleans_is_not_indexed_where_its_operands_were_cut() {
        let s = Solid::sphere(1.0, 24, 12).unwrap();
        let ab = boolean(&s, &s.clone().translate(DVec3::X).unwrap(), BoolOp::Union);
        // `ab` carries a tolerance: its far part may hold T-junctions and is not indexed.
        let c = Solid::cube(0.5).unwrap();
        let out = boolean(&ab, &c, BoolOp::Difference);
        assert!(out.to_mesh().report().is_closed_manifold());
        assert!(out.flipped().index().is_none());
    }
}
