//! The crate's hashers and the hash-map types and position keys built on them. A leaf: vertex
//! welding, booleans, file readers and marching cubes all hash positions or small integer keys.
//!
//! Two hashers, for two kinds of key:
//! - [`FxHasher`] (FxHash's multiply-rotate), unkeyed and fastest, for keys the crate makes
//!   itself: vertex and polygon indices, grid cells of its own lattices.
//! - [`KeyedHasher`], for keys that come from input files: positions (and cells of positions),
//!   and pairs of vertex indices whose pairing a file chooses (the directed edges of its
//!   triangles).
//!   A fixed, unkeyed hash lets a file be crafted whose positions all land in one bucket, which
//!   makes welding quadratic (a 1M-vertex OBJ took 300 s instead of 1.6 s). Keyed per process
//!   with random keys, a collision found for one run says nothing about the next.
//!
//! Where a key's hash is wanted for more than one map (to shard the keys, say), it is made once
//! by one of the two and a [`PrehashedMap`] passes it on.
//!
//! Neither map type is ever iterated where its order would reach the output, so the random keys
//! never make results differ between runs.

use std::collections::HashMap;
use std::hash::{BuildHasher, BuildHasherDefault};
use std::sync::OnceLock;

use glam::DVec3;

/// A fast hasher for keys the crate makes itself (FxHash's multiply-rotate).
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

/// The full 128-bit product of two words, folded to 64 bits: every input bit reaches every
/// output bit, and with a secret factor the result cannot be steered.
#[inline]
fn folded_multiply(a: u64, b: u64) -> u64 {
    let p = u128::from(a) * u128::from(b);
    (p as u64) ^ ((p >> 64) as u64)
}

/// A hasher keyed per process, for keys that come from input (see the module docs). Each word
/// is folded in by a multiply with a secret odd factor, after a secret offset.
#[derive(Clone, Copy)]
pub(crate) struct KeyedHasher {
    state: u64,
    keys: [u64; 2],
}

impl std::hash::Hasher for KeyedHasher {
    #[inline]
    fn finish(&self) -> u64 {
        folded_multiply(self.state ^ self.keys[1], self.keys[0])
    }
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }
    #[inline]
    fn write_u64(&mut self, x: u64) {
        self.state = folded_multiply(self.state ^ x ^ self.keys[1], self.keys[0]);
    }
    #[inline]
    fn write_u32(&mut self, x: u32) {
        self.write_u64(u64::from(x));
    }
    #[inline]
    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

/// Builds [`KeyedHasher`]s with this process's keys, drawn once from the operating system's
/// randomness (through the standard library's `RandomState`).
#[derive(Clone, Copy)]
pub(crate) struct KeyedBuild {
    keys: [u64; 2],
}

impl Default for KeyedBuild {
    fn default() -> Self {
        static KEYS: OnceLock<[u64; 2]> = OnceLock::new();
        let keys = *KEYS.get_or_init(|| {
            let random = std::collections::hash_map::RandomState::new();
            [random.hash_one(1u64) | 1, random.hash_one(2u64)]
        });
        KeyedBuild { keys }
    }
}

impl BuildHasher for KeyedBuild {
    type Hasher = KeyedHasher;
    #[inline]
    fn build_hasher(&self) -> KeyedHasher {
        KeyedHasher {
            state: self.keys[1],
            keys: self.keys,
        }
    }
}

/// A map keyed by positions from input (see [`key`]) or cells of them.
pub(crate) type KeyedHashMap<K, V> = HashMap<K, V, KeyedBuild>;

/// A hasher for keys hashed already: it passes on the one word it is given (a key type for a
/// [`PrehashedMap`] writes its hash with `write_u64` and nothing else).
#[derive(Default)]
pub(crate) struct Prehashed(u64);

impl std::hash::Hasher for Prehashed {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = self.0.rotate_left(8) ^ u64::from(b);
        }
    }
    #[inline]
    fn write_u64(&mut self, x: u64) {
        self.0 = x;
    }
}

/// A map whose keys carry their own hash (see [`Prehashed`]).
pub(crate) type PrehashedMap<K, V> = HashMap<K, V, BuildHasherDefault<Prehashed>>;

/// The key of a position: its bits, with −0 folded onto +0.
#[inline]
pub(crate) fn key(p: DVec3) -> [u64; 3] {
    [
        (p.x + 0.0).to_bits(),
        (p.y + 0.0).to_bits(),
        (p.z + 0.0).to_bits(),
    ]
}

/// Helpers for tests of how keys spread over a table's buckets.
#[cfg(test)]
pub(crate) mod test_support {
    /// A linear congruential generator from `state`: each call steps it and returns the new
    /// state (Knuth's MMIX constants), the same numbers in every test that asks for a seed.
    pub(crate) fn lcg(mut state: u64) -> impl FnMut() -> u64 {
        move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            state
        }
    }

    /// Pairs of `hashes` a table of `buckets` (a power of two) starts probing at the same
    /// bucket: the work that collisions add to a map. A table whose keys spread has about
    /// `n² / 2·buckets` of them; one flooded into a bucket, `n² / 2`, each a longer probe.
    pub(crate) fn bucket_collisions(hashes: impl Iterator<Item = u64>, buckets: usize) -> u64 {
        let mut count = vec![0u64; buckets];
        for h in hashes {
            count[(h as usize) & (buckets - 1)] += 1;
        }
        count.iter().map(|&c| c * c.saturating_sub(1) / 2).sum()
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;
    use std::hash::BuildHasher;

    use super::*;

    #[test]
    fn keyed_hashes_spread_keys_that_differ_in_one_bit() {
        // Keys that differ only in one high bit (the kind an unkeyed multiply leaves in the
        // high half) land in different low bits under the keyed hash.
        let build = KeyedBuild::default();
        let low: HashSet<u64> = (0..64)
            .map(|bit| {
                build.hash_one(key(DVec3::new(f64::from_bits(1u64 << bit), 0.0, 0.0))) & 0xfff
            })
            .collect();
        assert!(low.len() > 48, "{}", low.len());
        // Equal keys hash equally, and the keys are the same for every map in the process.
        let p = key(DVec3::new(1.5, -2.0, 3.0));
        assert_eq!(build.hash_one(p), KeyedBuild::default().hash_one(p));
    }
}
