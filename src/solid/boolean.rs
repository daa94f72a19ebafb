//! The one boolean operation, by the csg.js rules; the named wrappers, operators and n-ary
//! reductions on top of it are in `ops.rs`.

use std::borrow::Cow;
use std::sync::Arc;

use glam::DVec3;

use super::far::{assemble, keep_far};
use super::flat::is_flat_sheet;
use super::vertex_ids::VertexIds;
use super::{Overrun, PrecisionLoss, Solid};
use crate::bsp::{Coplanar, FOCUS_MARGIN, Focus, Label, Meter, Surface, Tree};
use crate::geom::{Aabb, Plane, Tolerance};
use crate::mesh::repair::WELD_TOLERANCES;
use crate::polygon::{Polygon, Split, attach_edge_planes_among, share_near_parallel_vertices};

/// A boolean operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BoolOp {
    /// Points in either operand.
    Union,
    /// Points in both operands.
    Intersection,
    /// Points in the first operand and not the second.
    Difference,
}

impl BoolOp {
    /// Every operation, in the order `union`, `intersection`, `difference`.
    pub const ALL: [BoolOp; 3] = [BoolOp::Union, BoolOp::Intersection, BoolOp::Difference];

    /// The operation's name: `union`, `intersection` or `difference` (the command line's
    /// subcommands).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            BoolOp::Union => "union",
            BoolOp::Intersection => "intersection",
            BoolOp::Difference => "difference",
        }
    }
}

impl std::fmt::Display for BoolOp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The work a boolean may do at least, whatever its operands' size: the corners of the pieces
/// building its trees and clipping cut (see [`Solid::check_budget`]). 2²⁴, the scene's budget
/// too ([`crate::MAX_SCENE_WORK`]): about half a minute and 2–3 GB on a 2-core machine where
/// faces nearly coincide (four copies of a 10,000-point wavy outline extruded, 0.016 apart, cut
/// 21 M in clipping alone in 34 CPU-s and 3.1 GB; now they are stopped at 3.4 CPU-s and
/// 1.0 GB). Ordinary booleans cut far less: rocker-arm ∪ moved 0.25 M, the 256 × 128 sphere ∪
/// moved 0.10 M.
pub const MAX_BOOLEAN_WORK: u64 = 1 << 24;

/// The work a boolean may do per polygon of its operands, where that is more than
/// [`MAX_BOOLEAN_WORK`] (operands of over half a million polygons): ordinary booleans cut a
/// few corners per polygon, building and clipping (rocker-arm ∪ moved: 0.25 M for 40 k), so
/// large inputs stay well within it.
pub const WORK_PER_POLYGON: u64 = 32;

/// The meter of a boolean (or an n-ary reduction) over operands of `polygons` polygons in all.
pub(crate) fn meter_for(polygons: usize) -> Meter {
    Meter::new(MAX_BOOLEAN_WORK.max(WORK_PER_POLYGON.saturating_mul(polygons as u64)))
}

/// A name that is not a boolean operation.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown boolean operation `{0}`; expected union, intersection or difference")]
pub struct ParseBoolOpError(String);

impl std::str::FromStr for BoolOp {
    type Err = ParseBoolOpError;

    /// `union`, `intersection` or `difference`, and the scene format's spellings `intersect`
    /// and `subtract`; ASCII case is ignored.
    ///
    /// ```
    /// use bspcsg::BoolOp;
    /// assert_eq!("subtract".parse::<BoolOp>(), Ok(BoolOp::Difference));
    /// assert_eq!(BoolOp::Intersection.to_string(), "intersection");
    /// assert!("xor".parse::<BoolOp>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "union" => Ok(BoolOp::Union),
            "intersection" | "intersect" => Ok(BoolOp::Intersection),
            "difference" | "subtract" => Ok(BoolOp::Difference),
            _ => Err(ParseBoolOpError(s.to_owned())),
        }
    }
}

