//! Conservative bounds of what a program describes: for each subexpression, a box that holds
//! every point where its value is small, combined through the operations without evaluating.

use glam::{DAffine3, DVec3};

use super::Op;
use crate::geom::Aabb;
use crate::sdf::tree::SmoothKind;
use crate::solid::BoolOp;

/// A conservative bound on where a field is small: `{p : f(p) ≤ c}` lies inside
/// `bbox.expanded(alpha · c)` for every `c ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bound {
    pub bbox: Aabb,
    pub alpha: f64,
}

impl Bound {
    /// The bound of the empty set (an empty box; `alpha` is then immaterial).
    pub(crate) const EMPTY: Bound = Bound {
        bbox: Aabb::EMPTY,
        alpha: 1.0,
    };

    /// The box holding `{f ≤ c}`.
    pub(crate) fn at(&self, c: f64) -> Aabb {
        expand(&self.bbox, self.alpha * c)
    }
}

/// How far below `min(a, b)` one smooth fold can reach (and above `max` for the intersection).
fn smooth_margin(kind: SmoothKind, k: f64) -> f64 {
    match kind {
        SmoothKind::Exponential => std::f64::consts::LN_2 / k,
        SmoothKind::Polynomial => 0.25 * k,
    }
}

pub(super) fn combine_bounds(op: Op, a: Bound, b: Bound) -> Bound {
    let alpha = a.alpha.max(b.alpha);
    let (op, m) = match op {
        Op::Union => (BoolOp::Union, 0.0),
        Op::Intersect => (BoolOp::Intersection, 0.0),
        Op::Subtract => (BoolOp::Difference, 0.0),
        Op::Smooth { op, kind, k } => (op, smooth_margin(kind, k)),
    };
    // f ≤ c implies the deciding children are ≤ c + m.
    let (ab, bb) = (a.at(m), b.at(m));
    let bbox = match op {
        BoolOp::Union => ab.union(&bb),
        BoolOp::Intersection => ab.intersection(&bb),
        BoolOp::Difference => ab,
    };
    Bound { bbox, alpha }
}

/// Expands a box by `m` on every side; empty stays empty, infinite stays infinite.
fn expand(b: &Aabb, m: f64) -> Aabb {
    if b.is_empty() || m == 0.0 {
        return *b;
    }
    Aabb::new(b.min - DVec3::splat(m), b.max + DVec3::splat(m))
}

/// The world box of a local box; anything unbounded maps to everything (a rotated half-space
/// has no tighter axis-aligned box).
pub(crate) fn map_box(m: &DAffine3, b: &Aabb) -> Aabb {
    if b.is_empty() {
        return *b;
    }
    if !(b.min.is_finite() && b.max.is_finite()) {
        return Aabb::new(DVec3::NEG_INFINITY, DVec3::INFINITY);
    }
    let mut out = Aabb::EMPTY;
    for i in 0..8 {
        let c = DVec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        );
        out.grow(m.transform_point3(c));
    }
    out
}
