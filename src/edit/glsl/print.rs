//! Prints [`Code`] as GLSL ES 3.00: the 2D shape functions, `sceneDist` (the distance),
//! `sceneLeaf` (the distance and the deciding leaf), and the constants of the view.

use std::fmt::Write;

use glam::{DMat3, DVec2, DVec3};

use super::ir::{Call, Call2, Code, Combine, Cull, Stmt, Stmt2, Var};
use crate::solid::BoolOp;

/// A float literal: always with a point or an exponent; beyond f32 it saturates to ±EMPTY.
pub(crate) fn lit(x: f64) -> String {
    if !x.is_finite() || x.abs() > 1e30 {
        return if x < 0.0 {
            "-1e30".into()
        } else {
            "1e30".into()
        };
    }
    let s = format!("{x:?}");
    if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.0")
    }
}

fn v2(v: DVec2) -> String {
    format!("vec2({}, {})", lit(v.x), lit(v.y))
}

pub(crate) fn v3(v: DVec3) -> String {
    format!("vec3({}, {}, {})", lit(v.x), lit(v.y), lit(v.z))
}

fn m3(m: DMat3) -> String {
    // Column-major, as GLSL's constructor takes it.
    let c = m.to_cols_array();
    let parts: Vec<String> = c.iter().map(|&x| lit(x)).collect();
    format!("mat3({})", parts.join(", "))
}

/// The 2D shape functions and the polygon tables they read.
pub(crate) fn shapes(code: &Code, out: &mut String) {
    for (n, stmts) in code.shapes.iter().enumerate() {
        for s in stmts {
            if let Stmt2::Leaf {
                prim: Call2::Polygon { index, points },
                ..
            } = s
            {
                let pts: Vec<String> = points.iter().map(|&p| v2(p)).collect();
                let _ = writeln!(
                    out,
                    "const vec2 POLYGON_{index}[{}] = vec2[{}]({});",
                    points.len(),
                    points.len(),
                    pts.join(", ")
                );
                // IQ's polygon distance over this table (GLSL has no array parameters of
                // varying size, so one function per table).
                let _ = writeln!(
                    out,
                    "float sdPolygon_{index}(vec2 p) {{\n  \
                     float d = dot(p - POLYGON_{index}[0], p - POLYGON_{index}[0]);\n  \
                     float s = 1.0;\n  \
                     for (int i = 0, j = {last}; i < {n}; j = i, i++) {{\n    \
                     vec2 e = POLYGON_{index}[j] - POLYGON_{index}[i];\n    \
                     vec2 w = p - POLYGON_{index}[i];\n    \
                     vec2 b = w - e * clamp(dot(w, e) / dot(e, e), 0.0, 1.0);\n    \
                     d = min(d, dot(b, b));\n    \
                     bvec3 c = bvec3(p.y >= POLYGON_{index}[i].y, p.y < POLYGON_{index}[j].y, e.x * w.y > e.y * w.x);\n    \
                     if (all(c) || all(not(c))) s = -s;\n  \
                     }}\n  \
                     return s * sqrt(d);\n}}",
                    last = points.len() - 1,
                    n = points.len(),
                );
            }
        }
        let _ = writeln!(out, "float shape2d_{n}(vec2 p) {{");
        let mut last = None;
        for s in stmts {
            match s {
                Stmt2::Leaf { dst, prim, place } => {
                    let q = if place.pos == DVec2::ZERO && place.rot == 0.0 {
                        "p".to_string()
                    } else {
                        let r = place.rot.to_radians();
                        format!(
                            "unplace(p, {}, {})",
                            v2(place.pos),
                            v2(DVec2::new(r.cos(), r.sin()))
                        )
                    };
                    let call = match prim {
                        Call2::Rect { half } => format!("sdRect({q}, {})", v2(*half)),
                        Call2::Circle { radius } => format!("sdCircle({q}, {})", lit(*radius)),
                        Call2::RoundedRect { half, radius } => {
                            format!("sdRoundedRect({q}, {}, {})", v2(*half), lit(*radius))
                        }
                        Call2::Polygon { index, .. } => format!("sdPolygon_{index}({q})"),
                    };
                    let _ = writeln!(out, "  float e{dst} = {call};");
                    last = Some(*dst);
                }
                Stmt2::Combine { dst, op, a, b } => {
                    let e = match op {
                        BoolOp::Union => format!("min(e{a}, e{b})"),
                        BoolOp::Intersection => format!("max(e{a}, e{b})"),
                        BoolOp::Difference => format!("max(e{a}, -e{b})"),
                    };
                    let _ = writeln!(out, "  float e{dst} = {e};");
                    last = Some(*dst);
                }
            }
        }
        match last {
            Some(v) => {
                let _ = writeln!(out, "  return e{v};\n}}");
            }
            None => {
                let _ = writeln!(out, "  return EMPTY;\n}}");
            }
        }
    }
}

