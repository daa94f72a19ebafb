//! Validation of indexed meshes: a report of topology and orientation for any triangle mesh
//! ([`Mesh::report`]), and the checks that mesh and polyhedron input must pass to become a
//! [`Solid`](crate::Solid).
//!
//! Everything rests on one edge table: the half-edges of all faces, sorted by their undirected
//! edge, so that each edge's uses sit next to each other. That costs `O(n log n)` and no hashing;
//! components and vertex fans then come from union-find over triangles and triangle corners.

use std::f64::consts::PI;
use std::fmt;

use glam::DVec3;

use super::Mesh;
use crate::disjoint_sets::DisjointSets;
use crate::error::{Error, Result};
use crate::geom::Aabb;
use crate::geom::MAX_COORDINATE;
use crate::geom::solid_angle;

/// What [`Mesh::report`] finds in an indexed triangle mesh: counts, defects, shells, genus and
/// orientation.
///
/// # Definitions
///
/// - **Edges** are undirected vertex-index pairs used by at least one *usable* triangle: one
///   whose three indices are in range and distinct. Triangles with a repeated index are
///   [degenerate](Self::degenerate_triangles) and take no part in topology (they bound nothing;
///   a collapsed sliver between two good triangles then leaves those two properly joined).
///   Triangles with an index out of range are counted in
///   [`invalid_index_triangles`](Self::invalid_index_triangles) and otherwise ignored.
/// - An edge is a **boundary** edge when one triangle uses it, **non-manifold** when more than
///   two do, and **inconsistently oriented** when exactly two use it in the same direction.
/// - **Shells** are the connected components of the usable triangles, where two triangles are
///   connected when they share an edge used by exactly two triangles (manifold adjacency).
///   So two solids touching at a vertex, or along an edge (an edge of four triangles), are two
///   shells, not one.
/// - A vertex is **non-manifold** when the usable triangles around it form more than one fan,
///   fans being joined across edges used by exactly two triangles. Touching solids show up here.
/// - **Zero area**: the triangle's area cannot be told from zero at the precision of its
///   coordinates: twice the area is at most [`ZERO_AREA_ULPS`](Self::ZERO_AREA_ULPS) units in
///   the last place of what moving each corner by its own rounding (ε·|v|) could change it,
///   `ε · Σ |v| · |opposite edge|`. Scale-free, so tiny and huge meshes are judged alike, exact
///   zeros always count, and a needle that is merely thin (a 1-wide hole joined to corners
///   10³⁸ away) does not.
///
/// Self-intersections are not looked for: that needs geometry queries this report avoids.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub struct MeshReport {
    /// Number of triangles, all of them.
    pub triangles: usize,
    /// Number of distinct vertices referenced by triangles (unreferenced positions don't count).
    pub vertices: usize,
    /// Number of distinct undirected edges of usable triangles.
    pub edges: usize,
    /// Edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Edges used by more than two triangles.
    pub non_manifold_edges: usize,
    /// Edges used by exactly two triangles that traverse it in the same direction.
    pub inconsistent_edges: usize,
    /// Triangles with a repeated index or zero area (see the definitions above).
    pub degenerate_triangles: usize,
    /// The degenerate triangles that repeat an index (a subset of `degenerate_triangles`).
    pub repeated_index_triangles: usize,
    /// Triangles with a vertex index beyond the positions; ignored otherwise.
    pub invalid_index_triangles: usize,
    /// Referenced vertices with a NaN or infinite coordinate.
    pub non_finite_vertices: usize,
    /// Vertices whose triangles form more than one edge-connected fan.
    pub non_manifold_vertices: usize,
    /// The shells, in order of their first triangle.
    pub shells: Vec<ShellReport>,
    /// Total genus: the sum over shells, or `None` when any shell is open or inconsistently
    /// oriented (genus is then undefined). `Some(0)` for an empty mesh.
    pub genus: Option<u64>,
    /// Signed volume of all usable triangles by the divergence theorem, relative to the box
    /// centre. Meaningful only for closed, oriented meshes.
    pub volume: f64,
    /// No boundary edges and no non-manifold edges.
    pub closed: bool,
    /// No inconsistently oriented edges.
    pub oriented: bool,
    /// Every closed, consistently oriented shell faces outward: it encloses positive volume, or
    /// it is a [cavity](ShellReport::cavity). Open and inconsistent shells are not judged.
    pub outward: bool,
    /// Closed, consistently oriented shells that are not [outward](Self::outward): volume not
    /// positive and not a cavity. An inside-out solid has one per shell; a flat shell (two
    /// triangles back to back) counts too, as it bounds nothing.
    pub inverted_shells: usize,
}

