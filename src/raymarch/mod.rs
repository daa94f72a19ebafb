//! Seeing and checking: sphere tracing of scenes, ray casting of meshes, and the agreement
//! check between a mesh and the scene it was made from.
//!
//! ```text
//! Scene ──► Culler (per-node boxes) ──► per tile: pruned program ──► sphere tracing ─┐
//! Mesh ──► MeshBvh (binned SAH) ──────────────────────────────────► ray casting ───┴─► shade ─► Image ─► PNG
//! Scene + Mesh ──► check: surface distance, coverage, rays, sign ──► CheckReport
//! ```
//!
//! Both renderers share the camera, the lights and the shading model of seed 000: ambient
//! (0.1, scaled by ambient occlusion) plus Lambert diffuse from every light, colours adding up.
//! Work is split into 8×8 tiles rendered in parallel; nothing recurses.

mod bvh;
mod camera;
mod cast;
mod check;
mod image;
mod light;
mod march;
mod normals;
mod render;

/// The scene document's view types, used by the renderer as they are.
pub use crate::sdf::{DEFAULT_FOV_DEG, Light, LightKind, Projection, SceneCamera};
pub use bvh::{MeshBvh, MeshHit};
pub use camera::{Camera, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, Ray, View, framing_bounds};
pub use check::{
    CheckOptions, CheckReport, CheckThresholds, DistanceStats, RayStats, SignStats, check_mesh,
};
pub use image::{Image, Rgb8};
pub use light::DEFAULT_AMBIENT;
pub use normals::CREASE_DEG;
pub use render::{RenderOptions, Shading};

use crate::error::Result;
use crate::mesh::{Material, Mesh};
use crate::sdf::Scene;

/// Ray marches a scene. See [`render_scene_with_progress`].
///
/// ```
/// use bspcsg::Scene;
/// use bspcsg::raymarch::{Camera, RenderOptions, View, render_scene};
/// let scene = Scene::from_json_str(
///     r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#,
/// )?;
/// let camera = Camera::framing(&scene.bbox(), View::Iso, (32, 24))?;
/// let image = render_scene(&scene, &camera, &RenderOptions::default())?;
/// assert_eq!(image.pixels.len(), 32 * 24);
/// # Ok::<(), bspcsg::Error>(())
/// ```
///
/// # Errors
///
/// As [`render_scene_with_progress`].
pub fn render_scene(scene: &Scene, camera: &Camera, opts: &RenderOptions) -> Result<Image> {
    render_scene_with_progress(scene, camera, opts, &|_, _| {})
}

/// Ray marches a scene by sphere tracing, calling `progress(tiles done, tiles)` as it goes.
/// The options' profile decides steps, hit threshold, reach, shadows and occlusion (take the
/// scene's own with `RenderOptions::with_profile(scene.render_profile().clone())`). Fails for
/// an invalid camera or options.
///
/// # Errors
///
/// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for an invalid camera or
/// options.
pub fn render_scene_with_progress(
    scene: &Scene,
    camera: &Camera,
    opts: &RenderOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Image> {
    opts.validate()?;
    let frame = camera.frame()?;
    let tracer = march::SceneTracer::new(scene, frame, opts);
    Ok(render::render_tiles(&frame, progress, |t, out| {
        tracer.render_tile(t, out)
    }))
}

/// Ray casts a mesh (closed or not), building its BVH. `materials[s]` colours the triangles of
/// source id `s`; missing ones are grey.
///
/// # Errors
///
/// As [`render_mesh_with_progress`].
pub fn render_mesh(
    mesh: &Mesh,
    materials: &[Material],
    camera: &Camera,
    opts: &RenderOptions,
) -> Result<Image> {
    let bvh = MeshBvh::build(mesh);
    render_mesh_with_progress(mesh, &bvh, materials, camera, opts, &|_, _| {})
}

/// Ray casts a mesh through a BVH built from it, reporting progress.
///
/// # Errors
///
/// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for an invalid camera or
/// options.
pub fn render_mesh_with_progress(
    mesh: &Mesh,
    bvh: &MeshBvh,
    materials: &[Material],
    camera: &Camera,
    opts: &RenderOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Image> {
    opts.validate()?;
    let frame = camera.frame()?;
    let tracer = cast::MeshTracer::new(mesh, bvh, materials, frame, opts);
    Ok(render::render_tiles(&frame, progress, |t, out| {
        tracer.render_tile(t, out)
    }))
}
