//! The crate's one error type, and the defects of meshes that do not bound a solid.

use std::borrow::Cow;
use std::fmt;
use std::path::PathBuf;

use glam::DVec3;

/// Everything that can go wrong in `bspcsg`, with enough context to fix it.
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A primitive, transform or option parameter is out of range (non-finite, not positive,
    /// too few segments, a singular matrix …). Remedy: pass a value in the documented range.
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// The parameter's name as the API spells it.
        name: &'static str,
        /// The value that was refused.
        value: f64,
        /// What the value must be instead (limits quoted from their constants).
        reason: Cow<'static, str>,
    },

    /// An option leaves a region unbounded where a bounded one is needed: a scene with a
    /// half-space not intersected away, baked or tessellated without bounds. Remedy: the
    /// option named in the message.
    #[error("{what} is unbounded ({why}); {remedy}")]
    Unbounded {
        /// What is unbounded.
        what: &'static str,
        /// Why.
        why: &'static str,
        /// How to fix it.
        remedy: &'static str,
    },

    /// An indexed mesh or polyhedron is not a valid closed solid, or a mesh does not fit the
    /// file format it is written to. [`MeshDefect`] says which, with counts; `path` names the
    /// file the mesh came from, where there is one. Remedy: repair the mesh, or use the lenient
    /// options where the API offers them.
    #[error("invalid mesh: {}", mesh_message(path.as_ref(), defect))]
    InvalidMesh {
        /// The file the mesh was read from, if any.
        path: Option<PathBuf>,
        /// What is wrong.
        defect: MeshDefect,
    },

    /// Reading or writing a file failed at the operating-system level.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file involved.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },

    /// A file's content is malformed. `line` is 1-based where the format has lines.
    #[error("{}{}: {message}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    Parse {
        /// The file involved.
        path: PathBuf,
        /// The 1-based line, where the format has lines.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },

    /// A file format or feature that is not supported (unknown extension, non-triangle glTF
    /// primitive …).
    #[error("{}: {message}", path.display())]
    Unsupported {
        /// The file involved.
        path: PathBuf,
        /// What is not supported.
        message: String,
    },

    /// A file asks for more than a reader's budget (see [`crate::MAX_READ_TRIANGLES`] and
    /// [`crate::MAX_BUFFER_BYTES`]); refused before the memory is allocated. Remedy: split the
    /// file, or reduce its instancing.
    #[error("{}: {message}", path.display())]
    OverBudget {
        /// The file involved.
        path: PathBuf,
        /// What exceeds which limit.
        message: String,
    },

    /// A boolean's operands meet in a region too small for the precision of their coordinates
    /// (or of the tolerance an earlier boolean left them): its result would not be right to one
    /// part in 10⁵ of that region, so it is refused (see the crate docs, `# Precision`). Remedy:
    /// move the model nearer the origin, or make the features that meet larger.
    #[error(
        "beyond precision: where the operands meet (or a part lies), a region {region:.3e} \
         across, {magnitude:.3e} from the origin, is only resolved to {eps:.3e} (one part in \
         {:.1e}; one part in 1e5 is needed); move the model nearer the origin or make the \
         features that meet larger",
        region / eps
    )]
    BeyondPrecision {
        /// The diagonal of the region where the operands met.
        region: f64,
        /// The largest coordinate magnitude in it.
        magnitude: f64,
        /// The tolerance that region needed.
        eps: f64,
    },

    /// A boolean stopped at its work budget: building its trees and clipping cut the polygons
    /// into pieces with more corners than [`MAX_BOOLEAN_WORK`](crate::MAX_BOOLEAN_WORK) allows (or
    /// [`WORK_PER_POLYGON`](crate::WORK_PER_POLYGON) per polygon of large operands; see
    /// [`Solid::check_budget`](crate::Solid::check_budget)). It happens where faces of
    /// different operands nearly coincide over a wide area. Remedy: move such parts apart, or
    /// make them coincide exactly, or give them fewer points.
    #[error(
        "beyond the work budget: the booleans had cut their polygons into pieces of {work} \
         corners in all when they were stopped, more than the budget of {limit} (about half a \
         minute); faces of different operands nearly coincide over a wide area (as copies of \
         one detailed outline a little apart do): move such parts apart or make them coincide \
         exactly, or give them fewer points"
    )]
    BeyondBudget {
        /// The corners of the pieces cut when the booleans were stopped.
        work: u64,
        /// The budget.
        limit: u64,
    },

    /// A solid's mesh is not a closed 2-manifold though it should be (the result of booleans
    /// of solids): a fault of the kernel on hard input, reported by
    /// [`Solid::to_checked_mesh`](crate::Solid::to_checked_mesh) instead of passed on. A caller
    /// that wants the mesh as it is anyway takes [`Solid::to_mesh`](crate::Solid::to_mesh).
    /// Remedy: move or scale the operands slightly (the fault lies where nearly coincident
    /// features meet), or report the input.
    #[error("the result is not a closed 2-manifold: {report}")]
    BrokenResult {
        /// The mesh's report as text: what is wrong, with counts. (Text, not the `MeshReport`
        /// itself: errors sit below meshes in the crate's module order.)
        report: String,
    },

    /// A solid's mesh is a closed 2-manifold (or empty) but bounds a volume the solid's polygons
    /// do not, by more than the repair that made it may change it (see
    /// [`Solid::check_mesh_volume`](crate::Solid::check_mesh_volume)): the last guard against
    /// passing on a wrong result, a fault of the kernel on hard input. Remedy as for
    /// [`Error::BrokenResult`].
    #[error(
        "the result's mesh bounds a volume of {mesh:.6e} where the solid's polygons bound \
         {polygons:.6e}: they differ by {diff:.3e}, more than the {bound:.3e} its repair may \
         change; the repair went wrong on this input: move or scale the operands slightly (the \
         fault lies where nearly coincident features meet), or report the input",
        diff = (.mesh - .polygons).abs()
    )]
    WrongVolume {
        /// The mesh's volume.
        mesh: f64,
        /// The volume the solid's polygons bound.
        polygons: f64,
        /// How far apart the two may be.
        bound: f64,
    },

    /// A scene document is invalid. `json_path` locates the fault, e.g. `$.children[2].data.radius`;
    /// `file` names the document where it was read from a file.
    #[error("{}{json_path}: {message}", file.as_ref().map(|f| format!("{}: ", f.display())).unwrap_or_default())]
    Scene {
        /// The document's file, when it came from one.
        file: Option<PathBuf>,
        /// Where in the document the fault is.
        json_path: String,
        /// What is wrong.
        message: String,
    },
}

