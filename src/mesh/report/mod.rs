//! The validation report of any indexed triangle mesh ([`Mesh::report`]): counts, defects,
//! shells, genus and orientation.
//!
//! Everything rests on the edge table of [`crate::topology`]; components and vertex fans then
//! come from union-find over triangles and triangle corners.

mod display;
mod shells;

use glam::DVec3;

use super::Mesh;
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, unit_scale};
use crate::topology::EdgeTable;

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
/// - **Zero area**: the triangle's area cannot be told from zero by computing it from the
///   coordinates as given: twice the area is at most [`ZERO_AREA_ULPS`](Self::ZERO_AREA_ULPS)
///   units of the rounding of that computation, `ε · |e₁| · |e₂|` for the two shorter edges
///   (their differences are exact or nearly so, and so is their cross product to that bound).
///   Scale-free and translation-free, so tiny, huge and far meshes are judged alike (a fine
///   watertight sphere 10¹² from the origin has no zero-area triangles, though booleans there
///   are beyond precision), exact zeros always count, and a needle that is merely thin (a
///   1-wide hole joined to corners 10³⁸ away) does not. (Booleans judge their own output more
///   strictly, by the rounding its computed corners carry where they sit, `ε · |corner|`.)
///
/// - A **needle** is a usable triangle whose area is below
///   [`NEEDLE_AREA`](Self::NEEDLE_AREA) × d², `d` the diagonal of its shell's bounding box:
///   not a defect of topology (a closed 2-manifold may hold needles), but of geometry that
///   slicers, meshers and manifold3d's cleanup treat as degenerate. Booleans and marching
///   cubes remove them wherever that changes no topology, except in a shell where removing
///   them all would change its volume beyond the needle pass's bound: there they remove only
///   the thin ones and specks of [`is_needle_to_remove`](crate::is_needle_to_remove), or
///   none, and the well-shaped faces of a shell thinner than a speck's reach stay (a prism
///   6.7·10⁶ long on a 6 × 3 end keeps its end triangles, counted here).
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
    /// Signed volume of all usable triangles by the divergence theorem: the sum of the shells'
    /// [volumes](ShellReport::volume), relative to the box centre where a shell is open.
    /// Meaningful only for closed, oriented meshes.
    pub volume: f64,
    /// No boundary edges and no non-manifold edges.
    pub closed: bool,
    /// No inconsistently oriented edges.
    pub oriented: bool,
    /// Every closed, consistently oriented shell faces outward: it encloses positive volume, or
    /// it is a [cavity](ShellReport::cavity). Open and inconsistent shells are not judged.
    pub outward: bool,
    /// Usable triangles of area below [`NEEDLE_AREA`](Self::NEEDLE_AREA) × (their shell's box
    /// diagonal)²; see the definitions above. Not counted as degenerate.
    pub needles: usize,
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
    /// Signed volume enclosed, by the divergence theorem relative to the shell's own first
    /// corner where it is closed and oriented (else to the mesh's box centre, where an open
    /// shell's figure depends on it). Positive for a closed shell facing outward.
    ///
    /// Summed about the mesh's box centre, each triangle's term is rounded by about ε |p − c|³,
    /// which swamps a small shell's volume away from the centre: a closed, outward sliver
    /// shell of 1.0e-18 beside a solid of 0.021 came out −9.5e-19, flat by its sign.
    pub volume: f64,
    /// A closed, oriented shell of negative volume that bounds a hole inside the solid: the
    /// other closed shells wind once around it (a sphere minus a smaller sphere within it has
    /// an outer shell and a cavity). Such a shell is correctly oriented.
    pub cavity: bool,
    /// Triangles of this shell that are [needles](MeshReport::needles).
    pub needles: usize,
}

impl MeshReport {
    /// A triangle is degenerate when twice its area is at most this many units of rounding:
    /// `ε · |e₁| · |e₂|`, its two shorter edges.
    pub const ZERO_AREA_ULPS: f64 = crate::geom::ZERO_AREA_ULPS;

    /// A triangle is a needle when its area is below this fraction of the square of its
    /// shell's bounding-box diagonal. 10⁻¹²: a long needle's apex then lies within twice the
    /// booleans' plane tolerance of its base, and a short one is a speck under 1.4·10⁻⁶ of the
    /// shell across (the crate docs, `# Needles`, give the reasoning).
    pub const NEEDLE_AREA: f64 = crate::geom::NEEDLE_AREA;

