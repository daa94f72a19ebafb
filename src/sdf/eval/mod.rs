//! The tree flattened into a postfix program over a value stack, evaluated for one point or a
//! batch at a time, with the conservative bounds of what it describes.
//!
//! Flattening does three things once instead of at every point: it composes each leaf's
//! transforms into one world → local map, it turns every distance and smoothing constant into
//! world units, and it replaces the tree walk by a linear loop. A node with children
//! `c1 … cn` becomes `c1 c2 op c3 op … cn op`, a left fold as the spec's pseudocode does, so
//! the stack stays shallow however wide a node is.

mod bound;
mod combine;

use glam::{DAffine3, DVec3};
use smallvec::SmallVec;

use super::shapes::Shape;
use super::tree::{Frame, NodeId, NodeKind, SmoothKind, Tree};
use crate::error::{Error, Result};
use crate::solid::BoolOp;
use bound::combine_bounds;
pub(crate) use bound::{Bound, map_box};
use combine::{combine, combine_material, combine_slices};

/// One primitive, placed in the world.
#[derive(Clone, Debug)]
pub(crate) struct Leaf {
    pub shape: Shape,
    /// World → local.
    pub to_local: DAffine3,
    /// Local → world.
    pub to_world: DAffine3,
    pub identity: bool,
    /// World distance per local distance (σ of the frame: a lower bound on the stretch).
    pub factor: f64,
    /// Largest over smallest stretch of the frame.
    pub condition: f64,
    pub material: u32,
    /// The tree node it came from (the scene maps it to the node's JSON path).
    pub node: NodeId,
}

/// A binary combination of the two values on top of the stack (`a` below `b`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Op {
    Union,
    Intersect,
    /// `a` minus `b`.
    Subtract,
    /// A smooth variant with `k` in world units.
    Smooth {
        op: BoolOp,
        kind: SmoothKind,
        k: f64,
    },
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Instr {
    /// Push the value of `leaves[i]`.
    Leaf(u32),
    /// Push `+∞`: the empty set.
    Empty,
    Op(Op),
}

/// The flattened, evaluable form of a (sub)tree.
#[derive(Clone, Debug, Default)]
pub(crate) struct Program {
    pub instrs: Vec<Instr>,
    pub leaves: Vec<Leaf>,
    /// The deepest the value stack gets.
    pub depth: usize,
}

/// Points per batch: big enough to amortise the instruction dispatch, small enough that the
/// stack slots stay in L1.
const CHUNK: usize = 128;

/// Reusable buffers for batch evaluation; one per thread.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    vals: Vec<f64>,
    mats: Vec<u32>,
    local: Vec<DVec3>,
}

impl Scratch {
    /// Combines stack slot `top` into slot `top - 1` for the first `n` points.
    #[inline]
    fn combine_top<const MAT: bool>(&mut self, op: Op, top: usize, n: usize) {
        let (lo, hi) = self.vals.split_at_mut(top * CHUNK);
        let a = &mut lo[(top - 1) * CHUNK..(top - 1) * CHUNK + n];
        let b = &hi[..n];
        if MAT {
            let (mlo, mhi) = self.mats.split_at_mut(top * CHUNK);
            let ma = &mut mlo[(top - 1) * CHUNK..(top - 1) * CHUNK + n];
            let mb = &mhi[..n];
            for i in 0..n {
                let (d, m) = combine_material(op, (a[i], ma[i]), (b[i], mb[i]));
                a[i] = d;
                ma[i] = m;
            }
        } else {
            combine_slices(op, a, b);
        }
    }
}

impl Leaf {
    /// A primitive placed by `frame`; refused when the frame cannot be inverted.
    fn new(shape: &Shape, material: u32, node: NodeId, frame: &Frame) -> Result<Leaf> {
        let to_local = frame.to_world.inverse();
        if !(to_local.is_finite() && frame.to_world.is_finite()) {
            return Err(singular());
        }
        Ok(Leaf {
            shape: shape.clone(),
            to_local,
            to_world: frame.to_world,
            identity: frame.to_world == DAffine3::IDENTITY,
            factor: frame.sigma,
            condition: frame.condition(),
            material,
            node,
        })
    }

    /// World-unit distances at `points` into `dst`, using `local` for the points in the
    /// primitive's frame.
    #[inline]
    fn distances(&self, points: &[DVec3], local: &mut [DVec3], dst: &mut [f64]) {
        if self.identity {
            self.shape.distances(points, dst);
        } else {
            for (q, &p) in local.iter_mut().zip(points) {
                *q = self.to_local.transform_point3(p);
            }
            self.shape.distances(local, dst);
        }
        if self.factor != 1.0 {
            for d in dst.iter_mut() {
                *d *= self.factor;
            }
        }
    }
}

