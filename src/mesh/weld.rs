//! Bit-exact vertex welding: equal coordinates become one vertex.

use glam::DVec3;
use rayon::prelude::*;
use smallvec::SmallVec;

use crate::hash::{KeyedBuild, KeyedHashMap, key};

/// Assigns one index per distinct position.
#[derive(Default)]
pub(crate) struct Welder {
    map: KeyedHashMap<[u64; 3], u32>,
    pub positions: Vec<DVec3>,
}

impl Welder {
    pub fn with_capacity(n: usize) -> Self {
        Welder {
            map: KeyedHashMap::with_capacity_and_hasher(n, KeyedBuild::default()),
            positions: Vec::with_capacity(n),
        }
    }

    /// The index of `p`, new if no equal position was seen.
    #[inline]
    pub fn index(&mut self, p: DVec3) -> u32 {
        let next = self.positions.len() as u32;
        let i = *self.map.entry(key(p)).or_insert(next);
        if i == next {
            self.positions.push(p);
        }
        i
    }
}

mod grid;

/// From this many points on, and with more than one thread, the exact weld runs in two halves
/// (below it the join costs more than it saves).
const HALVES_FROM: usize = 1 << 13;

/// From this many distinct positions on, and with more than one thread, the grid pass marks
/// the lone positions in parallel and walks only the rest (see [`grid::lone_apart`]).
const LONE_FROM: usize = 1 << 11;

/// One index per distinct position of `points`, numbered in the order positions are first met
/// (as [`Welder::index`] over `points` in order): the positions and each point's index.
pub(crate) fn weld_exact(points: &[DVec3]) -> (Vec<DVec3>, Vec<u32>) {
    if points.len() >= HALVES_FROM && rayon::current_num_threads() > 1 {
        weld_exact_in_halves(points)
    } else {
        weld_exact_serial(points)
    }
}

fn weld_exact_serial(points: &[DVec3]) -> (Vec<DVec3>, Vec<u32>) {
    let (exact, first) = welded(points);
    (exact.positions, first)
}

/// The welder holding `points`' distinct positions, and each point's index in it.
fn welded(points: &[DVec3]) -> (Welder, Vec<u32>) {
    let mut exact = Welder::with_capacity(points.len());
    let first: Vec<u32> = points.iter().map(|&p| exact.index(p)).collect();
    (exact, first)
}

/// [`weld_exact`] with each half welded on its own thread, then merged: a position of the
/// second half the first half holds takes the first half's index; one first met in the second
/// half is numbered after every position of the first half, in second-half order. That is the
/// serial numbering, bit for bit (the first half's positions are its first occurrences, and the
/// second half's new ones follow in the order the serial weld meets them).
fn weld_exact_in_halves(points: &[DVec3]) -> (Vec<DVec3>, Vec<u32>) {
    let (a, b) = points.split_at(points.len() / 2);
    let ((first_half, mut first), (second_half, second)) = rayon::join(|| welded(a), || welded(b));
    // Per distinct position of the second half: its index in the first half, or none.
    let mut renumber: Vec<u32> = second_half
        .positions
        .par_iter()
        .map(|&p| first_half.map.get(&key(p)).copied().unwrap_or(u32::MAX))
        .collect();
    let mut positions = first_half.positions;
    for (r, &p) in renumber.iter_mut().zip(&second_half.positions) {
        if *r == u32::MAX {
            *r = positions.len() as u32;
            positions.push(p);
        }
    }
    first.par_extend(second.par_iter().map(|&i| renumber[i as usize]));
    (positions, first)
}

/// Where a wider weld is allowed: around the vertices of cracks an earlier pass left. A point
/// within `2 · delta` of one of them may weld and join edges `delta` away; the partner of a
/// crack vertex need not lie on a crack itself.
#[derive(Clone, Default)]
pub(crate) struct Wide {
    points: Vec<DVec3>,
    /// Cells of input-derived points: keyed (see `crate::hash`).
    grid: KeyedHashMap<[i64; 3], SmallVec<[u32; 2]>>,
    delta: f64,
}