/// One shell (connected component) of a mesh; see [`MeshReport`] for the definitions.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq)]
pub struct ShellReport {
    /// Number of triangles.
    pub triangles: usize,
    /// Number of distinct vertices its triangles use.
    pub vertices: usize,
    /// Number of distinct edges its triangles use.
    pub edges: usize,
    /// Euler characteristic χ = V − E + F of this shell alone.
    pub euler_characteristic: i64,
    /// Every edge of the shell is used by exactly two of the shell's own triangles. (Two cubes
    /// sharing an edge are two closed shells, though the mesh has a non-manifold edge.)
    pub closed: bool,
    /// Every edge used by two of the shell's triangles is traversed in opposite directions.
    pub oriented: bool,
    /// Genus `(2 − χ) / 2` of a closed, oriented shell; `None` for an open or inconsistently
    /// oriented shell, or a χ that no closed orientable surface has (a pinched vertex counts
    /// once in V, so it lowers the genus it would otherwise have).
    pub genus: Option<u64>,
    /// Signed volume enclosed, by the divergence theorem relative to the mesh's box centre.
    /// Positive for a closed shell facing outward.
    pub volume: f64,
    /// A closed, oriented shell of negative volume that bounds a hole inside the solid: the
    /// other closed shells wind once around it (a sphere minus a smaller sphere within it has
    /// an outer shell and a cavity). Such a shell is correctly oriented.
    pub cavity: bool,
}

impl MeshReport {
    /// A triangle is degenerate when twice its area is at most this many units of rounding:
    /// `ε · Σ |corner| · |opposite edge|`.
    pub const ZERO_AREA_ULPS: f64 = 32.0;

    /// True when the mesh bounds a valid solid: closed, every edge used by two triangles in
    /// opposite directions, every vertex a single fan, no degenerate triangles, no invalid
    /// indices or non-finite coordinates, and every shell facing outward (cavities included).
    /// The empty mesh counts as closed (the empty solid).
    pub fn is_closed_manifold(&self) -> bool {
        self.closed
            && self.oriented
            && self.outward
            && self.non_manifold_vertices == 0
            && self.degenerate_triangles == 0
            && self.invalid_index_triangles == 0
            && self.non_finite_vertices == 0
    }
}

impl Mesh {
    /// A validation report on this mesh (see [`MeshReport`] for what is counted and how).
    ///
    /// Costs `O(n log n)` for `n` triangles, plus, only for a closed shell of negative volume,
    /// a winding-number test against the closed shells whose boxes hold it (to tell a cavity
    /// from an inside-out solid). Never panics, whatever the indices or coordinates.
    ///
    /// ```
    /// let mesh = bspcsg::Solid::cube(1.0)?.to_mesh();
    /// let report = mesh.report();
    /// assert!(report.is_closed_manifold());
    /// assert_eq!((report.shells.len(), report.genus), (1, Some(0)));
    /// # Ok::<(), bspcsg::Error>(())
    /// ```
    pub fn report(&self) -> MeshReport {
        report(self)
    }
}

