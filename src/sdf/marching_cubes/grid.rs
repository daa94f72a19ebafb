//! The lattice of cubic cells a bake samples, from the scene's bounds and the options.

use glam::DVec3;

use super::options::{BakeOptions, MAX_GRID_CELLS, MAX_GRID_TOTAL, MAX_REFINE_STEPS};
use crate::error::{Error, Result};
use crate::geom::{Aabb, MAX_MOVE};

/// A block of cubic cells on a lattice: grid point `(i, j, k)` is lattice point
/// `first + (i, j, k)`, at `anchor + (first + (i, j, k)) · cell`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Grid {
    /// Lattice point 0.
    pub anchor: DVec3,
    /// The lattice index of grid point `(0, 0, 0)`.
    pub first: [i64; 3],
    pub cell: f64,
    /// Cells per axis.
    pub n: [usize; 3],
    /// Values inside by less than this count as outside (see `leaf::sample`):
    /// [`MAX_MOVE`] times the lattice's extent, the same for every grid of one lattice.
    pub hair: f64,
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
        let cell = cell_size(region.size().max_element(), opts, pad)?;
        let lattice = Lattice::laid(&region, cell, pad);
        let mut n = [0usize; 3];
        for (n, &cells) in n.iter_mut().zip(&lattice.cells) {
            *n = checked_cells(cells, cell)?;
        }
        check_total(&n, cell)?;
        Ok(Some(Grid {
            anchor: lattice.anchor,
            first: [0; 3],
            cell,
            n,
            hair: lattice.hair,
        }))
    }

    /// Grid point `(i, j, k)`: computed from its lattice index alone, the same way in every
    /// grid of the lattice.
    #[inline]
    pub(super) fn point(&self, i: usize, j: usize, k: usize) -> DVec3 {
        let at = |x: usize, a: usize| (self.first[a] + x as i64) as f64;
        self.anchor + DVec3::new(at(i, 0), at(j, 1), at(k, 2)) * self.cell
    }

    pub(super) fn bbox(&self) -> Aabb {
        Aabb::new(
            self.point(0, 0, 0),
            self.point(self.n[0], self.n[1], self.n[2]),
        )
    }
}

/// The lattice [`Grid::new`] lays over a region, unbounded: `anchor + (i, j, k) · cell` for
/// every integer `i, j, k`, with the extent of that grid (`cells` per axis from the anchor).
/// Grids on part of it ([`Lattice::around`]) sample their shared points bit for bit alike.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lattice {
    anchor: DVec3,
    cell: f64,
    /// Cells per axis of the grid over the whole region (whole numbers).
    cells: [f64; 3],
    /// [`Grid::hair`] of that grid.
    hair: f64,
}

impl Lattice {
    /// The lattice of the grid [`Grid::new`] makes for `region` without options' bounds (the
    /// region padded by a cell on every side, centred), cell `cell`: unchecked, so a fine cell
    /// over a large region still lays a lattice whose small parts may be gridded. Its hair is
    /// that grid's, but at most that of the largest grid a bake may have
    /// ([`MAX_GRID_CELLS`] along each axis, 0.028 of a cell): a small part baked on a
    /// lattice far wider than any grid loses no more to the hair than on a grid of its own.
    pub(crate) fn over(region: &Aabb, cell: f64) -> Result<Lattice> {
        if !(cell.is_finite() && cell > 0.0) {
            return Err(Error::param("cell", cell, "must be finite and > 0"));
        }
        let mut lattice = Lattice::laid(region, cell, true);
        let widest = MAX_GRID_CELLS as f64 * 3f64.sqrt() * cell;
        lattice.hair = lattice.hair.min(MAX_MOVE * widest);
        Ok(lattice)
    }

    /// The lattice of `region` with cells of `cell`, padded or not (the one layout of
    /// [`Grid::new`]).
    fn laid(region: &Aabb, cell: f64, pad: bool) -> Lattice {
        let size = region.size();
        let cells =
            [0, 1, 2].map(|i| (size[i] / cell).ceil().max(1.0) + if pad { 2.0 } else { 0.0 });
        let extent = DVec3::from(cells) * cell;
        let anchor = region.center() - extent * 0.5;
        let hair = MAX_MOVE * Aabb::new(anchor, anchor + extent).diagonal();
        Lattice {
            anchor,
            cell,
            cells,
            hair,
        }
    }

