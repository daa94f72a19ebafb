//! Renders every example scene to PNG with its own render profile and the default camera, and
//! its BSP-route mesh beside it (`NAME-mesh.png`):
//! `cargo run --release --example render_gallery -- OUT_DIR [WIDTHxHEIGHT]`.

use std::time::Instant;

use bspcsg::raymarch::{Camera, RenderOptions, View, render_mesh, render_scene};
use bspcsg::{Scene, TessellationOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = std::path::PathBuf::from(args.next().unwrap_or_else(|| ".".into()));
    let size = args.next().unwrap_or_else(|| "800x600".into());
    let (w, h) = size.split_once('x').ok_or("size must be WxH")?;
    let size = (w.parse()?, h.parse()?);
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenes");
    let mut paths: Vec<_> = std::fs::read_dir(dir)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    paths.sort();
    for path in paths {
        let scene = Scene::from_path(&path)?;
        let camera = Camera::for_scene(&scene, View::Iso, size)?;
        let opts = RenderOptions::with_profile(scene.render_profile().clone());
        let start = Instant::now();
        let image = render_scene(&scene, &camera, &opts)?;
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        println!("{name}: {:.3} s", start.elapsed().as_secs_f64());
        image.write_png(out.join(format!("{name}.png")))?;
        // The same scene meshed by the BSP route and ray cast.
        let mesh = scene.to_solid(&TessellationOptions::default())?.to_mesh();
        let start = Instant::now();
        let image = render_mesh(&mesh, scene.materials(), &camera, &opts)?;
        println!(
            "{name} mesh ({} triangles): {:.3} s",
            mesh.triangle_count(),
            start.elapsed().as_secs_f64()
        );
        image.write_png(out.join(format!("{name}-mesh.png")))?;
    }
    Ok(())
}
