//! Small generated inputs for the hostile-input tests (a glTF tetrahedron and its buffer,
//! boxes as files, points as flat triangles) and the right-or-refused check.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

use bspcsg::MeshReport;

use super::run::Run;
use super::{box_obj_text, obj_box_mesh};

/// The promise for results the kernel may not resolve: either right (exit 0, the written mesh
/// a closed 2-manifold whose report passes `check`) or refused with exit 2 as not a closed
/// 2-manifold, nothing written. Never exit 0 with an open mesh.
pub fn right_or_refused(run: Run, out: &Path, what: &str, check: impl FnOnce(&MeshReport)) {
    if run.code == 0 {
        let report = bspcsg::read_mesh(out).unwrap().report();
        assert!(report.is_closed_manifold(), "{what}: {report}");
        check(&report);
    } else {
        run.code(2).says(&["not a closed 2-manifold"]);
        assert!(!out.exists(), "{what}: nothing is written");
    }
}

/// A unit tetrahedron as a glTF buffer: 4 float32 positions, then 12 u16 indices.
pub fn tetra_buffer() -> Vec<u8> {
    let mut b = Vec::new();
    for p in [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ] {
        for x in p {
            b.extend_from_slice(&x.to_le_bytes());
        }
    }
    for i in [0u16, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3] {
        b.extend_from_slice(&i.to_le_bytes());
    }
    b
}

/// glTF JSON: one tetrahedron mesh drawn by every node of `nodes`, its buffer at `uri`.
pub fn tetra_gltf(uri: &str, byte_length: u64, nodes: &str, scene_nodes: &str) -> String {
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": {scene_nodes}}}],
  "nodes": {nodes},
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [0, 0, 0], "max": [1, 1, 1]}},
    {{"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}}
  ],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 24}}
  ],
  "buffers": [{{"byteLength": {byte_length}, "uri": "{uri}"}}]
}}"#
    )
}

/// A closed box mesh written to `path` in the format its extension names.
pub fn box_file(path: &Path, min: f64) -> PathBuf {
    let m = obj_box_mesh(
        bspcsg::glam::DVec3::splat(min),
        bspcsg::glam::DVec3::splat(min + 1.0),
    );
    bspcsg::write_mesh(path, &m, &[]).unwrap();
    path.to_path_buf()
}

/// One OBJ of several boxes, `(min, max, cavity)`: a cavity's faces wind inward.
pub fn boxes_obj(boxes: &[([f64; 3], [f64; 3], bool)]) -> String {
    let mut text = String::new();
    for (k, &(min, max, cavity)) in boxes.iter().enumerate() {
        for line in box_obj_text(min, max).lines() {
            match line.strip_prefix("f ") {
                Some(f) => {
                    let mut idx: Vec<String> = f
                        .split_whitespace()
                        .map(|i| (i.parse::<usize>().unwrap() + 8 * k).to_string())
                        .collect();
                    if cavity {
                        idx.reverse();
                    }
                    text += &format!("f {}\n", idx.join(" "));
                }
                None => text += &format!("{line}\n"),
            }
        }
    }
    text
}

/// OBJ text of `points` as vertices, each three a triangle.
pub fn points_obj(points: &[[f64; 3]]) -> String {
    let mut s = String::with_capacity(points.len() * 60);
    for p in points {
        s += &format!("v {:?} {:?} {:?}\n", p[0], p[1], p[2]);
    }
    for k in (0..points.len() - 2).step_by(3) {
        s += &format!("f {} {} {}\n", k + 1, k + 2, k + 3);
    }
    s
}

/// The volume of `a` less `b` for two convex solids, computed apart from the kernel: `a`'s
/// faces clipped by each of `b`'s planes in turn (a capped convex polyhedron, its volume by the
/// divergence theorem), that taken from `a`'s volume. Exact to a few rounding errors of the
/// volumes (10⁻¹⁵ of them): a check on booleans whose answer is a film of slivers.
pub fn convex_difference_volume(a: &bspcsg::Solid, b: &bspcsg::Solid) -> f64 {
    use bspcsg::glam::DVec3;
    let volume = |faces: &[Vec<DVec3>]| -> f64 {
        let triples = faces
            .iter()
            .flat_map(|f| (1..f.len() - 1).map(move |k| f[0].dot(f[k].cross(f[k + 1]))));
        triples.sum::<f64>() / 6.0
    };
    // Each face with a ball around it: a face whose ball lies wholly inside a plane (by far
    // more than the rounding of a distance) is kept as it is, unclipped and not copied, which
    // is what clipping it would give (every vertex inside): a 256×128 sphere's 32,768 faces
    // against as many planes took minutes of allocation otherwise.
    let ball = |f: &[DVec3]| {
        let c = f.iter().copied().sum::<DVec3>() / f.len() as f64;
        let r = f.iter().map(|&x| (x - c).length()).fold(0.0, f64::max);
        (c, r)
    };
    let mut faces: Vec<(Vec<DVec3>, (DVec3, f64))> = a
        .polygons()
        .iter()
        .map(|p| (p.vertices().to_vec(), ball(p.vertices())))
        .collect();
    let whole = volume(&faces.iter().map(|f| f.0.clone()).collect::<Vec<_>>());
    for p in b.polygons() {
        let v = p.vertices();
        let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        let d = n.dot(v[0]);
        let mut cut = Vec::new();
        let mut kept = Vec::with_capacity(faces.len() + 1);
        for (f, (c, r)) in faces {
            if n.dot(c) - d + r < -1e-9 {
                kept.push((f, (c, r)));
                continue;
            }
            let mut piece = Vec::new();
            for i in 0..f.len() {
                let (x, y) = (f[i], f[(i + 1) % f.len()]);
                let (dx, dy) = (n.dot(x) - d, n.dot(y) - d);
                if dx <= 0.0 {
                    piece.push(x);
                }
                if dx == 0.0 {
                    cut.push(x);
                }
                if (dx < 0.0 && dy > 0.0) || (dx > 0.0 && dy < 0.0) {
                    let at = x + (y - x) * (dx / (dx - dy));
                    piece.push(at);
                    cut.push(at);
                }
            }
            if piece.len() >= 3 {
                let b = ball(&piece);
                kept.push((piece, b));
            }
        }
        if cut.len() >= 3 {
            // The cap, counter-clockwise about `n` (its outward normal).
            let c = cut.iter().copied().sum::<DVec3>() / cut.len() as f64;
            let u = (cut[0] - c).normalize();
            let w = n.cross(u);
            let angle = |q: &DVec3| (*q - c).dot(w).atan2((*q - c).dot(u));
            cut.sort_by(|x, y| angle(x).total_cmp(&angle(y)));
            let b = ball(&cut);
            kept.push((cut, b));
        }
        faces = kept;
    }
    whole - volume(&faces.into_iter().map(|f| f.0).collect::<Vec<_>>())
}
