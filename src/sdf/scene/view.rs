//! How a scene wants to be seen: the envelope's optional `camera` and `lights`, checked field
//! by field like the rest of the document. The renderer (`raymarch`) turns them into pixels.

use glam::DVec3;
use serde_json::Value;

use super::colour::plain_colour;
use super::json::{
    array, fault, key_path, non_negative, number, object, only, required, string, vec3,
};
use crate::error::{Error, Result};

/// How a camera maps the scene to the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// A pinhole with the vertical field of view in degrees (0 < fov < 180).
    Perspective {
        /// Vertical field of view, degrees.
        fov_deg: f64,
    },
    /// Parallel rays; `height` is the extent of the world seen from bottom to top of the image.
    Orthographic {
        /// World units from the bottom to the top of the image.
        height: f64,
    },
}

/// A scene's camera: placement and projection, without an image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneCamera {
    /// Where the eye is.
    pub eye: DVec3,
    /// The point at the centre of the image.
    pub target: DVec3,
    /// Which way is up.
    pub up: DVec3,
    /// Perspective or orthographic.
    pub projection: Projection,
}

/// The default vertical field of view, degrees.
pub const DEFAULT_FOV_DEG: f64 = 40.0;

/// Where light comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Parallel light travelling along `direction` (from the light towards the scene).
    Directional {
        /// The direction the light travels (need not be of unit length).
        direction: DVec3,
    },
    /// Light from a point, without falloff (the seed's model).
    Point {
        /// Where the light is.
        position: DVec3,
    },
}

/// One light: where from, its linear RGB colour and a scalar intensity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Directional or point.
    pub kind: LightKind,
    /// Linear RGB, each usually in 0..=1.
    pub color: DVec3,
    /// Multiplies the colour.
    pub intensity: f64,
}

impl Light {
    /// A white directional light.
    #[must_use]
    pub fn directional(direction: DVec3, intensity: f64) -> Light {
        Light {
            kind: LightKind::Directional { direction },
            color: DVec3::ONE,
            intensity,
        }
    }

    /// A white point light.
    #[must_use]
    pub fn point(position: DVec3, intensity: f64) -> Light {
        Light {
            kind: LightKind::Point { position },
            color: DVec3::ONE,
            intensity,
        }
    }

    /// The pair used when a scene names no lights: a warm key from above front left and a
    /// cool, dimmer fill from the right, both directional so that they do not depend on scale.
    #[must_use]
    pub fn default_rig() -> Vec<Light> {
        vec![
            Light {
                kind: LightKind::Directional {
                    direction: DVec3::new(0.55, -1.0, -0.45),
                },
                color: DVec3::new(1.0, 0.96, 0.9),
                intensity: 0.85,
            },
            Light {
                kind: LightKind::Directional {
                    direction: DVec3::new(-0.9, -0.25, -0.3),
                },
                color: DVec3::new(0.75, 0.82, 1.0),
                intensity: 0.3,
            },
        ]
    }

    /// Checks that every number is finite, the direction non-zero and the intensity ≥ 0.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) naming the first value out
    /// of range.
    pub fn validate(&self) -> Result<()> {
        let v = match self.kind {
            LightKind::Directional { direction } => {
                if direction.try_normalize().is_none() {
                    return Err(Error::param(
                        "direction",
                        direction.length(),
                        "a light direction must be finite and non-zero",
                    ));
                }
                direction
            }
            LightKind::Point { position } => position,
        };
        if !v.is_finite() || !self.color.is_finite() || self.color.min_element() < 0.0 {
            return Err(Error::param(
                "light",
                f64::NAN,
                "light positions and colours must be finite, colours non-negative",
            ));
        }
        if !(self.intensity >= 0.0 && self.intensity.is_finite()) {
            return Err(Error::param(
                "intensity",
                self.intensity,
                "a light's intensity must be finite and non-negative",
            ));
        }
        Ok(())
    }

    /// From `p`: the unit direction towards the light and how far along it the light is.
    #[inline]
    pub(crate) fn towards(&self, p: DVec3) -> (DVec3, f64) {
        match self.kind {
            LightKind::Directional { direction } => (-direction.normalize(), f64::INFINITY),
            LightKind::Point { position } => {
                let d = position - p;
                let len = d.length();
                (d / len.max(f64::MIN_POSITIVE), len)
            }
        }
    }
}

