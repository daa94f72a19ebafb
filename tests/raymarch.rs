//! The ray marcher and mesh caster against projection formulas, lighting and committed golden
//! images; bad render input; camera and lights read from the scene's envelope. The agreement
//! check between a scene and a mesh is in `raymarch_check.rs`.

mod common;

use std::path::Path;

use bspcsg::raymarch::{
    Camera, Image, Light, LightKind, Projection, RenderOptions, Rgb8, Shading, View, render_mesh,
    render_scene,
};
use bspcsg::{Mesh, RenderProfile, Scene, Solid, TessellationOptions};
use common::scenes::{SPHERE, example, scenes_dir};
use glam::DVec3;

/// A render with no shadows, no occlusion and one light along the view: shading is simple.
fn plain() -> RenderOptions {
    RenderOptions {
        lights: vec![Light::directional(DVec3::NEG_Z, 1.0)],
        profile: RenderProfile {
            shadow_steps: 0,
            ao_steps: 0,
            ..RenderProfile::default()
        },
        ..RenderOptions::default()
    }
}

fn is_background(img: &Image, x: u32, y: u32) -> bool {
    img.get(x, y) == DVec3::ZERO
}

/// Half the widest run of surface pixels on the middle row.
fn silhouette_radius(img: &Image) -> f64 {
    let y = img.height / 2;
    let hit: Vec<u32> = (0..img.width)
        .filter(|&x| !is_background(img, x, y))
        .collect();
    (hit.last().unwrap() - hit.first().unwrap() + 1) as f64 / 2.0
}

#[test]
fn a_sphere_head_on_has_the_projected_radius() {
    let scene = Scene::from_json_str(SPHERE).unwrap();
    // Perspective: a sphere of radius r at distance d subtends asin(r/d); on an image of height
    // h with vertical field fov its radius is tan(asin(r/d)) / tan(fov/2) · h/2 pixels.
    let (w, h) = (201, 151);
    for (d, fov) in [(4.0f64, 40.0f64), (6.0, 30.0), (3.0, 70.0)] {
        let cam = Camera::look_at(DVec3::new(0.0, 0.0, d), DVec3::ZERO, DVec3::Y, fov, (w, h));
        let img = render_scene(&scene, &cam, &plain()).unwrap();
        let expected = (1.0 / d).asin().tan() / (0.5 * fov).to_radians().tan() * h as f64 / 2.0;
        let got = silhouette_radius(&img);
        assert!(
            (got - expected).abs() <= 1.0,
            "d {d} fov {fov}: {got} vs {expected}"
        );
    }
    // Orthographic: r / height · h pixels.
    let cam = Camera {
        projection: Projection::Orthographic { height: 3.0 },
        ..Camera::look_at(
            DVec3::new(0.0, 0.0, 5.0),
            DVec3::ZERO,
            DVec3::Y,
            40.0,
            (w, h),
        )
    };
    let img = render_scene(&scene, &cam, &plain()).unwrap();
    let expected = 1.0 / 3.0 * h as f64;
    assert!((silhouette_radius(&img) - expected).abs() <= 1.0);
}

#[test]
fn the_brightest_pixel_faces_the_light() {
    let scene = Scene::from_json_str(SPHERE).unwrap();
    let mesh = Solid::sphere(1.0, 96, 48).unwrap().to_mesh();
    let cam = Camera::look_at(
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::ZERO,
        DVec3::Y,
        40.0,
        (160, 120),
    );
    let toward_light = DVec3::new(0.5, 0.6, 1.0).normalize();
    let opts = RenderOptions {
        lights: vec![Light::directional(-toward_light, 1.0)],
        ..plain()
    };
    let frame_ray = |x: u32, y: u32| cam.ray(x as f64, y as f64).unwrap();
    let sdf = render_scene(&scene, &cam, &opts).unwrap();
    let cast = render_mesh(&mesh, &[], &cam, &opts).unwrap();
    for img in [sdf, cast] {
        let (mut best, mut at) = (0.0, (0, 0));
        for y in 0..img.height {
            for x in 0..img.width {
                let v = img.get(x, y).x;
                if v > best {
                    best = v;
                    at = (x, y);
                }
            }
        }
        // Where that pixel's ray meets the unit sphere, the normal points at the light.
        let r = frame_ray(at.0, at.1);
        let b = r.origin.dot(r.dir);
        let t = -b - (b * b - r.origin.length_squared() + 1.0).sqrt();
        let n = r.at(t).normalize();
        assert!(
            n.dot(toward_light) > 0.995,
            "{at:?}: {}",
            n.dot(toward_light)
        );
    }
}

