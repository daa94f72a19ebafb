//! `render`: a scene (ray marched, or one of its meshes ray cast) or a mesh file to PNG.

use std::path::{Path, PathBuf};
use std::time::Instant;

use bspcsg::glam::DVec3;
use bspcsg::raymarch::{
    Camera, MeshBvh, RenderOptions, Shading, View, framing_bounds, render_mesh_with_progress,
    render_scene_with_progress,
};
use bspcsg::{Error, Mesh, Scene, read_mesh};

use crate::cli::{RenderArgs, RenderVia, Via, ViewArg};
use crate::export::scene_mesh;
use crate::failure::Failure;
use crate::output::{make_parents, print_stderr, remove_dirs};
use crate::progress::Progress;

/// What is drawn: the distance field, or a mesh with its materials.
enum Subject {
    Field(Box<Scene>),
    Mesh {
        mesh: Mesh,
        bvh: Box<MeshBvh>,
        scene: Option<Box<Scene>>,
    },
}

/// `render`.
pub(crate) fn render(args: &RenderArgs, progress: &Progress) -> Result<(), Failure> {
    check_png(&args.output)?;
    let input = &args.input;
    let named = |e: Error| -> Failure {
        match e {
            Error::Io { .. } | Error::Scene { .. } | Error::Parse { .. } => e.into(),
            other => {
                let mut f = Failure::from(other);
                f.message = format!("{}: {}", input.display(), f.message);
                f
            }
        }
    };
    progress.step(format!("reading {}", input.display()));
    let is_scene = input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let subject = if is_scene {
        let scene = Scene::from_path(input).map_err(named)?;
        match args.via {
            RenderVia::Sdf => Subject::Field(Box::new(scene)),
            via => {
                let route = if via == RenderVia::Bsp {
                    Via::Bsp
                } else {
                    Via::Sdf
                };
                let (mesh, _) = scene_mesh(&scene, route, None, None, progress).map_err(named)?;
                progress.step("building the BVH");
                let bvh = Box::new(MeshBvh::build(&mesh));
                Subject::Mesh {
                    mesh,
                    bvh,
                    scene: Some(Box::new(scene)),
                }
            }
        }
    } else {
        if args.via != RenderVia::Sdf {
            return Err(Failure::usage_or_io(format!(
                "{}: --via applies to scene documents; a mesh file is rendered as it is",
                input.display()
            )));
        }
        let mesh = read_mesh(input)?;
        if mesh.is_empty() {
            return Err(Failure::usage_or_io(format!(
                "{}: holds no triangles: nothing to draw",
                input.display()
            )));
        }
        progress.step("building the BVH");
        let bvh = Box::new(MeshBvh::build(&mesh));
        Subject::Mesh {
            mesh,
            bvh,
            scene: None,
        }
    };
    // A scene's meshes are framed by the scene's solid, so every route gets the same picture.
    let (scene, bounds) = match &subject {
        Subject::Field(s) => (Some(&**s), framing_bounds(s)),
        Subject::Mesh { scene: Some(s), .. } => (Some(&**s), framing_bounds(s)),
        Subject::Mesh { bvh, .. } => (None, bvh.bounds()),
    };
    let camera = camera(args, scene, &bounds).map_err(named)?;
    let mut opts = scene.map_or_else(RenderOptions::default, RenderOptions::for_scene);
    if args.flat {
        opts.shading = Shading::Flat;
    }
    let frames: Vec<(Camera, PathBuf)> = match args.turntable {
        None => vec![(camera, args.output.clone())],
        Some(n) => (0..n)
            .map(|i| {
                let angle = std::f64::consts::TAU * i as f64 / n as f64;
                let (s, c) = angle.sin_cos();
                let r = camera.eye - camera.target;
                let eye = camera.target + DVec3::new(c * r.x + s * r.z, r.y, -s * r.x + c * r.z);
                (Camera { eye, ..camera }, frame_path(&args.output, i, n))
            })
            .collect(),
    };
    let made = make_parents(&args.output)?;
    let start = Instant::now();
    for (k, (cam, out)) in frames.iter().enumerate() {
        let prefix = if frames.len() > 1 {
            format!("frame {}/{}: ", k + 1, frames.len())
        } else {
            String::new()
        };
        let report = |done: usize, total: usize| {
            progress.step(format!("{prefix}rendering: {done}/{total} tiles"));
        };
        let image = match &subject {
            Subject::Field(scene) => render_scene_with_progress(scene, cam, &opts, &report),
            Subject::Mesh {
                mesh, bvh, scene, ..
            } => {
                let materials = scene.as_ref().map_or(&[][..], |s| s.materials());
                render_mesh_with_progress(mesh, bvh, materials, cam, &opts, &report)
            }
        };
        let written = image.map_err(named).and_then(|img| {
            progress.step(format!("writing {}", out.display()));
            img.write_png(out).map_err(Failure::from)
        });
        if let Err(e) = written {
            // Frames already written stay: each is complete.
            if k == 0 {
                remove_dirs(&made);
            }
            return Err(e);
        }
    }
    progress.finish();
    if !progress.quiet {
        let what = match frames.len() {
            1 => args.output.display().to_string(),
            n => format!("{n} frames {} …", frames[0].1.display()),
        };
        print_stderr(&format!(
            "wrote {what} ({}x{}) in {:.2} s",
            camera.width,
            camera.height,
            start.elapsed().as_secs_f64()
        ));
    }
    Ok(())
}

