//! Every scene document the `scenes` fuzz target in `fuzz/` found failing
//! (`tests/fuzz_findings/*.json`), replayed as a named test: baked as the target bakes it, and
//! by the BSP route at the target's coarse settings. The `booleans` target's findings are in
//! `fuzz_findings.rs`; those on shells thinner than they are long, in
//! `fuzz_findings_thin_shells.rs`.

#[path = "../fuzz/fuzz_targets/scene_check.rs"]
#[allow(dead_code)]
mod scene_check;

/// A finding's scene document (`tests/fuzz_findings/<name>.json`).
fn finding_json(name: &str) -> String {
    let path = format!(
        "{}/tests/fuzz_findings/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).unwrap()
}

/// A finding's scene.
fn finding_scene(name: &str) -> bspcsg::Scene {
    bspcsg::Scene::from_json_str(&finding_json(name)).unwrap()
}

/// The report of a finding's bake at resolution 12, as the `scenes` target bakes it.
fn bake_report(name: &str) -> bspcsg::MeshReport {
    finding_scene(name)
        .bake(&bspcsg::BakeOptions::with_resolution(12))
        .unwrap()
        .report()
}

/// The report of a finding's BSP route at the `scenes` target's coarse settings.
fn coarse_bsp_report(name: &str) -> bspcsg::MeshReport {
    coarse_route(name).2.to_mesh().report()
}

/// A finding's scene, the `scenes` target's coarse settings for it and its BSP route there.
fn coarse_route(name: &str) -> (bspcsg::Scene, bspcsg::TessellationOptions, bspcsg::Solid) {
    let scene = finding_scene(name);
    let options = scene_check::coarse(&scene).unwrap();
    let solid = scene.to_solid(&options).unwrap();
    (scene, options, solid)
}

/// [`coarse_route`], the scene first checked as the `scenes` target checks it.
fn checked_coarse_route(name: &str) -> (bspcsg::Scene, bspcsg::TessellationOptions, bspcsg::Solid) {
    let route = coarse_route(name);
    if let Err(e) = scene_check::check_bsp_route(&route.0) {
        panic!("{name}: {e}");
    }
    route
}

/// The volume at `options` of `variant`, a document that must give the same solid as `scene`
/// over the same box.
fn variant_volume(
    scene: &bspcsg::Scene,
    variant: &str,
    options: &bspcsg::TessellationOptions,
) -> f64 {
    let variant = bspcsg::Scene::from_json_str(variant).unwrap();
    assert_eq!(variant.bbox(), scene.bbox());
    variant.to_solid(options).unwrap().volume()
}

/// Asserts that a finding's solid and its mesh both have the volume `expected` (that of
/// `what`) to 1e-12.
fn assert_volume(
    name: &str,
    solid: &bspcsg::Solid,
    mesh: &bspcsg::Mesh,
    expected: f64,
    what: &str,
) {
    assert!(
        (mesh.volume() - expected).abs() < 1e-12 * expected
            && (solid.volume() - expected).abs() < 1e-12 * expected,
        "{name}: mesh volume {}, solid's {}, {what} {expected}",
        mesh.volume(),
        solid.volume()
    );
}

/// Found by a 10-minute run of the `scenes` target: variations of the example bracket whose
/// coarse BSP route gave a flat inverted shell. Closed since the BSP's cell planes leave a
/// polygon whole on each side.
#[test]
fn scenes_bsp_route_of_coarse_brackets() {
    for i in [1, 2, 4, 5] {
        let report = coarse_bsp_report(&format!("scene_{i}"));
        assert!(
            report.is_closed_manifold() && report.needles == 0,
            "scene_{i}: {report}"
        );
    }
}

/// From the same run: a bracket variant whose coarse BSP route kept a needle, fixed as
/// `a_needle_that_no_flip_or_collapse_removes`.
#[test]
fn scene_bsp_route_keeps_a_needle() {
    let report = coarse_bsp_report("scene_3");
    assert!(
        report.is_closed_manifold() && report.needles == 0,
        "scene_3: {report}"
    );
}

/// Found by a second 10-minute run of the `scenes` target: a document whose coarse BSP route
/// left two needles on a shell larger than the region where the last boolean's operands met;
/// fixed as `a_needle_that_no_flip_or_collapse_removes`.
#[test]
fn scene_bsp_route_needles_on_a_shell_beyond_the_region() {
    let report = coarse_bsp_report("bsp_3");
    assert!(
        report.is_closed_manifold() && report.needles == 0,
        "bsp_3: {report}"
    );
}

/// From the same run: documents whose coarse BSP route left 14 needles (`bsp_1`, one is left) and 2
/// (`bsp_2`, both left). `bsp_1`'s profile turns back on itself at (0.12, 0.6) by 2.35·10⁻⁴ rad, a
/// notch 3·10⁻⁵ wide; the needle left is the notch's end, on a neck whose short edge no collapse
/// can take without pinching the surface. `bsp_2`'s are triangles 0.02 across, real detail where a
/// beam meets a bolt hole, on a shell 12,000 across (a rectangle 2·10⁴ wide): the report counts
/// them by the shell's diagonal, but `to_mesh` judges needles at no more than 16 times the region
/// where the last boolean's operands met, as the fuzz target now does (`scene_check.rs`).
#[test]
fn scenes_bsp_route_leave_needles() {
    for i in 1..=2 {
        let name = format!("bsp_{i}");
        if let Err(e) = scene_check::check_bsp_route(&finding_scene(&name)) {
            panic!("{name}: {e}");
        }
    }
}

/// Found by a second 10-minute run of the `scenes` target: ten documents (I-beam and other
/// variants) whose bake at resolution 12 leaves four needles in a second shell of twelve triangles:
/// a rod 1.2e-6 across and 0.6 long (volume 4.3e-13) along a row of grid vertices where the field
/// is a hair below zero. Its end caps (area 3.59999999995e-13 against a threshold of 3.6e-13 of its
/// 0.6 diagonal) cannot collapse without changing the rod's topology. Marching cubes now counts a
/// point inside by less than the needle pass's largest move as a hair outside, so no such shell is
/// made.
#[test]
fn bakes_of_i_beam_variants() {
    for i in 1..=10 {
        let report = bake_report(&format!("bake_{i}"));
        assert!(
            report.is_closed_manifold() && report.needles == 0,
            "bake_{i}: {report}"
        );
    }
}

/// Found by a 9-minute `scenes` run whose binary was built without the hair rule above: bakes
/// leaving 4 or 8 needles in small extra shells; they pass with it.
#[test]
fn bakes_with_speck_shells_found_by_a_second_run() {
    for i in 1..=4 {
        let report = bake_report(&format!("bake_thin_{i}"));
        assert!(
            report.is_closed_manifold() && report.needles == 0,
            "bake_thin_{i}: {report}"
        );
    }
}

/// From the same run: a document whose coarse BSP route leaves 40 needles in three shells: a
/// profile reaching 10⁶ from a beam 1 across puts bars 0.12 thick and the beam's 0.2-wide end
/// faces on shells 10⁶ across. They are whole parts, not slivers: no flip or collapse removes
/// them without changing topology, and `to_mesh`, judging at the region where the last
/// boolean's operands met, keeps them (the report still counts them by the shells' diagonals).
#[test]
fn scene_bsp_route_leaves_forty_needles() {
    let scene = finding_scene("bsp_4");
    if let Err(e) = scene_check::check_bsp_route(&scene) {
        panic!("bsp_4: {e}");
    }
    let solid = scene
        .to_solid(&scene_check::coarse(&scene).unwrap())
        .unwrap();
    let mesh = solid.to_mesh();
    let report = mesh.report();
    assert_eq!(report.needles, 40, "bsp_4: {report}");
    // Kept whole: the mesh holds the solid's volume.
    assert!(
        (mesh.volume() - solid.volume()).abs() < 1e-9 * solid.volume(),
        "bsp_4: mesh volume {} against the solid's {}",
        mesh.volume(),
        solid.volume()
    );
}

/// Found by a 10-minute run of the `scenes` target (artifact crash-dd29a0ee…): the example
/// bracket with a mounting hole of radius 2·10⁻¹⁰⁶. At x = 1.5 the hole's circle rounds onto
/// its centre, so its faces are flat, and the coarse BSP route left 72 boundary edges. A
/// primitive thinner where it lies than twice the weld distance of its coordinates' rounding
/// floor is now refused as beyond precision (`bsp_5`, and below the box minus that hole alone).
#[test]
fn scene_with_a_hole_thinner_than_rounding() {
    let scene = finding_scene("bsp_5");
    if let Err(e) = scene_check::check_bsp_route(&scene) {
        panic!("bsp_5: {e}");
    }
    let minimal = bspcsg::Scene::from_json_str(
        r#"{"op": "subtract", "children": [
            {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [3.0, 0.5, 3.0]}},
            {"kind": "sdf_primitive", "pos": [1.5, 0, -1.0],
             "data": {"primitive_type": "cylinder", "radius": 2e-103, "height": 2.0}}
        ]}"#,
    )
    .unwrap();
    let options = scene_check::coarse(&minimal).unwrap();
    match minimal.to_solid(&options) {
        Err(bspcsg::Error::BeyondPrecision { magnitude, .. }) => {
            assert!((magnitude - 1.5).abs() < 1e-12, "{magnitude}");
        }
        other => panic!("want beyond precision, got {other:?}"),
    }
}

