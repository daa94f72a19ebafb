//! Cameras: look-at placement, perspective or orthographic projection, and a default framing
//! from a bounding box.

use glam::DVec3;

use crate::error::{Error, Result};
use crate::geom::Aabb;
use crate::sdf::{BakeOptions, Projection, Scene, SceneCamera};

/// The largest image side accepted, and the most pixels: a 16k × 16k image is already 1 GiB
/// of pixels in flight.
pub const MAX_IMAGE_SIDE: u32 = 16_384;
/// The most pixels of one image (64 megapixels).
pub const MAX_IMAGE_PIXELS: u64 = 64 << 20;

/// A named direction to look from, for the default framing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// Three-quarter view from the front right, above: perspective.
    #[default]
    Iso,
    /// From +Z towards −Z: orthographic.
    Front,
    /// From +X towards −X: orthographic.
    Side,
    /// From +Y down (the image's up is −Z): orthographic.
    Top,
}

impl View {
    /// Parses `iso`, `front`, `side` or `top`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<View> {
        Some(match name {
            "iso" => View::Iso,
            "front" => View::Front,
            "side" => View::Side,
            "top" => View::Top,
            _ => return None,
        })
    }
}

/// A camera: where it is, what it looks at, and the image it makes.
///
/// Pixel `(x, y)` (origin top left) looks through its centre; the image's right is
/// `forward × up`, Y up as everywhere in the crate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye (for orthographic views: the centre of the image plane).
    pub eye: DVec3,
    /// The point at the centre of the image.
    pub target: DVec3,
    /// Which way is up (need not be orthogonal to the view direction, must not be parallel).
    pub up: DVec3,
    /// Perspective or orthographic.
    pub projection: Projection,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

/// A ray through a pixel: `origin + t · dir`, `dir` of unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where it starts.
    pub origin: DVec3,
    /// Unit direction.
    pub dir: DVec3,
}

impl Ray {
    /// The point at parameter `t`.
    #[inline]
    #[must_use]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.dir * t
    }
}

/// The camera's orthonormal frame and per-pixel steps, computed once per image.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    /// World size of one pixel at unit distance (perspective) or on the image plane (ortho).
    pub pixel: f64,
    pub ortho: bool,
    pub eye: DVec3,
    pub width: u32,
    pub height: u32,
}

impl Camera {
    /// A perspective camera.
    #[must_use]
    pub fn look_at(eye: DVec3, target: DVec3, up: DVec3, fov_deg: f64, size: (u32, u32)) -> Self {
        Camera {
            eye,
            target,
            up,
            projection: Projection::Perspective { fov_deg },
            width: size.0,
            height: size.1,
        }
    }

    /// A scene's own camera with an image size.
    #[must_use]
    pub fn from_scene(c: &SceneCamera, size: (u32, u32)) -> Camera {
        Camera {
            eye: c.eye,
            target: c.target,
            up: c.up,
            projection: c.projection,
            width: size.0,
            height: size.1,
        }
    }

    /// The scene's own camera, or else the default framing of its solid from `view`.
    ///
    /// # Errors
    ///
    /// As [`Camera::framing`] (an empty or unbounded scene without a camera, an image size out
    /// of range), or [`Camera::validate`] for the scene's camera.
    pub fn for_scene(scene: &Scene, view: View, size: (u32, u32)) -> Result<Camera> {
        match scene.camera() {
            Some(c) => {
                let cam = Camera::from_scene(c, size);
                cam.validate()?;
                Ok(cam)
            }
            None => Camera::framing(&framing_bounds(scene), view, size),
        }
    }

