//! Operation nodes: booleans (plain and smooth), extrusions and revolutions of 2D shapes.

use serde_json::{Map, Value};

use glam::DVec2;

use super::json::{
    array, fault, key_path, non_negative, number, only, positive, required, string, type_name,
};
use super::parser::Parser;
use super::shapes2d::shape_2d;
use super::transform::transform;
use crate::error::Result;
use crate::sdf::shapes::{Extrusion, Shape};
use crate::sdf::shapes2d::Shape2;
use crate::sdf::tree::{Node, NodeKind, SmoothKind, Transform};
use crate::solid::BoolOp;

impl Parser {
    /// An `op` node: an extrusion (a leaf) or a boolean whose children come back unparsed.
    #[allow(clippy::type_complexity)]
    pub(super) fn op_node<'a>(
        &mut self,
        m: &'a Map<String, Value>,
        op: &str,
        path: &str,
        scope: usize,
    ) -> Result<(Node, Vec<(&'a Value, String, usize)>)> {
        let transform = transform(m, path)?;
        if op == "extrude" {
            return Ok((self.extrude(m, path, scope, transform)?, vec![]));
        }
        if op == "revolve" {
            return Ok((self.revolve(m, path, scope, transform)?, vec![]));
        }
        let (base, smooth) = op_kind(op, path)?;
        if smooth {
            only(
                m,
                path,
                &[
                    "op", "children", "smooth_k", "smooth", "pos", "rot", "scale", "name",
                ],
                "a smooth operation",
            )?;
        } else {
            only(
                m,
                path,
                &["op", "children", "pos", "rot", "scale", "name"],
                "an operation (smooth_k and smooth belong to smooth_* ops)",
            )?;
        }
        let smooth = if smooth {
            Some(smoothing(m, path)?)
        } else {
            None
        };
        let cp = key_path(path, "children");
        let children = array(required(m, path, "children", "the operands")?, &cp, None)?;
        if children.is_empty() {
            return Err(fault(&cp, "an operation needs at least one child"));
        }
        let kids = children
            .iter()
            .enumerate()
            .map(|(i, c)| (c, format!("{cp}[{i}]"), scope))
            .collect();
        Ok((
            Node {
                transform,
                kind: NodeKind::Op {
                    op: base,
                    smooth,
                    children: Vec::with_capacity(children.len()),
                },
            },
            kids,
        ))
    }

    /// An extrusion of a declared or inline 2D shape along z, optionally twisted and scaled
    /// towards the top: a leaf.
    fn extrude(
        &mut self,
        m: &Map<String, Value>,
        path: &str,
        scope: usize,
        transform: Transform,
    ) -> Result<Node> {
        only(
            m,
            path,
            &[
                "op",
                "source_2d_sdf",
                "extrude_depth",
                "twist",
                "scale_top",
                "material",
                "pos",
                "rot",
                "scale",
                "name",
            ],
            "an extrude node",
        )?;
        let shape = self.source_2d(m, path, scope)?;
        let depth = positive(
            required(m, path, "extrude_depth", "the extrusion's depth along z")?,
            &key_path(path, "extrude_depth"),
        )?;
        let twist = match m.get("twist") {
            Some(v) => number(v, &key_path(path, "twist"))?,
            None => 0.0,
        };
        let scale_top = match m.get("scale_top") {
            None => DVec2::ONE,
            Some(v @ Value::Array(_)) => {
                let sp = key_path(path, "scale_top");
                let a = array(v, &sp, Some(2))?;
                DVec2::new(
                    non_negative(&a[0], &format!("{sp}[0]"))?,
                    non_negative(&a[1], &format!("{sp}[1]"))?,
                )
            }
            Some(v) => DVec2::splat(non_negative(v, &key_path(path, "scale_top"))?),
        };
        if scale_top.min_element() == 0.0 && scale_top != DVec2::ZERO {
            return Err(fault(
                &key_path(path, "scale_top"),
                "may be 0 on both axes (a point) but not on one alone",
            ));
        }
        let material = self.optional_material(m, path)?;
        Ok(Node {
            transform,
            kind: NodeKind::Leaf {
                shape: Shape::Extrude(Extrusion::new(shape, 0.5 * depth, twist, scale_top)),
                material,
            },
        })
    }

    /// A revolution of a declared or inline 2D shape's half-plane x ≥ 0 about y: a leaf.
    fn revolve(
        &mut self,
        m: &Map<String, Value>,
        path: &str,
        scope: usize,
        transform: Transform,
    ) -> Result<Node> {
        only(
            m,
            path,
            &[
                "op",
                "source_2d_sdf",
                "angle",
                "material",
                "pos",
                "rot",
                "scale",
                "name",
            ],
            "a revolve node",
        )?;
        let shape = self.source_2d(m, path, scope)?;
        let angle = match m.get("angle") {
            Some(v) => {
                let ap = key_path(path, "angle");
                let a = positive(v, &ap)?;
                if a > 360.0 {
                    return Err(fault(&ap, format!("the angle {a} exceeds 360 degrees")));
                }
                a
            }
            None => 360.0,
        };
        let (lo, hi) = shape.bounds();
        if lo.cmpgt(hi).any() || hi.x <= 0.0 {
            return Err(fault(
                &key_path(path, "source_2d_sdf"),
                "the profile has nothing at x > 0 to revolve about the y axis",
            ));
        }
        let material = self.optional_material(m, path)?;
        Ok(Node {
            transform,
            kind: NodeKind::Leaf {
                shape: Shape::Revolve { shape, angle },
                material,
            },
        })
    }

    /// An extrusion's or revolution's `source_2d_sdf`: a declared shape's id or a 2D shape.
    fn source_2d(&self, m: &Map<String, Value>, path: &str, scope: usize) -> Result<Shape2> {
        let sp = key_path(path, "source_2d_sdf");
        let src = required(
            m,
            path,
            "source_2d_sdf",
            "the id of a declared 2D shape, or the shape itself",
        )?;
        match src {
            Value::String(id) => self.lookup_2d(scope, id).cloned().ok_or_else(|| {
                let known = self.known_2d(scope);
                fault(
                    &sp,
                    if known.is_empty() {
                        format!("unknown 2D shape id `{id}`: no shapes are declared in `sdf_2d`")
                    } else {
                        format!("unknown 2D shape id `{id}`; declared: {}", known.join(", "))
                    },
                )
            }),
            Value::Object(_) => shape_2d(src, &sp, &|id| self.lookup_2d(scope, id).cloned()),
            other => Err(fault(
                &sp,
                format!(
                    "expected a 2D shape id (a string) or a 2D shape (an object), found {}",
                    type_name(other)
                ),
            )),
        }
    }
}

