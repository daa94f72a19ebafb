//! Bit-exact vertex welding: equal coordinates become one vertex.

use glam::DVec3;
use smallvec::SmallVec;

use crate::hash::{FxHashMap, KeyedBuild, KeyedHashMap, key};

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

/// Where a wider weld is allowed: around the vertices of cracks an earlier pass left. A point
/// within `2 · delta` of one of them may weld and join edges `delta` away; the partner of a
/// crack vertex need not lie on a crack itself.
#[derive(Clone, Default)]
pub(crate) struct Wide {
    points: Vec<DVec3>,
    grid: FxHashMap<[i64; 3], SmallVec<[u32; 2]>>,
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
        let c = (p / (2.0 * self.delta)).floor();
        [c.x as i64, c.y as i64, c.z as i64]
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
    let mut exact = Welder::with_capacity(points.len());
    let first: Vec<u32> = points.iter().map(|&p| exact.index(p)).collect();
    if delta <= 0.0 {
        return (exact.positions, first);
    }
    // Cells much larger than any reach: a representative within reach of a point lies in the
    // point's own cell, or in a neighbour only where the point is within reach of that side.
    let widest = wide.widest(delta);
    let cell_size = 64.0 * widest;
    let cell = |p: DVec3| -> [i64; 3] {
        // `as` saturates, so coordinates beyond the i64 range share the outermost cells.
        let c = (p / cell_size).floor();
        [c.x as i64, c.y as i64, c.z as i64]
    };
    let mut grid: KeyedHashMap<[i64; 3], SmallVec<[u32; 2]>> =
        KeyedHashMap::with_capacity_and_hasher(exact.positions.len(), KeyedBuild::default());
    let mut reps: Vec<DVec3> = Vec::with_capacity(exact.positions.len());
    let mut rep_reach: Vec<f64> = Vec::with_capacity(exact.positions.len());
    let mut rep_of: Vec<u32> = Vec::with_capacity(exact.positions.len());
    for &p in &exact.positions {
        let reach = wide.reach(p, delta);
        let c = cell(p);
        // Per axis, the neighbour offsets worth looking at.
        let offsets = |k: usize| -> SmallVec<[i64; 3]> {
            let lo = c[k] as f64 * cell_size;
            let mut o: SmallVec<[i64; 3]> = smallvec::smallvec![0];
            if p[k] - lo <= widest {
                o.push(-1);
            }
            if lo + cell_size - p[k] <= widest {
                o.push(1);
            }
            o
        };
        let (ox, oy, oz) = (offsets(0), offsets(1), offsets(2));
        let mut found = None;
        'search: for &dx in &ox {
            for &dy in &oy {
                for &dz in &oz {
                    let k = [
                        c[0].saturating_add(dx),
                        c[1].saturating_add(dy),
                        c[2].saturating_add(dz),
                    ];
                    if let Some(list) = grid.get(&k)
                        && let Some(&r) = list.iter().find(|&&r| {
                            reps[r as usize].distance(p) <= reach.max(rep_reach[r as usize])
                        })
                    {
                        found = Some(r);
                        break 'search;
                    }
                }
            }
        }
        let r = found.unwrap_or_else(|| {
            reps.push(p);
            rep_reach.push(reach);
            let r = (reps.len() - 1) as u32;
            grid.entry(c).or_default().push(r);
            r
        });
        rep_of.push(r);
    }
    let map = first.into_iter().map(|i| rep_of[i as usize]).collect();
    (reps, map)
}
