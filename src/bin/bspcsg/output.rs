//! Output shared by the subcommands: the output path checked before any work, the result
//! written (directories made only then, and removed again if the write fails) with its
//! summary, and printing that survives closed pipes.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use bspcsg::{Format, Material, Mesh, MeshReport, Solid, write_mesh_as};

use crate::cli::OutputArgs;
use crate::failure::Failure;
use crate::progress::Progress;

/// The output path and format, checked before any work so that a typo costs nothing: the
/// format from `--format` or the extension, the output not a directory, and its nearest
/// existing ancestor a directory (missing ones are created when the output is written).
pub(crate) fn output_target(args: &OutputArgs) -> Result<(&Path, Format), Failure> {
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

/// Directories made for an output not yet written, for the signal handler to remove.
static MADE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn made() -> MutexGuard<'static, Vec<PathBuf>> {
    MADE.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Removes the directories made for an output whose write failed, innermost first.
fn remove_made_dirs() {
    remove_dirs(&std::mem::take(&mut *made()));
}

/// For the signal handler: removes the directories made for the output and keeps the list
/// locked, so that none is made between this and the process's exit.
pub(crate) fn remove_made_dirs_before_exit() {
    let mut made = made();
    remove_dirs(&std::mem::take(&mut *made));
    std::mem::forget(made);
}

/// The output is written: its directories stay.
fn keep_made_dirs() {
    made().clear();
}

/// Creates the missing directories above `out`, returning those it made, outermost first.
/// Each is made and listed under one lock, so a signal handler never misses one.
pub(crate) fn make_parents(out: &Path) -> Result<Vec<PathBuf>, Failure> {
    let mut missing: Vec<PathBuf> = out
        .ancestors()
        .skip(1)
        .take_while(|d| !d.as_os_str().is_empty() && !d.exists())
        .map(Path::to_path_buf)
        .collect();
    missing.reverse();
    let mut made = made();
    for d in &missing {
        if let Err(e) = std::fs::create_dir(d) {
            remove_dirs(&std::mem::take(&mut *made));
            return Err(Failure::usage_or_io(format!(
                "{}: cannot create the output's directory: {e}",
                d.display()
            )));
        }
        made.push(d.clone());
    }
    Ok(missing)
}

/// Removes directories made by [`make_parents`], innermost first; only empty ones go.
pub(crate) fn remove_dirs(dirs: &[PathBuf]) {
    for d in dirs.iter().rev() {
        let _ = std::fs::remove_dir(d);
    }
}

/// What the result must be before it is written.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Expect {
    /// A closed 2-manifold: the inputs were (booleans of solids, scene exports). Anything else
    /// is a fault, refused with exit 2 and nothing written.
    Closed,
    /// Anything (`convert`, or booleans of inputs let in by `--allow-open`): a result that is
    /// not closed is written with a warning.
    Any,
}

/// The refusal of a result that should be a closed 2-manifold and is not: a fault, exit 2.
/// Where it is open, the message says what to change: the open results seen come from faces
/// of two operands that nearly coincide (a 256×128 sphere less itself turned 10⁻⁴°: its pole
/// fans' facets cross their twins and each other nearly in parallel), or from a part far
/// smaller than what it meets (a cube of side 10⁻²⁰ at a unit cube's corner).
pub(crate) fn not_written(out: &Path, report: &MeshReport) -> Failure {
    let hint = if report.boundary_edges > 0 {
        "\nAn open result most often comes from faces of the operands that nearly coincide without being \
         equal (one operand a copy of another turned or moved by a hair): make such faces \
         coincide exactly, or move the operands clearly apart. It also comes from a part far \
         smaller than the parts it meets (10⁻¹² of their size or less): make it larger, or \
         leave it out."
    } else {
        ""
    };
    Failure {
        message: format!(
            "the result is not a closed 2-manifold, so {} is not written: {report}{hint}",
            out.display()
        ),
        code: 2,
    }
}

/// Writes the result and prints a summary, with a warning when the result is empty or (where
/// that is allowed) not a closed 2-manifold. A result expected closed that is made from a solid
/// (`made_from`: a boolean's, a scene's by the BSP route) must also bound the volume the solid's
/// polygons do ([`Solid::check_mesh_volume`]), or nothing is written (exit 2); `--allow-open`,
/// which takes a boolean's result as it comes, skips that check too.
pub(crate) fn finish(
    out: &Path,
    format: Format,
    mesh: &Mesh,
    materials: &[Material],
    expect: Expect,
    made_from: Option<&Solid>,
    progress: &Progress,
) -> Result<(), Failure> {
    progress.step("checking the result");
    let report = mesh.report();
    if expect == Expect::Closed && !mesh.is_empty() && !report.is_closed_manifold() {
        return Err(not_written(out, &report));
    }
    if let Some(solid) = made_from.filter(|_| expect == Expect::Closed) {
        solid.check_mesh_volume(mesh).map_err(|e| Failure {
            message: format!("{e}; {} is not written", out.display()),
            code: 2,
        })?;
    }
    progress.step(format!("writing {}", out.display()));
    // Directories too appear only once the work has succeeded, and go again if the write fails.
    let made = make_parents(out)?;
    if let Err(e) = write_mesh_as(out, mesh, materials, format) {
        remove_made_dirs();
        return Err(e.into());
    }
    keep_made_dirs();
    drop(made);
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
    } else if let Some(back) = bspcsg::as_read_back_from(mesh, format) {
        let back = back.report();
        let exact_closed = || {
            mesh.as_read_back()
                .is_none_or(|m| m.report().is_closed_manifold())
        };
        if !back.is_closed_manifold() && format != Format::Obj && exact_closed() {
            print_stderr(&format!(
                "bspcsg: warning: {} stores float32 coordinates, and the result has features \
                 finer than float32 resolves there (vertices that round to one, triangles that \
                 lose their area), so read back it is not a closed 2-manifold: {back} \
                 (OBJ keeps every coordinate)",
                out.display()
            ));
        } else if !back.is_closed_manifold() {
            print_stderr(&format!(
                "bspcsg: warning: {}: its shells touch along {} edges and at {} vertices where \
                 they cannot be told apart once read back, so read back it is not a closed \
                 2-manifold \
                 (`info` says so, and a boolean refuses it as an input unless given \
                 --allow-open)",
                out.display(),
                back.non_manifold_edges,
                back.non_manifold_vertices
            ));
        }
    }
    if !progress.quiet {
        print_stderr(&format!(
            "wrote {} ({format}): {} triangles, {} vertices, volume {}",
            out.display(),
            report.triangles,
            report.vertices,
            // An empty mesh's volume sums no terms: -0.0 only by the sign of nothing.
            report.volume + 0.0
        ));
    }
    Ok(())
}

