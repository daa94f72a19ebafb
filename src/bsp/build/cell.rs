//! Cell splits: where an axis-aligned plane goes, and how it parts a cell's polygons.

use glam::DVec3;

use super::arena::Arena;
use super::{Ids, Scratch};
use crate::geom::{Aabb, Plane};
use crate::polygon::{Polygon, Split};

/// An axis-aligned plane through a gap between polygon centroids near their median, on the
/// longest axis that has one. The gap is wider than four tolerances, so no polygon lies in the
/// plane and both sides keep a polygon whose centroid, hence some vertex, is clearly on it.
/// `None` when no axis has such a gap, the plane would cut too many polygons, or one side would
/// get no polygon whole.
pub(super) fn cell_plane(
    ids: &[u32],
    arena: &Arena,
    eps: f64,
    keys: &mut Vec<i64>,
) -> Option<Plane> {
    let size = Aabb::from_points(ids.iter().map(|&i| &arena.centroids[i as usize])).size();
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&a, &b| size[b].total_cmp(&size[a]));
    let n = ids.len();
    for axis in axes {
        if size[axis] <= 4.0 * eps {
            break;
        }
        keys.clear();
        keys.extend(
            ids.iter()
                .map(|&i| order_key(arena.centroids[i as usize][axis])),
        );
        let Some(at) = gap_near_median(keys, 4.0 * eps) else {
            continue;
        };
        let (mut spanning, mut whole_front, mut whole_back) = (0usize, 0usize, 0usize);
        for &i in ids {
            let b = &arena.boxes[i as usize];
            if b.min[axis] > at + eps {
                whole_front += 1;
            } else if b.max[axis] < at - eps {
                whole_back += 1;
            } else if b.min[axis] < at - eps && b.max[axis] > at + eps {
                spanning += 1;
            }
        }
        // Each side must lose a polygon: a plane that only cuts pieces off the polygons it
        // spans would be followed by another half as far away, and so on (polygons in z = 2
        // beside walls rising from it drew planes at 2 + 2⁻¹, 2 + 2⁻², … 2 + 2⁻³⁶, slivers
        // thinner than the weld that moved vertices off their grid).
        if spanning * 2 <= n && whole_front > 0 && whole_back > 0 {
            let mut normal = DVec3::ZERO;
            normal[axis] = 1.0;
            return Some(Plane::through(normal * at, normal));
        }
    }
    None
}

/// A cell plane midway across the gap between the box of a cell's polygons that are not far
/// (`near`) and the far polygons wholly beyond it, on the side where those are most, if they
/// are at least half the cell's: that side then holds far polygons only and is left unbuilt
/// at once. Two tolerances outside the box, it cut clipped fragments into slivers (grid boxes'
/// vertices left the grid by 4.5e-12, a union of 1,000 of them came out open). Planes placed by the
/// near polygons' centroids alone always keep near polygons on both sides, so without this
/// the far polygons of a sphere (31 k of 32 k quads) rode down every level (its boolean took
/// 558 M instructions instead of 367 M). At a quarter of the cell's, fandisk's difference
/// came out cut so that `to_mesh` needed its wider welds (93 → 672 M).
///
/// `near_box` is the box of the `near` polygons (`None` where there are none), which the build
/// has made for the focus already: making it again here was 5 M instructions of fandisk's 65 M
/// of trees, both booleans.
pub(super) fn wrap_plane(
    ids: &Ids,
    near_box: Option<&Aabb>,
    arena: &Arena,
    eps: f64,
) -> Option<Plane> {
    // The plane needs at least half the cell's polygons far and beyond the near box.
    let bbox = near_box?;
    if 2 * ids.far.len() < ids.len() {
        return None;
    }
    // Far polygons wholly beyond the near ones' box by more than four tolerances, counted per
    // side, with the nearest such coordinate.
    let (low, high) = (bbox.min - 4.0 * eps, bbox.max + 4.0 * eps);
    let (mut below, mut above) = ([0usize; 3], [0usize; 3]);
    let (mut below_edge, mut above_edge) = ([f64::NEG_INFINITY; 3], [f64::INFINITY; 3]);
    // The count a side needs; once no side can reach it with the far polygons left, none will
    // (checked every `CHUNK` polygons).
    const CHUNK: usize = 32;
    let need = ids.len().div_ceil(2);
    let mut left = ids.far.len();
    for chunk in ids.far.chunks(CHUNK) {
        let most = below.iter().chain(&above).copied().max().unwrap_or(0);
        if most + left < need {
            return None;
        }
        left -= chunk.len();
        for &i in chunk {
            let b = &arena.boxes[i as usize];
            // Plain comparisons, not `f64::max`/`min` (which spend instructions on NaN): a
            // coordinate that passed the test above is no NaN, and the edges start infinite.
            for axis in 0..3 {
                let (max, min) = (b.max[axis], b.min[axis]);
                if max < low[axis] {
                    below[axis] += 1;
                    if max > below_edge[axis] {
                        below_edge[axis] = max;
                    }
                }
                if min > high[axis] {
                    above[axis] += 1;
                    if min < above_edge[axis] {
                        above_edge[axis] = min;
                    }
                }
            }
        }
    }
    // The plane lies midway across the gap, as a cell plane does: more than two tolerances
    // from the near polygons and from the far ones it leaves wholly to one side.
    let mut best = (0usize, 0usize, 0.0f64);
    for axis in 0..3 {
        if below[axis] > best.0 {
            best = (below[axis], axis, 0.5 * (bbox.min[axis] + below_edge[axis]));
        }
        if above[axis] > best.0 {
            best = (above[axis], axis, 0.5 * (bbox.max[axis] + above_edge[axis]));
        }
    }
    let (count, axis, at) = best;
    (count > 0 && 2 * count >= ids.len()).then(|| {
        let mut normal = DVec3::ZERO;
        normal[axis] = 1.0;
        Plane::through(normal * at, normal)
    })
}