impl Wide {
    /// Widens to `delta` around `points` (plus the points widened before).
    pub fn widen(&mut self, points: &[DVec3], delta: f64) {
        self.points.extend_from_slice(points);
        self.delta = delta;
        self.grid.clear();
        for (i, &p) in self.points.iter().enumerate() {
            self.grid.entry(self.cell(p)).or_default().push(i as u32);
        }
    }

    fn cell(&self, p: DVec3) -> [i64; 3] {
        cell_of(p, 2.0 * self.delta)
    }

    /// The weld reach of `p`: `self.delta` near a crack, else `delta`.
    pub fn reach(&self, p: DVec3, delta: f64) -> f64 {
        if self.points.is_empty() {
            return delta;
        }
        let c = self.cell(p);
        for dx in -1..=1i64 {
            for dy in -1..=1i64 {
                for dz in -1..=1i64 {
                    let k = [
                        c[0].saturating_add(dx),
                        c[1].saturating_add(dy),
                        c[2].saturating_add(dz),
                    ];
                    if let Some(list) = self.grid.get(&k)
                        && list
                            .iter()
                            .any(|&i| self.points[i as usize].distance(p) <= 2.0 * self.delta)
                    {
                        return self.delta.max(delta);
                    }
                }
            }
        }
        delta
    }

    /// The widest reach any point may have.
    pub fn widest(&self, delta: f64) -> f64 {
        if self.points.is_empty() {
            delta
        } else {
            self.delta.max(delta)
        }
    }
}

/// Welds points within reach of each other: each point maps to the first earlier
/// representative within the larger of their reaches (`delta`, or `wide.delta` for listed
/// points), or becomes one. Representatives are more than `delta` apart, so clusters cannot
/// chain along a line of close points. Returns the representatives and, for each input point,
/// its representative's index.
pub(crate) fn weld_within(points: &[DVec3], delta: f64, wide: &Wide) -> (Vec<DVec3>, Vec<u32>) {
    let (positions, first) = weld_exact(points);
    if delta <= 0.0 {
        return (positions, first);
    }
    let (reps, rep_of) = if positions.len() >= LONE_FROM && rayon::current_num_threads() > 1 {
        grid::lone_apart(&positions, delta, wide, rayon::current_num_threads())
    } else {
        grid::serial(&positions, delta, wide)
    };
    let map = first.par_iter().map(|&i| rep_of[i as usize]).collect();
    (reps, map)
}

/// The grid cell of side `size` holding `p`.
#[inline]
fn cell_of(p: DVec3, size: f64) -> [i64; 3] {
    let c = p / size;
    [floor(c.x), floor(c.y), floor(c.z)]
}

