//! Turning a boolean's polygon soup into a closed 2-manifold triangle mesh.
//!
//! A BSP boolean leaves T-junctions (a split polygon's new vertex lies in the middle of a
//! neighbour's edge), near-duplicate vertices (the same point computed along two paths) and
//! many coplanar slivers. The steps, each in its own module:
//!
//! 1. **Weld** positions within `δ` (a few plane tolerances) and drop polygons that collapse.
//! 2. **T-junctions**: every vertex within `δ` of another polygon's edge is inserted into it
//!    ([`tjunction`]). Now every edge is used by both polygons beside it.
//! 3. **Regions**: edge-adjacent polygons of one source in one plane merge; their shared edges
//!    cancel, leaving each region's boundary. A vertex that only passes straight through on
//!    every boundary it lies on is dropped from all of them at once, so neighbours stay matched
//!    ([`regions`], [`straight`]).
//! 4. **Triangulate** each region by constrained Delaunay triangulation of its boundary: no
//!    zero-area triangles, no new vertices (`mesh::triangulate`). A region whose boundary crosses
//!    itself keeps its polygons instead.
//! 5. **Shells**: a triangle and its reverse (a sliver thinner than the weld, laid flat as a fin),
//!    and four triangles closing a flat tetrahedron within a weld of one plane (a quad's two
//!    triangulations, or a triangle folded over a sliver), are dropped together ([`fins`]);
//!    half-edges are paired (around an edge shared by more than two triangles, by angle, so each
//!    pair encloses solid) and every vertex is split into one copy per fan of triangles around
//!    it. Solids touching along an edge or at a vertex come out as separate manifold shells
//!    ([`shells`]).
//!
//! One pass runs these steps ([`pass`]); this module chooses which passes run (wider welds
//! around cracks, the flat fill) and which one's mesh is kept.

mod buckets;
mod cracks;
mod discs;
mod edges;
mod fins;
mod grid;
mod indexed;
mod pass;
mod regions;
mod runs;
mod shells;
mod straight;
mod thin;
mod tjunction;

pub(crate) use discs::Links;
pub(crate) use shells::split_touching;

use glam::DVec3;
use smallvec::SmallVec;

use super::Mesh;
use super::weld::Wide;
use crate::geom::Tolerance;
use crate::polygon::Polygon;
use pass::{measured_repair, repair, tie_repair};

pub(crate) use indexed::Indexed;

/// Positions closer than this many plane tolerances are one vertex; a vertex this close to an
/// edge lies on it.
pub(crate) const WELD_TOLERANCES: f64 = 8.0;
/// Where the first weld leaves cracks, it is retried this many times, ten times wider each.
///
/// One point can be computed two ways: where an edge of A crosses a face of B (well
/// conditioned), and where the traces of A's two faces beside that edge meet on B's face, which
/// is off by about a rounding error over their dihedral angle. For the nearly flat neighbours
/// of tessellated CAD models (fandisk: 10⁻⁵ rad) that is 10⁻⁹ of the model, beyond the first
/// weld. The widest weld stays near 10⁻⁷ of the model.
const WELD_RETRIES: u32 = 4;

/// The most crack points (ends of edges used by one triangle) after the full first pass for
/// which the wider welds and the flat fill are tried.
///
/// Both are local repairs: a point computed two ways a little beyond the first weld, a slit
/// between two cut lines. Measured over the whole test suite, every result they closed had at
/// most 118 crack points after the full pass. Where thousands are left, the operands disagree
/// along whole crossing lines (a 32×16 sphere less itself turned 1e-4°, before both cut its
/// facets on one line: 3618 crack points; 512×256: 3 minutes and 2.3 GB of retries, none
/// closed), and each retry costs a whole repair
/// pass: such a result is returned open, for the caller to refuse.
///
/// It also ends the repair after the indexed or the quick pass where that leaves more: no later
/// pass came below it. Measured over the test suite and the 900 cross-check cases, every
/// result a later pass closed had at most 100 crack points after the first, and the passes after
/// a first one over the limit left nearly as many (1942 → 1912, 8740 → 8600; a 512×256 sphere
/// less itself turned 1e-4°: 492,992 → 492,584, the full pass 25 of the 58 s).
const WIDEN_CRACKS: usize = 1024;

