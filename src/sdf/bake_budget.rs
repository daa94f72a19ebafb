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
/// a cell that fits: `grid_at(cell)` is the grid the bake would lay with that cell.
pub(crate) fn check_bake_work(
    program: &Program,
    grid: &Grid,
    grid_at: impl Fn(f64) -> Result<Option<Grid>>,
) -> Result<()> {
    let outline: u64 = program
        .leaves
        .iter()
        .map(|leaf| match &leaf.shape {
            Shape::Extrude(e) => outline_points(&e.shape),
            Shape::Revolve { shape, .. } => outline_points(shape),
            _ => 0,
        })
        .fold(0, u64::saturating_add);
    let points = grid_points(grid);
    let work = points.saturating_mul(outline);
    if work <= MAX_BAKE_WORK {
        return Ok(());
    }
    let cell = cell_that_fits(grid, outline, grid_at)
        .map(|c| format!("a cell of at least {c:.3e}, "))
        .unwrap_or_default();
    Err(Error::param(
        "cell",
        grid.cell,
        format!(
            "{points} grid points, each evaluating 2D outlines of {outline} points in all: about \
             {work} units of work, more than the budget of {MAX_BAKE_WORK} (about a minute); use \
             {cell}outlines of fewer points, or the BSP route (--via bsp), which takes polygons \
             as they are"
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

fn grid_points(grid: &Grid) -> u64 {
    grid.n
        .iter()
        .map(|&n| n as u64 + 1)
        .fold(1, u64::saturating_mul)
}

/// A cell whose grid (`grid_at`) keeps `outline` points' work within the budget, rounded up to
/// the four digits the message shows. Grid points go as 1/cell³, but each axis also has its
/// padding cells and the rounding of the region to whole cells, so the cube root alone named
/// cells that were refused in turn (2.260e-2 for a 10,000-point outline, which needs
/// 2.283e-2): the cell is raised until the grid it lays fits. `None` where none does in 64
/// steps (outlines so long that a grid of a few cells is over the budget).
fn cell_that_fits(
    grid: &Grid,
    outline: u64,
    grid_at: impl Fn(f64) -> Result<Option<Grid>>,
) -> Option<f64> {
    let work = |g: &Grid| grid_points(g).saturating_mul(outline);
    let over = |g: &Grid| work(g) as f64 / MAX_BAKE_WORK as f64;
    let mut cell = grid.cell * over(grid).cbrt();
    for _ in 0..64 {
        let shown = round_up(cell);
        let Ok(Some(g)) = grid_at(shown) else {
            return None;
        };
        if work(&g) <= MAX_BAKE_WORK {
            return Some(shown);
        }
        cell = shown * over(&g).cbrt().max(1.0 + 1e-3);
    }
    None
}

/// `x` rounded up to four significant digits, as `{:.3e}` shows it (the value shown, so the
/// cell checked is the cell named).
fn round_up(x: f64) -> f64 {
    let unit = 10f64.powi(x.log10().floor() as i32 - 3);
    let mut up = (x / unit).ceil() * unit;
    loop {
        let shown: f64 = format!("{up:.3e}").parse().unwrap_or(up);
        if shown >= x {
            return shown;
        }
        up += unit;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sdf::{BakeOptions, Scene};

    /// One extruded outline of `n` points (a wavy ring about 2 across).
    fn outline_scene(n: u32) -> Scene {
        let points: Vec<String> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
                let r = 1.0 + 0.05 * (37.0 * a).sin();
                format!("[{:.6},{:.6}]", r * a.cos(), r * a.sin())
            })
            .collect();
        Scene::from_json_str(&format!(
            r#"{{"kind":"sdf_scene","version":1,"tree":{{"op":"extrude","extrude_depth":1,"source_2d_sdf":{{"type":"polygon","points":[{}]}}}}}}"#,
            points.join(",")
        ))
        .unwrap()
    }

    /// The cell a refusal names is one the budget takes: a 10,000-point outline at the
    /// default 128 cells across was told "a cell of at least 2.260e-2", which was refused in
    /// turn (442,368 grid points); each outline length here must name a cell whose own grid
    /// fits, and a cell a little finer must not.
    #[test]
    fn the_cell_a_refusal_names_fits_the_budget() {
        for n in [5_000, 7_500, 10_000] {
            let scene = outline_scene(n);
            let grid_at = |cell: f64| Grid::new(&scene.bound.bbox, &BakeOptions::with_cell(cell));
            let grid = Grid::new(&scene.bound.bbox, &BakeOptions::default())
                .unwrap()
                .unwrap();
            let err = check_bake_work(&scene.program, &grid, grid_at).unwrap_err();
            let named: f64 = err
                .to_string()
                .split("a cell of at least ")
                .nth(1)
                .and_then(|r| r.split(',').next())
                .unwrap()
                .parse()
                .unwrap();
            let fits = |c: f64| {
                let g = grid_at(c).unwrap().unwrap();
                check_bake_work(&scene.program, &g, grid_at).is_ok()
            };
            assert!(fits(named), "{n} points: named {named:e}: {err}");
            assert!(
                !fits(named * 0.99),
                "{n} points: {named:e} is far from the least"
            );
        }
    }
}
