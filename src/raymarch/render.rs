//! Render options and the tile loop that both renderers share.

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use super::camera::Frame;
use super::image::Image;
use super::light::DEFAULT_AMBIENT;
use crate::geom::Aabb;
use crate::sdf::RenderProfile;
use crate::sdf::{Light, Scene};

/// How a mesh's surface normal is chosen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shading {
    /// Each triangle's own normal: facets show.
    Flat,
    /// Normals interpolated across triangles from each corner's angle-weighted average over the
    /// triangles at its vertex, split at creases: triangles whose normals differ by more than
    /// [`CREASE_DEG`](crate::raymarch::CREASE_DEG) (30°) do not share a normal, so hard edges
    /// stay hard and a flat face fanned from a fillet's rim shades flat.
    #[default]
    Smooth,
}

/// Everything a render needs besides the camera and the geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// The lights; an empty list leaves only the ambient term.
    pub lights: Vec<Light>,
    /// The ambient term (scaled by ambient occlusion).
    pub ambient: f64,
    /// Steps, hit epsilon, distances, shadow and occlusion samples, background. For meshes
    /// `max_distance` and `hit_epsilon` do not apply (rays run to infinity), `shadow_steps > 0`
    /// turns on hard shadows and `ao_steps` is the number of occlusion rays.
    pub profile: RenderProfile,
    /// Mesh normals.
    pub shading: Shading,
    /// The hit threshold grows with distance: a ray hits where the field is below
    /// `max(hit_epsilon, pixel_epsilon × pixel footprint at t)`. 0 keeps `hit_epsilon` fixed.
    pub pixel_epsilon: f64,
    /// Sphere-tracing steps are `step_scale ×` the field (≤ 1). The scene's field is
    /// 1-Lipschitz (exact primitives, min / max and both smooth blends are convex combinations
    /// of their operands' gradients), so 1 is safe; lower it for fields that are not.
    pub step_scale: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            lights: Light::default_rig(),
            ambient: DEFAULT_AMBIENT,
            profile: RenderProfile::default(),
            shading: Shading::default(),
            pixel_epsilon: 0.25,
            step_scale: 1.0,
        }
    }
}

impl RenderOptions {
    /// Defaults with a given render profile.
    #[must_use]
    pub fn with_profile(profile: RenderProfile) -> Self {
        RenderOptions {
            profile,
            ..Default::default()
        }
    }

    /// What the scene document asks for: its render profile, and its lights or, when it names
    /// none, the default key + fill pair.
    pub fn for_scene(scene: &Scene) -> Self {
        RenderOptions {
            profile: scene.render_profile().clone(),
            lights: scene
                .lights()
                .map_or_else(Light::default_rig, <[Light]>::to_vec),
            ..Default::default()
        }
    }

    pub(crate) fn validate(&self) -> crate::Result<()> {
        use crate::Error;
        for l in &self.lights {
            l.validate()?;
        }
        if !(self.ambient >= 0.0 && self.ambient.is_finite()) {
            return Err(Error::param(
                "ambient",
                self.ambient,
                "must be finite and ≥ 0",
            ));
        }
        if !(self.step_scale > 0.0 && self.step_scale <= 1.0) {
            return Err(Error::param(
                "step_scale",
                self.step_scale,
                "must lie in (0, 1]",
            ));
        }
        if !(self.pixel_epsilon >= 0.0 && self.pixel_epsilon.is_finite()) {
            return Err(Error::param(
                "pixel_epsilon",
                self.pixel_epsilon,
                "must be finite and ≥ 0",
            ));
        }
        let p = &self.profile;
        if !(p.hit_epsilon > 0.0 && p.hit_epsilon.is_finite()) {
            return Err(Error::param(
                "hit_epsilon",
                p.hit_epsilon,
                "must be positive and finite",
            ));
        }
        if p.max_distance.is_nan() || p.max_distance <= 0.0 {
            return Err(Error::param(
                "max_distance",
                p.max_distance,
                "must be positive",
            ));
        }
        if p.max_steps == 0 {
            return Err(Error::param("max_steps", 0.0, "must be at least 1"));
        }
        Ok(())
    }

    pub(crate) fn background(&self) -> DVec3 {
        let b = self.profile.background;
        DVec3::new(b[0], b[1], b[2])
    }
}

/// Tiles are this many pixels square: the unit of parallel work and of culling.
pub(crate) const TILE: u32 = 8;

/// The pixel rectangle `[x0, x1) × [y0, y1)` of one tile.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tile {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl Tile {
    pub fn pixels(&self) -> usize {
        ((self.x1 - self.x0) * (self.y1 - self.y0)) as usize
    }

    /// The tiles covering a `w` × `h` image, row by row (the last row and column cut short).
    pub fn grid(w: u32, h: u32) -> Vec<Tile> {
        (0..h.div_ceil(TILE))
            .flat_map(|ty| {
                (0..w.div_ceil(TILE)).map(move |tx| Tile {
                    x0: tx * TILE,
                    y0: ty * TILE,
                    x1: ((tx + 1) * TILE).min(w),
                    y1: ((ty + 1) * TILE).min(h),
                })
            })
            .collect()
    }
}

