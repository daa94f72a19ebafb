//! Wavefront OBJ: positions and faces in, positions, faces and materials (`.mtl`) out.
//!
//! Reading parses the text once: `v` lines give positions, `f` lines faces of position indices
//! (texture and normal indices are ignored, so UV and normal seams do not split vertices), and
//! every fault names its line. Positions are welded bit for bit in the order faces first use
//! them. Faces are triangulated here:
//!
//! - a triangle, or a face that is strictly convex about its Newell normal, is fanned from its
//!   first corner;
//! - any other face (a concave n-gon such as the L-shaped cap Blender writes, or a face with
//!   collinear corners) is triangulated by the crate's constrained Delaunay triangulation in
//!   the plane of its Newell normal, so concave faces keep their area;
//! - a face that is not a simple polygon in that plane (self-intersecting, or non-planar
//!   enough to fold over) is fanned from its first corner, as most readers do.

use std::collections::{BTreeMap, HashSet};
use std::fmt::Write as _;
use std::path::Path;

use glam::DVec3;

use super::triangles::Triangles;
use super::{Files, OutFile, generator, parse_error};
use crate::error::{Error, Result};
use crate::geom::Plane;
use crate::geom::triangulate::triangulate_boundary;
use crate::mesh::weld::Welder;
use crate::mesh::{Material, Mesh};

/// Reads OBJ text.
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<Mesh> {
    let parsed = Parsed::read(path, bytes)?;
    // Weld in the order faces first use positions; unused positions are dropped.
    let mut welder = Welder::with_capacity(parsed.positions.len());
    let mut id = vec![u32::MAX; parsed.positions.len()];
    let mut triangles = Triangles::with_capacity(parsed.indices.len());
    let mut face: Vec<u32> = Vec::new();
    let mut sorted: Vec<u32> = Vec::new();
    for range in &parsed.faces {
        face.clear();
        let raw = &parsed.indices[range.clone()];
        for &i in raw {
            let slot = &mut id[i as usize];
            if *slot == u32::MAX {
                *slot = welder.index(parsed.positions[i as usize]);
            }
            face.push(*slot);
        }
        // Whether the face names distinct vertices: a repeat after welding is then theirs
        // coinciding, not an index repeated (see `Triangles`).
        sorted.clear();
        sorted.extend_from_slice(raw);
        sorted.sort_unstable();
        let distinct = sorted.windows(2).all(|w| w[0] != w[1]);
        triangulate_face(&welder.positions, &face, distinct, &mut triangles);
    }
    triangles.into_mesh(path, welder.positions)
}

/// Appends the triangles of one face (welded vertex ids); `out` drops those that repeat a
/// vertex. `distinct`: the file named distinct vertices for the face's corners.
fn triangulate_face(positions: &[DVec3], face: &[u32], distinct: bool, out: &mut Triangles) {
    let mut push = |t: [u32; 3]| out.push(t, distinct);
    let fan = |push: &mut dyn FnMut([u32; 3])| {
        for k in 1..face.len() - 1 {
            push([face[0], face[k], face[k + 1]]);
        }
    };
    if face.len() == 3 {
        fan(&mut push);
        return;
    }
    let points: Vec<DVec3> = face.iter().map(|&i| positions[i as usize]).collect();
    let Some(plane) = Plane::from_points(&points) else {
        fan(&mut push);
        return;
    };
    if strictly_convex(&points, plane.normal) {
        fan(&mut push);
        return;
    }
    let n = face.len() as u32;
    let edges: Vec<(u32, u32)> = (0..n).map(|k| (k, (k + 1) % n)).collect();
    match triangulate_boundary(&points, plane.normal, &edges) {
        Some(tris) if !tris.is_empty() => {
            for t in tris {
                push(t.map(|k| face[k as usize]));
            }
        }
        _ => fan(&mut push),
    }
}

/// Every corner turns left about `normal`: fanning from any corner covers the face exactly.
fn strictly_convex(points: &[DVec3], normal: DVec3) -> bool {
    let n = points.len();
    (0..n).all(|i| {
        let (a, b, c) = (points[i], points[(i + 1) % n], points[(i + 2) % n]);
        (b - a).cross(c - b).dot(normal) > 0.0
    })
}

/// The statements of OBJ and its free-form geometry: any other first word on a line (outside a
/// comment) says the file is something else.
const STATEMENTS: [&str; 36] = [
    "v",
    "vt",
    "vn",
    "vp",
    "f",
    "fo",
    "l",
    "p",
    "g",
    "o",
    "s",
    "mg",
    "mtllib",
    "usemtl",
    "maplib",
    "usemap",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "bevel",
    "c_interp",
    "d_interp",
    "lod",
    "shadow_obj",
    "trace_obj",
];

