//! Reading and writing mesh files: OBJ, STL and glTF 2.0 (`.gltf` + `.bin`, and `.glb`).
//!
//! Readers return one welded [`Mesh`] (bit-identical positions become one vertex) with every
//! triangle's source id 0. Writers replace their output atomically: everything is written to
//! temporary files beside the destination, which are renamed into place only once complete.

use std::fmt;
use std::fs;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use crate::error::{Error, MeshDefect, Result};
use crate::geom::is_zero_area;
use crate::mesh::{FromMeshOptions, Material, Mesh};
use crate::solid::Solid;
use crate::topology::check_face_indices;

mod atomic;
mod gltf;
mod obj;
mod stl;
mod triangles;

pub use atomic::cleanup_interrupted_writes;
use atomic::write_atomically;
pub(crate) use atomic::{write_file_atomically, write_file_with};

/// The largest glTF buffer file read, in bytes (2 GiB): beyond any mesh held in memory here,
/// small enough that a hostile `byteLength` cannot claim the machine's memory.
pub const MAX_BUFFER_BYTES: u64 = 1 << 31;

/// The most triangles the glTF reader returns (OBJ and STL are bounded by their file size
/// alone), counted after instancing (each primitive times
/// the nodes that place it) and checked before any is allocated: 20 million triangles take
/// about 1 GB as a [`Mesh`], and more as BSP polygons. A small document naming one mesh
/// thousands of times is refused with [`Error::OverBudget`] instead of exhausting memory.
pub const MAX_READ_TRIANGLES: u64 = 20_000_000;

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Wavefront OBJ (text). Writing adds a sibling `.mtl` file when materials are given.
    Obj,
    /// STL. Reads ASCII and binary; writes binary.
    Stl,
    /// glTF 2.0 JSON with an external `.bin` buffer (reading also accepts embedded `data:`
    /// buffers).
    Gltf,
    /// Binary glTF 2.0: JSON and buffer in one file.
    Glb,
}

impl Format {
    /// Every format, in the order they are listed in messages.
    pub const ALL: [Format; 4] = [Format::Obj, Format::Stl, Format::Gltf, Format::Glb];

    /// The format named by `path`'s extension (case-insensitive: `.obj`, `.stl`, `.gltf`,
    /// `.glb`).
    ///
    /// # Errors
    ///
    /// [`Error::Unsupported`] when the extension is missing or unknown; pass a [`Format`]
    /// explicitly (e.g. parsed from a `--format` option) to [`read_mesh_as`] or
    /// [`write_mesh_as`] instead.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Format> {
        let path = path.as_ref();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref().map(str::parse::<Format>) {
            Some(Ok(f)) => Ok(f),
            Some(Err(_)) | None => Err(Error::Unsupported {
                path: path.to_path_buf(),
                message: format!(
                    "{}; expected .obj, .stl, .gltf or .glb, or name the format explicitly",
                    match &ext {
                        Some(e) => format!("unknown file extension `.{e}`"),
                        None => "no file extension".to_owned(),
                    }
                ),
            }),
        }
    }

    /// The usual file extension, lower case and without the dot.
    #[must_use]
    pub fn extension(self) -> &'static str {
        match self {
            Format::Obj => "obj",
            Format::Stl => "stl",
            Format::Gltf => "gltf",
            Format::Glb => "glb",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.extension())
    }
}

/// The error of parsing a [`Format`] from a string that names none.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseFormatError {
    name: String,
}

impl fmt::Display for ParseFormatError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown mesh format `{}`: expected obj, stl, gltf or glb",
            self.name
        )
    }
}

impl std::error::Error for ParseFormatError {}

impl FromStr for Format {
    type Err = ParseFormatError;

    /// Parses a format name, case-insensitive and with an optional leading dot: `obj`, `stl`,
    /// `gltf`, `glb`.
    fn from_str(s: &str) -> std::result::Result<Format, ParseFormatError> {
        let name = s.trim();
        let name = name.strip_prefix('.').unwrap_or(name);
        Format::ALL
            .into_iter()
            .find(|f| f.extension().eq_ignore_ascii_case(name))
            .ok_or_else(|| ParseFormatError { name: s.to_owned() })
    }
}