    /// True when the mesh bounds a valid solid: closed, every edge used by two triangles in
    /// opposite directions, every vertex a single fan, no degenerate triangles, no invalid
    /// indices or non-finite coordinates, and every shell facing outward (cavities included).
    /// The empty mesh counts as closed (the empty solid).
    #[must_use]
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
    #[must_use]
    pub fn report(&self) -> MeshReport {
        report(self)
    }
}

fn report(mesh: &Mesh) -> MeshReport {
    let tris = &mesh.triangles;
    let census = TriangleCensus::new(mesh);
    let (bbox, vertices, non_finite) = referenced_vertices(mesh, &census.referenced);
    let centre = if bbox.is_empty() {
        DVec3::ZERO
    } else {
        bbox.center()
    };
    let table = EdgeTable::new(tris, |t| census.usable[t]);
    let counts = table.counts();
    let mut tri_sets = DisjointSets::new(tris.len());
    let non_manifold_vertices = join_across_edges(mesh, &census.usable, &table, &mut tri_sets);
    let shells = shells::shells(mesh, &census.usable, &table, &mut tri_sets, centre);
    let volume = shells.iter().map(|s| s.volume).sum();
    let inverted_shells = shells
        .iter()
        .filter(|s| s.closed && s.oriented && !(s.volume > 0.0 || s.cavity))
        .count();
    let genus: Option<u64> = shells.iter().map(|s| s.genus).sum();
    let needles = shells.iter().map(|s| s.needles).sum();
    MeshReport {
        triangles: tris.len(),
        vertices,
        edges: counts.edges,
        boundary_edges: counts.boundary,
        non_manifold_edges: counts.non_manifold,
        inconsistent_edges: counts.inconsistent,
        degenerate_triangles: census.degenerate,
        repeated_index_triangles: census.repeated,
        invalid_index_triangles: census.invalid,
        non_finite_vertices: non_finite,
        non_manifold_vertices,
        shells,
        genus,
        volume,
        closed: counts.boundary == 0 && counts.non_manifold == 0,
        oriented: counts.inconsistent == 0,
        outward: inverted_shells == 0,
        inverted_shells,
        needles,
    }
}

/// Which triangles take part in topology, and why the others do not.
struct TriangleCensus {
    /// Per vertex: used by a triangle whose indices are all in range.
    referenced: Vec<bool>,
    /// Per triangle: indices in range and distinct.
    usable: Vec<bool>,
    degenerate: usize,
    repeated: usize,
    invalid: usize,
}

impl TriangleCensus {
    fn new(mesh: &Mesh) -> Self {
        let nv = mesh.positions.len();
        let tris = &mesh.triangles;
        let mut c = TriangleCensus {
            referenced: vec![false; nv],
            usable: vec![false; tris.len()],
            degenerate: 0,
            repeated: 0,
            invalid: 0,
        };
        for (t, tri) in tris.iter().enumerate() {
            if tri.iter().any(|&i| i as usize >= nv) {
                c.invalid += 1;
                continue;
            }
            for &i in tri {
                c.referenced[i as usize] = true;
            }
            if has_repeat(tri) {
                c.repeated += 1;
                c.degenerate += 1;
                continue;
            }
            c.usable[t] = true;
            if is_zero_area_as_given(tri.map(|i| mesh.positions[i as usize])) {
                c.degenerate += 1;
            }
        }
        c
    }
}

/// True when twice the triangle's area is at most [`MeshReport::ZERO_AREA_ULPS`] units of the
/// rounding of computing it from its corners as given: `ε · |e₁| · |e₂|`, the two shorter edges
/// crossed at their common corner. Edges are scaled by a power of two (exact) so that nothing
/// overflows or underflows.
fn is_zero_area_as_given([a, b, c]: [DVec3; 3]) -> bool {
    let (ab, bc, ca) = (b - a, c - b, a - c);
    // The corner opposite the longest edge, and its two edges (pointing away from it).
    let (l_ab, l_bc, l_ca) = (ab.length(), bc.length(), ca.length());
    let (e1, e2) = if l_ab >= l_bc && l_ab >= l_ca {
        (-bc, ca)
    } else if l_bc >= l_ca {
        (ab, -ca)
    } else {
        (bc, -ab)
    };
    let reach = e1.abs().max(e2.abs()).max_element();
    if !reach.is_finite() {
        return false;
    }
    if reach == 0.0 {
        return true;
    }
    let s = unit_scale(reach);
    let (e1, e2) = (e1 * s, e2 * s);
    e1.cross(e2).length() <= MeshReport::ZERO_AREA_ULPS * f64::EPSILON * e1.length() * e2.length()
}

