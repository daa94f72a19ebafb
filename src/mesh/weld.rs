//! Bit-exact vertex welding: equal coordinates become one vertex.

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use glam::DVec3;

use super::Mesh;
use crate::solid::Solid;

/// A fast hasher for vertex keys (FxHash's multiply-rotate).
#[derive(Default, Clone, Copy)]
pub(crate) struct FxHasher(u64);

impl std::hash::Hasher for FxHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    #[inline]
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

pub(crate) type FxBuild = BuildHasherDefault<FxHasher>;
pub(crate) type FxHashMap<K, V> = HashMap<K, V, FxBuild>;

/// The key of a position: its bits, with −0 folded onto +0.
#[inline]
pub(crate) fn key(p: DVec3) -> [u64; 3] {
    [
        (p.x + 0.0).to_bits(),
        (p.y + 0.0).to_bits(),
        (p.z + 0.0).to_bits(),
    ]
}

/// Assigns one index per distinct position.
#[derive(Default)]
pub(crate) struct Welder {
    map: FxHashMap<[u64; 3], u32>,
    pub positions: Vec<DVec3>,
}

impl Welder {
    pub fn with_capacity(n: usize) -> Self {
        Welder {
            map: FxHashMap::with_capacity_and_hasher(n, FxBuild::default()),
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

impl Solid {
    /// The solid as an indexed triangle mesh: positions welded bit for bit, each polygon
    /// fanned into triangles, each triangle carrying its polygon's source id.
    pub fn to_mesh(&self) -> Mesh {
        let mut welder = Welder::with_capacity(self.corner_count() / 2);
        let mut triangles = Vec::with_capacity(self.corner_count());
        let mut sources = Vec::with_capacity(self.corner_count());
        for p in self.polygons() {
            let idx: Vec<u32> = p.vertices().iter().map(|&v| welder.index(v)).collect();
            for k in 1..idx.len() - 1 {
                let t = [idx[0], idx[k], idx[k + 1]];
                if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                    triangles.push(t);
                    sources.push(p.source());
                }
            }
        }
        Mesh {
            positions: welder.positions,
            triangles,
            sources,
        }
    }
}