fn report(mesh: &Mesh) -> MeshReport {
    let nv = mesh.positions.len();
    let tris = &mesh.triangles;
    let mut referenced = vec![false; nv];
    let mut usable = vec![false; tris.len()];
    let (mut degenerate, mut repeated, mut invalid) = (0, 0, 0);
    for (t, tri) in tris.iter().enumerate() {
        if tri.iter().any(|&i| i as usize >= nv) {
            invalid += 1;
            continue;
        }
        for &i in tri {
            referenced[i as usize] = true;
        }
        if has_repeat(tri) {
            repeated += 1;
            degenerate += 1;
            continue;
        }
        usable[t] = true;
        if is_zero_area(tri.map(|i| mesh.positions[i as usize])) {
            degenerate += 1;
        }
    }
    let mut bbox = Aabb::EMPTY;
    let (mut vertices, mut non_finite) = (0, 0);
    for (p, _) in mesh.positions.iter().zip(&referenced).filter(|(_, r)| **r) {
        vertices += 1;
        if p.is_finite() {
            bbox.grow(*p);
        } else {
            non_finite += 1;
        }
    }
    let centre = if bbox.is_empty() {
        DVec3::ZERO
    } else {
        bbox.center()
    };

    let table = EdgeTable::new(tris, |t| usable[t]);
    let mut tri_sets = DisjointSets::new(tris.len());
    // Corner `3t + k` is triangle t's k-th corner; corners joined across manifold edges make
    // the fans around each vertex.
    let mut corner_sets = DisjointSets::new(3 * tris.len());
    let counts = table.counts();
    for run in table.runs() {
        if let &[(_, x), (_, y)] = run {
            let (s, t) = (x >> 1, y >> 1);
            tri_sets.union(s, t);
            for v in [tris[s][0], tris[s][1], tris[s][2]] {
                if let (Some(ks), Some(kt)) = (corner_of(&tris[s], v), corner_of(&tris[t], v)) {
                    corner_sets.union(3 * s + ks, 3 * t + kt);
                }
            }
        }
    }
    let mut fans = vec![0u32; nv];
    for (t, tri) in tris.iter().enumerate().filter(|(t, _)| usable[*t]) {
        for (k, &v) in tri.iter().enumerate() {
            if corner_sets.find(3 * t + k) == 3 * t + k {
                fans[v as usize] += 1;
            }
        }
    }
    let non_manifold_vertices = fans.iter().filter(|&&f| f > 1).count();

    let shells = shells(mesh, &usable, &table, &mut tri_sets, centre);
    let volume = shells.iter().map(|s| s.volume).sum();
    let inverted_shells = shells
        .iter()
        .filter(|s| s.closed && s.oriented && !(s.volume > 0.0 || s.cavity))
        .count();
    let genus: Option<u64> = shells.iter().map(|s| s.genus).sum();
    MeshReport {
        triangles: tris.len(),
        vertices,
        edges: counts.edges,
        boundary_edges: counts.boundary,
        non_manifold_edges: counts.non_manifold,
        inconsistent_edges: counts.inconsistent,
        degenerate_triangles: degenerate,
        repeated_index_triangles: repeated,
        invalid_index_triangles: invalid,
        non_finite_vertices: non_finite,
        non_manifold_vertices,
        shells,
        genus,
        volume,
        closed: counts.boundary == 0 && counts.non_manifold == 0,
        oriented: counts.inconsistent == 0,
        outward: inverted_shells == 0,
        inverted_shells,
    }
}

/// Per-shell figures, shells numbered by their first triangle.
fn shells(
    mesh: &Mesh,
    usable: &[bool],
    table: &EdgeTable,
    tri_sets: &mut DisjointSets,
    centre: DVec3,
) -> Vec<ShellReport> {
    let tris = &mesh.triangles;
    const NONE: usize = usize::MAX;
    let mut shell_of_root = vec![NONE; tris.len()];
    let mut shell_of = vec![NONE; tris.len()];
    let mut out: Vec<ShellReport> = Vec::new();
    let mut boxes: Vec<Aabb> = Vec::new();
    for t in (0..tris.len()).filter(|&t| usable[t]) {
        let root = tri_sets.find(t);
        if shell_of_root[root] == NONE {
            shell_of_root[root] = out.len();
            out.push(ShellReport {
                triangles: 0,
                vertices: 0,
                edges: 0,
                euler_characteristic: 0,
                closed: true,
                oriented: true,
                genus: None,
                volume: 0.0,
                cavity: false,
            });
            boxes.push(Aabb::EMPTY);
        }
        let s = shell_of_root[root];
        shell_of[t] = s;
        let [a, b, c] = tris[t].map(|i| mesh.positions[i as usize]);
        out[s].triangles += 1;
        out[s].volume += (a - centre).dot((b - centre).cross(c - centre));
        for p in [a, b, c] {
            boxes[s].grow(p);
        }
    }

    // Edges per shell. An edge of several shells counts in each; each shell must use it
    // exactly twice, in opposite directions, to be closed and oriented.
    let mut uses: Vec<(usize, usize)> = Vec::new();
    for run in table.runs() {
        uses.clear();
        uses.extend(run.iter().map(|&(_, tag)| (shell_of[tag >> 1], tag & 1)));
        uses.sort_unstable();
        for group in uses.chunk_by(|x, y| x.0 == y.0) {
            let shell = &mut out[group[0].0];
            shell.edges += 1;
            match group {
                [(_, x), (_, y)] => shell.oriented &= x != y,
                _ => shell.closed = false,
            }
        }
    }

    // Distinct vertices per shell.
    let mut pairs: Vec<(usize, u32)> = (0..tris.len())
        .filter(|&t| usable[t])
        .flat_map(|t| tris[t].map(|v| (shell_of[t], v)))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    for &(s, _) in &pairs {
        out[s].vertices += 1;
    }

    for s in &mut out {
        s.volume /= 6.0;
        s.euler_characteristic = s.vertices as i64 - s.edges as i64 + s.triangles as i64;
        let twice_genus = 2 - s.euler_characteristic;
        s.genus = (s.closed && s.oriented && twice_genus >= 0 && twice_genus % 2 == 0)
            .then_some(twice_genus as u64 / 2);
    }
    find_cavities(mesh, usable, &shell_of, &boxes, &mut out, centre);
    out
}

