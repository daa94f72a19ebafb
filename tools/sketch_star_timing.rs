//! Times the union of two 10,000-vertex random star polygons and of 1,000 random circles (the
//! bench's cases) once each. With `--dump FILE` it also writes both cases' input rings as JSON,
//! so another library can time the same booleans on the same machine:
//!
//! ```text
//! cargo run --release --example sketch_star_timing -- --dump /tmp/sketch_cases.json
//! ```

#[path = "../benches/common/sketch_cases.rs"]
mod cases;

use bspcsg::Sketch;

fn rings(s: &Sketch) -> serde_json::Value {
    serde_json::json!(
        s.rings()
            .map(|r| r.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    )
}

fn main() {
    let a = cases::random_star(10_000, 1, glam::DVec2::ZERO);
    let b = cases::random_star(10_000, 2, glam::DVec2::new(0.3, 0.1));
    let circles = cases::random_circles(1000, 3);
    let t = std::time::Instant::now();
    let u = &a | &b;
    println!(
        "star union: {:?}, {} regions, {} holes, {} vertices, area {:.9}",
        t.elapsed(),
        u.regions().len(),
        u.regions().iter().map(|r| r.holes().len()).sum::<usize>(),
        u.vertex_count(),
        u.area()
    );
    let t = std::time::Instant::now();
    let c = Sketch::union_all(circles.clone());
    println!(
        "1000 circles: {:?}, {} regions, {} vertices, area {:.9}",
        t.elapsed(),
        c.regions().len(),
        c.vertex_count(),
        c.area()
    );
    let mut args = std::env::args().skip(1);
    if let (Some(flag), Some(path)) = (args.next(), args.next())
        && flag == "--dump"
    {
        let doc = serde_json::json!({
            "stars": [rings(&a), rings(&b)],
            "circles": circles.iter().map(rings).collect::<Vec<_>>(),
        });
        std::fs::write(&path, doc.to_string()).expect("writable dump path");
        println!("inputs written to {path}");
    }
}