/// Found by a second 10-minute run of the `scenes` target (libFuzzer seed 2, artifact
/// crash-73f3fb0b…, at about 545 s), minimised to four operands (`bsp_6`): the baked smooth
/// union of the example bracket's plate and boss, minus a bore, a union of two mounting holes
/// (one of radius 5.2, wider than the plate) and a slot turned by (8°, 45°, 1°). The coarse
/// BSP route leaves 3 boundary edges, a slit of zero width on the plane y = 1: vertex
/// (−0.67355, 1, 0.38405) lies 1.15e-10 off the edge from (−0.67898, 1, 0.37351) to
/// (−0.61627, 1, 0.49512), 3.6 weld distances at the boolean's tolerance 4.0e-12, and no repair
/// pass splits the edge there. The solid's polygons bound the right volume (0.53204365322 by
/// both the solid and its fan mesh). A third run (seed 3, artifact crash-e5c509be…, after
/// 289,404 executions) found the same kind (`bsp_7`, another bracket variant): a slit of three
/// collinear vertices on y = 1, the mounting holes' top plane again. The first pass leaves
/// slits where one point was computed twice 2.4·10⁻¹⁰ apart; the wider weld that joins them
/// drags the edges at that point, and the vertex lay within reach of the edge as computed, not
/// as dragged. Closed since the T-junction search allows an edge the distance a wide weld
/// moved its ends (`mesh/repair/pass.rs`, `wide_drag`).
#[test]
fn scene_bsp_route_crack_where_a_bake_meets_four_cuts() {
    for name in ["bsp_6", "bsp_7"] {
        if let Err(e) = scene_check::check_bsp_route(&finding_scene(name)) {
            panic!("{name}: {e}");
        }
    }
}

