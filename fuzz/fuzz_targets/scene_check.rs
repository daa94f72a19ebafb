//! Scene documents checked both ways, shared by the `scenes` fuzz target and the regression
//! tests that replay what it found (`tests/fuzz_findings_scenes.rs`,
//! `tests/fuzz_findings_thin_shells.rs`).
//!
//! Needles are judged as the kernel promises to remove them. A bake's are judged by each
//! shell's diagonal, as [`bspcsg::MeshReport`] counts them. The BSP route's mesh comes from a
//! boolean, and `to_mesh` judges a shell at no more than 16 times the region where that
//! boolean's operands met (`Solid::tolerance` is 10⁻¹² of it): a part 0.1 across on a beam
//! 10⁶ long is kept whole although the report, by the beam's diagonal, counts its triangles as
//! needles. A needle on a neck stays too: where the ends of its shortest edge share more
//! neighbours than the two triangles on that edge give them, collapsing it would pinch the
//! surface (the rule `to_mesh` follows: needles go unless removing them changes topology).
//!
//! Nor is every needle by area one the kernel must remove: the check counts those the needle
//! pass removes, by the library's rule ([`bspcsg::is_needle_to_remove`]: thin, within a weld's
//! reach, or a speck of its shell judged by its slab thickness `2V/A`). A well-shaped triangle
//! larger than both is the input's own detail on a shell thinner than it is long: the end face
//! of a prism 6.7·10⁶ long on a 6 × 3 end (`2V/A` = 1.5; its end triangles, of area 9, are below
//! 10⁻¹² d² = 44 by its diagonal). The thickness judges specks only on shells whose 6 × `2V/A`
//! is under 10⁻⁵ of their diagonal ([`bspcsg::NEEDLE_THIN_SHELL`]); on every other shell (a cube
//! or a sphere is 5.2 slab thicknesses across, the stored brackets 10 to 10⁴) the speck rule
//! is the report's.

use bspcsg::glam::DVec3;
use bspcsg::{Aabb, BakeOptions, Mesh, Scene, TessellationOptions, Tolerance};

/// How far beyond the region where its operands met a boolean's needles are judged.
const REGION_REACH: f64 = 16.0;
/// The resolution of the bake.
pub const BAKE_RESOLUTION: u32 = 12;

/// The coarse BSP route: chordal tolerance 1/20 and cell 1/12 of the scene's diagonal.
pub fn coarse(scene: &Scene) -> Option<TessellationOptions> {
    let diagonal = scene.bbox().diagonal();
    (diagonal.is_finite() && diagonal > 0.0).then(|| TessellationOptions {
        tolerance: Some(diagonal / 20.0),
        cell: Some(diagonal / 12.0),
        max_angle: None,
    })
}

/// The bake at [`BAKE_RESOLUTION`]: a closed 2-manifold without needles, or an error to pass.
pub fn check_bake(scene: &Scene) -> Result<(), String> {
    let Ok(mesh) = scene.bake(&BakeOptions::with_resolution(BAKE_RESOLUTION)) else {
        return Ok(());
    };
    let report = mesh.report();
    if !report.is_closed_manifold() || report.needles > 0 {
        return Err(format!("bake: {report}"));
    }
    Ok(())
}

/// The coarse BSP route: a closed 2-manifold without needles (judged as `to_mesh` judges
/// them), or an error to pass.
pub fn check_bsp_route(scene: &Scene) -> Result<(), String> {
    let Some(options) = coarse(scene) else {
        return Ok(());
    };
    let Ok(solid) = scene.to_solid(&options) else {
        return Ok(());
    };
    let mesh = solid.to_mesh();
    let report = mesh.report();
    let reach = REGION_REACH * solid.tolerance().eps() / Tolerance::RELATIVE;
    let needles = needles_within(&mesh, reach);
    if !report.is_closed_manifold() || needles > 0 {
        return Err(format!(
            "bsp route: {needles} needles by shells capped at {reach:e}; {report}"
        ));
    }
    Ok(())
}

/// Both checks on a JSON document; a document that does not parse passes.
pub fn check(json: &str) -> Result<(), String> {
    let Ok(scene) = Scene::from_json_str(json) else {
        return Ok(());
    };
    check_bake(&scene)?;
    check_bsp_route(&scene)
}

/// Triangles of area below [`bspcsg::MeshReport::NEEDLE_AREA`] × d², d the diagonal of their shell's box capped at
/// `reach`, that are slivers or specks of their shell, except those on a neck (see the module
/// docs).
pub fn needles_within(mesh: &Mesh, reach: f64) -> usize {
    let n = mesh.positions.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut v: usize) -> usize {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    }
    for t in &mesh.triangles {
        for k in 1..3 {
            let (a, b) = (
                root(&mut parent, t[0] as usize),
                root(&mut parent, t[k] as usize),
            );
            parent[a] = b;
        }
    }
    let roots: Vec<usize> = (0..n).map(|v| root(&mut parent, v)).collect();
    let corner = |v: u32| -> DVec3 { mesh.positions[v as usize] };
    let mut boxes = vec![Aabb::EMPTY; n];
    // Each shell's volume (about its root, for precision) and area.
    let (mut volumes, mut areas) = (vec![0.0; n], vec![0.0; n]);
    for t in &mesh.triangles {
        let r = roots[t[0] as usize];
        for &v in t {
            boxes[r].grow(mesh.positions[v as usize]);
        }
        let [a, b, c] = t.map(|v| corner(v) - mesh.positions[r]);
        volumes[r] += a.dot(b.cross(c)) / 6.0;
        areas[r] += 0.5 * (b - a).cross(c - a).length();
    }
    let needles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .filter(|t| {
            let r = roots[t[0] as usize];
            let d = boxes[r].diagonal().min(reach);
            let slab = 2.0 * volumes[r].abs() / areas[r];
            bspcsg::is_needle_to_remove(t.map(corner), d, slab)
        })
        .copied()
        .collect();
    if needles.is_empty() {
        return 0;
    }
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); n];
    for t in &mesh.triangles {
        for k in 0..3 {
            for j in 1..3 {
                let (v, w) = (t[k] as usize, t[(k + j) % 3]);
                if !neighbours[v].contains(&w) {
                    neighbours[v].push(w);
                }
            }
        }
    }
    needles
        .iter()
        .filter(|t| {
            let c = t.map(corner);
            let k = (0..3)
                .min_by(|&i, &j| {
                    let li = c[i].distance(c[(i + 1) % 3]);
                    li.total_cmp(&c[j].distance(c[(j + 1) % 3]))
                })
                .unwrap_or(0);
            let (p, q) = (t[k] as usize, t[(k + 1) % 3]);
            let shared = neighbours[p]
                .iter()
                .filter(|w| neighbours[q as usize].contains(w))
                .count();
            shared <= 2
        })
        .count()
}