/// How far beyond the region where a boolean's operands met (as a multiple of its diagonal) a
/// shell's own size still sets the needle pass's bound on its moves in `to_mesh`. A union's
/// shell is often a few times that region (a box joined at one corner of another): judged by
/// the region alone, a triangle the report counts as a needle by its shell was left (a spike
/// 1.5e-8 long on a shell 3.5 times the region). Beyond it the region caps the scale, so a
/// part joined to a box 10³⁸ across keeps its well-shaped triangles: the moves are then at most
/// 32 × 10⁻⁶ of the region's diagonal, and only thin needles by the shell's diagonal are
/// removed (see [`super::needles::remove_needles`]).
pub(crate) const NEEDLE_REGION_REACH: f64 = 16.0;

/// A polygon as a ring of welded vertex indices, with the polygon it came from.
#[derive(Clone, Debug)]
pub(crate) struct Ring {
    pub verts: SmallVec<[u32; 8]>,
    pub polygon: u32,
}

/// The repaired mesh of a closed polygon soup whose booleans used plane tolerance `eps`.
///
/// Where the boolean kept its far parts indexed (`index`), the first pass repairs only the rim
/// and the cut polygons and passes the core's fans through ([`indexed`]); if that leaves cracks,
/// every polygon takes the passes below. Otherwise the first pass searches for T-junctions only
/// on edges not already matched; if it leaves cracks (edges used by one triangle), a pass
/// searches every edge, taken where it leaves a closed 2-manifold even with cracks listed (see
/// [`closed_at_first_weld`]). Any pass that leaves more than [`WIDEN_CRACKS`] crack points ends the
/// repair, its mesh returned open (the indexed or quick pass too: no later one closes such a
/// mesh). Where a few cracks remain, a pass first fills the flat ones (taken only if that closes
/// the mesh); else each further pass lets the points near them weld and join edges ten times
/// farther, and the pass with the fewest cracks is kept; where none closes the mesh, a last pass
/// at the first weld orders tied sheets about crowded edges to alternate (taken only if that
/// closes it, see [`tie_repair`]). Every pass drops closed shells thinner than the weld (see
/// [`thin`]).
pub(crate) fn polygons_to_mesh(polygons: &[Polygon], eps: f64, index: Option<&Indexed>) -> Mesh {
    counted_repair(polygons, eps, index).0
}