/// The box of the referenced finite vertices, how many vertices are referenced, and how many of
/// those have a non-finite coordinate.
fn referenced_vertices(mesh: &Mesh, referenced: &[bool]) -> (Aabb, usize, usize) {
    let mut bbox = Aabb::EMPTY;
    let (mut vertices, mut non_finite) = (0, 0);
    for (p, _) in mesh.positions.iter().zip(referenced).filter(|(_, r)| **r) {
        vertices += 1;
        if p.is_finite() {
            bbox.grow(*p);
        } else {
            non_finite += 1;
        }
    }
    (bbox, vertices, non_finite)
}

/// Joins triangles (in `tri_sets`) and their corners across every edge used by exactly two
/// triangles, and returns the number of non-manifold vertices: those whose corners form more
/// than one fan.
fn join_across_edges(
    mesh: &Mesh,
    usable: &[bool],
    table: &EdgeTable,
    tri_sets: &mut DisjointSets,
) -> usize {
    let tris = &mesh.triangles;
    // Corner `3t + k` is triangle t's k-th corner; corners joined across manifold edges make
    // the fans around each vertex.
    let mut corner_sets = DisjointSets::new(3 * tris.len());
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
    let mut fans = vec![0u32; mesh.positions.len()];
    for (t, tri) in tris.iter().enumerate().filter(|(t, _)| usable[*t]) {
        for (k, &v) in tri.iter().enumerate() {
            if corner_sets.find(3 * t + k) == 3 * t + k {
                fans[v as usize] += 1;
            }
        }
    }
    fans.iter().filter(|&&f| f > 1).count()
}

/// The corner (0, 1, 2) of `tri` holding vertex `v`.
fn corner_of(tri: &[u32; 3], v: u32) -> Option<usize> {
    tri.iter().position(|&i| i == v)
}

fn has_repeat(tri: &[u32; 3]) -> bool {
    tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::is_zero_area_as_given;
    use crate::mesh::Mesh;

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
    fn zero_area_as_given_is_free_of_scale_and_place() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        // A small triangle: 0.05 across, its apex 0.04 off the base.
        let small = [DVec3::ZERO, DVec3::X * 0.05, DVec3::new(0.02, 0.04, 0.0)];
        let place = |t: [DVec3; 3], at: f64| t.map(|p| p + DVec3::splat(at));
        for at in [0.0, 1e6, 1e12] {
            assert!(is_zero_area_as_given(place(line, at)), "{at}");
            // 10¹² from the origin coordinates round to 1.2·10⁻⁴: the corners move a little,
            // the triangle keeps its area.
            assert!(!is_zero_area_as_given(place(small, at)), "{at}");
        }
        // At 10¹⁶ they round to 2: the small triangle collapses.
        assert!(is_zero_area_as_given(place(small, 1e16)));
        for scale in [1e-200, 1e-6, 1e6, 1e200] {
            assert!(is_zero_area_as_given(line.map(|p| p * scale)));
            assert!(!is_zero_area_as_given(small.map(|p| p * scale)), "{scale}");
        }
        let cap = |h: f64| [DVec3::ZERO, DVec3::X, DVec3::new(0.5, h, 0.0)];
        assert!(is_zero_area_as_given(cap(1e-15)));
        assert!(!is_zero_area_as_given(cap(1e-13)));
        // Thin is not flat: a 1-wide base joined to a corner 10³⁸ away.
        let far = [DVec3::ZERO, DVec3::X, DVec3::new(3e38, 3e38, 0.0)];
        assert!(!is_zero_area_as_given(far));
        assert!(is_zero_area_as_given([DVec3::ONE; 3]));
        assert!(!is_zero_area_as_given([DVec3::ZERO, DVec3::X, DVec3::NAN]));
    }
}