/// The positions and faces of an OBJ file, indices absolute and 0-based.
struct Parsed {
    positions: Vec<DVec3>,
    /// Every face's position indices, one after another.
    indices: Vec<u32>,
    /// Each face's range in `indices`.
    faces: Vec<std::ops::Range<usize>>,
}

impl Parsed {
    /// Parses and checks the `v` and `f` lines; other lines are ignored.
    fn read(path: &Path, bytes: &[u8]) -> Result<Parsed> {
        let mut parsed = Parsed {
            positions: Vec::new(),
            indices: Vec::new(),
            faces: Vec::new(),
        };
        // Positive indices past the vertices read so far: allowed if the file defines them later.
        let mut forward: Vec<(usize, i64)> = Vec::new();
        // The first line that is not OBJ, which tells a file of no faces from another file.
        let mut stranger: Option<(usize, String)> = None;
        // A UTF-8 byte-order mark (some Windows editors write one) is no part of the first
        // line: left in, it hid the first `v` and shifted every index after it.
        let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
        for (n, raw) in bytes.split(|&b| b == b'\n').enumerate() {
            let line_no = n + 1;
            let err = |message: String| parse_error(path, Some(line_no), message);
            // Comments and names may be in any encoding; only `v` and `f` lines must be ASCII.
            let line = String::from_utf8_lossy(raw);
            // A `#` starts a comment, also after data (`v 1 2 3 # corner`).
            let data = line.split_once('#').map_or(&*line, |(d, _)| d);
            let mut words = data.split_whitespace();
            match words.next() {
                Some("v") => parsed.positions.push(vertex(words, &err)?),
                Some("f") => {
                    let start = parsed.indices.len();
                    for w in words {
                        let i = parsed.face_index(w, &err)?;
                        if i as u64 >= parsed.positions.len() as u64 {
                            forward.push((line_no, i + 1));
                        }
                        // Beyond u32 only as a forward reference, refused below.
                        parsed.indices.push(u32::try_from(i).unwrap_or(u32::MAX));
                    }
                    let corners = parsed.indices.len() - start;
                    if corners < 3 {
                        return Err(err(format!(
                            "face has {corners} vertices, needs at least 3"
                        )));
                    }
                    parsed.faces.push(start..parsed.indices.len());
                }
                // Texture coordinates, normals, groups, materials, lines, points, comments …
                Some(word) if stranger.is_none() && !STATEMENTS.contains(&word) => {
                    stranger = Some((line_no, word.chars().take(16).collect::<String>()));
                }
                _ => {}
            }
        }
        let vertices = parsed.positions.len();
        if let Some(&(line, i)) = forward.iter().find(|&&(_, i)| i as u64 > vertices as u64) {
            return Err(parse_error(
                path,
                Some(line),
                format!("vertex index {i} is out of range: the file has {vertices} vertices"),
            ));
        }
        // No faces: the empty mesh (as written for an empty result) when the file is OBJ and
        // nothing else; vertices alone are points or lines, and stray words are another file.
        if parsed.faces.is_empty() {
            if vertices > 0 {
                return Err(parse_error(
                    path,
                    None,
                    format!(
                        "the file holds {vertices} vert{} but no faces: points, not a surface",
                        if vertices == 1 { "ex" } else { "ices" }
                    ),
                ));
            }
            if let Some((line, word)) = stranger {
                return Err(parse_error(
                    path,
                    Some(line),
                    format!("the file holds no faces, and `{word}` is not an OBJ statement"),
                ));
            }
        }
        Ok(parsed)
    }

    /// The 0-based position index of a face corner `v`, `v/vt`, `v//vn` or `v/vt/vn` (only the
    /// position matters here); relative indices count back from the vertices read so far.
    fn face_index(&self, w: &str, err: &dyn Fn(String) -> Error) -> Result<i64> {
        let v = w.split('/').next().unwrap_or(w);
        let i: i64 = v
            .parse()
            .map_err(|_| err(format!("face vertex `{w}` is not an index")))?;
        let vertices = self.positions.len() as i64;
        if i > 0 {
            Ok(i - 1)
        } else if i < 0 {
            let abs = vertices + i + 1;
            if abs < 1 {
                return Err(err(format!(
                    "relative vertex index {i} reaches before the first vertex ({vertices} \
                     vertices precede this line)"
                )));
            }
            Ok(abs - 1)
        } else {
            Err(err(
                "vertex index 0 in a face: OBJ indices start at 1".into()
            ))
        }
    }
}