    /// The default camera for a bounded box: the named view, the whole box in the picture with
    /// a small margin. Fails for an empty or unbounded box (give a camera then).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for an empty box or an image
    /// size out of range, [`Error::Unbounded`](crate::Error::Unbounded) for an unbounded box.
    pub fn framing(bounds: &Aabb, view: View, size: (u32, u32)) -> Result<Camera> {
        if bounds.is_empty() {
            return Err(Error::param(
                "bounds",
                f64::NAN,
                "nothing to frame: the scene or mesh is empty",
            ));
        }
        if !(bounds.min.is_finite() && bounds.max.is_finite()) {
            return Err(Error::Unbounded {
                what: "the scene",
                why: "a half-space not intersected with a bounded shape",
                remedy: "the default camera cannot frame it: give a camera (`camera` in the \
                         scene, or --eye and --target)",
            });
        }
        check_size(size)?;
        let c = bounds.center();
        // At least a sliver of size, so that a flat mesh still frames.
        let radius = (0.5 * bounds.diagonal()).max(1e-9 * (1.0 + c.abs().max_element()));
        let aspect = size.0 as f64 / size.1 as f64;
        let (dir, up) = match view {
            View::Iso => (DVec3::new(1.0, 0.8, 1.4).normalize(), DVec3::Y),
            View::Front => (DVec3::Z, DVec3::Y),
            View::Side => (DVec3::X, DVec3::Y),
            View::Top => (DVec3::Y, DVec3::NEG_Z),
        };
        // The box's corners in the camera's frame (right, up, towards the eye), about its
        // centre: every one must fall inside the image with a small margin.
        let back = dir;
        let right = up.cross(back).normalize();
        let true_up = back.cross(right);
        let corners: Vec<DVec3> = (0..8)
            .map(|i| {
                let p = DVec3::new(
                    if i & 1 == 0 {
                        bounds.min.x
                    } else {
                        bounds.max.x
                    },
                    if i & 2 == 0 {
                        bounds.min.y
                    } else {
                        bounds.max.y
                    },
                    if i & 4 == 0 {
                        bounds.min.z
                    } else {
                        bounds.max.z
                    },
                ) - c;
                DVec3::new(p.dot(right), p.dot(true_up), p.dot(back))
            })
            .collect();
        let margin = 1.08;
        let cam = if view == View::Iso {
            let fov_deg: f64 = 35.0;
            let tan_v = (0.5 * fov_deg).to_radians().tan();
            let tan_h = tan_v * aspect;
            // A corner at depth z towards the eye is d − z in front of it.
            let dist = corners
                .iter()
                .map(|k| k.z + margin * (k.x.abs() / tan_h).max(k.y.abs() / tan_v))
                .fold(radius * 1e-3, f64::max);
            Camera {
                eye: c + dir * dist,
                target: c,
                up,
                projection: Projection::Perspective { fov_deg },
                width: size.0,
                height: size.1,
            }
        } else {
            let half = corners
                .iter()
                .map(|k| k.y.abs().max(k.x.abs() / aspect))
                .fold(radius * 1e-3, f64::max);
            Camera {
                eye: c + dir * (2.0 * radius + 1.0),
                target: c,
                up,
                projection: Projection::Orthographic {
                    height: 2.0 * margin * half,
                },
                width: size.0,
                height: size.1,
            }
        };
        Ok(cam)
    }

    /// Checks every field: finite, eye ≠ target, up not along the view, a field of view in
    /// (0°, 180°), a positive orthographic height, an image size in range.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) naming the first field out
    /// of range.
    pub fn validate(&self) -> Result<()> {
        for (name, v) in [("eye", self.eye), ("target", self.target), ("up", self.up)] {
            if !v.is_finite() {
                return Err(Error::param(
                    name,
                    if v.is_nan() { f64::NAN } else { f64::INFINITY },
                    "camera vectors must be finite",
                ));
            }
            if v.abs().max_element() > crate::geom::MAX_COORDINATE {
                return Err(Error::param(
                    name,
                    v.abs().max_element(),
                    "camera coordinates must be at most 1e100",
                ));
            }
        }
        let fwd = self.target - self.eye;
        if fwd.try_normalize().is_none() {
            return Err(Error::param(
                "target",
                fwd.length(),
                "the target must differ from the eye",
            ));
        }
        let fwd = fwd.normalize();
        if self.up.try_normalize().is_none() || fwd.cross(self.up).try_normalize().is_none() {
            return Err(Error::param(
                "up",
                self.up.length(),
                "`up` must be non-zero and not parallel to the view direction",
            ));
        }
        match self.projection {
            Projection::Perspective { fov_deg } => {
                if !(fov_deg > 0.0 && fov_deg < 180.0) {
                    return Err(Error::param(
                        "fov_deg",
                        fov_deg,
                        "the field of view must lie strictly between 0 and 180 degrees",
                    ));
                }
            }
            Projection::Orthographic { height } => {
                if !(height > 0.0 && height.is_finite()) {
                    return Err(Error::param(
                        "height",
                        height,
                        "the orthographic height must be positive and finite",
                    ));
                }
            }
        }
        check_size((self.width, self.height))
    }

    pub(crate) fn frame(&self) -> Result<Frame> {
        self.validate()?;
        let forward = (self.target - self.eye).normalize();
        let right = forward.cross(self.up).normalize();
        let up = right.cross(forward);
        let (pixel, ortho) = match self.projection {
            Projection::Perspective { fov_deg } => (
                2.0 * (0.5 * fov_deg).to_radians().tan() / self.height as f64,
                false,
            ),
            Projection::Orthographic { height } => (height / self.height as f64, true),
        };
        Ok(Frame {
            forward,
            right,
            up,
            pixel,
            ortho,
            eye: self.eye,
            width: self.width,
            height: self.height,
        })
    }

