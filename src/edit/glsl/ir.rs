//! The scene's distance function as straight-line code: one statement per transform, primitive
//! or combination, each of which is one call of a helper in `prelude.glsl`. The GLSL printer
//! and the test interpreter both read this form, so the interpreter checks what the GPU runs.

use glam::{DMat3, DVec2, DVec3};

use crate::sdf::{Instr, Instr2, Op, Place2, Prim2, Program, Shape, Shape2, SmoothKind};
use crate::solid::BoolOp;

/// A value in the generated code: `p` (the world point) or a numbered local.
pub(crate) type Var = u32;

/// One statement of the 3D scene function.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Stmt {
    /// `vec3 q{dst} = m * p + t;` the world → local map of a primitive.
    Point { dst: Var, m: DMat3, t: DVec3 },
    /// `float d{dst} = call(q{q} or p) * factor;` a primitive's world distance, from leaf `leaf`;
    /// with `cull`, skipped where it cannot change the combination it feeds.
    Dist {
        dst: Var,
        q: Option<Var>,
        call: Call,
        factor: f64,
        leaf: u32,
        cull: Option<Cull>,
    },
    /// `float d{dst} = EMPTY;` an operation without children.
    Empty { dst: Var },
    /// `float d{dst} = combine(d{a}, d{b});`
    Combine {
        dst: Var,
        op: Combine,
        a: Var,
        b: Var,
    },
}

/// When a primitive is the right operand of a union or a subtraction, far from its bounding
/// sphere it cannot change the result: there the code uses the sphere's bound
/// `L = ratio · |p − center| − radius` (≤ the primitive's value) instead of evaluating it. `L`
/// is taken where `L > ±d{against} + margin` (`+` for a union, `−` for a subtraction): then the
/// combination's value and deciding operand are those of `d{against}` either way (up to
/// `e^(−40)` of the blend for an exponential smooth one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Cull {
    pub center: DVec3,
    pub ratio: f64,
    pub radius: f64,
    pub against: Var,
    pub negate: bool,
    pub margin: f64,
}

/// A boolean with its smoothing, `k` in world units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Combine {
    pub op: BoolOp,
    /// `(polynomial?, k)` for the smooth variants.
    pub smooth: Option<(bool, f64)>,
}

/// One call of a primitive's helper; 2D shapes are functions of their own (`shape2d_{n}`).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Call {
    Box {
        half: DVec3,
    },
    Sphere {
        radius: f64,
    },
    Cylinder {
        radius: f64,
        half_height: f64,
    },
    Cone {
        half_height: f64,
        r_bottom: f64,
        r_top: f64,
    },
    Pyramid {
        base: f64,
        height: f64,
    },
    Plane {
        normal: DVec3,
        offset: f64,
    },
    Torus {
        major: f64,
        minor: f64,
    },
    /// A plain extrusion of 2D function `shape` over `|z| ≤ half_depth`.
    Extrude {
        shape: u32,
        half_depth: f64,
    },
    /// A twisted and / or tapered extrusion and its Lipschitz constants (see `sdf::extrusion`).
    Warped {
        shape: u32,
        half_depth: f64,
        twist: f64,
        scale_top: DVec2,
        reach: f64,
        slope: DVec3,
        bmin: DVec3,
        bmax: DVec3,
    },
    /// A revolution of 2D function `shape` by `angle` degrees.
    Revolve {
        shape: u32,
        angle: f64,
    },
}

/// One statement of a 2D shape function (the postfix program of `Shape2`, unrolled).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Stmt2 {
    /// `float e{dst} = prim(place⁻¹(p));`
    Leaf {
        dst: Var,
        prim: Call2,
        place: Place2,
    },
    /// `float e{dst} = min / max(e{a}, ±e{b});`
    Combine {
        dst: Var,
        op: BoolOp,
        a: Var,
        b: Var,
    },
}

