//! Random primitive booleans under random rigid motions: how many results' meshes are not
//! closed 2-manifolds or lose volume. A quick robustness probe while changing the kernel.
//!
//! usage: cargo run --release --example random_booleans -- [CASES] [SEED]
use bspcsg::Solid;
use glam::{DQuat, DVec3};
use std::time::Instant;
fn lcg(s: &mut u64) -> f64 {
    *s = s
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    ((*s >> 11) as f64) / ((1u64 << 53) as f64)
}
fn prim(s: &mut u64) -> Solid {
    let k = (lcg(s) * 5.0) as u32;
    let seg = 5 + (lcg(s) * 20.0) as u32;
    let sz = |s: &mut u64| 0.3 + 1.2 * lcg(s);
    let p = match k {
        0 => Solid::cuboid(DVec3::new(sz(s), sz(s), sz(s))),
        1 => Solid::sphere(sz(s) * 0.7, seg, seg / 2 + 2),
        2 => Solid::cylinder(sz(s) * 0.6, sz(s), seg),
        3 => Solid::torus(0.6, 0.25, seg, seg / 2 + 3),
        _ => Solid::frustum(sz(s) * 0.6, sz(s) * 0.3, sz(s), seg),
    }
    .unwrap();
    let axis = DVec3::new(lcg(s) - 0.5, lcg(s) - 0.5, lcg(s) - 0.5).normalize();
    p.rotate(DQuat::from_axis_angle(axis, lcg(s) * 6.3))
        .unwrap()
        .translate(DVec3::new(lcg(s) - 0.5, lcg(s) - 0.5, lcg(s) - 0.5) * 1.6)
        .unwrap()
}
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(200);
    let mut s = std::env::args()
        .nth(2)
        .and_then(|a| a.parse().ok())
        .unwrap_or(12345u64);
    let (mut bad, mut total) = (0, 0);
    let t0 = Instant::now();
    for case in 0..n {
        let a = prim(&mut s);
        let b = prim(&mut s);
        for (name, r) in [("union", &a | &b), ("inter", &a & &b), ("diff", &a - &b)] {
            total += 1;
            let m = r.to_mesh();
            let rep = m.report();
            let vol_err = (m.volume() - r.volume()).abs() / a.volume().max(b.volume());
            if !rep.is_closed_manifold() || vol_err > 1e-9 {
                bad += 1;
                if bad <= 10 {
                    println!(
                        "case {case} {name}: vol_err {vol_err:.2e} {}",
                        rep.to_string().replace('\n', " | ")
                    );
                }
            }
        }
    }
    println!("{bad}/{total} bad in {:.1}s", t0.elapsed().as_secs_f64());
}