/// The output must be a PNG whose directory can exist.
fn check_png(out: &Path) -> Result<(), Failure> {
    let refuse = |why: &str| {
        Failure::usage_or_io(format!("{}: cannot write the image: {why}", out.display()))
    };
    if !out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        return Err(refuse("images are written as PNG; name the output *.png"));
    }
    if out.is_dir() {
        return Err(refuse("it is a directory"));
    }
    let existing = out
        .ancestors()
        .skip(1)
        .find(|d| d.as_os_str().is_empty() || d.exists());
    if existing.is_some_and(|d| !d.as_os_str().is_empty() && !d.is_dir()) {
        return Err(refuse("a parent is not a directory"));
    }
    Ok(())
}

/// `OUT.png` → `OUT-007.png` (as many digits as the count needs, at least three).
fn frame_path(out: &Path, i: u32, n: u32) -> PathBuf {
    let stem = out.file_stem().map(|s| s.to_string_lossy().into_owned());
    let digits = n.saturating_sub(1).to_string().len().max(3);
    out.with_file_name(format!(
        "{}-{i:0digits$}.png",
        stem.unwrap_or_else(|| "frame".into())
    ))
}

/// --eye/--target, else the scene's camera (unless --view is given), else the default framing.
fn camera(
    args: &RenderArgs,
    scene: Option<&Scene>,
    bounds: &bspcsg::Aabb,
) -> Result<Camera, Error> {
    let view = match args.view {
        None | Some(ViewArg::Iso) => View::Iso,
        Some(ViewArg::Front) => View::Front,
        Some(ViewArg::Side) => View::Side,
        Some(ViewArg::Top) => View::Top,
    };
    if let Some(eye) = args.eye {
        let target = match args.target {
            Some(t) => DVec3::from_array(t),
            None if bounds.min.is_finite() && bounds.max.is_finite() && !bounds.is_empty() => {
                bounds.center()
            }
            None => DVec3::ZERO,
        };
        let cam = Camera::look_at(DVec3::from_array(eye), target, DVec3::Y, 40.0, args.size);
        cam.validate()?;
        return Ok(cam);
    }
    match scene.and_then(Scene::camera) {
        Some(c) if args.view.is_none() => {
            let cam = Camera::from_scene(c, args.size);
            cam.validate()?;
            Ok(cam)
        }
        _ => Camera::framing(bounds, view, args.size),
    }
}
