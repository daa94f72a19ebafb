//! The lattice of cubic cells a bake samples, from the scene's bounds and the options.

use glam::DVec3;

use super::options::{BakeOptions, MAX_GRID_CELLS, MAX_GRID_TOTAL, MAX_REFINE_STEPS};
use crate::error::{Error, Result};
use crate::geom::Aabb;

/// A lattice of cubic cells.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Grid {
    pub origin: DVec3,
    pub cell: f64,
    /// Cells per axis.
    pub n: [usize; 3],
}

impl Grid {
    /// The grid for a bound and options.
    pub(crate) fn new(solid_box: &Aabb, opts: &BakeOptions) -> Result<Option<Grid>> {
        if opts.refine_steps > MAX_REFINE_STEPS {
            return Err(Error::param(
                "refine_steps",
                opts.refine_steps as f64,
                format!("must be at most {MAX_REFINE_STEPS}"),
            ));
        }
        let Some((region, pad)) = region(solid_box, opts)? else {
            return Ok(None);
        };
        let size = region.size();
        let cell = cell_size(size.max_element(), opts, pad)?;
        let mut n = [0usize; 3];
        for i in 0..3 {
            let cells = (size[i] / cell).ceil().max(1.0) + if pad { 2.0 } else { 0.0 };
            if cells.is_nan() || cells > MAX_GRID_CELLS as f64 {
                return Err(Error::param(
                    "cell",
                    cell,
                    format!(
                        "gives more than {MAX_GRID_CELLS} cells along an axis; use a larger cell"
                    ),
                ));
            }
            n[i] = cells as usize;
        }
        if n.iter().map(|&c| c as u64).product::<u64>() > MAX_GRID_TOTAL {
            return Err(Error::param(
                "cell",
                cell,
                format!("gives more than {MAX_GRID_TOTAL} cells in all; use a larger cell"),
            ));
        }
        let extent = DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64) * cell;
        let origin = region.center() - extent * 0.5;
        Ok(Some(Grid { origin, cell, n }))
    }

    #[inline]
    pub(super) fn point(&self, i: usize, j: usize, k: usize) -> DVec3 {
        self.origin + DVec3::new(i as f64, j as f64, k as f64) * self.cell
    }

    pub(super) fn bbox(&self) -> Aabb {
        Aabb::new(self.origin, self.point(self.n[0], self.n[1], self.n[2]))
    }
}

/// The region to mesh and whether it gets a padding cell on every side: the caller's bounds
/// as they are, or the scene's bounds padded. `None` for an empty scene without bounds.
fn region(solid_box: &Aabb, opts: &BakeOptions) -> Result<Option<(Aabb, bool)>> {
    match opts.region {
        Some(b) => {
            if !(b.min.is_finite() && b.max.is_finite()) || b.is_empty() {
                return Err(Error::param(
                    "bounds",
                    b.diagonal(),
                    "must be a finite, non-empty box",
                ));
            }
            Ok(Some((b, false)))
        }
        None => {
            if solid_box.is_empty() {
                return Ok(None);
            }
            if !(solid_box.min.is_finite() && solid_box.max.is_finite()) {
                return Err(Error::Unbounded {
                    what: "the scene",
                    why: "a half-space not intersected with a bounded shape",
                    remedy: "it has no solid to mesh; intersect the half-space with a bounded \
                             shape (or, in the library, give BakeOptions::region)",
                });
            }
            Ok(Some((*solid_box, true)))
        }
    }
}

/// The cell edge: the options' cell, or the longest side divided by the resolution (the
/// padding cells counting towards it).
fn cell_size(longest: f64, opts: &BakeOptions, pad: bool) -> Result<f64> {
    match (opts.cell, opts.resolution) {
        (Some(h), _) => {
            if !(h.is_finite() && h > 0.0) {
                return Err(Error::param("cell", h, "must be finite and > 0"));
            }
            Ok(h)
        }
        (None, r) => {
            let r = r.unwrap_or(128);
            if !(1..=MAX_GRID_CELLS).contains(&r) {
                return Err(Error::param(
                    "resolution",
                    r as f64,
                    format!("must be in 1..={MAX_GRID_CELLS} cells"),
                ));
            }
            // The padding cells count towards the resolution.
            let inner = if pad { r.saturating_sub(2).max(1) } else { r };
            if longest > 0.0 {
                Ok(longest / inner as f64)
            } else {
                // A degenerate (flat or point) box: any cell will do.
                Ok(1.0)
            }
        }
    }
}
