//! Does a mesh agree with its scene? Four measures, each with a threshold that follows from the
//! tolerance the mesh was made with:
//!
//! - **surface distance**: `|SDF|` at every vertex, every triangle centroid and area-weighted
//!   random points on the mesh: is every point of the mesh on the surface?
//! - **coverage**: the mesh's distance from points where the SDF is zero (camera-ray hits and
//!   random points projected onto the surface along the gradient): is every part of the
//!   surface in the mesh? This catches a deleted part, which the first measure cannot.
//! - **rays**: the same camera rays through both from three views: hit/miss agreement (a ray
//!   that hits one and passes within the tolerance of the other counts as agreeing) and the
//!   depth difference where both hit.
//! - **sign**: inside/outside agreement at random points farther than a band from the surface,
//!   SDF sign against the mesh's ray-crossing parity (majority of three directions).

use glam::DVec3;
use rayon::prelude::*;

use super::bvh::MeshBvh;
use super::camera::{Camera, View, framing_bounds};
use super::image::{Rgb8, encode_srgb};
use super::march::SceneTracer;
use super::render::{RenderOptions, TILE, Tile};
use crate::error::{Error, MeshDefect, Result};
use crate::geom::Aabb;
use crate::mesh::Mesh;
use crate::sdf::Scene;

/// How thorough the check is, and against what tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckOptions {
    /// The distance the mesh may stray from the surface, in scene units: the chordal
    /// tolerance or marching-cubes cell it was made with. `None`: 1/250 of the scene's
    /// bounding diagonal.
    pub tolerance: Option<f64>,
    /// Random points on the mesh, on top of every vertex and triangle centroid.
    pub surface_samples: usize,
    /// Random points projected onto the SDF's surface for coverage (ray hits add more).
    pub coverage_samples: usize,
    /// Side of the square image of rays, per view.
    pub ray_size: u32,
    /// The views rays come from.
    pub views: Vec<View>,
    /// Points tested for inside/outside agreement.
    pub sign_samples: usize,
    /// Seed of the random points (the check is deterministic for a seed).
    pub seed: u64,
    /// Make a difference image of the ray views side by side.
    pub diff_image: bool,
}

impl Default for CheckOptions {
    fn default() -> Self {
        CheckOptions {
            tolerance: None,
            surface_samples: 100_000,
            coverage_samples: 30_000,
            ray_size: 512,
            views: vec![View::Iso, View::Front, View::Top],
            sign_samples: 20_000,
            seed: 0x5eed,
            diff_image: false,
        }
    }
}

/// The limits a mesh must meet, in scene units and percent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckThresholds {
    /// Largest `|SDF|` on the mesh.
    pub surface_max: f64,
    /// 99th percentile of `|SDF|` on the mesh.
    pub surface_p99: f64,
    /// Largest distance from the SDF's surface to the mesh.
    pub coverage_max: f64,
    /// Least share of rays that agree, percent.
    pub ray_agreement_pct: f64,
    /// 99th percentile of depth differences where both hit.
    pub depth_p99: f64,
    /// Least share of points whose inside/outside agree, percent.
    pub sign_pct: f64,
    /// Sign points are this far or farther from the surface.
    pub sign_band: f64,
}

impl CheckThresholds {
    /// The thresholds for a tolerance `tol`: every mesh point within `tol` of the surface and
    /// every surface point within `tol` of the mesh; depths within `4 tol` at the 99th
    /// percentile (a surface moved by `tol` moves `tol / cos θ` along a ray at incidence θ:
    /// 4 allows 75°, and twisted or curved facets seen edge-on are common); all but 0.5 %
    /// of rays and 0.1 % of sign points (taken `2 tol` or farther from the surface) agreeing.
    #[must_use]
    pub fn for_tolerance(tol: f64) -> CheckThresholds {
        CheckThresholds {
            surface_max: tol,
            surface_p99: tol,
            coverage_max: tol,
            ray_agreement_pct: 99.5,
            depth_p99: 4.0 * tol,
            sign_pct: 99.9,
            sign_band: 2.0 * tol,
        }
    }
}

/// Statistics of a distance measure.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DistanceStats {
    /// Points measured.
    pub samples: usize,
    /// Largest distance.
    pub max: f64,
    /// 99th percentile.
    pub p99: f64,
    /// Mean.
    pub mean: f64,
    /// Where the largest distance was measured.
    pub worst: DVec3,
}

/// The ray comparison.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayStats {
    /// Rays cast through both.
    pub rays: usize,
    /// Rays that agree on hit or miss, percent.
    pub agreement_pct: f64,
    /// 99th percentile of depth differences where both hit.
    pub depth_p99: f64,
    /// Largest depth difference where both hit.
    pub depth_max: f64,
    /// A point on the worst disagreeing ray (where the one that hit, hit).
    pub worst: Option<DVec3>,
}