/// One 2D primitive's helper call.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Call2 {
    Rect {
        half: DVec2,
    },
    Circle {
        radius: f64,
    },
    RoundedRect {
        half: DVec2,
        radius: f64,
    },
    /// Points of constant array `polygon_{index}`.
    Polygon {
        index: u32,
        points: Vec<DVec2>,
    },
}

/// The scene's code: the 3D statements (the last one's value is the distance), the 2D shape
/// functions they call, and the material of each leaf.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Code {
    pub stmts: Vec<Stmt>,
    pub shapes: Vec<Vec<Stmt2>>,
    pub materials: Vec<u32>,
    /// The variable holding the result; `None` for an empty program.
    pub result: Option<Var>,
}

impl Code {
    /// Unrolls a compiled program (the same one the CPU evaluates, so transforms, world-unit
    /// factors and smoothing constants are taken over exactly).
    /// With `cull`, primitives are skipped by their bounding spheres where they cannot matter
    /// (see [`Cull`]).
    pub(crate) fn from_program(program: &Program, cull: bool) -> Code {
        let mut code = Code::default();
        let mut stack: Vec<Var> = Vec::new();
        let mut next: Var = 0;
        let mut polygons = 0u32;
        for ins in &program.instrs {
            match *ins {
                Instr::Leaf(i) => {
                    let leaf = &program.leaves[i as usize];
                    let q = if leaf.identity {
                        None
                    } else {
                        let m = leaf.to_local;
                        code.stmts.push(Stmt::Point {
                            dst: next,
                            m: m.matrix3,
                            t: m.translation,
                        });
                        next += 1;
                        Some(next - 1)
                    };
                    let call = code.call(&leaf.shape, &mut polygons);
                    code.stmts.push(Stmt::Dist {
                        dst: next,
                        q,
                        call,
                        factor: leaf.factor,
                        leaf: i,
                        cull: None,
                    });
                    code.materials.push(leaf.material);
                    stack.push(next);
                    next += 1;
                }
                Instr::Empty => {
                    code.stmts.push(Stmt::Empty { dst: next });
                    stack.push(next);
                    next += 1;
                }
                Instr::Op(op) => {
                    let (Some(b), Some(a)) = (stack.pop(), stack.pop()) else {
                        break;
                    };
                    let op = combine_of(op);
                    if cull {
                        code.cull(program, &op, a, b);
                    }
                    code.stmts.push(Stmt::Combine {
                        dst: next,
                        op,
                        a,
                        b,
                    });
                    stack.push(next);
                    next += 1;
                }
            }
        }
        code.result = stack.pop();
        code
    }

    /// Marks `d{b}` as culled against `d{a}` when it is a bounded primitive whose distance is
    /// exact in its frame (so never below its bounding sphere's) and `op` lets it be skipped.
    fn cull(&mut self, program: &Program, op: &Combine, a: Var, b: Var) {
        let (negate, margin) = match (op.op, op.smooth) {
            (BoolOp::Intersection, _) => return,
            (BoolOp::Union, None) => (false, 0.0),
            (BoolOp::Difference, None) => (true, 0.0),
            (o, Some((poly, k))) => (
                o == BoolOp::Difference,
                // A polynomial blend ends where the operands differ by k; an exponential one
                // adds at most ln(1 + e^(−40)) / k beyond 40 / k.
                if poly { k } else { 40.0 / k },
            ),
        };
        let Some(Stmt::Dist {
            dst, leaf, cull, ..
        }) = self.stmts.last_mut()
        else {
            return;
        };
        if *dst != b {
            return;
        }
        let l = &program.leaves[*leaf as usize];
        let exact = matches!(
            l.shape,
            Shape::Box { .. }
                | Shape::Sphere { .. }
                | Shape::Cylinder { .. }
                | Shape::Cone { .. }
                | Shape::Pyramid { .. }
                | Shape::Torus { .. }
        );
        let bounds = l.shape.local_bounds();
        if !exact || bounds.is_empty() || !(l.factor > 0.0 && l.condition.is_finite()) {
            return;
        }
        let center = bounds.center();
        *cull = Some(Cull {
            center: l.to_world.transform_point3(center),
            ratio: 1.0 / l.condition,
            radius: l.factor * 0.5 * bounds.diagonal(),
            against: a,
            negate,
            margin,
        });
    }

