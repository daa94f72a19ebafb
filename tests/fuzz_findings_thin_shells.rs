//! The `scenes` fuzz target's findings on shells thinner than they are long (round 23): the
//! needles by area that are the shape's own faces, and those the kernel should still remove
//! (see `scene_check.rs` for the rule). The other findings are in `fuzz_findings_scenes.rs`.

#[path = "../fuzz/fuzz_targets/scene_check.rs"]
#[allow(dead_code)]
mod scene_check;

/// A finding's scene (`tests/fuzz_findings/<name>.json`).
fn finding_scene(name: &str) -> bspcsg::Scene {
    let path = format!(
        "{}/tests/fuzz_findings/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    bspcsg::Scene::from_json_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

/// Minimised from round 23's 10-minute `scenes` run (8 findings, all I-beam profiles with one
/// corner 6.7·10⁵ … 6.7·10⁶ out): a right prism 6,666,122 long whose end face is 6 × 3. Its
/// two end triangles (area 9) are needles by the shell's diagonal (10⁻¹² d² = 44): the report
/// counts them, and no removal within the needle pass's bound keeps the volume (collapsing one
/// takes a third of the prism). They are the shape's own faces, well-shaped and larger than a
/// weld's reach on a shell 1.5 thick by `2V/A`: the check no longer demands them away
/// (`scene_check.rs`). A sliver a cut would leave on the same prism still counts.
#[test]
fn scene_bsp_route_of_a_prism_thinner_than_a_speck() {
    let scene = bspcsg::Scene::from_json_str(
        r#"{"sdf_2d":{"i_section":{"type":"polygon","points":[[0,6],[6666122,0],[0,0]]}},
            "nodes":[{"tree":{"op":"union","children":[
                {"op":"extrude","source_2d_sdf":"i_section","extrude_depth":3}]}}]}"#,
    )
    .unwrap();
    if let Err(e) = scene_check::check_bsp_route(&scene) {
        panic!("prism: {e}");
    }
    let mut mesh = scene
        .to_solid(&scene_check::coarse(&scene).unwrap())
        .unwrap()
        .to_mesh();
    let report = mesh.report();
    let exact = 0.5 * 6.0 * 6666122.0 * 3.0;
    assert!(
        report.is_closed_manifold()
            && report.needles == 2
            && (report.volume - exact).abs() < 1e-12 * exact,
        "prism: {report}"
    );
    // A vertex 10⁻⁹ of the way from a corner of the largest triangle to its other two splits it
    // into one fat triangle and two slivers (area 0.02, thin): both count.
    let area = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        (b - a).cross(c - a).length()
    };
    let k = (0..mesh.triangles.len())
        .max_by(|&i, &j| area(&mesh.triangles[i]).total_cmp(&area(&mesh.triangles[j])))
        .unwrap();
    let [a, b, c] = mesh.triangles[k];
    let [pa, pb, pc] = [a, b, c].map(|v| mesh.positions[v as usize]);
    let p = mesh.positions.len() as u32;
    mesh.positions
        .push(pa + 1e-9 * (pb - pa) + 1e-9 * (pc - pa));
    mesh.triangles[k] = [a, b, p];
    mesh.triangles.extend([[b, c, p], [c, a, p]]);
    mesh.sources.extend([mesh.sources[k]; 2]);
    assert!(mesh.report().is_closed_manifold(), "{}", mesh.report());
    assert_eq!(scene_check::needles_within(&mesh, f64::INFINITY), 2);
}

/// From the same run (artifact crash-76222a05…, `bsp_18`): an I-beam variant whose profile has
/// a corner 666,660 out and whose coarse BSP route left 71 needles by the shell's diagonal,
/// every one the profile's own detail (triangles 0.1 … 1 across on a beam 6 deep): passes the
/// check as the prism above does.
#[test]
fn scene_bsp_route_of_an_i_beam_with_a_corner_666660_out() {
    let scene = finding_scene("bsp_18");
    if let Err(e) = scene_check::check_bsp_route(&scene) {
        panic!("bsp_18: {e}");
    }
    let options = scene_check::coarse(&scene).unwrap();
    let solid = scene.to_solid(&options).unwrap();
    let report = solid.to_mesh().report();
    // 71 needles by area before round 23's needles23 (the pass undid all its moves); its 10 thin
    // ones go now, the profile's own 61 stay.
    assert!(
        report.is_closed_manifold()
            && report.needles == 61
            && (report.volume - solid.volume()).abs() < 1e-9 * solid.volume(),
        "bsp_18: {report}"
    );
}