#[test]
fn shadows_darken_what_lies_behind_an_occluder() {
    // A ball above a slab, lit from straight above: the slab under the ball is in shadow.
    let scene = Scene::from_json_str(
        r#"{"op": "union", "children": [
            {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [6, 0.2, 6]}},
            {"kind": "sdf_primitive", "pos": [0, 1.5, 0], "data": {"primitive_type": "sphere", "radius": 0.6}}
        ]}"#,
    )
    .unwrap();
    let cam = Camera::look_at(
        DVec3::new(0.0, 8.0, 0.01),
        DVec3::ZERO,
        DVec3::Y,
        50.0,
        (64, 64),
    );
    let lit = RenderOptions {
        lights: vec![Light::directional(DVec3::NEG_Y, 1.0)],
        profile: RenderProfile {
            ao_steps: 0,
            ..RenderProfile::default()
        },
        ..RenderOptions::default()
    };
    let img = render_scene(&scene, &cam, &lit).unwrap();
    // Lit at a slant the ball's shadow falls beside it.
    let slanted = RenderOptions {
        lights: vec![Light::directional(DVec3::new(1.0, -1.0, 0.0), 1.0)],
        ..lit.clone()
    };
    let img2 = render_scene(&scene, &cam, &slanted).unwrap();
    let no_shadow = RenderOptions {
        profile: RenderProfile {
            shadow_steps: 0,
            ao_steps: 0,
            ..RenderProfile::default()
        },
        ..slanted.clone()
    };
    let img3 = render_scene(&scene, &cam, &no_shadow).unwrap();
    // The shadow falls 1.5 units towards +x from under the ball: find that pixel.
    let (fx, fy) = project(&cam, DVec3::new(1.4, 0.1, 0.0));
    assert!(
        img2.get(fx, fy).x < 0.5 * img3.get(fx, fy).x,
        "{:?}",
        img2.get(fx, fy)
    );
    // Far from the ball the slab is equally lit either way.
    let (gx, gy) = project(&cam, DVec3::new(-2.0, 0.1, 2.0));
    assert!((img2.get(gx, gy).x - img3.get(gx, gy).x).abs() < 1e-9);
    assert!(img.get(gx, gy).x > 0.5);
    // The mesh route shadows the same place.
    let mesh = bspcsg_mesh(&scene);
    let m2 = render_mesh(&mesh, &[], &cam, &slanted).unwrap();
    let m3 = render_mesh(&mesh, &[], &cam, &no_shadow).unwrap();
    assert!(m2.get(fx, fy).x < 0.5 * m3.get(fx, fy).x);
}

fn bspcsg_mesh(scene: &Scene) -> Mesh {
    scene
        .to_solid(&TessellationOptions::default())
        .unwrap()
        .to_mesh()
}

/// The pixel whose centre ray passes nearest to `p`.
fn project(cam: &Camera, p: DVec3) -> (u32, u32) {
    let mut best = (f64::INFINITY, (0, 0));
    for y in 0..cam.height {
        for x in 0..cam.width {
            let r = cam.ray(x as f64, y as f64).unwrap();
            let v = p - r.origin;
            let d = (v - r.dir * v.dot(r.dir)).length();
            if d < best.0 {
                best = (d, (x, y));
            }
        }
    }
    best.1
}

/// Compares with the committed golden image; `BSPCSG_BLESS=1` rewrites it instead.
fn golden(name: &str, img: &Image) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/golden/{name}.png"));
    if std::env::var_os("BSPCSG_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        img.write_png(&path).unwrap();
        return;
    }
    let want = Rgb8::read_png(&path).unwrap();
    let (mean, max) = img.to_rgb8().difference(&want).expect("same size");
    // Float noise moves a value by a step or flips a rare silhouette pixel; a changed
    // light, material, shape or camera moves thousands of pixels by much more.
    assert!(
        mean <= 0.5 && max <= 96,
        "{name}: mean {mean:.3}, max {max} (rewrite with BSPCSG_BLESS=1 if the change is meant)"
    );
}

