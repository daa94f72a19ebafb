//! A scene as a WebGL2 fragment shader: its distance function as GLSL, and the CPU renderer's
//! sphere tracing, shading, soft shadows and occlusion around it, so the editor's preview shows
//! what `bspcsg render` draws.
//!
//! The scene's compiled program (the one the CPU evaluates) is unrolled into straight-line
//! code (`ir.rs`): one statement per transform, primitive or combination, each a call of a
//! helper in `prelude.glsl`. The printer turns it into GLSL; the tests run the same statements
//! through an interpreter that follows the helpers line by line, and check that its distance is
//! the scene's at sample points around every example scene.

mod ir;
mod print;

#[cfg(test)]
mod interp;

use std::fmt::Write;

use glam::DVec3;

use crate::raymarch::DEFAULT_AMBIENT;
use crate::sdf::{Light, LightKind, Scene};
use ir::Code;
use print::{lit, v3};

/// The helpers every generated shader starts with.
const PRELUDE: &str = include_str!("prelude.glsl");
/// The ray marcher every generated shader ends with.
const MARCHER: &str = include_str!("main.glsl");

/// A generated fragment shader and what the page needs to drive it.
#[derive(Clone, Debug)]
pub struct Shader {
    /// GLSL ES 3.00 source of the fragment shader (pair it with a full-screen triangle).
    pub source: String,
    /// The JSON path of the node of each leaf the shader numbers: leaf `i` is the `i`-th. The
    /// leaves of a subtree are a contiguous run, so selecting a node sets the uniform range
    /// `uSelLo..uSelHi` to its run.
    pub leaf_paths: Vec<String>,
}

/// The fragment shader of a scene: its distance field, its materials, its render profile
/// (steps, hit epsilon, reach, shadow and occlusion samples, background) and its lights (or the
/// default key and fill pair), ray marched as `raymarch::render_scene` does.
///
/// Uniforms: `uResolution` (pixels), `uEye`, `uTarget`, `uUp`, `uFov` (degrees) or
/// `uOrthoHeight` (> 0: orthographic), and `uSelLo`, `uSelHi` (the highlighted leaves).
#[must_use]
pub fn fragment_shader(scene: &Scene) -> Shader {
    fragment_shader_with(scene, false)
}

/// [`fragment_shader`], with the skipping of primitives by their bounding spheres on or off.
/// Skipping evaluates a primitive that is the right operand of a union or subtraction only
/// where it can change the result; it pays where neighbouring pixels branch alike, and costs
/// where a GPU (or SwiftShader, measured: 30 % slower on the mechanical example) runs both
/// sides of a branch for a group of pixels, so it is off in [`fragment_shader`].
#[must_use]
pub fn fragment_shader_with(scene: &Scene, cull: bool) -> Shader {
    let code = Code::from_program(&scene.program, cull);
    let mut out = String::from("#version 300 es\nprecision highp float;\nprecision highp int;\n");
    constants(scene, &code, &mut out);
    out.push_str(PRELUDE);
    print::shapes(&code, &mut out);
    print::scene_function(&code, false, &mut out);
    print::scene_function(&code, true, &mut out);
    out.push_str(MARCHER);
    Shader {
        source: out,
        leaf_paths: scene.primitive_paths().to_vec(),
    }
}

