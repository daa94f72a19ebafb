//! 2D shapes of the xy plane, the sources of extrusions and revolutions: primitives placed by a
//! rigid motion and combined by 2D booleans, flattened into a postfix program (as the 3D tree
//! is) so that neither evaluation nor conversion recurses.
//!
//! Two readings of one shape: [`Shape2::distance`] is the signed distance (exact for each
//! primitive, Inigo Quilez's 2D formulas; min / max for the booleans, so exact outside unions
//! and a bound elsewhere), and [`Shape2::to_sketch`] is the polygonal region the BSP route
//! extrudes, built by the sketch booleans.

use std::sync::Arc;

use glam::{DAffine2, DVec2};

use super::shapes::{polygon, rect};
use crate::error::Result;
use crate::sketch::{FillRule, Sketch};
use crate::solid::BoolOp;

/// A 2D primitive, centred at the origin.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Prim2 {
    Rect {
        half: DVec2,
    },
    Circle {
        radius: f64,
    },
    /// A simple polygon, counter-clockwise (made so by the parser).
    Polygon {
        points: Arc<[DVec2]>,
    },
    /// A rectangle of half extents `half` with corners rounded to `radius`.
    RoundedRect {
        half: DVec2,
        radius: f64,
    },
    /// A regular polygon; `points` are the sketch's own vertices, so both routes see one shape.
    RegularPolygon {
        sides: u32,
        radius: f64,
        points: Arc<[DVec2]>,
    },
}

/// A rigid placement: rotate by `rot` degrees counter-clockwise about the origin, then move by
/// `pos`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Place2 {
    pub pos: DVec2,
    pub rot: f64,
}

impl Place2 {
    pub(crate) const IDENTITY: Place2 = Place2 {
        pos: DVec2::ZERO,
        rot: 0.0,
    };

    fn rotation(&self) -> DVec2 {
        DVec2::from_angle(self.rot.to_radians())
    }

    /// `self` after `inner`: a shape placed by `inner` inside a frame placed by `self`.
    pub(crate) fn then(&self, inner: &Place2) -> Place2 {
        Place2 {
            pos: self.pos + self.rotation().rotate(inner.pos),
            rot: self.rot + inner.rot,
        }
    }

    #[inline]
    fn to_local(self, p: DVec2) -> DVec2 {
        if self == Place2::IDENTITY {
            return p;
        }
        let r = self.rotation();
        DVec2::new(r.x, -r.y).rotate(p - self.pos)
    }

    fn affine(&self) -> DAffine2 {
        DAffine2::from_angle_translation(self.rot.to_radians(), self.pos)
    }
}

/// One step of a 2D program: push a leaf's distance, or combine the top two values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Instr2 {
    Leaf(u32),
    Op(BoolOp),
}

/// A 2D shape: placed primitives and the postfix program combining them.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Shape2 {
    leaves: Arc<[(Prim2, Place2)]>,
    instrs: Arc<[Instr2]>,
}

/// Builds a [`Shape2`] in postfix order.
#[derive(Default)]
pub(crate) struct Builder {
    leaves: Vec<(Prim2, Place2)>,
    instrs: Vec<Instr2>,
}

impl Builder {
    pub(crate) fn leaf(&mut self, prim: Prim2, place: Place2) {
        self.leaves.push((prim, place));
        self.instrs.push(Instr2::Leaf(self.leaves.len() as u32 - 1));
    }

    pub(crate) fn op(&mut self, op: BoolOp) {
        self.instrs.push(Instr2::Op(op));
    }

    /// Appends a whole shape, placed by `place`.
    pub(crate) fn shape(&mut self, shape: &Shape2, place: Place2) {
        let base = self.leaves.len() as u32;
        self.leaves.extend(
            shape
                .leaves
                .iter()
                .map(|(prim, inner)| (prim.clone(), place.then(inner))),
        );
        self.instrs.extend(shape.instrs.iter().map(|i| match *i {
            Instr2::Leaf(k) => Instr2::Leaf(base + k),
            op => op,
        }));
    }

    pub(crate) fn finish(self) -> Shape2 {
        Shape2 {
            leaves: self.leaves.into(),
            instrs: self.instrs.into(),
        }
    }
}

impl Prim2 {
    fn distance(&self, p: DVec2) -> f64 {
        match self {
            Prim2::Rect { half } => rect(p, *half),
            Prim2::Circle { radius } => p.length() - radius,
            Prim2::Polygon { points } | Prim2::RegularPolygon { points, .. } => polygon(points, p),
            Prim2::RoundedRect { half, radius } => rect(p, *half - *radius) - radius,
        }
    }

