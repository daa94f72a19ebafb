//! The command line's arguments, and the checks clap cannot express.

use std::path::PathBuf;

use bspcsg::Format;
use bspcsg::raymarch::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE};
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
  bspcsg render examples/scenes/mechanical_part.json -o part.png
  bspcsg check examples/scenes/mechanical_part.json part.glb

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

    /// Render a scene document (ray marched) or a mesh file (ray cast) to a PNG image.
    ///
    /// A scene is drawn with its own camera and lights when the document has them; otherwise
    /// the default camera frames its bounds and a key + fill light pair lights it. A mesh file
    /// (closed or not) is framed and lit the same way. Shadows and ambient occlusion follow
    /// the scene's render profile (`shadow_steps`, `ao_steps`).
    #[command(after_help = concat!(
        "Examples:
  bspcsg render examples/scenes/mechanical_part.json -o part.png
  bspcsg render examples/scenes/organic_blend.json -o blend.png --size 400x300 --view front
  bspcsg render examples/scenes/mechanical_part.json -o part-mesh.png --via bsp
  bspcsg render fandisk.obj -o fandisk.png --eye 3,2,4 --target 0,0,0
  bspcsg render examples/scenes/mechanical_part.json -o spin.png --turntable 36

",
        exit_codes!()
    ))]
    Render(RenderArgs),

    /// Check that a mesh is the surface of a scene's distance field.
    ///
    /// MESH is a mesh file, or, when absent, the scene's own export by --via (made as
    /// `bspcsg export` makes it). Four measures, each against a threshold that follows from the
    /// tolerance: surface distance (|SDF| on the mesh: max and p99 ≤ T), coverage (the mesh's
    /// distance from points of the SDF's surface: max ≤ T), rays (512×512 rays from three
    /// views: ≥ 99.5 % agree on hit or miss, depth difference p99 ≤ 4T), sign (inside/outside
    /// agreement at points 2T or farther from the surface: ≥ 99.9 %). T is --tolerance, or:
    /// 2 × the chordal tolerance of --via bsp, the cell of --via sdf, 1/250 of the scene's
    /// bounding diagonal for a mesh file. Exit 3 when any measure fails, naming it and the
    /// worst place.
    #[command(after_help = concat!(
        "JSON keys (--json): passed, tolerance, diagonal, thresholds, surface, coverage, rays, sign,
failures. surface and coverage: samples, max, p99, mean, worst ([x, y, z]). rays: rays,
agreement_pct, depth_p99, depth_max, worst. sign: samples, agreement_pct, worst.

Examples:
  bspcsg check examples/scenes/mechanical_part.json
  bspcsg check examples/scenes/organic_blend.json --via sdf --json
  bspcsg check examples/scenes/mechanical_part.json part.glb --tolerance 0.02 --image diff.png

",
        exit_codes!()
    ))]
    Check(CheckArgs),

    /// Edit a scene in the browser: a live preview, a tree of nodes, save and export.
    ///
    /// Serves a single-page editor of SCENE (created on the first save when it does not exist;
    /// default `untitled.json`) on 127.0.0.1 only, and prints its URL. The page previews the
    /// scene by a WebGL2 ray marcher generated from it, validates every edit with the scene
    /// reader's JSON-path messages, saves atomically, exports OBJ / STL / glTF / GLB by either
    /// route and runs `check`. Saves and exports stay in SCENE's folder. Stop it with Ctrl-C.
    #[command(after_help = concat!(
        "Examples:
  bspcsg edit examples/scenes/mechanical_part.json
  bspcsg edit part.json --port 8080

",
        exit_codes!()
    ))]
    Edit(EditArgs),
}

#[derive(Args)]
pub(crate) struct BooleanArgs {
    /// Input meshes (.obj, .stl, .gltf, .glb), two or more.
    #[arg(required = true, num_args = 2.., value_name = "MESH")]
    pub(crate) inputs: Vec<PathBuf>,

    #[command(flatten)]
    pub(crate) output: OutputArgs,

    /// Go on with inputs that are not closed (open, non-manifold, inside out). The result is
    /// then only as meaningful as the inputs: an open surface has no well-defined inside; it
    /// is written even where it is not closed (with a warning), which is otherwise refused.
    #[arg(long)]
    pub(crate) allow_open: bool,

    /// Take an input whose closed shells overlap (two boxes written into one file) as the
    /// union of its shells, each shell a solid on its own; otherwise such an input is refused
    /// (exit 2). A shell that crosses itself is refused either way, naming the crossing.
    #[arg(long)]
    pub(crate) union_shells: bool,
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

#[derive(Args)]
pub(crate) struct RenderArgs {
    /// A scene document (.json) or a mesh file (.obj, .stl, .gltf, .glb).
    pub(crate) input: PathBuf,