/// `x.floor() as i64` (saturating, NaN to 0) without the library call (a call per axis of every
/// distinct position was 1.5 M instructions of a to_mesh on rocker-arm).
#[inline]
fn floor(x: f64) -> i64 {
    // Truncation toward zero, exact where `x` fits; one less where that rounded a negative
    // fraction up. Saturated ends stay (at the low end, one less saturates too).
    let t = x as i64;
    if (t as f64) > x {
        t.saturating_sub(1)
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use std::hash::BuildHasher;

    use super::*;
    use crate::hash::FxBuild;
    use crate::hash::test_support::{bucket_collisions, lcg};

    /// The exact weld in two halves numbers positions as the serial weld does, bit for bit:
    /// repeats within each half and across the halves, a position first met in the second half
    /// (numbered after all of the first half's), and the signed zeros that are one key (the
    /// first one met is kept).
    #[test]
    fn the_exact_weld_in_halves_is_the_serial_weld() {
        let mut next = lcg(11);
        for n in [2usize, 3, 17, 1000, 5000] {
            for spread in [1u64, 7, 40, 4000] {
                let points: Vec<DVec3> = (0..n)
                    .map(|_| {
                        let c = |s: u64| (s % spread) as f64 - (spread / 2) as f64;
                        let p = DVec3::new(c(next() >> 20), c(next() >> 20), 0.0);
                        if next() >> 63 == 1 { -p } else { p }
                    })
                    .collect();
                let (serial, first) = weld_exact_serial(&points);
                let (halves, first_halves) = weld_exact_in_halves(&points);
                let bits = |v: &[DVec3]| v.iter().map(|p| key_bits(*p)).collect::<Vec<_>>();
                assert_eq!(bits(&serial), bits(&halves), "{n} points, spread {spread}");
                assert_eq!(first, first_halves, "{n} points, spread {spread}");
                // A weld that merges nothing (spread 4000 over 17 points) is tested too, and
                // one that merges most (spread 1).
                assert!(serial.len() <= n);
            }
        }
    }

    /// The raw bits of `p`, signed zeros apart.
    fn key_bits(p: DVec3) -> [u64; 3] {
        [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
    }

    /// The cell floor agrees with the library's floor, saturation and NaN included.
    #[test]
    fn floor_matches_the_library() {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1.5,
            2.5e15,
            -2.5e15 - 0.5,
            9.3e18,
            -9.3e18,
            1e300,
            -1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            -(2f64.powi(63)),
        ];
        let mut next = lcg(7);
        for _ in 0..1000 {
            let s = next();
            xs.push(f64::from_bits(s));
            xs.push((s >> 11) as f64 / (1u64 << 40) as f64 - 4096.0);
        }
        for x in xs {
            assert_eq!(floor(x), x.floor() as i64, "{x}");
        }
    }

    /// Issue 12 item 8: positions crafted so that the crate's former unkeyed position hash
    /// (FxHash over the key) puts them all in one bucket cost the welder no more than random
    /// positions of the same form. Counted, not timed: the collisions the welder's own hasher
    /// gives each set at the table size it uses, and the welder's result on both.
    #[test]
    fn welder_hash_flooding_costs_no_more_than_random_positions() {
        const N: usize = 4096;
        // The buckets of a table sized for N keys (hashbrown keeps it at most 7/8 full).
        let buckets = (N * 8 / 7).next_power_of_two();
        let mask = (buckets - 1) as u64;
        let fx = FxBuild::default();
        // FxHash of `[u64; 3]` is a fold over its length and its words' bytes: the state after
        // the length, x = 1 and y = 2 is shared, so only z's eight bytes are hashed per try.
        let prefix = fx_bytes(
            0,
            &[
                &3usize.to_ne_bytes()[..],
                &1.0f64.to_bits().to_le_bytes(),
                &2.0f64.to_bits().to_le_bytes(),
            ]
            .concat(),
        );
        let mut crafted = Vec::with_capacity(N);
        let mut k = 0u64;
        while crafted.len() < N {
            let z = f64::from_bits(3.0f64.to_bits() + k);
            k += 1;
            if fx_bytes(prefix, &z.to_bits().to_le_bytes()) & mask == 0 {
                crafted.push(DVec3::new(1.0, 2.0, z));
            }
        }
        let mut next = lcg(0x9e37_79b9_7f4a_7c15);
        let random: Vec<DVec3> = (0..N)
            .map(|_| DVec3::new(1.0, 2.0, f64::from_bits(3.0f64.to_bits() + (next() >> 24))))
            .collect();
        let collisions = |points: &[DVec3], build: &dyn Fn(DVec3) -> u64| {
            bucket_collisions(points.iter().map(|&p| build(p)), buckets)
        };
        let unkeyed = |p: DVec3| fx.hash_one(key(p));
        // The welder's map hashes `key(p)` with a `KeyedBuild`, as here.
        let keyed = |p: DVec3| KeyedBuild::default().hash_one(key(p));
        let flooded = collisions(&crafted, &unkeyed);
        assert_eq!(flooded, (N * (N - 1) / 2) as u64, "crafted into one bucket");
        let (c, r) = (collisions(&crafted, &keyed), collisions(&random, &keyed));
        let spread = (N * N / (2 * buckets)) as u64;
        assert!(c <= 3 * r, "crafted {c} vs random {r} collisions");
        assert!(
            r <= 2 * spread,
            "random {r} collisions, expected about {spread}"
        );
        assert!(flooded > 500 * c, "unkeyed {flooded} vs keyed {c}");
        // And the welder keeps every one of them apart.
        for points in [&crafted, &random] {
            let mut welder = Welder::with_capacity(N);
            for &p in points.iter() {
                welder.index(p);
            }
            assert_eq!(welder.positions.len(), N);
        }
    }

    /// FxHash's per-byte fold (the crate's unkeyed hasher) from `state` over `bytes`.
    fn fx_bytes(state: u64, bytes: &[u8]) -> u64 {
        bytes.iter().fold(state, |h, &b| {
            (h.rotate_left(5) ^ u64::from(b)).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
        })
    }

    /// Issue 12 item 8 (the crack welder's grid): cells of crack points come from input
    /// positions, so cells crafted to share one bucket under the unkeyed hash spread under the
    /// grid's own hasher as well as random cells do, and the wide reach still finds them.
    #[test]
    fn a_wide_grid_of_crafted_cells_spreads_like_a_random_one() {
        const N: usize = 1024;
        let buckets = (N * 8 / 7).next_power_of_two();
        let mask = (buckets - 1) as u64;
        // `[i64; 3]` hashes as its length then its 24 bytes: cells (1, 2, z), z crafted.
        let prefix = fx_bytes(
            0,
            &[
                &3usize.to_ne_bytes()[..],
                &1i64.to_le_bytes(),
                &2i64.to_le_bytes(),
            ]
            .concat(),
        );
        let mut crafted = Vec::with_capacity(N);
        let mut z = 0i64;
        while crafted.len() < N {
            if fx_bytes(prefix, &z.to_le_bytes()) & mask == 0 {
                crafted.push(z);
            }
            z += 1;
        }
        // Points at those cells' centres (cells of side 2 · delta = 1).
        let delta = 0.5;
        let at = |z: i64| DVec3::new(1.5, 2.5, z as f64 + 0.5);
        let crafted: Vec<DVec3> = crafted.into_iter().map(at).collect();
        let mut next = lcg(0x9e37_79b9_7f4a_7c15);
        let random: Vec<DVec3> = (0..N).map(|_| at((next() >> 40) as i64)).collect();
        let fx = FxBuild::default();
        let cells = |points: &[DVec3]| -> Vec<[i64; 3]> {
            points.iter().map(|&p| cell_of(p, 2.0 * delta)).collect()
        };
        assert_eq!(
            bucket_collisions(cells(&crafted).iter().map(|c| fx.hash_one(c)), buckets),
            (N * (N - 1) / 2) as u64,
            "crafted into one bucket under the unkeyed hash"
        );
        let count = |points: &[DVec3]| {
            let mut wide = Wide::default();
            wide.widen(points, delta);
            let h = wide.grid.hasher();
            for &p in points {
                assert_eq!(wide.reach(p + DVec3::splat(0.1), 1e-9), delta);
            }
            bucket_collisions(cells(points).iter().map(|c| h.hash_one(c)), buckets)
        };
        let (c, r) = (count(&crafted), count(&random));
        let spread = (N * N / (2 * buckets)) as u64;
        assert!(
            c <= 3 * r.max(spread),
            "crafted {c} vs random {r} collisions"
        );
        assert!(c <= 2 * spread, "crafted {c}, expected about {spread}");
    }
}