    fn call(&mut self, shape: &Shape, polygons: &mut u32) -> Call {
        match shape {
            Shape::Box { half } => Call::Box { half: *half },
            Shape::Sphere { radius } => Call::Sphere { radius: *radius },
            Shape::Cylinder {
                radius,
                half_height,
            } => Call::Cylinder {
                radius: *radius,
                half_height: *half_height,
            },
            Shape::Cone {
                r_bottom,
                r_top,
                half_height,
            } => Call::Cone {
                half_height: *half_height,
                r_bottom: *r_bottom,
                r_top: *r_top,
            },
            Shape::Pyramid { base, height } => Call::Pyramid {
                base: *base,
                height: *height,
            },
            Shape::Plane { normal, offset } => Call::Plane {
                normal: *normal,
                offset: *offset,
            },
            Shape::Torus { major, minor } => Call::Torus {
                major: *major,
                minor: *minor,
            },
            Shape::Extrude(e) => {
                let shape = self.shape2(&e.shape, polygons);
                if e.is_plain() {
                    Call::Extrude {
                        shape,
                        half_depth: e.half_depth,
                    }
                } else {
                    let (reach, turn, rate, per_rho) = e.slope();
                    let b = e.local_bounds();
                    Call::Warped {
                        shape,
                        half_depth: e.half_depth,
                        twist: e.twist,
                        scale_top: e.scale_top,
                        reach,
                        slope: DVec3::new(turn, rate, per_rho),
                        bmin: b.min,
                        bmax: b.max,
                    }
                }
            }
            Shape::Revolve { shape, angle } => Call::Revolve {
                shape: self.shape2(shape, polygons),
                angle: *angle,
            },
        }
    }

    /// Adds a 2D shape function and returns its number.
    fn shape2(&mut self, shape: &Shape2, polygons: &mut u32) -> u32 {
        let (leaves, instrs) = shape.parts();
        let mut stmts = Vec::new();
        let mut stack: Vec<Var> = Vec::new();
        for (next, ins) in instrs.iter().enumerate() {
            let dst = next as Var;
            match *ins {
                Instr2::Leaf(k) => {
                    let (prim, place) = &leaves[k as usize];
                    let prim = match prim {
                        Prim2::Rect { half } => Call2::Rect { half: *half },
                        Prim2::Circle { radius } => Call2::Circle { radius: *radius },
                        Prim2::RoundedRect { half, radius } => Call2::RoundedRect {
                            half: *half,
                            radius: *radius,
                        },
                        Prim2::Polygon { points } | Prim2::RegularPolygon { points, .. } => {
                            *polygons += 1;
                            Call2::Polygon {
                                index: *polygons - 1,
                                points: points.to_vec(),
                            }
                        }
                    };
                    stmts.push(Stmt2::Leaf {
                        dst,
                        prim,
                        place: *place,
                    });
                    stack.push(dst);
                }
                Instr2::Op(op) => {
                    let (Some(b), Some(a)) = (stack.pop(), stack.pop()) else {
                        break;
                    };
                    stmts.push(Stmt2::Combine { dst, op, a, b });
                    stack.push(dst);
                }
            }
        }
        self.shapes.push(stmts);
        self.shapes.len() as u32 - 1
    }
}

fn combine_of(op: Op) -> Combine {
    match op {
        Op::Union => Combine {
            op: BoolOp::Union,
            smooth: None,
        },
        Op::Intersect => Combine {
            op: BoolOp::Intersection,
            smooth: None,
        },
        Op::Subtract => Combine {
            op: BoolOp::Difference,
            smooth: None,
        },
        Op::Smooth { op, kind, k } => Combine {
            op,
            smooth: Some((kind == SmoothKind::Polynomial, k)),
        },
    }
}
