//! Booleans of the shared real meshes (`$BSPCSG_MODELS`, else `../shared/models`) with rotated
//! copies of themselves and of each other: time, inclusion–exclusion error, and whether each
//! result's mesh is a closed 2-manifold. A developer's probe, not an example of the API.
//!
//! usage: cargo run --release --example model_booleans

use bspcsg::{
    Solid,
    glam::{DQuat, DVec3},
    read_mesh,
};
use std::time::Instant;
fn load(name: &str) -> Solid {
    let dir = std::env::var("BSPCSG_MODELS").unwrap_or_else(|_| "../shared/models".into());
    let p = format!("{dir}/{name}.obj");
    Solid::from_mesh(&read_mesh(&p).unwrap()).unwrap()
}
fn check(label: &str, a: &Solid, b: &Solid) {
    let t = Instant::now();
    let (u, i, d) = (a | b, a & b, a - b);
    let dt = t.elapsed().as_secs_f64() * 1e3;
    let (va, vb) = (a.volume(), b.volume());
    let ie = (u.volume() + i.volume() - va - vb).abs() / va.max(vb);
    let de = (d.volume() - (va - i.volume())).abs() / va.max(vb);
    let mut line = format!("{label:28} {dt:8.1} ms  ie {ie:.1e} de {de:.1e}");
    for (n, s) in [("U", &u), ("I", &i), ("D", &d)] {
        let t = Instant::now();
        let m = s.to_mesh();
        let r = m.report();
        let verr = (m.volume() - s.volume()).abs() / va.max(vb);
        line += &format!(
            " | {n}: {} tris {} {:.0}ms vΔ{:.0e}{}",
            m.triangle_count(),
            if r.is_closed_manifold() { "ok" } else { "BAD" },
            t.elapsed().as_secs_f64() * 1e3,
            verr,
            if r.is_closed_manifold() {
                String::new()
            } else {
                format!(" [{}]", r.to_string().replace('\n', "; "))
            }
        );
    }
    println!("{line}");
}
fn main() {
    let names: Vec<String> = std::env::args().skip(1).collect();
    for name in ["spot", "fandisk", "rocker-arm"] {
        if !names.is_empty() && !names.contains(&name.to_string()) {
            continue;
        }
        let a = load(name);
        let bb = a.bbox();
        let d = bb.diagonal();
        let b = a
            .clone()
            .rotate(DQuat::from_axis_angle(
                DVec3::new(0.3, 1.0, 0.2).normalize(),
                0.4,
            ))
            .unwrap()
            .translate(bb.size() * 0.13)
            .unwrap();
        check(&format!("{name} op moved"), &a, &b);
        check(&format!("{name} op itself"), &a, &a);
        let boxx = Solid::cuboid(bb.size() * 0.6)
            .unwrap()
            .translate(bb.center() + DVec3::splat(d * 0.05))
            .unwrap();
        check(&format!("{name} op box"), &a, &boxx);
        let sph = Solid::sphere(d * 0.3, 48, 24)
            .unwrap()
            .translate(bb.center())
            .unwrap();
        check(&format!("{name} op sphere"), &a, &sph);
    }
    if names.is_empty() || names.contains(&"havoc".to_string()) {
        let (l, r) = (load("Havocglass8_left"), load("Havocglass8_right"));
        check("havocglass l op r", &l, &r);
        println!(
            "   expected union 3.05989e6 inter 68524.4: got {:.6e} {:.6}",
            (&l | &r).volume(),
            (&l & &r).volume()
        );
    }
    if names.is_empty() || names.contains(&"cray".to_string()) {
        let (l, r) = (load("Cray_left"), load("Cray_right"));
        check("cray l op r", &l, &r);
        println!(
            "   expected l-r 9.82418622e11: got {:.9e}",
            (&l - &r).volume()
        );
    }
}
