//! Union, intersection and difference of sketches: one core operation, named wrappers,
//! operators, and balanced n-ary reductions.
//!
//! Each operand's edges are cut by the other's knife tree; the pieces kept are
//!
//! | op | from A | from B |
//! |---|---|---|
//! | union | outside B, on B facing the same way | outside A |
//! | intersection | inside B, on B facing the same way | inside A |
//! | difference | outside B, on B facing the other way | inside A, reversed |
//!
//! so an edge both operands share is kept once, and edges where they touch from opposite sides
//! cancel.

use std::ops::{BitAnd, BitOr, Sub};

use glam::DVec2;

use super::classify::{Class, classify};
use super::knife::{Frag, KnifeTree, Label};
use super::{Sketch, assemble};
use crate::geom::{Aabb, Tolerance};
use crate::solid::BoolOp;
use crate::solid::Containment;

impl Sketch {
    /// Combines two sketches. Always succeeds; the result may be empty.
    #[must_use]
    pub fn boolean(&self, other: &Sketch, op: BoolOp) -> Sketch {
        let (box_a, box_b) = (self.aabb(), other.aabb());
        let eps = Tolerance::for_operands(&box_a, &box_b)
            .max(Tolerance::new(self.eps))
            .max(Tolerance::new(other.eps))
            .eps();
        if self.is_empty() || other.is_empty() || !box_a.overlaps(&box_b, eps) {
            return disjoint(self, other, op, eps);
        }
        // Only the rings whose boxes reach the other operand's box take part; the others lie
        // wholly outside it and pass through (or drop out) whole, so drilling one more hole in
        // a plate costs the hole, not the plate's other holes.
        let margin = 0.01 * box_a.intersection(&box_b).diagonal() + 8.0 * eps;
        let (focus_a, focus_b) = (box_b.expanded(margin), box_a.expanded(margin));
        let (near_a, far_a) = split_rings(self, &focus_a);
        let (near_b, far_b) = split_rings(other, &focus_b);
        let (ea, eb) = (ring_edges(&near_a), ring_edges(&near_b));
        // Each tree needs only the edges where the other operand's edges can reach: clipped to
        // the other's box, it labels every point of that box right.
        let (ta, tb) = rayon::join(
            || focused_tree(self, &ea, &focus_a, eps),
            || focused_tree(other, &eb, &focus_b, eps),
        );
        let keep_a = |c: Class| match op {
            BoolOp::Union => matches!(c, Class::Outside | Class::OnSame),
            BoolOp::Intersection => matches!(c, Class::Inside | Class::OnSame),
            BoolOp::Difference => matches!(c, Class::Outside | Class::OnOpposite),
        };
        let keep_b = |c: Class| match op {
            BoolOp::Union => c == Class::Outside,
            BoolOp::Intersection | BoolOp::Difference => c == Class::Inside,
        };
        let reverse_b = op == BoolOp::Difference;
        let (mut segs, segs_b) = rayon::join(
            || {
                let mut out = Vec::new();
                classify(&tb, &ea, eps, |f, c| {
                    if keep_a(c) {
                        out.push([f.a, f.b]);
                    }
                });
                out
            },
            || {
                let mut out = Vec::new();
                classify(&ta, &eb, eps, |f, c| {
                    if keep_b(c) {
                        out.push(if reverse_b { [f.b, f.a] } else { [f.a, f.b] });
                    }
                });
                out
            },
        );
        segs.extend(segs_b);
        let mut rings = assemble::rings(&segs, eps);
        // Far rings are outside the other operand: A's stay in a union or difference, B's in a
        // union only.
        if op != BoolOp::Intersection {
            rings.extend(far_a.into_iter().map(<[DVec2]>::to_vec));
        }
        if op == BoolOp::Union {
            rings.extend(far_b.into_iter().map(<[DVec2]>::to_vec));
        }
        Sketch::from_regions(assemble::nest(rings), eps)
    }

    /// The points in either sketch.
    #[must_use]
    pub fn union(&self, other: &Sketch) -> Sketch {
        self.boolean(other, BoolOp::Union)
    }

    /// The points in both sketches.
    #[must_use]
    pub fn intersection(&self, other: &Sketch) -> Sketch {
        self.boolean(other, BoolOp::Intersection)
    }

