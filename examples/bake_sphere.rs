//! Bakes a unit sphere at a given resolution (default 128) and prints the median time, for a
//! ratio against manifold3d's level_set in the same session.
use bspcsg::{BakeOptions, Scene};
fn main() {
    let r: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(128);
    let s = Scene::from_json_str(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#,
    )
    .unwrap();
    let mut t = Vec::new();
    let mut tris = 0;
    for _ in 0..9 {
        let t0 = std::time::Instant::now();
        let m = s.bake(&BakeOptions::with_resolution(r)).unwrap();
        t.push(t0.elapsed().as_secs_f64() * 1e3);
        tris = m.triangle_count();
    }
    t.sort_by(f64::total_cmp);
    println!(
        "bspcsg bake sphere {r}^3: median {:.1} ms, {tris} triangles",
        t[4]
    );
}