/// Found by a 10-minute run of the `scenes` target in round 15 (libFuzzer seed 0 picked by the
/// run, artifact crash-c9666e9f…, after 2.75 M executions at about 405 s), not minimised: a
/// variant of the example bracket whose cross slot is a box 10¹¹ long (size 2.2 × 99999999990.3 ×
/// 0.25, turned (1°, 45°, 0°), through a plate 6 across). The coarse BSP route left 3 boundary
/// edges (501 triangles, 2 shells, volume 7.0801435605), and did so before the crossing-line
/// judgement too (main 56775cb: 514 triangles, 4 shells, volume 6.6983). The slot's corners lie
/// 5·10¹⁰ away, so its long edges are known only to the rounding of such coordinates: where they
/// crossed the plate they lay 1–2·10⁻⁷ off their own faces' planes, ten thousand times the
/// boolean's tolerance there (1.5·10⁻¹¹). The plate's bottom face, cut by the slot's planes, and
/// the slot's faces, cut by the plate's, then disagreed about the slot's trace on y = −0.25 by
/// 10⁻⁷: a slit of three vertices, one 1.06·10⁻⁷ off the line of the other two, beyond any weld.
/// The plate minus the slot alone closed but wrongly: the slot an inner cavity, not a hole
/// (2 shells, genus 0), volume 5·10⁻⁸ high. The BSP route now cuts a box, cylinder or cone off
/// where it reaches more than the scene's diagonal beyond the scene's box
/// (`sdf/bsp_route/reach.rs`): nothing there is part of the scene, and the slot's coordinates are then of the
/// scene's size.
#[test]
fn scene_bsp_route_of_a_bracket_with_a_slot_1e11_long() {
    let (scene, options, solid) = checked_coarse_route("bsp_8");
    let mesh = solid.to_mesh();
    let report = mesh.report();
    assert!(
        report.is_closed_manifold() && report.needles == 0 && report.genus == Some(4),
        "bsp_8: {report}"
    );
    // The same document with a slot 12 long, which still passes through the plate and the boss
    // and reaches less than the scene's diagonal beyond its box: nothing of it is cut off, and
    // its coordinates are of the scene's size.
    let short = finding_json("bsp_8").replace("99999999990.3", "12.0");
    let expected = variant_volume(&scene, &short, &options);
    assert_volume("bsp_8", &solid, &mesh, expected, "the short slot's");

    // The plate less the slot alone: the slot's trace through the plate's thickness t is its
    // cross-section (2.2 × 0.25) over the cosine of its 1° tilt from the plate's normal.
    let minimal = bspcsg::Scene::from_json_str(
        r#"{"op": "subtract", "children": [
            {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [6.0, 0.5, 3.0]}},
            {"kind": "sdf_primitive", "pos": [1, 1.3, 0], "rot": [1, 45, 0],
             "data": {"primitive_type": "box", "size": [2.2, 99999999990.3, 0.25]}}
        ]}"#,
    )
    .unwrap();
    let mesh = minimal
        .to_solid(&scene_check::coarse(&minimal).unwrap())
        .unwrap()
        .to_mesh();
    let report = mesh.report();
    assert!(
        report.is_closed_manifold()
            && report.needles == 0
            && report.shells.len() == 1
            && report.genus == Some(1),
        "plate less slot: {report}"
    );
    let exact = 6.0 * 0.5 * 3.0 - 2.2 * 0.25 * 0.5 / 1f64.to_radians().cos();
    assert!(
        (mesh.volume() - exact).abs() < 1e-12 * exact,
        "plate less slot: {} against {exact}",
        mesh.volume()
    );
}