/// Warns that an input holds no triangles: it is read as the empty mesh (a well-formed file
/// with no faces, as written for an empty result), which is allowed but rarely meant.
pub(crate) fn warn_if_empty_input(path: &Path, empty: bool, progress: &Progress) {
    if empty {
        progress.println(&format!(
            "bspcsg: warning: {} holds no triangles: read as the empty mesh",
            path.display()
        ));
    }
}

/// Prints to stdout. A closed pipe (`bspcsg info x | head -1`) is not an error.
pub(crate) fn print_stdout(text: &str) -> Result<(), Failure> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure::usage_or_io(format!(
            "cannot write to standard output: {e}"
        ))),
        _ => Ok(()),
    }
}

/// Prints a line to stderr; nothing more can be done if that fails.
pub(crate) fn print_stderr(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// Refuses an output whose companion file (`X.bin` beside `X.gltf`, `X.mtl` beside `X.obj`)
/// would replace one of the inputs or a file an input refers to (a glTF buffer, an OBJ
/// `mtllib`), or the output itself (`-o x.bin --format gltf`): the main output may replace
/// an input, which is read in full first, but a companion would break the input that needs it.
/// OBJ writes its `.mtl` only with `materials`.
pub(crate) fn protect_inputs(
    out: &Path,
    format: Format,
    materials: bool,
    inputs: &[&Path],
) -> Result<(), Failure> {
    let companion = match format {
        Format::Gltf => out.with_extension("bin"),
        Format::Obj if materials => out.with_extension("mtl"),
        _ => return Ok(()),
    };
    if companion == out || same_file(&companion, out) {
        return Err(Failure::usage_or_io(format!(
            "{}: cannot write the output: its companion {} would be the output itself; \
             give the output its format's extension",
            out.display(),
            companion.display()
        )));
    }
    for input in inputs {
        let mut needed = vec![input.to_path_buf()];
        needed.extend(bspcsg::referenced_files(input));
        if let Some(hit) = needed.iter().find(|p| same_file(&companion, p)) {
            return Err(Failure::usage_or_io(format!(
                "{}: cannot write the output: its companion {} would replace {}, which the \
                 input {} needs; choose another output name",
                out.display(),
                companion.display(),
                hit.display(),
                input.display()
            )));
        }
    }
    Ok(())
}

/// Whether two paths name one existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use bspcsg::{Format, Solid};

    use super::{Expect, finish};
    use crate::progress::Progress;

    /// Issue 12 (no silent wrong answer): a result that is a closed 2-manifold but bounds
    /// another volume than the solid it was made from is refused with exit 2 and not written;
    /// its own mesh is written, and a result allowed open is not held to it.
    #[test]
    fn a_closed_result_bounding_another_volume_than_its_solid_is_not_written() {
        let dir = std::env::temp_dir().join(format!("bspcsg-volume-guard-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("result.obj");
        let cube = Solid::cube(1.0).unwrap();
        let larger = Solid::cube(1.1).unwrap().to_mesh();
        let quiet = Progress::new(true);
        let refused = finish(
            &out,
            Format::Obj,
            &larger,
            &[],
            Expect::Closed,
            Some(&cube),
            &quiet,
        )
        .unwrap_err();
        assert_eq!(refused.code, 2);
        assert!(
            refused.message.contains("bounds a volume of 1.331000e0")
                && refused
                    .message
                    .contains("polygons bound 1.000000e0: they differ by 3.310e-1")
                && refused.message.ends_with("result.obj is not written"),
            "{}",
            refused.message
        );
        assert!(!out.exists());
        let own = cube.to_mesh();
        finish(
            &out,
            Format::Obj,
            &own,
            &[],
            Expect::Closed,
            Some(&cube),
            &quiet,
        )
        .unwrap();
        assert!(out.exists());
        std::fs::remove_file(&out).unwrap();
        finish(
            &out,
            Format::Obj,
            &larger,
            &[],
            Expect::Any,
            Some(&cube),
            &quiet,
        )
        .unwrap();
        assert!(out.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
