//! 2D shape declarations (`sdf_2d` tables and inline shapes, 2D operations over them) and the
//! simplicity check of polygons.

use std::collections::HashMap;
use std::sync::Arc;

use glam::DVec2;
use serde_json::{Map, Value};

use super::json::{
    array, count, fault, key_path, non_negative, number, object, only, positive, required, string,
    vec2,
};
use crate::error::Result;
use crate::sdf::shapes2d::{Builder, Place2, Prim2, Shape2};
use crate::sketch::Sketch;
use crate::solid::BoolOp;

/// The most points a 2D polygon may have (its simplicity check is quadratic).
pub const MAX_POLYGON_POINTS: usize = 10_000;

/// How a 2D shape reference (a string id) finds its shape: the declarations in scope.
pub(super) type Lookup<'a> = &'a dyn Fn(&str) -> Option<Shape2>;

/// An `sdf_2d` table. Its entries may name shapes of enclosing tables (through `lookup`), not
/// each other.
pub(super) fn shapes_2d(
    v: &Value,
    path: &str,
    lookup: Lookup<'_>,
) -> Result<HashMap<String, Shape2>> {
    let m = object(v, path, "a table of 2D shapes (id → shape)")?;
    m.iter()
        .map(|(id, s)| Ok((id.clone(), shape_2d(s, &key_path(path, id), lookup)?)))
        .collect()
}

/// A 2D shape: a primitive `{"type": …}`, a 2D operation `{"op": "union"|"intersect"|
/// "subtract", "children": […]}`, or (inside an operation) the id of a declared shape. Shapes
/// and operations may carry `"pos": [x, y]` and `"rot": degrees`. Nested operations are read
/// with an explicit work stack into one postfix program.
pub(super) fn shape_2d(v: &Value, path: &str, lookup: Lookup<'_>) -> Result<Shape2> {
    enum Work<'a> {
        Visit(&'a Value, String, Place2),
        Op(BoolOp),
    }
    let mut out = Builder::default();
    let mut work = vec![Work::Visit(v, path.to_string(), Place2::IDENTITY)];
    while let Some(w) = work.pop() {
        let (v, path, outer) = match w {
            Work::Op(op) => {
                out.op(op);
                continue;
            }
            Work::Visit(v, path, outer) => (v, path, outer),
        };
        if let Value::String(id) = v {
            let shape = lookup(id).ok_or_else(|| {
                fault(
                    &path,
                    format!(
                        "unknown 2D shape id `{id}` (ids name shapes of enclosing sdf_2d tables)"
                    ),
                )
            })?;
            out.shape(&shape, outer);
            continue;
        }
        let m = object(
            v,
            &path,
            "a 2D shape, a 2D operation or a declared shape's id",
        )?;
        let place = outer.then(&placement(m, &path)?);
        let Some(op) = m.get("op") else {
            out.leaf(primitive_2d(m, &path)?, place);
            continue;
        };
        only(
            m,
            &path,
            &["op", "children", "pos", "rot", "name"],
            "a 2D operation",
        )?;
        let op = match string(op, &key_path(&path, "op"))? {
            "union" => BoolOp::Union,
            "intersect" => BoolOp::Intersection,
            "subtract" => BoolOp::Difference,
            other => {
                return Err(fault(
                    &key_path(&path, "op"),
                    format!("unknown 2D op `{other}`; expected union, intersect or subtract"),
                ));
            }
        };
        let cp = key_path(&path, "children");
        let children = array(required(m, &path, "children", "the operands")?, &cp, None)?;
        if children.is_empty() {
            return Err(fault(&cp, "a 2D operation needs at least one child"));
        }
        // Postfix, folded left: c0 c1 op c2 op …; pushed in reverse so they pop in order.
        for (i, c) in children.iter().enumerate().skip(1).rev() {
            work.push(Work::Op(op));
            work.push(Work::Visit(c, format!("{cp}[{i}]"), place));
        }
        work.push(Work::Visit(&children[0], format!("{cp}[0]"), place));
    }
    Ok(out.finish())
}

/// A 2D shape's optional placement: `pos` [x, y] and `rot` in degrees.
fn placement(m: &Map<String, Value>, path: &str) -> Result<Place2> {
    let pos = match m.get("pos") {
        Some(v) => vec2(v, &key_path(path, "pos"))?,
        None => DVec2::ZERO,
    };
    let rot = match m.get("rot") {
        Some(v) => number(v, &key_path(path, "rot"))?,
        None => 0.0,
    };
    Ok(Place2 { pos, rot })
}

