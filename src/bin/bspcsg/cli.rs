//! The command line's arguments, and the checks clap cannot express.

use std::path::PathBuf;

use bspcsg::Format;
use clap::error::ErrorKind;
use clap::{Args, CommandFactory, Parser, Subcommand, ValueEnum};

/// Constructive solid geometry on mesh files: booleans, reports, conversion, scene export.
///
/// Reads and writes OBJ, STL (ASCII or binary in, binary out), glTF (.gltf + .bin) and
/// binary glTF (.glb); the format follows the file extension.
#[derive(Parser)]
#[command(
    name = "bspcsg",
    version,
    propagate_version = true,
    after_help = concat!(
        "Examples:
  bspcsg union body.obj boss.stl -o part.glb
  bspcsg difference part.glb hole.obj -o drilled.obj
  bspcsg info drilled.obj --json
  bspcsg convert scan.stl -o scan.gltf
  bspcsg export examples/scenes/mechanical_part.json -o part.glb --via sdf

",
        exit_codes!()
    )
)]
pub(crate) struct Cli {
    /// Print no progress and no summary on stderr (errors and warnings still print).
    #[arg(short, long, global = true)]
    pub(crate) quiet: bool,

    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Union of mesh files: the points in any input, A ∪ B ∪ C …
    #[command(after_help = concat!(
        "Each input's triangles keep its source id (0, 1, 2 … in the order given), written as \
a material named after the file (glTF materials, OBJ usemtl with a sibling .mtl).

Example:
  bspcsg union spot.obj spot-moved.stl -o herd.glb

",
        exit_codes!()
    ))]
    Union(BooleanArgs),

    /// Intersection of mesh files: the points in every input, A ∩ B ∩ C …
    #[command(after_help = concat!(
        "Each input's triangles keep its source id (0, 1, 2 … in the order given), written as \
a material named after the file.

Example:
  bspcsg intersection rocker-arm.obj box.obj -o clipped.obj

",
        exit_codes!()
    ))]
    Intersection(BooleanArgs),

    /// Difference of mesh files: the first input less all the others, A − B − C …
    #[command(after_help = concat!(
        "Computed as A − (B ∪ C ∪ …). Each input's triangles keep its source id (0, 1, 2 … in \
the order given), written as a material named after the file.

Example:
  bspcsg difference fandisk.obj cutter.glb -o cut.stl

",
        exit_codes!()
    ))]
    Difference(BooleanArgs),

    /// Report on a mesh file: counts, volume, area, bounding box, defects, genus.
    ///
    /// Reports on any mesh, closed or not (that is its job): an open or non-manifold mesh
    /// exits 0 with its defects listed.
    #[command(after_help = concat!(
        "JSON keys (--json): triangles, vertices, volume, area, bbox_min, bbox_max, watertight,
boundary_edges, nonmanifold_edges, degenerate_triangles, needles, components, genus.
needles: triangles of area below 1e-12 x (their shell's box diagonal)^2, valid but useless
geometry that booleans and bakes remove. watertight: every edge used by exactly two triangles in opposite directions. components: the
shells (triangles joined across edges used by exactly two triangles). genus: null when
undefined (an open or inconsistently oriented shell). volume: by the divergence theorem,
meaningful only for a watertight mesh.

Example:
  bspcsg info stanford-bunny.obj --json

",
        exit_codes!()
    ))]
    Info(InfoArgs),

    /// Convert a mesh file to another format (any mesh, closed or not).
    #[command(after_help = concat!(
        "Example:
  bspcsg convert fandisk.obj -o fandisk.glb

",
        exit_codes!()
    ))]
    Convert(ConvertArgs),

    /// Export a scene document (JSON SDF tree) to a mesh file.
    ///
    /// `--via bsp` (the default) tessellates every primitive and combines them with the BSP
    /// kernel; `--via sdf` bakes the distance field by marching cubes. The scene's materials
    /// become glTF materials and OBJ `usemtl` groups (with a sibling .mtl).
    #[command(after_help = concat!(
        "Examples:
  bspcsg export examples/scenes/mechanical_part.json -o part.glb
  bspcsg export examples/scenes/organic_blend.json -o blend.obj --via sdf --cell 0.02