/// The inside/outside comparison.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SignStats {
    /// Points compared.
    pub samples: usize,
    /// Points where both agree, percent.
    pub agreement_pct: f64,
    /// A point where they disagree, the deepest one.
    pub worst: Option<DVec3>,
}

/// The result of [`check_mesh`].
#[derive(Clone, Debug, PartialEq)]
pub struct CheckReport {
    /// The tolerance the thresholds follow from.
    pub tolerance: f64,
    /// The scene's bounding diagonal (distances as a fraction of it: divide).
    pub diagonal: f64,
    /// The limits applied.
    pub thresholds: CheckThresholds,
    /// `|SDF|` on the mesh.
    pub surface: DistanceStats,
    /// Distance of the SDF's surface from the mesh.
    pub coverage: DistanceStats,
    /// Camera rays through both.
    pub rays: RayStats,
    /// Inside/outside agreement.
    pub sign: SignStats,
    /// Each measure out of bounds, with its value, its limit and the worst place.
    pub failures: Vec<String>,
    /// The ray views side by side when asked for: grey where both agree (lighter where both
    /// hit), red where only the SDF hits, blue where only the mesh hits, yellow where depths
    /// differ by more than the tolerance.
    pub diff_image: Option<Rgb8>,
}

impl CheckReport {
    /// True when every measure is within its threshold.
    #[must_use]
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }
}

/// A small deterministic generator (xorshift64*), so checks repeat exactly.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn in_box(&mut self, b: &Aabb) -> DVec3 {
        let s = b.size();
        b.min + DVec3::new(self.next() * s.x, self.next() * s.y, self.next() * s.z)
    }
}

/// Checks that `mesh` is the surface of `scene` (see the module docs for the measures).
/// Fails for an empty or unbounded scene, an empty mesh or out-of-range options; a mesh that
/// disagrees is a report with failures, not an error.
///
/// # Errors
///
/// [`Error::InvalidParameter`](crate::Error::InvalidParameter) or
/// [`Error::Unbounded`](crate::Error::Unbounded) for an empty or unbounded scene, an empty mesh
/// or out-of-range options.
pub fn check_mesh(scene: &Scene, mesh: &Mesh, opts: &CheckOptions) -> Result<CheckReport> {
    let bounds = scene.bbox();
    if bounds.is_empty() {
        return Err(Error::param(
            "scene",
            0.0,
            "the scene is empty: there is no surface to check against",
        ));
    }
    if !(bounds.min.is_finite() && bounds.max.is_finite()) {
        return Err(Error::Unbounded {
            what: "the scene",
            why: "a half-space not intersected with a bounded shape",
            remedy: "only a bounded scene can be checked; intersect the half-space with a \
                     bounded shape",
        });
    }
    let bvh = MeshBvh::build(mesh);
    if bvh.triangle_count() == 0 {
        return Err(Error::mesh(MeshDefect::NoFaces));
    }
    let diagonal = bounds.diagonal();
    let tol = opts.tolerance.unwrap_or(diagonal / 250.0);
    if !(tol > 0.0 && tol.is_finite()) {
        return Err(Error::param(
            "tolerance",
            tol,
            "must be positive and finite",
        ));
    }
    if opts.ray_size == 0 || opts.ray_size > 4096 || opts.views.is_empty() {
        return Err(Error::param(
            "ray_size",
            opts.ray_size as f64,
            "needs 1 to 4096 rays a side and at least one view",
        ));
    }
    let thresholds = CheckThresholds::for_tolerance(tol);
    let surface = surface_distance(scene, mesh, opts);
    let rays = ray_views(scene, &bvh, tol, opts)?;
    let coverage = coverage(scene, &bvh, tol, opts, &rays.surface_points);
    let sign = sign_agreement(scene, &bvh, &bounds, thresholds.sign_band, opts);

    let mut failures = Vec::new();
    let at = |p: DVec3| format!("({:.4}, {:.4}, {:.4})", p.x, p.y, p.z);
    if surface.max > thresholds.surface_max {
        failures.push(format!(
            "surface distance: the mesh strays {:.4} from the surface (limit {:.4}) at {}",
            surface.max,
            thresholds.surface_max,
            at(surface.worst)
        ));
    } else if surface.p99 > thresholds.surface_p99 {
        failures.push(format!(
            "surface distance: p99 {:.4} (limit {:.4}), worst at {}",
            surface.p99,
            thresholds.surface_p99,
            at(surface.worst)
        ));
    }
    if coverage.max > thresholds.coverage_max {
        failures.push(format!(
            "coverage: the surface at {} is {:.4} from the mesh (limit {:.4}): a part is \
             missing or misplaced",
            at(coverage.worst),
            coverage.max,
            thresholds.coverage_max
        ));
    }
    if rays.stats.agreement_pct < thresholds.ray_agreement_pct {
        failures.push(format!(
            "rays: {:.2} % agree on hit or miss (limit {:.2} %){}",
            rays.stats.agreement_pct,
            thresholds.ray_agreement_pct,
            rays.stats
                .worst
                .map(|p| format!(", e.g. at {}", at(p)))
                .unwrap_or_default()
        ));
    }
    if rays.stats.depth_p99 > thresholds.depth_p99 {
        failures.push(format!(
            "rays: depth difference p99 {:.4} (limit {:.4})",
            rays.stats.depth_p99, thresholds.depth_p99
        ));
    }
    if sign.samples > 0 && sign.agreement_pct < thresholds.sign_pct {
        failures.push(format!(
            "sign: inside/outside agree at {:.2} % of points (limit {:.2} %){}",
            sign.agreement_pct,
            thresholds.sign_pct,
            sign.worst
                .map(|p| format!(", e.g. at {}", at(p)))
                .unwrap_or_default()
        ));
    }
    Ok(CheckReport {
        tolerance: tol,
        diagonal,
        thresholds,
        surface,
        coverage,
        rays: rays.stats,
        sign,
        failures,
        diff_image: rays.image,
    })
}

