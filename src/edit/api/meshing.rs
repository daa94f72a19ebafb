//! Requests that mesh the scene and look at the result: `POST /api/check` (the mesh against
//! the scene's field) and `POST /api/mesh` (the mesh for the page's mesh view); the meshing and
//! the mesh report export shares.

use std::time::Instant;

use serde_json::{Map, Value, json};

use super::transport::{Answer, Response, field, from_error, number, request, via_sdf};
use crate::mesh::Mesh;
use crate::raymarch::{CheckOptions, CheckReport, check_mesh};
use crate::sdf::{BakeOptions, Scene, TessellationOptions};

/// The largest mesh the mesh view is sent (triangles); larger ones are reported, not drawn.
const MAX_VIEW_TRIANGLES: usize = 2_000_000;

/// The request's scene, meshed by its route, and the seconds that took. By the BSP route a
/// closed (or empty) mesh that bounds another volume than the scene's solid is an error, as on
/// the command line ([`crate::Solid::check_mesh_volume`]).
pub(super) fn scene_mesh(m: &Map<String, Value>) -> Answer<(Scene, Mesh, f64)> {
    let scene =
        Scene::from_json_value(field(m, "document")?).map_err(|e| from_error(e, "$.document"))?;
    let sdf = via_sdf(m)?;
    let (tolerance, cell) = (number(m, "tolerance")?, number(m, "cell")?);
    let start = Instant::now();
    let mesh = if sdf {
        scene.bake(&BakeOptions {
            cell,
            ..BakeOptions::default()
        })
    } else {
        scene
            .to_solid(&TessellationOptions {
                tolerance,
                cell,
                ..TessellationOptions::default()
            })
            .and_then(|solid| {
                let mesh = solid.to_mesh();
                if mesh.is_empty() || mesh.report().is_closed_manifold() {
                    solid.check_mesh_volume(&mesh)?;
                }
                Ok(mesh)
            })
    }
    .map_err(|e| from_error(e, "$.document"))?;
    Ok((scene, mesh, start.elapsed().as_secs_f64()))
}

/// The mesh's figures: counts, closedness, genus, volume, and the seconds it took.
pub(super) fn mesh_report(mesh: &Mesh, seconds: f64) -> Value {
    let r = mesh.report();
    json!({
        "triangles": r.triangles,
        "vertices": r.vertices,
        "closed_manifold": r.is_closed_manifold(),
        "boundary_edges": r.boundary_edges,
        "non_manifold_edges": r.non_manifold_edges,
        "degenerate_triangles": r.degenerate_triangles,
        "shells": r.shells.len(),
        "genus": r.genus,
        "volume": mesh.volume(),
        "area": mesh.area(),
        "seconds": seconds,
    })
}

/// `POST /api/check`: `{"document", "via"}`: the scene's own export checked against its
/// field, with the route's own tolerance, as `bspcsg check SCENE` does.
pub(super) fn check(body: &[u8]) -> Answer {
    let req = request(body, &["document", "via", "tolerance", "cell"])?;
    let (scene, mesh, seconds) = scene_mesh(&req)?;
    let b = scene.bbox();
    let tolerance = if via_sdf(&req)? {
        number(&req, "cell")?.unwrap_or(b.size().max_element() / 128.0)
    } else {
        2.0 * number(&req, "tolerance")?.unwrap_or(b.diagonal() / 500.0)
    };
    let opts = CheckOptions {
        tolerance: Some(tolerance),
        ..CheckOptions::default()
    };
    let start = Instant::now();
    let report = check_mesh(&scene, &mesh, &opts).map_err(|e| from_error(e, "$.document"))?;
    Ok(Response::json(
        200,
        &check_json(
            &report,
            mesh_report(&mesh, seconds),
            start.elapsed().as_secs_f64(),
        ),
    ))
}

fn check_json(r: &CheckReport, mesh: Value, seconds: f64) -> Value {
    let t = &r.thresholds;
    json!({
        "passed": r.passed(),
        "tolerance": r.tolerance,
        "diagonal": r.diagonal,
        "surface": { "max": r.surface.max, "p99": r.surface.p99, "mean": r.surface.mean,
                     "samples": r.surface.samples, "limit": t.surface_max },
        "coverage": { "max": r.coverage.max, "p99": r.coverage.p99,
                      "samples": r.coverage.samples, "limit": t.coverage_max },
        "rays": { "agreement_pct": r.rays.agreement_pct, "depth_p99": r.rays.depth_p99,
                  "rays": r.rays.rays, "limit_pct": t.ray_agreement_pct },
        "sign": { "agreement_pct": r.sign.agreement_pct, "samples": r.sign.samples,
                  "limit_pct": t.sign_pct },
        "failures": r.failures,
        "mesh": mesh,
        "seconds": seconds,
    })
}

/// `POST /api/mesh`: `{"document", "via", …}`: the mesh for the page's mesh view, as flat
/// position and index arrays, with its report.
pub(super) fn mesh_view(body: &[u8]) -> Answer {
    let req = request(body, &["document", "via", "tolerance", "cell"])?;
    let (_, mesh, seconds) = scene_mesh(&req)?;
    let report = mesh_report(&mesh, seconds);
    if mesh.triangle_count() > MAX_VIEW_TRIANGLES {
        return Ok(Response::json(
            200,
            &json!({ "report": report, "positions": [], "triangles": [], "too_large": true }),
        ));
    }
    let positions: Vec<f32> = mesh
        .positions
        .iter()
        .flat_map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect();
    let triangles: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    Ok(Response::json(
        200,
        &json!({ "report": report, "positions": positions, "triangles": triangles }),
    ))
}
