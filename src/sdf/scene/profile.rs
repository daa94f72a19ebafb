//! The render profile: raymarching settings that travel with a scene.

use serde_json::Value;

use super::colour::colour;
use super::json::{count, key_path, object, only, positive};
use crate::error::Result;

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

pub(super) fn render_profile(v: &Value, path: &str) -> Result<RenderProfile> {
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
