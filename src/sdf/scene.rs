//! Scene documents: the seed spec's `sdf_csg_tree` in JSON, checked field by field so that
//! every fault is reported with its JSON path. The format is written down in
//! `docs/scene-format.md`.
//!
//! The document is parsed by `serde_json` into a `Value` (whose nesting limit of 128 keeps its
//! own recursion bounded) and then walked here with an explicit work stack.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use glam::{DVec2, DVec3};
use serde_json::{Map, Value};

use super::eval::{Bound, Program};
use super::shapes::{Shape, Shape2};
use super::tree::{BoolKind, Frame, Node, NodeId, NodeKind, SmoothKind, Transform, Tree};
use crate::error::{Error, Result};
use crate::geom::Aabb;
use crate::mesh::Material;

/// The largest magnitude any length, position or scale in a document may have. Beyond it the
/// distance arithmetic (squares of lengths) would lose all precision or overflow.
pub const MAX_SCENE_MAGNITUDE: f64 = 1e12;

/// The most points a 2D polygon may have (its simplicity check is quadratic).
pub const MAX_POLYGON_POINTS: usize = 10_000;

/// The colour of primitives without a material, and of material ids the document uses without
/// a materials table: linear RGBA.
pub const FALLBACK_COLOR: [f64; 4] = [0.8, 0.8, 0.8, 1.0];

/// The raymarching settings that travel with a scene (the spec's render profile).
#[derive(Clone, Debug, PartialEq)]
pub struct RenderProfile {
    /// Most sphere-tracing steps per ray.
    pub max_steps: u32,
    /// A ray hits where the distance falls below this.
    pub hit_epsilon: f64,
    /// A ray misses beyond this distance.
    pub max_distance: f64,
    /// Steps of the soft-shadow march (0: no shadows).
    pub shadow_steps: u32,
    /// Samples of ambient occlusion (0: none).
    pub ao_steps: u32,
    /// The colour of a miss, linear RGBA.
    pub background: [f64; 4],
}

impl Default for RenderProfile {
    fn default() -> Self {
        RenderProfile {
            max_steps: 128,
            hit_epsilon: 1e-3,
            max_distance: 100.0,
            shadow_steps: 32,
            ao_steps: 5,
            background: [0.0, 0.0, 0.0, 1.0],
        }
    }
}

/// A scene: a tree of signed distance functions with its materials and render profile.
///
/// Distances are negative inside. Evaluation runs a flattened program (no recursion), so
/// scenes of any depth are safe.
///
/// ```
/// use bspcsg::Scene;
/// use glam::DVec3;
///
/// let scene = Scene::from_json_str(r#"{
///     "op": "subtract",
///     "children": [
///         {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [2, 2, 2]}},
///         {"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1.2}}
///     ]
/// }"#)?;
/// assert!(scene.distance(DVec3::new(0.95, 0.95, 0.95)) < 0.0); // a corner survives
/// assert!(scene.distance(DVec3::ZERO) > 0.0); // the centre is cut away
/// # Ok::<(), bspcsg::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Scene {
    pub(crate) tree: Tree,
    pub(crate) root: NodeId,
    pub(crate) program: Program,
    pub(crate) bound: Bound,
    materials: Vec<Material>,
    profile: RenderProfile,
}

impl Scene {
    /// Parses and checks a scene document (a bare node or the envelope; see
    /// `docs/scene-format.md`). Every fault is an [`Error::Scene`] naming its JSON path.
    pub fn from_json_str(json: &str) -> Result<Scene> {
        let value: Value = serde_json::from_str(json).map_err(|e| Error::Scene {
            file: None,
            json_path: "$".into(),
            message: format!("not valid JSON: {e}"),
        })?;
        Scene::from_json_value(&value)
    }