/// The boolean of an op name, and whether it is smooth.
fn op_kind(op: &str, path: &str) -> Result<(BoolOp, bool)> {
    Ok(match op {
        "union" => (BoolOp::Union, false),
        "intersect" => (BoolOp::Intersection, false),
        "subtract" => (BoolOp::Difference, false),
        "smooth_union" => (BoolOp::Union, true),
        "smooth_intersect" => (BoolOp::Intersection, true),
        "smooth_subtract" => (BoolOp::Difference, true),
        other => {
            return Err(fault(
                &key_path(path, "op"),
                format!(
                    "unknown op `{other}`; expected union, intersect, subtract, smooth_union, \
                     smooth_intersect, smooth_subtract, extrude or revolve"
                ),
            ));
        }
    })
}

/// A smooth op's blend: `smooth` (the kind, exponential by default) and `smooth_k` (> 0).
fn smoothing(m: &Map<String, Value>, path: &str) -> Result<(SmoothKind, f64)> {
    let k = positive(
        required(
            m,
            path,
            "smooth_k",
            "a smooth op needs its blend constant k > 0",
        )?,
        &key_path(path, "smooth_k"),
    )?;
    let kind = match m.get("smooth") {
        None => SmoothKind::Exponential,
        Some(v) => match string(v, &key_path(path, "smooth"))? {
            "exponential" => SmoothKind::Exponential,
            "polynomial" => SmoothKind::Polynomial,
            other => {
                return Err(fault(
                    &key_path(path, "smooth"),
                    format!("unknown smoothing `{other}`; expected exponential or polynomial"),
                ));
            }
        },
    };
    Ok((kind, k))
}