/// Renders every tile in parallel (`shade` fills a tile's pixels row by row) and reports
/// progress as `(tiles done, tiles)`.
pub(crate) fn render_tiles(
    frame: &Frame,
    progress: &(dyn Fn(usize, usize) + Sync),
    shade: impl Fn(&Tile, &mut Vec<DVec3>) + Sync,
) -> Image {
    let (w, h) = (frame.width, frame.height);
    let mut img = Image::new(w, h);
    img.pixels = shade_tiles(w, h, progress, shade);
    img
}

/// Fills every tile of a `w` × `h` grid in parallel (`shade` fills a tile's values row by
/// row), reports progress as `(tiles done, tiles)`, and lays the values out row by row: the
/// loop of the renderers and of the check's ray views, whatever a pixel holds.
pub(crate) fn shade_tiles<T: Copy + Default + Send>(
    w: u32,
    h: u32,
    progress: &(dyn Fn(usize, usize) + Sync),
    shade: impl Fn(&Tile, &mut Vec<T>) + Sync,
) -> Vec<T> {
    let tiles = Tile::grid(w, h);
    let done = AtomicUsize::new(0);
    let total = tiles.len();
    let every = (total / 100).max(1);
    let shaded: Vec<(Tile, Vec<T>)> = tiles
        .par_iter()
        .map(|t| {
            let mut buf = Vec::with_capacity(t.pixels());
            shade(t, &mut buf);
            let d = done.fetch_add(1, Ordering::Relaxed) + 1;
            if d.is_multiple_of(every) || d == total {
                progress(d, total);
            }
            (*t, buf)
        })
        .collect();
    let mut grid = vec![T::default(); w as usize * h as usize];
    for (t, buf) in shaded {
        let tw = (t.x1 - t.x0) as usize;
        for (row, chunk) in buf.chunks(tw).enumerate() {
            let start = ((t.y0 as usize + row) * w as usize) + t.x0 as usize;
            grid[start..start + tw].copy_from_slice(chunk);
        }
    }
    grid
}

/// True when the box moving linearly from `a0` to `a1` meets `b` at some moment: the swept
/// region holds every ray of a tile's beam, or every shadow ray from a tile's hits.
pub(crate) fn sweep_touches(a0: &Aabb, a1: &Aabb, b: &Aabb) -> bool {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    // alpha + beta·t ≤ 0 for some t in [lo, hi].
    let mut constrain = |alpha: f64, beta: f64| {
        if beta == 0.0 || !beta.is_finite() {
            if alpha > 0.0 {
                hi = -1.0;
            }
        } else if beta > 0.0 {
            hi = hi.min(-alpha / beta);
        } else {
            lo = lo.max(-alpha / beta);
        }
    };
    for k in 0..3 {
        constrain(a0.min[k] - b.max[k], a1.min[k] - a0.min[k]);
        constrain(b.min[k] - a0.max[k], -(a1.max[k] - a0.max[k]));
    }
    lo <= hi
}

/// The parameter range where a ray is inside `b` (clipped to `[0, t_max]`); `None` when it
/// misses. Works for boxes with infinite sides.
pub(crate) fn clip_to_box(origin: DVec3, dir: DVec3, b: &Aabb, t_max: f64) -> Option<(f64, f64)> {
    if b.is_empty() {
        return None;
    }
    b.ray_span(origin, dir.recip(), t_max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweeps_and_clips() {
        let a0 = Aabb::new(DVec3::ZERO, DVec3::ONE);
        let a1 = Aabb::new(DVec3::splat(10.0), DVec3::splat(11.0));
        let on_path = Aabb::new(DVec3::splat(5.0), DVec3::splat(5.5));
        let off_path = Aabb::new(DVec3::new(5.0, -3.0, 5.0), DVec3::new(5.5, -2.0, 5.5));
        assert!(sweep_touches(&a0, &a1, &on_path));
        assert!(!sweep_touches(&a0, &a1, &off_path));
        let inf = Aabb::new(
            DVec3::NEG_INFINITY,
            DVec3::new(f64::INFINITY, -2.5, f64::INFINITY),
        );
        assert!(!sweep_touches(&a0, &a1, &inf));
        let (n, f) = clip_to_box(DVec3::new(-1.0, 0.5, 0.5), DVec3::X, &a0, 100.0).unwrap();
        assert_eq!((n, f), (1.0, 2.0));
        assert!(clip_to_box(DVec3::new(-1.0, 2.5, 0.5), DVec3::X, &a0, 100.0).is_none());
        // Rays running in the box's faces (zero direction components, 0 · ∞ once) still meet it.
        for y in [0.0, 1.0] {
            let along_face = clip_to_box(DVec3::new(-1.0, y, 0.0), DVec3::X, &a0, 100.0);
            assert_eq!(along_face, Some((1.0, 2.0)), "y = {y}");
        }
    }
}