/// Marks the closed, oriented shells of negative volume around which the other closed,
/// oriented shells wind exactly once: holes in a solid, not inside-out solids.
///
/// In a valid solid the winding number is 1 in material and 0 outside, and a shell's own
/// winding number is ±1 inside it, so a shell facing inward must have the others winding once
/// around it. Only shells whose boxes hold the test point can wind around it.
fn find_cavities(
    mesh: &Mesh,
    usable: &[bool],
    shell_of: &[usize],
    boxes: &[Aabb],
    shells: &mut [ShellReport],
    centre: DVec3,
) {
    let sound = |s: &ShellReport| s.closed && s.oriented;
    let negative: Vec<usize> = (0..shells.len())
        .filter(|&s| sound(&shells[s]) && shells[s].volume < 0.0)
        .collect();
    // Only a shell of positive volume can make the others wind once around anything.
    if negative.is_empty() || !shells.iter().any(|s| sound(s) && s.volume > 0.0) {
        return;
    }
    // Triangles grouped by shell (counting sort), and each shell's largest triangle, whose
    // centroid is the point least likely to lie on another shell.
    let tris = &mesh.triangles;
    let mut start = vec![0usize; shells.len() + 1];
    let mut largest: Vec<Option<(f64, usize)>> = vec![None; shells.len()];
    for t in (0..tris.len()).filter(|&t| usable[t]) {
        let s = shell_of[t];
        start[s + 1] += 1;
        let [a, b, c] = tris[t].map(|i| mesh.positions[i as usize] - centre);
        let area = (b - a).cross(c - a).length_squared();
        if largest[s].is_none_or(|(best, _)| area > best) {
            largest[s] = Some((area, t));
        }
    }
    for s in 0..shells.len() {
        start[s + 1] += start[s];
    }
    let mut fill = start.clone();
    let mut by_shell = vec![0usize; start[shells.len()]];
    for t in (0..tris.len()).filter(|&t| usable[t]) {
        by_shell[fill[shell_of[t]]] = t;
        fill[shell_of[t]] += 1;
    }
    for s in negative {
        let Some((_, t)) = largest[s] else { continue };
        let [a, b, c] = tris[t].map(|i| mesh.positions[i as usize] - centre);
        let p = (a + b + c) / 3.0;
        let mut winding = 0.0;
        for other in 0..shells.len() {
            if other == s || !sound(&shells[other]) || !boxes[other].contains_point(p + centre, 0.0)
            {
                continue;
            }
            for &t in &by_shell[start[other]..start[other + 1]] {
                let [a, b, c] = tris[t].map(|i| mesh.positions[i as usize] - centre);
                winding += solid_angle(a - p, b - p, c - p);
            }
        }
        shells[s].cavity = (winding / (4.0 * PI)).round() == 1.0;
    }
}

/// The corner (0, 1, 2) of `tri` holding vertex `v`.
fn corner_of(tri: &[u32; 3], v: u32) -> Option<usize> {
    tri.iter().position(|&i| i == v)
}

fn has_repeat(tri: &[u32; 3]) -> bool {
    tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]
}