impl Op {
    /// The instruction of a boolean node in `frame`.
    fn new(op: BoolOp, smooth: Option<(SmoothKind, f64)>, frame: &Frame) -> Op {
        match smooth {
            None => match op {
                BoolOp::Union => Op::Union,
                BoolOp::Intersection => Op::Intersect,
                BoolOp::Difference => Op::Subtract,
            },
            // Smoothing constants to world units (the blends are homogeneous of degree one in
            // (distance, 1/k) resp. (distance, k)).
            Some((kind, k)) => Op::Smooth {
                op,
                kind,
                k: match kind {
                    SmoothKind::Exponential => k / frame.sigma,
                    SmoothKind::Polynomial => k * frame.sigma,
                },
            },
        }
    }
}

impl Program {
    /// Flattens the subtree at `root`, whose parent frame is `parent`.
    pub(crate) fn compile(tree: &Tree, root: NodeId, parent: Frame) -> Result<Program> {
        enum Work {
            Visit(NodeId, Frame),
            Emit(Op),
        }
        let mut prog = Program::default();
        let mut work = vec![Work::Visit(root, parent)];
        let mut depth = 0usize;
        while let Some(w) = work.pop() {
            match w {
                Work::Emit(op) => {
                    prog.instrs.push(Instr::Op(op));
                    depth -= 1;
                }
                Work::Visit(id, parent) => {
                    let node = tree.node(id);
                    let frame = parent.child(&node.transform);
                    if !(frame.sigma > 0.0 && frame.sigma_max.is_finite()) {
                        return Err(singular());
                    }
                    match &node.kind {
                        NodeKind::Leaf { shape, material } => {
                            prog.instrs.push(Instr::Leaf(prog.leaves.len() as u32));
                            prog.leaves.push(Leaf::new(shape, *material, id, &frame)?);
                            depth += 1;
                            prog.depth = prog.depth.max(depth);
                        }
                        NodeKind::Op {
                            op,
                            smooth,
                            children,
                        } => {
                            if children.is_empty() {
                                prog.instrs.push(Instr::Empty);
                                depth += 1;
                                prog.depth = prog.depth.max(depth);
                                continue;
                            }
                            let code = Op::new(*op, *smooth, &frame);
                            // Pushed in reverse so they pop as c1 c2 op c3 op … cn op.
                            for (i, &c) in children.iter().enumerate().rev() {
                                if i > 0 {
                                    work.push(Work::Emit(code));
                                }
                                work.push(Work::Visit(c, frame));
                            }
                        }
                    }
                }
            }
        }
        Ok(prog)
    }

    /// The value at one point.
    pub(crate) fn eval(&self, p: DVec3) -> f64 {
        self.eval_scalar::<false>(p).0
    }

    /// The value at one point and the material of the primitive that decides it.
    pub(crate) fn eval_material(&self, p: DVec3) -> (f64, u32) {
        self.eval_scalar::<true>(p)
    }

    fn eval_scalar<const MAT: bool>(&self, p: DVec3) -> (f64, u32) {
        run_at::<MAT>(&self.instrs, &self.leaves, p)
    }

