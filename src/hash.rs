//! The crate's one fast hasher (FxHash's multiply-rotate) and the hash-map types and position
//! keys built on it. A leaf: vertex welding, booleans, file readers and marching cubes all hash
//! positions or small integer keys, where SipHash's DoS resistance buys nothing.

use std::collections::{HashMap, HashSet};
use std::hash::BuildHasherDefault;

use glam::DVec3;

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
pub(crate) type FxHashSet<K> = HashSet<K, FxBuild>;

/// The key of a position: its bits, with −0 folded onto +0.
#[inline]
pub(crate) fn key(p: DVec3) -> [u64; 3] {
    [
        (p.x + 0.0).to_bits(),
        (p.y + 0.0).to_bits(),
        (p.z + 0.0).to_bits(),
    ]
}