/// `Result` with this crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub(crate) fn param(
        name: &'static str,
        value: f64,
        reason: impl Into<Cow<'static, str>>,
    ) -> Self {
        Error::InvalidParameter {
            name,
            value,
            reason: reason.into(),
        }
    }

    /// An [`Error::InvalidMesh`] not tied to a file.
    pub(crate) fn mesh(defect: MeshDefect) -> Self {
        Error::InvalidMesh { path: None, defect }
    }

    /// The mesh defect, for an [`Error::InvalidMesh`].
    #[must_use]
    pub fn mesh_defect(&self) -> Option<&MeshDefect> {
        match self {
            Error::InvalidMesh { defect, .. } => Some(defect),
            _ => None,
        }
    }
}

/// Why a mesh does not bound a solid, or does not fit a file format: the kinds callers match
/// on (the command line offers `--allow-open` for [`NotClosed`](Self::NotClosed) and
/// [`InsideOut`](Self::InsideOut) only). `Display` gives the counts.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub enum MeshDefect {
    /// No faces at all (a polyhedron needs some).
    NoFaces,
    /// Edges used by one face, by more than two, or by two in the same direction.
    NotClosed {
        /// Edges used by one face.
        boundary_edges: usize,
        /// Edges used by more than two faces.
        non_manifold_edges: usize,
        /// Edges used by two faces in the same direction.
        inconsistent_edges: usize,
        /// All edges.
        edges: usize,
    },
    /// Closed, but shells enclose no positive volume and are no cavities: the faces wind
    /// clockwise seen from outside.
    InsideOut {
        /// Shells facing inward.
        inverted_shells: usize,
        /// All shells.
        shells: usize,
    },
    /// Faces (or triangles) refer to vertices that do not exist.
    IndexOutOfRange {
        /// How many faces do.
        faces: usize,
        /// The first such face.
        first_face: usize,
        /// The index it uses.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// A face with fewer than three indices.
    TooFewIndices {
        /// The face.
        face: usize,
        /// Its number of indices.
        indices: usize,
    },
    /// Faces that use one vertex twice.
    RepeatedIndex {
        /// How many faces do.
        faces: usize,
        /// The first such face.
        first_face: usize,
        /// Its indices.
        indices: Vec<u32>,
    },
    /// A face whose corners span no area.
    ZeroAreaFace {
        /// The face.
        face: usize,
    },
    /// Every triangle spans no area within the rounding of its coordinates: the mesh bounds
    /// nothing, or it is too small for its distance from the origin.
    AllZeroArea {
        /// How many triangles.
        triangles: usize,
        /// The largest coordinate magnitude.
        reach: f64,
    },
    /// Closed, but triangles cross each other: overlapping shells, or a shell through itself.
    /// It bounds no solid (its volume counts the overlap twice). Remedy: union the shells in
    /// the program that made it, or combine them as separate inputs.
    SelfIntersecting {
        /// Pairs of triangles that cross.
        pairs: usize,
        /// True when the search stopped at `MAX_CROSSING_PAIRS` and there may be more.
        more: bool,
        /// The first pair.
        first: [usize; 2],
    },
    /// Closed, and a shell crosses itself (not only another shell): it has no inside, so
    /// [`FromMeshOptions::union_shells`](crate::FromMeshOptions::union_shells) cannot unite
    /// the shells. Remedy: repair the shell in the program that made it.
    ShellCrossesItself {
        /// Pairs of triangles of one shell that cross.
        pairs: usize,
        /// True when the search stopped at `MAX_CROSSING_PAIRS` and there may be more.
        more: bool,
        /// The first pair.
        first: [usize; 2],
    },
    /// Closed, but the check for crossing triangles gave up: it looked at its budget of
    /// candidate pairs ([`PAIR_BUDGET_PER_TRIANGLE`](crate::PAIR_BUDGET_PER_TRIANGLE) per
    /// triangle, [`PAIR_BUDGET_BASE`](crate::PAIR_BUDGET_BASE) more) without finding a crossing
    /// or finishing. Valid meshes use a few per triangle; this takes many triangles crowded into
    /// one place (a fan folded through itself, slivers stacked within rounding of one another,
    /// fans meeting point to point). Remedy: remesh the crowded part, or read the mesh
    /// unchecked ([`FromMeshOptions::lenient`](crate::FromMeshOptions::lenient)).
    CrossingCheckOverBudget {
        /// The mesh's triangles.
        triangles: usize,
        /// Candidate pairs looked at.
        candidates: usize,
    },
    /// A face whose boundary crosses itself, so it cannot be triangulated.
    SelfIntersectingFace {
        /// The face.
        face: usize,
    },
    /// Vertices with a NaN or infinite coordinate.
    NonFinite {
        /// How many.
        vertices: usize,
        /// The first.
        first: usize,
        /// Its position.
        position: DVec3,
    },
    /// Vertices beyond the supported range, [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    BeyondRange {
        /// How many.
        vertices: usize,
        /// The first.
        first: usize,
        /// Its position.
        position: DVec3,
        /// The largest magnitude accepted, [`MAX_COORDINATE`](crate::MAX_COORDINATE).
        limit: f64,
    },
    /// A source-id list whose length is not the number of triangles.
    SourceCount {
        /// Source ids given.
        sources: usize,
        /// Triangles.
        triangles: usize,
    },
    /// The mesh does not fit the file format: coordinates beyond float32, more triangles or
    /// bytes than the format can count.
    TooLargeForFormat {
        /// The format's name.
        format: &'static str,
        /// What exceeds which limit.
        detail: String,
    },
}

