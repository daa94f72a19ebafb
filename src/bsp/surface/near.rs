//! Which polygons of two surfaces come near each other: boxes meeting within a margin, less
//! pairs parted by a plane of one ([`beyond`]) or by the direction across an edge of each
//! ([`apart_across_edges`]).

use std::sync::atomic::{AtomicBool, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use super::Surface;
use crate::polygon::Polygon;

impl Surface<'_> {
    /// For each polygon of this surface and of `other`, whether it comes within `margin` of one
    /// of the other's polygons: their boxes do, and neither lies wholly beyond the other's plane
    /// by more than that and [`NEAR_GAP`] tolerances (see [`beyond`]), nor do they lie that far
    /// apart across an edge of each (see [`apart_across_edges`]). Box overlap alone kept
    /// 2,974 of rocker-arm's 20,088 triangles near the moved copy; the planes leave about 1,200
    /// (the band a cut crosses); the edges' directions leave fewer still (rocker-arm ∪ moved:
    /// 358.7 → 345.8 M instructions per boolean and mesh, measured when the edge test was
    /// still asked of every pair, before it was kept to triangle pairs; the output the same on
    /// the measured speed cases). It is not output-neutral in general: in near-coplanar cases
    /// with tiny rotations, trees focused on fewer near polygons can label unbuilt cells'
    /// fragments otherwise. With the round-17/18/20 fork inputs replayed on their operands'
    /// own triangle meshes, `ca3a7ad3` fails with the edge test (mesh volume
    /// 0.25694701517087715, solid 0.2569470126909814) and passes without it, `dd18b60b` the
    /// other way; the failing count is the same either way.
    ///
    /// One descent of both hierarchies together ([`Bvh::visit_pairs_within`]), in parallel over
    /// pieces of this one: walking `other`'s from its root once per leaf of this one entered
    /// its top levels again for every leaf. It gives only pairs whose own boxes meet within the
    /// margin, having kept each leaf's polygons to those near the other leaf's box first. Each
    /// pair of polygons found settles both sides' flags at once.
    pub fn near_each_other(&self, other: &Surface, margin: f64) -> (Vec<bool>, Vec<bool>) {
        let mine: Vec<AtomicBool> = self.boxes.iter().map(|_| AtomicBool::new(false)).collect();
        let theirs: Vec<AtomicBool> = other.boxes.iter().map(|_| AtomicBool::new(false)).collect();
        // Polygons whose boxes meet but that lie apart by a plane of one of them are not near
        // (see [`beyond`]), where the gap is more than [`NEAR_GAP`] tolerances.
        let apart = margin + NEAR_GAP * self.eps.max(other.eps);
        let pieces = self.bvh.cut(64);
        pieces.par_iter().for_each(|&piece| {
            self.bvh.visit_pairs_within(
                piece,
                &other.bvh,
                margin,
                (&self.boxes, &other.boxes),
                |i, j| {
                    let (i, j) = (i as usize, j as usize);
                    let (seen_i, seen_j) = (
                        mine[i].load(Ordering::Relaxed),
                        theirs[j].load(Ordering::Relaxed),
                    );
                    if seen_i && seen_j {
                        return;
                    }
                    let (p, q) = (&self.polygons[i], &other.polygons[j]);
                    if beyond(p, q, apart) || beyond(q, p, apart) || apart_across_edges(p, q, apart)
                    {
                        return;
                    }
                    if !seen_i {
                        mine[i].store(true, Ordering::Relaxed);
                    }
                    if !seen_j {
                        theirs[j].store(true, Ordering::Relaxed);
                    }
                },
            );
        });
        let plain =
            |flags: Vec<AtomicBool>| flags.into_iter().map(AtomicBool::into_inner).collect();
        (plain(mine), plain(theirs))
    }
}

/// How far apart, in tolerances beyond the margin, two polygons whose boxes meet must lie for
/// [`Surface::near_each_other`] to call them not near: 10⁷, at the relative tolerance
/// (10⁻¹² of the region) 10⁻⁵ of the region. Faces that nearly coincide stay near, clipped
/// as before: in a fuzz finding (`a_fin_drop_takes_volume_from_the_mesh`: spheres about one
/// centre, one turned 10⁻³°) polygons so close were passed whole with a gap of up to 10⁵
/// tolerances, and the mesh came out 1.2·10⁻⁹ short of the solid's volume; from 10⁶ it is
/// right. The speed cases count the same at 1 and at 10⁷ (rocker-arm, sphere 256: within
/// 0.3 M instructions per boolean).
const NEAR_GAP: f64 = 1e7;

