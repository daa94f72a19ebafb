//! STL: ASCII and binary in, binary out.
//!
//! Binary files are recognised by their size, `84 + 50 n` bytes for the `n` triangles their
//! header announces, not by a missing `solid` prefix: plenty of binary files start their
//! free-form header with "solid".

use std::path::Path;

use glam::{DVec3, Vec3};

use super::triangles::Triangles;
use super::{Files, parse_error};
use crate::error::{Error, MeshDefect, Result};
use crate::mesh::Mesh;
use crate::mesh::weld::Welder;

const HEADER: usize = 80;
const RECORD: usize = 50;

/// Reads ASCII or binary STL.
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<Mesh> {
    let announced = announced_triangles(bytes);
    if let Some(n) = announced
        && binary_size(n) == Some(bytes.len() as u64)
    {
        return read_binary(path, bytes, n as usize);
    }
    if bytes.trim_ascii_start().starts_with(b"solid") {
        let ascii = read_ascii(path, bytes);
        // Text has no NUL bytes; a binary file whose header starts with "solid" but whose size
        // is off lands here, and deserves to hear so rather than only about a strange line
        // (or, if its bytes happen to hold no newline, about having no triangles).
        let failed = !matches!(&ascii, Ok(m) if !m.is_empty());
        if let (true, Some(n), true) = (failed, announced, bytes.contains(&0)) {
            let why = match ascii {
                Err(Error::Parse { line, message, .. }) => format!(
                    " (read as ASCII, line {}: {message})",
                    line.unwrap_or_default()
                ),
                _ => String::new(),
            };
            return Err(parse_error(
                path,
                None,
                format!(
                    "damaged binary STL: its header announces {n} triangles, {} bytes, but the \
                     file has {} bytes{why}",
                    binary_size(n).unwrap_or(u64::MAX),
                    bytes.len()
                ),
            ));
        }
        return ascii;
    }
    match announced {
        Some(n) => Err(parse_error(
            path,
            None,
            format!(
                "binary STL header announces {n} triangles, which take {} bytes, but the file \
                 has {} bytes (truncated or not an STL file)",
                binary_size(n).unwrap_or(u64::MAX),
                bytes.len()
            ),
        )),
        None => Err(parse_error(
            path,
            None,
            format!(
                "not an STL file: {} bytes, too short for a binary STL and not starting \
                 with `solid`",
                bytes.len()
            ),
        )),
    }
}

/// The triangle count in a binary header, if the file is long enough to have one.
fn announced_triangles(bytes: &[u8]) -> Option<u32> {
    let b = bytes.get(HEADER..HEADER + 4)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// The size of a binary STL with `n` triangles.
fn binary_size(n: u32) -> Option<u64> {
    (n as u64)
        .checked_mul(RECORD as u64)?
        .checked_add(HEADER as u64 + 4)
}

fn read_binary(path: &Path, bytes: &[u8], n: usize) -> Result<Mesh> {
    let mut welder = Welder::with_capacity(n / 2 + 3);
    let mut triangles = Triangles::with_capacity(n);
    let records = bytes.get(HEADER + 4..).unwrap_or_default();
    for (t, rec) in records.chunks_exact(RECORD).enumerate() {
        let f = |k: usize| {
            let o = 12 + 4 * k;
            f32::from_le_bytes([rec[o], rec[o + 1], rec[o + 2], rec[o + 3]]) as f64
        };
        let mut tri = [0u32; 3];
        for (c, slot) in tri.iter_mut().enumerate() {
            let p = DVec3::new(f(3 * c), f(3 * c + 1), f(3 * c + 2));
            if !p.is_finite() {
                return Err(parse_error(
                    path,
                    None,
                    format!("triangle {t} has a non-finite coordinate: {p}"),
                ));
            }
            *slot = welder.index(p);
        }
        // STL gives every corner by its coordinates: a repeat is corners coinciding.
        triangles.push(tri, true);
    }
    triangles.into_mesh(path, welder.positions)
}

/// Where the ASCII parser is in the grammar.
#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    /// Before `solid` or after `endsolid`.
    Outside,
    /// Inside a solid, between facets.
    Solid,
    /// After `facet normal …`, expecting `outer loop`.
    Facet,
    /// Inside `outer loop`, reading vertices.
    Loop,
    /// After `endloop`, expecting `endfacet`.
    EndLoop,
}

