//! `info`: a mesh's measurements and validity report, as text or JSON.

use std::fmt::Write as _;

use bspcsg::{MAX_CROSSING_PAIRS, MeshReport, read_mesh};

use crate::cli::InfoArgs;
use crate::failure::Failure;
use crate::output::{print_stdout, warn_if_empty_input};
use crate::progress::Progress;

/// `info`.
pub(crate) fn info(args: &InfoArgs, progress: &Progress) -> Result<(), Failure> {
    progress.step(format!("reading {}", args.mesh.display()));
    let mesh = read_mesh(&args.mesh)?;
    warn_if_empty_input(&args.mesh, mesh.is_empty(), progress);
    progress.step("checking");
    let report = mesh.report();
    let area = mesh.area();
    let bbox = mesh.bbox();
    // `None` where the search gave up at its budget without finding a crossing.
    let crossing = mesh.crossing_triangle_pairs().ok().map(|p| p.len());
    progress.finish();
    let watertight = watertight(&report);
    let text = if args.json {
        let value = serde_json::json!({
            "triangles": report.triangles,
            "vertices": report.vertices,
            "volume": report.volume,
            "area": area,
            "bbox_min": bbox.min.to_array(),
            "bbox_max": bbox.max.to_array(),
            "watertight": watertight,
            "boundary_edges": report.boundary_edges,
            "nonmanifold_edges": report.non_manifold_edges,
            "degenerate_triangles": report.degenerate_triangles,
            "needles": report.needles,
            "crossing_triangle_pairs": crossing,
            "components": report.shells.len(),
            "genus": report.genus,
        });
        // A `Value` of plain numbers, strings and arrays always serializes.
        let mut s = serde_json::to_string_pretty(&value).unwrap_or_default();
        s.push('\n');
        s
    } else {
        let yes = |b: bool| if b { "yes" } else { "no" };
        let v = |p: bspcsg::glam::DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
        let mut s = String::new();
        let mut line = |k: &str, v: String| {
            let _ = writeln!(s, "{k:<31} {v}");
        };
        line("file", args.mesh.display().to_string());
        line("triangles", report.triangles.to_string());
        line("vertices", report.vertices.to_string());
        line("volume", report.volume.to_string());
        line("area", area.to_string());
        line("bbox min", v(bbox.min));
        line("bbox max", v(bbox.max));
        line("watertight", yes(watertight).to_owned());
        line("boundary edges", report.boundary_edges.to_string());
        line("non-manifold edges", report.non_manifold_edges.to_string());
        line(
            "inconsistently oriented edges",
            report.inconsistent_edges.to_string(),
        );
        line(
            "non-manifold vertices",
            report.non_manifold_vertices.to_string(),
        );
        line(
            "degenerate triangles",
            report.degenerate_triangles.to_string(),
        );
        line("needles", report.needles.to_string());
        line(
            "crossing triangle pairs",
            match crossing {
                Some(n) if n >= MAX_CROSSING_PAIRS => {
                    format!("{n} or more (the search stops there)")
                }
                Some(n) => n.to_string(),
                None => "not known: the search gave up at its budget (crowded triangles)".into(),
            },
        );
        line("components", report.shells.len().to_string());
        line("inside-out shells", report.inverted_shells.to_string());
        line(
            "genus",
            report
                .genus
                .map_or_else(|| "undefined".to_owned(), |g| g.to_string()),
        );
        line("closed 2-manifold", yes(report.is_closed_manifold()).into());
        // Closed and manifold is not yet a solid: shells that cross count space twice.
        line(
            "bounds a solid",
            match crossing {
                _ if !report.is_closed_manifold() || report.inverted_shells > 0 => "no".into(),
                Some(n) => yes(n == 0).into(),
                None => "not known (see crossing triangle pairs)".into(),
            },
        );
        s
    };
    print_stdout(&text)
}

/// Every edge used by exactly two triangles in opposite directions (the definition the shared
/// models' README and trimesh use).
pub(crate) fn watertight(report: &MeshReport) -> bool {
    report.boundary_edges == 0 && report.non_manifold_edges == 0 && report.inconsistent_edges == 0
}
