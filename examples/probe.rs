use bspcsg::Solid;
use glam::DVec3;
use std::time::Instant;
fn main() {
    for n in [32u32, 64, 128, 256] {
        let a = Solid::sphere(1.0, n, n / 2).unwrap();
        let b = a.clone().translate(DVec3::new(0.5, 0.0, 0.0)).unwrap();
        let mut times = vec![];
        let mut u = Solid::empty();
        for _ in 0..7 {
            let t = Instant::now();
            u = &a | &b;
            times.push(t.elapsed().as_secs_f64() * 1e3);
        }
        times.sort_by(f64::total_cmp);
        println!(
            "n={n} polys={} -> {} polys, vol {:.6}, median {:.2} ms",
            a.polygon_count(),
            u.polygon_count(),
            u.volume(),
            times[3]
        );
    }
}
