//! Which corners of an exact solid's polygons are one vertex, and which polygons are around
//! each vertex: what a boolean needs to pass its far part on indexed (see `far.rs`), made once
//! per solid rather than once per boolean. A solid read from a mesh also holds here what each
//! boolean would otherwise make of it again: its polygons' boxes and their hierarchy (a
//! [`SurfaceIndex`]), the merge floor of each vertex ([`merge_floors`]), and what its fans
//! are ([`check_fans`]).
//!
//! A solid made from a mesh carries it from the start; an exact operand without one (a
//! primitive, a moved solid) has its vertex ids made by each boolean it enters (without the
//! rest).

use std::sync::OnceLock;

use crate::bsp::SurfaceIndex;
use crate::geom::{Aabb, is_zero_area};
use crate::hash::{KeyedHashMap, key};
use crate::mesh::needles::twice_area_squared;
use crate::polygon::{Polygon, bbox_of};

/// The vertex ids of a solid's polygon corners and the polygons around each vertex; for a
/// solid read from a mesh, also its polygons' [`SurfaceIndex`], merge floors and fan checks.
#[derive(Debug)]
pub(crate) struct VertexIds {
    /// Polygon `i`'s corners' ids are `ids[start[i]..start[i + 1]]`. Equal ids are equal
    /// positions bit for bit (−0 taken as +0), and equal positions equal ids.
    ids: Vec<u32>,
    start: Vec<u32>,
    vertices: usize,
    /// Whether the polygons are discs by position (a checked mesh's: see
    /// `mesh::import::MeshPolygons::discs_if_apart`).
    discs: bool,
    /// Whether no triangle of any polygon's fan from its first corner is of zero area (by
    /// `geom::is_zero_area`, on these corners in this order; see [`check_fans`]).
    fans: bool,
    /// The least twice area, squared, of a triangle of any polygon's fan from its first corner
    /// (as `mesh::needles::twice_area_squared` computes it; see [`check_fans`]), or 0 where
    /// not known.
    least_fan: f64,
    /// Made when first asked: at every read from a mesh ([`merge_floors`] asks it), and in a
    /// boolean only for an operand passed on indexed.
    around: OnceLock<Around>,
    /// Per vertex, a floor under the distance at which two polygons around it could be merged
    /// as coplanar (see [`merge_floors`]), where made (a solid read from a mesh).
    merge_floor: Option<Vec<f64>>,
    /// The polygons' boxes and their hierarchy, where made (a solid read from a mesh).
    surface_index: Option<SurfaceIndex>,
    /// The polygons' box, made with the surface index: what `Solid::bbox` gives, bit for bit.
    bbox: Option<Aabb>,
}

/// The polygons around vertex `v` are `list[at[v]..at[v + 1]]`, ascending (a polygon with a
/// repeated corner as often as it has it).
#[derive(Debug)]
struct Around {
    list: Vec<u32>,
    at: Vec<u32>,
}

impl VertexIds {
    /// The vertex ids of `polys`.
    pub(crate) fn new(polys: &[Polygon]) -> VertexIds {
        let mut id_of: KeyedHashMap<[u64; 3], u32> =
            KeyedHashMap::with_capacity_and_hasher(polys.len(), Default::default());
        let mut start = Vec::with_capacity(polys.len() + 1);
        let mut ids = Vec::with_capacity(3 * polys.len());
        for p in polys {
            start.push(ids.len() as u32);
            for &v in p.vertices() {
                let next = id_of.len() as u32;
                ids.push(*id_of.entry(key(v)).or_insert(next));
            }
        }
        start.push(ids.len() as u32);
        VertexIds {
            ids,
            start,
            vertices: id_of.len(),
            discs: false,
            fans: false,
            least_fan: 0.0,
            around: OnceLock::new(),
            merge_floor: None,
            surface_index: None,
            bbox: None,
        }
    }

    /// The table of polygons around each vertex, compressed by vertex id.
    fn make_around(&self) -> Around {
        let mut at = vec![0u32; self.vertices + 1];
        for &id in &self.ids {
            at[id as usize + 1] += 1;
        }
        for v in 0..self.vertices {
            at[v + 1] += at[v];
        }
        let mut fill = at.clone();
        let mut list = vec![0u32; self.ids.len()];
        for (i, s) in self.start.windows(2).enumerate() {
            for &id in &self.ids[s[0] as usize..s[1] as usize] {
                list[fill[id as usize] as usize] = i as u32;
                fill[id as usize] += 1;
            }
        }
        Around { list, at }
    }

    /// Whether these are the vertex ids of `polys` (its polygon and corner counts match).
    pub(crate) fn fits(&self, polys: &[Polygon]) -> bool {
        self.start.len() == polys.len() + 1
            && polys
                .iter()
                .zip(self.start.windows(2))
                .all(|(p, s)| p.vertices().len() == (s[1] - s[0]) as usize)
    }

    /// Polygon `i`'s corners' vertex ids.
    #[inline]
    pub(crate) fn corners(&self, i: usize) -> &[u32] {
        &self.ids[self.start[i] as usize..self.start[i + 1] as usize]
    }

