//! Mutated documents never panic: parsing refuses them or the scene evaluates and meshes.

use bspcsg::{BakeOptions, Scene, TessellationOptions};
use proptest::prelude::*;
use serde_json::Value;

fn leaves(v: &Value, path: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    out.push(path.clone());
    match v {
        Value::Object(m) => {
            for (k, c) in m {
                path.push(k.clone());
                leaves(c, path, out);
                path.pop();
            }
        }
        Value::Array(a) => {
            for (i, c) in a.iter().enumerate() {
                path.push(i.to_string());
                leaves(c, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn at<'a>(v: &'a mut Value, path: &[String]) -> &'a mut Value {
    path.iter().fold(v, |v, k| match v {
        Value::Object(m) => m.get_mut(k).expect("key"),
        Value::Array(a) => &mut a[k.parse::<usize>().expect("index")],
        _ => unreachable!(),
    })
}

fn replacement(kind: u8, x: f64) -> Value {
    match kind % 9 {
        0 => Value::Null,
        1 => serde_json::json!(x),
        2 => serde_json::json!(-x),
        3 => serde_json::json!(0),
        4 => serde_json::json!("sphere"),
        5 => serde_json::json!([x, x, x]),
        6 => serde_json::json!([]),
        7 => serde_json::json!({}),
        _ => serde_json::json!(1e-300),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn mutated_examples_never_panic(which in 0usize..3, pick in any::<prop::sample::Index>(), kind in any::<u8>(), x in 0.001f64..1e6) {
        let name = ["mechanical_part", "organic_blend", "extruded_profile"][which];
        let text = std::fs::read_to_string(format!("{}/examples/scenes/{name}.json", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let mut doc: Value = serde_json::from_str(&text).unwrap();
        let mut paths = Vec::new();
        leaves(&doc, &mut Vec::new(), &mut paths);
        let path = pick.get(&paths).clone();
        *at(&mut doc, &path) = replacement(kind, x);
        if let Ok(scene) = Scene::from_json_str(&doc.to_string()) {
            let _ = scene.distance(glam::DVec3::new(0.1, 0.2, 0.3));
            let _ = scene.bake(&BakeOptions::with_resolution(12));
            let _ = scene.to_solid(&TessellationOptions {
                tolerance: Some(0.2),
                cell: Some(0.3),
                max_angle: None,
            });
        }
    }
}

#[test]
fn polygon_with_collinear_points_extrudes_by_both_routes() {
    let s = Scene::from_json_str(
        r#"{"op": "extrude", "source_2d_sdf": {"type": "polygon", "points": [[0, 0], [1, 0], [2, 0], [2, 1], [1, 2], [0, 1]]}, "extrude_depth": 1}"#,
    )
    .unwrap();
    let solid = s.to_solid(&TessellationOptions::default()).unwrap();
    assert!((solid.volume() - 3.0).abs() < 1e-9, "{}", solid.volume());
}
