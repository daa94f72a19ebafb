//! The document walk: the envelope, the node tree (with an explicit work stack), nested trees,
//! 2D shape scopes and the material table.

use std::collections::HashMap;

use serde_json::{Map, Value};

use super::Scene;
use super::colour::colour;
use super::json::{array, count, fault, key_path, object, only, required, string};
use super::profile::{RenderProfile, render_profile};
use super::shapes2d::shapes_2d;
use super::transform::transform;
use super::view::{Light, SceneCamera, camera, lights};
use crate::error::Result;
use crate::mesh::Material;
use crate::sdf::eval::Program;
use crate::sdf::shapes2d::Shape2;
use crate::sdf::tree::{Frame, Node, NodeId, NodeKind, Transform, Tree};
use crate::solid::BoolOp;

#[derive(Default)]
pub(super) struct Scope {
    parent: Option<usize>,
    shapes: HashMap<String, Shape2>,
}

/// The envelope's settings for seeing the scene.
#[derive(Default)]
struct Header {
    profile: RenderProfile,
    camera: Option<SceneCamera>,
    lights: Option<Vec<Light>>,
}

#[derive(Default)]
pub(super) struct Parser {
    tree: Tree,
    scopes: Vec<Scope>,
    /// Material id → index, and whether a materials table was given.
    material_index: HashMap<String, u32>,
    materials: Vec<Material>,
    has_table: bool,
    /// The JSON path of every leaf node (primitives, extrusions, revolutions), by node id.
    leaf_paths: HashMap<NodeId, String>,
}

impl Parser {
    pub(super) fn document(mut self, v: &Value) -> Result<Scene> {
        let m = object(v, "$", "a scene node or a scene envelope")?;
        let is_node = m.contains_key("op")
            || m.contains_key("kind") && m.get("kind") != Some(&Value::String("sdf_scene".into()));
        if !is_node && !m.contains_key("tree") && !m.contains_key("nodes") {
            return Err(fault(
                "$",
                "expected a node (with `op` or `kind`) or a scene envelope (with `tree` or `nodes`)",
            ));
        }
        let (root, header) = if is_node {
            self.scopes.push(Scope::default());
            (self.node_tree(v, "$".into(), 0)?, Header::default())
        } else {
            self.envelope(m)?
        };
        let program = Program::compile(&self.tree, root, Frame::WORLD)?;
        let bound = program.bound();
        let primitive_paths = program
            .leaves
            .iter()
            .map(|l| self.leaf_paths.remove(&l.node).unwrap_or_default())
            .collect();
        Ok(Scene {
            primitive_paths,
            tree: self.tree,
            root,
            program,
            bound,
            materials: self.materials,
            profile: header.profile,
            camera: header.camera,
            lights: header.lights,
        })
    }

