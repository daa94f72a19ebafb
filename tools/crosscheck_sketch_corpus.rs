//! Writes the corpus of the manifold3d `CrossSection` cross-check
//! (`tests/crosscheck/crosscheck_sketch.py`).
//!
//! ```text
//! cargo run --release --example crosscheck_sketch_corpus -- OUT_DIR
//! ```
//!
//! Each case is a 2D boolean of two shapes (rectangles, circles, regular and rounded polygons,
//! star polygons, a pentagram by the non-zero rule) in random rigid motions, or of two squares
//! whose edges coincide, overlap or touch at a corner: both operands'
//! rings, exactly as our sketches hold them, go into `OUT_DIR/manifest.json` with the operation
//! and what we measured — the result's area and validity, the volume of its extrusion (plain or
//! tapered), and of its revolution (moved to x > 0, full or partial turns). The checker builds
//! the same operands as manifold3d `CrossSection`s, runs the same boolean, extrudes and revolves
//! its own result, and compares.
//!
//! The random numbers come from a fixed-seed LCG, so the corpus is the same on every run.

use std::f64::consts::TAU;
use std::path::PathBuf;
use std::process::ExitCode;

use bspcsg::glam::DVec2;
use bspcsg::{BoolOp, ExtrudeOptions, FillRule, Sketch};
use serde_json::{Value, json};

/// A deterministic generator (Knuth's MMIX LCG, top 53 bits).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

const KINDS: [&str; 6] = [
    "rectangle",
    "circle",
    "regular_polygon",
    "rounded_rectangle",
    "star",
    "pentagram",
];

/// A shape of `kind` with random size about unit, and how it was made.
fn shape(kind: &str, rng: &mut Lcg) -> (Sketch, String) {
    let s = |rng: &mut Lcg| rng.range(0.4, 1.6);
    match kind {
        "rectangle" => {
            let (w, h) = (s(rng), s(rng));
            (
                Sketch::rectangle(w, h).unwrap(),
                format!("rectangle({w:.3}, {h:.3})"),
            )
        }
        "circle" => {
            let r = 0.5 * s(rng);
            let n = 12 + (rng.next() * 52.0) as u32;
            (
                Sketch::circle_with_segments(r, n).unwrap(),
                format!("circle({r:.3}, {n} segments)"),
            )
        }
        "regular_polygon" => {
            let n = 3 + (rng.next() * 9.0) as u32;
            let r = 0.6 * s(rng);
            (
                Sketch::regular_polygon(n, r).unwrap(),
                format!("regular_polygon({n}, {r:.3})"),
            )
        }
        "rounded_rectangle" => {
            let (w, h) = (s(rng), s(rng));
            let r = 0.45 * w.min(h) * rng.next();
            (
                Sketch::rounded_rectangle(w, h, r, 2e-3).unwrap(),
                format!("rounded_rectangle({w:.3}, {h:.3}, {r:.3})"),
            )
        }
        "star" => {
            let n = 5 + (rng.next() * 40.0) as usize;
            let pts: Vec<DVec2> = (0..n)
                .map(|i| DVec2::from_angle(TAU * i as f64 / n as f64) * rng.range(0.3, 0.9))
                .collect();
            (
                Sketch::polygon(&pts, FillRule::NonZero).unwrap(),
                format!("star polygon of {n} points"),
            )
        }
        _ => {
            let r = 0.7 * s(rng);
            let pts: Vec<DVec2> = (0..5)
                .map(|k| DVec2::from_angle(TAU * (2 * k) as f64 / 5.0) * r)
                .collect();
            (
                Sketch::polygon(&pts, FillRule::NonZero).unwrap(),
                format!("pentagram({r:.3}), non-zero"),
            )
        }
    }
}

fn placed(kind: &str, rng: &mut Lcg) -> (Sketch, String) {
    let (s, d) = shape(kind, rng);
    let angle = rng.range(0.0, 360.0);
    let at = DVec2::new(rng.range(-0.6, 0.6), rng.range(-0.6, 0.6));
    (
        s.rotate(angle).unwrap().translate(at).unwrap(),
        format!(
            "{d} rotated {angle:.1}° moved to ({:.3}, {:.3})",
            at.x, at.y
        ),
    )
}