fn read_ascii(path: &Path, bytes: &[u8]) -> Result<Mesh> {
    let mut welder = Welder::default();
    let mut triangles = Triangles::default();
    let mut state = State::Outside;
    let mut corners: Vec<u32> = Vec::with_capacity(3);
    let mut line_no = 0;
    for raw in bytes.split(|&b| b == b'\n') {
        line_no += 1;
        let err = |message: String| parse_error(path, Some(line_no), message);
        let line = String::from_utf8_lossy(raw);
        let mut words = line.split_whitespace();
        // Each keyword group below consumes its whole line; several groups on one line are
        // not STL as written by any tool we know of.
        let Some(first) = words.next() else { continue };
        let kw = first.to_ascii_lowercase();
        let expect = |want: &str| err(format!("expected {want}, found `{first}`"));
        match (state, kw.as_str()) {
            (State::Outside, "solid") => state = State::Solid,
            (State::Solid, "facet") => {
                // The stored normal is ignored (it is recomputed from the winding wherever
                // needed), but it must be there and be numbers.
                let normal = words.next().map(str::to_ascii_lowercase);
                if normal.as_deref() != Some("normal") {
                    return Err(err("expected `facet normal nx ny nz`".into()));
                }
                parse_numbers(&mut words, &err, "normal")?;
                state = State::Facet;
            }
            (State::Solid, "endsolid") => state = State::Outside,
            (State::Facet, "outer") => {
                if words.next().map(str::to_ascii_lowercase).as_deref() != Some("loop") {
                    return Err(err("expected `outer loop`".into()));
                }
                corners.clear();
                state = State::Loop;
            }
            (State::Loop, "vertex") => {
                let p = parse_numbers(&mut words, &err, "vertex")?;
                if !p.is_finite() {
                    return Err(err(format!("vertex {p} is not finite")));
                }
                corners.push(welder.index(p));
            }
            (State::Loop, "endloop") => {
                if corners.len() < 3 {
                    return Err(err(format!(
                        "facet has {} vertices, needs 3",
                        corners.len()
                    )));
                }
                // Three corners is the rule; a few writers emit polygons, taken as fans.
                for k in 1..corners.len() - 1 {
                    triangles.push([corners[0], corners[k], corners[k + 1]], true);
                }
                state = State::EndLoop;
            }
            (State::EndLoop, "endfacet") => state = State::Solid,
            (State::Outside, _) => return Err(expect("`solid`")),
            (State::Solid, _) => return Err(expect("`facet` or `endsolid`")),
            (State::Facet, _) => return Err(expect("`outer loop`")),
            (State::Loop, _) => return Err(expect("`vertex` or `endloop`")),
            (State::EndLoop, _) => return Err(expect("`endfacet`")),
        }
    }
    // A missing final `endsolid` is forgiven; a facet cut short is not.
    if !matches!(state, State::Outside | State::Solid) {
        return Err(parse_error(
            path,
            Some(line_no),
            "the file ends inside a facet",
        ));
    }
    triangles.into_mesh(path, welder.positions)
}

/// Parses exactly three numbers from the rest of a line.
///
/// STL coordinates are float32 in either encoding, so text is parsed as f32 and widened: an
/// ASCII file then reads exactly like its binary twin, and two spellings of one float32
/// (`0.1`, `0.100000001`) still weld into one vertex.
fn parse_numbers<'a>(
    words: &mut impl Iterator<Item = &'a str>,
    err: &impl Fn(String) -> Error,
    what: &str,
) -> Result<DVec3> {
    let mut v = [0.0; 3];
    for slot in &mut v {
        let w = words
            .next()
            .ok_or_else(|| err(format!("{what} needs three numbers")))?;
        *slot = w
            .parse::<f32>()
            .map_err(|_| err(format!("{what} coordinate `{w}` is not a number")))?
            as f64;
    }
    if let Some(w) = words.next() {
        return Err(err(format!(
            "unexpected `{w}` after the {what}'s three numbers"
        )));
    }
    Ok(DVec3::from_array(v))
}

/// Writes binary STL: float32 coordinates and per-triangle normals from the winding.
pub(crate) fn write(mesh: &Mesh) -> Result<Files> {
    let n = u32::try_from(mesh.triangles.len()).map_err(|_| {
        Error::mesh(MeshDefect::TooLargeForFormat {
            format: "binary STL",
            detail: format!(
                "{} triangles; it holds at most {}",
                mesh.triangles.len(),
                u32::MAX
            ),
        })
    })?;
    let mut out = Vec::with_capacity(HEADER + 4 + RECORD * mesh.triangles.len());
    // The header must not start with "solid", or readers that go by the prefix take the file
    // for ASCII.
    let mut header = format!("{} binary STL", super::generator()).into_bytes();
    header.resize(HEADER, b' ');
    out.extend_from_slice(&header[..HEADER]);
    out.extend_from_slice(&n.to_le_bytes());
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(t);
        let normal = (b - a).cross(c - a).try_normalize().unwrap_or(DVec3::ZERO);
        for v in [normal, a, b, c] {
            let v: Vec3 = v.as_vec3();
            for x in v.to_array() {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0, 0]);
    }
    Ok(Files {
        main: out,
        companions: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra() -> Mesh {
        Mesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        )
    }

    #[test]
    fn binary_round_trip() {
        let bytes = write(&tetra()).unwrap().main;
        assert_eq!(bytes.len(), 84 + 4 * 50);
        let m = read(Path::new("t.stl"), &bytes).unwrap();
        assert_eq!(m.triangle_count(), 4);
        assert_eq!(m.vertex_count(), 4);
        assert!((m.volume() - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn binary_starting_with_solid() {
        let mut bytes = write(&tetra()).unwrap().main;
        bytes[..6].copy_from_slice(b"solid ");
        let m = read(Path::new("t.stl"), &bytes).unwrap();
        assert_eq!(m.triangle_count(), 4);
    }

    #[test]
    fn truncated_binary_starting_with_solid_mentions_binary() {
        let mut bytes = write(&tetra()).unwrap().main;
        bytes[..6].copy_from_slice(b"solid ");
        bytes.truncate(150);
        let e = read(Path::new("t.stl"), &bytes).unwrap_err().to_string();
        assert!(e.contains("binary STL"), "{e}");
    }

    #[test]
    fn ascii_errors_name_the_line() {
        let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 x\n";
        match read(Path::new("t.stl"), text.as_bytes()) {
            Err(Error::Parse { line, .. }) => assert_eq!(line, Some(5)),
            other => panic!("{other:?}"),
        }
        let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
        assert!(read(Path::new("t.stl"), text.as_bytes()).is_err());
        let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\n";
        assert!(read(Path::new("t.stl"), text.as_bytes()).is_err());
    }

    #[test]
    fn binary_with_nan_is_an_error() {
        let mut bytes = write(&tetra()).unwrap().main;
        bytes[84 + 12..84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
        assert!(read(Path::new("t.stl"), &bytes).is_err());
    }
}