/// Reads a mesh file, choosing the format by the file's extension.
///
/// The result is welded (bit-identical positions share one vertex), every triangle has
/// source id 0, and triangles that repeat a vertex after welding are dropped.
///
/// A well-formed file with no faces at all — what the writers produce for an empty result:
/// an OBJ of comments and statements only, an STL of no facets, a glTF whose scenes draw no
/// triangles — is the empty mesh, so that an empty result written and read back is the empty
/// solid again (check [`Mesh::is_empty`] to warn about it).
///
/// # Errors
///
/// [`Error::Unsupported`] for an unknown extension or an unsupported feature of the format,
/// [`Error::Io`] when the file (or a glTF's external buffer) cannot be read, and
/// [`Error::Parse`] naming the file (and, for OBJ and ASCII STL, the line) when the content is
/// malformed or has non-finite coordinates; when the file is empty (zero bytes or only
/// whitespace: a write that never happened, not an empty mesh); when every triangle repeats a
/// vertex; and for an OBJ with vertices but no faces (points, not a surface).
pub fn read_mesh(path: impl AsRef<Path>) -> Result<Mesh> {
    let path = path.as_ref();
    read_mesh_as(path, Format::from_path(path)?)
}

/// Reads a mesh file in the given format, whatever its extension. See [`read_mesh`].
///
/// # Errors
///
/// As [`read_mesh`].
pub fn read_mesh_as(path: impl AsRef<Path>, format: Format) -> Result<Mesh> {
    let path = path.as_ref();
    let bytes = fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_mesh_from_bytes(path, &bytes, format)
}

/// Reads a mesh from the bytes of a file already in memory. `path` names it in error messages
/// and, for a `.gltf`, is where external buffers are looked up relative to. See [`read_mesh`].
///
/// ```
/// use bspcsg::{Format, read_mesh_from_bytes};
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
/// let mesh = read_mesh_from_bytes("mem.obj".as_ref(), obj, Format::Obj)?;
/// assert_eq!(mesh.triangle_count(), 1);
/// assert!(read_mesh_from_bytes("bad.obj".as_ref(), b"f 1 2 3", Format::Obj).is_err());
/// # Ok::<(), bspcsg::Error>(())
/// ```
///
/// # Errors
///
/// As [`read_mesh`].
pub fn read_mesh_from_bytes(path: &Path, bytes: &[u8], format: Format) -> Result<Mesh> {
    // A zero-byte file is a write that never happened or a truncation, not an empty mesh (and
    // saying so beats a parser's "EOF at column 0").
    if bytes.iter().all(u8::is_ascii_whitespace) {
        return Err(parse_error(path, None, "the file is empty"));
    }
    match format {
        Format::Obj => obj::read(path, bytes),
        Format::Stl => stl::read(path, bytes),
        Format::Gltf | Format::Glb => gltf::read(path, bytes),
    }
}

/// Reads a mesh file (format by extension, as [`read_mesh`]) and makes a [`Solid`] of it with
/// [`Solid::from_mesh_with`], every error naming the file.
///
/// With [`require_closed`](FromMeshOptions::require_closed) (the default options) the mesh
/// must bound a solid: a mesh with boundary, non-manifold or inconsistently oriented edges is
/// refused with its counts (`bunny.obj is not closed: 223 boundary edges`), and so is a closed
/// mesh turned inside out (a shell enclosing no positive volume that is not a cavity), which
/// would otherwise stand for its complement in every boolean. [`FromMeshOptions::lenient`]
/// accepts any mesh the file holds.
///
/// ```no_run
/// use bspcsg::{FromMeshOptions, read_solid};
/// let part = read_solid("part.obj", &FromMeshOptions::default())?;
/// let scan = read_solid("scan.stl", &FromMeshOptions::lenient())?;
/// let both = &part | &scan;
/// # Ok::<(), bspcsg::Error>(())
/// ```
///
/// # Errors
///
/// As [`read_mesh`] for the file itself, and [`Error::InvalidMesh`] with the path and the
/// [`MeshDefect`](crate::MeshDefect) when the mesh does not bound a solid.
pub fn read_solid(path: impl AsRef<Path>, options: &FromMeshOptions) -> Result<Solid> {
    let path = path.as_ref();
    let mesh = read_mesh(path)?;
    Solid::from_mesh_with(&mesh, options).map_err(|e| match e {
        // "x.obj is not closed: …", "x.obj is inside out: …", else "is not a valid solid".
        Error::InvalidMesh { path: None, defect } => Error::InvalidMesh {
            path: Some(path.to_path_buf()),
            defect,
        },
        other => other,
    })
}