/// True when twice the triangle's area is at most [`MeshReport::ZERO_AREA_ULPS`] units of the
/// rounding its corners carry. Coordinates are first scaled by a power of two (exact) so that
/// nothing overflows or underflows.
pub(crate) fn is_zero_area([a, b, c]: [DVec3; 3]) -> bool {
    let reach = a.abs().max(b.abs()).max(c.abs()).max_element();
    if !reach.is_finite() {
        return false;
    }
    if reach == 0.0 {
        return true;
    }
    let s = crate::geom::unit_scale(reach);
    let (a, b, c) = (a * s, b * s, c * s);
    // Cross the two shorter edges, at the corner opposite the longest: differences taken at a
    // far corner would round the near corners together.
    let (ab, bc, ca) = (
        (b - a).length_squared(),
        (c - b).length_squared(),
        (a - c).length_squared(),
    );
    let twice = if ab >= bc && ab >= ca {
        (a - c).cross(b - c).length()
    } else if bc >= ca {
        (b - a).cross(c - a).length()
    } else {
        (c - b).cross(a - b).length()
    };
    let rounding = a.length() * (b - c).length()
        + b.length() * (c - a).length()
        + c.length() * (a - b).length();
    twice <= MeshReport::ZERO_AREA_ULPS * f64::EPSILON * rounding
}

/// The half-edges of a set of faces, sorted so that the uses of each undirected edge are
/// adjacent. Each entry is `(edge key, face << 1 | forward)`, where the key packs the smaller
/// and larger vertex index and `forward` says the face runs from the smaller to the larger.
pub(crate) struct EdgeTable {
    half: Vec<(u64, usize)>,
}

/// How many edges of each kind an [`EdgeTable`] holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct EdgeCounts {
    pub edges: usize,
    /// Used by one face.
    pub boundary: usize,
    /// Used by more than two faces.
    pub non_manifold: usize,
    /// Used by two faces in the same direction.
    pub inconsistent: usize,
}

impl EdgeTable {
    /// The table of the faces `f` for which `include(f)` holds. Faces must have distinct
    /// indices (a repeated one would make a loop edge).
    pub fn new<F: AsRef<[u32]>>(faces: &[F], include: impl Fn(usize) -> bool) -> Self {
        let mut half = Vec::with_capacity(3 * faces.len());
        for (f, face) in faces.iter().enumerate().filter(|(f, _)| include(*f)) {
            let face = face.as_ref();
            for (k, &a) in face.iter().enumerate() {
                let b = face[(k + 1) % face.len()];
                let (lo, hi) = (a.min(b), a.max(b));
                half.push((
                    (u64::from(lo) << 32) | u64::from(hi),
                    (f << 1) | usize::from(a < b),
                ));
            }
        }
        half.sort_unstable_by_key(|h| h.0);
        EdgeTable { half }
    }

    /// The uses of each undirected edge, one slice per edge.
    pub fn runs(&self) -> impl Iterator<Item = &[(u64, usize)]> {
        self.half.chunk_by(|x, y| x.0 == y.0)
    }

    /// Counts edges by kind.
    pub fn counts(&self) -> EdgeCounts {
        let mut c = EdgeCounts::default();
        for run in self.runs() {
            c.edges += 1;
            match run {
                [_] => c.boundary += 1,
                [(_, x), (_, y)] => c.inconsistent += usize::from((x ^ y) & 1 == 0),
                _ => c.non_manifold += 1,
            }
        }
        c
    }
}

/// Refuses positions with a NaN or infinite coordinate, among those for which `used` holds.
pub(crate) fn check_finite(positions: &[DVec3], used: impl Fn(usize) -> bool) -> Result<()> {
    let bad = |i: &usize| used(*i) && !positions[*i].is_finite();
    let count = (0..positions.len()).filter(bad).count();
    if let Some(first) = (0..positions.len()).find(bad) {
        return Err(Error::InvalidMesh(format!(
            "vertices with a non-finite coordinate: {count} (first: vertex {first} = {})",
            positions[first]
        )));
    }
    let far = |i: &usize| used(*i) && positions[*i].abs().max_element() > MAX_COORDINATE;
    let count = (0..positions.len()).filter(far).count();
    match (0..positions.len()).find(far) {
        Some(first) => Err(Error::InvalidMesh(format!(
            "vertices beyond the supported range of ±{MAX_COORDINATE:e}: {count} (first: vertex \
             {first} = [{:e}, {:e}, {:e}]); scale the mesh down",
            positions[first].x, positions[first].y, positions[first].z
        ))),
        None => Ok(()),
    }
}