/// A 2D primitive: `{"type": "rectangle"|"circle"|"polygon"|"rounded_rectangle"|
/// "regular_polygon", …}`.
fn primitive_2d(m: &Map<String, Value>, path: &str) -> Result<Prim2> {
    const TYPES: &str = "rectangle, circle, polygon, rounded_rectangle or regular_polygon";
    let ty = string(required(m, path, "type", TYPES)?, &key_path(path, "type"))?;
    let fields = |extra: &[&'static str]| {
        let mut f = vec!["type", "name", "pos", "rot"];
        f.extend_from_slice(extra);
        f
    };
    let size = |m: &Map<String, Value>| -> Result<DVec2> {
        let sp = key_path(path, "size");
        let a = array(required(m, path, "size", "[width, height]")?, &sp, Some(2))?;
        Ok(DVec2::new(
            positive(&a[0], &format!("{sp}[0]"))?,
            positive(&a[1], &format!("{sp}[1]"))?,
        ))
    };
    match ty {
        "rectangle" => {
            only(m, path, &fields(&["size"]), "a rectangle")?;
            Ok(Prim2::Rect {
                half: size(m)? * 0.5,
            })
        }
        "rounded_rectangle" => {
            only(m, path, &fields(&["size", "radius"]), "a rounded rectangle")?;
            let half = size(m)? * 0.5;
            let rp = key_path(path, "radius");
            let radius = non_negative(required(m, path, "radius", "the corner radius")?, &rp)?;
            if radius > half.min_element() {
                return Err(fault(
                    &rp,
                    format!(
                        "the corner radius {radius} exceeds half the shorter side ({})",
                        half.min_element()
                    ),
                ));
            }
            Ok(Prim2::RoundedRect { half, radius })
        }
        "circle" => {
            only(m, path, &fields(&["radius"]), "a circle")?;
            Ok(Prim2::Circle {
                radius: positive(
                    required(m, path, "radius", "the circle's radius")?,
                    &key_path(path, "radius"),
                )?,
            })
        }
        "regular_polygon" => {
            only(m, path, &fields(&["sides", "radius"]), "a regular polygon")?;
            let sp = key_path(path, "sides");
            let sides = count(
                required(m, path, "sides", "the number of sides (≥ 3)")?,
                &sp,
                3,
            )?;
            if sides > MAX_SIDES {
                return Err(fault(&sp, format!("at most {MAX_SIDES} sides")));
            }
            let radius = positive(
                required(m, path, "radius", "the circumradius (centre to vertex)")?,
                &key_path(path, "radius"),
            )?;
            let sketch =
                Sketch::regular_polygon(sides, radius).map_err(|e| fault(path, e.to_string()))?;
            let points = sketch.regions()[0].outer().to_vec();
            Ok(Prim2::RegularPolygon {
                sides,
                radius,
                points: Arc::from(points),
            })
        }
        "polygon" => {
            only(m, path, &fields(&["points"]), "a polygon")?;
            let pp = key_path(path, "points");
            let a = array(required(m, path, "points", "[[x, y], …]")?, &pp, None)?;
            if a.len() < 3 || a.len() > MAX_POLYGON_POINTS {
                return Err(fault(
                    &pp,
                    format!(
                        "a polygon needs 3 to {MAX_POLYGON_POINTS} points, found {}",
                        a.len()
                    ),
                ));
            }
            let mut pts = a
                .iter()
                .enumerate()
                .map(|(i, q)| vec2(q, &format!("{pp}[{i}]")))
                .collect::<Result<Vec<_>>>()?;
            check_simple(&pts, &pp)?;
            let area2: f64 = (0..pts.len())
                .map(|i| pts[i].perp_dot(pts[(i + 1) % pts.len()]))
                .sum();
            if area2 < 0.0 {
                // Counter-clockwise, so the extruded prism's faces wind outward.
                pts.reverse();
            }
            Ok(Prim2::Polygon {
                points: Arc::from(pts),
            })
        }
        other => Err(fault(
            &key_path(path, "type"),
            format!("unknown 2D shape type `{other}`; expected {TYPES}"),
        )),
    }
}

/// The most sides a regular polygon may have (as many as a round primitive's segments).
const MAX_SIDES: u32 = crate::primitives::MAX_SEGMENTS;

/// A polygon must have distinct consecutive points, an area, and no crossing edges.
pub(super) fn check_simple(pts: &[DVec2], path: &str) -> Result<()> {
    let n = pts.len();
    let scale = pts
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()))
        .max(1e-300);
    for i in 0..n {
        if (pts[(i + 1) % n] - pts[i]).length() <= 1e-12 * scale {
            return Err(fault(
                &format!("{path}[{}]", (i + 1) % n),
                "repeats the previous point (edges must have length)",
            ));
        }
    }
    let area2: f64 = (0..n).map(|i| pts[i].perp_dot(pts[(i + 1) % n])).sum();
    if area2.abs() <= 1e-12 * scale * scale {
        return Err(fault(path, "the polygon has no area"));
    }
    let orient = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        for j in i + 1..n {
            // Adjacent edges share a point; they may only touch there (checked by the length
            // test above and by collinear overlap below).
            let (c, d) = (pts[j], pts[(j + 1) % n]);
            let crosses = if j == i + 1 {
                // Adjacent at b: they only meet wrongly by folding back along each other.
                orient(a, b, d) == 0.0 && (d - b).dot(a - b) > 0.0
            } else if i == 0 && j == n - 1 {
                // Adjacent at a (= d).
                orient(c, a, b) == 0.0 && (b - a).dot(c - a) > 0.0
            } else {
                let (o1, o2) = (orient(a, b, c), orient(a, b, d));
                let (o3, o4) = (orient(c, d, a), orient(c, d, b));
                (o1 > 0.0 && o2 < 0.0 || o1 < 0.0 && o2 > 0.0)
                    && (o3 > 0.0 && o4 < 0.0 || o3 < 0.0 && o4 > 0.0)
                    || on_segment(a, b, c)
                    || on_segment(a, b, d)
                    || on_segment(c, d, a)
                    || on_segment(c, d, b)
            };
            if crosses {
                return Err(fault(
                    path,
                    format!(
                        "the polygon is not simple: edge {i}–{} meets edge {j}–{}",
                        (i + 1) % n,
                        (j + 1) % n
                    ),
                ));
            }
        }
    }
    Ok(())
}

pub(super) fn on_segment(a: DVec2, b: DVec2, p: DVec2) -> bool {
    (b - a).perp_dot(p - a) == 0.0
        && p.x >= a.x.min(b.x)
        && p.x <= a.x.max(b.x)
        && p.y >= a.y.min(b.y)
        && p.y <= a.y.max(b.y)
}