/// Writes a mesh file, choosing the format by the file's extension.
///
/// `materials[i]` is the material of the triangles whose source id is `i`; triangles whose
/// source id has no entry get a default grey material. OBJ writes the materials to a sibling
/// `.mtl` file (none when `materials` is empty), glTF as one primitive and material per source
/// id, and STL ignores them.
///
/// STL and glTF store float32 coordinates: a feature finer than that (a slab 10⁻⁹ thick at
/// x = 1) reads back open. [`as_read_back_from`] gives the mesh a reader will get, to check
/// before writing (the command line warns).
///
/// The output is replaced atomically: the content goes to temporary files in the same
/// directory, renamed over the destination only once complete. On error no temporary file
/// remains and an existing destination is left untouched. (For the two-file formats the
/// companion file, `.mtl` or `.bin`, is renamed first; only a failure between the two renames
/// can leave a new companion beside an old main file.)
///
/// # Errors
///
/// [`Error::Unsupported`] for an unknown extension, [`Error::InvalidMesh`] when an index is
/// out of range, `sources` and `triangles` differ in length, a used position is not finite,
/// or (STL, glTF) does not fit in float32, [`Error::InvalidParameter`] for a material colour
/// outside 0..=1, and [`Error::Io`] naming the destination when writing fails.
pub fn write_mesh(path: impl AsRef<Path>, mesh: &Mesh, materials: &[Material]) -> Result<()> {
    let path = path.as_ref();
    write_mesh_as(path, mesh, materials, Format::from_path(path)?)
}

/// Writes a mesh file in the given format, whatever the path's extension. See [`write_mesh`].
///
/// # Errors
///
/// As [`write_mesh`].
pub fn write_mesh_as(
    path: impl AsRef<Path>,
    mesh: &Mesh,
    materials: &[Material],
    format: Format,
) -> Result<()> {
    let mut files = encode_mesh(path, mesh, materials, format)?;
    // The main file comes first in `files`; companions are renamed before it so that a reader
    // never sees a main file that refers to a missing or stale companion.
    files.rotate_left(1);
    write_atomically(&files)
}

