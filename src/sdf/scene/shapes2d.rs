//! 2D shape declarations (`sdf_2d` tables and inline shapes) and the simplicity check of
//! polygons.

use std::collections::HashMap;
use std::sync::Arc;

use glam::DVec2;
use serde_json::Value;

use super::json::{array, fault, key_path, object, only, positive, required, string, vec2};
use crate::error::Result;
use crate::sdf::shapes::Shape2;

/// The most points a 2D polygon may have (its simplicity check is quadratic).
pub const MAX_POLYGON_POINTS: usize = 10_000;

pub(super) fn shapes_2d(v: &Value, path: &str) -> Result<HashMap<String, Shape2>> {
    let m = object(v, path, "a table of 2D shapes (id → shape)")?;
    m.iter()
        .map(|(id, s)| Ok((id.clone(), shape_2d(s, &key_path(path, id))?)))
        .collect()
}

/// A 2D shape declaration: `{"type": "rectangle"|"circle"|"polygon", …}`.
pub(super) fn shape_2d(v: &Value, path: &str) -> Result<Shape2> {
    let m = object(v, path, "a 2D shape")?;
    let ty = string(
        required(m, path, "type", "rectangle, circle or polygon")?,
        &key_path(path, "type"),
    )?;
    match ty {
        "rectangle" => {
            only(m, path, &["type", "size", "name"], "a rectangle")?;
            let sp = key_path(path, "size");
            let a = array(required(m, path, "size", "[width, height]")?, &sp, Some(2))?;
            let w = positive(&a[0], &format!("{sp}[0]"))?;
            let h = positive(&a[1], &format!("{sp}[1]"))?;
            Ok(Shape2::Rect {
                half: DVec2::new(w, h) * 0.5,
            })
        }
        "circle" => {
            only(m, path, &["type", "radius", "name"], "a circle")?;
            Ok(Shape2::Circle {
                radius: positive(
                    required(m, path, "radius", "the circle's radius")?,
                    &key_path(path, "radius"),
                )?,
            })
        }
        "polygon" => {
            only(m, path, &["type", "points", "name"], "a polygon")?;
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
            Ok(Shape2::Polygon {
                points: Arc::from(pts),
            })
        }
        other => Err(fault(
            &key_path(path, "type"),
            format!("unknown 2D shape type `{other}`; expected rectangle, circle or polygon"),
        )),
    }
}

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