/// Combines two solids. Booleans of valid solids always succeed; the result may be empty. One
/// whose operands' faces nearly coincide over a wide area may stop at its work budget instead,
/// leaving the empty solid marked: [`Solid::check_budget`] says so.
///
/// This follows csg.js's sequence — clip A by B's tree, clip B by A's tree, clip B again
/// inverted so that faces both solids share are kept once, merge — with the inversions
/// expressed as which side coplanar polygons go and which leaf label is kept:
///
/// | op | A keeps | B keeps (both passes) | B flipped |
/// |---|---|---|---|
/// | union | outside B, coplanar same-facing to the front | outside A | no |
/// | intersection | inside B, coplanar same-facing to the back | inside A | no |
/// | difference | outside B, coplanar same-facing to the back | inside A | yes |
///
/// B's first pass sends same-facing coplanar polygons to the front and the second to the back;
/// only fragments that met a coplanar node in the first pass can change in the second, so only
/// those are clipped again.
#[must_use]
pub fn boolean(a: &Solid, b: &Solid, op: BoolOp) -> Solid {
    let meter = meter_for(a.polygon_count() + b.polygon_count());
    boolean_at_least(
        Cow::Borrowed(a),
        Cow::Borrowed(b),
        op,
        Tolerance::new(0.0),
        &meter,
    )
}

/// [`boolean`] with a tolerance of at least `tolerance`: the boolean uses the larger of it and
/// the one it would choose itself (relative to where the operands meet, and never below what
/// either carries; see the crate docs, `# Tolerance`). A larger tolerance treats vertices
/// within it of a plane as lying on it, so faces of imprecise input that nearly coincide are
/// merged instead of leaving slivers. The result carries the tolerance used.
///
/// ```
/// use bspcsg::{BoolOp, Solid, Tolerance, boolean, boolean_with};
/// use bspcsg::glam::DVec3;
///
/// // Two boxes 10⁻⁹ apart: two shells by default, one flush box at a tolerance of 10⁻⁶.
/// let a = Solid::cube(1.0)?;
/// let b = Solid::cube(1.0)?.translate(DVec3::new(1.0 + 1e-9, 0.0, 0.0))?;
/// let exact = boolean(&a, &b, BoolOp::Union);
/// let merged = boolean_with(&a, &b, BoolOp::Union, Tolerance::new(1e-6));
/// assert_eq!(exact.to_mesh().report().shells.len(), 2);
/// let report = merged.to_mesh().report();
/// assert_eq!(report.shells.len(), 1);
/// assert!(report.is_closed_manifold());
/// assert!(merged.carried_eps() >= 1e-6);
/// # Ok::<(), bspcsg::Error>(())
/// ```
#[must_use]
pub fn boolean_with(a: &Solid, b: &Solid, op: BoolOp, tolerance: Tolerance) -> Solid {
    let meter = meter_for(a.polygon_count() + b.polygon_count());
    boolean_at_least(Cow::Borrowed(a), Cow::Borrowed(b), op, tolerance, &meter)
}

/// [`boolean`] on owned operands, charging the pieces it cuts to `meter`.
pub(super) fn boolean_owned(a: Solid, b: Solid, op: BoolOp, meter: &Meter) -> Solid {
    boolean_cow(Cow::Owned(a), Cow::Owned(b), op, meter)
}

/// [`boolean`] on operands each owned or borrowed, charging the pieces it cuts to `meter`.
pub(super) fn boolean_cow(
    a: Cow<'_, Solid>,
    b: Cow<'_, Solid>,
    op: BoolOp,
    meter: &Meter,
) -> Solid {
    boolean_at_least(a, b, op, Tolerance::new(0.0), meter)
}

/// The mark of a boolean whose `meter` is past its limit.
fn stopped(meter: &Meter) -> Option<Overrun> {
    meter.exceeded().then(|| Overrun {
        work: meter.used(),
        limit: meter.limit(),
    })
}

/// A boolean stopped by its meter, or after an operand's was: the empty solid, marked.
fn overran(a: &Solid, b: &Solid, meter: &Meter) -> Option<Solid> {
    let overrun = a.overrun().or(b.overrun()).or_else(|| stopped(meter));
    overrun.map(Solid::overran)
}

