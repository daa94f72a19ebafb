//! One 128×64 sphere union, for instruction counts under callgrind.
#[path = "../benches/common/cases.rs"]
mod cases;
fn main() {
    let n: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(128);
    let (a, b) = cases::sphere_pair(n);
    let u = &a | &b;
    println!("{}", u.polygon_count());
}
