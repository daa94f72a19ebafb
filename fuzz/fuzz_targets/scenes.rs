//! Scene documents: JSON bytes parsed, then meshed both ways at a small resolution — marching
//! cubes (bake) and the BSP route (tessellate and combine) — each giving a closed 2-manifold
//! without needles, or a clear error. Never a panic.
#![no_main]

use bspcsg::{BakeOptions, Scene, TessellationOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(json) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = Scene::from_json_str(json) else {
        return;
    };
    if let Ok(mesh) = scene.bake(&BakeOptions::with_resolution(12)) {
        let report = mesh.report();
        assert!(report.is_closed_manifold(), "bake: {report}");
        assert_eq!(report.needles, 0, "bake: {report}");
    }
    let bbox = scene.bbox();
    let diagonal = bbox.diagonal();
    if !(diagonal.is_finite() && diagonal > 0.0) {
        return;
    }
    let coarse = TessellationOptions {
        tolerance: Some(diagonal / 20.0),
        cell: Some(diagonal / 12.0),
        max_angle: None,
    };
    if let Ok(solid) = scene.to_solid(&coarse) {
        let report = solid.to_mesh().report();
        assert!(report.is_closed_manifold(), "bsp route: {report}");
        assert_eq!(report.needles, 0, "bsp route: {report}");
    }
});
