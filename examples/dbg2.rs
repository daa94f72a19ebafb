use bspcsg::{Polygon, Solid, glam::DVec3, read_mesh};
fn load(name: &str) -> Solid {
    let p = format!("/work/shared/models/{name}.obj");
    Solid::from_mesh(&read_mesh(p.as_ref()).unwrap()).unwrap()
}
fn area(v: &[DVec3]) -> f64 {
    if v.len() < 3 {
        return 0.0;
    }
    let mut s = DVec3::ZERO;
    for i in 1..v.len() - 1 {
        s += (v[i] - v[0]).cross(v[i + 1] - v[0]);
    }
    0.5 * s.length()
}
fn clip(mut v: Vec<DVec3>, n: DVec3, a: DVec3) -> Vec<DVec3> {
    let mut out = vec![];
    for i in 0..v.len() {
        let (p, q) = (v[i], v[(i + 1) % v.len()]);
        let (dp, dq) = (n.dot(p - a), n.dot(q - a));
        if dp <= 0.0 {
            out.push(p);
        }
        if (dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    v.clear();
    out
}
fn main() {
    let l = load("Havocglass8_left");
    let r = load("Havocglass8_right").with_source(9999);
    let polys: Vec<Polygon> = l
        .polygons()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut p = p.clone();
            p.set_source(i as u32);
            p
        })
        .collect();
    let l = Solid::from_polygons(polys);
    let u = &l | &r;
    let d = &l - &r;
    let mut tot = 0.0;
    for (i, p) in l.polygons().iter().enumerate() {
        let mut inside = p.vertices().to_vec();
        for q in r.polygons() {
            inside = clip(inside, q.plane().normal, q.plane().anchor);
        }
        let expect = p.area() - area(&inside);
        let got_u: f64 = u
            .polygons()
            .iter()
            .filter(|x| x.source() == i as u32)
            .map(|x| x.area())
            .sum();
        let got_d: f64 = d
            .polygons()
            .iter()
            .filter(|x| x.source() == i as u32)
            .map(|x| x.area())
            .sum();
        if (got_u - expect).abs() > 1e-6 * p.area().max(1.0)
            || (got_d - expect).abs() > 1e-6 * p.area().max(1.0)
        {
            println!(
                "L{i}: area {:.4e} expect_out {:.6e} union {:.6e} diff {:.6e} n {:.5?}",
                p.area(),
                expect,
                got_u,
                got_d,
                p.plane().normal
            );
            tot += got_u - expect;
        }
    }
    println!("total union area error {tot:.4e}");
}