    /// The polygons around vertex `v`.
    #[inline]
    pub(crate) fn around(&self, v: u32) -> &[u32] {
        let Around { list, at } = self.around.get_or_init(|| self.make_around());
        &list[at[v as usize] as usize..at[v as usize + 1] as usize]
    }

    pub(crate) fn vertex_count(&self) -> usize {
        self.vertices
    }

    /// Marks the polygons as discs by position, or not.
    pub(crate) fn set_discs(&mut self, discs: bool) {
        self.discs = discs;
    }

    /// Whether the polygons are discs by position.
    pub(crate) fn discs(&self) -> bool {
        self.discs
    }

    /// Records what [`check_fans`] found of every polygon's fan.
    pub(crate) fn set_fans(&mut self, (spans, least): (bool, f64)) {
        self.fans = spans;
        self.least_fan = least;
    }

    /// Whether no polygon's fan from its first corner has a triangle of zero area.
    pub(crate) fn fans(&self) -> bool {
        self.fans
    }

    /// The least twice area, squared, of a triangle of a polygon's fan (0 where not known).
    pub(crate) fn least_fan(&self) -> f64 {
        self.least_fan
    }

    /// Records [`merge_floors`] of `polys`, the polygons these are the ids of.
    pub(crate) fn set_merge_floors(&mut self, polys: &[Polygon]) {
        self.merge_floor = Some(merge_floors(polys, self));
    }

    /// Records the [`SurfaceIndex`] of `polys`, the polygons these are the ids of, and their
    /// box (`bbox_of`, as `Solid::bbox` makes it, so a boolean need not walk every corner for
    /// it: 1.5 M instructions per operand on rocker-arm).
    pub(crate) fn set_surface_index(&mut self, polys: &[Polygon]) {
        self.surface_index = Some(SurfaceIndex::new(polys));
        self.bbox = Some(bbox_of(polys));
    }

    /// The polygons' box, where made with the surface index.
    pub(crate) fn bbox(&self) -> Option<Aabb> {
        self.bbox
    }

    /// The polygons' boxes and hierarchy, where made.
    pub(crate) fn surface_index(&self) -> Option<&SurfaceIndex> {
        self.surface_index.as_ref()
    }

    /// Whether no two polygons around vertex `v` can be within `flat` of each other's plane
    /// (see [`merge_floors`]): false where not known.
    #[inline]
    pub(crate) fn apart_beyond(&self, v: u32, flat: f64) -> bool {
        self.merge_floor
            .as_ref()
            .is_some_and(|floor| floor[v as usize] > flat)
    }
}

/// The most polygons around a vertex whose pairs [`merge_floors`] compares: above it a
/// vertex's floor is 0 (not known), and a boolean's `keep_far` runs its own test there, once
/// per vertex it asks about, stopping at the first pair that merges. Bounds the work of
/// reading a mesh at `STAR_CAP` times its corners (a cone's apex around n triangles would
/// otherwise cost n²/2 pair tests at every read).
pub(crate) const STAR_CAP: usize = 32;

/// Per vertex, the least over pairs of polygons around it facing the same way (normals' dot
/// above 0) of the farthest any corner of one lies from the other's plane, the lesser of the
/// two ways round (∞ where no pair, or a distance is NaN; 0, not known, where more than
/// [`STAR_CAP`] polygons are around it). Two such polygons have every corner of one within
/// `flat` of the other's plane only where this is at most `flat`, whatever their sources: a
/// boolean's `keep_far` asks the full test (sources too) only there. Made once per solid read
/// from a mesh, not per boolean.
pub(crate) fn merge_floors(polys: &[Polygon], ids: &VertexIds) -> Vec<f64> {
    (0..ids.vertex_count() as u32)
        .map(|v| {
            let star = ids.around(v);
            if star.len() > STAR_CAP {
                return 0.0;
            }
            let mut least = f64::INFINITY;
            for (k, &x) in star.iter().enumerate() {
                let p = &polys[x as usize];
                for &y in &star[k + 1..] {
                    let q = &polys[y as usize];
                    if p.plane().normal.dot(q.plane().normal) > 0.0 {
                        least = least.min(reach(p, q).min(reach(q, p)));
                    }
                }
            }
            least
        })
        .collect()
}

/// How far `b`'s corners lie from `a`'s plane at most (∞ where a distance is NaN: never
/// within anything). `to_mesh` could merge the two as coplanar only where this is at most its
/// weld distance one way round or the other: [`merge_floors`] and a boolean's `keep_far` both
/// ask it, so they agree.
pub(crate) fn reach(a: &Polygon, b: &Polygon) -> f64 {
    b.vertices().iter().fold(0.0f64, |m, &v| {
        let d = a.plane().distance(v).abs();
        if d.is_nan() { f64::INFINITY } else { m.max(d) }
    })
}