    /// The scene envelope: header fields, materials, 2D shapes, then `tree` and `nodes`, all
    /// united under one root.
    fn envelope(&mut self, m: &Map<String, Value>) -> Result<(NodeId, Header)> {
        only(
            m,
            "$",
            &[
                "kind",
                "version",
                "name",
                "render_profile",
                "camera",
                "lights",
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
        let header = Header {
            profile: match m.get("render_profile") {
                Some(v) => render_profile(v, "$.render_profile")?,
                None => RenderProfile::default(),
            },
            camera: m.get("camera").map(|v| camera(v, "$.camera")).transpose()?,
            lights: m.get("lights").map(|v| lights(v, "$.lights")).transpose()?,
        };
        if let Some(v) = m.get("materials") {
            self.material_table(v, "$.materials")?;
        }
        let mut scope = Scope::default();
        if let Some(v) = m.get("sdf_2d") {
            scope.shapes = shapes_2d(v, "$.sdf_2d", &|_| None)?;
        }
        self.scopes.push(scope);
        let mut roots = Vec::new();
        if let Some(t) = m.get("tree") {
            roots.push(self.node_tree(t, "$.tree".into(), 0)?);
        }
        if let Some(ns) = m.get("nodes") {
            self.placed_trees(ns, &mut roots)?;
        }
        let root = match roots.len() {
            0 => return Err(fault("$", "the envelope needs `tree` or `nodes`")),
            1 => roots[0],
            _ => self.tree.push(union_of(Transform::default(), roots)),
        };
        Ok((root, header))
    }

    /// The envelope's `nodes`: trees placed by a transform each, appended to `roots`.
    fn placed_trees(&mut self, ns: &Value, roots: &mut Vec<NodeId>) -> Result<()> {
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
            roots.push(self.tree.push(union_of(t, vec![child])));
        }
        Ok(())
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
        let name = id.unwrap_or(Material::DEFAULT_NAME);
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
            base_color: Material::DEFAULT_COLOR,
        });
        Ok(i)
    }

    pub(super) fn lookup_2d(&self, scope: usize, id: &str) -> Option<&Shape2> {
        let mut s = Some(scope);
        while let Some(i) = s {
            if let Some(shape) = self.scopes[i].shapes.get(id) {
                return Some(shape);
            }
            s = self.scopes[i].parent;
        }
        None
    }

    pub(super) fn known_2d(&self, scope: usize) -> Vec<String> {
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
            let is_leaf = matches!(node.kind, NodeKind::Leaf { .. });
            let id = self.tree.push(node);
            if is_leaf {
                self.leaf_paths.insert(id, w.path.clone());
            }
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
            "sdf_primitive" => Ok((self.primitive_node(m, path, transform)?, vec![])),
            "sdf_csg_tree" => self.nested_tree(m, path, scope, transform),
            other => Err(fault(
                &key_path(path, "kind"),
                format!(
                    "unknown node kind `{other}`; expected sdf_primitive or sdf_csg_tree (or an `op` node)"
                ),
            )),
        }
    }

    /// A primitive node: its `data` read into a leaf.
    fn primitive_node(
        &mut self,
        m: &Map<String, Value>,
        path: &str,
        transform: Transform,
    ) -> Result<Node> {
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
        Ok(Node {
            transform,
            kind: NodeKind::Leaf { shape, material },
        })
    }

    /// A nested tree: a union node over its root, in a new scope when it declares 2D shapes.
    #[allow(clippy::type_complexity)]
    fn nested_tree<'a>(
        &mut self,
        m: &'a Map<String, Value>,
        path: &str,
        scope: usize,
        transform: Transform,
    ) -> Result<(Node, Vec<(&'a Value, String, usize)>)> {
        only(
            m,
            path,
            &["kind", "root", "sdf_2d", "pos", "rot", "scale", "name"],
            "a nested tree",
        )?;
        let mut inner = scope;
        if let Some(v) = m.get("sdf_2d") {
            let shapes = shapes_2d(v, &key_path(path, "sdf_2d"), &|id| {
                self.lookup_2d(scope, id).cloned()
            })?;
            self.scopes.push(Scope {
                parent: Some(scope),
                shapes,
            });
            inner = self.scopes.len() - 1;
        }
        let child = required(m, path, "root", "the nested tree's root node")?;
        Ok((
            union_of(transform, vec![]),
            vec![(child, key_path(path, "root"), inner)],
        ))
    }

    pub(super) fn optional_material(&mut self, m: &Map<String, Value>, path: &str) -> Result<u32> {
        let mp = key_path(path, "material");
        let id = match m.get("material") {
            Some(v) => Some(string(v, &mp)?),
            None => None,
        };
        self.material(id, &mp)
    }
}

/// A plain union node: how placed trees, nested trees and several roots join the tree.
pub(super) fn union_of(transform: Transform, children: Vec<NodeId>) -> Node {
    Node {
        transform,
        kind: NodeKind::Op {
            op: BoolOp::Union,
            smooth: None,
            children,
        },
    }
}
