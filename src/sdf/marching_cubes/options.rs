//! What a bake may ask for: [`BakeOptions`] and the limits it is checked against.

use crate::geom::Aabb;

/// How to bake a scene into a mesh by marching cubes.
#[derive(Clone, Debug, PartialEq)]
pub struct BakeOptions {
    /// Edge length of the grid's cubic cells. Takes precedence over `resolution`.
    pub cell: Option<f64>,
    /// Cells along the longest side of the bounds (used when `cell` is `None`); 128 when both
    /// are `None`.
    pub resolution: Option<u32>,
    /// The region to mesh. `None`: the scene's conservative bounds plus one cell on every side.
    /// A surface cut by these bounds is closed by a cap on them.
    pub region: Option<Aabb>,
    /// Steps of root refinement (Illinois regula falsi) per vertex after the linear guess, at
    /// most [`MAX_REFINE_STEPS`] (it converges in a handful).
    pub refine_steps: u32,
}

impl Default for BakeOptions {
    fn default() -> Self {
        BakeOptions {
            cell: None,
            resolution: None,
            region: None,
            refine_steps: 3,
        }
    }
}

impl BakeOptions {
    /// Options with a cell size.
    #[must_use]
    pub fn with_cell(cell: f64) -> Self {
        BakeOptions {
            cell: Some(cell),
            ..Default::default()
        }
    }

    /// Options with a resolution (cells along the longest side).
    #[must_use]
    pub fn with_resolution(resolution: u32) -> Self {
        BakeOptions {
            resolution: Some(resolution),
            ..Default::default()
        }
    }
}

/// The most cells along one axis of a grid. Work and memory grow with the surface's area in
/// cells, not with the grid's volume, but a grid this fine around a large surface still needs
/// gigabytes.
pub const MAX_GRID_CELLS: u32 = 1 << 14;

/// The most cells a grid may have in all (1024³): a large surface in a grid this fine already
/// makes tens of millions of triangles, so finer requests are refused before memory runs out.
pub const MAX_GRID_TOTAL: u64 = 1 << 30;

/// The most root-refinement steps a bake accepts.
pub const MAX_REFINE_STEPS: u32 = 64;

/// The most triangles one bake may make (about 2 GB of mesh). Cells bound the grid's volume,
/// not its surface: a flat surface across a fine grid would otherwise exhaust memory.
pub const MAX_BAKE_TRIANGLES: usize = 1 << 25;