/// The other seven findings of that run (`bsp_14` … `bsp_17`, `bsp_19` … `bsp_21`; artifacts
/// crash-040cfbca…, 203444b3…, 2b9c935f…, 2d21d903…, 7c264ed4…, ad321bd3…, da72c346…), each
/// two I-beams with a profile corner 666,660 out, one less two bolt holes, one with a cross
/// piece. Besides the profiles' own detail they keep 3, 10, 13, 10, 7, 5 and 11 thin needles:
/// steps 2·10⁻⁵ … 3·10⁻⁵ high (30 … 50 plane tolerances) where the profile's edge, sloping
/// 9.3·10⁻⁶, passes under the cross piece's flat top, and thin triangles of the profiles'
/// faces. The needle pass removes every needle of each mesh (it finds 47 … 155, leaves 0), but
/// taking the profiles' own faces changed the volume by 1.4 % … 26 %, beyond its 1 % bound, so
/// it undid all its moves, the thin needles' too. Now the pass judges the volume per shell and
/// redoes a shell over the bound removing only the needles of the check's rule
/// (`bspcsg::is_needle_to_remove`): the thin needles go, the profiles' own faces stay, the
/// volume within the 1 % bound. `bsp_13` (an earlier finding of the same kind, whose own test
/// does not ask the check) kept 6 thin needles so too.
#[test]
fn scenes_bsp_route_of_i_beams_lose_their_thin_needles() {
    for i in [13, 14, 15, 16, 17, 19, 20, 21] {
        let name = format!("bsp_{i}");
        let scene = finding_scene(&name);
        if let Err(e) = scene_check::check_bsp_route(&scene) {
            panic!("{name}: {e}");
        }
        let solid = scene
            .to_solid(&scene_check::coarse(&scene).unwrap())
            .unwrap();
        let report = solid.to_mesh().report();
        let exact = solid.volume();
        // The route's mesh has the solid's volume (to 4e-8 before the needle pass). The pass
        // changes it where a thin needle's flip sweeps the tetrahedron on its long edge: the
        // needle's area (under 10⁻¹² d², d 1.3·10⁶) times the reach of the neighbour across
        // that edge, an end face's triangle 10⁴ wide: bsp_15, bsp_19 and bsp_21 end 1.6e-3,
        // 5.4e-3 and 1.2e-3 under (one flip of -4,638 on bsp_15), within the pass's 1 % bound
        // of the shell. The others end within 4e-8.
        let bound = if [15, 19, 21].contains(&i) {
            1e-2
        } else {
            1e-7
        };
        assert!(
            report.is_closed_manifold() && (report.volume - exact).abs() < bound * exact.abs(),
            "{name}: {exact} {report}"
        );
    }
}

/// Round 23's second 10-minute `scenes` run (artifacts crash-1158cc33…, crash-1207e49a…,
/// crash-81803af6…; `bsp_22` … `bsp_24`): a box 28 × 1 × 3 (23, 34 long) less a cylinder of
/// radius 4·10⁷ … 8·10⁷ and height 1 turned a few degrees: the box less a tilted slab 1
/// thick, two wedges. Features of 1 on operands 8·10⁷ across are within the precision
/// contract: the coarse BSP route must give a closed 2-manifold of positive shells or refuse.
#[test]
fn scenes_bsp_route_of_a_box_less_a_cylinder_4e7_wide() {
    for i in [22, 23, 24] {
        let name = format!("bsp_{i}");
        let scene = finding_scene(&name);
        if let Err(e) = scene_check::check_bsp_route(&scene) {
            panic!("{name}: {e}");
        }
        let Ok(solid) = scene.to_solid(&scene_check::coarse(&scene).unwrap()) else {
            continue;
        };
        let report = solid.to_mesh().report();
        // Within the box the cylinder is a slab: a box 200 wide in its place cuts the same.
        let json = std::fs::read_to_string(format!(
            "{}/tests/fuzz_findings/{name}.json",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        let i = json.find("\"cylinder\"").unwrap();
        let j = i + json[i..].find('}').unwrap();
        let slab = format!(
            "{}\"box\", \"size\": [200, 1, 200]{}",
            &json[..i],
            &json[j..]
        );
        let slab = bspcsg::Scene::from_json_str(&slab).unwrap();
        let exact = slab
            .to_solid(&scene_check::coarse(&slab).unwrap())
            .unwrap()
            .to_mesh()
            .report()
            .volume;
        assert!(
            report.is_closed_manifold()
                && exact > 1.0
                && (report.volume - exact).abs() < 1e-9 * exact,
            "{name}: {report}, slab's volume {exact}"
        );
    }
}