/// Found by a 10-minute run of the `scenes` target in round 16 (libFuzzer seed 1628396729 picked
/// by the run, artifact crash-264abf94…, after 2.64 M executions at about 490 s), minimised by
/// hand to the baked plate and boss (plate 1 wide, boss of radius 1.8) less the bore, the
/// counterbore and two mounting holes of radius 1.2 (`bsp_9`). The coarse BSP route left a
/// flat shell of two triangles (378 triangles, 2 shells; the solid's volume 5.3e-7 below its
/// mesh's): a sliver of a hole's ceiling (y = 1) kept outside the boss, 0.09 long and up to
/// 9.5e-5 wide. The boss's tree had labelled that wedge inside: building it, a wall triangle
/// split its two neighbours above it, 9e-4 rad off its plane, judging their shared corner,
/// 2.7e-12 in front, by the narrow band of nearly parallel planes, while the triangle round the
/// corner (0.2 rad off) counted it as on the plane. The neighbours' slivers carried their
/// planes into the front subtree alone. The build now sends a polygon beyond the tolerance on
/// one side only whole to that side (`bsp/build/face.rs`, `face_node`).
#[test]
fn scene_bsp_route_of_a_bracket_keeps_a_sliver_of_a_holes_ceiling() {
    let (scene, options, solid) = checked_coarse_route("bsp_9");
    let mesh = solid.to_mesh();
    let report = mesh.report();
    assert!(
        report.is_closed_manifold()
            && report.needles == 0
            && report.shells.len() == 1
            && report.genus == Some(1),
        "bsp_9: {report}"
    );
    // The same cuts made in two steps (the bore and counterbore, then each hole), so every tree
    // but the first is another solid's: the same volume.
    let mut doc: serde_json::Value = serde_json::from_str(&finding_json("bsp_9")).unwrap();
    let cuts = doc["tree"]["children"].as_array().unwrap().clone();
    let holes = cuts[3]["children"].as_array().unwrap().clone();
    let mut steps = vec![serde_json::json!({"op": "subtract", "children": cuts[..3]})];
    steps.extend(holes);
    doc["tree"] = serde_json::json!({"op": "subtract", "children": steps});
    let expected = variant_volume(&scene, &doc.to_string(), &options);
    assert_volume("bsp_9", &solid, &mesh, expected, "stepwise");
}

