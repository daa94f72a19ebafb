//! `export`: a scene document to a mesh, by the BSP route or by marching cubes.

use bspcsg::{BakeOptions, Error, Mesh, Scene, TessellationOptions};

use crate::cli::{ExportArgs, Via};
use crate::failure::Failure;
use crate::output::{Expect, finish, output_target};
use crate::progress::Progress;

/// `export`.
pub(crate) fn export(args: &ExportArgs, progress: &Progress) -> Result<(), Failure> {
    let (out, format) = output_target(&args.output)?;
    // Option faults carry a name but not the file: name it here. I/O and scene errors name it
    // already.
    let in_scene = |e: Error| match e {
        Error::Io { .. } | Error::Scene { .. } => Failure::from(e),
        other => {
            let mut f = Failure::from(other);
            f.message = format!("{}: {}", args.scene.display(), f.message);
            f
        }
    };
    progress.step(format!("reading {}", args.scene.display()));
    let scene = Scene::from_path(&args.scene).map_err(in_scene)?;
    let mesh =
        scene_mesh(&scene, args.via, args.tolerance, args.cell, progress).map_err(in_scene)?;
    if args.via == Via::Sdf && mesh.is_empty() {
        warn_lost_to_the_grid(&scene, args.cell, progress);
    }
    finish(
        out,
        format,
        &mesh,
        scene.materials(),
        Expect::Closed,
        progress,
    )
}

/// Marching cubes found no surface in a scene that is not empty: what it had was thinner than
/// a cell (a sheet, a fine rod) and fell between the grid's points. Says so, with a cell that
/// resolves the scene's thinnest extent, rather than only "the result is empty".
fn warn_lost_to_the_grid(scene: &Scene, cell: Option<f64>, progress: &Progress) {
    let size = scene.bbox().size();
    if !(size.is_finite() && size.max_element() > 0.0) {
        return;
    }
    // The default cell: the longest side over the default resolution of 128 cells.
    let cell = cell.unwrap_or(size.max_element() / 128.0);
    let thinnest = size.min_element();
    progress.println(&format!(
        "bspcsg: warning: marching cubes at a cell of {cell:.3e} found no surface, though the \
         scene spans {:.3e} × {:.3e} × {:.3e}: parts thinner than a cell fall between the grid's \
         points and are lost (its thinnest extent is {thinnest:.3e}); use --cell {:.3e} or \
         finer, or the BSP route (--via bsp), which keeps them",
        size.x,
        size.y,
        size.z,
        thinnest / 2.0
    ));
}

/// The scene's mesh by either route, as `export` makes it (also for `render` and `check`).
pub(crate) fn scene_mesh(
    scene: &Scene,
    via: Via,
    tolerance: Option<f64>,
    cell: Option<f64>,
    progress: &Progress,
) -> Result<Mesh, Error> {
    Ok(match via {
        Via::Bsp => {
            progress.step("tessellating and combining");
            let options = TessellationOptions {
                tolerance,
                cell,
                ..TessellationOptions::default()
            };
            let solid = scene.to_solid(&options)?;
            progress.step("repairing (welding, closing T-junctions)");
            solid.to_mesh()
        }
        Via::Sdf => {
            progress.step("baking by marching cubes");
            let options = BakeOptions {
                cell,
                ..BakeOptions::default()
            };
            scene.bake(&options)?
        }
    })
}
