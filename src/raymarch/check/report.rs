//! What a check answers: each measure's statistics, the failures, the report.

use glam::DVec3;

use super::CheckThresholds;
use crate::raymarch::image::Rgb8;

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

/// The result of [`check_mesh`](super::check_mesh).
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

/// Max, p99 and mean of `(value, where)` pairs.
pub(super) fn stats(mut v: Vec<(f64, DVec3)>) -> DistanceStats {
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

/// What the measures say failed, one line each with the worst place: empty when the mesh
/// meets every threshold.
pub(super) fn failures(
    thresholds: &CheckThresholds,
    surface: &DistanceStats,
    coverage: &DistanceStats,
    rays: &RayStats,
    sign: &SignStats,
) -> Vec<String> {
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
    if rays.agreement_pct < thresholds.ray_agreement_pct {
        failures.push(format!(
            "rays: {:.2} % agree on hit or miss (limit {:.2} %){}",
            rays.agreement_pct,
            thresholds.ray_agreement_pct,
            rays.worst
                .map(|p| format!(", e.g. at {}", at(p)))
                .unwrap_or_default()
        ));
    }
    if rays.depth_p99 > thresholds.depth_p99 {
        failures.push(format!(
            "rays: depth difference p99 {:.4} (limit {:.4})",
            rays.depth_p99, thresholds.depth_p99
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
    failures
}