/// Found by a second 10-minute run of the `scenes` target in round 16 (after the fix above,
/// libFuzzer seed 1987012407, artifact crash-6c049723…, after 1.64 M executions at about 360 s),
/// not minimised (`bsp_10`): the example bracket less, among its cuts, a second smooth union of
/// plate and boss (the first's plate 0.6 thick, the second's 0.5). The coarse BSP route left
/// 6 boundary edges and 8 shells (864 triangles), all on the boss's wall at z = −0.8, x ≈ 0,
/// y 0.62 … 0.94; the purer form below, a smooth union of the boss alone less the smooth union
/// of plate and boss (empty: a smooth union holds its operands), left 62 boundary edges, 18
/// shells and volume 3.1e-4. The two smooth unions were baked on grids of their own (centred on
/// their bounds), so the one boss came out as two marching-cubes walls 10⁻⁹ … 10⁻⁸ apart; baked
/// on one lattice they still differed by 10⁻¹⁴ … 10⁻⁵ where a grid point beside the wall lay in
/// the other smooth union's blend (the fields equal on the wall, not there), since three steps
/// of root refinement still lean on the bracket's starting values. Closed since the BSP route
/// bakes every smooth subtree on the lattice of the grid over the whole scene, each on the part
/// around its bound, and refines each root until it no longer moves (`sdf/bsp_route.rs`,
/// `Ctx::bake`; `marching_cubes::Refine::Converge`): the boss's vertices come out bit for bit
/// alike in both bakes and the booleans meet coincident faces.
#[test]
fn scene_bsp_route_less_a_second_bake_of_the_same_boss() {
    let (scene, options, solid) = checked_coarse_route("bsp_10");
    let mesh = solid.to_mesh();
    let report = mesh.report();
    assert!(
        report.is_closed_manifold() && report.needles == 0 && report.genus == Some(1),
        "bsp_10: {report}"
    );
    // The same cuts made in two steps (the first three, then the rest), each bake on the same
    // lattice (the scene's box is the same): the same volume.
    let mut doc: serde_json::Value = serde_json::from_str(&finding_json("bsp_10")).unwrap();
    let children = doc["tree"]["children"].as_array().unwrap().clone();
    let mut steps = vec![serde_json::json!({"op": "subtract", "children": children[..4]})];
    steps.extend_from_slice(&children[4..]);
    doc["tree"] = serde_json::json!({"op": "subtract", "children": steps});
    let expected = variant_volume(&scene, &doc.to_string(), &options);
    assert_volume("bsp_10", &solid, &mesh, expected, "stepwise");
    // Reduced: a smooth union holds its operands, so the boss less plate and boss is empty.
    let reduced = bspcsg::Scene::from_json_str(
        r#"{"op": "subtract", "children": [
            {"op": "smooth_union", "smooth": "polynomial", "smooth_k": 0.3, "children": [
                {"kind": "sdf_primitive", "pos": [0, 0.75, 0],
                 "data": {"primitive_type": "cylinder", "radius": 0.8, "height": 1.5}}]},
            {"op": "smooth_union", "smooth": "polynomial", "smooth_k": 0.3, "children": [
                {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [1.0, 0.5, 3.0]}},
                {"kind": "sdf_primitive", "pos": [0, 0.75, 0],
                 "data": {"primitive_type": "cylinder", "radius": 0.8, "height": 1.5}}]}
        ]}"#,
    )
    .unwrap();
    let options = scene_check::coarse(&reduced).unwrap();
    let rest = reduced.to_solid(&options).unwrap();
    assert!(rest.is_empty(), "reduced: {}", rest.to_mesh().report());
}