/// [`polygons_to_mesh`], and how many repair passes it took (the indexed one included): at
/// most `2 × WELD_RETRIES + 6`, and one where the first pass leaves more than [`WIDEN_CRACKS`]
/// crack points (three where a later one does).
fn counted_repair(polygons: &[Polygon], eps: f64, index: Option<&Indexed>) -> (Mesh, u32) {
    if polygons.is_empty() {
        return (Mesh::default(), 0);
    }
    let delta = WELD_TOLERANCES * eps;
    // Needles are judged at the scale of the shell, as the report judges them; the pass's moves
    // are bounded at no more than `NEEDLE_REGION_REACH` times the region the boolean worked in,
    // and beyond that scale only thin needles are removed (see
    // [`super::needles::remove_needles`]).
    let scale = Some(NEEDLE_REGION_REACH * eps / Tolerance::RELATIVE);
    let mut passes = u32::from(index.is_some());
    match index.and_then(|i| indexed::repair(polygons, i, delta)) {
        Some((mut mesh, cracks, known)) if cracks.is_empty() => {
            // The known triangles keep their places unless a shell is dropped.
            let dropped = thin::drop_thin_shells(&mut mesh, delta, usize::MAX);
            super::needles::remove_needles(&mut mesh, scale, (dropped == 0).then_some(&known));
            return (mesh, passes);
        }
        // Open, and so refused by every caller that needs a solid: removing its needles (a
        // sixth of the time at 256×128) would not change that.
        Some((mesh, cracks, _)) if cracks.len() > WIDEN_CRACKS => return (mesh, passes),
        _ => {}
    }
    let mut wide = Wide::default();
    // First the quick pass, then the full T-junction search at the same weld. A full pass that
    // leaves a closed 2-manifold all the same is taken as it is (see [`closed_at_first_weld`]).
    let (mut mesh, mut cracks) = repair(polygons, delta, &wide, true, false, None);
    passes += 1;
    if !cracks.is_empty() && cracks.len() <= WIDEN_CRACKS {
        (mesh, cracks) = repair(polygons, delta, &wide, false, false, None);
        passes += 1;
        if closed_at_first_weld(&mesh, &cracks) {
            cracks.clear();
        }
    }
    if cracks.is_empty() {
        super::needles::remove_needles(&mut mesh, scale, None);
        return (mesh, passes);
    }
    if cracks.len() > WIDEN_CRACKS {
        return (mesh, passes);
    }
    let mut best = Attempt::new(mesh, cracks.len(), polygons, delta);
    {
        // First the flat fill at the first weld (see [`cracks`]): where the cracks are the rims
        // of flat loops (a flap at a corner where four planes meet to rounding), it closes the
        // mesh and moves nothing. A wider weld would close them too, by welding the flap's
        // corners together, and so flatten any real wedge thinner than its reach that ends there
        // (a cube less itself turned 1e-7°: two wedges 3e-10 thick, 4 % of the volume). Taken
        // only where it leaves a closed 2-manifold.
        let (mesh, _) = repair(polygons, delta, &wide, false, false, Some(delta));
        passes += 1;
        best.take_if_clean(mesh);
    }
    // Wider welds around the cracks. A wide weld can also flatten a feature thinner than its
    // reach (a wedge 10⁻¹⁰ thick between faces crossing at a tiny angle), so a pass without
    // cracks still has to be a closed 2-manifold, and its weld must sweep no more volume than
    // the first weld explains, to be taken (see [`Attempt`]).
    let mut reach = delta;
    for _ in 0..WELD_RETRIES {
        if best.clean {
            break;
        }
        reach *= 10.0;
        wide.widen(&cracks, reach);
        let (mesh, swept);
        (mesh, cracks, swept) = measured_repair(polygons, delta, &wide, false, false);
        passes += 1;
        best.consider(mesh, cracks.len(), swept);
        if best.clean || cracks.is_empty() {
            break;
        }
        // Only where the weld alone leaves cracks are edges allowed their drag (see
        // [`pass::wide_drag`]): allowed always, it joined Havocglass8_left − _right's vertices to
        // edges they are not on, a flat shell where the weld alone closes the mesh.
        let (mesh, left, swept) = measured_repair(polygons, delta, &wide, false, true);
        passes += 1;
        best.consider(mesh, left.len(), swept);
        if best.clean {
            break;
        }
    }
    if !best.clean {
        // What no weld closes: slits between two cut lines of faces crossing at a tiny angle,
        // filled flat on the pass before any widening (see [`cracks`]). Its weld is the first
        // one: it sweeps nothing beyond it.
        let (mesh, left) = repair(polygons, delta, &Wide::default(), false, false, Some(reach));
        passes += 1;
        best.consider(mesh, left.len(), 0.0);
    }
    // Last, sheets touching across a gap thinner than the first weld, which it welded onto each
    // other: their triangles' angles about a crowded edge can tie and not alternate (see
    // `shells::around_edge`). Ordered to alternate, by the quick pass and then the full one,
    // taken only where that closes the mesh; they move nothing beyond the first weld.
    for quick in [true, false] {
        if !best.clean {
            let (mesh, _) = tie_repair(polygons, delta, quick);
            passes += 1;
            best.take_if_clean(mesh);
        }
    }
    let mut mesh = best.mesh;
    super::needles::remove_needles(&mut mesh, scale, None);
    (mesh, passes)
}

/// Whether a pass at the first weld left a closed 2-manifold despite its `cracks`, as the flat
/// fill's pass is taken ([`Attempt::take_if_clean`]): the pairing can leave an edge's two
/// half-edges without each other as twins where the edge is crowded, and the fans still join
/// them. Such a pass moved nothing beyond the first weld, and the flat fill's, another whole
/// pass, would only add to it. (A 256×128 sphere less itself turned 1e-4°: the full pass left 4
/// crack points on a closed 2-manifold; the flat fill's pass took 4.8 s more and filled nothing.)
fn closed_at_first_weld(mesh: &Mesh, cracks: &[DVec3]) -> bool {
    !cracks.is_empty() && mesh.report().is_closed_manifold()
}