/// Of the triangles of every polygon's fan from its first corner, `(v₀, vₖ, vₖ₊₁)`: whether
/// none is of zero area ([`is_zero_area`] on its corners in that order), and the least twice
/// area, squared ([`twice_area_squared`]). `to_mesh` asks both of a core polygon's fan, on the
/// same positions bit for bit where every corner is one of the core's own vertices, and takes
/// these answers instead (see `mesh::repair::indexed`).
pub(crate) fn check_fans(polys: &[Polygon]) -> (bool, f64) {
    let mut spans = true;
    let mut least = f64::INFINITY;
    for p in polys {
        let vs = p.vertices();
        for k in 1..vs.len() - 1 {
            let t = [vs[0], vs[k], vs[k + 1]];
            spans &= !is_zero_area(t);
            least = least.min(twice_area_squared(t));
        }
    }
    // NaN (a non-finite corner) is never at least anything.
    (spans, if least >= 0.0 { least } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn equal_positions_are_one_vertex() {
        let tri = |a: DVec3, b: DVec3, c: DVec3| Polygon::new(&[a, b, c], 0).unwrap();
        let (o, x, y, z) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
        let polys = [
            tri(o, y, x),
            tri(DVec3::new(-0.0, 0.0, 0.0), x, z),
            tri(o, z, y),
            tri(x, y, z),
        ];
        let t = VertexIds::new(&polys);
        assert!(t.fits(&polys) && !t.fits(&polys[1..]));
        assert_eq!(t.vertex_count(), 4);
        assert_eq!(t.corners(1), [0, 2, 3]);
        assert_eq!(t.around(0), [0, 1, 2]);
        assert_eq!(t.around(3), [1, 2, 3]);
    }

    /// Two triangles on an edge: in one plane, their shared corners' floor is 0 and the others'
    /// ∞ (no pair around them); folded up by 0.5 at the far corner, the floor is the lesser
    /// of that corner's height and the origin's distance from the folded plane, 1/√6; facing
    /// apart, ∞.
    #[test]
    fn merge_floors_are_the_nearest_pair_around_each_vertex() {
        let tri = |a: DVec3, b: DVec3, c: DVec3| Polygon::new(&[a, b, c], 0).unwrap();
        let (o, x, y) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let floors = |far: DVec3, flip: bool| {
            let mut second = tri(x, far, y);
            if flip {
                second = tri(x, y, far);
            }
            let polys = [tri(o, x, y), second];
            let ids = VertexIds::new(&polys);
            merge_floors(&polys, &ids)
        };
        let inf = f64::INFINITY;
        assert_eq!(
            floors(DVec3::new(1.0, 1.0, 0.0), false),
            [inf, 0.0, 0.0, inf]
        );
        let folded = floors(DVec3::new(1.0, 1.0, 0.5), false);
        assert!((folded[1] - 1.0 / 6f64.sqrt()).abs() < 1e-15, "{folded:?}");
        assert_eq!(folded[1], folded[2]);
        assert_eq!((folded[0], folded[3]), (inf, inf));
        assert_eq!(floors(DVec3::new(1.0, 1.0, 0.5), true), [inf; 4]);
    }

    /// A cone read from a mesh: with its apex among 16 triangles the apex's floor is known (the
    /// sides fold away from each other: above 0); among 64, more than [`STAR_CAP`], it is 0,
    /// not known, so `keep_far` runs its full test there.
    #[test]
    fn a_star_above_the_cap_has_no_floor() {
        let apex_floor = |segments: u32| {
            let mesh = crate::Solid::cone(1.0, 1.0, segments).unwrap().to_mesh();
            let solid = crate::Solid::from_mesh(&mesh).unwrap();
            let (polys, ids) = solid.into_parts();
            let ids = ids.unwrap();
            let apex = (0..ids.vertex_count() as u32)
                .max_by_key(|&v| ids.around(v).len())
                .unwrap();
            (
                ids.around(apex).len(),
                merge_floors(&polys, &ids)[apex as usize],
            )
        };
        let (star, floor) = apex_floor(16);
        assert!(star <= STAR_CAP && floor > 0.0, "{star} {floor}");
        let (star, floor) = apex_floor(64);
        assert!(star > STAR_CAP && floor == 0.0, "{star} {floor}");
    }

    /// A square of side 2 fans from its first corner into two right triangles of twice area 4:
    /// the least, squared, is 16. With a corner on an edge next to the first, a fan triangle
    /// has no area.
    #[test]
    fn fans_are_checked_from_the_first_corner() {
        let (o, x, y) = (DVec3::ZERO, 2.0 * DVec3::X, 2.0 * DVec3::Y);
        let square = Polygon::new(&[o, x, x + y, y], 0).unwrap();
        assert_eq!(check_fans(std::slice::from_ref(&square)), (true, 16.0));
        let beside = Polygon::new(&[o, x, x + y, y, 0.5 * y], 0).unwrap();
        let (spans, least) = check_fans(&[square, beside]);
        assert!(!spans);
        assert_eq!(least, 0.0);
        // Read from a mesh, a solid keeps what its polygons' fans are.
        let cube = crate::Solid::from_mesh(&crate::Solid::cube(2.0).unwrap().to_mesh()).unwrap();
        let ids = cube.into_parts().1.unwrap();
        assert!(ids.fans());
        assert_eq!(ids.least_fan(), 16.0);
    }
}
