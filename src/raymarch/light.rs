//! The shading model of seed 000: a constant ambient term plus Lambert diffuse from
//! every light, colours adding up.

use glam::DVec3;

use crate::sdf::Light;

/// The ambient term of the seed's model.
pub const DEFAULT_AMBIENT: f64 = 0.1;

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