/// An integer that orders as [`f64::total_cmp`] orders `x`: selecting on these is a plain
/// integer comparison where `total_cmp` is several instructions (the median's selection was a
/// third of the cell plane's cost).
#[inline]
pub(super) fn order_key(x: f64) -> i64 {
    let bits = x.to_bits() as i64;
    bits ^ (((bits >> 63) as u64) >> 1) as i64
}

/// The value whose [`order_key`] is `key` (the map is its own inverse).
#[inline]
fn from_key(key: i64) -> f64 {
    f64::from_bits((key ^ (((key >> 63) as u64) >> 1) as i64) as u64)
}

/// The midpoint of a gap wider than `min_gap` next to the median of the values whose
/// [`order_key`]s are `keys` (reordered), in linear time; where the median value repeats, the
/// gap nearest the middle of the sorted values within the middle half.
fn gap_near_median(keys: &mut [i64], min_gap: f64) -> Option<f64> {
    let n = keys.len();
    let mid = n / 2;
    let (below, &mut median, above) = keys.select_nth_unstable(mid);
    let median = from_key(median);
    let lower = below
        .iter()
        .max()
        .map_or(f64::NEG_INFINITY, |&k| from_key(k));
    if median - lower > min_gap && lower.is_finite() {
        return Some(0.5 * (lower + median));
    }
    let upper = above.iter().min().map_or(f64::INFINITY, |&k| from_key(k));
    if upper - median > min_gap && upper.is_finite() {
        return Some(0.5 * (median + upper));
    }
    keys.sort_unstable();
    for k in 0..=n / 4 {
        for i in [mid + k, mid.wrapping_sub(k)] {
            if i >= 1 && i < n && from_key(keys[i]) - from_key(keys[i - 1]) > min_gap {
                let (a, b) = (from_key(keys[i - 1]), from_key(keys[i]));
                return Some(0.5 * (a + b));
            }
        }
    }
    None
}

/// Splits a cell's polygons by its axis plane. No polygon is coplanar with it (see
/// [`cell_plane`]); one that is anyway, within tolerance, goes the way its normal points.
///
/// A far polygon (see [`Focus`]) goes whole to each side its box reaches beyond the tolerance
/// (both, where it lies within it).
pub(super) fn split_cell(
    ids: Ids,
    plane: &Plane,
    eps: f64,
    arena: &mut Arena,
    scratch: &mut Scratch,
) -> (Ids, Ids) {
    let axis = plane.normal.abs().max_position();
    let at = plane.offset;
    // Either side may take every polygon (and pieces of the spanning ones): no regrowing.
    let (mut front, mut back) = (scratch.ids_like(&ids), scratch.ids_like(&ids));
    let (far, boxes) = (&ids.far, &arena.boxes);
    match axis {
        0 => far_sides::<0>(far, boxes, at, eps, &mut front.far, &mut back.far),
        1 => far_sides::<1>(far, boxes, at, eps, &mut front.far, &mut back.far),
        _ => far_sides::<2>(far, boxes, at, eps, &mut front.far, &mut back.far),
    }
    for &id in &ids.near {
        let b = &arena.boxes[id as usize];
        let given = arena.given(id);
        match axis_split(arena.poly(id), b, given, plane, axis, eps) {
            Split::Front => front.near.push(id),
            Split::Back => back.near.push(id),
            Split::Coplanar if arena.poly(id).plane().normal.dot(plane.normal) > 0.0 => {
                front.near.push(id)
            }
            Split::Coplanar => back.near.push(id),
            Split::Spanning { front: f, back: b } => {
                front.near.push(arena.push(f, id));
                back.near.push(arena.push(b, id));
            }
        }
    }
    scratch.recycle_ids(ids);
    (front, back)
}

