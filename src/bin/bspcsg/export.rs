//! `export`: a scene document to a mesh, by the BSP route or by marching cubes.

use bspcsg::{BakeOptions, Error, Mesh, Scene, Solid, TessellationOptions};

use crate::cli::{ExportArgs, Via};
use crate::failure::Failure;
use crate::output::{Expect, finish, output_target};
use crate::progress::Progress;

/// `export`.
pub(crate) fn export(args: &ExportArgs, progress: &Progress) -> Result<(), Failure> {
    let (out, format) = output_target(&args.output)?;
    // Option faults carry a name but not the file: name it here. I/O errors and faults of the
    // scene's text name it already; those of the scene as a whole (its work budget, transforms
    // that compose to a singular map) are found after reading, without it.
    let in_scene = |e: Error| match e {
        Error::Io { .. } | Error::Scene { file: Some(_), .. } => Failure::from(e),
        other => {
            let mut f = Failure::from(other);
            f.message = format!("{}: {}", args.scene.display(), f.message);
            f
        }
    };
    progress.step(format!("reading {}", args.scene.display()));
    let scene = Scene::from_path(&args.scene).map_err(in_scene)?;
    let (mesh, solid) =
        scene_mesh(&scene, args.via, args.tolerance, args.cell, progress).map_err(in_scene)?;
    if args.via == Via::Sdf {
        warn_lost_to_the_grid(&scene, args.cell, mesh.is_empty(), progress);
    }
    finish(
        out,
        format,
        &mesh,
        scene.materials(),
        Expect::Closed,
        solid.as_ref(),
        progress,
    )
}

/// How many thin parts a warning names before it only counts the rest.
const NAMED_THIN_PARTS: usize = 8;

/// Parts thinner than a marching-cubes cell (a sheet, a fine rod) fall between the grid's
/// points and are lost. Names each primitive whose own box is thinner than the cell by its JSON
/// path, with a cell that resolves it. When the bake is empty though the scene is not, says so
/// with the scene's thinnest extent, rather than only "the result is empty".
fn warn_lost_to_the_grid(scene: &Scene, cell: Option<f64>, empty: bool, progress: &Progress) {
    let size = scene.bbox().size();
    if !(size.is_finite() && size.max_element() > 0.0) {
        return;
    }
    // The default cell: the longest side over the default resolution of 128 cells.
    let cell = cell.unwrap_or(size.max_element() / 128.0);
    let thin = thin_parts(scene, cell);
    if empty {
        let thinnest = size.min_element();
        let named = if thin.is_empty() {
            String::new()
        } else {
            format!("; lost: {}", list_parts(&thin))
        };
        progress.println(&format!(
            "bspcsg: warning: marching cubes at a cell of {cell:.3e} found no surface, though the \
             scene spans {:.3e} × {:.3e} × {:.3e}: parts thinner than a cell fall between the \
             grid's points and are lost (its thinnest extent is {thinnest:.3e}); use --cell {:.3e} \
             or finer, or the BSP route (--via bsp), which keeps them{named}",
            size.x,
            size.y,
            size.z,
            thinnest / 2.0
        ));
        return;
    }
    for (path, thinnest) in thin.iter().take(NAMED_THIN_PARTS) {
        progress.println(&format!(
            "bspcsg: warning: the part at {path} is {thinnest:.3e} thin, less than the cell of \
             {cell:.3e}: marching cubes may lose it between the grid's points; use --cell {:.3e} \
             or finer, or the BSP route (--via bsp), which keeps it",
            thinnest / 2.0
        ));
    }
    if thin.len() > NAMED_THIN_PARTS {
        progress.println(&format!(
            "bspcsg: warning: {} more parts are thinner than the cell of {cell:.3e}",
            thin.len() - NAMED_THIN_PARTS
        ));
    }
}

/// Each primitive whose own bounded box is thinner than `cell` on some axis: its JSON path and
/// that thinnest extent, in document order. Unbounded primitives (half-spaces) are skipped.
fn thin_parts(scene: &Scene, cell: f64) -> Vec<(&str, f64)> {
    scene
        .primitive_paths()
        .iter()
        .zip(scene.primitive_bboxes())
        .filter(|(_, b)| !b.is_empty() && b.size().is_finite())
        .map(|(path, b)| (path.as_str(), b.size().min_element()))
        .filter(|&(_, thinnest)| thinnest < cell)
        .map(|(path, thinnest)| (if path.is_empty() { "$" } else { path }, thinnest))
        .collect()
}

/// `$.a (4.000e-3 thin), $.b (…), and 3 more`.
fn list_parts(parts: &[(&str, f64)]) -> String {
    let mut list: Vec<String> = parts
        .iter()
        .take(NAMED_THIN_PARTS)
        .map(|(path, thinnest)| format!("{path} ({thinnest:.3e} thin)"))
        .collect();
    if parts.len() > NAMED_THIN_PARTS {
        list.push(format!("and {} more", parts.len() - NAMED_THIN_PARTS));
    }
    list.join(", ")
}

/// The scene's mesh by either route, as `export` makes it (also for `render` and `check`).
pub(crate) fn scene_mesh(
    scene: &Scene,
    via: Via,
    tolerance: Option<f64>,
    cell: Option<f64>,
    progress: &Progress,
) -> Result<(Mesh, Option<Solid>), Error> {
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
            (solid.to_mesh(), Some(solid))
        }
        Via::Sdf => {
            progress.step("baking by marching cubes");
            let options = BakeOptions {
                cell,
                ..BakeOptions::default()
            };
            (scene.bake(&options)?, None)
        }
    })
}
