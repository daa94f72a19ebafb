//! The two distance measures: is every point of the mesh on the surface (`|SDF|` at mesh
//! points), and is every part of the surface in the mesh (the mesh's distance from points the
//! SDF puts on the surface)?

use glam::DVec3;
use rayon::prelude::*;

use super::report::stats;
use super::{CheckOptions, DistanceStats, Rng};
use crate::mesh::Mesh;
use crate::raymarch::bvh::MeshBvh;
use crate::sdf::Scene;

pub(super) fn surface_distance(scene: &Scene, mesh: &Mesh, opts: &CheckOptions) -> DistanceStats {
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

pub(super) fn coverage(
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