/// A `v` line's position: `x y z`, `x y z w` (divided by `w`) or `x y z r g b` (colours are
/// ignored); finite.
fn vertex<'a>(
    words: impl Iterator<Item = &'a str>,
    err: &dyn Fn(String) -> Error,
) -> Result<DVec3> {
    let mut c = [0.0f64; 4];
    let mut count = 0;
    for w in words {
        let x: f64 = w
            .parse()
            .map_err(|_| err(format!("vertex coordinate `{w}` is not a number")))?;
        if count < 4 {
            c[count] = x;
        }
        count += 1;
    }
    if count < 3 {
        return Err(err(format!(
            "vertex has {count} coordinates, needs 3 (x y z)"
        )));
    }
    let mut p = DVec3::new(c[0], c[1], c[2]);
    // Exactly four numbers are x y z w; six are x y z r g b (colours are ignored).
    if count == 4 {
        let w = c[3];
        if w == 0.0 || !w.is_finite() {
            return Err(err(format!("vertex weight w = {w} is not usable")));
        }
        p /= w;
    }
    if !p.is_finite() {
        return Err(err(format!(
            "vertex coordinates ({}, {}, {}) are not all finite",
            p.x, p.y, p.z
        )));
    }
    Ok(p)
}

/// Writes OBJ text, and a sibling `.mtl` when `materials` is not empty.
pub(crate) fn write(path: &Path, mesh: &Mesh, materials: &[Material]) -> Files {
    let mut obj = String::with_capacity(32 * mesh.positions.len() + 24 * mesh.triangles.len());
    let _ = writeln!(obj, "# {}", generator());
    let _ = writeln!(
        obj,
        "# {} vertices, {} triangles",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    let mtl_path = path.with_extension("mtl");
    let with_materials = !materials.is_empty();
    if with_materials && let Some(name) = mtl_path.file_name() {
        let _ = writeln!(obj, "mtllib {}", name.to_string_lossy());
    }
    for p in &mesh.positions {
        // `{}` is the shortest representation that parses back to the same f64.
        let _ = writeln!(obj, "v {} {} {}", p.x, p.y, p.z);
    }
    let face = |obj: &mut String, t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| u64::from(i) + 1);
        let _ = writeln!(obj, "f {a} {b} {c}");
    };
    let mut companions = Vec::new();
    if with_materials {
        // One `usemtl` group per source id, in increasing order.
        let mut groups: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
        for (t, &s) in mesh.sources.iter().enumerate() {
            groups.entry(s).or_default().push(t);
        }
        let names = material_names(materials);
        let mut mtl = format!("# {}\n", generator());
        let mut default_written = false;
        for (&s, tris) in &groups {
            let name = match names.get(s as usize) {
                Some(n) => n.as_str(),
                None => {
                    if !default_written {
                        write_material(&mut mtl, Material::DEFAULT_NAME, Material::DEFAULT_COLOR);
                        default_written = true;
                    }
                    Material::DEFAULT_NAME
                }
            };
            let _ = writeln!(obj, "usemtl {name}");
            for &t in tris {
                face(&mut obj, &mesh.triangles[t]);
            }
        }
        for (name, m) in names.iter().zip(materials) {
            write_material(&mut mtl, name, m.base_color);
        }
        companions.push(OutFile {
            path: mtl_path,
            bytes: mtl.into_bytes(),
        });
    } else {
        for t in &mesh.triangles {
            face(&mut obj, t);
        }
    }
    Files {
        main: obj.into_bytes(),
        companions,
    }
}

fn write_material(mtl: &mut String, name: &str, c: [f64; 4]) {
    let _ = writeln!(
        mtl,
        "\nnewmtl {name}\nKd {} {} {}\nd {}",
        c[0], c[1], c[2], c[3]
    );
}

