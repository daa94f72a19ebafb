//! Output shared by the subcommands: the output path checked before any work, the result
//! written (directories made only then, and removed again if the write fails) with its
//! summary, and printing that survives closed pipes.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use bspcsg::{Format, Material, Mesh, write_mesh_as};

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

/// Creates the missing directories above `out`, returning those it made, outermost first.
pub(crate) fn make_parents(out: &Path) -> Result<Vec<PathBuf>, Failure> {
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
pub(crate) fn remove_dirs(dirs: &[PathBuf]) {
    for d in dirs.iter().rev() {
        let _ = std::fs::remove_dir(d);
    }
}

/// Writes the result and prints a summary, with a warning when the result is empty or not a
/// closed 2-manifold (from inputs let in by `--allow-open` or `convert`, or a library fault).
pub(crate) fn finish(
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