/// Whether the indexed pass alone closes the mesh (no fallback to the full passes).
#[cfg(test)]
pub(crate) fn indexed_pass_closes(polygons: &[Polygon], eps: f64, index: &Indexed) -> bool {
    indexed::repair(polygons, index, WELD_TOLERANCES * eps).is_some_and(|(_, c, _)| c.is_empty())
}

/// How many first welds (`delta`) times the polygons' area a pass after the first may sweep
/// (see [`pass::swept_beyond`]): the first weld itself moves corners by up to `delta`.
const SWEPT_WELDS: f64 = 4.0;

/// The part of the polygons' volume a pass after the first may sweep besides: the volume a
/// boolean is checked to (the `booleans` fuzz target's slack).
const SWEPT_RELATIVE: f64 = 1e-9;

/// The best repair pass so far: a closed 2-manifold if any, else the one with fewest cracks.
///
/// A pass with a wider weld is taken as clean only where the volume its weld sweeps
/// ([`pass::swept_beyond`]) is within what the first weld explains: [`SWEPT_WELDS`] ×
/// `delta` × the polygons' area, plus [`SWEPT_RELATIVE`] of their volume. A wider weld is for
/// one point computed two ways a little apart, and sweeps next to nothing. Where it instead pulls the
/// two sides of a real feature thinner than its reach onto each other, it sweeps the feature:
/// a cube less itself turned 1e-6° about its diagonal is six wedges up to 1e-8 thick, which a
/// weld 1.4e-7 wide flattened into flat shells, dropped: an empty mesh, "closed" (at 2e-6° and
/// 3e-6°, 67 % and 33 % of the volume lost). Such a pass is passed over and the result stays
/// open, for the caller to refuse. (The polygons' own volume is no measure: where the first
/// pass leaves cracks it is 10–50 % off in those cases.)
struct Attempt {
    mesh: Mesh,
    cracks: usize,
    clean: bool,
    /// The most volume a pass's wider weld may sweep.
    slack: f64,
}

impl Attempt {
    fn new(mesh: Mesh, cracks: usize, polygons: &[Polygon], delta: f64) -> Self {
        let volume = crate::polygon::volume_of(polygons);
        let area: f64 = polygons.iter().map(|p| p.area().abs()).sum();
        Attempt {
            mesh,
            cracks,
            clean: false,
            slack: SWEPT_WELDS * delta * area + SWEPT_RELATIVE * volume.abs(),
        }
    }

    /// Takes `mesh` only if it is a closed 2-manifold (and nothing clean was taken before),
    /// whatever its crack list says: the pairing can leave an edge's two half-edges without
    /// each other as twins where the fill made its edge crowded, and the fans still join them
    /// (a cube less itself turned 3e-6°: 8 crack points on a closed mesh of the exact volume,
    /// passed over for a wider weld that flattened a wedge, 35 % of the volume). For the fill
    /// and the tie pass at the first weld, which move nothing.
    fn take_if_clean(&mut self, mesh: Mesh) {
        if !self.clean && mesh.report().is_closed_manifold() {
            self.clean = true;
            (self.mesh, self.cracks) = (mesh, 0);
        }
    }

