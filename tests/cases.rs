//! Larger cases with known answers: the Menger sponge, a block with a grid of holes.

#[path = "../benches/common/cases.rs"]
mod cases;
mod common;

use approx::assert_relative_eq;
use bspcsg::Solid;
use common::{assert_clean_mesh, shells_and_genus};

#[test]
fn menger_sponge_volumes() {
    for depth in 1..=3 {
        let sponge = cases::menger_sponge(depth);
        assert_relative_eq!(
            sponge.volume(),
            (20.0f64 / 27.0).powi(depth as i32),
            max_relative = 1e-12
        );
        // One shell, of the Menger sponge's known genus: 5, 81 and 1409 at depths 1 to 3.
        let mesh = assert_clean_mesh(&sponge, "sponge");
        let (shells, genus) = shells_and_genus(&mesh, "sponge");
        assert_eq!(shells, 1);
        assert_eq!(genus, [5, 81, 1409][depth as usize - 1], "depth {depth}");
    }
}

#[test]
fn sequential_and_balanced_unions_agree() {
    let bars = cases::menger_bars(2);
    let sequential = bars.iter().fold(Solid::empty(), |acc, b| &acc | b);
    let balanced = Solid::union_all(bars);
    assert_relative_eq!(sequential.volume(), balanced.volume(), max_relative = 1e-12);
    assert_clean_mesh(&sequential, "sequential union");
    assert_clean_mesh(&balanced, "balanced union");
}

#[test]
fn block_minus_grid_of_cylinders() {
    let segments = 32;
    let (block, holes) = cases::block_and_holes(segments);
    let n = segments as f64;
    let hole_area = 0.5 * n * 0.3 * 0.3 * (std::f64::consts::TAU / n).sin();
    let part = &block - &holes;
    assert_relative_eq!(
        part.volume(),
        100.0 - 100.0 * hole_area,
        max_relative = 1e-12
    );
}