    /// Reads and parses a scene file.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Scene> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Scene::from_json_str(&text).map_err(|e| match e {
            Error::Scene {
                json_path, message, ..
            } => Error::Scene {
                file: Some(path.to_path_buf()),
                json_path,
                message,
            },
            other => other,
        })
    }

    /// Builds a scene from an already parsed JSON value.
    pub fn from_json_value(value: &Value) -> Result<Scene> {
        Parser::default().document(value)
    }

    /// The signed distance at `p`: negative inside, exact for single primitives under rigid
    /// motion and uniform scale, otherwise a bound that never overestimates.
    pub fn distance(&self, p: DVec3) -> f64 {
        self.program.eval(p)
    }

    /// The material (index into [`Scene::materials`], the same as a mesh source id) of the
    /// primitive that decides the distance at `p`.
    pub fn material_at(&self, p: DVec3) -> u32 {
        self.program.eval_material(p).1
    }

    /// The materials; a material's index is the source id its triangles carry.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// The render profile (defaults where the document gives none).
    pub fn render_profile(&self) -> &RenderProfile {
        &self.profile
    }

    /// A box holding the solid, from conservative per-node boxes; infinite on the sides where
    /// the scene is unbounded (a half-space not intersected away).
    pub fn bounds(&self) -> Aabb {
        self.bound.bbox
    }

    /// Number of primitives (leaves) in the scene.
    pub fn primitive_count(&self) -> usize {
        self.program.leaves.len()
    }
}

fn fault(path: &str, message: impl Into<String>) -> Error {
    Error::Scene {
        file: None,
        json_path: path.to_string(),
        message: message.into(),
    }
}

fn key_path(path: &str, key: &str) -> String {
    if !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        format!("{path}.{key}")
    } else {
        format!("{path}[{}]", Value::String(key.to_string()))
    }
}

fn type_name(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

fn object<'a>(v: &'a Value, path: &str, what: &str) -> Result<&'a Map<String, Value>> {
    v.as_object().ok_or_else(|| {
        fault(
            path,
            format!("expected {what} (an object), found {}", type_name(v)),
        )
    })
}

/// Refuses fields outside `allowed`, naming the first stray one and the expected set.
fn only(map: &Map<String, Value>, path: &str, allowed: &[&str], context: &str) -> Result<()> {
    for k in map.keys() {
        if !allowed.contains(&k.as_str()) {
            let hint = match k.as_str() {
                "pos" | "rot" | "scale" => {
                    " (transforms belong on the node, beside `kind`/`op`, not inside `data`)"
                }
                _ => "",
            };
            return Err(fault(
                &key_path(path, k),
                format!(
                    "unknown field `{k}` in {context}{hint}; expected one of: {}",
                    allowed.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

fn number(v: &Value, path: &str) -> Result<f64> {
    let x = v
        .as_f64()
        .ok_or_else(|| fault(path, format!("expected a number, found {}", type_name(v))))?;
    if !x.is_finite() || x.abs() > MAX_SCENE_MAGNITUDE {
        return Err(fault(
            path,
            format!("{x} is outside the supported range ±{MAX_SCENE_MAGNITUDE:e}"),
        ));
    }
    Ok(x)
}

fn positive(v: &Value, path: &str) -> Result<f64> {
    let x = number(v, path)?;
    if x <= 0.0 {
        return Err(fault(path, format!("must be > 0, found {x}")));
    }
    Ok(x)
}

fn non_negative(v: &Value, path: &str) -> Result<f64> {
    let x = number(v, path)?;
    if x < 0.0 {
        return Err(fault(path, format!("must be ≥ 0, found {x}")));
    }
    Ok(x)
}

fn count(v: &Value, path: &str, min: u64) -> Result<u32> {
    match v.as_u64() {
        Some(n) if n >= min && n <= u32::MAX as u64 => Ok(n as u32),
        _ => Err(fault(
            path,
            format!("expected a whole number ≥ {min}, found {v}"),
        )),
    }
}

fn string<'a>(v: &'a Value, path: &str) -> Result<&'a str> {
    v.as_str()
        .ok_or_else(|| fault(path, format!("expected a string, found {}", type_name(v))))
}

fn array<'a>(v: &'a Value, path: &str, len: Option<usize>) -> Result<&'a [Value]> {
    let a = v
        .as_array()
        .ok_or_else(|| fault(path, format!("expected an array, found {}", type_name(v))))?;
    if let Some(n) = len
        && a.len() != n
    {
        return Err(fault(
            path,
            format!("expected {n} numbers, found {}", a.len()),
        ));
    }
    Ok(a)
}

fn vec3(v: &Value, path: &str) -> Result<DVec3> {
    let a = array(v, path, Some(3))?;
    Ok(DVec3::new(
        number(&a[0], &format!("{path}[0]"))?,
        number(&a[1], &format!("{path}[1]"))?,
        number(&a[2], &format!("{path}[2]"))?,
    ))
}

fn positive_vec3(v: &Value, path: &str) -> Result<DVec3> {
    let a = array(v, path, Some(3))?;
    Ok(DVec3::new(
        positive(&a[0], &format!("{path}[0]"))?,
        positive(&a[1], &format!("{path}[1]"))?,
        positive(&a[2], &format!("{path}[2]"))?,
    ))
}

fn vec2(v: &Value, path: &str) -> Result<DVec2> {
    let a = array(v, path, Some(2))?;
    Ok(DVec2::new(
        number(&a[0], &format!("{path}[0]"))?,
        number(&a[1], &format!("{path}[1]"))?,
    ))
}

fn required<'a>(
    map: &'a Map<String, Value>,
    path: &str,
    key: &str,
    why: &str,
) -> Result<&'a Value> {
    map.get(key)
        .ok_or_else(|| fault(&key_path(path, key), format!("missing `{key}` ({why})")))
}

