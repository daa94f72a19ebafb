//! Sketch bench and test cases shared by `benches/sketch.rs` and `tests/sketch.rs`.
#![allow(dead_code)]

use std::f64::consts::TAU;

use bspcsg::{FillRule, Sketch};
use glam::DVec2;

/// A small deterministic generator (xorshift64*), so cases repeat without a dependency.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed.max(1))
    }

    /// Uniform in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A star polygon of `n` vertices at evenly spaced angles, radii uniform in [0.5, 1].
pub fn random_star(n: usize, seed: u64, centre: DVec2) -> Sketch {
    let mut rng = Rng::new(seed);
    let pts: Vec<DVec2> = (0..n)
        .map(|i| centre + DVec2::from_angle(TAU * i as f64 / n as f64) * (0.5 + 0.5 * rng.next()))
        .collect();
    Sketch::polygon(&pts, FillRule::NonZero).unwrap()
}

/// `n` circles of radius 0.5 (chordal tolerance 1e-3) at random centres in a square sized so
/// that they overlap in chains and leave holes.
pub fn random_circles(n: usize, seed: u64) -> Vec<Sketch> {
    let mut rng = Rng::new(seed);
    let side = (n as f64).sqrt() * 0.8;
    let circle = Sketch::circle(0.5, 1e-3).unwrap();
    (0..n)
        .map(|_| {
            circle
                .translate(DVec2::new(rng.next() * side, rng.next() * side))
                .unwrap()
        })
        .collect()
}

/// An `n × n` grid of circles of radius 0.3 (chordal tolerance 1e-3), one per unit cell of a
/// square of side `n` centred at the origin.
pub fn hole_grid(n: usize) -> Vec<Sketch> {
    let circle = Sketch::circle(0.3, 1e-3).unwrap();
    let half = n as f64 / 2.0;
    (0..n * n)
        .map(|k| {
            let (i, j) = ((k / n) as f64, (k % n) as f64);
            circle
                .translate(DVec2::new(i + 0.5 - half, j + 0.5 - half))
                .unwrap()
        })
        .collect()
}
