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
//!
//! `options.rs` holds what is asked ([`CheckOptions`], [`CheckThresholds`]), `report.rs` what is
//! answered; one file per measure: `surface.rs` (surface distance and coverage), `rays.rs`,
//! `sign.rs`.

use glam::DVec3;

use super::bvh::MeshBvh;
use crate::error::{Error, MeshDefect, Result};
use crate::geom::Aabb;
use crate::mesh::Mesh;
use crate::sdf::Scene;

mod options;
mod rays;
mod report;
mod sign;
mod surface;

pub use options::{CheckOptions, CheckThresholds};
pub use report::{CheckReport, DistanceStats, RayStats, SignStats};

use rays::ray_views;
use report::failures;
use sign::sign_agreement;
use surface::{coverage, surface_distance};

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

    let failures = failures(&thresholds, &surface, &coverage, &rays.stats, &sign);
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
