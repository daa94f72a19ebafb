use super::*;
use crate::hash::FxBuild;
use crate::hash::test_support::lcg;
use crate::mesh::weld::weld_exact;

/// Soups of distinct positions with clusters closer than the reach, points at cell sides,
/// lone points, huge and infinite coordinates, and crack points that widen the reach.
fn soups() -> Vec<(Vec<DVec3>, f64, Wide)> {
    let mut next = lcg(29);
    let mut unit = move || (next() >> 11) as f64 / (1u64 << 53) as f64;
    let mut out = Vec::new();
    for (n, spread, delta) in [(40usize, 1e-6, 1e-8), (3000, 1e-3, 1e-6), (6000, 1.0, 1e-4)] {
        let cell = 64.0 * delta;
        let mut points = Vec::with_capacity(n);
        while points.len() < n {
            let base = DVec3::new(unit(), unit(), unit()) * spread * n as f64;
            points.push(base);
            // A cluster around it, some within reach, some just beyond.
            for _ in 0..(unit() * 4.0) as usize {
                let d = DVec3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5) * 3.0 * delta;
                points.push(base + d);
            }
            // Near a cell side, and a point one cell over.
            if unit() < 0.1 {
                let side = (base.x / cell).floor() * cell;
                points.push(DVec3::new(side + 0.25 * delta, base.y, base.z));
                points.push(DVec3::new(side - 0.5 * delta, base.y, base.z));
                points.push(DVec3::new(side - cell, base.y, base.z));
            }
        }
        points.extend([
            DVec3::splat(1e300),
            DVec3::new(1e300, 1e300, -1e300),
            DVec3::new(f64::INFINITY, 0.0, 0.0),
            DVec3::new(f64::NEG_INFINITY, 0.0, 0.0),
            DVec3::new(-0.0, 0.0, 0.0),
        ]);
        let (distinct, _) = weld_exact(&points);
        out.push((distinct.clone(), delta, Wide::default()));
        let mut wide = Wide::default();
        let cracks: Vec<DVec3> = distinct.iter().step_by(7).copied().collect();
        wide.widen(&cracks, 4.0 * delta);
        out.push((distinct, delta, wide));
    }
    out
}

/// The grid pass with its lone positions apart gives the serial pass's representatives and
/// numbering bit for bit, its walk in one part or split into several, and the soups have both
/// lone positions and others.
#[test]
fn lone_apart_is_the_serial_pass() {
    for (k, (positions, delta, wide)) in soups().iter().enumerate() {
        let (serial_reps, serial_of) = serial(positions, *delta, wide);
        let bits = |v: &[DVec3]| {
            v.iter()
                .map(|p| p.to_array().map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        let mut reps = Vec::new();
        for parts in [1, 2, 3, 8] {
            let (r, rep_of) = lone_apart(positions, *delta, wide, parts);
            assert_eq!(bits(&serial_reps), bits(&r), "soup {k}, {parts} parts");
            assert_eq!(serial_of, rep_of, "soup {k}, {parts} parts");
            reps = r;
        }
        assert!(
            reps.len() < positions.len(),
            "soup {k}: some positions weld"
        );
        let cell_size = 64.0 * wide.widest(*delta);
        let cells: Vec<[i64; 3]> = positions.iter().map(|&p| cell_of(p, cell_size)).collect();
        let lone = lone_cells(&cells, &FxBuild::default());
        let alone = lone.iter().filter(|&&l| l).count();
        assert!(
            alone > 0 && alone < positions.len(),
            "soup {k}: {alone} lone"
        );
    }
}

/// A cell marked lone has no other cell within one step on every axis (checked pair by pair),
/// at the ends of the integers too.
#[test]
fn a_lone_cell_has_no_neighbour() {
    let mut next = lcg(5);
    let mut cells: Vec<[i64; 3]> = (0..2000)
        .map(|_| [0, 1, 2].map(|_| (next() >> 58) as i64 * 7 - 200))
        .collect();
    cells.extend([
        [i64::MAX, 0, 0],
        [i64::MAX - 1, 0, 0],
        [i64::MIN, 5, 5],
        [i64::MIN + 40, 5, 5],
        [i64::MAX, i64::MAX, i64::MAX],
        [i64::MIN, i64::MIN, i64::MIN],
    ]);
    let lone = lone_cells(&cells, &FxBuild::default());
    let near = |a: [i64; 3], b: [i64; 3]| (0..3).all(|k| a[k].abs_diff(b[k]) <= 1);
    let mut marked = 0;
    for (i, &a) in cells.iter().enumerate() {
        let alone = cells
            .iter()
            .enumerate()
            .all(|(j, &b)| j == i || !near(a, b));
        if lone[i] {
            marked += 1;
            assert!(alone, "cell {a:?} marked lone");
        }
    }
    assert!(
        lone[cells.len() - 1] && lone[cells.len() - 2],
        "the far corners are lone"
    );
    assert!(!lone[2000] && !lone[2001], "neighbours at the top end");
    assert!(
        lone[2002] && lone[2003],
        "40 apart at the bottom end (blocks of 16 cells)"
    );
    assert!(marked > 100, "{marked} marked lone");
}

/// The walk's parts: every position that is not lone in exactly one part, in order, no cell of
/// one part within a step of another part's on the split axis; the larger soups do split.
#[test]
fn parts_cannot_reach_each_other() {
    let mut split = 0;
    for (k, (positions, delta, wide)) in soups().iter().enumerate() {
        let cell_size = 64.0 * wide.widest(*delta);
        let cells: Vec<[i64; 3]> = positions.iter().map(|&p| cell_of(p, cell_size)).collect();
        let lone = lone_cells(&cells, &FxBuild::default());
        let rest: Vec<u32> = (0..cells.len() as u32)
            .filter(|&i| !lone[i as usize])
            .collect();
        for want in [2, 3, 8] {
            let parts = parts_apart(&cells, &rest, want);
            assert!(parts.len() <= want, "soup {k}: {} parts", parts.len());
            let mut all: Vec<u32> = parts.concat();
            assert!(parts.iter().all(|p| p.is_sorted()), "soup {k}");
            all.sort_unstable();
            assert_eq!(all, (0..rest.len() as u32).collect::<Vec<_>>(), "soup {k}");
            if parts.len() > 1 {
                split += 1;
            }
            // No two positions of different parts within a step on every axis.
            let near = |a: [i64; 3], b: [i64; 3]| {
                (0..3).all(|d| (i128::from(a[d]) - i128::from(b[d])).abs() <= 1)
            };
            for (x, p) in parts.iter().enumerate() {
                for q in &parts[x + 1..] {
                    for &a in p {
                        for &b in q {
                            let (a, b) = (rest[a as usize], rest[b as usize]);
                            assert!(!near(cells[a as usize], cells[b as usize]), "soup {k}");
                        }
                    }
                }
            }
        }
    }
    assert!(split >= 6, "{split} splits");
}