/// Whether every vertex of `poly` lies farther than `apart` to one side of `other`'s plane, and
/// farther than `apart` beyond `other`'s own corners' distances from it: then every point of
/// `poly` lies farther than `apart` from every point of `other` (a convex polygon lies between
/// its corners' distances from any plane).
fn beyond(poly: &Polygon, other: &Polygon, apart: f64) -> bool {
    let plane = other.plane();
    let vertices = poly.vertices();
    let first = plane.distance(vertices[0]);
    if first.abs() <= apart {
        return false;
    }
    let own = other
        .vertices()
        .iter()
        .fold(0.0f64, |m, &v| m.max(plane.distance(v).abs()));
    let reach = apart + own;
    if first > reach {
        vertices[1..].iter().all(|&v| plane.distance(v) > reach)
    } else if first < -reach {
        vertices[1..].iter().all(|&v| plane.distance(v) < -reach)
    } else {
        false
    }
}

/// Whether `poly` and `other` lie farther than `apart` from each other along the direction
/// across an edge of each (their cross product): the separating axes a pair of triangles has
/// beyond their two planes ([`beyond`]). Each polygon lies within its corners' span along any
/// direction, so a gap of more than `apart` between the two spans along a unit direction puts
/// every point of one farther than `apart` from every point of the other. Edges parallel to
/// within rounding give no direction and are passed over.
///
/// Asked of two triangles only, neither facing along a coordinate axis. Where one does, the
/// pair is not tested: a pruning missed, not one the box test makes. The triangles
/// (0,0,0), (1,0,0), (0,1,0) and (0.6,0.6,−1), (0.6,0.6,1), (2,2,0) have overlapping boxes
/// and each spans the other's plane, yet along (1,1,0)/√2 they lie 0.849 − 0.707 apart; only
/// this skip keeps them near. Keeping them is sound, just slower, and testing such pairs was
/// measured not to pay (a Menger sponge: 9.5 M instructions per boolean, no pair parted). On
/// the quads of primitives it parted pairs in a fuzz finding (`1037da39` of the
/// round-17 fork run, with tiny rotations) whose result then came out open, 15 boundary
/// edges: the parting is sound (a gap of 10⁷ tolerances), but the trees focused on fewer near
/// polygons label their unbuilt cells' fragments otherwise, and that near-coplanar case is
/// fragile there (not yet understood).
fn apart_across_edges(poly: &Polygon, other: &Polygon, apart: f64) -> bool {
    let square = |p: &Polygon| p.plane().normal.abs().max_element() >= 1.0 - 1e-9;
    let (p, q) = (poly.vertices(), other.vertices());
    if p.len() != 3 || q.len() != 3 || square(poly) || square(other) {
        return false;
    }
    let span = |vs: &[DVec3], u: DVec3| {
        vs.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                let d = v.dot(u);
                (lo.min(d), hi.max(d))
            })
    };
    // Each triangle's edges and their lengths, once: the pairs' loop asks each three times.
    let edges = |vs: &[DVec3]| {
        let e = [vs[1] - vs[0], vs[2] - vs[1], vs[0] - vs[2]];
        (e, e.map(DVec3::length))
    };
    let ((pe, pl), (qe, ql)) = (edges(p), edges(q));
    for (&e, &e_len) in pe.iter().zip(&pl) {
        for (&f, &f_len) in qe.iter().zip(&ql) {
            let axis = e.cross(f);
            let len = axis.length();
            if len.is_nan() || len <= 1e-9 * e_len * f_len {
                continue;
            }
            let u = axis / len;
            let ((p_lo, p_hi), (q_lo, q_hi)) = (span(p, u), span(q, u));
            if q_lo - p_hi > apart || p_lo - q_hi > apart {
                return true;
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles crossed like an X, their long edges 0.1 apart across both (turned off the
    /// coordinate axes): their boxes meet and neither lies beyond the other's plane, but the
    /// direction across their long edges parts them; moved into each other, it does not.
    #[test]
    fn triangles_apart_across_their_edges_are_not_near() {
        let turn = glam::DQuat::from_axis_angle(DVec3::new(0.3, 1.0, 0.2).normalize(), 0.7);
        let triangle = |corners: [[f64; 3]; 3]| {
            let corners = corners.map(|c| turn * DVec3::from(c));
            Polygon::new(&corners, 0).unwrap()
        };
        for (gap, apart) in [(0.1, true), (-0.1, false)] {
            let p = triangle([[-1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [0.5, -0.5, -1.0]]);
            let q = triangle([[1.0, -1.0, gap], [-1.0, 1.0, gap], [0.5, 0.5, gap + 1.0]]);
            assert!(p.bbox().overlaps(&q.bbox(), 0.0));
            assert!(!beyond(&p, &q, 0.01) && !beyond(&q, &p, 0.01), "{gap}");
            assert_eq!(apart_across_edges(&p, &q, 0.01), apart, "{gap}");
            assert_eq!(apart_across_edges(&q, &p, 0.01), apart, "{gap}");
        }
    }
}
