//! The one boolean operation, by the csg.js rules; the named wrappers, operators and n-ary
//! reductions on top of it are in `ops.rs`.

use glam::DVec3;
use rayon::prelude::*;

use super::Solid;
use crate::bsp::{Coplanar, FOCUS_MARGIN, Label, Surface, Tree};
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, Plane, Tolerance};
use crate::hash::{FxHashMap, key};
use crate::polygon::{Polygon, Split};

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

/// Combines two solids. Booleans of valid solids always succeed; the result may be empty.
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
pub fn boolean(a: &Solid, b: &Solid, op: BoolOp) -> Solid {
    boolean_owned(a.clone(), b.clone(), op)
}

pub(super) fn boolean_owned(a: Solid, b: Solid, op: BoolOp) -> Solid {
    let (box_a, box_b) = (a.bbox(), b.bbox());
    let tol = Tolerance::for_operands(&box_a, &box_b)
        .max(Tolerance::new(a.carried_eps()))
        .max(Tolerance::new(b.carried_eps()));
    let eps = tol.eps();
    if a.is_empty() || b.is_empty() || !box_a.overlaps(&box_b, eps) {
        return disjoint(a, b, op);
    }
    let a = cut_down(a.into_polygons(), &box_b, eps);
    let b = cut_down(b.into_polygons(), &box_a, eps);
    let (a_rule, a_keep) = match op {
        BoolOp::Union => (Coplanar::SameFront, Label::Outside),
        BoolOp::Intersection => (Coplanar::SameBack, Label::Inside),
        BoolOp::Difference => (Coplanar::SameBack, Label::Outside),
    };
    let b_keep = match op {
        BoolOp::Union => Label::Outside,
        BoolOp::Intersection | BoolOp::Difference => Label::Inside,
    };
    let (surface_a, surface_b) = rayon::join(|| Surface::new(&a, eps), || Surface::new(&b, eps));
    let margin = FOCUS_MARGIN * eps;
    let (near_a, near_b) = rayon::join(
        || near_flags(&a, &surface_b, margin),
        || near_flags(&b, &surface_a, margin),
    );
    let (a_kept, b_kept) = rayon::join(
        || {
            let tree_b = Tree::build_focused(b.clone(), eps, Some(&boxes(&a, &near_a)));
            let mut kept = keep_far(&a, &near_a, &surface_b, a_keep);
            let near = tree_b.clip(pick(&a, &near_a), a_keep, a_rule, &surface_b);
            kept.extend(near.into_iter().map(|c| c.polygon));
            kept
        },
        || {
            let tree_a = Tree::build_focused(a.clone(), eps, Some(&boxes(&b, &near_b)));
            let mut kept = keep_far(&b, &near_b, &surface_a, b_keep);
            let first = tree_a.clip(pick(&b, &near_b), b_keep, Coplanar::SameFront, &surface_a);
            let (again, done): (Vec<_>, Vec<_>) = first.into_iter().partition(|c| c.coplanar);
            let again: Vec<Polygon> = again.into_iter().map(|c| c.polygon).collect();
            let second = tree_a.clip(again, b_keep, Coplanar::SameBack, &surface_a);
            kept.extend(done.into_iter().chain(second).map(|c| c.polygon));
            kept
        },
    );
    let mut polygons = a_kept;
    polygons.reserve(b_kept.len());
    for mut p in b_kept {
        if op == BoolOp::Difference {
            p.flip();
        }
        polygons.push(p);
    }
    Solid::with_eps(polygons, eps)
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
fn cut_down(polys: Vec<Polygon>, other: &Aabb, eps: f64) -> Vec<Polygon> {
    let reach = HUGE * other.diagonal();
    if !polys.iter().any(|p| p.bbox().diagonal() > reach) {
        return polys;
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
    for p in polys {
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
    out
}

/// For each polygon, whether its box comes within `margin` of the other operand's surface.
fn near_flags(polys: &[Polygon], other: &Surface, margin: f64) -> Vec<bool> {
    polys
        .par_iter()
        .with_min_len(256)
        .map(|p| other.near(&p.bbox(), margin))
        .collect()
}

fn pick(polys: &[Polygon], near: &[bool]) -> Vec<Polygon> {
    polys
        .iter()
        .zip(near)
        .filter(|(_, n)| **n)
        .map(|(p, _)| p.clone())
        .collect()
}

fn boxes(polys: &[Polygon], near: &[bool]) -> Vec<Aabb> {
    polys
        .iter()
        .zip(near)
        .filter(|(_, n)| **n)
        .map(|(p, _)| p.bbox())
        .collect()
}

/// The polygons away from the other surface whose region is labelled `keep`. Polygons sharing a
/// vertex, both away from the other surface, lie in the same region, so each connected group
/// needs one ray.
fn keep_far(polys: &[Polygon], near: &[bool], other: &Surface, keep: Label) -> Vec<Polygon> {
    let mut groups = DisjointSets::new(polys.len());
    let mut first_at: FxHashMap<[u64; 3], u32> =
        FxHashMap::with_capacity_and_hasher(polys.len(), Default::default());
    for (i, p) in polys.iter().enumerate() {
        if near[i] {
            continue;
        }
        for &v in p.vertices() {
            let j = *first_at.entry(key(v)).or_insert(i as u32);
            groups.union(i, j as usize);
        }
    }
    let mut label: Vec<Option<Label>> = vec![None; polys.len()];
    let mut kept = Vec::new();
    for (i, p) in polys.iter().enumerate() {
        if near[i] {
            continue;
        }
        let root = groups.find(i);
        let l = *label[root].get_or_insert_with(|| other.label(p.centroid()));
        if l == keep {
            kept.push(p.clone());
        }
    }
    kept
}

/// The result when the operands cannot interact: one is empty or their boxes do not meet.
fn disjoint(a: Solid, b: Solid, op: BoolOp) -> Solid {
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
            let mut polygons = a.into_polygons();
            polygons.extend(b.into_polygons());
            Solid::with_eps(polygons, eps)
        }
        BoolOp::Intersection => Solid::empty(),
        BoolOp::Difference => a,
    }
}
