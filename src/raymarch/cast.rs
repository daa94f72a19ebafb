//! Ray casting of a triangle mesh through its BVH: the same camera, lights and shading model as
//! the sphere tracer, hard shadows by shadow rays, occlusion by short rays around the normal.

use glam::DVec3;

use super::bvh::MeshBvh;
use super::camera::{Frame, Ray};
use super::light::shade;
use super::normals::{corner_normals, corners};
use super::render::{RenderOptions, Shading, Tile};
use crate::mesh::{Material, Mesh};

/// A mesh prepared for casting.
pub(crate) struct MeshTracer<'a> {
    mesh: &'a Mesh,
    bvh: &'a MeshBvh,
    pub frame: Frame,
    opts: &'a RenderOptions,
    /// Per triangle corner, split at creases (empty for flat shading).
    corner_normals: Vec<[DVec3; 3]>,
    colors: Vec<DVec3>,
    /// Offset of secondary rays from the surface.
    bias: f64,
    ao_len: f64,
}

impl<'a> MeshTracer<'a> {
    pub fn new(
        mesh: &'a Mesh,
        bvh: &'a MeshBvh,
        materials: &[Material],
        frame: Frame,
        opts: &'a RenderOptions,
    ) -> MeshTracer<'a> {
        let corner_normals = if opts.shading == Shading::Smooth {
            corner_normals(mesh)
        } else {
            Vec::new()
        };
        let colors = (0..=mesh.sources.iter().copied().max().unwrap_or(0))
            .map(|s| {
                let c = materials
                    .get(s as usize)
                    .map_or(Material::DEFAULT_COLOR, |m| m.base_color);
                DVec3::new(c[0], c[1], c[2])
            })
            .collect();
        let size = bvh.bounds().diagonal();
        let bias = 1e-7 * size + 1e-12 * bvh.bounds().max_abs();
        MeshTracer {
            mesh,
            bvh,
            frame,
            opts,
            corner_normals,
            colors,
            bias,
            ao_len: 0.04 * size,
        }
    }

    /// The shading normal at a hit, facing the ray.
    fn normal(&self, triangle: u32, uv: (f64, f64), dir: DVec3) -> DVec3 {
        let t = triangle as usize;
        let Some(c) = corners(self.mesh, &self.mesh.triangles[t]) else {
            return -dir;
        };
        let face = (c[1] - c[0]).cross(c[2] - c[0]).normalize_or_zero();
        let mut n = face;
        if let Some(&[a, b, cc]) = self.corner_normals.get(t) {
            let s = a * (1.0 - uv.0 - uv.1) + b * uv.0 + cc * uv.1;
            n = s.try_normalize().unwrap_or(face);
        }
        // Open meshes show their back faces: light them as seen.
        if n.dot(dir) > 0.0 { -n } else { n }
    }

    /// Renders one tile into `out`, row by row.
    pub fn render_tile(&self, tile: &Tile, out: &mut Vec<DVec3>) {
        let bg = self.opts.background();
        let profile = &self.opts.profile;
        for y in tile.y0..tile.y1 {
            for x in tile.x0..tile.x1 {
                let ray = self.frame.ray(x as f64 + 0.5, y as f64 + 0.5);
                let Some(hit) = self.bvh.intersect(&ray, 0.0, f64::INFINITY) else {
                    out.push(bg);
                    continue;
                };
                let p = ray.at(hit.t);
                let n = self.normal(hit.triangle, hit.uv, ray.dir);
                let src = self
                    .mesh
                    .sources
                    .get(hit.triangle as usize)
                    .copied()
                    .unwrap_or(0);
                let base = self.colors.get(src as usize).copied().unwrap_or(DVec3::ONE);
                let origin = p + n * (self.bias + 1e-9 * hit.t);
                let occlusion = if profile.ao_steps > 0 {
                    self.occlusion(origin, n, profile.ao_steps)
                } else {
                    1.0
                };
                let c = shade(
                    base,
                    self.opts.ambient,
                    occlusion,
                    n,
                    p,
                    &self.opts.lights,
                    |_, dir, dist| {
                        if profile.shadow_steps == 0 {
                            return 1.0;
                        }
                        let r = Ray { origin, dir };
                        if self.bvh.occluded(&r, 0.0, dist) {
                            0.0
                        } else {
                            1.0
                        }
                    },
                );
                out.push(c);
            }
        }
    }

    /// The fraction of `steps` short rays around the normal that escape within `ao_len`.
    fn occlusion(&self, origin: DVec3, n: DVec3, steps: u32) -> f64 {
        let (t1, t2) = n.any_orthonormal_pair();
        let mut open = 0.0;
        // A fixed spiral over the hemisphere, denser towards the normal (cosine-weighted).
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        for i in 0..steps {
            let r2 = (i as f64 + 0.5) / steps as f64;
            let phi = golden * i as f64;
            let (s, c) = phi.sin_cos();
            let r = r2.sqrt();
            let dir = (t1 * (r * c) + t2 * (r * s) + n * (1.0 - r2).sqrt()).normalize();
            if !self.bvh.occluded(&Ray { origin, dir }, 0.0, self.ao_len) {
                open += 1.0;
            }
        }
        open / steps as f64
    }
}
