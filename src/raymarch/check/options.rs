//! What a check is asked: how thorough, against what tolerance, and the limits that follow.

use crate::raymarch::camera::View;

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
