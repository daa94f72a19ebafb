//! `check`: does a mesh (a file, or the scene's own export) agree with the scene's SDF?

use std::fmt::Write as _;

use bspcsg::glam::DVec3;
use bspcsg::raymarch::{CheckOptions, CheckReport, DistanceStats, check_mesh};
use bspcsg::{Error, Scene, read_mesh};

use crate::cli::{CheckArgs, Via};
use crate::export::scene_mesh;
use crate::failure::Failure;
use crate::output::{make_parents, print_stdout, remove_dirs};
use crate::progress::Progress;

/// Exit code of a check that ran and found the mesh disagreeing.
const DISAGREES: u8 = 3;

/// `check`.
pub(crate) fn check(args: &CheckArgs, progress: &Progress) -> Result<(), Failure> {
    if let Some(img) = &args.image
        && !img
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        return Err(Failure::usage_or_io(format!(
            "{}: the difference image is written as PNG; name it *.png",
            img.display()
        )));
    }
    let in_scene = |e: Error| match e {
        Error::Io { .. } | Error::Scene { .. } | Error::Parse { .. } => Failure::from(e),
        other => {
            let mut f = Failure::from(other);
            f.message = format!("{}: {}", args.scene.display(), f.message);
            f
        }
    };
    progress.step(format!("reading {}", args.scene.display()));
    let scene = Scene::from_path(&args.scene).map_err(in_scene)?;
    let diagonal = scene.bbox().diagonal();
    let (mesh, what, tolerance) = match &args.mesh {
        Some(path) => {
            progress.step(format!("reading {}", path.display()));
            let mesh = read_mesh(path)?;
            if mesh.is_empty() {
                return Err(Failure {
                    message: format!(
                        "{}: holds no triangles: nothing to compare with the scene",
                        path.display()
                    ),
                    code: 2,
                });
            }
            (mesh, path.display().to_string(), None)
        }
        None => {
            let (mesh, _) = scene_mesh(&scene, args.via, None, None, progress).map_err(in_scene)?;
            // The route's own accuracy: the chordal tolerance (twice it: smooth blends are
            // baked at four times it) or the marching-cubes cell, at their defaults.
            let t = match args.via {
                Via::Bsp => 2.0 * diagonal / 500.0,
                Via::Sdf => scene.bbox().size().max_element() / 128.0,
            };
            let route = if args.via == Via::Bsp { "bsp" } else { "sdf" };
            (mesh, format!("its {route} export"), Some(t))
        }
    };
    let options = CheckOptions {
        tolerance: args.tolerance.or(tolerance),
        ray_size: args.rays,
        diff_image: args.image.is_some(),
        ..CheckOptions::default()
    };
    progress.step(format!("checking {} triangles", mesh.triangle_count()));
    let report = check_mesh(&scene, &mesh, &options).map_err(in_scene)?;
    if let (Some(path), Some(img)) = (&args.image, &report.diff_image) {
        progress.step(format!("writing {}", path.display()));
        let made = make_parents(path)?;
        if let Err(e) = img.write_png(path) {
            remove_dirs(&made);
            return Err(e.into());
        }
    }
    progress.finish();
    let text = if args.json {
        json(&report)
    } else {
        text(
            &report,
            &args.scene.display().to_string(),
            &what,
            mesh.triangle_count(),
        )
    };
    print_stdout(&text)?;
    if report.passed() {
        Ok(())
    } else {
        Err(Failure {
            message: format!(
                "{} disagrees with {}: {}",
                what,
                args.scene.display(),
                report.failures.join("; ")
            ),
            code: DISAGREES,
        })
    }
}

fn json(r: &CheckReport) -> String {
    let v = |p: DVec3| [p.x, p.y, p.z];
    let stats = |s: &DistanceStats| {
        serde_json::json!({
            "samples": s.samples, "max": s.max, "p99": s.p99, "mean": s.mean, "worst": v(s.worst),
        })
    };
    let t = &r.thresholds;
    let value = serde_json::json!({
        "passed": r.passed(),
        "tolerance": r.tolerance,
        "diagonal": r.diagonal,
        "thresholds": {
            "surface_max": t.surface_max,
            "surface_p99": t.surface_p99,
            "coverage_max": t.coverage_max,
            "ray_agreement_pct": t.ray_agreement_pct,
            "depth_p99": t.depth_p99,
            "sign_pct": t.sign_pct,
            "sign_band": t.sign_band,
        },
        "surface": stats(&r.surface),
        "coverage": stats(&r.coverage),
        "rays": {
            "rays": r.rays.rays,
            "agreement_pct": r.rays.agreement_pct,
            "depth_p99": r.rays.depth_p99,
            "depth_max": r.rays.depth_max,
            "worst": r.rays.worst.map(v),
        },
        "sign": {
            "samples": r.sign.samples,
            "agreement_pct": r.sign.agreement_pct,
            "worst": r.sign.worst.map(v),
        },
        "failures": r.failures,
    });
    // A `Value` of plain numbers, strings and arrays always serializes.
    let mut s = serde_json::to_string_pretty(&value).unwrap_or_default();
    s.push('\n');
    s
}

fn text(r: &CheckReport, scene: &str, what: &str, triangles: usize) -> String {
    let t = &r.thresholds;
    let ok = |pass: bool| if pass { "ok" } else { "FAIL" };
    let pct = |x: f64| 100.0 * x / r.diagonal;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "check {scene} against {what} ({triangles} triangles)\ntolerance {:.5} ({:.3} % of the bounding diagonal {:.4})",
        r.tolerance,
        pct(r.tolerance),
        r.diagonal
    );
    let _ = writeln!(
        s,
        "  surface distance  max {:.5} ({:.3} %)  p99 {:.5}  mean {:.5}  over {} points   limit {:.5}  {}",
        r.surface.max,
        pct(r.surface.max),
        r.surface.p99,
        r.surface.mean,
        r.surface.samples,
        t.surface_max,
        ok(r.surface.max <= t.surface_max && r.surface.p99 <= t.surface_p99)
    );
    let _ = writeln!(
        s,
        "  coverage          max {:.5} ({:.3} %)  p99 {:.5}  over {} surface points   limit {:.5}  {}",
        r.coverage.max,
        pct(r.coverage.max),
        r.coverage.p99,
        r.coverage.samples,
        t.coverage_max,
        ok(r.coverage.max <= t.coverage_max)
    );
    let _ = writeln!(
        s,
        "  rays              {:.3} % agree over {} rays; depth p99 {:.5}, max {:.5}   limits {} %, {:.5}  {}",
        r.rays.agreement_pct,
        r.rays.rays,
        r.rays.depth_p99,
        r.rays.depth_max,
        t.ray_agreement_pct,
        t.depth_p99,
        ok(r.rays.agreement_pct >= t.ray_agreement_pct && r.rays.depth_p99 <= t.depth_p99)
    );
    let _ = writeln!(
        s,
        "  sign              {:.3} % agree over {} points {:.5}+ from the surface   limit {} %  {}",
        r.sign.agreement_pct,
        r.sign.samples,
        t.sign_band,
        t.sign_pct,
        ok(r.sign.samples == 0 || r.sign.agreement_pct >= t.sign_pct)
    );
    let _ = writeln!(s, "{}", if r.passed() { "PASS" } else { "FAIL" });
    for f in &r.failures {
        let _ = writeln!(s, "  {f}");
    }
    s
}