/// The files [`write_mesh_as`] would write, as bytes in memory: the main file first (its
/// `path` is `path`), then any companion beside it (an OBJ's `.mtl` when materials are given,
/// a `.gltf`'s `.bin`). Nothing is written. `path` only names the files: a `.gltf` and an OBJ
/// refer to their companion by its file name, and the companions' paths are derived from it.
///
/// ```
/// use bspcsg::{Format, Mesh, encode_mesh, read_mesh_from_bytes};
/// use bspcsg::glam::DVec3;
/// let tetra = Mesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// );
/// let files = encode_mesh("tetra.stl", &tetra, &[], Format::Stl)?;
/// assert_eq!(files.len(), 1);
/// assert_eq!(files[0].bytes.len(), 84 + 4 * 50);
/// let back = read_mesh_from_bytes(&files[0].path, &files[0].bytes, Format::Stl)?;
/// assert_eq!(back.triangle_count(), 4);
/// # Ok::<(), bspcsg::Error>(())
/// ```
///
/// # Errors
///
/// As [`write_mesh`], except that nothing is written: [`Error::InvalidMesh`] and
/// [`Error::InvalidParameter`] as there, and [`Error::Io`] only when a companion's path would
/// be `path` itself (a `.gltf` named `x.bin`, an OBJ with materials named `x.mtl`).
pub fn encode_mesh(
    path: impl AsRef<Path>,
    mesh: &Mesh,
    materials: &[Material],
    format: Format,
) -> Result<Vec<OutFile>> {
    let path = path.as_ref();
    check_mesh(mesh, format != Format::Obj)?;
    for m in materials {
        for &c in &m.base_color {
            if !(0.0..=1.0).contains(&c) {
                return Err(Error::param(
                    "base_color",
                    c,
                    "each colour component must be in 0..=1",
                ));
            }
        }
    }
    let files = match format {
        Format::Obj => obj::write(path, mesh, materials),
        Format::Stl => stl::write(mesh)?,
        Format::Gltf => gltf::write(path, mesh, materials, false)?,
        Format::Glb => gltf::write(path, mesh, materials, true)?,
    };
    if let Some(c) = files.companions.iter().find(|c| c.path == path) {
        return Err(Error::Io {
            path: path.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "the {format} companion {} would be the output itself; give the output \
                     its format's extension",
                    c.path.display()
                ),
            ),
        });
    }
    let mut out = vec![OutFile {
        path: path.to_path_buf(),
        bytes: files.main,
    }];
    out.extend(files.companions);
    Ok(out)
}

/// The files beside a mesh file that it refers to: a glTF's buffer and image URIs (decoded as
/// the reader decodes them; `data:` URIs are no files), an OBJ's `mtllib` names. For callers
/// that must not overwrite what an input needs (the command line's companion-file check).
/// Best effort: a file that cannot be read or parsed yields none (reading it says why).
#[must_use]
pub fn referenced_files(input: &Path) -> Vec<PathBuf> {
    let dir = input.parent().unwrap_or(Path::new(""));
    let Ok(bytes) = fs::read(input) else {
        return Vec::new();
    };
    let mut names = Vec::new();
    if let Ok(doc) = serde_json::from_slice::<serde_json::Value>(&bytes) {
        for key in ["buffers", "images"] {
            for item in doc[key].as_array().into_iter().flatten() {
                if let Some(uri) = item["uri"].as_str().filter(|u| !u.starts_with("data:")) {
                    names.push(gltf::percent_decode(uri).unwrap_or_else(|| uri.to_owned()));
                }
            }
        }
    } else {
        let text = String::from_utf8_lossy(&bytes);
        for line in text.lines() {
            if let Some(rest) = line.trim_start().strip_prefix("mtllib") {
                names.extend(rest.split_whitespace().map(str::to_owned));
            }
        }
    }
    names.into_iter().map(|n| dir.join(n)).collect()
}

/// `mesh` as a reader gives it back from a file written in `format`, or `None` when it reads
/// back as it is. Bit-identical positions become one vertex, as [`Mesh::as_read_back`] says;
/// where the format stores float32 coordinates (STL, glTF, GLB), positions are first rounded
/// to float32, so vertices closer than its resolution become one and triangles thinner than it
/// lose their area. A closed mesh with such features, which a boolean can make from parts a
/// hair apart, reads back open; OBJ keeps every coordinate.
///
/// ```
/// use bspcsg::{Format, Mesh, as_read_back_from, glam::DVec3};
/// // A box 10⁻⁹ thick at x = 1: in float32 its two sides are one plane.
/// let slab = bspcsg::Solid::cuboid(DVec3::new(1e-9, 1.0, 1.0))?
///     .translate(DVec3::X)?
///     .to_mesh();
/// assert!(slab.report().is_closed_manifold());
/// assert!(as_read_back_from(&slab, Format::Obj).is_none());
/// let back = as_read_back_from(&slab, Format::Stl).expect("its sides merge");
/// assert!(!back.report().is_closed_manifold());
/// # Ok::<(), bspcsg::Error>(())
/// ```
#[must_use]
pub fn as_read_back_from(mesh: &Mesh, format: Format) -> Option<Mesh> {
    if format == Format::Obj {
        return mesh.as_read_back();
    }
    let rounded = Mesh {
        positions: mesh
            .positions
            .iter()
            .map(|p| p.as_vec3().as_dvec3())
            .collect(),
        ..mesh.clone()
    };
    let flattened = rounded.triangles.iter().any(|t| {
        t.iter().all(|&i| (i as usize) < rounded.positions.len())
            && is_zero_area(t.map(|i| rounded.positions[i as usize]))
    });
    // No two rounded positions are one, so neither are the exact ones.
    match rounded.as_read_back() {
        Some(welded) => Some(welded),
        None => flattened.then_some(rounded),
    }
}