/// Refuses faces with fewer than three indices or an index out of range, and unless
/// `allow_repeats`, faces that repeat an index.
pub(crate) fn check_face_indices<F: AsRef<[u32]>>(
    faces: &[F],
    vertex_count: usize,
    allow_repeats: bool,
) -> Result<()> {
    if let Some((f, face)) = faces.iter().enumerate().find(|(_, f)| f.as_ref().len() < 3) {
        return Err(Error::InvalidMesh(format!(
            "face {f} has {} indices; a face needs at least 3",
            face.as_ref().len()
        )));
    }
    let out_of_range = |f: &F| f.as_ref().iter().any(|&i| i as usize >= vertex_count);
    let bad = faces.iter().filter(|f| out_of_range(f)).count();
    if let Some(first) = faces.iter().position(out_of_range) {
        let index = faces[first]
            .as_ref()
            .iter()
            .copied()
            .find(|&i| i as usize >= vertex_count)
            .unwrap_or_default();
        return Err(Error::InvalidMesh(format!(
            "faces with a vertex index out of range: {bad} (first: face {first} uses {index}, \
             but there are only {vertex_count} vertices)"
        )));
    }
    if !allow_repeats {
        let bad = faces.iter().filter(|f| repeats(f.as_ref())).count();
        if let Some(first) = faces.iter().position(|f| repeats(f.as_ref())) {
            return Err(Error::InvalidMesh(format!(
                "faces that repeat a vertex index: {bad} (first: face {first} = {:?})",
                faces[first].as_ref()
            )));
        }
    }
    Ok(())
}

/// True when a face uses some index twice: pairwise for small faces, by sorting for large ones.
pub(crate) fn repeats(face: &[u32]) -> bool {
    if face.len() <= 16 {
        face.iter()
            .enumerate()
            .any(|(k, i)| face[k + 1..].contains(i))
    } else {
        let mut sorted = face.to_vec();
        sorted.sort_unstable();
        sorted.windows(2).any(|w| w[0] == w[1])
    }
}

/// Refuses faces that do not close up: every edge must be used by exactly two faces, in
/// opposite directions. Faces must have passed [`check_face_indices`] without repeats.
pub(crate) fn check_closed<F: AsRef<[u32]>>(faces: &[F]) -> Result<()> {
    let c = EdgeTable::new(faces, |_| true).counts();
    let defects: Vec<String> = [
        (c.boundary, "boundary edges"),
        (c.non_manifold, "non-manifold edges"),
        (c.inconsistent, "inconsistently oriented edges"),
    ]
    .into_iter()
    .filter(|&(n, _)| n > 0)
    .map(|(n, what)| format!("{n} {what}"))
    .collect();
    if defects.is_empty() {
        Ok(())
    } else {
        Err(Error::InvalidMesh(format!(
            "not closed: {} (of {} edges)",
            defects.join(", "),
            c.edges
        )))
    }
}

impl fmt::Display for MeshReport {
    /// A compact summary: one line of counts and verdict, then one line per kind of defect
    /// found.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let plural =
            |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
        write!(
            f,
            "{}, {}, {}, {}: ",
            plural(self.triangles, "triangle", "triangles"),
            plural(self.vertices, "vertex", "vertices"),
            plural(self.edges, "edge", "edges"),
            plural(self.shells.len(), "shell", "shells"),
        )?;
        if self.is_closed_manifold() {
            f.write_str("closed 2-manifold")?;
        } else {
            f.write_str("NOT a closed 2-manifold")?;
        }
        match self.genus {
            Some(g) => write!(f, ", genus {g}")?,
            None => f.write_str(", genus undefined")?,
        }
        write!(f, ", volume {}", Number(self.volume))?;
        let cavities = self.shells.iter().filter(|s| s.cavity).count();
        if cavities > 0 {
            write!(f, ", {}", plural(cavities, "cavity", "cavities"))?;
        }
        let defects = [
            (self.boundary_edges, "boundary edges"),
            (
                self.non_manifold_edges,
                "non-manifold edges (more than two triangles)",
            ),
            (self.inconsistent_edges, "inconsistently oriented edges"),
            (self.non_manifold_vertices, "non-manifold vertices"),
            (
                self.invalid_index_triangles,
                "triangles with an index out of range",
            ),
            (
                self.non_finite_vertices,
                "vertices with a non-finite coordinate",
            ),
            (
                self.inverted_shells,
                "closed shells of non-positive volume (inside out or flat)",
            ),
        ];
        for (n, what) in defects.iter().filter(|(n, _)| *n > 0) {
            write!(f, "\n  {what}: {n}")?;
        }
        let (degenerate, repeated) = (self.degenerate_triangles, self.repeated_index_triangles);
        if repeated == 0 && degenerate > 0 {
            write!(f, "\n  degenerate triangles (zero area): {degenerate}")?;
        } else if repeated == degenerate && degenerate > 0 {
            write!(f, "\n  degenerate triangles (repeated index): {degenerate}")?;
        } else if degenerate > 0 {
            write!(
                f,
                "\n  degenerate triangles: {degenerate} ({repeated} repeat an index, the rest \
                 have zero area)"
            )?;
        }
        Ok(())
    }
}

