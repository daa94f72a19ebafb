//! Union, intersection and difference by the csg.js rules: one core operation, thin named
//! wrappers, operators on top, and balanced n-ary reductions.

use std::ops::{BitAnd, BitAndAssign, BitOr, BitOrAssign, Sub, SubAssign};

use rayon::prelude::*;

use crate::bsp::{Coplanar, Label, Tree};
use crate::geom::Tolerance;
use crate::polygon::Polygon;
use crate::solid::Solid;

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

fn boolean_owned(a: Solid, b: Solid, op: BoolOp) -> Solid {
    let (box_a, box_b) = (a.bbox(), b.bbox());
    let tol = Tolerance::for_operands(&box_a, &box_b)
        .max(Tolerance::new(a.carried_eps()))
        .max(Tolerance::new(b.carried_eps()));
    let eps = tol.eps();
    if a.is_empty() || b.is_empty() || !box_a.overlaps(&box_b, eps) {
        return disjoint(a, b, op);
    }
    let (a, b) = (a.into_polygons(), b.into_polygons());
    let (tree_a, tree_b) = rayon::join(
        || Tree::build(a.clone(), eps),
        || Tree::build(b.clone(), eps),
    );
    let (a_rule, keep) = match op {
        BoolOp::Union => (Coplanar::SameFront, Label::Outside),
        BoolOp::Intersection => (Coplanar::SameBack, Label::Inside),
        BoolOp::Difference => (Coplanar::SameBack, Label::Outside),
    };
    let b_keep = match op {
        BoolOp::Union => Label::Outside,
        BoolOp::Intersection | BoolOp::Difference => Label::Inside,
    };
    let (a_kept, b_kept) = rayon::join(
        || {
            tree_b
                .clip(a, keep, a_rule)
                .into_iter()
                .map(|c| c.polygon)
                .collect::<Vec<_>>()
        },
        || {
            let first = tree_a.clip(b, b_keep, Coplanar::SameFront);
            let (again, done): (Vec<_>, Vec<_>) = first.into_iter().partition(|c| c.coplanar);
            let again: Vec<Polygon> = again.into_iter().map(|c| c.polygon).collect();
            let second = tree_a.clip(again, b_keep, Coplanar::SameBack);
            done.into_iter()
                .chain(second)
                .map(|c| c.polygon)
                .collect::<Vec<_>>()
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

/// The result when the operands cannot interact: one is empty or their boxes do not meet.
fn disjoint(a: Solid, b: Solid, op: BoolOp) -> Solid {
    match op {
        BoolOp::Union => {
            let eps = a.carried_eps().max(b.carried_eps());
            let mut polygons = a.into_polygons();
            polygons.extend(b.into_polygons());
            Solid::with_eps(polygons, eps)
        }
        BoolOp::Intersection => Solid::empty(),
        BoolOp::Difference => a,
    }
}

impl Solid {
    /// Points in `self` or `other`.
    pub fn union(&self, other: &Solid) -> Solid {
        boolean(self, other, BoolOp::Union)
    }

    /// Points in both `self` and `other`.
    pub fn intersection(&self, other: &Solid) -> Solid {
        boolean(self, other, BoolOp::Intersection)
    }

    /// Points in `self` and not in `other`.
    pub fn difference(&self, other: &Solid) -> Solid {
        boolean(self, other, BoolOp::Difference)
    }

    /// The union of many solids, reduced as a balanced tree (pairs in parallel), so each
    /// boolean sees operands of similar size. Empty input gives the empty solid.
    pub fn union_all(solids: impl IntoIterator<Item = Solid>) -> Solid {
        reduce_balanced(solids.into_iter().collect(), BoolOp::Union)
    }

    /// The intersection of many solids, reduced as a balanced tree. Empty input gives the empty
    /// solid.
    pub fn intersection_all(solids: impl IntoIterator<Item = Solid>) -> Solid {
        reduce_balanced(solids.into_iter().collect(), BoolOp::Intersection)
    }
}

fn reduce_balanced(mut level: Vec<Solid>, op: BoolOp) -> Solid {
    while level.len() > 1 {
        let mut pairs = Vec::with_capacity(level.len() / 2 + 1);
        let mut it = level.into_iter();
        while let Some(a) = it.next() {
            pairs.push((a, it.next()));
        }
        level = pairs
            .into_par_iter()
            .map(|(a, b)| match b {
                Some(b) => boolean_owned(a, b, op),
                None => a,
            })
            .collect();
    }
    level.pop().unwrap_or_default()
}

macro_rules! operator {
    ($trait:ident, $method:ident, $assign:ident, $assign_method:ident, $op:expr) => {
        impl $trait<&Solid> for &Solid {
            type Output = Solid;
            fn $method(self, rhs: &Solid) -> Solid {
                boolean(self, rhs, $op)
            }
        }
        impl $trait<Solid> for Solid {
            type Output = Solid;
            fn $method(self, rhs: Solid) -> Solid {
                boolean_owned(self, rhs, $op)
            }
        }
        impl $trait<&Solid> for Solid {
            type Output = Solid;
            fn $method(self, rhs: &Solid) -> Solid {
                boolean_owned(self, rhs.clone(), $op)
            }
        }
        impl $trait<Solid> for &Solid {
            type Output = Solid;
            fn $method(self, rhs: Solid) -> Solid {
                boolean_owned(self.clone(), rhs, $op)
            }
        }
        impl $assign<&Solid> for Solid {
            fn $assign_method(&mut self, rhs: &Solid) {
                *self = boolean_owned(std::mem::take(self), rhs.clone(), $op);
            }
        }
        impl $assign<Solid> for Solid {
            fn $assign_method(&mut self, rhs: Solid) {
                *self = boolean_owned(std::mem::take(self), rhs, $op);
            }
        }
    };
}

operator!(BitOr, bitor, BitOrAssign, bitor_assign, BoolOp::Union);
operator!(
    BitAnd,
    bitand,
    BitAndAssign,
    bitand_assign,
    BoolOp::Intersection
);
operator!(Sub, sub, SubAssign, sub_assign, BoolOp::Difference);