    /// Values at many points into `out` (same length).
    pub(crate) fn eval_batch(&self, scratch: &mut Scratch, points: &[DVec3], out: &mut [f64]) {
        for (p, o) in points.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            self.run_chunk::<false>(scratch, p, o, &mut []);
        }
    }

    /// Values and deciding materials at many points.
    pub(crate) fn eval_batch_material(
        &self,
        scratch: &mut Scratch,
        points: &[DVec3],
        out: &mut [f64],
        materials: &mut [u32],
    ) {
        for ((p, o), m) in points
            .chunks(CHUNK)
            .zip(out.chunks_mut(CHUNK))
            .zip(materials.chunks_mut(CHUNK))
        {
            self.run_chunk::<true>(scratch, p, o, m);
        }
    }

    fn run_chunk<const MAT: bool>(
        &self,
        s: &mut Scratch,
        points: &[DVec3],
        out: &mut [f64],
        materials: &mut [u32],
    ) {
        let n = points.len();
        let slots = self.depth.max(1);
        if s.vals.len() < slots * CHUNK {
            s.vals.resize(slots * CHUNK, 0.0);
        }
        if MAT && s.mats.len() < slots * CHUNK {
            s.mats.resize(slots * CHUNK, 0);
        }
        if s.local.len() < CHUNK {
            s.local.resize(CHUNK, DVec3::ZERO);
        }
        let mut top = 0usize;
        for ins in &self.instrs {
            match *ins {
                Instr::Leaf(i) => {
                    let l = &self.leaves[i as usize];
                    let dst = &mut s.vals[top * CHUNK..top * CHUNK + n];
                    l.distances(points, &mut s.local[..n], dst);
                    if MAT {
                        s.mats[top * CHUNK..top * CHUNK + n].fill(l.material);
                    }
                    top += 1;
                }
                Instr::Empty => {
                    s.vals[top * CHUNK..top * CHUNK + n].fill(f64::INFINITY);
                    if MAT {
                        s.mats[top * CHUNK..top * CHUNK + n].fill(0);
                    }
                    top += 1;
                }
                Instr::Op(op) => {
                    if top < 2 {
                        // Unreachable for a compiled program; stay total anyway.
                        continue;
                    }
                    top -= 1;
                    s.combine_top::<MAT>(op, top, n);
                }
            }
        }
        if top == 0 {
            out.fill(f64::INFINITY);
            materials.fill(0);
            return;
        }
        out.copy_from_slice(&s.vals[(top - 1) * CHUNK..(top - 1) * CHUNK + n]);
        if MAT {
            materials.copy_from_slice(&s.mats[(top - 1) * CHUNK..(top - 1) * CHUNK + n]);
        }
    }

    /// The conservative bound of the whole program (see [`Bound`]).
    pub(crate) fn bound(&self) -> Bound {
        // In postfix order the last instruction closes the whole program.
        let mut last = Bound::EMPTY;
        if !self.walk_bounds(|_, b, _| last = b) {
            return Bound::EMPTY;
        }
        last
    }

    /// One postfix walk over the bounds of every subexpression: `visit(i, bound, operands)` is
    /// called for each instruction `i` with the bound of the subexpression it closes and, for an
    /// operation, the instructions closing its two operands `(a, b)`. Returns false, having
    /// stopped, at an operation short of operands (unreachable for a compiled program).
    pub(crate) fn walk_bounds(
        &self,
        mut visit: impl FnMut(usize, Bound, Option<(usize, usize)>),
    ) -> bool {
        // Per stack entry: (instruction that closes it, its bound).
        let mut stack: Vec<(usize, Bound)> = Vec::with_capacity(self.depth);
        for (i, ins) in self.instrs.iter().enumerate() {
            let (b, operands) = match *ins {
                Instr::Leaf(l) => {
                    let l = &self.leaves[l as usize];
                    let bbox = map_box(&l.to_world, &l.shape.local_bounds());
                    let b = Bound {
                        bbox,
                        alpha: l.condition,
                    };
                    (b, None)
                }
                Instr::Empty => (Bound::EMPTY, None),
                Instr::Op(op) => {
                    let (Some((jb, b)), Some((ja, a))) = (stack.pop(), stack.pop()) else {
                        return false;
                    };
                    (combine_bounds(op, a, b), Some((ja, jb)))
                }
            };
            visit(i, b, operands);
            stack.push((i, b));
        }
        true
    }

    /// The material ids the program can answer.
    pub(crate) fn materials(&self) -> impl Iterator<Item = u32> + '_ {
        self.leaves.iter().map(|l| l.material)
    }
}

fn singular() -> Error {
    Error::Scene {
        file: None,
        json_path: "$".into(),
        message: "the nested transforms compose to a map that cannot be inverted in f64 \
                  (scales too small or too large)"
            .into(),
    }
}

/// Runs `instrs` (postfix, over `leaves`) at one point: the value and, with `MAT`, the material
/// deciding it. Shared by the whole program and by the culler's pruned programs.
#[inline]
pub(super) fn run_at<const MAT: bool>(instrs: &[Instr], leaves: &[Leaf], p: DVec3) -> (f64, u32) {
    let mut stack: SmallVec<[(f64, u32); 16]> = SmallVec::new();
    for ins in instrs {
        match *ins {
            Instr::Leaf(i) => {
                let l = &leaves[i as usize];
                let q = if l.identity {
                    p
                } else {
                    l.to_local.transform_point3(p)
                };
                stack.push((l.shape.distance(q) * l.factor, l.material));
            }
            Instr::Empty => stack.push((f64::INFINITY, 0)),
            Instr::Op(op) => {
                let (Some(b), Some(a)) = (stack.pop(), stack.pop()) else {
                    return (f64::INFINITY, 0);
                };
                stack.push(if MAT {
                    combine_material(op, a, b)
                } else {
                    (combine(op, a.0, b.0), 0)
                });
            }
        }
    }
    stack.pop().unwrap_or((f64::INFINITY, 0))
}