#[test]
fn example_scenes_match_their_golden_images() {
    for name in [
        "mechanical_part",
        "organic_blend",
        "extruded_profile",
        "turned_and_twisted",
    ] {
        let scene = example(name);
        let cam = Camera::for_scene(&scene, View::Iso, (128, 96)).unwrap();
        let opts = RenderOptions::with_profile(scene.render_profile().clone());
        golden(name, &render_scene(&scene, &cam, &opts).unwrap());
    }
}

#[test]
fn a_mesh_matches_its_golden_image() {
    let scene = example("mechanical_part");
    let mesh = bspcsg_mesh(&scene);
    let cam = Camera::framing(&mesh.bbox(), View::Iso, (128, 96)).unwrap();
    let opts = RenderOptions::with_profile(scene.render_profile().clone());
    golden(
        "mechanical_part_mesh",
        &render_mesh(&mesh, scene.materials(), &cam, &opts).unwrap(),
    );
    let flat = RenderOptions {
        shading: Shading::Flat,
        ..opts
    };
    let front = Camera::framing(&mesh.bbox(), View::Front, (128, 96)).unwrap();
    golden(
        "mechanical_part_mesh_front_flat",
        &render_mesh(&mesh, scene.materials(), &front, &flat).unwrap(),
    );
}

#[test]
fn golden_comparison_notices_a_real_change() {
    let scene = example("mechanical_part");
    let cam = Camera::for_scene(&scene, View::Iso, (128, 96)).unwrap();
    let opts = RenderOptions::with_profile(scene.render_profile().clone());
    let a = render_scene(&scene, &cam, &opts).unwrap().to_rgb8();
    // The same scene without its mounting holes.
    let text = std::fs::read_to_string(scenes_dir().join("mechanical_part.json")).unwrap();
    let holes = text.find("\"pos\": [1.5, 0, 1.0]").unwrap();
    let edited = text.replacen("\"pos\": [1.5, 0, 1.0]", "\"pos\": [1.5, 9, 1.0]", 1);
    assert!(holes > 0);
    let b = render_scene(&Scene::from_json_str(&edited).unwrap(), &cam, &opts)
        .unwrap()
        .to_rgb8();
    let (_, max) = a.difference(&b).unwrap();
    assert!(max > 96, "a filled hole changes pixels by {max}");
    // A moved light changes the mean.
    let moved = RenderOptions {
        lights: vec![Light::directional(DVec3::new(-1.0, -0.2, 0.0), 1.0)],
        ..opts
    };
    let c = render_scene(&scene, &cam, &moved).unwrap().to_rgb8();
    assert!(a.difference(&c).unwrap().0 > 0.5);
}

#[test]
fn bad_render_input_is_refused() {
    let scene = Scene::from_json_str(SPHERE).unwrap();
    let opts = RenderOptions::default();
    for size in [(0, 10), (10, 0), (100_000, 100_000)] {
        let cam = Camera::look_at(DVec3::Z * 4.0, DVec3::ZERO, DVec3::Y, 40.0, size);
        assert!(render_scene(&scene, &cam, &opts).is_err(), "{size:?}");
    }
    let nan = Camera::look_at(
        DVec3::new(f64::NAN, 0.0, 4.0),
        DVec3::ZERO,
        DVec3::Y,
        40.0,
        (8, 8),
    );
    let err = render_scene(&scene, &nan, &opts).unwrap_err().to_string();
    assert!(err.contains("eye"), "{err}");
    let bad_light = RenderOptions {
        lights: vec![Light::directional(DVec3::ZERO, 1.0)],
        ..RenderOptions::default()
    };
    let cam = Camera::look_at(DVec3::Z * 4.0, DVec3::ZERO, DVec3::Y, 40.0, (8, 8));
    assert!(render_scene(&scene, &cam, &bad_light).is_err());
}

