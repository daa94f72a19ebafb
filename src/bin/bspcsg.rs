//! The `bspcsg` command line tool: argument parsing, progress and printing only. Every piece of
//! work — reading, checking, combining, repairing, baking, writing — is a library call.

use std::borrow::Cow;
use std::fmt::Write as _;
use std::io::{IsTerminal, Write as _};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use bspcsg::{
    BakeOptions, BoolOp, Error, Format, FromMeshOptions, Material, Mesh, MeshReport, Scene,
    TessellationOptions, boolean_all, read_mesh, read_solid, write_mesh_as,
};
use clap::error::ErrorKind;
use clap::{Args, CommandFactory, Parser, Subcommand, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// The exit codes, shown in every `--help` and in the README. A macro so that `concat!` can put
/// it after each subcommand's examples.
macro_rules! exit_codes {
    () => {
        "Exit codes:
  0  success
  1  usage error; a file that cannot be read, parsed or written (a missing or truncated
     file, a syntax error, NaN or infinite coordinates, a vertex index out of range, an
     unknown extension, an invalid scene document); nothing is written
  2  invalid geometry: an input mesh that does not bound a solid (open, non-manifold,
     inside out; --allow-open goes on anyway), or a result the output format cannot hold
     (coordinates beyond float32); nothing is written"
    };
}

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
struct Cli {
    /// Print no progress and no summary on stderr (errors and warnings still print).
    #[arg(short, long, global = true)]
    quiet: bool,

    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
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
boundary_edges, nonmanifold_edges, degenerate_triangles, components, genus.
watertight: every edge used by exactly two triangles in opposite directions. components: the
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
struct BooleanArgs {
    /// Input meshes (.obj, .stl, .gltf, .glb), two or more.
    #[arg(required = true, num_args = 2.., value_name = "MESH")]
    inputs: Vec<PathBuf>,

    #[command(flatten)]
    output: OutputArgs,

    /// Go on with inputs that are not closed (open, non-manifold, inside out). The result is
    /// then only as meaningful as the inputs: an open surface has no well-defined inside.
    #[arg(long)]
    allow_open: bool,
}

#[derive(Args)]
struct OutputArgs {
    /// The output file; its extension names the format unless --format is given. Written only
    /// once the work has succeeded, and atomically; missing directories above it are created.
    #[arg(short, long, value_name = "OUT")]
    output: PathBuf,

    /// The output format, whatever the extension.
    #[arg(long, value_enum, value_name = "FORMAT")]
    format: Option<FormatArg>,
}

#[derive(Args)]
struct InfoArgs {
    /// The mesh file (.obj, .stl, .gltf, .glb).
    mesh: PathBuf,

    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct ConvertArgs {
    /// The mesh file to read (.obj, .stl, .gltf, .glb).
    input: PathBuf,

    #[command(flatten)]
    output: OutputArgs,
}

#[derive(Args)]
struct ExportArgs {
    /// The scene document (JSON; see docs/scene-format.md).
    scene: PathBuf,

    #[command(flatten)]
    output: OutputArgs,

    /// How to turn the scene into a mesh.
    #[arg(long, value_enum, default_value_t = Via::Bsp)]
    via: Via,

    /// The largest distance a chord may stray from a curved surface (bsp route only).
    /// Default: 1/500 of the scene's bounding diagonal.
    #[arg(long, value_name = "T", value_parser = positive, allow_negative_numbers = true)]
    tolerance: Option<f64>,

    /// The marching-cubes cell edge: the grid of the sdf route (default: 128 cells along the
    /// longest side), and of smooth blends in the bsp route (default: 4 × tolerance).
    #[arg(long, value_name = "H", value_parser = positive, allow_negative_numbers = true)]
    cell: Option<f64>,
}

/// `--format` values.
#[derive(Clone, Copy, ValueEnum)]
enum FormatArg {
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
enum Via {
    /// Tessellate and combine with the BSP kernel.
    Bsp,
    /// Bake the distance field by marching cubes.
    Sdf,
}

/// A finite number above zero, for `--tolerance` and `--cell`.
fn positive(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        Ok(v) => Err(format!("{v} is not a finite number above zero")),
        Err(e) => Err(format!("not a number: {e}")),
    }
}

/// Why a command failed: the message printed and the exit code.
struct Failure {
    message: String,
    code: u8,
}

impl Failure {
    /// Exit code 1: usage, or a file that cannot be read, parsed or written.
    fn usage_or_io(message: impl Into<String>) -> Self {
        Failure {
            message: message.into(),
            code: 1,
        }
    }
}

impl From<Error> for Failure {
    /// The library's errors name their file already (except scene faults, which the export
    /// command prefixes). Invalid geometry exits 2; everything else concerns reading, parsing,
    /// options or writing, and exits 1.
    fn from(e: Error) -> Self {
        let code = match e {
            Error::InvalidMesh(_) => 2,
            _ => 1,
        };
        Failure {
            message: e.to_string(),
            code,
        }
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse().and_then(Cli::checked) {
        Ok(cli) => cli,
        Err(e) => {
            // clap exits 2 on usage errors; here 2 means invalid geometry, so usage exits 1.
            let _ = e.print();
            return match e.kind() {
                ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => ExitCode::SUCCESS,
                _ => ExitCode::from(1),
            };
        }
    };
    let progress = Progress::new(cli.quiet);
    let result = match cli.command {
        Command::Union(args) => combine(BoolOp::Union, &args, &progress),
        Command::Intersection(args) => combine(BoolOp::Intersection, &args, &progress),
        Command::Difference(args) => combine(BoolOp::Difference, &args, &progress),
        Command::Info(args) => info(&args, &progress),
        Command::Convert(args) => convert(&args, &progress),
        Command::Export(args) => export(&args, &progress),
    };
    progress.finish();
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            print_stderr(&format!("bspcsg: error: {}", f.message));
            ExitCode::from(f.code)
        }
    }
}

impl Cli {
    /// The checks clap cannot express, reported as clap usage errors.
    fn checked(self) -> Result<Self, clap::Error> {
        if let Command::Export(args) = &self.command {
            if args.via == Via::Sdf && args.tolerance.is_some() {
                let mut cli = Cli::command();
                cli.build();
                // The subcommand's own usage line, as clap prints for its own errors.
                let mut export = cli.find_subcommand_mut("export").cloned().unwrap_or(cli);
                return Err(export.error(
                    ErrorKind::ArgumentConflict,
                    "--tolerance applies to --via bsp only; the sdf route's resolution is --cell",
                ));
            }
        }
        Ok(self)
    }
}

/// `union`, `intersection`, `difference`.
fn combine(op: BoolOp, args: &BooleanArgs, progress: &Progress) -> Result<(), Failure> {
    let (out, format) = output_target(&args.output)?;
    let options = if args.allow_open {
        FromMeshOptions::lenient()
    } else {
        FromMeshOptions::default()
    };
    let mut solids = Vec::with_capacity(args.inputs.len());
    let mut materials = Vec::with_capacity(args.inputs.len());
    for (i, path) in args.inputs.iter().enumerate() {
        progress.step(format!("reading {}", path.display()));
        let solid = read_solid(path, &options).map_err(|e| {
            // The flag helps with open or inside-out input only, and only if not given yet.
            let hint = !args.allow_open
                && matches!(&e, Error::InvalidMesh(m)
                    if m.contains(" is not closed") || m.contains(" is inside out"));
            let mut f = Failure::from(e);
            if hint {
                f.message.push_str(" (pass --allow-open to go on anyway)");
            }
            f
        })?;
        // Source ids record which input each output triangle came from.
        let id = u32::try_from(i).map_err(|_| Failure::usage_or_io("too many inputs"))?;
        solids.push(solid.with_source(id));
        materials.push(input_material(path, i));
    }
    progress.step(format!("combining {} solids", solids.len()));
    let solid = boolean_all(op, solids);
    progress.step("repairing (welding, closing T-junctions)");
    let mesh = solid.to_mesh();
    finish(out, format, &mesh, &materials, progress)
}

/// `convert`.
fn convert(args: &ConvertArgs, progress: &Progress) -> Result<(), Failure> {
    let (out, format) = output_target(&args.output)?;
    progress.step(format!("reading {}", args.input.display()));
    let mesh = read_mesh(&args.input)?;
    finish(out, format, &mesh, &[], progress)
}

/// `export`.
fn export(args: &ExportArgs, progress: &Progress) -> Result<(), Failure> {
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
    let mesh = match args.via {
        Via::Bsp => {
            progress.step("tessellating and combining");
            let options = TessellationOptions {
                tolerance: args.tolerance,
                cell: args.cell,
            };
            let solid = scene.to_solid(&options).map_err(in_scene)?;
            progress.step("repairing (welding, closing T-junctions)");
            solid.to_mesh()
        }
        Via::Sdf => {
            progress.step("baking by marching cubes");
            let options = BakeOptions {
                cell: args.cell,
                ..BakeOptions::default()
            };
            scene.bake(&options).map_err(in_scene)?
        }
    };
    finish(out, format, &mesh, scene.materials(), progress)
}

/// The output path and format, checked before any work so that a typo costs nothing: the
/// format from `--format` or the extension, the output not a directory, and its nearest
/// existing ancestor a directory (missing ones are created when the output is written).
fn output_target(args: &OutputArgs) -> Result<(&Path, Format), Failure> {
    let out = args.output.as_path();
    let format = match args.format {
        Some(f) => Format::from(f),
        None => Format::from_path(out)?,
    };
    let refuse = |why: String| {
        Failure::usage_or_io(format!("{}: cannot write the output: {why}", out.display()))
    };
    if out.is_dir() {
        return Err(refuse("it is a directory".into()));
    }
    let existing = out
        .ancestors()
        .skip(1)
        .find(|d| d.as_os_str().is_empty() || d.exists());
    if let Some(d) = existing.filter(|d| !d.as_os_str().is_empty() && !d.is_dir()) {
        return Err(refuse(format!("{} is not a directory", d.display())));
    }
    Ok((out, format))
}

/// Creates the missing directories above `out`, returning those it made, outermost first.
fn make_parents(out: &Path) -> Result<Vec<PathBuf>, Failure> {
    let mut missing: Vec<PathBuf> = out
        .ancestors()
        .skip(1)
        .take_while(|d| !d.as_os_str().is_empty() && !d.exists())
        .map(Path::to_path_buf)
        .collect();
    missing.reverse();
    for (k, d) in missing.iter().enumerate() {
        if let Err(e) = std::fs::create_dir(d) {
            remove_dirs(&missing[..k]);
            return Err(Failure::usage_or_io(format!(
                "{}: cannot create the output's directory: {e}",
                d.display()
            )));
        }
    }
    Ok(missing)
}

/// Removes directories made by [`make_parents`], innermost first; only empty ones go.
fn remove_dirs(dirs: &[PathBuf]) {
    for d in dirs.iter().rev() {
        let _ = std::fs::remove_dir(d);
    }
}

/// Writes the result and prints a summary, with a warning when the result is empty or not a
/// closed 2-manifold (from inputs let in by `--allow-open` or `convert`, or a library fault).
fn finish(
    out: &Path,
    format: Format,
    mesh: &Mesh,
    materials: &[Material],
    progress: &Progress,
) -> Result<(), Failure> {
    progress.step("checking the result");
    let report = mesh.report();
    progress.step(format!("writing {}", out.display()));
    // Directories too appear only once the work has succeeded, and go again if the write fails.
    let made = make_parents(out)?;
    if let Err(e) = write_mesh_as(out, mesh, materials, format) {
        remove_dirs(&made);
        return Err(e.into());
    }
    progress.finish();
    if mesh.is_empty() {
        print_stderr(&format!(
            "bspcsg: warning: the result is empty; {} holds no triangles",
            out.display()
        ));
    } else if !report.is_closed_manifold() {
        print_stderr(&format!(
            "bspcsg: warning: {} is not a closed 2-manifold: {report}",
            out.display()
        ));
    }
    if !progress.quiet {
        print_stderr(&format!(
            "wrote {} ({format}): {} triangles, {} vertices, volume {}",
            out.display(),
            report.triangles,
            report.vertices,
            report.volume
        ));
    }
    Ok(())
}

/// `info`.
fn info(args: &InfoArgs, progress: &Progress) -> Result<(), Failure> {
    progress.step(format!("reading {}", args.mesh.display()));
    let mesh = read_mesh(&args.mesh)?;
    progress.step("checking");
    let report = mesh.report();
    let area = mesh.area();
    let bbox = mesh.bbox();
    progress.finish();
    let watertight = watertight(&report);
    let text = if args.json {
        let value = serde_json::json!({
            "triangles": report.triangles,
            "vertices": report.vertices,
            "volume": report.volume,
            "area": area,
            "bbox_min": bbox.min.to_array(),
            "bbox_max": bbox.max.to_array(),
            "watertight": watertight,
            "boundary_edges": report.boundary_edges,
            "nonmanifold_edges": report.non_manifold_edges,
            "degenerate_triangles": report.degenerate_triangles,
            "components": report.shells.len(),
            "genus": report.genus,
        });
        // A `Value` of plain numbers, strings and arrays always serializes.
        let mut s = serde_json::to_string_pretty(&value).unwrap_or_default();
        s.push('\n');
        s
    } else {
        let yes = |b: bool| if b { "yes" } else { "no" };
        let v = |p: bspcsg::glam::DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
        let mut s = String::new();
        let mut line = |k: &str, v: String| {
            let _ = writeln!(s, "{k:<31} {v}");
        };
        line("file", args.mesh.display().to_string());
        line("triangles", report.triangles.to_string());
        line("vertices", report.vertices.to_string());
        line("volume", report.volume.to_string());
        line("area", area.to_string());
        line("bbox min", v(bbox.min));
        line("bbox max", v(bbox.max));
        line("watertight", yes(watertight).to_owned());
        line("boundary edges", report.boundary_edges.to_string());
        line("non-manifold edges", report.non_manifold_edges.to_string());
        line(
            "inconsistently oriented edges",
            report.inconsistent_edges.to_string(),
        );
        line(
            "non-manifold vertices",
            report.non_manifold_vertices.to_string(),
        );
        line(
            "degenerate triangles",
            report.degenerate_triangles.to_string(),
        );
        line("components", report.shells.len().to_string());
        line("inside-out shells", report.inverted_shells.to_string());
        line(
            "genus",
            report
                .genus
                .map_or_else(|| "undefined".to_owned(), |g| g.to_string()),
        );
        line("closed 2-manifold", yes(report.is_closed_manifold()).into());
        s
    };
    print_stdout(&text)
}

/// Every edge used by exactly two triangles in opposite directions (the definition the shared
/// models' README and trimesh use).
fn watertight(report: &MeshReport) -> bool {
    report.boundary_edges == 0 && report.non_manifold_edges == 0 && report.inconsistent_edges == 0
}

/// The material that marks input `i`'s triangles: named after its file, coloured from a small
/// palette so that the inputs tell apart in a viewer.
fn input_material(path: &Path, i: usize) -> Material {
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

/// Prints to stdout. A closed pipe (`bspcsg info x | head -1`) is not an error.
fn print_stdout(text: &str) -> Result<(), Failure> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure::usage_or_io(format!(
            "cannot write to standard output: {e}"
        ))),
        _ => Ok(()),
    }
}

/// Prints a line to stderr; nothing more can be done if that fails.
fn print_stderr(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// A spinner on stderr naming the current step; absent with `--quiet` or when stderr is not a
/// terminal (so logs and pipes get no control characters).
struct Progress {
    bar: Option<ProgressBar>,
    quiet: bool,
}

impl Progress {
    fn new(quiet: bool) -> Self {
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} ({elapsed})") {
                bar.set_style(style);
            }
            bar.enable_steady_tick(Duration::from_millis(120));
            bar
        });
        Progress { bar, quiet }
    }

    fn step(&self, message: impl Into<Cow<'static, str>>) {
        if let Some(bar) = &self.bar {
            bar.set_message(message);
        }
    }

    /// Clears the spinner before the summary, warnings or errors print.
    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