/// The profile, the scene's box and size, leaf colours and lights as GLSL constants.
fn constants(scene: &Scene, code: &Code, out: &mut String) {
    let p = scene.render_profile();
    let b = scene.bbox();
    // The size that scales occlusion and shadow steps, as the CPU tracer picks it.
    let diag = b.diagonal();
    let size = if diag.is_finite() && diag > 0.0 {
        diag
    } else {
        0.1 * p.max_distance
    };
    let (bmin, bmax) = if b.is_empty() {
        // A box no ray enters.
        (DVec3::splat(1.0), DVec3::splat(-1.0))
    } else {
        (b.min, b.max)
    };
    let _ = writeln!(out, "#define MAX_STEPS {}", p.max_steps.min(100_000));
    let _ = writeln!(out, "#define HIT_EPS {}", lit(p.hit_epsilon));
    let _ = writeln!(out, "#define MAX_DIST {}", lit(p.max_distance));
    let _ = writeln!(out, "#define SHADOW_STEPS {}", p.shadow_steps.min(100_000));
    let _ = writeln!(out, "#define AO_STEPS {}", p.ao_steps.min(100_000));
    let bg = p.background;
    let _ = writeln!(
        out,
        "#define BACKGROUND {}",
        v3(DVec3::new(bg[0], bg[1], bg[2]))
    );
    let _ = writeln!(out, "#define AMBIENT {}", lit(DEFAULT_AMBIENT));
    let _ = writeln!(out, "#define SIZE {}", lit(size));
    let _ = writeln!(out, "#define BOX_MIN {}", v3(bmin));
    let _ = writeln!(out, "#define BOX_MAX {}", v3(bmax));
    let materials = scene.materials();
    let colours: Vec<String> = code
        .materials
        .iter()
        .map(|&m| {
            let c = materials
                .get(m as usize)
                .map_or(crate::mesh::Material::DEFAULT_COLOR, |m| m.base_color);
            v3(DVec3::new(c[0], c[1], c[2]))
        })
        .collect();
    let _ = writeln!(out, "#define LEAVES {}", colours.len());
    let n = colours.len().max(1);
    let colours = if colours.is_empty() {
        "vec3(0.8)".to_string()
    } else {
        colours.join(", ")
    };
    let _ = writeln!(out, "const vec3 LEAF_COLOR[{n}] = vec3[{n}]({colours});");
    let lights = scene
        .lights()
        .map_or_else(Light::default_rig, <[Light]>::to_vec);
    let _ = writeln!(out, "#define LIGHTS {}", lights.len());
    let n = lights.len().max(1);
    let mut wheres: Vec<String> = lights
        .iter()
        .map(|l| match l.kind {
            LightKind::Directional { direction } => {
                format!("vec4({}, 0.0)", &v3(direction)[5..v3(direction).len() - 1])
            }
            LightKind::Point { position } => {
                format!("vec4({}, 1.0)", &v3(position)[5..v3(position).len() - 1])
            }
        })
        .collect();
    let mut colours: Vec<String> = lights.iter().map(|l| v3(l.color * l.intensity)).collect();
    if lights.is_empty() {
        wheres.push("vec4(0.0, -1.0, 0.0, 0.0)".into());
        colours.push("vec3(0.0)".into());
    }
    let _ = writeln!(
        out,
        "const vec4 LIGHT_WHERE[{n}] = vec4[{n}]({});",
        wheres.join(", ")
    );
    let _ = writeln!(
        out,
        "const vec3 LIGHT_COLOR[{n}] = vec3[{n}]({});",
        colours.join(", ")
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points spread over the scene's box grown by a quarter on each side (a fixed sequence).
    fn samples(scene: &Scene, n: usize) -> Vec<DVec3> {
        let b = scene.bbox();
        let (lo, hi) = if b.min.is_finite() && b.max.is_finite() {
            let pad = 0.25 * (b.max - b.min);
            (b.min - pad, b.max + pad)
        } else {
            (DVec3::splat(-3.0), DVec3::splat(3.0))
        };
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n)
            .map(|_| lo + (hi - lo) * DVec3::new(next(), next(), next()))
            .collect()
    }

    /// The interpreted shader code against the scene at sample points: distance and material.
    /// Returns how many primitive evaluations the bounding spheres saved.
    fn agree(name: &str, scene: &Scene) -> usize {
        let code = Code::from_program(&scene.program, true);
        let mut culled = 0;
        for p in samples(scene, 4000) {
            let want = scene.distance(p);
            let (got, leaf, skipped) = interp::scene_leaf(&code, p);
            culled += skipped;
            assert!(
                (got - want).abs() <= 1e-9 * (1.0 + want.abs()),
                "{name}: at {p} the shader code gives {got}, the scene {want}"
            );
            let material = code.materials[leaf as usize];
            assert_eq!(
                material,
                scene.material_at(p),
                "{name}: at {p} the shader code's leaf {leaf} has another material"
            );
        }
        culled
    }

    #[test]
    fn shader_code_matches_every_example_scene() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
        let mut scenes = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().and_then(|e| e.to_str()) != Some("json") {
                continue;
            }
            let scene = Scene::from_path(&path).unwrap();
            let culled = agree(&path.display().to_string(), &scene);
            if path.ends_with("mechanical_part.json") {
                // The holes and slots are skipped away from them: the culled path is tested.
                assert!(culled > 4000, "only {culled} primitives culled");
            }
            let shader = fragment_shader(&scene);
            assert_eq!(shader.leaf_paths.len(), scene.primitive_count());
            assert!(!shader.source.contains("NaN") && !shader.source.contains("inf"));
            scenes += 1;
        }
        assert_eq!(scenes, 4, "the example scenes");
    }

    /// Every primitive, 2D primitive, smooth kind and operation, under rotations and a
    /// non-uniform scale: what the examples do not cover.
    #[test]
    fn shader_code_matches_every_shape_and_operation() {
        let scene = Scene::from_json_str(
            r##"{
            "kind": "sdf_scene",
            "materials": {"a": [0.9, 0.1, 0.1], "b": "#3060c0", "c": [0.2, 0.8, 0.3]},
            "tree": {"op": "union", "children": [
              {"op": "smooth_union", "smooth_k": 6, "rot": [10, 20, 30], "children": [
                {"kind": "sdf_primitive", "data": {"primitive_type": "pyramid", "base": 1, "height": 1.4, "material": "a"}},
                {"kind": "sdf_primitive", "pos": [0.6, 0, 0], "scale": [1, 0.5, 2],
                 "data": {"primitive_type": "torus", "radius": 0.5, "tube_radius": 0.15, "material": "b"}}]},
              {"op": "smooth_intersect", "smooth": "polynomial", "smooth_k": 0.2, "pos": [3, 0, 0], "children": [
                {"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 1, "material": "c"}},
                {"kind": "sdf_primitive", "data": {"primitive_type": "plane", "normal": [0.2, 1, 0.1], "offset": -0.3}}]},
              {"op": "smooth_subtract", "smooth_k": 0.25, "smooth": "polynomial", "pos": [-3, 0, 0], "children": [
                {"kind": "sdf_primitive", "data": {"primitive_type": "cone", "radius": 0.8, "radius_top": 0.2, "height": 1.5, "material": "a"}},
                {"kind": "sdf_primitive", "pos": [0, 0.5, 0], "data": {"primitive_type": "cylinder", "radius": 0.3, "height": 2}}]},
              {"op": "smooth_subtract", "smooth_k": 12, "pos": [0, 3, 0], "children": [
                {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [1, 1, 1], "material": "b"}},
                {"kind": "sdf_primitive", "pos": [0.5, 0.5, 0.5], "data": {"primitive_type": "sphere", "radius": 0.4, "material": "c"}}]},
              {"op": "intersect", "pos": [0, -3, 0], "children": [
                {"op": "extrude", "extrude_depth": 1, "twist": 45, "scale_top": [0.5, 0.8], "material": "c",
                 "source_2d_sdf": {"op": "intersect", "children": [
                   {"type": "polygon", "points": [[0, 0], [1, 0], [0.2, 0.3], [0, 1]]},
                   {"type": "rounded_rectangle", "size": [1.2, 0.9], "radius": 0.2, "pos": [0.3, 0.2], "rot": 15}]}},
                {"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": 0.9}}]},
              {"op": "revolve", "angle": 120, "pos": [0, 0, 3], "rot": [0, 0, 90],
               "source_2d_sdf": {"type": "regular_polygon", "sides": 5, "radius": 0.3, "pos": [0.6, 0]}},
              {"op": "revolve", "angle": 250, "pos": [0, 0, -3],
               "source_2d_sdf": {"type": "circle", "radius": 0.2, "pos": [0.6, 0.1]}}
            ]}
        }"##,
        )
        .unwrap();
        assert!(agree("every shape", &scene) > 0);
        let shader = fragment_shader(&scene);
        for helper in [
            "sdPyramid(",
            "sdTorus(",
            "sdPlane(",
            "sdCone(",
            "sdCylinder(",
            "sdBox(",
            "warpedBound(",
            "revolution(",
            "sdPolygon_0(",
            "sdRoundedRect(",
            "sminPoly",
            "smax(",
            "smin(",
        ] {
            assert!(shader.source.contains(helper), "{helper} is not called");
        }
        assert_eq!(shader.leaf_paths[0], "$.tree.children[0].children[0]");
        assert_eq!(shader.leaf_paths.last().unwrap(), "$.tree.children[6]");
    }
}