/// Found by a 10-minute run of the `scenes` target in round 17 (libFuzzer seed 1703, artifact
/// crash-ab383ffc…, after 2.12 M executions at about 480 s), not minimised (`bsp_11`): a bracket
/// variant whose bore (radius 1.45) takes the whole boss, one of whose mounting holes sits at
/// z = −1.4·10¹⁰, far outside the scene. The coarse BSP route left 18 boundary edges (194
/// triangles, volume 3.4292); with the children removed while it failed, the bracket less the
/// bore and three holes came out at volume 1.531 where it is 3.392 with the far hole anywhere
/// within 10⁶. The far cylinder is within the reach along its axis (y), so `reach` kept it
/// whole; united with the near holes, its coordinates of 10¹⁰ set the tolerance of the booleans
/// it entered. The BSP route now leaves out a primitive wholly outside the scene's box (nothing
/// there is part of the scene; `sdf/bsp_route.rs`, `Ctx::solid`), so the far hole changes
/// nothing: the same volume as the document without it.
#[test]
fn scene_bsp_route_of_a_bracket_with_a_hole_1e10_away() {
    let (scene, options, solid) = checked_coarse_route("bsp_11");
    let mesh = solid.to_mesh();
    let report = mesh.report();
    assert!(
        report.is_closed_manifold()
            && report.needles == 0
            && report.shells.len() == 1
            && report.genus == Some(2),
        "bsp_11: {report}"
    );
    let mut doc: serde_json::Value = serde_json::from_str(&finding_json("bsp_11")).unwrap();
    let holes = doc["tree"]["children"][3]["children"]
        .as_array_mut()
        .unwrap();
    assert_eq!(holes[3]["pos"][2], -14444444444.0);
    holes.pop();
    let expected = variant_volume(&scene, &doc.to_string(), &options);
    assert_volume("bsp_11", &solid, &mesh, expected, "without the far hole");
    // Left out before it is made: made 10⁻⁴ tall, the far hole set the booleans a region
    // beyond precision while it was left out only after tessellating.
    let mut doc: serde_json::Value = serde_json::from_str(&finding_json("bsp_11")).unwrap();
    let far = &mut doc["tree"]["children"][3]["children"][3];
    assert_eq!(far["data"]["primitive_type"], "cylinder");
    far["data"]["height"] = 1e-4.into();
    let thin = bspcsg::Scene::from_json_str(&doc.to_string()).unwrap();
    let volume = thin.to_solid(&options).unwrap().volume();
    assert!(
        (volume - expected).abs() < 1e-12 * expected,
        "bsp_11 with a thin far hole: {volume} vs {expected}"
    );
}

/// A primitive wholly outside the scene's box is neither made nor counted: a unit box less a
/// sphere of radius 20,000 at 10⁶ is the box, where the sphere's polygons alone (about
/// 1.4·10⁷ at the box's tolerance) were refused against the scene's polygon budget.
#[test]
fn a_huge_primitive_outside_the_scene_is_not_counted_against_its_budget() {
    let scene = bspcsg::Scene::from_json_str(
        r#"{"op": "subtract", "children": [
            {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [1, 1, 1]}},
            {"kind": "sdf_primitive", "pos": [0, 0, 1000000],
             "data": {"primitive_type": "sphere", "radius": 20000}}]}"#,
    )
    .unwrap();
    let solid = scene
        .to_solid(&bspcsg::TessellationOptions::default())
        .unwrap();
    assert_eq!(solid.volume(), 1.0);
}

