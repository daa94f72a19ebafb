//! `union`, `intersection`, `difference`: read each input as a solid, combine, write.

use std::path::{Path, PathBuf};

use bspcsg::{BoolOp, FromMeshOptions, Material, MeshDefect, boolean_all, read_solid};

use crate::cli::BooleanArgs;
use crate::failure::Failure;
use crate::output::{Expect, finish, output_target, protect_inputs, warn_if_empty_input};
use crate::progress::Progress;

/// `union`, `intersection`, `difference`.
pub(crate) fn combine(op: BoolOp, args: &BooleanArgs, progress: &Progress) -> Result<(), Failure> {
    let (out, format) = output_target(&args.output)?;
    let inputs: Vec<&Path> = args.inputs.iter().map(PathBuf::as_path).collect();
    protect_inputs(out, format, true, &inputs)?;
    let options = if args.allow_open {
        FromMeshOptions::lenient()
    } else {
        FromMeshOptions::default()
    }
    .with_union_shells(args.union_shells);
    let mut solids = Vec::with_capacity(args.inputs.len());
    let mut materials = Vec::with_capacity(args.inputs.len());
    for (i, path) in args.inputs.iter().enumerate() {
        progress.step(format!("reading {}", path.display()));
        let solid = read_solid(path, &options).map_err(|e| {
            // The flag lets open or inside-out input in, and only helps if not given yet; an
            // inside-out mesh is mostly one whose faces wind the wrong way.
            let hint = match e.mesh_defect() {
                _ if args.allow_open => None,
                Some(MeshDefect::NotClosed { .. }) => Some(" (pass --allow-open to go on anyway)"),
                Some(MeshDefect::InsideOut { .. }) => Some(
                    " (reverse its faces' winding to make it a solid; --allow-open goes on \
                     with it as it is)",
                ),
                Some(MeshDefect::SelfIntersecting { .. }) if !args.union_shells => {
                    Some(" (pass --union-shells to take its shells as their union)")
                }
                Some(MeshDefect::CrossingCheckOverBudget { .. }) => {
                    Some(" (pass --allow-open to do so)")
                }
                _ => None,
            };
            let mut f = Failure::from(e);
            f.message.push_str(hint.unwrap_or_default());
            f
        })?;
        warn_if_empty_input(path, solid.is_empty(), progress);
        // Source ids record which input each output triangle came from.
        let id = u32::try_from(i).map_err(|_| Failure::usage_or_io("too many inputs"))?;
        solids.push(solid.with_source(id));
        materials.push(input_material(path, i));
    }
    progress.step(format!("combining {} solids", solids.len()));
    let solid = boolean_all(solids, op);
    progress.step("repairing (welding, closing T-junctions)");
    // Inputs let in open may give an open result; solids must give a solid (`finish` refuses
    // anything else: Solid::to_checked_mesh's promise, with the report computed once).
    solid.check_budget()?;
    solid.check_precision()?;
    let expect = if args.allow_open {
        Expect::Any
    } else {
        Expect::Closed
    };
    finish(
        out,
        format,
        &solid.to_mesh(),
        &materials,
        expect,
        Some(&solid),
        progress,
    )
}

/// The material that marks input `i`'s triangles: named after its file, coloured from a small
/// palette so that the inputs tell apart in a viewer.
pub(crate) fn input_material(path: &Path, i: usize) -> Material {
    const PALETTE: [[f64; 3]; 8] = [
        [0.70, 0.70, 0.72],
        [0.90, 0.35, 0.20],
        [0.20, 0.50, 0.90],
        [0.30, 0.75, 0.30],
        [0.90, 0.75, 0.15],
        [0.60, 0.30, 0.80],
        [0.15, 0.75, 0.75],
        [0.85, 0.40, 0.65],
    ];
    let [r, g, b] = PALETTE[i % PALETTE.len()];
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| format!("input_{i}"));
    Material {
        name,
        base_color: [r, g, b, 1.0],
    }
}
