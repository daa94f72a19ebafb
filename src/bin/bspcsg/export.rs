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
    finish(
        out,
        format,
        &mesh,
        scene.materials(),
        Expect::Closed,
        progress,
    )
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
