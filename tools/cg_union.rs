//! One sphere union (128×64 unless an argument says otherwise), for instruction counts under
//! callgrind; a second argument also runs `to_mesh`.
#[path = "../benches/common/cases.rs"]
mod cases;
fn main() {
    let n: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(128);
    let (a, b) = cases::sphere_pair(n);
    let u = &a | &b;
    let mesh_too = std::env::args().nth(2).is_some();
    if mesh_too {
        println!("{} triangles", u.to_mesh().triangle_count());
    } else {
        println!("{} polygons", u.polygon_count());
    }
}
