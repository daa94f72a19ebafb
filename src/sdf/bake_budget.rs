//! The work budget of a bake: a 2D polygon's distance visits every edge, so a bake of a
//! 10,000-point outline extruded costs 10,000 times a box's at every grid point. Estimated
//! from the grid and the outlines before any point is sampled.

use super::eval::Program;
use super::marching_cubes::Grid;
use super::shapes::Shape;
use super::shapes2d::{Prim2, Shape2};
use crate::error::{Error, Result};

/// The most outline work a bake takes on: grid points times the points of every 2D polygon
/// outline the field evaluates at each (extruded or revolved polygons and regular polygons;
/// other primitives cost a few operations and are bounded by the grid budget alone). 2³²:
/// about a minute on a 2-core machine (one 1,000-point outline at the default 128 cells
/// across, 10⁹, takes 5–15 s). An upper bound: the octree skips blocks far from the surface,
/// so a sparse scene does less.
pub const MAX_BAKE_WORK: u64 = 1 << 32;

/// Refuses a bake of `program` on `grid` whose outline work exceeds [`MAX_BAKE_WORK`], naming
/// a cell that fits.
pub(crate) fn check_bake_work(program: &Program, grid: &Grid) -> Result<()> {
    let outline: u64 = program
        .leaves
        .iter()
        .map(|leaf| match &leaf.shape {
            Shape::Extrude(e) => outline_points(&e.shape),
            Shape::Revolve { shape, .. } => outline_points(shape),
            _ => 0,
        })
        .fold(0, u64::saturating_add);
    let points = grid
        .n
        .iter()
        .map(|&n| n as u64 + 1)
        .fold(1, u64::saturating_mul);
    let work = points.saturating_mul(outline);
    if work <= MAX_BAKE_WORK {
        return Ok(());
    }
    // Grid points go as 1/cell³.
    let enough = grid.cell * (work as f64 / MAX_BAKE_WORK as f64).cbrt();
    Err(Error::param(
        "cell",
        grid.cell,
        format!(
            "{points} grid points, each evaluating 2D outlines of {outline} points in all: about \
             {work} units of work, more than the budget of {MAX_BAKE_WORK} (about a minute); use \
             a cell of at least {enough:.3e}, outlines of fewer points, or the BSP route \
             (--via bsp), which takes polygons as they are"
        ),
    ))
}

/// Points of the polygon outlines of a 2D shape (the primitives whose distance visits every
/// edge).
fn outline_points(shape: &Shape2) -> u64 {
    shape
        .parts()
        .0
        .iter()
        .map(|(prim, _)| match prim {
            Prim2::Polygon { points } | Prim2::RegularPolygon { points, .. } => points.len() as u64,
            _ => 0,
        })
        .sum()
}