/// Material names usable in `newmtl` / `usemtl`: whitespace becomes `_` (the name ends at the
/// first space), empty names and names already taken (including the default's) get a
/// numbered one.
fn material_names(materials: &[Material]) -> Vec<String> {
    let mut taken: HashSet<String> = HashSet::new();
    taken.insert(Material::DEFAULT_NAME.to_owned());
    materials
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let clean: String = m
                .name
                .chars()
                .map(|c| if c.is_whitespace() { '_' } else { c })
                .collect();
            let mut name = if clean.is_empty() {
                format!("material_{i}")
            } else {
                clean
            };
            while !taken.insert(name.clone()) {
                name = format!("{name}_{i}");
            }
            name
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Mesh> {
        read(Path::new("t.obj"), text.as_bytes())
    }

    fn line_of(e: Error) -> Option<usize> {
        match e {
            Error::Parse { line, .. } => line,
            other => panic!("expected a parse error, got {other}"),
        }
    }

    #[test]
    fn quad_with_uv_seams_is_one_welded_quad() {
        let m = parse(
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\n\
             f 1/1/1 2/2/1 3/1/1 4/2/1\n",
        )
        .unwrap();
        assert_eq!(m.triangle_count(), 2);
        assert_eq!(m.vertex_count(), 4);
    }

    #[test]
    fn relative_indices_and_objects_merge() {
        let m =
            parse("o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\no b\nv 0 0 1\nf 1 2 -1\n").unwrap();
        assert_eq!(m.triangle_count(), 2);
        assert_eq!(m.vertex_count(), 4);
    }

    #[test]
    fn duplicate_positions_weld() {
        let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nf 1 2 3\nf 4 3 2\n").unwrap();
        assert_eq!(m.vertex_count(), 3);
        // The second face repeats the first's vertices in another order; both stay.
        assert_eq!(m.triangle_count(), 2);
    }

    #[test]
    fn trailing_comments() {
        let m = parse("v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nf 1 2 3 # the face\n").unwrap();
        assert_eq!(m.triangle_count(), 1);
    }

    #[test]
    fn weighted_vertex() {
        let m = parse("v 2 0 0 2\nv 0 1 0\nv 0 0 1\nf 1 2 3\n").unwrap();
        assert_eq!(m.positions[0], DVec3::X);
    }

    #[test]
    fn errors_name_the_line() {
        assert_eq!(line_of(parse("v 0 0 0\nv 1 nan 0\n").unwrap_err()), Some(2));
        assert_eq!(line_of(parse("v 0 0 0\nv 1 inf 0\n").unwrap_err()), Some(2));
        assert_eq!(line_of(parse("v 0 0 0\nv 1 x 0\n").unwrap_err()), Some(2));
        assert_eq!(line_of(parse("v 0 0\n").unwrap_err()), Some(1));
        assert_eq!(line_of(parse("v 1e400 0 0\n").unwrap_err()), Some(1));
        assert_eq!(line_of(parse("v 0 0 0\n\nf 1 2 3\n").unwrap_err()), Some(3));
        assert_eq!(line_of(parse("v 0 0 0\nf 1 -2 1\n").unwrap_err()), Some(2));
        assert_eq!(line_of(parse("v 0 0 0\nf 0 1 1\n").unwrap_err()), Some(2));
        assert_eq!(line_of(parse("v 0 0 0\nf 1 1\n").unwrap_err()), Some(2));
        assert_eq!(line_of(parse("v 0 0 0\nf 1 a 1\n").unwrap_err()), Some(2));
        assert_eq!(line_of(parse("v 0 0 0 0\n").unwrap_err()), Some(1));
        // Comments alone are the empty mesh; a line that is not OBJ is named.
        assert!(parse("# nothing\n").unwrap().is_empty());
        assert_eq!(line_of(parse("# a\nnothing\n").unwrap_err()), Some(2));
    }

    #[test]
    fn huge_relative_texture_indices_do_not_panic() {
        // Texture indices are never read, however far out of range.
        let m = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/-9 2/-9 3/-9223372036854775807\n")
            .unwrap();
        assert_eq!(m.triangle_count(), 1);
    }

    #[test]
    fn forward_references_are_allowed_if_defined_later() {
        let m = parse("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(m.triangle_count(), 1);
    }

    #[test]
    fn material_names_are_unique_and_spaceless() {
        let m = |n: &str| Material {
            name: n.into(),
            base_color: [1.0; 4],
        };
        let names = material_names(&[m("a b"), m("a_b"), m(""), m("default")]);
        assert_eq!(names, ["a_b", "a_b_1", "material_2", "default_3"]);
    }

    #[test]
    fn writes_materials_grouped_by_source() {
        let mesh = Mesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            triangles: vec![[0, 1, 2], [0, 2, 3], [0, 3, 1]],
            sources: vec![1, 0, 5],
        };
        let mats = [
            Material {
                name: "red".into(),
                base_color: [1.0, 0.0, 0.0, 1.0],
            },
            Material {
                name: "blue".into(),
                base_color: [0.0, 0.0, 1.0, 0.5],
            },
        ];
        let files = write(Path::new("dir/x.obj"), &mesh, &mats);
        let obj = String::from_utf8(files.main).unwrap();
        assert!(obj.contains("mtllib x.mtl\n"));
        let order: Vec<&str> = obj.lines().filter(|l| l.starts_with("usemtl")).collect();
        assert_eq!(order, ["usemtl red", "usemtl blue", "usemtl default"]);
        assert_eq!(files.companions.len(), 1);
        assert_eq!(files.companions[0].path, Path::new("dir/x.mtl"));
        let mtl = String::from_utf8(files.companions[0].bytes.clone()).unwrap();
        assert!(mtl.contains("newmtl blue\nKd 0 0 1\nd 0.5\n"));
        assert!(mtl.contains("newmtl default\nKd 0.8 0.8 0.8\nd 1\n"));
        let back = parse(&obj).unwrap();
        assert_eq!(back.triangle_count(), 3);
    }
}
