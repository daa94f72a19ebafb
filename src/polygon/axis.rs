//! The tree's cell cuts: [`Polygon::split`] by an axis-aligned plane that no vertex lies near,
//! without the general case's bookkeeping.

use glam::DVec3;

use super::split::edge_cut;
use super::{Polygon, Split, Vertices};
use crate::geom::Plane;

impl Polygon {
    /// [`Polygon::split`] by `plane`, whose normal is the unit vector along `axis`, for a
    /// polygon without edge planes whose every vertex lies farther than `eps` from the plane:
    /// the same answer, bit for bit, without the near-parallel bands and the edge-plane
    /// bookkeeping, which cost several times the cut itself. `None` where that does not hold
    /// (the caller takes [`Polygon::split`]).
    pub(crate) fn split_axis(&self, plane: &Plane, axis: usize, eps: f64) -> Option<Split> {
        if self.edges.is_some() || self.plane.is_same_or_flipped(plane) {
            return None;
        }
        let at = plane.anchor[axis];
        let n = self.vertices.len();
        let mut dist = [0.0f64; 8];
        if n > dist.len() {
            return None;
        }
        // `plane.distance(v)` exactly: the normal's zero components add nothing.
        let (mut any_front, mut any_back) = (false, false);
        for (d, v) in dist.iter_mut().zip(&self.vertices) {
            *d = v[axis] - at;
            if d.abs() <= eps {
                return None;
            }
            any_front |= *d > 0.0;
            any_back |= *d < 0.0;
        }
        match (any_front, any_back) {
            (true, false) => return Some(Split::Front),
            (false, true) => return Some(Split::Back),
            _ => {}
        }
        let (mut front, mut back) = (Vertices::new(), Vertices::new());
        let push = |ring: &mut Vertices, p: DVec3| {
            if ring.last() != Some(&p) {
                ring.push(p);
            }
        };
        for i in 0..n {
            let j = (i + 1) % n;
            let (vi, di, dj) = (self.vertices[i], dist[i], dist[j]);
            if di > 0.0 {
                push(&mut front, vi);
            } else {
                push(&mut back, vi);
            }
            if (di > 0.0) != (dj > 0.0) {
                let p = edge_cut(vi, di, self.vertices[j], dj, plane, Some(axis));
                push(&mut front, p);
                push(&mut back, p);
            }
        }
        let piece = |mut ring: Vertices| {
            while ring.len() > 1 && ring.first() == ring.last() {
                ring.pop();
            }
            (ring.len() >= 3).then(|| Polygon::with_plane(ring, self.plane, self.source))
        };
        Some(match (piece(front), piece(back)) {
            (Some(front), Some(back)) => Split::Spanning { front, back },
            (Some(_), None) => Split::Front,
            (None, _) => Split::Back,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the general split, on polygons cut by axis planes at many offsets.
    #[test]
    fn the_same_pieces_as_split() {
        let ring = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.3, 0.1, 0.7),
            DVec3::new(1.7, 1.1, 1.9),
            DVec3::new(0.4, 1.6, 1.2),
        ];
        let poly = Polygon::new(&ring, 7).unwrap();
        let (mut spanning, mut declined) = (0, 0);
        for axis in 0..3 {
            for k in 0..=40 {
                let mut normal = DVec3::ZERO;
                normal[axis] = 1.0;
                let plane = Plane::through(normal * (0.013 + k as f64 * 0.047), normal);
                let Some(fast) = poly.split_axis(&plane, axis, 1e-9) else {
                    declined += 1;
                    continue;
                };
                let full = poly.split(&plane, 1e-9);
                spanning += usize::from(matches!(full, Split::Spanning { .. }));
                assert_eq!(
                    format!("{fast:?}"),
                    format!("{full:?}"),
                    "axis {axis}, k {k}"
                );
            }
        }
        assert!(spanning > 20, "{spanning} spanning");
        assert!(declined < 10, "{declined} declined");
    }
}