/// The operands are borrowed where the caller keeps them: their polygons are cloned only as
/// the boolean keeps or clips them, not first as a whole.
fn boolean_at_least(
    a: Cow<'_, Solid>,
    b: Cow<'_, Solid>,
    op: BoolOp,
    floor: Tolerance,
    meter: &Meter,
) -> Solid {
    if let Some(marked) = overran(&a, &b, meter) {
        return marked;
    }
    let (box_a, box_b) = (known_bbox(&a), known_bbox(&b));
    let region = Tolerance::region(&box_a, &box_b);
    let needed = Tolerance::for_region(&region)
        .max(Tolerance::new(a.carried_eps()))
        .max(Tolerance::new(b.carried_eps()));
    let eps = needed.max(floor).eps();
    // Inherited first, so the first loss on the way is the one reported.
    let inherited = a.precision_loss().or(b.precision_loss());
    if a.is_empty() || b.is_empty() || !box_a.overlaps(&box_b, eps) {
        return disjoint(a, b, op, floor.eps(), inherited);
    }
    // A tolerance asked for by the caller is not a loss; one forced by the coordinates'
    // magnitude or carried from a larger boolean is, where it dwarfs the region.
    let lost = inherited.or_else(|| PrecisionLoss::check(&region, needed));
    // An operand made by no boolean shares its vertices bit for bit (a mesh, a primitive), so
    // its far part can be passed on indexed; cut down, it has T-junctions.
    let flat = WELD_TOLERANCES * eps;
    let (a_exact, b_exact) = (a.carried_eps() == 0.0, b.carried_eps() == 0.0);
    let (a, a_ids) = parts(a);
    let (b, b_ids) = parts(b);
    let (a, a_cut) = cut_down(a, &box_a, &box_b, eps);
    let (b, b_cut) = cut_down(b, &box_b, &box_a, eps);
    // Beside a huge operand neither is indexed: the cross-check's huge-box case (Cray) came out
    // with a flat shell through the indexed pass, closed through the full one (not yet
    // understood).
    let huge = a_cut || b_cut;
    let a_flat = (a_exact && !huge).then_some(flat);
    let b_flat = (b_exact && !huge).then_some(flat);
    let (a_rule, a_keep) = match op {
        BoolOp::Union => (Coplanar::SameFront, Label::Outside),
        BoolOp::Intersection => (Coplanar::SameBack, Label::Inside),
        BoolOp::Difference => (Coplanar::SameBack, Label::Outside),
    };
    let b_keep = match op {
        BoolOp::Union => Label::Outside,
        BoolOp::Intersection | BoolOp::Difference => Label::Inside,
    };
    // The operands' vertex ids: their own, or made here (polygons cut down are new ones).
    let ids_of = |polys: &[Polygon], own: Option<Arc<VertexIds>>, cut: bool| {
        own.filter(|_| !cut)
            .unwrap_or_else(|| Arc::new(VertexIds::new(polys)))
    };
    let (a_ids, b_ids) = (ids_of(&a, a_ids, a_cut), ids_of(&b, b_ids, b_cut));
    let (surface_a, surface_b) =
        rayon::join(|| surface(&a, &a_ids, eps), || surface(&b, &b_ids, eps));
    let margin = FOCUS_MARGIN * eps;
    let (near_a, near_b) = surface_a.near_each_other(&surface_b, margin);
    let (a_kept, b_kept) = rayon::join(
        || {
            let tree_b = focused_tree(&surface_b, &near_b, &surface_a, &near_a, eps, meter);
            let far = keep_far(&a, &a_ids, &near_a, &surface_b, a_keep, a_flat, false);
            let near = tree_b.clip(pick(&a, &near_a), a_keep, a_rule, &surface_b, meter);
            (far, near.into_iter().map(|c| c.polygon).collect())
        },
        || {
            let tree_a = focused_tree(&surface_a, &near_a, &surface_b, &near_b, eps, meter);
            let turned = op == BoolOp::Difference;
            let far = keep_far(&b, &b_ids, &near_b, &surface_a, b_keep, b_flat, turned);
            let first = tree_a.clip(
                pick(&b, &near_b),
                b_keep,
                Coplanar::SameFront,
                &surface_a,
                meter,
            );
            let (again, done): (Vec<_>, Vec<_>) = first.into_iter().partition(|c| c.coplanar);
            let again: Vec<Polygon> = again.into_iter().map(|c| c.polygon).collect();
            let second = tree_a.clip(again, b_keep, Coplanar::SameBack, &surface_a, meter);
            let near: Vec<Polygon> = done.into_iter().chain(second).map(|c| c.polygon).collect();
            (far, near)
        },
    );
    // Stopped: the fragments are incomplete, and none is passed on.
    if let Some(overrun) = stopped(meter) {
        return Solid::overran(overrun);
    }
    let ((a_far, mut a_near), (b_far, mut b_near)) = (a_kept, b_kept);
    // Both operands' cut points on three planes, two nearly parallel, made one point.
    share_near_parallel_vertices(&mut [&mut a_near, &mut b_near], eps);
    let (polygons, index) = assemble((a_far, a_near), (b_far, b_near), op == BoolOp::Difference);
    // A flat closed sheet bounds nothing within the tolerance; passed on, a later boolean would
    // keep one of its sides (see `flat.rs`).
    if is_flat_sheet(&polygons, flat) {
        return Solid::with_eps(Vec::new(), eps, lost);
    }
    Solid::with_eps(polygons, eps, lost).with_index(index)
}

