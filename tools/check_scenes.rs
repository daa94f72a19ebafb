//! Checks every example scene against its own meshes by both routes and prints the agreement
//! figures: `cargo run --release --example check_scenes`.

use std::time::Instant;

use bspcsg::raymarch::{CheckOptions, check_mesh};
use bspcsg::{BakeOptions, Scene, TessellationOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenes");
    let mut paths: Vec<_> = std::fs::read_dir(dir)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    paths.sort();
    println!(
        "| scene | route | triangles | T | rays agree % | depth p99 | depth max | surface max | surface p99 | coverage max | coverage p99 | sign % | check time |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for path in paths {
        let scene = Scene::from_path(&path)?;
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let diag = scene.bbox().diagonal();
        for route in ["sdf", "bsp"] {
            let (mesh, tol) = if route == "sdf" {
                let cell = scene.bbox().size().max_element() / 128.0;
                (scene.bake(&BakeOptions::with_cell(cell))?, cell)
            } else {
                // As `bspcsg check --via bsp`: twice the default chordal tolerance (smooth
                // blends are baked at four times it).
                let tol = diag / 500.0;
                (
                    scene
                        .to_solid(&TessellationOptions::with_tolerance(tol))?
                        .to_mesh(),
                    2.0 * tol,
                )
            };
            let start = Instant::now();
            let r = check_mesh(
                &scene,
                &mesh,
                &CheckOptions {
                    tolerance: Some(tol),
                    ..Default::default()
                },
            )?;
            println!(
                "| {name} | {route} | {} | {tol:.4} | {:.3} | {:.4} | {:.3} | {:.4} | {:.4} | {:.4} | {:.4} | {:.2} | {:.2} s |",
                mesh.triangle_count(),
                r.rays.agreement_pct,
                r.rays.depth_p99,
                r.rays.depth_max,
                r.surface.max,
                r.surface.p99,
                r.coverage.max,
                r.coverage.p99,
                r.sign.agreement_pct,
                start.elapsed().as_secs_f64()
            );
            for f in &r.failures {
                println!("    FAIL {f}");
            }
        }
    }
    Ok(())
}