/// Found in round 17 by a reader of the shared-lattice change, not by the fuzz target
/// (`bsp_12`): random scenes `op(smooth_union(S, X₁), smooth_union(S, X₂))` holding one sphere
/// S in both unions; this one, a difference, is the one of 17 run that got worse. At be1b9bf
/// (each smooth union baked on a grid of its own) it closed, with 166,768 triangles (slivers
/// between the two walls of S) and volume 0.35927. Since the bakes share one lattice and
/// converge their roots (bsp_10's fix) it has 7,024 triangles, 2 shells, 4 boundary edges and
/// volume 0.3590904, refused by the command line (exit 2); with 3 refinement steps on the
/// shared lattice instead of converged roots, 443 boundary edges. Four other scenes of the 17
/// (5,443, 597, 2 and 4,142 boundary edges before) close since that change. Not traced: at the
/// rim of a blend the two fields stop agreeing beside the surface, and the two bakes may
/// also decide an ambiguous face of a cell differently.
#[test]
#[ignore = "open: two smooth unions sharing a sphere, differenced — 4 boundary edges since the bakes share one lattice"]
fn scene_bsp_route_of_two_smooth_unions_sharing_a_sphere_differenced() {
    let scene = finding_scene("bsp_12");
    let solid = scene
        .to_solid(&bspcsg::TessellationOptions::default())
        .unwrap();
    let report = solid.to_mesh().report();
    assert!(
        report.is_closed_manifold() && report.needles == 0,
        "bsp_12: {report}"
    );
    // The SDF route gives 0.35883 at its default cell, be1b9bf's BSP route 0.35927.
    assert!(
        (report.volume - 0.3590).abs() < 2e-3 * 0.3590,
        "bsp_12: volume {}",
        report.volume
    );
}

/// Found by round 19's 10-minute `scenes` run (seed 1901; `bsp_13`): two I-beams whose
/// profile has a corner 7·10⁶ out, so each is a sliver 10⁷ long, a unit across, whose whole
/// profile is needles by the shell's diagonal (needle area 1e-12 d² ≈ 320). The boolean's
/// polygons were right (volume 15,276,840.7) and the weld closed them, but the needle pass
/// moved corners of the profile by up to 36 (within its bound, 2·10⁻⁶ d) on triangles 10⁷
/// long, each move sweeping up to 5·10⁷: the mesh came out inside out (volume −8.7·10⁶, the
/// command line refusing it), and the same union of the two beams' meshes closed with volume
/// 7.4·10⁷, written with exit 0. The needle pass now leaves the mesh as it was where it would
/// change the volume.
#[test]
fn scene_bsp_route_of_two_beams_ten_million_long_keeps_its_volume() {
    let (scene, _, solid) = coarse_route("bsp_13");
    let default = scene
        .to_solid(&bspcsg::TessellationOptions::default())
        .unwrap();
    for (what, solid) in [("coarse", solid), ("default", default)] {
        let mesh = solid.to_mesh();
        let report = mesh.report();
        assert!(report.is_closed_manifold(), "bsp_13 {what}: {report}");
        assert!(
            (report.volume - solid.volume()).abs() < 1e-8 * solid.volume(),
            "bsp_13 {what}: mesh volume {} but the solid's {}",
            report.volume,
            solid.volume()
        );
        let (inside, reach) = (solid.bbox(), 1e-9 * solid.bbox().diagonal());
        let bbox = mesh.bbox();
        assert!(
            inside.contains_point(bbox.min, reach) && inside.contains_point(bbox.max, reach),
            "bsp_13 {what}: the mesh reaches {:?} beyond the solid's {:?}",
            mesh.bbox(),
            solid.bbox()
        );
    }
}
