//! Lights and the shading model of seed 000: a constant ambient term plus Lambert diffuse from
//! every light, colours adding up.

use glam::DVec3;

use crate::error::{Error, Result};

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

/// The ambient term of the seed's model.
pub const DEFAULT_AMBIENT: f64 = 0.1;

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

/// Ambient plus, per light, `visibility · max(0, n·l) · colour · intensity`, all times the
/// base colour; `ambient` is scaled by the occlusion factor.
#[inline]
pub(crate) fn shade(
    base: DVec3,
    ambient: f64,
    occlusion: f64,
    normal: DVec3,
    p: DVec3,
    lights: &[Light],
    mut visibility: impl FnMut(usize, DVec3, f64) -> f64,
) -> DVec3 {
    let mut light = DVec3::splat(ambient * occlusion);
    for (i, l) in lights.iter().enumerate() {
        let (dir, dist) = l.towards(p);
        let lambert = normal.dot(dir);
        if lambert <= 0.0 {
            continue;
        }
        let v = visibility(i, dir, dist);
        light += l.color * (l.intensity * lambert * v);
    }
    base * light
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lambert_adds_up_and_ignores_back_faces() {
        let lights = [
            Light::directional(DVec3::NEG_Y, 1.0),
            Light::directional(DVec3::Y, 1.0),
        ];
        let c = shade(
            DVec3::ONE,
            0.1,
            1.0,
            DVec3::Y,
            DVec3::ZERO,
            &lights,
            |_, _, _| 1.0,
        );
        assert!((c - DVec3::splat(1.1)).length() < 1e-12);
        let half = shade(
            DVec3::ONE,
            0.0,
            1.0,
            DVec3::Y,
            DVec3::ZERO,
            &lights,
            |_, _, _| 0.5,
        );
        assert!((half - DVec3::splat(0.5)).length() < 1e-12);
        assert!(Light::directional(DVec3::ZERO, 1.0).validate().is_err());
        assert!(Light::point(DVec3::ONE, f64::NAN).validate().is_err());
    }
}