",
        exit_codes!()
    ))]
    Export(ExportArgs),
}

#[derive(Args)]
pub(crate) struct BooleanArgs {
    /// Input meshes (.obj, .stl, .gltf, .glb), two or more.
    #[arg(required = true, num_args = 2.., value_name = "MESH")]
    pub(crate) inputs: Vec<PathBuf>,

    #[command(flatten)]
    pub(crate) output: OutputArgs,

    /// Go on with inputs that are not closed (open, non-manifold, inside out). The result is
    /// then only as meaningful as the inputs: an open surface has no well-defined inside.
    #[arg(long)]
    pub(crate) allow_open: bool,
}

#[derive(Args)]
pub(crate) struct OutputArgs {
    /// The output file; its extension names the format unless --format is given. Written only
    /// once the work has succeeded, and atomically; missing directories above it are created.
    #[arg(short, long, value_name = "OUT")]
    pub(crate) output: PathBuf,

    /// The output format, whatever the extension.
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub(crate) format: Option<FormatArg>,
}

#[derive(Args)]
pub(crate) struct InfoArgs {
    /// The mesh file (.obj, .stl, .gltf, .glb).
    pub(crate) mesh: PathBuf,

    /// Print JSON instead of text.
    #[arg(long)]
    pub(crate) json: bool,
}

#[derive(Args)]
pub(crate) struct ConvertArgs {
    /// The mesh file to read (.obj, .stl, .gltf, .glb).
    pub(crate) input: PathBuf,

    #[command(flatten)]
    pub(crate) output: OutputArgs,
}

#[derive(Args)]
pub(crate) struct ExportArgs {
    /// The scene document (JSON; see docs/scene-format.md).
    pub(crate) scene: PathBuf,

    #[command(flatten)]
    pub(crate) output: OutputArgs,

    /// How to turn the scene into a mesh.
    #[arg(long, value_enum, default_value_t = Via::Bsp)]
    pub(crate) via: Via,

    /// The largest distance a chord may stray from a curved surface (bsp route only).
    /// Default: 1/500 of the scene's bounding diagonal.
    #[arg(long, value_name = "T", value_parser = positive, allow_negative_numbers = true)]
    pub(crate) tolerance: Option<f64>,

    /// The marching-cubes cell edge: the grid of the sdf route (default: 128 cells along the
    /// longest side), and of smooth blends in the bsp route (default: 4 × tolerance).
    #[arg(long, value_name = "H", value_parser = positive, allow_negative_numbers = true)]
    pub(crate) cell: Option<f64>,
}

/// `--format` values.
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum FormatArg {
    Obj,
    Stl,
    Gltf,
    Glb,
}

impl From<FormatArg> for Format {
    fn from(f: FormatArg) -> Format {
        match f {
            FormatArg::Obj => Format::Obj,
            FormatArg::Stl => Format::Stl,
            FormatArg::Gltf => Format::Gltf,
            FormatArg::Glb => Format::Glb,
        }
    }
}

/// `--via` values.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Via {
    /// Tessellate and combine with the BSP kernel.
    Bsp,
    /// Bake the distance field by marching cubes.
    Sdf,
}

/// A finite number above zero, for `--tolerance` and `--cell`.
pub(crate) fn positive(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        Ok(v) => Err(format!("{v} is not a finite number above zero")),
        Err(e) => Err(format!("not a number: {e}")),
    }
}

impl Cli {
    /// The checks clap cannot express, reported as clap usage errors.
    pub(crate) fn checked(self) -> Result<Self, clap::Error> {
        if let Command::Export(args) = &self.command
            && args.via == Via::Sdf
            && args.tolerance.is_some()
        {
            let mut cli = Cli::command();
            cli.build();
            // The subcommand's own usage line, as clap prints for its own errors.
            let mut export = cli.find_subcommand_mut("export").cloned().unwrap_or(cli);
            return Err(export.error(
                ErrorKind::ArgumentConflict,
                "--tolerance applies to --via bsp only; the sdf route's resolution is --cell",
            ));
        }
        Ok(self)
    }
}