/// Max, p99 and mean of `(value, where)` pairs.
fn stats(mut v: Vec<(f64, DVec3)>) -> DistanceStats {
    if v.is_empty() {
        return DistanceStats::default();
    }
    let n = v.len();
    let mean = v.iter().map(|x| x.0).sum::<f64>() / n as f64;
    let k = ((n as f64 * 0.99).ceil() as usize).clamp(1, n) - 1;
    let (_, p99, _) = v.select_nth_unstable_by(k, |a, b| a.0.total_cmp(&b.0));
    let p99 = p99.0;
    let worst = v
        .iter()
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .copied()
        .unwrap_or_default();
    DistanceStats {
        samples: n,
        max: worst.0,
        p99,
        mean,
        worst: worst.1,
    }
}

fn surface_distance(scene: &Scene, mesh: &Mesh, opts: &CheckOptions) -> DistanceStats {
    let tris: Vec<[DVec3; 3]> = (0..mesh.triangles.len())
        .filter_map(|t| {
            let c = mesh.triangles[t].map(|i| mesh.positions.get(i as usize).copied());
            Some([c[0]?, c[1]?, c[2]?])
        })
        .filter(|c| c.iter().all(|p| p.is_finite()))
        .collect();
    let mut points: Vec<DVec3> = tris.iter().map(|t| (t[0] + t[1] + t[2]) / 3.0).collect();
    points.extend(mesh.positions.iter().filter(|p| p.is_finite()));
    // Area-weighted random points: pick triangles by cumulative area.
    let mut cumulative = Vec::with_capacity(tris.len());
    let mut total = 0.0;
    for t in &tris {
        total += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
        cumulative.push(total);
    }
    if total > 0.0 {
        let mut rng = Rng::new(opts.seed);
        for _ in 0..opts.surface_samples {
            let a = rng.next() * total;
            let i = cumulative.partition_point(|&c| c < a).min(tris.len() - 1);
            let (mut u, mut v) = (rng.next(), rng.next());
            if u + v > 1.0 {
                u = 1.0 - u;
                v = 1.0 - v;
            }
            let t = &tris[i];
            points.push(t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v);
        }
    }
    let values = points
        .par_iter()
        .map(|&p| (scene.distance(p).abs(), p))
        .collect();
    stats(values)
}

struct RayViews {
    stats: RayStats,
    /// SDF hits: points on the surface, for coverage.
    surface_points: Vec<DVec3>,
    image: Option<Rgb8>,
}

/// Per pixel: the SDF's hit and the mesh's hit.
#[derive(Clone, Copy, Default)]
struct PixelPair {
    sdf: Option<(f64, DVec3)>,
    mesh: Option<(f64, DVec3)>,
    /// A one-sided hit passes within the tolerance of the other surface.
    grazing: bool,
}