/// `$.camera`.
pub(super) fn camera(v: &Value, path: &str) -> Result<SceneCamera> {
    let m = object(v, path, "a camera")?;
    only(
        m,
        path,
        &["eye", "target", "up", "fov_deg", "projection", "height"],
        "the camera",
    )?;
    let eye = vec3(
        required(m, path, "eye", "where the camera is")?,
        &key_path(path, "eye"),
    )?;
    let target = vec3(
        required(m, path, "target", "the point the camera looks at")?,
        &key_path(path, "target"),
    )?;
    if (target - eye).try_normalize().is_none() {
        return Err(fault(
            &key_path(path, "target"),
            "the target must differ from the eye",
        ));
    }
    let up = match m.get("up") {
        Some(u) => vec3(u, &key_path(path, "up"))?,
        None => DVec3::Y,
    };
    if (target - eye)
        .normalize()
        .cross(up)
        .try_normalize()
        .is_none()
    {
        return Err(fault(
            &key_path(path, "up"),
            "`up` must be non-zero and not along the view direction (eye → target)",
        ));
    }
    let kind = match m.get("projection") {
        Some(p) => string(p, &key_path(path, "projection"))?,
        None => "perspective",
    };
    let projection = match kind {
        "perspective" => {
            if m.contains_key("height") {
                return Err(fault(
                    &key_path(path, "height"),
                    "`height` belongs to an orthographic camera; a perspective one has `fov_deg`",
                ));
            }
            let fov_deg = match m.get("fov_deg") {
                Some(f) => number(f, &key_path(path, "fov_deg"))?,
                None => DEFAULT_FOV_DEG,
            };
            if !(fov_deg > 0.0 && fov_deg < 180.0) {
                return Err(fault(
                    &key_path(path, "fov_deg"),
                    format!(
                        "the field of view must lie strictly between 0 and 180 degrees, found {fov_deg}"
                    ),
                ));
            }
            Projection::Perspective { fov_deg }
        }
        "orthographic" => {
            if m.contains_key("fov_deg") {
                return Err(fault(
                    &key_path(path, "fov_deg"),
                    "`fov_deg` belongs to a perspective camera; an orthographic one has `height`",
                ));
            }
            let height = number(
                required(
                    m,
                    path,
                    "height",
                    "the world height an orthographic image spans",
                )?,
                &key_path(path, "height"),
            )?;
            if height <= 0.0 {
                return Err(fault(
                    &key_path(path, "height"),
                    format!("must be > 0, found {height}"),
                ));
            }
            Projection::Orthographic { height }
        }
        other => {
            return Err(fault(
                &key_path(path, "projection"),
                format!("expected \"perspective\" or \"orthographic\", found {other:?}"),
            ));
        }
    };
    Ok(SceneCamera {
        eye,
        target,
        up,
        projection,
    })
}

/// `$.lights`.
pub(super) fn lights(v: &Value, path: &str) -> Result<Vec<Light>> {
    let a = array(v, path, None)?;
    let mut out = Vec::with_capacity(a.len());
    for (i, l) in a.iter().enumerate() {
        let p = format!("{path}[{i}]");
        let m = object(l, &p, "a light")?;
        only(
            m,
            &p,
            &[
                "type",
                "direction",
                "position",
                "color",
                "intensity",
                "name",
            ],
            "a light",
        )?;
        let kind = string(
            required(m, &p, "type", "\"directional\" or \"point\"")?,
            &key_path(&p, "type"),
        )?;
        let kind = match kind {
            "directional" => {
                if m.contains_key("position") {
                    return Err(fault(
                        &key_path(&p, "position"),
                        "a directional light has a `direction`, not a `position`",
                    ));
                }
                let dp = key_path(&p, "direction");
                let direction = vec3(
                    required(m, &p, "direction", "where the light travels")?,
                    &dp,
                )?;
                if direction.try_normalize().is_none() {
                    return Err(fault(&dp, "the direction must be non-zero"));
                }
                LightKind::Directional { direction }
            }
            "point" => {
                if m.contains_key("direction") {
                    return Err(fault(
                        &key_path(&p, "direction"),
                        "a point light has a `position`, not a `direction`",
                    ));
                }
                LightKind::Point {
                    position: vec3(
                        required(m, &p, "position", "where the light is")?,
                        &key_path(&p, "position"),
                    )?,
                }
            }
            other => {
                return Err(fault(
                    &key_path(&p, "type"),
                    format!("expected \"directional\" or \"point\", found {other:?}"),
                ));
            }
        };
        let color = match m.get("color") {
            Some(c) => {
                let c = plain_colour(c, &key_path(&p, "color"))?;
                DVec3::new(c[0], c[1], c[2])
            }
            None => DVec3::ONE,
        };
        let intensity = match m.get("intensity") {
            Some(x) => non_negative(x, &key_path(&p, "intensity"))?,
            None => 1.0,
        };
        out.push(Light {
            kind,
            color,
            intensity,
        });
    }
    Ok(out)
}
