//! The sign measure: inside/outside agreement at random points away from the surface, the
//! SDF's sign against the mesh's ray-crossing parity.

use glam::DVec3;
use rayon::prelude::*;

use super::{CheckOptions, Rng, SignStats};
use crate::geom::Aabb;
use crate::raymarch::bvh::MeshBvh;
use crate::sdf::Scene;

pub(super) fn sign_agreement(
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
                .filter(|&&dir| {
                    bvh.crossings(&crate::raymarch::camera::Ray { origin: p, dir }) % 2 == 1
                })
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