fn ray_views(scene: &Scene, bvh: &MeshBvh, tol: f64, opts: &CheckOptions) -> Result<RayViews> {
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
        let tiles: Vec<Tile> = (0..n.div_ceil(TILE))
            .flat_map(|ty| {
                (0..n.div_ceil(TILE)).map(move |tx| Tile {
                    x0: tx * TILE,
                    y0: ty * TILE,
                    x1: ((tx + 1) * TILE).min(n),
                    y1: ((ty + 1) * TILE).min(n),
                })
            })
            .collect();
        let pairs: Vec<(Tile, Vec<PixelPair>)> = tiles
            .par_iter()
            .map(|t| {
                let prog = tracer.beam_program(t.x0 as f64, t.y0 as f64, t.x1 as f64, t.y1 as f64);
                let mut out = Vec::with_capacity(t.pixels());
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
                (*t, out)
            })
            .collect();
        let mut grid = vec![PixelPair::default(); (n * n) as usize];
        for (t, out) in pairs {
            let tw = (t.x1 - t.x0) as usize;
            for (row, chunk) in out.chunks(tw).enumerate() {
                let start = (t.y0 as usize + row) * n as usize + t.x0 as usize;
                grid[start..start + tw].copy_from_slice(chunk);
            }
        }
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

fn gradient(scene: &Scene, p: DVec3, h: f64) -> DVec3 {
    let k = [
        DVec3::new(1.0, -1.0, -1.0),
        DVec3::new(-1.0, -1.0, 1.0),
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, 1.0, 1.0),
    ];
    k.iter()
        .map(|&k| k * scene.distance(p + k * h))
        .sum::<DVec3>()
        / (4.0 * h)
}

fn coverage(
    scene: &Scene,
    bvh: &MeshBvh,
    tol: f64,
    opts: &CheckOptions,
    ray_points: &[DVec3],
) -> DistanceStats {
    let region = scene.bbox().expanded(0.05 * scene.bbox().diagonal());
    let mut rng = Rng::new(opts.seed ^ 0xC0FE);
    let starts: Vec<DVec3> = (0..opts.coverage_samples)
        .map(|_| rng.in_box(&region))
        .collect();
    let h = 0.01 * tol;
    // Newton steps along the gradient onto the zero set; points that do not settle are dropped.
    let projected: Vec<DVec3> = starts
        .par_iter()
        .filter_map(|&start| {
            let mut p = start;
            for _ in 0..12 {
                let d = scene.distance(p);
                let g = gradient(scene, p, h);
                let g2 = g.length_squared();
                // Where two solids touch face to face the field is zero on both sides of the
                // contact and its gradient cancels: that sheet is inside the solid, not on its
                // boundary, so such points are dropped.
                if g2.is_nan() || g2 <= 0.25 {
                    return None;
                }
                if d.abs() < 1e-3 * tol {
                    return Some(p);
                }
                p -= g * (d / g2);
            }
            None
        })
        .collect();
    // Ray hits are dense where the views look; thin them to a few per projected point.
    let stride = (ray_points.len() / (3 * opts.coverage_samples).max(1)).max(1);
    let points: Vec<DVec3> = projected
        .into_iter()
        .chain(ray_points.iter().step_by(stride).copied())
        .collect();
    let far = scene.bbox().diagonal() + bvh.bounds().diagonal();
    let values = points
        .par_iter()
        .map(|&p| {
            let d = bvh.closest_point(p, far).map_or(far, |(_, d, _)| d);
            (d, p)
        })
        .collect();
    stats(values)
}

fn sign_agreement(
    scene: &Scene,
    bvh: &MeshBvh,
    bounds: &Aabb,
    band: f64,
    opts: &CheckOptions,
) -> SignStats {
    let region = bounds.expanded(0.1 * bounds.diagonal());
    let mut rng = Rng::new(opts.seed ^ 0x5167);
    // Draw up to four times the wanted count: points inside the band are skipped.
    let candidates: Vec<DVec3> = (0..4 * opts.sign_samples)
        .map(|_| rng.in_box(&region))
        .collect();
    let dirs = [
        DVec3::new(0.5773, 0.5774, 0.5775).normalize(),
        DVec3::new(-0.8017, 0.2673, 0.5345).normalize(),
        DVec3::new(0.1961, -0.9806, 0.0123).normalize(),
    ];
    let results: Vec<Option<(bool, f64, DVec3)>> = candidates
        .par_iter()
        .map(|&p| {
            let d = scene.distance(p);
            if d.abs() <= band {
                return None;
            }
            let votes = dirs
                .iter()
                .filter(|&&dir| bvh.crossings(&super::camera::Ray { origin: p, dir }) % 2 == 1)
                .count();
            let inside_mesh = votes >= 2;
            Some((inside_mesh == (d < 0.0), d.abs(), p))
        })
        .collect();
    let taken: Vec<_> = results
        .into_iter()
        .flatten()
        .take(opts.sign_samples)
        .collect();
    let agree = taken.iter().filter(|r| r.0).count();
    let worst = taken
        .iter()
        .filter(|r| !r.0)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|r| r.2);
    SignStats {
        samples: taken.len(),
        agreement_pct: 100.0 * agree as f64 / taken.len().max(1) as f64,
        worst,
    }
}