    fn bounds(&self) -> (DVec2, DVec2) {
        match self {
            Prim2::Rect { half } | Prim2::RoundedRect { half, .. } => (-*half, *half),
            Prim2::Circle { radius } => (DVec2::splat(-radius), DVec2::splat(*radius)),
            Prim2::Polygon { points } | Prim2::RegularPolygon { points, .. } => points.iter().fold(
                (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                |(lo, hi), &q| (lo.min(q), hi.max(q)),
            ),
        }
    }

    /// The polygonal region, round parts within the chordal `tolerance`.
    fn to_sketch(&self, tolerance: f64) -> Result<Sketch> {
        match self {
            Prim2::Rect { half } => Sketch::rectangle(2.0 * half.x, 2.0 * half.y),
            Prim2::Circle { radius } => Sketch::circle(*radius, tolerance),
            Prim2::Polygon { points } => Sketch::polygon(points, FillRule::NonZero),
            Prim2::RoundedRect { half, radius } => {
                Sketch::rounded_rectangle(2.0 * half.x, 2.0 * half.y, *radius, tolerance)
            }
            Prim2::RegularPolygon { sides, radius, .. } => Sketch::regular_polygon(*sides, *radius),
        }
    }
}

impl Shape2 {
    /// The placed primitives and the postfix program over them.
    pub(crate) fn parts(&self) -> (&[(Prim2, Place2)], &[Instr2]) {
        (&self.leaves, &self.instrs)
    }

    /// The signed distance (a bound where booleans meet; see the module docs).
    pub(crate) fn distance(&self, p: DVec2) -> f64 {
        let mut stack: smallvec::SmallVec<[f64; 8]> = smallvec::SmallVec::new();
        for instr in self.instrs.iter() {
            match *instr {
                Instr2::Leaf(k) => {
                    let (prim, place) = &self.leaves[k as usize];
                    stack.push(prim.distance(place.to_local(p)));
                }
                Instr2::Op(op) => {
                    let b = stack.pop().unwrap_or(f64::INFINITY);
                    let a = stack.pop().unwrap_or(f64::INFINITY);
                    stack.push(match op {
                        BoolOp::Union => a.min(b),
                        BoolOp::Intersection => a.max(b),
                        BoolOp::Difference => a.max(-b),
                    });
                }
            }
        }
        stack.pop().unwrap_or(f64::INFINITY)
    }

    /// A rectangle holding the shape, as (min, max); min > max when it is provably empty.
    pub(crate) fn bounds(&self) -> (DVec2, DVec2) {
        let mut stack: Vec<(DVec2, DVec2)> = Vec::new();
        for instr in self.instrs.iter() {
            match *instr {
                Instr2::Leaf(k) => {
                    let (prim, place) = &self.leaves[k as usize];
                    let (lo, hi) = prim.bounds();
                    let m = place.affine();
                    let corners = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)]
                        .map(|c| m.transform_point2(c));
                    stack.push(corners.iter().fold(
                        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                        |(lo, hi), &q| (lo.min(q), hi.max(q)),
                    ));
                }
                Instr2::Op(op) => {
                    let b = stack.pop().unwrap_or(EMPTY);
                    let a = stack.pop().unwrap_or(EMPTY);
                    stack.push(match op {
                        BoolOp::Union => (a.0.min(b.0), a.1.max(b.1)),
                        BoolOp::Intersection => (a.0.max(b.0), a.1.min(b.1)),
                        BoolOp::Difference => a,
                    });
                }
            }
        }
        stack.pop().unwrap_or(EMPTY)
    }

    /// The largest distance from the origin to the bounding rectangle (0 when empty).
    pub(crate) fn reach(&self) -> f64 {
        let (lo, hi) = self.bounds();
        if lo.cmpgt(hi).any() {
            return 0.0;
        }
        lo.abs().max(hi.abs()).length()
    }

    /// The polygonal region, round parts within the chordal `tolerance` (in the shape's units).
    pub(crate) fn to_sketch(&self, tolerance: f64) -> Result<Sketch> {
        let mut stack: Vec<Sketch> = Vec::new();
        for instr in self.instrs.iter() {
            match *instr {
                Instr2::Leaf(k) => {
                    let (prim, place) = &self.leaves[k as usize];
                    let s = prim.to_sketch(tolerance)?;
                    stack.push(if *place == Place2::IDENTITY {
                        s
                    } else {
                        s.transform(place.affine())?
                    });
                }
                Instr2::Op(op) => {
                    let b = stack.pop().unwrap_or_default();
                    let a = stack.pop().unwrap_or_default();
                    stack.push(match op {
                        BoolOp::Union => &a | &b,
                        BoolOp::Intersection => &a & &b,
                        BoolOp::Difference => &a - &b,
                    });
                }
            }
        }
        Ok(stack.pop().unwrap_or_default())
    }
}

const EMPTY: (DVec2, DVec2) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
