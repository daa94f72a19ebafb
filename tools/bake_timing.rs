//! Quick timing of a bake: `cargo run --release --example bake_timing -- SCENE.json RES`.

use std::time::Instant;

use bspcsg::{BakeOptions, Scene};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let scene = match args.get(1).map(String::as_str) {
        Some("sphere") | None => Scene::from_json_str(
            r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#,
        )?,
        Some(path) => Scene::from_path(path)?,
    };
    let res: u32 = args.get(2).map(|s| s.parse()).transpose()?.unwrap_or(128);
    let opts = BakeOptions::with_resolution(res);
    let mut times = Vec::new();
    let mut mesh = scene.bake(&opts)?;
    for _ in 0..10 {
        let t = Instant::now();
        mesh = scene.bake(&opts)?;
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    println!(
        "{} triangles, {} vertices, volume {:.6}, of 10 runs: median {:.1} ms, best {:.1} ms",
        mesh.triangle_count(),
        mesh.vertex_count(),
        mesh.volume(),
        times[5] * 1e3,
        times[0] * 1e3
    );
    Ok(())
}
