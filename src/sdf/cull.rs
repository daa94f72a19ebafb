//! Pruning a scene's program to a region of space, for sphere tracing.
//!
//! A ray marcher only ever evaluates the field along rays that stay inside some region `R` (a
//! tile's beam, the sweep of a tile's hit points towards a light). Inside `R` many subtrees
//! cannot matter: a union member whose solid does not reach `R`, a cutter that misses `R`, an
//! intersection with a part outside `R` (which empties the whole intersection). Dropping them
//! gives a shorter program `f'` with the same solid inside `R`; `f'` is still 1-Lipschitz, so
//! sphere tracing with it finds the same first hit along every ray in `R`. This is the
//! per-tile pruning that makes implicit-surface renderers fast (fidget does it with interval
//! arithmetic; the conservative per-node boxes of [`Bound`] serve the same purpose here).
//!
//! Under a smooth operation a far child still shifts the blend a little, so a child is only
//! dropped when its field exceeds the blend's reach everywhere in `R`: `2k` for the polynomial
//! kind (beyond it the blend returns the other operand exactly) and `ln(1/(k·δ))/k` for the
//! exponential kind (the surface moves by at most `δ`, a 10⁻⁹ fraction of the scene's size).
//! These reaches add up along the path from the root.

use glam::DVec3;

use super::Scene;
use super::eval::{Bound, Instr, Op, run_at};
use super::tree::SmoothKind;
use crate::geom::Aabb;
use crate::solid::BoolOp;

/// A scene's program with, per instruction, the bound of the subexpression it closes and how
/// far that subexpression's field must be from zero before it can be dropped.
#[derive(Clone, Debug)]
pub(crate) struct Culler<'a> {
    scene: &'a Scene,
    /// Bound of the subexpression ending at each instruction.
    bounds: Vec<Bound>,
    /// The field level beyond which the subexpression ending here can be dropped.
    reach: Vec<f64>,
    /// First instruction of the subexpression ending at each instruction.
    start: Vec<u32>,
}

/// A program pruned to a region (see the module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct Pruned {
    instrs: Vec<Instr>,
}

