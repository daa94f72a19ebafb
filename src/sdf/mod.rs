//! Scenes as trees of signed distance functions: the seed spec's JSON format
//! (`docs/scene-format.md`), exact distance functions, and two ways to a mesh — marching cubes
//! ([`Scene::bake`]) and the BSP kernel ([`Scene::to_solid`]).
//!
//! ```text
//! scene JSON ──► Tree (arena) ──► Program (flattened, world units) ──┬─► distance / material
//!                                                                    └─► marching cubes ─► Mesh
//!            └─► tessellated primitives ─► BSP booleans (smooth subtrees baked) ─► Solid
//! ```

mod bake_budget;
mod bsp_route;
mod cull;
mod eval;
mod extrusion;
mod marching_cubes;
mod scene;
mod shapes;
mod shapes2d;
mod tree;

use rayon::prelude::*;

pub use bake_budget::MAX_BAKE_WORK;
pub use bsp_route::{DEFAULT_MAX_ANGLE, MAX_SCENE_POLYGONS, MAX_SCENE_WORK, TessellationOptions};
pub(crate) use cull::{Culler, Pruned};
pub use marching_cubes::{
    BakeOptions, MAX_BAKE_TRIANGLES, MAX_GRID_CELLS, MAX_GRID_TOTAL, MAX_REFINE_STEPS,
};
pub use scene::{
    DEFAULT_FOV_DEG, Light, LightKind, MAX_POLYGON_POINTS, MAX_SCENE_MAGNITUDE, Projection,
    RenderProfile, Scene, SceneCamera,
};

use crate::error::Result;
use crate::mesh::Mesh;
use eval::Scratch;
pub(crate) use eval::{Instr, Op, Program};
pub(crate) use shapes::Shape;
pub(crate) use shapes2d::{Instr2, Place2, Prim2, Shape2};
pub(crate) use tree::SmoothKind;

impl Scene {
    /// Bakes the scene into a closed, consistently oriented triangle mesh by marching cubes,
    /// each triangle carrying the material of the primitive that decides the surface there.
    ///
    /// Empty scenes give an empty mesh. Fails for an unbounded scene without
    /// [`BakeOptions::region`], or for a cell or resolution out of range.
    ///
    /// ```
    /// use bspcsg::{BakeOptions, Scene};
    /// let s = Scene::from_json_str(
    ///     r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#,
    /// )?;
    /// let mesh = s.bake(&BakeOptions::with_cell(0.1))?;
    /// assert!((mesh.volume() - 4.18879).abs() < 0.03);
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::Unbounded`](crate::Error::Unbounded) for an unbounded scene without [`BakeOptions::region`](crate::BakeOptions::region),
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for a cell, resolution, region or refinement out of range or
    /// a surface that needs more than [`MAX_BAKE_TRIANGLES`] triangles.
    pub fn bake(&self, opts: &BakeOptions) -> Result<Mesh> {
        let Some(grid) = marching_cubes::Grid::new(&self.bound.bbox, opts)? else {
            return Ok(Mesh::default());
        };
        bake_budget::check_bake_work(&self.program, &grid, |cell| {
            let opts = BakeOptions {
                cell: Some(cell),
                ..opts.clone()
            };
            marching_cubes::Grid::new(&self.bound.bbox, &opts)
        })?;
        let mut mesh = marching_cubes::march(
            &self.program,
            grid,
            marching_cubes::Refine::Steps(opts.refine_steps),
        )?;
        assign_sources(&self.program, &mut mesh);
        // Where the surface passes within a hair of a grid vertex, the triangles of the cells
        // around it shrink to specks: flipped or collapsed away, the mesh staying closed.
        crate::mesh::needles::remove_needles(&mut mesh, None, None);
        Ok(mesh)
    }
}

/// Sets each triangle's source to the material deciding the field at its centroid.
pub(crate) fn assign_sources(program: &Program, mesh: &mut Mesh) {
    let mut ids = program.materials();
    let first = ids.next().unwrap_or(0);
    if ids.all(|m| m == first) {
        mesh.sources.fill(first);
        return;
    }
    let Mesh {
        positions,
        triangles,
        sources,
    } = mesh;
    sources
        .par_chunks_mut(1024)
        .zip(triangles.par_chunks(1024))
        .for_each_init(Scratch::default, |scratch, (src, tris)| {
            let centroids: Vec<_> = tris
                .iter()
                .map(|t| {
                    t.iter()
                        .map(|&i| positions[i as usize])
                        .sum::<glam::DVec3>()
                        / 3.0
                })
                .collect();
            let mut d = vec![0.0; tris.len()];
            program.eval_batch_material(scratch, &centroids, &mut d, src);
        });
}
