//! The named wrappers of [`boolean`] (`union`, `intersection`, `difference`), the operators
//! `|`, `&`, `-` and their assigning forms, and the balanced n-ary reductions.

use std::borrow::Cow;
use std::ops::{BitAnd, BitAndAssign, BitOr, BitOrAssign, Sub, SubAssign};

use rayon::prelude::*;

use super::Solid;
use super::boolean::{BoolOp, boolean, boolean_cow, boolean_owned, meter_for};
use crate::bsp::Meter;

impl Solid {
    /// Points in `self` or `other`.
    #[must_use]
    pub fn union(&self, other: &Solid) -> Solid {
        boolean(self, other, BoolOp::Union)
    }

    /// Points in both `self` and `other`.
    #[must_use]
    pub fn intersection(&self, other: &Solid) -> Solid {
        boolean(self, other, BoolOp::Intersection)
    }

    /// Points in `self` and not in `other`.
    #[must_use]
    pub fn difference(&self, other: &Solid) -> Solid {
        boolean(self, other, BoolOp::Difference)
    }

    /// The union of many solids, reduced as a balanced tree (pairs in parallel), so each
    /// boolean sees operands of similar size. Empty input gives the empty solid. The booleans
    /// share one work budget (see [`Solid::check_budget`]).
    pub fn union_all(solids: impl IntoIterator<Item = Solid>) -> Solid {
        boolean_all(solids, BoolOp::Union)
    }

    /// The intersection of many solids, reduced as a balanced tree. Empty input gives the empty
    /// solid. The booleans share one work budget (see [`Solid::check_budget`]).
    pub fn intersection_all(solids: impl IntoIterator<Item = Solid>) -> Solid {
        boolean_all(solids, BoolOp::Intersection)
    }
}

/// Combines many solids left to right, `s₀ op s₁ op s₂ …`: the n-ary form of [`boolean`], for
/// callers (such as the command line) that take any number of operands.
///
/// Union and intersection are reduced as balanced trees ([`Solid::union_all`],
/// [`Solid::intersection_all`]). Difference takes the union of all the others away from the
/// first, `s₀ − (s₁ ∪ s₂ ∪ …)`: the same set as subtracting them one by one, but one difference
/// against a balanced union instead of a chain that clips the growing result again and again.
/// Empty input gives the empty solid; a single solid comes back as it is.
///
/// ```
/// use bspcsg::{BoolOp, Solid, boolean_all};
/// use bspcsg::glam::DVec3;
///
/// let cube = |x: f64| Solid::cube(1.0)?.translate(DVec3::new(x, 0.0, 0.0));
/// let row = boolean_all([cube(0.0)?, cube(0.5)?, cube(1.0)?], BoolOp::Union);
/// assert!((row.volume() - 2.0).abs() < 1e-9);
/// let cut = boolean_all([cube(0.0)?, cube(0.5)?, cube(-0.75)?], BoolOp::Difference);
/// assert!((cut.volume() - 0.25).abs() < 1e-9);
/// # Ok::<(), bspcsg::Error>(())
/// ```
pub fn boolean_all(solids: impl IntoIterator<Item = Solid>, op: BoolOp) -> Solid {
    let solids: Vec<Solid> = solids.into_iter().collect();
    let meter = meter_for(solids.iter().map(Solid::polygon_count).sum());
    boolean_all_metered(solids, op, &meter)
}

/// [`boolean_all`] charging every boolean's cut pieces to one `meter` (a scene's: see
/// [`Solid::check_budget`]).
pub(crate) fn boolean_all_metered(solids: Vec<Solid>, op: BoolOp, meter: &Meter) -> Solid {
    let mut solids = solids.into_iter();
    match op {
        BoolOp::Union | BoolOp::Intersection => reduce_balanced(solids.collect(), op, meter),
        BoolOp::Difference => match solids.next() {
            Some(first) => {
                let rest = reduce_balanced(solids.collect(), BoolOp::Union, meter);
                boolean_owned(first, rest, BoolOp::Difference, meter)
            }
            None => Solid::empty(),
        },
    }
}

fn reduce_balanced(mut level: Vec<Solid>, op: BoolOp, meter: &Meter) -> Solid {
    while level.len() > 1 {
        let mut pairs = Vec::with_capacity(level.len() / 2 + 1);
        let mut it = level.into_iter();
        while let Some(a) = it.next() {
            pairs.push((a, it.next()));
        }
        level = pairs
            .into_par_iter()
            .map(|(a, b)| match b {
                Some(b) => boolean_owned(a, b, op, meter),
                None => a,
            })
            .collect();
    }
    level.pop().unwrap_or_default()
}

/// [`boolean`] on operands each owned or borrowed (a borrowed one is cloned only as far as
/// the boolean keeps it), with a meter of its own (the operators').
fn metered(a: Cow<'_, Solid>, b: Cow<'_, Solid>, op: BoolOp) -> Solid {
    let meter = meter_for(a.polygon_count() + b.polygon_count());
    boolean_cow(a, b, op, &meter)
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
                metered(Cow::Owned(self), Cow::Owned(rhs), $op)
            }
        }
        impl $trait<&Solid> for Solid {
            type Output = Solid;
            fn $method(self, rhs: &Solid) -> Solid {
                metered(Cow::Owned(self), Cow::Borrowed(rhs), $op)
            }
        }
        impl $trait<Solid> for &Solid {
            type Output = Solid;
            fn $method(self, rhs: Solid) -> Solid {
                metered(Cow::Borrowed(self), Cow::Owned(rhs), $op)
            }
        }
        impl $assign<&Solid> for Solid {
            fn $assign_method(&mut self, rhs: &Solid) {
                *self = metered(Cow::Owned(std::mem::take(self)), Cow::Borrowed(rhs), $op);
            }
        }
        impl $assign<Solid> for Solid {
            fn $assign_method(&mut self, rhs: Solid) {
                *self = metered(Cow::Owned(std::mem::take(self)), Cow::Owned(rhs), $op);
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