impl<'a> Culler<'a> {
    pub(crate) fn new(scene: &'a Scene) -> Culler<'a> {
        let prog = &scene.program;
        let n = prog.instrs.len();
        let mut bounds = Vec::with_capacity(n);
        let mut start = Vec::with_capacity(n);
        let mut parent = vec![u32::MAX; n];
        let well_formed = prog.walk_bounds(|i, b, operands| {
            bounds.push(b);
            start.push(match operands {
                Some((ja, jb)) => {
                    parent[ja] = i as u32;
                    parent[jb] = i as u32;
                    start[ja]
                }
                None => i as u32,
            });
        });
        if !well_formed {
            // Unreachable for a compiled program; keep everything.
            return Culler::keep_all(scene);
        }
        let diag = scene.bound.bbox.diagonal();
        let delta = if diag.is_finite() && diag > 0.0 {
            1e-9 * diag
        } else {
            1e-12
        };
        let mut reach = vec![0.0; n];
        // Parents follow their children in postfix order.
        for i in (0..n).rev() {
            let p = parent[i];
            if p == u32::MAX {
                continue;
            }
            let own = match prog.instrs[p as usize] {
                Instr::Op(Op::Smooth { kind, k, .. }) => match kind {
                    SmoothKind::Polynomial => 2.0 * k,
                    SmoothKind::Exponential => {
                        (1.0 / (k * delta)).ln().max(std::f64::consts::LN_2) / k
                    }
                },
                _ => 0.0,
            };
            reach[i] = reach[p as usize] + own;
        }
        Culler {
            scene,
            bounds,
            reach,
            start,
        }
    }

    fn keep_all(scene: &'a Scene) -> Culler<'a> {
        let n = scene.program.instrs.len();
        Culler {
            scene,
            bounds: vec![
                Bound {
                    bbox: Aabb::new(DVec3::NEG_INFINITY, DVec3::INFINITY),
                    alpha: 1.0,
                };
                n
            ],
            reach: vec![0.0; n],
            start: (0..n as u32).collect(),
        }
    }

    /// The program pruned to a region: `touches(b)` must be true whenever the region meets box
    /// `b`. A subexpression is dropped when the box of `{f ≤ reach + pad}` misses the region, so
    /// `pad` keeps the pruned field exact within `pad` of the region (for normals and
    /// penumbrae).
    pub(crate) fn prune(&self, pad: f64, touches: impl Fn(&Aabb) -> bool) -> Pruned {
        #[derive(Clone, Copy)]
        enum Work {
            Visit(u32),
            Emit(Op),
        }
        #[derive(Clone, Copy)]
        struct Part {
            /// Where its code starts in the output.
            at: usize,
            present: bool,
        }
        let instrs = &self.scene.program.instrs;
        let mut out = Vec::with_capacity(instrs.len());
        let Some(root) = instrs.len().checked_sub(1) else {
            return Pruned { instrs: out };
        };
        let mut work = vec![Work::Visit(root as u32)];
        let mut parts: Vec<Part> = Vec::new();
        while let Some(w) = work.pop() {
            match w {
                Work::Visit(i) => {
                    let iu = i as usize;
                    let at = out.len();
                    let b = self.bounds[iu].at(self.reach[iu] + pad);
                    if b.is_empty() || !touches(&b) {
                        parts.push(Part { at, present: false });
                        continue;
                    }
                    match instrs[iu] {
                        Instr::Leaf(_) => {
                            out.push(instrs[iu]);
                            parts.push(Part { at, present: true });
                        }
                        Instr::Empty => parts.push(Part { at, present: false }),
                        Instr::Op(op) => {
                            // Children: b closes at i − 1, a closes just before b starts.
                            let jb = i - 1;
                            let ja = self.start[jb as usize] - 1;
                            work.push(Work::Emit(op));
                            work.push(Work::Visit(jb));
                            work.push(Work::Visit(ja));
                        }
                    }
                }
                Work::Emit(op) => {
                    let (Some(b), Some(a)) = (parts.pop(), parts.pop()) else {
                        break;
                    };
                    let base = match op {
                        Op::Union => BoolOp::Union,
                        Op::Intersect => BoolOp::Intersection,
                        Op::Subtract => BoolOp::Difference,
                        Op::Smooth { op, .. } => op,
                    };
                    let keep = match (base, a.present, b.present) {
                        (_, true, true) => {
                            out.push(Instr::Op(op));
                            Part {
                                at: a.at,
                                present: true,
                            }
                        }
                        // One operand alone: the union is it, the difference is `a`.
                        (BoolOp::Union, true, false) | (BoolOp::Difference, true, false) => a,
                        (BoolOp::Union, false, true) => {
                            out.drain(a.at..b.at);
                            Part {
                                at: a.at,
                                present: true,
                            }
                        }
                        // An intersection with nothing, or nothing minus anything.
                        _ => {
                            out.truncate(a.at);
                            Part {
                                at: a.at,
                                present: false,
                            }
                        }
                    };
                    parts.push(keep);
                }
            }
        }
        Pruned { instrs: out }
    }
}

impl Pruned {
    /// True when nothing is left: every ray in the region misses.
    pub(crate) fn is_empty(&self) -> bool {
        self.instrs.is_empty()
    }

    /// Number of primitives left.
    #[cfg(test)]
    pub(crate) fn leaf_count(&self) -> usize {
        self.instrs
            .iter()
            .filter(|i| matches!(i, Instr::Leaf(_)))
            .count()
    }

    /// The pruned field at `p` (`+∞` when empty).
    #[inline]
    pub(crate) fn distance(&self, scene: &Scene, p: DVec3) -> f64 {
        self.run::<false>(scene, p).0
    }

    /// The pruned field at `p` and the material deciding it.
    pub(crate) fn distance_material(&self, scene: &Scene, p: DVec3) -> (f64, u32) {
        self.run::<true>(scene, p)
    }

    #[inline]
    fn run<const MAT: bool>(&self, scene: &Scene, p: DVec3) -> (f64, u32) {
        run_at::<MAT>(&self.instrs, &scene.program.leaves, p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        Scene::from_json_str(
            r#"{"op": "subtract", "children": [
                {"op": "union", "children": [
                    {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [2, 2, 2]}},
                    {"kind": "sdf_primitive", "pos": [5, 0, 0],
                     "data": {"primitive_type": "sphere", "radius": 1}}
                ]},
                {"kind": "sdf_primitive", "pos": [5, 1, 0],
                 "data": {"primitive_type": "sphere", "radius": 0.5}},
                {"kind": "sdf_primitive", "pos": [0, 1, 0],
                 "data": {"primitive_type": "sphere", "radius": 0.5}}
            ]}"#,
        )
        .unwrap()
    }

