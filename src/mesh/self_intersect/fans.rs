//! Vertices around which no two triangles can cross: checked once per vertex in time linear in
//! its valence, so the pairs of triangles sharing it need no test of their own. At a cone's
//! apex or a cap's centre of valence `n` that is `n` predicates instead of `n²/2` pair tests.

use glam::DVec3;
use rayon::prelude::*;

use super::orient;
use crate::mesh::repair::Links;

/// Per vertex: its valence when no two triangles around it cross (by [`embedded`]), else 0;
/// and the links of the vertices, where every vertex a triangle uses is one closed disc
/// ([`Links::disc`]).
pub(super) fn embedded_valences(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
) -> (Vec<u32>, Option<Links>) {
    let links = Links::new(triangles, positions.len());
    let valences = (0..positions.len())
        .into_par_iter()
        .with_min_len(4096)
        .map(|v| {
            let link = links.of(v);
            if links.disc[v] && embedded(positions, positions[v], link) {
                link.len() as u32
            } else {
                0
            }
        })
        .collect();
    (valences, all_discs(&links).then_some(links))
}

/// Whether every vertex of `links` that a triangle uses is a disc. Kept out of line, so as not
/// to change how the crossing search is compiled.
#[inline(never)]
fn all_discs(links: &Links) -> bool {
    links
        .disc
        .iter()
        .enumerate()
        .all(|(v, &disc)| disc || links.of(v).is_empty())
}

/// Whether the fan of triangles `(v, a, b)`, one per edge `(a, b)` of `link` (a closed disc in
/// cycle order: [`Links::of`]), is embedded near `v`: seen along some direction `n`, every
/// triangle turns counter-clockwise about `v`, and the link goes round `v` exactly once.
///
/// Then the fan seen along `n` is a disc cut into wedges at `v` that meet only along the rays
/// their neighbours share; the view is one-to-one on each triangle (none is seen edge-on), so
/// two triangles of the fan meet only where their views do: at `v`, or along the edge two
/// neighbours share. No two cross (in the sense of [`super::cross`]).
///
/// `n` is the sum of the triangles' unit normals, which points out of a cone (its axis), a cap
/// (its normal) and the corner of a box or a crease (the vector area would not: along an edge
/// where a cone meets its base it lies in the base, edge-on to the base's triangles). Rounded
/// as it is, it is only a direction, and the tests on it are exact: with
/// `w = v + n`, the turn of wedge `(a, b)` is the sign of `orient3d(w, a, b, v)`. Going once
/// round is checked against the first link vertex `a₀`: the sign of the turn from `a₀` to each
/// later `aₖ` may only fall (positive while under half a turn, zero at most once at half, then
/// negative); a second time round would have to rise again, as no wedge turns half a turn.
fn embedded(positions: &[DVec3], v: DVec3, link: &[(u32, u32)]) -> bool {
    let at = |i: u32| positions[i as usize];
    let mut normals = DVec3::ZERO;
    let mut reach = 0.0f64;
    for &(a, b) in link {
        let (a, b) = (at(a) - v, at(b) - v);
        normals += a.cross(b).normalize_or_zero();
        reach = reach.max(a.abs().max_element());
    }
    let length = normals.length();
    if !(length > 0.0 && length.is_finite() && reach.is_finite()) {
        return false;
    }
    // Scaled to the fan's size so that `w` stays a point apart from `v` after rounding.
    let w = v + normals * (reach / length);
    if !w.is_finite() {
        return false;
    }
    let sign = |x: f64| (x > 0.0) as i8 - (x < 0.0) as i8;
    let first = at(link[0].0);
    let mut last = 1;
    for (k, &(a, b)) in link.iter().enumerate() {
        if orient([w, at(a), at(b)], v) <= 0.0 {
            return false;
        }
        if k > 0 {
            let s = sign(orient([w, first, at(a)], v));
            if s > last {
                return false;
            }
            last = s;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::super::tests::cone;
    use super::*;

    #[test]
    fn a_cone_is_embedded_at_every_vertex() {
        for h in [1.0, 1e-3, -0.5] {
            let (p, t) = cone(64, h);
            let v = embedded_valences(&p, &t).0;
            assert_eq!(&v[..2], [64, 64], "{h}");
            assert!(v[2..].iter().all(|&k| k == 4), "{h}");
        }
        // A flat cone: the apex fan lies on the base fan, all of it in one plane; each fan on
        // its own is still embedded (the two cross each other, which is not this test's).
        let (p, t) = cone(16, 0.0);
        assert_eq!(&embedded_valences(&p, &t).0[..2], [16, 16]);
    }

    #[test]
    fn a_fan_folded_or_going_round_twice_is_not_embedded() {
        // One ring vertex pulled across the apex fan: its two wedges turn the other way.
        let (mut p, t) = cone(64, 1.0);
        p[2 + 10] = DVec3::new(-2.0 * p[12].x, -2.0 * p[12].y, 0.0);
        let v = embedded_valences(&p, &t).0;
        assert_eq!(v[0], 0);
        assert_eq!(v[1], 0);
        // A link going round the apex twice: ring vertex i at angle 2·(2π i / n), every wedge
        // turning the same way by 4π / n.
        let (mut p, t) = cone(64, 1.0);
        for (i, q) in p[2..].iter_mut().enumerate() {
            let a = 2.0 * std::f64::consts::TAU * i as f64 / 64.0;
            *q = DVec3::new(a.cos(), a.sin(), 0.0);
        }
        let v = embedded_valences(&p, &t).0;
        assert_eq!(v[0], 0);
        assert_eq!(v[1], 0);
    }
}