    /// The grid on this lattice that covers `region` with a cell to spare on every side, as
    /// far as the lattice's own grid reaches: every point of it is that grid's point of the
    /// same index, computed alike, so two bakes on one lattice give bit-identical vertices
    /// where their fields agree. `None` for an empty region.
    pub(crate) fn around(&self, region: &Aabb) -> Result<Option<Grid>> {
        if region.is_empty() {
            return Ok(None);
        }
        let cell = self.cell;
        let mut first = [0i64; 3];
        let mut n = [0usize; 3];
        for i in 0..3 {
            let lo = (((region.min[i] - self.anchor[i]) / cell).floor() - 1.0).max(0.0);
            let hi = (((region.max[i] - self.anchor[i]) / cell).ceil() + 1.0).min(self.cells[i]);
            // Indices beyond 2⁵² would no longer give points exactly: refused as too many
            // cells, as a NaN is.
            let cells = if hi <= (1u64 << 52) as f64 {
                (hi - lo).max(1.0)
            } else {
                f64::NAN
            };
            n[i] = checked_cells(cells, cell)?;
            first[i] = lo as i64;
        }
        check_total(&n, cell)?;
        Ok(Some(Grid {
            anchor: self.anchor,
            first,
            cell,
            n,
            hair: self.hair,
        }))
    }
}

/// `cells` along an axis as a count, refused beyond [`MAX_GRID_CELLS`] (or NaN).
fn checked_cells(cells: f64, cell: f64) -> Result<usize> {
    if cells.is_nan() || cells > MAX_GRID_CELLS as f64 {
        return Err(Error::param(
            "cell",
            cell,
            format!("gives more than {MAX_GRID_CELLS} cells along an axis; use a larger cell"),
        ));
    }
    Ok(cells as usize)
}

/// Refuses a grid of more than [`MAX_GRID_TOTAL`] cells.
fn check_total(n: &[usize; 3], cell: f64) -> Result<()> {
    if n.iter().map(|&c| c as u64).product::<u64>() > MAX_GRID_TOTAL {
        return Err(Error::param(
            "cell",
            cell,
            format!("gives more than {MAX_GRID_TOTAL} cells in all; use a larger cell"),
        ));
    }
    Ok(())
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The lattice over a region reproduces the grid `Grid::new` lays there, point for point;
    /// grids around two parts of it sample their shared points bit for bit alike.
    #[test]
    fn grids_on_one_lattice_share_their_points() {
        let scene = Aabb::new(DVec3::new(-1.3, -0.7, 0.1), DVec3::new(2.9, 1.7, 3.3));
        let cell = 0.137;
        let whole = Grid::new(&scene, &BakeOptions::with_cell(cell))
            .unwrap()
            .unwrap();
        let lattice = Lattice::over(&scene, cell).unwrap();
        let same = lattice.around(&scene).unwrap().unwrap();
        assert_eq!(
            (same.first, same.n, same.hair),
            ([0; 3], whole.n, whole.hair)
        );
        let a = lattice
            .around(&Aabb::new(
                DVec3::new(-1.0, -0.5, 0.2),
                DVec3::new(0.4, 0.3, 1.9),
            ))
            .unwrap()
            .unwrap();
        let b = lattice
            .around(&Aabb::new(
                DVec3::new(0.1, -0.2, 1.0),
                DVec3::new(2.0, 1.1, 3.0),
            ))
            .unwrap()
            .unwrap();
        let mut shared = 0;
        for i in 0..=a.n[0] {
            for j in 0..=a.n[1] {
                for k in 0..=a.n[2] {
                    let at = [i, j, k].map(|x| x as i64);
                    let global = [0, 1, 2].map(|x| a.first[x] + at[x]);
                    assert_eq!(
                        a.point(i, j, k),
                        whole.point(global[0] as usize, global[1] as usize, global[2] as usize,)
                    );
                    let local = [0, 1, 2].map(|x| global[x] - b.first[x]);
                    if (0..3).all(|x| local[x] >= 0 && local[x] <= b.n[x] as i64) {
                        let q = local.map(|x| x as usize);
                        assert_eq!(a.point(i, j, k), b.point(q[0], q[1], q[2]));
                        shared += 1;
                    }
                }
            }
        }
        assert!(shared > 0);
    }
}
