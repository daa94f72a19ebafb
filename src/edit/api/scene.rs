//! The scene and its preview: `GET /api/scene` (the file's document), `POST /api/validate`
//! and `POST /api/shader` (the page's GLSL and camera).

use glam::DVec3;
use serde_json::{Value, json};

use super::Editor;
use super::transport::{Answer, Response, bad, from_error};
use crate::edit::glsl::fragment_shader_with;
use crate::raymarch::{Camera, View};
use crate::sdf::{Projection, Scene};

/// What a new scene starts as: an empty union with a few materials to pick from.
const STARTER: &str = r##"{
  "kind": "sdf_scene",
  "version": 1,
  "materials": {
    "grey": [0.7, 0.7, 0.72],
    "steel": [0.56, 0.57, 0.58],
    "brass": "#c9b27c",
    "red": [0.75, 0.12, 0.1]
  },
  "tree": { "op": "union", "children": [] }
}"##;

impl Editor {
    /// `GET /api/scene`: the file's document (or the starter), and its fault if it has one.
    pub(super) fn scene(&self) -> Response {
        let name = self
            .path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned());
        // The document goes out as its own text (checked to be JSON), keys in the file's order.
        let (document, exists, error) = match std::fs::read_to_string(&self.path) {
            Ok(text) => match serde_json::from_str::<Value>(&text) {
                Ok(v) => {
                    let err = Scene::from_json_value(&v).err().map(|e| e.to_string());
                    (text, true, err)
                }
                Err(e) => (
                    STARTER.to_string(),
                    true,
                    Some(format!("the file is not valid JSON ({e}); starting afresh")),
                ),
            },
            Err(_) => (STARTER.to_string(), false, None),
        };
        let head = json!({ "file": name, "exists": exists, "error": error }).to_string();
        let mut body = head[..head.len() - 1].to_string();
        body.push_str(",\"document\":");
        body.push_str(document.trim());
        body.push('}');
        Response {
            status: 200,
            content_type: "application/json",
            headers: Vec::new(),
            body: body.into_bytes(),
        }
    }
}

fn v3(p: DVec3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// A body that is a scene document, read.
fn scene_of(body: &[u8]) -> Answer<Scene> {
    let v: Value =
        serde_json::from_slice(body).map_err(|e| bad("$", format!("$: not valid JSON: {e}")))?;
    Scene::from_json_value(&v).map_err(|e| from_error(e, ""))
}

/// `POST /api/validate`: the body is a scene document.
pub(super) fn validate(body: &[u8]) -> Answer {
    let scene = scene_of(body)?;
    let b = scene.bbox();
    let bbox = (!b.is_empty() && b.min.is_finite() && b.max.is_finite())
        .then(|| json!({ "min": v3(b.min), "max": v3(b.max) }));
    let materials: Vec<&str> = scene.materials().iter().map(|m| m.name.as_str()).collect();
    Ok(Response::json(
        200,
        &json!({
            "ok": true,
            "primitives": scene.primitive_count(),
            "bbox": bbox,
            "materials": materials,
        }),
    ))
}

/// A query parameter as an image side (1..=4096), or `default`.
fn side(query: &str, key: &str, default: u32) -> Answer<u32> {
    for pair in query.split('&') {
        if let Some((k, v)) = pair.split_once('=')
            && k == key
        {
            return match v.parse::<u32>() {
                Ok(n) if (1..=4096).contains(&n) => Ok(n),
                _ => Err(bad(
                    "$",
                    format!("query `{key}`: expected a whole number of pixels in 1..=4096"),
                )),
            };
        }
    }
    Ok(default)
}

/// `POST /api/shader?w=W&h=H[&cull=1]`: the body is a scene document; the answer is the fragment
/// shader, each leaf's JSON path and the camera `bspcsg render` would use at W × H.
pub(super) fn shader(body: &[u8], query: &str) -> Answer {
    let (w, h) = (side(query, "w", 800)?, side(query, "h", 600)?);
    // `cull=1` skips primitives by their bounding spheres where they cannot matter. Off by
    // default: in software GL (SwiftShader, which runs branches of neighbouring pixels
    // together) it measured 30 % slower on the mechanical example.
    let cull = query.split('&').any(|kv| kv == "cull=1");
    let scene = scene_of(body)?;
    let shader = fragment_shader_with(&scene, cull);
    let camera = Camera::for_scene(&scene, View::Iso, (w, h)).unwrap_or_else(|_| {
        // Nothing to frame (an empty scene): a plain view of the unit box.
        Camera::look_at(
            DVec3::new(4.0, 3.0, 6.0),
            DVec3::ZERO,
            DVec3::Y,
            crate::sdf::DEFAULT_FOV_DEG,
            (w, h),
        )
    });
    let (fov, ortho) = match camera.projection {
        Projection::Perspective { fov_deg } => (fov_deg, 0.0),
        Projection::Orthographic { height } => (0.0, height),
    };
    Ok(Response::json(
        200,
        &json!({
            "glsl": shader.source,
            "leaf_paths": shader.leaf_paths,
            "camera": {
                "eye": v3(camera.eye), "target": v3(camera.target), "up": v3(camera.up),
                "fov_deg": fov, "ortho_height": ortho,
            },
        }),
    ))
}
