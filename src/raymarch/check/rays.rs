//! The ray measure: the same camera rays through the scene (sphere tracing) and the mesh (its
//! BVH) from each view; hit/miss agreement, depth differences, and the difference image.

use glam::DVec3;

use super::report::stats;
use super::{CheckOptions, RayStats};
use crate::error::Result;
use crate::raymarch::bvh::MeshBvh;
use crate::raymarch::camera::{Camera, framing_bounds};
use crate::raymarch::image::{Rgb8, encode_srgb};
use crate::raymarch::march::SceneTracer;
use crate::raymarch::render::{RenderOptions, shade_tiles};
use crate::sdf::Scene;

pub(super) struct RayViews {
    pub(super) stats: RayStats,
    /// SDF hits: points on the surface, for coverage.
    pub(super) surface_points: Vec<DVec3>,
    pub(super) image: Option<Rgb8>,
}

/// Per pixel: the SDF's hit and the mesh's hit.
#[derive(Clone, Copy, Default)]
struct PixelPair {
    sdf: Option<(f64, DVec3)>,
    mesh: Option<(f64, DVec3)>,
    /// A one-sided hit passes within the tolerance of the other surface.
    grazing: bool,
}

pub(super) fn ray_views(
    scene: &Scene,
    bvh: &MeshBvh,
    tol: f64,
    opts: &CheckOptions,
) -> Result<RayViews> {
    let frame_box = framing_bounds(scene).union(&bvh.bounds());
    let n = opts.ray_size;
    let mut render = RenderOptions::with_profile(scene.render_profile().clone());
    // A fixed threshold well inside the tolerance: depths are compared, not pictures.
    render.pixel_epsilon = 0.0;
    render.profile.hit_epsilon = render.profile.hit_epsilon.min(0.05 * tol);
    render.profile.max_steps = render.profile.max_steps.max(256);
    let mut views = Vec::new();
    for &view in &opts.views {
        let camera = Camera::framing(&frame_box, view, (n, n))?;
        let mut opts_v = render.clone();
        // Orthographic views start far out; make sure the march reaches the scene.
        let reach = camera.eye.distance(frame_box.center()) + frame_box.diagonal();
        opts_v.profile.max_distance = opts_v.profile.max_distance.max(reach);
        let frame = camera.frame()?;
        let tracer = SceneTracer::new(scene, frame, &opts_v);
        let grid = shade_tiles(n, n, &|_, _| {}, |t, out| {
            let prog = tracer.beam_program(t.x0 as f64, t.y0 as f64, t.x1 as f64, t.y1 as f64);
            for y in t.y0..t.y1 {
                for x in t.x0..t.x1 {
                    let ray = frame.ray(x as f64 + 0.5, y as f64 + 0.5);
                    let s = tracer.trace(&prog, &ray).map(|h| (h.t, h.p));
                    let m = bvh
                        .intersect(&ray, 0.0, f64::INFINITY)
                        .map(|h| (h.t, ray.at(h.t)));
                    let grazing = match (s, m) {
                        (Some((_, p)), None) => {
                            bvh.closest_point(p, tol).is_some_and(|(_, d, _)| d <= tol)
                        }
                        (None, Some((_, q))) => scene.distance(q).abs() <= tol,
                        _ => false,
                    };
                    out.push(PixelPair {
                        sdf: s,
                        mesh: m,
                        grazing,
                    });
                }
            }
        });
        views.push(grid);
    }
    let mut agree = 0usize;
    let mut total = 0usize;
    let mut depths = Vec::new();
    let mut worst: Option<(f64, DVec3)> = None;
    let mut surface_points = Vec::new();
    for grid in &views {
        for px in grid {
            total += 1;
            match (px.sdf, px.mesh) {
                (Some((ts, p)), Some((tm, _))) => {
                    agree += 1;
                    depths.push(((ts - tm).abs(), p));
                    surface_points.push(p);
                }
                (None, None) => agree += 1,
                (Some((_, p)), None) | (None, Some((_, p))) => {
                    if px.sdf.is_some() {
                        surface_points.push(p);
                    }
                    if px.grazing {
                        agree += 1;
                    } else {
                        // The worst is the one farthest from the other surface; lacking
                        // that distance, the first will do.
                        let d = scene.distance(p).abs();
                        if worst.is_none_or(|w| d > w.0) {
                            worst = Some((d, p));
                        }
                    }
                }
            }
        }
    }
    let depth = stats(depths);
    let image = opts.diff_image.then(|| diff_image(&views, n, tol));
    Ok(RayViews {
        stats: RayStats {
            rays: total,
            agreement_pct: 100.0 * agree as f64 / total.max(1) as f64,
            depth_p99: depth.p99,
            depth_max: depth.max,
            worst: worst.map(|w| w.1),
        },
        surface_points,
        image,
    })
}

fn diff_image(views: &[Vec<PixelPair>], n: u32, tol: f64) -> Rgb8 {
    let width = n * views.len() as u32;
    let mut data = vec![0u8; (width * n * 3) as usize];
    for (v, grid) in views.iter().enumerate() {
        for y in 0..n {
            for x in 0..n {
                let px = &grid[(y * n + x) as usize];
                let c = match (px.sdf, px.mesh) {
                    (None, None) => [0.02, 0.02, 0.02],
                    (Some((ts, _)), Some((tm, _))) => {
                        if (ts - tm).abs() > tol {
                            [0.9, 0.8, 0.0]
                        } else {
                            [0.3, 0.3, 0.3]
                        }
                    }
                    _ if px.grazing => [0.1, 0.1, 0.1],
                    (Some(_), None) => [0.9, 0.05, 0.02],
                    (None, Some(_)) => [0.02, 0.2, 0.95],
                };
                let i = (3 * (y * width + v as u32 * n + x)) as usize;
                for k in 0..3 {
                    data[i + k] = encode_srgb(c[k]);
                }
            }
        }
    }
    Rgb8 {
        width,
        height: n,
        data,
    }
}