/// The far polygons of a cell split at `at` on axis `AXIS`: each goes whole to each side its
/// box reaches beyond the tolerance (both, where it lies within it). The axis is a constant,
/// chosen once per cell, so each box's two coordinates are read at fixed offsets, not through
/// an index per polygon: this loop walks about twelve far ids for each near one (rocker-arm:
/// `split_cell` 34.1 → 30.3 M instructions over two booleans).
fn far_sides<const AXIS: usize>(
    far: &[u32],
    boxes: &[Aabb],
    at: f64,
    eps: f64,
    front: &mut Vec<u32>,
    back: &mut Vec<u32>,
) {
    let (high, low) = (at + eps, at - eps);
    for &id in far {
        let b = &boxes[id as usize];
        let (min, max) = (b.min[AXIS], b.max[AXIS]);
        if max > high || min >= low {
            front.push(id);
        }
        if min < low || max <= high {
            back.push(id);
        }
    }
}

/// [`Polygon::split_as`] by an axis-aligned plane (normal `+axis`), settled from the box where
/// it lies to one side; `given` as [`Arena::given`] says.
fn axis_split(
    poly: &Polygon,
    b: &Aabb,
    given: bool,
    plane: &Plane,
    axis: usize,
    eps: f64,
) -> Split {
    let at = plane.offset;
    // The box settles most polygons without looking at their vertices.
    if b.min[axis] >= at - eps && b.max[axis] > at + eps {
        return Split::Front;
    }
    if b.max[axis] <= at + eps && b.min[axis] < at - eps {
        return Split::Back;
    }
    // A strict span with no vertex near the plane takes the quick axis cut.
    let quick = (b.min[axis] < at - eps && b.max[axis] > at + eps)
        .then(|| poly.split_axis(plane, axis, eps))
        .flatten();
    quick.unwrap_or_else(|| poly.split_as(plane, eps, given.then_some(&[][..])))
}

/// The axis of an axis-aligned plane with normal `+axis` (a cell's), or `None`.
pub(super) fn axis_of(plane: &Plane) -> Option<usize> {
    let axis = plane.normal.abs().max_position();
    (plane.normal[axis] == 1.0).then_some(axis)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gap_next_to_the_median() {
        let keys = |v: &[f64]| v.iter().map(|&x| order_key(x)).collect::<Vec<_>>();
        let mut v = keys(&[5.0, 1.0, 3.0, 3.0, 3.0, 2.0, 4.0]);
        assert_eq!(gap_near_median(&mut v, 0.5), Some(2.5));
        let mut same = keys(&[1.0; 8]);
        assert_eq!(gap_near_median(&mut same, 0.5), None);
        let mut negative = keys(&[-4.0, -0.0, 0.0, -1.0, 3.0, -2.0]);
        assert_eq!(gap_near_median(&mut negative, 0.5), Some(-0.5));
    }

    /// Keys order as `total_cmp` does and map back to the same bits.
    #[test]
    fn order_keys_follow_total_cmp() {
        let v = [
            f64::NEG_INFINITY,
            -1e300,
            -1.5,
            -f64::MIN_POSITIVE / 4.0,
            -0.0,
            0.0,
            f64::MIN_POSITIVE / 4.0,
            2.0,
            1e300,
            f64::INFINITY,
        ];
        for a in v {
            assert_eq!(from_key(order_key(a)).to_bits(), a.to_bits());
            for b in v {
                assert_eq!(order_key(a).cmp(&order_key(b)), a.total_cmp(&b), "{a} {b}");
            }
        }
    }
}