/// The solid's box: the one its vertex ids hold where it was read from a mesh (made then, the
/// same bit for bit), else made now.
fn known_bbox(solid: &Solid) -> Aabb {
    solid
        .vertex_ids
        .as_ref()
        .and_then(|ids| ids.bbox())
        .unwrap_or_else(|| solid.bbox())
}

/// The surface of an operand's polygons: on the boxes and hierarchy it brings along where it
/// was read from a mesh (made once then, not per boolean).
fn surface<'a>(polys: &'a [Polygon], ids: &'a VertexIds, eps: f64) -> Surface<'a> {
    match ids.surface_index() {
        Some(index) => Surface::indexed(polys, index, eps),
        None => Surface::new(polys, eps),
    }
}

/// A solid's polygons, borrowed where the solid is, and its vertex ids.
fn parts(solid: Cow<'_, Solid>) -> (Cow<'_, [Polygon]>, Option<Arc<VertexIds>>) {
    match solid {
        Cow::Borrowed(s) => (Cow::Borrowed(&s.polygons), s.vertex_ids.clone()),
        Cow::Owned(s) => {
            let (polygons, ids) = s.into_parts();
            (Cow::Owned(polygons), ids)
        }
    }
}

/// A polygon whose box is this many times the other operand's is cut down first.
const HUGE: f64 = 16.0;

/// Cuts every polygon far larger than `other` by the axis-aligned planes of `other` grown by a
/// quarter of its diagonal, keeping all the pieces.
///
/// Cuts along an edge are interpolated between its ends: along an edge 10³⁸ long, a cut near
/// the origin is off by 10²². An axis-aligned cut of an axis-aligned edge is exact (the cut
/// coordinate is the plane's, the others the edge's), so a huge face (a box out to 10³⁸ around
/// a small part) becomes a piece with small, exact corners where the other operand is, and
/// pieces far away that are classified whole.
///
/// Also says whether anything was cut. `own`, the polygons' box, answers for all of them where
/// it is no larger than the reach (a polygon's box lies within it): no polygon's is then asked.
fn cut_down<'a>(
    polys: Cow<'a, [Polygon]>,
    own: &Aabb,
    other: &Aabb,
    eps: f64,
) -> (Cow<'a, [Polygon]>, bool) {
    let reach = HUGE * other.diagonal();
    if own.diagonal() <= reach || !polys.iter().any(|p| p.bbox().diagonal() > reach) {
        return (polys, false);
    }
    let frame = other.expanded(0.25 * other.diagonal() + eps);
    let mut planes = Vec::with_capacity(6);
    for axis in 0..3 {
        let mut n = DVec3::ZERO;
        n[axis] = 1.0;
        planes.push(Plane::through(n * frame.min[axis], n));
        planes.push(Plane::through(n * frame.max[axis], -n));
    }
    let mut out = Vec::with_capacity(polys.len());
    for p in polys.into_owned() {
        if p.bbox().diagonal() <= reach || !p.bbox().overlaps(&frame, 0.0) {
            out.push(p);
            continue;
        }
        // Each plane faces into the frame: the front piece goes on to the next plane.
        let mut inside = Some(p);
        for plane in &planes {
            let Some(piece) = inside.take() else { break };
            match piece.split(plane, eps) {
                Split::Spanning { front, back } => {
                    out.push(back);
                    inside = Some(front);
                }
                Split::Back => out.push(piece),
                Split::Front | Split::Coplanar => inside = Some(piece),
            }
        }
        out.extend(inside);
    }
    (Cow::Owned(out), true)
}

/// The polygons near the other surface, the ones clipped, each edge knowing its neighbour's
/// plane where the operand has one, near or far (see [`attach_edge_planes_among`]).
fn pick(polys: &[Polygon], near: &[bool]) -> Vec<Polygon> {
    let mut picked: Vec<Polygon> = polys
        .iter()
        .zip(near)
        .filter(|(_, n)| **n)
        .map(|(p, _)| p.clone())
        .collect();
    let far = polys.iter().zip(near).filter(|(_, n)| !**n).map(|(p, _)| p);
    attach_edge_planes_among(&mut picked, far);
    picked
}

