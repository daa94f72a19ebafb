//! Sphere tracing of a scene's distance field, per tile with a pruned program.
//!
//! For each 8×8 tile the program is pruned to the tile's beam between the depths where it meets
//! the scene's box (see `sdf::cull`), each ray is clipped to that box, and marching steps by
//! the field until it falls below the hit threshold. Shadows and occlusion use programs pruned
//! to the sweep of the tile's hit points towards each light and to their neighbourhood.

use glam::DVec3;

use super::camera::{Frame, Ray};
use super::light::shade;
use super::render::{RenderOptions, Tile, clip_to_box, sweep_touches};
use crate::geom::Aabb;
use crate::sdf::{Culler, Pruned, Scene};

/// Penumbra sharpness of the soft shadows (larger: harder).
const PENUMBRA: f64 = 10.0;

/// What a ray found on the surface.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SurfaceHit {
    pub t: f64,
    pub p: DVec3,
    pub normal: DVec3,
    pub material: u32,
}

/// A scene prepared for tracing with one camera.
pub(crate) struct SceneTracer<'a> {
    culler: Culler<'a>,
    scene: &'a Scene,
    pub frame: Frame,
    opts: &'a RenderOptions,
    bounds: Aabb,
    /// Size used for scale-relative lengths (occlusion radius, shadow steps).
    size: f64,
    colors: Vec<DVec3>,
}

