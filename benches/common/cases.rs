//! Bench and test cases shared by `benches/booleans.rs` and `tests/cases.rs`.
#![allow(dead_code)]

use bspcsg::Solid;
use glam::DVec3;

/// A `segments × segments/2` sphere and the same moved by half its radius along X.
pub fn sphere_pair(segments: u32) -> (Solid, Solid) {
    let a = Solid::sphere(1.0, segments, segments / 2).unwrap();
    let b = a.clone().translate(DVec3::new(0.5, 0.0, 0.0)).unwrap();
    (a, b)
}

/// A unit block 10 × 1 × 10 and the union of a 10 × 10 grid of cylinders through it.
pub fn block_and_holes(segments: u32) -> (Solid, Solid) {
    let block = Solid::cuboid(DVec3::new(10.0, 1.0, 10.0)).unwrap();
    let holes = Solid::union_all((0..100).map(|k| {
        let (i, j) = ((k / 10) as f64, (k % 10) as f64);
        Solid::cylinder(0.3, 2.0, segments)
            .unwrap()
            .translate(DVec3::new(i - 4.5, 0.0, j - 4.5))
            .unwrap()
    }));
    (block, holes)
}

/// The bars a Menger sponge of the given depth removes from the unit cube centred at 0.
pub fn menger_bars(depth: u32) -> Vec<Solid> {
    let mut bars = Vec::new();
    for level in 1..=depth {
        let cells = 3u32.pow(level - 1);
        let cell = 1.0 / cells as f64;
        let hole = cell / 3.0;
        for axis in 0..3 {
            for i in 0..cells {
                for j in 0..cells {
                    let (u, v) = (
                        -0.5 + cell * (i as f64 + 0.5),
                        -0.5 + cell * (j as f64 + 0.5),
                    );
                    let (size, centre) = match axis {
                        0 => (DVec3::new(1.5, hole, hole), DVec3::new(0.0, u, v)),
                        1 => (DVec3::new(hole, 1.5, hole), DVec3::new(u, 0.0, v)),
                        _ => (DVec3::new(hole, hole, 1.5), DVec3::new(u, v, 0.0)),
                    };
                    bars.push(Solid::cuboid(size).unwrap().translate(centre).unwrap());
                }
            }
        }
    }
    bars
}

/// The Menger sponge of the given depth: the unit cube minus the union of its bars.
pub fn menger_sponge(depth: u32) -> Solid {
    let cube = Solid::cube(1.0).unwrap();
    cube - Solid::union_all(menger_bars(depth))
}