fn call(c: &Call, q: &str) -> String {
    match c {
        Call::Box { half } => format!("sdBox({q}, {})", v3(*half)),
        Call::Sphere { radius } => format!("sdSphere({q}, {})", lit(*radius)),
        Call::Cylinder {
            radius,
            half_height,
        } => format!("sdCylinder({q}, {}, {})", lit(*radius), lit(*half_height)),
        Call::Cone {
            half_height,
            r_bottom,
            r_top,
        } => format!(
            "sdCone({q}, {}, {}, {})",
            lit(*half_height),
            lit(*r_bottom),
            lit(*r_top)
        ),
        Call::Pyramid { base, height } => {
            format!("sdPyramid({q}, {}, {})", lit(*base), lit(*height))
        }
        Call::Plane { normal, offset } => {
            format!("sdPlane({q}, {}, {})", v3(*normal), lit(*offset))
        }
        Call::Torus { major, minor } => {
            format!("sdTorus({q}, {}, {})", lit(*major), lit(*minor))
        }
        Call::Extrude { shape, half_depth } => format!(
            "extrusion(shape2d_{shape}({q}.xy), {q}.z, {})",
            lit(*half_depth)
        ),
        Call::Warped {
            shape,
            half_depth,
            twist,
            scale_top,
            reach,
            slope,
            bmin,
            bmax,
        } => {
            let slice = format!(
                "warpedSlice({q}, {}, {}, {})",
                lit(*half_depth),
                lit(*twist),
                v2(*scale_top)
            );
            // The slice point is computed twice; the GLSL compiler folds the common call.
            format!(
                "warpedBound(shape2d_{shape}({slice}.xy) * {slice}.z, {q}, {}, {}, {}, {}, {})",
                lit(*half_depth),
                lit(*reach),
                v3(*slope),
                v3(*bmin),
                v3(*bmax)
            )
        }
        Call::Revolve { shape, angle } => format!(
            "revolution(shape2d_{shape}(meridian({q})), {q}, {})",
            lit(*angle)
        ),
    }
}

fn combine(c: &Combine, a: &str, b: &str) -> String {
    match c.smooth {
        None => match c.op {
            BoolOp::Union => format!("min({a}, {b})"),
            BoolOp::Intersection => format!("max({a}, {b})"),
            BoolOp::Difference => format!("max({a}, -{b})"),
        },
        Some((poly, k)) => {
            let (k, poly) = (lit(k), if poly { "true" } else { "false" });
            match c.op {
                BoolOp::Union => format!("smin({a}, {b}, {k}, {poly})"),
                BoolOp::Intersection => format!("smax({a}, {b}, {k}, {poly})"),
                BoolOp::Difference => format!("smax({a}, -{b}, {k}, {poly})"),
            }
        }
    }
}

/// Writes the bounding-sphere test that guards culled primitive `e` (see [`Cull`]) and returns
/// the variable that then holds its value.
fn cull_guard(k: &Cull, dst: Var, e: &str, with_leaf: bool, out: &mut String) -> String {
    // The bound first: the primitive is evaluated only where it may matter.
    let against = if with_leaf {
        format!("d{}.x", k.against)
    } else {
        format!("d{}", k.against)
    };
    let sign = if k.negate { "-" } else { "" };
    let _ = writeln!(
        out,
        "  float b{dst} = {} * length(p - {}) - {};",
        lit(k.ratio),
        v3(k.center),
        lit(k.radius)
    );
    // A branch, not `?:`, so that the primitive is not evaluated where skipped.
    let _ = writeln!(
        out,
        "  if (!(b{dst} > {sign}{against} + {})) b{dst} = {e};",
        lit(k.margin)
    );
    format!("b{dst}")
}

/// `sceneDist` (with `LEAF == false`) or `sceneLeaf` (distance and deciding leaf as a vec2).
pub(crate) fn scene_function(code: &Code, with_leaf: bool, out: &mut String) {
    let (ty, name) = if with_leaf {
        ("vec2", "sceneLeaf")
    } else {
        ("float", "sceneDist")
    };
    let _ = writeln!(out, "{ty} {name}(vec3 p) {{");
    for s in &code.stmts {
        match s {
            Stmt::Point { dst, m, t } => {
                let _ = writeln!(out, "  vec3 q{dst} = {} * p + {};", m3(*m), v3(*t));
            }
            Stmt::Dist {
                dst,
                q,
                call: c,
                factor,
                leaf,
                cull,
            } => {
                let q = q.map_or("p".to_string(), |v| format!("q{v}"));
                let mut e = call(c, &q);
                if *factor != 1.0 {
                    e = format!("{e} * {}", lit(*factor));
                }
                if let Some(k) = cull {
                    e = cull_guard(k, *dst, &e, with_leaf, out);
                }
                if with_leaf {
                    let _ = writeln!(out, "  vec2 d{dst} = vec2({e}, {leaf}.0);");
                } else {
                    let _ = writeln!(out, "  float d{dst} = {e};");
                }
            }
            Stmt::Empty { dst } => {
                if with_leaf {
                    let _ = writeln!(out, "  vec2 d{dst} = vec2(EMPTY, -1.0);");
                } else {
                    let _ = writeln!(out, "  float d{dst} = EMPTY;");
                }
            }
            Stmt::Combine { dst, op, a, b } => {
                if with_leaf {
                    let pick = match op.op {
                        BoolOp::Union => "pickUnion",
                        BoolOp::Intersection => "pickIntersect",
                        BoolOp::Difference => "pickSubtract",
                    };
                    let d = combine(op, &format!("d{a}.x"), &format!("d{b}.x"));
                    let _ = writeln!(out, "  vec2 d{dst} = {pick}(d{a}, d{b}, {d});");
                } else {
                    let d = combine(op, &format!("d{a}"), &format!("d{b}"));
                    let _ = writeln!(out, "  float d{dst} = {d};");
                }
            }
        }
    }
    match (code.result, with_leaf) {
        (Some(v), _) => {
            let _ = writeln!(out, "  return d{v};\n}}");
        }
        (None, true) => {
            let _ = writeln!(out, "  return vec2(EMPTY, -1.0);\n}}");
        }
        (None, false) => {
            let _ = writeln!(out, "  return EMPTY;\n}}");
        }
    }
}