/// The tree of `solid` focused on the near polygons of `clipped`, the operand its tree clips
/// (a polygon is near when one of the other operand's comes within the margin, see
/// [`Surface::near_each_other`]): `solid`'s
/// polygons not near `clipped` are carried whole. The polygons' boxes are the surfaces' own.
fn focused_tree(
    solid: &Surface,
    solid_near: &[bool],
    clipped: &Surface,
    clipped_near: &[bool],
    eps: f64,
    meter: &Meter,
) -> Tree {
    let boxes = near_boxes(clipped.boxes(), clipped_near);
    Tree::build_focused(
        solid.polygons(),
        eps,
        Some(Focus {
            boxes: &boxes,
            near: solid_near,
            own_boxes: solid.boxes(),
        }),
        Some(meter),
    )
}

fn near_boxes(boxes: &[Aabb], near: &[bool]) -> Vec<Aabb> {
    boxes
        .iter()
        .zip(near)
        .filter(|(_, n)| **n)
        .map(|(b, _)| *b)
        .collect()
}

/// The result when the operands cannot interact: one is empty or their boxes do not meet.
/// Operands borrowed are cloned only where kept: both for a union, A for a difference.
fn disjoint(
    a: Cow<'_, Solid>,
    b: Cow<'_, Solid>,
    op: BoolOp,
    floor: f64,
    lost: Option<PrecisionLoss>,
) -> Solid {
    match op {
        BoolOp::Union => {
            // Two parts of different scales: the finer tolerance serves both, but never below
            // what either already carries (its fragments were made with that).
            let eps = match (a.is_empty(), b.is_empty()) {
                (true, _) => b.carried_eps(),
                (_, true) => a.carried_eps(),
                _ => a
                    .tolerance()
                    .eps()
                    .min(b.tolerance().eps())
                    .max(a.carried_eps())
                    .max(b.carried_eps()),
            };
            let eps = if floor > f64::MIN_POSITIVE {
                eps.max(floor)
            } else {
                eps
            };
            let mut polygons = a.into_owned().into_polygons();
            polygons.extend(b.into_owned().into_polygons());
            Solid::with_eps(polygons, eps, lost)
        }
        BoolOp::Intersection => Solid::with_eps(Vec::new(), 0.0, lost),
        BoolOp::Difference => {
            let eps = a.carried_eps();
            Solid::with_eps(a.into_owned().into_polygons(), eps, lost)
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};

    use super::*;
    use crate::error::Error;
    use crate::sketch::{FillRule, Sketch};

    /// An outline r = 1 + 0.05 sin 37a of `n` points, extruded to a unit height: copies of it a
    /// little apart nearly coincide all along their walls.
    fn wavy(n: u32) -> Solid {
        let points: Vec<DVec2> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
                DVec2::from_angle(a) * (1.0 + 0.05 * (37.0 * a).sin())
            })
            .collect();
        Sketch::polygon(&points, FillRule::EvenOdd)
            .unwrap()
            .extrude(1.0)
            .unwrap()
    }

    /// A boolean whose clipping cuts more than its meter allows stops and leaves the empty
    /// solid, marked: the mark turns into [`Error::BeyondBudget`] and passes through later
    /// booleans (which do no work) and transforms. With room, the same boolean gives a closed
    /// solid, and the meter has counted what it cut.
    #[test]
    fn a_boolean_past_its_meter_leaves_the_empty_solid_marked() {
        let a = wavy(2_000);
        let b = a.clone().translate(DVec3::new(0.01, 0.013, 0.0)).unwrap();
        let limit = 100_000;
        let tight = Meter::new(limit);
        let stopped = boolean_owned(a.clone(), b.clone(), BoolOp::Union, &tight);
        assert!(stopped.is_empty());
        let Err(Error::BeyondBudget { work, limit: l }) = stopped.check_budget() else {
            panic!("{:?}", stopped.check_budget());
        };
        assert_eq!(l, limit);
        // Stopped soon after the limit: each thread charges every `CHARGE_EVERY` corners.
        assert!(work > limit && work < 2 * limit, "{work}");
        assert!(matches!(
            stopped.to_checked_mesh(),
            Err(Error::BeyondBudget { .. })
        ));
        let moved = stopped.clone().translate(DVec3::X).unwrap();
        let later = &moved | &Solid::cube(1.0).unwrap();
        assert!(later.is_empty());
        assert_eq!(later.overrun(), stopped.overrun());
        let roomy = Meter::new(MAX_BOOLEAN_WORK);
        let done = boolean_owned(a, b, BoolOp::Union, &roomy);
        assert!(done.check_budget().is_ok());
        assert!(roomy.used() > limit && roomy.used() < MAX_BOOLEAN_WORK);
        let mesh = done.to_checked_mesh().unwrap();
        assert!(
            mesh.volume() > 3.15 && mesh.volume() < 3.25,
            "{}",
            mesh.volume()
        );
    }
}
