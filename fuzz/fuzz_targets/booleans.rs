//! Boolean programs in the style of manifold's fuzzer: a bounded program of boxes, spheres,
//! cylinders and triangulated (OBJ-style, 12-triangle) boxes under bounded transforms —
//! including tiny rotations and placements on an exact grid, so faces meet coplanar or a hair
//! off — combined step by step by union, intersection and difference.
//!
//! After every step: the mesh is a closed 2-manifold without needles, its volume is the
//! solid's, and the solid's volume lies within the bounds the operation allows
//! (`max(a, b) ≤ a ∪ b ≤ a + b`, `0 ≤ a ∩ b ≤ min(a, b)`, `a − b ≤ a − b ≤ a`).
#![no_main]

mod program;

use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;

/// `BSPCSG_FUZZ_NO_TINY=1` leaves tiny rotations out (the bounded run in CI does, while faces a
/// hair off coplanar still have open findings; see the README).
fn tiny() -> bool {
    static TINY: OnceLock<bool> = OnceLock::new();
    *TINY.get_or_init(|| std::env::var_os("BSPCSG_FUZZ_NO_TINY").is_none())
}

fuzz_target!(|data: &[u8]| {
    if let Err(e) = program::run(data, tiny()) {
        panic!("{e}");
    }
});