impl fmt::Display for MeshDefect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshDefect::NoFaces => f.write_str("no faces"),
            MeshDefect::NotClosed {
                boundary_edges,
                non_manifold_edges,
                inconsistent_edges,
                edges,
            } => {
                let defects: Vec<String> = [
                    (*boundary_edges, "boundary edges"),
                    (*non_manifold_edges, "non-manifold edges"),
                    (*inconsistent_edges, "inconsistently oriented edges"),
                ]
                .into_iter()
                .filter(|&(n, _)| n > 0)
                .map(|(n, what)| format!("{n} {what}"))
                .collect();
                write!(f, "not closed: {} (of {edges} edges)", defects.join(", "))
            }
            MeshDefect::InsideOut {
                inverted_shells,
                shells,
            } => write!(
                f,
                "inside out: {inverted_shells} of {shells} shells enclose no positive volume and \
                 are not cavities (faces must wind counter-clockwise seen from outside)"
            ),
            MeshDefect::IndexOutOfRange {
                faces,
                first_face,
                index,
                vertices,
            } => write!(
                f,
                "faces with a vertex index out of range: {faces} (first: face {first_face} uses \
                 {index}, but there are only {vertices} vertices)"
            ),
            MeshDefect::TooFewIndices { face, indices } => write!(
                f,
                "face {face} has {indices} indices; a face needs at least 3"
            ),
            MeshDefect::RepeatedIndex {
                faces,
                first_face,
                indices,
            } => write!(
                f,
                "faces that repeat a vertex index: {faces} (first: face {first_face} = {indices:?})"
            ),
            MeshDefect::ZeroAreaFace { face } => write!(f, "face {face} has no area"),
            MeshDefect::SelfIntersecting { pairs, more, first } => write!(
                f,
                "self-intersecting: {} pairs of triangles cross (first: triangles {} and \
                 {}); overlapping shells bound no solid: unite them first, or give them as \
                 separate inputs",
                pair_count(*pairs, *more),
                first[0],
                first[1]
            ),
            MeshDefect::ShellCrossesItself { pairs, more, first } => write!(
                f,
                "self-intersecting within a shell: {} pairs of triangles of one shell cross \
                 (first: triangles {} and {}); a shell through itself has no inside, so the \
                 shells cannot be united",
                pair_count(*pairs, *more),
                first[0],
                first[1]
            ),
            // Corners all at the origin coincide at any scale: nothing to move.
            MeshDefect::AllZeroArea { triangles, reach } if *reach == 0.0 => write!(
                f,
                "all {triangles} triangles have zero area: every corner is at the origin, the \
                 mesh bounds no volume"
            ),
            MeshDefect::AllZeroArea { triangles, reach } => write!(
                f,
                "all {triangles} triangles have zero area within the rounding of their \
                 coordinates (up to {reach:e} from the origin): the mesh bounds no volume, or is \
                 too small for its distance from the origin; move it nearer the origin"
            ),
            MeshDefect::CrossingCheckOverBudget {
                triangles,
                candidates,
            } => write!(
                f,
                "the check for crossing triangles gave up after {candidates} candidate pairs (its \
                 budget for {triangles} triangles) without finding one: many triangles crowd one \
                 place (a fan folded through itself, slivers stacked on one another, fans meeting \
                 point to point); remesh that part, or read the mesh unchecked"
            ),
            MeshDefect::SelfIntersectingFace { face } => write!(
                f,
                "face {face} is self-intersecting and cannot be triangulated"
            ),
            MeshDefect::NonFinite {
                vertices,
                first,
                position,
            } => write!(
                f,
                "vertices with a non-finite coordinate: {vertices} (first: vertex {first} = \
                 {position})"
            ),
            MeshDefect::BeyondRange {
                vertices,
                first,
                position,
                limit,
            } => write!(
                f,
                "vertices beyond the supported range of ±{limit:e}: {vertices} (first: vertex \
                 {first} = [{:e}, {:e}, {:e}]); scale the mesh down",
                position.x, position.y, position.z
            ),
            MeshDefect::SourceCount { sources, triangles } => write!(
                f,
                "{sources} source ids for {triangles} triangles; there must be one per triangle"
            ),
            MeshDefect::TooLargeForFormat { format, detail } => {
                write!(f, "too large for {format}: {detail}")
            }
        }
    }
}

/// `x.obj is not closed: …` / `x.obj is inside out: …` where the defect says what the mesh is,
/// `x.obj is not a valid solid: …` for the rest; the bare defect without a file.
/// A count of crossing pairs, "at least" where the search stopped early.
fn pair_count(pairs: usize, more: bool) -> String {
    if more {
        format!("at least {pairs}")
    } else {
        pairs.to_string()
    }
}

fn mesh_message(path: Option<&PathBuf>, defect: &MeshDefect) -> String {
    match path {
        None => defect.to_string(),
        Some(p) => match defect {
            MeshDefect::NotClosed { .. } | MeshDefect::InsideOut { .. } => {
                format!("{} is {defect}", p.display())
            }
            _ => format!("{} is not a valid solid: {defect}", p.display()),
        },
    }
}
