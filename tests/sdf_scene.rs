//! Scene documents: the examples parse, and every bad document is refused with its JSON path.

use bspcsg::{Error, Scene};

fn fault(json: &str) -> (String, String) {
    match Scene::from_json_str(json) {
        Err(Error::Scene {
            json_path, message, ..
        }) => (json_path, message),
        Err(e) => panic!("not a scene error: {e}"),
        Ok(_) => panic!("accepted: {json}"),
    }
}

fn assert_fault(json: &str, path: &str, words: &str) {
    let (p, m) = fault(json);
    assert_eq!(p, path, "{m}");
    assert!(m.contains(words), "{p}: {m} (wanted `{words}`)");
}

const SPHERE: &str =
    r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}"#;

#[test]
fn examples_parse() {
    for name in ["mechanical_part", "organic_blend", "extruded_profile"] {
        let path = format!("{}/examples/scenes/{name}.json", env!("CARGO_MANIFEST_DIR"));
        let s = Scene::from_path(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(s.primitive_count() > 1, "{name}");
        assert!(s.bbox().diagonal().is_finite());
        assert!(!s.materials().is_empty());
    }
    let m = Scene::from_path(format!(
        "{}/examples/scenes/mechanical_part.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    assert_eq!(m.render_profile().max_steps, 160);
    assert_eq!(m.render_profile().hit_epsilon, 0.0005);
}

#[test]
fn bare_node_is_a_document() {
    let s = Scene::from_json_str(SPHERE).unwrap();
    assert_eq!(s.materials().len(), 1);
    assert_eq!(s.materials()[0].name, "default");
    assert_eq!(*s.render_profile(), bspcsg::RenderProfile::default());
}

#[test]
fn faults_name_their_json_path() {
    assert_fault(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "blob", "radius": 1}}"#,
        "$.data.primitive_type",
        "unknown primitive_type `blob`",
    );
    assert_fault(
        r#"{"op": "union", "children": [{"kind": "sdf_primitive", "data": {"primitive_type": "sphere"}}]}"#,
        "$.children[0].data.radius",
        "missing `radius`",
    );
    assert_fault(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [1, -2, 1]}}"#,
        "$.data.size[1]",
        "must be > 0",
    );
    assert_fault(
        &format!(r#"{{"op": "smooth_union", "children": [{SPHERE}, {SPHERE}]}}"#),
        "$.smooth_k",
        "smooth op needs",
    );
    assert_fault(
        &format!(r#"{{"op": "smooth_union", "smooth_k": 0, "children": [{SPHERE}]}}"#),
        "$.smooth_k",
        "must be > 0",
    );
    assert_fault(
        r#"{"sdf_2d": {"a": {"type": "circle", "radius": 1}},
            "tree": {"op": "extrude", "source_2d_sdf": "b", "extrude_depth": 1}}"#,
        "$.tree.source_2d_sdf",
        "unknown 2D shape id `b`; declared: a",
    );
    assert_fault(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": "1"}}"#,
        "$.data.radius",
        "expected a number, found a string",
    );
    assert_fault(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1, "colour": "red"}}"#,
        "$.data.colour",
        "unknown field `colour`",
    );
    assert_fault(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1, "pos": [0, 0, 0]}}"#,
        "$.data.pos",
        "belong on the node",
    );
    assert_fault(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "box", "radius": 1}}"#,
        "$.data.radius",
        "unknown field `radius` in a box primitive",
    );
    assert_fault(
        &format!(r#"{{"op": "union", "smooth_k": 2, "children": [{SPHERE}]}}"#),
        "$.smooth_k",
        "unknown field",
    );
    assert_fault(
        r#"{"op": "union", "children": []}"#,
        "$.children",
        "at least one child",
    );
    assert_fault(
        r#"{"op": "merge", "children": []}"#,
        "$.op",
        "unknown op `merge`",
    );
    assert_fault(
        &format!(r#"{{"op": "union", "children": [{SPHERE}, 3]}}"#),
        "$.children[1]",
        "found a number",
    );
    assert_fault(
        r#"{"kind": "sdf_primitive", "pos": [0, 0], "data": {"primitive_type": "sphere", "radius": 1}}"#,
        "$.pos",
        "expected 3 numbers",
    );
    assert_fault(
        r#"{"kind": "sdf_primitive", "scale": [1, 0, 1], "data": {"primitive_type": "sphere", "radius": 1}}"#,
        "$.scale[1]",
        "non-zero",
    );
    assert_fault(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "torus", "radius": 1, "tube_radius": 2}}"#,
        "$.data.tube_radius",
        "smaller than radius",
    );
    assert_fault(
        r#"{"op": "extrude", "source_2d_sdf": {"type": "polygon", "points": [[0, 0], [2, 2], [2, 0], [0, 1]]}, "extrude_depth": 1}"#,
        "$.source_2d_sdf.points",
        "not simple",
    );
    assert_fault(
        r#"{"op": "extrude", "source_2d_sdf": {"type": "polygon", "points": [[0, 0], [1, 0]]}, "extrude_depth": 1}"#,
        "$.source_2d_sdf.points",
        "3 to",
    );
    assert_fault(
        r#"{"materials": {"steel": [0.5, 0.5, 0.5]},
            "tree": {"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1, "material": "stell"}}}"#,
        "$.tree.data.material",
        "unknown material `stell`",
    );
    assert_fault(
        r#"{"materials": {"steel": [0.5, 0.5, 2]}, "tree": {"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1}}}"#,
        "$.materials.steel[2]",
        "0..1",
    );
    assert_fault(
        &format!(r#"{{"render_profile": {{"max_steps": 1.5}}, "tree": {SPHERE}}}"#),
        "$.render_profile.max_steps",
        "whole number",
    );
    assert_fault(
        &format!(r#"{{"nodes": [{{"tree": {SPHERE}, "rotation": [0, 0, 0]}}]}}"#),
        "$.nodes[0].rotation",
        "unknown field",
    );
    assert_fault(r#"{"data": 1}"#, "$", "expected a node");
    assert_fault(r#"[1, 2]"#, "$", "found an array");
    assert_fault(r#"{"op": "union", "children": [}"#, "$", "not valid JSON");
    assert_fault(
        r#"{"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1e300}}"#,
        "$.data.radius",
        "supported range",
    );
}

#[test]
fn nested_trees_and_scoped_2d_shapes() {
    let s = Scene::from_json_str(
        r#"{"sdf_2d": {"outer": {"type": "circle", "radius": 1}},
            "tree": {"kind": "sdf_csg_tree", "pos": [10, 0, 0],
                     "sdf_2d": {"inner": {"type": "rectangle", "size": [1, 1]}},
                     "root": {"op": "union", "children": [
                        {"op": "extrude", "source_2d_sdf": "outer", "extrude_depth": 1},
                        {"op": "extrude", "source_2d_sdf": "inner", "extrude_depth": 3}
                     ]}}}"#,
    )
    .unwrap();
    assert!(s.distance(glam::DVec3::new(10.0, 0.0, 1.4)) < 0.0);
    // Declarations inside a nested tree are not visible outside it.
    assert_fault(
        r#"{"op": "union", "children": [
            {"kind": "sdf_csg_tree", "sdf_2d": {"inner": {"type": "circle", "radius": 1}},
             "root": {"op": "extrude", "source_2d_sdf": "inner", "extrude_depth": 1}},
            {"op": "extrude", "source_2d_sdf": "inner", "extrude_depth": 1}]}"#,
        "$.children[1].source_2d_sdf",
        "unknown 2D shape id `inner`",
    );
}

#[test]
fn deep_and_wide_documents_do_not_overflow() {
    // Within serde_json's nesting limit (128 levels, about 60 tree levels) a deep chain works.
    let mut doc = SPHERE.to_string();
    for _ in 0..60 {
        doc = format!(r#"{{"op": "union", "pos": [0.01, 0, 0], "children": [{doc}]}}"#);
    }
    let s = Scene::from_json_str(&doc).unwrap();
    assert!((s.distance(glam::DVec3::new(0.6, 0.0, 0.0)) + 1.0).abs() < 1e-9);
    // Deeper documents are refused, not a stack overflow.
    for _ in 0..100 {
        doc = format!(r#"{{"op": "union", "children": [{doc}]}}"#);
    }
    assert_fault(&doc, "$", "recursion limit");
    // Very wide nodes evaluate with a shallow stack.
    let kids: Vec<String> = (0..5000)
        .map(|i| {
            format!(
                r#"{{"kind": "sdf_primitive", "pos": [{}, 0, 0], "data": {{"primitive_type": "sphere", "radius": 0.4}}}}"#,
                i
            )
        })
        .collect();
    let s = Scene::from_json_str(&format!(
        r#"{{"op": "union", "children": [{}]}}"#,
        kids.join(",")
    ))
    .unwrap();
    assert!((s.distance(glam::DVec3::new(4999.0, 0.0, 0.0)) + 0.4).abs() < 1e-9);
}

#[test]
fn several_placed_trees() {
    let s = Scene::from_json_str(&format!(
        r#"{{"nodes": [{{"tree": {SPHERE}, "pos": [-3, 0, 0]}}, {{"tree": {SPHERE}, "pos": [3, 0, 0], "scale": 2}}]}}"#
    ))
    .unwrap();
    assert!((s.distance(glam::DVec3::new(-3.0, 0.0, 0.0)) + 1.0).abs() < 1e-12);
    assert!((s.distance(glam::DVec3::new(3.0, 0.0, 0.0)) + 2.0).abs() < 1e-12);
}

#[test]
fn the_documented_complete_example_parses_and_bakes() {
    let doc = std::fs::read_to_string(format!(
        "{}/docs/scene-format.md",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let block = doc
        .split("## A complete example")
        .nth(1)
        .and_then(|s| s.split("```json").nth(1))
        .and_then(|s| s.split("```").next())
        .unwrap();
    let s = Scene::from_json_str(block).unwrap();
    assert_eq!(s.primitive_count(), 5);
    let mesh = s.bake(&bspcsg::BakeOptions::with_resolution(64)).unwrap();
    assert!(mesh.volume() > 0.0);
    let names: Vec<&str> = s.materials().iter().map(|m| m.name.as_str()).collect();
    assert!(names.contains(&"steel") && names.contains(&"machined") && names.contains(&"default"));
}