    /// The PNG to write (written whole or not at all; missing directories are created).
    /// With --turntable, frames go to OUT-000.png, OUT-001.png …
    #[arg(short, long, value_name = "OUT.png")]
    pub(crate) output: PathBuf,

    /// Image size in pixels.
    #[arg(long, value_name = "WxH", default_value = "800x600", value_parser = image_size)]
    pub(crate) size: (u32, u32),

    /// A default view: iso (three-quarter, perspective) or front, side, top (orthographic).
    /// Used when the scene names no camera.
    #[arg(long, value_enum, conflicts_with_all = ["eye", "target"])]
    pub(crate) view: Option<ViewArg>,

    /// The eye position (the target defaults to the centre of the bounds).
    #[arg(long, value_name = "X,Y,Z", value_parser = point, allow_hyphen_values = true)]
    pub(crate) eye: Option<[f64; 3]>,

    /// The point at the centre of the image (needs --eye).
    #[arg(long, value_name = "X,Y,Z", value_parser = point, allow_hyphen_values = true, requires = "eye")]
    pub(crate) target: Option<[f64; 3]>,

    /// For a scene: render the distance field itself (sdf), or the mesh of the BSP route
    /// (bsp) or of marching cubes (mc), as `bspcsg export` makes them.
    #[arg(long, value_enum, default_value_t = RenderVia::Sdf)]
    pub(crate) via: RenderVia,

    /// Facet shading for meshes (default: smooth, keeping creases sharper than 35°).
    #[arg(long)]
    pub(crate) flat: bool,

    /// Write N frames turning the camera once around the vertical axis through the target.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=3600))]
    pub(crate) turntable: Option<u32>,
}

#[derive(Args)]
pub(crate) struct CheckArgs {
    /// The scene document (JSON; see docs/scene-format.md).
    pub(crate) scene: PathBuf,

    /// The mesh to check (.obj, .stl, .gltf, .glb); default: the scene's own export by --via.
    pub(crate) mesh: Option<PathBuf>,

    /// Which export of the scene to check when no MESH is given.
    #[arg(long, value_enum, default_value_t = Via::Bsp)]
    pub(crate) via: Via,

    /// The tolerance T the thresholds follow from, in scene units.
    #[arg(long, value_name = "T", value_parser = positive, allow_negative_numbers = true)]
    pub(crate) tolerance: Option<f64>,

    /// Rays per side of each of the three views.
    #[arg(long, value_name = "N", default_value_t = 512, value_parser = clap::value_parser!(u32).range(16..=4096))]
    pub(crate) rays: u32,

    /// Print the report as JSON on stdout.
    #[arg(long)]
    pub(crate) json: bool,

    /// Write the ray views side by side as a PNG: grey where both agree, red where only the
    /// SDF is hit, blue where only the mesh is, yellow where depths differ by more than T.
    #[arg(long, value_name = "DIFF.png")]
    pub(crate) image: Option<PathBuf>,
}

#[derive(Args)]
pub(crate) struct EditArgs {
    /// The scene document to edit (JSON; see docs/scene-format.md); it need not exist yet.
    #[arg(default_value = "untitled.json")]
    pub(crate) scene: PathBuf,

    /// The port on 127.0.0.1 to serve on; 0 picks a free one.
    #[arg(long, default_value_t = 8737)]
    pub(crate) port: u16,
}

/// `--view` values.
#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum ViewArg {
    Iso,
    Front,
    Side,
    Top,
}

/// `render --via` values.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum RenderVia {
    /// Ray march the distance field.
    Sdf,
    /// Ray cast the BSP route's mesh.
    Bsp,
    /// Ray cast the marching-cubes mesh.
    Mc,
}

/// `WxH`, each side at least 1 and the image within the renderer's limits.
pub(crate) fn image_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, e.g. 800x600, found {s:?}"))?;
    let side = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|e| format!("{v:?} is not a pixel count: {e}"))
    };
    let (w, h) = (side(w)?, side(h)?);
    if w == 0 || h == 0 {
        return Err(format!(
            "the image must be at least 1x1 pixels, found {w}x{h}"
        ));
    }
    if w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE || w as u64 * h as u64 > MAX_IMAGE_PIXELS {
        return Err(format!(
            "{w}x{h} is too large: at most {MAX_IMAGE_SIDE} pixels a side and {} megapixels",
            MAX_IMAGE_PIXELS >> 20
        ));
    }
    Ok((w, h))
}

/// `X,Y,Z`, three finite numbers.
pub(crate) fn point(s: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("expected X,Y,Z, found {s:?}"));
    }
    let mut p = [0.0; 3];
    for (v, part) in p.iter_mut().zip(&parts) {
        *v = part
            .trim()
            .parse::<f64>()
            .map_err(|e| format!("{part:?} is not a number: {e}"))?;
        if !v.is_finite() {
            return Err(format!("{part:?} is not a finite number"));
        }
    }
    Ok(p)
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