/// The envelope around a sphere with extra fields.
fn envelope(extra: &str) -> bspcsg::Result<Scene> {
    Scene::from_json_str(&format!(
        r#"{{"kind": "sdf_scene", {extra}
            "tree": {{"kind": "sdf_primitive", "data": {{"primitive_type": "sphere", "radius": 1}}}}}}"#
    ))
}

#[test]
fn camera_and_lights_are_read_from_the_envelope() {
    let s = envelope(
        r##""camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov_deg": 30},
           "lights": [{"type": "directional", "direction": [0, -1, 0], "intensity": 0.5},
                      {"type": "point", "position": [1, 2, 3], "color": "#ff8000"}],"##,
    )
    .unwrap();
    let c = s.camera().unwrap();
    assert_eq!(c.eye, DVec3::new(0.0, 0.0, 5.0));
    assert_eq!(c.up, DVec3::Y);
    assert_eq!(c.projection, Projection::Perspective { fov_deg: 30.0 });
    let l = s.lights().unwrap();
    assert_eq!(l.len(), 2);
    assert_eq!(l[0].intensity, 0.5);
    assert_eq!(
        l[1].kind,
        LightKind::Point {
            position: DVec3::new(1.0, 2.0, 3.0)
        }
    );
    assert_eq!(l[1].color.x, 1.0);
    assert!(
        l[1].color.y > 0.2 && l[1].color.y < 0.25,
        "sRGB hex decodes to linear"
    );
    let o = envelope(r#""camera": {"eye": [5, 0, 0], "target": [0, 0, 0], "projection": "orthographic", "height": 3},"#)
        .unwrap();
    assert_eq!(
        o.camera().unwrap().projection,
        Projection::Orthographic { height: 3.0 }
    );
    // None given: none reported; an empty list is "no lights".
    let plain = envelope("").unwrap();
    assert!(plain.camera().is_none() && plain.lights().is_none());
    assert_eq!(
        envelope(r#""lights": [],"#).unwrap().lights(),
        Some(&[][..])
    );
    // The render options follow the document.
    let opts = RenderOptions::for_scene(&s);
    assert_eq!(opts.lights.len(), 2);
    assert_eq!(
        RenderOptions::for_scene(&plain).lights,
        Light::default_rig()
    );
}

#[test]
fn camera_and_light_faults_name_their_json_path() {
    let cases = [
        (r#""camera": {"eye": [0, 0, 5]},"#, "$.camera.target"),
        (
            r#""camera": {"eye": [0, 0, 5], "target": [0, 0, 5]},"#,
            "$.camera.target",
        ),
        (
            r#""camera": {"eye": [0, 5, 0], "target": [0, 0, 0]},"#,
            "$.camera.up",
        ),
        (
            r#""camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov_deg": 180},"#,
            "$.camera.fov_deg",
        ),
        (
            r#""camera": {"eye": [0, 0, "x"], "target": [0, 0, 0]},"#,
            "$.camera.eye[2]",
        ),
        (
            r#""camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "fov": 30},"#,
            "$.camera.fov",
        ),
        (
            r#""camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "projection": "orthographic"},"#,
            "$.camera.height",
        ),
        (
            r#""camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "projection": "fisheye"},"#,
            "$.camera.projection",
        ),
        (r#""lights": {"type": "point"},"#, "$.lights"),
        (
            r#""lights": [{"type": "spot", "position": [0, 0, 0]}],"#,
            "$.lights[0].type",
        ),
        (
            r#""lights": [{"type": "directional", "direction": [0, 0, 0]}],"#,
            "$.lights[0].direction",
        ),
        (r#""lights": [{"type": "point"}],"#, "$.lights[0].position"),
        (
            r#""lights": [{"type": "point", "position": [0, 0, 0], "intensity": -1}],"#,
            "$.lights[0].intensity",
        ),
        (
            r#""lights": [{"type": "point", "position": [0, 0, 0], "color": [1, 2]}],"#,
            "$.lights[0].color",
        ),
        (
            r#""lights": [{"type": "directional", "position": [0, 0, 0]}],"#,
            "$.lights[0].position",
        ),
    ];
    for (extra, path) in cases {
        let err = envelope(extra).unwrap_err().to_string();
        assert!(err.starts_with(&format!("{path}:")), "{extra} → {err}");
    }
}
