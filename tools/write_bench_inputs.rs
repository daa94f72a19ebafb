//! Writes the boolean benches' inputs as OBJ files (for timing manifold3d on the same meshes):
//! sphere pairs at 32–256 segments, the cube and sphere of `cube − sphere`, the block and the
//! union of its 10 × 10 cylinders, and the Menger sponge's cube and bar union.
//!
//! usage: cargo run --release --example write_bench_inputs -- OUT_DIR

#[path = "../benches/common/cases.rs"]
mod cases;

use bspcsg::{Solid, write_mesh};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).ok_or("usage: OUT_DIR")?);
    std::fs::create_dir_all(&dir)?;
    let put = |name: &str, s: &Solid| write_mesh(dir.join(name), &s.to_mesh(), &[]);
    for n in [32u32, 64, 128, 256] {
        let (a, b) = cases::sphere_pair(n);
        put(&format!("sphere{n}_a.obj"), &a)?;
        put(&format!("sphere{n}_b.obj"), &b)?;
    }
    put("cube.obj", &Solid::cube(1.6)?)?;
    put("sphere64.obj", &Solid::sphere(1.0, 64, 32)?)?;
    let (block, holes) = cases::block_and_holes(32);
    put("block.obj", &block)?;
    put("holes.obj", &holes)?;
    put("menger_cube.obj", &Solid::cube(1.0)?)?;
    put("menger_bars3.obj", &Solid::union_all(cases::menger_bars(3)))?;
    Ok(())
}