fn rings(s: &Sketch) -> Value {
    json!(
        s.rings()
            .map(|r| r.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    )
}

fn main() -> ExitCode {
    let Some(out) = std::env::args().nth(1).map(PathBuf::from) else {
        eprintln!("usage: crosscheck_sketch_corpus OUT_DIR");
        return ExitCode::from(2);
    };
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("{}: {e}", out.display());
        return ExitCode::FAILURE;
    }
    let mut rng = Lcg(0x005e_ed2d);
    let ops = [
        (BoolOp::Union, "union"),
        (BoolOp::Intersection, "intersection"),
        (BoolOp::Difference, "difference"),
    ];
    let mut cases = Vec::new();
    let mut id = 0;
    for ka in KINDS {
        for kb in KINDS {
            for (op, name) in ops {
                let (a, da) = placed(ka, &mut rng);
                let (b, db) = placed(kb, &mut rng);
                let r = a.boolean(&b, op);
                let report = r.report();
                let mut case = json!({
                    "id": format!("sketch_{id:03}_{ka}_{name}_{kb}"),
                    "op": name,
                    "a": rings(&a),
                    "b": rings(&b),
                    "a_describe": da,
                    "b_describe": db,
                    "ours": {
                        "area": r.area(),
                        "valid": report.is_valid(),
                        "report": format!("{report:?}"),
                        "regions": r.regions().len(),
                    },
                });
                if !r.is_empty() {
                    // Extrusion: plain, or tapered (uniform, so the walls are planar in both).
                    let h = rng.range(0.3, 2.0);
                    let top = if id % 3 == 0 {
                        1.0
                    } else {
                        (id % 4) as f64 * 0.4
                    };
                    let solid = r
                        .extrude_with(
                            h,
                            &ExtrudeOptions {
                                scale_top: DVec2::splat(top),
                                ..Default::default()
                            },
                        )
                        .unwrap();
                    let mesh = solid.to_mesh();
                    case["extrude"] = json!({
                        "height": h, "scale_top": top, "volume": mesh.volume(),
                        "closed": mesh.report().is_closed_manifold(),
                    });
                    // Revolution of the result moved to x ≥ 0.1, full or a multiple of 90°.
                    let [lo, _] = r.bounds().unwrap();
                    let moved = r.translate(DVec2::new(0.1 - lo.x, 0.0)).unwrap();
                    let angle = [360.0, 90.0, 180.0, 270.0][id % 4];
                    let segments = 32;
                    let solid = moved.revolve(angle, segments).unwrap();
                    let mesh = solid.to_mesh();
                    // The steps our revolve takes: a partial turn takes its share of a full
                    // turn's segments (manifold3d takes its circular_segments over any angle).
                    let steps = if angle == 360.0 {
                        segments
                    } else {
                        (segments as f64 * angle / 360.0).ceil() as u32
                    };
                    case["revolve"] = json!({
                        "shift": 0.1 - lo.x, "angle": angle, "steps": steps,
                        "volume": mesh.volume(), "closed": mesh.report().is_closed_manifold(),
                    });
                }
                cases.push(case);
                id += 1;
            }
        }
    }
    // Aligned cases: edges that coincide, overlap or touch, corners that meet (dyadic
    // coordinates, exact in every representation).
    let unit = Sketch::rectangle(1.0, 1.0).unwrap();
    let offsets = [
        (0.5, 0.0),
        (1.0, 0.0),
        (1.0, 1.0),
        (0.25, 0.25),
        (0.0, 0.0),
        (0.5, 0.5),
    ];
    for (k, &(x, y)) in offsets.iter().enumerate() {
        let b = if k == 3 {
            Sketch::rectangle(0.5, 0.5).unwrap()
        } else {
            unit.clone()
        }
        .translate(DVec2::new(x, y))
        .unwrap();
        for (op, name) in ops {
            let r = unit.boolean(&b, op);
            let report = r.report();
            cases.push(json!({
                "id": format!("sketch_{id:03}_aligned_{name}_{x}_{y}"),
                "op": name,
                "a": rings(&unit),
                "b": rings(&b),
                "a_describe": "rectangle(1, 1)",
                "b_describe": format!("rectangle moved to ({x}, {y})"),
                "ours": {
                    "area": r.area(),
                    "valid": report.is_valid(),
                    "report": format!("{report:?}"),
                    "regions": r.regions().len(),
                },
            }));
            id += 1;
        }
    }
    let manifest = json!({
        "generator": concat!("bspcsg ", env!("CARGO_PKG_VERSION"), " examples/crosscheck_sketch_corpus.rs"),
        "cases": cases,
    });
    let path = out.join("manifest.json");
    let text = serde_json::to_string_pretty(&manifest).expect("JSON values serialize");
    if let Err(e) = std::fs::write(&path, text) {
        eprintln!("{}: {e}", path.display());
        return ExitCode::FAILURE;
    }
    eprintln!("{id} sketch cases written to {}", out.display());
    ExitCode::SUCCESS
}
