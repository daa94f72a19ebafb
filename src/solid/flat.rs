//! A boolean's result that is a flat closed sheet: empty within the tolerance.
//!
//! Where the faces of two operands cross at a tiny angle, what is left between them can be a
//! sheet thinner than the weld (8 tolerances): two sides back to back, each side's polygons
//! within a weld of the other's, facing the other way. `to_mesh` welds the two sides onto each
//! other and drops the shell (`mesh/repair/thin.rs`); the mesh is empty. Passed on as polygons
//! to a later boolean, though, both sides lie on the other operand's face within the tolerance,
//! and the coplanar rule sends each by the way it faces: one side is kept, the other dropped,
//! and the result is an open surface whose "volume" is its area times its lever (an
//! intersection with a slab through such a sheet came out 7.9e-6 from an operand of 1.5e-12).
//! By the precision contract the sheet bounds nothing: the result is the empty solid.

use crate::polygon::{Polygon, volume_of};

/// Above this many polygons the sheet test (quadratic) is not made; such a result is passed on
/// as it is.
const SHEET_MAX: usize = 1 << 12;

/// True when the mean thickness of `polygons` (twice the volume over the area) is at most
/// `weld` and each of them lies within two welds of a polygon facing the other way (a side of
/// the sheet: a wedge of mean thickness a weld is up to two thick at its end) or is narrower
/// than two welds (an edge of the sheet): a flat closed sheet, or several, and nothing else.
/// A face of any part thicker than that has no such backing, and is wider.
///
/// The first polygon is tested alone first (a pass of dot products), so a result with any
/// volume to it costs little more than that.
pub(super) fn is_flat_sheet(polygons: &[Polygon], weld: f64) -> bool {
    let Some(first) = polygons.first() else {
        return false;
    };
    let reach = 2.0 * weld;
    let flat = |p: &Polygon| narrow(p, reach) || polygons.iter().any(|q| backs(p, q, reach));
    if polygons.len() > SHEET_MAX || !flat(first) {
        return false;
    }
    let area: f64 = polygons.iter().map(Polygon::area).sum();
    if 2.0 * volume_of(polygons).abs() > weld * area {
        return false;
    }
    polygons.iter().all(flat)
}

/// True when `p`'s mean width across its longest edge is at most `reach`.
fn narrow(p: &Polygon, reach: f64) -> bool {
    let v = p.vertices();
    let longest = (0..v.len())
        .map(|i| v[i].distance(v[(i + 1) % v.len()]))
        .fold(0.0, f64::max);
    p.area() <= reach * longest
}

/// True when `q` faces the other way from `p` and every corner of `p` lies within `reach` of
/// `q`'s plane and of `q`'s box.
fn backs(p: &Polygon, q: &Polygon, reach: f64) -> bool {
    if p.plane().normal().dot(q.plane().normal()) >= 0.0 {
        return false;
    }
    let v = p.vertices();
    v.iter().all(|&v| q.plane().distance(v).abs() <= reach) && {
        let bbox = q.bbox();
        v.iter().all(|&v| bbox.contains_point(v, reach))
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::primitives::cuboid_between;

    fn slab(lo: DVec3, hi: DVec3) -> Vec<Polygon> {
        cuboid_between(lo, hi).unwrap()
    }

    /// A box 2e-13 thick is a sheet at a weld of 1e-12 (its sides back each other, its edges
    /// are narrow), and not at a weld of 1e-14; one 4e-12 thick is not (mean thickness twice
    /// the weld). Beside a cube 1e-9 across, a sheet is not the whole result: the cube's faces
    /// have no backing and are wide, and the result is passed on.
    #[test]
    fn a_sheet_is_a_box_thinner_than_the_weld_and_nothing_else() {
        let thin = slab(DVec3::ZERO, DVec3::new(1.0, 1.0, 2e-13));
        assert!(is_flat_sheet(&thin, 1e-12));
        assert!(!is_flat_sheet(&thin, 1e-14));
        let thick = slab(DVec3::ZERO, DVec3::new(1.0, 1.0, 4e-12));
        assert!(!is_flat_sheet(&thick, 1e-12));
        let mut both = thin.clone();
        both.extend(slab(DVec3::splat(2.0), DVec3::splat(2.0 + 1e-9)));
        assert!(!is_flat_sheet(&both, 1e-12));
        // The cube first: the first polygon's test alone says no.
        both.rotate_right(6);
        assert!(!is_flat_sheet(&both, 1e-12));
        assert!(!is_flat_sheet(&[], 1e-12));
    }
}
