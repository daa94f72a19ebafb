//! Times the union of two 10,000-vertex random star polygons (the bench's case) once.

#[path = "../benches/common/sketch_cases.rs"]
mod cases;

fn main() {
    let a = cases::random_star(10_000, 1, glam::DVec2::ZERO);
    let b = cases::random_star(10_000, 2, glam::DVec2::new(0.3, 0.1));
    let t = std::time::Instant::now();
    let u = &a | &b;
    println!(
        "union: {:?}, {} regions, {} holes, {} vertices",
        t.elapsed(),
        u.regions().len(),
        u.regions().iter().map(|r| r.holes().len()).sum::<usize>(),
        u.vertex_count()
    );
}
