//! Scene documents: JSON bytes parsed, then meshed both ways at a small resolution — marching
//! cubes (bake) and the BSP route (tessellate and combine) — each giving a closed 2-manifold
//! without needles, or a clear error. Never a panic. The checks are in `scene_check.rs`, which
//! the regression tests replay.
#![no_main]

mod scene_check;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(json) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(e) = scene_check::check(json) {
        panic!("{e}");
    }
});
