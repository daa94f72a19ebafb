//! The `bspcsg` command line tool: argument parsing, progress and printing only. Every piece of
//! work — reading, checking, combining, repairing, baking, writing — is a library call.
//!
//! `cli.rs` holds the arguments, one file per subcommand does its work, `output.rs` checks the
//! output path and writes results, `failure.rs` maps errors to exit codes.

use std::process::ExitCode;

use bspcsg::BoolOp;
use clap::Parser;
use clap::error::ErrorKind;

/// The exit codes, shown in every `--help` and in the README. A macro so that `concat!` can put
/// it after each subcommand's examples.
macro_rules! exit_codes {
    () => {
        "Exit codes:
  0  success
  1  usage error; a file that cannot be read, parsed or written (a missing or truncated
     file, a syntax error, NaN or infinite coordinates, a vertex index out of range, an
     unknown extension, an invalid scene document, a glTF buffer URI that is not a regular
     file inside the document's folder); nothing is written
  2  invalid geometry: an input mesh that does not bound a solid (open, non-manifold,
     inside out; --allow-open goes on anyway), a result that is not a closed 2-manifold
     (booleans without --allow-open, export), a boolean beyond the precision contract
     (parts too small for their distance from the origin), or a result the output format
     cannot hold (coordinates beyond float32); an input over the reader's budget (a glTF
     placing more than 20 million triangles after instancing); booleans over their work
     budget (inputs whose faces nearly coincide over a wide area); nothing is written
  3  check: the mesh disagrees with the scene (each failed measure is named with its
     value, its limit and the worst place)"
    };
}

mod check;
mod cli;
mod combine;
mod convert;
mod edit;
mod export;
mod failure;
mod info;
mod output;
mod progress;
mod render;

use cli::{Cli, Command};
use output::print_stderr;
use progress::Progress;

/// SIGINT, SIGTERM and SIGHUP are taken by a thread of their own: it removes the temporary
/// files of a write in progress (putting back a companion already replaced) and, unless the
/// output was already renamed into place, the directories made for it, then exits 128 + the
/// signal's number (130 for SIGINT, 143 for SIGTERM), as a shell reports a process that a
/// signal ended.
fn handle_signals() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(sig) = signals.forever().next() {
            if bspcsg::cleanup_interrupted_writes() {
                // The output was already in place: it is whole, and it stays.
                print_stderr("bspcsg: interrupted after the output was written");
            } else {
                output::remove_made_dirs_before_exit();
                print_stderr("bspcsg: interrupted; no output written");
            }
            std::process::exit(128 + sig);
        }
    });
}

fn main() -> ExitCode {
    handle_signals();
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
        Command::Union(args) => combine::combine(BoolOp::Union, &args, &progress),
        Command::Intersection(args) => combine::combine(BoolOp::Intersection, &args, &progress),
        Command::Difference(args) => combine::combine(BoolOp::Difference, &args, &progress),
        Command::Info(args) => info::info(&args, &progress),
        Command::Convert(args) => convert::convert(&args, &progress),
        Command::Export(args) => export::export(&args, &progress),
        Command::Render(args) => render::render(&args, &progress),
        Command::Check(args) => check::check(&args, &progress),
        Command::Edit(args) => edit::edit(&args),
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