impl<'a> SceneTracer<'a> {
    pub fn new(scene: &'a Scene, frame: Frame, opts: &'a RenderOptions) -> SceneTracer<'a> {
        let bounds = scene.bbox();
        let diag = bounds.diagonal();
        let size = if diag.is_finite() && diag > 0.0 {
            diag
        } else {
            // Unbounded: judge by how far the camera looks.
            0.1 * opts.profile.max_distance
        };
        let colors = scene
            .materials()
            .iter()
            .map(|m| DVec3::new(m.base_color[0], m.base_color[1], m.base_color[2]))
            .collect();
        SceneTracer {
            culler: Culler::new(scene),
            scene,
            frame,
            opts,
            bounds,
            size,
            colors,
        }
    }

    fn epsilon(&self, t: f64) -> f64 {
        self.opts
            .profile
            .hit_epsilon
            .max(self.opts.pixel_epsilon * self.frame.footprint(t))
    }

    /// The depths along the view direction between which the scene's box lies.
    fn depth_band(&self) -> Option<(f64, f64)> {
        let max = self.opts.profile.max_distance;
        let b = &self.bounds;
        if b.is_empty() {
            return None;
        }
        if !(b.min.is_finite() && b.max.is_finite()) {
            return Some((0.0, max));
        }
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..8 {
            let c = DVec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            let z = (c - self.frame.eye).dot(self.frame.forward);
            lo = lo.min(z);
            hi = hi.max(z);
        }
        let (lo, hi) = (lo.max(0.0), hi.min(max));
        (lo <= hi).then_some((lo, hi))
    }

    /// The program pruned to the beam of the pixel rectangle `[u0, u1) × [v0, v1)`.
    pub fn beam_program(&self, u0: f64, v0: f64, u1: f64, v1: f64) -> Pruned {
        let Some((z0, z1)) = self.depth_band() else {
            return Pruned::default();
        };
        let (a0, a1) = self.frame.beam(u0, v0, u1, v1, z0, z1);
        let pad = 4.0 * self.epsilon(z1.min(self.opts.profile.max_distance));
        self.culler.prune(pad, |b| sweep_touches(&a0, &a1, b))
    }

    /// Marches one ray with a program pruned to a region holding it.
    pub fn trace(&self, prog: &Pruned, ray: &Ray) -> Option<SurfaceHit> {
        if prog.is_empty() {
            return None;
        }
        let (t0, t1) = clip_to_box(
            ray.origin,
            ray.dir,
            &self.bounds,
            self.opts.profile.max_distance,
        )?;
        let scale = self.opts.step_scale;
        let mut t = t0;
        let mut last = f64::INFINITY;
        for _ in 0..self.opts.profile.max_steps {
            let p = ray.at(t);
            let d = prog.distance(self.scene, p);
            let eps = self.epsilon(t);
            if d < eps {
                return Some(self.hit(prog, ray, t));
            }
            last = d;
            t += d * scale;
            if t > t1 {
                return None;
            }
        }
        // Out of steps while creeping along a surface at a grazing angle: a hit.
        (last < 4.0 * self.epsilon(t)).then(|| self.hit(prog, ray, t))
    }

    fn hit(&self, prog: &Pruned, ray: &Ray, t: f64) -> SurfaceHit {
        let p = ray.at(t);
        let h = 0.5 * self.epsilon(t);
        // The tetrahedron technique: four evaluations at the corners of a regular tetrahedron.
        let k = [
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(-1.0, 1.0, -1.0),
            DVec3::new(1.0, 1.0, 1.0),
        ];
        let g: DVec3 = k
            .iter()
            .map(|&k| k * prog.distance(self.scene, p + k * h))
            .sum();
        let normal = g.try_normalize().unwrap_or(-ray.dir);
        let material = prog.distance_material(self.scene, p).1;
        SurfaceHit {
            t,
            p,
            normal,
            material,
        }
    }

    fn color(&self, material: u32) -> DVec3 {
        self.colors
            .get(material as usize)
            .copied()
            .unwrap_or(DVec3::new(
                crate::mesh::Material::DEFAULT_COLOR[0],
                crate::mesh::Material::DEFAULT_COLOR[1],
                crate::mesh::Material::DEFAULT_COLOR[2],
            ))
    }

    /// Renders one tile into `out`, row by row.
    pub fn render_tile(&self, tile: &Tile, out: &mut Vec<DVec3>) {
        let bg = self.opts.background();
        let prog = self.beam_program(
            tile.x0 as f64,
            tile.y0 as f64,
            tile.x1 as f64,
            tile.y1 as f64,
        );
        if prog.is_empty() {
            out.resize(tile.pixels(), bg);
            return;
        }
        let mut hits = Vec::with_capacity(tile.pixels());
        let mut hit_box = Aabb::EMPTY;
        for y in tile.y0..tile.y1 {
            for x in tile.x0..tile.x1 {
                let ray = self.frame.ray(x as f64 + 0.5, y as f64 + 0.5);
                let h = self.trace(&prog, &ray);
                if let Some(h) = &h {
                    hit_box.grow(h.p);
                }
                hits.push(h);
            }
        }
        if hit_box.is_empty() {
            out.resize(tile.pixels(), bg);
            return;
        }
        let profile = &self.opts.profile;
        let eps = self.epsilon(self.frame.eye.distance(hit_box.center()));
        // Penumbrae come from within a few percent of the scene's size of the shadow ray.
        let pad = 0.02 * self.size + 4.0 * eps;
        let shadow_progs: Vec<Pruned> = if profile.shadow_steps > 0 {
            self.opts
                .lights
                .iter()
                .map(|l| {
                    let (dir, dist) = l.towards(hit_box.center());
                    let far = if dist.is_finite() {
                        // The light's position.
                        let to = hit_box.center() + dir * dist;
                        Aabb::new(to, to)
                    } else {
                        let reach = self.bounds.union(&hit_box).diagonal();
                        let reach = if reach.is_finite() {
                            reach
                        } else {
                            profile.max_distance
                        };
                        Aabb::new(hit_box.min + dir * reach, hit_box.max + dir * reach)
                    };
                    let near = hit_box.expanded(pad);
                    self.culler
                        .prune(pad, |b| sweep_touches(&near, &far.expanded(pad), b))
                })
                .collect()
        } else {
            Vec::new()
        };
        let ao_len = 0.04 * self.size;
        let ao_prog = if profile.ao_steps > 0 {
            let b = hit_box.expanded(ao_len + 4.0 * eps);
            self.culler.prune(0.0, |x| x.overlaps(&b, 0.0))
        } else {
            Pruned::default()
        };
        for h in hits {
            let Some(h) = h else {
                out.push(bg);
                continue;
            };
            let eps = self.epsilon(h.t);
            let occlusion = if profile.ao_steps > 0 {
                self.occlusion(&ao_prog, h.p, h.normal, ao_len, profile.ao_steps)
            } else {
                1.0
            };
            let base = self.color(h.material);
            let c = shade(
                base,
                self.opts.ambient,
                occlusion,
                h.normal,
                h.p,
                &self.opts.lights,
                |i, dir, dist| {
                    if profile.shadow_steps == 0 {
                        return 1.0;
                    }
                    self.soft_shadow(
                        &shadow_progs[i],
                        h.p + h.normal * (2.0 * eps),
                        dir,
                        dist,
                        eps,
                    )
                },
            );
            out.push(c);
        }
    }

    /// Soft shadow by the penumbra estimate: the least `k · d / t` along the march to the light.
    fn soft_shadow(&self, prog: &Pruned, origin: DVec3, dir: DVec3, dist: f64, eps: f64) -> f64 {
        if prog.is_empty() {
            return 1.0;
        }
        let steps = self.opts.profile.shadow_steps;
        let exit = clip_to_box(origin, dir, &self.bounds, self.opts.profile.max_distance)
            .map_or(0.0, |(_, f)| f);
        let t_max = exit.min(dist);
        let min_step = self.size / (4.0 * steps as f64);
        let mut res: f64 = 1.0;
        let mut t = 2.0 * eps;
        for _ in 0..steps {
            if t >= t_max {
                break;
            }
            let d = prog.distance(self.scene, origin + dir * t);
            if d < 0.5 * eps {
                return 0.0;
            }
            res = res.min(PENUMBRA * d / t);
            t += d.max(min_step);
        }
        let r = res.clamp(0.0, 1.0);
        r * r * (3.0 - 2.0 * r)
    }

    /// Ambient occlusion from `steps` samples along the normal up to `len`.
    fn occlusion(&self, prog: &Pruned, p: DVec3, n: DVec3, len: f64, steps: u32) -> f64 {
        if prog.is_empty() {
            return 1.0;
        }
        let (mut occ, mut w, mut wsum) = (0.0, 1.0, 0.0);
        for i in 1..=steps {
            let h = len * i as f64 / steps as f64;
            let d = prog.distance(self.scene, p + n * h);
            occ += w * ((h - d) / h).clamp(0.0, 1.0);
            wsum += w;
            w *= 0.7;
        }
        (1.0 - occ / wsum).clamp(0.0, 1.0)
    }
}