/// A colour: `[r, g, b]` or `[r, g, b, a]` in linear 0..1, `"#rrggbb"` / `"#rrggbbaa"` in sRGB,
/// or `{"base_color": …}`.
fn colour(v: &Value, path: &str) -> Result<[f64; 4]> {
    match v {
        // A material object holds a plain colour, not another material.
        Value::Object(m) => {
            only(m, path, &["base_color", "name"], "a material")?;
            plain_colour(
                required(m, path, "base_color", "the material's colour")?,
                &key_path(path, "base_color"),
            )
        }
        _ => plain_colour(v, path),
    }
}

/// A colour as `[r, g, b(, a)]` or `"#rrggbb(aa)"`.
fn plain_colour(v: &Value, path: &str) -> Result<[f64; 4]> {
    match v {
        Value::Array(a) => {
            if !(a.len() == 3 || a.len() == 4) {
                return Err(fault(
                    path,
                    format!("a colour has 3 or 4 components, found {}", a.len()),
                ));
            }
            let mut c = [1.0; 4];
            for (i, x) in a.iter().enumerate() {
                let p = format!("{path}[{i}]");
                let x = number(x, &p)?;
                if !(0.0..=1.0).contains(&x) {
                    return Err(fault(
                        &p,
                        format!("colour components lie in 0..1, found {x}"),
                    ));
                }
                c[i] = x;
            }
            Ok(c)
        }
        Value::String(s) => {
            let hex = s.strip_prefix('#').unwrap_or(s);
            if !(hex.len() == 6 || hex.len() == 8) || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
                return Err(fault(
                    path,
                    format!("expected \"#rrggbb\" or \"#rrggbbaa\", found {s:?}"),
                ));
            }
            let mut c = [1.0; 4];
            for (i, slot) in c.iter_mut().enumerate().take(hex.len() / 2) {
                let byte = u8::from_str_radix(&hex[2 * i..2 * i + 2], 16)
                    .map_err(|_| fault(path, "bad hex digit"))?;
                let x = byte as f64 / 255.0;
                // sRGB → linear for the colour channels; alpha is linear already.
                *slot = if i == 3 {
                    x
                } else if x <= 0.04045 {
                    x / 12.92
                } else {
                    ((x + 0.055) / 1.055).powf(2.4)
                };
            }
            Ok(c)
        }
        _ => Err(fault(
            path,
            format!(
                "expected a colour ([r, g, b(, a)], \"#rrggbb\" or {{\"base_color\": …}}), found {}",
                type_name(v)
            ),
        )),
    }
}