    #[test]
    fn pruning_keeps_what_the_region_sees() {
        let s = scene();
        let c = Culler::new(&s);
        assert_eq!(c.prune(0.0, |_| true).leaf_count(), 4);
        // Around the box only: the far sphere and its cutter go.
        let near = Aabb::new(DVec3::splat(-1.5), DVec3::splat(1.5));
        let p = c.prune(0.0, |b| b.overlaps(&near, 0.0));
        assert_eq!(p.leaf_count(), 2);
        for q in [
            DVec3::new(0.0, 1.2, 0.0),
            DVec3::new(1.2, 0.3, -0.4),
            DVec3::ZERO,
        ] {
            assert_eq!(p.distance(&s, q), s.distance(q), "{q}");
        }
        // Far from everything: nothing left.
        let far = Aabb::new(DVec3::splat(20.0), DVec3::splat(21.0));
        assert!(c.prune(0.0, |b| b.overlaps(&far, 0.0)).is_empty());
    }

    #[test]
    fn smooth_children_are_kept_within_the_blend_reach() {
        let s = Scene::from_json_str(
            r#"{"op": "smooth_union", "smooth": "polynomial", "smooth_k": 0.5, "children": [
                {"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}},
                {"kind": "sdf_primitive", "pos": [2.6, 0, 0],
                 "data": {"primitive_type": "sphere", "radius": 1}}
            ]}"#,
        )
        .unwrap();
        let c = Culler::new(&s);
        // Between the spheres: the second is within 2k = 1 of the region, so both stay.
        let between = Aabb::new(DVec3::new(0.65, -0.1, -0.1), DVec3::new(0.7, 0.1, 0.1));
        assert_eq!(c.prune(0.0, |b| b.overlaps(&between, 0.0)).leaf_count(), 2);
        // Beyond the first sphere's far side the second is out of reach, and the value holds.
        let left = Aabb::new(DVec3::new(-1.2, -0.1, -0.1), DVec3::new(-1.1, 0.1, 0.1));
        let p = c.prune(0.0, |b| b.overlaps(&left, 0.0));
        assert_eq!(p.leaf_count(), 1);
        let q = DVec3::new(-1.15, 0.0, 0.0);
        assert_eq!(p.distance(&s, q), s.distance(q));
    }

    #[test]
    fn pruned_fields_agree_inside_their_regions() {
        // Every example scene, many small regions: inside each, the pruned field has the
        // full field's sign everywhere and its value near the surface.
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenes");
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for name in ["mechanical_part", "organic_blend", "extruded_profile"] {
            let s = Scene::from_path(format!("{dir}/{name}.json")).unwrap();
            let c = Culler::new(&s);
            let b = s.bbox().expanded(0.2);
            let pad = 0.01;
            let mut dropped = 0;
            for _ in 0..300 {
                let corner = b.min + b.size() * DVec3::new(next(), next(), next());
                let region = Aabb::new(corner, corner + b.size() * 0.1);
                let p = c.prune(pad, |x| x.overlaps(&region, 0.0));
                dropped += s.primitive_count() - p.leaf_count();
                for _ in 0..40 {
                    let q = region.min + region.size() * DVec3::new(next(), next(), next());
                    let (full, pruned) = (s.distance(q), p.distance(&s, q));
                    assert_eq!(
                        full <= 0.0,
                        pruned <= 0.0,
                        "{name} at {q}: {full} vs {pruned}"
                    );
                    if pruned.abs() < pad {
                        assert!(
                            (full - pruned).abs() < 1e-6,
                            "{name} at {q}: {full} vs {pruned}"
                        );
                    }
                }
            }
            assert!(dropped > 0, "{name}: pruning never dropped anything");
        }
    }
}
