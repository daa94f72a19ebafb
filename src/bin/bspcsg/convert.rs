//! `convert`: read a mesh in one format, write it in another.

use bspcsg::read_mesh;

use crate::cli::ConvertArgs;
use crate::failure::Failure;
use crate::output::{Expect, finish, output_target, protect_inputs, warn_if_empty_input};
use crate::progress::Progress;

/// `convert`.
pub(crate) fn convert(args: &ConvertArgs, progress: &Progress) -> Result<(), Failure> {
    let (out, format) = output_target(&args.output)?;
    protect_inputs(out, format, false, &[args.input.as_path()])?;
    progress.step(format!("reading {}", args.input.display()));
    let mesh = read_mesh(&args.input)?;
    warn_if_empty_input(&args.input, mesh.is_empty(), progress);
    finish(out, format, &mesh, &[], Expect::Any, None, progress)
}
