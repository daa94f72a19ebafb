//! Writes the speed comparison's inputs as OBJ files, so bspcsg and manifold3d read the same
//! meshes (`tools/speed_table.sh` runs both on them): sphere pairs at 32–512 segments (and
//! 1024 with `--large`, the 1M-triangle case), the cube and sphere of `cube − sphere`, the
//! block and its 10 × 10 cylinders (disjoint, one file), the Menger sponge's cube and bar union,
//! and, when `BSPCSG_MODELS` names the test-model folder, spot, fandisk and rocker-arm each with
//! a moved copy.
//!
//! usage: cargo run --release --example write_bench_inputs -- OUT_DIR [--large]
//!
//! Files already present are kept (they are deterministic), so a second run is quick.

#[path = "../benches/common/cases.rs"]
mod cases;

use std::path::{Path, PathBuf};

use bspcsg::glam::DVec3;
use bspcsg::{Mesh, Solid, read_mesh, write_mesh};

/// The real models and how far their copies move: a fraction of their size, so the copies cut
/// through each other on curved and flat faces alike.
const MODEL_CASES: [(&str, [f64; 3]); 3] = [
    ("spot", [0.3, 0.1, 0.2]),
    ("fandisk", [0.5, 0.5, 0.25]),
    ("rocker-arm", [0.05, 0.02, 0.01]),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let large = args.iter().any(|a| a == "--large");
    args.retain(|a| a != "--large");
    let dir = PathBuf::from(args.first().ok_or("usage: OUT_DIR [--large]")?);
    std::fs::create_dir_all(&dir)?;
    let put = |name: &str, make: &dyn Fn() -> Result<Mesh, Box<dyn std::error::Error>>| {
        let path = dir.join(name);
        if path.exists() {
            return Ok::<(), Box<dyn std::error::Error>>(());
        }
        write_mesh(&path, &make()?, &[])?;
        Ok(())
    };
    let mut sizes = vec![32u32, 64, 128, 256, 512];
    if large {
        sizes.push(1024);
    }
    for n in sizes {
        put(&format!("sphere{n}_a.obj"), &|| {
            Ok(sphere_mesh(n, DVec3::ZERO))
        })?;
        put(&format!("sphere{n}_b.obj"), &|| {
            Ok(sphere_mesh(n, DVec3::new(0.5, 0.0, 0.0)))
        })?;
    }
    put("cube.obj", &|| Ok(Solid::cube(1.6)?.to_mesh()))?;
    put("cube2.obj", &|| Ok(Solid::cube(2.0)?.to_mesh()))?;
    put(
        "sphere64.obj",
        &|| Ok(Solid::sphere(1.0, 64, 32)?.to_mesh()),
    )?;
    let (block, holes) = cases::block_and_holes(32);
    put("block.obj", &|| Ok(block.to_mesh()))?;
    put("holes.obj", &|| Ok(holes.to_mesh()))?;
    put("menger_cube.obj", &|| Ok(Solid::cube(1.0)?.to_mesh()))?;
    put("menger_bars3.obj", &|| {
        Ok(Solid::union_all(cases::menger_bars(3)).to_mesh())
    })?;
    if let Some(models) = std::env::var_os("BSPCSG_MODELS") {
        for (name, offset) in MODEL_CASES {
            let source = Path::new(&models).join(format!("{name}.obj"));
            let mesh = read_mesh(&source)?;
            put(&format!("{name}_a.obj"), &|| Ok(mesh.clone()))?;
            put(&format!("{name}_b.obj"), &|| {
                Ok(moved(&mesh, DVec3::from_array(offset)))
            })?;
        }
    } else {
        eprintln!("BSPCSG_MODELS is not set: the real-model cases are not written");
    }
    Ok(())
}

/// The UV sphere of radius 1 with `n × n/2` segments, centred at `centre`, as the plain quads
/// and pole triangles of the primitive fanned into triangles (what a mesh file of it holds).
fn sphere_mesh(n: u32, centre: DVec3) -> Mesh {
    Solid::sphere(1.0, n, n / 2)
        .and_then(|s| s.translate(centre))
        .expect("a sphere with at least 3 segments is valid")
        .to_mesh_unrepaired()
}

fn moved(mesh: &Mesh, by: DVec3) -> Mesh {
    let mut out = mesh.clone();
    for p in &mut out.positions {
        *p += by;
    }
    out
}