/// The bytes a writer produced: the main file and any companions (`.mtl`, `.bin`).
pub(crate) struct Files {
    pub main: Vec<u8>,
    pub companions: Vec<OutFile>,
}

/// One file of a mesh encoded by [`encode_mesh`]: where it belongs and its content.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OutFile {
    /// The file's path: the one given for the main file, derived from it for a companion.
    pub path: PathBuf,
    /// The file's content.
    pub bytes: Vec<u8>,
}

/// `"bspcsg <version>"`, written as the generator of every file.
pub(crate) fn generator() -> String {
    format!("bspcsg {}", env!("CARGO_PKG_VERSION"))
}

/// An [`Error::Parse`] for `path`.
pub(crate) fn parse_error(path: &Path, line: Option<usize>, message: impl Into<String>) -> Error {
    Error::Parse {
        path: path.to_path_buf(),
        line,
        message: message.into(),
    }
}

/// Refuses meshes a writer would turn into a broken file: indices out of range, a `sources`
/// list of the wrong length, used positions that are not finite or, where the format stores
/// float32, that overflow it.
fn check_mesh(mesh: &Mesh, float32: bool) -> Result<()> {
    if mesh.sources.len() != mesh.triangles.len() {
        return Err(Error::mesh(MeshDefect::SourceCount {
            sources: mesh.sources.len(),
            triangles: mesh.triangles.len(),
        }));
    }
    let n = mesh.positions.len();
    // All positions, used or not: OBJ writes every one.
    let non_finite = mesh.positions.iter().filter(|p| !p.is_finite()).count();
    if let Some(first) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(Error::mesh(MeshDefect::NonFinite {
            vertices: non_finite,
            first,
            position: mesh.positions[first],
        }));
    }
    check_face_indices(&mesh.triangles, n, true)?;
    for &i in mesh.triangles.iter().flatten() {
        let p = mesh.positions[i as usize];
        if float32 && !p.as_vec3().is_finite() {
            return Err(Error::mesh(MeshDefect::TooLargeForFormat {
                format: "float32 coordinates",
                detail: format!("vertex {i} = {p} is beyond ±{:e}", f32::MAX),
            }));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_from_path_is_case_insensitive() {
        let f = |p: &str| Format::from_path(Path::new(p));
        assert_eq!(f("a/b.OBJ").ok(), Some(Format::Obj));
        assert_eq!(f("b.Stl").ok(), Some(Format::Stl));
        assert_eq!(f("b.gltf").ok(), Some(Format::Gltf));
        assert_eq!(f("b.GLB").ok(), Some(Format::Glb));
        assert!(matches!(f("b.ply"), Err(Error::Unsupported { .. })));
        assert!(matches!(f("noext"), Err(Error::Unsupported { .. })));
    }

    #[test]
    fn format_from_str() {
        assert_eq!("glb".parse::<Format>(), Ok(Format::Glb));
        assert_eq!(".OBJ".parse::<Format>(), Ok(Format::Obj));
        let e = "ply".parse::<Format>().unwrap_err();
        assert!(e.to_string().contains("ply"));
        for f in Format::ALL {
            assert_eq!(f.to_string().parse::<Format>(), Ok(f));
        }
    }
}
