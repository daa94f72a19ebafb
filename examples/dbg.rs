use bspcsg::{Solid, read_mesh};
fn load(name: &str) -> Solid {
    let p = format!("/work/shared/models/{name}.obj");
    let m = read_mesh(p.as_ref()).unwrap();
    println!(
        "{name}: {} bbox {:?}",
        m.report().to_string().lines().next().unwrap(),
        m.bbox()
    );
    Solid::from_mesh(&m).unwrap()
}
fn main() {
    let (l, r) = (load("Havocglass8_left"), load("Havocglass8_right"));
    println!("vol l {} r {}", l.volume(), r.volume());
    let u = &l | &r;
    println!(
        "union eps {:e} polys {}",
        u.carried_eps(),
        u.polygon_count()
    );
    let i = &l & &r;
    let d = &l - &r;
    let d2 = &r - &l;
    println!(
        "U {} I {} D {} D2 {}",
        u.volume(),
        i.volume(),
        d.volume(),
        d2.volume()
    );
    println!(
        "U+I-L-R = {:e}",
        u.volume() + i.volume() - l.volume() - r.volume()
    );
    println!("D - (L - I) = {:e}", d.volume() - (l.volume() - i.volume()));
    println!(
        "D2 - (R - I) = {:e}",
        d2.volume() - (r.volume() - i.volume())
    );
    let raw = u.to_mesh_unrepaired().report();
    println!("raw union: {}", raw.to_string().replace("\n", "; "));
    let m = u.to_mesh();
    for (a, b) in boundary_edges(&m) {
        println!(
            "  edge {:?} -> {:?}  len {:.3e}",
            m.positions[a as usize],
            m.positions[b as usize],
            m.positions[a as usize].distance(m.positions[b as usize])
        );
    }
}
pub fn boundary_edges(m: &bspcsg::Mesh) -> Vec<(u32, u32)> {
    use std::collections::HashMap;
    let mut c: HashMap<(u32, u32), i32> = HashMap::new();
    for t in &m.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *c.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut v: Vec<_> = c
        .into_iter()
        .filter(|(_, n)| *n != 2)
        .map(|(e, _)| e)
        .collect();
    v.sort();
    v
}