/// A 2D shape declaration: `{"type": "rectangle"|"circle"|"polygon", …}`.
fn shape_2d(v: &Value, path: &str) -> Result<Shape2> {
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
fn check_simple(pts: &[DVec2], path: &str) -> Result<()> {
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

fn on_segment(a: DVec2, b: DVec2, p: DVec2) -> bool {
    (b - a).perp_dot(p - a) == 0.0
        && p.x >= a.x.min(b.x)
        && p.x <= a.x.max(b.x)
        && p.y >= a.y.min(b.y)
        && p.y <= a.y.max(b.y)
}

/// Reads `pos`, `rot`, `scale` of a node.
fn transform(m: &Map<String, Value>, path: &str) -> Result<Transform> {
    let mut t = Transform::default();
    if let Some(v) = m.get("pos") {
        t.pos = vec3(v, &key_path(path, "pos"))?;
    }
    if let Some(v) = m.get("rot") {
        t.rot = vec3(v, &key_path(path, "rot"))?;
    }
    if let Some(v) = m.get("scale") {
        let sp = key_path(path, "scale");
        t.scale = match v {
            Value::Number(_) => DVec3::splat(number(v, &sp)?),
            _ => vec3(v, &sp)?,
        };
        for (i, s) in t.scale.to_array().into_iter().enumerate() {
            if s.abs() < 1.0 / MAX_SCENE_MAGNITUDE {
                let p = if v.is_number() {
                    sp.clone()
                } else {
                    format!("{sp}[{i}]")
                };
                return Err(fault(
                    &p,
                    format!("a scale must be non-zero (|s| ≥ 1e-12), found {s}"),
                ));
            }
        }
    }
    Ok(t)
}

#[derive(Default)]
struct Scope {
    parent: Option<usize>,
    shapes: HashMap<String, Shape2>,
}

#[derive(Default)]
struct Parser {
    tree: Tree,
    scopes: Vec<Scope>,
    /// Material id → index, and whether a materials table was given.
    material_index: HashMap<String, u32>,
    materials: Vec<Material>,
    has_table: bool,
}

impl Parser {
    fn document(mut self, v: &Value) -> Result<Scene> {
        let m = object(v, "$", "a scene node or a scene envelope")?;
        let is_node = m.contains_key("op")
            || m.contains_key("kind") && m.get("kind") != Some(&Value::String("sdf_scene".into()));
        if !is_node && !m.contains_key("tree") && !m.contains_key("nodes") {
            return Err(fault(
                "$",
                "expected a node (with `op` or `kind`) or a scene envelope (with `tree` or `nodes`)",
            ));
        }
        let mut profile = RenderProfile::default();
        let root = if is_node {
            self.scopes.push(Scope::default());
            self.node_tree(v, "$".into(), 0)?
        } else {
            only(
                m,
                "$",
                &[
                    "kind",
                    "version",
                    "name",
                    "render_profile",
                    "materials",
                    "sdf_2d",
                    "tree",
                    "nodes",
                ],
                "the scene envelope",
            )?;
            if let Some(k) = m.get("kind") {
                let k = string(k, "$.kind")?;
                if k != "sdf_scene" {
                    return Err(fault(
                        "$.kind",
                        format!("expected \"sdf_scene\", found {k:?}"),
                    ));
                }
            }
            if let Some(v) = m.get("version") {
                count(v, "$.version", 1)?;
            }
            if let Some(v) = m.get("render_profile") {
                profile = render_profile(v, "$.render_profile")?;
            }
            if let Some(v) = m.get("materials") {
                self.material_table(v, "$.materials")?;
            }
            let mut scope = Scope::default();
            if let Some(v) = m.get("sdf_2d") {
                scope.shapes = shapes_2d(v, "$.sdf_2d")?;
            }
            self.scopes.push(scope);
            let mut roots = Vec::new();
            if let Some(t) = m.get("tree") {
                roots.push(self.node_tree(t, "$.tree".into(), 0)?);
            }
            if let Some(ns) = m.get("nodes") {
                let a = array(ns, "$.nodes", None)?;
                for (i, n) in a.iter().enumerate() {
                    let p = format!("$.nodes[{i}]");
                    let nm = object(n, &p, "a placed tree ({\"tree\": …, \"pos\": …})")?;
                    only(
                        nm,
                        &p,
                        &["tree", "pos", "rot", "scale", "name"],
                        "a placed tree",
                    )?;
                    let t = transform(nm, &p)?;
                    let child = self.node_tree(
                        required(nm, &p, "tree", "the tree to place")?,
                        key_path(&p, "tree"),
                        0,
                    )?;
                    roots.push(self.tree.push(Node {
                        transform: t,
                        kind: NodeKind::Op {
                            op: BoolKind::Union,
                            smooth: None,
                            children: vec![child],
                        },
                    }));
                }
            }
            match roots.len() {
                0 => return Err(fault("$", "the envelope needs `tree` or `nodes`")),
                1 => roots[0],
                _ => self.tree.push(Node {
                    transform: Transform::default(),
                    kind: NodeKind::Op {
                        op: BoolKind::Union,
                        smooth: None,
                        children: roots,
                    },
                }),
            }
        };
        let program = Program::compile(&self.tree, root, Frame::WORLD)?;
        let bound = program.bound();
        Ok(Scene {
            tree: self.tree,
            root,
            program,
            bound,
            materials: self.materials,
            profile,
        })
    }

    fn material_table(&mut self, v: &Value, path: &str) -> Result<()> {
        let m = object(v, path, "a materials table (id → colour)")?;
        self.has_table = true;
        for (id, c) in m {
            let base_color = colour(c, &key_path(path, id))?;
            self.material_index
                .insert(id.clone(), self.materials.len() as u32);
            self.materials.push(Material {
                name: id.clone(),
                base_color,
            });
        }
        Ok(())
    }

    fn material(&mut self, id: Option<&str>, path: &str) -> Result<u32> {
        let name = id.unwrap_or("default");
        if let Some(&i) = self.material_index.get(name) {
            return Ok(i);
        }
        if self.has_table && id.is_some() {
            let known: Vec<&str> = self.materials.iter().map(|m| m.name.as_str()).collect();
            return Err(fault(
                path,
                format!(
                    "unknown material `{name}`; the materials table has: {}",
                    known.join(", ")
                ),
            ));
        }
        let i = self.materials.len() as u32;
        self.material_index.insert(name.to_string(), i);
        self.materials.push(Material {
            name: name.to_string(),
            base_color: FALLBACK_COLOR,
        });
        Ok(i)
    }

    fn lookup_2d(&self, scope: usize, id: &str) -> Option<&Shape2> {
        let mut s = Some(scope);
        while let Some(i) = s {
            if let Some(shape) = self.scopes[i].shapes.get(id) {
                return Some(shape);
            }
            s = self.scopes[i].parent;
        }
        None
    }

    fn known_2d(&self, scope: usize) -> Vec<String> {
        let mut out = Vec::new();
        let mut s = Some(scope);
        while let Some(i) = s {
            out.extend(self.scopes[i].shapes.keys().cloned());
            s = self.scopes[i].parent;
        }
        out.sort();
        out
    }

    /// Parses the node at `v` and everything below it with an explicit work stack, returning
    /// the id of its root in the arena.
    fn node_tree(&mut self, v: &Value, path: String, scope: usize) -> Result<NodeId> {
        struct Work<'a> {
            value: &'a Value,
            path: String,
            scope: usize,
            parent: Option<NodeId>,
        }
        let mut work = vec![Work {
            value: v,
            path,
            scope,
            parent: None,
        }];
        let mut root = None;
        while let Some(w) = work.pop() {
            let (node, children) = self.node(w.value, &w.path, w.scope)?;
            let id = self.tree.push(node);
            match w.parent {
                Some(p) => {
                    if let NodeKind::Op { children, .. } = &mut self.tree.nodes[p as usize].kind {
                        children.push(id);
                    }
                }
                None => root = Some(id),
            }
            // Reversed, so that children pop (and are appended) in document order.
            for (value, path, scope) in children.into_iter().rev() {
                work.push(Work {
                    value,
                    path,
                    scope,
                    parent: Some(id),
                });
            }
        }
        root.ok_or_else(|| fault("$", "empty tree"))
    }

    /// One node; its children come back unparsed, with their paths and scopes.
    #[allow(clippy::type_complexity)]
    fn node<'a>(
        &mut self,
        v: &'a Value,
        path: &str,
        scope: usize,
    ) -> Result<(Node, Vec<(&'a Value, String, usize)>)> {
        let m = object(
            v,
            path,
            "a node (a primitive, an operation or a nested tree)",
        )?;
        if let Some(op) = m.get("op") {
            if m.contains_key("kind") {
                return Err(fault(
                    &key_path(path, "kind"),
                    "a node has either `op` (an operation) or `kind` (a primitive or nested tree), not both",
                ));
            }
            let op = string(op, &key_path(path, "op"))?;
            return self.op_node(m, op, path, scope);
        }
        let kind = string(
            required(
                m,
                path,
                "kind",
                "or `op`: every node is a primitive, a nested tree or an operation",
            )?,
            &key_path(path, "kind"),
        )?;
        let transform = transform(m, path)?;
        match kind {
            "sdf_primitive" => {
                only(
                    m,
                    path,
                    &["kind", "data", "pos", "rot", "scale", "name"],
                    "a primitive node",
                )?;
                let dp = key_path(path, "data");
                let data = object(
                    required(m, path, "data", "the primitive's parameters")?,
                    &dp,
                    "the primitive's data",
                )?;
                let (shape, material) = self.primitive(data, &dp)?;
                Ok((
                    Node {
                        transform,
                        kind: NodeKind::Leaf { shape, material },
                    },
                    vec![],
                ))
            }
            "sdf_csg_tree" => {
                only(
                    m,
                    path,
                    &["kind", "root", "sdf_2d", "pos", "rot", "scale", "name"],
                    "a nested tree",
                )?;
                let mut inner = scope;
                if let Some(v) = m.get("sdf_2d") {
                    let shapes = shapes_2d(v, &key_path(path, "sdf_2d"))?;
                    self.scopes.push(Scope {
                        parent: Some(scope),
                        shapes,
                    });
                    inner = self.scopes.len() - 1;
                }
                let child = required(m, path, "root", "the nested tree's root node")?;
                Ok((
                    Node {
                        transform,
                        kind: NodeKind::Op {
                            op: BoolKind::Union,
                            smooth: None,
                            children: vec![],
                        },
                    },
                    vec![(child, key_path(path, "root"), inner)],
                ))
            }
            other => Err(fault(
                &key_path(path, "kind"),
                format!(
                    "unknown node kind `{other}`; expected sdf_primitive or sdf_csg_tree (or an `op` node)"
                ),
            )),
        }
    }

    #[allow(clippy::type_complexity)]
    fn op_node<'a>(
        &mut self,
        m: &'a Map<String, Value>,
        op: &str,
        path: &str,
        scope: usize,
    ) -> Result<(Node, Vec<(&'a Value, String, usize)>)> {
        let transform = transform(m, path)?;
        if op == "extrude" {
            only(
                m,
                path,
                &[
                    "op",
                    "source_2d_sdf",
                    "extrude_depth",
                    "material",
                    "pos",
                    "rot",
                    "scale",
                    "name",
                ],
                "an extrude node",
            )?;
            let sp = key_path(path, "source_2d_sdf");
            let src = required(
                m,
                path,
                "source_2d_sdf",
                "the id of a declared 2D shape, or the shape itself",
            )?;
            let shape = match src {
                Value::String(id) => self.lookup_2d(scope, id).cloned().ok_or_else(|| {
                    let known = self.known_2d(scope);
                    fault(
                        &sp,
                        if known.is_empty() {
                            format!(
                                "unknown 2D shape id `{id}`: no shapes are declared in `sdf_2d`"
                            )
                        } else {
                            format!("unknown 2D shape id `{id}`; declared: {}", known.join(", "))
                        },
                    )
                })?,
                Value::Object(_) => shape_2d(src, &sp)?,
                other => {
                    return Err(fault(
                        &sp,
                        format!(
                            "expected a 2D shape id (a string) or a 2D shape (an object), found {}",
                            type_name(other)
                        ),
                    ));
                }
            };
            let depth = positive(
                required(m, path, "extrude_depth", "the extrusion's depth along z")?,
                &key_path(path, "extrude_depth"),
            )?;
            let material = self.optional_material(m, path)?;
            return Ok((
                Node {
                    transform,
                    kind: NodeKind::Leaf {
                        shape: Shape::Extrude {
                            shape,
                            half_depth: 0.5 * depth,
                        },
                        material,
                    },
                },
                vec![],
            ));
        }
        let (base, smooth) = match op {
            "union" => (BoolKind::Union, false),
            "intersect" => (BoolKind::Intersect, false),
            "subtract" => (BoolKind::Subtract, false),
            "smooth_union" => (BoolKind::Union, true),
            "smooth_intersect" => (BoolKind::Intersect, true),
            "smooth_subtract" => (BoolKind::Subtract, true),
            other => {
                return Err(fault(
                    &key_path(path, "op"),
                    format!(
                        "unknown op `{other}`; expected union, intersect, subtract, smooth_union, \
                         smooth_intersect, smooth_subtract or extrude"
                    ),
                ));
            }
        };
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
                            format!(
                                "unknown smoothing `{other}`; expected exponential or polynomial"
                            ),
                        ));
                    }
                },
            };
            Some((kind, k))
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

    fn optional_material(&mut self, m: &Map<String, Value>, path: &str) -> Result<u32> {
        let mp = key_path(path, "material");
        let id = match m.get("material") {
            Some(v) => Some(string(v, &mp)?),
            None => None,
        };
        self.material(id, &mp)
    }

    fn primitive(&mut self, d: &Map<String, Value>, path: &str) -> Result<(Shape, u32)> {
        let tp = key_path(path, "primitive_type");
        let ty = string(
            required(
                d,
                path,
                "primitive_type",
                "box, sphere, cylinder, cone, pyramid, plane or torus",
            )?,
            &tp,
        )?;
        let fields: &[&str] = match ty {
            "box" => &["size"],
            "sphere" => &["radius"],
            "cylinder" => &["radius", "height"],
            "cone" => &["radius", "height", "radius_top"],
            "pyramid" => &["base", "height"],
            "plane" => &["normal", "offset"],
            "torus" => &["radius", "tube_radius"],
            other => {
                return Err(fault(
                    &tp,
                    format!(
                        "unknown primitive_type `{other}`; expected box, sphere, cylinder, cone, \
                         pyramid, plane or torus"
                    ),
                ));
            }
        };
        let mut allowed = vec!["primitive_type", "material", "name"];
        allowed.extend_from_slice(fields);
        only(d, path, &allowed, &format!("a {ty} primitive"))?;
        let get = |key: &str, why: &str| -> Result<f64> {
            positive(required(d, path, key, why)?, &key_path(path, key))
        };
        let shape = match ty {
            "box" => Shape::Box {
                half: positive_vec3(
                    required(d, path, "size", "[x, y, z] edge lengths")?,
                    &key_path(path, "size"),
                )? * 0.5,
            },
            "sphere" => Shape::Sphere {
                radius: get("radius", "the sphere's radius")?,
            },
            "cylinder" => Shape::Cylinder {
                radius: get("radius", "the cylinder's radius")?,
                half_height: 0.5 * get("height", "the cylinder's height along Y")?,
            },
            "cone" => Shape::Cone {
                r_bottom: get("radius", "the cone's base radius")?,
                r_top: match d.get("radius_top") {
                    Some(v) => non_negative(v, &key_path(path, "radius_top"))?,
                    None => 0.0,
                },
                half_height: 0.5 * get("height", "the cone's height along Y")?,
            },
            "pyramid" => Shape::Pyramid {
                base: get("base", "the side of the square base")?,
                height: get("height", "the pyramid's height along Y")?,
            },
            "plane" => {
                let np = key_path(path, "normal");
                let n = vec3(
                    required(d, path, "normal", "[x, y, z], pointing out of the solid")?,
                    &np,
                )?;
                let normal = n
                    .try_normalize()
                    .ok_or_else(|| fault(&np, "the normal must not be zero"))?;
                let offset = match d.get("offset") {
                    Some(v) => number(v, &key_path(path, "offset"))?,
                    None => 0.0,
                };
                Shape::Plane { normal, offset }
            }
            _ => {
                let major = get("radius", "the distance from the axis to the tube's centre")?;
                let minor = get("tube_radius", "the tube's radius")?;
                if minor >= major {
                    return Err(fault(
                        &key_path(path, "tube_radius"),
                        format!("must be smaller than radius ({major}), found {minor}"),
                    ));
                }
                Shape::Torus { major, minor }
            }
        };
        let material = self.optional_material(d, path)?;
        Ok((shape, material))
    }
}

