//! Scene documents: the seed spec's `sdf_csg_tree` in JSON, checked field by field so that
//! every fault is reported with its JSON path. The format is written down in
//! `docs/scene-format.md`.
//!
//! The document is parsed by `serde_json` into a `Value` (whose nesting limit of 128 keeps its
//! own recursion bounded) and then walked here with an explicit work stack.

mod colour;
mod duplicates;
mod json;
mod ops;
mod parser;
mod primitive;
mod profile;
mod shapes2d;
mod transform;
mod view;

use std::path::Path;

use glam::DVec3;
use serde_json::Value;

pub use profile::RenderProfile;
pub use shapes2d::MAX_POLYGON_POINTS;
pub use view::{DEFAULT_FOV_DEG, Light, LightKind, Projection, SceneCamera};

use super::eval::{Bound, Instr, Program};
use super::tree::{NodeId, Tree};
use crate::error::{Error, Result};
use crate::geom::Aabb;
use crate::mesh::Material;
use parser::Parser;

/// The largest magnitude any length, position or scale in a document may have. Beyond it the
/// distance arithmetic (squares of lengths) would lose all precision or overflow.
pub const MAX_SCENE_MAGNITUDE: f64 = 1e12;

/// A scene: a tree of signed distance functions with its materials and render profile.
///
/// Distances are negative inside. Evaluation runs a flattened program (no recursion), so
/// scenes of any depth are safe.
///
/// ```
/// use bspcsg::Scene;
/// use bspcsg::glam::DVec3;
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
    camera: Option<SceneCamera>,
    lights: Option<Vec<Light>>,
    /// The JSON path of each primitive's node, in evaluation order.
    primitive_paths: Vec<String>,
}

impl Scene {
    /// Parses and checks a scene document (a bare node or the envelope; see
    /// `docs/scene-format.md`). Every fault is an [`Error::Scene`] naming its JSON path.
    ///
    /// # Errors
    ///
    /// [`Error::Scene`] naming the JSON path of the first fault: invalid JSON, a key repeated
    /// in one object, an unknown or missing field, a value out of range, an unknown material or 2D shape.
    pub fn from_json_str(json: &str) -> Result<Scene> {
        // A byte-order mark (some Windows editors write one) is no part of the document.
        let json = json.strip_prefix('\u{feff}').unwrap_or(json);
        let value: Value =
            duplicates::parse(json).map_err(|(json_path, message)| Error::Scene {
                file: None,
                json_path,
                message,
            })?;
        Scene::from_json_value(&value)
    }

    /// Reads and parses a scene file.
    ///
    /// # Errors
    ///
    /// [`Error::Io`] when the file cannot be read, and [`Error::Scene`] naming the file and the
    /// JSON path as [`Scene::from_json_str`].
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
    pub(crate) fn from_json_value(value: &Value) -> Result<Scene> {
        Parser::default().document(value)
    }

    /// The signed distance at `p`: negative inside, exact for single primitives under rigid
    /// motion and uniform scale, otherwise a bound that never overestimates.
    #[must_use]
    pub fn distance(&self, p: DVec3) -> f64 {
        self.program.eval(p)
    }

    /// The material (index into [`Scene::materials`], the same as a mesh source id) of the
    /// primitive that decides the distance at `p`.
    #[must_use]
    pub fn material_at(&self, p: DVec3) -> u32 {
        self.program.eval_material(p).1
    }

    /// The materials; a material's index is the source id its triangles carry.
    #[must_use]
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// The render profile (defaults where the document gives none).
    #[must_use]
    pub fn render_profile(&self) -> &RenderProfile {
        &self.profile
    }

    /// The document's camera, if it gives one.
    #[must_use]
    pub fn camera(&self) -> Option<&SceneCamera> {
        self.camera.as_ref()
    }

    /// The document's lights, if it gives a `lights` list (possibly empty: ambient only).
    #[must_use]
    pub fn lights(&self) -> Option<&[Light]> {
        self.lights.as_deref()
    }

    /// A box holding the solid, from conservative per-node boxes; infinite on the sides where
    /// the scene is unbounded (a half-space not intersected away).
    #[must_use]
    pub fn bbox(&self) -> Aabb {
        self.bound.bbox
    }

    /// The JSON path of each primitive's node (`$.tree.children[1]`), extrusions and
    /// revolutions included, in evaluation order: the primitives of any subtree are a
    /// contiguous run of this list, in document order.
    #[must_use]
    pub fn primitive_paths(&self) -> &[String] {
        &self.primitive_paths
    }

    /// A conservative world box of each primitive on its own (before any combination), in the
    /// order of [`Scene::primitive_paths`]; infinite on the sides where the primitive is
    /// unbounded (a half-space). What a marching-cubes cell must resolve to keep each part.
    #[must_use]
    pub fn primitive_bboxes(&self) -> Vec<Aabb> {
        let mut boxes = vec![Aabb::EMPTY; self.program.leaves.len()];
        self.program.walk_bounds(|i, bound, _| {
            if let Instr::Leaf(l) = self.program.instrs[i] {
                boxes[l as usize] = bound.bbox;
            }
        });
        boxes
    }

    /// Number of primitives (leaves) in the scene.
    #[must_use]
    pub fn primitive_count(&self) -> usize {
        self.program.leaves.len()
    }
}
