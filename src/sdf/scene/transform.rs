//! A node's placement: `pos`, `rot` (degrees) and `scale`.

use glam::DVec3;
use serde_json::{Map, Value};

use super::MAX_SCENE_MAGNITUDE;
use super::json::{fault, key_path, number, vec3};
use crate::error::Result;
use crate::sdf::tree::Transform;

/// Reads `pos`, `rot`, `scale` of a node.
pub(super) fn transform(m: &Map<String, Value>, path: &str) -> Result<Transform> {
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