fn shapes_2d(v: &Value, path: &str) -> Result<HashMap<String, Shape2>> {
    let m = object(v, path, "a table of 2D shapes (id → shape)")?;
    m.iter()
        .map(|(id, s)| Ok((id.clone(), shape_2d(s, &key_path(path, id))?)))
        .collect()
}

fn render_profile(v: &Value, path: &str) -> Result<RenderProfile> {
    let m = object(v, path, "a render profile")?;
    only(
        m,
        path,
        &[
            "max_steps",
            "hit_epsilon",
            "max_distance",
            "shadow_steps",
            "ao_steps",
            "background",
        ],
        "the render profile",
    )?;
    let mut p = RenderProfile::default();
    if let Some(v) = m.get("max_steps") {
        p.max_steps = count(v, &key_path(path, "max_steps"), 1)?;
    }
    if let Some(v) = m.get("hit_epsilon") {
        p.hit_epsilon = positive(v, &key_path(path, "hit_epsilon"))?;
    }
    if let Some(v) = m.get("max_distance") {
        p.max_distance = positive(v, &key_path(path, "max_distance"))?;
    }
    if let Some(v) = m.get("shadow_steps") {
        p.shadow_steps = count(v, &key_path(path, "shadow_steps"), 0)?;
    }
    if let Some(v) = m.get("ao_steps") {
        p.ao_steps = count(v, &key_path(path, "ao_steps"), 0)?;
    }
    if let Some(v) = m.get("background") {
        p.background = colour(v, &key_path(path, "background"))?;
    }
    Ok(p)
}