    /// The points in `self` and not in `other`.
    #[must_use]
    pub fn difference(&self, other: &Sketch) -> Sketch {
        self.boolean(other, BoolOp::Difference)
    }

    /// The union of many sketches, combined pairwise in a balanced tree (so each edge takes
    /// part in `O(log n)` booleans, not `n`).
    pub fn union_all(sketches: impl IntoIterator<Item = Sketch>) -> Sketch {
        reduce(sketches.into_iter().collect(), BoolOp::Union)
    }

    /// The intersection of many sketches (empty for none).
    pub fn intersection_all(sketches: impl IntoIterator<Item = Sketch>) -> Sketch {
        reduce(sketches.into_iter().collect(), BoolOp::Intersection)
    }
}

/// The rings whose boxes reach `focus`, and the rest.
fn split_rings<'a>(s: &'a Sketch, focus: &Aabb) -> (Vec<&'a [DVec2]>, Vec<&'a [DVec2]>) {
    s.rings().partition(|r| {
        let (lo, hi) = r
            .iter()
            .fold((r[0], r[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        Aabb::new(lo.extend(0.0), hi.extend(0.0)).overlaps(focus, 0.0)
    })
}

/// The directed edges of `rings`, zero-length ones left out.
fn ring_edges(rings: &[&[DVec2]]) -> Vec<[DVec2; 2]> {
    let mut out = Vec::with_capacity(rings.iter().map(|r| r.len()).sum());
    for ring in rings {
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            if a != b {
                out.push([a, b]);
            }
        }
    }
    out
}

/// The knife tree of `sketch`'s `edges` clipped to `focus`: right for every point of `focus`.
fn focused_tree(sketch: &Sketch, edges: &[[DVec2; 2]], focus: &Aabb, eps: f64) -> KnifeTree {
    let frags: Vec<Frag> = edges
        .iter()
        .enumerate()
        .filter_map(|(i, &e)| Frag::clipped(i as u32, e, focus))
        .filter(|f| f.a != f.b)
        .collect();
    // No edge reaches the box: it lies wholly inside or outside, as its centre does.
    let empty = match sketch.contains(focus.center().truncate()) {
        Containment::Inside => Label::Inside,
        _ => Label::Outside,
    };
    KnifeTree::build_from(edges, frags, eps, empty)
}

/// The result where the operands cannot interact (one empty, or boxes apart).
fn disjoint(a: &Sketch, b: &Sketch, op: BoolOp, eps: f64) -> Sketch {
    match op {
        BoolOp::Union => {
            let mut regions = a.regions.clone();
            regions.extend(b.regions.iter().cloned());
            Sketch::from_regions(regions, eps)
        }
        BoolOp::Intersection => Sketch {
            regions: Vec::new(),
            eps,
        },
        BoolOp::Difference => Sketch::from_regions(a.regions.clone(), a.eps),
    }
}

/// Balanced pairwise reduction: rounds of neighbours combined in parallel.
fn reduce(mut items: Vec<Sketch>, op: BoolOp) -> Sketch {
    use rayon::prelude::*;
    if items.is_empty() {
        return Sketch::empty();
    }
    while items.len() > 1 {
        items = items
            .par_chunks(2)
            .map(|pair| match pair {
                [a, b] => a.boolean(b, op),
                [a] => a.clone(),
                _ => unreachable!("chunks of two"),
            })
            .collect();
    }
    items.pop().unwrap_or_default()
}

macro_rules! operator {
    ($trait:ident, $method:ident, $op:expr) => {
        impl $trait<&Sketch> for &Sketch {
            type Output = Sketch;
            fn $method(self, rhs: &Sketch) -> Sketch {
                self.boolean(rhs, $op)
            }
        }
        impl $trait<Sketch> for Sketch {
            type Output = Sketch;
            fn $method(self, rhs: Sketch) -> Sketch {
                self.boolean(&rhs, $op)
            }
        }
    };
}

operator!(BitOr, bitor, BoolOp::Union);
operator!(BitAnd, bitand, BoolOp::Intersection);
operator!(Sub, sub, BoolOp::Difference);