    /// Takes `mesh` if it is a closed 2-manifold whose weld swept no more than the slack, else
    /// keeps it as the best open one if it has fewer cracks.
    fn consider(&mut self, mesh: Mesh, cracks: usize, swept: f64) {
        if self.clean {
            return;
        }
        if cracks == 0 && mesh.report().is_closed_manifold() {
            if swept <= self.slack {
                self.clean = true;
                (self.mesh, self.cracks) = (mesh, cracks);
            }
        } else if cracks < self.cracks {
            (self.mesh, self.cracks) = (mesh, cracks);
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::{Indexed, counted_repair};
    use crate::mesh::Mesh;
    use crate::polygon::Polygon;
    use crate::solid::Solid;

    /// The repair of `a` less itself turned by `degrees` about a skew axis, and its passes.
    fn turned_difference(a: Solid, degrees: f64) -> (Mesh, u32) {
        let b = a
            .clone()
            .rotate_axis_angle(DVec3::new(0.3, 1.0, 0.2), degrees)
            .unwrap();
        let d = a.difference(&b);
        counted_repair(d.polygons(), d.tolerance().eps(), d.index())
    }

    /// 1,500 separate triangles: 4,500 crack points, whichever pass repairs them.
    fn scattered_triangles() -> Vec<Polygon> {
        (0..1500)
            .map(|k| {
                let o = DVec3::new(f64::from(k % 50) * 3.0, f64::from(k / 50) * 3.0, 0.0);
                let corners = [o, o + DVec3::X, o + DVec3::new(0.2, 1.0, 0.5)];
                Polygon::new(&corners, 0).unwrap()
            })
            .collect()
    }

    /// Thousands of crack points end the repair after the first pass that leaves them (the
    /// quick one here, without an index), not two or eight: no later pass closes such a
    /// result. A soup of separate triangles stands for it. (The 32×16 and 64×32 spheres less
    /// themselves turned 1e-4° served here until their facets were cut on one crossing line by
    /// both operands, then the 256×128 one until its ring edges were cut at meets too: all now
    /// close.)
    #[test]
    fn cracks_along_whole_crossings_end_the_repair_early() {
        let (mesh, passes) = counted_repair(&scattered_triangles(), 1e-10, None);
        assert_eq!(passes, 1);
        assert!(mesh.report().boundary_edges > 1000);
    }

    /// The same where the indexed pass leaves them: it ends the repair itself (one pass), before
    /// the quick one. No boolean found still leaves that many after its indexed pass (a 256×128
    /// sphere less itself turned 1e-5° or 1e-6° leaves 39 or 362 boundary edges after the whole
    /// repair), so the index is made by hand: no core and no rim, every polygon a cut one.
    #[test]
    fn cracks_after_the_indexed_pass_end_the_repair_there() {
        let index = Indexed::default();
        let (mesh, passes) = counted_repair(&scattered_triangles(), 1e-10, Some(&index));
        assert_eq!(passes, 1);
        assert!(mesh.report().boundary_edges > 1000);
    }

    /// A 16×8 sphere less itself turned 1e-6° leaves a few cracks that no flat fill closes,
    /// and a wider weld does: more passes than the indexed, quick, full and flat-fill ones.
    /// (The cube less itself turned 5e-5° served here first: it closes by the flat fill. The
    /// 12-sided cylinder turned 1e-4° served next, until both operands cut its faces on one
    /// crossing line: it now closes in the first pass.)
    #[test]
    fn a_few_cracks_are_still_widened_and_closed() {
        let (mesh, passes) = turned_difference(Solid::sphere(1.0, 16, 8).unwrap(), 1e-6);
        assert!(passes >= 5, "{passes}");
        assert!(mesh.report().is_closed_manifold(), "{}", mesh.report());
    }

    /// A 32×16 sphere less itself turned 1e-6°: the full pass lists 8 crack points, yet its
    /// mesh is a closed 2-manifold (as at 256×128 turned 1e-4°, where the flat fill's pass
    /// after it cost a third of the repair). It is taken as it is: no pass after the full one.
    #[test]
    fn a_full_pass_that_closes_the_mesh_despite_its_cracks_is_the_last() {
        let a = Solid::sphere(1.0, 32, 16).unwrap();
        let b = a
            .clone()
            .rotate_axis_angle(DVec3::new(0.3, 1.0, 0.2), 1e-6)
            .unwrap();
        let d = a.difference(&b);
        let (mesh, passes) = counted_repair(d.polygons(), d.tolerance().eps(), d.index());
        let report = mesh.report();
        assert!(report.is_closed_manifold(), "{report}");
        assert_eq!(passes, 2 + u32::from(d.index().is_some()));
        // The slivers' volume: about 10⁻² of the 1e-4° case's (3.58e-7), as the angle.
        assert!((report.volume - 3.58e-9).abs() < 1e-2 * 3.58e-9, "{report}");
    }

    /// A cube less itself turned 5e-9°: slivers about the weld thick, which the weld flattened
    /// into four closed shells of no volume (inside out by the report). Dropped as empty, the
    /// rest is closed, and no volume is lost beyond the weld times the slivers' area.
    #[test]
    fn shells_thinner_than_the_weld_are_dropped() {
        let (mesh, _) = turned_difference(Solid::cube(1.0).unwrap(), 5e-9);
        let report = mesh.report();
        assert!(report.is_closed_manifold(), "{report}");
        assert_eq!(report.inverted_shells, 0, "{report}");
    }
}