    /// The ray through pixel `(x, y)`'s centre (fractional pixels allowed).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) when the camera does not
    /// validate ([`Camera::validate`]).
    pub fn ray(&self, x: f64, y: f64) -> Result<Ray> {
        Ok(self.frame()?.ray(x + 0.5, y + 0.5))
    }
}

impl Frame {
    /// The ray through image point `(u, v)` in pixels from the top-left corner.
    #[inline]
    pub fn ray(&self, u: f64, v: f64) -> Ray {
        let sx = (u - 0.5 * self.width as f64) * self.pixel;
        let sy = (0.5 * self.height as f64 - v) * self.pixel;
        if self.ortho {
            Ray {
                origin: self.eye + self.right * sx + self.up * sy,
                dir: self.forward,
            }
        } else {
            Ray {
                origin: self.eye,
                dir: (self.forward + self.right * sx + self.up * sy).normalize(),
            }
        }
    }

    /// The world size of a pixel at distance `t` along a ray.
    #[inline]
    pub fn footprint(&self, t: f64) -> f64 {
        if self.ortho {
            self.pixel
        } else {
            self.pixel * t
        }
    }

    /// A box around every ray through the image rectangle `[u0, u1] × [v0, v1]` between
    /// depths `z0` and `z1` along the view direction, as two boxes to sweep between.
    pub fn beam(&self, u0: f64, v0: f64, u1: f64, v1: f64, z0: f64, z1: f64) -> (Aabb, Aabb) {
        let corner = |u: f64, v: f64, z: f64| {
            let sx = (u - 0.5 * self.width as f64) * self.pixel;
            let sy = (0.5 * self.height as f64 - v) * self.pixel;
            if self.ortho {
                self.eye + self.right * sx + self.up * sy + self.forward * z
            } else {
                self.eye + (self.forward + self.right * sx + self.up * sy) * z
            }
        };
        let slab = |z: f64| {
            Aabb::from_points(&[
                corner(u0, v0, z),
                corner(u1, v0, z),
                corner(u0, v1, z),
                corner(u1, v1, z),
            ])
        };
        (slab(z0), slab(z1))
    }
}

/// A box around the scene's solid for framing it. The per-node boxes are conservative (smooth
/// blends and stretched primitives widen them), so a coarse marching-cubes pass (48 cells a
/// side, a few milliseconds) finds the solid's real extent; the conservative box is the
/// fallback.
#[must_use]
pub fn framing_bounds(scene: &Scene) -> Aabb {
    let b = scene.bbox();
    if b.is_empty() || !(b.min.is_finite() && b.max.is_finite()) {
        return b;
    }
    const CELLS: u32 = 48;
    let cell = b.size().max_element() / CELLS as f64;
    match scene.bake(&BakeOptions::with_resolution(CELLS)) {
        Ok(mesh) if !mesh.is_empty() => mesh.bbox().expanded(cell).intersection(&b),
        _ => b,
    }
}

fn check_size((w, h): (u32, u32)) -> Result<()> {
    if w == 0 || h == 0 {
        return Err(Error::param(
            "size",
            (w.min(h)) as f64,
            "the image must be at least 1×1 pixels",
        ));
    }
    if w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE || (w as u64) * (h as u64) > MAX_IMAGE_PIXELS {
        return Err(Error::param(
            "size",
            w.max(h) as f64,
            "the image is too large: at most 16384 pixels a side and 64 megapixels",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framing_puts_the_box_in_the_middle() {
        let b = Aabb::new(DVec3::new(1.0, 2.0, 3.0), DVec3::new(3.0, 4.0, 7.0));
        for view in [View::Iso, View::Front, View::Side, View::Top] {
            let cam = Camera::framing(&b, view, (64, 48)).unwrap();
            let r = cam.ray(31.5, 23.5).unwrap();
            // The centre ray passes through the box centre.
            let to_c = b.center() - r.origin;
            assert!((to_c - r.dir * to_c.dot(r.dir)).length() < 1e-9, "{view:?}");
        }
    }

    #[test]
    fn bad_cameras_are_refused() {
        let b = Aabb::new(DVec3::ZERO, DVec3::ONE);
        assert!(Camera::framing(&b, View::Iso, (0, 10)).is_err());
        assert!(Camera::framing(&b, View::Iso, (100_000, 100_000)).is_err());
        let inf = Aabb::new(DVec3::NEG_INFINITY, DVec3::ONE);
        assert!(Camera::framing(&inf, View::Iso, (10, 10)).is_err());
        let mut c = Camera::framing(&b, View::Iso, (10, 10)).unwrap();
        c.eye.x = f64::NAN;
        assert!(c.validate().is_err());
        let c = Camera::look_at(DVec3::Y, DVec3::ZERO, DVec3::Y, 40.0, (10, 10));
        assert!(c.validate().is_err());
    }
}