/// A number printed plainly, or in scientific notation when very large or small (a box out to
/// 10³⁸ has a volume of 81 digits).
struct Number(f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0.abs();
        if v == 0.0 || (1e-4..1e9).contains(&v) || !v.is_finite() {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra() -> Mesh {
        Mesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        )
    }

    #[test]
    fn tetrahedron() {
        let r = tetra().report();
        assert!(r.is_closed_manifold(), "{r}");
        assert_eq!((r.triangles, r.vertices, r.edges), (4, 4, 6));
        assert_eq!(r.genus, Some(0));
        assert_eq!(r.shells[0].euler_characteristic, 2);
        assert!((r.volume - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn zero_area_is_scale_free() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        let fat = [DVec3::ZERO, DVec3::X, DVec3::Y];
        for scale in [1e-200, 1e-6, 1.0, 1e6, 1e200] {
            assert!(is_zero_area(line.map(|p| p * scale)));
            assert!(!is_zero_area(fat.map(|p| p * scale)), "{scale}");
        }
        // A cap whose apex is off the base by about its own rounding is flat; by 10⁻¹³, not.
        let cap = |h: f64, at: DVec3| [at, at + DVec3::X, at + DVec3::new(0.5, h, 0.0)];
        assert!(is_zero_area(cap(1e-15, DVec3::ZERO)));
        assert!(!is_zero_area(cap(1e-13, DVec3::ZERO)));
        // A million units from the origin, corners carry 10⁻¹⁰ of rounding.
        assert!(is_zero_area(cap(1e-11, DVec3::splat(1e6))));
        assert!(!is_zero_area(cap(1e-7, DVec3::splat(1e6))));
        // Thin is not flat: a 1-wide base joined to a corner 10³⁸ away has area 10³⁸.
        let far = [DVec3::ZERO, DVec3::X, DVec3::new(3e38, 3e38, 0.0)];
        assert!(!is_zero_area(far));
        assert!(is_zero_area([DVec3::ONE; 3]));
        assert!(!is_zero_area([DVec3::ZERO, DVec3::X, DVec3::NAN]));
    }

    #[test]
    fn out_of_range_and_non_finite_do_not_panic() {
        let mut m = tetra();
        m.triangles.push([0, 1, 99]);
        m.positions[3] = DVec3::new(f64::NAN, 0.0, 0.0);
        let r = m.report();
        assert_eq!(r.invalid_index_triangles, 1);
        assert_eq!(r.non_finite_vertices, 1);
        assert!(!r.is_closed_manifold());
    }

    #[test]
    fn collapsed_triangle_between_good_ones() {
        // A tetrahedron with one extra triangle [0, 0, 1]: degenerate, but the rest is closed.
        let mut m = tetra();
        m.triangles.push([0, 0, 1]);
        let r = m.report();
        assert_eq!((r.degenerate_triangles, r.repeated_index_triangles), (1, 1));
        assert!(r.closed && r.oriented);
        assert_eq!(r.genus, Some(0));
    }

    #[test]
    fn polygon_faces_close() {
        let quad_pyramid: [&[u32]; 5] = [
            &[0, 3, 2, 1],
            &[0, 1, 4],
            &[1, 2, 4],
            &[2, 3, 4],
            &[3, 0, 4],
        ];
        assert!(check_closed(&quad_pyramid).is_ok());
        let open: [&[u32]; 4] = [&[0, 3, 2, 1], &[0, 1, 4], &[1, 2, 4], &[2, 3, 4]];
        let e = check_closed(&open).unwrap_err().to_string();
        assert!(e.contains("3 boundary edges"), "{e}");
    }

    #[test]
    fn repeats_small_and_large() {
        assert!(repeats(&[1, 2, 1]));
        assert!(!repeats(&[1, 2, 3]));
        let big: Vec<u32> = (0..40).collect();
        assert!(!repeats(&big));
        let mut twice = big.clone();
        twice.push(17);
        assert!(repeats(&twice));
    }
}
