#[path = "../benches/common/cases.rs"]
mod cases;
use std::time::Instant;
fn med(mut f: impl FnMut() -> usize) -> (f64, usize) {
    let mut t = vec![];
    let mut n = 0;
    for _ in 0..9 {
        let s = Instant::now();
        n = f();
        t.push(s.elapsed().as_secs_f64() * 1e3);
    }
    t.sort_by(f64::total_cmp);
    (t[4], n)
}
fn main() {
    for n in [32u32, 64, 128, 256] {
        let (a, b) = cases::sphere_pair(n);
        let (t, c) = med(|| (&a | &b).polygon_count());
        println!(
            "sphere {n}: {t:.2} ms, {c} polys, vol {:.9}",
            (&a | &b).volume()
        );
    }
    let (t, c) = med(|| cases::menger_sponge(3).polygon_count());
    println!(
        "menger3: {t:.2} ms {c} polys vol {:.9}",
        cases::menger_sponge(3).volume()
    );
    let (bl, h) = cases::block_and_holes(32);
    let (t, c) = med(|| (&bl - &h).polygon_count());
    println!("block-holes: {t:.2} ms {c} polys");
}
