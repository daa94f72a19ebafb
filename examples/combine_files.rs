//! Combine two mesh files, and handle input that is not a solid.
//!
//! Reads two meshes (OBJ, STL, glTF), makes solids of them, and writes their union,
//! intersection or difference. Input that does not bound a solid is refused with the reason;
//! this example shows how to tell the kinds apart and, for open or inside-out meshes, go on
//! anyway with the lenient options, as the `bspcsg` command line does with `--allow-open`.
//!
//! ```text
//! cargo run --release --example combine_files -- A.obj B.stl union|intersection|difference OUT.glb
//! ```

use std::path::Path;
use std::process::ExitCode;

use bspcsg::{BoolOp, Error, FromMeshOptions, MeshDefect, Solid, boolean, read_solid, write_mesh};

/// A solid from a file: strict first; lenient, with a warning, where the mesh is only open or
/// inside out.
fn load(path: &Path) -> Result<Solid, Error> {
    match read_solid(path, &FromMeshOptions::default()) {
        Ok(solid) => Ok(solid),
        Err(e) => match e.mesh_defect() {
            Some(MeshDefect::NotClosed { .. } | MeshDefect::InsideOut { .. }) => {
                eprintln!("warning: {e}; going on with the lenient options");
                read_solid(path, &FromMeshOptions::lenient())
            }
            // Files that cannot be read or parsed, indices out of range, NaN coordinates …
            _ => Err(e),
        },
    }
}

fn run(a: &str, b: &str, op: BoolOp, out: &str) -> Result<(), Error> {
    let (a, b) = (load(Path::new(a))?, load(Path::new(b))?);
    // Source ids say which input each output triangle came from.
    let result = boolean(&a.with_source(0), &b.with_source(1), op);
    let mesh = result.to_mesh();
    let report = mesh.report();
    println!("{op}: {report}");
    write_mesh(out, &mesh, &[])?;
    println!("wrote {out}");
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [a, b, op, out] = args.as_slice() else {
        eprintln!("usage: combine_files A B union|intersection|difference OUT");
        return ExitCode::from(2);
    };
    // BoolOp parses its own names (and the scene format's `intersect` and `subtract`).
    let op: BoolOp = match op.parse() {
        Ok(op) => op,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    match run(a, b, op, out) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
